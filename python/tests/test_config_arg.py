"""`config=` is a file's path or TOML text (README): a string that names no file and looks like
TOML is parsed as TOML (its error has the line and column), one that looks like a file name is
a file that does not exist — the same for every function that takes a config."""

import os
from pathlib import Path

import numpy as np
import pytest

import fuzzymotiv as fm
import fuzzymotiv.gym as fmgym

FEW = {"trial.steps": 5, "ga.population": 4, "ga.generations": 1, "aem.enabled": False}

# Every public entry point that takes a config (or, for plan and sweep, a sweep file).
ENTRY_POINTS = {
    "Problem": lambda c: fm.Problem(c, FEW),
    "run": lambda c: fm.run(c, FEW),
    "simulate": lambda c: fm.simulate(np.zeros(68), "H", seed=1, config=c),
    "frames": lambda c: fm.frames(np.zeros(68), "H", config=c),
    "save_gif": lambda c: fm.save_gif(np.zeros(68), os.devnull, room="H", config=c),
    "KheperaEnv": lambda c: fmgym.KheperaEnv("H", config=c),
    "KheperaVectorEnv": lambda c: fmgym.KheperaVectorEnv(2, "H", config=c),
    "plan": lambda c: fm.plan(c),
}


def refusal(call, config):
    with pytest.raises(fm.FuzzymotivError) as e:
        call(config)
    return str(e.value)


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_config_text_that_does_not_parse_gives_the_toml_error_with_line_and_column(name):
    message = refusal(ENTRY_POINTS[name], "[[[garbage")
    assert "cannot read" not in message and "does not exist" not in message
    assert "line 1, column" in message, message


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_config_file_name_that_names_no_file_says_the_file_does_not_exist(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    arg = "sweep" if name == "plan" else "config"
    for missing in ["no-such-config.toml", "runs/a=1/config.resolved.toml", "no-such-config"]:
        message = refusal(ENTRY_POINTS[name], missing)
        assert message == (
            f"{arg}: the file {missing} does not exist (relative to the working directory "
            f"{os.getcwd()}); {arg} is a TOML file's path or TOML text"
        )
    absolute = tmp_path / "gone.toml"
    assert refusal(ENTRY_POINTS[name], absolute) == (
        f"{arg}: the file {absolute} does not exist; {arg} is a TOML file's path or TOML text"
    )


def test_one_line_toml_text_is_text_and_an_existing_file_wins(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert fm.Problem("seed = 11", FEW).seed == 11
    assert fm.Problem('rooms = ["H"]', FEW).rooms == ["H"]
    # A file whose name looks like TOML text is still the file.
    Path("seed = 3").write_text("seed = 12\n")
    assert fm.Problem("seed = 3", FEW).seed == 12


def test_empty_config_string_is_refused_with_what_to_pass_instead():
    assert refusal(ENTRY_POINTS["Problem"], "") == (
        "config: an empty string is neither a file nor TOML text; pass a file's path, TOML text, "
        "or None for the built-in defaults"
    )
