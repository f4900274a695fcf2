"""The module explains itself: a docstring on every public function, class, method and property,
and a type stub (aief/_aief.pyi, shipped beside the module) naming every one of them."""
import ast
import inspect
import pathlib
import pydoc
import re

import aief
import aief._aief
import aief.dask_batch

# Named by the language, documented by it: nothing of the module's own to say.
INHERITED = {"__init__", "__repr__", "__len__"}


def public_members(cls):
    return [name for name, _ in inspect.getmembers(cls) if not name.startswith("_") and name not in dir(BaseException)]


def own_text(doc):
    """The docstring without pybind11's signature lines ("name(args) -> type")."""
    lines = [line for line in (doc or "").strip().splitlines() if line.strip() and not re.match(r"\s*\w+\(.*\) -> ", line)]
    return " ".join(lines).strip()


def stub_names():
    """{name: set of member names} for every top-level def and class of the shipped stub."""
    stub = pathlib.Path(aief._aief.__file__).with_name("_aief.pyi")
    assert stub.is_file(), f"no type stub beside the module: {stub}"
    tree = ast.parse(stub.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        elif isinstance(node, ast.AnnAssign):
            names[node.target.id] = set()
    return names


def test_every_public_name_has_a_docstring():
    undocumented = []
    for name in aief.__all__:
        obj = getattr(aief, name)
        if not own_text(obj.__doc__):
            undocumented.append(name)
        if inspect.isclass(obj):
            undocumented += [f"{name}.{member}" for member in public_members(obj)
                             if not own_text(getattr(obj, member).__doc__)]
    for name, function in inspect.getmembers(aief.dask_batch, inspect.isfunction):
        if function.__module__ == aief.dask_batch.__name__ and not own_text(function.__doc__):
            undocumented.append(f"dask_batch.{name}")
    assert not undocumented, f"without a docstring: {undocumented}"


def test_the_stub_names_every_public_function_class_and_member():
    stub = stub_names()
    missing = []
    for name in dir(aief._aief):
        if name.startswith("_") and name != "__version__":
            continue
        if name not in stub:
            missing.append(name)
            continue
        obj = getattr(aief._aief, name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            missing += [f"{name}.{member}" for member in public_members(obj) if member not in stub[name]]
    assert not missing, f"in aief._aief but not in _aief.pyi: {missing}"


def test_the_package_is_typed():
    assert pathlib.Path(aief.__file__).with_name("py.typed").is_file()


def test_help_shows_the_usage_and_every_name():
    text = pydoc.render_doc(aief, renderer=pydoc.plaintext)
    assert "Extractor(n_features=1000)" in text  # the usage example of the package docstring
    for name in aief.__all__:
        assert name in text
