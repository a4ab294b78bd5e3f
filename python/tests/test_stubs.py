"""The type stubs (frugal/_frugal.pyi) say what the library's schema says. Their settings' parts
are python/stubgen.py's, made from frugal.settings_schema(): the file must be what it makes, so a
setting added to, renamed in or removed from the library fails here until `stubgen.py` is run.
And what the parts say is checked as Python reads them: the keyword arguments of Renderer and
frugal.settings() are the settings in their order after settings=, a choice a Literal of exactly
its choices. (That every name, class and property exists: stubtest, CTest PythonStubs.)"""
import ast
import importlib.util
from pathlib import Path

import pytest

import frugal

PYTHON = Path(__file__).resolve().parents[1]
STUB = PYTHON / "frugal" / "_frugal.pyi"
TREE = ast.parse(STUB.read_text())
SCHEMA = frugal.settings_schema()
# python/stubgen.py, loaded from its file: python/ on sys.path would hide the module built behind
# the package's sources (and the tests that start interpreters pass sys.path on).
_spec = importlib.util.spec_from_file_location("stubgen", PYTHON / "stubgen.py")
stubgen = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(stubgen)


def aliases():
    return {node.targets[0].id: node.value for node in TREE.body
            if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)}


def definition(name, within=None):
    body = TREE.body if within is None else definition(within).body
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name == name:
            return node
    raise AssertionError(f"{STUB.name}: no {name}" + (f" in {within}" if within else ""))


def literal(annotation):
    """The values of a Literal[...] annotation, through the aliases; None when it is none."""
    node = annotation
    while isinstance(node, ast.Name) and node.id in aliases():
        node = aliases()[node.id]
    if not (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id == "Literal"):
        return None
    items = node.slice.elts if isinstance(node.slice, ast.Tuple) else [node.slice]
    return [item.value for item in items]


def test_the_settings_parts_are_what_stubgen_makes_from_the_schema():
    text = STUB.read_text()
    assert stubgen.render(text, SCHEMA) == text, \
        "python/frugal/_frugal.pyi is stale: run PYTHONPATH=<build>/python python3 python/stubgen.py"


def test_the_stubs_take_every_setting_as_a_keyword_typed_by_its_kind():
    names = frugal.settings_names()
    assert [s["name"] for s in SCHEMA] == names
    for function in (definition("__init__", "Renderer"), definition("settings")):
        assert not function.args.kwarg, f"{function.name} takes **kwargs in the stubs"
        keywords = [(a.arg, a.annotation) for a in function.args.kwonlyargs]
        assert [name for name, _ in keywords] == ["settings"] + names
        for info, (_, annotation) in zip(SCHEMA, keywords[1:]):
            if info["kind"] == "choice":
                assert literal(annotation) == info["choices"], info["name"]
            else:
                assert ast.unparse(annotation) == stubgen.KEYWORD[info["kind"]], info["name"]
    fields = [node.target.id for node in definition("_Settings").body if isinstance(node, ast.AnnAssign)]
    assert fields == names
    defaults = frugal.default_settings()
    for info in SCHEMA:  # what the module gives has the stubs' kind of value
        value = defaults[info["name"]]
        kind = {"switch": bool, "whole": int, "pair": tuple, "colour": tuple, "choice": str, "real": float,
                "text": str}[info["kind"]]
        assert type(value) is kind, f"{info['name']}: {value!r}"


def test_the_stubs_name_what_the_package_exports():
    public = {node.name for node in TREE.body
              if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and not node.name.startswith("_")}
    assert public | {"__version__"} == set(frugal.__all__), \
        f"frugal/__init__.py's __all__ and the stubs differ: {sorted(public ^ (set(frugal.__all__) - {'__version__'}))}"
    for name in frugal.__all__:
        assert getattr(frugal, name) is getattr(frugal._frugal, name)


def test_the_allowlist_names_the_classes_without_a_constructor():
    """stubtest-allowlist.txt lets the classes that bind no constructor keep pybind11's __init__
    (which raises TypeError); it names exactly those."""
    import re
    line = [s for s in (STUB.parent.parent / "tests" / "stubtest-allowlist.txt").read_text().splitlines()
            if s and not s.startswith("#")]
    assert len(line) == 1 and line[0].endswith(r")\.__init__")
    listed = set(re.search(r"\\.\((\w+(?:\|\w+)*)\)\\.__init__$", line[0]).group(1).split("|"))
    import types
    pybind11_type = type(frugal.Frame)
    bound = {name for name in frugal.__all__ if type(getattr(frugal, name)) is pybind11_type}
    assert {"Scene", "Renderer", "Writer", "Frame"} <= bound
    # A constructor bound is a pybind11 method; without one, __init__ is pybind11_object's C slot.
    without = {name for name in bound if isinstance(vars(getattr(frugal, name))["__init__"], types.WrapperDescriptorType)}
    assert listed == without, f"stubtest-allowlist.txt lists {sorted(listed)}; without a constructor: {sorted(without)}"
    assert bound - without == {"Scene", "Renderer", "Writer"}
    for name in without:
        with pytest.raises(TypeError):
            getattr(frugal, name)()
