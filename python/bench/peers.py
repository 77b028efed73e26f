"""geotracks against potpourri3d and tvb-gdist from Python, the same jobs on one shared
mesh, timed and measured against the exact reference (the README's table
and the guide's Accuracy page):

    python python/bench/peers.py ../shared/data MESH [RADIUS_PERCENT] [SOURCES]

Needs `pip install potpourri3d tvb-gdist` beside geotracks. Jobs:
1. the distance from vertex 0 to every vertex (geotracks; potpourri3d's heat method,
   one call and with its solver built first; tvb-gdist's exact MMP);
2. the shortest path from vertex 0 to the vertex farthest from it (geotracks' straightened
   path; potpourri3d's edge-flip geodesic; tvb-gdist gives the exact length only);
3. SOURCES rows of the dense matrix (geotracks on all cores; the others one source at
   a time, as their APIs go);
4. every pair within RADIUS_PERCENT of the bounding-box diagonal (geotracks'
   `local_distance_matrix`; tvb-gdist's `local_gdist_matrix`, exact).
Errors are relative to `reference/MESH.src0.f64` (jobs 1–2) or to tvb-gdist's exact
values (jobs 3–4), in %.
"""

import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import geotracks


def timed(f):
    t = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t


def errors(values, exact):
    ok = exact > 0
    rel = np.abs(values[ok] - exact[ok]) / exact[ok]
    return 100 * rel.mean(), 100 * rel.max()


def main():
    data, name = Path(sys.argv[1]), sys.argv[2]
    radius_percent = float(sys.argv[3]) if len(sys.argv) > 3 else 2.0
    count = int(sys.argv[4]) if len(sys.argv) > 4 else 50
    import gdist
    import potpourri3d as pp3d

    mesh = data / "meshes" / f"{name}.obj"
    V, F = geotracks.read_mesh(mesh)
    F32 = F.astype(np.int32)
    exact = np.fromfile(data / "reference" / f"{name}.src0.f64", dtype="<f8")
    diagonal = float(np.linalg.norm(V.max(0) - V.min(0)))
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    print(f"{name}: {len(V)} vertices, {len(F)} faces; {os.cpu_count()} cores ({platform.machine()}); geotracks at {commit}, "
          f"potpourri3d {pp3d.__version__ if hasattr(pp3d, '__version__') else '1.4.0'}, tvb-gdist 2.9.2\n")
    rows = []

    # 1. One field.
    (solver, setup) = timed(lambda: geotracks.MeshSolver(V, F))
    d, solve = timed(lambda: solver.distance(0))
    rows.append(("distance from vertex 0", "geotracks (wave, k = 2; solver setup included)", setup + solve, *errors(d, exact)))
    d, t = timed(lambda: pp3d.compute_distance(V, F, 0))
    rows.append(("distance from vertex 0", "potpourri3d heat method, one call", t, *errors(d, exact)))
    heat, setup = timed(lambda: pp3d.MeshHeatMethodDistanceSolver(V, F))
    d, solve = timed(lambda: heat.compute_distance(0))
    rows.append(("distance from vertex 0", f"potpourri3d heat method, solver built first ({setup:.2f} s)", solve, *errors(d, exact)))
    d, t = timed(lambda: gdist.compute_gdist(V, F32, source_indices=np.array([0], np.int32)))
    rows.append(("distance from vertex 0", "tvb-gdist (exact MMP)", t, *errors(d, exact)))

    # 2. One path, to the farthest vertex.
    target = int(np.argmax(exact))
    path, t = timed(lambda: solver.path(0, target))
    rel = abs(path.length - exact[target]) / exact[target] * 100
    rows.append((f"path 0 → {target}", "geotracks (solver reused)", t, rel, rel))
    flip, setup = timed(lambda: pp3d.EdgeFlipGeodesicSolver(V, F))
    points, solve = timed(lambda: flip.find_geodesic_path(0, target))
    length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    rel = abs(length - exact[target]) / exact[target] * 100
    rows.append((f"path 0 → {target}", f"potpourri3d edge flips (solver {setup:.2f} s)", solve, rel, rel))
    d, t = timed(lambda: gdist.compute_gdist(V, F32, np.array([0], np.int32), np.array([target], np.int32)))
    rel = abs(float(d[0]) - exact[target]) / exact[target] * 100
    rows.append((f"path 0 → {target}", "tvb-gdist (length only)", t, rel, rel))

    # 3. Dense rows.
    sources = np.linspace(0, len(V) - 1, count).astype(np.int64)
    truth, t_exact = timed(lambda: np.array([gdist.compute_gdist(V, F32, np.array([s], np.int32)) for s in sources]))
    ours, t = timed(lambda: solver.distance_matrix(sources))
    rows.append((f"{count} rows", "geotracks distance_matrix (all cores)", t, *errors(ours.ravel(), truth.ravel())))
    pp, t = timed(lambda: np.array([heat.compute_distance(int(s)) for s in sources]))
    rows.append((f"{count} rows", "potpourri3d heat, one source at a time", t, *errors(pp.ravel(), truth.ravel())))
    rows.append((f"{count} rows", "tvb-gdist, one source at a time", t_exact, 0.0, 0.0))

    # 4. Pairs within a radius.
    r = radius_percent / 100 * diagonal
    exact_local, t_exact = timed(lambda: gdist.local_gdist_matrix(V, F32, max_distance=r).tocsr())
    ours_local, t = timed(lambda: solver.local_distance_matrix(r))
    e = exact_local.tocoo()
    mine = ours_local.tocsr()
    found = np.asarray(mine[e.row, e.col]).ravel()
    off = (e.data > 0) & (found > 0)
    rel = np.abs(found[off] - e.data[off]) / e.data[off]
    label = f"pairs within {radius_percent:g} % of the diagonal"
    rows.append((label, f"geotracks local_distance_matrix (all cores; {mine.nnz} pairs)", t, 100 * rel.mean(), 100 * rel.max()))
    rows.append((label, f"tvb-gdist local_gdist_matrix ({exact_local.nnz} pairs)", t_exact, 0.0, 0.0))

    print("| job | tool | seconds | mean error % | max error % |")
    print("|---|---|---:|---:|---:|")
    for job, tool, seconds, mean, worst in rows:
        print(f"| {job} | {tool} | {seconds:.3f} | {mean:.3g} | {worst:.3g} |")


if __name__ == "__main__":
    main()
