#!/usr/bin/python3
"""Synthetic road sequences with known lane lines, for the lane tests.

Writes OUT_DIR/road_<name>.y4m (grey, Cmono) and OUT_DIR/road_<name>.csv with
one line per frame: frame, left bottom x, left top x, right bottom x, right
top x, left visible, right visible (x at the bottom row and at the ROI top,
0.6 * height, of the drawn marking's centre line).

The road is drawn in perspective: a lane marking at lateral position X (in
lane widths) and depth t (0 at the bottom row, 1 at the horizon) sits at
x = vx + (xb - vx) * (1 - t) + bend * t^2 * width, its width shrinking with
depth. The camera sways sideways (the lanes move together), the road bends
gently, dashes move towards the camera, and the frames carry noise, shadows
crossing the road, darker and lighter road patches and, in one stretch,
a marking that has worn away (the tracker must hold it).

Deterministic (fixed seeds). Needs python3-opencv and numpy:
    /usr/bin/python3 tools/make_road_fixtures.py OUT_DIR
"""
import math
import os
import sys

import cv2
import numpy as np

W, H = 480, 270
HORIZON = 0.55   # vanishing row as a fraction of the height
ROI_TOP = 0.6    # the lane pipeline's default ROI top


def marking_x(xb, vx, bend, t):
    return vx + (xb - vx) * (1.0 - t) + bend * t * t * W


def draw_marking(img, xb, vx, bend, dashed, phase, colour, rng_row_limit):
    """Fills the marking as quads between sample rows; returns nothing."""
    yb, yh = H - 1, HORIZON * H
    rows = np.linspace(yb + 2, yh + 4, 160)
    for i in range(len(rows) - 1):
        ya, yc = rows[i], rows[i + 1]
        ta, tc = (yb - ya) / (yb - yh), (yb - yc) / (yb - yh)
        if dashed:
            # depth grows like 1 / (1 - t): dashes 3 m long every 12 m
            z = 1.0 / max(1e-3, 1.0 - 0.97 * (ta + tc) / 2) * 6.0 + phase
            if (z % 12.0) > 4.0:
                continue
        xa, xc = marking_x(xb, vx, bend, ta), marking_x(xb, vx, bend, tc)
        wa, wc = max(1.0, 9.0 * (1 - ta)), max(1.0, 9.0 * (1 - tc))
        poly = np.array([[xa - wa / 2, ya], [xa + wa / 2, ya], [xc + wc / 2, yc], [xc - wc / 2, yc]])
        cv2.fillPoly(img, [np.round(poly * 16).astype(np.int32)], colour, cv2.LINE_AA, 4)


def frame(rng, k, n, cfg):
    img = np.zeros((H, W, 3), np.float32)
    img[:] = (200, 170, 140)  # sky
    yh = int(HORIZON * H)
    img[yh:] = (95, 95, 95)  # asphalt
    sway = cfg["sway"] * math.sin(2 * math.pi * k / n)
    bend = cfg["bend"] * math.sin(math.pi * k / n)
    vx = W / 2 + cfg["vx_shift"] * math.sin(2 * math.pi * k / n + 1.0)
    xl, xr = W * 0.5 - 0.36 * W - sway, W * 0.5 + 0.36 * W - sway
    # road patches (lighter / darker asphalt) and shadows across the road
    prng = np.random.default_rng(cfg["seed"] * 1000 + k // 10)
    for _ in range(cfg["patches"]):
        x0, y0 = prng.integers(0, W), prng.integers(yh + 10, H)
        pw, ph = prng.integers(30, 140), prng.integers(8, 40)
        img[y0:y0 + ph, x0:x0 + pw] *= prng.uniform(0.75, 1.3)
    for s in range(cfg["shadows"]):
        y0 = yh + ((k * 3 + s * 71) % (H - yh))
        poly = np.array([[-10, y0], [W + 10, y0 + 25 * (s - 0.5)], [W + 10, y0 + 35], [-10, y0 + 25]], np.int32)
        mask = np.zeros((H, W), np.uint8)
        cv2.fillPoly(mask, [poly], 255)
        img[mask > 0] *= 0.45
    road = img.copy()
    marks = np.zeros((H, W, 3), np.float32)
    cover = np.zeros((H, W), np.float32)
    phase = k * cfg["speed"]
    left_visible = not (cfg["gap_side"] == 0 and cfg["gap"][0] <= k < cfg["gap"][1])
    right_visible = not (cfg["gap_side"] == 1 and cfg["gap"][0] <= k < cfg["gap"][1])
    for xb, dashed, colour, vis in ((xl, cfg["left_dashed"], cfg["left_colour"], left_visible),
                                    (xr, cfg["right_dashed"], (225, 225, 225), right_visible)):
        if not vis:
            continue
        m = np.zeros((H, W), np.uint8)
        draw_marking(m, xb, vx, bend, dashed, phase, 255, None)
        a = m.astype(np.float32) / 255.0
        cover = np.maximum(cover, a)
        marks += a[..., None] * np.array(colour, np.float32)
    # shadows darken the markings too
    shade = np.where(road[..., 0:1] < 60, 0.45, 1.0)
    img = road * (1 - cover[..., None]) + marks * shade
    img += rng.normal(0, cfg["noise"], img.shape)
    img = np.clip(img, 0, 255).astype(np.uint8)
    yb, ytop = H - 1, int(round(ROI_TOP * H))
    tt = (yb - ytop) / (yb - HORIZON * H)
    truth = (marking_x(xl, vx, bend, 0), marking_x(xl, vx, bend, tt),
             marking_x(xr, vx, bend, 0), marking_x(xr, vx, bend, tt), left_visible, right_visible)
    return img, truth


SEQUENCES = {
    # straight road, dashed right line, shadows and patches, right line worn for 3 frames
    "straight": dict(seed=1, n=60, sway=18, bend=0.0, vx_shift=6, patches=6, shadows=2, noise=6,
                     speed=0.9, left_dashed=False, right_dashed=True, left_colour=(40, 200, 230),
                     gap_side=1, gap=(30, 33)),
    # gentle bend, dashed left line, left line worn for 3 frames
    "bend": dict(seed=2, n=60, sway=12, bend=0.015, vx_shift=10, patches=8, shadows=1, noise=8,
                 speed=1.1, left_dashed=True, right_dashed=False, left_colour=(225, 225, 225),
                 gap_side=0, gap=(40, 43)),
}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    for name, cfg in SEQUENCES.items():
        rng = np.random.default_rng(cfg["seed"])
        with open(os.path.join(out, "road_%s.y4m" % name), "wb") as y4m, \
                open(os.path.join(out, "road_%s.csv" % name), "w") as csv:
            y4m.write(b"YUV4MPEG2 W%d H%d F30:1 Ip A1:1 Cmono\n" % (W, H))
            csv.write("frame,left_bottom,left_top,right_bottom,right_top,left_visible,right_visible\n")
            for k in range(cfg["n"]):
                img, t = frame(rng, k, cfg["n"], cfg)
                grey = cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
                y4m.write(b"FRAME\n" + grey.tobytes())
                csv.write("%d,%.2f,%.2f,%.2f,%.2f,%d,%d\n" % ((k,) + t[:4] + (int(t[4]), int(t[5]))))
                if len(sys.argv) > 2 and k % 10 == 0:
                    cv2.imwrite(os.path.join(out, "road_%s_%02d.png" % (name, k)), img)


if __name__ == "__main__":
    main()
