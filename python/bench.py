#!/usr/bin/env python3
"""Frames per CPU-second from Python: robowire beside pure-Python stream parsers.

Three streams, each fed in 4 KiB chunks, as a host reads a serial port:

* OmniTiles: 53-byte BLE telemetry frames (the frames of
  tests/data/ble_telemetry.bin, cycled);
* Telemetrix: the reports a mirte robot streams (the digital, analog, sonar
  and encoder reports of tests/data/telemetrix_reports.bin, cycled);
* Pixy2: both directions of a conversation with the camera (the frames of
  tests/data/pixy2_conversation.hex, cycled); it has no pure-Python
  baseline, so its rows have no ratios.

As a host uses them, every item is kept in a list with the garbage collector
on, and the run reads no field, a few (OmniTiles: ``m1_pos`` and ``imu.az``;
Telemetrix: ``type`` and the first field) or all of them. The same runs with
the items dropped at once are there for comparison. In the same run, two
pure-Python parsers of the same framing, written below, decode the same bytes
into the same dicts (the CLI's JSON-lines schema), as the baselines:

* the *plain* parser is the shape most Python hosts have (the OmniTiles SDK,
  tmx-pico-aio): a state machine fed one byte at a time;
* the *tuned* parser is as fast as we could make pure Python: whole frames
  found with ``bytearray.find`` and read with ``struct``.

Both check what robowire checks on a clean stream (start byte, id, length,
checksum) and keep a cut frame across chunks; neither has robowire's resync
verification. Each figure is the median of ``--repeat`` runs of the process's
CPU time (the machine may be shared; CPU time is steadier than the wall
clock), and every ratio is to a baseline measured in the same run, kept and
read alike.

Run from the repository root after installing the package (numpy for the
``feed_array`` row)::

    pip install './python[numpy]'
    python python/bench.py            # or: --frames 200000 --repeat 5

``--sdk DIR`` adds the OmniTiles SDK's own parser (its
``omnitiles.protocol.StreamParser``, imported from ``DIR``, the SDK's
``sdk/src`` in a checkout of Clue88/OmniTiles) beside
``robowire.omnitiles.sdk.StreamParser``, both used as the SDK's ``Tile`` uses
its parser: fed each chunk, every frame kept, in 4 KiB chunks and in 53-byte
BLE notifications.
"""

from __future__ import annotations

import argparse
import gc
import glob
import math
import os
import platform
import statistics
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

from robowire import omnitiles, pixy2, telemetrix  # noqa: E402
from robowire.omnitiles import sdk  # noqa: E402

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


def pixy2_stream(frames: int) -> bytes:
    with open(os.path.join(DATA, "pixy2_conversation.hex")) as f:
        capture = bytes.fromhex(" ".join(line.split("#")[0] for line in f))
    decoded = pixy2.Decoder(typed=False).feed(capture)
    raw = [capture[d["offset"] : d["offset"] + d["len"]] for d in decoded]
    return b"".join(raw[k % len(raw)] for k in range(frames))


# --------------------------------------------------------------------------
# What a host reads of each item
# --------------------------------------------------------------------------


def omni_few_typed(t: Any) -> Any:
    return t.m1_pos, t.imu.az


def omni_few_dict(d: Any) -> Any:
    return d["m1_pos"], d["imu"]["az"]


def omni_all_typed(t: Any) -> Any:
    imu = t.imu
    return (
        t.offset, t.len, t.type, t.layout, t.m1_pos, t.m2_pos, t.uwb, t.tof,
        imu.ax, imu.ay, imu.az, imu.gx, imu.gy, imu.gz, t.m1_adcs, t.m2_adcs,
    )


def omni_all_dict(d: Any) -> Any:
    imu = d["imu"]
    return (
        d["offset"], d["len"], d["type"], d["layout"], d["m1_pos"], d["m2_pos"], d["uwb"], d["tof"],
        imu["ax"], imu["ay"], imu["az"], imu["gx"], imu["gy"], imu["gz"], d["m1_adcs"], d["m2_adcs"],
    )


_TMX_FIELDS = {
    "digital_report": ("pin", "value"),
    "analog_report": ("pin", "value"),
    "sonar_distance": ("trig", "echo", "cm"),
    "encoder_report": ("pin_a", "steps"),
}


def kind_of(t: Any) -> Any:
    return t.type


def px_few_typed(t: Any) -> Any:
    return t.type, t.checksum


def px_all_typed(t: Any) -> Any:
    return [t[k] for k in t]


def px_few_dict(d: Any) -> Any:
    return d["type"], d["checksum"]


def px_all_dict(d: Any) -> Any:
    return [d[k] for k in d]


def tmx_few_typed(t: Any) -> Any:
    kind = t.type
    return kind, getattr(t, _TMX_FIELDS[kind][0])


def tmx_few_dict(d: Any) -> Any:
    kind = d["type"]
    return kind, d[_TMX_FIELDS[kind][0]]


def tmx_all_typed(t: Any) -> Any:
    kind = t.type
    return t.offset, t.len, kind, [getattr(t, f) for f in _TMX_FIELDS[kind]]


def tmx_all_dict(d: Any) -> Any:
    kind = d["type"]
    return d["offset"], d["len"], kind, [d[f] for f in _TMX_FIELDS[kind]]


# --------------------------------------------------------------------------
# Timing
# --------------------------------------------------------------------------

Feed = Callable[[bytes], Any]


def timed(
    make: Callable[[], Feed],
    stream: bytes,
    repeat: int,
    keep: bool = True,
    read: Callable[[Any], Any] | None = None,
    chunk: int = CHUNK,
    count: Callable[[Any], int] = len,
) -> tuple[int, float]:
    """(frames, median CPU seconds) of `repeat` runs that feed `stream` in
    `chunk`-byte pieces, keep every item (or drop it) and `read` each one."""
    gc.enable()
    times = []
    frames = 0
    for _ in range(repeat):
        feed = make()
        kept: list[Any] = []
        frames = 0
        cpu = time.process_time()
        for start in range(0, len(stream), chunk):
            items = feed(stream[start : start + chunk])
            frames += count(items)
            if read is not None:
                for item in items:
                    read(item)
            if keep:
                kept.append(items)
        times.append(time.process_time() - cpu)
        del kept, items
        gc.collect()
    return frames, statistics.median(times)


def array_frames(arrays: dict[str, Any]) -> int:
    """Frames in `feed_array` tables: a record each, or (the tables of a
    frame's listed elements, a row per element) each distinct `frame`."""
    import numpy

    listed = [a["frame"] for a in arrays.values() if "frame" in a.dtype.names]
    whole = sum(len(a) for a in arrays.values() if "frame" not in a.dtype.names)
    return whole + (len(numpy.unique(numpy.concatenate(listed))) if listed else 0)


def same_items(ours: list[dict[str, Any]], theirs: list[dict[str, Any]]) -> bool:
    """Whether two parsers agree (both give an f32 as its exact value; the
    comparison allows for f32 precision all the same)."""

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
    parser.add_argument("--repeat", type=int, default=5, help="runs per row; the median counts (default 5)")
    parser.add_argument("--sdk", metavar="DIR", help="the OmniTiles SDK's sdk/src, to time its parser beside ours")
    args = parser.parse_args()
    sdk_parser = None
    if args.sdk:
        sys.path.insert(0, args.sdk)
        from omnitiles.protocol import StreamParser as sdk_parser  # the SDK's own package
    try:
        import numpy  # noqa: F401

        has_numpy = True
    except ImportError:
        has_numpy = False

    print(f"Python {platform.python_version()} on {platform.machine()}, {os.cpu_count()} CPUs; ", end="")
    print(f"{args.frames} frames per stream, {CHUNK}-byte chunks, median of {args.repeat}, GC on")
    cases = [
        (
            "OmniTiles 53-byte telemetry",
            omnitiles_stream(args.frames),
            lambda **kw: omnitiles.Decoder(source="tile", layouts="ble53", **kw),
            PlainOmniTiles,
            TunedOmniTiles,
            (omni_few_typed, omni_all_typed, omni_few_dict, omni_all_dict),
            has_numpy,
        ),
        (
            "Telemetrix reports",
            telemetrix_stream(args.frames),
            lambda **kw: telemetrix.Decoder(source="pico", **kw),
            PlainTelemetrix,
            TunedTelemetrix,
            (tmx_few_typed, tmx_all_typed, tmx_few_dict, tmx_all_dict),
            has_numpy,
        ),
        (
            "Pixy2 conversation",
            pixy2_stream(args.frames),
            lambda **kw: pixy2.Decoder(**kw),
            None,
            None,
            (px_few_typed, px_all_typed, px_few_dict, px_all_dict),
            has_numpy,
        ),
    ]
    ok = True
    for name, stream, ours, plain, tuned, (few_t, all_t, few_d, all_d), arrays in cases:
        first = stream[: 100 * CHUNK]
        for baseline in (b for b in (plain, tuned) if b is not None):
            if not same_items(ours(typed=False).feed(first), baseline().feed(first)):
                print(f"{name}: robowire and {baseline.__name__} disagree", file=sys.stderr)
                ok = False
        if ours().feed(first) != ours(typed=False).feed(first):
            print(f"{name}: typed items and dicts disagree", file=sys.stderr)
            ok = False
        r = args.repeat
        # (label, baseline row for the ratios or None, (frames, CPU seconds))
        rows: list[tuple[str, str | None, tuple[int, float]]] = []

        def row(label: str, base: str | None, result: tuple[int, float]) -> None:
            rows.append((label, base, result))

        if plain is not None and tuned is not None:
            row("plain Python, kept", None, timed(lambda: plain().feed, stream, r))
            row("tuned Python, kept", None, timed(lambda: tuned().feed, stream, r))
            row("plain Python, kept, all read", None, timed(lambda: plain().feed, stream, r, read=all_d))
            row("tuned Python, kept, all read", None, timed(lambda: tuned().feed, stream, r, read=all_d))
        row("typed, kept", "", timed(lambda: ours().feed, stream, r))
        row("typed, kept, type read", "", timed(lambda: ours().feed, stream, r, read=kind_of))
        row("typed, kept, a few read", "", timed(lambda: ours().feed, stream, r, read=few_t))
        row("typed, kept, all read", " all", timed(lambda: ours().feed, stream, r, read=all_t))
        row("dicts, kept", "", timed(lambda: ours(typed=False).feed, stream, r))
        row("dicts, kept, all read", " all", timed(lambda: ours(typed=False).feed, stream, r, read=all_d))
        if arrays:
            row("feed_array, kept", "", timed(lambda: ours(typed=False).feed_array, stream, r, count=array_frames))
            row(
                "feed_array, 64 KiB chunks, kept",
                "",
                timed(lambda: ours(typed=False).feed_array, stream, r, count=array_frames, chunk=16 * CHUNK),
            )
        row("typed, one feed, kept", "", timed(lambda: ours().feed, stream, r, chunk=len(stream)))
        row("dicts, one feed, kept", "", timed(lambda: ours(typed=False).feed, stream, r, chunk=len(stream)))
        row("typed, dropped", None, timed(lambda: ours().feed, stream, r, keep=False))
        row("dicts, dropped", None, timed(lambda: ours(typed=False).feed, stream, r, keep=False))
        row("dicts, one feed, dropped", None, timed(lambda: ours(typed=False).feed, stream, r, keep=False, chunk=len(stream)))
        row("decoding only (_count)", None, timed(lambda: ours(typed=False)._count, stream, r, count=int))
        if name.startswith("OmniTiles"):  # the SDK's parser API
            row("sdk.StreamParser, kept", "", timed(lambda: sdk.StreamParser().feed, stream, r))
            row("sdk.StreamParser, 53 B chunks, kept", "", timed(lambda: sdk.StreamParser().feed, stream, r, chunk=53))
            if sdk_parser is not None:
                row("the SDK's parser, kept", "", timed(lambda: sdk_parser().feed, stream, r))
                row("the SDK's parser, 53 B chunks, kept", "", timed(lambda: sdk_parser().feed, stream, r, chunk=53))
        if any(frames != args.frames for _, _, (frames, _) in rows):
            print(f"{name}: frame counts differ: {[(l, f) for l, _, (f, _) in rows]}", file=sys.stderr)
            ok = False
        rate = {label: frames / cpu for label, _, (frames, cpu) in rows}
        print(f"\n{name}: {args.frames} frames, {len(stream) / 1e6:.1f} MB")
        print(f"  {'':33} {'frames/CPU-s':>13} {'vs plain':>9} {'vs tuned':>9}")
        for label, base, _ in rows:
            line = f"  {label:33} {rate[label] / 1e6:>11.2f} M"
            if base is not None and "plain Python, kept" in rate:
                suffix = ", all read" if base == " all" else ""
                line += f" {rate[label] / rate['plain Python, kept' + suffix]:>8.1f}x"
                line += f" {rate[label] / rate['tuned Python, kept' + suffix]:>8.1f}x"
            print(line)
        if "the SDK's parser, kept" in rate:
            for suffix in ("", ", 53 B chunks"):
                ratio = rate[f"sdk.StreamParser{suffix}, kept"] / rate[f"the SDK's parser{suffix}, kept"]
                print(f"  sdk.StreamParser{suffix} / the SDK's parser: {ratio:.1f}x")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
