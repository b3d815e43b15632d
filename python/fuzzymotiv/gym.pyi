import os
from typing import Any, Callable, Optional, Sequence, Union

import gymnasium as gym
import numpy as np
import numpy.typing as npt
from gymnasium.vector import VectorEnv

ACTIONS: tuple[str, str, str, str]

RoomArg = Union[str, os.PathLike[str], Sequence[Union[str, os.PathLike[str]]]]

def network(genome: Any) -> Callable[[Any], npt.NDArray[np.float64]]: ...

class KheperaEnv(gym.Env[npt.NDArray[np.floating[Any]], Any]):
    rooms: list[str]
    max_steps: int
    size: int
    def __init__(
        self,
        room: RoomArg = ...,
        *,
        config: Union[str, os.PathLike[str], None] = ...,
        config_text: Optional[str] = ...,
        overrides: Any = ...,
        reward: str = ...,
        dtype: Any = ...,
        discrete: bool = ...,
        render_mode: Optional[str] = ...,
        size: int = ...,
    ) -> None: ...
    def reset(
        self, *, seed: Optional[int] = ..., options: Optional[dict[str, Any]] = ...
    ) -> tuple[npt.NDArray[np.floating[Any]], dict[str, Any]]: ...
    def step(
        self, action: Any
    ) -> tuple[npt.NDArray[np.floating[Any]], float, bool, bool, dict[str, Any]]: ...
    def trajectory(self) -> dict[str, npt.NDArray[Any]]: ...
    def render(self) -> Optional[npt.NDArray[np.uint8]]: ...

class KheperaVectorEnv(VectorEnv[npt.NDArray[np.floating[Any]], Any, Any]):
    rooms: list[str]
    max_steps: int
    def __init__(
        self,
        num_envs: int = ...,
        room: RoomArg = ...,
        *,
        config: Union[str, os.PathLike[str], None] = ...,
        config_text: Optional[str] = ...,
        overrides: Any = ...,
        reward: str = ...,
        dtype: Any = ...,
        discrete: bool = ...,
    ) -> None: ...
    def reset(
        self,
        *,
        seed: Union[int, Sequence[Optional[int]], None] = ...,
        options: Optional[dict[str, Any]] = ...,
    ) -> tuple[npt.NDArray[np.floating[Any]], dict[str, Any]]: ...
    def step(
        self, actions: Any
    ) -> tuple[
        npt.NDArray[np.floating[Any]],
        npt.NDArray[np.float64],
        npt.NDArray[np.bool_],
        npt.NDArray[np.bool_],
        dict[str, Any],
    ]: ...
