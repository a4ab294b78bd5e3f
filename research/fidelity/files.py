"""Writing output files: whole or not at all, and JSON a person can read in a diff."""

import json
import os


def write_atomic(path, data):
    """Writes bytes to path through a temporary file, so that no reader sees half a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp-%d" % os.getpid())
    tmp.write_bytes(data)
    os.replace(tmp, path)


def json_text(value, indent=""):
    """JSON with one key per line, but lists of numbers on one line (cameras, bounds)."""
    step = indent + "  "
    if isinstance(value, dict) and value:
        items = ",\n".join("%s%s: %s" % (step, json.dumps(k), json_text(v, step))
                           for k, v in value.items())
        return "{\n%s\n%s}" % (items, indent)
    if isinstance(value, list) and value and not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        return "[\n%s\n%s]" % (",\n".join(step + json_text(v, step) for v in value), indent)
    return json.dumps(value, separators=(", ", ": "))
