"""Gymnasium environments of a robot's trial (``pip install fuzzymotiv[gym]``).

``import fuzzymotiv.gym`` registers, for each built-in robot (``ENV_IDS``):

* ``fuzzymotiv/Khepera-v0``: observation ``Box(0, 1, (8,))`` — the eight IR sensors / 1023,
  noise included (what the network reads); action ``Box(0, 1, (2,))`` — the two motor outputs
  ``mL, mR`` the network gives the simulator; a finite value outside [0, 1] is clipped to it
  (``(5, -5)`` is ``(1, 0)``, as ``gymnasium.wrappers.ClipAction`` would make it), NaN or an
  infinity raises :class:`fuzzymotiv.FuzzymotivError`;
* ``fuzzymotiv/KheperaDiscrete-v0``: the same with ``Discrete(4)`` actions, executed as given
  (0 ``straight``, 1 ``left30``, 2 ``right30``, 3 ``turn180``; ``motion = "actions"``);
* ``fuzzymotiv/EPuck2-v0`` and ``fuzzymotiv/EPuck2Discrete-v0``: the e-puck2, observation
  ``Box(0, 1, (8,))`` — its eight IR sensors / 3731;
* ``fuzzymotiv/Thymio2-v0`` and ``fuzzymotiv/Thymio2Discrete-v0``: the Thymio II, observation
  ``Box(0, 1, (7,))`` — its seven horizontal IR sensors / 4505 (its rooms must fit its 160 mm
  body: configs/thymio2.toml's, rooms/thymio2/).

In general the observation is ``Box(0, 1, (N,))``: the robot's N readings / its
``reading_max``. ``robot=`` (a built-in robot's name or a robot file's path, as
:func:`fuzzymotiv.run` takes it; None: the config's) chooses the robot of :class:`RobotEnv`
and :class:`RobotVectorEnv` (``KheperaEnv`` and ``KheperaVectorEnv`` are the same classes);
each id above passes its robot (``gym.make(ID, robot=...)`` overrides it).

The step is the library's own (``fuzzymotiv::simulation::TrialRun``): the same
sensors, noise streams, motion model and end at home as :func:`fuzzymotiv.simulate`. An episode
is the trial ``fm.simulate(genome, room, seed)`` runs: reset with ``seed=S`` in room ``R`` and
drive it with the genome's network outputs, and you get that trajectory, bit for bit (with
``dtype=np.float64``; float32 observations are rounded).

``room=`` is a room name (of the config or built in), a room file, or a list of them: each
reset draws one from the env's seeded ``np_random`` (``options={"room": NAME}`` picks one).
Each reset's trial runs under base seed ``seed`` when given, else one drawn from ``np_random``.

Reward (``reward=``): ``"end"`` (default) gives the TSK fitness F of the trial at its last step
and 0 before — F of the terms a, g, b with l = 0 (orientation is measured across rooms), under
the config's motivations, exactly as ``fm.simulate`` reports it; ``"per-step"`` gives the
change of F of the terms so far at each step (F of an empty trial counted as 0), so an
episode's rewards add up to its F (up to rounding). ``terminated`` is True when the trial ends
at home (``trial.end_at_home``), ``truncated`` at ``T`` = ``trial.steps``. ``info`` holds the
terms so far ``a``, ``g``, ``l``, ``b``, the pose ``x``, ``y`` (mm), ``heading`` (rad), the
step count ``t``, the ``room`` and the executed ``action``.

Terms of your own (``terms={"name": fn}``, as :class:`fuzzymotiv.Problem` takes them; a
config's motivation may weigh them): at an episode's last step ``fn`` is called once with the
finished trial as a :class:`fuzzymotiv.Trials` of shape ``(1, 1)`` (arrays ``(1, 1, T + 1)``,
the idle rest after an end at home included, as ``fm.Problem`` gives a trial), its value goes
into F with the library's terms — the reward is then ``fm.simulate(genome, room, seed,
terms=...)["F"]``, bit for bit — and ``info[name]`` holds it (at the last step only; the vector
env's ``info[name]`` is NaN, ``info["_name"]`` False, for the envs whose episode did not end,
and its term functions are called once per room with the episodes that ended at a step). Values
are checked as ``fm.Problem`` checks them: out of [0, 1], NaN, the wrong shape, or an exception
raise :class:`FuzzymotivError` naming the term, and the env then needs ``reset()`` (a step
raises :class:`ResetNeeded`). ``reward="per-step"`` is refused with terms of your own: a term
is a value of the whole trial (what ``fm.Problem`` gives it), not defined for the trial so far.

:class:`KheperaVectorEnv` steps all its environments in Rust in one call. It follows
Gymnasium 1.x's **next-step autoreset** (``metadata["autoreset_mode"] ==
AutoresetMode.NEXT_STEP``): the step after an env's episode ended resets that env (a new room
and seed drawn from a stream of its seed) and ignores its action, returning the new first
observation with reward 0 and ``terminated = truncated = False``.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import gymnasium as gym
import numpy as np
import numpy.typing as npt
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from ._checks import FloatArray, _real_array
from ._fuzzymotiv import FuzzymotivError, ResetNeeded
from .config import Robot, _config_args, _robot_sets, _sets
from .trials import TermFunction, _supplier, _term_names
from . import _fuzzymotiv as _native

ACTIONS = ("straight", "left30", "right30", "turn180")
"""The actions of the ``Discrete(4)`` variant, by index."""

_SEED_BOUND = 2**53

Obs = npt.NDArray[np.floating[Any]]
"""An observation: the robot's N sensors / its ``reading_max`` (the Khepera's eight IR sensors
/ 1023), float32 or float64 as the env's dtype."""

ENV_IDS = {
    "khepera": ("fuzzymotiv/Khepera-v0", "fuzzymotiv/KheperaDiscrete-v0"),
    "epuck2": ("fuzzymotiv/EPuck2-v0", "fuzzymotiv/EPuck2Discrete-v0"),
    "thymio2": ("fuzzymotiv/Thymio2-v0", "fuzzymotiv/Thymio2Discrete-v0"),
}
"""Per built-in robot, the ids of its env with motor outputs and with ``Discrete(4)`` actions."""

Source = Tuple[Optional[str], Optional[str], List[str]]
"""A config as the native core takes it: (file path, TOML text, ``--set`` strings)."""

RoomArg = Union[str, "os.PathLike[str]", Sequence[Union[str, "os.PathLike[str]"]]]


def _rooms(room: Any) -> List[str]:
    if isinstance(room, (str, os.PathLike)):
        return [os.fspath(room)]
    rooms = [os.fspath(r) for r in room]
    if not rooms:
        raise FuzzymotivError("room: expected a room name or file, or a non-empty list of them")
    return rooms


def _dtype(dtype: Any) -> "np.dtype[Any]":
    d = np.dtype(dtype)
    if d not in (np.dtype(np.float32), np.dtype(np.float64)):
        raise FuzzymotivError(f"dtype: expected np.float32 or np.float64, got {d}")
    return d


Terms = Optional[Mapping[str, TermFunction]]
"""Terms of your own (``terms={"name": fn}``), as :class:`fuzzymotiv.Problem` takes them."""


def _core(
    room: Any, num_envs: int, source: Source, reward: str, dtype: "np.dtype[Any]", terms: Terms
) -> Any:
    """The native core of ``num_envs`` envs; ``source`` is (config path, config text, sets);
    ``terms`` the terms of your own (their names, and the function that supplies their values
    for a batch of finished trials, as :class:`fuzzymotiv.Problem` has it)."""
    path, text, sets = source
    names = [] if terms is None else _term_names(terms)
    supply = _supplier(dict(terms)) if terms is not None and names else None
    return _native.GymCore(
        _rooms(room), num_envs, path, text, sets, reward, dtype == np.float64, names, supply
    )


def _spaces(
    dtype: "np.dtype[Any]", discrete: bool, sensors: int
) -> Tuple["spaces.Space[Any]", "spaces.Space[Any]"]:
    """The observation space (``sensors`` readings / reading_max) and the action space."""
    obs = spaces.Box(0.0, 1.0, (sensors,), dtype)
    act = spaces.Discrete(4) if discrete else spaces.Box(0.0, 1.0, (2,), dtype)
    return obs, act


def network(genome: npt.ArrayLike, robot: Robot = "khepera") -> Callable[[npt.ArrayLike], FloatArray]:
    """The network of ``genome`` (its weights, the library's own MLP, ``N-h-2`` for the N
    sensors of ``robot`` — a built-in robot's name or a robot file's path — with ``h`` from the
    length): a function from an observation (N inputs in [0, 1]) to the two motor outputs the
    network gives the simulator — the action that replays :func:`fuzzymotiv.simulate`."""
    weights = _real_array("genome", genome, "a vector of weights").ravel()
    n = int(_native.robot_info(os.fspath(robot if robot is not None else "khepera"))["sensors"])
    hidden, rest = divmod(len(weights) - 2, n + 3)
    if rest or hidden < 1:
        raise FuzzymotivError(
            f"genome: {len(weights)} weights is no {n}-h-2 network's length "
            f"({n + 3}·h + 2, for the robot's {n} sensors)"
        )
    w = weights.tolist()

    def outputs(obs: npt.ArrayLike) -> FloatArray:
        inputs = _real_array("obs", obs, f"{n} sensor inputs").ravel().tolist()
        if len(inputs) != n:
            raise FuzzymotivError(f"obs: expected {n} sensor inputs (one per sensor), got {len(inputs)}")
        return np.array(_native.network_outputs(w, hidden, inputs))

    return outputs


class RobotEnv(gym.Env[npt.NDArray[np.floating[Any]], npt.NDArray[Any]]):
    """One trial of the robot (the config's, or ``robot=``) as a Gymnasium environment (see the
    module's docs); ``KheperaEnv`` is this class. Attributes: ``robot`` (its name),
    ``sensors`` (N, the observation's length), ``reading_max``, ``rooms``, ``max_steps``.

    >>> env = RobotEnv("H", overrides={"trial.steps": 5})
    >>> obs, info = env.reset(seed=1)
    >>> obs.shape, obs.dtype, info["room"]
    ((8,), dtype('float32'), 'H')
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(
        self,
        room: RoomArg = "H",
        *,
        config: Union[str, "os.PathLike[str]", None] = None,
        config_text: Optional[str] = None,
        overrides: Any = None,
        reward: str = "end",
        dtype: Any = np.float32,
        discrete: bool = False,
        render_mode: Optional[str] = None,
        size: int = 256,
        terms: Terms = None,
        robot: Robot = None,
    ) -> None:
        if render_mode not in (None, "rgb_array"):
            raise FuzzymotivError(f"render_mode: expected None or 'rgb_array', got {render_mode!r}")
        self._dtype = _dtype(dtype)
        self._room_args = _rooms(room)
        # The config as the native code takes it, kept for render() (same robot, same rooms).
        self._source = (*_config_args(config, config_text), _sets(overrides) + _robot_sets(robot))
        self._core = _core(self._room_args, 1, self._source, reward, self._dtype, terms)
        self._user: List[str] = [] if terms is None else list(terms)
        self.robot: str = self._core.robot
        self.sensors: int = self._core.sensors
        self.reading_max: float = self._core.reading_max
        self.observation_space, self.action_space = _spaces(self._dtype, discrete, self.sensors)
        self.rooms: List[str] = list(self._core.room_names)
        self.max_steps: int = self._core.max_steps
        self.render_mode = render_mode
        self.size = size
        self._discrete = discrete
        self._room = 0
        self._trace: Dict[str, List[Any]] = {}

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None
    ) -> Tuple[Obs, Dict[str, Any]]:
        _check_seed(seed)
        super().reset(seed=seed)
        room = (options or {}).get("room")
        if room is None:
            self._room = int(self.np_random.integers(len(self.rooms)))
        elif room in self.rooms:
            self._room = self.rooms.index(room)
        else:
            raise FuzzymotivError(f"options['room']: {room!r} is not one of {self.rooms}")
        base = seed if seed is not None else int(self.np_random.integers(_SEED_BOUND))
        self._core.reset_one(0, self._room, base)
        obs, info = self._core.state()
        info = self._info(info)
        self._trace = {"x": [info["x"]], "y": [info["y"]], "heading": [info["heading"]],
                       "sensors": [], "action": []}
        self._last_obs = obs[0]
        self._over = False
        return obs[0], info

    def step(self, action: Any) -> Tuple[Obs, float, bool, bool, Dict[str, Any]]:
        if getattr(self, "_over", True):
            raise ResetNeeded("step: no episode is running; call reset() first")
        actions = _actions(action, 1, self._discrete)
        seen = self._last_obs
        obs, reward, terminated, truncated, info = self._core.step(actions)
        info = self._info(info)
        self._record(seen, info)
        self._last_obs = obs[0]
        self._over = bool(terminated[0] or truncated[0])
        return obs[0], float(reward[0]), bool(terminated[0]), bool(truncated[0]), info

    def _info(self, native: Dict[str, Any]) -> Dict[str, Any]:
        info: Dict[str, Any] = {k: float(native[k][0]) for k in ("a", "g", "l", "b", "x", "y", "heading")}
        info["t"] = int(native["t"][0])
        info["room"] = self.rooms[int(native["room"][0])]
        action = int(native["action"][0])
        if action >= 0:
            info["action"] = ACTIONS[action]
        for name in self._user:
            if native[f"_{name}"][0]:
                info[name] = float(native[name][0])
        return info

    def _record(self, seen: Obs, info: Dict[str, Any]) -> None:
        for k in ("x", "y", "heading"):
            self._trace[k].append(info[k])
        self._trace["sensors"].append(np.asarray(seen, dtype=np.float64) * self.reading_max)
        self._trace["action"].append(info.get("action", "straight"))

    def trajectory(self) -> Dict[str, npt.NDArray[Any]]:
        """The episode so far, shaped like :func:`fuzzymotiv.simulate`'s result: ``x``,
        ``y``, ``heading`` (steps + 1 poses), ``sensors`` (steps × N, 0 to the robot's
        ``reading_max``: the Khepera's 0–1023; rounded when the env is float32) and ``action``
        (labels)."""
        t = self._trace
        sensors = np.array(t["sensors"], dtype=np.float64).reshape(-1, self.sensors)
        return {
            "x": np.array(t["x"]),
            "y": np.array(t["y"]),
            "heading": np.array(t["heading"]),
            "sensors": sensors,
            "action": np.array(t["action"], dtype=str),
        }

    def render(self) -> Optional[npt.NDArray[np.uint8]]:
        """With ``render_mode="rgb_array"``: the frame of the episode so far, ``(H, W, 3)``
        uint8 — the last frame :func:`fuzzymotiv.frames` draws of :meth:`trajectory` with the
        env's ``config`` and ``overrides`` (its robot, its rooms), drawn alone: one frame per
        call, whatever the episode's length."""
        if self.render_mode != "rgb_array":
            return None
        if not self._trace:
            raise ResetNeeded("render: no episode yet; call reset() first")
        path, text, sets = self._source
        room = self._room_args[self._room] if len(self._room_args) > 1 else self._room_args[0]
        return _native.last_frame(self.trajectory(), room, self.size, path, text, sets, self._user)


def _check_seed(seed: Any) -> None:
    """A reset seed is None or a whole number from 0 to 2^53 − 1 (as :func:`fuzzymotiv.simulate`
    takes: a seeded episode is that trial)."""
    whole = isinstance(seed, (int, np.integer)) and not isinstance(seed, bool)
    if seed is not None and not (whole and 0 <= seed < _SEED_BOUND):
        raise FuzzymotivError(
            f"seed: {seed!r} is not a seed; a seed is a whole number from 0 to "
            f"{_SEED_BOUND - 1} (2^53 − 1)"
        )


def _actions(action: Any, n: int, discrete: bool) -> npt.NDArray[Any]:
    """The actions of ``n`` environments as the native step takes them: ``(n,)`` int64 action
    numbers, or ``(n, 2)`` float64 motor outputs (the native step clips them to [0, 1], the
    Box's bounds). Anything else is a FuzzymotivError saying what was expected (no silent
    rounding of 1.7 to 1, no NaN or infinity clipped into a number)."""
    a = np.asarray(action)
    numeric = a.dtype.kind in "iu" or (a.dtype.kind == "f" and bool(np.all(np.isfinite(a))))
    if discrete:
        whole = numeric and (a.dtype.kind in "iu" or bool(np.all(a == np.round(a))))
        if a.size != n or not whole:
            raise FuzzymotivError(
                f"action: expected {n} whole number(s) of Discrete(4) (0 straight, 1 left30, "
                f"2 right30, 3 turn180), got {action!r}"
            )
        return a.astype(np.int64).reshape(n)
    if a.size != 2 * n or not numeric:
        raise FuzzymotivError(
            f"action: expected {n} pair(s) of finite motor outputs (shape ({n}, 2) or "
            f"({2 * n},)); values outside [0, 1] are clipped to it, NaN and infinities "
            f"refused; got {action!r}"
        )
    return a.astype(np.float64).reshape(n, 2)


class RobotVectorEnv(VectorEnv[npt.NDArray[np.floating[Any]], npt.NDArray[Any], npt.NDArray[Any]]):
    """``num_envs`` trials of the robot (the config's, or ``robot=``) stepped together in Rust
    (one call per step), with next-step autoreset (see the module's docs); observations
    ``(num_envs, N)``. ``reset(seed=S)`` seeds env ``i`` with ``S + i`` (its trial's base seed;
    its room drawn from the vector env's ``np_random``). ``KheperaVectorEnv`` is this class."""

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(
        self,
        num_envs: int = 64,
        room: RoomArg = "H",
        *,
        config: Union[str, "os.PathLike[str]", None] = None,
        config_text: Optional[str] = None,
        overrides: Any = None,
        reward: str = "end",
        dtype: Any = np.float32,
        discrete: bool = False,
        terms: Terms = None,
        robot: Robot = None,
    ) -> None:
        if not isinstance(num_envs, (int, np.integer)) or isinstance(num_envs, bool) or num_envs < 1:
            raise FuzzymotivError(f"num_envs: expected a whole number >= 1, got {num_envs!r}")
        self.num_envs = int(num_envs)
        self._dtype = _dtype(dtype)
        source = (*_config_args(config, config_text), _sets(overrides) + _robot_sets(robot))
        self._core = _core(room, self.num_envs, source, reward, self._dtype, terms)
        self._discrete = discrete
        # The actions the native step takes without conversion (see `step`).
        self._native_dtype = np.dtype(np.int64) if discrete else np.dtype(np.float64)
        self._native_shape = (self.num_envs,) if discrete else (self.num_envs, 2)
        self.robot: str = self._core.robot
        self.sensors: int = self._core.sensors
        self.reading_max: float = self._core.reading_max
        self.single_observation_space, self.single_action_space = _spaces(
            self._dtype, discrete, self.sensors
        )
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.rooms: List[str] = list(self._core.room_names)
        self.max_steps: int = self._core.max_steps
        self.render_mode = None

    def reset(
        self, *, seed: Union[int, Sequence[Optional[int]], None] = None,
        options: Optional[Dict[str, Any]] = None,
    ) -> Tuple[Obs, Dict[str, Any]]:
        if isinstance(seed, (list, tuple, np.ndarray)):
            for s in seed:
                _check_seed(s)
        else:
            _check_seed(seed)
        first = seed if isinstance(seed, (int, np.integer)) or seed is None else None
        super().reset(seed=first)
        if seed is None or isinstance(seed, (int, np.integer)):
            seeds: List[Optional[int]] = [None if seed is None else int(seed) + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise FuzzymotivError(f"seed: expected {self.num_envs} seeds, got {len(seeds)}")
        for i, s in enumerate(seeds):
            room = int(self.np_random.integers(len(self.rooms)))
            base = s if s is not None else int(self.np_random.integers(_SEED_BOUND))
            self._core.reset_one(i, room, base)
        obs, info = self._core.state()
        return obs, info

    def step(
        self, actions: Any
    ) -> Tuple[Obs, FloatArray, npt.NDArray[np.bool_], npt.NDArray[np.bool_], Dict[str, Any]]:
        # An array already as the native step takes it ((N, 2) float64 or (N,) int64) goes to
        # it as is: the native step refuses what is not finite or not an action before any env
        # moves, and the check below then names the fault as for any other argument. (The
        # NumPy calls of that check cost a sixth of a 64-env step.)
        a = actions
        if type(a) is np.ndarray and a.dtype is self._native_dtype and a.shape == self._native_shape:
            try:
                obs, reward, terminated, truncated, info = self._core.step(a)
            except FuzzymotivError:
                _actions(a, self.num_envs, self._discrete)
                raise
        else:
            obs, reward, terminated, truncated, info = self._core.step(
                _actions(actions, self.num_envs, self._discrete)
            )
        return obs, reward, terminated, truncated, info


KheperaEnv = RobotEnv
"""The Khepera's env: :class:`RobotEnv` (the Khepera unless the config or ``robot=`` names
another robot)."""

KheperaVectorEnv = RobotVectorEnv
"""The Khepera's vector env: :class:`RobotVectorEnv`."""

for _robot, (_continuous, _discrete) in ENV_IDS.items():
    # Each id passes its robot (gym.make(ID, robot=...) still chooses another).
    _kwargs: Dict[str, Any] = {"robot": _robot}
    gym.register(
        id=_continuous,
        entry_point="fuzzymotiv.gym:RobotEnv",
        vector_entry_point="fuzzymotiv.gym:RobotVectorEnv",
        kwargs=_kwargs,
    )
    gym.register(
        id=_discrete,
        entry_point="fuzzymotiv.gym:RobotEnv",
        vector_entry_point="fuzzymotiv.gym:RobotVectorEnv",
        kwargs={**_kwargs, "discrete": True},
    )
