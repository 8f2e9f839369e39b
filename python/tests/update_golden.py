#!/usr/bin/env python3
"""Rewrite tests/golden/*.jsonl from the robowire tool: the lines it gives for
each sample-capture case in conftest.CASES.

    cargo build --features cli --bin robowire
    ROBOWIRE_CLI=target/debug/robowire python python/tests/update_golden.py
"""

from __future__ import annotations

import os
import subprocess
import sys

from conftest import CASES, GOLDEN


def main() -> int:
    binary = os.environ.get("ROBOWIRE_CLI")
    if not binary:
        print("set ROBOWIRE_CLI to the robowire tool", file=sys.stderr)
        return 2
    GOLDEN.mkdir(exist_ok=True)
    for case in CASES:
        run = subprocess.run([binary, *case.cli_args()], capture_output=True, check=True)
        (GOLDEN / f"{case.name}.jsonl").write_bytes(run.stdout)
        print(f"{case.name}: {len(run.stdout.splitlines())} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
