#!/usr/bin/python3
"""rtedge contours / shapes / grasp end to end.

contours: the contours and features against OpenCV 4.6 on real photos.
shapes and grasp: the objects photos, checked against what the images show
(positions and classes written down from looking at each picture).

usage: test_grasp_cli.py RTEDGE_EXE SHARED_DATA_DIR
"""
import json
import math
import os
import sys
import tempfile

import cv2
import numpy as np

from cli_checks import Checks

RTEDGE = sys.argv[1]
SHARED = sys.argv[2] if len(sys.argv) > 2 else os.environ.get("RTE_SHARED_DATA_DIR", "")
OBJECTS = os.path.join(SHARED, "objects")
tally = Checks(RTEDGE)
run, check, failures = tally.run, tally.check, tally.failures


def shapes(name, *opts):
    """The table of `rtedge shapes` as a list of dicts."""
    r = run("shapes", os.path.join(OBJECTS, name), *opts)
    check(r.returncode == 0, f"shapes {name} {opts}: exit {r.returncode} {r.stderr}")
    rows = []
    for line in r.stdout.splitlines()[1:]:
        f = line.split()
        if len(f) == 8 and f[0].isdigit():
            rows.append({"shape": f[1], "area": float(f[2]), "perimeter": float(f[3]),
                         "solidity": float(f[4]), "aspect": float(f[5]), "c": (float(f[6]), float(f[7]))})
    return rows


def find(rows, x, y, tol=10):
    best = min(rows, key=lambda o: math.hypot(o["c"][0] - x, o["c"][1] - y), default=None)
    if best is None or math.hypot(best["c"][0] - x, best["c"][1] - y) > tol:
        return None
    return best


def expect(name, rows, x, y, shape, what, aspect=None):
    o = find(rows, x, y)
    check(o is not None, f"{name}: {what} near ({x},{y}) not found in {[(r['shape'], r['c']) for r in rows]}")
    if o is None:
        return None
    if shape:
        check(o["shape"] == shape, f"{name}: {what} at ({x},{y}) is {o['shape']}, expected {shape}")
    if aspect:
        check(aspect[0] <= o["aspect"] <= aspect[1], f"{name}: {what} aspect {o['aspect']} not in {aspect}")
    return o


def objects_photos():
    # pic1: white page, black objects. Top left a wide black rectangle
    # (x 43..231, y 25..128) with white dots inside; top right a black
    # rectangle tilted about 33 degrees; a head silhouette (left) with a
    # question mark; a thin upright bar (x 153..196, y 178..277, blurred
    # edges); a triangle pointing down (245,206)-(378,206)-(300,278).
    rows = shapes("pic1.png")
    check(5 <= len(rows) <= 7, f"pic1: {len(rows)} objects, expected 6 (5 shapes, the '?' hook)")
    expect("pic1", rows, 137, 76, "rectangle", "the dotted rectangle", (1.7, 1.95))
    expect("pic1", rows, 318, 112, "rectangle", "the tilted rectangle", (1.2, 1.45))
    expect("pic1", rows, 175, 228, "rectangle", "the upright bar", (2.0, 2.6))
    expect("pic1", rows, 308, 230, "triangle", "the triangle")
    expect("pic1", rows, 55, 219, "other", "the head")
    check(rows and rows[0]["c"][0] > 120 and rows[0]["c"][0] < 150, "pic1: the dotted rectangle is the largest")

    # pic2: salt-and-pepper noise everywhere; three noisy squares: green
    # (x 182..362, y 55..224), red (x 23..151, y 35..170), blue (x 53..126,
    # y 191..259). Nothing else.
    rows = shapes("pic2.png")
    check(len(rows) == 3, f"pic2: {len(rows)} objects, expected 3 squares")
    expect("pic2", rows, 271, 139, "square", "the green square")
    expect("pic2", rows, 87, 102, "square", "the red square")
    expect("pic2", rows, 89, 225, "square", "the blue square")

    # pic3: four hand-drawn thick outlines on white: a square (green, top
    # left), a triangle (salmon, top right), an ellipse (cyan, bottom
    # left), a square (purple, bottom right). Their outer borders are the
    # objects.
    rows = shapes("pic3.png")
    check(len(rows) == 4, f"pic3: {len(rows)} objects, expected 4")
    expect("pic3", rows, 140, 105, "square", "the green square")
    expect("pic3", rows, 295, 227, "square", "the purple square")
    expect("pic3", rows, 133, 251, "circle", "the cyan ellipse")
    # The salmon triangle's apex is rounded (approxPolyDP keeps a fourth
    # vertex there); it fills half its minimum-area box, so still a triangle.
    expect("pic3", rows, 322, 107, "triangle", "the salmon triangle")

    # pic4: red textured table; a black square (x 46..195, y 45..180), a
    # white rectangle (x 228..384, y 117..247), a green textured rectangle
    # (bottom left). One threshold per object colour.
    rows = shapes("pic4.png", "--binarize", "50", "--polarity", "dark")
    check(len(rows) >= 1 and rows[0]["shape"] == "square", f"pic4 dark: largest is {rows[:1]}")
    expect("pic4", rows, 120, 112, "square", "the black square")
    rows = shapes("pic4.png", "--binarize", "220", "--polarity", "bright", "--skip-border")
    check(len(rows) == 1, f"pic4 bright: {len(rows)} objects, expected the white rectangle")
    expect("pic4", rows, 305, 182, "rectangle", "the white rectangle", (1.1, 1.3))

    # pic5: a dark panel (x 20..240, y 10..278) holding a green tilted
    # rectangle, a white triangle and a pentagon outline; an orange tilted
    # rectangle overlapping the panel's right edge; a yellow rectangle
    # holding a blue square turned 45 degrees. Dark objects: the panel and
    # the blue square (the yellow, orange, white are lighter than the table).
    rows = shapes("pic5.png", "--binarize", "100", "--polarity", "dark", "--skip-border")
    check(len(rows) == 2, f"pic5 dark: {len(rows)} objects, expected the panel and the blue square")
    expect("pic5", rows, 130, 144, "rectangle", "the dark panel")
    expect("pic5", rows, 305, 208, "square", "the blue square (45 degrees)")

    # pic6: grey table; a black triangle (right, x 295..385, y 22..140);
    # a rectangle and a blob shaded from black to white (no global
    # threshold separates those from the grey). The triangle:
    rows = shapes("pic6.png", "--binarize", "40", "--polarity", "dark")
    expect("pic6", rows, 350, 82, "triangle", "the black triangle")

    # stuff.jpg: a wooden table; a white ball (centre ~395,185), a dark cap
    # with its shadow (~230,60), a pencil lying diagonally (~190,168), a
    # coin (~209,307), a red lighter (upright, ~337,390). Objects both darker
    # and lighter than the table: Canny + close.
    rows = shapes("stuff.jpg", "--binarize", "canny", "--canny-low", "30", "--canny-high", "90")
    check(len(rows) == 5, f"stuff: {len(rows)} objects, expected 5")
    expect("stuff", rows, 395, 185, "circle", "the ball")
    expect("stuff", rows, 209, 307, "circle", "the coin")
    expect("stuff", rows, 231, 61, None, "the cap")
    expect("stuff", rows, 189, 168, "rectangle", "the pencil", (10, 30))
    expect("stuff", rows, 337, 390, "rectangle", "the lighter", (2.5, 4))


def grasp_json():
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "g.png")
        r = run("grasp", os.path.join(OBJECTS, "pic1.png"), "--overlay", out)
        check(r.returncode == 0, f"grasp pic1: exit {r.returncode} {r.stderr}")
        d = json.loads(r.stdout)
        objs = d["objects"]
        check(len(objs) == 6 and d["truncated"] is False, f"grasp pic1: {len(objs)} objects")
        keys = [(o["score"], o["area"]) for o in objs]
        check(keys == sorted(keys, reverse=True), f"grasp: sorted by score, then area: {keys}")
        for o in objs:
            # opened 8 px (--margin's default) wider on each side; the jaws that far apart
            jd = math.hypot(o["jaws"][1][0] - o["jaws"][0][0], o["jaws"][1][1] - o["jaws"][0][1])
            check(0 <= o["score"] <= 1 and abs(o["opening"] - o["width"] - 16) < 0.02 and
                  abs(jd - o["opening"]) < 0.1 and 0 <= o["clearance"] <= 16, f"grasp fields {o}")
        # the wide rectangle: close vertically (90 degrees) to its 103 px height,
        # the best grasp (convex, room all round)
        o = min(objs, key=lambda o: math.hypot(o["center"][0] - 137, o["center"][1] - 76.5))
        check(o is objs[0] and o["score"] == 1, f"grasp: the wide rectangle first, score 1: {objs[:1]}")
        check(abs(o["center"][0] - 137) < 1 and abs(o["center"][1] - 76.5) < 1, f"grasp centre {o['center']}")
        check(o["angle"] == 90 and abs(o["width"] - 103) < 1, f"grasp angle/width {o['angle']} {o['width']}")
        # the tilted rectangle: long side at about 57 degrees, close at about -33
        t = min(objs, key=lambda o: math.hypot(o["center"][0] - 318, o["center"][1] - 112))
        check(abs(t["angle"] + 33) < 3 and t["shape"] == "rectangle", f"tilted rectangle grasp {t}")
        img, src = cv2.imread(out), cv2.imread(os.path.join(OBJECTS, "pic1.png"))
        check(img is not None and img.shape == src.shape, "grasp overlay written at the input's size")
        if img is not None and img.shape == src.shape:
            changed = np.count_nonzero(np.any(img != src, axis=2))
            check(500 < changed < img.shape[0] * img.shape[1] // 4, f"overlay draws ({changed} pixels)")
            # the grasp point is a red dot at the centroid
            check(tuple(img[76, 137]) == (0, 0, 255), f"red grasp dot at (137,76): {img[76, 137]}")
        r = run("shapes", os.path.join(OBJECTS, "stuff.jpg"), "--binarize", "canny", "--overlay",
                os.path.join(tmp, "s.ppm"))
        check(r.returncode == 0 and cv2.imread(os.path.join(tmp, "s.ppm")) is not None, "shapes overlay .ppm")
        r = run("grasp", os.path.join(OBJECTS, "pic1.png"), "--overlay", os.path.join(tmp, "no", "x.png"))
        check(r.returncode == 1, f"unwritable overlay: exit {r.returncode}")
    # --roi: a workspace over the right half of pic1; only objects inside it,
    # and the tilted rectangle (x ~318) found where it was found without one
    src = cv2.imread(os.path.join(OBJECTS, "pic1.png"))
    r = run("grasp", os.path.join(OBJECTS, "pic1.png"), "--roi", "0.5,0;1,0;1,1;0.5,1")
    check(r.returncode == 0, f"grasp --roi: exit {r.returncode} {r.stderr}")
    if r.returncode == 0 and src is not None:
        inside = json.loads(r.stdout)["objects"]
        half = src.shape[1] / 2
        check(inside and all(min(x for x, _ in o["box"]) >= half - 1 for o in inside),
              f"grasp --roi: objects outside the workspace: {[o['center'] for o in inside]}")
        t = [o for o in inside if math.hypot(o["center"][0] - 318, o["center"][1] - 112) < 3]
        check(len(t) == 1 and abs(t[0]["angle"] + 33) < 3, f"grasp --roi: tilted rectangle {t}")
    # a gripper opening at most 100 px: the 103 px rectangle cannot be taken
    r = run("grasp", os.path.join(OBJECTS, "pic1.png"), "--gripper-max", "100")
    check(r.returncode == 0, f"grasp --gripper-max: exit {r.returncode} {r.stderr}")
    if r.returncode == 0:
        objs = json.loads(r.stdout)["objects"]
        wide = [o for o in objs if math.hypot(o["center"][0] - 137, o["center"][1] - 76.5) < 1]
        check(len(wide) == 1 and wide[0]["score"] == 0 and
              all(o["score"] == 0 for o in objs[objs.index(wide[0]):]),
              f"grasp --gripper-max 100: the wide rectangle {wide} among the last")
    for bad in (["--binarize", "foo"], ["--binarize", "300"], ["--blur", "4"], ["--polarity", "up"],
                ["--roi", "0.5,0;1,0"], ["--roi", "a,b;c,d;e,f"], ["--gripper-min", "90", "--gripper-max", "80"],
                ["--margin", "-1"], ["--finger", "5000"], ["--edge-support", "1.5"]):
        r = run("grasp", os.path.join(OBJECTS, "pic1.png"), *bad)
        check(r.returncode == 2, f"grasp {bad}: exit {r.returncode}, expected 2")
    r = run("grasp", "/nonexistent.png")
    check(r.returncode == 3, f"missing input: exit {r.returncode}")


def large_image():
    """A photo taken at 1920x1440 (the smarties enlarged): more possible
    contours than the library stores (w h / 2), so the command runs with
    the library's bounds and all the sweets are still found; and one at
    4032x3024, larger than the grasp path takes."""
    src = cv2.imread(os.path.join(OBJECTS, "smarties.png"))
    with tempfile.TemporaryDirectory() as tmp:
        big = os.path.join(tmp, "big.png")
        cv2.imwrite(big, cv2.resize(src, (1920, 1440), interpolation=cv2.INTER_CUBIC))
        for cmd in ("contours", "shapes", "grasp"):
            r = run(cmd, big)
            check(r.returncode == 0, f"{cmd} 1920x1440: exit {r.returncode} {r.stderr}")
        r = run("grasp", big)
        if r.returncode == 0:
            n = len(json.loads(r.stdout)["objects"])
            check(n == 10, f"grasp 1920x1440: {n} objects, expected the 10 whole sweets")
        # a phone's 4032x3024: beyond the grasp path's 2048 px a side, reduced 2x
        # (block means) and reported in the photo's pixels; the sizes in pixels
        # grown with it (the sweets are about 500 px across)
        huge = os.path.join(tmp, "huge.jpg")
        cv2.imwrite(huge, cv2.resize(src, (4032, 3024), interpolation=cv2.INTER_CUBIC))
        r = run("grasp", huge, "--overlay", os.path.join(tmp, "h.png"))
        check(r.returncode == 0, f"grasp 4032x3024: exit {r.returncode} {r.stderr}")
        if r.returncode == 0:
            d = json.loads(r.stdout)
            sx, sy = 4032 / src.shape[1], 3024 / src.shape[0]
            sweets = [(378, 81), (269, 118), (206, 212), (287.5, 214), (348, 239), (34, 229),
                      (98.75, 259), (152, 272), (219.75, 306.5), (295, 321)]
            worst = max(min(math.hypot(o["center"][0] - ((x + 0.5) * sx - 0.5),
                                       o["center"][1] - ((y + 0.5) * sy - 0.5)) for o in d["objects"])
                        for x, y in sweets)
            check(d["reduced"] == 2 and len(d["objects"]) == 10 and worst < 0.06 * 54 * sx,
                  f"grasp 4032x3024: reduced {d['reduced']}, {len(d['objects'])} objects, "
                  f"worst centre {worst:.1f} px")
            o = cv2.imread(os.path.join(tmp, "h.png"))
            check(o is not None and o.shape == (3024, 4032, 3), "grasp 4032x3024: overlay at the photo's size")
            check(all(ob["score"] > 0.9 for ob in d["objects"]),
                  f"grasp 4032x3024: a gripper for the photo's size (scores {[ob['score'] for ob in d['objects']]})")
        # a gripper given is taken as given: 160 px cannot take a 500 px sweet
        r = run("grasp", huge, "--gripper-max", "160")
        if r.returncode == 0:
            d = json.loads(r.stdout)
            check(d["objects"] and all(ob["score"] == 0 for ob in d["objects"]),
                  "grasp 4032x3024 --gripper-max 160: no sweet graspable")
        r = run("shapes", huge)
        check(r.returncode == 0, f"shapes 4032x3024: exit {r.returncode} {r.stderr}")
        # too long and thin to reduce: refused, saying why
        thin = os.path.join(tmp, "thin.png")
        cv2.imwrite(thin, np.full((2, 30000), 128, np.uint8))
        r = run("grasp", thin)
        check(r.returncode == 3 and "too thin to reduce 15 times" in r.stderr,
              f"grasp 30000x2: exit {r.returncode} {r.stderr}")
        # contours prints OpenCV's contours of the image as it is: refused, saying why
        r = run("contours", huge)
        check(r.returncode == 3 and "larger than 2048 px a side" in r.stderr,
              f"contours 4032x3024: exit {r.returncode} {r.stderr}")


def contours_vs_opencv():
    """rtedge contours against cv2 on threshold-127 images of the photos."""
    names = ["pic1.png", "pic3.png", "stuff.jpg", "smarties.png"]
    for name in names:
        path = os.path.join(OBJECTS, name)
        gray = cv2.cvtColor(cv2.imread(path), cv2.COLOR_BGR2GRAY)
        _, binary = cv2.threshold(gray, 127, 255, cv2.THRESH_BINARY)
        for mode, cvmode in (("external", cv2.RETR_EXTERNAL), ("list", cv2.RETR_LIST), ("ccomp", cv2.RETR_CCOMP),
                             ("tree", cv2.RETR_TREE)):
            for method, cvmethod in (("none", cv2.CHAIN_APPROX_NONE), ("simple", cv2.CHAIN_APPROX_SIMPLE)):
                r = run("contours", path, "--binarize", "127", "--polarity", "bright", "--mode", mode,
                        "--method", method)
                check(r.returncode == 0, f"contours {name} {mode} {method}: exit {r.returncode} {r.stderr}")
                if r.returncode:
                    continue
                got = json.loads(r.stdout)["contours"]
                cs, hier = cv2.findContours(binary, cvmode, cvmethod)
                check(len(got) == len(cs), f"{name} {mode} {method}: {len(got)} contours, cv2 {len(cs)}")
                for g in got:
                    i = g["index"]
                    if i >= len(cs):
                        break
                    c = cs[i]
                    pts = c.reshape(-1, 2).tolist()
                    check(g["points"] == pts, f"{name} {mode} {method} #{i}: points differ")
                    check(g["hierarchy"] == hier[0][i].tolist(), f"{name} {mode} #{i}: hierarchy")
                    if mode != "tree" or method != "simple":
                        continue  # the features once per image
                    features(name, i, g, c)


def features(name, i, g, c):
    what = f"{name} #{i}"
    check(abs(g["area"] - cv2.contourArea(c)) < 1e-9, f"{what}: area {g['area']} vs {cv2.contourArea(c)}")
    per = cv2.arcLength(c, True)
    check(abs(g["perimeter"] - per) <= 1e-4 + len(c) / 131072, f"{what}: perimeter {g['perimeter']} vs {per}")
    m = cv2.moments(c)
    if m["m00"] != 0:
        check(abs(g["centroid"][0] - m["m10"] / m["m00"]) < 1e-4 and abs(g["centroid"][1] - m["m01"] / m["m00"]) < 1e-4,
              f"{what}: centroid {g['centroid']}")
    check(g["bbox"] == list(cv2.boundingRect(c)), f"{what}: bbox {g['bbox']} vs {cv2.boundingRect(c)}")
    (cx, cy), (w, h), _ = cv2.minAreaRect(c)
    mr = g["min_rect"]
    # the minimum area is unique; the rectangle is not when areas tie (tiny
    # contours: a 1x1 square and a 0.7x1.4 diamond), so compare the area,
    # and the rectangle itself on contours of some size
    check(abs(mr["size"][0] * mr["size"][1] - w * h) < 0.05 + 0.01 * w * h, f"{what}: min rect area")
    if w * h > 16:
        check(abs(mr["center"][0] - cx) < 0.02 and abs(mr["center"][1] - cy) < 0.02, f"{what}: min rect centre")
        check(abs(max(mr["size"]) - max(w, h)) < 0.02 and abs(min(mr["size"]) - min(w, h)) < 0.02,
              f"{what}: min rect size {mr['size']} vs {(w, h)}")
    (ex, ey), er = cv2.minEnclosingCircle(c)
    ci = g["circle"]
    check(abs(ci["center"][0] - ex) < 0.02 and abs(ci["center"][1] - ey) < 0.02 and abs(ci["r"] - er) < 0.02,
          f"{what}: circle {ci} vs {(ex, ey, er)}")
    hull = cv2.convexHull(c, clockwise=False).reshape(-1, 2).tolist()
    check(g["hull"] == hull, f"{what}: hull differs")
    if len(c) > 3 and len(hull) >= 3:
        hidx = cv2.convexHull(c, clockwise=False, returnPoints=False)
        try:
            d = cv2.convexityDefects(c, hidx)
        except cv2.error:
            d = None
        if d is not None:
            exp = [[int(a), int(b), int(f), round(dd / 256.0, 2)] for a, b, f, dd in d.reshape(-1, 4)]
            check([x[:3] for x in g["defects"]] == [x[:3] for x in exp], f"{what}: defects differ")
    ap = cv2.approxPolyDP(c, 0.02 * per, True).reshape(-1, 2).tolist()
    # epsilon is 0.02 x the Q16 perimeter: equal but for exact ties
    check(g["approx"] == ap or abs(len(g["approx"]) - len(ap)) <= 1, f"{what}: approx {g['approx']} vs {ap}")


def main():
    if not os.path.isdir(OBJECTS):
        print(f"SKIP: {OBJECTS} not found")
        return 77
    objects_photos()
    grasp_json()
    large_image()
    contours_vs_opencv()
    return tally.finish("grasp cli")


if __name__ == "__main__":
    sys.exit(main())
