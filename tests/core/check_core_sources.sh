#!/usr/bin/env bash
# Fails when a core source allocates, prints, includes stdio or names a float type.
# A deliberate exception must carry a greppable "DEVIATION(" comment on its line.
set -u
core=${1:?usage: check_core_sources.sh CORE_DIR}
pattern='\b(malloc|calloc|realloc|free|printf|fprintf|sprintf|snprintf|puts|putchar)[[:space:]]*\(|#[[:space:]]*include[[:space:]]*<(stdio|stdlib|math|float)\.h>|\b(float|double)\b'
hits=$(grep -rnE "$pattern" "$core" --include='*.c' --include='*.h' | grep -v 'DEVIATION(')
if [ -n "$hits" ]; then
    echo "core/ must not allocate, print or use floating point:"
    echo "$hits"
    exit 1
fi
count=$(find "$core" -name '*.[ch]' | wc -l)
echo "checked $count core files: no heap, stdio or floating point"
