"""Evolution: the built-in GA as :func:`run` (the CLI's ``run``) and as ask/tell steps
(:class:`GA`), and any optimiser's fitness function (:class:`Problem`)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, NamedTuple, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

from . import _fuzzymotiv as _native
from ._checks import FloatArray, MotivationWeights, _float_array
from ._fuzzymotiv import DependencyNotInstalled, FuzzymotivError
from .config import Config, Overrides, Robot, _config_args, _robot_sets, _sets
from .tables import Table, table_of
from .trials import TermFunction, _supplier, _term_names

__all__ = ["DESCRIPTORS", "Best", "Evaluation", "GA", "GAState", "Problem", "RunResult", "run"]


class RunResult:
    """What :func:`run` returns.

    Attributes:
        generations: per generation (and run), the columns of ``generations.csv``
            (``generation, best, mean, std, min, max, a, g, l, b, room``) with the values
            that file holds (9 decimals), with or without ``out``: a :class:`Table` (a dict of
            numpy arrays, whatever is installed; ``.to_pandas()`` for a DataFrame).
        rooms: the per-room table (``room, average_fitness, exploration_pct,
            recognition_pct, battery_pct, homing_pct, r_node``; a mission run's also
            ``mission_done_pct``, the % of test runs whose mission was done, and, for each term
            measured beyond a, g, l, b — the mission terms, terms of your own —
            ``terms_pct.NAME``, its mean over the test runs in %: table.md's columns), a
            :class:`Table`.
        best_genome: the best robot's weights (numpy array; the first run's for per-room
            training, as ``best_genome.json``'s ``weights``).
        best_genomes: per run label, the best robot's weights.
        trajectories: per room, the best robot's room-modelling path (``x``, ``y``,
            ``heading`` arrays), as drawn in the report.
        summary: ``summary.json`` as a dict.
        out: the run directory (written, resumed or read back), or None.
    """

    def __init__(self, native: Dict[str, Any], out: Optional[Path]) -> None:
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


Progress = Callable[[int, int, float], Any]


def _progress_callback(progress: Union[None, bool, Progress]) -> Optional[Progress]:
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    if progress is True:
        try:
            from tqdm.auto import tqdm  # type: ignore[import-untyped]
        except ImportError:
            raise DependencyNotInstalled("progress=True needs tqdm (pip install tqdm)") from None
        bar: Dict[str, Any] = {}

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
    config: Config = None,
    overrides: Overrides = None,
    threads: Optional[int] = None,
    out: Union[str, "os.PathLike[str]", None] = None,
    *,
    seed: Optional[int] = None,
    progress: Union[None, bool, Progress] = None,
    force: bool = False,
    config_text: Optional[str] = None,
    terms: Optional[Mapping[str, TermFunction]] = None,
    robot: Robot = None,
) -> RunResult:
    """Evolve controllers as ``fuzzymotiv run`` does and return a :class:`RunResult`.

    ``config`` is a config file's path (None: the built-in defaults), ``config_text`` TOML text
    instead (at most one of them); ``overrides``
    a dict of dotted keys, the same as ``--set`` (``{"ga.generations": 20, "rooms": ["H"]}``);
    ``seed`` overrides the base seed (a whole number from 0 to 2^53 − 1). ``robot`` is the robot
    (a built-in robot's name, ``"epuck2"``, or a robot file's path; None: the config's, the
    Khepera unless it names one): its N sensors are the network's inputs, so genomes have
    ``hidden·(N + 1) + 2·(hidden + 1)`` weights; a wrong name or a bad robot file raises
    :class:`ConfigError` naming the file and the field. ``threads`` sizes
    the worker pool (1 to 256; results do not depend on it). ``progress`` is a callable
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

    ``terms`` adds terms of your own, as :class:`Problem` takes them (``{"name": fn}``, a
    config's motivation weighing ``name``): the library calls ``fn`` with every finished trial
    (each evaluation trial, room-modelling run and test run) as a :class:`Trials` of shape
    ``(1, 1)``, as ``fm.simulate(..., terms=...)`` does, so the run, its files
    (``summary.json``'s and table.md's ``% name``, the report) and :attr:`RunResult.rooms`
    (``terms_pct.name``) have the term. The calls hold the GIL, one at a time: a term in
    Python slows a run down. A value out of [0, 1], NaN, the wrong shape, anything but numbers,
    or an exception raises :class:`FuzzymotivError` naming the term and stops the run (with
    ``out``, the unfinished run stays at ``OUT.partial/`` and resumes as after Ctrl-C). The
    CLI has no Python: ``fuzzymotiv replay`` and ``report`` of such a run directory refuse
    its config, whose motivation weighs a term they do not know.

    The run releases the GIL; Ctrl-C raises KeyboardInterrupt after the current generation.
    Same config and seed → the same numbers as the CLI.

    >>> res = run("configs/tiny.toml", {"ga.generations": 3})  # doctest: +SKIP
    >>> res.generations["best"][-1]                           # doctest: +SKIP
    """
    path, text = _config_args(config, config_text)
    sets = _sets(overrides) + _robot_sets(robot)
    out_path = None if out is None else os.fspath(out)
    if out_path == "":
        raise FuzzymotivError("out: an empty path; give a directory, e.g. out=\"runs/tiny\"")
    names = [] if terms is None else _term_names(terms)
    suppliers = [(n, _supplier({n: terms[n]})) for n in names] if terms is not None else []
    native = _native.run(
        path, text, sets, threads, out_path, _progress_callback(progress), seed, bool(force),
        suppliers,
    )
    return RunResult(native, None if out_path is None else Path(out_path))


DESCRIPTORS = tuple(_native.Problem.descriptor_names())
"""The behaviour descriptors :meth:`Problem.evaluate` can return (docs/model.md §7): final
``x``, ``y`` (normalised to the room's bounding box), the terms ``a``, ``g``, ``b``, and the
fractions of the executed steps that were ``straight``, ``left30``, ``right30``, ``turn180``."""


class Evaluation(NamedTuple):
    """What :meth:`Problem.evaluate` returns (numpy arrays)."""

    fitness: FloatArray
    """F per genome, shape ``(pop,)``: the mean over the rooms of the TSK fitness; higher is
    better (in [0, 1])."""
    terms: FloatArray
    """The fitness terms per genome and room, shape ``(pop, rooms, N)``: one per motivation,
    named by :attr:`Problem.term_names` (a, g, l, b for the paper's four)."""
    descriptors: Optional[FloatArray]
    """The chosen descriptors per genome and room, shape ``(pop, rooms, D)``, or None when
    none were asked for."""


class Problem:
    """One evolution's fitness function for any optimiser: the validated experiment of a
    config, evaluated in batches.

    ``config``, ``config_text``, ``overrides`` and ``robot`` are :func:`run`'s (a file, TOML
    text; dotted keys as ``--set``; a built-in robot's name or a robot file's path, the
    config's robot when None); ``seed`` overrides the config's seed. With ``training = "per-room"`` there is
    one problem per room: ``room=NAME``. ``threads`` sizes the pool that evaluates (results do
    not depend on it; None: all cores).

    ``terms`` adds terms of your own: ``{"name": fn}``, each name one a motivation's ``term``
    can weigh (``[motivations] smooth = { weight = 0.3, term = "name" }``). Every
    :meth:`evaluate` calls each ``fn`` once with the generation's evaluation trials
    (:class:`Trials`: x, y, heading, actions, sensors, ... as numpy arrays ``(pop, rooms,
    ...)``); it returns their values ``(pop, rooms)`` in [0, 1], which set F. A value outside
    [0, 1], NaN or the wrong shape raises :class:`FuzzymotivError` naming the term. Trials are
    recorded only when ``terms`` is given.

    A problem only evaluates: room modelling never runs, so a one-room config needs no
    ``aem.enabled = false``.

    Attributes: ``genome_size`` (weights per genome: ``hidden·(N + 1) + 2·(hidden + 1)`` for
    the robot's N sensors, 68 for the Khepera's 8-6-2), ``robot`` (its name), ``sensors``
    (N), ``rooms`` (the rooms each genome is
    evaluated in), ``motivations`` (every motivation's weight, in input order, as a
    :class:`MotivationWeights`: a tuple — ``(C, H, O, E)`` for the paper's four, each other
    motivation after them, e.g. urgency's — with the names in ``.names`` and
    ``.as_dict()``), ``term_names``
    (the N fuzzy inputs' names: the last axis of ``terms``), ``seed``, ``run`` (``"all"`` or
    the room), ``population`` and ``generations`` (the config's GA sizes), ``hidden``,
    ``steps``.

    >>> p = Problem(overrides={"rooms": ["H", "T"], "trial.steps": 50})
    >>> p.genome_size, p.rooms
    (68, ['H', 'T'])
    >>> ev = p.evaluate(np.zeros((3, p.genome_size)), descriptors=["x", "y"])
    >>> ev.fitness.shape, ev.terms.shape, ev.descriptors.shape
    ((3,), (3, 2, 4), (3, 2, 2))
    """

    def __init__(
        self,
        config: Config = None,
        overrides: Overrides = None,
        *,
        room: Optional[str] = None,
        threads: Optional[int] = None,
        seed: Optional[int] = None,
        config_text: Optional[str] = None,
        terms: Optional[Mapping[str, TermFunction]] = None,
        robot: Robot = None,
    ):
        path, text = _config_args(config, config_text)
        sets = _sets(overrides) + _robot_sets(robot)
        names = [] if terms is None else _term_names(terms)
        self._terms: Dict[str, TermFunction] = {} if terms is None else dict(terms)
        self._supply = _supplier(self._terms) if names else None
        self._native = _native.Problem(path, text, sets, room, threads, seed, names)
        # What pickling needs to make this problem again (the file made absolute).
        self._made_from = (
            path and os.path.abspath(path), text, sets, room, threads, seed, self._terms or None
        )
        self.genome_size: int = self._native.genome_size
        self.robot: str = self._native.robot
        self.sensors: int = self._native.sensors
        self.rooms: List[str] = self._native.rooms
        self.motivations = MotivationWeights(self._native.motivations, self._native.motivation_names)
        self.seed: int = self._native.seed
        self.run: str = self._native.label
        self.population, self.generations = self._native.ga_sizes
        self.hidden: int = self._native.hidden
        self.steps: int = self._native.steps
        self.term_names: List[str] = self._native.term_names

    def evaluate(
        self,
        genomes: npt.ArrayLike,
        *,
        generation: int = 0,
        seed: Optional[int] = None,
        descriptors: Union[None, bool, str, Sequence[str]] = None,
    ) -> Evaluation:
        """Evaluate a ``(pop, genome_size)`` array of genomes: :class:`Evaluation` of numpy
        arrays ``fitness`` (pop,) — F, higher is better —, ``terms`` (pop, rooms, N), in the
        order of :attr:`term_names`, and ``descriptors`` (pop, rooms, D).

        Genome i of ``generation`` g runs on the noise streams the built-in GA gives individual
        i of generation g (seed, run, g, i, room; ``seed=None``: the problem's seed), so
        evaluating generation g's population gives the F that :func:`run` logged for it, and
        the same call gives the same bytes on any number of threads. The GIL is released.

        ``descriptors``: None (default: none computed), True (all of :data:`DESCRIPTORS`), or
        names from it or of any term the problem measures (its :attr:`term_names`, a, g, l, b,
        the mission terms when it weighs one, its own ``terms``), in the order wanted. Wrong shapes, anything but real numbers (complex,
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
        fitness, terms, desc, _ = self._native.evaluate(
            g, generation, seed, describe, names, self._supply
        )
        return Evaluation(fitness, terms, desc)

    def __reduce__(self) -> Tuple[Any, ...]:
        """Pickles as the arguments it was made from (the config file's absolute path or the
        config text, the overrides, room, threads, seed, terms: their functions pickle by
        reference): unpickling builds the same problem again, which evaluates to the same bytes
        (the file must still be there)."""
        return (_problem_again, self._made_from)

    def __repr__(self) -> str:
        return (
            f"<Problem run {self.run!r} robot {self.robot!r} rooms {self.rooms} "
            f"genome_size {self.genome_size} seed {self.seed}>"
        )


def _problem_again(
    path: Optional[str], text: Optional[str], sets: List[str], room: Optional[str],
    threads: Optional[int], seed: Optional[int],
    terms: Optional[Mapping[str, TermFunction]] = None,
) -> Problem:
    """A :class:`Problem` from the arguments :meth:`Problem.__reduce__` saved."""
    return Problem(path, sets, room=room, threads=threads, seed=seed, config_text=text, terms=terms)


class Best(NamedTuple):
    """The best genome told to a :class:`GA` so far."""

    genome: FloatArray
    fitness: float
    generation: int


class GAState(TypedDict):
    """:attr:`GA.state`: everything a GA needs to continue, in JSON types (floats exact)."""

    format: str
    version: int
    model: int
    config: str
    run: str
    seed: int
    generation: int
    population: List[List[float]]
    history: List[Dict[str, Any]]
    best: Optional[Dict[str, Any]]


class GA:
    """The built-in genetic algorithm (docs/model.md §6) as ask/tell steps, for the robot of its
    problem (``GA(Problem(robot="epuck2"))``: genomes of that robot's network).

    ``ga.ask()`` gives the current generation's genomes (``(pop, genome_size)``);
    ``ga.tell(F, terms=None)`` takes their F (higher is better; ``terms`` ``(pop, rooms, N)``,
    as :meth:`Problem.evaluate` returns them, only feed the logged means of a, g, l, b and of
    the problem's other :attr:`Problem.term_names`) and breeds the next generation. Asking, evaluating with
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
    >>> ga.generation, bool(ga.best.fitness == max(ga.history["best"]))
    (2, True)
    """

    def __init__(
        self, problem: Problem, seed: Optional[int] = None, *, genomes: Optional[npt.ArrayLike] = None
    ) -> None:
        if not isinstance(problem, Problem):
            raise FuzzymotivError(f"problem: expected a fuzzymotiv.Problem, got {type(problem).__name__}")
        self.problem = problem
        start = None
        if genomes is not None:
            start = _float_array("genomes", genomes, 2, f"a (population, {problem.genome_size}) array")
        self._native = _native.GA(problem._native, seed, start)

    def ask(self) -> FloatArray:
        """The current generation's genomes, ``(pop, genome_size)`` (the same until tell)."""
        return self._native.ask()

    def tell(self, fitness: Any, terms: Any = None) -> None:
        """F of the genomes of :meth:`ask` (higher is better), optionally their terms
        ``(pop, rooms, N)`` (N = ``len(problem.term_names)``); breeds the next generation. Each tell needs an :meth:`ask` of
        its generation first (a restored GA's too): telling before asking, or twice, raises
        :class:`FuzzymotivError`."""
        f = _float_array("F", fitness, 1, "one value per genome")
        t = None if terms is None else _float_array("terms", terms, 3, "a (pop, rooms, N) array")
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
    def history(self) -> Table:
        """Per generation told, ``generations.csv``'s columns as a :class:`Table` (a dict of
        numpy arrays), then one column per other term of :attr:`Problem.term_names`; a term
        is NaN where tell had no terms (a, g, l, b also where the problem does not weigh it)."""
        return table_of(self._native.history)

    @property
    def state(self) -> GAState:
        """Everything needed to continue: a plain dict (``format``, ``version``, the resolved
        ``config``, ``run``, ``seed``, ``generation``, ``population``, ``history``, ``best``)
        of JSON types; ``json.dumps`` and back restores it exactly."""
        state: GAState = json.loads(self._native.state_json())
        return state

    @classmethod
    def from_state(cls, state: Mapping[str, Any], problem: Optional[Problem] = None) -> "GA":
        """A GA from :attr:`state`; ``problem`` (optional) must be made from the same config;
        without it one is made from the state's config (a problem with terms of its own,
        ``terms=``, must be given: the state holds no functions)."""
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

    def __reduce__(self) -> Tuple[Any, ...]:
        """Pickles as its :attr:`state` and its problem: unpickled, it asks and breeds exactly
        as this one would."""
        return (GA.from_state, (self.state, self.problem))

    @classmethod
    def from_run(
        cls,
        run_dir: Union[str, "os.PathLike[str]"],
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
