#!/usr/bin/python3
"""rtedged under systemd's notification protocol, for real: this test owns
the AF_UNIX datagram socket that NOTIFY_SOCKET names (as systemd does) and
starts the built rtedged with NOTIFY_SOCKET, WATCHDOG_USEC and WATCHDOG_PID.

  1. a recording: STATUS while opening, READY=1 with the first frame's size,
     periodic STATUS, WATCHDOG=1 every half period; SIGSTOP stops the pings
     for longer than the watchdog period (systemd would act), SIGCONT brings
     them back; SIGHUP gives RELOADING=1 then READY=1; SIGTERM STOPPING=1
     and exit 0.
  2. a camera that is not there (/dev/video99; then libcamera's camera 99),
     on an abstract socket address: STATUS says it is waited for with
     growing retries, no READY, the watchdog goes on, SIGTERM ends it
     cleanly; stderr as the journal (JOURNAL_STREAM): lines with their
     priority.
  3. WATCHDOG_PID naming another process: no pings.

  test_notify.py RTEDGED Y4M TMPDIR
"""
import os
import signal
import socket
import subprocess
import sys
import time

RTEDGED, Y4M, TMP = sys.argv[1], sys.argv[2], sys.argv[3]
WATCHDOG_USEC = 1000000  # WatchdogSec=1 s: pings every 0.5 s
PERIOD = WATCHDOG_USEC / 1e6


def fail(why):
    print("FAIL: " + why)
    sys.exit(1)


class Daemon:
    """rtedged with its notifications: (time, text) in self.got."""

    def __init__(self, name, args, abstract=False, watchdog_pid=None, journal=False):
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
        if abstract:
            addr = "@rtedge-notify-test-%d-%s" % (os.getpid(), name)
            self.sock.bind("\0" + addr[1:])
        else:
            addr = os.path.join(TMP, "notify-%d-%s.sock" % (os.getpid(), name))
            if os.path.exists(addr):
                os.unlink(addr)
            self.sock.bind(addr)
            self.path = addr
        self.sock.settimeout(0.05)
        env = dict(os.environ, NOTIFY_SOCKET=addr, WATCHDOG_USEC=str(WATCHDOG_USEC))
        self.err_path = os.path.join(TMP, "notify-%d-%s.err" % (os.getpid(), name))
        self.err = open(self.err_path, "w")
        if journal:  # stderr as if it were the journal's stream
            st = os.fstat(self.err.fileno())
            env["JOURNAL_STREAM"] = "%d:%d" % (st.st_dev, st.st_ino)
        # WATCHDOG_PID is rtedged's own pid: the shell's, which exec keeps.
        pid = watchdog_pid if watchdog_pid else "$$"
        cmd = 'WATCHDOG_PID=%s exec "$0" "$@"' % pid
        self.proc = subprocess.Popen(["/bin/sh", "-c", cmd, RTEDGED] + args, env=env,
                                     stdout=subprocess.DEVNULL, stderr=self.err)
        self.got = []

    def receive(self, seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            try:
                data = self.sock.recv(4096)
            except socket.timeout:
                continue
            self.got.append((time.monotonic(), data.decode()))

    def until(self, pred, seconds, what):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            if any(pred(t) for _, t in self.got):
                return
            self.receive(0.05)
        fail("%s: not within %g s; got %r; stderr %s" % (what, seconds, self.got, self.stderr()))

    def pings(self, since=0.0):
        return [t for t, m in self.got if m == "WATCHDOG=1" and t >= since]

    def statuses(self):
        return [line[7:] for _, m in self.got for line in m.split("\n")
                if line.startswith("STATUS=")]

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        try:
            code = self.proc.wait(5)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            fail("SIGTERM: rtedged did not exit")
        self.receive(0.1)
        self.sock.close()
        if hasattr(self, "path"):
            os.unlink(self.path)
        self.err.close()
        return code

    def stderr(self):
        with open(self.err_path) as f:
            return f.read()


def max_gap(times):
    return max(b - a for a, b in zip(times, times[1:]))


def recording():
    conf = os.path.join(TMP, "notify-%d.conf" % os.getpid())
    log = os.path.join(TMP, "notify-%d.lcm" % os.getpid())
    with open(conf, "w") as f:
        f.write("[source]\npath = %s\nloop = true\n[publish]\nurl = file://%s\n" % (Y4M, log))
    d = Daemon("rec", ["--config", conf])
    d.until(lambda m: m.startswith("READY=1"), 10, "READY=1")
    ready = next(m for _, m in d.got if m.startswith("READY=1"))
    first = d.got[0][1]
    if not first.startswith("STATUS=") or "waiting for the first frame" not in first:
        fail("the first notification is not the opening status: %r" % d.got)
    if "STATUS=streaming y4m:%s 480x270" % Y4M not in ready:
        fail("READY=1 does not say the first frame's size: %r" % ready)
    if "ready: y4m:%s streaming, first frame 480x270" % Y4M not in d.stderr():
        fail("no 'ready' line on stderr: %s" % d.stderr())
    print("ok: " + ready.replace("\n", " | "))
    t_ready = next(t for t, m in d.got if m.startswith("READY=1"))
    d.receive(2.4)
    pings = d.pings(t_ready)
    if len(pings) < 4 or max_gap(pings) >= PERIOD:
        fail("watchdog pings after READY: %d, largest gap %.3f s (watchdog %.1f s)"
             % (len(pings), max_gap(pings) if len(pings) > 1 else 0, PERIOD))
    mean = (pings[-1] - pings[0]) / (len(pings) - 1)
    if not PERIOD / 2 * 0.8 <= mean <= PERIOD / 2 * 1.5:
        fail("pings every %.3f s, not about %.3f s" % (mean, PERIOD / 2))
    print("ok: %d watchdog pings, every %.3f s on average, largest gap %.3f s"
          % (len(pings), mean, max_gap(pings)))
    periodic = [s for s in d.statuses() if " fps, p99 " in s]
    if not periodic:
        fail("no periodic STATUS: %r" % d.statuses())
    print("ok: STATUS=" + periodic[-1])

    # A stalled loop: no pings for longer than the watchdog period.
    os.kill(d.proc.pid, signal.SIGSTOP)
    t_stop = time.monotonic()
    d.receive(1.6)
    os.kill(d.proc.pid, signal.SIGCONT)
    d.receive(1.2)
    before = [t for t in d.pings() if t <= t_stop]
    after = [t for t in d.pings() if t > t_stop]
    if len(after) < 2:
        fail("pings after SIGCONT: %d" % len(after))
    gap = after[0] - before[-1]
    if gap <= PERIOD:
        fail("SIGSTOP: a gap of %.3f s, within the watchdog's %.1f s" % (gap, PERIOD))
    print("ok: SIGSTOP 1.6 s: watchdog gap %.3f s > WatchdogSec %.1f s (systemd would act); "
          "%d pings in the 1.2 s after SIGCONT" % (gap, PERIOD, len(after)))

    n = len(d.got)
    d.proc.send_signal(signal.SIGHUP)
    d.until(lambda m: m.startswith("READY=1\nSTATUS=configuration"), 5, "READY=1 after SIGHUP")
    after_hup = [m for _, m in d.got[n:] if m.startswith(("RELOADING=", "READY="))]
    if not after_hup[0].startswith("RELOADING=1\nMONOTONIC_USEC="):
        fail("SIGHUP: %r" % after_hup)
    print("ok: SIGHUP: %s" % " then ".join(m.replace("\n", " | ") for m in after_hup[:2]))

    code = d.stop()
    if code != 0:
        fail("SIGTERM: exit %d: %s" % (code, d.stderr()))
    if not any(m.startswith("STOPPING=1") for _, m in d.got):
        fail("no STOPPING=1: %r" % d.got[-5:])
    print("ok: SIGTERM: %s, exit 0" % next(m for _, m in d.got if m.startswith("STOPPING=1"))
          .replace("\n", " | "))
    os.unlink(conf)
    os.unlink(log)


def camera_missing(name="/dev/video99", options=()):
    log = os.path.join(TMP, "notify-%d-cam.lcm" % os.getpid())
    d = Daemon("cam", ["--source", name, "--lcm-url", "file://" + log] + list(options),
               abstract=True, journal=True)
    d.receive(2.3)  # tries after 0.5 and 1.5 s
    if d.proc.poll() is not None:
        fail("rtedged exited (%d) without the camera: %s" % (d.proc.returncode, d.stderr()))
    statuses = d.statuses()
    if not statuses or statuses[0] != "waiting for camera " + name:
        fail("first STATUS: %r" % statuses)
    tries = [s for s in statuses if s.startswith("waiting for camera: %s: " % name)]
    if len(tries) < 2 or [
            "retrying in 1000 ms" in tries[0], "retrying in 2000 ms" in tries[1]] != [True, True]:
        fail("retries: %r" % tries)
    if any(m.startswith("READY=1") for _, m in d.got):
        fail("READY=1 without a camera")
    pings = d.pings()
    if len(pings) < 4 or max_gap(pings) >= PERIOD:
        fail("waiting: %d pings, largest gap %.3f s" % (len(pings), max_gap(pings)))
    for s in statuses:
        print("ok: STATUS=" + s)
    print("ok: waiting, %d watchdog pings, largest gap %.3f s" % (len(pings), max_gap(pings)))
    code = d.stop()
    err = d.stderr()
    if code != 0 or "<4>rtedged: warning: waiting for camera: " + name not in err:
        fail("SIGTERM while waiting: exit %d: %s" % (code, err))
    for line in err.splitlines():
        if "waiting" in line:
            print("ok: stderr: " + line)
    os.unlink(log)


def watchdog_elsewhere():
    log = os.path.join(TMP, "notify-%d-pid.lcm" % os.getpid())
    d = Daemon("pid", ["--source", Y4M, "--loop", "--lcm-url", "file://" + log],
               watchdog_pid="1")
    d.until(lambda m: m.startswith("READY=1"), 10, "READY=1")
    d.receive(0.6)
    if d.pings():
        fail("WATCHDOG_PID=1: %d pings" % len(d.pings()))
    if d.stop() != 0:
        fail("WATCHDOG_PID=1 run: exit code")
    print("ok: WATCHDOG_PID of another process: READY=1, no pings")
    os.unlink(log)


def libcamera_built():
    """Whether rtedged opens libcamera cameras (not RTE_ERR_UNSUPPORTED)."""
    out = subprocess.run([RTEDGED, "--set", "source.kind=libcamera", "--source", "99",
                          "--set", "source.wait=false", "--lcm-url", "memq://"],
                         capture_output=True, text=True, timeout=30)
    return "built without libcamera" not in out.stderr


recording()
camera_missing()
# libcamera has no reconnection of its own: the daemon waits through a
# waiting source (src/sources/waiting.c), with the format set.
if libcamera_built():
    camera_missing("99", ["--set", "source.kind=libcamera", "--set", "source.format=nv12"])
else:
    print("note: rtedged built without libcamera: its missing camera not tried")
watchdog_elsewhere()
print("ok: notify protocol")
