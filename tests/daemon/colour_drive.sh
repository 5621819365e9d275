#!/bin/sh
# rtedged on a colour recording: the freeway's labelled frames
# (fixtures/lanes/challenge02_*.jpg, whose left line is yellow on light
# concrete) as one 4:2:0 Y4M made by ffmpeg, read as NV12 frames. Both
# lanes must be reported in 20 of the 21 frames with the colour cue from
# the chroma (today 21), and in at most 16 without it (lane.use_color =
# false; today 12): the daemon's lanes take the cue from a YUV source.
#   colour_drive.sh RTEDGED SUBSCRIBE_PY LCM_PYTHON_TYPES FIXTURES_LANES TMPDIR
set -u
rtedged=$1 subscribe=$2 types=$3 frames=$4 tmp=$5/colour_drive_test
mkdir -p "$tmp" || exit 1
y4m=$tmp/freeway.y4m
if ! ffmpeg -loglevel error -y -pattern_type glob -i "$frames/challenge02_*.jpg" \
    -pix_fmt yuvj420p -strict -1 "$y4m"; then
    echo "FAIL: ffmpeg could not make $y4m"
    exit 1
fi
# frames published with both lanes, and frames published
both_lanes() {
    RTEDGE_LCM_PYTHON=$types /usr/bin/python3 "$subscribe" --summary --transport builtin "$1" |
        awk '$1 == "frame" { n++; if ($4 == 2) both++ } END { print both + 0, n + 0 }'
}
failed=0
for run in true:20:21 false:0:16; do
    colour=${run%%:*} range=${run#*:}
    low=${range%%:*} high=${range#*:}
    rm -f "$tmp/$colour.lcm"
    if ! "$rtedged" --source "$y4m" --set source.pace=fast --set lane.use_color="$colour" \
        --lcm-url "file://$tmp/$colour.lcm" 2>"$tmp/$colour.err"; then
        echo "FAIL: rtedged with lane.use_color = $colour"
        cat "$tmp/$colour.err"
        failed=1
        continue
    fi
    # shellcheck disable=SC2046 # two numbers, split on purpose
    set -- $(both_lanes "$tmp/$colour.lcm")
    if [ "$2" -eq 21 ] && [ "$1" -ge "$low" ] && [ "$1" -le "$high" ]; then
        echo "ok: lane.use_color = $colour: both lanes in $1 of $2 frames ($low..$high wanted)"
    else
        echo "FAIL: lane.use_color = $colour: both lanes in $1 of $2 frames ($low..$high wanted)"
        failed=1
    fi
done
exit $failed
