#!/usr/bin/env bash
# The Python lint test: ruff and mypy over tools/sva_tools with the settings of
# tools/pyproject.toml, the venv's pinned binaries. First a planted file with a lint
# defect (an unused import) and a type error (a str returned as an int) must be rejected
# by each, so a tool that checks nothing (or a lost configuration) cannot pass.
# Usage: check_lint.sh SOURCE_ROOT WORK_DIR PYTHON
set -euo pipefail
root=$1
work=$2
bin=$(dirname "$3")
ruff=$bin/ruff
mypy=$bin/mypy
for tool in "$ruff" "$mypy"; do
    [ -x "$tool" ] || { echo "FAIL: $tool is missing (scripts/setup.sh installs requirements.txt)"; exit 1; }
done
"$ruff" --version
"$mypy" --version
rm -rf "$work" && mkdir -p "$work/canary"

# The canaries, checked with the tools' configuration.
cp "$root/tools/pyproject.toml" "$work/canary/pyproject.toml"
cat >"$work/canary/canary.py" <<'PY'
"""A planted lint defect and a planted type error."""
from __future__ import annotations

import os


def count(text: str) -> int:
    return text
PY
if (cd "$work/canary" && "$ruff" check --no-cache canary.py) >"$work/ruff-canary.txt" 2>&1; then
    echo "FAIL: ruff accepted the planted unused import in canary.py"
    exit 1
fi
grep -q 'F401' "$work/ruff-canary.txt" || { echo "FAIL: ruff did not report F401 in canary.py:"; cat "$work/ruff-canary.txt"; exit 1; }
echo "canary: ruff rejects an unused import"
if (cd "$work/canary" && "$mypy" --cache-dir "$work/mypy-cache-canary" canary.py) >"$work/mypy-canary.txt" 2>&1; then
    echo "FAIL: mypy accepted the planted type error in canary.py"
    exit 1
fi
grep -q 'canary.py:8: error: .*\[return-value\]' "$work/mypy-canary.txt" || {
    echo "FAIL: mypy did not report the return-value error in canary.py:"; cat "$work/mypy-canary.txt"; exit 1; }
echo "canary: mypy rejects a str returned as an int"

# The tree.
cd "$root/tools"
"$ruff" check --no-cache sva_tools
"$mypy" --cache-dir "$work/mypy-cache"
