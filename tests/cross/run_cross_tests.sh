#!/usr/bin/env bash
# Runs a selection of a cross sub-build's ctest tests (tests/cross/CMakeLists.txt).
# The sub-build's tests already run under qemu-user (CMAKE_CROSSCOMPILING_EMULATOR);
# this script first checks that qemu can start a program of that architecture at all.
# Exit 77 (ctest: skipped) only when it cannot: that is a limit of the kernel or of
# the sandbox, not of the project. Anything else that goes wrong is a failure.
# Usage: run_cross_tests.sh CTEST QEMU SYSROOT SUBBUILD CTEST_ARGS...
set -uo pipefail
ctest=${1:?CTEST}; qemu=${2:?QEMU}; sysroot=${3:?SYSROOT}; subbuild=${4:?SUBBUILD}; shift 4

if [ ! -f "$subbuild/CTestTestfile.cmake" ]; then
    echo "cross: $subbuild is not built (the cross_* targets of the main build make it)" >&2
    exit 1
fi
# The dynamic loader of the target's C library is a program qemu can always run.
loader=$(ls "$sysroot"/lib/ld-linux*.so.* "$sysroot"/lib/ld.so.1 2>/dev/null | head -n 1)
if [ -z "$loader" ]; then
    echo "cross: no dynamic loader in $sysroot/lib (is libc6-dev-*-cross installed?)" >&2
    exit 1
fi
if ! probe=$("$qemu" -L "$sysroot" "$loader" --version 2>&1); then
    echo "cross: SKIP: $qemu cannot start $loader on this kernel:" >&2
    printf '%s\n' "$probe" | head -n 5 >&2
    exit 77
fi
echo "cross: $(basename "$qemu") runs $(basename "$loader") ($(printf '%s' "$probe" | head -n 1))"
cd "$subbuild" && exec "$ctest" --output-on-failure --no-tests=error "$@"
