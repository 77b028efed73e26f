"""Type stubs of the compiled module (`python/src/lib.rs`); use the `geotracks`
package's wrappers, which check arrays and document the calls."""

from os import PathLike
from typing import Optional, Union

import numpy as np
import numpy.typing as npt

_Point = Union[int, str]

class GeotracksError(ValueError):
    """What the geotracks library refused, with its message."""

#: The default work limit: estimated distance tests per run (`Options::DEFAULT_WORK_LIMIT`).
DEFAULT_WORK_LIMIT: int

class MeshSolverCore:
    def __init__(
        self,
        vertices: npt.NDArray[np.float64],
        faces: npt.NDArray[np.int64],
        k: Optional[float],
        method: str,
        metric: str,
        data: Optional[npt.NDArray[np.float64]] = None,
        work_limit: Optional[int] = ...,
    ) -> None: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def face_count(self) -> int: ...
    @property
    def method(self) -> str: ...
    @property
    def runs(self) -> int: ...
    def field(
        self,
        sources: list[_Point],
        max_distance: float = ...,
        targets: Optional[list[_Point]] = None,
    ) -> FieldCore: ...
    def distance(
        self,
        sources: list[_Point],
        max_distance: float = ...,
        targets: Optional[list[_Point]] = None,
    ) -> npt.NDArray[np.float64]: ...
    def voronoi(
        self, sources: list[_Point]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
    def path(
        self, sources: list[_Point], target: _Point
    ) -> tuple[npt.NDArray[np.float64], list[str], float]: ...
    def gradient(
        self, sources: list[_Point], points: list[_Point]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def isolines(
        self, sources: list[_Point], levels: list[float], subdivisions: Optional[int] = None
    ) -> list[tuple[float, npt.NDArray[np.float64], bool]]: ...
    def regions(
        self,
        sources: list[_Point],
        faces: Optional[npt.NDArray[np.int64]] = None,
        subdivisions: Optional[int] = None,
    ) -> list[
        tuple[
            int,
            tuple[str, int],
            int,
            npt.NDArray[np.float64],
            float,
            npt.NDArray[np.float64],
            list[str],
            list[npt.NDArray[np.float64]],
            float,
        ]
    ]: ...
    def distance_matrix(
        self,
        sources: npt.NDArray[np.int64],
        targets: Optional[npt.NDArray[np.int64]] = None,
    ) -> npt.NDArray[np.float64]: ...
    def local_distance_rows(
        self, sources: npt.NDArray[np.int64], max_distance: float
    ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.float64]]: ...

class FieldCore:
    @property
    def sources(self) -> list[str]: ...
    @property
    def stats(self) -> dict[str, Union[str, float, int, bool]]: ...
    @property
    def vertex_count(self) -> int: ...
    def distance(self) -> npt.NDArray[np.float64]: ...
    def distance_at(self, points: list[_Point]) -> npt.NDArray[np.float64]: ...
    def path(self, target: _Point) -> tuple[npt.NDArray[np.float64], list[str], float]: ...
    def gradient(
        self, points: list[_Point]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def isolines(
        self, levels: list[float], subdivisions: Optional[int] = None
    ) -> list[tuple[float, npt.NDArray[np.float64], bool]]: ...
    def regions(
        self,
        faces: Optional[npt.NDArray[np.int64]] = None,
        subdivisions: Optional[int] = None,
    ) -> list[
        tuple[
            int,
            tuple[str, int],
            int,
            npt.NDArray[np.float64],
            float,
            npt.NDArray[np.float64],
            list[str],
            list[npt.NDArray[np.float64]],
            float,
        ]
    ]: ...
    def voronoi(self) -> npt.NDArray[np.int64]: ...

def read_mesh(
    path: Union[str, PathLike[str]],
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
def terrain_route(
    dem: str,
    start: tuple[float, float],
    end: tuple[float, float],
    cost: str = "none",
    k: float = 2.0,
    method: str = "wave",
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], float]: ...
def skeleton(
    axis: str,
    prune: str = "5%",
    burn: str = "boundary",
    k: float = 5.0,
    tubular: float = 1.0,
    spacing: float | None = None,
    angle: float = 60.0,
    span: float = 1.5,
    weld: bool = False,
    centred: bool | None = None,
    protrusion: float = 0.5,
    trim_tips: bool = True,
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.int64],
    int,
]: ...
def medial_axis(
    mesh: str,
    spacing: float | None = None,
    angle: float = 60.0,
    span: float = 1.5,
    weld: bool = False,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
