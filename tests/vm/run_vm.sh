#!/usr/bin/env bash
# The `vm` suite: proves the camera sources against real kernel drivers.
# Boots Debian's own kernel under qemu (TCG) with an initramfs holding
# busybox, rtedged, the test programs with their libraries, vivid and an
# out-of-tree vimc, and parses the console for "RTE-VM PASS|FAIL name" lines
# (qemu exits 0 whatever happened inside). The LCM logs rtedged wrote in the
# VM come out on the console too; check_logs.py decodes and checks them.
#
#   run_vm.sh WORK_DIR RTEDGED VM_VIVID VM_CTL LCM_PYTHON_TYPES [VM_LIBCAMERA]
#
# Packages come from `apt-get download` + `dpkg -x` into WORK_DIR (nothing
# is installed); downloads, the extracted kernel and vimc.ko are cached
# there. Exits 77 (meson's skip) with "SKIP: reason" when it cannot run.
set -uo pipefail

work=$1
rtedged=$2
vm_vivid=$3
vm_ctl=$4
lcm_types=$5
vm_libcamera=${6:-}
here=$(cd "$(dirname "$0")" && pwd)

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
# shellcheck source=common.sh
. "$here/common.sh"

vm_tools
if [ -n "$vm_libcamera" ]; then
    for tool in make gcc; do
        command -v "$tool" >/dev/null || skip "$tool is missing (needed to build vimc.ko)"
    done
fi

mkdir -p "$work" || fail "cannot create $work"
cd "$work" || fail "cannot enter $work"

# ---- the kernel, and for vimc its headers and sources (cached) ----
kernel_version
extra=()
if [ -n "$vm_libcamera" ]; then
    lcver=$(dpkg-query -W -f='${Version}' libcamera-dev 2>/dev/null)
    [ -n "$lcver" ] || skip "libcamera-dev is not installed"
    extra=("linux-headers-$kver=$version" "linux-headers-$abi-common=$version"
           "linux-kbuild-$series=$version" "linux-source-$series=$version"
           "libcamera-ipa=$lcver")
fi
vm_kernel "${extra[@]}"

# ---- vimc: Debian does not build it; build it out of tree (cached) ----
if [ -n "$vm_libcamera" ] && [ ! -f "vimc-$kver/vimc.ko" ]; then
    step "building vimc.ko"
    rm -rf "headers-$kver" "vimc-$kver"
    mkdir -p "headers-$kver" "vimc-$kver"
    for d in "$(deb "linux-headers-$kver" "$version")" "$(deb "linux-headers-$abi-common" "$version")" \
             "$(deb "linux-kbuild-$series" "$version")" "$(deb "linux-source-$series" "$version")"; do
        dpkg -x "$d" "headers-$kver" || fail "dpkg -x $d"
    done
    hdr="$work/headers-$kver/usr/src/linux-headers-$kver"
    # The arch headers' Makefile includes the common tree by absolute path.
    sed -i "s|/usr/src/|$work/headers-$kver/usr/src/|g" "$hdr/Makefile"
    tar -xJf "headers-$kver/usr/src/linux-source-$series.tar.xz" -C "vimc-$kver" \
        --strip-components=4 "linux-source-$series/drivers/media/test-drivers/vimc" ||
        fail "vimc sources not found in linux-source-$series"
    rm -f "headers-$kver/usr/src/linux-source-$series.tar.xz"
    make -s -C "$hdr" M="$work/vimc-$kver/vimc" CONFIG_VIDEO_VIMC=m modules \
        >"vimc-$kver/build.log" 2>&1 || { tail -n 20 "vimc-$kver/build.log"; fail "vimc build"; }
    cp "vimc-$kver/vimc/vimc.ko" "vimc-$kver/vimc.ko"
    rm -rf "headers-$kver"
fi

# ---- initramfs ----
step "assembling the initramfs"
root="$work/root"
rm -rf "$root"
mkdir -p "$root"/{bin,proc,sys,dev,run,tmp,lib64,usr/lib/x86_64-linux-gnu} "$root/lib/modules/$kver" ||
    fail "mkdir $root"
cp "$busybox" "$root/bin/busybox"
for applet in $applets; do
    [ -e "$root/bin/$applet" ] || ln -s busybox "$root/bin/$applet"
done
install -m 755 "$here/init.sh" "$root/init"

# Modules: vivid and vimc with what modules.dep says they need (the
# kernel tree's modules.dep is made once, with vimc.ko in extra/).
wanted=(vivid)
if [ -n "$vm_libcamera" ]; then
    wanted+=(vimc)
    if [ ! -f "$modroot/extra/vimc.ko" ]; then
        mkdir -p "$modroot/extra"
        cp "vimc-$kver/vimc.ko" "$modroot/extra/"
        rm -f "$modroot/modules.dep"
    fi
fi
vm_modules "$root" "${wanted[@]}"

# Programs with their shared libraries (flat in one directory, found
# through LD_LIBRARY_PATH; the loader at its absolute path).
programs=("$rtedged" "$vm_vivid" "$vm_ctl")
cp "$rtedged" "$root/bin/rtedged"
cp "$vm_vivid" "$root/bin/vm_vivid"
cp "$vm_ctl" "$root/bin/vm_ctl"
libcamera_extra=()
if [ -n "$vm_libcamera" ]; then
    cp "$vm_libcamera" "$root/bin/vm_libcamera"
    programs+=("$vm_libcamera")
    # The IPA module unstripped next to its .sign (or the signature check
    # fails), its proxy, and its configuration, at the paths libcamera uses.
    dpkg -x "$(deb libcamera-ipa "$lcver")" "$work/ipa" || fail "dpkg -x libcamera-ipa"
    for f in usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so.sign \
             usr/lib/x86_64-linux-gnu/libcamera/vimc_ipa_proxy usr/share/libcamera/ipa/vimc/vimc.conf; do
        mkdir -p "$root/$(dirname "$f")"
        cp -a "$work/ipa/$f" "$root/$f" || fail "libcamera-ipa lacks $f"
    done
    libcamera_extra=("$work/ipa/usr/lib/x86_64-linux-gnu/libcamera/ipa_vimc.so"
                     "$work/ipa/usr/lib/x86_64-linux-gnu/libcamera/vimc_ipa_proxy")
fi
copy_libraries "$root" "${programs[@]}" "${libcamera_extra[@]}"
rm -rf "$work/ipa"

(cd "$root" && find . | "$busybox" cpio -o -H newc >"$work/initramfs.cpio" 2>/dev/null) ||
    fail "cpio"
step "initramfs: $(du -m "$work/initramfs.cpio" | cut -f1) MB"

boot "$work/initramfs.cpio" "$work/console.txt" ""
# The files sent back are long: the console log has them, not the output.
grep -v '^[A-Za-z0-9+/=]*$' "$work/console.txt"

# ---- the daemon's logs, decoded on the host ----
checks="$work/checks.txt"
if [ -x /usr/bin/python3 ]; then
    /usr/bin/python3 "$here/check_logs.py" "$work/console.txt" "$lcm_types" "$rtedged" \
        "$work/logs" >"$checks" 2>&1
    cat "$checks"
else
    echo "SKIP: the daemon's logs are not checked: no /usr/bin/python3" | tee "$checks"
fi

# ---- verdict ----
expected=(daemon-wait-run vivid-yuyv vivid-grey vivid-uyvy vivid-nv12 vivid-drops vivid-buf-error vivid-fatal-error
          vivid-streamon-error vivid-disconnect vivid-reload daemon-vivid-run daemon-record-run
          list-cameras)
[ -n "$vm_libcamera" ] && expected+=(libcamera-vimc daemon-libcamera-run)
# The host's checks of the logs (unless python3 is missing: SKIP above).
host_expected=(daemon-wait-log daemon-vivid-log daemon-vivid-faults record-replay)
[ -n "$vm_libcamera" ] && host_expected+=(daemon-libcamera-log)
bad=0
verdict "$work/console.txt" "${expected[@]}"
if ! grep -q '^SKIP' "$checks"; then
    for t in "${host_expected[@]}"; do
        if grep -q "^PASS $t:" "$checks" && ! grep -q "^FAIL $t:" "$checks"; then
            echo "PASS $t (host)"
        else
            echo "FAIL $t (host)"; bad=1
        fi
    done
    grep -q '^FAIL' "$checks" && bad=1
fi
[ -n "$vm_libcamera" ] || echo "NOTE: built without libcamera: the vimc test did not run"
grep -q '^RTE-VM end' "$work/console.txt" || { echo "FAIL: the VM did not finish its tests"; bad=1; }
exit $bad
