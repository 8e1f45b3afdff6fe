#!/usr/bin/env bash
# The supported Pythons besides the one the README's test command uses (3.11 here): for each,
# a fresh virtualenv with urdf-lint and its test tools, then a fast subset of the suite (the
# demo, expand, the sandbox, the CLI conventions, the pytest plugin, a corpus slice). Then the
# install path users take: `python -m build` makes an sdist and a wheel, the wheel is installed
# (not editable) into a fresh virtualenv, and the demo runs from it outside the checkout.
# A Python that is missing is a failure, not a skip. PYTHONS overrides the list.
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHONS=${PYTHONS:-"3.10 3.12 3.13"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

find_python() {   # python3.X on PATH (a real one, not a pyenv shim without it), else pyenv's
  local v=$1 p
  if p=$(command -v "python$v") && "$p" -c 'import sys' >/dev/null 2>&1; then
    echo "$p"; return 0
  fi
  for p in "${PYENV_ROOT:-$HOME/.pyenv}"/versions/"$v".*/bin/"python$v"; do
    if [ -x "$p" ]; then echo "$p"; return 0; fi
  done
  return 1
}

SUBSET=(tests/test_architecture.py tests/test_sandbox.py tests/test_cli_conventions.py
        tests/test_startup.py tests/test_pytest_plugin.py tests/test_expand_corpus.py
        "tests/test_accuracy.py::test_broken_demo_shows_every_class")

for v in $PYTHONS; do
  py=$(find_python "$v") || { echo "test_pythons: Python $v is not installed" >&2; exit 1; }
  echo "== Python $v ($py): fresh virtualenv, the fast subset"
  "$py" -m venv "$work/venv$v"
  if ! "$work/venv$v/bin/python" -m pip install -q -e '.[test]' >"$work/pip$v.log" 2>&1; then
    cat "$work/pip$v.log" >&2; echo "test_pythons: install failed on Python $v" >&2; exit 1
  fi
  "$work/venv$v/bin/python" -m pytest -q -p no:cacheprovider "${SUBSET[@]}"
done

echo "== the wheel: built, installed into a fresh virtualenv, the demo run from it"
rm -rf "$work/dist"
.venv/bin/python -m build -q --outdir "$work/dist" . >"$work/build.log" 2>&1 || {
  cat "$work/build.log" >&2; exit 1; }
ls "$work/dist"
wheel=$(ls "$work"/dist/urdf_lint-*.whl)
ls "$work"/dist/urdf_lint-*.tar.gz >/dev/null
py=$(find_python 3.12) || py=python3
"$py" -m venv "$work/wheel-venv"
"$work/wheel-venv/bin/python" -m pip install -q "$wheel"
cp -r descriptions "$work/demo"
set +e
( cd "$work" && "$work/wheel-venv/bin/urdf-lint" check demo ) >"$work/demo.log" 2>&1
rc=$?
set -e
tail -n 1 "$work/demo.log"
want=$(grep -o 'Found [0-9]* problem(s) ([^)]*) in [0-9]* model(s)\.' README.md | head -n 1)
if [ "$rc" != 1 ] || [ "$(tail -n 1 "$work/demo.log")" != "$want" ]; then
  cat "$work/demo.log" >&2
  echo "test_pythons: the demo from the installed wheel exited $rc and did not end with: $want" >&2
  exit 1
fi
( cd "$work" && "$work/wheel-venv/bin/urdf-lint" check demo/r2d2_description && \
  "$work/wheel-venv/bin/urdf-lint" rules >/dev/null && "$work/wheel-venv/bin/urdf-lint" doctor )
echo "test_pythons: $PYTHONS and the wheel: ok"
