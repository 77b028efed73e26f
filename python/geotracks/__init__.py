"""Geodesic distances, shortest paths and distance matrices on triangle meshes.

Any topology (non-manifold edges, medial axes with free edges), under the Euclidean
metric, a density per vertex (:class:`Density`), a tensor per face (:class:`Tensor`) or per
vertex (:class:`TensorField`);
numpy arrays in and out. Build a :class:`MeshSolver` once per mesh and ask it many
questions; the work runs in Rust with the GIL released, matrices on all cores.
:meth:`MeshSolver.field` runs once from a set of sources and returns a :class:`Field`
that answers every question about that run (distances anywhere, paths, gradients,
isolines, regions, nearest sources) without running the engine again.

>>> import numpy as np, geotracks
>>> V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
>>> F = np.array([[0, 1, 2], [0, 2, 3]])
>>> solver = geotracks.MeshSolver(V, F)
>>> d = solver.distance(0)
>>> round(float(d[2]), 12) == round(2 ** 0.5, 12)
True
>>> field = solver.field(0)                          # one run from vertex 0
>>> at = field.distance_at([2, "f:0:0.2,0.3,0.5"])   # a vertex, and (0.8, 0.5) in face 0
>>> bool(abs(at[1] - np.hypot(0.8, 0.5)) < 1e-12)
True
>>> path = field.path(2)                             # from vertex 0 to vertex 2
>>> round(path.length, 12) == round(2 ** 0.5, 12)
True
>>> solver.runs                                      # solver.distance, then the field
2
"""

from __future__ import annotations

from typing import NamedTuple, Optional, Union

import numpy as np

from ._geotracks import DEFAULT_WORK_LIMIT, GeotracksError
from ._geotracks import MeshSolverCore as _Core
from ._geotracks import read_mesh as _read_mesh
from ._geotracks import skeleton as _skeleton
from ._geotracks import medial_axis as _medial_axis
from ._geotracks import terrain_route as _terrain_route

__all__ = [
    "DEFAULT_WORK_LIMIT",
    "Density",
    "Field",
    "GeotracksError",
    "Isoline",
    "MeshSolver",
    "Path",
    "Region",
    "Route",
    "Skeleton",
    "Tensor",
    "TensorField",
    "read_mesh",
    "skeleton",
    "medial_axis",
    "MedialAxis",
    "terrain_route",
]

#: A source or target: a vertex id, or a surface point written as on the command line:
#: ``"e:E:t"`` (edge ``E`` at parameter ``t`` from its lower-id vertex) or
#: ``"f:F:b0,b1,b2"`` (face ``F`` at barycentric coordinates).
Point = Union[int, str]


def _array(array, name: str, shape: tuple, integer: bool = False) -> np.ndarray:
    """`array` as a C-contiguous float64 (or, with `integer`, int64) array of `shape`
    (a tuple of sizes, a name such as ``"n"`` standing for any size), refusing what
    is not real numbers (integers only, with `integer`) and other shapes."""
    a = np.asarray(array)
    if integer:
        if a.size == 0 and a.dtype.kind == "f":
            a = a.astype(np.int64)  # an empty list
        if a.dtype.kind not in "iu":
            raise TypeError(f"{name} must hold integer vertex ids; got dtype {a.dtype}")
        if a.dtype == np.uint64 and a.size and a.max() > np.iinfo(np.int64).max:
            raise GeotracksError(f"{name} holds a vertex id beyond 2^63")
    elif a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers; got dtype {a.dtype}")
    if a.ndim != len(shape) or any(
        isinstance(want, int) and size != want for size, want in zip(a.shape, shape)
    ):
        sizes = ", ".join(str(want) for want in shape)
        raise ValueError(f"{name} must have shape ({sizes}{',' if len(shape) == 1 else ''}); got {a.shape}")
    return np.ascontiguousarray(a, dtype=np.int64 if integer else np.float64)


def _real(value, name: str) -> float:
    """`value` as a float, refusing what is not a real number (a string such as
    ``"0.6"``, a bool, None) with a TypeError naming the argument: numbers are numbers,
    as on the command line, where the text is parsed once. Whether the number is in
    range is the library's to check."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a real number; got {type(value).__name__} {value!r}")
    return float(value)


def _integer(value, name: str) -> int:
    """`value` as an int, refusing what is not an integer (a string, a float, a bool)
    with a TypeError naming the argument."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer; got {type(value).__name__} {value!r}")
    return int(value)


def _points(points, name: str) -> list:
    """One point or a sequence of them, as a list of ints and strings."""
    if isinstance(points, (str, int, np.integer)):
        points = [points]
    elif isinstance(points, np.ndarray):
        points = points.ravel().tolist()
    out = []
    for p in points:
        if isinstance(p, (bool, np.bool_)):
            raise TypeError(f"{name}: {p!r} is not a vertex id or a surface point")
        if isinstance(p, (int, np.integer)):
            out.append(int(p))
        elif isinstance(p, str):
            out.append(p)
        else:
            raise TypeError(f"{name}: {p!r} is not a vertex id or a surface point")
    if not out:
        raise GeotracksError(f"{name}: no point given")
    return out


class Density:
    """A positive cost per vertex, linear on each face: a segment costs its length times
    the mean density along it (weighted geodesics). A constant ``c`` scales every
    distance by ``c``.

    :param rho: one positive number per vertex, shape ``(n,)``.
    """

    def __init__(self, rho):
        self.rho = _array(rho, "rho", ("n",))

    def _data(self) -> tuple:
        return "density", self.rho.reshape(-1, 1)


def _symmetric_upper(m, name: str, rows: str) -> np.ndarray:
    """``(k, 3, 3)`` symmetric matrices as their ``(k, 6)`` upper entries."""
    m = _array(m, name, (rows, 3, 3))
    if not np.allclose(m, np.swapaxes(m, 1, 2), rtol=1e-12, atol=0.0, equal_nan=True):
        raise GeotracksError(f"{name}: each matrix must be symmetric")
    upper = np.stack([m[:, 0, 0], m[:, 0, 1], m[:, 0, 2], m[:, 1, 1], m[:, 1, 2], m[:, 2, 2]], axis=1)
    return np.ascontiguousarray(upper)


class Tensor:
    """A symmetric positive-definite 3 × 3 matrix per face, in world coordinates,
    restricted to each face's plane: a segment ``v`` inside a face costs
    ``sqrt(vᵀ M v)`` (direction-dependent, anisotropic cost).

    :param per_face: shape ``(m, 3, 3)``, symmetric, one matrix per face.
    """

    def __init__(self, per_face):
        self.per_face = _symmetric_upper(per_face, "per_face", "m")

    def _data(self) -> tuple:
        return "tensor", self.per_face


class TensorField:
    """A symmetric positive-definite 3 × 3 matrix per vertex, in world coordinates,
    interpolated linearly across each face (in each face's plane): a smooth Riemannian
    metric. A segment costs the exact integral of ``sqrt(vᵀ M v)`` along it; a field
    that is constant on a face costs what :class:`Tensor` does. Runs the ``"tracks"``
    engine, or ``"wave"`` when the field is constant on every face.

    :param per_vertex: shape ``(n, 3, 3)``, symmetric, one matrix per vertex.
    """

    def __init__(self, per_vertex):
        self.per_vertex = _symmetric_upper(per_vertex, "per_vertex", "n")

    def _data(self) -> tuple:
        return "tensor_field", self.per_vertex


class Path(NamedTuple):
    """A shortest path, from the source to the target."""

    #: World positions, shape ``(p, 3)``.
    points: np.ndarray
    #: Where each point lies: ``"V"`` (a vertex), ``"e:E:t"`` or ``"f:F:b0,b1,b2"``.
    surface_points: list
    #: Its length under the solver's metric.
    length: float


class Isoline(NamedTuple):
    """One piece of a level set of a distance field."""

    #: The level.
    level: float
    #: World positions along the line, shape ``(p, 3)``.
    points: np.ndarray
    #: Whether the line closes on itself (its last point is then its first).
    closed: bool


class Region(NamedTuple):
    """One region of a face: where one candidate gives the distance. Inside it the
    distance at ``x`` is ``offset`` plus the metric length of the straight segment from
    ``virtual_source`` to ``x`` in the face's plane, so its gradient points straight
    away from ``virtual_source``."""

    #: The face.
    face: int
    #: What gives the distance: ``("node", id)`` (a vertex or Steiner node), ``("source",
    #: i)`` (the i-th source), ``("wave", id)`` (a Steiner node's wave, from its virtual
    #: source), ``("wave_bend", id)`` (that wave bending round an end of its window) or
    #: ``("window", id)`` (a window of the exact engine, from its virtual source).
    source: tuple
    #: For a candidate of the neighbouring face, the edge its lines cross; ``-1``: none.
    across: int
    #: Where its straight lines come from (world, in the face's plane; a wave's virtual
    #: source usually lies outside the face), shape ``(3,)``.
    virtual_source: np.ndarray
    #: The distance at ``virtual_source``.
    offset: float
    #: The boundary, counter-clockwise, shape ``(p, 3)``; not closed (the last point is
    #: not repeated).
    polygon: np.ndarray
    #: Where each boundary point lies, as for :attr:`Path.surface_points`.
    surface_points: list
    #: Other regions inside this one, each a clockwise ``(h, 3)`` loop (usually none).
    holes: list
    #: Area, holes excluded.
    area: float


class MeshSolver:
    """A mesh and a solver on it, reused by every query.

    :param V: vertex positions, shape ``(n, 3)``, real numbers.
    :param F: triangles, shape ``(m, 3)``, integer vertex ids (0-based). Faces with a
        repeated vertex or no area are dropped.
    :param k: mean number of Steiner points per edge (default: 2 for the wavefront
        engine, 5 where the Steiner graph runs: a density, or ``method="tracks"``).
    :param method: ``"wave"`` (the default: exact on planar and developable meshes from
        one source; with a density it runs ``"tracks"``), ``"tracks"`` (the
        track-pruned Steiner graph), ``"graph"`` (the complete Steiner graph),
        ``"dijkstra"`` (mesh edges only) or ``"exact"`` (exact geodesics, for the
        Euclidean metric or a constant :class:`Tensor`; a metric whose faces do not glue
        is refused).
    :param metric: ``None`` (Euclidean), a :class:`Density`, a :class:`Tensor` or a
        :class:`TensorField`.
    :param work_limit: the most distance tests one run may be estimated to make
        (default :data:`DEFAULT_WORK_LIMIT`, a few minutes of one core; ``None``: no
        limit): a ``k`` that needs more is refused before any work, with the estimate
        and the largest ``k`` that fits.
    :raises GeotracksError: for a mesh the library refuses (NaN or huge coordinates, a
        face naming a missing vertex, no usable face), a bad metric, or a ``k`` that is
        not > 0 or breaks a limit (memory, work).
    :raises TypeError: for a ``k`` or ``work_limit`` that is not a number (``"2"``).
    """

    def __init__(
        self,
        V,
        F,
        k: Optional[float] = None,
        method: str = "wave",
        metric=None,
        work_limit: Optional[int] = DEFAULT_WORK_LIMIT,
    ):
        V = _array(V, "V", ("n", 3))
        F = _array(F, "F", ("m", 3), integer=True)
        if metric is None:
            kind, data = "euclidean", None
        elif isinstance(metric, (Density, Tensor, TensorField)):
            kind, data = metric._data()
        else:
            raise TypeError(
                "metric must be None, geotracks.Density, geotracks.Tensor or geotracks.TensorField; "
                f"got {type(metric).__name__}"
            )
        k = None if k is None else _real(k, "k")
        if work_limit is not None:
            work_limit = _integer(work_limit, "work_limit")
            if work_limit < 1:
                raise GeotracksError(f"work_limit = {work_limit}: it must be at least 1 (None: no limit)")
        self._core = _Core(V, F, k, str(method), kind, data, work_limit)

    @property
    def vertex_count(self) -> int:
        """Number of vertices."""
        return self._core.vertex_count

    @property
    def face_count(self) -> int:
        """Number of faces kept."""
        return self._core.face_count

    @property
    def method(self) -> str:
        """The engine that runs."""
        return self._core.method

    @property
    def runs(self) -> int:
        """How many times this solver's engine has run (read-only): one per
        :meth:`field` and per one-call method (:meth:`distance`, :meth:`path`,
        :meth:`gradient`, ...), one per row of :meth:`distance_matrix` and
        :meth:`local_distance_rows`. Questions asked of a :class:`Field` add nothing."""
        return self._core.runs

    def field(self, sources, max_distance: Optional[float] = None, targets=None) -> "Field":
        """One run from ``sources``: a :class:`Field` that answers every question about
        it (distances at vertices and at any surface point, paths, gradients, isolines,
        regions, nearest sources) without running the engine again. Ask a field rather
        than the one-call methods when several questions share their sources.

        :param sources: a vertex id or surface point, or a sequence of them.
        :param max_distance: stop there (``None``: no limit); farther points are
            ``inf``. A number ``>= 0`` (a negative one or NaN is refused).
        :param targets: stop once the values at these points are final (the values
            there are exact; others may be ``inf``, and paths from them unreachable).
        :raises GeotracksError: for a source or target that is not a point of the mesh,
            or a bad ``max_distance``.
        """
        max_distance = np.inf if max_distance is None else _real(max_distance, "max_distance")
        targets = None if targets is None else _points(targets, "targets")
        return Field(self._core.field(_points(sources, "sources"), max_distance, targets))

    def distance(self, sources, max_distance: float = np.inf, targets=None) -> np.ndarray:
        """Distance from the nearest of ``sources`` to every vertex, shape ``(n,)``;
        ``inf`` where unreached (another component, beyond ``max_distance``).

        :param sources: a vertex id or surface point, or a sequence of them.
        :param max_distance: stop there; farther vertices are ``inf``. A number ``>= 0``
            (a negative one or NaN is refused, as on the command line).
        :param targets: stop once the values at these points are final (the values
            returned there are exact; others may be ``inf``).

        Only the values at vertices are kept, no field: under ``method="exact"`` the
        run then holds only its wavefront's windows, not every window a field keeps
        (on a million faces, a few hundred megabytes instead of gigabytes). Use
        :meth:`field` for values at points, paths or isolines from one run.
        """
        targets = None if targets is None else _points(targets, "targets")
        return self._core.distance(_points(sources, "sources"), _real(max_distance, "max_distance"), targets)

    def voronoi(self, sources) -> tuple:
        """``(distances, labels)``: the distance to every vertex and the index (into
        ``sources``) of its nearest source, ``-1`` where unreached."""
        return self._core.voronoi(_points(sources, "sources"))

    def path(self, source, target) -> Path:
        """The shortest path from ``source`` (one point or several: the nearest) to
        ``target``, straightened, as a :class:`Path` (points from the source to the
        target)."""
        points, names, length = self._core.path(_points(source, "source"), _points(target, "target")[0])
        return Path(points[::-1].copy(), names[::-1], length)

    def gradient(self, sources, points) -> tuple:
        """The field from ``sources`` at ``points`` (vertex ids or surface points):
        ``(distances (p,), gradients (p, 3), directions (p, 3))``. The gradient of the
        distance and the unit direction in which the geodesic that reaches the point
        travels there, away from its source, both world vectors in the plane of the
        point's face. ``inf`` and NaN where unreached; NaN vectors where the distance
        has no gradient (at a source)."""
        return self._core.gradient(_points(sources, "sources"), _points(points, "points"))

    def isolines(self, sources, levels, subdivisions: Optional[int] = None) -> list:
        """The level sets of the distance from ``sources`` at each of ``levels``, as a
        list of :class:`Isoline` (several per level where the set has several pieces),
        each point on its level to 1e-12. ``subdivisions``: sub-triangles per face
        edge (default 4); a loop smaller than one can be missed. At most 1000 levels
        per call (``geotracks::trace::MAX_LEVELS``)."""
        levels = [_real(x, "levels") for x in np.atleast_1d(levels).tolist()]
        if subdivisions is not None:
            subdivisions = _integer(subdivisions, "subdivisions")
        lines = self._core.isolines(_points(sources, "sources"), levels, subdivisions)
        return [Isoline(level, points, closed) for level, points, closed in lines]

    def regions(self, sources, faces=None, subdivisions: Optional[int] = None) -> list:
        """The regions of the distance from ``sources`` in each of ``faces`` (default:
        every face), as a list of :class:`Region`, face by face. Each face is cut by a
        grid of ``subdivisions`` steps per edge (default 16): boundaries on the face's
        edges and straight boundaries are exact, curved ones are chords between points
        on the true boundary, and a region thinner than a grid step may be missed.
        Unreached parts of a face belong to no region."""
        if faces is not None:
            faces = _array(np.atleast_1d(faces), "faces", ("n",), integer=True)
        if subdivisions is not None:
            subdivisions = _integer(subdivisions, "subdivisions")
        regions = self._core.regions(_points(sources, "sources"), faces, subdivisions)
        return [Region(*r) for r in regions]

    def distance_matrix(self, sources, targets=None) -> np.ndarray:
        """Distances from each source vertex (rows) to every vertex, or to ``targets``
        (columns), computed in parallel; shape ``(len(sources), n or len(targets))``.
        A matrix that would not fit in the memory available (8 bytes a value) is
        refused before any row is computed."""
        sources = _array(np.atleast_1d(sources), "sources", ("n",), integer=True)
        targets = None if targets is None else _array(np.atleast_1d(targets), "targets", ("n",), integer=True)
        return self._core.distance_matrix(sources, targets)

    def local_distance_rows(self, sources, max_distance: float) -> tuple:
        """For each source vertex, every vertex within ``max_distance``: ``(rows,
        columns, distances)`` arrays (row: the source's vertex id), computed in
        parallel: the triples of :meth:`local_distance_matrix` for some rows only."""
        sources = _array(np.atleast_1d(sources), "sources", ("n",), integer=True)
        return self._core.local_distance_rows(sources, _real(max_distance, "max_distance"))

    def local_distance_matrix(self, max_distance: float):
        """Every pair of vertices within ``max_distance`` of each other, as a
        ``scipy.sparse.csr_matrix`` of shape ``(n, n)`` (row: the source vertex; the
        diagonal's zeros are stored). What tvb-gdist's ``local_gdist_matrix`` gives."""
        from scipy.sparse import csr_matrix

        n = self.vertex_count
        rows, cols, data = self._core.local_distance_rows(
            np.arange(n, dtype=np.int64), _real(max_distance, "max_distance")
        )
        return csr_matrix((data, (rows, cols)), shape=(n, n))


class Field:
    """One run of a :class:`MeshSolver` from a set of sources
    (:meth:`MeshSolver.field`), which answers every question about it without running
    the engine again. It keeps the solver's mesh and engine alive on its own (deleting
    the :class:`MeshSolver` does not break it), and several threads may ask it at
    once: the work runs in Rust with the GIL released.

    Each method gives what the one-call method of the same name of
    :class:`MeshSolver` gives for the same sources, without the sources.
    """

    __slots__ = ("_core",)

    def __init__(self, core):
        self._core = core

    def __repr__(self) -> str:
        stats = self.stats
        return f"<geotracks.Field from {self.sources!r}, {stats['method']}, k = {stats['k']:g}>"

    @property
    def sources(self) -> list:
        """The run's sources, as :attr:`Path.surface_points` writes points (``"V"``,
        ``"e:E:t"``, ``"f:F:b0,b1,b2"``; accepted back as sources)."""
        return self._core.sources

    @property
    def stats(self) -> dict:
        """The run's counters: ``method`` (the engine that ran), ``k`` (mean Steiner
        points per edge), ``settles`` (nodes taken from the queue), ``pushes`` (queue
        insertions), ``distance_tests`` (metric evaluations), ``propagate_seconds``
        and ``stopped_early`` (the run ended at its targets)."""
        return self._core.stats

    @property
    def vertex_count(self) -> int:
        """Number of vertices of the mesh."""
        return self._core.vertex_count

    def distance(self) -> np.ndarray:
        """Distance from the nearest source to every vertex, shape ``(n,)``; ``inf``
        where unreached (as :meth:`MeshSolver.distance`)."""
        return self._core.distance()

    def distance_at(self, points) -> np.ndarray:
        """The distance at each of ``points`` (vertex ids or surface points, one or a
        sequence), shape ``(p,)``: the engine's value anywhere on the surface, not an
        interpolation of vertex values; ``inf`` where unreached.

        :raises GeotracksError: for a point that is not a point of the mesh."""
        return self._core.distance_at(_points(points, "points"))

    def path(self, target) -> Path:
        """The shortest path from the nearest source to ``target``, straightened, as a
        :class:`Path` (points from the source to the target).

        :raises GeotracksError: for a target off the mesh, or one no source reaches
            (another component, beyond the run's ``max_distance`` or past its targets)."""
        points, names, length = self._core.path(_points(target, "target")[0])
        return Path(points[::-1].copy(), names[::-1], length)

    def gradient(self, points) -> tuple:
        """At ``points``: ``(distances (p,), gradients (p, 3), directions (p, 3))``, as
        :meth:`MeshSolver.gradient`."""
        return self._core.gradient(_points(points, "points"))

    def isolines(self, levels, subdivisions: Optional[int] = None) -> list:
        """The level sets at each of ``levels``, as a list of :class:`Isoline`, as
        :meth:`MeshSolver.isolines` (a NaN or infinite level is refused)."""
        levels = [_real(x, "levels") for x in np.atleast_1d(levels).tolist()]
        if subdivisions is not None:
            subdivisions = _integer(subdivisions, "subdivisions")
        return [Isoline(level, points, closed) for level, points, closed in self._core.isolines(levels, subdivisions)]

    def regions(self, faces=None, subdivisions: Optional[int] = None) -> list:
        """The regions of each of ``faces`` (default: every face), as a list of
        :class:`Region`, as :meth:`MeshSolver.regions`."""
        if faces is not None:
            faces = _array(np.atleast_1d(faces), "faces", ("n",), integer=True)
        if subdivisions is not None:
            subdivisions = _integer(subdivisions, "subdivisions")
        return [Region(*r) for r in self._core.regions(faces, subdivisions)]

    def voronoi(self) -> np.ndarray:
        """Per vertex, the index (into :attr:`sources`) of its nearest source, int64,
        ``-1`` where unreached: the labels of :meth:`MeshSolver.voronoi`."""
        return self._core.voronoi()


def read_mesh(path) -> tuple:
    """Reads a mesh file (OBJ, PLY, OFF, STL, ``.ma``): ``(V (n, 3) float64, F (m, 3)
    int64)``; degenerate faces are dropped."""
    return _read_mesh(str(path))


class Route(NamedTuple):
    """A route across an elevation grid, from the start to the end."""

    #: Map x, y and elevation z of each point, shape ``(p, 3)``.
    points: np.ndarray
    #: The cost from the start to each point, shape ``(p,)`` (0 at the start).
    cumulative_cost: np.ndarray
    #: The route's total cost.
    cost: float


def terrain_route(
    dem, start, end, cost: str = "none", k: float = 2.0, method: str = "wave"
) -> Route:
    """The least-cost route across an elevation grid (ESRI ASCII ``.asc`` or GeoTIFF)
    between two map points ``(x, y)``, straightened. Only the window of the grid that
    a route as cheap could cross is searched, and no mesh is built
    (``geotracks::terrain::route_on_grid``):
    the same route as on the whole grid, in a fraction of the time and memory.

    :param cost: ``"none"`` (3D length), ``"slope:A"`` (length times ``1 + A·tan²``),
        ``"slope:A,max:DEG"`` (faces steeper than DEG impassable), ``"incline:B"``
        (crossing the contour lines costs more, either way), or a directed cost,
        climbing dearer than descending, from ``start``: ``"uphill:B"`` (3D length +
        B per metre climbed), ``"naismith"``, ``"rwalk[:a,b,c,d[,sf]]"`` (GRASS
        r.walk's walking time, seconds), ``"tobler[:offpath]"`` (Tobler's hiking
        function, seconds); as ``geotracks terrain --cost``.
    :param method: ``"wave"`` (the best route at a given k; ``"none"`` and
        ``"incline:B"`` run it, the other costs the Steiner graph) or ``"tracks"``
        (the Steiner graph, goal-directed: it settles a corridor around the route;
        ``"none"`` at ``k=4`` routes as well as ``"wave"`` at ``k=2``, faster), as
        ``geotracks terrain --method``.
    :raises GeotracksError: for an unreadable grid, a point off the grid or on NODATA,
        a bad cost, a bad method, or no route.
    """
    start = tuple(_real(c, "start") for c in start)
    end = tuple(_real(c, "end") for c in end)
    if len(start) != 2 or len(end) != 2:
        raise ValueError("start and end are map points (x, y)")
    points, cumulative, total = _terrain_route(
        str(dem), start, end, str(cost), _real(k, "k"), str(method)
    )
    return Route(points, cumulative, total)


class Skeleton(NamedTuple):
    """A curve skeleton: points on the medial axis and straight edges between them."""

    #: Positions, shape ``(p, 3)``.
    points: np.ndarray
    #: The medial radius interpolated at each point, shape ``(p,)``.
    radii: np.ndarray
    #: Each point's branch significance (erosion thickness; ``inf`` on loops and for
    #: the last point of each component), shape ``(p,)``.
    significance: np.ndarray
    #: Point index pairs, shape ``(e, 2)``.
    edges: np.ndarray
    #: The axis's first Betti number (from a surface mesh, the solid's: its handles).
    #: The skeleton has as many independent cycles (edges − points + components),
    #: less the holes of the axis that its medial balls fill (no tunnel of the solid,
    #: which approximate axes have: the command line's JSON says how many as
    #: ``opened_cycles``).
    b1: int


def skeleton(
    axis,
    prune="5%",
    burn: str = "boundary",
    k: float = 5.0,
    tubular: float = 1.0,
    spacing: Optional[float] = None,
    angle: float = 60.0,
    span: float = 1.5,
    weld: bool = False,
    centred: Optional[bool] = None,
    protrusion: float = 0.5,
    trim_tips: bool = True,
) -> Skeleton:
    """The curve skeleton of a medial axis file (``.ma``), or of a closed surface mesh
    file (OBJ, PLY, OFF, STL) through its :func:`medial_axis`, with the axis's topology,
    as ``geotracks skeleton`` makes it.

    :param prune: a length, or a percentage of the bounding-box diagonal (``"5%"``, the
        default); branches whose erosion thickness is less go whole, and once the
        skeleton is placed, branches from tips shorter than that.
    :param tubular: branches whose erosion thickness is less than this many times the
        medial radius where they join the rest go whole too (a bump short for its
        thickness before a thin limb of the same length); 0 keeps them.
    :param protrusion: then branches whose medial balls reach out of the rest of the
        skeleton's balls by less than this many times the medial radius where they
        join go whole, least protrusive first (spurs inside the body, low bumps); 0
        keeps them.
    :param trim_tips: cut each placed branch from a tip back to the innermost medial
        ball that holds its end, by no more than the end's radius, near where a
        mean-curvature-flow skeleton's tips lie (the default); ``False`` lets branches
        run out to where the axis meets the surface.
    :param burn: ``"boundary"`` (the grassfire from the axis's border) or ``"radius"``
        (each point burns at its medial radius).
    :param spacing, angle, span, weld: for a surface mesh, as in :func:`medial_axis`.
    :param centred: ``True`` moves the points off the axis to the centre of the
        shape's cross-section there (the cut of the medial balls by the plane across the
        curve), as a mean-curvature-flow skeleton lies; radii are then those of the
        largest balls centred there. ``False`` keeps them on the axis (a computed one
        zig-zags round the true one where a limb is only a few samples across). By
        default (``None``), centred, for a ``.ma`` file and a surface mesh alike. An
        axis of curves only keeps its points on its curves either way.
    """
    return Skeleton(
        *_skeleton(
            str(axis),
            str(prune),
            str(burn),
            _real(k, "k"),
            _real(tubular, "tubular"),
            None if spacing is None else _real(spacing, "spacing"),
            _real(angle, "angle"),
            _real(span, "span"),
            bool(weld),
            None if centred is None else bool(centred),
            _real(protrusion, "protrusion"),
            bool(trim_tips),
        )
    )


class MedialAxis(NamedTuple):
    """A medial axis: sheets of triangles with the medial ball radius at each vertex."""

    #: Vertex positions, shape ``(n, 3)``.
    positions: np.ndarray
    #: The medial ball radius at each vertex, shape ``(n,)``.
    radii: np.ndarray
    #: Triangles (vertex indices), shape ``(f, 3)``.
    faces: np.ndarray


def medial_axis(
    mesh,
    spacing: Optional[float] = None,
    angle: float = 60.0,
    span: float = 1.5,
    weld: bool = False,
) -> MedialAxis:
    """The medial axis of the solid that a closed surface mesh file bounds, from the
    Voronoi diagram of points sampled on it, as ``geotracks medial-axis`` makes it.

    :param spacing: the largest distance between samples on a face (points are added
        on faces larger than that); ``None``: the mesh's mean edge length.
    :param angle: keep the Voronoi facets whose two samples are seen under at least
        this many degrees from the facet, and half of it from its deepest point;
        larger drops more spikes toward the surface.
    :param span: keep the Voronoi facets whose two samples lie at least this many
        spacings apart; larger drops more of the sampling's spikes, and more of the
        axis at the tips of limbs.
    :param weld: merge vertices at identical positions first (seams split them, which
        would leave the surface open).
    :raises GeotracksError: for an open or non-manifold surface, or one with no volume.
    """
    positions, radii, faces = _medial_axis(
        str(mesh),
        None if spacing is None else _real(spacing, "spacing"),
        _real(angle, "angle"),
        _real(span, "span"),
        bool(weld),
    )
    return MedialAxis(positions, radii, faces)
