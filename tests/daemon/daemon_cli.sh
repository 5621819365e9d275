#!/bin/sh
# rtedged as a program: rtedged.conf is what --help-config prints, every
# kind of bad configuration exits 2 with file:line, SIGTERM finishes with a
# final status and exit 0, SIGHUP applies a runtime key and refuses a size.
#   daemon_cli.sh RTEDGED SUBSCRIBE_PY TYPES_DIR TMPDIR Y4M CONF
set -u
RTEDGED=$1 SUB=$2 TYPES=$3 TMP=$4/daemon_cli.$$ Y4M=$5 CONF=$6
PY=/usr/bin/python3
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
summary() { $PY "$SUB" --types "$TYPES" --quiet --summary "$1"; }
field() { $PY -c 'import json,sys; d=json.loads(sys.argv[1]); exec("print(" + sys.argv[2] + ")")' "$1" "$2"; }

# The documented default file is the table's own output.
"$RTEDGED" --help-config | diff -u "$CONF" - >/dev/null ||
    fail "rtedged.conf differs from rtedged --help-config (regenerate it)"
"$RTEDGED" --config "$CONF" --check-config >"$TMP/eff" || fail "--check-config on rtedged.conf"
grep -q '^\[realtime\]' "$TMP/eff" || fail "--check-config prints no [realtime]"
echo "ok: rtedged.conf and --check-config"
"$RTEDGED" --version | grep -Eq '^rtedged [0-9]+\.[0-9]+\.[0-9]+ \(git [^)]+\)$' ||
    fail "--version: $("$RTEDGED" --version)"
# --dump-config writes a commented rtedged.conf that reads back to the same
# effective configuration, text with ';' and a choice among its values.
DUMP_SETS="--set lane.canny_mode=fixed --set lane.canny_low=40 --set lane.canny_high=120"
# shellcheck disable=SC2086
"$RTEDGED" --config "$CONF" $DUMP_SETS --set 'lane.roi=0,1;0.4,0.6;0.6,0.6;1,1' \
    --dump-config "$TMP/dumped.conf" || fail "--dump-config"
# shellcheck disable=SC2086
"$RTEDGED" --config "$CONF" $DUMP_SETS --set 'lane.roi=0,1;0.4,0.6;0.6,0.6;1,1' \
    --check-config >"$TMP/eff1" || fail "--check-config with the dump's options"
"$RTEDGED" --config "$TMP/dumped.conf" --check-config >"$TMP/eff2" || fail "the dump is refused"
cmp -s "$TMP/eff1" "$TMP/eff2" || fail "the dump reads back differently: $(diff "$TMP/eff1" "$TMP/eff2")"
grep -q '^# Canny thresholds' "$TMP/dumped.conf" || fail "the dump has no help comments"
"$RTEDGED" --dump-config - | grep -q '^canny_mode = median$' || fail "--dump-config - (stdout)"
"$RTEDGED" --dump-config "$TMP/no/such/dir.conf" 2>"$TMP/err"
[ $? -eq 1 ] && grep -q "cannot create" "$TMP/err" || fail "--dump-config to a bad path: $(cat "$TMP/err")"
echo "ok: --dump-config round trip"

# Inline comments: '#' after a blank ends the line; ';' separates list items.
printf '[grasp] # objects\nthreshold = 3\t# inline\n[lane]\nroi = 0,1;0.4,0.6;0.6,0.6;1,1 # fractions\n' >"$TMP/inline.conf"
"$RTEDGED" --config "$TMP/inline.conf" --check-config >"$TMP/eff" || fail "inline comments refused"
grep -qx 'threshold = 3' "$TMP/eff" && grep -qx 'roi = 0,1;0.4,0.6;0.6,0.6;1,1' "$TMP/eff" ||
    fail "inline comments: $(grep -e '^threshold' -e '^roi' "$TMP/eff")"
# A text value the file could not hold (it would read back as a comment) is refused.
"$RTEDGED" --set 'source.path=run #3.y4m' --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "begins a comment" "$TMP/err" || fail "'#' in a value: $(cat "$TMP/err")"
echo "ok: inline comments"

# Bad configurations: exit 2 and the file:line in the message.
bad() { # NAME LINE EXPECTED-TEXT CONTENT
    printf '%b' "$4" >"$TMP/$1.conf"
    "$RTEDGED" --config "$TMP/$1.conf" --check-config >/dev/null 2>"$TMP/err"
    rc=$?
    [ $rc -eq 2 ] || fail "$1: exit $rc, not 2"
    grep -q "$TMP/$1.conf:$2: .*$3" "$TMP/err" || fail "$1: message '$(cat "$TMP/err")'"
    echo "ok: $1: $(cat "$TMP/err")"
}
bad unknown_key 2 "unknown key 'foo'" '[lane]\nfoo = 1\n'
bad wrong_type 3 "not an integer" '# c\n[lane]\ncanny_low = abc\n'
bad bad_bool 2 "not a boolean" '[source]\nloop = maybe\n'
bad out_of_range 2 "out of range 0..255" '[grasp]\nthreshold = 300\n'
bad real_range 2 "out of range" '[source]\nspeed = 0\n'
bad threads 3 "out of range 1..2" '[realtime]\ncpu = 0\nthreads = 3\n'
bad bad_enum 2 "not one of" '[source]\npace = warp\n'
bad bad_section 1 "unknown section \[nosuch\]" '[nosuch]\nx = 1\n'
bad broken_header 1 "bad section header" '[lane\n'
bad duplicate 3 "duplicate key grasp.threshold" '[grasp]\nthreshold = 3\nthreshold = 4\n'
bad no_equals 2 "expected 'key = value'" '[grasp]\nthreshold\n'
bad no_section 1 "outside a \[section\]" 'threshold = 3\n'
# Command-line and cross-key errors: exit 2 too.
"$RTEDGED" --set grasp.threshold=-1 --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "out of range" "$TMP/err" || fail "--set out of range"
"$RTEDGED" --set lane.canny_low=100 --set lane.canny_high=50 --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "exceeds" "$TMP/err" || fail "canny low > high"
"$RTEDGED" --deadline-ms abc --check-config 2>/dev/null >/dev/null
[ $? -eq 2 ] || fail "--deadline-ms abc"
"$RTEDGED" --bogus 2>/dev/null >/dev/null
[ $? -eq 2 ] || fail "unknown option"
# Values that are in a type's range but nonsense for a daemon.
for set in 'deadline.ms=1e-300:out of range 0.1..10000 (or 0)' \
           'lane.hough_threshold=100000:out of range 1..16384 (or -1)' \
           'grasp.min_area=100000000:out of range 0..67108864' \
           'params.keys=lane.roi,lane.max_segments:max_segments' \
           'params.keys=source.path:not a runtime key' \
           'params.channel=RTEDGE_.*:not a channel name'; do
    "$RTEDGED" --set "${set%%:*}" --check-config 2>"$TMP/err" >/dev/null
    [ $? -eq 2 ] && grep -qF "${set#*:}" "$TMP/err" || fail "--set ${set%%:*}: $(cat "$TMP/err")"
done
# A NUL byte in a configuration line is said as such.
printf '[grasp]\nthreshold = 3\0\n' >"$TMP/nul.conf"
"$RTEDGED" --config "$TMP/nul.conf" --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "nul.conf:2: a NUL byte in the line" "$TMP/err" || fail "NUL: $(cat "$TMP/err")"
# A line over the limit is refused, never cut.
{ printf '[source]\npath = '; head -c 1100 /dev/zero | tr '\0' a; printf '\n'; } >"$TMP/long.conf"
"$RTEDGED" --config "$TMP/long.conf" --check-config 2>"$TMP/err" >/dev/null
[ $? -eq 2 ] && grep -q "long.conf:2: line longer than 1022 characters" "$TMP/err" ||
    fail "long line: $(cat "$TMP/err")"
echo "ok: command-line errors"

# Values that do not fit the source's frames (480x270): refused at start, exit 1.
for set in 'grasp.min_area=200000:grasp.min_area = 200000 px is beyond the 480x270 frame' \
           'lane.roi=0.5,0.5;0.51,0.5;0.5,0.51:lane.roi: '"'"'0.5,0.5;0.51,0.5;0.5,0.51'"'"' covers 6x4 px' \
           'lane.max_gap=2000:lane.max_gap = 2000 is beyond'; do
    "$RTEDGED" --source "$Y4M" --fast --max-frames 2 --lcm-url "file://$TMP/fit.lcm" \
        --set "${set%%:*}" 2>"$TMP/err" >/dev/null
    [ $? -eq 1 ] && grep -qF "does not fit the source: ${set#*:}" "$TMP/err" ||
        fail "--set ${set%%:*}: $(cat "$TMP/err")"
done
echo "ok: values that do not fit the source"

# Recordings that cannot spin: a header whose size overflows is refused; a
# looping recording without one readable frame stops (exit 3) at once; one
# with a bad frame among good ones says it once, not at every pass.
printf 'YUV4MPEG2 W4294967300 H2 F30:1 Cmono\nFRAME\n' >"$TMP/wrap.y4m"
"$RTEDGED" --source "$TMP/wrap.y4m" --lcm-url "file://$TMP/wrap.lcm" 2>"$TMP/err" >/dev/null
[ $? -eq 1 ] && grep -q "bad frame width in tag 'W4294967300'" "$TMP/err" ||
    fail "W4294967300: $(cat "$TMP/err")"
printf 'YUV4MPEG2 W64 H48 F30:1 Cmono\n' >"$TMP/header.y4m"
printf 'YUV4MPEG2 W64 H48 F30:1 Cmono\nFRAME\nabc' >"$TMP/cut.y4m"
for rec in header cut; do
    timeout 10 "$RTEDGED" --source "$TMP/$rec.y4m" --loop --fast --lcm-url "file://$TMP/$rec.lcm" \
        2>"$TMP/err" >/dev/null
    rc=$?
    [ $rc -eq 3 ] && grep -q "gave no readable frame" "$TMP/err" && [ "$(wc -l <"$TMP/err")" -le 3 ] ||
        fail "$rec.y4m --loop: exit $rc, $(wc -l <"$TMP/err") lines: $(head -5 "$TMP/err")"
done
$PY - "$Y4M" "$TMP/onebad.y4m" <<'EOP' || fail "cannot make onebad.y4m"
import sys
src, dst = open(sys.argv[1], "rb"), open(sys.argv[2], "wb")
header = src.readline()
w, h = [int(t[1:]) for t in header.split()[1:3]]
dst.write(header)
for i in range(4):
    src.readline()
    frame = src.read(w * h)
    dst.write((b"FRAMX\n" if i == 2 else b"FRAME\n") + frame)
EOP
"$RTEDGED" --source "$TMP/onebad.y4m" --loop --fast --max-frames 600 --lcm-url "file://$TMP/ob.lcm" \
    --set publish.status_period_ms=60000 2>"$TMP/err" >/dev/null || fail "onebad: exit $?"
lines=$(wc -l <"$TMP/err")
[ "$lines" -le 3 ] && grep -q "600 processed" "$TMP/err" && ! grep -q "streaming again" "$TMP/err" ||
    fail "onebad.y4m looped: $lines lines: $(head -5 "$TMP/err")"
s=$(summary "$TMP/ob.lcm")
[ "$(field "$s" 'd["statuses"]')" -eq 2 ] || fail "onebad.y4m: statuses: $s"
echo "ok: recordings that cannot spin ($lines stderr lines for 600 frames over 199 rewinds)"

# SIGTERM: finish the frame, final status, exit 0.
"$RTEDGED" --source "$Y4M" --loop --fps 50 --lcm-url "file://$TMP/term.lcm" 2>"$TMP/term.err" &
pid=$!
sleep 1.5
kill -TERM $pid
wait $pid
rc=$?
[ $rc -eq 0 ] || fail "SIGTERM: exit $rc: $(cat "$TMP/term.err")"
s=$(summary "$TMP/term.lcm")
lanes=$(field "$s" 'd["lanes"]')
final=$(field "$s" 'd["last_status"]["frames_processed"]')
[ "$lanes" -gt 10 ] || fail "SIGTERM: only $lanes lane messages"
[ "$final" -eq "$lanes" ] || fail "SIGTERM: final status says $final frames, $lanes published"
tail -c 1000 "$TMP/term.lcm" | grep -q RTEDGE_STATUS || fail "SIGTERM: the log does not end with a status"
echo "ok: SIGTERM after $lanes frames, final status, exit 0"

# SIGHUP: a runtime key applied at the next frame, a size change refused.
cat >"$TMP/hup.conf" <<EOC
[source]
path = $Y4M
loop = true
pace = fps
fps = 50
[publish]
url = file://$TMP/hup.lcm
EOC
"$RTEDGED" --config "$TMP/hup.conf" 2>"$TMP/hup.err" &
pid=$!
sleep 1
# the clip's frame area (480x270): no object is that large
printf '[grasp]\nmin_area = 129600\n' >>"$TMP/hup.conf"
kill -HUP $pid
sleep 1
printf 'max_objects = 5\n' >>"$TMP/hup.conf"
kill -HUP $pid
sleep 1
kill -TERM $pid
wait $pid || fail "SIGHUP run: exit $?"
grep -q "re-read and applied" "$TMP/hup.err" || fail "SIGHUP: not applied: $(cat "$TMP/hup.err")"
grep -q "refused: grasp.max_objects cannot change" "$TMP/hup.err" ||
    fail "SIGHUP: size change not refused: $(cat "$TMP/hup.err")"
grep -q "1 reloads, 1 refused" "$TMP/hup.err" || fail "SIGHUP counters: $(tail -1 "$TMP/hup.err")"
s=$(summary "$TMP/hup.lcm")
[ "$(field "$s" 'd["objects_last"]')" -eq 0 ] || fail "SIGHUP: min_area not applied"
[ "$(field "$s" 'len(d["config_hashes"])')" -eq 2 ] || fail "SIGHUP: status hashes $s"
echo "ok: SIGHUP applied grasp.min_area, refused grasp.max_objects"

# [realtime]: SCHED_FIFO, affinity and mlockall are applied or warned about, never fatal.
"$RTEDGED" --source "$Y4M" --fast --max-frames 3 --lcm-url "file://$TMP/rt.lcm" \
    --set realtime.priority=10 --set realtime.cpu=0 --set realtime.mlockall=true 2>"$TMP/rt.err" ||
    fail "realtime: exit $?: $(cat "$TMP/rt.err")"
grep -q "3 processed" "$TMP/rt.err" || fail "realtime: $(cat "$TMP/rt.err")"
echo "ok: realtime settings: $(grep -c warning "$TMP/rt.err") warnings: $(grep warning "$TMP/rt.err" | tr '\n' ' ')"

# realtime.cpu_dma_latency_us: the PM QoS request holds while rtedged runs and
# goes with it (the kernel's target is the least of all requests: checked where
# none below 7 was there before); where /dev/cpu_dma_latency may not be
# written, a warning.
qos() { od -An -td4 -N4 /dev/cpu_dma_latency 2>/dev/null | tr -d ' '; }
before=$(qos) during= watch=
[ -w /dev/cpu_dma_latency ] && [ "${before:-0}" -gt 7 ] && watch=1
"$RTEDGED" --source "$Y4M" --speed 0.05 --lcm-url "file://$TMP/qos.lcm" \
    --set realtime.cpu_dma_latency_us=7 2>"$TMP/qos.err" &
pid=$!
if [ -n "$watch" ]; then
    for _ in $(seq 50); do
        during=$(qos)
        [ "$during" = 7 ] && break
        sleep 0.2
    done
else
    sleep 1
fi
kill -TERM $pid
wait $pid || fail "cpu_dma_latency_us: exit $?: $(cat "$TMP/qos.err")"
if [ -n "$watch" ]; then
    [ "$during" = 7 ] || fail "cpu_dma_latency_us = 7: the kernel's target was $during while rtedged ran"
    [ "$(qos)" = "$before" ] || fail "cpu_dma_latency_us: $(qos) after rtedged ended, $before before"
    echo "ok: realtime.cpu_dma_latency_us = 7 held while running ($before before and after)"
elif [ -w /dev/cpu_dma_latency ]; then
    echo "ok: realtime.cpu_dma_latency_us: not checked (a request of $before us was there before)"
else
    grep -q "realtime.cpu_dma_latency_us = 7: /dev/cpu_dma_latency: .* (not set)" "$TMP/qos.err" ||
        fail "cpu_dma_latency_us without access: no warning: $(cat "$TMP/qos.err")"
    echo "ok: realtime.cpu_dma_latency_us without access to /dev/cpu_dma_latency: a warning"
fi

# A slow recorded pace still stops at once on SIGTERM (no wait for the next frame's time).
"$RTEDGED" --source "$Y4M" --speed 0.01 --lcm-url "file://$TMP/slow.lcm" 2>"$TMP/slow.err" &
pid=$!
sleep 1
kill -TERM $pid
start=$(date +%s)
wait $pid || fail "slow: exit $?"
[ $(( $(date +%s) - start )) -le 1 ] || fail "slow pace: SIGTERM took too long"
echo "ok: SIGTERM during a long wait for a frame's time"

# A camera that is not there, not waited for (source.wait; tests/daemon/test_notify.py
# waits): a clear message and exit 1 (not a configuration error).
"$RTEDGED" --source /dev/video99 --set source.wait=false --lcm-url "file://$TMP/cam.lcm" \
    2>"$TMP/cam.err" >/dev/null
rc=$?
[ $rc -eq 1 ] && grep -q "cannot open v4l2 source /dev/video99" "$TMP/cam.err" ||
    fail "missing camera: exit $rc: $(cat "$TMP/cam.err")"
echo "ok: missing camera: $(tail -1 "$TMP/cam.err")"

# A camera's format and controls: a format V4L2 is not read in and a
# malformed control list are refused with the reason.
"$RTEDGED" --source /dev/video99 --set source.format=bgr24 --lcm-url "file://$TMP/cam.lcm" \
    2>"$TMP/cam.err" >/dev/null
[ $? -eq 1 ] && grep -q "a V4L2 camera is read as yuyv, uyvy, grey, nv12 or mjpeg, not: bgr24" \
    "$TMP/cam.err" || fail "v4l2 bgr24: $(cat "$TMP/cam.err")"
for controls in 'brightness' 'brightness=x' '=3' 'gain=1;exposure'; do
    "$RTEDGED" --set "source.controls=$controls" --check-config 2>"$TMP/err" >/dev/null
    [ $? -eq 2 ] && grep -q "source.controls: '$controls'" "$TMP/err" ||
        fail "source.controls=$controls: $(cat "$TMP/err")"
done
"$RTEDGED" --set 'source.controls=brightness=140; white_balance_automatic = 0;gain=0x10' \
    --check-config >/dev/null || fail "a good source.controls refused"
echo "ok: v4l2 format and controls checked"

# --list-cameras: every camera, or exit 1 saying there is none.
"$RTEDGED" --list-cameras >"$TMP/list.txt" 2>"$TMP/list.err"
rc=$?
if [ $rc -eq 0 ]; then
    grep -qE '^(v4l2|libcamera) ' "$TMP/list.txt" || fail "--list-cameras: $(cat "$TMP/list.txt")"
else
    [ $rc -eq 1 ] && grep -q "no camera found" "$TMP/list.err" ||
        fail "--list-cameras: exit $rc: $(cat "$TMP/list.err")"
fi
echo "ok: --list-cameras: exit $rc, $(grep -cE '^(v4l2|libcamera) ' "$TMP/list.txt") camera(s)"

# --record: the frames as the source delivers them (NV12 from a colour
# Y4M, made here from the mono clip with chroma that varies) into an LCM
# log of image_t; replayed through the lcm-log source, they give the same
# lane messages.
$PY - "$Y4M" "$TMP/colour.y4m" <<'EOP' || fail "cannot make a colour Y4M"
import sys
src, dst = open(sys.argv[1], "rb"), open(sys.argv[2], "wb")
header = src.readline().split()
w, h = int(header[1][1:]), int(header[2][1:])
dst.write(b" ".join(t for t in header if not t.startswith(b"C")) + b" C420jpeg\n")
cw, ch = (w + 1) // 2, (h + 1) // 2
for i in range(6):
    src.readline()
    y = src.read(w * h)
    u = bytes((64 + 2 * x + 8 * i) & 255 for x in range(cw)) * ch
    v = bytes((200 - r) & 255 for r in range(ch) for _ in range(cw))
    dst.write(b"FRAME\n" + y + u + v)
EOP
"$RTEDGED" --source "$TMP/colour.y4m" --fast --max-frames 6 --record "$TMP/rec.lcm" \
    --lcm-url "file://$TMP/rec-out.lcm" 2>"$TMP/rec.err" || fail "--record: $(cat "$TMP/rec.err")"
"$RTEDGED" --source "$TMP/rec.lcm" --fast --lcm-url "file://$TMP/replay.lcm" 2>>"$TMP/rec.err" ||
    fail "replay: $(cat "$TMP/rec.err")"
$PY - "$SUB" "$TYPES" "$TMP" <<'EOP' || fail "--record and replay differ"
import os, sys
sys.path.insert(0, os.path.dirname(sys.argv[1]))
import subscribe
dec, tmp = subscribe.Decoder(sys.argv[2]), sys.argv[3]
def msgs(name, kind):
    out = [dec.decode(d) for _t, _c, d in subscribe.read_log(os.path.join(tmp, name))]
    return [m for m in out if type(m).__name__ == kind]
def lane(m):
    return ([(s.x1, s.y1, s.x2, s.y2) for s in m.segments], m.left.found, m.left.x1, m.left.x2,
            m.right.found, m.right.x1, m.right.x2, m.centre_valid, m.centre_offset_px)
images = msgs("rec.lcm", "image_t")
first, again = msgs("rec-out.lcm", "lane_detection_t"), msgs("replay.lcm", "lane_detection_t")
nv12 = dec.types[3].PIXEL_FORMAT_NV12
ok = (len(images) == 6 and all(i.pixelformat == nv12 and i.size == i.row_stride * i.height * 3 // 2
                               for i in images)
      and len(first) == 6 and [lane(m) for m in first] == [lane(m) for m in again]
      and sum(m.left.found + m.right.found for m in first) > 0)
print("record: %d NV12 images %dx%d; lanes found %d; replay identical: %s"
      % (len(images), images[0].width if images else 0, images[0].height if images else 0,
         sum(m.left.found + m.right.found for m in first),
         [lane(m) for m in first] == [lane(m) for m in again]))
sys.exit(0 if ok else 1)
EOP
echo "ok: --record and its replay"

# tools/render_log draws the log's frames (its image_t when published) with
# the lanes on them: three frames, three PNGs of the frame's size, each the
# recorded picture with green lane curves.
"$RTEDGED" --source "$Y4M" --fast --max-frames 3 --lcm-url "file://$TMP/render.lcm" \
    --set publish.images=true 2>/dev/null || fail "rtedged for render_log"
$PY "$(dirname "$SUB")/render_log" --types "$TYPES" --out "$TMP/render" "$TMP/render.lcm" \
    >"$TMP/render.txt" || fail "render_log: $(cat "$TMP/render.txt")"
$PY - "$TMP/render" "$Y4M" <<'EOP' || fail "render_log's overlays"
import glob, sys
import cv2, numpy as np
pngs = sorted(glob.glob(sys.argv[1] + "/frame_*.png"))
frame = cv2.VideoCapture(sys.argv[2]).read()[1]
ok = len(pngs) == 3
for p in pngs:
    img = cv2.imread(p)
    green = (img[:, :, 1] > 200) & (img[:, :, 0] < 60) & (img[:, :, 2] < 60)
    ok = ok and img.shape == frame.shape and green.sum() > 500 and img.std() > 20
print("render_log: %d PNGs, %s" % (len(pngs), "lanes drawn on the frames" if ok else "WRONG"))
sys.exit(0 if ok else 1)
EOP
echo "ok: render_log"
