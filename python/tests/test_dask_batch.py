"""The Dask recipe on a LocalCluster of two worker processes equals the single-process CLI batch."""
import shutil

import h5py
import numpy
import pytest

from conftest import SEQUENCES, run_cli, sample_path

distributed = pytest.importorskip("dask.distributed")
from aief import dask_batch  # noqa: E402  (after the skip: it needs dask only when run)


def test_two_worker_processes_give_the_single_process_bytes(cli, tmp_path):
    images = tmp_path / "images"
    (images / "sub").mkdir(parents=True)
    for sequence in SEQUENCES:
        shutil.copy(sample_path(sequence, 1), images / f"{sequence}1.png")
        shutil.copy(sample_path(sequence, 2), images / "sub" / f"{sequence}2.png")
    single = tmp_path / "single.h5"
    run_cli(cli, "extract", "--batch", images, "-o", single, "--format", "h5", "--threads", 1)

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  local_directory=tmp_path / "dask") as cluster, distributed.Client(cluster) as client:
        outputs, totals = dask_batch.run(client, images, tmp_path / "shards", shards=4)
        assert totals[:2] == (6, 0)
        _, again = dask_batch.run(client, images, tmp_path / "shards", shards=4)  # resumes: nothing left to do
        assert again == (0, 6, 0)
    merged = tmp_path / "merged.h5"
    run_cli(cli, "merge", "-o", merged, *outputs)

    with h5py.File(single, "r") as s, h5py.File(merged, "r") as m:
        names = dask_batch.list_images(images)
        assert len(names) == 6 and all(name in s and name in m for name in names)
        for name in names:
            assert sorted(m[name]) == sorted(s[name])
            for dataset in s[name]:
                a, b = s[name][dataset][()], m[name][dataset][()]
                assert a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes(), f"{name}/{dataset}"
