"""The rtedge types with the `lcm` Python package (PyPI; Debian has none;
tools/test installs it into build/pylcm and sets RTE_PYTHON_LCM): the C
writer's log read through lcm.EventLog, and a message published and
received in-process over memq:// with lcm.LCM. Skipped (exit 77, with the
reason) when the package cannot be imported.

    test_lcm_package.py WRITE_SAMPLE_LOG PYTHON_TYPES_DIR TMPDIR
"""
import os
import subprocess
import sys

writer, types_dir, tmp = sys.argv[1:4]
sys.path.insert(0, types_dir)
if os.environ.get("RTE_PYTHON_LCM"):
    sys.path.insert(0, os.environ["RTE_PYTHON_LCM"])
try:
    import lcm
except ImportError as e:
    print("SKIP: the lcm Python package is not installed (%s); tools/test installs it" % e)
    sys.exit(77)
import rtedge  # noqa: E402  (generated)

types = {"LANES": rtedge.lane_detection_t, "GRASP": rtedge.grasp_detection_t,
         "STATUS": rtedge.status_t, "PARAMS": rtedge.params_t, "IMAGE": rtedge.image_t}
path = os.path.join(tmp, "lcm_package.%d.lcmlog" % os.getpid())
subprocess.run([writer, path], check=True)
got = {}
for n, event in enumerate(lcm.EventLog(path, "r")):
    assert event.eventnum == n, (event.eventnum, n)
    msg = types[event.channel].decode(event.data)
    assert msg.encode() == event.data, event.channel + ": re-encoding differs"
    got[event.channel] = msg
os.unlink(path)
assert sorted(got) == sorted(types), sorted(got)
assert got["LANES"].nsegments == 7 and got["LANES"].segments_truncated
assert (got["STATUS"].frames_received, got["STATUS"].frames_processed) == (1000, 990)

# In-process publish and subscribe: what a Python node next to rtedged does.
lc = lcm.LCM("memq://")
received = []
lc.subscribe("RTEDGE_LANES", lambda channel, data: received.append(types["LANES"].decode(data)))
lc.publish("RTEDGE_LANES", got["LANES"].encode())
assert lc.handle_timeout(1000) > 0, "nothing received over memq://"
assert len(received) == 1 and received[0].encode() == got["LANES"].encode()
print("lcm package %s: 5 messages read with lcm.EventLog, 1 round trip over memq://"
      % getattr(lcm, "__version__", "?"))
