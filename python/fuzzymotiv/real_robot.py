"""A run's evolved controller for a real robot: C99 (the simulator's outputs bit for bit) or a
self-describing JSON document or an ONNX model, as ``fuzzymotiv export`` writes them; and its
robustness to the reality gap, as ``fuzzymotiv robustness`` measures it; and the rooms a robot's
logs are recognised as, as ``fuzzymotiv recognise`` says."""

from __future__ import annotations

import os
import sys
from typing import List, Literal, Optional, Sequence, Union

from . import _fuzzymotiv as _native
from .tables import Table, table_of

PathLike = Union[str, "os.PathLike[str]"]


def export_controller(
    run_or_genome: PathLike,
    *,
    to: Literal["c", "json", "onnx"],
    out: PathLike,
    config: Optional[PathLike] = None,
    room: Optional[str] = None,
    force: bool = False,
    target: Literal["generic", "epuck2", "thymio2", "khepera"] = "generic",
) -> List[str]:
    """Exports the controller of a run directory (or a ``best_genome.json``, its robot from the
    ``config.resolved.toml`` beside it or ``config``) and returns the paths written.

    ``out="-"`` with ``to="json"`` writes the document to ``sys.stdout`` (text) and with
    ``to="onnx"`` the model to ``sys.stdout.buffer`` (bytes), as ``--out -`` does, and returns
    ``[]`` (no file written); ``to="c"`` writes two files, so ``out="-"`` raises ``ValueError``.

    ``to="c"``: ``out`` is a directory (created if missing) receiving ``fm_controller.h`` and
    ``fm_controller.c``; ``to="json"``: ``out`` is the JSON file; ``to="onnx"``: ``out`` is the
    ONNX model. ``target`` (with ``to="c"``) picks a robot's deployment kit, as ``--target``:
    ``"epuck2"``, ``"thymio2"`` (an Aseba program, ``fm_controller.aesl``, with its README and
    golden vectors), ``"khepera"``; the kit must be the one of the run's robot, else
    ``FuzzymotivError`` names both robots; ``"generic"`` (the default) is the plain export. An
    unknown ``target``, or a kit with ``to="json"`` or ``"onnx"``, raises ``FuzzymotivError``
    naming ``target``. Other files there are kept
    unless ``force=True`` (``OutputExistsError``); the same export again writes nothing. A bad
    genome or config raises ``FuzzymotivError`` naming the file and field. ``room`` picks the
    robot evolved in that room (per-room training). The same as ``fuzzymotiv export
    RUN_OR_GENOME --to TO --target TARGET --out OUT``.
    """
    config_path = None if config is None else os.fspath(config)
    if os.fspath(out) == "-":
        data = _native.export_controller_bytes(
            os.fspath(run_or_genome), to, config_path, room, target
        )
        if to == "onnx":
            sys.stdout.flush()
            sys.stdout.buffer.write(data)
            sys.stdout.buffer.flush()
        else:
            sys.stdout.write(data.decode("utf-8"))
            sys.stdout.flush()
        return []
    return _native.export_controller(
        os.fspath(run_or_genome),
        to,
        os.fspath(out),
        config_path,
        room,
        force,
        target,
    )


def robustness(run_dir: PathLike, *, trials: int = 10) -> Table:
    """The run's best robot under the perturbations a real robot brings (sensor and wheel
    noise, the sensor table scaled, each sensor dead, a wheel-speed bias, a larger body), with
    ``trials`` trials per room on the same random streams under every perturbation: one row per
    perturbation, the rows of ``fuzzymotiv robustness RUN_DIR``'s ``robustness.csv``. A run
    whose sensors are the ``linear`` model has no table to scale, so no ``table×k`` rows. What
    the rows change: ``noise=n`` is sensor and wheel noise together; ``wheels×k`` scales both
    wheel speeds alike, which with ``actions`` motion (exact steps) only moves the thresholds
    of the action labels; ``radius=r`` enlarges the body for collisions only, the sensors
    staying at the Khepera's positions (``robustness.md`` ends with these notes).

    Columns: ``perturbation`` (its label, ``none`` first), ``trials``, then for ``f``,
    ``exploration``, ``homing``, ``battery`` and, for a run with one room model (room modelling
    on, all-rooms training), ``recognition`` (the share of trials the unperturbed robot's room
    model recognises as their room) the mean and the bounds of its 95 % bootstrap interval
    (``f``, ``f_lo``, ``f_hi``, ...). A directory that is not a run, or ``trials``
    outside 2..=10000, raises ``FuzzymotivError`` naming it.
    """
    if isinstance(trials, bool) or not isinstance(trials, int):
        raise TypeError(f"trials must be a whole number, got {trials!r}")
    if not 2 <= trials <= 10_000:
        raise _native.FuzzymotivError(
            f"trials must be a whole number in 2..=10000 (an interval needs two trials), got {trials}"
        )
    return table_of(_native.robustness(os.fspath(run_dir), trials))


def recognise(run_dir: PathLike, logs: Sequence[PathLike]) -> Table:
    """The rooms the run's room model (its best robot's SOM, rebuilt as the run trained it)
    recognises in a robot's ``logs``: CSV files, one row per step, with an ``action`` column
    (``straight``, ``left``, ``right``, ``back``) or ``m_left`` and ``m_right`` (motor outputs in
    [0, 1]). One row per log, the rows of ``fuzzymotiv recognise RUN_DIR LOG…``'s
    ``recognised.csv``: ``log``, ``steps``, ``used``, ``room`` (empty: not recognised),
    ``winner`` (the SOM node), ``straight``, ``left``, ``right``, ``back``, and the gate's
    reasons: ``r_node`` (the recognised room's r-node), ``node_distance`` (|winner − r_node|),
    ``gate`` (``aem.threshold``, the widest node distance that passes) and ``vector_distance``
    (the log's distance to the room's stored vector), NaN where no room is recognised. A bad log raises
    ``FuzzymotivError`` naming its file, line and field. ``mL`` and ``mR`` are read as
    ``m_left`` and ``m_right`` (a ``fuzzymotiv replay`` CSV is a log too); other columns
    (``ir0`` ... ``ir7``, a time stamp) are read past.
    """
    if isinstance(logs, (str, os.PathLike)):
        raise TypeError("logs must be a list of paths, not one path")
    if not logs:
        raise _native.FuzzymotivError("name at least one log")
    return table_of(_native.recognise(os.fspath(run_dir), [os.fspath(p) for p in logs]))
