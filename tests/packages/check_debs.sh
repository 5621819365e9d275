#!/usr/bin/env bash
# tools/test's package stage: builds rtedge's Debian packages from a copy of
# the source tree as a user would (dpkg-buildpackage -b -us -uc), runs
# lintian on them, unpacks them (dpkg -x) and uses what they hold; then
# cross-builds the arm64 packages with Debian's cross toolchain and runs
# their binaries and the golden suite's program on their library under
# qemu-aarch64, which must give the same bytes as the amd64 ones
# (docs/packaging.md). With VM_WORK_DIR (the vm suite's cache of
# the kernel and Debian's packages), the .debs are also installed in the vm
# suite's systemd guest and rtedged.service run there on vivid
# (tests/vm/run_systemd_vm.sh).
#
#   check_debs.sh SOURCE_DIR WORK_DIR [VM_WORK_DIR]
#
# Prints "ok: ..." or "FAIL: ..." per check and ends with "N passed, N
# failed"; exits 1 on any failure.
set -uo pipefail

src=$(cd "$1" && pwd)
work=$2
vm_work=${3:-}
rm -rf "$work" && mkdir -p "$work" || exit 1
work=$(cd "$work" && pwd)
passed=0
failed=0
ok() { echo "ok: $*"; passed=$((passed + 1)); }
bad() { echo "FAIL: $*"; failed=$((failed + 1)); }
finish() {
    echo "packages: $passed passed, $failed failed"
    [ "$failed" -eq 0 ]
    exit
}
jobs=$(nproc 2>/dev/null || echo 2)
host=$(dpkg --print-architecture)

# build ARCH [dpkg-buildpackage args...]: the packages of ARCH in
# $work/ARCH (the .debs land beside the copied tree).
build() {
    local arch=$1; shift
    mkdir -p "$work/$arch/rtedge"
    (cd "$src" && git ls-files -co --exclude-standard -z | grep -zv '^build/' |
        tar --null -T - -cf -) | tar -xf - -C "$work/$arch/rtedge" || return 1
    local start=$SECONDS
    (cd "$work/$arch/rtedge" &&
        DEB_BUILD_OPTIONS="parallel=$jobs nocheck" dpkg-buildpackage -b -us -uc "$@") \
        >"$work/$arch/build.log" 2>&1 || { tail -30 "$work/$arch/build.log"; return 1; }
    echo "  built in $((SECONDS - start)) s:"
    (cd "$work/$arch" && for deb in *.deb; do
        printf '    %-44s %7d bytes, installed %5s KiB\n' "$deb" "$(stat -c %s "$deb")" \
            "$(dpkg-deb -f "$deb" Installed-Size)"
    done)
}

# lint ARCH: lintian on the .changes; errors fail, the rest is shown.
lint() {
    local changes out
    changes=$(ls "$work/$1"/*.changes)
    out=$(lintian --fail-on error "$changes" 2>&1)
    local status=$?
    out=$(echo "$out" | grep -v '^running with root privileges')
    [ -n "$out" ] && echo "$out" | sed 's/^/  /'
    [ $status -eq 0 ] && ok "lintian on the $1 packages: no errors ($(echo "$out" | grep -c '^W:') warnings)" ||
        bad "lintian on the $1 packages"
}

# unpack ARCH: every .deb of ARCH (but the debug symbols) into $work/ARCH/root.
unpack() {
    local deb
    for deb in "$work/$1"/*.deb; do
        case $deb in *-dbgsym_*) continue ;; esac
        dpkg -x "$deb" "$work/$1/root" || return 1
    done
}

# program ARCH TRIPLET SOURCE NAME: SOURCE built with TRIPLET-gcc against
# the unpacked librtedge-dev (its rtedge.pc, resolved by TRIPLET-pkg-config;
# the root's /usr stands in for the system's, which pkg-config leaves out)
# into $work/ARCH/NAME.
program() {
    local root=$work/$1/root triplet=$2 flags
    flags=$(PKG_CONFIG_PATH=$root/usr/lib/$triplet/pkgconfig "$triplet-pkg-config" \
        --cflags --libs rtedge) || return 1
    # shellcheck disable=SC2086
    "$triplet-gcc" -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Werror -o "$work/$1/$4" "$3" \
        -I"$root/usr/include" -L"$root/usr/lib/$triplet" $flags -lm
}

echo "== $host packages =="
if ! build "$host"; then
    bad "dpkg-buildpackage -b -us -uc ($work/$host/build.log)"
    finish
fi
ok "dpkg-buildpackage -b -us -uc: $(cd "$work/$host" && ls ./*.deb | grep -vc dbgsym) packages"
lint "$host"
unpack "$host" || bad "dpkg -x"
root=$work/$host/root
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)

conffiles=$(dpkg-deb --ctrl-tarfile "$work/$host"/rtedged_*.deb | tar -xOf - ./conffiles 2>/dev/null)
[ "$conffiles" = /etc/rtedge/rtedged.conf ] && ok "rtedged: /etc/rtedge/rtedged.conf is its conffile" ||
    bad "rtedged's conffiles: '$conffiles'"
"$root/usr/bin/rtedged" --config "$root/etc/rtedge/rtedged.conf" --check-config >/dev/null &&
    grep -q '^path = /dev/video0' "$root/etc/rtedge/rtedged.conf" &&
    ok "rtedged accepts the packaged rtedged.conf (camera /dev/video0)" ||
    bad "the packaged rtedged and rtedged.conf"
unit=$root/lib/systemd/system/rtedged.service
grep -q '^ExecStart=/usr/bin/rtedged --config /etc/rtedge/rtedged.conf$' "$unit" &&
    grep -q '^Type=notify$' "$unit" && [ -f "$root/usr/lib/sysctl.d/60-rtedge-lcm.conf" ] &&
    ok "rtedged.service (Type=notify) runs the packaged daemon; the sysctl.d drop-in is in" ||
    bad "the unit or the sysctl.d drop-in"
postinst=$(dpkg-deb --ctrl-tarfile "$work/$host"/rtedged_*.deb | tar -xOf - ./postinst)
echo "$postinst" | grep -q 'deb-systemd-helper enable' &&
    echo "$postinst" | grep -q 'sysctl -q -p /usr/lib/sysctl.d/60-rtedge-lcm.conf' &&
    ok "rtedged's postinst enables the unit and applies the receive buffers" ||
    bad "rtedged's postinst"

symbols=$(dpkg-deb --ctrl-tarfile "$work/$host"/librtedge0_*.deb | tar -xOf - ./symbols | grep -c '^ rte_')
[ "$symbols" -gt 100 ] && ok "librtedge0: a symbols file of $symbols functions" || bad "librtedge0's symbols"
host_triplet=$(dpkg-architecture -qDEB_HOST_GNU_TYPE)
if program "$host" "$host_triplet" "$src/tests/build/installed_consumer.c" consumer &&
    LD_LIBRARY_PATH=$root/usr/lib/$multiarch "$work/$host/consumer" "$work/$host/step.png" >/dev/null; then
    ok "a program built against librtedge-dev runs on librtedge0"
else
    bad "a program built against librtedge-dev"
fi

PYTHONPATH=$root/usr/lib/python3/dist-packages /usr/bin/python3 -c '
import rtedge, sys
m = rtedge.lane_detection_t()
m.nsegments = 0
sys.exit(0 if rtedge.lane_detection_t.decode(m.encode()).nsegments == 0 else 1)' &&
    ok "python3-rtedge-lcm: import rtedge, a lane_detection_t round trip" || bad "python3-rtedge-lcm"
unzip -l "$root/usr/share/java/rtedge-lcmtypes.jar" 2>/dev/null | grep -q 'rtedge/lane_detection_t.class' ||
    jar tf "$root/usr/share/java/rtedge-lcmtypes.jar" | grep -q 'rtedge/lane_detection_t.class' &&
    ok "librtedge-lcmtypes-java: rtedge-lcmtypes.jar holds the types" || bad "the Java types jar"
for tool in rtedge rtedge-subscribe rtedge-render-log rtedge-web rtedge-spy; do
    [ -x "$(readlink -f "$root/usr/bin/$tool")" ] || bad "rtedge-tools: $tool missing or dangling"
done
"$root/usr/bin/rtedge" --version | grep -q '^rtedge 0' &&
    PYTHONPATH=$root/usr/lib/python3/dist-packages "$root/usr/bin/rtedge-subscribe" --help >/dev/null &&
    ok "rtedge-tools: rtedge --version, rtedge-subscribe --help; every tool in place" ||
    bad "rtedge-tools' programs"

if [ -n "$vm_work" ]; then
    echo "== the $host packages installed in a guest with systemd as PID 1 =="
    # (run_systemd_vm.sh's BUILD_DIR is not read when it is given .debs.)
    "$src/tests/vm/run_systemd_vm.sh" "$vm_work" "$work/$host" "$work/$host" >"$work/vm.log" 2>&1
    status=$?
    grep -E '^RTE-VM (PASS|FAIL)|SKIP:' "$work/vm.log" | sed 's/^/  /'
    case $status in
        0) ok "rtedged.service from the .debs under systemd: waits, READY, messages, watchdog restart" ;;
        77) echo "skip: the systemd guest ($(grep -m1 SKIP: "$work/vm.log"))" ;;
        *) bad "rtedged.service from the .debs under systemd ($work/vm.log)" ;;
    esac
fi

echo "== arm64 packages (cross-built; LCM and libcamera left out) =="
if ! build arm64 -a arm64 -Pcross,nocheck,pkg.rtedge.nolcm,pkg.rtedge.nolibcamera; then
    bad "dpkg-buildpackage -a arm64 ($work/arm64/build.log)"
    finish
fi
ok "dpkg-buildpackage -a arm64: $(cd "$work/arm64" && ls ./*.deb | grep -vc dbgsym) packages"
lint arm64
unpack arm64 || bad "dpkg -x arm64"
aroot=$work/arm64/root
qemu() { qemu-aarch64 -L /usr/aarch64-linux-gnu "$@"; }
# The same command on both architectures' packaged rtedge: the same bytes
# (the golden property: integer kernels, NEON and AVX2 rows alike), but for
# the times in the JSON (stage_ns, timing_ns).
same() {
    local name=$1 arch; shift
    "$root/usr/bin/rtedge" "$@" "$work/$name.$host.png" >"$work/$name.$host.out" 2>&1 &&
        qemu "$aroot/usr/bin/rtedge" "$@" "$work/$name.arm64.png" >"$work/$name.arm64.out" 2>&1 &&
        cmp -s "$work/$name.$host.png" "$work/$name.arm64.png" || return 1
    for arch in "$host" arm64; do
        sed -E 's/"(stage|timing)_ns":\{[^}]*\}//g' "$work/$name.$arch.out" >"$work/$name.$arch.json"
    done
    cmp -s "$work/$name.$host.json" "$work/$name.arm64.json"
}
fx=$src/fixtures
# The golden suite's program (tests/golden/golden.c: every kernel, its
# tables and both pipelines on the fixtures, hashed) built against each
# architecture's librtedge-dev and run on its librtedge0: the amd64 plain C
# path writes the reference, which arm64 (NEON and plain C, under qemu) and
# amd64 (its SIMD rows) must match.
golden_inputs=()
for f in solidWhiteCurve.jpg solidWhiteCurve_gray.pgm smarties.png smarties.ppm stuff.jpg \
    solidWhiteRight_clip.y4m; do
    golden_inputs+=("$fx/$f")
done
if program "$host" "$host_triplet" "$src/tests/golden/golden.c" golden &&
    program arm64 aarch64-linux-gnu "$src/tests/golden/golden.c" golden &&
    LD_LIBRARY_PATH=$root/usr/lib/$multiarch RTE_FORCE_C=1 "$work/$host/golden" write \
        "$work/golden-reference.txt" "${golden_inputs[@]}" >/dev/null &&
    LD_LIBRARY_PATH=$root/usr/lib/$multiarch "$work/$host/golden" check \
        "$work/golden-reference.txt" "${golden_inputs[@]}" >"$work/golden.$host.log" 2>&1 &&
    LD_LIBRARY_PATH=$aroot/usr/lib/aarch64-linux-gnu qemu "$work/arm64/golden" check \
        "$work/golden-reference.txt" "${golden_inputs[@]}" >"$work/golden.arm64.log" 2>&1 &&
    LD_LIBRARY_PATH=$aroot/usr/lib/aarch64-linux-gnu RTE_FORCE_C=1 qemu "$work/arm64/golden" check \
        "$work/golden-reference.txt" "${golden_inputs[@]}" >"$work/golden.arm64-c.log" 2>&1; then
    ok "golden: the packaged librtedge0 on arm64 (qemu; NEON and plain C) and $host: $(wc -l <"$work/golden-reference.txt") outputs alike"
else
    bad "golden on the packaged libraries ($work/golden.*.log)"
fi
same canny canny "$fx/solidWhiteCurve.jpg" --low 50 --high 150 &&
    same lanes lanes "$fx/solidWhiteCurve.jpg" --overlay &&
    same grasp grasp "$fx/stuff.jpg" --overlay &&
    ok "arm64 rtedge under qemu-aarch64: canny, lanes and grasp give the $host bytes" ||
    bad "arm64 rtedge and $host rtedge differ ($work/*.out)"
if program arm64 aarch64-linux-gnu "$src/tests/build/installed_consumer.c" consumer &&
    LD_LIBRARY_PATH=$aroot/usr/lib/aarch64-linux-gnu qemu "$work/arm64/consumer" "$work/arm64/step.png" >/dev/null; then
    ok "an arm64 program built against librtedge-dev:arm64 runs on librtedge0:arm64 (qemu)"
else
    bad "the arm64 program built against librtedge-dev:arm64"
fi
finish
