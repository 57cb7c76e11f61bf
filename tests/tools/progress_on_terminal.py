"""Runs kinema with stderr on a pseudo-terminal and prints what the terminal got
(run by tests/cli/streaming_test.cpp, which checks it).

usage: progress_on_terminal.py [--stdout-too] KINEMA ARGS...
Prints the exit status on the first line, then the bytes written to the terminal
(escaped with repr, so control characters can be checked); with --stdout-too (the
results on the terminal as well) only their count and whether a progress line was among them.
"""
import os
import pty
import subprocess
import sys


def main(command):
    stdout_too = command[0] == "--stdout-too"  # the results on the same terminal
    if stdout_too:
        command = command[1:]
    master, slave = pty.openpty()
    process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=slave if stdout_too else subprocess.DEVNULL,
                               stderr=slave)
    os.close(slave)
    chunks = []
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: the other side is closed
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(master)
    received = b"".join(chunks)
    print(process.wait())
    if stdout_too:
        print(len(received), b"values/s" in received)
    else:
        print(repr(received))


if __name__ == "__main__":
    main(sys.argv[1:])
