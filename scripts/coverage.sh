#!/usr/bin/env bash
# Line and branch coverage of core/ over the core tests (`ctest -L core`, but for the
# symbol allow-list check), with gcc
# --coverage and lcov, in its own build directory (build-coverage/; the main build
# stays as it is). Prints the lcov summary and the per-file table of core/; the HTML
# report goes to build-coverage/coverage-html/.
# Usage: scripts/coverage.sh            (after scripts/setup.sh; lcov is in apt.txt)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scripts/setup.sh
out=build-coverage
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
unity=()  # Unity's release beside the checkout, for builds without internet
if [ -f "$root/../shared/unity/src/unity.c" ]; then
    unity=(-DFETCHCONTENT_SOURCE_DIR_UNITY="$(cd "$root/../shared/unity" && pwd)")
fi
cmake -S . -B "$out" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS="--coverage -O0" \
      -DSVA_BUILD_PORTS=OFF -DSVA_SANITIZE_TESTS=OFF "${unity[@]}" >/dev/null
cmake --build "$out" -j "$jobs" >/dev/null
lcov_rc=(--rc lcov_branch_coverage=1)
lcov "${lcov_rc[@]}" --quiet --zerocounters --directory "$out"
# core_purity_symbols is left out: the instrumented library needs the gcov runtime's
# symbols, which its allow-list rightly refuses.
(cd "$out" && ctest -L core -E '^core_purity_symbols$' -j "$jobs" --output-on-failure >/dev/null)
# lcov 1.16 with perl 5.36 prints "Subroutine ... redefined" warnings: dropped.
lcov "${lcov_rc[@]}" --quiet --capture --directory "$out" --output-file "$out/all.info" 2>&1 |
    grep -v "redefined at" || true
lcov "${lcov_rc[@]}" --quiet --extract "$out/all.info" "$root/core/*" --output-file "$out/core.info"
echo "coverage of core/ by ctest -L core ($(lcov --version | sed 's/.*: //'), $(gcc --version | head -1)):"
lcov "${lcov_rc[@]}" --list "$out/core.info" | sed "s|$root/||"
lcov "${lcov_rc[@]}" --summary "$out/core.info" 2>&1 | grep -E 'lines|functions|branches'
genhtml "${lcov_rc[@]}" --quiet --output-directory "$out/coverage-html" "$out/core.info" >/dev/null
echo "HTML report: $out/coverage-html/index.html"
