"""Configs and overrides as the native layer takes them: ``config=`` a TOML file's path,
``config_text=`` TOML text, ``overrides=`` dotted keys (``{"ga.population": 20}``, as ``--set``),
``robot=`` a built-in robot's name or a robot file's path.
"""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ._fuzzymotiv import FuzzymotivError, robot_info

__all__ = ["Config", "Overrides", "Robot"]

Config = Union[str, "os.PathLike[str]", None]
"""A config file's path (None: the built-in defaults)."""

Overrides = Union[Mapping[str, Any], Sequence[str], None]
"""Dotted keys and values (``{"ga.generations": 20, "rooms": ["H"]}``) or ``"key=value"``
strings, as ``--set``."""


Robot = Union[str, "os.PathLike[str]", None]
"""A robot: a built-in robot's name (``"khepera"``, ``"epuck2"``, ``"thymio2"``: ``ROBOTS``) or a
robot file's path (relative to the working directory); None: the config's (the Khepera unless
it names one, ``robot = "epuck2"`` or ``[robot] file = "..."``)."""


def _robot_sets(robot: Robot) -> List[str]:
    """The ``--set`` that makes the config's robot ``robot`` (none for None): its
    ``robot.file``, a built-in name or the file's absolute path, read and checked first as the
    CLI reads a robot file (a wrong name or a bad file raises :class:`ConfigError` naming the
    file and the field). The config's other ``[robot]`` keys (radius, ...) stay."""
    if robot is None:
        return []
    if not isinstance(robot, (str, os.PathLike)):
        raise FuzzymotivError(
            f"robot: expected a built-in robot's name or a robot file's path, got {type(robot).__name__}"
        )
    file = robot_info(os.fspath(robot))["file"]
    return [f"robot={{file = {json.dumps(file)}}}"]


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if v != v:
            return "nan"
        if v in (float("inf"), float("-inf")):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, (str, os.PathLike)):
        return json.dumps(os.fspath(value))
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {_toml_value(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise FuzzymotivError(f"overrides: cannot write {value!r} ({type(value).__name__}) as a TOML value")


def _sets(overrides: Any) -> List[str]:
    """``--set`` strings from a dict of dotted keys (or a list of ``"key=value"`` strings)."""
    if overrides is None:
        return []
    if isinstance(overrides, Mapping):
        return [f"{k}={_toml_value(v)}" for k, v in overrides.items()]
    if isinstance(overrides, str):
        return [overrides]
    if not isinstance(overrides, Iterable):
        raise FuzzymotivError(
            "overrides: expected a dict of dotted keys (e.g. {\"ga.population\": 20}) or a list "
            f"of \"key=value\" strings, got {type(overrides).__name__}"
        )
    return [str(s) for s in overrides]


def _looks_like_toml(text: str) -> bool:
    """Whether a string that names no file is meant as TOML text: several lines, or one line
    with a ``key = value``, a ``[table]`` or a ``# comment`` — unless it ends in ``.toml``."""
    line = text.strip()
    if "\n" in line or "\r" in line:
        return True
    if line.lower().endswith(".toml"):
        return False
    return "=" in line or line.startswith(("[", "#"))


def _config_source(
    arg: str, config: Union[str, "os.PathLike[str]", None], text: Optional[str] = None,
    text_arg: str = "config_text", stacklevel: int = 4,
) -> Tuple[Optional[str], Optional[str]]:
    """(path, text) of a config or sweep file given as ``arg`` (a path) or ``text_arg`` (TOML
    text), at most one of them. A path that names no file is an error saying so. A string
    ``arg`` that names no file but looks like TOML text is still read as text for one release,
    with a DeprecationWarning pointing at ``text_arg``."""
    if text is not None:
        if config is not None:
            raise FuzzymotivError(
                f"{arg} and {text_arg}: give one of them, a file's path ({arg}=) or TOML text "
                f"({text_arg}=), not both"
            )
        if not isinstance(text, str):
            raise FuzzymotivError(f"{text_arg}: expected TOML text (a str), got {type(text).__name__}")
        return None, text
    if config is None:
        return None, None
    if not isinstance(config, (str, os.PathLike)):
        raise FuzzymotivError(f"{arg}: expected a file's path, got {type(config).__name__}")
    if isinstance(config, str) and not os.path.isfile(config) and _looks_like_toml(config):
        warnings.warn(
            f"{arg}: TOML text passed as {arg}= is deprecated and will be refused in the next "
            f"release; pass it as {text_arg}= ({arg}= is a file's path)",
            DeprecationWarning,
            stacklevel=stacklevel,
        )
        return None, config
    path = os.fspath(config)
    if path == "":
        raise FuzzymotivError(
            f"{arg}: an empty string names no file; pass a file's path, TOML text as "
            f"{text_arg}=, or None for the built-in defaults"
        )
    if not os.path.exists(path):
        where = "" if os.path.isabs(path) else f" (relative to the working directory {os.getcwd()})"
        raise FuzzymotivError(
            f"{arg}: the file {path} does not exist{where}; {arg} is a TOML file's path "
            f"(TOML text goes in {text_arg}=)"
        )
    return path, None


def _config_args(config: Any, config_text: Optional[str] = None) -> Tuple[Optional[str], Optional[str]]:
    """(path, text) for the native functions' ``config_path`` and ``config_text`` from the
    public ``config=`` (a file's path; None: the built-in defaults) and ``config_text=``."""
    return _config_source("config", config, config_text)
