#!/usr/bin/env bash
# The main job: build, plan a bundled mission and print the schedule.
# Usage: scripts/demo.sh [MISSION.json] [ALGORITHM]
#        scripts/demo.sh --live [SCENARIO.json] [ALGORITHM]   (scripts/demo-live.sh)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
if [ "${1:-}" = "--live" ]; then
    shift
    exec scripts/demo-live.sh "$@"
fi
mission=${1:-fixtures/missions/hand_5_3.json}
algo=${2:-sva}
scripts/build.sh >/dev/null
build/bin/sva plan --algo "$algo" --schedule "$mission"
