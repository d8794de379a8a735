"""Type stubs of the compiled module (the package's public names are in __init__.py)."""

from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

__version__: str

class InputError(ValueError): ...

class Curve:
    def __init__(
        self,
        times: np.ndarray,
        rotations: np.ndarray,
        scheme: str = ...,
        *,
        velocities: Optional[np.ndarray] = ...,
        tcb: Optional[np.ndarray] = ...,
        ends: str = ...,
        start_velocity: Optional[np.ndarray] = ...,
        end_velocity: Optional[np.ndarray] = ...,
        path: str = ...,
        scalar_first: bool = ...,
        grid_rate: Any = ...,
        tangent: Optional[str] = ...,
    ) -> None: ...
    def __call__(self, t: np.ndarray, order: int = ..., frame: Optional[str] = ...) -> np.ndarray: ...
    @property
    def span(self) -> Tuple[float, float]: ...
    @property
    def joints(self) -> Optional[int]: ...
    @property
    def scheme(self) -> str: ...

def resample(
    rotations: np.ndarray,
    fps_in: Any,
    fps_out: Any,
    *,
    scheme: str = ...,
    ends: str = ...,
    path: str = ...,
    scalar_first: bool = ...,
    velocity: bool = ...,
    frame: Optional[str] = ...,
    translations: Optional[np.ndarray] = ...,
    tangent: Optional[str] = ...,
) -> Union[np.ndarray, Tuple[np.ndarray, np.ndarray]]: ...
def frame_times(n: int, fps_in: Any, fps_out: Any) -> np.ndarray: ...
def reduce(
    rotations: np.ndarray,
    fps: Any,
    tolerance: float,
    *,
    scheme: str = ...,
    method: str = ...,
    distance: Optional[float] = ...,
    shared_keys: bool = ...,
    velocities: bool = ...,
    translations: Optional[np.ndarray] = ...,
    translation_tolerance: Optional[float] = ...,
    ends: str = ...,
    path: str = ...,
    scalar_first: bool = ...,
) -> List[Dict[str, Any]]: ...
def read(
    path: str,
    *,
    rotation: Optional[str] = ...,
    angles: str = ...,
    key_fps: Any = ...,
    quat_order: str = ...,
    scalar_first: bool = ...,
    max_bytes: int = ...,
    columns: Optional[Union[str, Dict[str, Union[str, int]]]] = ...,
    time_unit: Optional[str] = ...,
    times: Optional[str] = ...,
) -> Dict[str, Any]: ...
def write(
    path: str,
    tracks: List[Tuple[str, np.ndarray, np.ndarray, Optional[np.ndarray]]],
    *,
    fps: Any = ...,
    skeleton: Optional[str] = ...,
    asset: Optional[Tuple[str, str, bytes]] = ...,
    to: str = ...,
    angles: str = ...,
    precision: Optional[int] = ...,
    euler: str = ...,
    scalar_first: bool = ...,
) -> None: ...
def process_file(
    path: str,
    out: str,
    command: str,
    options: Optional[Dict[str, Any]] = ...,
    refresh: bool = ...,
) -> Dict[str, Any]: ...
def cpu_has_avx2() -> bool: ...
