"""Shared by the rtedge command-line test scripts: running the tool and
tallying checks (failed ones are printed as they happen).

In a cross build meson test sets MESON_EXE_WRAPPER (the cross file's
exe_wrapper, e.g. "qemu-aarch64 -L /usr/aarch64-linux-gnu"): it is put
before the tool on every run."""
import os
import shlex
import subprocess


class Checks:
    def __init__(self, rtedge):
        self.rtedge = rtedge
        self.wrapper = shlex.split(os.environ.get("MESON_EXE_WRAPPER", ""))
        self.count = 0
        self.failures = []

    def run(self, *args):
        return subprocess.run([*self.wrapper, self.rtedge, *args], capture_output=True, text=True)

    def check(self, cond, what):
        self.count += 1
        if not cond:
            self.failures.append(what)
            print("FAIL:", what)

    def finish(self, name):
        """Prints the tally; returns the exit code."""
        print(f"{name}: {self.count} checks, {len(self.failures)} failed")
        return 1 if self.failures else 0
