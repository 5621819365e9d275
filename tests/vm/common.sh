# Sourced by the vm suite's scripts (run_vm.sh, run_systemd_vm.sh): Debian
# packages by `apt-get download` (cached in WORK_DIR/debs), Debian's kernel
# as an ELF vmlinux, modules and shared libraries copied into a root, and
# the qemu boot. The caller has entered WORK_DIR and defines skip and fail.

step() { echo "[$(date +%T)] $*"; }

# vm_tools: the host tools every VM needs, and busybox-static's applets
# (in $applets) for the guest.
busybox=/bin/busybox
vm_tools() {
    local tool applet file_type
    for tool in qemu-system-x86_64 apt-get apt-cache dpkg xz timeout; do
        command -v "$tool" >/dev/null || skip "$tool is missing (tools/packages.sh lists the packages)"
    done
    # (No `busybox --list | grep -q`: with pipefail, grep's early exit is a failure.)
    applets=$("$busybox" --list 2>/dev/null)
    for applet in cpio depmod modprobe gzip base64 usleep; do
        grep -qx "$applet" <<<"$applets" || skip "$busybox with $applet is missing (busybox-static)"
    done
    file_type=$(LC_ALL=C od -An -tx1 -N4 "$busybox" | tr -d ' ')
    [ "$file_type" = 7f454c46 ] || skip "$busybox is not an ELF binary"
    if ldd "$busybox" >/dev/null 2>&1; then skip "$busybox is not static (busybox-static)"; fi
}

# candidate PACKAGE: the version apt would install.
candidate() {
    apt-cache show --no-all-versions "$1" 2>/dev/null | sed -n 's/^Version: //p' | head -n 1
}

# fetch NAME=VERSION...: downloads the packages not in debs/ yet.
fetch() {
    local p name ver missing=()
    mkdir -p debs
    for p in "$@"; do
        name=${p%%=*} ver=${p#*=}
        compgen -G "debs/${name}_${ver//:/%3a}_*.deb" >/dev/null || missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
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
}
deb() { compgen -G "debs/${1}_${2//:/%3a}_*.deb" | head -n 1; }

# kernel_version: the kernel linux-image-amd64 points at (sets abi, kver,
# version, series, modroot).
kernel_version() {
    abi=$(apt-cache depends linux-image-amd64 2>/dev/null |
          sed -n 's/^ *Depends: linux-image-\([0-9.]*-[0-9]*\)-amd64$/\1/p' | head -n 1)
    [ -n "$abi" ] || skip "apt-cache does not know linux-image-amd64 (run apt-get update)"
    kver=$abi-amd64
    version=$(candidate "linux-image-$kver")
    [ -n "$version" ] || skip "apt-cache has no version of linux-image-$kver"
    series=${abi%%-*}                  # 6.1.0
    series=${series%.*}                # 6.1
    modroot="kernel-$kver/lib/modules/$kver"
    step "kernel $kver ($version)"
}

# vm_kernel [EXTRA=VERSION...]: after kernel_version, the kernel downloaded
# with the extra packages given and extracted with its ELF vmlinux (cached).
vm_kernel() {
    fetch "linux-image-$kver=$version" "$@"
    [ -f "kernel-$kver/.done" ] && return 0
    step "extracting the kernel"
    rm -rf "kernel-$kver"
    dpkg -x "$(deb "linux-image-$kver" "$version")" "kernel-$kver" || fail "dpkg -x of the kernel"
    # Booting the ELF vmlinux directly (PVH) saves the bzImage's
    # decompression under TCG: find the xz stream inside the bzImage.
    local bz="kernel-$kver/boot/vmlinuz-$kver" offset
    offset=$(LC_ALL=C grep -obUaP '\xfd7zXZ\x00' "$bz" | head -n 1 | cut -d: -f1)
    [ -n "$offset" ] || fail "no xz stream in $bz"
    tail -c +$((offset + 1)) "$bz" | xz -dc --single-stream >"kernel-$kver/vmlinux" 2>/dev/null
    [ "$(od -An -tx1 -N4 "kernel-$kver/vmlinux" | tr -d ' ')" = 7f454c46 ] ||
        fail "the vmlinux extracted from $bz is not ELF"
    touch "kernel-$kver/.done"
}

# vm_modules ROOT MODULE...: the modules with what modules.dep says they
# need, and ROOT's modules.dep.
vm_modules() {
    local root=$1 m line f
    shift
    if [ ! -f "$modroot/modules.dep" ]; then
        "$busybox" depmod -b "$PWD/kernel-$kver" "$kver" || fail "depmod"
    fi
    for m in "$@"; do
        line=$(grep -E "(^|/)$m\.ko:" "$modroot/modules.dep") || fail "$m.ko is not in modules.dep"
        for f in ${line/:/}; do
            mkdir -p "$root/lib/modules/$kver/$(dirname "$f")"
            cp "$modroot/$f" "$root/lib/modules/$kver/$f"
        done
    done
    "$busybox" depmod -b "$root" "$kver" || fail "depmod in $root"
}

# closure FILE...: the shared libraries the programs need (and the loader).
closure() {
    ldd "$@" 2>/dev/null | awk '$2 == "=>" && $3 ~ /^\// {print $3} $1 ~ /^\// && $2 ~ /^\(/ {print $1}' | sort -u
}

# copy_libraries ROOT FILE...: the closure into ROOT: the loader at its
# path, the rest flat in /usr/lib/x86_64-linux-gnu, but for libraries
# already under ROOT.
copy_libraries() {
    local root=$1 lib
    shift
    for lib in $(closure "$@"); do
        case $lib in
            "$root"/*) ;;
            */ld-linux*) mkdir -p "$root$(dirname "$lib")"; cp -L "$lib" "$root$lib" ;;
            *) cp -L "$lib" "$root/usr/lib/x86_64-linux-gnu/" ;;
        esac
    done
    [ -e "$root/lib64/ld-linux-x86-64.so.2" ] || fail "the dynamic loader is not in the closure"
}

# boot CPIO CONSOLE CMDLINE: qemu (TCG, one CPU) until the guest powers off;
# the console in CONSOLE's name with .log for .txt, and without carriage
# returns in CONSOLE (NAME.txt).
boot() {
    local start status
    step "booting under qemu (TCG)"
    start=$(date +%s)
    timeout 600 qemu-system-x86_64 -accel tcg -cpu max -smp 1 -m 768M -nographic -no-reboot \
        -nic none -kernel "kernel-$kver/vmlinux" -initrd "$1" \
        -append "console=ttyS0 panic=-1 quiet loglevel=3 $3" </dev/null >"${2%.txt}.log" 2>&1
    status=$?
    step "qemu finished with status $status after $(( $(date +%s) - start )) s"
    tr -d '\r' <"${2%.txt}.log" >"$2"
}

# verdict CONSOLE NAME...: each test's "RTE-VM PASS|FAIL name" line; sets bad.
verdict() {
    local console=$1 t
    shift
    echo "---- results ----"
    for t in "$@"; do
        if grep -q "^RTE-VM FAIL $t:" "$console"; then
            echo "FAIL $t"; bad=1
        elif grep -q "^RTE-VM PASS $t:" "$console"; then
            echo "PASS $t"
        else
            echo "FAIL $t (no result line)"; bad=1
        fi
    done
    if grep -q '^RTE-VM FAIL' "$console"; then
        grep '^RTE-VM FAIL' "$console"; bad=1
    fi
}
