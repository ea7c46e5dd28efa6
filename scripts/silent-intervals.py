#!/usr/bin/python3
"""The longest silence of each command a person runs on the shipped scenes: dampbound on a
terminal (a pseudo-terminal, as a person's shell gives it: stdout line-buffered, stderr
beside it), with the time of every line that reaches it. A silence is the time from the start
to the first line, between two lines (or two rewrites of a progress line), or from the last
line to the exit; dampbound promises
a progress line on every wait over 2 s (docs/hardening.md), so a silence above about 2 s plus
one stage's length is a wait nobody was told about.

    /usr/bin/python3 scripts/silent-intervals.py [--dampbound build/app/dampbound]
                                                 [--scenes paper-plane,tissue-block,...]
                                                 [--commands bounds,suggest,run]

Prints one row per command (its wall time, its longest silence and where it fell) and the
longest over all. Times are wall clock: run it on an otherwise idle machine.
"""
import argparse
import glob
import os
import pty
import select
import subprocess
import sys
import time


def timed_lines(argv):
    """Runs argv on a pseudo-terminal; returns (exit code, wall s, [(t, line), ...])."""
    master, slave = pty.openpty()
    t0 = time.monotonic()
    p = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=slave, stderr=slave,
                         close_fds=True)
    os.close(slave)
    lines = []
    while True:
        ready, _, _ = select.select([master], [], [], 0.05)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # the child closed the terminal
                chunk = b""
            if not chunk:
                break
            # What reaches the terminal is seen when it arrives, a partial line too: a progress
            # note on a terminal rewrites its line ("\r", erase) without a newline.
            seen = [t for t in chunk.decode("utf-8", "replace").replace("\x1b[K", "")
                    .replace("\r", "\n").split("\n") if t.strip()]
            if seen:
                lines.append((time.monotonic() - t0, seen[-1].strip()))
        elif p.poll() is not None:
            break
    rc = p.wait()
    os.close(master)
    return rc, time.monotonic() - t0, lines


def longest_silence(wall, lines):
    """(seconds, after which line) of the longest interval without output."""
    marks = [(0.0, "(start)")] + lines + [(wall, "(exit)")]
    best = (0.0, "")
    for (a, what), (b, _) in zip(marks, marks[1:]):
        if b - a > best[0]:
            best = (b - a, what)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dampbound", default="build/app/dampbound")
    ap.add_argument("--scenes", default="", help="comma-separated names (default: every shipped scene)")
    ap.add_argument("--commands", default="bounds,suggest,run")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scenes = [s for s in a.scenes.split(",") if s] or sorted(
        os.path.basename(f)[:-5] for f in glob.glob(os.path.join(root, "scenes", "*.toml")))
    if not os.access(a.dampbound, os.X_OK):
        sys.exit(f"silent-intervals: {a.dampbound} is not an executable (build it, or pass --dampbound)")
    print(f"{'command':<44} {'exit':>4} {'wall s':>8} {'longest silence s':>18}  after")
    worst = (0.0, "")
    for scene in scenes:
        for command in [c for c in a.commands.split(",") if c]:
            argv = [a.dampbound, command, os.path.join(root, "scenes", scene + ".toml")]
            rc, wall, lines = timed_lines(argv)
            gap, after = longest_silence(wall, lines)
            label = f"{command} {scene}"
            print(f"{label:<44} {rc:>4} {wall:>8.2f} {gap:>18.2f}  {after[:60]}", flush=True)
            if gap > worst[0]:
                worst = (gap, label)
    print(f"longest silence over all: {worst[0]:.2f} s ({worst[1]})")


if __name__ == "__main__":
    main()
