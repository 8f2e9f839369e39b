"""Typed items (the default): an omnitiles.Telemetry per telemetry frame,
a robowire.Item for every other message and rejection; attributes, keys,
to_dict(), ==, repr, and the same items however the bytes are split."""

from __future__ import annotations

import gc
import math
import struct
import warnings
from pathlib import Path
from collections.abc import Mapping
from typing import Any

import pytest

import robowire
from robowire import omnitiles, pixy2, telemetrix

from conftest import CASES, Case, _module_of, decode_all

POS7 = bytes.fromhex("a5 60 d0 07 ff ff 35")
UWB15 = bytes.fromhex("a5 60 d0 07 e8 03 dc 05 c4 09 ff ff b8 0b 91")


def attribute_form(value: Any) -> Any:
    """A dict-form value as the typed item's attribute gives it: lists are tuples."""
    return tuple(value) if isinstance(value, list) else value


def expected_class(case: Case, d: dict[str, Any]) -> type:
    """The class of the typed item whose dict is ``d``: OmniTiles telemetry's,
    a Telemetrix or Pixy2 message's own, else (commands, rejections) Item."""
    if d.get("type") == "telemetry":
        return omnitiles.Telemetry
    module = _module_of(case.make)
    if module is omnitiles or "type" not in d:
        return robowire.Item
    return getattr(module, "".join(w.capitalize() for w in d["type"].split("_")))


def test_typed_items_equal_the_dicts(case: Case) -> None:
    typed = decode_all(case, typed=True)
    dicts = decode_all(case)
    assert len(typed) == len(dicts) > 0
    assert typed == dicts and dicts == typed
    assert [item.to_dict() for item in typed] == dicts
    for item, d in zip(typed, dicts):
        assert type(item) is expected_class(case, d)
        for key, value in d.items():
            assert item[key] == attribute_form(value) or item[key] == value, key
            assert getattr(item, key) == item[key], key
            assert key in item


def test_fields_read_before_any_dict_is_built(case: Case) -> None:
    # A field read alone is made from the frame in Rust (no dict): each
    # must be the dict's value, read on items nothing else has touched.
    dicts = decode_all(case)
    for key_of in (lambda d: list(d), lambda d: list(d)[::-1]):
        fresh = decode_all(case, typed=True)
        for item, d in zip(fresh, dicts):
            if isinstance(item, omnitiles.Telemetry):
                continue
            for key in key_of(d):
                assert item.get(key) == d[key], key
                assert key in item
                assert item[key] == d[key]
                if key not in ("offset", "items", "keys", "values", "get"):
                    assert getattr(item, key) == d[key], key
            assert item.get("no such field") is None and "no such field" not in item
            with pytest.raises(KeyError):
                item["no such field"]
        assert fresh == dicts


def test_a_field_read_builds_no_dict() -> None:
    # Reading one field keeps no dict alive: the items held take no more
    # memory after the read than before (a dict each took ~600 B).
    import tracemalloc

    capture = (Path(__file__).parents[2] / "tests" / "data" / "telemetrix_reports.bin").read_bytes()
    items = telemetrix.Decoder(source="pico").feed(capture * 20)
    assert len(items) > 1000
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        kinds = {item.type for item in items} | {item.get("pin") for item in items}
        grown = tracemalloc.get_traced_memory()[0] - before
    finally:
        tracemalloc.stop()
    assert "digital_report" in kinds
    assert grown / len(items) < 50, f"{grown / len(items):.0f} B per item"


def test_receive_time_read_before_any_dict_is_built() -> None:
    frame = bytes.fromhex("05 0b 09 0a 00 77")
    (timed,) = telemetrix.Decoder(source="pico").feed(frame, t=12.5)
    assert (timed.t, timed["t"], "t" in timed) == (12.5, 12.5, True)
    assert list(timed)[0] == "t"
    (untimed,) = telemetrix.Decoder(source="pico").feed(frame)
    assert "t" not in untimed and untimed.get("t") is None


@pytest.mark.parametrize("chunk", [1, 5, 53, 4096])
def test_typed_items_do_not_depend_on_chunking(case: Case, chunk: int) -> None:
    if case.datagrams:
        pytest.skip("datagrams are decoded whole")
    assert decode_all(case, chunk, typed=True) == decode_all(case, typed=True)


def test_telemetry_attributes() -> None:
    data = CASES[1].input()
    (t, *_) = omnitiles.Decoder(source="tile", layouts="ble53").feed(data)
    assert isinstance(t, omnitiles.Telemetry)
    assert (t.offset, t.len, t.type, t.layout) == (0, 53, "telemetry", "ble53")
    assert (t.m1_pos, t.m2_pos, t.tof) == (1104, 2852, 448)
    assert t.uwb == (4579, 3151, 3112, None)
    assert t.m1_adcs == (1103, 1107, 2255, 2252) and t.m2_adcs == (2854, 2851)
    assert isinstance(t.imu, omnitiles.Imu)
    # The f32's exact value, as struct reads it.
    assert t.imu.ax == struct.unpack("<f", data[16:20])[0] == t["imu"]["ax"]
    assert t.imu == t.to_dict()["imu"] and t.imu.to_dict() == t.to_dict()["imu"]
    assert list(t.imu.keys()) == ["ax", "ay", "az", "gx", "gy", "gz"]
    assert t.keys() == list(t.to_dict())
    assert t.get("nope", 5) == 5 and t.get("tof") == 448


def test_groups_not_carried_and_no_reading() -> None:
    (t,) = omnitiles.Decoder(source="tile", layouts="pos7").feed(POS7)
    assert (t.m1_pos, t.m2_pos) == (2000, None)  # 0xffff: no reading
    assert t.uwb is None and t.tof is None and t.imu is None and t.m1_adcs is None
    assert "uwb" not in t and "m2_pos" in t
    with pytest.raises(KeyError):
        t["uwb"]
    assert t.to_dict() == {"offset": 0, "len": 7, "type": "telemetry", "layout": "pos7", "m1_pos": 2000, "m2_pos": None}
    (u,) = omnitiles.Decoder(source="tile", layouts="uwb15").feed(UWB15)
    assert u.uwb == (1500, 2500, None, 3000) and "tof" not in u


def test_repr_eq_and_immutability() -> None:
    (t,) = omnitiles.Decoder(source="tile", layouts="uwb15").feed(UWB15)
    assert repr(t) == (
        "Telemetry(offset=0, len=15, layout='uwb15', m1_pos=2000, m2_pos=1000, uwb=(1500, 2500, None, 3000))"
    )
    (same,) = omnitiles.Decoder(source="tile", layouts="uwb15").feed(UWB15)
    assert t == same and not (t != same)
    assert t != omnitiles.Decoder(source="tile", layouts="uwb15").feed(b"\x00" + UWB15)[0]
    assert (t == 3) is False
    with pytest.raises(AttributeError):
        t.m1_pos = 5  # type: ignore[misc]
    # One object per frame, not tracked by the garbage collector.
    assert not gc.is_tracked(t)


def test_imu_compares_bit_patterns() -> None:
    body = bytes([0x60]) + bytes(14) + struct.pack("<6I", 0x7FC00000, 0, 0, 0, 0, 0) + bytes(12)
    frame = b"\xa5" + body + bytes([sum(body) & 0xFF])
    decoder = omnitiles.Decoder(source="tile", layouts="ble53")
    (a,) = decoder.feed(frame)
    (b,) = decoder.feed(frame)
    assert math.isnan(a.imu.ax) and a.imu == b.imu
    assert "Imu(ax=nan, ay=0.0" in repr(a.imu)


def test_other_messages_are_items_with_attributes() -> None:
    (cmd,) = omnitiles.Decoder().feed(bytes.fromhex("a5 70 0a fb 14 89"))
    assert isinstance(cmd, robowire.Item)
    assert (cmd.type, cmd.vx, cmd.vy, cmd.omega, cmd.offset) == ("base_velocity", 10, -5, 20, 0)
    with pytest.raises(AttributeError, match="base_velocity item has no field speed"):
        cmd.speed
    (report,) = telemetrix.Decoder(source="pico").feed(bytes.fromhex("05 0b 09 0a 00 77"))
    assert (report.type, report.trig, report.echo, report.cm) == ("sonar_distance", 9, 10, 119)
    (result,) = pixy2.Decoder(source="device").feed(bytes.fromhex("af c1 01 04 3d 00 3d 00 00 00"))
    assert (result.type, result.value, result.checksum) == ("result", 61, True)
    (bad, ping) = omnitiles.Decoder(source="host", errors=True).feed(bytes.fromhex("a5 30 c8 f7 a5 50 50"))
    assert (bad.error, bad.expected, bad.found) == ("checksum", 0xF8, 0xF7)
    assert ping.type == "ping"


def test_telemetrix_items_keep_frames_of_every_length_and_their_attribution() -> None:
    # An item keeps a short frame in place and a long one on the heap: I2C
    # read reports of 8 to 64 bytes cross the limit. A frame valid both ways
    # keeps `also`, and MODULE_DATA the module type an earlier MODULE_NEW gave.
    frames = [
        telemetrix.encode({"type": "i2c_read_report", "port": 0, "msg_id": 3, "reg": 117, "data": list(range(n))})
        for n in range(1, 58)
    ]
    data = bytes.fromhex("03 02 19 01") + b"".join(frames)
    items = telemetrix.Decoder(source="any").feed(data)
    dicts = telemetrix.Decoder(source="any", typed=False).feed(data)
    assert len(items) == 58 and items == dicts and [i.to_dict() for i in items] == dicts
    assert items[0].also == "digital_write"
    for item, frame in zip(items[1:], frames):
        assert len(item.data) == frame[5] and telemetrix.encode(item) == frame
    capture = bytes.fromhex("0A 21 01 00 01 00 01 00 02 01 02 09 22 00 01 01 00 2E E0 01 F4")
    (_, angle) = telemetrix.Decoder(source="host").feed(capture)
    assert (angle.module_type, angle.message["subtype"]) == ("hiwonder_servo", "set_angle")


@pytest.mark.skipif(not Path("/proc/self/statm").exists(), reason="reads the resident size from /proc")
def test_a_kept_telemetrix_report_costs_little_memory() -> None:
    # docs/python.md: about 150 B a kept report (428 B when each held the
    # library's 256-byte MessageBuf). Resident pages grown per item kept.
    def resident() -> int:
        return int(Path("/proc/self/statm").read_text().split()[1]) * 4096

    data = bytes.fromhex("04 03 1a 04 c9 05 0b 09 0a 00 77 03 02 19 01") * 40_000
    gc.collect()
    before = resident()
    items = telemetrix.Decoder(source="pico").feed(data)
    grown = (resident() - before) / len(items)
    assert len(items) == 120_000 and grown < 250, f"{grown:.0f} B per kept report"


def test_typed_items_encode_back() -> None:
    data = CASES[0].input()
    for item in omnitiles.Decoder().feed(data):
        assert omnitiles.encode(item) == data[item.offset : item.offset + item.len]
    (report,) = telemetrix.Decoder(source="pico").feed(bytes.fromhex("04 03 1a 04 c9"))
    assert telemetrix.encode(report) == bytes.fromhex("04 03 1a 04 c9")


def test_options() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        decoder = omnitiles.Decoder(source="tile")
        assert decoder.typed and not decoder.lazy
        assert repr(decoder) == 'robowire.omnitiles.Decoder(source="tile")'
        assert omnitiles.DatagramDecoder().typed
        for make in (omnitiles.Decoder, omnitiles.DatagramDecoder, pixy2.Decoder, telemetrix.Decoder):
            dicts = make(typed=False)
            assert not dicts.typed and not dicts.lazy
            assert repr(dicts).endswith("typed=False)")
    # The spelling from before typed items were the default still works, with a warning.
    for make in (omnitiles.Decoder, omnitiles.DatagramDecoder, pixy2.Decoder, telemetrix.Decoder):
        with pytest.warns(DeprecationWarning, match="typed=True is deprecated: typed items are the default"):
            assert make(typed=True).typed
    with pytest.raises(ValueError, match="typed=True"):
        telemetrix.Decoder(lazy=True, typed=True)
    with pytest.warns(DeprecationWarning, match="lazy=True is deprecated"):
        assert pixy2.Decoder(lazy=True).lazy


def test_telemetry_and_imu_are_mappings() -> None:
    data = CASES[0].input()
    (t, *_) = omnitiles.Decoder(source="tile", layouts="ble53").feed(data)
    assert isinstance(t, Mapping) and isinstance(t.imu, Mapping)
    keys = ["offset", "len", "type", "layout", "m1_pos", "m2_pos", "uwb", "tof", "imu", "m1_adcs", "m2_adcs"]
    assert list(t) == t.keys() == keys and len(t) == len(keys)
    assert t.values() == [t[key] for key in keys]
    assert t.items() == list(zip(keys, t.values()))
    assert dict(t) == dict(t.items()) and dict(t)["imu"] is not None
    assert 5 not in t and None not in t and "tof" in t
    imu = t.imu
    assert list(imu) == ["ax", "ay", "az", "gx", "gy", "gz"] and len(imu) == 6
    assert dict(imu) == imu.to_dict() and imu.values() == [imu[k] for k in imu]
    assert 0 not in imu
    (short,) = omnitiles.Decoder(source="tile", layouts="pos7").feed(POS7)
    assert list(short) == ["offset", "len", "type", "layout", "m1_pos", "m2_pos"] and "imu" not in short
