#!/usr/bin/env python3
"""Streams PROGRAM to the board at PORT with grbl-streamer 2.0.2 (PyPI) in its raw
mode: the file's lines go into `GrblStreamer.buffer` as they are and `job_run()`
streams them with character counting, bypassing `load_file`/`write`, whose
preprocessor splits blocks before every G/M/T word and comments out every code not
in grbl's own list (docs/SENDERS.md). Waits for every `ok` and then for the board to
be Idle; exit 0, or 1 on an `error:`/alarm/undefined variable or a timeout.

    run_grbl_streamer.py PROGRAM PORT [TIMEOUT_S]

What the sender wrote is printed (`> line`), so that what its per-line processing
(`_set_next_line`: variables, feed and spindle words) did to the file shows.
"""
import sys
import threading
import time

from grbl_streamer import GrblStreamer


def main():
    program, port = sys.argv[1], sys.argv[2]
    timeout = float(sys.argv[3]) if len(sys.argv) > 3 else 300
    booted, finished = threading.Event(), threading.Event()
    problems, state = [], {"mode": None}

    def callback(event, *data):
        if event == "on_boot":
            booted.set()
        elif event == "on_job_completed":
            finished.set()
        elif event in ("on_error", "on_alarm", "on_var_undefined"):
            problems.append(f"{event}: {data}")
            print(f"{event}: {data}", flush=True)
        elif event == "on_write":
            print("> " + data[0].rstrip("\n"), flush=True)
        elif event == "on_stateupdate":
            state["mode"] = data[0]

    g = GrblStreamer(callback, name="board")
    g.cnect(port, 115200)
    if not booted.wait(10):
        print("no welcome from the board")
        return 1
    g.poll_start()
    time.sleep(1)  # its $$ / $# / $G requests after the welcome
    lines = open(program).read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    finished.clear()
    g.buffer.extend(lines)
    g.buffer_size = len(g.buffer)
    g.job_run()
    deadline = time.time() + timeout
    ok = finished.wait(timeout)
    # Every line answered: the board runs on; wait until it is Idle again.
    idle = 0
    while ok and not problems and time.time() < deadline and idle < 3:
        time.sleep(0.3)
        idle = idle + 1 if state["mode"] == "Idle" else 0
    g.poll_stop()
    g.disconnect()
    if problems or not ok or idle < 3:
        print(f"FAILED: problems {problems}, all answered {ok}, idle {idle >= 3}")
        return 1
    print("grbl-streamer: job finished")
    return 0


if __name__ == "__main__":
    sys.exit(main())
