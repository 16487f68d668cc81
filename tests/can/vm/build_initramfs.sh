#!/usr/bin/env bash
# Builds the initramfs of the SocketCAN VM test.
# Usage: build_initramfs.sh OUTDIR NODE_BIN BRIDGE_BIN MISSION_JSON
# OUTDIR/clock_tick and OUTDIR/bad_begin.frame (written by run_vm_test.sh) go in too.
# Writes OUTDIR/initrd.gz and OUTDIR/kernel (path of the kernel image to boot).
# Contents: busybox-static (shell, insmod, ip), the CAN modules of the kernel that
# Debian's linux-image-amd64 installs (can, can-raw, can-dev, vcan, in dependency
# order), candump and cansend from can-utils with the shared libraries ldd lists, the two
# statically linked test programs, the mission and /init.
set -euo pipefail
out=$1 node=$2 bridge=$3 mission=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { echo "build_initramfs: $*" >&2; exit 1; }

for tool in cpio gzip modinfo ldd; do command -v "$tool" >/dev/null || die "$tool not found (scripts/setup.sh installs it)"; done
[ -x /bin/busybox ] || die "/bin/busybox missing (busybox-static)"
command -v candump >/dev/null || die "candump not found (can-utils)"

# The kernel linux-image-amd64 depends on, e.g. linux-image-6.1.0-56-amd64.
pkg=$(dpkg-query -W -f='${Depends}' linux-image-amd64 2>/dev/null | grep -o 'linux-image-[0-9][^ ,]*' | head -1) \
    || die "linux-image-amd64 is not installed"
[ -n "$pkg" ] || die "linux-image-amd64 is not installed"
kver=${pkg#linux-image-}
kernel=/boot/vmlinuz-$kver
[ -r "$kernel" ] || die "$kernel not readable"
[ -d "/lib/modules/$kver" ] || die "/lib/modules/$kver missing"

root=$out/root
rm -rf "$root"
mkdir -p "$root"/{bin,dev,proc,sys,tmp,lib/modules,lib64}
cp /bin/busybox "$root/bin/busybox"

# Modules in dependency order (modinfo's depends field), decompressed if needed.
order=()
add_module() {
    local m=$1 dep
    for dep in $(modinfo -k "$kver" -F depends "$m" | tr ',' ' '); do add_module "$dep"; done
    case " ${order[*]-} " in *" $m "*) return ;; esac
    order+=("$m")
}
for m in can can-raw can-dev vcan; do add_module "$m"; done
: > "$root/modules.order"
for m in "${order[@]}"; do
    f=$(modinfo -k "$kver" -F filename "$m") || die "module $m not found for $kver"
    case $f in
        *.ko) cp "$f" "$root/lib/modules/$m.ko" ;;
        *.ko.xz) xz -dc "$f" > "$root/lib/modules/$m.ko" ;;
        *.ko.zst) zstd -dcq "$f" > "$root/lib/modules/$m.ko" ;;
        *.ko.gz) gzip -dc "$f" > "$root/lib/modules/$m.ko" ;;
        *) die "unknown module format $f" ;;
    esac
    echo "$m" >> "$root/modules.order"
done

# candump, cansend and their shared libraries (path-preserving copy).
command -v cansend >/dev/null || die "cansend not found (can-utils)"
for tool in candump cansend; do
    cp "$(command -v "$tool")" "$root/bin/$tool"
    for lib in $(ldd "$(command -v "$tool")" | grep -o '/[^ ]*'); do
        mkdir -p "$root$(dirname "$lib")"
        cp -L "$lib" "$root$lib"
    done
done

cp "$node" "$root/bin/sva_can_node"
cp "$bridge" "$root/bin/can_vm_bridge"
cp "$mission" "$root/mission.json"
cp "$out/clock_tick" "$root/clock_tick"
cp "$out/bad_begin.frame" "$root/bad_begin.frame"
cp "$here/init.sh" "$root/init"
chmod +x "$root/init"

(cd "$root" && find . | LC_ALL=C sort | cpio -o -H newc --quiet | gzip -1) > "$out/initrd.gz"
echo "$kernel" > "$out/kernel"
echo "build_initramfs: kernel $kver, modules ${order[*]}, $(du -k "$out/initrd.gz" | cut -f1) KiB"
