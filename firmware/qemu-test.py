#!/usr/bin/env python3
"""Boot test of the firmware's QEMU build: builds it (qemu-run.sh --build), boots it on
QEMU netduinoplus2 with USART2 on a TCP socket, and checks the link: the welcome line,
a `?` status report, a line answered `ok`, a rapid (`$MOVE`) run by the motion core on
the software time base until the status shows it arrived, and the welcome again after a
soft reset (0x18). Exits non-zero on the first failure. Used by .ci/run.
"""
import os
import socket
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
WELCOME = b"Grbl 1.1h ['$' for help]\r\n"
TIMEOUT = 20.0


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def connect(port, deadline):
    while time.monotonic() < deadline:
        try:
            return socket.create_connection(("127.0.0.1", port), timeout=1.0)
        except OSError:
            time.sleep(0.1)
    raise SystemExit("qemu-test: QEMU never opened the USART2 socket")


class Link:
    def __init__(self, sock):
        self.sock = sock
        self.buf = b""

    def send(self, data):
        self.sock.sendall(data)

    def expect(self, wanted, what):
        """Reads until `wanted` has arrived; returns everything up to and including it."""
        deadline = time.monotonic() + TIMEOUT
        while wanted not in self.buf:
            if time.monotonic() > deadline:
                raise SystemExit(f"qemu-test: no {what} (got {self.buf!r})")
            self.sock.settimeout(max(0.1, deadline - time.monotonic()))
            try:
                chunk = self.sock.recv(4096)
            except socket.timeout:
                continue
            if not chunk:
                raise SystemExit(f"qemu-test: link closed waiting for {what} (got {self.buf!r})")
            self.buf += chunk
        end = self.buf.index(wanted) + len(wanted)
        got, self.buf = self.buf[:end], self.buf[end:]
        print(f"qemu-test: {what}: {got!r}")
        return got


def main():
    elf = subprocess.run([os.path.join(HERE, "qemu-run.sh"), "--build"], check=True,
                         stdout=subprocess.PIPE, text=True).stdout.strip().splitlines()[-1]
    port = free_port()
    qemu = subprocess.Popen([
        "qemu-system-arm", "-M", "netduinoplus2", "-nographic", "-monitor", "none",
        "-chardev", f"socket,id=dnc,host=127.0.0.1,port={port},server=on,wait=on",
        "-serial", "null", "-serial", "chardev:dnc", "-kernel", elf,
    ])
    try:
        link = Link(connect(port, time.monotonic() + TIMEOUT))
        link.expect(WELCOME, "welcome")
        link.send(b"?")
        status = link.expect(b">\r\n", "status report")
        # Reference position 1 of the built-in machine: X 150 mm radius = 300 diameter, Z 250.
        if not status.startswith(b"<Idle|MPos:300.000,0.000,250.000|"):
            raise SystemExit(f"qemu-test: unexpected status {status!r}")
        link.send(b"G01 X10 Z-5 F0.2\r\n")
        link.expect(b"[ECHO:G01 X10 Z-5 F0.2]\r\nok\r\n", "line answered")
        # The motion path on the software time base: a rapid, then Idle at the target.
        link.send(b"$MOVE X310 Z240.5\n")
        link.expect(b"ok\r\n", "move queued")
        deadline = time.monotonic() + TIMEOUT
        while True:
            link.send(b"?")
            status = link.expect(b">\r\n", "status while moving")
            if status.startswith(b"<Idle|MPos:310.000,0.000,240.500|"):
                break
            if not status.startswith(b"<Run|"):
                raise SystemExit(f"qemu-test: not running towards the target ({status!r})")
            if time.monotonic() > deadline:
                raise SystemExit(f"qemu-test: the rapid never arrived ({status!r})")
            time.sleep(0.05)
        link.send(b"\x18")
        link.expect(WELCOME, "welcome after soft reset")
        print("qemu-test: passed")
    finally:
        qemu.kill()
        qemu.wait()


if __name__ == "__main__":
    sys.exit(main())
