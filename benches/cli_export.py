#!/usr/bin/env python3
"""Export speed of the robowire tool: JSON lines (the baseline), CSV and MCAP
from one file of 53-byte OmniTiles telemetry, measured in the same run.

    python3 benches/cli_export.py [--repeat-capture N] [--runs R] [--bin PATH]

Builds the release binary (unless --bin is given; it lands in
$CARGO_TARGET_DIR, default target/), writes tests/data/ble_telemetry.bin
repeated N times to a scratch directory, and decodes it R times per format,
keeping each format's best user+system CPU time (the machine is shared: the
best run is the least disturbed). Prints frames per second and each format's
ratio to JSON lines. A file is judged whole before it is printed (a first
pass without output); the `--allow-noise` row skips that pass, so its ratio
is the pass's cost. Stdlib only.
"""

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

from release_binary import release_binary

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_of(args):
    """User+system CPU seconds and wall seconds of one run of `args`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"{' '.join(args)} failed: {done.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, done.stderr


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat-capture", type=int, default=1000)
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--bin", help="a built robowire binary (default: build the release one)")
    options = parser.parse_args()

    binary = release_binary(options.bin, "cli")

    scratch = tempfile.mkdtemp(prefix="robowire-export-bench-")
    try:
        with open(os.path.join(ROOT, "tests", "data", "ble_telemetry.bin"), "rb") as f:
            capture = f.read()
        big = os.path.join(scratch, "ble_big.bin")
        with open(big, "wb") as f:
            f.write(capture * options.repeat_capture)
        # The frame count from the tool's own summary.
        _, _, summary = cpu_of([binary, "decode", "omnitiles", "--from", "tile", big])
        frames = int(summary.split("robowire: ")[1].split(" frame")[0])
        csv_dir = os.path.join(scratch, "csv")
        mcap_file = os.path.join(scratch, "out.mcap")
        formats = [
            ("jsonl (stdout)", [binary, "decode", "omnitiles", "--from", "tile", big]),
            ("jsonl, one pass", [binary, "decode", "omnitiles", "--from", "tile", "--allow-noise", big]),
            ("csv -o DIR", [binary, "decode", "omnitiles", "--from", "tile", "--format", "csv", "-o", csv_dir, "--force", big]),
            ("mcap -o FILE", [binary, "decode", "omnitiles", "--from", "tile", "--format", "mcap", "-o", mcap_file, "--force", big]),
            ("mcap, no zstd", [binary, "decode", "omnitiles", "--from", "tile", "--format", "mcap", "--compression", "none", "-o", mcap_file, "--force", big]),
        ]
        best = {name: (float("inf"), 0.0) for name, _ in formats}
        # Interleaved, so a busy moment of the machine hits every format alike.
        for _ in range(options.runs):
            for name, args in formats:
                cpu, wall, _ = cpu_of(args)
                if cpu < best[name][0]:
                    best[name] = (cpu, wall)
        print(f"{len(capture) * options.repeat_capture / 1e6:.1f} MB of 53-byte telemetry, "
              f"{frames} frames, best of {options.runs} runs each (CPU = user + system)")
        base = best[formats[0][0]][0]
        print(f"{'format':16} {'CPU s':>7} {'wall s':>7} {'M frames/s':>11} {'vs jsonl':>9}")
        for name, _ in formats:
            cpu, wall = best[name]
            print(f"{name:16} {cpu:7.3f} {wall:7.3f} {frames / cpu / 1e6:11.2f} {base / cpu:8.2f}x")
    finally:
        shutil.rmtree(scratch)


if __name__ == "__main__":
    main()
