"""Reads an rtedge LCM log with lcm-gen's Python types and a small pure-Python
log reader (Debian has no python3-lcm; the types only need `struct`).
Each message decodes, has the values the C side put in, and re-encodes to
the same bytes.

    test_python.py WRITE_SAMPLE_LOG PYTHON_TYPES_DIR TMPDIR
"""
import os
import struct
import subprocess
import sys

writer, types_dir, tmp = sys.argv[1:4]
sys.path.insert(0, types_dir)
import rtedge  # noqa: E402  (generated)

SYNC = 0xEDA1DA01


def read_log(path):
    """Yields (eventnum, utime, channel, data) as lcm.EventLog would."""
    with open(path, "rb") as f:
        while True:
            header = f.read(28)
            if not header:
                return
            sync, eventnum, utime, clen, dlen = struct.unpack(">IqqII", header)
            assert sync == SYNC, "bad sync word"
            channel = f.read(clen).decode()
            data = f.read(dlen)
            assert len(data) == dlen, "event cut short"
            yield eventnum, utime, channel, data


path = os.path.join(tmp, "python.%d.lcmlog" % os.getpid())
subprocess.run([writer, path], check=True)
types = {"LANES": rtedge.lane_detection_t, "GRASP": rtedge.grasp_detection_t,
         "STATUS": rtedge.status_t, "PARAMS": rtedge.params_t, "IMAGE": rtedge.image_t}
got = {}
for n, (eventnum, utime, channel, data) in enumerate(read_log(path)):
    assert eventnum == n
    msg = types[channel].decode(data)
    assert msg.encode() == data, channel + ": re-encoding differs"
    got[channel] = msg
os.unlink(path)
assert sorted(got) == sorted(types), sorted(got)

lane = got["LANES"]
assert lane.header.source_id == "v4l2:/dev/video0"
assert (lane.header.width, lane.header.height) == (1280, 720)
assert lane.header.roi_npoints == 4 and len(lane.header.roi) == 4
assert lane.nsegments == 7 and lane.segments_truncated
assert lane.right.predicted and not lane.left.predicted
assert lane.heading_rad == -0.5 and lane.centre_offset_frac == 0.125
assert rtedge.lane_t.MAX_POINTS == 32 and len(lane.left.points_x) == 32
assert lane.left.npoints == 3 and list(lane.left.points_y[:4]) == [700.0, 690.0, 680.0, 0.0]
assert abs(lane.left.curvature + 0.001) < 1e-9
grasp = got["GRASP"]
assert grasp.nobjects == 3
assert grasp.objects[2].shape == rtedge.grasp_object_t.SHAPE_HEXAGON
assert (grasp.objects[1].bbox_width, grasp.objects[1].bbox_height) == (11, 21)
assert [o.score for o in grasp.objects] == [0.0, 0.25, 0.5]
assert len(grasp.objects[0].jaw_x) == 2 and len(grasp.objects[0].jaw_y) == 2
status = got["STATUS"]
assert status.source_state == rtedge.status_t.SOURCE_ENDED
assert (status.frames_received, status.frames_processed) == (1000, 990)
assert abs(status.fps - 29.97) < 1e-3
assert status.config_hash == 0x8badf00ddeadbeef - (1 << 64)
assert status.stage_names == ["lane.canny", "debug"] and list(status.stage_max_us) == [2500, 1900]
params = got["PARAMS"]
assert [p.name for p in params.params] == ["lane.canny_low", "deadline.ms", "lane.canny_mode"]
assert params.params[0].int_value == 50 and params.params[1].real_value == 0.25
assert params.params[2].kind == rtedge.param_t.KIND_TEXT and params.params[2].text_value == "fixed"
assert params.action == rtedge.params_t.ACTION_SET
image = got["IMAGE"]
assert image.pixelformat == rtedge.image_t.PIXEL_FORMAT_GRAY == 1497715271
assert (image.width, image.height, image.size) == (33, 5, 165) and len(image.data) == 165
assert image.metadata[0].key == "exposure" and list(image.metadata[0].value) == [1, 2, 3]
print("python: 5 messages decoded and re-encoded")
