#!/usr/bin/env bash
# Packaging tests (ctest label package; tests/package/CMakeLists.txt sets the variables):
#   package_test.sh install    cmake --install into one prefix; the expected files are there;
#                              the installed sva_mavlink_bridge answers --help and bad options
#   package_test.sh cmake      find_package(sva) consumers and the README example, built and run
#   package_test.sh pkgconfig  the same consumers with pkg-config only, from make and from a
#                              plain shell; the README's pkg-config line as written
#   package_test.sh subdir     add_subdirectory() of the source tree
#   package_test.sh units      systemd-analyze verify of the installed units
#   package_test.sh deb        cpack's .deb: fields, dpkg into a throw-away root, the
#                              installed programs run, the node answers over LCM
# Environment: SVA_SOURCE_DIR SVA_BUILD_DIR SVA_WORK SVA_COMPONENTS (e.g. "can lcm json")
# SVA_MAVLINK_BRIDGE (1 when sva_mavlink_bridge is built) SVA_PYTHON SVA_LCM_PYTHON_DIR
# SVA_NETNS_RUN.
set -euo pipefail
step=${1:?usage: package_test.sh install|cmake|pkgconfig|subdir|units|deb}
src=${SVA_SOURCE_DIR:?}
build=${SVA_BUILD_DIR:?}
work=${SVA_WORK:?}
prefix="$work/prefix"
components=${SVA_COMPONENTS:-}
bridge=${SVA_MAVLINK_BRIDGE:-0}
here="$src/tests/package"
version=$(sed -n 's/^#define SVA_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' \
          "$src/core/include/sva/sva.h" | paste -sd.)

fail() { echo "package_test $step: FAIL: $*" >&2; exit 1; }
has() { [[ " $components " == *" $1 "* ]]; }
run() { echo "+ $*" >&2; "$@"; }

# The README's pkg-config command: the one `...` span under "## Embedding the core" that
# holds "$(pkg-config --cflags --libs sva)", as written (a line of its own in the README).
readme_pkgconfig_command() {
    local cmd
    cmd=$(awk '/^## Embedding the core/ {s=1; next} s && /^## / {exit} s {print}' "$src/README.md" |
          grep -o '`[^`]*\$(pkg-config --cflags --libs sva)[^`]*`' | tr -d '`')
    [ "$(printf '%s\n' "$cmd" | grep -c .)" -eq 1 ] ||
        fail "README.md: expected one \`... \$(pkg-config --cflags --libs sva)\` command in '## Embedding the core', found: $cmd"
    printf '%s\n' "$cmd"
}

# The README's embedding example: the first ```c block (```c file=main.c) after "## Embedding the core".
readme_example() {
    local out="$1"
    awk '/^## Embedding the core/ {s=1; next}
         s && /^## / {exit}
         s && /^```c( |$)/ {c=1; next}
         c && /^```$/ {exit}
         c {print}' "$src/README.md" > "$out"
    grep -q 'int main(void)' "$out" || fail "README.md: no complete C program (int main) in '## Embedding the core'"
}

expect_files() {
    local root="$1"; shift
    local f missing=0
    for f in "$@"; do
        if [ ! -e "$root/$f" ]; then echo "missing: $root/$f" >&2; missing=1; fi
    done
    [ $missing -eq 0 ] || fail "files missing from the installed tree"
}

installed_files() {  # the files every install must have, relative to the prefix
    local lib=$1
    echo "bin/sva include/sva/sva.h include/sva/sva_config.h include/sva_build_config.h"
    echo "$lib/libsva_core.a $lib/cmake/sva/svaConfig.cmake $lib/cmake/sva/svaConfigVersion.cmake"
    echo "$lib/cmake/sva/svaTargets.cmake $lib/pkgconfig/sva.pc share/doc/sva/copyright"
    if has frame; then
        echo "include/sva/sva_frame.h $lib/libsva_frame.a $lib/pkgconfig/sva-frame.pc"
        echo "$lib/cmake/sva/sva_frameTargets.cmake"
    fi
    if has can; then
        echo "bin/sva_can_node include/sva/sva_can.h $lib/libsva_can.a $lib/pkgconfig/sva-can.pc"
        echo "$lib/cmake/sva/sva_canTargets.cmake share/sva/sva.dbc lib/systemd/system/sva-can-node.service"
    fi
    if has lcm; then
        echo "bin/sva_node include/sva/sva_lcm.h include/sva/sva_lcm_plan_t.h $lib/libsva_lcm.a"
        echo "$lib/libsva_lcm_types.a $lib/pkgconfig/sva-lcm.pc $lib/cmake/sva/sva_lcmTargets.cmake"
        echo "share/sva/lcm/mission_t.lcm share/sva/lcm/fleet_state_t.lcm share/sva/lcm/plan_t.lcm"
        echo "share/sva/lcm/node_status_t.lcm share/sva/lcm/frame_t.lcm"
        echo "lib/systemd/system/sva-node.service"
    fi
    if has mavlink; then
        # sva_mavlink.h includes mavgen's "common/mavlink.h" (include/sva/mavlink).
        echo "include/sva/sva_mavlink.h include/sva/mavlink/common/mavlink.h"
        echo "include/sva/mavlink/minimal/mavlink.h include/sva/mavlink/protocol.h"
        echo "$lib/libsva_mavlink.a $lib/pkgconfig/sva-mavlink.pc $lib/cmake/sva/sva_mavlinkTargets.cmake"
    fi
    if [ "$bridge" = 1 ]; then
        echo "bin/sva_mavlink_bridge"
    fi
}

check_bridge() {  # check_bridge PROGRAM: --help, --version, bad options refused with their name
    local prog="$1" out rc
    out=$("$prog" --help) || fail "$prog --help exited $?"
    [[ "$out" == "usage: sva_mavlink_bridge --vehicle "* ]] || { echo "$out" >&2; fail "$prog --help: no usage line"; }
    [[ "$out" == *"--ardupilot"* ]] || fail "$prog --help does not list --ardupilot"
    [ "$("$prog" --version)" = "sva_mavlink_bridge $version" ] || fail "$prog --version"
    rc=0; out=$("$prog" --no-such-option 1 2>&1 >/dev/null) || rc=$?
    [ $rc -eq 2 ] || fail "$prog --no-such-option 1 exited $rc, expected 2"
    [[ "$out" == *"sva_mavlink_bridge: error: --no-such-option: unknown option"* ]] || { echo "$out" >&2; fail "$prog: no message naming --no-such-option"; }
    rc=0; out=$("$prog" --vehicle 1=udp:127.0.0.1:14550 --system 0 2>&1 >/dev/null) || rc=$?
    [ $rc -eq 2 ] || fail "$prog --system 0 exited $rc, expected 2"
    [[ "$out" == *"--system: must be an integer in [1, 255], got \"0\""* ]] || { echo "$out" >&2; fail "$prog --system 0: no message naming the rule"; }
    echo "package_test $step: $prog: --help, --version, --no-such-option, --system 0 ok" >&2
}

run_consumers() {  # runs every consumer program built in $1
    local dir="$1" p n=0
    for p in consumer_core consumer_frame consumer_can consumer_lcm consumer_mavlink readme_example; do
        if [ -x "$dir/$p" ]; then run "$dir/$p" || fail "$p exited $?"; n=$((n + 1)); fi
    done
    local want=2  # core and the README example, and one per port
    for p in $components; do [ "$p" = json ] || want=$((want + 1)); done
    [ $n -eq "$want" ] || fail "$n consumer programs built in $dir, expected $want"
}

verify_unit() {  # verify_unit UNIT_FILE [--root=DIR]
    local out
    # --man=no: no man pages to look up; SYSTEMD_LOG_LEVEL: warnings are findings too.
    if ! out=$(systemd-analyze verify --man=no "${@:2}" "$1" 2>&1) || [ -n "$out" ]; then
        echo "$out" >&2
        return 1
    fi
}

case "$step" in
install)
    rm -rf "$prefix"
    run cmake --install "$build" --prefix "$prefix" >/dev/null
    # shellcheck disable=SC2046
    expect_files "$prefix" $(installed_files lib)
    grep -q "SVA_VERSION_MINOR" "$prefix/include/sva/sva.h" || fail "installed sva.h"
    grep -q "^Version: $version$" "$prefix/lib/pkgconfig/sva.pc" || fail "sva.pc: Version is not $version"
    if [ "$bridge" = 1 ]; then check_bridge "$prefix/bin/sva_mavlink_bridge"; fi
    ;;
cmake)
    [ -f "$prefix/lib/cmake/sva/svaConfig.cmake" ] || fail "no install in $prefix (package_install)"
    d="$work/consumer_cmake"
    rm -rf "$d" && mkdir -p "$d"
    readme_example "$d/readme_example.c"
    run cmake -S "$here/consumer" -B "$d" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
        -DSVA_COMPONENTS="${components// /;}" -DREADME_EXAMPLE="$d/readme_example.c" \
        -DSVA_WANTED_VERSION="${version%.*}" >/dev/null
    run cmake --build "$d" >/dev/null
    run_consumers "$d"
    # Exactly as the README says: find_package(sva) with no component, then sva::core.
    d1="$work/consumer_cmake_plain"
    rm -rf "$d1" && mkdir -p "$d1"
    run cmake -S "$here/consumer" -B "$d1" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
        -DREADME_EXAMPLE="$d/readme_example.c" >/dev/null
    run cmake --build "$d1" >/dev/null
    components="" run_consumers "$d1"
    # A component that is not installed is an error naming it, not a silent success.
    d2="$work/consumer_cmake_missing"
    rm -rf "$d2" && mkdir -p "$d2"
    if cmake -S "$here/consumer" -B "$d2" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
            -DSVA_COMPONENTS="nosuch" > "$d2/log" 2>&1; then
        fail "find_package(sva COMPONENTS nosuch) succeeded"
    fi
    grep -q "sva component 'nosuch' is not installed (installed: core $components" "$d2/log" || { cat "$d2/log" >&2; fail "no message naming the component"; }
    ;;
pkgconfig)
    [ -f "$prefix/lib/pkgconfig/sva.pc" ] || fail "no install in $prefix (package_install)"
    d="$work/consumer_pkgconfig"
    rm -rf "$d" && mkdir -p "$d"
    export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
    [ "$(pkg-config --modversion sva)" = "$version" ] || fail "pkg-config --modversion sva"
    # No installed .pc file hands out a flag that needs quoting: a shell passes quotes and
    # backslashes from $(pkg-config ...) to the compiler as they are.
    for pc in "$prefix"/lib/pkgconfig/*.pc; do
        name=$(basename "$pc" .pc)
        flags=$(pkg-config --cflags --libs "$name") || fail "pkg-config --cflags --libs $name"
        case "$flags" in
        *[\"\'\\]*) fail "pkg-config --cflags --libs $name: a flag needs quoting: $flags" ;;
        esac
    done
    cflags=$(pkg-config --cflags sva)
    [[ " $cflags " == *" -DSVA_BUILD_CONFIG=1 "* ]] || fail "pkg-config --cflags sva: no -DSVA_BUILD_CONFIG=1 ($cflags)"
    # ... and with it a consumer includes the build's bound profile (consumer_core checks
    # its layout against the library's).
    # shellcheck disable=SC2046
    deps=$(cc -std=c99 -M "$here/consumer/consumer_core.c" $(pkg-config --cflags sva))
    [[ "$deps" == *"/include/sva_build_config.h"* ]] || fail "consumer_core.c does not include sva_build_config.h with pkg-config's flags"
    readme_example "$d/readme_example.c"
    ports=$(for p in $components; do [ "$p" = json ] || printf '%s ' "$p"; done)
    run make -s -f "$here/consumer/Makefile" O="$d" PORTS="$ports" README_EXAMPLE="$d/readme_example.c"
    run_consumers "$d"
    # The same programs from a plain shell: $(pkg-config ...) unquoted, word-split.
    ds="$d/shell"
    mkdir -p "$ds"
    for p in core $ports; do
        pc=sva; [ "$p" = core ] || pc="sva-$p"
        # shellcheck disable=SC2046
        run cc -std=c99 -Wall -Wextra -Werror -o "$ds/consumer_$p" "$here/consumer/consumer_$p.c" \
            $(pkg-config --cflags --libs "$pc") || fail "consumer_$p.c with \$(pkg-config --cflags --libs $pc) in a shell"
    done
    # shellcheck disable=SC2046
    run cc -std=c99 -Wall -Wextra -Werror -o "$ds/readme_example" "$d/readme_example.c" \
        $(pkg-config --cflags --libs sva) || fail "readme_example.c with \$(pkg-config --cflags --libs sva) in a shell"
    run_consumers "$ds"
    # The README's command exactly as written, in bash, on the README's example as main.c.
    dr="$d/readme"
    mkdir -p "$dr"
    cp "$d/readme_example.c" "$dr/main.c"
    cmd=$(readme_pkgconfig_command)
    (cd "$dr" && run bash -euc "$cmd") || fail "the README's '$cmd' failed in a shell"
    exe=$(find "$dr" -maxdepth 1 -type f -perm -u+x)
    [ "$(printf '%s\n' "$exe" | grep -c .)" -eq 1 ] || fail "the README's '$cmd' made no program (or several: $exe)"
    run "$exe" || fail "the README example built by '$cmd' exited $?"
    ;;
subdir)
    d="$work/consumer_subdir"
    rm -rf "$d" && mkdir -p "$d"
    readme_example "$d/readme_example.c"
    run cmake -S "$here/consumer" -B "$d" -G Ninja -DSVA_SOURCE_DIR="$src" \
        -DREADME_EXAMPLE="$d/readme_example.c" >/dev/null
    run cmake --build "$d" >/dev/null
    components="" run_consumers "$d"
    ;;
units)
    n=0
    for u in "$prefix"/lib/systemd/system/*.service; do
        [ -e "$u" ] || fail "no unit installed in $prefix/lib/systemd/system"
        grep -q "^ExecStart=$prefix/bin/" "$u" || fail "$u: ExecStart= is not under $prefix/bin"
        run verify_unit "$u" || fail "systemd-analyze verify $u"
        n=$((n + 1))
    done
    # The check can fail: a unit whose program does not exist is a finding.
    bad="$work/sva-broken.service"
    sed "s|^ExecStart=[^ ]*|ExecStart=$prefix/bin/no_such_program|" "$u" > "$bad"
    if verify_unit "$bad" 2>/dev/null; then fail "systemd-analyze verify accepted $bad"; fi
    echo "package_test units: $n units verified" >&2
    ;;
deb)
    d="$work/deb"
    rm -rf "$d" && mkdir -p "$d"
    run cpack --config "$build/CPackConfig.cmake" -B "$d" >/dev/null
    deb=$(ls "$d"/sva_"$version"_*.deb) || fail "cpack made no sva_${version}_*.deb"
    [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "Version field"
    depends=$(dpkg-deb -f "$deb" Depends)
    echo "Depends: $depends" >&2
    for p in libc6 libjansson4 $(has lcm && echo libglib2.0-0); do
        [[ ", $depends" == *", $p "* || ", $depends," == *", $p,"* ]] || fail "Depends lacks $p"
    done
    [[ "$(dpkg-deb -f "$deb" Suggests)" == *libproj-dev* ]] || fail "Suggests lacks libproj-dev"
    [ -n "$(dpkg-deb -f "$deb" Maintainer)" ] || fail "no Maintainer"
    # A fresh dpkg database in a throw-away root. --force-depends: that database knows
    # none of the host's packages (libc6, libjansson4, ...), which the programs then use
    # from the host; nothing else is forced. --log keeps the host's dpkg.log untouched.
    root="$d/root"
    mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates" "$root/var/log"
    : > "$root/var/lib/dpkg/status"
    run dpkg --root="$root" --log="$root/var/log/dpkg.log" --force-depends -i "$deb" >/dev/null
    dpkg --root="$root" -s sva | grep -q '^Status: install ok installed' || fail "dpkg -s sva in $root"
    # shellcheck disable=SC2046
    expect_files "$root/usr" $(installed_files lib)
    # The package's own pkg-config file, from a shell: the README example builds and runs.
    readme_example "$d/readme_example.c"
    # shellcheck disable=SC2046
    run cc -std=c99 -Wall -Wextra -Werror -o "$d/readme_example" "$d/readme_example.c" \
        $(PKG_CONFIG_PATH="$root/usr/lib/pkgconfig" pkg-config --cflags --libs sva) ||
        fail "the README example with the package's sva.pc in a shell"
    run "$d/readme_example" || fail "the README example built with the package's sva.pc exited $?"
    # PROJ: an installed program that links it at run time makes Depends name libprojNN;
    # the static sva::frame needs libproj-dev to be linked by a consumer (Suggests).
    if objdump -p "$root"/usr/bin/* 2>/dev/null | grep -q 'NEEDED.*libproj'; then
        [[ "$depends" =~ (^|,\ )libproj[0-9]+ ]] || fail "a program links PROJ, Depends lacks libproj"
    fi
    out=$("$root/usr/bin/sva" --version) || fail "installed sva --version"
    [[ "$out" == "sva $version "* ]] || fail "sva --version says '$out'"
    "$root/usr/bin/sva" plan --algo sva "$src/fixtures/missions/hand_5_3.json" > "$d/plan.json" || fail "installed sva plan"
    grep -q '"status": *"complete"' "$d/plan.json" || { cat "$d/plan.json" >&2; fail "installed sva: plan not complete"; }
    for u in "$root"/usr/lib/systemd/system/*.service; do
        grep -q "^ExecStart=/usr/bin/" "$u" || fail "$u: ExecStart= is not /usr/bin/..."
        # Verified against the host's systemd units (a throw-away root has none), the
        # program path mapped into the root.
        mapped="$d/$(basename "$u")"
        sed "s|^ExecStart=/usr/bin/|ExecStart=$root/usr/bin/|" "$u" > "$mapped"
        run verify_unit "$mapped" || fail "systemd-analyze verify $u (as $mapped)"
    done
    if has can; then
        "$root/usr/bin/sva_can_node" --help | grep -q '^usage: sva_can_node --mission' || fail "sva_can_node --help"
        [ "$("$root/usr/bin/sva_can_node" --version)" = "sva_can_node $version" ] || fail "sva_can_node --version"
        "$root/usr/bin/sva_can_node" --iface vcan0 >/dev/null 2>&1 && fail "sva_can_node without --mission succeeded"
    fi
    if [ "$bridge" = 1 ]; then check_bridge "$root/usr/bin/sva_mavlink_bridge"; fi
    if has lcm; then
        "$root/usr/bin/sva_node" --help | grep -q '^usage: sva_node' || fail "sva_node --help"
        [ "$("$root/usr/bin/sva_node" --version)" = "sva_node $version" ] || fail "sva_node --version"
        # A real start: the installed node in a network namespace must publish its status.
        rc=0
        run "$SVA_NETNS_RUN" env PYTHONPATH="$SVA_LCM_PYTHON_DIR" "$SVA_PYTHON" \
            "$here/node_answers.py" "$root/usr/bin/sva_node" || rc=$?
        [ $rc -ne 77 ] || { echo "package_test deb: no network namespace (needs root): node start skipped" >&2; exit 77; }
        [ $rc -eq 0 ] || fail "the installed sva_node did not answer"
    fi
    ;;
*)
    fail "unknown step"
    ;;
esac
echo "package_test $step: ok" >&2
