#!/usr/bin/env bash
# The main job: install what it needs (a C compiler, CMake, Ninja, pkg-config, jansson,
# PROJ: scripts/deps/apt-demo.txt; no Python), build the sva CLI alone, plan a bundled
# mission and print the schedule. One line per step on stderr.
# Usage: scripts/demo.sh [MISSION.json] [ALGORITHM]
#        scripts/demo.sh --live [SCENARIO.json] [ALGORITHM]   (scripts/demo-live.sh; adds
#        Python and a small venv, scripts/deps/apt-live.txt and requirements-live.txt)
#        scripts/demo.sh --sitl [SCENARIO.json] [ALGORITHM]   (root: flies the scenario,
#        by default fixtures/scenarios/sitl_3uav.json, three vehicles and one loss, with
#        ArduCopter SITL from ../shared/sitl or $SVA_SITL; docs/sitl.md)
# The build goes to build/ (or $SVA_BUILD_DIR).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
if [ "${1:-}" = "--live" ]; then
    shift
    printf 'demo: live mission (setup part live, then scripts/demo-live.sh)\n' >&2
    # the simulator finds the CLI through SVA_BIN when the build is not in build/
    export SVA_BIN=${SVA_BIN:-$root/${SVA_BUILD_DIR:-build}/bin/sva}
    SVA_SETUP_PART=live exec scripts/demo-live.sh "$@"
fi
if [ "${1:-}" = "--sitl" ]; then
    shift
    scenario=${1:-fixtures/scenarios/sitl_3uav.json}
    algo=${2:-sva}
    build=${SVA_BUILD_DIR:-build}
    printf 'demo: flight in ArduCopter SITL (setup part flight, then sva-tools sitl)\n' >&2
    SVA_SETUP_PART=flight scripts/build.sh >/dev/null
    printf 'demo: flying %s with %s (sva-tools sitl, plot in %s/sitl_demo.png)\n' \
        "$scenario" "$algo" "$build" >&2
    export SVA_BIN="$root/$build/bin/sva" SVA_NODE="$root/$build/bin/sva_node" \
        SVA_MAVLINK_BRIDGE="$root/$build/bin/sva_mavlink_bridge" \
        SVA_LCM_PYTHON_TYPES="$root/$build/port/lcm/python"
    exec .venv/bin/python -m sva_tools sitl "$scenario" --algo "$algo" --plot "$build/sitl_demo.png"
fi
mission=${1:-fixtures/missions/hand_5_3.json}
algo=${2:-sva}
build=${SVA_BUILD_DIR:-build}
SVA_SETUP_PART=demo scripts/build.sh >/dev/null
printf 'demo: planning %s with %s (%s/bin/sva plan --schedule)\n' "$mission" "$algo" "$build" >&2
"$build/bin/sva" plan --algo "$algo" --schedule "$mission"
