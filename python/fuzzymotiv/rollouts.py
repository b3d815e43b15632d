"""Rooms, one trial (:func:`simulate`) and its pictures (:func:`frames`, :func:`save_gif`)."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, TypedDict, Union, cast

import numpy as np
import numpy.typing as npt

from . import _fuzzymotiv as _native
from ._checks import FloatArray, _float_array, _real_array, _whole
from ._fuzzymotiv import FuzzymotivError
from .config import Config, Overrides, Robot, _config_args, _robot_sets, _sets
from .trials import TermFunction, _supplier, _term_names

__all__ = ["Home", "HomeZone", "RoomInfo", "Trajectory", "frames", "load_room", "rooms",
           "save_gif", "simulate"]


class Home(TypedDict):
    """A room's home pose (mm; heading in rad and in degrees)."""

    x: float
    y: float
    heading: float
    heading_deg: float


class HomeZone(TypedDict):
    """The disc a trial can end in (mm)."""

    x: float
    y: float
    radius: float


class RoomInfo(TypedDict):
    """A room as :func:`rooms` and :func:`load_room` return it."""

    name: str
    outline: FloatArray
    obstacles: List[FloatArray]
    home: Home
    home_zone: HomeZone
    area: float
    perimeter: float


class Trajectory(TypedDict):
    """One trial as :func:`simulate` returns it."""

    x: FloatArray
    y: FloatArray
    heading: FloatArray
    sensors: FloatArray
    motors: FloatArray
    action: npt.NDArray[np.str_]
    idle: npt.NDArray[np.bool_]
    energy: FloatArray
    escaped: npt.NDArray[np.bool_]
    collision: npt.NDArray[np.bool_]
    a: float
    g: float
    l: float
    b: float
    F: float
    room: str
    seed: int


def rooms(
    files: Union[str, "os.PathLike[str]", Sequence[Union[str, "os.PathLike[str]"]], None] = None,
) -> List[RoomInfo]:
    """The built-in rooms (or the given room files, validated like ``fuzzymotiv rooms --check``)
    as dicts: ``name``, ``outline`` (n × 2 array, mm), ``obstacles`` (list of arrays),
    ``home`` (``x``, ``y``, ``heading`` in rad, ``heading_deg``), ``home_zone`` (``x``,
    ``y``, ``radius``: the disc a trial can end in), ``area`` (mm²), ``perimeter`` (mm).

    >>> [r["name"] for r in rooms()]
    ['H', 'T', 'L', 'square', 'rectangle']
    """
    if files is None:
        return cast(List[RoomInfo], _native.rooms(None))
    if isinstance(files, (str, os.PathLike)):
        files = [files]
    return cast(List[RoomInfo], _native.rooms([os.fspath(f) for f in files]))


def load_room(path: Union[str, "os.PathLike[str]"]) -> RoomInfo:
    """One room file (docs/model.md §4 format) as a dict like those of :func:`rooms`."""
    return cast(RoomInfo, _native.rooms([os.fspath(path)])[0])


def simulate(
    genome: Any,
    room: Union[str, "os.PathLike[str]"],
    seed: int,
    config: Config = None,
    overrides: Overrides = None,
    *,
    config_text: Optional[str] = None,
    terms: Optional[Mapping[str, TermFunction]] = None,
    robot: Robot = None,
) -> Trajectory:
    """Run ``genome`` (the network's weights) for one trial from home in ``room`` (a room of the
    config, a built-in room or a room file) under base seed ``seed`` — exactly the trial of
    ``fuzzymotiv replay GENOME --room ROOM --seed SEED``.

    Returns a dict of numpy arrays: ``x``, ``y``, ``heading`` (T + 1 poses: the pose at the
    start of every step, then the final one), ``sensors`` (T × N: the raw readings of the
    robot's N sensors, 0 to its ``reading_max``; the Khepera's 8, 0–1023), ``motors`` (T × 2,
    mL, mR), ``action`` (T labels: the executed actions), ``idle`` (T booleans: steps after
    the trial ended at home), ``energy`` (T), ``escaped`` (T booleans: out of the home zone
    yet), ``collision`` (T booleans); and the fitness terms ``a``, ``g``, ``l``, ``b`` with
    ``F`` under the config's motivations. ``seed`` is a whole number from 0 to 2^53 − 1; NaN
    or infinite weights raise :class:`FuzzymotivError`. ``robot`` is :func:`fuzzymotiv.run`'s
    (a built-in robot's name or a robot file's path; None: the config's); the genome has that
    robot's network's length.

    ``terms={"name": fn}`` supplies terms of your own as :class:`fuzzymotiv.Problem` takes them
    (a config's motivation may weigh them): ``fn`` is called once with the trial as a
    :class:`fuzzymotiv.Trials` of shape ``(1, 1)``; its value is in the result by name and
    sets ``F``.

    >>> tr = simulate(np.zeros(68), "H", seed=3, overrides={"trial.steps": 20})
    >>> tr["x"].shape, tr["sensors"].shape, str(tr["action"][0])
    ((21,), (20, 8), 'straight')
    """
    path, text = _config_args(config, config_text)
    weights = _real_array("genome", genome, "a vector of weights").ravel().tolist()
    names = [] if terms is None else _term_names(terms)
    supply = _supplier(dict(terms)) if terms is not None and names else None
    sets = _sets(overrides) + _robot_sets(robot)
    trajectory = _native.simulate(weights, os.fspath(room), seed, path, text, sets, names, supply)
    return cast(Trajectory, trajectory)


def _rollout(source: Any) -> Union[List[float], Dict[str, Any]]:
    """A trajectory dict with its columns as the native code takes them (x, y, heading as
    float64 vectors; sensors as a float64 (n, N) array, N checked against the robot natively;
    action and idle as lists), or the genome as a list of floats."""
    if not isinstance(source, Mapping):
        weights: List[float] = _real_array("genome", source, "a vector of weights").ravel().tolist()
        return weights
    cols: Dict[str, Any] = {}
    for key in ("x", "y", "heading"):
        if key not in source:
            raise FuzzymotivError(
                f"trajectory: no `{key}` column; expected a dict like fm.simulate's "
                "(x, y, heading, and optionally sensors, action, idle)"
            )
        cols[key] = _float_array(f"trajectory['{key}']", source[key], 1, "a vector")
    sensors = source.get("sensors")
    if sensors is not None:
        cols["sensors"] = _float_array(
            "trajectory['sensors']", sensors, 2, "a (T, N) array (N: the robot's sensors)"
        )
    if source.get("action") is not None:
        cols["action"] = [str(a) for a in np.asarray(source["action"]).ravel()]
    if source.get("idle") is not None:
        cols["idle"] = [bool(i) for i in np.asarray(source["idle"]).ravel()]
    return cols


def _room_arg(source: Any, room: Any) -> Optional[str]:
    if room is None and isinstance(source, Mapping) and source.get("room") is not None:
        room = source["room"]
    return None if room is None else os.fspath(room)


def frames(
    trajectory_or_genome: Union[Mapping[str, Any], npt.ArrayLike],
    room: Union[str, "os.PathLike[str]", None] = None,
    *,
    size: int = 320,
    stride: int = 1,
    config: Config = None,
    config_text: Optional[str] = None,
    overrides: Overrides = None,
    seed: Optional[int] = None,
    terms: Optional[Mapping[str, TermFunction]] = None,
    robot: Robot = None,
) -> npt.NDArray[np.uint8]:
    """Frames of a rollout as a ``(T, H, W, 3)`` uint8 array (RGB, ``H = W = size``): the room,
    home zone, the path so far, the robot's body and heading, its sensors' rays (grey and thin
    when they read nothing, red and thick near a wall), the step counter and the action taken —
    the frames of ``fuzzymotiv replay --gif``.

    ``trajectory_or_genome`` is a dict shaped like :func:`simulate`'s result — only ``x``,
    ``y``, ``heading`` (T + 1 poses) are required; ``sensors`` (T or T + 1 rows of N, one
    reading per sensor of the robot),
    ``action`` (labels) and ``idle`` are drawn when present — or a genome, run first exactly as
    ``simulate(genome, room, seed, config, overrides)`` (``seed=None``: the config's seed).
    ``room`` is a room of the config, a built-in room or a room file; None means the dict's
    ``room``, else the config's first room. The config (and ``robot``, as :func:`simulate`
    takes it) also gives the robot's size, sensors and sensor model. A frame is drawn at poses 0, ``stride``, 2·``stride``, … and at the last pose, so
    ``frames[-1]`` is always where the rollout ends (``stride=len(x)`` draws only the first and
    the last). ``size`` is 64 to 2048 pixels. ``terms`` (as :class:`Problem` takes them) lets
    a config weigh terms of your own; a path does not depend on F, so they are not called.
    Same input → the same bytes.

    >>> tr = simulate(np.zeros(68), "H", seed=3, overrides={"trial.steps": 20})
    >>> frames(tr, size=96, stride=5).shape
    (5, 96, 96, 3)
    """
    path, text = _config_args(config, config_text)
    return _native.frames(
        _rollout(trajectory_or_genome), _room_arg(trajectory_or_genome, room),
        _whole("size", size), _whole("stride", stride), seed, path, text,
        _sets(overrides) + _robot_sets(robot), [] if terms is None else _term_names(terms),
    )


def save_gif(
    frames_or_trajectory: Union[npt.NDArray[np.uint8], Mapping[str, Any], npt.ArrayLike],
    path: Union[str, "os.PathLike[str]"],
    *,
    fps: float = 25.0,
    force: bool = False,
    room: Union[str, "os.PathLike[str]", None] = None,
    size: int = 320,
    stride: int = 1,
    config: Config = None,
    config_text: Optional[str] = None,
    overrides: Overrides = None,
    seed: Optional[int] = None,
    terms: Optional[Mapping[str, TermFunction]] = None,
    robot: Robot = None,
) -> int:
    """Write an animated GIF (looping; the last frame held for a second) to ``path`` and return
    its number of frames.

    ``frames_or_trajectory`` is a ``(T, H, W, 3)`` uint8 array (e.g. from :func:`frames`), or
    anything :func:`frames` takes, drawn with its ``room``, ``size``, ``stride``, ``config``,
    ``overrides``, ``seed``, ``terms`` and ``robot``. Colours are mapped to one fixed 256-colour palette that holds
    the frames' own colours exactly. ``fps`` is 0.01 to 50. The file is written atomically;
    a file with other contents is kept unless ``force=True`` (the same bytes again: nothing to
    do), and a directory, link or device is never replaced.
    """
    if isinstance(frames_or_trajectory, np.ndarray) and frames_or_trajectory.ndim == 4:
        a = frames_or_trajectory
        if a.dtype != np.uint8:
            raise FuzzymotivError(
                f"frames: expected a (T, H, W, 3) uint8 array, got dtype {a.dtype}"
            )
        source: Any = np.ascontiguousarray(a)
    elif isinstance(frames_or_trajectory, np.ndarray) and frames_or_trajectory.dtype == np.uint8:
        raise FuzzymotivError(
            f"frames: a uint8 array of shape {list(frames_or_trajectory.shape)}; expected "
            "(T, H, W, 3) frames (one frame: frames[None])"
        )
    else:
        source = _rollout(frames_or_trajectory)
    cfg_path, text = _config_args(config, config_text)
    return _native.save_gif(
        source, os.fspath(path), float(fps), bool(force),
        _room_arg(frames_or_trajectory, room), _whole("size", size), _whole("stride", stride),
        seed, cfg_path, text, _sets(overrides) + _robot_sets(robot),
        [] if terms is None else _term_names(terms),
    )
