"""Every ```python block of README.md and docs/python.md runs as written (in a folder of its own,
with this module), so the documentation cannot drift from the module."""
import re
import runpy
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BLOCKS = [(page, i, code) for page in ("README.md", "docs/python.md")
          for i, code in enumerate(re.findall(r"```python\n(.*?)```", (ROOT / page).read_text(), re.S))]


@pytest.mark.parametrize("page, index, code", BLOCKS, ids=[f"{p}#{i}" for p, i, _ in BLOCKS])
def test_example_runs(tmp_path, monkeypatch, bunny, page, index, code):
    monkeypatch.chdir(tmp_path)
    script = tmp_path / "example.py"
    script.write_text(code)
    runpy.run_path(str(script), run_name="__main__")
    written = [p for p in tmp_path.iterdir() if p.suffix == ".png"]
    assert all(p.stat().st_size > 0 for p in written)


def test_readme_has_a_python_example():
    assert any(page == "README.md" for page, _, _ in BLOCKS)
