#!/usr/bin/env bash
# Rewrites fixtures/golden/<algo>/<mission>.json from build/bin/sva: every mission of
# fixtures/missions with every algorithm, "stats" removed (timings vary). bfa plans
# only the missions within its limits: a refusal naming an SVA_BFA_MAX_* limit is
# skipped, and its old golden file removed. Any other failure stops the script.
# Review the diff (git diff fixtures/golden) before committing: a changed golden plan
# is a changed behaviour.
# Usage: tools/regen-golden.sh [path/to/sva]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sva=${1:-$root/build/bin/sva}
[ -x "$sva" ] || { echo "regen-golden: $sva not built (run scripts/build.sh)" >&2; exit 1; }
algos=$("$sva" --help | sed -n 's/.*--algo NAME *algorithm: \(.*\) (default.*/\1/p' | tr -d ',')
written=0
skipped=0
for algo in $algos; do
    mkdir -p "$root/fixtures/golden/$algo"
    for mission in "$root"/fixtures/missions/*.json; do
        name=$(basename "$mission" .json)
        out="$root/fixtures/golden/$algo/$name.json"
        if plan=$("$sva" plan --algo "$algo" "$mission" 2>/tmp/regen-golden.err); then
            printf '%s\n' "$plan" | python3 -c '
import json, sys
plan = json.load(sys.stdin)
del plan["stats"]
sys.stdout.write(json.dumps(plan, indent=2) + "\n")' > "$out"
            written=$((written + 1))
        elif [ "$algo" = bfa ] && grep -q 'SVA_BFA_MAX_' /tmp/regen-golden.err; then
            echo "regen-golden: skipped bfa/$name: $(sed 's/^sva: error: //' /tmp/regen-golden.err)"
            rm -f "$out"
            skipped=$((skipped + 1))
        else
            echo "regen-golden: $algo/$name failed: $(cat /tmp/regen-golden.err)" >&2
            exit 1
        fi
    done
done
rm -f /tmp/regen-golden.err
echo "regen-golden: wrote $written golden plans to fixtures/golden/ ($skipped skipped), from $sva"
