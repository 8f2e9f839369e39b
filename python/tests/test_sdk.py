"""robowire.omnitiles.sdk: the OmniTiles SDK's parser API over robowire's
engine, used as the SDK's own docs and tests use its parser; and
``settle()`` on the native decoders."""

from __future__ import annotations

import copy
import pickle
import random
import struct

from robowire import omnitiles
from robowire.omnitiles import sdk
from robowire.omnitiles.sdk import StreamParser

from conftest import DATA


def packet(payload: bytes) -> bytes:
    """A telemetry frame as the SDK's tests build one: a5 60, payload, sum."""
    body = bytes([0x60]) + payload
    return b"\xa5" + body + bytes([sum(body) & 0xFF])


def test_each_layout_as_the_sdk_tests_feed_it() -> None:
    parser = StreamParser()
    [frame] = parser.feed(packet(struct.pack("<HH", 2048, 1024)))
    assert (frame.m1_pos_adc, frame.m2_pos_adc) == (2048, 1024)
    assert frame.m1_pos_mm == (2048 / 4095) * 150.0 and frame.m2_pos_mm == (1024 / 4095) * 100.0
    assert (frame.uwb_mm, frame.tof_mm, frame.imu, frame.m1_adcs, frame.m2_adcs) == (None, None, None, (), ())

    [frame] = parser.feed(packet(struct.pack("<HH4H", 1, 2, 100, 0xFFFF, 300, 400)))
    assert frame.uwb_mm == (100, None, 300, 400) and frame.tof_mm is None

    [frame] = parser.feed(packet(struct.pack("<HH4HH", 1, 2, 100, 200, 300, 400, 0xFFFF)))
    assert frame.uwb_mm == (100, 200, 300, 400) and frame.tof_mm is None

    imu = (0.5, -1.25, 9.75, 0.125, -0.25, 2.0)
    payload = struct.pack("<HH4HH6f4H2H", 10, 20, 1, 2, 3, 4, 550, *imu, 11, 12, 13, 14, 21, 22)
    raw = packet(payload)
    [frame] = parser.feed(raw)
    assert frame.tof_mm == 550 and frame.m1_adcs == (11, 12, 13, 14) and frame.m2_adcs == (21, 22)
    assert frame.imu is not None
    assert (frame.imu.ax, frame.imu.ay, frame.imu.az, frame.imu.gx, frame.imu.gy, frame.imu.gz) == imu
    assert frame.raw == raw and frame.layout == "ble53"
    assert parser.stats["frames"] == 4


def test_a_host_loop_as_the_sdk_tile_runs_it() -> None:
    """The SDK's Tile hands each notification to ``feed`` and keeps the latest
    frame; the values equal robowire's own items field for field."""
    data = (DATA / "ble_telemetry.bin").read_bytes()
    parser = StreamParser()
    frames: list[sdk.Telemetry] = []
    latest = None
    for start in range(0, len(data), 244):  # a BLE MTU's worth at a time
        for frame in parser.feed(data[start : start + 244]):
            latest = frame
            frames.append(frame)
    native = omnitiles.Decoder(source="tile").feed(data)
    assert latest is frames[-1] and len(frames) == len(native) > 0
    for ours, t in zip(frames, native):
        assert (ours.m1_pos_adc, ours.m2_pos_adc, ours.uwb_mm, ours.tof_mm) == (t.m1_pos, t.m2_pos, t.uwb, t.tof)
        assert (ours.m1_pos_mm, ours.imu, ours.raw, ours.offset) == (t.m1_pos_mm, t.imu, t.raw, t.offset)
        assert ours.m1_adcs == (t.m1_adcs or ()) and ours.m2_adcs == (t.m2_adcs or ())


def test_timestamp_is_the_clock_at_each_feed() -> None:
    ticks = iter([10.0, 20.0])
    parser = StreamParser(clock=lambda: next(ticks))
    [a] = parser.feed(packet(struct.pack("<HH", 1, 2)))
    [b] = parser.feed(packet(struct.pack("<HH", 3, 4)))
    assert (a.timestamp, b.timestamp) == (10.0, 20.0)
    default = StreamParser().feed(packet(struct.pack("<HH", 1, 2)))[0]
    import time

    assert abs(default.timestamp - time.monotonic()) < 5


def test_strokes_are_configurable() -> None:
    parser = StreamParser(m1_stroke_mm=200.0, m2_stroke_mm=50.0, adc_max=4096.0)
    [frame] = parser.feed(packet(struct.pack("<HH", 2048, 2048)))
    assert (frame.m1_pos_mm, frame.m2_pos_mm) == (100.0, 25.0)


def test_no_reading_positions_are_none() -> None:
    [frame] = StreamParser().feed(packet(struct.pack("<HH", 0xFFFF, 7)))
    assert frame.m1_pos_adc is None and frame.m1_pos_mm is None and frame.m2_pos_adc == 7


def false_prefix_frames(count: int) -> list[bytes]:
    """53-byte frames whose first 7 bytes pass as a 7-byte frame too."""
    rng = random.Random(5)
    found = []
    while len(found) < count:
        payload = bytes([0x10, 0x04, 0x20, 0x08]) + bytes(rng.randrange(256) for _ in range(46))
        raw = packet(payload)
        if sum(raw[1:6]) & 0xFF == raw[6]:
            found.append(raw)
    return found


def test_no_false_short_frame_at_a_chunk_boundary() -> None:
    """Each of these frames is cut right after its 7-byte prefix, which
    checksums: the SDK's parser takes the prefix; robowire waits for the rest."""
    frames = false_prefix_frames(20)
    parser = StreamParser()
    out = []
    for raw in frames:
        out += parser.feed(b"\x00" * 3 + raw[:7])  # the cut lands mid-chunk, after noise
        out += parser.feed(raw[7:])
    assert [f.raw for f in out] == frames


def test_a_stray_a5_does_not_stall_the_parser() -> None:
    """A stray start byte before every frame: the SDK's feed stops draining
    at each one; robowire skips it and goes on."""
    raws = [t.raw for t in omnitiles.Decoder(source="tile").feed((DATA / "ble_telemetry.bin").read_bytes())]
    noisy = b"".join(b"\xa5\x01" + raw for raw in raws)
    frames = StreamParser().feed(noisy)
    assert [f.raw for f in frames] == raws


def test_items_are_values() -> None:
    ticks = iter([1.5, 1.5])
    parser = StreamParser(clock=lambda: next(ticks))
    [a] = parser.feed(packet(struct.pack("<HH", 5, 6)))
    again = pickle.loads(pickle.dumps(a))
    assert again == a and hash(again) == hash(a) and copy.deepcopy(a) == a
    [b] = parser.feed(packet(struct.pack("<HH", 5, 6)))
    assert b != a  # another offset
    assert "m1_pos_adc=5" in repr(a)


def test_settle_hands_out_a_short_frame_that_ends_a_read() -> None:
    pos7 = packet(struct.pack("<HH", 2000, 1000))
    decoder = omnitiles.Decoder(source="tile")
    # Two back-to-back frames in one read: the second might be a longer
    # layout's start until the next byte (or settle) decides.
    assert [t.offset for t in decoder.feed(pos7 + pos7)] == [0]
    assert [t.offset for t in decoder.settle()] == [7]
    assert decoder.settle() == [] and decoder.buffered == 0
    # Half a frame stays for its rest; nothing is rejected.
    assert decoder.feed(pos7[:3]) == [] and decoder.settle() == []
    assert [t.offset for t in decoder.feed(pos7[3:] + pos7)] == [14]
    assert decoder.stats["checksum_failures"] + decoder.stats["other_rejections"] == 0
    parser = StreamParser()
    assert len(parser.feed(pos7 + pos7)) == 1 and len(parser.settle()) == 1


def test_the_migration_tables_name_real_fields() -> None:
    """docs/python.md's two tables: every field the drop-in's table names is
    an attribute of sdk.Telemetry; in the move to the native decoder, every
    ``t.name`` on the SDK's side is one of the SDK's fields (which the
    drop-in has, by the first table) and every one on robowire's side an
    attribute of omnitiles.Telemetry."""
    import re

    from conftest import REPO

    text = (REPO / "docs" / "python.md").read_text()
    section = text[text.index("## Moving an OmniTiles SDK host loop") : text.index("## Benchmark")]
    rows = [line for line in section.splitlines() if line.startswith("| ") and "---" not in line]
    [(frame,)] = [StreamParser().feed(packet(struct.pack("<HH", 1, 2)))]
    checked = 0
    for row in rows:
        cells = [c.strip() for c in row.strip("|").split("|")]
        if cells[0] in ("field", "OmniTiles SDK"):
            continue
        if len(cells) == 2 and not cells[0].startswith("`t."):
            for name in re.findall(r"`(\w+)`", cells[0]):  # the drop-in's fields
                assert hasattr(frame, name), name
                checked += 1
        else:
            for name in re.findall(r"`t\.(\w+)`", cells[0]):
                assert hasattr(frame, name), name
                checked += 1
            for name in re.findall(r"`t\.(\w+)`", cells[1]):
                assert hasattr(omnitiles.Telemetry, name), name
                checked += 1
    assert checked >= 30
