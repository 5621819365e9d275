#!/bin/sh
# tools/rtedge-spy on a virtual X server (Xvfb) in a private network
# namespace (run inside tests/lcm/netns.sh) while rtedged publishes over
# udpm:// there: the Spy window must appear (xwininfo), list every channel
# of rtedged with its rtedge type decoded, and open a channel's viewer when
# its row is double-clicked. A probe agent in the Spy's JVM
# (java/SpyProbe.java) reads the window's table and does the double-click.
# A screenshot goes to OUTDIR/spy.png. Fails if the Spy exits.
#   spy.sh RTEDGE_SPY TYPES_JAR SPYPROBE_JAVA RTEDGED OUTDIR Y4M
set -u
SPY=$1 TYPES_JAR=$2 PROBE_SRC=$3 RTEDGED=$4 OUT=$5/spy_test Y4M=$6
URL='udpm://239.255.76.67:7667?ttl=0'
for p in Xvfb:xvfb xwininfo:x11-utils javac:default-jdk-headless jar:default-jdk-headless \
    ffmpeg:ffmpeg; do
    command -v "${p%%:*}" >/dev/null || { echo "SKIP: ${p%%:*} missing (Debian ${p#*:})"; exit 77; }
done
java_home=$(dirname "$(dirname "$(readlink -f "$(command -v java)")")")
ls "$java_home"/lib/libawt_xawt.* >/dev/null 2>&1 ||
    { echo "SKIP: $java_home is a headless Java (Debian default-jre)"; exit 77; }
[ -f /usr/share/java/jchart2d.jar ] || { echo "SKIP: jchart2d.jar missing (Debian libjchart2d-java)"; exit 77; }
rm -rf "$OUT"
mkdir -p "$OUT/probe"
pids=
cleanup() { for p in $pids; do kill "$p" 2>/dev/null; done; }
trap cleanup EXIT
fail() {
    echo "FAIL: $*"
    echo "--- rtedge-spy's output:"; cat "$OUT/spy.log"
    exit 1
}

# The probe agent.
javac -d "$OUT/probe" "$PROBE_SRC" || fail "javac SpyProbe.java"
printf 'Premain-Class: SpyProbe\n' >"$OUT/probe/manifest"
jar cfm "$OUT/probe.jar" "$OUT/probe/manifest" -C "$OUT/probe" . || fail "jar"

# Xvfb picks a free display and writes its number to fd 3.
Xvfb -displayfd 3 -screen 0 1480x800x24 -nolisten tcp 3>"$OUT/display" 2>"$OUT/xvfb.log" &
pids="$pids $!"
for _ in $(seq 50); do
    [ -s "$OUT/display" ] && break
    sleep 0.1
done
[ -s "$OUT/display" ] || { cat "$OUT/xvfb.log"; echo "FAIL: Xvfb did not start"; exit 1; }
DISPLAY=:$(cat "$OUT/display")
export DISPLAY

# rtedged: lanes, grasps, status, the parameters' state, the frames and the
# debug overlay stream, looping the recording until the end of the test.
"$RTEDGED" --source "$Y4M" --fps 25 --loop --deadline-ms 1000 --lcm-url "$URL" \
    --set publish.images=true --set debug.enabled=true 2>"$OUT/rtedged.log" &
pids="$pids $!"

JAVA_TOOL_OPTIONS="-javaagent:$OUT/probe.jar=$OUT/table.txt,RTEDGE_LANES" \
    "$SPY" --lcm-url="$URL" --types-jar "$TYPES_JAR" >"$OUT/spy.log" 2>&1 &
spy=$!
pids="$pids $spy"

# channel type: what rtedged publishes (rtedged.conf's default channels).
expect='RTEDGE_LANES lane_detection_t
RTEDGE_GRASP grasp_detection_t
RTEDGE_STATUS status_t
RTEDGE_PARAM_STATE param_state_t
RTEDGE_IMAGE image_t
RTEDGE_DEBUG image_t'
missing=x
# Java's start on a loaded 2-core machine (the suites run side by side) can
# take tens of seconds: wait up to a minute.
end=$(($(date +%s) + 60))
while [ "$(date +%s)" -lt "$end" ]; do
    kill -0 "$spy" 2>/dev/null || fail "rtedge-spy exited"
    if [ -f "$OUT/table.txt" ] && xwininfo -root -tree | grep -q '"LCM Spy"'; then
        missing=$(echo "$expect" | while read -r ch type; do
            grep -q "^row	$ch	$type	[1-9]" "$OUT/table.txt" || echo "$ch $type"
        done)
        [ -z "$missing" ] && grep -q "^window	RTEDGE_LANES" "$OUT/table.txt" && break
    fi
    sleep 0.1
done
[ -f "$OUT/table.txt" ] || fail "no Spy window within 60 s"
xwininfo -root -tree | grep -q '"LCM Spy"' || fail "no 'LCM Spy' window on the X server"
[ -z "$missing" ] || fail "channels not listed with their types: $missing; the table: $(cat "$OUT/table.txt")"
grep -q "^window	RTEDGE_LANES" "$OUT/table.txt" ||
    fail "double-clicking RTEDGE_LANES opened no viewer: $(cat "$OUT/table.txt")"
echo "ok: the Spy window lists:"
grep '^row' "$OUT/table.txt" | cut -f2-4 | sed 's/	/  /g; s/^/  /'
echo "ok: its RTEDGE_LANES viewer opened; the windows on the X server:"
xwininfo -root -tree | grep -E '"(LCM Spy|RTEDGE_LANES)"' | sed 's/^ */  /'
sleep 1   # the viewer's first paint
ffmpeg -loglevel error -y -f x11grab -video_size 1480x800 -i "$DISPLAY" -frames:v 1 "$OUT/spy.png" ||
    fail "screenshot"
kill -0 "$spy" 2>/dev/null || fail "rtedge-spy exited"
echo "screenshot: $OUT/spy.png"
