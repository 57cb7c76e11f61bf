"""Runs kinema with stderr on a pseudo-terminal and prints what the terminal got
(run by tests/cli/streaming_test.cpp, which checks it).

usage: progress_on_terminal.py KINEMA ARGS...
Prints the exit status on the first line, then the bytes written to the terminal
(escaped with repr, so control characters can be checked).
"""
import os
import pty
import subprocess
import sys


def main(command):
    master, slave = pty.openpty()
    process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    received = b""
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: the other side is closed
            break
        if not chunk:
            break
        received += chunk
    os.close(master)
    print(process.wait())
    print(repr(received))


if __name__ == "__main__":
    main(sys.argv[1:])
