"""Starts a real `rrlab serve --port 0` on a temporary database for Python
tests (as tests/server/support/server_process.cpp does for the C++ ones) and
stops it with SIGTERM."""

import ctypes
import os
import re
import select
import shutil
import signal
import subprocess
import tempfile
import time

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _end_with_parent():
    """In the child: SIGTERM when the test process ends, however it ends."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


class Server:
    def __init__(self, binary, extra_args=()):
        self.dir = tempfile.mkdtemp(prefix="rrlab-py-")
        self.db = os.path.join(self.dir, "rrlab.db")
        self.log = open(os.path.join(self.dir, "serve.log"), "w+")
        self.process = subprocess.Popen(
            [binary, "serve", "--port", "0", "--db", self.db, "--scenarios", os.path.join(SOURCE_DIR, "scenarios"),
             "--web", os.path.join(SOURCE_DIR, "web"), *extra_args],
            stdout=subprocess.PIPE, stderr=self.log, text=True, preexec_fn=_end_with_parent)
        # "rrlab: serving http://127.0.0.1:PORT/ (database ...)", within 60 s
        ready, _, _ = select.select([self.process.stdout], [], [], 60)
        line = self.process.stdout.readline() if ready else "(nothing within 60 s)"
        match = re.search(r"serving (http://[^/ ]+)/", line)
        if not match:
            self.process.kill()
            self.log.seek(0)
            raise RuntimeError(f"rrlab serve did not start: {line!r} {self.log.read()}")
        self.url = match.group(1)

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.process.stdout.close()
        self.log.close()
        shutil.rmtree(self.dir, ignore_errors=True)
        return self.process.returncode

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


def wait_until(predicate, timeout=30.0, poll=0.05):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(poll)
    return False
