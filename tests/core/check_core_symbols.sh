#!/usr/bin/env bash
# Fails when the built core library needs any symbol outside a short allow-list:
# no allocator, no stdio, no libm and no soft-float helper can sneak in.
set -u
lib=${1:?usage: check_core_symbols.sh LIBSVA_CORE}
# strlen: GCC at -O2 and above (CMAKE_BUILD_TYPE Release) makes one of the diagnostic
# writer's string loop (core/src/model/diag.c).
allowed='^(memset|memcpy|memmove|strlen|__assert_fail|__stack_chk_fail)$'
# Undefined in some member and defined in none: what the library needs from outside.
defined=$(nm --defined-only "$lib" | awk 'NF == 3 {print $3}' | sort -u)
undefined=$(nm -u "$lib" | awk 'NF == 2 && $1 == "U" {print $2}' | sort -u |
            comm -23 - <(printf '%s\n' "$defined"))
bad=$(printf '%s\n' "$undefined" | grep -v '^$' | grep -vE "$allowed")
if [ -n "$bad" ]; then
    echo "core library needs symbols outside the allow-list:"
    echo "$bad"
    exit 1
fi
echo "undefined symbols of $(basename "$lib"): $(printf '%s ' $undefined)(all allowed)"
