"""aief.match, aief.find_homography, aief.adapt: the CLI's answers, and their errors."""
import json
import pickle
import re
import subprocess

import numpy
import pytest

import aief
from conftest import SEQUENCES, read_unchanged, run_cli, sample_path


@pytest.mark.parametrize("sequence", SEQUENCES)
def test_match_and_homography_give_the_cli_answer(cli, tmp_path, sequence):
    out = tmp_path / "matches.json"
    run_cli(cli, "match", sample_path(sequence, 1), sample_path(sequence, 2), "-o", out)
    expected = json.loads(out.read_text())
    extractor = aief.Extractor()
    a = extractor.extract(read_unchanged(sample_path(sequence, 1)))
    b = extractor.extract(read_unchanged(sample_path(sequence, 2)))
    matches = aief.match(a, b)
    assert matches.dtype == numpy.int32 and matches.shape == (expected["putative"], 3)
    numpy.testing.assert_array_equal(matches, [[m["query"], m["train"], m["distance"]] for m in expected["matches"]])
    numpy.testing.assert_array_equal(aief.match(a.descriptors, b.descriptors), matches)
    H, mask = aief.find_homography(a.keypoints[matches[:, 0]], b.keypoints[matches[:, 1]])
    assert (H is not None) == expected["homography_found"]
    numpy.testing.assert_array_equal(mask, [m["inlier"] for m in expected["matches"]])
    assert int(mask.sum()) == expected["inliers"]
    numpy.testing.assert_array_equal(H.ravel(), expected["homography"])


def test_adapt_gives_the_cli_threshold_and_curve(cli, tmp_path):
    out = tmp_path / "adapt.json"
    run_cli(cli, "adapt", sample_path("graf", 1), sample_path("graf", 2), "-o", out)
    expected = json.loads(out.read_text())
    result = aief.adapt(read_unchanged(sample_path("graf", 1)), read_unchanged(sample_path("graf", 2)))
    assert result.found == expected["found"] and result.threshold == expected["threshold"]
    assert [(p["threshold"], p["putative"], p["inliers"]) for p in result.curve] == \
           [(p["threshold"], p["putative"], p["inliers"]) for p in expected["curve"]]
    assert result.matches.shape[0] == result.curve[result.chosen_index]["putative"]
    H, mask = result.homography
    assert H.shape == (3, 3) and int(mask.sum()) == result.curve[result.chosen_index]["inliers"]


def test_matcher_options():
    rng = numpy.random.default_rng(7)
    a = rng.integers(0, 256, (50, 32), dtype=numpy.uint8)
    b = numpy.concatenate([a[::-1], rng.integers(0, 256, (10, 32), dtype=numpy.uint8)])
    for matcher in ("mutual", "ratio", "paper", "mutual_ratio"):
        matches = aief.match(a, b, matcher=matcher)
        numpy.testing.assert_array_equal(matches[:, 1], 49 - matches[:, 0])
        assert (matches[:, 2] == 0).all()
    assert aief.match(a, b, max_distance=0).shape == (50, 3)
    assert aief.match(a[:0], b).shape == (0, 3)


def test_guided_matching_gives_the_cli_answer(cli, tmp_path):
    out = tmp_path / "matches.json"
    run_cli(cli, "match", sample_path("boat", 1), sample_path("boat", 2), "--matcher", "guided", "-o", out)
    expected = json.loads(out.read_text())
    extractor = aief.Extractor()
    a = extractor.extract(read_unchanged(sample_path("boat", 1)))
    b = extractor.extract(read_unchanged(sample_path("boat", 2)))
    matches = aief.match(a, b, matcher="guided", ratio=0.8, epipolar_band=1.0)
    numpy.testing.assert_array_equal(matches, [[m["query"], m["train"], m["distance"]] for m in expected["matches"]])
    assert len(matches) > len(aief.match(a, b, matcher="mutual_ratio"))
    with pytest.raises(aief.Error, match="matcher='guided' needs aief.Features"):
        aief.match(a.descriptors, b, matcher="guided")
    with pytest.raises(aief.Error, match="epipolar_band applies to matcher guided only"):
        aief.match(a, b, epipolar_band=2.0)


@pytest.mark.parametrize("call, message", [
    (lambda d: aief.match(d, d, matcher="nearest"), "unknown matcher"),
    (lambda d: aief.match(d, d, ratio=1.5), "ratio"),
    (lambda d: aief.match(d, d, ratio=0), "ratio"),
    (lambda d: aief.match(d, d, max_distance=-1), "max_distance"),
    (lambda d: aief.match(d[:, :16], d), "N x 32 uint8"),
    (lambda d: aief.match(d.astype(numpy.int32), d), "N x 32 uint8"),
    (lambda d: aief.match(d, [1, 2]), "b must be"),
    (lambda d: aief.find_homography(numpy.zeros((5, 2)), numpy.zeros((4, 2))), "5 source points but 4 destination points"),
    (lambda d: aief.find_homography(numpy.zeros((5, 3)), numpy.zeros((5, 3))), "N x 2"),
    (lambda d: aief.find_homography("points", numpy.zeros((5, 2))), "N x 2"),
    (lambda d: aief.find_homography(numpy.zeros((5, 2)), numpy.zeros((5, 2)), threshold_px=-1), "threshold_px"),
    (lambda d: aief.find_homography(numpy.zeros((5, 2)), numpy.zeros((5, 2)), confidence=1.5), "confidence"),
    (lambda d: aief.find_homography(numpy.zeros((5, 2)), numpy.zeros((5, 2)), max_iterations=0), "max_iterations"),
    (lambda d: aief.adapt(numpy.zeros((64, 64), numpy.uint8), numpy.zeros((64, 64), numpy.uint8), step=0), "step"),
    (lambda d: aief.adapt(numpy.zeros((64, 64), numpy.uint8), numpy.zeros((64, 64), numpy.uint8), min_inliers=-1), "min_inliers"),
    (lambda d: aief.adapt(numpy.zeros((64, 64), numpy.uint8), numpy.zeros((8, 8), numpy.uint8)), "smaller than"),
    (lambda d: aief.adapt(numpy.zeros((64, 64), numpy.uint8), numpy.zeros((64, 64), numpy.uint8),
                          aief.Extractor(mode="orbslam2")), "entropy"),
])
def test_invalid_arguments_raise_aief_error(call, message):
    descriptors = numpy.zeros((4, 32), numpy.uint8)
    with pytest.raises(aief.Error, match=message):
        call(descriptors)


def test_no_model_gives_none():
    H, mask = aief.find_homography(numpy.zeros((3, 2)), numpy.zeros((3, 2)))
    assert H is None and mask.tolist() == [0, 0, 0]


def test_features_say_their_descriptor_and_different_kinds_are_not_matched():
    image_a = read_unchanged(sample_path("graf", 1))
    image_b = read_unchanged(sample_path("graf", 2))
    rbrief = aief.Extractor(n_features=300).extract(image_a)
    box_a = aief.Extractor(n_features=300, descriptor="box").extract(image_a)
    box_b = aief.Extractor(n_features=300, descriptor="box").extract(image_b)
    assert rbrief.descriptor == "rbrief" and box_a.descriptor == "box"
    assert aief.match(box_a, box_b).shape[0] > 0
    with pytest.raises(aief.Error, match="a holds rbrief descriptors, b box descriptors: they cannot be matched"):
        aief.match(rbrief, box_b)
    # Arrays carry no kind: matched as given.
    assert aief.match(rbrief.descriptors, box_b.descriptors).shape[1] == 3


# pybind11's "Unable to cast Python instance to C++ type" and "got 2 dimensions" said nothing of
# what was wrong.
def test_adapt_names_an_extractor_of_another_type():
    gray = numpy.zeros((64, 64), numpy.uint8)
    with pytest.raises(TypeError, match="extractor must be an aief.Extractor \\(or None\\), got str"):
        aief.adapt(gray, gray, extractor="aief")


def test_find_homography_names_the_shape_given():
    with pytest.raises(aief.Error, match="src must be an N x 2 array of \\(x, y\\), got 10 x 3"):
        aief.find_homography(numpy.ones((10, 3)), numpy.ones((10, 3)))
    with pytest.raises(aief.Error, match="got 1 dimensions"):
        aief.find_homography(numpy.ones(10), numpy.ones((10, 2)))


# The adaptive sweep chooses F itself and has no threshold fallback: an extractor asking for F, the
# frame-wide guard or extrema scales ran the default sweep without a word, where aief adapt exits 2.
SWEEP_IGNORES = [
    (dict(entropy_threshold=3.0), ["--entropy-threshold", "3"], "entropy_threshold 3.0"),
    (dict(entropy_threshold="auto"), ["--entropy-threshold", "auto"], "entropy_threshold auto"),
    (dict(starvation_guard="frame"), ["--starvation-guard", "frame"], "starvation_guard frame"),
    (dict(scale_selection="extrema"), ["--scale-selection", "extrema"], "scale_selection extrema"),
]


@pytest.mark.parametrize("kwargs, flags, named", SWEEP_IGNORES, ids=[n for _, _, n in SWEEP_IGNORES])
def test_adapt_refuses_what_the_sweep_never_reads_as_the_cli_does(cli, kwargs, flags, named):
    a, b = sample_path("graf", 1), sample_path("graf", 2)
    run = subprocess.run([cli, "adapt", str(a), str(b), *flags], capture_output=True, text=True)
    cli_says = run.stderr.strip()
    assert run.returncode == 2 and cli_says.startswith("aief: error: " + " ".join(flags) + " does nothing"), cli_says
    reason = cli_says[cli_says.index(" does nothing"):cli_says.index(": drop ")]
    extractor = aief.Extractor(**kwargs)
    with pytest.raises(aief.Error) as refused:
        aief.adapt(read_unchanged(a), read_unchanged(b), extractor=extractor)
    assert str(refused.value) == named + reason + ": drop " + next(iter(kwargs))
    with pytest.raises(aief.Error, match=re.escape(named + " does nothing in the adaptive sweep")):
        aief.adapt(read_unchanged(a), read_unchanged(b), extractor=pickle.loads(pickle.dumps(extractor)))


def test_adapt_takes_the_values_a_mode_or_the_defaults_hold():
    gray = read_unchanged(sample_path("graf", 1))
    for extractor in (aief.Extractor(entropy_threshold=4.0), aief.Extractor(mode="aief-paper"),
                      aief.Extractor(**aief.Extractor(mode="aief-paper").options)):
        assert aief.adapt(gray, gray, extractor=extractor).found


def test_adapt_refuses_the_automatic_f_of_a_rebuilt_extractor():
    """Extractor(**e.options) gives auto_threshold=True by its record key: the sweep never reads it either."""
    gray = read_unchanged(sample_path("graf", 1))
    rebuilt = aief.Extractor(**aief.Extractor(entropy_threshold="auto").options)
    with pytest.raises(aief.Error, match="auto_threshold on does nothing in the adaptive sweep"):
        aief.adapt(gray, gray, extractor=rebuilt)
