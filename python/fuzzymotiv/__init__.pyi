"""Type stubs of the fuzzymotiv Python API (see the module docstring for examples)."""

import os
from pathlib import Path
from typing import Any, Callable, Literal, Mapping, NamedTuple, Optional, Sequence, TypedDict, Union, overload

import numpy as np
import numpy.typing as npt

from . import stats as stats
from .tables import Table as Table
from .sweeps import Job as Job
from .sweeps import Plan as Plan
from .sweeps import SweepResult as SweepResult
from .sweeps import merge as merge
from .sweeps import plan as plan
from .sweeps import run_job as run_job
from .sweeps import sweep as sweep

__version__: str
MODEL_VERSION: int

Motivations = Union[Sequence[float], Mapping[str, float]]
Coefficients = Union[Literal["linear", "ratio"], Sequence[float], None]
Config = Union[str, os.PathLike[str], None]
Overrides = Union[Mapping[str, Any], Sequence[str], None]
FloatArray = npt.NDArray[np.float64]

class FuzzymotivError(ValueError):
    """Bad input: the message is the one the CLI prints (file, field, what is wrong)."""

class FuzzymotivOSError(FuzzymotivError, OSError):
    """A file-system failure (reading or writing a named path); the message is the CLI's."""

class ConfigError(FuzzymotivError):
    """A config, overrides, a room or a sweep file that cannot be used."""

class OutputExistsError(FuzzymotivError):
    """An output that must not be replaced (``force=True`` replaces fuzzymotiv's own)."""

class ResetNeeded(FuzzymotivError):
    """A Gymnasium environment used before ``reset()``."""

class DependencyNotInstalled(FuzzymotivError):
    """An optional package a call needs is not installed."""

class FiringRule(TypedDict):
    number: int
    labels: list[int]
    label_names: list[str]
    weight: float
    output: float

class Explanation(TypedDict):
    fitness: float
    weight_sum: float
    rules: list[FiringRule]
    text: str

@overload
def fuzzy_fitness(
    motivations: Motivations,
    terms: Sequence[float],
    explain: Literal[False] = ...,
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
) -> float: ...
@overload
def fuzzy_fitness(
    motivations: Motivations,
    terms: Union[Sequence[Sequence[float]], npt.ArrayLike],
    explain: Literal[False] = ...,
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
) -> Union[float, FloatArray]: ...
@overload
def fuzzy_fitness(
    motivations: Motivations,
    terms: npt.ArrayLike,
    explain: Literal[True],
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
) -> Union[Explanation, list[Explanation]]: ...
def export_fll(
    motivations: Motivations,
    path: Union[str, os.PathLike[str], None] = ...,
    *,
    peaks: Optional[Sequence[float]] = ...,
    coefficients: Coefficients = ...,
    name: Optional[str] = ...,
    force: bool = ...,
) -> str: ...

class Home(TypedDict):
    x: float
    y: float
    heading: float
    heading_deg: float

class HomeZone(TypedDict):
    x: float
    y: float
    radius: float

class RoomInfo(TypedDict):
    name: str
    outline: FloatArray
    obstacles: list[FloatArray]
    home: Home
    home_zone: HomeZone
    area: float
    perimeter: float

def rooms(files: Optional[Sequence[Union[str, os.PathLike[str]]]] = ...) -> list[RoomInfo]: ...
def load_room(path: Union[str, os.PathLike[str]]) -> RoomInfo: ...

class RunResult:
    generations: Table
    """generation,best,mean,std,min,max,a,g,l,b,room: a dict of numpy arrays."""
    rooms: Table
    """room,average_fitness,exploration_pct,recognition_pct,battery_pct,homing_pct,r_node."""
    best_genome: FloatArray
    best_genomes: dict[str, FloatArray]
    trajectories: dict[str, dict[str, FloatArray]]
    summary: dict[str, Any]
    hidden: int
    out: Optional[Path]
    def __init__(self, native: dict[str, Any], out: Optional[Path]) -> None:
        """Made by :func:`run` (from the native result)."""

def run(
    config: Config = ...,
    overrides: Overrides = ...,
    threads: Optional[int] = ...,
    out: Union[str, os.PathLike[str], None] = ...,
    *,
    seed: Optional[int] = ...,
    progress: Union[None, bool, Callable[[int, int, float], Any]] = ...,
    force: bool = ...,
    config_text: Optional[str] = ...,
) -> RunResult:
    """Evolve as ``fuzzymotiv run``. With ``out``, the directory follows ``fuzzymotiv run --out``:
    the same finished run is read back (nothing runs), an unfinished one (``OUT.partial/``) is
    resumed, another run's results raise FuzzymotivError unless ``force=True``; a directory that
    is not a fuzzymotiv output is never replaced."""

class Trajectory(TypedDict):
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

def simulate(
    genome: npt.ArrayLike,
    room: Union[str, os.PathLike[str]],
    seed: int,
    config: Config = ...,
    overrides: Overrides = ...,
    *,
    config_text: Optional[str] = ...,
) -> Trajectory: ...

def frames(
    trajectory_or_genome: Union[Mapping[str, Any], npt.ArrayLike],
    room: Union[str, os.PathLike[str], None] = ...,
    *,
    size: int = ...,
    stride: int = ...,
    config: Config = ...,
    config_text: Optional[str] = ...,
    overrides: Overrides = ...,
    seed: Optional[int] = ...,
) -> npt.NDArray[np.uint8]:
    """(T, H, W, 3) uint8 frames of a trajectory dict (x, y, heading; optionally sensors,
    action, idle) or of a genome run as ``simulate`` runs it."""

def save_gif(
    frames_or_trajectory: Union[npt.NDArray[np.uint8], Mapping[str, Any], npt.ArrayLike],
    path: Union[str, os.PathLike[str]],
    *,
    fps: float = ...,
    force: bool = ...,
    room: Union[str, os.PathLike[str], None] = ...,
    size: int = ...,
    stride: int = ...,
    config: Config = ...,
    config_text: Optional[str] = ...,
    overrides: Overrides = ...,
    seed: Optional[int] = ...,
) -> int:
    """Write an animated GIF of frames or of a rollout through the output guard; returns the
    number of frames."""

DESCRIPTORS: tuple[str, ...]

class Evaluation(NamedTuple):
    fitness: FloatArray
    terms: FloatArray
    descriptors: Optional[FloatArray]

class Problem:
    genome_size: int
    rooms: list[str]
    motivations: tuple[float, float, float, float]
    seed: int
    run: str
    population: int
    generations: int
    hidden: int
    steps: int
    def __init__(
        self,
        config: Config = ...,
        overrides: Overrides = ...,
        *,
        room: Optional[str] = ...,
        threads: Optional[int] = ...,
        seed: Optional[int] = ...,
        config_text: Optional[str] = ...,
    ) -> None: ...
    def evaluate(
        self,
        genomes: Any,
        *,
        generation: int = ...,
        seed: Optional[int] = ...,
        descriptors: Union[None, bool, str, Sequence[str]] = ...,
    ) -> Evaluation: ...
    def __reduce__(self) -> tuple[Any, ...]: ...

class Best(NamedTuple):
    genome: FloatArray
    fitness: float
    generation: int

class GAState(TypedDict):
    format: str
    version: int
    config: str
    run: str
    seed: int
    generation: int
    population: list[list[float]]
    history: list[dict[str, Any]]
    best: Optional[dict[str, Any]]

class GA:
    problem: Problem
    def __init__(self, problem: Problem, seed: Optional[int] = ..., *, genomes: Any = ...) -> None: ...
    def ask(self) -> FloatArray: ...
    def tell(self, fitness: Any, terms: Any = ...) -> None: ...
    @property
    def generation(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def best(self) -> Optional[Best]: ...
    @property
    def history(self) -> Table: ...
    @property
    def state(self) -> GAState: ...
    @classmethod
    def from_state(cls, state: Mapping[str, Any], problem: Optional[Problem] = ...) -> GA: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    @classmethod
    def from_run(
        cls,
        run_dir: Union[str, os.PathLike[str]],
        *,
        room: Optional[str] = ...,
        problem: Optional[Problem] = ...,
        threads: Optional[int] = ...,
    ) -> GA:
        """A GA continuing a finished run directory (its final population evaluated again and
        bred): asking, evaluating and telling up to N generations gives a fresh N-generation
        run's ``generations``. The directory is only read."""
