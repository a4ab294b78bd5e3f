#!/usr/bin/env python3
"""Writes the settings' parts of frugal/_frugal.pyi from the library's schema, so that no list of
settings in the stubs is kept by hand: the Literal of each choice, the dict of settings
(_Settings), and the keyword arguments of frugal.settings() and Renderer(). Each part lies between
two marker lines, '# <settings: PART>' and '# </settings: PART>'; the rest of the file is written
by hand. python/tests/test_stubs.py checks that the file is what this makes.

    PYTHONPATH=build/python python3 python/stubgen.py        # rewrite python/frugal/_frugal.pyi
"""
import re
import sys
from pathlib import Path

STUB = Path(__file__).resolve().parent / "frugal" / "_frugal.pyi"

# A keyword argument's type, and a value's in the dict of settings, by the setting's kind.
KEYWORD = {"switch": "bool", "whole": "int", "pair": "_Pair", "colour": "_Colour", "real": "float",
           "text": "str | os.PathLike[str]"}
VALUE = {"switch": "bool", "whole": "int", "pair": "tuple[int, int]", "colour": "tuple[float, float, float, float]",
         "real": "float", "text": "str"}


def alias(info):
    """The Literal alias of a choice setting: depth_format -> _DepthFormat."""
    return "_" + "".join(part.capitalize() for part in info["name"].split("_"))


def kind_type(info, value):
    if info["kind"] == "choice":
        return alias(info)
    return (VALUE if value else KEYWORD)[info["kind"]]


def wrapped(head, items, indent, width=112):
    """'head[a, b, ...]' over lines of at most `width`, continued under the first item."""
    lines, line = [], head + "["
    for i, item in enumerate(items):
        piece = item + ("]" if i + 1 == len(items) else ",")
        if len(line) + len(piece) + 1 > width and not line.endswith("["):
            lines.append(line)
            line = " " * indent + piece
        else:
            line += ("" if line.endswith("[") else " ") + piece
    return lines + [line]


def parts(schema):
    """The text of each part, by name."""
    choices = []
    for info in schema:
        if info["kind"] == "choice":
            head = f"{alias(info)} = Literal"
            choices += wrapped(head, [repr(c).replace("'", '"') for c in info["choices"]], len(head) + 1)
    fields = [f"    {info['name']}: {kind_type(info, True)}" for info in schema]
    keywords = [f"{info['name']}: {kind_type(info, False)} = ...," for info in schema]
    return {
        "choices": choices,
        "dict": fields,
        "keywords": ["    " + k for k in keywords],
        "renderer keywords": ["        " + k for k in keywords],
    }


def render(text, schema):
    """`text` with every part made anew. Error: a part's markers missing."""
    for name, lines in parts(schema).items():
        pattern = re.compile(rf"(^[ \t]*# <settings: {re.escape(name)}>\n).*?(^[ \t]*# </settings: {re.escape(name)}>\n)",
                             re.S | re.M)
        if not pattern.search(text):
            raise SystemExit(f"error: {STUB}: no '# <settings: {name}>' ... '# </settings: {name}>' lines")
        text = pattern.sub(lambda m: m.group(1) + "".join(line + "\n" for line in lines) + m.group(2), text)
    return text


def main():
    # The module built (PYTHONPATH), not the package's sources beside this script.
    sys.path = [p for p in sys.path if Path(p or ".").resolve() != STUB.parent.parent]
    import frugal
    text = STUB.read_text()
    made = render(text, frugal.settings_schema())
    if made != text:
        STUB.write_text(made)
        print(f"wrote {STUB}")
    else:
        print(f"{STUB} is current")


if __name__ == "__main__":
    sys.exit(main())
