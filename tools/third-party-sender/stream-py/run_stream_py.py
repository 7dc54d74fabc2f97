#!/usr/bin/env python3
"""Runs gnea/grbl's `stream.py` (doc/script/stream.py, Python 2) unchanged under
Python 3: its text goes through lib2to3's standard fixers (print statements,
raw_input) in memory, and pyserial's `Serial` is given Python 2's str interface
(writes take str, readline returns str; bytes as Latin-1, as Python 2 passed them).
Nothing else of the program is touched.

    run_stream_py.py [stream.py's arguments: GCODE_FILE DEVICE [-q] [-c] [-s]]
"""
import os
import sys
import warnings

warnings.filterwarnings("ignore", category=DeprecationWarning)
from lib2to3 import refactor  # noqa: E402

import serial  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


class Py2Serial(serial.Serial):
    """pyserial with Python 2's str in and out."""

    def write(self, data):
        if isinstance(data, str):
            data = data.encode("latin-1")
        return super().write(data)

    def readline(self, *args, **kwargs):
        return super().readline(*args, **kwargs).decode("latin-1")


def main():
    path = os.path.join(HERE, "stream.py")
    source = open(path).read()
    tool = refactor.RefactoringTool(refactor.get_fixers_from_package("lib2to3.fixes"))
    code = str(tool.refactor_string(source, path))
    serial.Serial = Py2Serial
    sys.argv = [path] + sys.argv[1:]
    exec(compile(code, path, "exec"), {"__name__": "__main__", "__file__": path})


if __name__ == "__main__":
    main()
