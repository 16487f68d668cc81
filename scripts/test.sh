#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs every ctest test.
# Run one part with e.g.: scripts/test.sh -L core   (arguments go to ctest)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/build.sh
cd build
ctest --output-on-failure -j "$(nproc)" "$@"
