"""The two routes into a COLMAP model, run with the binaries the user installed:

aief:  aief extract --batch --format h5 -> aief match --pairs -> aief colmap
       -> colmap matches_importer (two-view verification) -> colmap mapper
sift:  colmap feature_extractor (CPU SIFT) -> colmap exhaustive_matcher -> colmap mapper

Both give one SIMPLE_RADIAL camera per image with COLMAP's focal guess (1.2 max(w, h)), so the
mapper starts from the same calibration either way."""
import glob
import hashlib
import itertools
import os
from dataclasses import dataclass, field

from colmapbench.model import read_text_model
from colmapbench.runner import Steps


@dataclass
class Method:
    name: str
    kind: str                                        # "aief" or "sift"
    extract: list = field(default_factory=list)      # extra flags of the extraction
    match: list = field(default_factory=list)        # extra flags of the matching (aief)


def parse_method(text):
    """NAME=aief[:EXTRACT FLAGS][;MATCH FLAGS] or NAME=sift[:FEATURE_EXTRACTOR FLAGS], e.g.
    'quality=aief:--mode quality;--matcher ratio --ratio 0.9'. ValueError when malformed."""
    name, sep, rest = text.partition("=")
    kind = rest.split(":", 1)[0].split(";", 1)[0]
    flags = rest[len(kind):].removeprefix(":")
    if not sep or not name or kind not in ("aief", "sift"):
        raise ValueError(f"method {text!r}: expected NAME=aief[:EXTRACT FLAGS][;MATCH FLAGS] or "
                         f"NAME=sift[:FLAGS]")
    extract, _, match = flags.partition(";")
    if kind == "sift" and match.strip():
        raise ValueError(f"method {text!r}: sift takes no matcher flags")
    return Method(name, kind, extract.split(), match.split())


def write_pairs(path, images):
    """Every pair of images once (exhaustive), hloc's pairs.txt."""
    with open(path, "w") as handle:
        for a, b in itertools.combinations(images, 2):
            handle.write(f"{a} {b}\n")


def stage_images(scene, folder):
    """A folder of symbolic links to the scene's images, and nothing else (Strecha's images/ holds
    K.txt too)."""
    os.makedirs(folder, exist_ok=True)
    for name in scene.images:
        link = os.path.join(folder, name)
        if not os.path.lexists(link):
            os.symlink(os.path.abspath(os.path.join(scene.image_folder, name)), link)
    return folder


def _has_flag(flags, names):
    return any(flag.split("=")[0] in names for flag in flags)


def _slug(flags):
    text = " ".join(flags)
    return hashlib.sha1(text.encode()).hexdigest()[:10] if text else "default"


def map_and_read(steps, colmap, database, images, folder, threads):
    """colmap mapper, then the model with the most registered images as TXT; (model, models)."""
    sparse = os.path.join(folder, "sparse")
    steps.run("mapper", [colmap, "mapper", "--database_path", database, "--image_path", images,
                         "--output_path", sparse, "--Mapper.num_threads", str(threads)],
              folders=[sparse])
    best, models = None, sorted(glob.glob(os.path.join(sparse, "[0-9]*")))
    for index, model_folder in enumerate(models):
        text = os.path.join(folder, f"model_txt_{index}")
        steps.run(f"model_converter_{index}",
                  [colmap, "model_converter", "--input_path", model_folder, "--output_path", text,
                   "--output_type", "TXT"], inputs=[os.path.join(model_folder, "images.bin")],
                  folders=[text])
        model = read_text_model(text)
        if best is None or len(model.centres) > len(best.centres):
            best = model
    return best, len(models)


def run_aief(method, scene, images, scene_folder, binaries, n_features, threads, environment):
    """aief's route; (model, models, database, seconds by step)."""
    extract_flags = list(method.extract)
    if not _has_flag(extract_flags, ("--n-features",)):
        extract_flags += ["--n-features", str(n_features)]
    if not _has_flag(extract_flags, ("--threads",)):
        extract_flags += ["--threads", str(threads)]
    features_folder = os.path.join(scene_folder, "aief-features-" + _slug(extract_flags))
    features = os.path.join(features_folder, "features.h5")
    folder = os.path.join(scene_folder, method.name)
    steps = Steps(folder, environment)
    # Methods that differ only in matching share the features (and their extraction time).
    steps.seconds["extract"] = Steps(features_folder, environment).run(
        "extract", [binaries["aief"], "extract", "--batch", images, "-o", features, "--format", "h5",
                    *extract_flags], outputs=[features])
    pairs = os.path.join(scene_folder, "pairs.txt")
    matches = os.path.join(folder, "matches.h5")
    database = os.path.join(folder, "database.db")
    steps.run("match", [binaries["aief"], "match", "--pairs", pairs, "--features-file", features,
                        "-o", matches, *method.match], inputs=[features, pairs], outputs=[matches])
    steps.run("colmap_export", [binaries["aief"], "colmap", "--features-file", features,
                                "--matches", matches, "--pairs", pairs, "-o", database],
              inputs=[features, matches], outputs=[database])
    steps.run("verify", [binaries["colmap"], "matches_importer", "--database_path", database,
                         "--match_list_path", pairs, "--match_type", "pairs",
                         "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", str(threads)],
              inputs=[matches])
    model, models = map_and_read(steps, binaries["colmap"], database, images, folder, threads)
    return model, models, database, steps.seconds


def run_sift(method, scene, images, scene_folder, binaries, n_features, threads, environment):
    """COLMAP's own route, on the CPU; (model, models, database, seconds by step)."""
    flags = list(method.extract)
    if not _has_flag(flags, ("--SiftExtraction.max_num_features",)):
        flags += ["--SiftExtraction.max_num_features", str(n_features)]
    folder = os.path.join(scene_folder, method.name)
    steps = Steps(folder, environment)
    database = os.path.join(folder, "database.db")
    steps.run("extract", [binaries["colmap"], "feature_extractor", "--database_path", database,
                          "--image_path", images, "--ImageReader.camera_model", "SIMPLE_RADIAL",
                          "--SiftExtraction.use_gpu", "0",
                          "--SiftExtraction.num_threads", str(threads), *flags],
              outputs=[database])
    steps.run("match", [binaries["colmap"], "exhaustive_matcher", "--database_path", database,
                        "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", str(threads)])
    model, models = map_and_read(steps, binaries["colmap"], database, images, folder, threads)
    return model, models, database, steps.seconds
