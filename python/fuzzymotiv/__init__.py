"""fuzzymotiv: evolve robot controllers (the paper's Khepera, an e-puck2, a Thymio II or a robot
file's robot: ``robot=``) under fuzzy motivations, from Python.

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
``OSError`` with ``errno`` set. What the CLI notes on stderr (motivations normalised,
``force=True`` replacing an output, a sweep job waiting for another worker) is a
``UserWarning`` here (``warnings.warn``); how many jobs ran is returned, not warned; the
library itself never prints.
"""

from __future__ import annotations

from . import stats
from ._fuzzymotiv import MODEL_VERSION
from ._fuzzymotiv import VERSION as __version__
from ._fuzzymotiv import (
    ConfigError,
    DependencyNotInstalled,
    FuzzymotivError,
    FuzzymotivOSError,
    OutputExistsError,
    ResetNeeded,
)
from ._checks import MotivationWeights
from .config import Config, Overrides
from .fuzzy import Coefficients, Explanation, FiringRule, export_fll, fuzzy_fitness
from .optimisers import DESCRIPTORS, GA, Best, Evaluation, GAState, Problem, RunResult, run
from .optimisers import _problem_again  # noqa: F401  (Problems pickled before the split)
from .rollouts import (
    Home,
    HomeZone,
    RoomInfo,
    Trajectory,
    frames,
    load_room,
    rooms,
    save_gif,
    simulate,
)
from .studies import StudyResult, study
from .sweeps import Job, Plan, SweepResult, merge, plan, run_job, sweep
from .real_robot import export_controller, recognise, robustness
from .tables import Table
from .trials import TermFunction, Trials

__all__ = [
    "DESCRIPTORS",
    "Best",
    "Coefficients",
    "Config",
    "ConfigError",
    "DependencyNotInstalled",
    "Evaluation",
    "Explanation",
    "FiringRule",
    "FuzzymotivError",
    "FuzzymotivOSError",
    "GA",
    "GAState",
    "MotivationWeights",
    "Home",
    "HomeZone",
    "Job",
    "OutputExistsError",
    "Overrides",
    "Plan",
    "Problem",
    "ResetNeeded",
    "RoomInfo",
    "RunResult",
    "StudyResult",
    "SweepResult",
    "Table",
    "TermFunction",
    "Trials",
    "Trajectory",
    "export_controller",
    "export_fll",
    "frames",
    "fuzzy_fitness",
    "load_room",
    "merge",
    "plan",
    "recognise",
    "robustness",
    "rooms",
    "run",
    "save_gif",
    "run_job",
    "simulate",
    "stats",
    "study",
    "sweep",
    "__version__",
    "MODEL_VERSION",
]
