#!/usr/bin/env bash
# clang-tidy over core/src/*/*.c and core/src/*.c with the checked-in .clang-tidy
# (every warning an error), compiled as the default profile builds it (ctest
# analysis_clang_tidy). A planted defect (canary/tidy_canary.c) must be rejected first, or clang-tidy checks nothing.
# Usage: run_clang_tidy.sh SOURCE_ROOT WORK_DIR [PYTHON] [CLANG_TIDY]
set -euo pipefail
root=$1
work=$2
python=${3:-python3}
tidy=${4:-clang-tidy}
mkdir -p "$work"
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

# Every finding is an error; each must be listed in docs/misra-deviations.md (its
# "open findings" table, id clang-tidy/<check>) or the test fails. A clang-tidy run
# that fails without a finding (e.g. a compile error) fails the test by itself.
status=0
findings="$work/findings.txt"
: >"$findings"
for src in core/src/*/*.c core/src/*.c; do
    rc=0
    out=$("$tidy" --quiet --config-file="$root/.clang-tidy" "$src" -- "${flags[@]}" 2>&1) || rc=$?
    grep -v '^[0-9]* warnings\? generated\.$' <<<"$out" | grep -E ': (error|warning): ' || true
    parsed=$(sed -n -E "s|^$root/([^:]+):([0-9]+):[0-9]+: error: (.*) \[([^],]+)(,-warnings-as-errors)?\]$|\1:\2:error:clang-tidy/\4:\3|p" <<<"$out")
    if [ -n "$parsed" ]; then
        echo "$parsed" >>"$findings"
    elif [ "$rc" -ne 0 ]; then
        echo "$out"
        echo "FAIL: clang-tidy failed on $src without a finding"
        status=1
    fi
done
if ! "$python" "$here/check_deviations.py" "$findings" "$root/docs/misra-deviations.md"; then
    status=1
fi
echo "clang-tidy: $(wc -l <"$findings") findings in $(ls core/src/*/*.c core/src/*.c | wc -l) files of core/src"
exit "$status"
