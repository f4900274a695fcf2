"""The Dask recipe on a LocalCluster of two worker processes equals the single-process CLI batch."""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy
import pytest

from conftest import SEQUENCES, run_cli, sample_path

distributed = pytest.importorskip("dask.distributed")
from aief import dask_batch  # noqa: E402  (after the skip: it needs dask only when run)
import aief  # noqa: E402


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
        outputs, totals, failures = dask_batch.run(client, images, tmp_path / "shards", shards=4)
        assert totals[:2] == (6, 0) and failures == []
        _, again, _ = dask_batch.run(client, images, tmp_path / "shards", shards=4)  # resumes: nothing left to do
        assert again == (0, 6, 0)
        # Other options: every group is redone (its recorded options differ), then kept.
        _, other, _ = dask_batch.run(client, images, tmp_path / "other", shards=2, n_features=300)
        _, redone, _ = dask_batch.run(client, images, tmp_path / "other", shards=2, n_features=500)
        _, kept, _ = dask_batch.run(client, images, tmp_path / "other", shards=2, n_features=500)
        assert (other[:2], redone[:2], kept[:2]) == ((6, 0), (6, 0), (0, 6))
    merged = tmp_path / "merged.h5"
    run_cli(cli, "merge", "-o", merged, *outputs)

    with h5py.File(single, "r") as s, h5py.File(merged, "r") as m:
        names = [name for _, name in dask_batch.list_images(images)]
        assert len(names) == 6 and all(name in s and name in m for name in names)
        for name in names:
            assert sorted(m[name]) == sorted(s[name])
            # The Dask recipe records the options as the CLI does.
            assert aief.option_changes(m[name].attrs["options"], aief.Extractor()) == []
            assert aief.option_changes(s[name].attrs["options"], aief.Extractor()) == []
            for dataset in s[name]:
                a, b = s[name][dataset][()], m[name][dataset][()]
                assert a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes(), f"{name}/{dataset}"


def group_names(file):
    """The image groups of an hloc features file: the groups holding a "descriptors" dataset."""
    names = []
    file.visititems(lambda name, item: names.append(name) if isinstance(item, h5py.Group) and "descriptors" in item else None)
    return sorted(names)


def test_takes_the_clis_images_symlinked_folders_and_broken_links_included(cli, tmp_path):
    images, elsewhere = tmp_path / "images", tmp_path / "elsewhere"
    images.mkdir()
    (elsewhere / "deeper").mkdir(parents=True)
    shutil.copy(sample_path("graf", 1), images / "graf1.png")
    shutil.copy(sample_path("boat", 1), elsewhere / "boat1.png")
    shutil.copy(sample_path("leuven", 1), elsewhere / "deeper" / "leuven1.png")
    os.symlink(elsewhere, images / "linked")                     # a symlinked folder: taken
    os.symlink(tmp_path / "missing.png", images / "gone.png")    # a broken link: reported
    os.symlink(images, images / "linked_back")                   # a cycle: not followed

    single = tmp_path / "single.h5"
    cli_run = subprocess.run([cli, "extract", "--batch", str(images), "-o", str(single), "--format", "h5", "--threads", "1"],
                             capture_output=True, text=True)
    assert cli_run.returncode == 1 and "failed: " + str(images / "gone.png") in cli_run.stdout, cli_run.stdout

    assert [name for _, name in dask_batch.list_images(images)] == [
        "gone.png", "graf1.png", "linked/boat1.png", "linked/deeper/leuven1.png"]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  local_directory=tmp_path / "dask") as cluster, distributed.Client(cluster) as client:
        outputs, totals, failures = dask_batch.run(client, images, tmp_path / "shards", shards=2)
    assert totals[:2] == (3, 0)
    assert [failure.split(": ")[0] for failure in failures] == [os.path.abspath(images / "gone.png")]
    merged = tmp_path / "merged.h5"
    run_cli(cli, "merge", "-o", merged, *outputs)
    with h5py.File(single, "r") as s, h5py.File(merged, "r") as m:
        assert group_names(m) == group_names(s) == ["graf1.png", "linked/boat1.png", "linked/deeper/leuven1.png"]


@pytest.fixture
def small_disk(tmp_path):
    """A 4 MB tmpfs mounted on a folder of the test's own (mounting needs root; CI runs as root)."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root (CI runs these as root)")
    disk = tmp_path / "disk"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=4m", "tmpfs", str(disk)], capture_output=True, text=True)
    if mounted.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {mounted.stderr.strip()}")
    yield disk
    subprocess.run(["umount", str(disk)], check=True)


def test_a_full_disk_stops_the_shard_clearly_and_keeps_what_was_complete(small_disk, tmp_path):
    images = tmp_path / "images"
    images.mkdir()
    for copy in range(4):
        for sequence in SEQUENCES:
            shutil.copy(sample_path(sequence, 1), images / f"{sequence}{copy}.png")
    inputs = dask_batch.list_images(images)
    shard = str(small_disk / "features.0-of-1.h5")
    first = dask_batch.extract_shard(inputs[:3], shard, {})
    assert first[:2] == (3, 0)
    # Fill the disk but for a little room: the next images cannot all be written.
    free = shutil.disk_usage(small_disk).free
    with open(small_disk / "filler", "wb") as filler:
        filler.write(b"\0" * (free - 100_000))
    with pytest.raises(aief.Error, match="No space left on device.*run the same shard again to resume"):
        dask_batch.extract_shard(inputs, shard, {})
    with h5py.File(shard, "r") as file:  # was: unreadable ("addr overflow")
        kept = group_names(file)
        assert set(name for _, name in inputs[:3]) <= set(kept)
        for name in kept:
            assert file[name]["descriptors"].shape[0] == 32 and file[name]["image_size"].shape == (2,)
    os.remove(small_disk / "filler")
    extracted, skipped, _, failures = dask_batch.extract_shard(inputs, shard, {})
    assert failures == [] and skipped == len(kept) and extracted + skipped == len(inputs)


def test_a_full_disk_without_fallocate_counts_only_the_images_on_disk(small_disk, tmp_path):
    """On a file system without fallocate (NFSv3, FUSE) the writes since the last flush are lost
    when the disk fills at a flush: the message counts the new images the file holds, not those
    written (before: "stopped after 11 new images" for a file holding 1)."""
    shim = os.environ.get("AIEF_NO_FALLOCATE_SHIM", "")
    if not os.path.exists(shim):
        pytest.skip("the no-fallocate shim (tests/no_fallocate_shim.cpp) is not built")
    probe = subprocess.run(["fallocate", "-l", "1M", str(small_disk / "probe")], env=dict(os.environ, LD_PRELOAD=shim),
                           capture_output=True)
    assert probe.returncode != 0, "the shim does not take fallocate away"
    images = tmp_path / "images"
    images.mkdir()
    for copy in range(4):
        for sequence in SEQUENCES:
            shutil.copy(sample_path(sequence, 1), images / f"{sequence}{copy}.png")
    shard = small_disk / "features.0-of-1.h5"
    free = shutil.disk_usage(small_disk).free
    with open(small_disk / "filler", "wb") as filler:
        filler.write(b"\0" * (free - 300_000))
    script = ("import sys\nfrom aief import dask_batch\n"
              "inputs = dask_batch.list_images(sys.argv[1])\n"
              "dask_batch.extract_shard(inputs, sys.argv[2], {})\n")
    run = subprocess.run([sys.executable, "-c", script, str(images), str(shard)], env=dict(os.environ, LD_PRELOAD=shim),
                         capture_output=True, text=True)
    assert run.returncode != 0, run.stderr
    said = re.search(r"stopped with (\d+) new images on disk: .*No space left on device", run.stderr)
    assert said, run.stderr
    with h5py.File(shard, "r") as file:
        assert len(group_names(file)) == int(said.group(1)), run.stderr


@pytest.mark.parametrize("shards", [0, -1])
def test_no_shards_is_refused(tmp_path, shards):
    """Before: `--shards 0` exited 0 having done nothing."""
    run = subprocess.run([sys.executable, "-m", "aief.dask_batch", str(tmp_path), str(tmp_path / "out"),
                          "--shards", str(shards), "--local-workers", "1"], capture_output=True, text=True)
    assert run.returncode == 2 and "--shards expects an integer >= 1" in run.stderr, run.stderr
    with pytest.raises(aief.Error, match="shards expects an integer >= 1"):
        dask_batch.run(None, tmp_path, tmp_path / "out", shards)


def test_a_carried_threshold_is_refused():
    """Shards of one video each carried their own F: merged, they differed from one process."""
    with pytest.raises(aief.Error, match="carries F from frame to frame"):
        dask_batch.run(None, "images", "out", 2, threshold="carried")
    # The keyword of today (entropy_threshold) was let through, and the message named the CLI's
    # earlier flag (--threshold).
    with pytest.raises(aief.Error, match="entropy_threshold='carried'.*--entropy-threshold carried"):
        dask_batch.run(None, "images", "out", 2, entropy_threshold="carried")
