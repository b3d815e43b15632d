"""Terms of your own in the Gymnasium envs (terms={"name": fn}): the reward at the end is
fm.simulate's F with the same terms, bit for bit; the vector env; bad terms; the guide."""

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")

import fuzzymotiv as fm  # noqa: E402
import fuzzymotiv.gym as fmgym  # noqa: E402

from test_gym import drive, golden  # noqa: E402

SHORT = """rooms = ["H", "T"]
[trial]
steps = 40
[aem]
enabled = false
"""

SMOOTH_WEIGHED = (
    "\n[motivations]\ncuriosity = 0.6\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\n"
    'smooth = { weight = 0.2, term = "smooth" }\n'
)


def one_term(name: str) -> str:
    """A config whose only motivation weighs the term `name`."""
    return SHORT + f'[motivations]\nown = {{ weight = 1.0, term = "{name}" }}\n'


def constant(value: float):
    return lambda trials: np.full(trials.shape, value)


def smoothness(trials: fm.Trials) -> np.ndarray:
    turn = np.abs(np.angle(np.exp(1j * np.diff(trials.heading, axis=-1))))
    moving = ~trials.idle
    return 1 - (turn * moving).sum(-1) / np.maximum(moving.sum(-1), 1) / np.pi


def test_an_episodes_reward_with_a_term_of_your_own_is_simulates_f(repo):
    """A saved genome driven through the env (ends at T and at home): one call of the term per
    episode with the whole trial (1, 1, T + 1), and the reward at the end is fm.simulate's F
    with the same term, bit for bit; info carries the term's value at the end only."""
    weights, path = golden(repo, "default")
    config = open(path).read() + SMOOTH_WEIGHED
    calls = []

    def smooth(trials):
        calls.append(trials)
        return smoothness(trials)

    net = fmgym.network(weights)
    cases = [("H", 0), ("T", 11), ("rectangle", 2)]
    env = fmgym.KheperaEnv([r for r, _ in cases], config_text=config, dtype=np.float64,
                           terms={"smooth": smooth})
    homes = 0
    for room, seed in cases:
        calls.clear()
        tr = fm.simulate(weights, room, seed, config_text=config, terms={"smooth": smooth})
        (want,) = calls
        calls.clear()
        _, infos, rewards, home = drive(env, net, seed, room)
        (got,) = calls
        assert got.shape == (1, 1) and got.rooms == [room]
        assert got.x.shape == (1, 1, env.max_steps + 1)
        for key in ("x", "y", "heading", "actions", "idle", "energy", "sensors", "executed"):
            assert np.array_equal(getattr(got, key), getattr(want, key)), (room, key)
        assert rewards[-1] == tr["F"] and np.all(rewards[:-1] == 0.0), room
        assert infos[-1]["smooth"] == tr["smooth"] and 0 < tr["smooth"] <= 1
        assert all("smooth" not in i for i in infos[:-1])
        plain = fm.simulate(weights, room, seed, config=path)
        assert tr["F"] != plain["F"] and [tr[t] for t in "agb"] == [plain[t] for t in "agb"]
        homes += home
    assert homes >= 1  # the rectangle's trial ends at home


@pytest.mark.parametrize("value, f", [(0.25, 0.0625), (0.75, 0.5625), (0.0, 0.0), (1.0, 1.0)])
def test_a_constant_term_sets_the_episodes_reward_by_its_formula(value, f):
    """One motivation of weight 1 on a term of constant value v at a label's peak: the
    episode's reward is F = v · C(v) = v² (as fm.Problem's test of the same formula)."""
    for env_id in ("fuzzymotiv/Khepera-v0", "fuzzymotiv/KheperaDiscrete-v0"):
        env = gym.make(env_id, room="T", config_text=one_term("mine"),
                       terms={"mine": constant(value)})
        env.reset(seed=4)
        done, rewards = False, []
        while not done:
            _, reward, terminated, truncated, info = env.step(env.action_space.sample())
            rewards.append(reward)
            done = terminated or truncated
        assert rewards[-1] == f and info["mine"] == value, env_id
        assert all(r == 0.0 for r in rewards[:-1])


def test_the_vector_env_supplies_terms_at_each_episodes_end():
    """The vector env calls the term once per room with the episodes that ended at a step;
    rewards and info equal single envs'; info[name] is NaN (mask False) elsewhere."""
    config = SHORT + SMOOTH_WEIGHED
    calls = []

    def smooth(trials):
        calls.append((trials.shape, trials.rooms))
        return smoothness(trials)

    n, steps = 5, 40
    vec = fmgym.KheperaVectorEnv(n, ["H", "T"], config_text=config, dtype=np.float64,
                                 terms={"smooth": smooth})
    singles = [fmgym.KheperaEnv(["H", "T"], config_text=config, dtype=np.float64,
                                terms={"smooth": smoothness}) for _ in range(n)]
    obs, info = vec.reset(seed=20)
    assert np.isnan(info["smooth"]).all() and not info["_smooth"].any()
    for i, env in enumerate(singles):
        env.reset(seed=20 + i, options={"room": vec.rooms[info["room"][i]]})
    rng = np.random.default_rng(1)
    for t in range(steps):
        actions = rng.random((n, 2))
        obs, reward, term, trunc, info = vec.step(actions)
        ended = term | trunc
        assert np.array_equal(info["_smooth"], ended)
        assert np.isnan(info["smooth"][~ended]).all()
        for i, env in enumerate(singles):
            _, r, *_, inf = env.step(actions[i])
            assert r == reward[i]
            if ended[i]:
                assert inf["smooth"] == info["smooth"][i]
    assert trunc.all() and (reward > 0).all()
    rooms = sorted({vec.rooms[k] for k in info["room"]})
    assert sorted(r for (_, r) in calls) == [[r] for r in rooms]
    assert sum(shape[0] for shape, _ in calls) == n and all(s[1] == 1 for s, _ in calls)
    # Next step: autoreset, nothing supplied.
    *_, info = vec.step(rng.random((n, 2)))
    assert not info["_smooth"].any() and len(calls) == len(rooms)


def test_per_step_reward_with_terms_is_refused_naming_reward_end():
    for make in (fmgym.KheperaEnv, fmgym.KheperaVectorEnv):
        with pytest.raises(fm.FuzzymotivError, match=r'reward: "per-step" cannot be used with '
                           r'terms=.*use reward="end"'):
            make(room="H", config_text=one_term("mine"), terms={"mine": constant(0.5)},
                 reward="per-step")


def test_terms_are_checked_as_problem_checks_them():
    with pytest.raises(fm.ConfigError, match=r"motivations\.own.*\"mine\", which does not exist"):
        fmgym.KheperaEnv("H", config_text=one_term("mine"))
    with pytest.raises(fm.FuzzymotivError, match=r"terms\['mine'\]: expected a function"):
        fmgym.KheperaEnv("H", config_text=one_term("mine"), terms={"mine": 0.5})
    with pytest.raises(fm.FuzzymotivError, match=r"terms: expected a dict"):
        fmgym.KheperaVectorEnv(2, "H", config_text=one_term("mine"), terms=[constant(0.5)])
    with pytest.raises(fm.ConfigError, match=r"terms\.goal.*not one of the library's terms"):
        fmgym.KheperaEnv("H", config_text=one_term("goal"), terms={"goal": constant(0.5)})
    for taken in ("x", "heading", "room", "_mine"):
        with pytest.raises(fm.FuzzymotivError, match=rf"terms\[\"{taken}\"\]: the env reports "
                           r"each term of your own in `info` by its name"):
            fmgym.KheperaEnv("H", config_text=one_term(taken), terms={taken: constant(0.5)})


def boom(trials):
    raise RuntimeError("no smoothness today")


@pytest.mark.parametrize(
    "returned, says",
    [
        (constant(1.5), r"`1\.5` \(genome 0, room 0\) is not a number in \[0, 1\]"),
        (constant(np.nan), r"`nan` \(genome 0, room 0\) is not a number in \[0, 1\]"),
        (lambda t: np.zeros(3), r"returned shape \(3,\), expected \(\d, 1\)"),
        (boom, r"the function raised RuntimeError: no smoothness today"),
    ],
)
def test_a_bad_term_raises_naming_it_and_the_env_needs_a_reset(returned, says):
    """The error names the term at the episode's end; the next step raises ResetNeeded; after
    reset() the env runs again (the term fixed)."""
    broken = [True]

    def wobble(trials):
        return returned(trials) if broken[0] else np.full(trials.shape, 0.25)

    for make in (lambda **kw: fmgym.KheperaEnv("H", **kw),
                 lambda **kw: fmgym.KheperaVectorEnv(2, "H", **kw)):
        env = make(config_text=one_term("wobble"), terms={"wobble": wobble})
        broken[0] = True
        env.reset(seed=0)
        action = np.tile([0.9, 0.3], (getattr(env, "num_envs", 1), 1)).squeeze()
        with pytest.raises(fm.FuzzymotivError, match=r"terms\['wobble'\]: " + says):
            for _ in range(40):
                env.step(action)
        with pytest.raises(fm.ResetNeeded, match=r"call reset\(\) first"):
            env.step(action)
        broken[0] = False
        env.reset(seed=0)
        rewards = [env.step(action)[1] for _ in range(40)]
        assert np.all(np.asarray(rewards[-1]) == 0.0625)


def test_render_draws_an_env_whose_config_weighs_a_term_of_your_own():
    """render() loads the env's config with its terms (the motivation weighing one is known)."""
    if not hasattr(fm, "frames"):
        pytest.skip("fm.frames lands from the frames branch")
    env = fmgym.KheperaEnv("H", config_text=one_term("mine"), terms={"mine": constant(0.5)},
                           render_mode="rgb_array", size=96)
    env.reset(seed=0)
    for _ in range(5):
        env.step(np.array([0.9, 0.4], dtype=np.float32))
    frame = env.render()
    expected = fm.frames(env.trajectory(), "H", size=96, config_text=SHORT)[-1]
    assert frame.shape == (96, 96, 3) and np.array_equal(frame, expected)


def test_simulate_takes_terms_as_problem_does():
    """fm.simulate(terms=...): the term called once with the trial as (1, 1), its value by name
    in the result and in F; the same checks as fm.Problem's."""
    g = np.random.default_rng(3).normal(size=68)
    tr = fm.simulate(g, "T", 5, config_text=one_term("mine"), terms={"mine": constant(0.25)})
    assert tr["mine"] == 0.25 and tr["F"] == 0.0625
    with pytest.raises(fm.FuzzymotivError, match=r"terms\['mine'\]: returned shape \(2,\)"):
        fm.simulate(g, "T", 5, config_text=one_term("mine"), terms={"mine": lambda t: np.ones(2)})
    with pytest.raises(fm.FuzzymotivError, match=r'terms\["F"\]: simulate reports'):
        fm.simulate(g, "T", 5, config_text=one_term("F"), terms={"F": constant(0.5)})


def test_guide_gym_term_of_your_own_runs_as_written(doc_blocks, capsys):
    """docs/guide/motivations.md §7: the block runs and prints F and the term's value."""
    (code,) = doc_blocks("docs/guide/motivations.md", "## 7. The same term as a Gymnasium reward")
    exec(compile(code, "docs/guide/motivations.md (gym term)", "exec"), {})
    out = capsys.readouterr().out
    assert out.startswith("F = 0.") and "smoothness = 0." in out, out


def test_frames_and_gifs_of_a_config_weighing_a_term_of_your_own(tmp_path):
    """fm.frames and fm.save_gif take terms= as fm.Problem does: the config parses, the term is
    not called (a path does not depend on F), and the genome's frames are those of its
    simulated trajectory; without terms= the config's unknown term is named."""
    config = SHORT + SMOOTH_WEIGHED
    calls = []

    def smooth(trials):
        calls.append(1)
        return smoothness(trials)

    genome = np.zeros(68)
    tr = fm.simulate(genome, "H", seed=3, config_text=config, terms={"smooth": smooth})
    calls.clear()
    from_genome = fm.frames(genome, "H", size=64, stride=10, seed=3, config_text=config,
                            terms={"smooth": smooth})
    from_trajectory = fm.frames(tr, size=64, stride=10, config_text=config, terms={"smooth": smooth})
    assert np.array_equal(from_genome, from_trajectory)
    n = fm.save_gif(genome, tmp_path / "a.gif", room="H", size=64, stride=10, seed=3,
                    config_text=config, terms={"smooth": smooth})
    assert n == from_genome.shape[0] and (tmp_path / "a.gif").stat().st_size > 0
    assert calls == []
    with pytest.raises(fm.FuzzymotivError, match="smooth"):
        fm.frames(genome, "H", size=64, config_text=config)
