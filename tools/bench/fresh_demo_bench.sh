#!/usr/bin/env bash
# How long a newcomer waits for the first plan: a fresh Debian 12 (debootstrap's minbase
# variant, nothing else installed) gets a clean clone of this checkout's HEAD and runs
# the README's first command, `scripts/demo.sh`, as root in a chroot; wall time from the
# command to the printed schedule, its installs and build included. The figure goes to
# docs/results.md ("First plan on a fresh Debian 12") with --results.
#
# Usage (root, with debootstrap installed and a Debian mirror reachable):
#   tools/bench/fresh_demo_bench.sh [--runs N] [--mirror URL] [--keep DIR] [--results]
# Each run builds its own chroot (about 30 s with a near mirror), then times the demo.
# The chroot, its mounts and the clone are always removed (--keep DIR copies the demo's
# log there first). Exit status 0 when every run printed a schedule, 1 otherwise.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
runs=1
mirror=http://deb.debian.org/debian
keep=""
results=0
while [ $# -gt 0 ]; do
    case "$1" in
        --runs) runs=${2:?--runs needs a count}; shift 2 ;;
        --mirror) mirror=${2:?--mirror needs a URL}; shift 2 ;;
        --keep) keep=${2:?--keep needs a folder}; shift 2 ;;
        --results) results=1; shift ;;
        *) echo "fresh_demo_bench: unknown option $1" >&2; exit 2 ;;
    esac
done
case "$runs" in ''|*[!0-9]*|0) echo "fresh_demo_bench: --runs must be a whole number >= 1, got '$runs'" >&2; exit 2 ;; esac
[ "$(id -u)" = 0 ] || { echo "fresh_demo_bench: needs root (debootstrap, chroot)" >&2; exit 2; }
command -v debootstrap >/dev/null || { echo "fresh_demo_bench: debootstrap missing (apt-get install debootstrap)" >&2; exit 2; }

work=$(mktemp -d /tmp/sva-fresh-demo.XXXXXX)
chroot_dir="$work/debian"
cleanup() {
    for m in dev/pts dev proc; do
        mountpoint -q "$chroot_dir/$m" 2>/dev/null && umount -l "$chroot_dir/$m"
    done
    rm -rf --one-file-system "$work"
}
trap cleanup EXIT INT TERM

elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

failed=0
times=()
rows=()
for run in $(seq 1 "$runs"); do
    cleanup
    mkdir -p "$work"
    t0=$(date +%s.%N)
    debootstrap --variant=minbase bookworm "$chroot_dir" "$mirror" >"$work/debootstrap.log" 2>&1 \
        || { echo "fresh_demo_bench: debootstrap failed (see --keep)" >&2; tail -5 "$work/debootstrap.log" >&2; exit 1; }
    t1=$(date +%s.%N)
    git clone -q "$root" "$chroot_dir/root/sva"
    cp /etc/resolv.conf "$chroot_dir/etc/resolv.conf"
    mount --bind /proc "$chroot_dir/proc"
    mount --bind /dev "$chroot_dir/dev"
    mount --bind /dev/pts "$chroot_dir/dev/pts"
    t2=$(date +%s.%N)
    status=0
    chroot "$chroot_dir" /bin/bash -c 'cd /root/sva && scripts/demo.sh' >"$work/demo.log" 2>&1 || status=$?
    t3=$(date +%s.%N)
    if [ -n "$keep" ]; then
        mkdir -p "$keep" && cp "$work/demo.log" "$keep/demo-$run.log"
    fi
    if [ $status -ne 0 ] || ! grep -q "^mission .*covered" "$work/demo.log"; then
        echo "run $run: scripts/demo.sh failed (status $status); its last lines:" >&2
        tail -5 "$work/demo.log" >&2
        failed=1
        continue
    fi
    demo=$(elapsed "$t2" "$t3")
    times+=("$demo")
    installed=$(grep -m1 -o 'installing [0-9]* of [0-9]* Debian packages' "$work/demo.log" || echo 'nothing installed')
    rows+=("| $run | $(elapsed "$t0" "$t1") | $demo | $installed |")
    printf 'run %d: fresh Debian 12 in %.1f s; scripts/demo.sh to the schedule %.1f s (%s)\n' \
        "$run" "$(elapsed "$t0" "$t1")" "$demo" "$(grep -m1 '^setup: part demo' "$work/demo.log" || echo 'nothing installed')"
done
if [ ${#times[@]} -gt 0 ]; then
    summary=$(printf '%s\n' "${times[@]}" | sort -n | awk '{a[NR]=$1} END {printf "demo on a fresh Debian 12: %d runs, median %.1f s, max %.1f s", NR, a[int((NR+1)/2)], a[NR]}')
    echo "$summary"
    if [ $results = 1 ] && [ $failed = 0 ]; then
        {
            echo "A fresh Debian 12 (\`debootstrap --variant=minbase bookworm\`, nothing else installed) as root in a chroot, a clean clone of the checkout, then the README's first command, \`scripts/demo.sh\`: wall time from the command to the printed schedule, with its Debian installs (from $mirror) and the build of the \`sva\` CLI."
            echo
            echo "| run | debootstrap (s) | scripts/demo.sh to the schedule (s) | installed by the demo |"
            echo "|---|---|---|---|"
            printf '%s\n' "${rows[@]}"
            echo
            echo "$summary"
        } | python3 "$root/tools/bench/results.py" write setup \
            --command "tools/bench/fresh_demo_bench.sh --runs $runs --results"
    fi
fi
exit $failed
