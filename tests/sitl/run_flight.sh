#!/usr/bin/env bash
# Runs the SITL flight tests (pytest ARGS...) when they can run: as root (the tool makes
# a network namespace) with ArduCopter SITL at ../shared/sitl/arducopter (or $SVA_SITL).
# Otherwise exits 77 (ctest SKIP_RETURN_CODE) with the reason.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
sitl=${SVA_SITL:-$here/../../../shared/sitl/arducopter}
if [ ! -x "$sitl" ]; then
    echo "tests/sitl: skipped: no ArduCopter SITL binary at $sitl (set SVA_SITL)" >&2
    exit 77
fi
if [ "$(id -u)" -ne 0 ] || ! command -v ip >/dev/null; then
    echo "tests/sitl: skipped: needs root and iproute2 (the flight runs in a network namespace)" >&2
    exit 77
fi
export SVA_SITL="$sitl"
exec "$@"
