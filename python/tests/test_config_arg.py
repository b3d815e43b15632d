"""`config=` is a file's path and `config_text=` TOML text, for every function that takes a
config (`plan`: its sweep file and `sweep_text=`). TOML text given as `config=` still works for
one release, with a DeprecationWarning naming `config_text=`."""

import os
import warnings
from pathlib import Path

import numpy as np
import pytest

import fuzzymotiv as fm
import fuzzymotiv.gym as fmgym

FEW = {"trial.steps": 5, "ga.population": 4, "ga.generations": 1, "aem.enabled": False}

# Every public entry point that takes a config (or, for plan, a sweep file): called with the
# path as `path` and the text as `text` (each None when not given).
ENTRY_POINTS = {
    "Problem": lambda path, text: fm.Problem(path, FEW, config_text=text),
    "run": lambda path, text: fm.run(path, FEW, config_text=text),
    "simulate": lambda path, text: fm.simulate(np.zeros(68), "H", 1, path, config_text=text),
    "frames": lambda path, text: fm.frames(np.zeros(68), "H", config=path, config_text=text),
    "save_gif": lambda path, text: fm.save_gif(
        np.zeros(68), os.devnull, room="H", config=path, config_text=text
    ),
    "KheperaEnv": lambda path, text: fmgym.KheperaEnv("H", config=path, config_text=text),
    "KheperaVectorEnv": lambda path, text: fmgym.KheperaVectorEnv(
        2, "H", config=path, config_text=text
    ),
    "plan": lambda path, text: fm.plan(path, sweep_text=text),
}


def names(entry):
    """The path argument's and the text argument's names of an entry point."""
    return ("sweep", "sweep_text") if entry == "plan" else ("config", "config_text")


def refusal(call, path=None, text=None):
    with pytest.raises(fm.FuzzymotivError) as e:
        call(path, text)
    return str(e.value)


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_config_text_that_does_not_parse_gives_the_toml_error_with_line_and_column(name):
    message = refusal(ENTRY_POINTS[name], text="[[[garbage")
    assert "cannot read" not in message and "does not exist" not in message
    assert "line 1, column" in message, message


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_config_file_name_that_names_no_file_says_the_file_does_not_exist(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    arg, text_arg = names(name)
    for missing in ["no-such-config.toml", "runs/a=1/config.resolved.toml", "no-such-config"]:
        message = refusal(ENTRY_POINTS[name], missing)
        assert message == (
            f"{arg}: the file {missing} does not exist (relative to the working directory "
            f"{os.getcwd()}); {arg} is a TOML file's path (TOML text goes in {text_arg}=)"
        )
    absolute = tmp_path / "gone.toml"
    assert refusal(ENTRY_POINTS[name], absolute) == (
        f"{arg}: the file {absolute} does not exist; {arg} is a TOML file's path "
        f"(TOML text goes in {text_arg}=)"
    )


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_config_and_config_text_together_are_refused(name, repo):
    arg, text_arg = names(name)
    message = refusal(ENTRY_POINTS[name], repo / "configs" / "tiny.toml", "seed = 1")
    assert message.startswith(f"{arg} and {text_arg}: give one of them"), message


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_toml_text_as_config_still_works_with_a_deprecation_warning(name):
    arg, text_arg = names(name)
    with pytest.warns(DeprecationWarning, match=f"pass it as {text_arg}=") as caught:
        message = refusal(ENTRY_POINTS[name], "[[[garbage")
    assert "line 1, column" in message, message
    assert caught[0].filename == __file__  # the warning points at the caller's line


def test_config_text_is_read_as_toml_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert fm.Problem(config_text="seed = 11", overrides=FEW).seed == 11
        assert fm.Problem(config_text='rooms = ["H"]', overrides=FEW).rooms == ["H"]


def test_an_existing_file_named_like_toml_text_is_the_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("seed = 3").write_text("seed = 12\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert fm.Problem("seed = 3", FEW).seed == 12


def test_empty_config_string_is_refused_with_what_to_pass_instead():
    assert refusal(ENTRY_POINTS["Problem"], "") == (
        "config: an empty string names no file; pass a file's path, TOML text as config_text=, "
        "or None for the built-in defaults"
    )


def test_a_problem_made_from_config_text_pickles_without_a_warning():
    import pickle

    p = fm.Problem(config_text="seed = 5", overrides=FEW)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        again = pickle.loads(pickle.dumps(p))
    assert again.seed == 5
