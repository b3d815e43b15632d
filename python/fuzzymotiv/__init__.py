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

Errors in the input (configs, room files, motivations, overrides, NaN or infinite numbers,
an ``out`` directory that must not be replaced) raise :class:`FuzzymotivError`, a
``ValueError`` carrying the message the CLI prints; file-system failures raise
:class:`FuzzymotivOSError`, both a ``FuzzymotivError`` and an ``OSError``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np

from . import _fuzzymotiv as _native
from ._fuzzymotiv import VERSION as __version__
from ._fuzzymotiv import FuzzymotivError, FuzzymotivOSError
from . import stats

__all__ = [
    "FuzzymotivError",
    "FuzzymotivOSError",
    "RunResult",
    "export_fll",
    "fuzzy_fitness",
    "load_room",
    "rooms",
    "run",
    "simulate",
    "stats",
    "__version__",
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
    y = np.asarray(terms, dtype=np.float64)
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
    to ``path`` (atomically; an existing file only with ``force=True``).

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
    return [str(s) for s in overrides]


def _config_args(config: Any) -> tuple:
    """(path, text): a path-like is a file; a string is TOML text if it has a newline or an
    ``=`` and names no existing file, else a file name."""
    if config is None:
        return None, None
    if isinstance(config, os.PathLike):
        return os.fspath(config), None
    if isinstance(config, str):
        if os.path.isfile(config) or ("\n" not in config and "=" not in config):
            return config, None
        return None, config
    raise FuzzymotivError(f"config: expected a path or TOML text, got {type(config).__name__}")


def _frame(columns: dict) -> Any:
    try:
        import pandas as pd
    except ImportError:
        return columns
    return pd.DataFrame(columns)


class RunResult:
    """What :func:`run` returns.

    Attributes:
        generations: per generation (and run), the columns of ``generations.csv``
            (``generation, best, mean, std, min, max, a, g, l, b, room``) with the values
            that file holds (9 decimals), with or without ``out``: a pandas DataFrame when
            pandas is installed, else a dict of numpy arrays.
        rooms: the per-room table (``room, average_fitness, exploration_pct,
            recognition_pct, battery_pct, homing_pct, r_node``), DataFrame or dict.
        best_genome: the best robot's weights (numpy array; the first run's for per-room
            training, as ``best_genome.json``'s ``weights``).
        best_genomes: per run label, the best robot's weights.
        trajectories: per room, the best robot's room-modelling path (``x``, ``y``,
            ``heading`` arrays), as drawn in the report.
        summary: ``summary.json`` as a dict.
        out: the run directory (written, resumed or read back), or None.
    """

    def __init__(self, native: dict, out: Optional[Path]):
        self.generations = _frame(native["generations"])
        self.rooms = _frame(native["rooms"])
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
            raise FuzzymotivError("progress=True needs tqdm (pip install tqdm)") from None
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
) -> RunResult:
    """Evolve controllers as ``fuzzymotiv run`` does and return a :class:`RunResult`.

    ``config`` is a config file path or TOML text (None: the built-in defaults); ``overrides``
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
    >>> res.generations["best"].iloc[-1]                      # doctest: +SKIP
    """
    path, text = _config_args(config)
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
    path, text = _config_args(config)
    weights = np.asarray(genome, dtype=np.float64).ravel().tolist()
    return _native.simulate(weights, os.fspath(room), seed, path, text, _sets(overrides))
