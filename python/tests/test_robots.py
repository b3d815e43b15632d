"""Every Python front takes a robot (robot="epuck2", a robot file's path, or a config's
`robot = ...`): the genome length follows its N sensors (N-H-2: hidden·(N + 1) + 2·(hidden + 1)),
observations, trajectories and frames carry N readings, and a wrong robot raises naming it."""

import pickle

import numpy as np
import pytest

import fuzzymotiv as fm

SHORT = {"rooms": ["H"], "trial.steps": 50}


def genome_len(sensors, hidden=6):
    return hidden * (sensors + 1) + 2 * (hidden + 1)


@pytest.fixture(scope="module")
def thymio_config(repo):
    """The Thymio's experiment (configs/thymio2.toml: its 3× rooms), one room, short trials."""
    return str(repo / "configs" / "thymio2.toml")


THYMIO_SHORT = {"rooms": ["../rooms/thymio2/H.toml"], "trial.steps": 40, "aem.enabled": False}


def test_epuck2_problem_evaluates_genomes_of_its_network():
    p = fm.Problem(overrides=SHORT, robot="epuck2", threads=1)
    assert (p.robot, p.sensors, p.hidden) == ("epuck2", 8, 6)
    assert p.genome_size == genome_len(8) == 68
    genomes = np.random.default_rng(3).uniform(-1, 1, (4, p.genome_size))
    ev = p.evaluate(genomes)
    assert ev.fitness.shape == (4,) and np.all((ev.fitness >= 0) & (ev.fitness <= 1))
    # Its own robot: the e-puck2's sensors and body, not the Khepera's.
    khepera = fm.Problem(overrides=SHORT, threads=1).evaluate(genomes).fitness
    assert khepera.tobytes() != ev.fitness.tobytes()
    # A config's robot (a dict of overrides saying "robot": "epuck2") is the same problem.
    same = fm.Problem(overrides={**SHORT, "robot": "epuck2"}, threads=1).evaluate(genomes).fitness
    assert same.tobytes() == ev.fitness.tobytes()


def test_epuck2_problem_rejects_genomes_of_another_length():
    p = fm.Problem(overrides={**SHORT, "network.hidden": 4}, robot="epuck2")
    assert p.genome_size == genome_len(8, hidden=4) == 46
    with pytest.raises(
        fm.FuzzymotivError,
        match=r"expected a \(population, 46\) array \(an 8-4-2 network has 46 weights; "
        r"network.hidden = 4; robot epuck2: 8 sensors\), got shape \(2, 68\)",
    ):
        p.evaluate(np.zeros((2, 68)))


def test_thymio_problem_and_ga_use_seven_inputs(thymio_config):
    p = fm.Problem(thymio_config, THYMIO_SHORT, robot="thymio2", threads=1)
    assert (p.robot, p.sensors, p.genome_size) == ("thymio2", 7, genome_len(7)) == ("thymio2", 7, 62)
    with pytest.raises(fm.FuzzymotivError, match=r"a 7-6-2 network has 62 weights.*got shape \(3, 68\)"):
        p.evaluate(np.zeros((3, 68)))
    ga = fm.GA(p)
    genomes = ga.ask()
    assert genomes.shape == (p.population, 62)
    ev = p.evaluate(genomes, generation=ga.generation, seed=ga.seed)
    ga.tell(ev.fitness, ev.terms)
    assert ga.generation == 1
    with pytest.raises(fm.FuzzymotivError, match=r"genomes"):
        fm.GA(p, genomes=np.zeros((2, 68)))


def test_a_robot_file_path_is_read_as_the_cli_reads_it(repo, monkeypatch):
    monkeypatch.chdir(repo)
    by_path = fm.Problem(overrides=SHORT, robot="robots/epuck2.toml", threads=1)
    by_name = fm.Problem(overrides=SHORT, robot="epuck2", threads=1)
    assert by_path.robot == "epuck2" and by_path.genome_size == 68
    genomes = np.random.default_rng(5).uniform(-1, 1, (3, 68))
    assert by_path.evaluate(genomes).fitness.tobytes() == by_name.evaluate(genomes).fitness.tobytes()
    # The file is recorded by its absolute path: the problem pickles and evaluates elsewhere.
    again = pickle.loads(pickle.dumps(by_path))
    monkeypatch.chdir(repo / "python")
    assert again.evaluate(genomes).fitness.tobytes() == by_name.evaluate(genomes).fitness.tobytes()


def test_the_khepera_by_name_is_the_default_robot():
    genomes = np.random.default_rng(7).uniform(-1, 1, (3, 68))
    named = fm.Problem(overrides=SHORT, robot="khepera", threads=1).evaluate(genomes).fitness
    default = fm.Problem(overrides=SHORT, threads=1).evaluate(genomes).fitness
    assert named.tobytes() == default.tobytes()


@pytest.mark.parametrize(
    "call",
    [
        lambda: fm.Problem(overrides=SHORT, robot="nosuch"),
        lambda: fm.simulate(np.zeros(68), "H", 1, overrides=SHORT, robot="nosuch"),
        lambda: fm.run(overrides={**SHORT, "ga.generations": 1, "ga.population": 4,
                                  "aem.enabled": False}, robot="nosuch"),
        lambda: fm.frames(np.zeros(68), "H", overrides=SHORT, robot="nosuch"),
    ],
    ids=["Problem", "simulate", "run", "frames"],
)
def test_a_wrong_robot_name_raises_naming_it(call, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(fm.ConfigError) as e:
        call()
    assert str(e.value) == (
        f'robot: "nosuch" is neither a built-in robot (khepera, epuck2, thymio2) nor a robot file '
        f"(looked for {tmp_path / 'nosuch'})"
    )


def test_a_config_naming_a_wrong_robot_raises_naming_its_field():
    with pytest.raises(fm.ConfigError, match=r'robot.file`: "nosuch" is neither a built-in robot'):
        fm.Problem(overrides={**SHORT, "robot": "nosuch"})


def test_a_bad_robot_file_raises_naming_the_file_and_field(tmp_path, repo):
    good = (repo / "robots" / "epuck2.toml").read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(good.replace("reading_max = 3731", "reading_max = -5"))
    with pytest.raises(fm.ConfigError, match=rf"{bad}: field `reading_max`"):
        fm.Problem(overrides=SHORT, robot=bad)
    with pytest.raises(fm.FuzzymotivError, match=r"robot: expected a built-in robot's name or a robot file's path, got int"):
        fm.Problem(overrides=SHORT, robot=8)


def test_simulate_and_frames_carry_the_robots_readings(thymio_config):
    tr = fm.simulate(np.zeros(62), "H-x3", 2, thymio_config, THYMIO_SHORT)
    assert tr["sensors"].shape == (40, 7)
    assert tr["sensors"].max() <= 4505.0
    with pytest.raises(fm.FuzzymotivError, match=r"a 7-6-2 network needs 62 \(network.hidden = 6; robot thymio2: 7 sensors\)"):
        fm.simulate(np.zeros(68), "H-x3", 2, thymio_config, THYMIO_SHORT)
    video = fm.frames(tr, config=thymio_config, overrides=THYMIO_SHORT, size=64, stride=20)
    assert video.shape == (3, 64, 64, 3)
    with pytest.raises(fm.FuzzymotivError, match=r"expected a \(T, 7\) array of readings \(the robot thymio2 has 7 sensors\)"):
        fm.frames(dict(tr, sensors=np.zeros((40, 8))), config=thymio_config, overrides=THYMIO_SHORT)


def test_run_evolves_the_robots_network(thymio_config):
    res = fm.run(thymio_config, {**THYMIO_SHORT, "ga.generations": 1, "ga.population": 4}, threads=1)
    assert len(res.best_genome) == 62


@pytest.fixture(scope="module")
def gym():
    return pytest.importorskip("gymnasium")


@pytest.fixture(scope="module")
def fmgym(gym):
    import fuzzymotiv.gym

    return fuzzymotiv.gym


def test_thymio_gym_env_observes_its_seven_readings_scaled_to_one(thymio_config, gym, fmgym):
    env = gym.make("fuzzymotiv/Thymio2-v0", room="H-x3", config=thymio_config,
                   overrides=THYMIO_SHORT, dtype=np.float64)
    assert env.observation_space == gym.spaces.Box(0, 1, (7,), np.float64)
    assert (env.unwrapped.robot, env.unwrapped.sensors, env.unwrapped.reading_max) == ("thymio2", 7, 4505.0)
    weights = np.random.default_rng(11).uniform(-2, 2, 62)
    net = fmgym.network(weights, "thymio2")
    obs, _ = env.reset(seed=4)
    seen = [obs]
    done = False
    while not done:
        obs, reward, terminated, truncated, info = env.step(net(obs))
        seen.append(obs)
        done = terminated or truncated
    seen = np.array(seen)
    assert seen.shape[1:] == (7,) and seen.min() >= 0.0 and seen.max() <= 1.0 and seen.max() > 0.0
    # The trial fm.simulate runs, bit for bit: readings / 4505, the same F.
    tr = fm.simulate(weights, "H-x3", 4, thymio_config, THYMIO_SHORT)
    k = len(seen) - 1
    assert np.array_equal(seen[:-1], tr["sensors"][:k] / 4505.0)
    assert reward == tr["F"]
    assert env.unwrapped.trajectory()["sensors"].shape == (k, 7)


def test_thymio_vector_env_observes_seven_readings(thymio_config, fmgym):
    envs = fmgym.RobotVectorEnv(3, "H-x3", config=thymio_config, overrides=THYMIO_SHORT, robot="thymio2")
    assert envs.single_observation_space.shape == (7,)
    obs, _ = envs.reset(seed=0)
    assert obs.shape == (3, 7) and obs.dtype == np.float32
    obs, *_ = envs.step(np.full((3, 2), 0.9))
    assert obs.shape == (3, 7) and np.all((obs >= 0) & (obs <= 1))


def test_each_builtin_robot_has_its_env_ids(gym, fmgym):
    for robot, sensors in (("khepera", 8), ("epuck2", 8)):
        for env_id, space in zip(fmgym.ENV_IDS[robot], (gym.spaces.Box, gym.spaces.Discrete)):
            env = gym.make(env_id, room="H", overrides={"trial.steps": 5})
            assert env.unwrapped.robot == robot
            assert env.observation_space.shape == (sensors,)
            assert isinstance(env.action_space, space)
    assert fmgym.KheperaEnv is fmgym.RobotEnv


def test_network_follows_the_robots_sensors(fmgym):
    with pytest.raises(fm.FuzzymotivError, match=r"68 weights is no 7-h-2 network's length \(10·h \+ 2"):
        fmgym.network(np.zeros(68), "thymio2")
    net = fmgym.network(np.zeros(62), "thymio2")
    assert net(np.zeros(7)).shape == (2,)
    with pytest.raises(fm.FuzzymotivError, match=r"obs: expected 7 sensor inputs"):
        net(np.zeros(8))


def test_trials_of_own_terms_carry_the_robots_readings(repo, monkeypatch):
    monkeypatch.chdir(repo)  # config text's rooms are relative to the working directory
    seen = []

    def spy(trials):
        seen.append(trials.sensors.shape)
        return np.full(trials.shape, 0.5)

    text = (
        'robot = "thymio2"\nrooms = ["rooms/thymio2/H.toml"]\n[trial]\nsteps = 30\n[aem]\nenabled = false\n'
        '[motivations]\nown = { weight = 1.0, term = "spy" }\n'
    )
    p = fm.Problem(config_text=text, terms={"spy": spy})
    p.evaluate(np.zeros((2, 62)))
    tr = fm.simulate(np.zeros(62), "H-x3", 1, config_text=text, terms={"spy": spy})
    assert seen == [(2, 1, 30, 7), (1, 1, 30, 7)] and tr["sensors"].shape == (30, 7)


def test_guide_robots_section_runs(doc_blocks, repo, monkeypatch):
    """The guide's "Robots" code (docs/guide/python.md) runs as written."""
    (code,) = doc_blocks("docs/guide/python.md", "## Robots")
    monkeypatch.chdir(repo)
    exec(compile(code, "docs/guide/python.md (Robots)", "exec"), {})


def test_a_config_with_own_terms_reads_its_robot_file_as_a_robot_file(tmp_path):
    """With terms of your own the config's files are found by the package's own finder: a
    robot file there is read (and refused) as a robot file, not as a room file."""
    (tmp_path / "bot.toml").write_bytes(b"name = \"\xff\"\n")
    text = 'robot = "bot.toml"\nrooms = ["H"]\n[aem]\nenabled = false\n[motivations]\nown = { weight = 1.0, term = "spy" }\n'
    config = tmp_path / "c.toml"
    config.write_text(text)
    with pytest.raises(fm.FuzzymotivError, match=r"bot\.toml: line 1: byte 0xff is not UTF-8 text; a robot file is UTF-8 text"):
        fm.Problem(config, terms={"spy": lambda t: np.full(t.shape, 0.5)})
