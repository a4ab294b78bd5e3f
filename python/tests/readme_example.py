"""Prints the README's Python example: the first ```python block of the file named on the command
line (the test of `pip install .` runs it as written)."""
import re
import sys
from pathlib import Path

blocks = re.findall(r"```python\n(.*?)```", Path(sys.argv[1]).read_text(), re.S)
if not blocks:
    sys.exit(f"error: {sys.argv[1]}: no ```python block")
print(blocks[0], end="")
