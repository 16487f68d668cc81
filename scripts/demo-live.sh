#!/usr/bin/env bash
# A live mission flown by the simulator and steered by the on-board planner: builds the
# C CLI, flies a bundled scenario (docs/live.md), prints the timeline of events and
# replans, and writes the flight log and its picture under build/demo-live/.
# Usage: scripts/demo-live.sh [SCENARIO.json] [ALGORITHM]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
scenario=${1:-fixtures/scenarios/hand_events.json}
algo=${2:-sva}
scripts/build.sh >/dev/null
out=build/demo-live
mkdir -p "$out"
name=$(basename "$scenario" .json)
tools/sva-tools sim --algo "$algo" --timeline --out "$out/$name.log.json" \
    --plot "$out/$name.png" "$scenario"
echo "flight log: $out/$name.log.json"
echo "picture:    $out/$name.png"
