"""Smaller silent faults in the Python module: an aief.Features made by
Features.__new__ alone crashed when read; a carried Extractor lost its F when pickled or copied;
one bad name to FeaturesFile.write made every later write fail; names nesting one group in another."""
import copy
import os
import pickle

import pytest

import aief
from conftest import read_unchanged, sample_path


def test_a_features_made_by_new_alone_raises_instead_of_crashing():
    empty = aief.Features.__new__(aief.Features)
    for read in (lambda: empty.keypoints, lambda: empty.descriptors, lambda: empty.info,
                 lambda: len(empty), lambda: pickle.dumps(empty), lambda: copy.deepcopy(empty),
                 lambda: aief.match(empty, empty)):
        with pytest.raises(aief.Error, match="holds nothing"):
            read()
    assert "holding nothing" in repr(empty)


@pytest.mark.parametrize("name", ["Extractor", "AdaptResult", "FeaturesFile", "Features"])
def test_every_class_made_by_new_alone_raises_in_every_method_and_property(name):
    # pybind11 handed such an object's methods raw memory: Extractor.__new__(...).options and
    # AdaptResult's properties crashed the interpreter. Every attribute bound in C++ is tried
    # (the Python-level ones call them).
    cls = getattr(aief, name)
    empty = cls.__new__(cls)
    bound = [a for a in dir(cls) if (not a.startswith("_") or a in ("__len__", "__getstate__"))
             and type(getattr(cls, a)).__name__ in ("property", "instancemethod")]
    assert len(bound) >= 4
    for attribute in bound:
        with pytest.raises(aief.Error, match="holds nothing"):
            value = getattr(empty, attribute)
            for count in range(8):  # as many arguments as it takes (`self` is checked first)
                try:
                    value(*[None] * count)
                except TypeError:
                    continue


def test_reduce_called_directly_reduces_as_pickle_does():
    # object.__reduce__ (copyreg._reduce_ex) aborted the interpreter on a pybind11 class.
    extractor = aief.Extractor(n_features=300)
    function, arguments, state = extractor.__reduce__()
    rebuilt = function(*arguments)
    rebuilt.__setstate__(state)
    assert rebuilt.options == extractor.options
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        assert pickle.loads(pickle.dumps(extractor, protocol)).options == extractor.options


def test_an_open_features_file_is_not_pickled(tmp_path):
    with aief.FeaturesFile(str(tmp_path / "f.h5")) as file:
        for copying in (lambda: file.__reduce__(), lambda: pickle.dumps(file),
                        lambda: copy.deepcopy(file)):
            with pytest.raises(aief.Error, match="cannot be pickled"):
                copying()


def test_a_carried_extractor_is_not_pickled_or_copied_after_its_first_frame():
    extractor = aief.Extractor(threshold="carried")
    copy.deepcopy(extractor)  # before its first frame a copy is the same extractor
    pickle.loads(pickle.dumps(extractor))
    extractor.extract(read_unchanged(sample_path("graf", 1)))
    for copying in (lambda: pickle.dumps(extractor), lambda: copy.deepcopy(extractor),
                    lambda: copy.copy(extractor)):
        with pytest.raises(aief.Error, match="after its first frame"):
            copying()
    # Any other extractor pickles after frames as before (it carries nothing).
    plain = aief.Extractor()
    plain.extract(read_unchanged(sample_path("graf", 1)))
    assert pickle.loads(pickle.dumps(plain)).options == plain.options


def test_a_bad_name_fails_alone_and_later_writes_go_on(tmp_path):
    extractor = aief.Extractor(n_features=200)
    features = extractor.extract(read_unchanged(sample_path("graf", 1)))
    source = (1, 2)
    with aief.FeaturesFile(tmp_path / "f.h5") as file:
        with pytest.raises(aief.Error, match="needs a name"):
            file.write("", features, source, extractor)
        file.write("a.png", features, source, extractor)  # before: "an earlier write failed"
        file.write("x", features, source, extractor)
        with pytest.raises(aief.Error, match="inside the group of image 'x'"):
            file.write("x/y.png", features, source, extractor)
        file.write("d/e.png", features, source, extractor)
        with pytest.raises(aief.Error, match="folder of other images' groups"):
            file.write("d", features, source, extractor)
        file.write("b.png", features, source, extractor)
    with aief.FeaturesFile(tmp_path / "f.h5") as file:
        for name in ("a.png", "x", "d/e.png", "b.png"):
            assert file.is_current(name, source, extractor), name
