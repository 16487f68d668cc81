#!/usr/bin/env bash
# Configures and builds the project into build/ (after scripts/setup.sh).
# Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DPython3_EXECUTABLE="$root/.venv/bin/python" "$@" >/dev/null
cmake --build build -j "$(nproc)"
