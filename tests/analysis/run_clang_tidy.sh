#!/usr/bin/env bash
# clang-tidy over core/src/*.c with the checked-in .clang-tidy (every warning an error),
# compiled as the default profile builds it (ctest analysis_clang_tidy). A planted
# defect (canary/tidy_canary.c) must be rejected first, or clang-tidy checks nothing.
# Usage: run_clang_tidy.sh SOURCE_ROOT [CLANG_TIDY]
set -euo pipefail
root=$1
tidy=${2:-clang-tidy}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
command -v "$tidy" >/dev/null || { echo "$tidy not installed (scripts/setup.sh installs clang-tidy)"; exit 1; }
cd "$root"
"$tidy" --version | grep -i version
flags=(-std=c99 -Icore/include -Icore/src -Icore/profiles '-DSVA_CONFIG_HEADER="sva_profile_default.h"')

canary=$("$tidy" --quiet --config-file="$root/.clang-tidy" "$here/canary/tidy_canary.c" -- -std=c99 2>&1) &&
    { echo "FAIL: clang-tidy accepted the planted defects in canary/tidy_canary.c"; exit 1; }
for check in misc-no-recursion clang-analyzer-security.insecureAPI.strcpy; do
    if ! grep -q "\[$check,-warnings-as-errors\]" <<<"$canary"; then
        echo "FAIL: clang-tidy did not report $check as an error in canary/tidy_canary.c:"
        echo "$canary"
        exit 1
    fi
done

# clang-tidy prints "N warnings generated." for the (filtered) system-header warnings.
status=0
for src in core/src/*.c; do
    out=$("$tidy" --quiet --config-file="$root/.clang-tidy" "$src" -- "${flags[@]}" 2>&1) || status=1
    grep -v '^[0-9]* warnings\? generated\.$' <<<"$out" || true
done
if [ "$status" -ne 0 ]; then
    echo "FAIL: clang-tidy findings in core/ (fix them, or exclude the check in .clang-tidy with a reason)"
else
    echo "clang-tidy: 0 findings in $(ls core/src/*.c | wc -l) files of core/src"
fi
exit "$status"
