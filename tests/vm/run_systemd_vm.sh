#!/usr/bin/env bash
# The `vm` suite's systemd test: rtedged.service as installed, run by a
# real systemd. Boots Debian's kernel under qemu (TCG) with systemd as
# PID 1 on an initramfs root made of Debian's systemd and udev packages
# and kmod (`apt-get download` + `dpkg -x`), busybox for the shell, vivid, and
# rtedge installed by `meson install --destdir` of BUILD_DIR, or from the
# rtedge .deb files in DEBS_DIR (`dpkg -x`). rtedged.service is enabled
# (systemctl --root) with only its configuration file changed (the camera's
# size and format, a file:// log); systemd_test.sh checks the wait for
# the camera, READY=1, the messages and the watchdog's restart, and prints
# "RTE-VM PASS|FAIL name" lines.
#
#   run_systemd_vm.sh WORK_DIR BUILD_DIR [DEBS_DIR]   (or RTE_VM_DEBS=DEBS_DIR)
#
# Downloads and the kernel are cached in WORK_DIR (shared with run_vm.sh).
# Exits 77 (meson's skip) with "SKIP: reason" when it cannot run.
set -uo pipefail

work=$1
build=$(cd "$2" && pwd) || exit 1
debs_dir=${3:-${RTE_VM_DEBS:-}}
here=$(cd "$(dirname "$0")" && pwd)

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
# shellcheck source=common.sh
. "$here/common.sh"

vm_tools
for tool in systemctl ldconfig; do
    command -v "$tool" >/dev/null || skip "$tool is missing (tools/packages.sh lists the packages)"
done
[ -z "$debs_dir" ] || compgen -G "$debs_dir/*.deb" >/dev/null || fail "no .deb files in $debs_dir"

mkdir -p "$work" || fail "cannot create $work"
cd "$work" || fail "cannot enter $work"
work=$PWD

# ---- the kernel and systemd's packages (cached) ----
kernel_version
names=(systemd libsystemd-shared udev kmod)
mapfile -t systemd_packages < <(apt-cache show --no-all-versions "${names[@]}" 2>/dev/null |
    awk '/^Package: /{p = $2} /^Version: /{print p "=" $2}')
[ ${#systemd_packages[@]} -eq ${#names[@]} ] ||
    skip "apt-cache knows only ${systemd_packages[*]} of ${names[*]}"
vm_kernel "${systemd_packages[@]}"

# ---- the root ----
step "assembling the systemd initramfs"
root="$work/root-systemd"
rm -rf "$root"
mkdir -p "$root"/{bin,sbin,proc,sys,dev,run,tmp,var/tmp,var/log,var/lib,root,etc/systemd/system} \
    "$root/usr/lib/x86_64-linux-gnu" || fail "mkdir $root"
for p in "${systemd_packages[@]}"; do
    dpkg -x "$(deb "${p%%=*}" "${p#*=}")" "$root" || fail "dpkg -x $p"
done
rm -rf "$root/usr/share/"{doc,man,locale,bash-completion,zsh,lintian}
cp "$busybox" "$root/bin/busybox"
for applet in $applets; do
    [ -e "$root/bin/$applet" ] || [ -e "$root/sbin/$applet" ] || ln -s busybox "$root/bin/$applet"
done

# rtedge: its .deb files, or meson's install of the build (prefix as
# configured: the unit names the paths).
if [ -n "$debs_dir" ]; then
    for d in "$debs_dir"/*.deb; do
        dpkg -x "$d" "$root" || fail "dpkg -x $d"
    done
else
    rm -rf "$work/stage"
    meson install -C "$build" --destdir "$work/stage" --quiet >"$work/install.log" 2>&1 ||
        { tail -n 5 "$work/install.log"; fail "meson install"; }
    rm -rf "$work/stage"/*/{include,share/man,share/doc} "$work/stage"/*/*/{include,share/man,share/doc}
    cp -a "$work/stage/." "$root/" || fail "copying the installed tree"
fi
unit=$(find "$root" -path '*/lib/systemd/system/rtedged.service' | head -n 1)
[ -n "$unit" ] || fail "rtedged.service is not installed"
exec_start=$(sed -n 's/^ExecStart=//p' "$unit")
rtedged=$root${exec_start%% *}
conf=$root$(sed -n 's/.*--config \([^ ]*\).*/\1/p' <<<"$exec_start")
[ -x "$rtedged" ] && [ -f "$conf" ] || fail "$unit: no $rtedged or $conf"

# Libraries: systemd's and rtedged's closure; the installed libraries
# found through ld.so.cache.
libdirs=$(find "$root" -name 'librtedge*.so*' -printf '%h\n' | sort -u)
{ sed "s|^$root||" <<<"$libdirs"; echo /usr/lib/x86_64-linux-gnu; } >"$root/etc/ld.so.conf"
elves=$(find "$root/bin" "$root/lib/systemd" "$root/lib/udev" "$rtedged" -type f -perm -u+x)
LD_LIBRARY_PATH=$root/usr/lib/x86_64-linux-gnu/systemd:$(tr '\n' ':' <<<"$libdirs") \
    copy_libraries "$root" $elves
missing=$(LD_LIBRARY_PATH=$root/usr/lib/x86_64-linux-gnu/systemd:$(tr '\n' ':' <<<"$libdirs") \
          ldd $elves 2>/dev/null | grep 'not found' | sort -u)
[ -z "$missing" ] || fail "libraries not found: $missing"
ldconfig -r "$root" || fail "ldconfig -r $root"

# The modules, indexed by the guest's depmod (kmod's, run here): libkmod
# (systemd-modules-load, udev, modprobe) reads modules.dep.bin.
vm_modules "$root" vivid
for f in modules.order modules.builtin modules.builtin.modinfo; do
    cp "$modroot/$f" "$root/lib/modules/$kver/" || fail "no $f in the kernel package"
done
(exec -a depmod "$root/bin/kmod" -b "$root" "$kver") || fail "kmod's depmod"

# /etc: users and groups (sysusers adds systemd's), the machine, the
# camera's size and format and a file:// log (appended to across restarts)
# in rtedged's configuration, the units enabled, the test.
cat >"$root/etc/passwd" <<'EOF'
root:x:0:0:root:/root:/bin/sh
EOF
cat >"$root/etc/group" <<'EOF'
root:x:0:
video:x:44:
EOF
tr -d '-' </proc/sys/kernel/random/uuid >"$root/etc/machine-id"
printf 'ID=debian\nPRETTY_NAME="rtedge VM"\n' >"$root/etc/os-release"
# (and SCHED_FIFO with locked memory: what the unit's capabilities are for;
# the lane path only, as a vehicle runs it: the guest's one emulated CPU
# cannot run both paths at the camera's rate, and a SCHED_FIFO loop that
# always has a frame waiting leaves the guest's systemd no time)
sed -i -e '/^\[source\]/,/^\[/{s/^width = .*/width = 640/;s/^height = .*/height = 480/;s/^format = .*/format = yuyv/}' \
    -e '/^\[publish\]/,/^\[/{s|^url = .*|url = file:///var/log/rtedge/vm.lcm?mode=a|}' \
    -e '/^\[grasp\]/,/^\[/{s/^enabled = .*/enabled = false/}' \
    -e '/^\[realtime\]/,/^\[/{s/^priority = .*/priority = 10/;s/^mlockall = .*/mlockall = true/}' "$conf"
[ "$(grep -cE '^(width = 640|height = 480|format = yuyv|url = file:///var/log/rtedge/vm.lcm\?mode=a|priority = 10|mlockall = true)$' "$conf")" = 6 ] &&
    sed -n '/^\[grasp\]/,/^\[/p' "$conf" | grep -qx 'enabled = false' ||
    fail "$conf: the camera's size and format, the log, the paths and the realtime keys are not set"
install -D -m 755 "$here/systemd_test.sh" "$root/usr/local/sbin/rte-vm-test"
cat >"$root/etc/systemd/system/rte-vm-test.service" <<'EOF'
[Unit]
Description=rtedge VM test of rtedged.service
[Service]
Type=oneshot
ExecStart=/bin/sh /usr/local/sbin/rte-vm-test
[Install]
WantedBy=multi-user.target
EOF
# What this guest has no use for (logins, a getty on the console, TPM,
# partitions, binfmt): masked, to boot faster.
systemctl --root="$root" --quiet mask getty.target systemd-logind.service \
    systemd-user-sessions.service systemd-ask-password-wall.path \
    systemd-ask-password-console.path systemd-firstboot.service systemd-machine-id-commit.service \
    systemd-pcrphase.service systemd-pcrphase-sysinit.service systemd-repart.service \
    systemd-update-utmp.service systemd-update-utmp-runlevel.service systemd-binfmt.service \
    proc-sys-fs-binfmt_misc.automount systemd-random-seed.service systemd-tmpfiles-clean.timer \
    systemd-journald-audit.socket systemd-initctl.socket cryptsetup.target \
    integritysetup.target veritysetup.target || fail "systemctl mask"
systemctl --root="$root" --quiet enable rtedged.service rte-vm-test.service ||
    fail "systemctl enable"

(cd "$root" && find . | "$busybox" cpio -o -H newc >"$work/initramfs-systemd.cpio" 2>/dev/null) ||
    fail "cpio"
step "initramfs: $(du -m "$work/initramfs-systemd.cpio" | cut -f1) MB"

boot "$work/initramfs-systemd.cpio" "$work/console-systemd.txt" \
    "rdinit=/lib/systemd/systemd systemd.unit=multi-user.target systemd.show_status=0"
cat "$work/console-systemd.txt"

bad=0
verdict "$work/console-systemd.txt" systemd-wait systemd-ready systemd-sandbox systemd-realtime \
    systemd-messages systemd-watchdog
grep -q '^RTE-VM end' "$work/console-systemd.txt" || { echo "FAIL: the VM did not finish its tests"; bad=1; }
exit $bad
