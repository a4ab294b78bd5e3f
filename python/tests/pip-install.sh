#!/usr/bin/env bash
# `pip install .` as a user runs it, offline, with Debian's setuptools (no build isolation, no
# index): into a fresh venv that sees the system's numpy, packaging the module of an existing CMake
# build (FRUGAL_BUILD_DIR: nothing is compiled twice). Then `cmake --install` of the python
# component into a prefix. Each installed copy has the type stubs (_frugal.pyi, py.typed) and runs
# the README's Python example from a folder outside the source.
# usage: pip-install.sh PYTHON BUILD_DIR WORK_DIR
set -euo pipefail
python=$1 build=$(realpath "$2") work=$3
source_dir=$(realpath "$(dirname "$0")/../..")
rm -rf "$work" && mkdir -p "$work/run"
work=$(realpath "$work")

"$python" -m venv --system-site-packages "$work/venv"
FRUGAL_BUILD_DIR="$build" "$work/venv/bin/pip" install -q --no-build-isolation --no-index "$source_dir"
example="$work/readme_example.py"
"$python" "$source_dir/python/tests/readme_example.py" "$source_dir/README.md" > "$example"
(cd "$work/run" && "$work/venv/bin/python" "$example")
test -s "$work/run/bunny.png" || { echo "error: the README's example wrote no bunny.png" >&2; exit 1; }
"$work/venv/bin/python" -c 'import frugal, sys; sys.exit(0 if frugal.__file__.startswith(sys.prefix) else 1)'
# The type stubs and their marker (PEP 561) are installed beside the extension, by both.
installed=$("$work/venv/bin/python" -c 'import frugal, os; print(os.path.dirname(frugal.__file__))')
for f in _frugal.pyi py.typed; do
  test -f "$installed/$f" || { echo "error: pip install put no $f in $installed" >&2; exit 1; }
done

cmake --install "$build" --component python --prefix "$work/prefix" > /dev/null
site=$(cd "$work/prefix" && find . -name __init__.py -path '*frugal*' -printf '%h\n' | head -1)
[ -n "$site" ] || { echo "error: cmake --install put no frugal package under $work/prefix" >&2; exit 1; }
for f in _frugal.pyi py.typed; do
  test -f "$work/prefix/$site/$f" || { echo "error: cmake --install put no $f in $work/prefix/$site" >&2; exit 1; }
done
rm -f "$work/run/bunny.png"
(cd "$work/run" && PYTHONPATH="$work/prefix/$(dirname "$site")" "$python" "$example")
test -s "$work/run/bunny.png"
echo "pip install and cmake --install: the README's example ran from both"
