"""Item 5 of the Python issue: `derive` of the Koch island at 7 steps (15.6 M
symbols) into a Python string, against the command line writing the same
word to a pipe (read and thrown away by this process), each run RUNS times;
prints both times (best and median) and their ratios.

    python python/bench.py [PATH/TO/graftal]   # default: GRAFTAL_BIN, else target/release/graftal
"""

import os
import pathlib
import statistics
import subprocess
import sys
import time

import graftal

RUNS = 15
SPEC, STEPS = "std:koch-island", 7
REPO = pathlib.Path(__file__).resolve().parents[1]


def timed(work):
    times = []
    for _ in range(RUNS):
        start = time.perf_counter()
        work()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times)


def through_python():
    word = graftal.load(SPEC).derive(steps=STEPS)
    assert len(word) == 15_578_843


def through_a_pipe(binary):
    def run():
        p = subprocess.Popen([binary, "derive", SPEC, "-n", str(STEPS)], stdout=subprocess.PIPE)
        read = 0
        while chunk := p.stdout.read(1 << 20):
            read += len(chunk)
        assert p.wait() == 0 and read == 15_578_844  # the word and its newline

    return run


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else os.environ.get(
        "GRAFTAL_BIN", str(REPO / "target" / "release" / "graftal")
    )
    cli = timed(through_a_pipe(binary))
    py = timed(through_python)
    print(f"{SPEC} at {STEPS} steps, 15,578,843 symbols, best and median of {RUNS} runs:")
    print(f"  graftal derive into a pipe  {cli[0] * 1e3:7.1f} ms  {cli[1] * 1e3:7.1f} ms")
    print(f"  Model.derive into a str     {py[0] * 1e3:7.1f} ms  {py[1] * 1e3:7.1f} ms")
    print(f"  ratio (Python / command line): best {py[0] / cli[0]:.2f}, median {py[1] / cli[1]:.2f}")


if __name__ == "__main__":
    main()
