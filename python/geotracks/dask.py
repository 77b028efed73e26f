"""Many-source distance work spread over a Dask cluster.

The sources are cut into chunks, one task each. A worker builds the solver of a mesh
once (it keeps the last few in its process) and reuses it for every chunk it runs;
inside a task the chunk's rows run on all the worker's cores, with the GIL released.
The results are lazy Dask collections, so they go from the workers straight to storage
(``.to_zarr`` for dense matrices, ``.to_parquet`` for sparse triples) without passing
through the client.

>>> import geotracks.dask as gd                                      # doctest: +SKIP
>>> from dask.distributed import Client                              # doctest: +SKIP
>>> client = Client("tcp://scheduler:8786")                          # doctest: +SKIP
>>> rows = gd.distance_matrix("bunny.ply", sources=range(20000))    # doctest: +SKIP
>>> rows.to_zarr("bunny_rows.zarr")                                  # doctest: +SKIP
>>> pairs = gd.local_distance_matrix("bunny.ply", max_distance=0.01) # doctest: +SKIP
>>> pairs.to_parquet("bunny_pairs/")                                 # doctest: +SKIP

The mesh is a file path (each worker reads it: nothing large in the task graph) or a
``(V, F)`` pair (sent once per worker as one graph node). Any scheduler works; the
tests run a ``dask.distributed.LocalCluster`` of two worker processes and check the
results equal a single :class:`geotracks.MeshSolver`'s, exactly.

Needs ``dask[array,dataframe]`` (and ``distributed`` for a cluster, ``zarr`` and
``pyarrow`` to store): ``pip install "./python[dask]"``.
"""

from __future__ import annotations

import os
from collections import OrderedDict
from typing import Callable, Optional

import numpy as np

from . import MeshSolver, _array, read_mesh

__all__ = ["distance_matrix", "local_distance_matrix", "map_meshes"]

#: Solvers kept per worker process, least recently used dropped first.
SOLVERS_KEPT = 4
_solvers: "OrderedDict[str, MeshSolver]" = OrderedDict()
#: Solvers this process has built (for the tests: tasks reuse them).
builds = 0


def _solver(key: str, mesh, options: dict) -> MeshSolver:
    """This process's solver for `key`, built on first use."""
    global builds
    solver = _solvers.get(key)
    if solver is None:
        builds += 1
        V, F = read_mesh(mesh) if isinstance(mesh, (str, os.PathLike)) else mesh
        solver = MeshSolver(V, F, **options)
        _solvers[key] = solver
        while len(_solvers) > SOLVERS_KEPT:
            _solvers.popitem(last=False)
    else:
        _solvers.move_to_end(key)
    return solver


def _mesh_node(mesh, options: dict):
    """The mesh as the tasks see it, the key its solvers are kept under, and its vertex
    count (for a path, the client reads the file once to know the matrices' width)."""
    import dask
    from dask.base import tokenize

    if isinstance(mesh, (str, os.PathLike)):
        path = os.path.abspath(os.fspath(mesh))
        stat = os.stat(path)
        key = tokenize(path, stat.st_size, stat.st_mtime_ns, options)
        return path, key, len(read_mesh(path)[0])
    V, F = mesh
    V, F = np.asarray(V), np.asarray(F)
    key = tokenize(V, F, options)
    return dask.delayed((V, F), pure=True, name=f"geotracks-mesh-{key}"), key, len(V)


def _options(k, method, metric) -> dict:
    return {"k": k, "method": method, "metric": metric}


def _chunks(sources, chunk: int):
    sources = _array(np.atleast_1d(np.asarray(list(sources))), "sources", ("n",), integer=True)
    if chunk < 1:
        raise ValueError(f"chunk must be at least 1; got {chunk}")
    return [sources[i : i + chunk] for i in range(0, len(sources), chunk)]


def _rows(key, mesh, options, sources, targets):
    return _solver(key, mesh, options).distance_matrix(sources, targets)


def _triples(key, mesh, options, sources, max_distance):
    import pandas as pd

    rows, cols, data = _solver(key, mesh, options).local_distance_rows(sources, max_distance)
    return pd.DataFrame({"source": rows, "target": cols, "distance": data})


def distance_matrix(
    mesh,
    sources,
    targets=None,
    *,
    chunk: int = 256,
    k: Optional[float] = None,
    method: str = "wave",
    metric=None,
):
    """The distances from each source vertex (rows) to every vertex, or to
    ``targets``, as a lazy ``dask.array`` of shape ``(len(sources), n or
    len(targets))``, ``chunk`` rows per block (one task each). ``k``, ``method`` and
    ``metric`` as for :class:`geotracks.MeshSolver`.

    Store it from the workers with ``.to_zarr(path)``, or bring it home with
    ``.compute()``.
    """
    import dask
    import dask.array as da

    options = _options(k, method, metric)
    node, key, n = _mesh_node(mesh, options)
    if targets is None:
        width = n
        targets_array = None
    else:
        targets_array = np.asarray(targets, dtype=np.int64)
        width = len(targets_array)
    blocks = [
        da.from_delayed(
            dask.delayed(_rows, pure=True)(key, node, options, chunk_sources, targets_array),
            shape=(len(chunk_sources), width),
            dtype=np.float64,
        )
        for chunk_sources in _chunks(sources, chunk)
    ]
    if not blocks:
        raise ValueError("no sources")
    return da.concatenate(blocks, axis=0)


def local_distance_matrix(
    mesh,
    max_distance: float,
    sources=None,
    *,
    chunk: int = 1024,
    k: Optional[float] = None,
    method: str = "wave",
    metric=None,
):
    """Every (source, vertex) pair within ``max_distance``, for every vertex as a
    source (or ``sources``), as a lazy ``dask.dataframe`` with columns ``source``,
    ``target`` and ``distance``: one partition per ``chunk`` sources. Store it from
    the workers with ``.to_parquet(path)``; the triples of
    :meth:`geotracks.MeshSolver.local_distance_matrix`.
    """
    import dask
    import dask.dataframe as dd
    import pandas as pd

    options = _options(k, method, metric)
    node, key, n = _mesh_node(mesh, options)
    if sources is None:
        sources = np.arange(n, dtype=np.int64)
    meta = pd.DataFrame(
        {
            "source": pd.Series([], dtype=np.int64),
            "target": pd.Series([], dtype=np.int64),
            "distance": pd.Series([], dtype=np.float64),
        }
    )
    parts = [
        dask.delayed(_triples, pure=True)(key, node, options, chunk_sources, float(max_distance))
        for chunk_sources in _chunks(sources, chunk)
    ]
    if not parts:
        raise ValueError("no sources")
    return dd.from_delayed(parts, meta=meta, verify_meta=False)


def map_meshes(function: Callable[[MeshSolver], object], paths, *, k=None, method="wave", metric=None):
    """``function(solver)`` for the solver of each mesh file in ``paths`` (one task per
    mesh), as a lazy ``dask.bag``: per-mesh jobs over a dataset, such as a distance
    field per shape (``map_meshes(lambda s: s.distance(0), paths)``). Each task reads
    its mesh and builds its solver on the worker."""
    import dask.bag as db

    options = _options(k, method, metric)

    def run(path):
        return function(MeshSolver(*read_mesh(path), **options))

    paths = [os.fspath(p) for p in paths]
    return db.from_sequence(paths, npartitions=max(1, len(paths))).map(run)
