"""Every setting through the three front ends: the command line's flags (`frugal render`, whose
--save-settings writes the settings it renders with), a settings file (`render --settings`) and
Python's keyword arguments. A value either gives the same settings in all three, or is refused in
all three with the same words after the names of the settings it is about. The values tried come
from the schema itself (frugal.settings_schema()): each choice, the ends of each range, one value
out of range, and every pair of values of the settings each conflict names."""
import itertools
import json
import subprocess
from pathlib import Path

import frugal
import pytest

SCHEMA = {s["name"]: s for s in frugal.settings_schema()}
SCENE = "builtin:cubes?count=1"
REPO = Path(__file__).resolve().parents[2]


def samples(info):
    """Values of a setting within its range (the default's kind first)."""
    kind = info["kind"]
    if kind == "switch":
        return [True]  # a flag sets it; false is its default
    if kind == "choice":
        return list(info["choices"])
    lo, hi = info["range"] or (0, 0)
    if kind == "whole":
        return sorted({lo, min(hi, lo + 3), hi})
    if kind == "pair":
        return [(lo, min(hi, lo + 1)), (min(hi, 64), min(hi, 48))]
    if kind == "real":
        return [lo, min(hi, lo + 0.5)]
    if kind == "text":  # a file the renderer reads: a tiny Radiance image of the fuzzer's seeds
        return ["", str(REPO / "tests" / "data" / "fuzz" / "hdr" / "flat.hdr")]
    return [(0.25, 0.5, 0.75), (0.0, 0.0, 0.0, 0.5)]


def out_of_range(info):
    kind = info["kind"]
    return {"choice": "nope", "whole": info["range"][1] + 1 if info["range"] else None,
            "pair": (0, 4) if info["range"] else None, "colour": (2.0, 0.0, 0.0)}.get(kind)


def flag_text(info, value):
    if info["kind"] == "pair":
        return f"{value[0]}x{value[1]}"
    if info["kind"] == "colour":
        return ",".join(repr(float(v)) for v in value)
    return str(value)


def json_value(info, value):
    return list(value) if isinstance(value, tuple) else value


def python(values):
    try:
        return frugal.settings(**values), None
    except frugal.InputError as e:
        return None, str(e)


def run(cli, tmp_path, args, values):
    """`frugal render` with `args`; the settings it saved, or its one error line."""
    saved = tmp_path / "saved.json"
    saved.unlink(missing_ok=True)
    size = [] if "size" in values else ["--size", "8x8"]
    result = subprocess.run([cli, "render", SCENE, "-q", "-o", str(tmp_path / "x.png"), "--save-settings", str(saved)]
                            + size + args, capture_output=True, text=True, timeout=120)
    if saved.exists():
        return frugal.settings(settings=str(saved)), None
    assert result.returncode != 0 and result.stderr.count("\n") == 1, result.stderr
    assert result.stderr.startswith("error: ")
    return None, result.stderr[len("error: "):].rstrip("\n")


def command_line(cli, tmp_path, values):
    args = []
    for name, value in values.items():
        info = SCHEMA[name]
        args += [info["option"]] if info["kind"] == "switch" else [info["option"], flag_text(info, value)]
    return run(cli, tmp_path, args, values)


def settings_file(cli, tmp_path, values):
    path = tmp_path / "given.json"
    path.write_text(json.dumps({SCHEMA[n]["key"]: json_value(SCHEMA[n], v) for n, v in values.items()}))
    return run(cli, tmp_path, ["--settings", str(path)], values)


def words(message):
    """What a refusal says after naming the settings: from "is not" for a value, else after the
    first ': ' (the names and values before it are spelt as each front end spells them)."""
    if " is not " in message:
        return message[message.index(" is not "):]
    return message.split(": ", 1)[1]


def check(cli, tmp_path, values):
    expected, refused = python(values)
    if expected is not None and "size" not in values:
        expected = frugal.settings(**values, size=(8, 8))
    for name, (got, error) in (("command line", command_line(cli, tmp_path, values)),
                               ("settings file", settings_file(cli, tmp_path, values))):
        if refused is None:
            assert error is None, f"{values}: Python takes them, the {name} refuses: {error}"
            assert got == expected, f"{values}: the {name} gave other settings"
        else:
            assert error is not None, f"{values}: Python refuses them ({refused}), the {name} takes them"
            assert words(error) == words(refused), f"{values}: {name}: {error!r} against Python's {refused!r}"
    return refused


def flag_settings():
    return [name for name, info in SCHEMA.items() if info["option"]]


@pytest.mark.parametrize("name", flag_settings())
def test_every_value_round_trips_or_is_refused_alike(cli, tmp_path, name):
    info = SCHEMA[name]
    for value in samples(info):
        check(cli, tmp_path, {name: value})
    bad = out_of_range(info)
    if bad is not None:
        assert check(cli, tmp_path, {name: bad}) is not None, f"{name}={bad!r} was taken"


def test_every_conflict_is_refused_alike_in_all_three(cli, tmp_path):
    pairs = {tuple(sorted((name, other))) for name, info in SCHEMA.items() for other in info["conflicts"]}
    assert pairs, "the schema declares conflicts"
    refused = set()
    for first, second in sorted(pairs):
        for a, b in itertools.product(samples(SCHEMA[first]), samples(SCHEMA[second])):
            if check(cli, tmp_path, {first: a, second: b}) is not None:
                refused.add((first, second))
    assert refused == pairs, f"conflicts never met: {pairs - refused}"


def test_ids_is_a_setting_of_files_and_python_only(cli, tmp_path):
    info = SCHEMA["ids"]
    assert info["option"] is None and info["kind"] == "switch"
    path = tmp_path / "ids.json"
    path.write_text('{"ids": true}')
    assert frugal.settings(settings=str(path))["ids"] is True
    assert frugal.settings(ids=True)["ids"] is True


def test_the_schema_is_what_the_renderer_takes():
    assert list(SCHEMA) == frugal.settings_names()
    assert {n: s["default"] for n, s in SCHEMA.items()} == frugal.default_settings()
