"""Type stubs of the penumbra module (python/*.cpp): what each function takes and returns."""
import os
from typing import Callable, Iterable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayF32 = npt.NDArray[np.float32]
ArrayLike = npt.ArrayLike
PathLike = Union[str, bytes, os.PathLike[str], os.PathLike[bytes]]

class SceneError(ValueError):
    file: Optional[str]
    line: Optional[int]
    message: str

class Scene:
    settings: dict[str, str]
    strategy: str
    axes: dict[str, str]
    sampler: str
    sample_count: int
    seed: int
    width: int
    height: int
    path: str
    warnings: list[str]
    def set(self, key: str, value: Union[str, int, float, bool]) -> None: ...
    def to_xml(self) -> str: ...
    def render(self, spp: Optional[int] = None, time: Optional[float] = None, seed: int = 0,
               threads: Optional[int] = None,
               progress: Union[None, bool, Callable[[int, float], object]] = None) -> RenderResult: ...

class RenderResult:
    mean: ArrayF32  # H x W x 3
    stderr: ArrayF32  # H x W x 3
    spp: int
    seconds: float
    samples: int
    bad_samples: int
    threads: int
    metadata: dict[str, str]
    def save(self, path: PathLike, image: Optional[ArrayLike] = None) -> None: ...

class Chi2Result:
    warp: str
    param: Optional[float]
    p_value: float
    chi2: float
    dof: int
    alpha: float
    accepted: bool
    inconclusive: bool  # too few samples: no two cells left after pooling (dof 0, p_value NaN)
    verdict: str  # "accept", "REJECT" or "inconclusive"
    message: str
    pooled_cells: int
    observed: npt.NDArray[np.float64]
    expected: npt.NDArray[np.float64]
    rejected: float  # bsdf_chi2_test(): draws the BSDF rejected (0 for warps)
    expected_rejected: float  # the rejected draws the pdf's missing mass expects

def load_scene(path: PathLike, overrides: Optional[dict[str, Union[str, int, float, bool]]] = None) -> Scene: ...
def scene_from_string(xml: Union[str, bytes], base_dir: PathLike = "", name: str = "<string>",
                      overrides: Optional[dict[str, Union[str, int, float, bool]]] = None) -> Scene: ...
def axes() -> dict[str, list[dict[str, object]]]: ...
def samplers() -> list[dict[str, object]]: ...
def warp_names() -> list[str]: ...
def random_points(n: int, seed: int = 1, out: Optional[ArrayF32] = None) -> ArrayF32: ...
def warp(name: str, u: ArrayLike, param: Optional[float] = None, out: Optional[ArrayF32] = None) -> ArrayF32: ...
def pdf(name: str, v: ArrayLike, param: Optional[float] = None, out: Optional[ArrayF32] = None) -> ArrayF32: ...
def chi2_test(name: str, samples: int = 1000000, seed: int = 1, res: int = 51, param: Optional[float] = None,
              test_count: int = 1) -> Chi2Result: ...
def bsdf_names() -> list[str]: ...
def bsdf_sample(name: str, u: ArrayLike, alpha: float = 0.1, incident: float = 30.0, kd: float = 0.5,
                distribution: str = "beckmann", int_ior: float = 1.5046, ext_ior: float = 1.000277,
                out: Optional[ArrayF32] = None) -> ArrayF32: ...
def bsdf_pdf(name: str, v: ArrayLike, alpha: float = 0.1, incident: float = 30.0, kd: float = 0.5,
             distribution: str = "beckmann", int_ior: float = 1.5046, ext_ior: float = 1.000277,
             out: Optional[ArrayF32] = None) -> ArrayF32: ...
def bsdf_chi2_test(name: str, samples: int = 1000000, seed: int = 1, res: int = 51, alpha: float = 0.1,
                   incident: float = 30.0, kd: float = 0.5, distribution: str = "beckmann",
                   int_ior: float = 1.5046, ext_ior: float = 1.000277, test_count: int = 1) -> Chi2Result: ...
def sample_points(sampler: str, n: int, pixel: Tuple[int, int] = (0, 0), dims: Tuple[int, int] = (0, 1),
                  seed: int = 0, sample_count: Optional[int] = None) -> ArrayF32: ...
def converge(scene: Scene, strategies: Union[str, Sequence[str]] = "all",
             samplers: Union[None, str, Sequence[str]] = None,
             light_selection: Union[None, str, Sequence[str]] = None,
             light_measure: Union[None, str, Sequence[str]] = None,
             heuristic: Union[None, str, Sequence[str]] = None, time: Optional[float] = None,
             spp: Optional[int] = None, reference: Union[None, PathLike, ArrayLike, RenderResult] = None,
             seed: int = 0, threads: Optional[int] = None) -> dict[object, dict[str, object]]: ...

class closed_form:
    @staticmethod
    def sphere_light_irradiance_factor(cos_theta: ArrayLike, sin_alpha: ArrayLike) -> Union[float, np.ndarray]: ...
    @staticmethod
    def sphere_light_irradiance_factor_at(x: Sequence[float], n: Sequence[float], center: Sequence[float],
                                          radius: float, two_sided: bool = False) -> float: ...
    @staticmethod
    def ao_plane_with_sphere(cos_theta: ArrayLike, sin_alpha: ArrayLike) -> Union[float, np.ndarray]: ...
    @staticmethod
    def ao_plane_near_resting_sphere(rho: ArrayLike, radius: ArrayLike) -> Union[float, np.ndarray]: ...
    @staticmethod
    def ao_on_resting_convex_body(psi: ArrayLike) -> Union[float, np.ndarray]: ...
