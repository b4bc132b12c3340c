# Type stubs of the package asperity (PEP 561; installed with it). tests/python/test_notebook.py
# keeps the names here equal to the package's public names and Scene's methods.
import os
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import plot as plot

__version__: str
__all__: list[str]

_PathLike = Union[str, os.PathLike[str]]
_Progress = Union[bool, None, Callable[[int, int], object]]
_Column = Union[npt.ArrayLike, Any]  # a NumPy array, a list or a pandas Series

class InputError(ValueError): ...
class SolverError(RuntimeError): ...

class Scene:
    @property
    def file(self) -> str: ...
    @property
    def experiment(self) -> str: ...
    @property
    def junctions(self) -> int: ...
    @property
    def stand_in(self) -> bool: ...
    def to_yaml(self) -> str: ...
    @staticmethod
    def from_dict(d: Mapping[str, Any], areas: Optional[_Column] = None, x: Optional[_Column] = None,
                  y: Optional[_Column] = None, measured: Any = None) -> Scene: ...
    @staticmethod
    def from_yaml(text: str) -> Scene: ...

class Result:
    summary: dict[str, Any]
    series: dict[str, np.ndarray]
    peaks: list[dict[str, float]]
    summary_yaml: str
    units: dict[str, str]
    stand_in: bool
    def __init__(self, summary: dict[str, Any], series: dict[str, np.ndarray], peaks: list[dict[str, float]],
                 summary_yaml: str, units: dict[str, str] = ..., stand_in: bool = ...) -> None: ...
    def frame(self) -> Any: ...  # pandas.DataFrame

def load_scene(path: _PathLike, overrides: Union[Mapping[str, Any], Sequence[str], None] = None) -> Scene: ...
def run(scene: Union[Scene, _PathLike], overrides: Union[Mapping[str, Any], Sequence[str], None] = None) -> Result: ...
def generate_junctions(heights: np.ndarray, pixel_m: float, *, sphere_radius_m: float, load_N: float, E: float = 1.6e6,
                       nu: float = 0.5, tolerance: float = 1e-10, max_iterations: int = 5000,
                       connectivity: int = 8, threads: int = 1) -> dict[str, Any]: ...
def tangential_contact(heights: np.ndarray, pixel_m: float, *, sphere_radius_m: float, load_N: float,
                       displacements_m: Sequence[float], shear_strength_Pa: Optional[float] = None,
                       friction_coefficient: Optional[float] = None, E: float = 1.6e6, nu: float = 0.5,
                       tolerance: float = 1e-10, max_iterations: int = 5000, tangential_tolerance: float = 1e-8,
                       slip_maps: bool = False, threads: int = 1) -> dict[str, Any]: ...
def measured(scene: Scene) -> Optional[dict[str, np.ndarray]]: ...
def sweep(campaign: Union[_PathLike, Mapping[str, Any]], out: _PathLike = "", threads: Optional[int] = None,
          shard: str = "0/1", progress: _Progress = True, base: Optional[_PathLike] = None) -> dict[str, Any]: ...
class FitResult(dict[str, Any]):
    @property
    def parameters(self) -> Any: ...  # pandas.DataFrame
    @property
    def profiles(self) -> Any: ...  # pandas.DataFrame
    @property
    def runs(self) -> Any: ...  # pandas.DataFrame
def fit(spec: Union[_PathLike, Mapping[str, Any]], out: _PathLike = "", threads: Optional[int] = None,
        profile: bool = True, error_bars: bool = True, progress: _Progress = True,
        objective: Optional[Callable[..., float]] = None, series: bool = False,
        base: Optional[_PathLike] = None) -> FitResult: ...
def read_store(path: _PathLike) -> Any: ...  # pandas.DataFrame
def read_series(path: _PathLike, index: int) -> Any: ...  # pandas.DataFrame
def units(column: str) -> str: ...
STAND_IN_MARK: str
def version() -> str: ...
