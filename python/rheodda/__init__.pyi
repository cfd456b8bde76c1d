"""Type stubs of rheodda's pure-Python part (python/rheodda/__init__.py); the
compiled part is _rheodda.pyi. Checked by tests/python/test_typing.py."""
import os
from typing import Any, Callable, Mapping, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._rheodda import (
    AnyLaw as AnyLaw,
    CreepData as CreepData,
    DataError as DataError,
    Error as Error,
    FitError as FitError,
    FixedCombination as FixedCombination,
    Law as Law,
    LawError as LawError,
    ModelError as ModelError,
    ParameterEstimate as ParameterEstimate,
    PythonLaw as PythonLaw,
    PythonLawError as PythonLawError,
    RunError as RunError,
    Scene as Scene,
    SceneError as SceneError,
    StepConstants as StepConstants,
    StepReport as StepReport,
    UnitStepConstants as UnitStepConstants,
    __version__ as __version__,
    creep_curve as creep_curve,
    creep_data as creep_data,
    relaxation_curve as relaxation_curve,
    exact_displacement as exact_displacement,
    exact_force as exact_force,
    law as law,
    law_step as law_step,
    laws as laws,
    load_scene as load_scene,
    parse_scene as parse_scene,
    read_creep_csv as read_creep_csv,
    run as run,
)

FloatArray = npt.NDArray[np.float64]
PathLike = Union[str, os.PathLike[str]]
Staged = Union[float, str, Sequence[tuple[float, float]], FloatArray]
# params= of fit: per parameter an initial value, a dict of value/vary/min/max, or an lmfit.Parameter.
ParameterSpec = Union[float, Mapping[str, Union[float, bool, None]], Any]

__all__: list[str]

def law_info(name: str) -> dict[str, Any]: ...
def to_dataframe(columns: Mapping[str, npt.ArrayLike]) -> Any: ...

class FitResult:
    data: CreepData
    law: str
    parameters: list[ParameterEstimate]
    names: list[str]
    values: dict[str, float]
    errors: dict[str, float]
    units: dict[str, str]
    identifiable: dict[str, bool]
    reasons: dict[str, str]
    vary: dict[str, bool]
    at_bound: dict[str, str]
    combinations: list[FixedCombination]
    correlation: FloatArray
    covariance: FloatArray
    points: int
    rss: float
    chi_square: float
    reduced_chi_square: float
    varying: int
    weighted: bool
    scale_covariance: bool
    r2: float
    rmse: float
    aic: float
    bic: float
    iterations: int
    starts: int
    starts_agreeing: int
    structured_starts: int
    converged: bool
    minimum_certain: bool
    minimum_note: str
    warnings: list[str]
    fitted: FloatArray
    singular_values: FloatArray
    start_minima: FloatArray
    def __init__(self, raw: Any, data: CreepData) -> None: ...
    def make_law(self) -> Law: ...
    @property
    def yaml(self) -> str: ...
    def to_dataframe(self) -> Any: ...
    def fit_report(self, min_correlation: float = 0.1) -> str: ...

def fit(law_name: str, data: Union[PathLike, CreepData, npt.ArrayLike], t: npt.ArrayLike | None = None,
        stress: Staged | None = None, *, params: Mapping[str, ParameterSpec] | None = None,
        sigma: npt.ArrayLike | None = None, weights: npt.ArrayLike | None = None, absolute_sigma: bool = False,
        time_column: str = "t", displacement_column: str = "displacement", stress_column: str | None = None,
        sigma_column: str | None = None, restarts: int = 4, max_iterations: int = 500) -> FitResult: ...
def fit_all(data: Union[PathLike, CreepData, npt.ArrayLike], t: npt.ArrayLike | None = None,
            stress: Staged | None = None, *, rank_by: str = "bic", params: Mapping[str, ParameterSpec] | None = None,
            sigma: npt.ArrayLike | None = None, weights: npt.ArrayLike | None = None, absolute_sigma: bool = False,
            time_column: str = "t", displacement_column: str = "displacement", stress_column: str | None = None,
            sigma_column: str | None = None, restarts: int = 4,
            max_iterations: int = 500) -> tuple[list[FitResult], list[str]]: ...
def ranking_frame(results: Sequence[FitResult]) -> Any: ...
def scene_from_dict(scene: Mapping[str, Any], file: str = "<dict>") -> Scene: ...

class Simulation:
    scene: Scene
    callback: Callable[[Simulation, StepReport], object] | None
    def __init__(self, scene: Union[Scene, PathLike, Mapping[str, Any]], laws: Mapping[str, AnyLaw] | None = None,
                 callback: Callable[[Simulation, StepReport], object] | None = None) -> None: ...
    def step(self, n: int = 1) -> Simulation: ...
    def run(self, until: float | None = None) -> Simulation: ...
    @property
    def time(self) -> float: ...
    @property
    def step_count(self) -> int: ...
    @property
    def duration(self) -> float: ...
    @property
    def failed(self) -> bool: ...
    @property
    def block_positions(self) -> FloatArray: ...
    @property
    def block_velocities(self) -> FloatArray: ...
    @property
    def block_stresses(self) -> FloatArray: ...
    @property
    def settings(self) -> dict[str, Any]: ...
    @property
    def loads(self) -> list[FloatArray]: ...
    @property
    def units(self) -> dict[str, str]: ...
    @property
    def joint_sets(self) -> list[str]: ...
    @property
    def blocks(self) -> list[str]: ...
    @property
    def columns(self) -> list[str]: ...
    def block_vertices(self, block: Union[int, str]) -> FloatArray: ...
    def point_displacement(self, block: Union[int, str], x: float, y: float) -> FloatArray: ...
    def contacts(self) -> dict[str, npt.NDArray[Any]]: ...
    def history(self) -> dict[str, FloatArray]: ...
    def history_frame(self) -> Any: ...
    def set_load(self, index: int, force: Sequence[float]) -> None: ...
    def set_load_history(self, index: int, samples: Sequence[Sequence[float]]) -> None: ...
    def set_law_parameters(self, joint_set: str, parameters: Mapping[str, float] | None = None,
                           **kw: float) -> None: ...
    def law_parameters(self, joint_set: str) -> dict[str, float]: ...
    def set_settings(self, **settings: float | int | bool) -> None: ...

def rheodda_binary() -> str: ...
def run_study(path: PathLike, out_dir: PathLike, jobs: int = 0, plot: bool = False,
              rheodda_binary: PathLike | None = None) -> dict[str, Any]: ...
