"""The exception classes: everything under FuzzymotivError (a ValueError), the class picked by
what went wrong — a config (ConfigError), an output that must not be replaced
(OutputExistsError), a gym env used before reset() (ResetNeeded), an optional package missing
(DependencyNotInstalled), a file-system failure (FuzzymotivOSError, with errno)."""

import errno
import pickle
import sys

import numpy as np
import pytest

import fuzzymotiv as fm

TINY = {"ga.population": 4, "ga.generations": 1, "trial.steps": 20, "rooms": ["H"],
        "aem.enabled": False}


def test_every_error_class_is_a_fuzzymotiv_error_and_a_value_error():
    for cls in (fm.ConfigError, fm.OutputExistsError, fm.ResetNeeded, fm.DependencyNotInstalled,
                fm.FuzzymotivOSError):
        assert issubclass(cls, fm.FuzzymotivError) and issubclass(cls, ValueError)
        assert cls.__module__ == "fuzzymotiv"
    assert issubclass(fm.FuzzymotivOSError, OSError)


def test_a_config_that_cannot_be_used_raises_config_error():
    with pytest.raises(fm.ConfigError, match="population"):
        fm.Problem(config_text="[ga]\npopulation = -3\n")
    with pytest.raises(fm.ConfigError, match="populaton"):
        fm.run(overrides={"ga.populaton": 5})
    with pytest.raises(fm.ConfigError, match="room"):
        fm.simulate(np.zeros(68), "no-such-room", seed=1)


def test_a_room_file_that_cannot_be_used_raises_config_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "bad"\noutline = [[0, 0], [1, 0]]\n')
    with pytest.raises(fm.ConfigError, match="bad.toml"):
        fm.load_room(bad)


def test_a_bad_sweep_raises_config_error():
    with pytest.raises(fm.ConfigError, match="sweep.replicates"):
        fm.plan({"sweep": {"replicates": 0}})


def test_another_runs_out_raises_output_exists_error_until_force(tmp_path):
    out = tmp_path / "run"
    fm.run(overrides=TINY, out=out, seed=1)
    with pytest.raises(fm.OutputExistsError, match="force=True"):
        fm.run(overrides=TINY, out=out, seed=2)
    assert fm.run(overrides=TINY, out=out, seed=2, force=True).summary["seed"] == 2


def test_another_file_at_an_export_path_raises_output_exists_error(tmp_path):
    path = tmp_path / "hc.fll"
    path.write_text("mine\n")
    with pytest.raises(fm.OutputExistsError, match="force=True"):
        fm.export_fll([0.8, 0.1, 0, 0.1], path)
    assert path.read_text() == "mine\n"


def test_a_sweep_job_into_another_output_raises_output_exists_error_in_pythons_words(tmp_path):
    """The class comes from what the guard refused, wherever it refused it (here inside a
    job), and the words from its facts: `out` and `force=True`, never the CLI's options."""
    out = tmp_path / "run"
    fm.run(overrides=TINY, out=out, seed=1)
    job = fm.plan({"rooms": ["H"], "ga": {"population": 4, "generations": 1},
                   "trial": {"steps": 20}, "aem": {"enabled": False},
                   "sweep": {"replicates": 1}})[0]
    with pytest.raises(fm.OutputExistsError, match=r"^out .*not a sweep.*force=True") as e:
        fm.run_job(job, out)
    assert "--" not in str(e.value)


def test_a_gym_env_stepped_or_rendered_before_reset_raises_reset_needed():
    fmgym = pytest.importorskip("fuzzymotiv.gym")
    env = fmgym.KheperaEnv("H", render_mode="rgb_array")
    with pytest.raises(fm.ResetNeeded, match=r"call reset\(\) first"):
        env.step([0.5, 0.5])
    with pytest.raises(fm.ResetNeeded, match=r"call reset\(\) first"):
        env.render()


def test_progress_bar_without_tqdm_raises_dependency_not_installed(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    with pytest.raises(fm.DependencyNotInstalled, match="pip install tqdm"):
        fm.run(overrides=TINY, progress=True)


def test_a_file_system_failure_carries_the_os_errno(tmp_path):
    path = tmp_path / ("a" * 300 + ".fll")
    with pytest.raises(fm.FuzzymotivOSError) as e:
        fm.export_fll([0.8, 0.1, 0, 0.1], path)
    assert e.value.errno == errno.ENAMETOOLONG
    assert str(e.value).startswith(str(path))  # the CLI's message, no "[Errno 36]" prefix


def test_the_error_classes_survive_pickling():
    with pytest.raises(fm.ConfigError) as e:
        fm.Problem(config_text="[ga]\npopulation = -3\n")
    again = pickle.loads(pickle.dumps(e.value))
    assert type(again) is fm.ConfigError and str(again) == str(e.value)
