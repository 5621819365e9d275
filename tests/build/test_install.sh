#!/bin/sh
# `meson install` into a staging folder, then what a user does with the
# result: build a program against the installed headers and pkg-config file
# and run it, check the installed daemon's configuration with the installed
# rtedged, and check that the systemd unit starts that rtedged with that file.
#   test_install.sh BUILD_DIR CONSUMER_SOURCE SOURCE_DIR
set -eu
build=$1
consumer=$2
source=$3
dest=$(mktemp -d)
trap 'rm -rf "$dest"' EXIT

meson install -C "$build" --destdir "$dest" --no-rebuild --quiet >/dev/null
prefix=$(meson introspect "$build" --buildoptions |
    /usr/bin/python3 -c 'import json, sys; print([o["value"] for o in json.load(sys.stdin) if o["name"] == "prefix"][0])')
root=$dest$prefix

fail() { echo "FAIL: $*"; exit 1; }
pc=$(find "$root" -name rtedge.pc)
[ -n "$pc" ] || fail "no rtedge.pc under $root"
libdir=$(dirname "$(dirname "$pc")")
[ -e "$libdir/librtedge.so" ] || fail "no librtedge.so in $libdir"
# include/rtedge is the public API: exactly its headers are installed.
src_headers=$(cd "$source/include/rtedge" && ls)
installed=$(cd "$root/include/rtedge" && ls)
[ "$installed" = "$src_headers" ] ||
    fail "installed headers differ from include/rtedge: $(echo "$installed" | tr '\n' ' ')"
nheaders=$(echo "$installed" | wc -l)
# The shared library's ABI: it exports exactly what the headers declare
# with RTE_API (one declaration per line, the name before its '(').
declared=$(grep -ho '^RTE_API [^(;[]*' "$root"/include/rtedge/*.h | sed 's/.*[ *]//' | sort -u)
exported=$(nm -D --defined-only "$libdir/librtedge.so" | awk '$2 != "A" { sub(/@.*/, "", $3); print $3 }' | sort -u)
[ -n "$declared" ] && [ "$declared" = "$exported" ] ||
    fail "librtedge.so exports other symbols than the RTE_API declarations: $(echo "$declared" "$exported" | tr ' ' '\n' | sort | uniq -u | tr '\n' ' ')"
nsymbols=$(echo "$exported" | wc -l)

# A program built as a user builds one.
flags=$(PKG_CONFIG_PATH="$libdir/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$dest" pkg-config --cflags --libs rtedge)
${CC:-cc} -std=c11 -Wall -Werror -o "$dest/consumer" "$consumer" $flags ||
    fail "cannot build against the installed headers ($flags)"
LD_LIBRARY_PATH=$libdir "$dest/consumer" "$dest/step.png" || fail "the program built against the installed librtedge failed"

# The daemon, its configuration and the systemd unit (when LCM is built).
if [ -x "$root/bin/rtedged" ]; then
    conf=$(find "$root" -path '*rtedge/rtedged.conf')
    [ -n "$conf" ] || fail "rtedged.conf not installed"
    LD_LIBRARY_PATH=$libdir "$root/bin/rtedged" --config "$conf" --check-config >/dev/null ||
        fail "the installed rtedged refuses the installed $conf"
    unit=$root/lib/systemd/system/rtedged.service
    [ -f "$unit" ] || fail "no systemd unit at $unit"
    exec_start=$(sed -n 's/^ExecStart=//p' "$unit")
    [ "$exec_start" = "$prefix/bin/rtedged --config ${conf#"$dest"}" ] ||
        fail "the unit runs '$exec_start', not the installed rtedged with the installed configuration"
    for lcm in "$root"/share/rtedge/lcmtypes/*.lcm; do
        [ -f "$lcm" ] || fail "no LCM type definitions installed"
    done
    for f in share/man/man8/rtedged.8 share/man/man5/rtedged.conf.5 \
        share/bash-completion/completions/rtedged; do
        [ -f "$root/$f" ] || fail "$f not installed"
    done
    echo "ok: rtedged, ${conf#"$dest"}, the unit, its man pages, completion and $(ls "$root"/share/rtedge/lcmtypes | wc -l) LCM types installed"
    grep -q '^net.core.rmem_default = ' "$root/lib/sysctl.d/60-rtedge-lcm.conf" ||
        fail "no receive buffers in $root/lib/sysctl.d/60-rtedge-lcm.conf"
    grep -qx videodev "$root/lib/modules-load.d/rtedged.conf" ||
        fail "no videodev in $root/lib/modules-load.d/rtedged.conf (the unit's DeviceAllow= needs it)"
    if [ -f "$root/share/java/rtedge-lcmtypes.jar" ]; then
        [ -x "$root/bin/rtedge-spy" ] || fail "no rtedge-spy beside the Java types"
        # Past lcm.jar and the installed types jar, it stops at Java or the display.
        DISPLAY= "$root/bin/rtedge-spy" 2>&1 | grep -q -E 'no display|java not found|headless Java' ||
            fail "the installed rtedge-spy: $(DISPLAY= "$root/bin/rtedge-spy" 2>&1)"
        echo "ok: rtedge-spy finds the installed types jar; the sysctl.d drop-in installed"
    fi
fi
# rtedge's and the tools' man pages, and rtedge's bash completion.
for f in share/man/man1/rtedge.1 share/man/man1/rtedge-subscribe.1 \
    share/man/man1/rtedge-render-log.1 share/man/man1/rtedge-web.1 share/man/man1/rtedge-spy.1 \
    share/bash-completion/completions/rtedge; do
    [ -f "$root/$f" ] || fail "$f not installed"
done
echo "ok: librtedge ($nsymbols symbols), $nheaders headers and rtedge.pc installed under $prefix; a program built with them runs"
