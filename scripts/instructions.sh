#!/usr/bin/env bash
# Instructions per plan: valgrind's callgrind counts the instructions executed inside
# sva_plan() (--toggle-collect=sva_plan: no process start-up, no JSON) for one plan
# of each mission, on the paper's sizes, and estimates the time on a 168 MHz
# Cortex-M4. A figure printer, not a test. Counts are exact and repeatable for a
# given binary; the Cortex-M4 time is an estimate (see the CPI note it prints).
#
# Usage: scripts/instructions.sh [--results] [MISSIONS_PER_SIZE]     (default 5)
#   --results  also write its section of docs/results.md (docs/results/instructions.md)
# Environment:
#   SVA_ALGOS   algorithms, as the CLI's --algo names (default: sva ga hga bfa flow)
#   SVA_CPI     cycles per instruction assumed on the Cortex-M4 (default 1.5)
#   SVA_SIZES   "TARGETSxUAVS ..." (default: the paper's 3x3 5x3 7x5 10x5 25x5)
#   SVA_SEED    generator seed (default 2024)
#   SVA_INSTRUCTIONS_OUT  where the missions and callgrind files go (default
#               build/instructions)
#   SVA_NO_BUILD  1: use build/ as it is (its test, tests/tools/test_instructions.py)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

results=""
if [ "${1:-}" = "--results" ]; then results=1; shift; fi
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
per_size=${1:-5}
algos=${SVA_ALGOS:-sva ga hga bfa flow}
cpi=${SVA_CPI:-1.5}
sizes=${SVA_SIZES:-3x3 5x3 7x5 10x5 25x5}
seed=${SVA_SEED:-2024}
mhz=168

if [ "${SVA_NO_BUILD:-0}" != 1 ]; then scripts/build.sh >/dev/null; fi
out=${SVA_INSTRUCTIONS_OUT:-build/instructions}
rm -rf "$out"
mkdir -p "$out/missions" "$out/callgrind"

# Two builds of the CLI: the host's (x86-64, build/bin/sva) and a static 32-bit i686
# one. A Cortex-M4 is a 32-bit machine: the core's int64_t arithmetic takes two or
# more instructions there as on i686, so the i686 count is the basis of the estimate.
# (-O2 as the host build; the firmware example uses -Os. No PROJ for i686: the frame
# port's geodesy is left out, as in the cross builds.)
declare -A cli=([x86-64]=build/bin/sva)
prefix=build/cross/i686/prefix
if command -v i686-linux-gnu-gcc >/dev/null && [ -f "$prefix/lib/libjansson.a" ]; then
    i686-linux-gnu-gcc -std=c99 -O2 -g -static -DNDEBUG \
        -Icore/include -Icore/profiles -Iport/json/include -Iport/json/src -Iport/frame/include \
        -I"$prefix/include" -DSVA_CONFIG_HEADER='"sva_profile_default.h"' \
        core/src/*/*.c core/src/*.c tools/cli/*.c port/json/src/*.c port/frame/src/frame.c \
        port/frame/src/geodesy_none.c "$prefix/lib/libjansson.a" -o "$out/sva-i686"
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
# (gen writes one mission to a file, more into a folder.)
for size in $sizes; do
    t=${size%x*}; u=${size#*x}
    dest="$out/missions/$size"
    if [ "$per_size" -eq 1 ]; then mkdir -p "$dest"; dest="$dest/m${size}.json"; fi
    .venv/bin/sva-tools gen --targets "$t" --uavs "$u" --need 1 --hover 2 --width 10:20 \
        --max-coord 20 --seed "$seed" --count "$per_size" --name "m${size}" \
        -o "$dest" >/dev/null
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
md_head="| size (targets x UAVs) | algorithm |"
md_rule="|---|---|"
for a in $archs; do md_head+=" $a mean (max) |"; md_rule+="---|"; done
md_rows=()
commas() { sed ':a;s/\B[0-9]\{3\}\>/,&/;ta' <<<"$1"; }
for size in $sizes; do
    for algo in $algos; do
        printf '%-6s %-5s' "$size" "$algo"
        md="| ${size/x/ x } | $algo |"
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
                md+=" - |"
            else
                read -r mean max <<<"$stats"
                printf ' %24s' "$mean ($max)"
                md+=" $(commas "$mean") ($(commas "$max")) |"
                if [ "$arch" = "$base_arch" ]; then base_mean=$mean; fi
            fi
        done
        if [ -n "$base_mean" ]; then
            m4=$(awk -v n="$base_mean" -v c="$cpi" -v f="$mhz" 'BEGIN { printf "%.3f", n * c / (f * 1000) }')
            printf ' %10s\n' "$m4"
            md+=" $m4 |"
        else
            printf ' %10s\n' "-"
            md+=" - |"
        fi
        md_rows+=("$md")
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
[ -n "$results" ] || exit 0

{
    echo "Instructions executed inside \`sva_plan()\` (callgrind \`--toggle-collect=sva_plan\`: no process"
    echo "start-up, no JSON), one plan per mission, mean over $per_size missions per size (largest in"
    echo "brackets); missions from \`sva-tools gen --need 1 --hover 2 --width 10:20 --max-coord 20 --seed $seed\`"
    echo "(fuel 150: fuel rarely binds). $(valgrind --version). Builds: x86-64 \`-O2\` (the host build)"
    if [ "$base_arch" = i686 ]; then
        echo "and a static 32-bit i686 \`-O2\` build ($(i686-linux-gnu-gcc --version | head -1)), the basis of the estimate."
    else
        echo "only (no i686 build here), the basis of the estimate."
    fi
    echo
    echo "$md_head M4 ms (est.) |"
    echo "$md_rule---|"
    printf '%s\n' "${md_rows[@]}"
    echo
    echo "\"-\": bfa refuses missions over its limits (SVA_BFA_MAX_TARGETS/UAVS). M4 ms is an"
    echo "estimate, not a measurement: ${base_arch} instructions x CPI $cpi / $mhz MHz, assuming one cycle for"
    echo "most instructions, two for loads, two to four for taken branches, flash wait states"
    echo "hidden by the STM32F4's ART accelerator, and about as many Thumb-2 instructions as"
    echo "i686 ones. Counts are exact and repeatable for a given binary."
} | python3 tools/bench/results.py write instructions \
      --command "scripts/instructions.sh --results $per_size" --load-start "$load_start"
