"""Shared by the rtedge command-line test scripts: running the tool and
tallying checks (failed ones are printed as they happen)."""
import subprocess


class Checks:
    def __init__(self, rtedge):
        self.rtedge = rtedge
        self.count = 0
        self.failures = []

    def run(self, *args):
        return subprocess.run([self.rtedge, *args], capture_output=True, text=True)

    def check(self, cond, what):
        self.count += 1
        if not cond:
            self.failures.append(what)
            print("FAIL:", what)

    def finish(self, name):
        """Prints the tally; returns the exit code."""
        print(f"{name}: {self.count} checks, {len(self.failures)} failed")
        return 1 if self.failures else 0
