#!/usr/bin/python3
"""Scores `rtedge lanes` output against labelled lanes.

    eval_lanes.py TRUTH.csv LANES.jsonl [--tolerance 0.02] [--require 0.95]
    eval_lanes.py LABELS.json OUT_DIR --width 1280 [--tolerance 0.03] [--group]

TRUTH.csv is what tools/make_curved_roads.py writes (frame, side, visible,
then the marking's x on each labelled row; the header names the rows), and
LANES.jsonl holds one JSON object per frame, as `rtedge lanes --sequence`
prints them. LABELS.json (fixtures/lanes/labels.json) labels real frames by
file name: each side's centre line as [[x, y], ...] on the rows where it
can be seen, or null when it cannot be seen at all; OUT_DIR then holds each
frame's `rtedge lanes` output as NAME.json (NAME: the file name without its
extension). A side of a frame is right when
  - the marking is visible and the side is reported found (and not merely
    predicted), with every labelled row within tolerance x width of the
    reported lane (its "points" polyline when there is one, else the chord
    (x1, y1)-(x2, y2), extended along its last piece beyond its ends), or
  - the marking is hidden and the side is not reported as seen (absent,
    or `predicted`).
A frame is right when both sides are. Prints one line per run (frames
right, sides right, the worst error on a visible side; with --group, one
per group of frames, the name up to its last '_'; with --calibration the
sides seen and right per quarter of confidence) and exits 1 when the share
of frames right is below --require (or, with --bend, when fewer than 90% of
the sides seen curve that way: "curvature" > 0 bends right)."""
import argparse
import csv
import json
import os
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


def load_csv(truth_path, lanes_path):
    """[(name, {side: [(x, y), ...] or None}, lanes)] of a synthetic sequence."""
    with open(truth_path) as f:
        rd = csv.reader(f)
        rows = [int(v) for v in next(rd)[3:]]
        truth = {}
        for r in rd:
            pts = [(float(v), y) for v, y in zip(r[3:], rows)]
            truth.setdefault(int(r[0]), {})[r[1]] = pts if r[2] == "1" else None
    with open(lanes_path) as f:
        frames = [json.loads(line) for line in f if line.strip()]
    return [("frame %d" % k, truth[k], frames[k] if k < len(frames) else {})
            for k in range(max(truth) + 1)]


def load_labels(labels_path, out_dir):
    """The same for labelled real frames and a directory of outputs."""
    with open(labels_path) as f:
        labels = json.load(f)
    runs = []
    for name in sorted(labels):
        out = os.path.join(out_dir, os.path.splitext(name)[0] + ".json")
        with open(out) as f:
            lanes = json.load(f)
        runs.append((name, {side: labels[name].get(side) for side in ("left", "right")}, lanes))
    return runs


def is_seen(lane):
    """Whether a reported side is seen this frame (found, not predicted)."""
    return bool(lane) and bool(lane.get("found")) and not lane.get("predicted", False)


def score_side(lane, pts, tol):
    """(right, error in px or None, why not) for one side."""
    seen_now = is_seen(lane)
    if not pts:
        return (not seen_now, None, "hidden but seen")
    if not seen_now:
        return (False, None, "missed")
    err = max(abs(lane_x(lane, y) - x) for x, y in pts)
    return (err <= tol, err, "off by %.1f px" % err)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("truth", help="TRUTH.csv (synthetic) or LABELS.json (real frames)")
    ap.add_argument("lanes", help="LANES.jsonl for a .csv, an output directory for a .json")
    ap.add_argument("--width", type=float, default=640)
    ap.add_argument("--tolerance", type=float, default=0.02)
    ap.add_argument("--require", type=float, default=0.0)
    ap.add_argument("--bend", choices=("left", "right"),
                    help="also require the reported curvature to bend this way on 90%% of the sides seen")
    ap.add_argument("--group", action="store_true",
                    help="also print the frames right per group (the name up to its last '_')")
    ap.add_argument("--verbose", action="store_true")
    ap.add_argument("--calibration", action="store_true",
                    help="also print, per confidence bin, the sides seen and the share right")
    a = ap.parse_args()
    if a.truth.endswith(".json"):
        runs = load_labels(a.truth, a.lanes)
    else:
        runs = load_csv(a.truth, a.lanes)
    tol = a.tolerance * a.width
    frames_right = sides_right = 0
    worst = 0.0
    bins = [[0, 0] for _ in range(4)]  # per confidence quarter: sides seen, right
    groups = {}
    for name, truth, lanes in runs:
        ok_frame = True
        for side in ("left", "right"):
            lane = lanes.get(side)
            ok, err, why = score_side(lane, truth[side], tol)
            if err is not None:
                worst = max(worst, err)
            if a.verbose and not ok:
                print("%s %s: %s" % (name, side, why))
            if is_seen(lane):
                b = bins[min(int(lane.get("confidence", 0) * 4), 3)]
                b[0] += 1
                b[1] += ok
            sides_right += ok
            ok_frame &= ok
        frames_right += ok_frame
        g = groups.setdefault(name.rsplit("_", 1)[0], [0, 0])
        g[0] += ok_frame
        g[1] += 1
    share = frames_right / len(runs)
    bend_ok = True
    if a.bend:
        signs = [lanes[side].get("curvature", 0) for _, _, lanes in runs
                 for side in ("left", "right") if is_seen(lanes.get(side))]
        right_way = sum(1 for c in signs if (c > 0) == (a.bend == "right") and c != 0)
        bend_ok = len(signs) > 0 and right_way >= 0.9 * len(signs)
        print("%s: %d of %d sides seen bend %s" % (a.lanes, right_way, len(signs), a.bend))
    if a.group:
        for g, (right, n) in sorted(groups.items()):
            print("%s: %s: %d/%d frames right" % (a.lanes, g, right, n))
    print("%s: %d/%d frames right (%.0f%%), %d/%d sides, worst error on a seen visible side "
          "%.1f px (tolerance %.1f px)" % (a.lanes, frames_right, len(runs), 100 * share,
                                           sides_right, 2 * len(runs), worst, tol))
    if a.calibration:
        for i, (seen, right) in enumerate(bins):
            print("%s: confidence %.2f..%.2f: %d sides seen, %d right" %
                  (a.lanes, i / 4, (i + 1) / 4, seen, right))
    sys.exit(0 if share >= a.require and bend_ok else 1)


if __name__ == "__main__":
    main()
