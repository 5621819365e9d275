#!/bin/sh
# Runs a command in a private network namespace whose loopback carries
# multicast, so udpm:// traffic never leaves it (and never reaches another
# interface). Exit 77 (skipped) when namespaces are not permitted.
#   netns.sh COMMAND [ARGS...]
if ! command -v unshare >/dev/null || ! command -v ip >/dev/null; then
    echo "skipped: unshare or ip (util-linux, iproute2) missing"
    exit 77
fi
if ! unshare -n true 2>/dev/null; then
    if ! unshare -r -n true 2>/dev/null; then
        echo "skipped: unshare -n is not permitted here"
        exit 77
    fi
    userns=-r
fi
exec unshare ${userns:-} -n sh -c '
    ip link set lo up multicast on &&
    ip route add 224.0.0.0/4 dev lo || { echo "cannot set up multicast on lo"; exit 1; }
    exec "$@"' netns "$@"
