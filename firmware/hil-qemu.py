#!/usr/bin/env python3
"""Runs every bring-up test binary (`src/bin/hil_*.rs`, docs/BRINGUP.md) in QEMU's
netduinoplus2 (STM32F405): builds them with the `qemu` feature, boots each with
semihosting (its report on the console, its result as QEMU's exit status) and
checks that it reached its end and passed — the hardware checks report SKIP there
(QEMU models neither the timers, nor GPIO, nor flash programming, nor the watchdog,
nor USB), so this proves each binary boots, sets up its peripherals and passes its
self-check. `hil_link_echo` gets USART2 on a socket and `hil/echo.py` sends it
20,000 bytes, which must all come back. Used by .ci/run.
"""
import glob
import os
import socket
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TARGET = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(HERE, "..", "target")), "qemu")
ICOUNT = ["-icount", "shift=3,sleep=on"]
TIMEOUT = 120


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def qemu(elf, serial):
    return ["qemu-system-arm", "-M", "netduinoplus2", "-nographic", "-monitor", "none",
            "-semihosting-config", "enable=on,target=native", *serial, *ICOUNT, "-kernel", elf]


def run(name, elf):
    """Boots one test; (passed, its report)."""
    if name != "hil_link_echo":
        p = subprocess.run(qemu(elf, ["-serial", "null", "-serial", "null"]), stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT)
        return p.returncode == 0 and f"{name}: done: PASS" in p.stdout, p.stdout
    port = free_port()
    serial = ["-chardev", f"socket,id=dnc,host=127.0.0.1,port={port},server=on,wait=on",
              "-serial", "null", "-serial", "chardev:dnc"]
    q = subprocess.Popen(qemu(elf, serial), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        time.sleep(0.5)
        echo = subprocess.run([sys.executable, os.path.join(HERE, "hil", "echo.py"), f"tcp:127.0.0.1:{port}",
                               "--bytes", "20000", "--timeout", str(TIMEOUT)],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT)
        out, _ = q.communicate(timeout=TIMEOUT)
    finally:
        q.kill()
    return echo.returncode == 0 and q.returncode == 0 and f"{name}: done: PASS" in out, out + echo.stdout


def main():
    subprocess.run(["cargo", "build", "-q", "--release", "--no-default-features", "--features", "f405,qemu,siemens,mill",
                    "--target-dir", TARGET, "--bins"], cwd=HERE, check=True)
    names = sorted(os.path.basename(p)[:-3] for p in glob.glob(os.path.join(HERE, "src", "bin", "hil_*.rs")))
    failed = []
    for name in names:
        t0 = time.monotonic()
        ok, report = run(name, os.path.join(TARGET, "thumbv7em-none-eabihf", "release", name))
        print(report.rstrip())
        print(f"hil-qemu: {name}: {'passed' if ok else 'FAILED'} ({time.monotonic() - t0:.1f} s)")
        if not ok:
            failed.append(name)
    print(f"hil-qemu: {len(names) - len(failed)} of {len(names)} bring-up tests passed in QEMU"
          + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
