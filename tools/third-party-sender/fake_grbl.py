#!/usr/bin/env python3
"""A tiny fake grbl 1.1 board on a serial device (one end of a socat pty pair).

It stands in for `lathe board --pty` while testing third-party senders: it answers
the grbl 1.1 protocol just well enough for a sender to connect and stream, and it
records what the sender did so a test can check it:

- every program line received, in order (`program_lines` in the report);
- every `$` command line and every real-time byte (`?`, `!`, `~`, 0x18, >= 0x80);
- the largest number of bytes the sender had in flight unanswered (`max_unanswered`):
  grbl's receive buffer is 128 bytes, so a character-counting sender must never have
  more than 128 bytes of lines sent but not yet answered `ok`/`error`.

Lines are answered in order, each after `--line-ms` milliseconds (a slow board makes
the sender actually fill the buffer). Status is `Run` while program lines wait for
their answer, `Idle` otherwise, `Hold:0` after `!` until `~`.

The report (JSON) is written to `--report` on SIGTERM/SIGINT or when the device
closes. Every event is also appended to `--log` as it happens.
"""

import argparse
import json
import os
import select
import signal
import sys
import termios
import time
import tty

WELCOME = b"\r\nGrbl 1.1h ['$' for help]\r\n"
RX_BUFFER = 128
SETTINGS = [
    "$0=10", "$1=25", "$2=0", "$3=0", "$4=0", "$5=0", "$6=0", "$10=1", "$11=0.010",
    "$12=0.002", "$13=0", "$20=0", "$21=0", "$22=0", "$23=0", "$24=25.000",
    "$25=500.000", "$26=250", "$27=1.000", "$30=1000", "$31=0", "$32=0",
    "$100=250.000", "$101=250.000", "$102=250.000", "$110=500.000", "$111=500.000",
    "$112=500.000", "$120=10.000", "$121=10.000", "$122=10.000", "$130=200.000",
    "$131=200.000", "$132=200.000",
]
OFFSETS = [
    "[G54:0.000,0.000,0.000]", "[G55:0.000,0.000,0.000]", "[G56:0.000,0.000,0.000]",
    "[G57:0.000,0.000,0.000]", "[G58:0.000,0.000,0.000]", "[G59:0.000,0.000,0.000]",
    "[G28:0.000,0.000,0.000]", "[G30:0.000,0.000,0.000]", "[G92:0.000,0.000,0.000]",
    "[TLO:0.000]", "[PRB:0.000,0.000,0.000:0]",
]
PARSER_STATE = "[GC:G0 G54 G17 G21 G90 G94 M5 M9 T0 F0 S0]"
# --board-format: the answers docs/PROTOCOL.md gives for our lathe board.
BOARD_PARSER_STATE = "[GC:G1 G54 G18 G21 G97 G99 M5 M9 T0101 F0.2 S500]"
BOARD_VERSION = ["[VER:1.1h.lathe:]", "[OPT:,64,128]", "[MSG:lathe controller (fake_grbl.py)]"]


class FakeGrbl:
    """The board's state: receive buffer, pending lines, the record of the session."""

    def __init__(self, fd, log, line_s, error_on=None, alarm_on=None, board=False, strict=False,
                 parser_state=None):
        self.fd = fd
        self.parser_state = parser_state or (BOARD_PARSER_STATE if board else PARSER_STATE)
        self.board = board
        self.strict = strict
        self.error_on = error_on
        self.alarm_on = alarm_on
        self.alarm = False
        self.log = log
        self.line_s = line_s
        self.partial = bytearray()  # bytes of the line being received
        self.pending = []  # (text, nbytes) complete lines waiting for their answer
        self.next_answer_at = 0.0
        self.hold = False
        self.program_lines = []
        self.commands = []
        self.realtime = {}
        self.max_unanswered = 0
        self.overflows = 0
        self.resets = 0

    def unanswered(self):
        """Bytes in the receive buffer: lines not yet answered plus a partial line."""
        return sum(n for _, n in self.pending) + len(self.partial)

    def note(self, kind, text):
        """Append one event to the log file."""
        self.log.write(f"{time.monotonic():.4f} {kind} {text}\n")
        self.log.flush()

    def send(self, *lines):
        """Write response lines, each ended with CR LF as grbl does."""
        data = b"".join(line.encode() + b"\r\n" for line in lines)
        os.write(self.fd, data)
        for line in lines:
            self.note("TX", line)

    def status(self):
        """The `?` report: Run while program lines are pending."""
        busy = any(not text.startswith("$") for text, _ in self.pending)
        state = "Hold:0" if self.hold else ("Run" if busy else "Idle")
        state = "Alarm" if self.alarm else state
        free = RX_BUFFER - self.unanswered()
        if self.board:
            ln = len(self.program_lines)
            return (f"<{state}|MPos:40.000,0.000,-12.500|FS:0.2,500|Bf:15,{free}|Ln:{ln}"
                    "|WCO:0.000,0.000,0.000|Ov:100,100,100>")
        return f"<{state}|MPos:0.000,0.000,0.000|Bf:15,{free}|FS:0,0>"

    def reset(self):
        """Soft reset (0x18): drop everything buffered and greet again."""
        self.partial.clear()
        self.pending.clear()
        self.hold = False
        self.alarm = False
        self.resets += 1
        os.write(self.fd, WELCOME)
        self.note("TX", "Grbl 1.1h ['$' for help]")

    def feed(self, data):
        """Take received bytes: real-time bytes act at once, others build lines."""
        for byte in data:
            if self.realtime_byte(byte):
                continue
            if byte == 0x0A:
                text = self.partial.decode("latin-1").replace("\r", "").strip()
                self.pending.append((text, len(self.partial) + 1))
                self.note("RX", text)
                self.partial.clear()
                if not self.pending[:-1]:
                    self.next_answer_at = time.monotonic() + self.line_s
            else:
                self.partial.append(byte)
            self.check_buffer()

    def check_buffer(self):
        """Record the fill of the receive buffer; count overflows."""
        used = self.unanswered()
        self.max_unanswered = max(self.max_unanswered, used)
        if used > RX_BUFFER:
            self.overflows += 1
            self.note("OVERFLOW", str(used))

    def realtime_byte(self, byte):
        """Act on a real-time byte; False if the byte belongs to a line."""
        names = {0x3F: "?", 0x21: "!", 0x7E: "~", 0x18: "0x18"}
        if byte not in names and byte < 0x80:
            return False
        name = names.get(byte, f"0x{byte:02x}")
        self.realtime[name] = self.realtime.get(name, 0) + 1
        if byte != 0x3F:
            self.note("RT", name)
        if byte == 0x3F:
            self.send(self.status())
        elif byte == 0x21:
            self.hold = True
        elif byte == 0x7E:
            self.hold = False
        elif byte == 0x18:
            self.reset()
        return True

    def answer_due(self):
        """Answer the oldest pending line when its time has come."""
        if not self.pending or self.hold or time.monotonic() < self.next_answer_at:
            return
        text, _ = self.pending.pop(0)
        self.send(*self.answer(text))
        self.next_answer_at = time.monotonic() + self.line_s

    def answer(self, text):
        """The response lines for one received line."""
        if not text.startswith("$"):
            return self.program_line(text)
        self.commands.append(text)
        if self.strict and any(not t.startswith("$") for t, _ in self.pending):
            return ["[MSG:not idle]", "error:8"]
        replies = {
            "$$": SETTINGS,
            "$#": OFFSETS,
            "$G": [self.parser_state],
            "$I": BOARD_VERSION if self.board else ["[VER:1.1h.fake_grbl:]", "[OPT:V,15,128]"],
            "$": ["[HLP:$$ $# $G $I $N $x=val $Nx=line $J=line $SLP $C $X $H ~ ! ? ctrl-x]"],
        }
        if text in replies:
            return replies[text] + ["ok"]
        if text == "$X":
            self.alarm = False
            return ["[MSG:Caution: Unlocked]", "ok"]
        if text in ("$C", "$H", "$SLP", "$N") or "=" in text:
            return ["ok"]
        return ["error:3"]

    def program_line(self, text):
        """Answer a program line: ok, or the error/alarm the test asked for."""
        if self.alarm and text:
            return ["error:9"]
        if text:
            self.program_lines.append(text)
        if self.error_on and self.error_on in text:
            return ["error:20"]
        if self.alarm_on and self.alarm_on in text:
            self.alarm = True
            return ["ok", "[MSG:ALARM 0007 line 1: fake alarm]", "ALARM:20"]
        return ["ok"]

    def report(self):
        """The summary a test checks."""
        return {
            "program_lines": self.program_lines,
            "commands": self.commands,
            "realtime": self.realtime,
            "max_unanswered": self.max_unanswered,
            "overflows": self.overflows,
            "resets": self.resets,
            "rx_buffer": RX_BUFFER,
        }


def serve(fake, stop):
    """The event loop: read bytes, answer lines when due, until stopped or closed."""
    while not stop["now"]:
        timeout = 0.005 if fake.pending else 0.1
        ready, _, _ = select.select([fake.fd], [], [], timeout)
        if ready:
            try:
                data = os.read(fake.fd, 4096)
            except OSError:
                return
            if not data:
                return
            fake.feed(data)
        fake.answer_due()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("device", help="serial device (e.g. one end of a socat pty pair)")
    parser.add_argument("--log", required=True, help="event log file (appended)")
    parser.add_argument("--report", required=True, help="JSON report written at exit")
    parser.add_argument("--line-ms", type=float, default=10.0, help="time to answer each line")
    parser.add_argument("--error-on", help="answer error:20 to lines containing this text")
    parser.add_argument("--alarm-on", help="raise ALARM:20 after lines containing this text")
    parser.add_argument("--board-format", action="store_true",
                        help="answer ?, $G and $I in the formats of docs/PROTOCOL.md (lathe board)")
    parser.add_argument("--strict-dollar", action="store_true",
                        help="answer error:8 to $ commands while program lines are pending (Run)")
    parser.add_argument("--parser-state", help="the [GC:...] line to answer $G with")
    parser.add_argument("--no-welcome", action="store_true", help="stay silent at start")
    args = parser.parse_args()

    fd = os.open(args.device, os.O_RDWR | os.O_NOCTTY)
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)
    attrs[3] &= ~termios.ECHO
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    stop = {"now": False}

    def on_signal(_signum, _frame):
        stop["now"] = True

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)
    with open(args.log, "a", encoding="utf-8") as log:
        fake = FakeGrbl(fd, log, args.line_ms / 1000.0, args.error_on, args.alarm_on,
                        args.board_format, args.strict_dollar, args.parser_state)
        if not args.no_welcome:
            os.write(fd, WELCOME)
            fake.note("TX", "Grbl 1.1h ['$' for help]")
        serve(fake, stop)
        with open(args.report, "w", encoding="utf-8") as out:
            json.dump(fake.report(), out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
