#!/usr/bin/python3
"""Synthetic curved roads with exact ground truth, for the lane tests.

A pinhole camera (focal F px, height CAM_H m, looking level along the road)
drives along a flat road whose centre line bends: constant-curvature bends,
S-bends, a straight road into a sharp turn (its markings running nearly
along the rows near the horizon), a lane whose width changes, tree shadows, glare, worn and dashed
markings, a light/dark pavement seam parallel to the lane and a double
yellow centre line. Each scene is a directory of BGR PNG frames
(OUT/curve_<scene>/0000.png, ...) and OUT/curve_<scene>.csv with one line
per frame and side:

    frame,side,visible,x@row,x@row,...   (header: frame,side,visible,<rows>)

`side` is left or right, `visible` 1 when the side's marking can be seen
in the frame (0: hidden, e.g. by glare over the whole road), and each x is
the marking's centre (for the double yellow line: the centre between its
two lines) on that row, in pixels. The rows are every 10 px from the
bottom row up to 0.62 of the height (the lower 38% of the frame).

Geometry: a road point at distance z ahead and lateral offset X (metres,
positive right) is at x = W/2 + F * X / z, y = Y_HORIZON + F * CAM_H / z.
The ego lane's centre line is X_c(z) (the scene's bend, minus the camera's
lateral offset and yaw); a marking sits at X_c(z) +- half the lane width.
z is the distance along the road: for the curvatures used (radius >= 60 m
over 45 m) the difference from the straight-ahead distance is under 2 %.

Deterministic (fixed seeds). Needs python3-opencv and numpy:
    /usr/bin/python3 tools/make_curved_roads.py OUT_DIR [SCENE...]
"""
import math
import os
import sys
import zlib

import cv2
import numpy as np

W, H = 640, 360
F = 500.0  # focal length, px
CAM_H = 1.5  # camera height over the road, m
Y_HORIZON = 0.55 * H
LABEL_TOP = 0.62 * H  # labelled rows: the lower 38% of the frame
FRAMES = 24
SPEED = 0.8  # metres per frame (24 m/s at 30 fps)
SS = 2  # supersampling for anti-aliased markings

WHITE = (225, 225, 225)
YELLOW = (40, 190, 230)  # BGR


def label_rows():
    rows, y = [], H - 1
    while y >= LABEL_TOP:
        rows.append(y)
        y -= 10
    return rows


def curvature_at(scene, s):
    """Road curvature (1/m, positive right) at distance s along the road."""
    kind = scene["bend"]
    if kind == "left":
        return -1.0 / scene["radius"]
    if kind == "right":
        return 1.0 / scene["radius"]
    if kind == "s":  # right, then left, period `period` m
        return math.sin(2 * math.pi * s / scene["period"]) / scene["radius"]
    if kind == "turn":  # straight, then a sharp right turn from `turn_at` m
        return 1.0 / scene["radius"] if s >= scene["turn_at"] else 0.0
    return 0.0


def centre_profile(scene, s0):
    """The road centre's lateral offset (m) against distance ahead of the
    camera at s0, relative to the road's heading at s0: the curvature
    integrated twice (trapezoids on a 5 cm grid)."""
    z = np.linspace(0.0, 100.0, 2001)
    kappa = np.array([curvature_at(scene, s0 + zi) for zi in z])
    dz = z[1] - z[0]
    heading = np.concatenate(([0.0], np.cumsum((kappa[1:] + kappa[:-1]) / 2) * dz))
    offset = np.concatenate(([0.0], np.cumsum((heading[1:] + heading[:-1]) / 2) * dz))
    return z, offset


def lane_width(scene, z, k):
    w = scene.get("width", 3.6)
    if scene.get("width_change"):
        # +-0.5 m over a 150 m period: at most 1:48, a taper as steep as
        # road design allows
        w += 0.5 * math.sin(2 * math.pi * (k * SPEED + z) / 150.0)
    return w


def markings(scene, k):
    """(lateral offset function of z, half width m, colour, dashed, is_left)
    for every painted line; the double yellow centre line is two lines."""
    out = []
    left_kind = scene.get("left", "solid")
    right_kind = scene.get("right", "dashed")
    for side, kind in ((-1, left_kind), (1, right_kind)):
        colour = YELLOW if kind == "double_yellow" or (side < 0 and scene.get("left_yellow")) else WHITE
        if kind == "double_yellow":
            for d in (-0.2, 0.2):
                out.append((side, d, 0.06, colour, False))
        else:
            out.append((side, 0.0, 0.075, colour, kind == "dashed"))
    return out


def camera_pose(scene, k):
    sway = scene.get("sway", 0.25) * math.sin(2 * math.pi * k / FRAMES)
    yaw = scene.get("yaw", 0.004) * math.sin(2 * math.pi * k / FRAMES + 1.0)
    return sway, yaw


def lateral(scene, k, side, d, z, profile):
    """Marking's lateral offset (m) relative to the camera at depth z."""
    sway, yaw = camera_pose(scene, k)
    xc = np.interp(z, profile[0], profile[1])
    return xc + side * lane_width(scene, z, k) / 2 + d - sway - yaw * z


def render(scene, k, rng):
    hs, ws = H * SS, W * SS
    img = np.zeros((hs, ws, 3), np.float32)
    img[:] = (205, 175, 150)  # sky
    yh = int(Y_HORIZON * SS)
    ys = (np.arange(hs, dtype=np.float64) + 0.5) / SS
    xs = (np.arange(ws, dtype=np.float64) + 0.5) / SS
    road = np.full((hs - yh, ws), 100.0)
    # pavement texture: slow variation along the road and fine grain
    z_rows = F * CAM_H / np.maximum(ys[yh:] - Y_HORIZON, 0.5)
    road += 8 * np.sin(z_rows * 0.7 + k * SPEED * 0.7)[:, None]
    s0 = scene.get("start", 0.0) + k * SPEED
    profile = centre_profile(scene, s0)
    paint = np.zeros_like(road)
    colour_sum = np.zeros(road.shape + (3,), np.float32)
    seam = scene.get("seam")
    for r, y in enumerate(ys[yh:]):
        if y - Y_HORIZON < 0.5:
            continue
        z = F * CAM_H / (y - Y_HORIZON)
        if z > 80:
            continue
        if seam is not None:
            xsm = W / 2 + F * lateral(scene, k, -1, seam, z, profile) / z
            road[r, xs > xsm] *= 0.72
        for side, d, half, colour, dashed in markings(scene, k):
            if dashed and ((s0 + z) % 12.0) > 3.0:
                continue
            if scene.get("worn") and rng_worn(scene, side, s0 + z):
                continue
            xm = W / 2 + F * lateral(scene, k, side, d, z, profile) / z
            hw = max(F * half / z, 0.35)
            cover = np.clip(hw + 0.5 / SS - np.abs(xs - xm), 0, 1.0 / SS) * SS
            paint[r] = np.maximum(paint[r], cover)
            colour_sum[r] += cover[:, None] * np.array(colour, np.float32)
    col = road[..., None] * np.ones(3, np.float32)
    col = col * (1 - paint[..., None]) + np.minimum(colour_sum, 255) * (paint[..., None] > 0)
    img[yh:] = col
    img = shade_and_glare(scene, k, img, yh)
    img = cv2.resize(img, (W, H), interpolation=cv2.INTER_AREA)
    img += rng.normal(0, 4.0, img.shape)
    return np.clip(img, 0, 255).astype(np.uint8)


def rng_worn(scene, side, s):
    """Worn paint: pieces of the marking missing, fixed along the road."""
    cell = int(math.floor(s / 1.5))
    h = (cell * 2654435761 + (side + 3) * 40503) & 0xFFFF
    return h < 0x7000  # about 44 % missing


def shade_and_glare(scene, k, img, yh):
    hs, ws = img.shape[:2]
    out = img
    if scene.get("shadows"):
        prng = np.random.default_rng(1000 + k // 3)
        mask = np.zeros((hs, ws), np.float32)
        for _ in range(scene["shadows"]):
            cx = prng.uniform(0, ws)
            cy = prng.uniform(yh, hs)
            ax, ay = prng.uniform(30, 160) * SS, prng.uniform(6, 30) * SS
            cv2.ellipse(mask, (int(cx), int(cy)), (int(ax), int(ay)), prng.uniform(-20, 20), 0, 360,
                        1.0, -1)
        mask = cv2.GaussianBlur(mask, (0, 0), 2.0 * SS)
        out = out * (1 - 0.55 * mask[..., None])
    glare = scene.get("glare")
    if glare:
        mask = np.zeros((hs, ws), np.float32)
        if k in glare.get("hidden", ()):
            mask[yh:] = 1.0  # the whole road washed out
        else:
            prng = np.random.default_rng(2000 + k)
            for _ in range(glare.get("patches", 2)):
                cx, cy = prng.uniform(0, ws), prng.uniform(yh, hs)
                ax, ay = prng.uniform(40, 120) * SS, prng.uniform(15, 50) * SS
                cv2.ellipse(mask, (int(cx), int(cy)), (int(ax), int(ay)), 0, 0, 360, 1.0, -1)
            mask = cv2.GaussianBlur(mask, (0, 0), 6.0 * SS)
        out = out * (1 - mask[..., None]) + 255.0 * mask[..., None]
    return out


def truth(scene, k):
    """Per side: (visible, [x at each labelled row])."""
    hidden = k in scene.get("glare", {}).get("hidden", ())
    rows = label_rows()
    profile = centre_profile(scene, scene.get("start", 0.0) + k * SPEED)
    result = {}
    for side, name in ((-1, "left"), (1, "right")):
        xs = []
        for y in rows:
            z = F * CAM_H / (y + 0.5 - Y_HORIZON)
            # pixel centres are at +0.5: the row's centre line
            xs.append(W / 2 + F * lateral(scene, k, side, 0.0, z, profile) / z - 0.5)
        result[name] = (not hidden, xs)
    return result


SCENES = {
    "left_bend": dict(bend="left", radius=120.0, left="solid", right="dashed"),
    "right_bend": dict(bend="right", radius=120.0, left="solid", right="dashed", left_yellow=True),
    "tight_bend": dict(bend="right", radius=70.0, left="solid", right="solid"),
    "s_bend": dict(bend="s", radius=110.0, period=70.0, left="dashed", right="solid"),
    "width_change": dict(bend="left", radius=200.0, width_change=True, left="solid", right="dashed"),
    "shadows": dict(bend="s", radius=130.0, period=90.0, shadows=9, left="solid", right="dashed"),
    "glare": dict(bend="right", radius=150.0, glare={"patches": 2, "hidden": (9, 10, 11, 19)},
                  left="solid", right="solid"),
    "worn": dict(bend="left", radius=160.0, worn=True, left="solid", right="solid"),
    "seam": dict(bend="right", radius=180.0, seam=0.9, left="solid", right="dashed"),
    "double_yellow": dict(bend="left", radius=140.0, left="double_yellow", right="solid"),
    "straight": dict(bend="none", left="solid", right="dashed", left_yellow=True),
    "sharp_turn": dict(bend="turn", radius=22.0, turn_at=36.0, left="solid", right="solid",
                       left_yellow=True),
}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    names = sys.argv[2:] or list(SCENES)
    rows = label_rows()
    for name in names:
        scene = SCENES[name]
        d = os.path.join(out, "curve_" + name)
        os.makedirs(d, exist_ok=True)
        rng = np.random.default_rng(zlib.crc32(name.encode()))
        with open(os.path.join(out, "curve_%s.csv" % name), "w") as csv:
            csv.write("frame,side,visible," + ",".join(str(y) for y in rows) + "\n")
            for k in range(FRAMES):
                cv2.imwrite(os.path.join(d, "%04d.png" % k), render(scene, k, rng))
                for side, (visible, xs) in truth(scene, k).items():
                    csv.write("%d,%s,%d,%s\n" % (k, side, int(visible),
                                                 ",".join("%.2f" % x for x in xs)))


if __name__ == "__main__":
    main()
