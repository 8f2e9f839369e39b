"""Items behave like Python values: pickle, copy and deepcopy give equal
items (bit for bit for telemetry), Telemetry and Imu hash, and a decoder
refuses to be copied with a reason."""

from __future__ import annotations

import copy
import json
import math
import pickle
import struct

import pytest

from robowire import omnitiles, pixy2, telemetrix

from conftest import CASES, DATA, Case, decode_all


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.name)
def test_every_item_pickles_and_copies_equal(case: Case) -> None:
    items = decode_all(case, typed=True)
    assert items
    for item in items:
        for again in (pickle.loads(pickle.dumps(item)), copy.copy(item), copy.deepcopy(item)):
            assert type(again) is type(item)
            assert again == item and again.to_dict() == item.to_dict()
            assert again.offset == item.offset
    # All at once, as a list a host keeps (the pickle protocol's own path).
    assert pickle.loads(pickle.dumps(items, protocol=pickle.HIGHEST_PROTOCOL)) == items


def ble53(ax_bits: int) -> bytes:
    body = bytes([0x60]) + bytes(14) + struct.pack("<6I", ax_bits, 0, 0, 0, 0, 0) + bytes(12)
    return b"\xa5" + body + bytes([sum(body) & 0xFF])


def test_telemetry_keeps_its_bytes_through_pickle() -> None:
    # A signalling NaN: a float round trip through f64 would quiet it.
    frame = ble53(0x7FA00001)
    (t,) = omnitiles.Decoder(source="tile", layouts="ble53").feed(frame)
    assert t.raw == frame
    again = pickle.loads(pickle.dumps(t))
    assert again.raw == frame and again == t and hash(again) == hash(t)
    imu = pickle.loads(pickle.dumps(t.imu))
    assert imu == t.imu and hash(imu) == hash(t.imu) and math.isnan(imu.ax)
    assert copy.copy(t) is t and copy.deepcopy(t) is t  # immutable


def test_raw_is_the_frame_received() -> None:
    data = (DATA / "ble_telemetry.bin").read_bytes()
    items = omnitiles.Decoder(source="tile", layouts="auto,spi45").feed(data)
    assert items
    for t in items:
        assert t.raw == data[t.offset : t.offset + t.len]


def test_hash_and_equality() -> None:
    data = (DATA / "ble_telemetry.bin").read_bytes()
    first = omnitiles.Decoder(source="tile", layouts="ble53").feed(data)
    second = omnitiles.Decoder(source="tile", layouts="ble53").feed(data)
    assert len(set(first) | set(second)) == len(first)  # equal items hash alike
    assert {t.imu for t in first} == {t.imu for t in second}
    assert {t: t.offset for t in first}[second[5]] == second[5].offset
    # An Item equals its dict, which is unhashable: so is the Item.
    (ping,) = omnitiles.Decoder(source="host").feed(bytes.fromhex("a5 50 50"))
    assert ping == {"offset": 0, "len": 3, "type": "ping"}
    with pytest.raises(TypeError):
        hash(ping)


def test_to_dict_through_json_encodes_the_same_frame() -> None:
    for name in ("ble_telemetry.bin", "spi_telemetry.bin", "host_commands.bin"):
        data = (DATA / name).read_bytes()
        for item in omnitiles.Decoder(layouts="auto,spi45").feed(data):
            line = json.dumps(item.to_dict())
            assert omnitiles.encode(json.loads(line)) == data[item.offset : item.offset + item.len], line


@pytest.mark.parametrize(
    "decoder",
    [omnitiles.Decoder(), omnitiles.DatagramDecoder(), pixy2.Decoder(), telemetrix.Decoder(typed=False)],
    ids=repr,
)
def test_decoders_refuse_to_be_copied_and_say_why(decoder: object) -> None:
    for copier in (pickle.dumps, copy.copy, copy.deepcopy):
        with pytest.raises(TypeError, match="state of one live stream"):
            copier(decoder)
