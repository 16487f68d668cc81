#!/usr/bin/env bash
# Instructions per plan: valgrind's callgrind counts the instructions executed inside
# sva_plan() (--toggle-collect=sva_plan: no process start-up, no JSON) for one plan
# of each mission, on the paper's sizes, and estimates the time on a 168 MHz
# Cortex-M4. A figure printer, not a test. Counts are exact and repeatable for a
# given binary; the Cortex-M4 time is an estimate (see the CPI note it prints).
#
# Usage: scripts/instructions.sh [MISSIONS_PER_SIZE]     (default 5)
# Environment:
#   SVA_ALGOS   algorithms, as the CLI's --algo names (default: sva ga hga bfa flow)
#   SVA_CPI     cycles per instruction assumed on the Cortex-M4 (default 1.5)
#   SVA_SIZES   "TARGETSxUAVS ..." (default: the paper's 3x3 5x3 7x5 10x5 25x5)
#   SVA_SEED    generator seed (default 2024)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

per_size=${1:-5}
algos=${SVA_ALGOS:-sva ga hga bfa flow}
cpi=${SVA_CPI:-1.5}
sizes=${SVA_SIZES:-3x3 5x3 7x5 10x5 25x5}
seed=${SVA_SEED:-2024}
mhz=168

scripts/build.sh >/dev/null
out=build/instructions
rm -rf "$out"
mkdir -p "$out/missions" "$out/callgrind"

# Two builds of the CLI: the host's (x86-64, build/bin/sva) and a static 32-bit i686
# one. A Cortex-M4 is a 32-bit machine: the core's int64_t arithmetic takes two or
# more instructions there as on i686, so the i686 count is the basis of the estimate.
# (-O2 as the host build; the firmware example uses -Os.)
declare -A cli=([x86-64]=build/bin/sva)
prefix=build/cross/i686/prefix
if command -v i686-linux-gnu-gcc >/dev/null && [ -f "$prefix/lib/libjansson.a" ]; then
    i686-linux-gnu-gcc -std=c99 -O2 -g -static -DNDEBUG \
        -Icore/include -Icore/profiles -Iport/json/include -Iport/json/src -I"$prefix/include" \
        -DSVA_CONFIG_HEADER='"sva_profile_default.h"' \
        core/src/*.c tools/cli/*.c port/json/src/*.c "$prefix/lib/libjansson.a" -o "$out/sva-i686"
    cli[i686]=$out/sva-i686
    archs="x86-64 i686"
else
    echo "note: no i686 build (needs gcc-i686-linux-gnu and the cross tests' jansson in $prefix);" \
         "estimating from x86-64 counts" >&2
    archs="x86-64"
fi
base_arch=${archs##* }

# Missions: the paper's protocol as in scripts/bench.sh (20x20 grid, windows of 10 to
# 20 ticks, need 1, hover fuel 2), seeded, written by the host tools' generator.
for size in $sizes; do
    t=${size%x*}; u=${size#*x}
    .venv/bin/sva-tools gen --targets "$t" --uavs "$u" --need 1 --hover 2 --width 10:20 \
        --max-coord 20 --seed "$seed" --count "$per_size" --name "m${size}" \
        -o "$out/missions/$size" >/dev/null
done

# Instructions inside sva_plan for one run, or "-" when the plan fails (bfa over its
# limits) or takes longer than 5 minutes under callgrind.
count() {  # count ARCH ALGO MISSION
    local f="$out/callgrind/$1.$2.$(basename "$3" .json).out"
    if timeout 300 valgrind --tool=callgrind --toggle-collect=sva_plan --callgrind-out-file="$f" \
           "${cli[$1]}" plan --algo "$2" "$3" >/dev/null 2>"$f.log"; then
        awk '/^(summary|totals):/ {print $2; exit}' "$f"
    else
        echo "-"
    fi
}

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); $(valgrind --version)"
echo "missions: $per_size per size, sva-tools gen --need 1 --hover 2 --width 10:20 --max-coord 20 --seed $seed"
echo "instructions executed inside sva_plan(), mean over the missions (max in brackets);"
echo "M4 ms = ${base_arch} mean * CPI $cpi / $mhz MHz"
printf '\n%-6s %-5s' size algo
for a in $archs; do printf ' %24s' "$a"; done
printf ' %10s\n' "M4 ms"
for size in $sizes; do
    for algo in $algos; do
        printf '%-6s %-5s' "$size" "$algo"
        base_mean=""
        for arch in $archs; do
            vals=()
            for m in "$out/missions/$size"/*.json; do
                vals+=("$(count "$arch" "$algo" "$m")")
            done
            stats=$(printf '%s\n' "${vals[@]}" | awk '
                $1 == "-" {bad++; next} {n++; s += $1; if ($1 > mx) mx = $1}
                END { if (bad || !n) print "-"; else printf "%.0f %d\n", s / n, mx }')
            if [ "$stats" = "-" ]; then
                printf ' %24s' "-"
            else
                read -r mean max <<<"$stats"
                printf ' %24s' "$mean ($max)"
                if [ "$arch" = "$base_arch" ]; then base_mean=$mean; fi
            fi
        done
        if [ -n "$base_mean" ]; then
            awk -v n="$base_mean" -v c="$cpi" -v f="$mhz" 'BEGIN { printf " %10.3f\n", n * c / (f * 1000) }'
        else
            printf ' %10s\n' "-"
        fi
    done
done
cat <<EOF

"-": the plan failed (bfa refuses missions over SVA_BFA_MAX_TARGETS/UAVS) on some
mission of the size, or ran over 5 minutes under callgrind.
CPI note: a Cortex-M4 runs most integer instructions in one cycle, loads in two and
taken branches in two to four; with flash wait states hidden by the STM32F4's ART
accelerator, $cpi cycles per instruction is the assumption. Thumb-2 is taken to need
about as many instructions as i686 for this integer code. Both are assumptions: time
the firmware on the part for a real figure.
Callgrind output: $out/callgrind/ (callgrind_annotate FILE shows where they go).
EOF
