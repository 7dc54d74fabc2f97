#!/usr/bin/env python3
"""Host side of the bring-up test `hil_link_echo` (docs/BRINGUP.md): sends random
printable text to the board as fast as the link takes it, reads the echo at the
same time, compares, prints the throughput, and ends the run with EOT (0x04).

    python3 firmware/hil/echo.py /dev/ttyACM0            # the board's USB port
    python3 firmware/hil/echo.py /dev/ttyUSB0 --baud 115200  # USART2 via a USB-serial cable
    python3 firmware/hil/echo.py tcp:127.0.0.1:4000      # QEMU's USART2 (hil-qemu.py)

Exit status 0 when every byte came back in order. Linux/macOS (termios), no
third-party module.
"""
import argparse
import os
import random
import select
import socket
import sys
import termios
import time
import tty

EOT = b"\x04"


def open_link(spec, baud):
    """A (read, write, close) triple for a serial device or a tcp:HOST:PORT socket."""
    if spec.startswith("tcp:"):
        host, port = spec[4:].rsplit(":", 1)
        s = socket.create_connection((host, int(port)), timeout=10)
        s.setblocking(False)
        return s.fileno(), s.send, s.close
    fd = os.open(spec, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)
    speed = getattr(termios, f"B{baud}")
    attrs[4] = attrs[5] = speed
    attrs[2] |= termios.CLOCAL | termios.CREAD
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    termios.tcflush(fd, termios.TCIOFLUSH)
    return fd, lambda b: os.write(fd, b), lambda: os.close(fd)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("link")
    ap.add_argument("--baud", type=int, default=115200)
    ap.add_argument("--bytes", type=int, default=200_000)
    ap.add_argument("--timeout", type=float, default=60.0)
    ap.add_argument("--settle", type=float, default=1.0, help="seconds to wait after opening (the board starts)")
    args = ap.parse_args()
    rng = random.Random(18)
    data = bytes(rng.choice(b"ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789 \n") for _ in range(args.bytes))
    fd, write, close = open_link(args.link, args.baud)
    time.sleep(args.settle)
    sent, got = 0, bytearray()
    t0 = time.monotonic()
    deadline = t0 + args.timeout
    try:
        while len(got) < len(data):
            if time.monotonic() > deadline:
                break
            want_write = sent < len(data)
            r, w, _ = select.select([fd], [fd] if want_write else [], [], 0.5)
            if w:
                try:
                    sent += write(data[sent:sent + 4096])
                except (BlockingIOError, InterruptedError):
                    pass
            if r:
                try:
                    chunk = os.read(fd, 65536)
                except (BlockingIOError, InterruptedError):
                    chunk = b""
                if not chunk:
                    break
                got += chunk
        seconds = time.monotonic() - t0
        write(EOT)
    finally:
        time.sleep(0.2)
        close()
    ok = bytes(got) == data
    first_bad = next((i for i, (a, b) in enumerate(zip(got, data)) if a != b), None)
    print(f"echo: sent {sent} bytes, got {len(got)} back in {seconds:.2f} s "
          f"({len(got) / max(seconds, 1e-9):.0f} bytes/s each way): {'PASS' if ok else 'FAIL'}"
          + ("" if ok or first_bad is None else f" (first difference at byte {first_bad})"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
