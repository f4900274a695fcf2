"""Batch extraction over a Dask cluster: one task per shard, each writing its own HDF5 feature
file in hloc's layout (the layout of `aief extract --batch --format h5`, io/hdf5_file.hpp).

The images and their group names are the CLI's (aief.batch_inputs). Shard i of n takes images
i, i+n, i+2n ... of the sorted list, as `aief extract --shard i/n` does, so `aief merge -o features.h5 OUTDIR/features.*-of-n.h5` gives the single-process file's
groups, byte for byte in every dataset. A shard file resumes: a complete group whose `source`
(the image file's size and modification time) is the file as it is now is skipped. An image that
cannot be read (a broken link, a damaged file) is reported with its reason, as the CLI reports it.
Shards are written by the engine's own writer (aief.FeaturesFile): a full disk stops the task
with aief.Error and keeps every group complete before it readable (h5py left a file nobody could
open).

    python3 -m aief.dask_batch IMAGES OUTDIR --shards 8 --scheduler tcp://host:8786
    python3 -m aief.dask_batch IMAGES OUTDIR --shards 4 --local-workers 2   # a LocalCluster here

Each worker process runs one extraction per thread (the engine itself single-threaded, as the
CLI batch runs it): give workers threads_per_worker = cores for a machine's worth of images.
"""
import argparse
import os

import aief


def list_images(images):
    """(path, name) of every image `aief extract --batch IMAGES` takes from the folder or list
    file `images`, sorted by name: the engine's own rule (aief.batch_inputs), so the groups are
    the CLI's, symlinked folders and broken links included. Paths are made absolute here (a
    worker may run in another folder); names stay as the CLI gives them."""
    return [(os.path.abspath(path), name) for path, name in aief.batch_inputs(str(images))]


def shard_path(output_dir, index, count):
    """The file of shard `index` of `count` in `output_dir`: features.<index>-of-<count>.h5."""
    return os.path.join(output_dir, f"features.{index}-of-{count}.h5")


def source_of(path):
    """The image file's identity a resume compares: (size in bytes, modification time in ns), io/source_record.cpp."""
    info = os.stat(path)
    return info.st_size, info.st_mtime_ns


def extract_shard(inputs, output, options):
    """Runs on a worker: extracts the (path, name) `inputs` into the HDF5 file `output` through
    the engine's writer (aief.FeaturesFile, the writer of `aief extract --batch --format h5`).
    Returns (extracted, skipped, keypoints, failures), failures as "path: reason" lines. A write
    the file refuses (a full disk) raises aief.Error saying so: the groups complete before it stay
    readable, and the same call resumes once there is space."""
    extractor = aief.Extractor(**dict(options, threads=1))
    extracted = skipped = keypoints = 0
    failures = []
    file = aief.FeaturesFile(output)
    try:
        for path, name in inputs:
            try:
                source = source_of(path)
                if file.is_current(name, source, extractor):
                    skipped += 1
                    continue
                features = extractor.extract(aief.read_image(path))
            except (OSError, aief.Error) as error:
                failures.append(f"{path}: {error}")
                file.remove(name)  # an output of another or older file must not stay beside a failure
                continue
            try:
                file.write(name, features, source, extractor)
            except aief.Error as error:
                stopped(file, output, error)
            extracted += 1
            keypoints += len(features)
        try:
            file.close()  # the last writes reach the disk here, or fail
        except aief.Error as error:
            stopped(file, output, error)
    finally:
        try:
            file.close()
        except aief.Error:
            pass
    return extracted, skipped, keypoints, failures


def stopped(file, output, error):
    """Raises the error of a shard whose file refused a write, counting only the new images the
    file on disk holds (writes since its last flush are lost when the disk fills at a flush)."""
    try:
        file.close()
    except aief.Error:
        pass
    raise aief.Error(f"shard {output} stopped with {file.writes_on_disk} new images on disk: {error}; "
                     "run the same shard again to resume") from None


def run(client, images, output_dir, shards, **options):
    """Extracts every image of the folder or list file `images` on the cluster of `client` into
    `shards` files in `output_dir`; `options` are aief.Extractor's keyword arguments. Returns
    the shard files, the totals (extracted, skipped, keypoints) and the failures ("path: reason").
    Raises aief.Error for fewer than one shard, and for entropy_threshold='carried' (a video's
    frames carry F from one to the next: one extractor in frame order, `aief extract --batch VIDEO
    --entropy-threshold carried`, not independent shards)."""
    check_shards(shards, options)
    os.makedirs(output_dir, exist_ok=True)
    inputs = list_images(images)
    outputs = [shard_path(output_dir, i, shards) for i in range(shards)]
    futures = [client.submit(extract_shard, inputs[i::shards], outputs[i], options, pure=False) for i in range(shards)]
    results = client.gather(futures)
    totals = tuple(sum(result[k] for result in results) for k in range(3))
    failures = sorted(failure for result in results for failure in result[3])
    return outputs, totals, failures


def check_shards(shards, options):
    """Refuses a run that would do nothing or split what must not be split (see run)."""
    if not isinstance(shards, int) or shards < 1:
        raise aief.Error(f"shards expects an integer >= 1, got {shards!r}")
    keyword = next((k for k in ("entropy_threshold", "threshold") if options.get(k) == "carried"), None)
    if keyword:
        raise aief.Error(f"{keyword}='carried' carries F from frame to frame of one video, which "
                         "independent shards cannot: extract the video with one extractor in frame "
                         "order (aief extract --batch VIDEO --entropy-threshold carried)")


def main():
    """The command line of `python3 -m aief.dask_batch` (the module's docstring shows it)."""
    parser = argparse.ArgumentParser(description="aief batch extraction on a Dask cluster (hloc HDF5 shard files)")
    parser.add_argument("images", help="folder of images (recursively) or a text file of paths, as aief extract --batch")
    parser.add_argument("output_dir", help="folder for features.<i>-of-<n>.h5")
    parser.add_argument("--shards", type=int, default=8, help="number of shard files / tasks (default 8)")
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", help="address of a running dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--local-workers", type=int, help="start a LocalCluster of this many worker processes")
    parser.add_argument("--n-features", "--features", dest="n_features", type=int,  # --features: the earlier
                        default=aief.default_options()["n_features"], help="n_features")  # spelling

    args = parser.parse_args()
    if args.shards < 1:
        parser.error(f"--shards expects an integer >= 1, got {args.shards}")
    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.local_workers, threads_per_worker=1, processes=True))
    with client:
        outputs, (extracted, skipped, keypoints), failures = run(client, args.images, args.output_dir, args.shards,
                                                                 n_features=args.n_features)
    print(f"dask batch: {extracted} extracted, {skipped} already done, {len(failures)} failed; {keypoints} keypoints "
          f"in {len(outputs)} shard files")
    for failure in failures:
        print(f"  failed: {failure}")
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
