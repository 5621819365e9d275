#!/usr/bin/python3
"""rtedge compare and rtedge sobel --magnitude end to end.

- Every cell of the grid is, byte for byte, what its single command writes
  (the command each caption names, rtedge compare --help), on a road photo
  and a table-top photo; the grid's layout is the JSON printed.
- --rows picks and orders the rows; an unknown row is a usage error (exit
  2), a missing input exit 3.
- rtedge sobel --magnitude equals cv2.convertScaleAbs(cv2.magnitude(gx, gy))
  of OpenCV's float32 Sobel derivatives, for ksize 3, 5 and 7, on the
  fixtures and on random images.

usage: test_compare_cli.py RTEDGE_EXE FIXTURES_DIR
"""
import json
import os
import sys
import tempfile

import cv2
import numpy as np

from cli_checks import Checks

RTEDGE, FIXTURES = sys.argv[1], sys.argv[2]
tally = Checks(RTEDGE)
run, check = tally.run, tally.check

SINGLE = {  # caption -> the single command's arguments
    "SOBEL MAGNITUDE K=3": ["sobel", "--magnitude", "--ksize", "3"],
    "SOBEL MAGNITUDE K=5": ["sobel", "--magnitude", "--ksize", "5"],
    "SOBEL MAGNITUDE K=7": ["sobel", "--magnitude", "--ksize", "7"],
    "LOG SIGMA=0.5": ["log", "--blur", "0", "--sigma", "0.5"],
    "LOG SIGMA=1": ["log", "--blur", "0", "--sigma", "1"],
    "LOG SIGMA=2": ["log", "--blur", "0", "--sigma", "2"],
    "CANNY 20/60": ["canny", "--low", "20", "--high", "60"],
    "CANNY 50/150": ["canny", "--low", "50", "--high", "150"],
    "CANNY 100/200": ["canny", "--low", "100", "--high", "200"],
}


def compare(path, tmp, *rows):
    """The grid and its layout, or (None, None)."""
    out = os.path.join(tmp, "grid.png")
    r = run("compare", path, out, *rows)
    check(r.returncode == 0, f"compare {path} {rows}: exit {r.returncode}: {r.stderr.strip()}")
    if r.returncode != 0:
        return None, None
    return cv2.imread(out), json.loads(r.stdout)["cells"]


def check_cells(path, tmp):
    grid, cells = compare(path, tmp)
    if grid is None:
        return
    check([c["row"] for c in cells] == ["sobel"] * 3 + ["log"] * 3 + ["canny"] * 3,
          f"{path}: rows {[c['row'] for c in cells]}")
    check(sorted(c["caption"] for c in cells) == sorted(SINGLE), f"{path}: captions")
    gray = cv2.cvtColor(cv2.imread(path), cv2.COLOR_BGR2GRAY)
    for c in cells:
        single = os.path.join(tmp, "single.png")
        args = SINGLE.get(c["caption"], [])
        r = run(args[0], path, single, *args[1:]) if args else None
        if not r or r.returncode != 0:
            check(False, f"{path}: {c['caption']}: single command failed")
            continue
        want = cv2.imread(single, cv2.IMREAD_GRAYSCALE)
        cell = grid[c["y"]:c["y"] + c["height"], c["x"]:c["x"] + c["width"]]
        check(want.shape == gray.shape and cell.shape[:2] == want.shape, f"{path}: {c['caption']}: size")
        if cell.shape[:2] == want.shape:
            same = all(np.array_equal(cell[:, :, k], want) for k in range(3))
            check(same, f"{path}: {c['caption']}: cell differs from `rtedge {' '.join(args)}`")


def check_magnitude(gray, tmp, what):
    path = os.path.join(tmp, "in.png")
    cv2.imwrite(path, gray)
    for k in (3, 5, 7):
        out = os.path.join(tmp, "mag.png")
        r = run("sobel", path, out, "--magnitude", "--ksize", str(k))
        check(r.returncode == 0, f"{what}: sobel --magnitude --ksize {k}: exit {r.returncode}")
        gx = cv2.Sobel(gray, cv2.CV_32F, 1, 0, ksize=k)
        gy = cv2.Sobel(gray, cv2.CV_32F, 0, 1, ksize=k)
        want = cv2.convertScaleAbs(cv2.magnitude(gx, gy))
        got = cv2.imread(out, cv2.IMREAD_GRAYSCALE)
        check(got is not None and np.array_equal(got, want),
              f"{what}: sobel --magnitude --ksize {k} differs from OpenCV")


def main():
    tmp = tempfile.mkdtemp()
    for name in ("solidWhiteCurve.jpg", "stuff.jpg"):
        check_cells(os.path.join(FIXTURES, name), tmp)
        check_magnitude(cv2.cvtColor(cv2.imread(os.path.join(FIXTURES, name)), cv2.COLOR_BGR2GRAY),
                        tmp, name)
    rng = np.random.default_rng(7)
    for i in range(4):
        h, w = rng.integers(8, 90, size=2)
        check_magnitude(rng.integers(0, 256, size=(h, w), dtype=np.uint8), tmp, f"random {w}x{h}")

    road = os.path.join(FIXTURES, "solidWhiteCurve.jpg")
    grid, cells = compare(road, tmp, "--rows", "canny,sobel")
    if cells is not None:
        check([c["row"] for c in cells] == ["canny"] * 3 + ["sobel"] * 3, "--rows canny,sobel: rows")
        h, w = cv2.imread(road).shape[:2]
        check(grid.shape[1] == 3 * w + 8 and grid.shape[0] == cells[3]["y"] + h,
              f"--rows canny,sobel: grid {grid.shape}")
    for rows in ("foo", "sobel,", ",", "sobel,log,canny,log"):
        r = run("compare", road, os.path.join(tmp, "x.png"), "--rows", rows)
        check(r.returncode == 2 and "rows" in r.stderr, f"--rows '{rows}': exit {r.returncode}, not a usage error")
    check(run("compare", os.path.join(tmp, "missing.png"), os.path.join(tmp, "x.png")).returncode == 3,
          "missing input: not exit 3")
    check(run("sobel", road, os.path.join(tmp, "x.png"), "--magnitude", "--dy", "1").returncode == 2,
          "sobel --magnitude --dy 1: not a usage error")
    return tally.finish("compare cli")


sys.exit(main())
