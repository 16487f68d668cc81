#!/usr/bin/env bash
# Installs what the project needs and is missing: Debian packages listed in
# scripts/deps/apt.txt and a Python venv (.venv) with the pinned requirements.txt.
# Safe to run again: it installs nothing that is already there.
# Usage: scripts/setup.sh            (as root on Debian, or with sudo available)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

log() { printf 'setup: %s\n' "$*" >&2; }

# --- Debian packages -------------------------------------------------------------
mapfile -t wanted < <(sed -e 's/#.*//' -e 's/[[:space:]]//g' scripts/deps/apt.txt | grep -v '^$')
missing=()
for pkg in "${wanted[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed'; then
        missing+=("$pkg")
    fi
done
if [ ${#missing[@]} -gt 0 ]; then
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
    log "installing Debian packages: ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# --- Python venv -----------------------------------------------------------------
venv="$root/.venv"
stamp="$venv/.requirements.sha256"
want=$(sha256sum requirements.txt | cut -d' ' -f1)
if [ ! -x "$venv/bin/python" ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
    log "creating Python venv in .venv from requirements.txt"
    if [ ! -x "$venv/bin/python" ]; then
        python3 -m venv "$venv"
    fi
    "$venv/bin/pip" install -q --disable-pip-version-check -r requirements.txt
    if [ -f tools/pyproject.toml ]; then
        "$venv/bin/pip" install -q --disable-pip-version-check --no-deps -e tools
    fi
    echo "$want" > "$stamp"
fi
# The host tools (tools/pyproject.toml) into an existing venv that predates them.
if [ -f tools/pyproject.toml ] && [ ! -x "$venv/bin/sva-tools" ]; then
    log "installing the host tools (tools/) into .venv"
    "$venv/bin/pip" install -q --disable-pip-version-check --no-deps -e tools
fi
