"""geotracks.dask on a LocalCluster of two worker processes: the same numbers as one
MeshSolver, exactly, through Zarr and Parquet."""

from pathlib import Path

import numpy as np
import pytest

import geotracks

dask = pytest.importorskip("dask")
distributed = pytest.importorskip("dask.distributed")
import geotracks.dask as gd  # noqa: E402

SPOT = Path(__file__).resolve().parents[2] / "tests" / "data" / "spot.obj"


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    with distributed.Client(cluster) as client:
        yield client
    cluster.close()


@pytest.fixture(scope="module")
def solver():
    return geotracks.MeshSolver(*geotracks.read_mesh(SPOT))


def test_dense_rows_equal_one_solver_and_go_to_zarr(client, solver, tmp_path):
    sources = np.arange(0, 2930, 97)
    lazy = gd.distance_matrix(SPOT, sources, chunk=7)
    assert lazy.shape == (len(sources), 2930) and lazy.numblocks[0] == 5
    expected = solver.distance_matrix(sources)
    assert np.array_equal(lazy.compute(), expected)
    # Streamed from the workers to Zarr, read back.
    zarr = pytest.importorskip("zarr")
    lazy.to_zarr(str(tmp_path / "rows.zarr"))
    assert np.array_equal(zarr.open(str(tmp_path / "rows.zarr"), mode="r")[:], expected)
    # Arrays instead of a path, and targets.
    V, F = geotracks.read_mesh(SPOT)
    picked = gd.distance_matrix((V, F), sources, targets=[0, 5, 2929], chunk=10).compute()
    assert np.array_equal(picked, expected[:, [0, 5, 2929]])
    # 8 tasks on 2 workers, 2 meshes (the path and the arrays): each worker built each
    # solver at most once and reused it for its other chunks.
    builds = client.run(lambda: __import__("geotracks.dask").dask.builds)
    assert 2 <= sum(builds.values()) <= 4, builds


def test_sparse_triples_equal_one_solver_and_go_to_parquet(client, solver, tmp_path):
    pytest.importorskip("pyarrow")
    frame = gd.local_distance_matrix(SPOT, 0.08, chunk=500)
    assert frame.npartitions == 6
    frame.to_parquet(str(tmp_path / "pairs"))
    import pandas as pd

    back = pd.read_parquet(str(tmp_path / "pairs"))
    expected = solver.local_distance_matrix(0.08).tocoo()
    got = sorted(zip(back["source"], back["target"], back["distance"]))
    want = sorted(zip(expected.row.tolist(), expected.col.tolist(), expected.data.tolist()))
    assert got == want


def test_per_mesh_jobs(client, solver):
    fields = gd.map_meshes(lambda s: s.distance(0), [SPOT, SPOT]).compute()
    assert len(fields) == 2
    for field in fields:
        assert np.array_equal(field, solver.distance(0))


def test_bad_arguments():
    with pytest.raises(TypeError):
        gd.distance_matrix(SPOT, ["a"])
    with pytest.raises(ValueError):
        gd.distance_matrix(SPOT, [0], chunk=0)
