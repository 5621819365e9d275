#!/usr/bin/python3
"""rtedge lanes end to end: JSON on a photo, the overlay, sequences (a Y4M
file and a directory of images), usage and input errors.

usage: test_lanes_cli.py RTEDGE FIXTURES_DIR SHARED_DATA_DIR"""
import json
import os
import sys
import tempfile

import cv2
import numpy as np

from cli_checks import Checks

RTEDGE, FIXTURES, SHARED = sys.argv[1:4]
tally = Checks(RTEDGE)
check, failures = tally.check, tally.failures


def run(*args):
    p = tally.run("lanes", *args)
    return p.returncode, p.stdout, p.stderr


with tempfile.TemporaryDirectory() as tmp:
    photo = os.path.join(SHARED, "lanes", "solidWhiteRight.jpg")
    overlay = os.path.join(tmp, "overlay.png")
    rc, out, err = run(photo, "--overlay", overlay)
    check(rc == 0, "lanes on a photo exits 0 (%s)" % err)
    d = json.loads(out)
    for side in ("left", "right"):
        lane = d[side]
        check(lane["found"] and lane["y1"] == 539 and lane["y2"] < lane["y1"], side + " lane found, y1 on the bottom row")
        check(0 < lane["confidence"] <= 1, side + " confidence in (0, 1]")
    check(d["left"]["x2"] > d["left"]["x1"] and d["right"]["x2"] < d["right"]["x1"], "slope signs")
    check(abs(d["left"]["x1"] - 153) < 38 and abs(d["right"]["x1"] - 852) < 38, "bottom-row x near the eye's")
    check(isinstance(d["offset_px"], float) and d["segments"] and len(d["segments"][0]) == 5, "offset and segments")
    for side in ("left", "right"):
        pts = d[side]["points"]
        check(len(pts) >= 2 and pts[0] == [d[side]["x1"], 539] and
              all(b[1] < a[1] and a[1] - b[1] <= 10 for a, b in zip(pts, pts[1:])),
              side + " points: from the bottom row up, at most 10 rows apart")
        check(isinstance(d[side]["curvature"], float) and abs(d[side]["curvature"]) < 0.01,
              side + " curvature: a number, small on a straight road")
    img = cv2.imread(overlay)
    check(img is not None and img.shape == (540, 960, 3), "overlay written at the photo's size")
    if img is not None:
        blue = np.all(img == (255, 0, 0), axis=2).sum()
        red = np.all(img == (0, 0, 255), axis=2).sum()
        check(blue > 300 and red > 300, "overlay: left lane blue, right lane red (%d, %d px)" % (blue, red))
        # the blue line is on the left half, the red on the right
        ys, xs = np.nonzero(np.all(img == (255, 0, 0), axis=2))
        check(xs.mean() < 480, "blue on the left")

    # grey input works too (no colour cue)
    gray = os.path.join(FIXTURES, "solidWhiteCurve_gray.pgm")
    rc, out, _ = run(gray)
    check(rc == 0 and json.loads(out)["left"]["found"], "grey photo")

    # a Y4M sequence: one line per frame
    rc, out, err = run("--sequence", os.path.join(FIXTURES, "solidWhiteRight_clip.y4m"))
    lines = out.splitlines()
    check(rc == 0 and len(lines) == 22, "Y4M sequence: 22 JSON lines (%d, %s)" % (len(lines), err))
    frames = [json.loads(line) for line in lines]
    check(all(f["left"]["found"] and f["right"]["found"] for f in frames), "Y4M: both lanes in every frame")
    check([f["frame"] for f in frames] == list(range(22)), "Y4M: frame numbers")

    # a directory of images, in name order, with a frame where the paint is gone
    seq = os.path.join(tmp, "seq")
    os.mkdir(seq)
    base = cv2.imread(photo)
    blank = base.copy()
    blank[330:, 480:] = base[330:, 480:].mean(axis=(0, 1)).astype(np.uint8)  # right marking painted over
    for i, im in enumerate([base, base, blank, blank, base]):
        cv2.imwrite(os.path.join(seq, "f%02d.png" % i), im)
    rc, out, err = run("--sequence", seq)
    frames = [json.loads(line) for line in out.splitlines()]
    check(rc == 0 and len(frames) == 5, "directory sequence: 5 lines (%s)" % err)
    if len(frames) == 5:
        check(not frames[1]["right"]["predicted"] and frames[2]["right"]["predicted"]
              and frames[3]["right"]["predicted"] and not frames[4]["right"]["predicted"],
              "directory sequence: painted-over lane held as predicted")

    # errors
    rc, out, err = run(photo, "--hough-seed", "12345")
    check(rc == 0, "--hough-seed exits 0 (%s)" % err)
    if rc == 0:
        e = json.loads(out)
        check(abs(e["left"]["x1"] - 153) < 38 and abs(e["right"]["x1"] - 852) < 38,
              "another Hough point order: bottom-row x still near the eye's")
    check(run(photo, "--hough-seed", "-1")[0] == 2, "negative --hough-seed: usage error")
    check(run()[0] == 2, "no input: usage error")
    check(run(photo, "--blur", "4")[0] == 2, "even blur: usage error")
    check(run(photo, "--roi", "0,1;1,1")[0] == 2, "ROI of 2 points: usage error")
    check(run(photo, "--canny-low", "200", "--canny-high", "100", "--auto-canny", "none")[0] == 2, "low > high")
    check(run(os.path.join(tmp, "missing.png"))[0] == 3, "missing file: input error")
    bad = os.path.join(tmp, "bad.y4m")
    with open(bad, "wb") as f:
        f.write(b"YUV4MPEG2 W4 H4 Cmono\nFRAME\n\x00\x01")
    check(run("--sequence", bad)[0] == 3, "truncated Y4M: input error")
    check(run("--sequence", os.path.join(tmp, "nothing"))[0] == 3, "missing sequence: input error")

sys.exit(tally.finish("lanes cli"))
