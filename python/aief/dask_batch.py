"""Batch extraction over a Dask cluster: one task per shard, each writing its own HDF5 feature
file in hloc's layout (the layout of `aief extract --batch --format h5`, io/hdf5_features.hpp).

Shard i of n takes images i, i+n, i+2n ... of the sorted list, as `aief extract --shard i/n`
does, so `aief merge -o features.h5 OUTDIR/features.*-of-n.h5` gives the single-process file's
groups, byte for byte in every dataset. A shard file resumes: a complete group whose `source`
(the image file's size and modification time) is the file as it is now is skipped.

    python3 -m aief.dask_batch IMAGES OUTDIR --shards 8 --scheduler tcp://host:8786
    python3 -m aief.dask_batch IMAGES OUTDIR --shards 4 --local-workers 2   # a LocalCluster here

Each worker process runs one extraction per thread (the engine itself single-threaded, as the
CLI batch runs it): give workers threads_per_worker = cores for a machine's worth of images.
"""
import argparse
import os
import pathlib

import numpy

import aief

# The extensions `aief extract --batch` takes from a folder (tools/batch.cpp).
IMAGE_EXTENSIONS = {".png", ".jpg", ".jpeg", ".pgm", ".ppm", ".pbm", ".bmp", ".tif", ".tiff", ".webp"}


def list_images(folder):
    """Image paths below `folder`, relative with '/': the names the CLI batch gives them, sorted as it sorts them."""
    root = pathlib.Path(folder)
    return sorted(p.relative_to(root).as_posix() for p in root.rglob("*") if p.is_file() and p.suffix.lower() in IMAGE_EXTENSIONS)


def shard_path(output_dir, index, count):
    return os.path.join(output_dir, f"features.{index}-of-{count}.h5")


def source_of(path):
    """The image file's identity a resume compares: size in bytes, modification time in ns (io/source_record.cpp)."""
    info = os.stat(path)
    return numpy.array([info.st_size, info.st_mtime_ns], numpy.int64)


def is_current(file, name, source):
    """Whether `name` is a complete group written from the file `source` describes."""
    return f"{name}/image_size" in file and f"{name}/source" in file and numpy.array_equal(file[name]["source"][()], source)


def write_group(file, name, features, source):
    """One image's group, as io/hdf5_features.cpp writes it (image_size last marks it complete)."""
    if name in file:
        del file[name]
    group = file.create_group(name)
    group.create_dataset("keypoints", data=features.keypoints)
    group.create_dataset("descriptors", data=numpy.ascontiguousarray(features.descriptors.T))
    group.create_dataset("scores", data=features.response)
    group.create_dataset("size", data=features.size)
    group.create_dataset("angle", data=features.angle)
    group.create_dataset("octave", data=features.octave)
    group.create_dataset("source", data=source)
    group.create_dataset("image_size", data=numpy.array([features.image_width, features.image_height], numpy.int64))
    file.flush()


def extract_shard(folder, names, output, options):
    """Runs on a worker: extracts `names` into the HDF5 file `output`. Returns (extracted, skipped, keypoints)."""
    import h5py  # on the worker

    extractor = aief.Extractor(**dict(options, threads=1))
    extracted = skipped = keypoints = 0
    with h5py.File(output, "a") as file:
        for name in names:
            path = os.path.join(folder, name)
            source = source_of(path)
            if is_current(file, name, source):
                skipped += 1
                continue
            features = extractor.extract(aief.read_image(path))
            write_group(file, name, features, source)
            extracted += 1
            keypoints += len(features)
    return extracted, skipped, keypoints


def run(client, folder, output_dir, shards, **options):
    """Extracts every image of `folder` on the cluster of `client` into `shards` files in
    `output_dir`; `options` are aief.Extractor's keyword arguments. Returns the shard files and
    the totals (extracted, skipped, keypoints)."""
    os.makedirs(output_dir, exist_ok=True)
    names = list_images(folder)
    outputs = [shard_path(output_dir, i, shards) for i in range(shards)]
    futures = [client.submit(extract_shard, str(folder), names[i::shards], outputs[i], options, pure=False)
               for i in range(shards)]
    totals = numpy.sum(client.gather(futures), axis=0) if futures else numpy.zeros(3, int)
    return outputs, tuple(int(t) for t in totals)


def main():
    parser = argparse.ArgumentParser(description="aief batch extraction on a Dask cluster (hloc HDF5 shard files)")
    parser.add_argument("images", help="folder of images (recursively)")
    parser.add_argument("output_dir", help="folder for features.<i>-of-<n>.h5")
    parser.add_argument("--shards", type=int, default=8, help="number of shard files / tasks (default 8)")
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", help="address of a running dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--local-workers", type=int, help="start a LocalCluster of this many worker processes")
    parser.add_argument("--features", type=int, default=aief.default_options()["n_features"], help="n_features")
    args = parser.parse_args()
    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.local_workers, threads_per_worker=1, processes=True))
    with client:
        outputs, (extracted, skipped, keypoints) = run(client, args.images, args.output_dir, args.shards,
                                                       n_features=args.features)
    print(f"dask batch: {extracted} extracted, {skipped} already done, {keypoints} keypoints in {len(outputs)} shard files")


if __name__ == "__main__":
    main()
