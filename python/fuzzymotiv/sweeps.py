"""Sweeps from Python through any executor: :func:`plan`, :func:`run_job`, :func:`sweep`,
:func:`merge` (re-exported as ``fuzzymotiv.plan`` and so on).

The planning, the running of a job and the merging are the command line's own code
(``fuzzymotiv plan``, ``sweep``, ``merge``), so a sweep run from Python — in this process's
threads, on Dask, on SLURM through submitit, or with any ``concurrent.futures.Executor`` — writes
the same files as ``fuzzymotiv sweep`` and merges into the same ``results.csv``, byte for byte.

A :class:`Job` is a plain frozen dataclass (its plan line, the sweep's text, source and folder),
and :func:`run_job` a top-level function: both pickle, so any executor can send them to another
process or machine that sees the same file system.

**Locks.** A job runs under its lock, ``OUT/jobs/ID.lock`` (an exclusive ``flock``, the same rule
as ``fuzzymotiv sweep``). A worker that finds a job locked waits for it, then skips the job if the
holder finished it, or resumes it from its checkpoint if the holder died (the operating system
drops a dead process's lock). ``run_job(job, out, wait=False)`` returns ``"running"`` at once
instead of waiting. So two workers — or a resubmitted task beside a dying one — never run or
write the same job twice.
"""

from __future__ import annotations

import concurrent.futures
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, Iterator, Mapping, Optional, Protocol, Sequence, Tuple, Union, overload

from . import _fuzzymotiv as _native
from ._fuzzymotiv import FuzzymotivError
from .config import _config_source, _toml_value
from .tables import Table, read_table

__all__ = ["Job", "Plan", "SweepResult", "merge", "plan", "run_job", "sweep"]


@dataclass(frozen=True)
class Job:
    """One job of a sweep: a line of ``fuzzymotiv plan`` (``index``, ``id``, ``key``,
    ``setting``, ``replicate``, ``seed``, ``overrides``, and ``model``, the model version that
    planned it) and the sweep it belongs to
    (``sweep_text``, ``source``, ``base_dir``: what a worker needs to run it). Picklable."""

    index: int
    id: str
    key: str
    setting: str
    replicate: int
    seed: int
    overrides: Tuple[str, ...]
    model: int
    sweep_text: str = field(repr=False)
    source: str = field(repr=False)
    base_dir: str = field(repr=False)

    def record(self) -> Dict[str, Any]:
        """The job's line of ``plan.jsonl`` as a dict."""
        return {
            "index": self.index,
            "id": self.id,
            "key": self.key,
            "setting": self.setting,
            "replicate": self.replicate,
            "seed": self.seed,
            "overrides": list(self.overrides),
            "model": self.model,
        }


@dataclass(frozen=True)
class Plan(Sequence[Job]):
    """The jobs of a sweep file, in plan order (a sequence of :class:`Job`); ``jsonl`` is the
    text ``fuzzymotiv plan FILE`` prints. Picklable."""

    jobs: Tuple[Job, ...]
    source: str
    jsonl: str = field(repr=False)

    def __len__(self) -> int:
        return len(self.jobs)

    def __iter__(self) -> Iterator[Job]:
        return iter(self.jobs)

    @overload
    def __getitem__(self, i: int) -> Job: ...

    @overload
    def __getitem__(self, i: slice) -> Sequence[Job]: ...

    def __getitem__(self, i: Union[int, slice]) -> Union[Job, Sequence[Job]]:
        return self.jobs[i]


def _toml_document(sweep: Mapping[str, Any]) -> str:
    """A sweep dict as TOML text: one ``key = value`` line per top-level key (tables inline)."""
    return "".join(f"{json.dumps(str(k))} = {_toml_value(v)}\n" for k, v in sweep.items())


def plan(
    sweep_file_or_dict: Union[str, "os.PathLike[str]", Mapping[str, Any], None] = None,
    *,
    sweep_text: Optional[str] = None,
) -> Plan:
    """The jobs of a sweep, with the ids and seeds ``fuzzymotiv plan`` gives them.

    The argument is a sweep file's path (a config with a ``[sweep]`` table; its room files are
    relative to its folder) or a dict of the same document (``{"ga": {...}, "sweep":
    {"replicates": 2, "motivations": [[...]], "grid": {"trial.noise": [0.0, 0.06]}}}``; room
    files relative to the current directory); or, instead, ``sweep_text=`` the document as TOML
    text (TOML text as the first argument still works, with a DeprecationWarning, for one
    release). Every job's config is validated now: a bad point raises
    :class:`FuzzymotivError` before anything runs.
    """
    if isinstance(sweep_file_or_dict, Mapping):
        if sweep_text is not None:
            raise FuzzymotivError(
                "sweep and sweep_text: give one of them, a file's path or dict, or TOML text "
                "(sweep_text=), not both"
            )
        path: Optional[str] = None
        text: Optional[str] = _toml_document(sweep_file_or_dict)
    elif sweep_file_or_dict is None and sweep_text is None:
        raise FuzzymotivError("plan: expected a sweep file's path, a dict, or sweep_text=")
    elif sweep_file_or_dict is None or isinstance(sweep_file_or_dict, (str, os.PathLike)):
        path, text = _config_source(
            "sweep", sweep_file_or_dict, sweep_text, text_arg="sweep_text", stacklevel=3
        )
    else:
        raise FuzzymotivError(
            f"plan: expected a sweep file, a dict or sweep_text=, got {type(sweep_file_or_dict).__name__}"
        )
    sweep_text, source, base_dir, jsonl = _native.sweep_plan(path, text)
    jobs = []
    for line in jsonl.splitlines():
        r = json.loads(line)
        r["overrides"] = tuple(r["overrides"])
        jobs.append(Job(**r, sweep_text=sweep_text, source=source, base_dir=base_dir))
    return Plan(tuple(jobs), source, jsonl)


def _out_path(out: Union[str, "os.PathLike[str]"]) -> str:
    path = os.fspath(out)
    if path == "":
        raise FuzzymotivError('out: an empty path; give the sweep directory, e.g. out="sweeps/s1"')
    return path


def run_job(job: Job, out: Union[str, "os.PathLike[str]"], *, wait: bool = True) -> str:
    """Run one job into the sweep directory ``out`` exactly as ``fuzzymotiv sweep FILE --out
    OUT --index INDEX`` does (the same checks of ``out``, the same files in ``OUT/jobs/ID/``).

    Returns ``"ran"``, ``"skipped"`` (finished before: nothing runs) or, with ``wait=False``,
    ``"running"`` when another worker holds the job's lock. With ``wait=True`` (the default)
    a locked job is waited for, then skipped or resumed (see the module's notes on locks).
    Top-level and picklable, for any executor; the GIL is released while the job runs.
    """
    if not isinstance(job, Job):
        raise FuzzymotivError(f"job: expected a fuzzymotiv.Job from fuzzymotiv.plan, got {type(job).__name__}")
    return _native.sweep_run_job(
        job.sweep_text, job.source, job.base_dir, job.index, job.id, _out_path(out), bool(wait)
    )


@dataclass
class SweepResult:
    """A merged sweep directory (what :func:`sweep` and :func:`merge` return).

    Attributes:
        out: the sweep directory.
        results: ``results.csv`` (one row per room of a finished job) as a
            :class:`~fuzzymotiv.Table` (a dict of numpy arrays: numbers as float64, text as
            str; ``.to_pandas()`` for a DataFrame), whatever is installed.
        aggregate: ``aggregate.csv`` (mean ± std per setting and room), the same way.
        markdown: ``aggregate.md``'s text (the table ``fuzzymotiv merge`` prints).
        jobs: jobs in the plan; ``missing``: how many of them are not finished.
        statuses: per job id, what :func:`run_job` returned (``"ran"``, ``"skipped"``);
            empty for :func:`merge`.
    """

    out: Path
    results: Table
    aggregate: Table
    markdown: str
    jobs: int
    missing: int
    statuses: Dict[str, str] = field(default_factory=dict)

    def __repr__(self) -> str:
        ran = sum(1 for s in self.statuses.values() if s == "ran")
        return (
            f"<SweepResult {str(self.out)!r}: {self.jobs - self.missing} of {self.jobs} jobs "
            f"finished ({ran} ran now)>"
        )


def merge(out: Union[str, "os.PathLike[str]"]) -> SweepResult:
    """Merge the sweep directory ``out`` as ``fuzzymotiv merge OUT`` does (the same
    ``results.csv``, ``aggregate.csv``, ``aggregate.md`` and ``summary.svg``; unfinished jobs
    are left out) and return the tables as a :class:`SweepResult`."""
    path = Path(_out_path(out))
    markdown, jobs, missing, _rows = _native.sweep_merge(os.fspath(path))
    return SweepResult(
        out=path,
        results=read_table(path / "results.csv"),
        aggregate=read_table(path / "aggregate.csv"),
        markdown=markdown,
        jobs=jobs,
        missing=missing,
    )


def _jobs_of(the_plan: Any) -> Sequence[Job]:
    if isinstance(the_plan, Plan):
        return the_plan.jobs
    if isinstance(the_plan, (list, tuple)) and the_plan and all(isinstance(j, Job) for j in the_plan):
        if len({(j.sweep_text, j.source, j.base_dir) for j in the_plan}) != 1:
            raise FuzzymotivError("plan: these jobs come from different sweeps; run one sweep at a time")
        return the_plan
    return plan(the_plan).jobs


class SubmitExecutor(Protocol):
    """Any executor :func:`sweep` can use: ``submit(fn, *args)`` returning an object with
    ``result()`` (``concurrent.futures`` executors, Dask's ``client.get_executor()``, submitit's
    ``AutoExecutor``)."""

    def submit(self, fn: Callable[..., Any], /, *args: Any) -> Any: ...


def sweep(
    the_plan: Union[Plan, Sequence[Job], str, "os.PathLike[str]", Mapping[str, Any]],
    out: Union[str, "os.PathLike[str]"],
    executor: Optional[SubmitExecutor] = None,
    *,
    force: bool = False,
) -> SweepResult:
    """Run every job of ``the_plan`` (a :class:`Plan`, a list of its jobs, or anything
    :func:`plan` takes) into the sweep directory ``out`` through ``executor``, wait, and
    :func:`merge`.

    ``executor`` is anything with ``submit(fn, *args)`` returning an object with ``result()``:
    a ``concurrent.futures`` executor, ``dask.distributed.Client(...).get_executor()``,
    ``submitit.AutoExecutor(...)``. None runs the jobs in this process's threads (as many as
    cores; each job is parallel inside too). Finished jobs are skipped, locked ones waited for;
    results do not depend on the executor, the order or the number of workers. The first job's
    error is raised (after cancelling the jobs not started).

    ``out`` is checked before any job starts, as ``fuzzymotiv sweep`` checks ``--out``: the same
    plan (or one that only adds jobs) goes on; another plan's sweep, or another output, is kept
    unless ``force=True`` (which removes that sweep's own files, never a file of yours).
    """
    jobs = _jobs_of(the_plan)
    path = os.path.abspath(_out_path(out))
    if jobs:
        first = jobs[0]
        _native.sweep_prepare(first.sweep_text, first.source, first.base_dir, path, bool(force))
    own: Optional[concurrent.futures.ThreadPoolExecutor] = None
    if executor is None:
        own = concurrent.futures.ThreadPoolExecutor(max_workers=min(len(jobs), os.cpu_count() or 1))
        executor = own
    try:
        futures = [executor.submit(run_job, job, path) for job in jobs]
        statuses = {}
        try:
            for job, f in zip(jobs, futures):
                statuses[job.id] = f.result()
        except BaseException:
            for f in futures:
                cancel = getattr(f, "cancel", None)
                if cancel is not None:
                    cancel()
            raise
    finally:
        if own is not None:
            own.shutdown(wait=True)
    result = merge(out)
    result.statuses = statuses
    return result
