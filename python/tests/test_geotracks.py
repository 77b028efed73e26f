"""The Python bindings: results against exact references and analytic cases, the same
answers however a query is asked, and errors for bad input."""

import threading
from pathlib import Path

import numpy as np
import pytest

import geotracks

DATA = Path(__file__).resolve().parents[2] / "tests" / "data"


@pytest.fixture(scope="module")
def spot():
    return geotracks.read_mesh(DATA / "spot.obj")


def grid(n=8, size=1.0):
    """A flat n × n grid on [0, size]², z = 0."""
    xs = np.linspace(0.0, size, n + 1)
    X, Y = np.meshgrid(xs, xs)
    V = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            F += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return V, np.array(F)


def test_spot_against_the_exact_distances(spot):
    V, F = spot
    assert V.shape == (2930, 3) and F.shape == (5856, 3)
    assert V.dtype == np.float64 and F.dtype == np.int64
    exact = np.fromfile(DATA / "spot.src0.f64", dtype="<f8")
    solver = geotracks.MeshSolver(V, F)
    assert solver.method == "wave"
    d = solver.distance(0)
    assert d.shape == (2930,) and d[0] == 0.0
    error = np.abs(d[1:] - exact[1:]) / exact[1:]
    # The accuracy the README states at k = 2 (mean 0.002–0.06 % on the shared meshes).
    assert error.mean() < 1e-3 and error.max() < 2e-2, (error.mean(), error.max())
    tracks = geotracks.MeshSolver(V, F, method="tracks").distance(0)
    assert np.abs(tracks - exact)[1:].max() / exact.max() < 2e-2


def test_a_plane_is_exact_and_surface_points_are_sources():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    d = solver.distance(0)
    assert np.allclose(d, np.hypot(V[:, 0], V[:, 1]), atol=1e-12)
    # A source inside face 0 at its centroid, and on an edge.
    centroid = V[F[0]].mean(axis=0)
    d = solver.distance("f:0:0.3333333333333333,0.3333333333333333,0.3333333333333334")
    assert np.allclose(d, np.linalg.norm(V - centroid, axis=1), atol=1e-9)
    two = solver.distance([0, len(V) - 1])
    far = np.hypot(V[:, 0] - 1.0, V[:, 1] - 1.0)
    assert np.allclose(two, np.minimum(np.hypot(V[:, 0], V[:, 1]), far), atol=1e-12)


def test_early_stops():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    d = solver.distance(0, max_distance=0.5)
    r = np.hypot(V[:, 0], V[:, 1])
    assert np.all(np.isinf(d[r > 0.5 + 1e-9]))
    assert np.allclose(d[r <= 0.5], r[r <= 0.5], atol=1e-12)
    full = solver.distance(0)
    stopped = solver.distance(0, targets=[10])
    assert stopped[10] == full[10]
    assert np.isinf(stopped).any()


def test_metrics():
    V, F = grid(6)
    plain = geotracks.MeshSolver(V, F, method="tracks").distance(0)
    twice = geotracks.MeshSolver(V, F, metric=geotracks.Density(np.full(len(V), 2.0)))
    assert twice.method == "tracks"
    assert np.allclose(twice.distance(0), 2.0 * plain, rtol=1e-12)
    identity = geotracks.Tensor(np.repeat(np.eye(3)[None], len(F), axis=0))
    same = geotracks.MeshSolver(V, F, metric=identity).distance(0)
    assert np.allclose(same, np.hypot(V[:, 0], V[:, 1]), atol=1e-12)
    # Moving along x costs 3 times as much: the far corner along x is 3 away.
    stretched = np.repeat(np.diag([9.0, 1.0, 1.0])[None], len(F), axis=0)
    d = geotracks.MeshSolver(V, F, metric=geotracks.Tensor(stretched)).distance(0)
    assert abs(d[6] - 3.0) < 1e-9
    # A tensor per vertex: constant, it is the constant tensor (flat on every face, it
    # runs the wavefront engine at its k); growing along x, it runs tracks, and the
    # bottom row costs the integral of sqrt(1 + 8 x).
    constant = geotracks.TensorField(np.repeat(np.diag([9.0, 1.0, 1.0])[None], len(V), axis=0))
    field = geotracks.MeshSolver(V, F, metric=constant)
    assert field.method == "wave"
    tensor = geotracks.MeshSolver(V, F, metric=geotracks.Tensor(stretched))
    assert np.allclose(field.distance(0), tensor.distance(0), rtol=1e-12)
    growing = np.array([np.diag([1.0 + 8.0 * x, 1.0, 1.0]) for x in V[:, 0]])
    varying = geotracks.MeshSolver(V, F, metric=geotracks.TensorField(growing))
    assert varying.method == "tracks"
    assert abs(varying.distance(0)[6] - 26.0 / 12.0) < 1e-12
    with pytest.raises(geotracks.GeotracksError, match="vertex 3"):
        bad = growing.copy()
        bad[3] = -np.eye(3)
        geotracks.MeshSolver(V, F, metric=geotracks.TensorField(bad))


def test_voronoi_labels_each_source_region():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    d, labels = solver.voronoi([0, 80])
    assert labels.dtype == np.int64 and labels[0] == 0 and labels[80] == 1
    nearer_first = np.hypot(V[:, 0], V[:, 1]) < np.hypot(V[:, 0] - 1, V[:, 1] - 1) - 1e-9
    assert np.all(labels[nearer_first] == 0)
    assert np.allclose(d, solver.distance([0, 80]))


def test_path_on_spot(spot):
    V, F = spot
    solver = geotracks.MeshSolver(V, F)
    path = solver.path(0, 100)
    assert path.points.shape[1] == 3 and len(path.surface_points) == len(path.points)
    assert path.surface_points[0] == "0" and path.surface_points[-1] == "100"
    assert np.allclose(path.points[0], V[0]) and np.allclose(path.points[-1], V[100])
    d = solver.distance(0)[100]
    assert path.length <= d + 1e-12 and path.length > 0.999 * d
    steps = np.linalg.norm(np.diff(path.points, axis=0), axis=1).sum()
    assert abs(steps - path.length) < 1e-9


def test_dense_and_sparse_matrices_agree(spot):
    V, F = spot
    solver = geotracks.MeshSolver(V, F)
    rows = solver.distance_matrix(np.arange(5))
    assert rows.shape == (5, len(V))
    for i in range(5):
        assert np.array_equal(rows[i], solver.distance(i))
    picked = solver.distance_matrix([3, 7], targets=[0, 10, 20])
    assert picked.shape == (2, 3)
    assert np.array_equal(picked[0], rows[3][[0, 10, 20]])
    assert np.array_equal(picked[1], solver.distance(7)[[0, 10, 20]])
    radius = 0.1
    sparse = solver.local_distance_matrix(radius)
    assert sparse.shape == (len(V), len(V))
    for i in range(5):
        row = sparse.getrow(i)
        dense = rows[i]
        within = np.flatnonzero(dense <= radius)
        assert set(row.indices) == set(within)
        assert np.array_equal(row.toarray().ravel()[within], dense[within])


def test_many_threads_share_one_solver(spot):
    V, F = spot
    solver = geotracks.MeshSolver(V, F)
    expected = [solver.distance(s) for s in range(4)]
    results = [None] * 4

    def run(s):
        results[s] = solver.distance(s)

    threads = [threading.Thread(target=run, args=(s,)) for s in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for s in range(4):
        assert np.array_equal(results[s], expected[s])


def test_non_contiguous_and_other_numeric_types_give_the_same_answer():
    V, F = grid(4)
    base = geotracks.MeshSolver(V, F).distance(0)
    wide = np.zeros((len(V), 6))
    wide[:, ::2] = V  # every other column: a strided view
    assert not wide[:, ::2].flags["C_CONTIGUOUS"]
    assert np.array_equal(geotracks.MeshSolver(wide[:, ::2], F).distance(0), base)
    assert np.array_equal(geotracks.MeshSolver(V.astype(np.float32).astype(np.float64), F.astype(np.uint32)).distance(0), base)
    assert np.array_equal(geotracks.MeshSolver(V.tolist(), F.tolist()).distance(np.int32(0)), base)


@pytest.mark.parametrize(
    "V, F, error, words",
    [
        (np.zeros((4, 2)), [[0, 1, 2]], ValueError, "shape (n, 3)"),
        (np.zeros((4, 3)), [0, 1, 2], ValueError, "shape (m, 3)"),
        (np.array([["a", "b", "c"]] * 3), [[0, 1, 2]], TypeError, "real numbers"),
        (np.eye(3), np.array([[0.0, 1.0, 2.0]]), TypeError, "integer vertex ids"),
        (np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]]), [[0, 1, 2]], geotracks.GeotracksError, "vertex 2"),
        (np.eye(3), [[0, 1, 3]], geotracks.GeotracksError, "vertex"),
        (np.eye(3), [[0, 1, -1]], geotracks.GeotracksError, "not a vertex id"),
        (np.zeros((3, 3)), [[0, 1, 2]], geotracks.GeotracksError, "no usable face"),
    ],
)
def test_bad_meshes_are_refused(V, F, error, words):
    with pytest.raises(error, match=None) as info:
        geotracks.MeshSolver(V, F)
    assert words in str(info.value), str(info.value)


def test_bad_queries_are_refused():
    V, F = grid(2)
    solver = geotracks.MeshSolver(V, F)
    assert issubclass(geotracks.GeotracksError, ValueError)
    with pytest.raises(geotracks.GeotracksError, match="out of range|does not exist|vertex 99"):
        solver.distance(99)
    with pytest.raises(geotracks.GeotracksError, match="not a surface point"):
        solver.distance("f:0:2,3")
    with pytest.raises(TypeError):
        solver.distance(1.5)
    with pytest.raises(geotracks.GeotracksError, match="no point"):
        solver.distance([])
    with pytest.raises(geotracks.GeotracksError):
        solver.distance(0, max_distance=float("nan"))
    with pytest.raises(geotracks.GeotracksError, match="target"):
        solver.distance_matrix([0], targets=[1000])
    with pytest.raises(geotracks.GeotracksError, match="max_distance"):
        solver.local_distance_matrix(-1.0)
    with pytest.raises(geotracks.GeotracksError, match="method|wave"):
        geotracks.MeshSolver(V, F, method="fast")
    with pytest.raises(geotracks.GeotracksError, match="density"):
        geotracks.MeshSolver(V, F, metric=geotracks.Density(np.ones(3)))
    with pytest.raises(geotracks.GeotracksError):
        geotracks.MeshSolver(V, F, metric=geotracks.Density(-np.ones(len(V))))
    with pytest.raises(geotracks.GeotracksError, match="symmetric"):
        geotracks.Tensor(np.repeat(np.array([[[1.0, 2.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]]), len(F), 0))
    with pytest.raises(geotracks.GeotracksError):
        geotracks.MeshSolver(V, F, metric=geotracks.Tensor(np.repeat(-np.eye(3)[None], len(F), 0)))
    with pytest.raises(TypeError, match="metric"):
        geotracks.MeshSolver(V, F, metric="euclidean")
    with pytest.raises(geotracks.GeotracksError):
        geotracks.read_mesh(DATA / "no-such-file.obj")


def test_the_docstring_examples_run():
    import doctest

    result = doctest.testmod(geotracks)
    assert result.attempted > 0 and result.failed == 0


def test_terrain_route_on_a_plane(tmp_path):
    # A tilted plane z = 0.5 x on a 21 × 21 grid of 1 m cells.
    rows = "\n".join(" ".join(f"{0.5 * c:g}" for c in range(21)) for _ in range(21))
    dem = tmp_path / "tilted.asc"
    dem.write_text(
        "ncols 21\nnrows 21\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n" + rows + "\n"
    )
    route = geotracks.terrain_route(dem, (2.5, 2.5), (17.5, 10.5))
    straight = np.linalg.norm([15.0, 8.0, 7.5])
    assert abs(route.cost - straight) < 1e-6 * straight
    assert np.allclose(route.points[0][:2], [2.5, 2.5]) and np.allclose(route.points[-1][:2], [17.5, 10.5])
    assert route.cumulative_cost[0] == 0.0 and route.cumulative_cost[-1] == route.cost
    # The Steiner graph, goal-directed: on a plane, the same straight line.
    tracks = geotracks.terrain_route(dem, (2.5, 2.5), (17.5, 10.5), method="tracks")
    assert abs(tracks.cost - straight) < 1e-6 * straight
    steeper = geotracks.terrain_route(dem, (2.5, 2.5), (17.5, 10.5), cost="slope:4")
    assert steeper.cost > route.cost
    # Naismith's rule is directed: 0.72 s per map metre, and 6 s per metre climbed.
    up = geotracks.terrain_route(dem, (2.5, 2.5), (17.5, 10.5), cost="naismith")
    down = geotracks.terrain_route(dem, (17.5, 10.5), (2.5, 2.5), cost="naismith")
    assert abs(up.cost - (0.72 * 17.0 + 6.0 * 7.5)) < 1e-6 * up.cost
    assert abs(down.cost - 0.72 * 17.0) < 1e-6 * down.cost
    with pytest.raises(geotracks.GeotracksError, match="start"):
        geotracks.terrain_route(dem, (-50, 2), (10, 10))
    with pytest.raises(geotracks.GeotracksError):
        geotracks.terrain_route(dem, (2, 2), (10, 10), cost="steep")
    with pytest.raises(geotracks.GeotracksError, match="method"):
        geotracks.terrain_route(dem, (2, 2), (10, 10), method="fast")


def test_skeleton_of_a_medial_axis():
    sk = geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune="2%")
    p = len(sk.points)
    assert sk.points.shape == (p, 3) and sk.radii.shape == (p,) and sk.edges.shape[1] == 2
    assert np.all(sk.radii > 0) and sk.edges.max() < p
    # Cycles of the graph (E − V + C) equal the axis's b1.
    import scipy.sparse as sparse
    from scipy.sparse.csgraph import connected_components

    def cycles(sk):
        n = len(sk.points)
        edges = (np.ones(len(sk.edges)), (sk.edges[:, 0], sk.edges[:, 1]))
        components = connected_components(sparse.coo_matrix(edges, shape=(n, n)), directed=False)[0]
        return len(sk.edges) - n + components

    assert cycles(sk) == sk.b1
    everything = geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune=0, tubular=0, protrusion=0)
    assert len(everything.points) > p
    # By tubularity alone, branches go too, and the cycles stay.
    thick = geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune=0, tubular=1e9, protrusion=0)
    assert len(thick.points) < len(everything.points)
    assert cycles(thick) == thick.b1
    with pytest.raises(geotracks.GeotracksError, match="tubular"):
        geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", tubular=-1)
    # By protrusion alone, branches go as well, and the cycles stay.
    covered = geotracks.skeleton(
        DATA / "ma" / "sheet_fins.ma", prune=0, tubular=0, protrusion=1e9
    )
    assert len(covered.points) < len(everything.points)
    assert cycles(covered) == covered.b1
    with pytest.raises(geotracks.GeotracksError, match="protrusion"):
        geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", protrusion=-1)
    with pytest.raises(geotracks.GeotracksError, match="prune"):
        geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune="-1")
    with pytest.raises(geotracks.GeotracksError, match="burn"):
        geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", burn="fire")
    def length(sk):
        return np.linalg.norm(sk.points[sk.edges[:, 0]] - sk.points[sk.edges[:, 1]], axis=1).sum()

    def degrees(sk):
        return np.bincount(sk.edges.ravel(), minlength=len(sk.points))

    # Tips trimmed (the default): shorter than untrimmed, the same cycles and tips.
    untrimmed = geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune="2%", trim_tips=False)
    assert length(sk) < length(untrimmed) and cycles(untrimmed) == untrimmed.b1
    assert np.sum(degrees(untrimmed) == 1) == np.sum(degrees(sk) == 1)
    # Centred by default; on the axis, the same graph's shape (tips, junctions,
    # cycles), its points elsewhere; radii inside the balls either way.
    centred = geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune="2%", centred=True)
    assert np.array_equal(centred.points, sk.points)
    on_axis = geotracks.skeleton(DATA / "ma" / "sheet_fins.ma", prune="2%", centred=False)
    assert cycles(on_axis) == on_axis.b1
    assert not np.array_equal(on_axis.points, sk.points)
    for degree in (1, 3):
        assert np.sum(degrees(on_axis) == degree) == np.sum(degrees(sk) == degree)
    assert np.all(centred.radii >= 0) and np.all(on_axis.radii >= 0)


def test_isolines_lie_on_their_level():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    lines = solver.isolines(0, [0.5, 1.2])
    assert {line.level for line in lines} == {0.5, 1.2}
    for line in lines:
        r = np.hypot(line.points[:, 0], line.points[:, 1])
        assert np.allclose(r, line.level, atol=1e-9), line.level
        assert not line.closed and len(line.points) > 5
    # A closed loop round a source in the middle.
    (loop,) = solver.isolines(40, [0.25])
    assert loop.closed and np.allclose(loop.points[0], loop.points[-1])
    with pytest.raises(geotracks.GeotracksError):
        solver.isolines(0, [float("nan")])


def test_regions_on_a_plane_come_from_the_sources():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    sources = [0, 80]  # opposite corners: the bisector x + y = 1 cuts the diagonal faces
    regions = solver.regions(sources)
    area = np.zeros(len(F))
    big = np.zeros(len(F), dtype=int)
    cell = 0.5 * (1 / 8) ** 2
    for r in regions:
        assert r.across == -1 or 0 <= r.across
        assert r.polygon.shape == (len(r.surface_points), 3) and len(r.polygon) >= 3
        # The region's formula, offset plus the straight line from its virtual source,
        # is never below the distance (on a plane every candidate is a path), and
        # gives it at the mesh's vertices on the boundary (the other boundary points
        # are chords of curved boundaries, or where three regions meet).
        value = r.offset + np.linalg.norm(r.polygon - r.virtual_source, axis=1)
        exact = np.min([np.linalg.norm(r.polygon - V[s], axis=1) for s in sources], axis=0)
        assert np.all(value >= exact - 1e-12)
        at_vertex = np.array([p.isdigit() for p in r.surface_points])
        assert np.allclose(value[at_vertex], exact[at_vertex], atol=1e-12)
        # No slivers where a node ties with the source whose line it lies on; each
        # region's lines come straight from a source.
        assert r.area > 1e-6 * cell, r
        assert min(np.linalg.norm(r.virtual_source - V[s]) for s in sources) < 1e-9
        assert r.offset == pytest.approx(0.0, abs=1e-12)
        big[r.face] += 1
        area[r.face] += r.area
    assert np.allclose(area, cell, rtol=1e-9)  # the regions tile every face
    # Two real regions on the 16 faces the bisector x + y = 1 cuts (both halves of the
    # 8 cells along it); one elsewhere.
    assert np.count_nonzero(big == 2) == 16 and np.all(big >= 1)
    # Some faces only, and with a finer grid: the same regions there.
    some = solver.regions(sources, faces=[3, 7], subdivisions=32)
    assert {r.face for r in some} == {3, 7}
    with pytest.raises(geotracks.GeotracksError, match="face"):
        solver.regions(0, faces=[len(F)])
    with pytest.raises(geotracks.GeotracksError, match="face"):
        solver.regions(0, faces=[-1])
    with pytest.raises(geotracks.GeotracksError, match="subdivisions"):
        solver.regions(0, faces=[0], subdivisions=0)


def test_distance_and_gradient_at_surface_points():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    # The centroid of face 10, a point on edge 3, and a vertex.
    points = ["f:10:0.2,0.3,0.5", "e:3:0.25", 40]
    d, g, t = solver.gradient(0, points)
    xyz = np.array([
        0.2 * V[F[10][0]] + 0.3 * V[F[10][1]] + 0.5 * V[F[10][2]],
        [np.nan] * 3,
        V[40],
    ])
    for i in (0, 2):
        r = np.linalg.norm(xyz[i])
        assert abs(d[i] - r) < 1e-9
        assert np.allclose(g[i], xyz[i] / r, atol=1e-9)  # away from the source, unit
        assert np.allclose(t[i], xyz[i] / r, atol=1e-9)
    assert np.isfinite(d[1]) and abs(np.linalg.norm(g[1]) - 1.0) < 1e-9
    # At the source: distance 0, no gradient.
    d, g, t = solver.gradient(0, [0])
    assert d[0] == 0.0 and np.isnan(g[0]).all() and np.isnan(t[0]).all()
    with pytest.raises(geotracks.GeotracksError):
        solver.gradient(0, ["f:999:0.2,0.3,0.5"])


def test_python_refuses_what_the_command_line_refuses():
    V, F = grid(2)
    solver = geotracks.MeshSolver(V, F)
    # A negative maximum distance: refused by the library's own check (it used to
    # return inf everywhere, the source included), naming the argument.
    for bad in (-1, -1e-300, float("nan")):
        with pytest.raises(geotracks.GeotracksError, match="max_distance.*must be a number >= 0"):
            solver.distance(0, max_distance=bad)
        with pytest.raises(geotracks.GeotracksError, match="max_distance"):
            solver.local_distance_rows([0], bad)
    assert solver.distance(0, max_distance=0)[0] == 0.0
    assert solver.distance(0, max_distance=np.float32(0.5))[0] == 0.0
    # Numbers given as text are refused with a TypeError naming the argument.
    with pytest.raises(TypeError, match="max_distance"):
        solver.distance(0, max_distance="0.6")
    with pytest.raises(TypeError, match="max_distance"):
        solver.local_distance_matrix("0.6")
    with pytest.raises(TypeError, match="k must be a real number"):
        geotracks.MeshSolver(V, F, k="2")
    with pytest.raises(TypeError, match="k must be a real number"):
        geotracks.MeshSolver(V, F, k=True)
    with pytest.raises(TypeError, match="levels"):
        solver.isolines(0, ["0.5"])
    with pytest.raises(TypeError, match="subdivisions"):
        solver.isolines(0, [0.5], subdivisions="4")
    # k out of range: the library's error, as on the command line.
    for bad in (0, -2, float("nan"), float("inf")):
        with pytest.raises(geotracks.GeotracksError, match="k ="):
            geotracks.MeshSolver(V, F, k=bad)


def test_knobs_that_scale_work_are_bounded_before_any_work():
    V, F = grid(2)
    # A k whose estimated work breaks the limit is refused at once, naming the
    # estimate, the limit and the largest k that fits; the limit can be lifted.
    with pytest.raises(geotracks.GeotracksError, match="distance tests.*work limit.*largest k"):
        geotracks.MeshSolver(V, F, k=50000)
    with pytest.raises(geotracks.GeotracksError, match="work limit of 1.00e3"):
        geotracks.MeshSolver(V, F, k=20, work_limit=1000)
    assert geotracks.MeshSolver(V, F, k=50, work_limit=None).method == "wave"
    assert geotracks.DEFAULT_WORK_LIMIT == 4_000_000_000
    with pytest.raises(TypeError, match="work_limit"):
        geotracks.MeshSolver(V, F, work_limit="1e9")
    solver = geotracks.MeshSolver(V, F)
    # More levels than one call draws: refused before the field is computed.
    with pytest.raises(geotracks.GeotracksError, match="levels.*1000"):
        solver.isolines(0, np.linspace(0.1, 1.0, 1001))
    assert len(solver.isolines(0, np.linspace(0.1, 1.0, 1000))) > 0
    assert solver.isolines(0, []) == []
    # A distance matrix that cannot fit in memory (here 10⁷ rows of 3,721 values,
    # 298 GB) is refused before any row runs.
    V, F = grid(60)
    solver = geotracks.MeshSolver(V, F)
    with pytest.raises(geotracks.GeotracksError, match="distance matrix of 10000000 rows"):
        solver.distance_matrix(np.zeros(10_000_000, dtype=np.int64))
    # The rows and the array they are copied into are counted (16 bytes a value): on a
    # machine with 24 GB free, 10⁶ rows of Spot's 2,930 values (23.4 GB at 8 bytes a
    # value, 46.9 GB counted) are refused, not computed for hours.
    V, F = geotracks.read_mesh(DATA / "spot.obj")
    solver = geotracks.MeshSolver(V, F)
    with pytest.raises(geotracks.GeotracksError, match="distance matrix of 1000000 rows"):
        solver.distance_matrix(np.zeros(1_000_000, dtype=np.int64))


def test_medial_axis_and_skeleton_of_a_surface():
    axis = geotracks.medial_axis(DATA / "spot.obj")
    n = len(axis.positions)
    assert axis.positions.shape == (n, 3) and axis.radii.shape == (n,)
    assert axis.faces.shape[1] == 3 and axis.faces.max() < n
    assert np.all(axis.radii > 0)
    # Spot has no handle: its skeleton is one tree.
    sk = geotracks.skeleton(DATA / "spot.obj")
    assert sk.b1 == 0
    assert len(sk.edges) == len(sk.points) - 1
    # From a mesh, too, the points are centred by default.
    centred = geotracks.skeleton(DATA / "spot.obj", centred=True)
    on_axis = geotracks.skeleton(DATA / "spot.obj", centred=False)
    assert np.array_equal(sk.points, centred.points)
    assert not np.array_equal(sk.points, on_axis.points)
    # A stricter span keeps less of the axis.
    strict = geotracks.medial_axis(DATA / "spot.obj", span=3.0)
    assert len(strict.faces) < len(axis.faces)
    with pytest.raises(geotracks.GeotracksError, match="angle"):
        geotracks.medial_axis(DATA / "spot.obj", angle=200)
    with pytest.raises(geotracks.GeotracksError, match="spacing"):
        geotracks.medial_axis(DATA / "spot.obj", spacing=0)


def test_medial_axis_of_an_open_surface_is_refused(tmp_path):
    path = tmp_path / "open.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n")
    with pytest.raises(geotracks.GeotracksError, match="not closed"):
        geotracks.medial_axis(path)
