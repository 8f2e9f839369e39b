#!/usr/bin/env python3
"""Frames per second from Python: robowire beside a pure-Python stream parser.

Two streams, each fed in 4 KiB chunks, as a host reads a serial port:

* OmniTiles: 53-byte BLE telemetry frames (the 300 frames of
  tests/data/ble_telemetry.bin, cycled);
* Telemetrix: the reports a mirte robot streams (the digital, analog, sonar
  and encoder reports of tests/data/telemetrix_reports.bin, cycled).

For each, robowire's ``Decoder`` and two pure-Python parsers of the same
framing, written below, decode the same bytes in the same run and give the
same dicts (the CLI's JSON-lines schema):

* the *plain* parser is the shape most Python hosts have (the OmniTiles SDK,
  tmx-pico-aio): a state machine fed one byte at a time;
* the *tuned* parser is as fast as we could make pure Python: whole frames
  found with ``bytearray.find`` and read with ``struct``.

Both check what robowire checks on a clean stream (start byte, id, length,
checksum) and keep a cut frame across chunks; neither has robowire's resync
verification. Each figure is the best of ``--repeat`` runs, by wall clock and by the
process's CPU time (on a shared machine the CPU time is the steadier one;
the ratios use it). Two more lines per protocol: robowire with
``lazy=True`` (items that build their dict only when read; none is read
here), and robowire decoding without building any Python object
(``_count``): the difference to the first line is the cost of the dicts.

Run from the repository root after installing the package::

    python python/bench.py            # or: --frames 200000 --repeat 5
"""

from __future__ import annotations

import argparse
import glob
import math
import os
import platform
import struct
import sys
import time
from typing import Any, Callable

# Run as a script, Python puts python/ first on sys.path, where the source
# package has no compiled extension unless it was built in place
# (maturin develop): then import the installed package instead.
_HERE = os.path.dirname(os.path.abspath(__file__))
_BUILT = glob.glob(os.path.join(_HERE, "robowire", "_robowire*.so")) + glob.glob(
    os.path.join(_HERE, "robowire", "_robowire*.pyd")
)
if not _BUILT:
    sys.path = [p for p in sys.path if os.path.abspath(p or os.curdir) != _HERE]

from robowire import omnitiles, telemetrix  # noqa: E402

CHUNK = 4096
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data")

# --------------------------------------------------------------------------
# Baseline 1: OmniTiles 53-byte telemetry, a5 60 <50 bytes> sum
# --------------------------------------------------------------------------

_BLE53 = struct.Struct("<7H6f6H")


def _reading(v: int) -> int | None:
    return None if v == 0xFFFF else v


class TunedOmniTiles:
    """A tuned pure-Python stream parser for OmniTiles 53-byte telemetry:
    ``bytearray.find`` for the start byte, ``struct`` for the fields."""

    def __init__(self) -> None:
        self.buf = bytearray()
        self.offset = 0  # stream offset of buf[0]

    def feed(self, data: bytes) -> list[dict[str, Any]]:
        buf = self.buf
        buf += data
        out = []
        n = len(buf)
        i = 0
        while True:
            i = buf.find(0xA5, i)
            if i < 0:
                i = n
                break
            if n - i < 53:
                break
            if buf[i + 1] == 0x60 and sum(buf[i + 1 : i + 52]) & 0xFF == buf[i + 52]:
                out.append(_telemetry(buf, i, self.offset + i))
                i += 53
            else:
                i += 1
        del buf[:i]
        self.offset += i
        return out


class PlainOmniTiles:
    """The plain shape of a Python host's parser: a byte-at-a-time state
    machine (as the OmniTiles SDK's), with the same checks and dicts."""

    def __init__(self) -> None:
        self.frame = bytearray()
        self.pos = 0  # stream offset of the next byte

    def feed(self, data: bytes) -> list[dict[str, Any]]:
        out = []
        frame = self.frame
        for byte in data:
            self.pos += 1
            if not frame:
                if byte == 0xA5:
                    frame.append(byte)
                continue
            frame.append(byte)
            if len(frame) == 2 and byte != 0x60:
                self._resync()
            elif len(frame) == 53:
                if sum(frame[1:52]) & 0xFF == frame[52]:
                    out.append(_telemetry(frame, 0, self.pos - 53))
                    frame.clear()
                else:
                    self._resync()
        return out

    def _resync(self) -> None:
        i = self.frame.find(0xA5, 1)
        del self.frame[: i if i >= 0 else len(self.frame)]


def _telemetry(buf: bytearray, i: int, offset: int) -> dict[str, Any]:
    v = _BLE53.unpack_from(buf, i + 2)
    return {
        "offset": offset,
        "len": 53,
        "type": "telemetry",
        "layout": "ble53",
        "m1_pos": _reading(v[0]),
        "m2_pos": _reading(v[1]),
        "uwb": [_reading(v[2]), _reading(v[3]), _reading(v[4]), _reading(v[5])],
        "tof": _reading(v[6]),
        "imu": {"ax": v[7], "ay": v[8], "az": v[9], "gx": v[10], "gy": v[11], "gz": v[12]},
        "m1_adcs": [v[13], v[14], v[15], v[16]],
        "m2_adcs": [v[17], v[18]],
    }


# --------------------------------------------------------------------------
# Baseline 2: Telemetrix reports, LEN id payload (big-endian integers)
# --------------------------------------------------------------------------

_SONAR = {0xFFFC: "no_echo", 0xFFFD: "out_of_range", 0xFFFE: "stale"}


def _digital(b: bytearray, i: int, offset: int) -> dict[str, Any]:
    return {"offset": offset, "len": 4, "type": "digital_report", "pin": b[i + 2], "value": b[i + 3]}


def _analog(b: bytearray, i: int, offset: int) -> dict[str, Any]:
    value = b[i + 3] << 8 | b[i + 4]
    return {"offset": offset, "len": 5, "type": "analog_report", "pin": b[i + 2], "value": value}


def _sonar(b: bytearray, i: int, offset: int) -> dict[str, Any]:
    cm = b[i + 4] << 8 | b[i + 5]
    return {
        "offset": offset,
        "len": 6,
        "type": "sonar_distance",
        "trig": b[i + 2],
        "echo": b[i + 3],
        "cm": _SONAR.get(cm, cm),
    }


def _encoder(b: bytearray, i: int, offset: int) -> dict[str, Any]:
    steps = b[i + 3] - 256 if b[i + 3] > 127 else b[i + 3]
    return {"offset": offset, "len": 4, "type": "encoder_report", "pin_a": b[i + 2], "steps": steps}


# report id: (LEN, reader)
_REPORTS: dict[int, tuple[int, Callable[[bytearray, int, int], dict[str, Any]]]] = {
    2: (3, _digital),
    3: (4, _analog),
    11: (5, _sonar),
    14: (3, _encoder),
}


class PlainTelemetrix:
    """The plain shape of a Telemetrix client's reader (as tmx-pico-aio's):
    a length byte, then that many bytes, a byte at a time."""

    def __init__(self) -> None:
        self.frame = bytearray()
        self.need = 0
        self.pos = 0

    def feed(self, data: bytes) -> list[dict[str, Any]]:
        out = []
        frame = self.frame
        for byte in data:
            self.pos += 1
            if not frame:
                if byte:  # a 00 between frames is padding
                    self.need = byte + 1
                    frame.append(byte)
                continue
            frame.append(byte)
            if len(frame) == self.need:
                known = _REPORTS.get(frame[1])
                if known is not None and known[0] == frame[0]:
                    out.append(known[1](frame, 0, self.pos - self.need))
                frame.clear()
        return out


class TunedTelemetrix:
    """A tuned pure-Python stream parser for the streamed Telemetrix
    reports: whole frames sliced from a buffer, resync by one byte."""

    def __init__(self) -> None:
        self.buf = bytearray()
        self.offset = 0

    def feed(self, data: bytes) -> list[dict[str, Any]]:
        buf = self.buf
        buf += data
        out = []
        n = len(buf)
        i = 0
        reports = _REPORTS
        while i < n:
            length = buf[i]
            if length == 0:  # padding between frames
                i += 1
                continue
            if n - i <= length:
                break
            known = reports.get(buf[i + 1])
            if known is None or known[0] != length:
                i += 1  # not a report we know: resync by one byte
                continue
            out.append(known[1](buf, i, self.offset + i))
            i += length + 1
        del buf[:i]
        self.offset += i
        return out


# --------------------------------------------------------------------------
# Streams and timing
# --------------------------------------------------------------------------


def omnitiles_stream(frames: int) -> bytes:
    with open(os.path.join(DATA, "ble_telemetry.bin"), "rb") as f:
        capture = f.read()
    decoded = omnitiles.Decoder(source="tile", layouts="ble53").feed(capture)
    raw = [capture[d["offset"] : d["offset"] + 53] for d in decoded]
    return b"".join(raw[k % len(raw)] for k in range(frames))


def telemetrix_stream(frames: int) -> bytes:
    with open(os.path.join(DATA, "telemetrix_reports.bin"), "rb") as f:
        capture = f.read()
    kinds = {"digital_report", "analog_report", "sonar_distance", "encoder_report"}
    decoded = telemetrix.Decoder(source="pico").feed(capture)
    raw = [capture[d["offset"] : d["offset"] + d["len"]] for d in decoded if d["type"] in kinds]
    return b"".join(raw[k % len(raw)] for k in range(frames))


def timed(
    feed: Callable[[], Callable[[bytes], Any]], stream: bytes, repeat: int, count: bool = False
) -> tuple[int, float, float]:
    """(frames, best wall seconds, best CPU seconds) over `repeat` runs."""
    frames, best_wall, best_cpu = 0, math.inf, math.inf
    for _ in range(repeat):
        feed_fn = feed()
        frames = 0
        cpu = time.process_time()
        wall = time.perf_counter()
        for start in range(0, len(stream), CHUNK):
            got = feed_fn(stream[start : start + CHUNK])
            frames += got if count else len(got)
        best_wall = min(best_wall, time.perf_counter() - wall)
        best_cpu = min(best_cpu, time.process_time() - cpu)
    return frames, best_wall, best_cpu


def same_items(ours: list[dict[str, Any]], theirs: list[dict[str, Any]]) -> bool:
    """Whether two parsers agree (floats to f32 precision: the baseline keeps
    struct's widened f32, robowire the JSON decimal)."""

    def close(a: Any, b: Any) -> bool:
        if isinstance(a, float) and isinstance(b, float):
            return math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-30)
        if isinstance(a, dict) and isinstance(b, dict):
            return a.keys() == b.keys() and all(close(a[k], b[k]) for k in a)
        if isinstance(a, list) and isinstance(b, list):
            return len(a) == len(b) and all(close(x, y) for x, y in zip(a, b))
        return type(a) is type(b) and a == b

    return len(ours) == len(theirs) and all(close(a, b) for a, b in zip(ours, theirs))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=200_000, help="frames per stream (default 200000)")
    parser.add_argument("--repeat", type=int, default=5, help="runs per decoder; the best counts (default 5)")
    args = parser.parse_args()

    print(f"Python {platform.python_version()} on {platform.machine()}, {os.cpu_count()} CPUs; ", end="")
    print(f"{args.frames} frames per stream, {CHUNK}-byte chunks, best of {args.repeat}")
    cases = [
        (
            "OmniTiles 53-byte telemetry",
            omnitiles_stream(args.frames),
            lambda lazy=False: omnitiles.Decoder(source="tile", layouts="ble53", lazy=lazy),
            PlainOmniTiles,
            TunedOmniTiles,
        ),
        (
            "Telemetrix reports",
            telemetrix_stream(args.frames),
            lambda lazy=False: telemetrix.Decoder(source="pico", lazy=lazy),
            PlainTelemetrix,
            TunedTelemetrix,
        ),
    ]
    ok = True
    for name, stream, ours, plain, tuned in cases:
        first = stream[: 100 * CHUNK]
        for baseline in (plain, tuned):
            if not same_items(ours().feed(first), baseline().feed(first)):
                print(f"{name}: robowire and {baseline.__name__} disagree", file=sys.stderr)
                ok = False
        runs = [
            ("robowire", timed(lambda: ours().feed, stream, args.repeat)),
            ("robowire, lazy=True", timed(lambda: ours(lazy=True).feed, stream, args.repeat)),
            ("plain Python", timed(lambda: plain().feed, stream, args.repeat)),
            ("tuned Python", timed(lambda: tuned().feed, stream, args.repeat)),
            ("robowire, no items", timed(lambda: ours()._count, stream, args.repeat, count=True)),
        ]
        if any(frames != args.frames for _, (frames, _, _) in runs):
            print(f"{name}: frame counts differ: {[r[1][0] for r in runs]}", file=sys.stderr)
            ok = False
        mb = len(stream) / 1e6
        print(f"\n{name}: {args.frames} frames, {mb:.1f} MB; frames/s by wall clock and by CPU time")
        for label, (frames, wall, cpu) in runs:
            print(
                f"  {label:19} {frames / wall:>12,.0f} frames/s wall {frames / cpu:>12,.0f} frames/s CPU"
                f"  ({mb / cpu:7.1f} MB/s CPU)"
            )
        rw, lazy, plain_run, tuned_run, bare = (r[1][2] for r in runs)
        print(f"  robowire / plain Python (CPU): {plain_run / rw:.1f}x dicts, {plain_run / lazy:.1f}x lazy")
        print(f"  robowire / tuned Python (CPU): {tuned_run / rw:.1f}x dicts, {tuned_run / lazy:.1f}x lazy")
        print(f"  building the dicts takes {1 - bare / rw:.0%} of robowire's CPU time")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
