"""One machine against a Dask LocalCluster on a many-source distance matrix (the
guide's Performance page, Dask): python python/bench/dask_scaling.py MESH [SOURCES] [CHUNK]."""

import os
import platform
import subprocess
import sys
import time

import numpy as np

import geotracks
import geotracks.dask as gd
from dask.distributed import Client, LocalCluster, get_task_stream


def main():
    mesh = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 200
    chunk = int(sys.argv[3]) if len(sys.argv) > 3 else 25
    V, F = geotracks.read_mesh(mesh)
    sources = np.linspace(0, len(V) - 1, count).astype(np.int64)
    t = time.perf_counter()
    solver = geotracks.MeshSolver(V, F)
    single = solver.distance_matrix(sources)
    one = time.perf_counter() - t
    print(f"mesh {mesh}: {len(V)} vertices, {len(F)} faces; {count} sources, chunks of {chunk}")
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; "
          f"commit {subprocess.run(['git', 'rev-parse', '--short', 'HEAD'], capture_output=True, text=True).stdout.strip()}")
    print()
    print("| run | workers × threads | seconds (with solver setup) | tasks per worker | equal to one solver |")
    print("|---|---|---:|---|---|")
    print(f"| one MeshSolver, rows on all cores | 1 process | {one:.2f} | – | – |")
    for workers in (1, 2):
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        with Client(cluster) as client:
            client.run(lambda: __import__("geotracks.dask"))
            with get_task_stream(client) as stream:
                t = time.perf_counter()
                rows = gd.distance_matrix(mesh, sources, chunk=chunk).compute()
                seconds = time.perf_counter() - t
            tasks = {}
            for event in stream.data:
                # The row tasks (dask may fuse them with the block they fill).
                key = event["key"][0] if isinstance(event["key"], tuple) else event["key"]
                if "rows" in str(key):
                    tasks[event["worker"]] = tasks.get(event["worker"], 0) + 1
            split = " / ".join(str(n) for n in sorted(tasks.values())) or "?"
            same = bool(np.array_equal(rows, single))
            print(f"| LocalCluster | {workers} × 1 | {seconds:.2f} | {split} | {same} |")
        cluster.close()


if __name__ == "__main__":
    main()
