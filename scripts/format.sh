#!/usr/bin/env bash
# Formats every C source and header of the project with the checked-in .clang-format.
# Usage: scripts/format.sh          (rewrites files in place)
#        scripts/format.sh --check  (changes nothing; lists unformatted files, exit 1)
# The `format` test runs the check; clang-format comes from scripts/deps/apt.txt.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
fmt=${CLANG_FORMAT:-clang-format}
command -v "$fmt" >/dev/null || { echo "format: $fmt not installed (scripts/setup.sh installs clang-format)" >&2; exit 1; }
# The project's own C: every part's sources, not build trees or generated code.
mapfile -t files < <(find core port tools tests examples -type f \( -name '*.c' -o -name '*.h' \) \
                     -not -path '*/build*/*' | sort)
if [ "${1:-}" = "--check" ]; then
    bad=()
    for f in "${files[@]}"; do
        if ! "$fmt" --style=file --dry-run --Werror "$f" >/dev/null 2>&1; then
            bad+=("$f")
        fi
    done
    if [ ${#bad[@]} -gt 0 ]; then
        printf 'format: %d of %d C files differ from .clang-format (run scripts/format.sh):\n' \
            "${#bad[@]}" "${#files[@]}"
        printf '  %s\n' "${bad[@]}"
        exit 1
    fi
    printf 'format: %d C files follow .clang-format\n' "${#files[@]}"
else
    "$fmt" --style=file -i "${files[@]}"
    printf 'format: %d C files formatted\n' "${#files[@]}"
fi
