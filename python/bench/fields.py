"""A field against the one-call methods, on one mesh (the README's Python section):

    python python/bench/fields.py ../shared/data/meshes/bunny.obj

For the wavefront and the track-pruned engines, from vertex 0: the time of one run
(`MeshSolver.field`), of each question asked of its field (distances, the path to the
farthest vertex, the gradient at 200 face points, two isolines), of the same four
questions as one-call methods (four runs) and asked of one field (one run), with the
runs `MeshSolver.runs` counted; then one path three ways: the one-call `path` (stopped
at the target; from both ends for the Steiner graph), a field stopped at the target,
and a full field. Best of three each.
"""

import sys
import time

import numpy as np

import geotracks


def best(work, times=3):
    """The least of `times` timings of `work()`, and its last result."""
    least = float("inf")
    for _ in range(times):
        start = time.perf_counter()
        result = work()
        least = min(least, time.perf_counter() - start)
    return least, result


def main(path):
    V, F = geotracks.read_mesh(path)
    print(f"{path}: {len(V)} vertices, {len(F)} faces")
    for method in ("wave", "tracks"):
        solver = geotracks.MeshSolver(V, F, method=method)
        d0 = solver.distance(0)
        target = int(np.argmax(np.where(np.isfinite(d0), d0, -1.0)))
        points = [f"f:{f}:0.2,0.3,0.5" for f in range(0, len(F), max(1, len(F) // 200))]
        levels = [0.25 * d0[target], 0.5 * d0[target]]
        field = solver.field(0)
        for name, work in [
            ("one run (field)", lambda: solver.field(0)),
            ("field.distance()", field.distance),
            ("field.path", lambda: field.path(target)),
            (f"field.gradient ({len(points)} points)", lambda: field.gradient(points)),
            ("field.isolines (2 levels)", lambda: field.isolines(levels)),
        ]:
            print(f"{method:6} {name:32} {best(work)[0]:.4f} s")

        def one_call():
            solver.distance(0)
            solver.path(0, target)
            solver.gradient(0, points)
            solver.isolines(0, levels)

        def one_field():
            asked = solver.field(0)
            asked.distance()
            asked.path(target)
            asked.gradient(points)
            asked.isolines(levels)

        for name, work in [("4 questions, one-call", one_call), ("4 questions, one field", one_field)]:
            runs = solver.runs
            seconds, _ = best(work)
            print(f"{method:6} {name:32} {seconds:.4f} s, {(solver.runs - runs) // 3} runs")
        for name, work in [
            ("path, one-call", lambda: solver.path(0, target)),
            ("path, field stopped at target", lambda: solver.field(0, targets=[target]).path(target)),
            ("path, full field", lambda: solver.field(0).path(target)),
        ]:
            seconds, found = best(work)
            print(f"{method:6} {name:32} {seconds:.4f} s, length {found.length:.12f}")


if __name__ == "__main__":
    main(sys.argv[1])
