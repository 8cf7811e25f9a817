from typing import NamedTuple, Literal, Optional
import numpy as np
from numpy.typing import ArrayLike

class Efficiencies(NamedTuple):
    qext: np.ndarray
    qsca: np.ndarray
    qabs: np.ndarray
    qback: np.ndarray
    qpr: np.ndarray
    g: np.ndarray
    terms: np.ndarray

class ScatteringMatrix(NamedTuple):
    s11: np.ndarray
    s12: np.ndarray
    s33: np.ndarray
    s34: np.ndarray
    phase: np.ndarray

class ScatteringMatrixExpansion(NamedTuple):
    alpha1: np.ndarray
    alpha2: np.ndarray
    alpha3: np.ndarray
    alpha4: np.ndarray
    beta1: np.ndarray
    beta2: np.ndarray

def efficiencies(x: Optional[ArrayLike] = ..., m: Optional[ArrayLike] = ..., *, radius: Optional[ArrayLike] = ...,
                 wavelength: Optional[ArrayLike] = ..., medium_index: Optional[ArrayLike] = ...,
                 errors: Literal["raise", "nan"] = ..., threads: int = ...) -> Efficiencies: ...
def coefficients(x: float, m: complex) -> tuple[np.ndarray, np.ndarray]: ...
def amplitudes(x: float, m: complex, angles: ArrayLike) -> tuple[np.ndarray, np.ndarray]: ...
def scattering_matrix(x: float, m: complex, angles: ArrayLike) -> ScatteringMatrix: ...
def phase_function(x: float, m: complex, angles: ArrayLike,
                   normalization: Literal["4pi", "1", "bh"] = ...) -> np.ndarray: ...
def legendre_moments(x: float, m: complex, L: Optional[int] = ...) -> np.ndarray: ...
def scattering_matrix_expansion(x: float, m: complex, L: Optional[int] = ...) -> ScatteringMatrixExpansion: ...
def phase_function_from_moments(chi: ArrayLike, angles: ArrayLike) -> np.ndarray: ...

class Lidar(NamedTuple):
    backscatter_per_sr: np.ndarray
    lidar_ratio_sr: np.ndarray
    linear_depolarisation: np.ndarray

def lidar(x: Optional[ArrayLike] = ..., m: Optional[ArrayLike] = ..., **kwargs: object) -> Lidar: ...
