#!/usr/bin/env bash
# Create .venv at the repository root and install urdf-lint with its test tools.
# Idempotent and quiet: safe to run before every command.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
stamp=.venv/.urdf-lint-installed
want=$(cat pyproject.toml | (sha256sum 2>/dev/null || shasum -a 256) | cut -c1-16)
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  log=$(mktemp)
  if ! { .venv/bin/python -m pip install -q --upgrade pip &&
         .venv/bin/python -m pip install -q -e '.[test,render,server]'; } >"$log" 2>&1; then
    cat "$log" >&2
    echo "bootstrap: installation failed" >&2
    exit 1
  fi
  rm -f "$log"
  echo "$want" > "$stamp"
fi
