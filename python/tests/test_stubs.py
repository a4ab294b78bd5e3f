"""The type stubs (frugal/_frugal.pyi) say what the library's schema says: the keyword arguments of
Renderer and frugal.settings() are the settings (settings_names(), in their order, after settings=),
each typed by its kind, a choice as a Literal of exactly the schema's choices; the dict of settings
(_Settings) has every setting. A setting added to, renamed in or removed from the library fails
here until the stubs follow. (That every name, class and property exists: stubtest, CTest
PythonStubs.)"""
import ast
from pathlib import Path

import pytest

import frugal

STUB = Path(__file__).resolve().parents[1] / "frugal" / "_frugal.pyi"
TREE = ast.parse(STUB.read_text())
SCHEMA = frugal.settings_schema()

# The annotation of a keyword argument, and of the value in the dict of settings, by kind.
KEYWORD = {"switch": "bool", "whole": "int", "pair": "_Pair", "colour": "_Colour"}
VALUE = {"switch": "bool", "whole": "int", "pair": "tuple[int, int]", "colour": "tuple[float, float, float, float]"}


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


def stub_line(info, value=False):
    """What the stub should say of a setting (the failure's hint)."""
    if info["kind"] == "choice":
        return f"{info['name']}: Literal[{', '.join(repr(c) for c in info['choices'])}]"
    return f"{info['name']}: {(VALUE if value else KEYWORD)[info['kind']]}"


def check_setting(info, annotation, where, value=False):
    hint = f"{where}: {info['name']} should be '{stub_line(info, value)}' (a {info['kind']}), not '{ast.unparse(annotation)}'"
    if info["kind"] == "choice":
        assert literal(annotation) == info["choices"], hint
    else:
        assert ast.unparse(annotation) == (VALUE if value else KEYWORD)[info["kind"]], hint


def keyword_arguments(function):
    assert not function.args.kwarg, f"{function.name} takes **kwargs in the stubs: list the settings"
    return [(a.arg, a.annotation) for a in function.args.kwonlyargs]


def test_the_stubs_take_every_setting_as_a_keyword_typed_by_its_kind():
    names = frugal.settings_names()
    assert [s["name"] for s in SCHEMA] == names
    for where, function in (("Renderer.__init__", definition("__init__", "Renderer")),
                            ("settings()", definition("settings"))):
        keywords = keyword_arguments(function)
        given = [name for name, _ in keywords]
        missing = [stub_line(s) for s in SCHEMA if s["name"] not in given]
        assert given == ["settings"] + names, \
            f"{where} in {STUB.name} takes {given}; the settings are {names}; add: {missing}"
        assert ast.unparse(keywords[0][1]) == "_Path | None"
        for info, (_, annotation) in zip(SCHEMA, keywords[1:]):
            check_setting(info, annotation, where)


def test_the_dict_of_settings_has_every_setting():
    fields = [(node.target.id, node.annotation) for node in definition("_Settings").body
              if isinstance(node, ast.AnnAssign)]
    assert [name for name, _ in fields] == frugal.settings_names(), \
        f"_Settings in {STUB.name}: add {[stub_line(s, True) for s in SCHEMA if s['name'] not in dict(fields)]}"
    for info, (_, annotation) in zip(SCHEMA, fields):
        check_setting(info, annotation, "_Settings", value=True)
    defaults = frugal.default_settings()
    for info in SCHEMA:  # what the module gives has the stubs' kind of value
        value = defaults[info["name"]]
        kind = {"switch": bool, "whole": int, "pair": tuple, "colour": tuple, "choice": str}[info["kind"]]
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
