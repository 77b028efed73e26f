"""Fields: one run from a set of sources, asked every question. A field answers as the
one-call methods do (same engine, same run), never runs the engine again, outlives its
solver, can be shared by threads, and refuses bad questions with the package's usual
errors."""

import gc
import threading
import weakref
from pathlib import Path

import numpy as np
import pytest

import geotracks

DATA = Path(__file__).resolve().parents[2] / "tests" / "data"


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


def same_loop(points, names, other_points, other_names):
    """The same closed polygon, whichever point it starts at."""
    assert sorted(names) == sorted(other_names)
    shift = names.index(other_names[0])
    assert names[shift:] + names[:shift] == other_names
    assert np.array_equal(np.roll(points, -shift, axis=0), other_points)


def same_regions(a, b):
    """The same regions. Where a region's polygon starts, and so the last bits of its
    area, varies from call to call, even on one field (the library walks its boundary
    from a point of a hash map): the rest is equal to the bit."""
    assert len(a) == len(b) and len(a) > 0
    for r, s in zip(a, b):
        assert (r.face, r.source, r.across, r.offset) == (s.face, s.source, s.across, s.offset)
        assert np.array_equal(r.virtual_source, s.virtual_source)
        same_loop(r.polygon, r.surface_points, s.polygon, s.surface_points)
        assert r.area == pytest.approx(s.area, rel=1e-12, abs=0.0)
        assert len(r.holes) == len(s.holes)


def same_isolines(a, b):
    assert len(a) == len(b) and len(a) > 0
    for x, y in zip(a, b):
        assert x.level == y.level and x.closed == y.closed
        assert np.array_equal(x.points, y.points)


@pytest.mark.parametrize("method", ["wave", "tracks", "exact"])
def test_a_field_answers_as_the_one_call_methods(method):
    V, F = geotracks.read_mesh(DATA / "spot.obj")
    solver = geotracks.MeshSolver(V, F, method=method)
    sources = [0, "f:12:0.2,0.3,0.5"]
    field = solver.field(sources)
    points = ["f:100:0.2,0.3,0.5", "e:7:0.25", 2000, 0]

    assert np.array_equal(field.distance(), solver.distance(sources))
    d, labels = solver.voronoi(sources)
    assert np.array_equal(field.distance(), d)
    assert field.voronoi().dtype == np.int64
    assert np.array_equal(field.voronoi(), labels)
    at = field.distance_at(points)
    assert at.dtype == np.float64 and at.shape == (4,)
    assert np.array_equal(at, field.gradient(points)[0])
    assert at[2] == field.distance()[2000] and at[3] == 0.0
    for mine, theirs in zip(field.gradient(points), solver.gradient(sources, points)):
        np.testing.assert_array_equal(mine, theirs)  # NaN where NaN
    levels = [0.1, 0.4]
    same_isolines(field.isolines(levels), solver.isolines(sources, levels))
    same_isolines(field.isolines(levels, subdivisions=2), solver.isolines(sources, levels, subdivisions=2))
    same_regions(field.regions(faces=[12, 100, 3000]), solver.regions(sources, faces=[12, 100, 3000]))
    # A path from the field's sources: the one-call path runs until the target is
    # final (and, for the Steiner graph from one source, from both ends), so its
    # length agrees to rounding; from the same field, every path is the same.
    path = field.path(1500)
    assert path.surface_points[-1] == "1500" and path.surface_points[0] in ("0", "f:12:0.2,0.3,0.5")
    assert np.allclose(path.points[-1], V[1500])
    one_call = solver.path(sources, 1500)
    assert abs(path.length - one_call.length) <= 1e-9 * one_call.length
    again = field.path(1500)
    assert again.surface_points == path.surface_points and np.array_equal(again.points, path.points)
    assert path.length <= field.distance()[1500] + 1e-12


def test_the_exact_engine_on_a_plane_is_the_straight_distance():
    # Exact geodesics on a flat grid: the straight distance at every vertex, paths as
    # long as the value, and its windows counted in the stats.
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F, method="exact")
    assert solver.method == "exact"
    field = solver.field([0, "f:10:0.2,0.3,0.5"])
    inside = point_of(V, F, 10, [0.2, 0.3, 0.5])
    straight = np.minimum(np.linalg.norm(V - V[0], axis=1), np.linalg.norm(V - inside, axis=1))
    np.testing.assert_allclose(field.distance(), straight, rtol=1e-12, atol=1e-12)
    path = field.path(40)
    assert abs(path.length - field.distance()[40]) <= 1e-12
    assert field.stats["windows_created"] > 0 and field.stats["method"] == "exact"
    with pytest.raises(geotracks.GeotracksError, match="exact engine cannot run"):
        geotracks.MeshSolver(V, F, method="exact", metric=geotracks.Density(np.full(len(V), 2.0)))


def point_of(V, F, face, bary):
    return sum(b * V[v] for b, v in zip(bary, F[face]))


def test_a_field_path_from_one_source_is_the_one_call_path():
    # The wavefront engine (the default) runs one-ended, stopped at the target: the
    # same run up to the target as a field's, so the same path to the bit.
    V, F = geotracks.read_mesh(DATA / "spot.obj")
    solver = geotracks.MeshSolver(V, F)
    field = solver.field(0)
    for target in (100, 1500, "f:40:0.3,0.3,0.4"):
        mine, theirs = field.path(target), solver.path(0, target)
        assert mine.surface_points == theirs.surface_points
        assert np.array_equal(mine.points, theirs.points) and mine.length == theirs.length


def test_a_field_does_not_run_the_engine_again():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    assert solver.runs == 0
    field = solver.field([0, 80])
    assert solver.runs == 1
    for _ in range(3):
        field.distance()
        field.distance_at([3, "f:10:0.2,0.3,0.5"])
        field.path(40)
        field.gradient(["e:3:0.25", 40])
        field.isolines([0.25, 0.5])
        field.regions(faces=[3, 7])
        field.voronoi()
        field.stats, field.sources
    assert solver.runs == 1
    # Each one-call method is one run; a matrix, one per row.
    solver.distance(0)
    solver.voronoi([0, 80])
    solver.path(0, 40)
    solver.gradient(0, [40])
    solver.isolines(0, [0.5])
    solver.regions(0, faces=[3])
    assert solver.runs == 7
    solver.distance_matrix([0, 1, 2])
    solver.local_distance_rows([0, 1], 0.3)
    assert solver.runs == 12
    with pytest.raises(AttributeError):
        solver.runs = 0
    # Refused before any run: a bad point, too many levels, a bad maximum distance.
    with pytest.raises(geotracks.GeotracksError):
        solver.gradient(0, ["f:0:2,3"])
    with pytest.raises(geotracks.GeotracksError):
        solver.isolines(0, np.linspace(0.1, 1.0, 1001))
    with pytest.raises(geotracks.GeotracksError):
        solver.field(0, max_distance=-1.0)
    assert solver.runs == 12


def test_a_field_outlives_its_solver():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F)
    field = solver.field(0)
    expected = solver.distance(0)
    gone = weakref.ref(solver)
    del solver
    gc.collect()
    assert gone() is None
    assert np.array_equal(field.distance(), expected)
    path = field.path(80)
    assert abs(path.length - 2**0.5) < 1e-12
    inside = 0.2 * V[F[10][0]] + 0.3 * V[F[10][1]] + 0.5 * V[F[10][2]]
    assert abs(field.distance_at(["f:10:0.2,0.3,0.5"])[0] - np.linalg.norm(inside)) < 1e-12
    assert len(field.isolines([0.5])) == 1
    assert field.vertex_count == len(V)


def test_threads_share_one_field():
    V, F = geotracks.read_mesh(DATA / "spot.obj")
    field = geotracks.MeshSolver(V, F).field(0)
    targets = [100, 500, 1000, 1500, 2000, 2500]
    points = [f"f:{f}:0.2,0.3,0.5" for f in range(0, 5000, 50)]
    expected = ([field.path(t).length for t in targets], field.distance_at(points), field.gradient(points)[1])
    results = [None] * 4

    def ask(i):
        results[i] = ([field.path(t).length for t in targets], field.distance_at(points), field.gradient(points)[1])

    threads = [threading.Thread(target=ask, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for lengths, at, gradients in results:
        assert lengths == expected[0]
        assert np.array_equal(at, expected[1])
        np.testing.assert_array_equal(gradients, expected[2])


def test_stats_and_sources():
    V, F = grid(8)
    solver = geotracks.MeshSolver(V, F, method="tracks", k=3)
    field = solver.field([0, "e:5:0.25"])
    stats = field.stats
    assert set(stats) == {
        "method", "k", "settles", "pushes", "distance_tests", "propagate_seconds", "stopped_early",
        "windows_created", "windows_kept",
    }
    assert stats["method"] == "tracks" and stats["k"] == 3.0
    assert stats["settles"] > 0 and stats["pushes"] >= stats["settles"] and stats["distance_tests"] > 0
    assert stats["propagate_seconds"] >= 0.0 and stats["stopped_early"] is False
    assert field.sources == ["0", "e:5:0.25"]
    # The sources as given back are sources again: the same run.
    assert np.array_equal(solver.field(field.sources).distance(), field.distance())
    assert "tracks" in repr(field)
    # With targets the run stops early: exact there, unreached farther.
    stopped = solver.field(0, targets=[10])
    assert stopped.stats["stopped_early"] is True
    assert stopped.distance()[10] == solver.field(0).distance()[10]
    assert np.isinf(stopped.distance()).any()
    near = solver.field(0, max_distance=0.5)
    r = np.hypot(V[:, 0], V[:, 1])
    assert np.all(np.isinf(near.distance()[r > 0.5 + 1e-9]))
    assert np.array_equal(near.distance(), solver.distance(0, max_distance=0.5))


def test_a_field_refuses_bad_questions():
    # Two squares apart: vertices 4–7 are another component.
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]] * 2, dtype=float)
    V[4:, 0] += 5.0
    F = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    solver = geotracks.MeshSolver(V, F)
    field = solver.field(0)
    with pytest.raises(geotracks.GeotracksError, match="face 99"):
        field.distance_at(["f:99:0.2,0.3,0.5"])
    with pytest.raises(geotracks.GeotracksError, match="vertex 99|99"):
        field.distance_at([99])
    with pytest.raises(geotracks.GeotracksError, match="not a surface point"):
        field.gradient(["f:0:2,3"])
    with pytest.raises(geotracks.GeotracksError, match="point 6 is not reached"):
        field.path(6)
    with pytest.raises(geotracks.GeotracksError, match="point 2 is not reached"):
        solver.field(0, max_distance=0.5).path(2)
    with pytest.raises(geotracks.GeotracksError, match="isoline level 1 is NaN"):
        field.isolines([0.5, float("nan")])
    with pytest.raises(geotracks.GeotracksError, match="levels.*1000"):
        field.isolines(np.linspace(0.1, 1.0, 1001))
    with pytest.raises(geotracks.GeotracksError, match="face"):
        field.regions(faces=[len(F)])
    with pytest.raises(geotracks.GeotracksError, match="subdivisions"):
        field.regions(faces=[0], subdivisions=0)
    with pytest.raises(TypeError, match="levels"):
        field.isolines(["0.5"])
    with pytest.raises(TypeError, match="points"):
        field.distance_at([1.5])
    with pytest.raises(geotracks.GeotracksError, match="no point"):
        field.distance_at([])
    # The run itself: a bad source, a bad stop.
    with pytest.raises(geotracks.GeotracksError, match="source vertex 99"):
        solver.field(99)
    with pytest.raises(geotracks.GeotracksError, match="max_distance.*must be a number >= 0"):
        solver.field(0, max_distance=float("nan"))
    with pytest.raises(TypeError, match="max_distance"):
        solver.field(0, max_distance="0.5")
    with pytest.raises(geotracks.GeotracksError, match="target"):
        solver.field(0, targets=["f:99:0.2,0.3,0.5"])
    # An unreached point has no distance: inf, as at a vertex.
    assert np.isinf(field.distance_at([6, "f:2:0.2,0.3,0.5"])).all()
    assert list(field.voronoi()) == [0, 0, 0, 0, -1, -1, -1, -1]
