"""The Gymnasium environments (fuzzymotiv.gym): the library's step, exactly; check_env; the
native vector env and its next-step autoreset; the guide's Gymnasium page."""

import json
import re

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")

import fuzzymotiv as fm  # noqa: E402
import fuzzymotiv.gym as fmgym  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402

SHORT = {"trial.steps": 60}


def golden(repo, model):
    """A saved genome (a golden run's best robot) and its config."""
    d = repo / "crates" / "fuzzymotiv-cli" / "tests" / "golden" / model
    weights = np.array(json.loads((d / "best_genome.json").read_text())["weights"])
    return weights, str(d / "config.toml")


def drive(env, network, seed, room):
    """Drives `env` with the network's outputs; its observations, infos, rewards and flags."""
    obs, info = env.reset(seed=seed, options={"room": room})
    seen, infos, rewards = [obs], [info], []
    while True:
        obs, reward, terminated, truncated, info = env.step(network(obs))
        seen.append(obs)
        infos.append(info)
        rewards.append(reward)
        if terminated or truncated:
            return np.array(seen), infos, np.array(rewards), terminated


@pytest.mark.parametrize("model", ["default", "first-release"])
def test_driving_the_float64_env_with_a_saved_genome_replays_simulate(repo, model):
    weights, config = golden(repo, model)
    net = fmgym.network(weights)
    # The default golden's robot comes back home in the rectangle under seed 2.
    cases = [("H", 0), ("T", 11), ("rectangle", 2)]
    env = fmgym.KheperaEnv([r for r, _ in cases], config=config, dtype=np.float64)
    ended_at_home = 0
    for room, seed in cases:
        if True:
            tr = fm.simulate(weights, room, seed, config=config)
            obs, infos, rewards, home = drive(env, net, seed, room)
            k = len(rewards)
            # Observations are the sensors the trial read / 1023, bit for bit.
            assert np.array_equal(obs[:-1], tr["sensors"][:k] / 1023.0)
            for key in ("x", "y", "heading"):
                got = np.array([i[key] for i in infos])
                assert np.array_equal(got, tr[key][: k + 1]), (room, seed, key)
                assert np.all(tr[key][k:] == tr[key][k])  # the idle rest stays put
            assert [i["action"] for i in infos[1:]] == list(tr["action"][:k])
            assert home == bool(tr["idle"][-1])
            assert rewards[-1] == tr["F"] and np.all(rewards[:-1] == 0.0)
            for term in "agb":
                assert infos[-1][term] == tr[term]
            assert infos[-1]["l"] == 0.0
            ended_at_home += home
    assert model == "first-release" or ended_at_home > 0


def test_check_env_passes():
    for discrete in (False, True):
        for dtype in (np.float32, np.float64):
            env = fmgym.KheperaEnv(["H", "T"], overrides=SHORT, dtype=dtype, discrete=discrete)
            check_env(env, skip_render_check=True)


def test_registered_ids_make_envs():
    env = gym.make("fuzzymotiv/Khepera-v0", room="L", overrides=SHORT)
    assert env.observation_space == gym.spaces.Box(0, 1, (8,), np.float32)
    assert env.action_space == gym.spaces.Box(0, 1, (2,), np.float32)
    obs, info = env.reset(seed=2)
    assert obs.dtype == np.float32 and info["room"] == "L" and info["t"] == 0
    discrete = gym.make("fuzzymotiv/KheperaDiscrete-v0", overrides=SHORT)
    assert discrete.action_space == gym.spaces.Discrete(4)
    discrete.reset(seed=0)
    _, _, _, _, info = discrete.step(1)
    assert info["action"] == "left30"
    vec = gym.make_vec("fuzzymotiv/Khepera-v0", num_envs=3, vectorization_mode="vector_entry_point",
                       overrides=SHORT)
    assert isinstance(vec.unwrapped, fmgym.KheperaVectorEnv) and vec.num_envs == 3


def test_rooms_are_drawn_from_the_seeded_np_random():
    env = fmgym.KheperaEnv(["H", "T", "L", "square"], overrides=SHORT)
    first = [env.reset(seed=5)[1]["room"]] + [env.reset()[1]["room"] for _ in range(11)]
    again = [env.reset(seed=5)[1]["room"]] + [env.reset()[1]["room"] for _ in range(11)]
    assert first == again and len(set(first)) > 1


def test_per_step_rewards_add_up_to_f(repo):
    weights, config = golden(repo, "default")
    net = fmgym.network(weights)
    env = fmgym.KheperaEnv("H", config=config, dtype=np.float64, reward="per-step")
    _, _, rewards, _ = drive(env, net, 3, "H")
    tr = fm.simulate(weights, "H", 3, config=config)
    assert np.count_nonzero(rewards) > 1
    assert sum(rewards) == pytest.approx(tr["F"], abs=1e-12)


def test_bad_arguments_raise_fuzzymotiv_error():
    with pytest.raises(fm.FuzzymotivError, match="reward"):
        fmgym.KheperaEnv("H", reward="sometimes")
    with pytest.raises(fm.FuzzymotivError, match="dtype"):
        fmgym.KheperaEnv("H", dtype=np.int32)
    with pytest.raises(fm.FuzzymotivError, match="room"):
        fmgym.KheperaEnv("no-such-room")
    with pytest.raises(fm.FuzzymotivError, match=r"num_envs: at most 1048576 .* got 100000000"):
        fmgym.KheperaVectorEnv(num_envs=10**8, room="H")
    env = fmgym.KheperaEnv("H", overrides=SHORT)
    env.reset(seed=0)
    for bad in [np.array([np.nan, 0.5]), np.array([np.inf, 0.5]), np.array([0.1, 0.2, 0.3]), 0.5, "go"]:
        with pytest.raises(fm.FuzzymotivError, match=r"action: expected 1 pair\(s\) of finite"):
            env.step(bad)
    discrete = fmgym.KheperaEnv("H", discrete=True, overrides=SHORT)
    discrete.reset(seed=0)
    for bad in [1.7, np.nan, 2**70, [1, 2], "left30"]:
        with pytest.raises(fm.FuzzymotivError, match=r"action: expected 1 whole number"):
            discrete.step(bad)
    discrete.step(np.int64(2))  # a whole number of any integer type
    discrete.step(np.array([1]))
    with pytest.raises(fm.FuzzymotivError, match="room"):
        env.reset(options={"room": "nowhere"})
    env.reset(seed=1)
    done = False
    while not done:
        *_, terminated, truncated, _ = env.step(np.array([1.0, 0.2]))
        done = terminated or truncated
    with pytest.raises(fm.FuzzymotivError, match="reset"):
        env.step(np.array([1.0, 1.0]))


def test_vector_env_steps_like_single_envs_and_autoresets_next_step():
    n, steps = 4, 30
    vec = fmgym.KheperaVectorEnv(n, ["H", "T"], overrides={"trial.steps": steps}, dtype=np.float64)
    assert vec.metadata["autoreset_mode"] == gym.vector.AutoresetMode.NEXT_STEP
    obs, info = vec.reset(seed=100)
    assert obs.shape == (n, 8) and info["_a"].all()
    singles = [fmgym.KheperaEnv(["H", "T"], overrides={"trial.steps": steps}, dtype=np.float64)
               for _ in range(n)]
    rng = np.random.default_rng(0)
    for i, env in enumerate(singles):
        o, _ = env.reset(seed=100 + i, options={"room": vec.rooms[info["room"][i]]})
        assert np.array_equal(o, obs[i])
    for t in range(steps):
        actions = rng.random((n, 2))
        obs, reward, term, trunc, info = vec.step(actions)
        for i, env in enumerate(singles):
            o, r, te, tu, inf = env.step(actions[i])
            assert np.array_equal(o, obs[i]) and r == reward[i] and (te, tu) == (term[i], trunc[i])
            assert inf["x"] == info["x"][i]
    assert trunc.all() and reward.any()  # T reached (nobody drove home at random)
    obs, reward, term, trunc, info = vec.step(rng.random((n, 2)))
    # Next-step autoreset: the action is ignored, a new episode starts.
    assert not (term.any() or trunc.any()) and (reward == 0).all() and (info["t"] == 0).all()
    assert (info["action"] == -1).all()


def test_box_actions_outside_0_1_are_clipped_and_nan_is_refused_naming_the_range():
    """As Gymnasium users expect of a Box action (docs/guide/gymnasium.md): (5, −5) steps as
    (1, 0), in the env and the vector env; NaN, which no clip makes a number, is refused."""
    clipped, bounds = (fmgym.KheperaEnv("H", overrides=SHORT, dtype=np.float64) for _ in range(2))
    clipped.reset(seed=4)
    bounds.reset(seed=4)
    for _ in range(10):
        o1, r1, te1, tu1, i1 = clipped.step(np.array([5.0, -5.0]))
        o2, r2, te2, tu2, i2 = bounds.step(np.array([1.0, 0.0]))
        assert np.array_equal(o1, o2) and (r1, te1, tu1) == (r2, te2, tu2)
        assert (i1["x"], i1["y"], i1["heading"]) == (i2["x"], i2["y"], i2["heading"])
    says = r"action: expected 1 pair\(s\) of finite motor outputs .*; values outside \[0, 1\] are clipped to it, NaN and infinities refused; got array\(\[nan"
    with pytest.raises(fm.FuzzymotivError, match=says):
        clipped.step(np.array([np.nan, 0.5]))
    vec = fmgym.KheperaVectorEnv(2, "H", overrides=SHORT, dtype=np.float64)
    again = fmgym.KheperaVectorEnv(2, "H", overrides=SHORT, dtype=np.float64)
    vec.reset(seed=9)
    again.reset(seed=9)
    a = vec.step(np.array([[5.0, -5.0], [0.3, 2.0]]))
    b = again.step(np.array([[1.0, 0.0], [0.3, 1.0]]))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def test_vector_env_passes_gymnasiums_vector_checks():
    from gymnasium.utils.env_checker import data_equivalence

    vec = fmgym.KheperaVectorEnv(3, "H", overrides=SHORT)
    a = vec.reset(seed=7)
    b = vec.reset(seed=7)
    assert data_equivalence(a, b)
    assert vec.observation_space.contains(a[0])
    obs, *_ = vec.step(vec.action_space.sample())
    assert vec.observation_space.contains(obs)


def test_render_rgb_array():
    if not hasattr(fm, "frames"):
        pytest.skip("fm.frames lands from the frames branch")
    env = fmgym.KheperaEnv("H", overrides=SHORT, render_mode="rgb_array", size=128)
    env.reset(seed=0)
    for _ in range(5):
        env.step(env.action_space.sample())
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
    assert frame.std() > 0


def played(env, steps=5):
    """`env` reset with seed 0 and stepped `steps` times with fixed motor outputs."""
    env.reset(seed=0)
    for _ in range(steps):
        env.step(np.array([0.9, 0.4], dtype=env.action_space.dtype))
    return env


def test_render_draws_the_robot_of_the_envs_overrides():
    """A robot.* override is drawn: render() is the last frame fm.frames draws of the episode
    with the env's overrides, not with the default robot."""
    bigger = {**SHORT, "robot.radius": 38.0}
    env = played(fmgym.KheperaEnv("H", overrides=bigger, render_mode="rgb_array", size=128))
    frame = env.render()
    expected = fm.frames(env.trajectory(), "H", size=128, overrides=bigger)[-1]
    default_robot = fm.frames(env.trajectory(), "H", size=128, overrides=SHORT)[-1]
    assert frame.shape == (128, 128, 3) and frame.dtype == np.uint8
    assert np.array_equal(frame, expected)
    assert not np.array_equal(frame, default_robot)


def test_render_finds_a_room_known_only_to_the_envs_config(repo):
    """A room that only the env's config names (a room file beside it) is drawn by render()."""
    config = str(repo / "configs" / "tiny.toml")
    env = played(fmgym.KheperaEnv("U", config=config, overrides=SHORT, render_mode="rgb_array",
                                  size=96))
    expected = fm.frames(env.trajectory(), "U", size=96, config=config, overrides=SHORT)[-1]
    assert np.array_equal(env.render(), expected)


def test_guide_gymnasium_page(repo, doc_blocks, monkeypatch, capsys):
    """The guide's Gymnasium page (docs/guide/gymnasium.md: the reflex and the vector env) runs
    as written."""
    blocks = doc_blocks("docs/guide/gymnasium.md")
    assert len(blocks) == 2
    monkeypatch.chdir(repo)
    for k, code in enumerate(blocks):
        exec(compile(code, f"docs/guide/gymnasium.md (block {k})", "exec"), {})
    out = capsys.readouterr().out
    assert re.search(r"F = \d\.\d+", out), out


def test_module_doctests():
    import doctest

    failures, tried = doctest.testmod(fmgym)
    assert failures == 0 and tried >= 3


def test_seeds_and_sizes_are_checked_like_the_rest_of_the_package():
    """Reset seeds are whole numbers below 2^53 (as fm.simulate takes), num_envs a whole number,
    and render() needs an episode: FuzzymotivError naming the argument, not a numpy or Python
    error from inside."""
    env = fmgym.KheperaEnv("H", overrides=SHORT, render_mode="rgb_array")
    with pytest.raises(fm.FuzzymotivError, match="render: no episode yet"):
        env.render()
    for bad in [2**53, 2**64, -1, 1.5, "1", True]:
        with pytest.raises(fm.FuzzymotivError, match=r"seed: .* is not a seed"):
            env.reset(seed=bad)
    env.reset(seed=2**53 - 1)
    with pytest.raises(fm.FuzzymotivError, match="num_envs: expected a whole number"):
        fmgym.KheperaVectorEnv(num_envs=2.5, room="H")
    vec = fmgym.KheperaVectorEnv(num_envs=3, room="H", overrides=SHORT)
    with pytest.raises(fm.FuzzymotivError, match=r"seed: -2 is not a seed"):
        vec.reset(seed=[1, -2, 3])
    vec.reset(seed=[1, None, 3])


def test_native_step_refuses_infinite_motor_outputs_before_any_env_moves():
    """The vector env hands an (N, 2) float64 or (N,) int64 array to the native step as is, so
    the native step itself refuses infinities (it clipped them to 1 before) and bad action
    numbers, before any env moves; the vector env names the fault as for any other argument."""
    vec = fmgym.KheperaVectorEnv(2, "H", overrides=SHORT, dtype=np.float64)
    twin = fmgym.KheperaVectorEnv(2, "H", overrides=SHORT, dtype=np.float64)
    vec.reset(seed=3)
    twin.reset(seed=3)
    for bad in [[np.inf, 0.5], [0.5, -np.inf]]:
        with pytest.raises(fm.FuzzymotivError, match="not finite"):
            vec._core.step(np.array([[0.2, 0.9], bad]))
        with pytest.raises(fm.FuzzymotivError, match=r"action: expected 2 pair\(s\) of finite"):
            vec.step(np.array([[0.2, 0.9], bad]))
    a = np.array([[0.2, 0.9], [1.0, 1.0]])
    got, want = vec.step(a), twin.step(a)
    assert np.array_equal(got[0], want[0]) and np.array_equal(got[4]["x"], want[4]["x"])
    discrete = fmgym.KheperaVectorEnv(2, "H", overrides=SHORT, discrete=True)
    discrete.reset(seed=3)
    with pytest.raises(fm.FuzzymotivError, match="7 is not an action"):
        discrete.step(np.array([1, 7]))
    assert (discrete.step(np.array([1, 2]))[4]["t"] == 1).all()
