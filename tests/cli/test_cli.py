#!/usr/bin/python3
"""End-to-end tests of the rtedge command-line tool against OpenCV 4.6.

Runs every subcommand on real photos (fixtures/ and ../shared/data/real when
present) and compares the files it writes with what python3-opencv computes:
0 differing pixels. Also checks exit codes and messages for usage errors (2)
and input errors (3).

usage: test_cli.py RTEDGE_EXE FIXTURES_DIR [SHARED_DATA_DIR]
"""
import json
import os
import re
import sys
import tempfile

import cv2
import numpy as np

from cli_checks import Checks

RTEDGE, FIXTURES = sys.argv[1], sys.argv[2]
SHARED = sys.argv[3] if len(sys.argv) > 3 else ""
tally = Checks(RTEDGE)
run, check, failures = tally.run, tally.check, tally.failures


def photos():
    paths = []
    for d in (FIXTURES, os.path.join(SHARED, "lanes"), os.path.join(SHARED, "objects")):
        if d and os.path.isdir(d):
            for name in sorted(os.listdir(d)):
                if name.lower().endswith((".png", ".jpg", ".pgm", ".ppm")):
                    paths.append(os.path.join(d, name))
    # A few of each kind keep the suite quick; the oracle suite covers all.
    return paths[:4] + paths[-3:] if len(paths) > 7 else paths


def read_out(path):
    if path.endswith(".npy"):
        return np.load(path)
    return cv2.imread(path, cv2.IMREAD_UNCHANGED)


def same(cmd, expected, out):
    r = run(*cmd)
    check(r.returncode == 0, f"{' '.join(cmd)} exited {r.returncode}: {r.stderr.strip()}")
    if r.returncode != 0:
        return r
    got = read_out(out)
    ok = got is not None and got.shape == expected.shape and got.dtype == expected.dtype
    diff = int(np.count_nonzero(got != expected)) if ok else -1
    check(ok and diff == 0, f"{' '.join(cmd)}: {diff} differing pixels (shape {None if got is None else got.shape} vs {expected.shape})")
    return r


def main():
    tmp = tempfile.mkdtemp(prefix="rtedge-cli-")
    inputs = photos()
    check(len(inputs) > 0, "no input photos found")
    for path in inputs:
        gray = cv2.cvtColor(cv2.imread(path, cv2.IMREAD_COLOR), cv2.COLOR_BGR2GRAY)
        o = lambda name: os.path.join(tmp, name)
        same(["gray", path, o("g.png")], gray, o("g.png"))
        same(["blur", path, o("b.pgm"), "--ksize", "7", "--sigma", "1.5"],
             cv2.GaussianBlur(gray, (7, 7), 1.5), o("b.pgm"))
        same(["median", path, o("m.png"), "--ksize", "5"], cv2.medianBlur(gray, 5), o("m.png"))
        same(["sobel", path, o("s.npy"), "--dx", "1", "--dy", "1", "--ksize", "5"],
             cv2.Sobel(gray, cv2.CV_16S, 1, 1, ksize=5), o("s.npy"))
        same(["sobel", path, o("s.png"), "--dy", "1", "--dx", "0"],
             cv2.convertScaleAbs(cv2.Sobel(gray, cv2.CV_16S, 0, 1)), o("s.png"))
        same(["scharr", path, o("sc.npy"), "--dx", "0", "--dy", "1"],
             cv2.Scharr(gray, cv2.CV_16S, 0, 1), o("sc.npy"))
        same(["laplacian", path, o("l.npy"), "--ksize", "3"],
             cv2.Laplacian(gray, cv2.CV_16S, ksize=3), o("l.npy"))
        same(["log", path, o("log.npy"), "--blur", "5", "--ksize", "3"],
             cv2.Laplacian(cv2.GaussianBlur(gray, (5, 5), 0), cv2.CV_16S, ksize=3), o("log.npy"))
        same(["canny", path, o("c.png"), "--low", "50", "--high", "150", "--blur", "5"],
             cv2.Canny(cv2.GaussianBlur(gray, (5, 5), 0), 50, 150), o("c.png"))
        same(["canny", path, o("c2.png"), "--low", "200", "--high", "90", "--aperture", "5", "--l2"],
             cv2.Canny(gray, 200, 90, apertureSize=5, L2gradient=True), o("c2.png"))
        # Automatic thresholds, checked against the numpy recipes.
        med = float(np.median(gray))
        lo, hi = int(max(0, 0.67 * med)), int(min(255, 1.33 * med))
        r = same(["canny", path, o("c3.png"), "--auto", "median"], cv2.Canny(gray, lo, hi), o("c3.png"))
        if r.returncode == 0:
            t = json.loads(r.stdout)
            check((t["low"], t["high"]) == (lo, hi), f"canny --auto median on {path}: {t} vs {(lo, hi)}")
        otsu, _ = cv2.threshold(gray, 0, 255, cv2.THRESH_BINARY + cv2.THRESH_OTSU)
        same(["canny", path, o("c4.png"), "--auto", "otsu"],
             cv2.Canny(gray, int(otsu) // 2, int(otsu)), o("c4.png"))
        t_used, expected = cv2.threshold(gray, 0, 255, cv2.THRESH_BINARY_INV + cv2.THRESH_OTSU)
        r = same(["threshold", path, o("t.png"), "--otsu", "--type", "binary_inv"], expected, o("t.png"))
        if r.returncode == 0:
            check(json.loads(r.stdout) == {"threshold": int(t_used)}, f"threshold printed {r.stdout!r}, OpenCV {t_used}")
        same(["threshold", path, o("t2.png"), "--value", "100.5", "--type", "tozero"],
             cv2.threshold(gray, 100.5, 255, cv2.THRESH_TOZERO)[1], o("t2.png"))
        for op, cvop in (("erode", None), ("dilate", None), ("open", cv2.MORPH_OPEN), ("close", cv2.MORPH_CLOSE)):
            k = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (5, 5))
            if op == "erode":
                expected = cv2.erode(gray, k, iterations=2)
            elif op == "dilate":
                expected = cv2.dilate(gray, k, iterations=2)
            else:
                expected = cv2.morphologyEx(gray, cvop, k, iterations=2)
            same([op, path, o(op + ".png"), "--shape", "ellipse", "--ksize", "5", "--iterations", "2"],
                 expected, o(op + ".png"))
        h, w = gray.shape
        pts = np.array([[0, h], [w * 45 // 100, h * 6 // 10], [w * 55 // 100, h * 6 // 10], [w, h]], np.int32)
        mask = np.zeros_like(gray)
        cv2.fillPoly(mask, [pts], 255)
        poly = ";".join(f"{x},{y}" for x, y in pts)
        same(["mask", path, o("mask.png"), "--polygon", poly], cv2.bitwise_and(gray, mask), o("mask.png"))

    # Exit codes and messages.
    r = run()
    check(r.returncode == 2 and "usage" in r.stderr, "no command: exit 2 with usage")
    r = run("--help")
    check(r.returncode == 0 and "canny" in r.stdout, "--help lists the commands")
    r = run("--version")
    check(r.returncode == 0 and re.fullmatch(r"rtedge \d+\.\d+\.\d+ \(git ([0-9a-f]{7,}(-dirty)?|"
                                            r"[\w.-]+|unknown)\)\n", r.stdout) is not None,
          "--version: %r" % r.stdout)
    r = run("frobnicate")
    check(r.returncode == 2 and "unknown command" in r.stderr, "unknown command: exit 2")
    for sub in ("gray", "blur", "median", "sobel", "scharr", "laplacian", "log", "canny", "threshold",
                "erode", "dilate", "open", "close", "mask"):
        r = run(sub, "--help")
        check(r.returncode == 0 and r.stdout.startswith(f"usage: rtedge {sub}"), f"{sub} --help")
    src = inputs[0] if inputs else "x.png"
    out = os.path.join(tmp, "x.png")
    for args, what in (((("blur", src, out, "--ksize", "4")), "even ksize"),
                       (("blur", src, out, "--ksize", "abc"), "non-numeric ksize"),
                       (("blur", src, out, "--bogus", "1"), "unknown option"),
                       (("blur", src), "missing OUT"),
                       (("canny", src, out, "--aperture", "4"), "even aperture"),
                       (("canny", src, out, "--auto", "magic"), "unknown --auto rule"),
                       (("mask", src, out, "--polygon", "1,2;3"), "bad polygon"),
                       (("threshold", src, out, "--type", "sideways"), "bad type")):
        r = run(*args)
        check(r.returncode == 2 and r.stderr.startswith("rtedge "), f"{what}: exit {r.returncode}, {r.stderr!r}")
    missing = os.path.join(tmp, "missing.png")
    r = run("blur", missing, out)
    check(r.returncode == 3 and "missing.png" in r.stderr, f"missing input: exit {r.returncode}, {r.stderr!r}")
    bad = os.path.join(tmp, "bad.pgm")
    with open(bad, "wb") as f:
        f.write(b"P5\n640 480\n255\n" + b"\x00" * 100)
    r = run("canny", bad, out)
    check(r.returncode == 3 and "bad.pgm" in r.stderr and "truncated" in r.stderr,
          f"truncated input: exit {r.returncode}, {r.stderr!r}")
    with open(bad, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + os.urandom(64))
    r = run("gray", bad, out)
    check(r.returncode == 3 and "bad.pgm" in r.stderr, f"corrupt PNG: exit {r.returncode}, {r.stderr!r}")
    r = run("gray", src, os.path.join(tmp, "no-such-dir", "x.png"))
    check(r.returncode == 1 and "no-such-dir" in r.stderr, f"unwritable output: exit {r.returncode}, {r.stderr!r}")

    return tally.finish("cli")


if __name__ == "__main__":
    sys.exit(main())
