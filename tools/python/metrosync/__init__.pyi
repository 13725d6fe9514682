# Type stubs of the package `metrosync` (docs/python.md), for editors and type checkers.
# tests/python/test_stubs.py checks that they name every public call with its parameters.
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
import pandas as pd

Columns = Dict[str, npt.NDArray[Any]]
Value = Union[float, int, bool, str, Sequence[Any], Mapping[str, Any]]
RigLike = Union["Rig", Mapping[str, Any], str, os.PathLike]
Axis = Union[Tuple[float, float, int], Tuple[float, float, int, str], Sequence[float], str]

class RigError(ValueError): ...

class SimulationError(RuntimeError):
    result: Optional[Union[Result, CompareResult]]

class Rig:
    path: Optional[str]
    overrides: Dict[str, Value]
    @property
    def name(self) -> str: ...
    def scaled(self) -> Dict[str, Any]: ...
    def to_dict(self) -> Dict[str, Any]: ...

class Result:
    summary: Dict[str, Any]
    trajectory: Optional[Columns]
    envelope: Columns
    events: Optional[Columns]
    out: Optional[str]
    @property
    def regime(self) -> str: ...
    @property
    def complete(self) -> bool: ...
    @property
    def model(self) -> str: ...
    @property
    def engine(self) -> str: ...
    def to_pandas(self) -> pd.DataFrame: ...
    def envelope_frame(self) -> pd.DataFrame: ...
    def events_frame(self) -> Optional[pd.DataFrame]: ...

class CompareResult:
    summary: Dict[str, Any]
    full: Result
    slow: Result
    comparison: Columns
    out: Optional[str]
    @property
    def complete(self) -> bool: ...
    def to_pandas(self) -> pd.DataFrame: ...

class SweepResult:
    summary: Dict[str, Any]
    keys: List[str]
    values: List[npt.NDArray[np.float64]]
    shape: Tuple[int, ...]
    columns: Columns
    regime: npt.NDArray[np.str_]
    out: Optional[str]
    def __getitem__(self, name: str) -> npt.NDArray[Any]: ...
    @property
    def complete(self) -> bool: ...
    def to_pandas(self) -> pd.DataFrame: ...

class BasinResult:
    summary: Dict[str, Any]
    samples: Columns
    fractions: List[Dict[str, Any]]
    out: Optional[str]
    def fraction(self, regime: str) -> float: ...
    def to_pandas(self) -> pd.DataFrame: ...

class ContinuationResult:
    summary: Dict[str, Any]
    branches: Columns
    bifurcations: List[Dict[str, Any]]
    cycles: Optional[Columns]
    fold_curve: Optional[Columns]
    hopf_curve: Optional[Columns]
    out: Optional[str]
    def to_pandas(self) -> pd.DataFrame: ...

class FitResult:
    summary: Dict[str, Any]
    values: Dict[str, Optional[float]]
    std_errors: Dict[str, Optional[float]]
    identifiable: Dict[str, bool]
    rig: Rig
    out: Optional[str]
    @property
    def rms(self) -> float: ...
    @property
    def converged(self) -> bool: ...
    def to_pandas(self) -> pd.DataFrame: ...

def version() -> str: ...
def load_rig(rig: RigLike, overrides: Optional[Mapping[str, Value]] = None) -> Rig: ...
def run(
    rig: RigLike,
    model: Optional[str] = None,
    engine: Optional[str] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    **simulation: Value,
) -> Result: ...
def compare(
    rig: RigLike,
    engine: Optional[str] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    **simulation: Value,
) -> CompareResult: ...
def sweep(
    rig: RigLike,
    vary: Mapping[str, Axis],
    model: Optional[str] = None,
    engine: Optional[str] = None,
    jobs: Optional[int] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    **simulation: Value,
) -> SweepResult: ...
def basin(
    rig: RigLike,
    random: Mapping[str, Union[Tuple[float, float], str]],
    samples: int,
    seed: int = 1,
    model: Optional[str] = None,
    engine: Optional[str] = None,
    jobs: Optional[int] = None,
    out: Optional[Union[str, os.PathLike]] = None,
    **simulation: Value,
) -> BasinResult: ...
def continue_(
    rig: RigLike,
    param: str,
    to: float,
    from_: Optional[float] = None,
    start: Optional[Sequence[float]] = None,
    step: Optional[float] = None,
    max_points: int = 500,
    all: bool = False,
    no_cycles: bool = False,
    fold: Optional[str] = None,
    to2: Optional[float] = None,
    model: str = "slow",
    out: Optional[Union[str, os.PathLike]] = None,
) -> ContinuationResult: ...
def fit(
    rig: RigLike,
    data: Union[str, os.PathLike, Mapping[str, Sequence[float]], pd.DataFrame],
    free: Union[str, Sequence[str]],
    model: str = "full",
    out: Optional[Union[str, os.PathLike]] = None,
    noise: Optional[float] = None,
    starts: int = 6,
    local: bool = False,
    profile: bool = False,
) -> FitResult: ...
