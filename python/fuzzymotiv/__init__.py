"""fuzzymotiv: evolve Khepera controllers under fuzzy motivations, from Python.

Bindings of the Rust library and of the ``fuzzymotiv`` command line (same code, same results
for the same config and seed).

>>> import fuzzymotiv as fm
>>> round(fm.fuzzy_fitness([.8, .1, 0, .1], [.95, .5, 0, .79]), 6)
0.79722
>>> fm.fuzzy_fitness([.5, .3, 0, .2], [[.55, .3, 0, .58], [1, 1, 1, 1]]).round(6)
array([0.263309, 1.      ])
>>> res = fm.run(overrides={"ga.population": 6, "ga.generations": 2, "trial.steps": 50,
...                         "rooms": ["H"], "aem.enabled": False})
>>> res.summary["runs"][0]["run"], len(res.generations["best"])
('all', 2)
>>> tr = fm.simulate(res.best_genome, "H", seed=1, overrides={"trial.steps": 50})
>>> tr["sensors"].shape
(50, 8)

Errors in the input raise :class:`FuzzymotivError`, a ``ValueError`` carrying the message the
CLI prints, or one of its subclasses: :class:`ConfigError` (a config, overrides, a room or
sweep file), :class:`OutputExistsError` (an output at ``out=``/``path=`` that must not be
replaced; ``force=True`` replaces fuzzymotiv's own), :class:`ResetNeeded` (a Gymnasium env
used before ``reset()``), :class:`DependencyNotInstalled` (an optional package missing);
file-system failures raise :class:`FuzzymotivOSError`, both a ``FuzzymotivError`` and an
``OSError`` with ``errno`` set.
"""

from __future__ import annotations

import json
import operator
import os
import warnings
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping, NamedTuple, Optional, Sequence, Union

import numpy as np

from . import _fuzzymotiv as _native
from ._fuzzymotiv import VERSION as __version__
from ._fuzzymotiv import MODEL_VERSION
from ._fuzzymotiv import (
    ConfigError,
    DependencyNotInstalled,
    FuzzymotivError,
    FuzzymotivOSError,
    OutputExistsError,
    ResetNeeded,
)
from . import stats
from .tables import Table, table_of
from .sweeps import Job, Plan, SweepResult, merge, plan, run_job, sweep

__all__ = [
    "DESCRIPTORS",
    "Best",
    "Evaluation",
    "ConfigError",
    "DependencyNotInstalled",
    "FuzzymotivError",
    "FuzzymotivOSError",
    "OutputExistsError",
    "ResetNeeded",
    "GA",
    "Job",
    "Plan",
    "Problem",
    "RunResult",
    "SweepResult",
    "Table",
    "export_fll",
    "frames",
    "fuzzy_fitness",
    "load_room",
    "merge",
    "plan",
    "rooms",
    "run",
    "save_gif",
    "run_job",
    "simulate",
    "stats",
    "sweep",
    "__version__",
    "MODEL_VERSION",
]

_MOTIVATION_KEYS = ("curiosity", "homing", "orientation", "energy")


def _motivations(motivations: Any) -> list:
    """(C, H, O, E) from a sequence of four numbers or a dict with the config's keys."""
    if isinstance(motivations, Mapping):
        unknown = set(motivations) - set(_MOTIVATION_KEYS)
        if unknown:
            raise FuzzymotivError(
                f"motivations: unknown key(s) {sorted(unknown)}; expected {list(_MOTIVATION_KEYS)}"
            )
        return [float(motivations.get(k, 0.0)) for k in _MOTIVATION_KEYS]
    try:
        values = [float(v) for v in motivations]
    except (TypeError, ValueError):
        raise FuzzymotivError(
            f"motivations: expected four numbers (C, H, O, E), got {motivations!r}"
        ) from None
    if len(values) != 4:
        raise FuzzymotivError(
            f"motivations: expected four numbers (C, H, O, E), got {len(values)}"
        )
    return values


def fuzzy_fitness(
    motivations: Any,
    terms: Any,
    explain: bool = False,
    *,
    peaks: Optional[Sequence[float]] = None,
    coefficients: Union[str, Sequence[float], None] = None,
) -> Any:
    """The TSK motivation fitness F of fitness terms Y = (a, g, l, b) under motivations
    X = (C, H, O, E).

    ``terms`` is one vector of four values (→ float) or an ``n × 4`` array (→ numpy array of n
    values). Terms are clamped to [0, 1]. ``explain=True`` returns, for one vector, a dict
    ``{"fitness", "weight_sum", "rules", "text"}`` whose ``rules`` are the firing rules
    (number, labels, label names, weight w, output f); for an array, a list of such dicts.
    ``peaks`` and ``coefficients`` (``"linear"``, ``"ratio"`` or a list) default to the paper's.
    NaN or infinite values anywhere raise :class:`FuzzymotivError` naming the argument, the
    position and the value (as the CLI refuses them).

    >>> round(fuzzy_fitness([.8, .1, 0, .1], [.95, .5, 0, .79]), 6)
    0.79722
    >>> [r["number"] for r in fuzzy_fitness([.8, .1, 0, .1], [1, .25, 0, 0], explain=True)["rules"]]
    [10]
    """
    x = _motivations(motivations)
    y = _real_array("terms", terms, "a vector of 4 or an n × 4 array")
    coef = coefficients
    pk = None if peaks is None else [float(p) for p in peaks]
    if y.ndim == 1:
        if y.shape != (4,):
            raise FuzzymotivError(f"terms: expected four values (a, g, l, b), got {y.shape[0]}")
        if explain:
            return _native.explain(x, y.tolist(), pk, coef)
        return _native.fuzzy_fitness_one(x, y.tolist(), pk, coef)
    if y.ndim == 2:
        if y.shape[1] != 4:
            raise FuzzymotivError(
                f"terms: expected an n × 4 array of (a, g, l, b), got shape {y.shape}"
            )
        many = _native.fuzzy_fitness_many(x, np.ascontiguousarray(y), pk, coef)  # checks every row
        if explain:
            return [_native.explain(x, row.tolist(), pk, coef) for row in y]
        return many
    raise FuzzymotivError(f"terms: expected a vector of 4 or an n × 4 array, got shape {y.shape}")


def export_fll(
    motivations: Any,
    path: Union[str, os.PathLike, None] = None,
    *,
    peaks: Optional[Sequence[float]] = None,
    coefficients: Union[str, Sequence[float], None] = None,
    name: Optional[str] = None,
    force: bool = False,
) -> str:
    """The TSK of ``motivations`` as a fuzzylite FLL engine (625 rules by default); also written
    to ``path`` (atomically; a file with other contents is kept unless ``force=True``, the same
    text again is nothing to do, and a directory, link or device is never replaced).

    The text is the same as ``fuzzymotiv fuzzy --motivations C,H,O,E --export-fll FILE``.

    >>> text = export_fll([.8, .1, 0, .1])
    >>> text.count("\\n  rule: ")
    625
    """
    pk = None if peaks is None else [float(p) for p in peaks]
    return _native.export_fll(
        _motivations(motivations),
        None if path is None else os.fspath(path),
        pk,
        coefficients,
        name,
        force,
    )


def rooms(files: Optional[Sequence[Union[str, os.PathLike]]] = None) -> list:
    """The built-in rooms (or the given room files, validated like ``fuzzymotiv rooms --check``)
    as dicts: ``name``, ``outline`` (n × 2 array, mm), ``obstacles`` (list of arrays),
    ``home`` (``x``, ``y``, ``heading`` in rad, ``heading_deg``), ``home_zone`` (``x``,
    ``y``, ``radius``: the disc a trial can end in), ``area`` (mm²), ``perimeter`` (mm).

    >>> [r["name"] for r in rooms()]
    ['H', 'T', 'L', 'square', 'rectangle']
    """
    if files is None:
        return _native.rooms(None)
    if isinstance(files, (str, os.PathLike)):
        files = [files]
    return _native.rooms([os.fspath(f) for f in files])


def load_room(path: Union[str, os.PathLike]) -> dict:
    """One room file (docs/model.md §4 format) as a dict like those of :func:`rooms`."""
    return _native.rooms([os.fspath(path)])[0]


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


def _sets(overrides: Any) -> list:
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
    arg: str, config: Union[str, os.PathLike, None], text: Optional[str] = None,
    text_arg: str = "config_text", stacklevel: int = 4,
) -> tuple:
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


def _config_args(config: Any, config_text: Optional[str] = None) -> tuple:
    """(path, text) for the native functions' ``config_path`` and ``config_text`` from the
    public ``config=`` (a file's path; None: the built-in defaults) and ``config_text=``."""
    return _config_source("config", config, config_text)


class RunResult:
    """What :func:`run` returns.

    Attributes:
        generations: per generation (and run), the columns of ``generations.csv``
            (``generation, best, mean, std, min, max, a, g, l, b, room``) with the values
            that file holds (9 decimals), with or without ``out``: a :class:`Table` (a dict of
            numpy arrays, whatever is installed; ``.to_pandas()`` for a DataFrame).
        rooms: the per-room table (``room, average_fitness, exploration_pct,
            recognition_pct, battery_pct, homing_pct, r_node``), a :class:`Table`.
        best_genome: the best robot's weights (numpy array; the first run's for per-room
            training, as ``best_genome.json``'s ``weights``).
        best_genomes: per run label, the best robot's weights.
        trajectories: per room, the best robot's room-modelling path (``x``, ``y``,
            ``heading`` arrays), as drawn in the report.
        summary: ``summary.json`` as a dict.
        out: the run directory (written, resumed or read back), or None.
    """

    def __init__(self, native: dict, out: Optional[Path]):
        self.generations = table_of(native["generations"])
        self.rooms = table_of(native["rooms"])
        self.best_genomes = dict(native["best_genomes"])
        self.best_genome = next(iter(self.best_genomes.values()))
        self.trajectories = native["trajectories"]
        self.summary = json.loads(native["summary_json"])
        self.hidden = native["hidden"]
        self.out = out

    def __repr__(self) -> str:
        runs = ", ".join(
            f"{r['run']}: best F {r['best_fitness']:.4f}" for r in self.summary["runs"]
        )
        where = f", out={str(self.out)!r}" if self.out else ""
        return f"<RunResult {self.summary['name']!r} seed {self.summary['seed']} ({runs}){where}>"


def _progress_callback(progress: Any) -> Optional[Callable]:
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            raise DependencyNotInstalled("progress=True needs tqdm (pip install tqdm)") from None
        bar = {}

        def update(done: int, total: int, best: float) -> None:
            if "b" not in bar:
                bar["b"] = tqdm(total=total, unit="gen")
            bar["b"].n = done
            bar["b"].set_postfix(best=f"{best:.3f}", refresh=True)
            if done == total:
                bar["b"].close()

        return update
    raise FuzzymotivError("progress: expected None, True (tqdm) or a callable(done, total, best)")


def run(
    config: Union[str, os.PathLike, None] = None,
    overrides: Any = None,
    threads: Optional[int] = None,
    out: Union[str, os.PathLike, None] = None,
    *,
    seed: Optional[int] = None,
    progress: Any = None,
    force: bool = False,
    config_text: Optional[str] = None,
) -> RunResult:
    """Evolve controllers as ``fuzzymotiv run`` does and return a :class:`RunResult`.

    ``config`` is a config file's path (None: the built-in defaults), ``config_text`` TOML text
    instead (at most one of them); ``overrides``
    a dict of dotted keys, the same as ``--set`` (``{"ga.generations": 20, "rooms": ["H"]}``);
    ``seed`` overrides the base seed (a whole number from 0 to 2^53 − 1). ``threads`` sizes
    the worker pool (1 to 1024; results do not depend on it). ``progress`` is a callable
    ``(done, total, best_F)`` called after every generation, or True for a tqdm bar.

    ``out`` also writes the usual run directory (``generations.csv``, ``summary.json``,
    figures, ``report.html``, ...), by the rules of ``fuzzymotiv run --out``: the same config
    (the same resolved config) on a finished directory runs nothing and returns the result read
    back from it (equal to what the run returned); on an unfinished one (``OUT.partial/``, left
    by Ctrl-C, a failing callback or a killed process) it resumes from the last generation and
    ends with the files of an uninterrupted run. Another run's results or another kind of output
    there raise :class:`FuzzymotivError` unless ``force=True`` (which replaces them, or
    discards the unfinished run); a directory that is not a fuzzymotiv output is never
    replaced, and ``out`` cannot be the current directory.

    The run releases the GIL; Ctrl-C raises KeyboardInterrupt after the current generation.
    Same config and seed → the same numbers as the CLI.

    >>> res = run("configs/tiny.toml", {"ga.generations": 3})  # doctest: +SKIP
    >>> res.generations["best"][-1]                           # doctest: +SKIP
    """
    path, text = _config_args(config, config_text)
    sets = _sets(overrides)
    out_path = None if out is None else os.fspath(out)
    if out_path == "":
        raise FuzzymotivError("out: an empty path; give a directory, e.g. out=\"runs/tiny\"")
    native = _native.run(
        path, text, sets, threads, out_path, _progress_callback(progress), seed, bool(force)
    )
    return RunResult(native, None if out_path is None else Path(out_path))


def simulate(
    genome: Any,
    room: Union[str, os.PathLike],
    seed: int,
    config: Union[str, os.PathLike, None] = None,
    overrides: Any = None,
    *,
    config_text: Optional[str] = None,
) -> dict:
    """Run ``genome`` (the network's weights) for one trial from home in ``room`` (a room of the
    config, a built-in room or a room file) under base seed ``seed`` — exactly the trial of
    ``fuzzymotiv replay GENOME --room ROOM --seed SEED``.

    Returns a dict of numpy arrays: ``x``, ``y``, ``heading`` (T + 1 poses: the pose at the
    start of every step, then the final one), ``sensors`` (T × 8), ``motors`` (T × 2,
    mL, mR), ``action`` (T labels: the executed actions), ``idle`` (T booleans: steps after
    the trial ended at home), ``energy`` (T), ``escaped`` (T booleans: out of the home zone
    yet), ``collision`` (T booleans); and the fitness terms ``a``, ``g``, ``l``, ``b`` with
    ``F`` under the config's motivations. ``seed`` is a whole number from 0 to 2^53 − 1; NaN
    or infinite weights raise :class:`FuzzymotivError`.

    >>> tr = simulate(np.zeros(68), "H", seed=3, overrides={"trial.steps": 20})
    >>> tr["x"].shape, tr["sensors"].shape, str(tr["action"][0])
    ((21,), (20, 8), 'straight')
    """
    path, text = _config_args(config, config_text)
    weights = _real_array("genome", genome, "a vector of weights").ravel().tolist()
    return _native.simulate(weights, os.fspath(room), seed, path, text, _sets(overrides))


def _rollout(source: Any) -> Any:
    """A trajectory dict with its columns as the native code takes them (x, y, heading as
    float64 vectors; sensors as a float64 (n, 8) array; action and idle as lists), or the
    genome as a list of floats."""
    if not isinstance(source, Mapping):
        return _real_array("genome", source, "a vector of weights").ravel().tolist()
    cols: dict = {}
    for key in ("x", "y", "heading"):
        if key not in source:
            raise FuzzymotivError(
                f"trajectory: no `{key}` column; expected a dict like fm.simulate's "
                "(x, y, heading, and optionally sensors, action, idle)"
            )
        cols[key] = _float_array(f"trajectory['{key}']", source[key], 1, "a vector")
    sensors = source.get("sensors")
    if sensors is not None:
        a = _float_array("trajectory['sensors']", sensors, 2, "a (T, 8) array")
        if a.shape[1:] != (8,):
            raise FuzzymotivError(
                f"trajectory['sensors']: expected a (T, 8) array of IR readings, got shape {a.shape}"
            )
        cols["sensors"] = a
    if source.get("action") is not None:
        cols["action"] = [str(a) for a in np.asarray(source["action"]).ravel()]
    if source.get("idle") is not None:
        cols["idle"] = [bool(i) for i in np.asarray(source["idle"]).ravel()]
    return cols


def _whole(arg: str, value: Any) -> int:
    try:
        return operator.index(value)
    except TypeError:
        raise FuzzymotivError(f"{arg}: expected a whole number, got {value!r}") from None


def _room_arg(source: Any, room: Any) -> Optional[str]:
    if room is None and isinstance(source, Mapping) and source.get("room") is not None:
        room = source["room"]
    return None if room is None else os.fspath(room)


def frames(
    trajectory_or_genome: Any,
    room: Union[str, os.PathLike, None] = None,
    *,
    size: int = 320,
    stride: int = 1,
    config: Union[str, os.PathLike, None] = None,
    config_text: Optional[str] = None,
    overrides: Any = None,
    seed: Optional[int] = None,
) -> np.ndarray:
    """Frames of a rollout as a ``(T, H, W, 3)`` uint8 array (RGB, ``H = W = size``): the room,
    home zone, the path so far, the robot's body and heading, its eight IR rays (grey and thin
    when they read nothing, red and thick near a wall), the step counter and the action taken —
    the frames of ``fuzzymotiv replay --gif``.

    ``trajectory_or_genome`` is a dict shaped like :func:`simulate`'s result — only ``x``,
    ``y``, ``heading`` (T + 1 poses) are required; ``sensors`` (T or T + 1 rows of 8),
    ``action`` (labels) and ``idle`` are drawn when present — or a genome, run first exactly as
    ``simulate(genome, room, seed, config, overrides)`` (``seed=None``: the config's seed).
    ``room`` is a room of the config, a built-in room or a room file; None means the dict's
    ``room``, else the config's first room. The config also gives the robot's size and sensor
    model. A frame is drawn at poses 0, ``stride``, 2·``stride``, … and at the last pose, so
    ``frames[-1]`` is always where the rollout ends (``stride=len(x)`` draws only the first and
    the last). ``size`` is 64 to 2048 pixels. Same input → the same bytes.

    >>> tr = simulate(np.zeros(68), "H", seed=3, overrides={"trial.steps": 20})
    >>> frames(tr, size=96, stride=5).shape
    (5, 96, 96, 3)
    """
    path, text = _config_args(config, config_text)
    return _native.frames(
        _rollout(trajectory_or_genome), _room_arg(trajectory_or_genome, room),
        _whole("size", size), _whole("stride", stride), seed, path, text, _sets(overrides),
    )


def save_gif(
    frames_or_trajectory: Any,
    path: Union[str, os.PathLike],
    *,
    fps: float = 25.0,
    force: bool = False,
    room: Union[str, os.PathLike, None] = None,
    size: int = 320,
    stride: int = 1,
    config: Union[str, os.PathLike, None] = None,
    config_text: Optional[str] = None,
    overrides: Any = None,
    seed: Optional[int] = None,
) -> int:
    """Write an animated GIF (looping; the last frame held for a second) to ``path`` and return
    its number of frames.

    ``frames_or_trajectory`` is a ``(T, H, W, 3)`` uint8 array (e.g. from :func:`frames`), or
    anything :func:`frames` takes, drawn with its ``room``, ``size``, ``stride``, ``config``,
    ``overrides`` and ``seed``. Colours are mapped to one fixed 256-colour palette that holds
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
        seed, cfg_path, text, _sets(overrides),
    )


DESCRIPTORS = tuple(_native.Problem.descriptor_names())
"""The behaviour descriptors :meth:`Problem.evaluate` can return (docs/model.md §7): final
``x``, ``y`` (normalised to the room's bounding box), the terms ``a``, ``g``, ``b``, and the
fractions of the executed steps that were ``straight``, ``left30``, ``right30``, ``turn180``."""


_KINDS = {"c": "complex numbers", "O": "Python objects", "U": "strings", "S": "bytes", "b": "booleans"}


def _real_array(arg: str, value: Any, what: str) -> np.ndarray:
    """``value`` as a float64 array, or FuzzymotivError naming ``arg`` and ``what`` was expected
    when it is not an array of real numbers: numpy itself would drop an imaginary part with a
    mere ComplexWarning, and read strings and objects as numbers."""
    try:
        a = np.asarray(value)
    except (TypeError, ValueError) as e:
        raise FuzzymotivError(f"{arg}: expected {what} of numbers ({e})") from None
    if a.dtype.kind not in "iuf":
        got = _KINDS.get(a.dtype.kind, "no real numbers")
        raise FuzzymotivError(
            f"{arg}: expected {what} of real numbers (float64), got {got} (dtype {a.dtype})"
        )
    return a.astype(np.float64, copy=False)


def _float_array(arg: str, value: Any, ndim: int, what: str) -> np.ndarray:
    """``value`` as a C-contiguous float64 array of ``ndim`` dimensions, or FuzzymotivError."""
    a = _real_array(arg, value, what)
    if a.ndim != ndim:
        raise FuzzymotivError(f"{arg}: expected {what}, got an array of shape {a.shape}")
    return np.ascontiguousarray(a)


class Evaluation(NamedTuple):
    """What :meth:`Problem.evaluate` returns (numpy arrays)."""

    fitness: np.ndarray
    """F per genome, shape ``(pop,)``: the mean over the rooms of the TSK fitness; higher is
    better (in [0, 1])."""
    terms: np.ndarray
    """The fitness terms a, g, l, b per genome and room, shape ``(pop, rooms, 4)``."""
    descriptors: Optional[np.ndarray]
    """The chosen descriptors per genome and room, shape ``(pop, rooms, D)``, or None when
    none were asked for."""


class Problem:
    """One evolution's fitness function for any optimiser: the validated experiment of a
    config, evaluated in batches.

    ``config``, ``config_text`` and ``overrides`` are :func:`run`'s (a file, TOML text; dotted keys as
    ``--set``); ``seed`` overrides the config's seed. With ``training = "per-room"`` there is
    one problem per room: ``room=NAME``. ``threads`` sizes the pool that evaluates (results do
    not depend on it; None: all cores).

    Attributes: ``genome_size`` (weights per genome), ``rooms`` (the rooms each genome is
    evaluated in), ``motivations`` (C, H, O, E), ``seed``, ``run`` (``"all"`` or the room),
    ``population`` and ``generations`` (the config's GA sizes), ``hidden``, ``steps``.

    >>> p = Problem(overrides={"rooms": ["H", "T"], "trial.steps": 50})
    >>> p.genome_size, p.rooms
    (68, ['H', 'T'])
    >>> ev = p.evaluate(np.zeros((3, p.genome_size)), descriptors=["x", "y"])
    >>> ev.fitness.shape, ev.terms.shape, ev.descriptors.shape
    ((3,), (3, 2, 4), (3, 2, 2))
    """

    def __init__(
        self,
        config: Union[str, os.PathLike, None] = None,
        overrides: Any = None,
        *,
        room: Optional[str] = None,
        threads: Optional[int] = None,
        seed: Optional[int] = None,
        config_text: Optional[str] = None,
    ):
        path, text = _config_args(config, config_text)
        sets = _sets(overrides)
        self._native = _native.Problem(path, text, sets, room, threads, seed)
        # What pickling needs to make this problem again (the file made absolute).
        self._made_from = (path and os.path.abspath(path), text, sets, room, threads, seed)
        self.genome_size: int = self._native.genome_size
        self.rooms: list = self._native.rooms
        self.motivations: tuple = self._native.motivations
        self.seed: int = self._native.seed
        self.run: str = self._native.label
        self.population, self.generations = self._native.ga_sizes
        self.hidden: int = self._native.hidden
        self.steps: int = self._native.steps

    def evaluate(
        self,
        genomes: Any,
        *,
        generation: int = 0,
        seed: Optional[int] = None,
        descriptors: Union[None, bool, str, Sequence[str]] = None,
    ) -> Evaluation:
        """Evaluate a ``(pop, genome_size)`` array of genomes: :class:`Evaluation` of numpy
        arrays ``fitness`` (pop,) — F, higher is better —, ``terms`` (pop, rooms, 4) and
        ``descriptors`` (pop, rooms, D).

        Genome i of ``generation`` g runs on the noise streams the built-in GA gives individual
        i of generation g (seed, run, g, i, room; ``seed=None``: the problem's seed), so
        evaluating generation g's population gives the F that :func:`run` logged for it, and
        the same call gives the same bytes on any number of threads. The GIL is released.

        ``descriptors``: None (default: none computed), True (all of :data:`DESCRIPTORS`), or
        names from it, in the order wanted. Wrong shapes, anything but real numbers (complex,
        strings, objects), NaN or infinite weights raise :class:`FuzzymotivError` naming the
        argument.
        """
        g = _float_array("genomes", genomes, 2, f"a (population, {self.genome_size}) array")
        if descriptors is None or descriptors is False:
            describe, names = False, None
        elif descriptors is True:
            describe, names = True, None
        elif isinstance(descriptors, str):
            describe, names = True, [descriptors]
        elif isinstance(descriptors, Iterable):
            describe, names = True, [str(d) for d in descriptors]
        else:
            raise FuzzymotivError(
                "descriptors: expected None, True, a name or a list of names of "
                f"fuzzymotiv.DESCRIPTORS, got {descriptors!r}"
            )
        fitness, terms, desc, _ = self._native.evaluate(g, generation, seed, describe, names)
        return Evaluation(fitness, terms, desc)

    def __reduce__(self) -> tuple:
        """Pickles as the arguments it was made from (the config file's absolute path or the
        config text, the overrides, room, threads, seed): unpickling builds the same problem
        again, which evaluates to the same bytes (the file must still be there)."""
        return (_problem_again, self._made_from)

    def __repr__(self) -> str:
        return (
            f"<Problem run {self.run!r} rooms {self.rooms} genome_size {self.genome_size} "
            f"seed {self.seed}>"
        )


def _problem_again(path, text, sets, room, threads, seed) -> Problem:
    """A :class:`Problem` from the arguments :meth:`Problem.__reduce__` saved."""
    return Problem(path, sets, room=room, threads=threads, seed=seed, config_text=text)


class Best(NamedTuple):
    """The best genome told to a :class:`GA` so far."""

    genome: np.ndarray
    fitness: float
    generation: int


class GA:
    """The built-in genetic algorithm (docs/model.md §6) as ask/tell steps.

    ``ga.ask()`` gives the current generation's genomes (``(pop, genome_size)``);
    ``ga.tell(F, terms=None)`` takes their F (higher is better; ``terms`` only feed the
    logged means of a, g, l, b) and breeds the next generation. Asking, evaluating with
    ``problem.evaluate(genomes, generation=ga.generation, seed=ga.seed)`` and telling is
    exactly :func:`run`'s evolution: ``ga.history`` equals its ``generations``.

    ``seed`` (None: the problem's) seeds the initial population and breeding; ``genomes``
    warm-starts from given genomes instead of the random initial population (any number of
    them; later generations have the config's population size). ``ga.state`` is a plain,
    versioned dict (JSON types, floats exact) and :meth:`GA.from_state` restores it.

    >>> p = Problem(overrides={"rooms": ["H"], "aem.enabled": False, "ga.population": 6,
    ...                        "trial.steps": 50})
    >>> ga = GA(p)
    >>> for _ in range(2):
    ...     genomes = ga.ask()
    ...     ev = p.evaluate(genomes, generation=ga.generation, seed=ga.seed)
    ...     ga.tell(ev.fitness, ev.terms)
    >>> ga.generation, ga.best.fitness == max(ga.history["best"])
    (2, True)
    """

    def __init__(self, problem: Problem, seed: Optional[int] = None, *, genomes: Any = None):
        if not isinstance(problem, Problem):
            raise FuzzymotivError(f"problem: expected a fuzzymotiv.Problem, got {type(problem).__name__}")
        self.problem = problem
        start = None
        if genomes is not None:
            start = _float_array("genomes", genomes, 2, f"a (population, {problem.genome_size}) array")
        self._native = _native.GA(problem._native, seed, start)

    def ask(self) -> np.ndarray:
        """The current generation's genomes, ``(pop, genome_size)`` (the same until tell)."""
        return self._native.ask()

    def tell(self, fitness: Any, terms: Any = None) -> None:
        """F of the genomes of :meth:`ask` (higher is better), optionally their terms
        ``(pop, rooms, 4)``; breeds the next generation. Each tell needs an :meth:`ask` of
        its generation first (a restored GA's too): telling before asking, or twice, raises
        :class:`FuzzymotivError`."""
        f = _float_array("F", fitness, 1, "one value per genome")
        t = None if terms is None else _float_array("terms", terms, 3, "a (pop, rooms, 4) array")
        self._native.tell(f, t)

    @property
    def generation(self) -> int:
        """The generation :meth:`ask` returns (tells so far)."""
        return self._native.generation

    @property
    def seed(self) -> int:
        """The base seed of the GA's streams; evaluate with it to match :func:`run`."""
        return self._native.seed

    @property
    def best(self) -> Optional[Best]:
        """The best genome told so far (its F and generation), or None before any tell."""
        b = self._native.best
        return None if b is None else Best(*b)

    @property
    def history(self) -> Any:
        """Per generation told, ``generations.csv``'s columns as a :class:`Table` (a dict of
        numpy arrays); a, g, l, b are NaN where tell had no terms."""
        return table_of(self._native.history)

    @property
    def state(self) -> dict:
        """Everything needed to continue: a plain dict (``format``, ``version``, the resolved
        ``config``, ``run``, ``seed``, ``generation``, ``population``, ``history``, ``best``)
        of JSON types; ``json.dumps`` and back restores it exactly."""
        return json.loads(self._native.state_json())

    @classmethod
    def from_state(cls, state: Mapping, problem: Optional[Problem] = None) -> "GA":
        """A GA from :attr:`state`; ``problem`` (optional) must be made from the same config;
        without it one is made from the state's config."""
        if not isinstance(state, Mapping):
            raise FuzzymotivError(f"state: expected the dict of GA.state, got {type(state).__name__}")
        try:
            text = json.dumps(dict(state), allow_nan=False)
        except (TypeError, ValueError) as e:
            raise FuzzymotivError(f"state: not a GA state ({e})") from None
        if problem is None:
            run = state.get("run")
            config = state.get("config")
            if not isinstance(config, str) or not isinstance(run, str):
                raise FuzzymotivError("state: not a GA state (no config or run)")
            problem = Problem(config_text=config, room=None if run == "all" else run)
        if not isinstance(problem, Problem):
            raise FuzzymotivError(f"problem: expected a fuzzymotiv.Problem, got {type(problem).__name__}")
        self = cls.__new__(cls)
        self.problem = problem
        self._native = _native.GA.from_state_json(text, problem._native)
        return self

    def __reduce__(self) -> tuple:
        """Pickles as its :attr:`state` and its problem: unpickled, it asks and breeds exactly
        as this one would."""
        return (GA.from_state, (self.state, self.problem))

    @classmethod
    def from_run(
        cls,
        run_dir: Union[str, os.PathLike],
        *,
        room: Optional[str] = None,
        problem: Optional[Problem] = None,
        threads: Optional[int] = None,
    ) -> "GA":
        """A GA continuing the finished run directory ``run_dir`` (of :func:`run` or
        ``fuzzymotiv run``): its final population is evaluated again and bred, so
        :meth:`ask` gives the generation after its last and ``history`` holds its generations;
        asking, evaluating and telling up to N generations gives a fresh N-generation run's
        ``generations`` exactly. ``best`` starts as the final generation's best. ``problem``
        (None: one from the run's ``config.resolved.toml``, with ``room`` for per-room
        training and ``threads``) must be of the run's config. ``run_dir`` is only read; a
        directory without ``population.json`` (an older or unfinished run) is an error."""
        path = os.fspath(run_dir)
        if problem is None:
            config = os.path.join(path, "config.resolved.toml")
            if not os.path.isfile(config):
                _native.GA.from_run(path, None)  # raises the error naming what is missing
            problem = Problem(config, room=room, threads=threads)
        elif not isinstance(problem, Problem):
            raise FuzzymotivError(f"problem: expected a fuzzymotiv.Problem, got {type(problem).__name__}")
        self = cls.__new__(cls)
        self.problem = problem
        self._native = _native.GA.from_run(path, problem._native)
        return self

    def __repr__(self) -> str:
        best = "none" if self.best is None else f"{self.best.fitness:.4f}"
        return f"<GA generation {self.generation} seed {self.seed} best F {best}>"
