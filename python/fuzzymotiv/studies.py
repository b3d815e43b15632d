"""Studies of one's own from Python: :func:`study` (re-exported as ``fuzzymotiv.study``).

A study file (arms, paired seeds, typed hypotheses: docs/guide/studies.md) is checked, run and
analysed by the library's study pipeline, the code ``fuzzymotiv study`` runs, so the records a
study writes from Python (``per_seed.csv``, ``arms.csv``, ``study.json``, ``report.md``; with
hypotheses ``claims.csv``, ``rooms.csv``, ``forest.svg``; with several base seeds
``agreement.csv``) are the command line's, byte for byte. Ctrl-C (or an error in
the progress callback) stops the runs at their next generation; the same call again resumes
them from their checkpoints and writes the analysis of an uninterrupted study.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping, Optional, Tuple, Union

from . import _fuzzymotiv as _native
from ._fuzzymotiv import FuzzymotivError
from .config import _config_source
from .sweeps import _out_path, _toml_document
from .tables import Table, read_table

__all__ = ["StudyResult", "study"]


@dataclass
class StudyResult:
    """A study directory (what :func:`study` returns).

    Attributes:
        out: the study directory.
        done, total: the study's runs finished (by this call, earlier ones or other shards),
            and planned.
        claims: ``claims.csv`` (one row per hypothesis and scope: ``effect``, ``ci_low``,
            ``ci_high``, ``p``, ``p_adjusted``, ``detectable``, ``verdict``...) as a
            :class:`~fuzzymotiv.Table` (a dict of numpy arrays; ``.to_pandas()`` for a
            DataFrame); None until every run is finished (other shards).
        per_seed: ``per_seed.csv`` (every run's value of every measure), the same way.
        rooms: ``rooms.csv`` (each hypothesis per room), the same way.
        arms: ``arms.csv`` (each arm's seeds, mean and sd of every measure per scope and room).
        agreement: ``agreement.csv`` (each hypothesis on each base seed's first n seeds beside
            its pooled verdict); an empty table with one base seed.
        A study without hypotheses has empty ``claims`` and ``rooms`` tables.
        report: the path of ``report.md``; ``forest``: of ``forest.svg`` (None until analysed,
            or without hypotheses).
    """

    out: Path
    done: int
    total: int
    claims: Optional[Table]
    per_seed: Optional[Table]
    rooms: Optional[Table]
    arms: Optional[Table]
    agreement: Optional[Table]
    report: Optional[Path]
    forest: Optional[Path]

    @property
    def analysed(self) -> bool:
        """Whether every run is finished and the analysis written."""
        return self.per_seed is not None

    def __repr__(self) -> str:
        state = "analysed" if self.analysed else "waiting for the other shards"
        return f"<StudyResult {str(self.out)!r}: {self.done} of {self.total} runs, {state}>"


def _shard_arg(shard: Union[str, Tuple[int, int], None]) -> Optional[str]:
    """``shard=`` as the command line's ``K/N`` (a ``(k, n)`` pair or the text itself)."""
    if shard is None or isinstance(shard, str):
        return shard
    if isinstance(shard, tuple) and len(shard) == 2 and all(isinstance(v, int) and not isinstance(v, bool) for v in shard):
        return f"{shard[0]}/{shard[1]}"
    raise FuzzymotivError(f"shard: expected (k, n) or \"K/N\" with 0 <= k < n, got {shard!r}")


def study(
    study_file_or_dict: Union[str, "os.PathLike[str]", Mapping[str, Any], None] = None,
    *,
    out: Union[str, "os.PathLike[str]"],
    study_text: Optional[str] = None,
    base_dir: Union[str, "os.PathLike[str]", None] = None,
    threads: Optional[int] = None,
    force: bool = False,
    shard: Union[str, Tuple[int, int], None] = None,
    progress: Optional[Callable[[int, int], Any]] = None,
) -> StudyResult:
    """Run a study as ``fuzzymotiv study FILE --out OUT`` does and return its tables.

    The study is a study file's path (its configs relative to its folder), a dict of the same
    document (``{"study": {...}, "arm": [{...}, ...], "hypothesis": [{...}, ...]}``) or
    ``study_text=`` (TOML text); a dict's or a text's configs are relative to ``base_dir``
    (the working directory by default). Everything is checked before anything runs: a bad
    study raises :class:`ConfigError` naming the file (``(study dict)`` for a dict) and field.

    ``out`` is checked as ``--out`` is (another study there is kept unless ``force=True``);
    finished runs are kept and an interrupted one resumes. ``threads``: worker threads (all
    cores by default; results do not depend on it). ``shard=(k, n)`` runs only the runs whose
    plan index is k mod n; the analysis is written by whichever call finds every run finished
    (until then the result's tables are None). ``progress(done, total)`` is called, in this
    thread, as runs finish (counting this call's runs: its shard's, if it has one). Ctrl-C or
    an exception in ``progress`` stops the runs at their next generation and is raised; the
    same call again resumes the study.
    """
    path: Optional[str]
    text: Optional[str]
    if isinstance(study_file_or_dict, Mapping):
        if study_text is not None:
            raise FuzzymotivError("study and study_text: give one of them, not both")
        path, text = None, _toml_document(study_file_or_dict)
    elif study_file_or_dict is None and study_text is None:
        raise FuzzymotivError("study: expected a study file's path, a dict, or study_text=")
    elif study_file_or_dict is None or isinstance(study_file_or_dict, (str, os.PathLike)):
        path, text = _config_source("study", study_file_or_dict, study_text, text_arg="study_text", stacklevel=3)
    else:
        raise FuzzymotivError(
            f"study: expected a study file, a dict or study_text=, got {type(study_file_or_dict).__name__}"
        )
    if progress is not None and not callable(progress):
        raise FuzzymotivError(f"progress: expected a callable progress(done, total), got {type(progress).__name__}")
    directory = Path(_out_path(out))
    analysed, done, total = _native.study_run(
        os.fspath(directory),
        path,
        text,
        None if base_dir is None else os.fspath(base_dir),
        threads,
        bool(force),
        _shard_arg(shard),
        progress,
    )
    def table(name: str) -> Optional[Table]:
        if not analysed:
            return None
        return read_table(directory / name) if (directory / name).is_file() else Table()

    return StudyResult(
        out=directory,
        done=done,
        total=total,
        claims=table("claims.csv"),
        per_seed=table("per_seed.csv"),
        rooms=table("rooms.csv"),
        arms=table("arms.csv"),
        agreement=table("agreement.csv"),
        report=directory / "report.md" if analysed else None,
        forest=directory / "forest.svg" if analysed and (directory / "forest.svg").is_file() else None,
    )
