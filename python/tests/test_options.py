"""aief.Extractor's keywords: every row of the option table (core/options/option_table.hpp) reaches the engine, and
the CLI's rule holds: the mode first, the keywords given over it, a conflict refused; numbers as numbers."""
import numpy
import pytest

import aief

ROWS = aief._aief._option_table()


def other_value(row, default):
    """A value of the row other than its default, valid alone (the C++ test's choice)."""
    if row["kind"] == "integer":
        return default + 1 if default + 1 <= row["high"] else default - 1
    if row["kind"] == "number":
        return default * 1.25 if default * 1.25 <= row["high"] else default * 0.8
    if row["kind"] == "toggle":
        return not default
    return next(name for name in row["names"]
                if name != default and name not in ("off", "sse4.2", "avx2", "avx512", "neon64"))


# What a row needs beside it to act (its acts_with conditions the defaults do not meet).
NEEDS = {"distribution=quadtree": dict(mode="quadtree-entropy"), "auto_threshold=on": dict(threshold="auto"),
         "carried_threshold=on": dict(threshold="carried")}


def companions(row):
    beside = {}
    for condition in filter(None, row["acts_with"].split(",")):
        beside.update(NEEDS.get(condition, {}))
    return beside


@pytest.mark.parametrize("row", ROWS, ids=[row["keyword"] for row in ROWS])
def test_every_keyword_reaches_the_options(row):
    if row["key"] == "mode":
        assert aief.Extractor(mode="orbslam2").options["distribution"] == "quadtree"
        return
    default = aief.default_options()[row["key"]]
    value = other_value(row, default)
    beside = companions(row)
    options = aief.Extractor(**{row["keyword"]: value}, **beside).options
    assert options[row["key"]] == value
    assert {k: v for k, v in options.items() if k != row["key"]} == {
        k: v for k, v in aief.Extractor(**beside).options.items() if k != row["key"]}


# Options that cannot act with the others were accepted and did nothing: Extractor(mode='faithful',
# fast_threshold_from='entropy') gave faithful's bytes. Refused now, naming what they need.
@pytest.mark.parametrize("kwargs, says", [
    (dict(mode="faithful", fast_threshold_from="entropy"),
     "fast_threshold_from entropy does nothing unless detection_cells blocks, and mode faithful makes it orbslam"),
    (dict(detection_cells="orbslam", fast_threshold_from="entropy"), "detection_cells orbslam is given"),
    (dict(quadtree_weight="entropy"), "does nothing unless distribution quadtree"),
    (dict(mode="orbslam2", quadtree_weight="entropy", quadtree_ties="orbslam"), "unless quadtree_weight none"),
    (dict(carry_every=10), "does nothing unless carried_threshold on"),
    (dict(mode="orbslam2", pool=2), "does nothing unless distribution proportional"),
])
def test_an_option_that_cannot_act_is_refused(kwargs, says):
    with pytest.raises(aief.Error, match=says):
        aief.Extractor(**kwargs)


# A smoothing sigma that runs another value's passes (0.5 runs 1's one pass) was accepted and
# recorded as itself: the same bytes under another option record. Refused, naming the value.
@pytest.mark.parametrize("sigma, named", [(1e-320, "1"), (0.5, "1"), (1.2, "1"), (1.3, "1.5")])
def test_a_smoothing_that_runs_another_values_passes_is_refused(sigma, named):
    with pytest.raises(aief.Error, match=f"as {named} does: give that"):
        aief.Extractor(detection_smoothing=sigma)
    assert aief.Extractor(detection_smoothing=float(named)).options["detection_smoothing"] == float(named)


def test_the_options_of_a_variant_rebuild_it():
    extractor = aief.Extractor(mode="faithful", quadtree_weight="entropy")
    assert aief.Extractor(**extractor.options).options == extractor.options


# entropy_threshold's setter writes auto_threshold and carried_threshold too, so the record keys
# auto_threshold= and carried_threshold= set what it sets: a second value of one field, which table
# order used to drop without a word (entropy_threshold=3.0, auto_threshold=True ran the automatic F).
@pytest.mark.parametrize("kwargs, says", [
    (dict(entropy_threshold=3.0, auto_threshold=True), "entropy_threshold 3.0 means auto_threshold off, so auto_threshold on"),
    (dict(entropy_threshold="auto", auto_threshold=False), "entropy_threshold auto means auto_threshold on, so auto_threshold off"),
    (dict(entropy_threshold="carried", carried_threshold=False),
     "entropy_threshold carried means carried_threshold on, so carried_threshold off"),
    (dict(entropy_threshold="auto", carried_threshold=True),
     "entropy_threshold auto means carried_threshold off, so carried_threshold on"),
])
def test_two_keywords_that_set_one_field_differently_are_refused(kwargs, says):
    with pytest.raises(aief.Error, match=says + " cannot apply: drop one of the two"):
        aief.Extractor(**kwargs)


def test_keywords_that_agree_on_the_threshold_are_taken():
    assert aief.Extractor(entropy_threshold="auto", auto_threshold=True, carried_threshold=False).options["auto_threshold"]
    assert aief.Extractor(entropy_threshold=3.0, auto_threshold=False).options["entropy_threshold"] == 3.0
    automatic = aief.Extractor(entropy_threshold="auto")
    assert aief.Extractor(**automatic.options).options == automatic.options  # F is the mode's: no request
    carried = aief.Extractor(entropy_threshold="carried", carry_every=7)
    assert aief.Extractor(**carried.options).options == carried.options


OLD = [row for row in ROWS if row["old_keyword"]]


@pytest.mark.parametrize("row", OLD, ids=[row["old_keyword"] for row in OLD])
def test_an_earlier_keyword_is_still_accepted(row):
    """threshold= is entropy_threshold= (CHANGELOG.md): the same options, and not both at once."""
    value = other_value(row, aief.default_options()[row["key"]])
    assert aief.Extractor(**{row["old_keyword"]: value}).options == aief.Extractor(**{row["keyword"]: value}).options
    with pytest.raises(TypeError, match="multiple values"):
        aief.Extractor(**{row["old_keyword"]: value, row["keyword"]: value})


def test_positional_arguments_keep_their_order():
    options = aief.Extractor(300, "quadtree-entropy", 3.5, 6, 1.3, 1, "scalar").options
    assert (options["n_features"], options["distribution"], options["entropy_threshold"], options["n_levels"],
            options["scale_factor"], options["threads"], options["kernels"]) == (300, "quadtree", 3.5, 6, 1.3, 1, "scalar")
    with pytest.raises(TypeError, match="multiple values"):
        aief.Extractor(300, n_features=400)


# The mode sets its values first and the keywords given override them, as the CLI does. Before, the
# keywords were set first and the mode's preset overwrote them: entropy='off' kept the mask on.
@pytest.mark.parametrize("mode", ["aief", "aief-paper", "quadtree-entropy"])
def test_entropy_off_turns_the_mask_off_in_every_mode(mode):
    assert aief.Extractor(mode=mode, entropy="off").options["entropy"] == "off"


def test_a_keyword_the_mode_cannot_honour_is_refused():
    # Before: mode='orbslam2', entropy='histogram' silently gave off.
    with pytest.raises(aief.Error, match="mode orbslam2 means entropy off"):
        aief.Extractor(mode="orbslam2", entropy="histogram")
    # Before: entropy='off', threshold=7 ran with the mask at F = 7.
    with pytest.raises(aief.Error, match="threshold sets F of the entropy mask, which entropy off turns off"):
        aief.Extractor(entropy="off", threshold=7)
    with pytest.raises(aief.Error, match="which mode orbslam2 turns off"):
        aief.Extractor(mode="orbslam2", threshold="auto")


def test_none_keeps_the_modes_value():
    assert aief.Extractor(threshold=None, pool=None).options == aief.default_options()
    assert aief.Extractor(mode="aief-paper", coordinates=None).options["coordinates"] == "scaled"


def test_numpy_scalars_are_the_numbers_they_hold():
    # Before: threshold=numpy.float32(3) was refused as "not a number".
    options = aief.Extractor(threshold=numpy.float32(3), n_features=numpy.int64(500), pool=numpy.float64(2),
                             scale=numpy.float32(1.5)).options
    assert (options["entropy_threshold"], options["n_features"], options["candidate_pool"]) == (3.0, 500, 2.0)
    assert options["scale_factor"] == float(numpy.float32(1.5))


@pytest.mark.parametrize("kwargs", [dict(n_features=True), dict(levels=False), dict(threshold=True), dict(pool=True),
                                    dict(n_features=numpy.bool_(True)), dict(scale=numpy.bool_(True)),
                                    dict(n_features=numpy.float32(3)), dict(subpixel=1), dict(mode=2)])
def test_bools_are_no_numbers_and_numbers_no_bools(kwargs):
    # Before: n_features=True was accepted as 1.
    with pytest.raises(TypeError):
        aief.Extractor(**kwargs)


def test_numbers_follow_the_cli_rules():
    assert aief.Extractor(threshold=1e-320).options["entropy_threshold"] == 1e-320
    assert str(aief.Extractor(threshold=-0.0).options["entropy_threshold"]) == "0.0"
    with pytest.raises(aief.Error, match=r"n_features expects an integer in \[1, 1000000\], got '1099511627776'"):
        aief.Extractor(n_features=2**40)
    with pytest.raises(aief.Error, match="threshold expects a number in"):
        aief.Extractor(threshold="0x10")


def test_ratio_goes_with_the_ratio_matcher_only():
    descriptors = numpy.random.default_rng(1).integers(0, 256, (40, 32), dtype=numpy.uint8)
    # Before: ratio=0.1 without matcher='ratio' was ignored; the CLI refuses it.
    with pytest.raises(aief.Error, match="ratio applies to matcher ratio, mutual_ratio or guided only, not mutual"):
        aief.match(descriptors, descriptors, ratio=0.1)
    assert len(aief.match(descriptors, descriptors, matcher="ratio", ratio=0.9)) > 0
    assert len(aief.match(descriptors, descriptors, matcher="mutual_ratio", ratio=0.9)) > 0
    assert len(aief.match(descriptors, descriptors)) == 40


# Extractor.options holds the record's keys (scale_factor, candidate_pool, distribution, ...), which
# were not the constructor's keywords: Extractor(**e.options) raised TypeError. Now every record key
# is a keyword too, and giving the value an option already holds is no request (an orbslam2
# extractor's entropy_threshold with its mask off).
@pytest.mark.parametrize("kwargs", [dict(), dict(mode="aief-paper"), dict(mode="orbslam2"),
                                    dict(mode="quadtree-entropy", threshold="auto"), dict(threshold="carried"),
                                    dict(pool="inf", levels=3, scale=1.5, ranking="peak"),
                                    dict(entropy="off"), dict(n_features=123, kernels="scalar", threads=1)])
def test_the_options_rebuild_the_extractor(kwargs):
    extractor = aief.Extractor(**kwargs)
    rebuilt = aief.Extractor(**extractor.options)
    assert rebuilt.options == extractor.options
    assert rebuilt.option_record == extractor.option_record


def test_a_record_key_and_its_keyword_are_one_option():
    assert aief.Extractor(scale_factor=1.5).options["scale_factor"] == 1.5
    with pytest.raises(TypeError, match="multiple values"):
        aief.Extractor(scale=1.3, scale_factor=1.5)
    # Giving a value that changes nothing is no request; changing F with the mask off still is refused.
    assert aief.Extractor(entropy="off", entropy_threshold=4.0).options["entropy"] == "off"
    with pytest.raises(aief.Error, match="which entropy off turns off"):
        aief.Extractor(entropy="off", entropy_threshold=5.0)


def test_match_and_adapt_take_their_options_from_the_rows():
    descriptors = numpy.arange(4 * 32, dtype=numpy.uint8).reshape(4, 32)
    assert aief.match(descriptors, descriptors, "ratio", 0.9, 10).shape == (4, 3)
    assert aief.match(a=descriptors, b=descriptors, matcher="paper").shape == (4, 3)
    with pytest.raises(TypeError, match="unexpected keyword argument 'rato'"):
        aief.match(descriptors, descriptors, rato=0.5)
    with pytest.raises(TypeError, match="missing required argument 'b'"):
        aief.match(descriptors)
    with pytest.raises(aief.Error, match="ratio applies to matcher ratio, mutual_ratio or guided only, not mutual"):
        aief.adapt(numpy.zeros((64, 64), numpy.uint8), numpy.zeros((64, 64), numpy.uint8), ratio=0.5)
