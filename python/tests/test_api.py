"""The Python API: options, bad input, lazy items, random bytes."""

from __future__ import annotations

import inspect
import random
import sys
from collections.abc import Mapping
from typing import Any

import pytest

import robowire
from robowire import omnitiles, pixy2, telemetrix

from conftest import CASES, Case, decode_all

PING = bytes.fromhex("a5 50 50")
EXTEND = bytes.fromhex("a5 30 c8 f8")


# ---------------------------------------------------------------- options


@pytest.mark.parametrize(
    "make,kwargs,words",
    [
        (omnitiles.Decoder, {"source": "robot"}, ["source", "tile", "host", "any", "robot"]),
        (omnitiles.Decoder, {"layouts": "ble52"}, ["layout", "ble53"]),
        (omnitiles.Decoder, {"layouts": ["ble53", "x"]}, ["layout"]),
        (omnitiles.Decoder, {"source": "host", "layouts": "ble53"}, ["layouts", "host"]),
        (omnitiles.DatagramDecoder, {"source": "pico"}, ["source"]),
        (pixy2.Decoder, {"source": "tile"}, ["source", "device"]),
        (telemetrix.Decoder, {"source": "tile"}, ["source", "pico"]),
        (telemetrix.Decoder, {"dialect": "mirte14"}, ["dialect", "mirte13"]),
        (telemetrix.Decoder, {"source": "host", "lenient": True}, ["lenient", "host"]),
    ],
)
def test_bad_options_raise_value_error(make: Any, kwargs: dict[str, Any], words: list[str]) -> None:
    with pytest.raises(ValueError) as raised:
        make(**kwargs)
    for word in words:
        assert word in str(raised.value)


def test_layouts_as_list_or_string_are_the_same() -> None:
    capture = CASES[2].input()
    a = omnitiles.Decoder(source="tile", layouts=["pos7", "uwb15", "ble53", "spi45"]).feed(capture)
    b = omnitiles.Decoder(source="tile", layouts="pos7,uwb15,ble53,spi45").feed(capture)
    assert a == b and len(a) > 100


def test_repr() -> None:
    assert repr(omnitiles.Decoder(source="tile", layouts=["ble53"], errors=True)).startswith(
        "robowire.omnitiles.Decoder("
    )
    assert "dialect" in repr(telemetrix.Decoder())
    assert "checksum_only=True" in repr(pixy2.Decoder(checksum_only=True))


def test_classes_and_docs() -> None:
    for cls in (omnitiles.Decoder, pixy2.Decoder, telemetrix.Decoder):
        assert issubclass(cls, robowire.StreamDecoder)
        assert "source" in (cls.__doc__ or "")
        assert cls.__module__.startswith("robowire.")
    assert omnitiles.Decoder.__module__ == "robowire.omnitiles"
    for function in (omnitiles.encode, pixy2.encode, telemetrix.encode):
        assert "ValueError" in (function.__doc__ or "")
    assert "chunk" in (robowire.StreamDecoder.feed.__doc__ or "")
    if sys.version_info >= (3, 10):  # PyO3 gives classes no text signature on 3.9
        assert omnitiles.Decoder.__text_signature__ == '(source="any", layouts=None, errors=False, lazy=False, typed=None, clock=None)'
    assert str(inspect.signature(telemetrix.encode)) == "(message, /, dialect='mirte13')"
    feed = inspect.signature(robowire.StreamDecoder.feed).parameters["data"]
    assert feed.kind is inspect.Parameter.POSITIONAL_ONLY
    assert robowire.__version__


# ---------------------------------------------------------------- feeding


def test_feed_takes_bytes_like() -> None:
    data = EXTEND + PING
    expected = omnitiles.Decoder().feed(data)
    assert omnitiles.Decoder().feed(bytearray(data)) == expected
    assert omnitiles.Decoder().feed(memoryview(data)) == expected
    assert omnitiles.Decoder().feed(memoryview(b"xx" + data)[2:]) == expected
    assert len(expected) == 2


@pytest.mark.parametrize("bad", ["a5 50 50", 3, None, [0xA5, 0x50, 0x50], 1.5])
def test_feed_refuses_non_bytes(bad: Any) -> None:
    decoder = omnitiles.Decoder()
    with pytest.raises(TypeError, match="bytes"):
        decoder.feed(bad)
    with pytest.raises(TypeError):
        omnitiles.DatagramDecoder().decode(bad)
    assert decoder.stats["bytes"] == 0


def test_a_frame_split_anywhere_comes_out_once() -> None:
    data = b"\x00" + EXTEND + PING
    for cut in range(len(data) + 1):
        decoder = omnitiles.Decoder(source="host")
        items = decoder.feed(data[:cut]) + decoder.feed(data[cut:]) + decoder.finish()
        assert [i["type"] for i in items] == ["m1_extend", "ping"]
        assert [i["offset"] for i in items] == [1, 5]


def test_finish_reports_a_cut_frame_and_resets() -> None:
    decoder = omnitiles.Decoder(source="host", errors=True)
    assert decoder.feed(EXTEND[:2]) == []
    assert decoder.buffered == 2
    assert decoder.finish() == [{"offset": 0, "len": 2, "error": "truncated"}] or decoder.stats["other_rejections"] == 1
    assert decoder.buffered == 0
    assert decoder.feed(PING) == [{"offset": 2, "len": 3, "type": "ping"}]


def test_clear_counts_the_buffered_bytes_as_skipped() -> None:
    decoder = omnitiles.Decoder(source="host")
    decoder.feed(EXTEND[:3])
    decoder.clear()
    assert decoder.buffered == 0
    assert decoder.stats["skipped"] == 3
    assert decoder.feed(PING)[0]["offset"] == 3


def test_errors_flag() -> None:
    data = bytes.fromhex("a5 30 c8 f7") + PING  # a bad checksum, then a ping
    quiet = omnitiles.Decoder(source="host")
    loud = omnitiles.Decoder(source="host", errors=True)
    assert [i["type"] for i in quiet.feed(data)] == ["ping"]
    items = loud.feed(data)
    assert items[0] == {"offset": 0, "error": "checksum", "expected": 0xF8, "found": 0xF7}
    assert items[-1]["type"] == "ping"
    assert quiet.stats == loud.stats
    assert quiet.stats["checksum_failures"] == 1
    assert loud.errors and not quiet.errors


def test_stats_keys() -> None:
    stats = omnitiles.Decoder().stats
    assert list(stats) == [
        "bytes", "frames", "frame_bytes", "skipped", "checksum_failures", "other_rejections", "malformed",
        "superseded",
    ]
    assert isinstance(stats, dict)


def test_stats_old_keys_are_deprecated_aliases() -> None:
    # A bad checksum, an unknown id (a5 99 ...), a ping.
    decoder = omnitiles.Decoder(source="host")
    decoder.feed(bytes.fromhex("a5 30 c8 f7 a5 99 99 a5 50 50"))
    stats = decoder.stats
    assert stats["checksum_failures"] == 1 and stats["other_rejections"] >= 1
    with pytest.warns(DeprecationWarning, match="checksum_failures"):
        assert stats["checksum_errors"] == stats["checksum_failures"]
    with pytest.warns(DeprecationWarning, match="other_rejections"):
        assert stats["rejected"] == stats["other_rejections"] - stats["superseded"]
    assert "rejected" not in stats
    with pytest.raises(KeyError):
        stats["nope"]


# ---------------------------------------------------------------- lazy items


@pytest.mark.filterwarnings("ignore:lazy=True is deprecated:DeprecationWarning")
def test_lazy_item_is_a_read_only_mapping() -> None:
    (item,) = omnitiles.Decoder(lazy=True).feed(EXTEND)
    assert isinstance(item, robowire.Item)
    assert isinstance(item, Mapping)
    assert item.offset == 0
    assert item == {"offset": 0, "len": 4, "type": "m1_extend", "speed": 200}
    assert item != {"offset": 0}
    assert item["speed"] == 200 and "speed" in item and "tof" not in item
    assert item.get("tof") is None and item.get("tof", 7) == 7
    assert list(item) == ["offset", "len", "type", "speed"] == list(item.keys())
    assert list(item.values()) == [0, 4, "m1_extend", 200]
    assert dict(item.items()) == dict(item) == item.to_dict()
    assert len(item) == 4
    with pytest.raises(KeyError):
        item["tof"]
    copy = item.to_dict()
    copy["speed"] = 0
    assert item["speed"] == 200
    assert "m1_extend" in repr(item)
    with pytest.raises(TypeError):
        item["speed"] = 1  # type: ignore[index]


@pytest.mark.filterwarnings("ignore:lazy=True is deprecated:DeprecationWarning")
def test_lazy_items_encode_back() -> None:
    (item,) = omnitiles.Decoder(lazy=True).feed(EXTEND)
    assert omnitiles.encode(item) == EXTEND


# ---------------------------------------------------------------- encoding


@pytest.mark.parametrize(
    "encode,message,words",
    [
        (omnitiles.encode, {"type": "m1_extend", "speed": 256}, ["speed", "255"]),
        (omnitiles.encode, {"type": "m1_extend", "speed": -1}, ["speed"]),
        (omnitiles.encode, {"type": "base_velocity", "vx": 200, "vy": 0, "omega": 0}, ["vx", "127"]),
        (omnitiles.encode, {"type": "m1_extend"}, ["speed"]),
        (omnitiles.encode, {"type": "m1_extend", "speed": 1, "sped": 2}, ["sped"]),
        (omnitiles.encode, {"type": "warp"}, ["warp"]),
        (omnitiles.encode, {"speed": 1}, ["type"]),
        (pixy2.encode, {"type": "set_servos", "pan": 70000, "tilt": 0}, ["pan"]),
        (pixy2.encode, {"type": "set_led", "r": 256, "g": 0, "b": 0}, ["r"]),
        (telemetrix.encode, {"type": "digital_write", "pin": 25, "value": 2}, ["value"]),
        (telemetrix.encode, {"type": "digital_write", "pin": 300, "value": 1}, ["pin"]),
    ],
)
def test_encode_invalid_raises_value_error_naming_the_field(encode: Any, message: dict[str, Any], words: list[str]) -> None:
    with pytest.raises(ValueError) as raised:
        encode(message)
    for word in words:
        assert word in str(raised.value), str(raised.value)


@pytest.mark.parametrize("encode", [omnitiles.encode, pixy2.encode, telemetrix.encode])
@pytest.mark.parametrize("bad", ["ping", 3, None, [("type", "ping")]])
def test_encode_refuses_non_mappings(encode: Any, bad: Any) -> None:
    with pytest.raises(TypeError):
        encode(bad)


def test_marked_quirks_encode_to_the_frames_they_came_from() -> None:
    # What a real host sends and the encoder refuses without the decoder's marker.
    for module, frame in ((pixy2, "ae c1 20 02 00 00"), (telemetrix, "03 02 19 02")):
        data = bytes.fromhex(frame)
        (item,) = module.Decoder().feed(data)
        assert item.get("quirk"), item
        assert module.encode(item) == data
        unmarked = {k: v for k, v in item.items() if k != "quirk"}
        with pytest.raises(ValueError, match="quirk"):
            module.encode(unmarked)


def test_telemetrix_encode_takes_a_dialect() -> None:
    message = {"type": "get_firmware_version"}
    assert telemetrix.encode(message, dialect="upstream11") == bytes.fromhex("01 05")
    with pytest.raises(ValueError, match="dialect"):
        telemetrix.encode(message, dialect="nope")


def test_every_decoded_frame_encodes_back_to_its_bytes(case: Case) -> None:
    if case.datagrams:
        pytest.skip("datagrams are checked as streams")
    data = case.input()
    encode = {omnitiles.Decoder: omnitiles.encode, pixy2.Decoder: pixy2.encode}.get(case.make)
    if encode is None:
        dialect = case.kwargs.get("dialect", "mirte13")
        encode = lambda message: telemetrix.encode(message, dialect=dialect)  # noqa: E731
    frames = [item for item in decode_all(case, errors=False)]
    for item in frames:
        assert encode(item) == data[item["offset"] : item["offset"] + item["len"]], item


# ---------------------------------------------------------------- robustness


def _all_decoders(case: Case) -> Any:
    return case.decoder(errors=True)


def test_random_bytes_never_crash() -> None:
    rng = random.Random(14)
    for case in CASES:
        for trial in range(30):
            data = rng.randbytes(rng.randrange(0, 600))
            decoder = _all_decoders(case)
            if case.datagrams:
                items = decoder.decode(data)
            else:
                items = []
                start = 0
                while start < len(data):
                    step = rng.randrange(1, 80)
                    items += decoder.feed(data[start : start + step])
                    start += step
                items += decoder.finish()
            for item in items:
                assert ("type" in item) != ("error" in item)
                assert 0 <= item["offset"] < max(len(data), 1)
            stats = decoder.stats
            assert stats["bytes"] == len(data) == stats["frame_bytes"] + stats["skipped"]


def test_corrupted_captures_never_crash_and_split_alike() -> None:
    rng = random.Random(53)
    for case in CASES:
        if case.datagrams:
            continue
        data = bytearray(case.input())
        for _ in range(3):
            corrupt = bytearray(data)
            for _ in range(rng.randrange(1, 20)):
                corrupt[rng.randrange(len(corrupt))] = rng.randrange(256)
            whole = case.decoder()
            expected = whole.feed(bytes(corrupt)) + whole.finish()
            pieces = case.decoder()
            got: list[Any] = []
            start = 0
            while start < len(corrupt):
                step = rng.randrange(1, 200)
                got += pieces.feed(bytes(corrupt[start : start + step]))
                start += step
            got += pieces.finish()
            assert got == expected
            assert pieces.stats == whole.stats
