#!/usr/bin/env bash
# The format test: every C file of the project follows .clang-format. First a planted,
# badly formatted file must be caught, so a clang-format that checks
# nothing (or a missing .clang-format) cannot pass.
# Usage: check_format.sh SOURCE_ROOT WORK_DIR
set -euo pipefail
root=$1
work=$2
fmt=${CLANG_FORMAT:-clang-format}
command -v "$fmt" >/dev/null || { echo "FAIL: $fmt not installed (scripts/setup.sh installs clang-format)"; exit 1; }
"$fmt" --version
mkdir -p "$work"
cp "$root/.clang-format" "$work/.clang-format"
# The canary: a function in the wrong style (tabs, braces, one-line if).
printf 'int canary(int* p){\n\tif (p == 0) return 0;\n\treturn *p;}\n' >"$work/canary.c"
if (cd "$work" && "$fmt" --style=file --dry-run --Werror canary.c >/dev/null 2>&1); then
    echo "FAIL: clang-format accepted the planted unformatted canary.c"
    exit 1
fi
echo "canary: clang-format rejects an unformatted file"
exec "$root/scripts/format.sh" --check
