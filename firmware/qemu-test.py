#!/usr/bin/env python3
"""Boot test of the firmware's QEMU build: builds it (qemu-run.sh --build), boots it on
QEMU netduinoplus2 with USART2 on a TCP socket, and talks to the board's controller
(docs/PROTOCOL.md) as a grbl sender does: the welcome line, a `?` status report, a
short lathe program with G71/G70 roughing and finishing and a G76 thread streamed
with grbl character counting (128-byte receive buffer; every line must get `ok`),
run by the motion core on the software time base (with a simulated spindle encoder)
until the status shows Idle at the position `lathe sim` gives for the program's end;
then 8,000 lines `#1=1` and M30 streamed the same way, every one `ok` (a byte lost
on the link makes one of them unreadable, an alarm; a lost LF leaves an `ok` missing:
embassy's UART handler lost about one byte in 8 KB here, see `board::TcGuard`); then
a program with an illegal G code: the alarm message names its line, ALARM:20,
`$X` unlocks; then a sender that ignores character counting: 100 slow jogs in one
burst with a `?` behind the 20th, 60th and 100th — every `?` answered, the last
while the jogs ahead of it still fill the planner — and a soft reset (0x18) behind
them acted on at once (the welcome again). Then the mill profile: `$311=1` switches
the running board to a machining centre (`$I` says mill), a G17 G01 X Y Z block
runs on the third step channel (now Y) and the status reports show Y moving and
ending where the block says. Then the same firmware once more on a
CPU far too slow for its 1 ms control loop (`-icount shift=10`: 1,000 instructions
per millisecond), which is behind its ticks all the time: the link must still
answer (issue 18: the control task then kept the executor to itself, and received
bytes and replies waited until the UART's ring overflowed). Exits non-zero on the
first failure. Used by .ci/run.

Time. QEMU runs with `-icount` (QEMU_ICOUNT, default `shift=3,sleep=on`): the
guest's clock advances 8 ns per instruction while it works (a 125 MIPS core; the
board's 168 MHz M4 runs the motion interrupts that the QEMU build does in its
control task) and with the host's clock while it sleeps in WFI. So the firmware
never finds its millisecond ticks gone because the host was busy elsewhere: what
it does per millisecond is the same on a fast host, a loaded one, or under CI.
How long that takes on the host is not: every wait here fails on a lack of
progress (no reply, or the same status report, for TIMEOUT seconds), never on a
total time. `QEMU_ICOUNT=off` runs QEMU on the host's clock.
"""
import os
import socket
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
WELCOME = b"Grbl 1.1h ['$' for help]\r\n"
# Seconds without progress (no reply, or the same status report) that fail a stage.
TIMEOUT = 20.0
# The receive buffer a character-counting sender may fill (docs/PROTOCOL.md).
RX_BUFFER = 128

# G71 roughing + G70 finishing of a short shaft, a G76 M24x1.5 thread, back out.
# Everything up to the shape's last block (N20) fits into the first 128 bytes, so
# G71 finds its shape without waiting for text: the controller gives a look-ahead
# up after 200 ms of link silence, which a loaded CI machine can stall QEMU for.
# The program's text is shared with the controller's host test of the same stream
# (controller/tests/stream_chunks.rs).
with open(os.path.join(HERE, "qemu-program.nc"), encoding="ascii") as f:
    PROGRAM = f.read()
# Where `cargo run -p lathe -- sim firmware/qemu-program.nc --format jsonl | tail` ends: the last rapid
# to X50 Z20 (machine coordinates, diameter; no work offset), 18.6 s simulated.
PROGRAM_END = b"MPos:50.000,0.000,20.000|"
# Lines of which every byte matters: without any one of them (`#1=`, `#11`, `#=1`,
# `1=1`, or two lines run together) the line is refused with an alarm.
STRESS_LINE = "#1=1\n"
STRESS_LINES = 8000
# QEMU's clock (see the module doc).
ICOUNT_MODE = os.environ.get("QEMU_ICOUNT", "shift=3,sleep=on")
ICOUNT = [] if ICOUNT_MODE == "off" else ["-icount", ICOUNT_MODE]
# A jog of 6 s (1 mm on the diameter at F5), 13 bytes.
SLOW_JOG = b"$J=G91 X1 F5\n"
# The second line has a G code the lathe system does not have (alarm 0010).
ALARM_PROGRAM = b"G00 X60. Z30.\nG123 X10.\nG00 X70.\n"


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


def read_line(link, deadline, what):
    """One line from the board (CR LF stripped)."""
    while b"\r\n" not in link.buf:
        if time.monotonic() > deadline:
            raise SystemExit(f"qemu-test: no {what} (got {link.buf!r})")
        link.sock.settimeout(max(0.1, deadline - time.monotonic()))
        try:
            chunk = link.sock.recv(4096)
        except socket.timeout:
            continue
        if not chunk:
            raise SystemExit(f"qemu-test: link closed waiting for {what}")
        link.buf += chunk
    line, link.buf = link.buf.split(b"\r\n", 1)
    return line


def stream(link, text):
    """Streams `text` with grbl character counting: a line is sent while the bytes
    of the lines not yet answered fit into the board's receive buffer; every answer
    must be `ok`, each within TIMEOUT of the one before. Returns the other lines the
    board sent meanwhile."""
    pending, inflight, other = list(text.splitlines(keepends=True)), [], []
    while pending or inflight:
        while pending and sum(map(len, inflight)) + len(pending[0]) <= RX_BUFFER:
            line = pending.pop(0).encode()
            link.send(line)
            inflight.append(line)
        reply = read_line(link, time.monotonic() + TIMEOUT, "ok while streaming")
        if reply == b"ok":
            inflight.pop(0)
        elif reply.startswith((b"error", b"ALARM")):
            raise SystemExit(f"qemu-test: {inflight[0]!r} answered {reply!r} (before: {other!r})")
        else:
            other.append(reply)
    print(f"qemu-test: streamed {len(text.splitlines())} lines, every one ok")
    return other


def wait_status(link, wanted, what):
    """Polls `?` until the status report starts with `wanted`; the last report.
    Fails on an alarm or hold, or when the report stays the same (the machine made
    no progress) for TIMEOUT seconds."""
    said, last, since = [], None, time.monotonic()
    while True:
        link.send(b"?")
        while True:
            line = read_line(link, time.monotonic() + TIMEOUT, what)
            if line.startswith(b"<"):
                break
            said.append(line)
        if line.startswith(wanted):
            print(f"qemu-test: {what}: {line!r}")
            return line
        if line != last:
            last, since = line, time.monotonic()
        if line.startswith((b"<Alarm", b"<Hold")) or time.monotonic() - since > TIMEOUT:
            raise SystemExit(f"qemu-test: {what}: last status {line!r} after {said!r}")
        time.sleep(0.25)


def realtime_behind_a_burst(link):
    """A sender that ignores character counting: 100 slow jogs in one burst (64
    fill the planner, 9 the receive buffer, the rest wait in the link task; each
    jog takes 6 s), with a `?` behind the 20th, the 60th and the 100th. Every `?` is
    answered, once, while jogging; the last while some of the jogs' lines ahead of it
    still wait unanswered (taken in order,
    it would wait about 3.5 minutes for 36 jogs). Then a 0x18 behind it all resets
    at once. Nothing here depends on how fast QEMU runs."""
    polls = (20, 60, 100)
    burst = b"".join(SLOW_JOG * (b - a) + b"?" for a, b in zip((0,) + polls, polls))
    link.send(burst)
    reports, oks = [], 0
    while len(reports) < len(polls):
        line = read_line(link, time.monotonic() + TIMEOUT, f"status report {len(reports) + 1} of {len(polls)} behind a burst of jogs")
        if line == b"ok":
            oks += 1
        elif line.startswith(b"<"):
            reports.append((oks, line))
        else:
            raise SystemExit(f"qemu-test: {line!r} in a burst of jogs")
    for (before, report), sent in zip(reports, polls):
        print(f"qemu-test: `?` behind {sent} jogs answered after {before} ok: {report!r}")
        if not report.startswith(b"<Jog|"):
            raise SystemExit(f"qemu-test: not jogging behind a burst of jogs ({report!r})")
    # The last `?` is answered before the jogs ahead of it are all taken (fewer `ok`
    # than jogs): it did not wait in line. How full the planner is at that moment
    # depends on when the host's bytes reach the guest (a loaded host delivers the
    # burst in pieces): not asserted.
    before, last = reports[-1]
    if before >= polls[-1]:
        raise SystemExit(f"qemu-test: the last `?` waited for the jogs ahead of it ({before} ok, {last!r})")
    link.send(b"\x18")
    got = link.expect(WELCOME, "welcome after soft reset behind a burst of jogs")
    if b"<" in got:
        raise SystemExit(f"qemu-test: a `?` answered twice ({got!r})")


def boot(elf, icount, monitor=None):
    """QEMU running `elf` with USART2 on a local TCP socket; the link once the
    guest runs (it starts when the socket is connected)."""
    port = free_port()
    args = [
        "qemu-system-arm", "-M", "netduinoplus2", "-nographic",
        "-chardev", f"socket,id=dnc,host=127.0.0.1,port={port},server=on,wait=on",
        "-serial", "null", "-serial", "chardev:dnc", "-kernel", elf,
        "-monitor", f"unix:{monitor},server=on,wait=off" if monitor else "none",
    ] + icount
    qemu = subprocess.Popen(args)
    try:
        return qemu, Link(connect(port, time.monotonic() + TIMEOUT))
    except BaseException:
        qemu.kill()
        qemu.wait()
        raise


def overrun(elf):
    """The firmware on a 1 MIPS core (`-icount shift=10`, 1 µs per instruction):
    no turn of its 1 ms control loop fits into its millisecond, so the control
    task is always behind its ticker. The link must still answer: the welcome, a
    status report, lines streamed, a `?` behind a burst of jogs, a soft reset."""
    t0 = time.monotonic()
    qemu, link = boot(elf, ["-icount", "shift=10,sleep=on"])
    try:
        link.expect(WELCOME, "welcome from an overrun control loop")
        link.send(b"?")
        link.expect(b">\r\n", "status report from an overrun control loop")
        stream(link, "#1=1\n#2=#1+1\nM30\n")
        wait_status(link, b"<Idle|", "idle from an overrun control loop")
        link.send(SLOW_JOG * 20 + b"?")
        report = link.expect(b">\r\n", "status report behind jogs from an overrun control loop")
        if b"<Jog|" not in report:
            raise SystemExit(f"qemu-test: not jogging ({report!r})")
        link.send(b"\x18")
        link.expect(WELCOME, "welcome after soft reset from an overrun control loop")
    finally:
        qemu.kill()
        qemu.wait()
    print(f"qemu-test: the link answers with the control loop behind all the time ({time.monotonic() - t0:.1f} s)")


# The painted stack's high-water mark over this test may not exceed 40 KB: the
# STM32F446RE (no CCM) has a 44.6 KB stack region (firmware/memory-f446/memory.x) and
# must run every program the F405 runs, with 4 KB to spare. Static bound of the same:
# firmware/stack-bound.py (docs/STACK.md).
STACK_MARK_LIMIT = 40 * 1024


def stack_region(elf):
    """The stack (memory.x): from the end of the statics (`_stack_end`) to the top of
    the SRAM (`_stack_start`), painted 0xCCCCCCCC at reset."""
    syms = {}
    nm = subprocess.run(["arm-none-eabi-nm", elf], check=True, stdout=subprocess.PIPE, text=True).stdout
    for line in nm.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[2] in ("_stack_start", "_stack_end"):
            syms[parts[2]] = int(parts[0], 16)
    return syms["_stack_end"], syms["_stack_start"] - syms["_stack_end"]


def stack_check(monitor, elf):
    """Reads the stack through QEMU's monitor: its high-water mark."""
    STACK_BASE, STACK_SIZE = stack_region(elf)
    STACK_SIZE -= STACK_SIZE % 16
    with socket.socket(socket.AF_UNIX) as m:
        m.connect(monitor)
        m.sendall(f"xp /{STACK_SIZE // 4}wx {STACK_BASE:#x}\n".encode())
        out, deadline = b"", time.monotonic() + TIMEOUT
        last = f"{STACK_BASE + STACK_SIZE - 16:08x}:".encode()
        while last not in out or not out.rstrip().endswith(b"(qemu)"):
            if time.monotonic() > deadline:
                raise SystemExit("qemu-test: no memory dump from the QEMU monitor")
            m.settimeout(1.0)
            try:
                out += m.recv(65536)
            except socket.timeout:
                pass
    words = []
    for line in out.decode(errors="replace").splitlines():
        if ":" in line and line.strip()[:8].isalnum():
            addr, _, rest = line.partition(":")
            words += [(int(addr.strip(), 16) + 4 * i, int(w, 16)) for i, w in enumerate(rest.split())]
    used = [a for a, w in words if w != 0xCCCCCCCC]
    if not words or not used:
        raise SystemExit("qemu-test: could not read the stack")
    depth = STACK_BASE + STACK_SIZE - min(used)
    print(f"qemu-test: stack high-water mark {depth} bytes of {STACK_SIZE} (limit {STACK_MARK_LIMIT})")
    if depth > STACK_MARK_LIMIT:
        raise SystemExit(f"qemu-test: the stack's high-water mark {depth} is over {STACK_MARK_LIMIT} bytes")


# The mill stage: `$311=1`, then a G17 G01 block moving X, Y and Z at once (the
# lathe's X -5–160 and Z -600–300 mm travel, the mill's Y -400–0) and M30.
MILL_PROGRAM = "G17 G90 G94 G21\nG01 X30. Y-20. Z10. F600\nM30\n"
MILL_END = b"<Idle|MPos:30.000,-20.000,10.000|"


def mill(link):
    """The board switched to the mill profile runs a 3-axis block: `$I` names the
    kind, status reports show Y between its ends while the block runs and the end
    position exactly."""
    link.send(b"$311=1\n")
    said = link.expect(b"ok\r\n", "$311=1 accepted")
    if b"[MSG:Machine kind: mill]" not in said:
        raise SystemExit(f"qemu-test: $311=1 answered {said!r}")
    link.send(b"$I\n")
    info = link.expect(b"ok\r\n", "$I")
    if b"[VER:1.1h.mill:]" not in info:
        raise SystemExit(f"qemu-test: $I on a mill answered {info!r}")
    stream(link, MILL_PROGRAM)
    ys, last, since = set(), None, time.monotonic()
    while True:
        link.send(b"?")
        line = read_line(link, time.monotonic() + TIMEOUT, "mill status")
        if not line.startswith(b"<"):
            continue
        y = line.split(b"MPos:", 1)[1].split(b"|", 1)[0].split(b",")[1]
        ys.add(float(y))
        if line.startswith(MILL_END):
            break
        if line.startswith((b"<Alarm", b"<Hold")) or time.monotonic() - since > TIMEOUT:
            raise SystemExit(f"qemu-test: mill block: last status {line!r}")
        if line != last:
            last, since = line, time.monotonic()
        time.sleep(0.05)
    moving = sorted(y for y in ys if -20.0 < y < 0.0)
    if not moving:
        raise SystemExit(f"qemu-test: no status report with Y between 0 and -20 (Y seen: {sorted(ys)})")
    print(f"qemu-test: mill profile: G01 X Y Z ran to {MILL_END.decode()}; Y seen moving at {moving[:4]}")


def main():
    elf = subprocess.run([os.path.join(HERE, "qemu-run.sh"), "--build"], check=True,
                         stdout=subprocess.PIPE, text=True).stdout.strip().splitlines()[-1]
    monitor = os.path.join(tempfile.mkdtemp(prefix="qemu-test-"), "monitor")
    print(f"qemu-test: QEMU clock {' '.join(ICOUNT) or 'the host’s'}")
    qemu, link = boot(elf, ICOUNT, monitor)
    try:
        link.expect(WELCOME, "welcome")
        link.send(b"?")
        status = link.expect(b">\r\n", "status report")
        # Reference position 1 of the built-in machine: X 150 mm radius = 300 diameter, Z 250.
        if not status.startswith(b"<Idle|MPos:300.000,0.000,250.000|"):
            raise SystemExit(f"qemu-test: unexpected status {status!r}")
        # A program with G71/G70 and G76, streamed, run to its end.
        t0 = time.monotonic()
        assert len(PROGRAM[:PROGRAM.index("N20")].encode()) + len("N20 X40.\n") <= RX_BUFFER
        stream(link, PROGRAM)
        wait_status(link, b"<Idle|" + PROGRAM_END, "program ran to its end")
        print(f"qemu-test: program streamed and run in {time.monotonic() - t0:.1f} s")
        # Many short lines over the link: not one byte may be lost.
        t0 = time.monotonic()
        stream(link, STRESS_LINE * STRESS_LINES + "M30\n")
        wait_status(link, b"<Idle|" + PROGRAM_END, "idle after the line stress")
        print(f"qemu-test: {STRESS_LINES} lines streamed in {time.monotonic() - t0:.1f} s")
        # An alarm names the line; lines are refused until $X.
        link.send(ALARM_PROGRAM)
        alarm = link.expect(b"ALARM:20\r\n", "alarm")
        if b"[MSG:ALARM 0010 line 2: G123 " not in alarm:
            raise SystemExit(f"qemu-test: the alarm does not name line 2 ({alarm!r})")
        wait_status(link, b"<Alarm|", "alarm status")
        link.send(b"$X\n")
        link.expect(b"ok\r\n", "unlocked")
        wait_status(link, b"<Idle|", "idle after $X")
        realtime_behind_a_burst(link)
        mill(link)
        stack_check(monitor, elf)
    finally:
        qemu.kill()
        qemu.wait()
    overrun(elf)
    print("qemu-test: passed")


if __name__ == "__main__":
    sys.exit(main())
