#!/usr/bin/env bash
# The type stubs (python/frugal/_frugal.pyi, with py.typed) against the module built, with Debian's
# mypy (python3-mypy): stubtest finds every name, class, method and property of the module in the
# stubs and the reverse, of the same kind (pybind11's functions have no signature it can read, so
# arguments are python/tests/test_stubs.py's to check against the schema). Then mypy --strict on a
# typed example (typed_example.py, which then runs) and on the README's Python example, and on
# misuses it must refuse: a choice that is not one, a keyword that is not a setting, a float taken
# for an int, an optional part used without a check.
# usage: check-stubs.sh PYTHON BUILD_DIR WORK_DIR
# Exit status: 0 pass, 1 fail, 3 no mypy (a skip, unless FRUGAL_TEST_STRICT=1).
set -euo pipefail
python=$1 build=$(realpath "$2") work=$3
tests=$(realpath "$(dirname "$0")")
if ! "$python" -c "import mypy.stubtest" 2>/dev/null; then
  echo "no mypy for $python (Debian python3-mypy: scripts/install-deps --tests)" >&2
  [ "${FRUGAL_TEST_STRICT:-}" = 1 ] && { echo "error: FRUGAL_TEST_STRICT=1: a skip is a failure here" >&2; exit 1; }
  exit 3
fi
rm -rf "$work" && mkdir -p "$work"
work=$(realpath "$work")
cd "$work"
# The package as built: the extension, __init__.py, the stubs and py.typed (python/CMakeLists.txt).
for f in __init__.py _frugal.pyi py.typed; do
  test -f "$build/python/frugal/$f" || { echo "error: $build/python/frugal/$f is missing" >&2; exit 1; }
done
export PYTHONPATH="$build/python" MYPYPATH="$build/python" PYTHONDONTWRITEBYTECODE=1
mypy=("$python" -m mypy --strict --no-error-summary --cache-dir "$work/mypy-cache")

"$python" -m mypy.stubtest --concise --allowlist "$tests/stubtest-allowlist.txt" frugal  # and frugal._frugal
echo "stubtest: the stubs and the module have the same names, of the same kinds"

"$python" "$tests/readme_example.py" "$tests/../../README.md" > readme_example.py
"${mypy[@]}" "$tests/typed_example.py" readme_example.py
"$python" "$tests/typed_example.py" > /dev/null
echo "mypy --strict: the typed example and the README's example check; the typed example runs"

cat > misuse.py <<'PY'
import frugal

scene = frugal.load("builtin:cubes")
frugal.Renderer(scene, cull="nope")
frugal.Renderer(scene, sise=(64, 48))
frugal.Renderer(scene, threads=1.5)
pvs: int = frugal.Renderer(scene).render().stats.cull.pvs
draws: str = frugal.Renderer(scene).render().stats.state_changes.draws
PY
if "${mypy[@]}" misuse.py > misuse.txt 2>&1; then
  echo "error: mypy took misuse.py:" >&2; cat misuse.py >&2; exit 1
fi
for expected in 'misuse.py:4: error: Argument "cull" to "Renderer" has incompatible type' \
                'misuse.py:5: error: Unexpected keyword argument "sise" for "Renderer"' \
                'misuse.py:6: error: Argument "threads" to "Renderer" has incompatible type "float"' \
                'misuse.py:7: error: Item "None" of "Optional[CullStats]" has no attribute "pvs"' \
                'misuse.py:8: error: Incompatible types in assignment (expression has type "int", variable has type "str")'; do
  grep -qF "$expected" misuse.txt || { echo "error: mypy did not say: $expected" >&2; cat misuse.txt >&2; exit 1; }
done
echo "mypy --strict: each misuse refused ($(grep -c ': error:' misuse.txt) errors)"
