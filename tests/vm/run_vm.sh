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
step() { echo "[$(date +%T)] $*"; }

for tool in qemu-system-x86_64 apt-get apt-cache dpkg xz timeout; do
    command -v "$tool" >/dev/null || skip "$tool is missing (tools/packages.sh lists the packages)"
done
busybox=/bin/busybox
# (No `busybox --list | grep -q`: with pipefail, grep's early exit is a failure.)
applets=$("$busybox" --list 2>/dev/null)
for applet in cpio depmod modprobe gzip base64 usleep; do
    grep -qx "$applet" <<<"$applets" || skip "$busybox with $applet is missing (busybox-static)"
done
file_type=$(LC_ALL=C od -An -tx1 -N4 "$busybox" | tr -d ' ')
[ "$file_type" = 7f454c46 ] || skip "$busybox is not an ELF binary"
if ldd "$busybox" >/dev/null 2>&1; then skip "$busybox is not static (busybox-static)"; fi
if [ -n "$vm_libcamera" ]; then
    for tool in make gcc; do
        command -v "$tool" >/dev/null || skip "$tool is missing (needed to build vimc.ko)"
    done
fi

mkdir -p "$work" || fail "cannot create $work"
cd "$work" || fail "cannot enter $work"

# ---- which kernel: the one linux-image-amd64 points at ----
abi=$(apt-cache depends linux-image-amd64 2>/dev/null |
      sed -n 's/^ *Depends: linux-image-\([0-9.]*-[0-9]*\)-amd64$/\1/p' | head -n 1)
[ -n "$abi" ] || skip "apt-cache does not know linux-image-amd64 (run apt-get update)"
kver=$abi-amd64
version=$(apt-cache show --no-all-versions "linux-image-$kver" 2>/dev/null |
          sed -n 's/^Version: //p' | head -n 1)
[ -n "$version" ] || skip "apt-cache has no version of linux-image-$kver"
series=${abi%%-*}                  # 6.1.0
series=${series%.*}                # 6.1
step "kernel $kver ($version)"

# ---- downloads (cached) ----
packages=("linux-image-$kver=$version")
if [ -n "$vm_libcamera" ]; then
    lcver=$(dpkg-query -W -f='${Version}' libcamera-dev 2>/dev/null)
    [ -n "$lcver" ] || skip "libcamera-dev is not installed"
    packages+=("linux-headers-$kver=$version" "linux-headers-$abi-common=$version"
               "linux-kbuild-$series=$version" "linux-source-$series=$version"
               "libcamera-ipa=$lcver")
fi
mkdir -p debs
missing=()
for p in "${packages[@]}"; do
    name=${p%%=*} ver=${p#*=}
    compgen -G "debs/${name}_${ver//:/%3a}_*.deb" >/dev/null || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    step "downloading ${missing[*]}"
    if ! (cd debs && apt-get download -q "${missing[@]}" >download.log 2>&1); then
        # The lists may be older than the mirror: refresh them once as root.
        if [ "$(id -u)" -eq 0 ] && apt-get update -q >/dev/null 2>&1 &&
           (cd debs && apt-get download -q "${missing[@]}" >download.log 2>&1); then
            :
        else
            tail -n 3 debs/download.log
            skip "apt-get download failed (no network or no such version)"
        fi
    fi
fi
deb() { compgen -G "debs/${1}_${2//:/%3a}_*.deb" | head -n 1; }

# ---- kernel and its modules (cached) ----
if [ ! -f "kernel-$kver/.done" ]; then
    step "extracting the kernel"
    rm -rf "kernel-$kver"
    dpkg -x "$(deb "linux-image-$kver" "$version")" "kernel-$kver" || fail "dpkg -x of the kernel"
    # Booting the ELF vmlinux directly (PVH) saves the bzImage's
    # decompression under TCG: find the xz stream inside the bzImage.
    bz="kernel-$kver/boot/vmlinuz-$kver"
    offset=$(LC_ALL=C grep -obUaP '\xfd7zXZ\x00' "$bz" | head -n 1 | cut -d: -f1)
    [ -n "$offset" ] || fail "no xz stream in $bz"
    tail -c +$((offset + 1)) "$bz" | xz -dc --single-stream >"kernel-$kver/vmlinux" 2>/dev/null
    [ "$(od -An -tx1 -N4 "kernel-$kver/vmlinux" | tr -d ' ')" = 7f454c46 ] ||
        fail "the vmlinux extracted from $bz is not ELF"
    touch "kernel-$kver/.done"
fi
modroot="kernel-$kver/lib/modules/$kver"

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
if [ ! -f "$modroot/modules.dep" ]; then
    "$busybox" depmod -b "$work/kernel-$kver" "$kver" || fail "depmod"
fi
for m in "${wanted[@]}"; do
    line=$(grep -E "(^|/)$m\.ko:" "$modroot/modules.dep") || fail "$m.ko is not in modules.dep"
    for f in ${line/:/}; do
        mkdir -p "$root/lib/modules/$kver/$(dirname "$f")"
        cp "$modroot/$f" "$root/lib/modules/$kver/$f"
    done
done
"$busybox" depmod -b "$root" "$kver" || fail "depmod in the initramfs"

# Programs with their shared libraries (flat in one directory, found
# through LD_LIBRARY_PATH; the loader at its absolute path).
closure() {
    ldd "$@" 2>/dev/null | awk '$2 == "=>" && $3 ~ /^\// {print $3} $1 ~ /^\// && $2 ~ /^\(/ {print $1}' | sort -u
}
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
for lib in $(closure "${programs[@]}" "${libcamera_extra[@]}"); do
    case $lib in
        */ld-linux*) mkdir -p "$root$(dirname "$lib")"; cp -L "$lib" "$root$lib" ;;
        *) cp -L "$lib" "$root/usr/lib/x86_64-linux-gnu/" ;;
    esac
done
rm -rf "$work/ipa"
[ -e "$root/lib64/ld-linux-x86-64.so.2" ] || fail "the dynamic loader is not in the closure"

(cd "$root" && find . | "$busybox" cpio -o -H newc >"$work/initramfs.cpio" 2>/dev/null) ||
    fail "cpio"
step "initramfs: $(du -m "$work/initramfs.cpio" | cut -f1) MB"

# ---- boot ----
step "booting under qemu (TCG)"
start=$(date +%s)
timeout 600 qemu-system-x86_64 -accel tcg -cpu max -smp 1 -m 768M -nographic -no-reboot \
    -kernel "kernel-$kver/vmlinux" -initrd "$work/initramfs.cpio" \
    -append 'console=ttyS0 panic=-1 quiet loglevel=3' </dev/null >"$work/console.log" 2>&1
qemu_status=$?
step "qemu finished with status $qemu_status after $(( $(date +%s) - start )) s"
tr -d '\r' <"$work/console.log" >"$work/console.txt"
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
expected=(vivid-yuyv vivid-grey vivid-uyvy vivid-nv12 vivid-drops vivid-buf-error vivid-fatal-error
          vivid-streamon-error vivid-disconnect vivid-reload daemon-vivid-run daemon-record-run
          list-cameras)
[ -n "$vm_libcamera" ] && expected+=(libcamera-vimc daemon-libcamera-run)
# The host's checks of the logs (unless python3 is missing: SKIP above).
host_expected=(daemon-vivid-log daemon-vivid-faults record-replay)
[ -n "$vm_libcamera" ] && host_expected+=(daemon-libcamera-log)
bad=0
echo "---- results ----"
for t in "${expected[@]}"; do
    if grep -q "^RTE-VM FAIL $t:" "$work/console.txt"; then
        echo "FAIL $t"; bad=1
    elif grep -q "^RTE-VM PASS $t:" "$work/console.txt"; then
        echo "PASS $t"
    else
        echo "FAIL $t (no result line)"; bad=1
    fi
done
if grep -q '^RTE-VM FAIL' "$work/console.txt"; then
    grep '^RTE-VM FAIL' "$work/console.txt"; bad=1
fi
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
