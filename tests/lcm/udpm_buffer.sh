#!/bin/sh
# lcm-logger keeps every image_t of a burst from rtedged over udpm:// with the
# receive buffers of data/sysctl.d/60-rtedge-lcm.conf (tools/lcm_burst, the
# logger stalled during the burst), in a private network namespace
# (tests/lcm/netns.sh). First the namespace's own values, reported; then the
# drop-in's values: applied with `sysctl -p` inside the namespace where the
# kernel keeps net.core.rmem_* per namespace, otherwise (they are the host's,
# read-only in a namespace) asked for by lcm-logger's socket with the URL's
# recv_buf_size (rmem_default / 2: the kernel doubles SO_RCVBUF). The host's
# values are checked afterwards and put back if a write in the namespace
# reached them.
#   udpm_buffer.sh LCM_BURST NETNS_SH DROPIN RTEDGED TYPES_DIR Y4M
set -u
BURST=$1 NETNS=$2 DROPIN=$3
shift 3
URL='udpm://239.255.76.67:7667?ttl=0'
value() { sed -n "s/^$1 *= *//p" "$DROPIN"; }

if [ "${RTE_UDPM_BUFFER_INSIDE:-}" != 1 ]; then
    host_max=$(cat /proc/sys/net/core/rmem_max) host_default=$(cat /proc/sys/net/core/rmem_default)
    RTE_UDPM_BUFFER_INSIDE=1 "$NETNS" "$0" "$BURST" "$NETNS" "$DROPIN" "$@"
    rc=$?
    if [ "$(cat /proc/sys/net/core/rmem_max)" != "$host_max" ] ||
        [ "$(cat /proc/sys/net/core/rmem_default)" != "$host_default" ]; then
        sysctl -q -w net.core.rmem_max="$host_max" net.core.rmem_default="$host_default"
        echo "FAIL: sysctl -p in the namespace changed the host's net.core.rmem_* (put back)"
        exit 1
    fi
    exit $rc
fi

RTEDGED=$1 TYPES=$2 Y4M=$3
command -v lcm-logger >/dev/null || { echo "SKIP: lcm-logger (liblcm-bin) missing"; exit 77; }
command -v ss >/dev/null || { echo "SKIP: ss (iproute2) missing"; exit 77; }
burst() { "$BURST" --rtedged "$RTEDGED" --types "$TYPES" --source "$Y4M" --url "$URL" "$@"; }
fail() { echo "FAIL: $*"; exit 1; }

# The namespace's own values (the kernel's, or what the host set).
out=$(burst --stream debug)
[ $? -le 1 ] || fail "tools/lcm_burst: $out"
echo "net.core.rmem_default = $(cat /proc/sys/net/core/rmem_default): $out"

want_max=$(value net.core.rmem_max) want_default=$(value net.core.rmem_default)
[ -n "$want_max" ] && [ -n "$want_default" ] || fail "no rmem_max/rmem_default in $DROPIN"
# (sysctl -p's exit code does not tell: the values read back do.)
sysctl -q -p "$DROPIN" 2>/dev/null
if [ "$(cat /proc/sys/net/core/rmem_default)" = "$want_default" ] &&
    [ "$(cat /proc/sys/net/core/rmem_max)" = "$want_max" ]; then
    logger_url=$URL
    how="in force in the namespace (sysctl -p)"
else
    echo "SKIP (part): net.core.rmem_* cannot be set in a network namespace on this kernel" \
        "($(uname -r): they are the host's, read-only here); the drop-in's" \
        "rmem_default is asked for by lcm-logger's socket instead (recv_buf_size)"
    half=$((want_default / 2))
    if [ "$(cat /proc/sys/net/core/rmem_max)" -lt "$half" ]; then
        echo "SKIP: the host's net.core.rmem_max ($(cat /proc/sys/net/core/rmem_max)) is below" \
            "$half: no socket here can have the drop-in's buffer"
        exit 77
    fi
    logger_url="$URL&recv_buf_size=$half"
    how="lcm-logger's socket asked for it"
fi
out=$(burst --stream debug --logger-url "$logger_url")
rc=$?
echo "the drop-in's rmem_default = $want_default ($how): $out"
case " $out " in *" receive buffer $want_default bytes"*) ;; *) fail "not the drop-in's buffer" ;; esac
case " $out " in *" 0 bytes queued"*) fail "nothing waited in the socket: was lcm-logger stalled?" ;; esac
[ $rc -eq 0 ] || fail "lcm-logger lost image_t with the drop-in's receive buffer"
echo "ok: every image_t of the burst kept"
