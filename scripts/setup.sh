#!/usr/bin/env bash
# Installs what a part of the project needs and is missing, one line per step on stderr.
# Safe to run again: it installs nothing that is already there.
# Usage: scripts/setup.sh [--part demo|live|flight|all]   (as root on Debian, or with sudo)
#   demo  the sva CLI's build: scripts/deps/apt-demo.txt; no Python
#   live  the live demo: demo + scripts/deps/apt-live.txt and a venv (.venv) from
#         scripts/deps/requirements-live.txt with the host tools (tools/)
#   flight  the flight demo: live + scripts/deps/apt-flight.txt and
#         scripts/deps/requirements-flight.txt (LCM, pymavlink, pymap3d)
#   all   (default) the whole build and test suite: demo + live + scripts/deps/apt.txt
#         and the venv from the pinned requirements.txt
# The part may also come from $SVA_SETUP_PART (scripts/demo.sh --live sets it).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

log() { printf 'setup: %s\n' "$*" >&2; }
die() { printf 'setup: error: %s\n' "$*" >&2; exit 2; }

part=${SVA_SETUP_PART:-all}
while [ $# -gt 0 ]; do
    case "$1" in
        --part) [ $# -ge 2 ] || die "--part needs a value (demo, live, flight or all)"; part=$2; shift 2 ;;
        --part=*) part=${1#--part=}; shift ;;
        -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) die "unknown argument \"$1\" (usage: scripts/setup.sh [--part demo|live|flight|all])" ;;
    esac
done
case "$part" in
    demo) apt_files=(scripts/deps/apt-demo.txt); requirements="" ;;
    live) apt_files=(scripts/deps/apt-demo.txt scripts/deps/apt-live.txt)
          requirements=scripts/deps/requirements-live.txt ;;
    flight) apt_files=(scripts/deps/apt-demo.txt scripts/deps/apt-live.txt scripts/deps/apt-flight.txt)
          requirements=scripts/deps/requirements-flight.txt ;;
    all)  apt_files=(scripts/deps/apt-demo.txt scripts/deps/apt-live.txt scripts/deps/apt-flight.txt
                     scripts/deps/apt.txt)
          requirements=requirements.txt ;;
    *) die "unknown part \"$part\" (known: demo, live, flight, all)" ;;
esac

# --- Debian packages -------------------------------------------------------------
mapfile -t wanted < <(sed -e 's/#.*//' -e 's/[[:space:]]//g' "${apt_files[@]}" | grep -v '^$')
missing=()
for pkg in "${wanted[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed'; then
        missing+=("$pkg")
    fi
done
if [ ${#missing[@]} -gt 0 ]; then
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
    log "part $part: installing ${#missing[@]} of ${#wanted[@]} Debian packages: ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
    log "part $part: all ${#wanted[@]} Debian packages present (${apt_files[*]})"
fi

[ -n "$requirements" ] || exit 0

# --- Python venv -----------------------------------------------------------------
# One stamp per requirements file; the full venv (requirements.txt) serves every part.
venv="$root/.venv"
stamp_of() { echo "$venv/.requirements-$(basename "$1" .txt).sha256"; }
have() { [ -x "$venv/bin/python" ] && [ "$(cat "$(stamp_of "$1")" 2>/dev/null)" = "$(sha256sum "$1" | cut -d' ' -f1)" ]; }
# a venv made before the per-file stamps carries requirements.txt's as .requirements.sha256
if [ -f "$venv/.requirements.sha256" ] && [ ! -f "$(stamp_of requirements.txt)" ]; then
    cp "$venv/.requirements.sha256" "$(stamp_of requirements.txt)"
fi
if have "$requirements" || have requirements.txt; then
    log "Python venv .venv up to date ($requirements)"
else
    log "Python venv .venv: installing $requirements"
    if [ ! -x "$venv/bin/python" ]; then
        python3 -m venv "$venv"
    fi
    "$venv/bin/pip" install -q --disable-pip-version-check -r "$requirements"
    sha256sum "$requirements" | cut -d' ' -f1 > "$(stamp_of "$requirements")"
    if [ "$requirements" = requirements.txt ]; then
        cp "$(stamp_of requirements.txt)" "$venv/.requirements.sha256"
    fi
fi
# The host tools (tools/pyproject.toml), editable, into the venv; again when that file
# changes, as its entry points are written into .venv/bin/sva-tools at install time.
tools_stamp="$venv/.tools-pyproject.sha256"
if [ ! -x "$venv/bin/sva-tools" ] ||
   [ "$(cat "$tools_stamp" 2>/dev/null)" != "$(sha256sum tools/pyproject.toml | cut -d' ' -f1)" ]; then
    log "installing the host tools (tools/, editable) into .venv"
    "$venv/bin/pip" install -q --disable-pip-version-check --no-deps -e tools
    sha256sum tools/pyproject.toml | cut -d' ' -f1 > "$tools_stamp"
fi
