#!/usr/bin/python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/NAME/): small
valid inputs of every kind each target reads, damaged variants, and the
reproducers of the hostile cases that issue 18 lists (repro_* files). The
output is committed; run this again only to change the seeds.

    tests/fuzz/make_seeds.py BUILD/src/publish/python [OUT_DIR]

Needs python3-opencv and python3-numpy (Debian's /usr/bin/python3) for the
PNG and JPEG seeds, and lcm-gen's Python types for params_t and image_t.
"""
import os
import struct
import sys
import zlib

import cv2
import numpy as np

TYPES = sys.argv[1]
OUT = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "corpus")
sys.path.insert(0, TYPES)
from rtedge import image_t, param_t, params_t  # noqa: E402


def write(target, name, data):
    d = os.path.join(OUT, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def picture(w, h, channels):
    y, x = np.mgrid[0:h, 0:w]
    img = ((x * 37 + y * 11) % 256).astype(np.uint8)
    if channels == 1:
        return img
    return np.dstack([img, (img * 3) % 256, 255 - img]).astype(np.uint8)


# ---- image: PGM/PPM, PNG, JPEG ----
def pnm(magic, img, maxval=255, comment=b""):
    h, w = img.shape[:2]
    head = b"P%d\n%s%d %d\n%d\n" % (magic, comment, w, h, maxval)
    if magic in (2, 3):
        return head + b" ".join(b"%d" % min(v, maxval) for v in img.flatten()) + b"\n"
    return head + img.tobytes()


def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def palette_png(w, h):
    rows = b"".join(b"\0" + bytes((x + y) % 4 for x in range(w)) for y in range(h))
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 3, 0, 0, 0))
            + png_chunk(b"PLTE", bytes([0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255]))
            + png_chunk(b"IDAT", zlib.compress(rows)) + png_chunk(b"IEND", b""))


def with_exif_orientation(jpeg, orientation):
    tiff = b"MM\0\x2a\0\0\0\x08" + struct.pack(">H", 1) + struct.pack(">HHIHH", 0x0112, 3, 1,
                                                                        orientation, 0) + b"\0\0\0\0"
    app1 = b"Exif\0\0" + tiff
    return jpeg[:2] + b"\xff\xe1" + struct.pack(">H", len(app1) + 2) + app1 + jpeg[2:]


grey, colour = picture(8, 6, 1), picture(8, 6, 3)
write("image", "p2.pgm", pnm(2, grey))
write("image", "p3.ppm", pnm(3, colour, maxval=100))
write("image", "p5.pgm", pnm(5, grey, comment=b"# a comment\n"))
write("image", "p6.ppm", pnm(6, colour))
write("image", "p5_truncated.pgm", pnm(5, grey)[:-10])
write("image", "p5_absurd_size.pgm", b"P5\n99999 99999\n255\n" + bytes(64))
write("image", "p5_overflow_size.pgm", b"P5\n4294967297 2\n255\n" + bytes(64))
for name, img in (("grey.png", grey), ("rgb.png", colour),
                  ("rgba.png", np.dstack([colour, grey])),
                  ("grey16.png", (grey.astype(np.uint16) * 257))):
    write("image", name, cv2.imencode(".png", img)[1].tobytes())
write("image", "palette.png", palette_png(8, 6))
write("image", "png_truncated.png", cv2.imencode(".png", colour)[1].tobytes()[:-20])
write("image", "rgb.jpg", cv2.imencode(".jpg", picture(16, 16, 3))[1].tobytes())
write("image", "grey.jpg", cv2.imencode(".jpg", picture(16, 8, 1))[1].tobytes())
write("image", "progressive.jpg", cv2.imencode(".jpg", picture(16, 16, 3),
                                               [cv2.IMWRITE_JPEG_PROGRESSIVE, 1])[1].tobytes())
write("image", "exif6.jpg", with_exif_orientation(cv2.imencode(".jpg", picture(16, 8, 3))[1].tobytes(), 6))
write("image", "jpg_truncated.jpg", cv2.imencode(".jpg", picture(16, 16, 3))[1].tobytes()[:-30])

# ---- y4m ----
def y4m(header, frames):
    return header + b"".join(b"FRAME\n" + f for f in frames)


w, h = 16, 8
mono = [picture(w, h, 1).tobytes() for _ in range(3)]
i420 = [picture(w, h, 1).tobytes() + bytes(range(64)) for _ in range(2)]
write("y4m", "mono.y4m", y4m(b"YUV4MPEG2 W16 H8 F30:1 Ip A1:1 Cmono\n", mono))
write("y4m", "i420.y4m", y4m(b"YUV4MPEG2 W16 H8 F30000:1001 C420jpeg XYSCSS=420JPEG\n", i420))
write("y4m", "odd_size.y4m", y4m(b"YUV4MPEG2 W7 H5 C420\n", [bytes(35 + 2 * 12)]))
write("y4m", "frame_params.y4m", b"YUV4MPEG2 W4 H2 Cmono\nFRAME Ixyz\n" + bytes(8) + b"FRAME\n" + bytes(8))
write("y4m", "damaged_frame.y4m", b"YUV4MPEG2 W4 H2 Cmono\nFRAMX\n" + bytes(8) + b"FRAME\n" + bytes(8))
write("y4m", "c444.y4m", y4m(b"YUV4MPEG2 W4 H2 C444\n", [bytes(24)]))
write("y4m", "c422.y4m", y4m(b"YUV4MPEG2 W4 H2 C422\n", [bytes(16)]))
write("y4m", "interlaced.y4m", y4m(b"YUV4MPEG2 W4 H2 It Cmono\n", [bytes(8)]))
# issue 18: a wrapping width, a recording with no good frame, a header only
write("y4m", "repro_width_wraps.y4m", b"YUV4MPEG2 W4294967300 H2 F30:1 Cmono\nFRAME\n" + bytes(8))
write("y4m", "repro_cut_short.y4m", b"YUV4MPEG2 W64 H48 F30:1 Cmono\nFRAME\nabc")
write("y4m", "repro_header_only.y4m", b"YUV4MPEG2 W64 H48 F30:1 Cmono\n")
write("y4m", "rate_overflow.y4m", b"YUV4MPEG2 W4 H2 F4294967326:1 Cmono\nFRAME\n" + bytes(8))

# ---- raw: format index, width - 1, height - 1, then the file ----
write("raw", "grey_8x4.raw", bytes([0, 7, 3]) + bytes(range(64)))
write("raw", "bgr_4x2_cut.raw", bytes([1, 3, 1]) + bytes(24 + 10))
write("raw", "yuyv_8x2.raw", bytes([3, 7, 1]) + bytes(range(32)) * 2)
write("raw", "nv12_6x4.raw", bytes([5, 5, 3]) + bytes(36) * 3)
write("raw", "bad_format.raw", bytes([6, 3, 3]) + bytes(16))

# ---- lcm_log: mode byte (bit 0 sized, bit 1 channel CAMERA, bits 2-3 format), then the log ----
def event(n, channel, data, utime=1000):
    return struct.pack(">IqqII", 0xEDA1DA01, n, utime, len(channel), len(data)) + channel + data


def image(w, h, fmt, stride=0, utime=1000):
    m = image_t()
    m.utime, m.width, m.height, m.pixelformat = utime, w, h, fmt
    rows = {image_t.PIXEL_FORMAT_GRAY: 1, image_t.PIXEL_FORMAT_BGR: 3,
            image_t.PIXEL_FORMAT_YUYV: 2, image_t.PIXEL_FORMAT_NV12: 1}[fmt]
    m.row_stride = stride or w * rows
    lines = h + (h + 1) // 2 if fmt == image_t.PIXEL_FORMAT_NV12 else h
    m.data = bytes((i * 7) % 256 for i in range(m.row_stride * lines))
    m.size = len(m.data)
    return m.encode()


G, B, N, Y = (image_t.PIXEL_FORMAT_GRAY, image_t.PIXEL_FORMAT_BGR, image_t.PIXEL_FORMAT_NV12,
              image_t.PIXEL_FORMAT_YUYV)
log = (event(0, b"CAMERA", image(16, 8, G)) + event(1, b"OTHER", b"not an image")
       + event(2, b"CAMERA", image(16, 8, G, utime=34000)))
write("lcm_log", "grey_any", b"\x00" + log)
write("lcm_log", "grey_sized_channel", b"\x03" + log)
write("lcm_log", "bgr_padded", b"\x05" + event(0, b"CAMERA", image(6, 4, B, stride=20)))
write("lcm_log", "nv12", b"\x09" + event(0, b"CAMERA", image(6, 5, N)))
write("lcm_log", "yuyv", b"\x0d" + event(0, b"CAMERA", image(8, 2, Y)))
write("lcm_log", "corrupt_sync", b"\x00" + b"garbage!" + log)
write("lcm_log", "truncated", b"\x00" + log[:-7])
write("lcm_log", "bad_lengths", b"\x00" + struct.pack(">IqqII", 0xEDA1DA01, 0, 0, 0x7fffffff, 0xffffffff))
inconsistent = bytearray(image(16, 8, G))
inconsistent[24:28] = struct.pack(">i", -5)   # stride
write("lcm_log", "image_inconsistent", b"\x00" + event(0, b"CAMERA", bytes(inconsistent)))

# ---- config: 1 + an INI file, or 0 + --set lines ----
conf = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "rtedged.conf")
write("config", "rtedged.conf", b"\x01" + open(conf, "rb").read())
write("config", "small.conf", b"\x01[source]\npath = a.y4m\nloop = true\n[lane]\nroi = 0,1;0.4,0.6;0.6,0.6;1,1\n"
      b"canny_low = 40\ncanny_high = 120\n[params]\nenabled = true\nkeys = grasp.min_area, lane.canny_low\n"
      b"[deadline]\nms = 33.333333333333336\n")
write("config", "repro_nul_byte.conf", b"\x01[grasp]\nthreshold = 3\0\n")
write("config", "bad_lines.conf", b"\x01[lane\n[nosuch]\nx = 1\n[grasp]\nthreshold\nthreshold = 300\n")
write("config", "long_line.conf", b"\x01[source]\npath = " + b"x" * 1100 + b"\n")
write("config", "sets", b"\x00source.path=/dev/video0\nsource.width=640\nlane.roi=0,1;0.5,0.5;1,1\n"
      b"deadline.ms=1e-300\nparams.keys=lane.roi\n")
write("config", "sets_frame", b"\x00grasp.min_area=5000000\nlane.hough_threshold=16000\n"
      b"lane.roi=0.5,0.5;0.51,0.5;0.5,0.51\x7f")


# ---- params: encoded params_t ----
def params(values, request_id=1, action=0):
    m = params_t()
    m.utime, m.request_id, m.action = 123, request_id, action
    m.params = []
    for name, kind, iv, rv, *text in values:
        p = param_t()
        p.name, p.kind, p.int_value, p.real_value = name, kind, iv, rv
        p.text_value = text[0] if text else ""
        m.params.append(p)
    m.nparams = len(m.params)
    return m.encode()


I, R, BO, T = param_t.KIND_INT, param_t.KIND_REAL, param_t.KIND_BOOL, param_t.KIND_TEXT
head = params([("grasp.min_area", I, 1, 0)])[:29]  # fingerprint, utime, request_id, action, nparams
write("params", "valid_int", params([("grasp.min_area", I, 920, 0)]))
write("params", "valid_three", params([("lane.canny_low", I, 40, 0), ("lane.canny_high", I, 120, 0),
                                       ("deadline.ms", R, 0, 25.0)]))
write("params", "valid_bool", params([("grasp.skip_border", BO, 1, 0), ("lane.use_color", BO, 0, 0)]))
write("params", "valid_text", params([("lane.canny_mode", T, 0, 0, "fixed"),
                                      ("lane.roi", T, 0, 0, "0,1;0.4,0.55;0.6,0.55;1,1")]))
write("params", "valid_save", params([], action=params_t.ACTION_SAVE))
write("params", "bad_action", params([("grasp.min_area", I, 920, 0)], action=9))
write("params", "text_newline", params([("lane.roi", T, 0, 0, "0,1;1,1\n[params]")]))
write("params", "text_comment", params([("lane.roi", T, 0, 0, "0,1;0.5,0.5;1,1 # x")]))
write("params", "repro_nparams_0x7fffffff", (head[:25] + struct.pack(">I", 0x7fffffff) + b"A" * 53)[:53])
unterminated = params([("grasp.min_area", I, 5, 0)])
write("params", "repro_name_without_nul", unterminated[:29] + struct.pack(">I", 14) + b"grasp.min_area"
      + unterminated[29 + 4 + 15:])
write("params", "repro_57k_malformed", head[:25] + struct.pack(">I", 1) + b"\xff" * (57000 - 29))
write("params", "repro_injection", params([("lane.canny_mode=fixed     ", I, 0, 0)]))
write("params", "repro_real_for_int", params([("grasp.min_area", R, 0, 5000.0)]))
write("params", "repro_kind_7", params([("grasp.min_area", 7, 5000, 0)]))
write("params", "repro_negative_count", head[:25] + struct.pack(">i", -3) + params([("x.y", I, 0, 0)])[29:])
write("params", "repro_deadline_1e-300", params([("deadline.ms", R, 0, 1e-300)]))
write("params", "repro_hough_threshold_100000", params([("lane.hough_threshold", I, 100000, 0)]))
write("params", "repro_min_area_1e8", params([("grasp.min_area", I, 100000000, 0)]))
write("params", "repro_tiny_roi_as_text", params([("lane.roi", I, 0, 0)]))
write("params", "fixed_key", params([("lane.max_segments", I, 10, 0)]))
write("params", "duplicate", params([("grasp.min_area", I, 10, 0), ("grasp.min_area", I, 20, 0)]))

# ---- params_values: bytes that steer the structured target ----
for i, seed in enumerate([b"\x00\x10\x00\x05" + bytes(24), b"\x02" + bytes([3, 0, 130, 1, 200]) * 6,
                          bytes(range(64)), b"\xff" * 40, b"\xf5" + bytes(range(200, 256)) * 3]):
    write("params_values", "seed_%d" % i, seed)
print("seeds written to", OUT)
