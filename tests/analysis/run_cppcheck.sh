#!/usr/bin/env bash
# cppcheck with its MISRA C 2012 addon over core/ (ctest analysis_cppcheck).
# Every finding must be covered by a row of docs/misra-deviations.md (rule, file, count,
# reason); anything beyond is a new finding and fails the test. The MISRA rule texts
# are not available, so findings carry rule numbers only. A planted violation
# (canary/misra_canary.c) must be reported, or the addon is not working.
# Usage: run_cppcheck.sh SOURCE_ROOT WORK_DIR [PYTHON]
set -euo pipefail
root=$1
work=$2
python=${3:-python3}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
command -v cppcheck >/dev/null || { echo "cppcheck not installed (scripts/setup.sh installs it)"; exit 1; }
rm -rf "$work" && mkdir -p "$work/build" "$work/canary-build"
echo "$(cppcheck --version), MISRA C 2012 addon"

common=(--addon=misra --std=c99 --enable=warning,style,performance,portability
        --suppress=missingIncludeSystem
        --template='{file}:{line}:{severity}:{id}:{message}')

# The canary first: it proves the addon runs and reports.
cppcheck "${common[@]}" --cppcheck-build-dir="$work/canary-build" \
    --output-file="$work/canary.txt" "$here/canary/misra_canary.c" >/dev/null
if ! grep -q 'misra-c2012-15.5' "$work/canary.txt"; then
    echo "FAIL: the MISRA addon did not report the planted rule 15.5 violation:"
    cat "$work/canary.txt"
    exit 1
fi

# The core, in the default profile's configuration (one configuration, as built).
cd "$root"
cppcheck "${common[@]}" --cppcheck-build-dir="$work/build" --output-file="$work/findings.txt" \
    -Icore/include -Icore/src -Icore/profiles '-DSVA_CONFIG_HEADER="sva_profile_default.h"' \
    core/src/*/*.c core/src/*.c >/dev/null
"$python" "$here/check_deviations.py" "$work/findings.txt" "$root/docs/misra-deviations.md"
