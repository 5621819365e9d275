#!/bin/sh
# The systemd unit as built: `systemd-analyze verify` accepts it (with the
# built rtedged in ExecStart, no man page lookup) and
# `systemd-analyze security` rates its exposure at most 3.0 (--threshold
# is the exposure times 10: the command fails above it).
#   check_unit.sh UNIT RTEDGED TMPDIR
set -u
unit=$1 rtedged=$2 tmp=$3/check_unit.$$
case $rtedged in /*) ;; *) rtedged=$PWD/$rtedged ;; esac
fail() { echo "FAIL: $*"; exit 1; }
command -v systemd-analyze >/dev/null || { echo "SKIP: no systemd-analyze (Debian's systemd)"; exit 77; }
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT
sed "s|^ExecStart=[^ ]*|ExecStart=$rtedged|" "$unit" >"$tmp/rtedged.service"
systemd-analyze verify --man=no "$tmp/rtedged.service" >"$tmp/verify" 2>&1 ||
    fail "systemd-analyze verify: $(cat "$tmp/verify")"
echo "ok: systemd-analyze verify"
systemd-analyze security --offline=true --threshold=30 "$tmp/rtedged.service" >"$tmp/security" 2>&1
rc=$?
grep -v '✓' "$tmp/security"
[ $rc -eq 0 ] || fail "exposure above 3.0: $(tail -1 "$tmp/security")"
grep -q 'Overall exposure level' "$tmp/security" || fail "no exposure figure"
echo "ok: $(tail -1 "$tmp/security" | sed 's/^→ //')"
