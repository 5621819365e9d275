#!/usr/bin/python3
"""Scores `rtedge lanes --sequence` output against labelled lanes.

    eval_lanes.py TRUTH.csv LANES.jsonl [--tolerance 0.02] [--require 0.95]

TRUTH.csv is what tools/make_curved_roads.py writes (frame, side, visible,
then the marking's x on each labelled row; the header names the rows).
LANES.jsonl holds one JSON object per frame, as `rtedge lanes --sequence`
prints them. A side of a frame is right when
  - the marking is visible and the side is reported found (and not merely
    predicted), with every labelled row within tolerance x width of the
    reported lane (its "points" polyline when there is one, else the chord
    (x1, y1)-(x2, y2), extended along its last piece beyond its ends), or
  - the marking is hidden and the side is not reported as seen (absent,
    or `predicted`).
A frame is right when both sides are. Prints one line per sequence
(frames right, sides right, the worst error on a visible side; with
--calibration the sides seen and right per quarter of confidence) and exits 1
when the share of frames right is below --require (or, with --bend, when
fewer than 90% of the sides seen curve that way: "curvature" > 0 bends
right)."""
import argparse
import csv
import json
import sys


def lane_x(lane, y):
    """x of the reported lane on row y: its polyline ("points", else the
    chord), extended along its end pieces beyond its ends."""
    pts = lane.get("points")
    if not pts or len(pts) < 2:
        pts = [[lane["x1"], lane["y1"]], [lane["x2"], lane["y2"]]]
    pts = sorted(pts, key=lambda p: -p[1])  # bottom first
    piece = 0
    while piece < len(pts) - 2 and y < pts[piece + 1][1]:
        piece += 1
    (xa, ya), (xb, yb) = pts[piece], pts[piece + 1]
    return xa if ya == yb else xa + (xb - xa) * (y - ya) / (yb - ya)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("truth")
    ap.add_argument("lanes")
    ap.add_argument("--width", type=float, default=640)
    ap.add_argument("--tolerance", type=float, default=0.02)
    ap.add_argument("--require", type=float, default=0.0)
    ap.add_argument("--bend", choices=("left", "right"),
                    help="also require the reported curvature to bend this way on 90%% of the sides seen")
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--calibration", action="store_true",
                    help="also print, per confidence bin, the sides seen and the share right")
    a = ap.parse_args()
    with open(a.truth) as f:
        rd = csv.reader(f)
        rows = [int(v) for v in next(rd)[3:]]
        truth = {}
        for r in rd:
            truth[(int(r[0]), r[1])] = (r[2] == "1", [float(v) for v in r[3:]])
    with open(a.lanes) as f:
        frames = [json.loads(line) for line in f if line.strip()]
    tol = a.tolerance * a.width
    n_frames = max(k for k, _ in truth) + 1
    frames_right = sides_right = 0
    worst = 0.0
    bins = [[0, 0] for _ in range(4)]  # per confidence quarter: sides seen, right
    for k in range(n_frames):
        ok_frame = True
        lanes = frames[k] if k < len(frames) else {}
        for side in ("left", "right"):
            visible, xs = truth[(k, side)]
            lane = lanes.get(side)
            seen = bool(lane) and lane.get("found", False) and not lane.get("predicted", False)
            if visible:
                ok = seen
                if seen:
                    err = max(abs(lane_x(lane, y) - x) for y, x in zip(rows, xs))
                    worst = max(worst, err)
                    ok = err <= tol
            else:
                ok = not seen
            if a.verbose and not ok:
                print("frame %d %s: %s" % (k, side, "hidden but seen" if not visible else
                      "missed" if not seen else "off by %.1f px" % err))
            if seen:
                b = bins[min(int(lane.get("confidence", 0) * 4), 3)]
                b[0] += 1
                b[1] += ok
            sides_right += ok
            ok_frame &= ok
        frames_right += ok_frame
    share = frames_right / n_frames
    bend_ok = True
    if a.bend:
        signs = [frame[side].get("curvature", 0) for frame in frames for side in ("left", "right")
                 if frame.get(side, {}).get("found") and not frame[side].get("predicted")]
        right_way = sum(1 for c in signs if (c > 0) == (a.bend == "right") and c != 0)
        bend_ok = len(signs) > 0 and right_way >= 0.9 * len(signs)
        print("%s: %d of %d sides seen bend %s" % (a.lanes, right_way, len(signs), a.bend))
    print("%s: %d/%d frames right (%.0f%%), %d/%d sides, worst error on a seen visible side "
          "%.1f px (tolerance %.1f px)" % (a.lanes, frames_right, n_frames, 100 * share,
                                           sides_right, 2 * n_frames, worst, tol))
    if a.calibration:
        for i, (seen, right) in enumerate(bins):
            print("%s: confidence %.2f..%.2f: %d sides seen, %d right" %
                  (a.lanes, i / 4, (i + 1) / 4, seen, right))
    sys.exit(0 if share >= a.require and bend_ok else 1)


if __name__ == "__main__":
    main()
