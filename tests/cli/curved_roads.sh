#!/bin/sh
# rtedge lanes --sequence on the synthetic curved roads of
# tools/make_curved_roads.py, scored by tools/eval_lanes.py: the share of
# frames whose both sides are right (every labelled row in the lower 38% of
# the frame within 2% of the width; hidden markings not reported as seen)
# must reach each scene's floor, bends must be reported the right way, and
# over all scenes the sides seen with confidence >= 0.5 must be right in 95%
# of cases (the confidence's calibration, docs/lanes.md).
# The floors are 95% (23 of 24 frames), and today's result less a frame
# where a scene is below that (the width change: its first five frames;
# the sharp turn: its last three frames, 6 to 8 m before the turn, where
# the curve fit of the whole lane leaves the near marking, docs/lanes.md,
# "Accuracy"); the sharp turn bends only far up, so its bottom-row
# curvature is not checked; the scenes run with the ROI's top widened to
# 0.25..0.75 of the width, where a tight bend's far dashes lie. With the
# default ROI (the tutorial's trapezoid, which seeds the lanes only from
# segments inside it) 95% of all frames must be right.
# In a cross build meson test sets MESON_EXE_WRAPPER (qemu-user).
#   curved_roads.sh RTEDGE EVAL_LANES DIR
set -u
RTEDGE=$1 EVAL=$2 DIR=$3
ROI="0,1;0.25,0.6;0.75,0.6;1,1"
failed=0
cal="$DIR/curve_calibration.txt"
: >"$cal"
# scene floor [bend]
while read -r scene floor bend; do
    out="$DIR/curve_$scene.jsonl"
    # shellcheck disable=SC2086 # the cross build's wrapper is a command line
    if ! ${MESON_EXE_WRAPPER:-} "$RTEDGE" lanes --sequence "$DIR/curve_$scene" --roi "$ROI" >"$out"; then
        echo "FAIL: $scene: rtedge lanes exited non-zero"
        failed=1
        continue
    fi
    if /usr/bin/python3 "$EVAL" "$DIR/curve_$scene.csv" "$out" --require "$floor" \
        ${bend:+--bend "$bend"} --calibration >"$DIR/curve_$scene.eval"; then
        echo "ok: $scene (floor $floor${bend:+, bends $bend})"
    else
        echo "FAIL: $scene below its floor $floor${bend:+ or not bending $bend}"
        failed=1
    fi
    grep -v ' confidence ' "$DIR/curve_$scene.eval"
    grep ' confidence ' "$DIR/curve_$scene.eval" >>"$cal"
done <<'SCENES'
tight_bend 0.95 right
s_bend 0.95
worn 0.95 left
left_bend 0.95 left
right_bend 0.95 right
shadows 0.95
seam 0.95 right
glare 0.95 right
straight 0.95
width_change 0.75 left
double_yellow 0.95 left
sharp_turn 0.83
SCENES
# The default ROI, over all scenes: "...: N/24 frames right ..."
for scene in tight_bend s_bend worn left_bend right_bend shadows seam glare straight \
    width_change double_yellow sharp_turn; do
    # shellcheck disable=SC2086 # the cross build's wrapper is a command line
    ${MESON_EXE_WRAPPER:-} "$RTEDGE" lanes --sequence "$DIR/curve_$scene" >"$DIR/curve_default_$scene.jsonl" &&
        /usr/bin/python3 "$EVAL" "$DIR/curve_$scene.csv" "$DIR/curve_default_$scene.jsonl"
done >"$DIR/curve_default.txt"
if ! awk '/frames right/ { split($2, f, "/"); right += f[1]; n += f[2] }
    END { printf "default ROI: %d/%d frames right\n", right, n; exit !(n == 288 && right >= 0.95 * n) }' \
    "$DIR/curve_default.txt"; then
    echo "FAIL: with the default ROI fewer than 95% of the frames are right"
    failed=1
fi
if ! awk -v floor=0.95 -f "$(dirname "$0")/confident_share.awk" "$cal"; then
    echo "FAIL: sides seen with confidence >= 0.5 are right in fewer than 95% of cases"
    failed=1
fi
exit $failed
