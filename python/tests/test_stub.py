"""The type stub (aief/_aief.pyi) says what the option tables say: every call that takes options
(Extractor, match, find_homography, adapt) has the rows' parameters, in their order, positional or
keyword-only as the rows place them, with the rows' defaults; a number that also takes words
(threshold's "auto" and "carried") names them. Before, the stub was a hand copy: no carry_every,
threshold without "carried", match's ratio defaulting to 0.8 where the call has None."""
import ast
import pathlib

import pytest

import aief._aief

SIGNATURES = aief._aief._signatures()
STUB = ast.parse(pathlib.Path(aief._aief.__file__).with_name("_aief.pyi").read_text())


def stub_function(name):
    for node in STUB.body:
        if isinstance(node, ast.FunctionDef) and node.name == name:
            return node
        if isinstance(node, ast.ClassDef) and node.name == name:
            return next(n for n in node.body if isinstance(n, ast.FunctionDef) and n.name == "__init__")
    raise AssertionError(f"{name} is not in the stub")


def parameters(function):
    """[(name, default or None, keyword_only)], self left out."""
    arguments = function.args
    positional = [a for a in arguments.posonlyargs + arguments.args if a.arg != "self"]
    defaults = [None] * (len(positional) - len(arguments.defaults)) + [ast.literal_eval(d) for d in arguments.defaults]
    out = [(a.arg, default, False) for a, default in zip(positional, defaults)]
    out += [(a.arg, None if d is None else ast.literal_eval(d), True)
            for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults)]
    return out


@pytest.mark.parametrize("name", sorted(SIGNATURES))
def test_the_stub_has_the_rows_parameters_order_and_defaults(name):
    expected = parameters(ast.parse(f"def {SIGNATURES[name]}: ...").body[0])
    assert parameters(stub_function(name)) == expected


def test_every_call_that_takes_options_is_checked():
    assert set(SIGNATURES) == {"Extractor", "match", "find_homography", "adapt"}


def test_a_number_that_takes_words_names_them():
    init = stub_function("Extractor")
    annotations = {a.arg: ast.unparse(a.annotation) for a in init.args.args + init.args.kwonlyargs if a.annotation}
    for row in aief._aief._option_table():
        if row["kind"] == "number" and row["words"]:
            for word in row["words"].split("|"):
                assert f"'{word}'" in annotations[row["keyword"]], (row["keyword"], word)


@pytest.mark.parametrize("record", sorted(aief._aief._record_fields()))
def test_the_stubs_typed_dicts_are_the_records_field_lists(record):
    """Each result record's TypedDict has its one field list's keys, in order, with their types
    (io/record_fields.hpp): the dicts Features.info and AdaptResult.curve hand out."""
    node = next((n for n in STUB.body if isinstance(n, ast.ClassDef) and n.name == record), None)
    assert node is not None, f"{record} is not in the stub"
    stub = [(n.target.id, ast.unparse(n.annotation)) for n in node.body if isinstance(n, ast.AnnAssign)]
    assert stub == [tuple(field) for field in aief._aief._record_fields()[record]]


def test_the_dicts_handed_out_are_the_field_lists():
    import numpy
    extractor = aief.Extractor(n_features=50)
    info = extractor.extract(numpy.full((64, 64), 7, numpy.uint8)).info
    assert list(info) == [key for key, _ in aief._aief._record_fields()["ExtractionInfo"]]
