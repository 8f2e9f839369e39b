"""Golden vectors of each protocol (from the wire specifications): each
decodes to one item with the expected fields, and encodes back to its bytes."""

from __future__ import annotations

from typing import Any

import pytest

from robowire import omnitiles, pixy2, telemetrix

from conftest import f32

OMNITILES = [
    ("a5 50 50", {"type": "ping"}),
    ("a5 30 c8 f8", {"type": "m1_extend", "speed": 200}),
    ("a5 30 ff 2f", {"type": "m1_extend", "speed": 255}),
    ("a5 31 ff 30", {"type": "m1_retract", "speed": 255}),
    ("a5 40 c8 08", {"type": "m2_extend", "speed": 200}),
    ("a5 41 c8 09", {"type": "m2_retract", "speed": 200}),
    ("a5 30 00 30", {"type": "m1_extend", "speed": 0}),
    ("a5 32 32", {"type": "m1_brake"}),
    ("a5 42 42", {"type": "m2_brake"}),
    ("a5 33 80 b3", {"type": "m1_set_position", "position": 128}),
    ("a5 43 00 43", {"type": "m2_set_position", "position": 0}),
    ("a5 70 0a fb 14 89", {"type": "base_velocity", "vx": 10, "vy": -5, "omega": 20}),
    ("a5 70 80 7f 00 6f", {"type": "base_velocity", "vx": -128, "vy": 127, "omega": 0}),
    ("a5 70 a5 00 00 15", {"type": "base_velocity", "vx": -91, "vy": 0, "omega": 0}),
    ("a5 71 71", {"type": "base_brake"}),
    ("a5 60 d0 07 e8 03 22", {"type": "telemetry", "layout": "pos7", "m1_pos": 2000, "m2_pos": 1000}),
    (
        "a5 60 d0 07 e8 03 dc 05 c4 09 ff ff b8 0b 91",
        {"type": "telemetry", "layout": "uwb15", "uwb": [1500, 2500, None, 3000]},
    ),
    (
        "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 70",
        {"type": "telemetry", "layout": "uwbtof17", "uwb": [1500, 2500, 3500, 4500], "tof": 321},
    ),
    (
        "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 cd cc cc 3d cd cc 4c 3e cd cc 1c 41 0a d7 23 3c"
        " 0a d7 a3 bc 8f c2 f5 3c d1 07 d2 07 d3 07 d4 07 e9 03 ea 03 6c",
        {
            "type": "telemetry",
            "layout": "ble53",
            "m1_pos": 2000,
            "m2_pos": 1000,
            "uwb": [1500, 2500, 3500, 4500],
            "tof": 321,
            # The f32 values exactly (0.1f32 is 0.10000000149011612).
            "imu": {"ax": f32(0.1), "ay": f32(0.2), "az": f32(9.8), "gx": f32(0.01), "gy": f32(-0.02), "gz": f32(0.03)},
            "m1_adcs": [2001, 2002, 2003, 2004],
            "m2_adcs": [1001, 1002],
        },
    ),
]

PIXY2 = [
    ("ae c1 0e 00", {"type": "get_version", "checksum": False}),
    (
        "af c1 0f 10 0d 03 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00",
        {
            "type": "version",
            "checksum": True,
            "hardware": 0x2200,
            "firmware_major": 3,
            "firmware_minor": 0,
            "firmware_build": 10,
            "firmware_type": "general",
        },
    ),
    ("ae c1 0c 01 00", {"type": "get_resolution"}),
    ("ae c1 10 01 80", {"type": "set_camera_brightness", "brightness": 128}),
    ("ae c1 12 04 f4 01 f4 01", {"type": "set_servos", "pan": 500, "tilt": 500}),
    ("ae c1 12 04 00 00 e8 03", {"type": "set_servos", "pan": 0, "tilt": 1000}),
    ("ae c1 14 03 ff 00 00", {"type": "set_led", "r": 255, "g": 0, "b": 0}),
    ("ae c1 18 00", {"type": "get_fps"}),
    ("ae c1 38 01 03", {"type": "set_vector", "index": 3}),
    ("ae c1 3a 02 a6 ff", {"type": "set_next_turn", "angle": -90}),
    ("ae c1 3e 00", {"type": "reverse_vector"}),
    ("ae c1 02 21 6c 69 6e 65" + " 00" * 29, {"type": "change_prog", "name": "line"}),
    ("af c1 01 04 00 00 00 00 00 00", {"type": "result", "checksum": True, "value": 0}),
    ("af c1 01 04 3d 00 3d 00 00 00", {"type": "result", "value": 61}),
    ("af c1 03 01 fe 00 fe", {"type": "error", "code": "busy"}),
    ("af c1 0d 04 0d 01 3c 01 d0 00", {"type": "resolution", "width": 316, "height": 208}),
    ("af c1 21 00 00 00", {"type": "blocks", "blocks": []}),
    (
        "af c1 21 0e b7 01 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff",
        {
            "type": "blocks",
            "blocks": [
                {"signature": 1, "x": 100, "y": 50, "width": 20, "height": 10, "angle": 0, "index": 3, "age": 255}
            ],
        },
    ),
]

# (source, bytes, fields)
TELEMETRIX = [
    ("host", "01 05", {"type": "get_firmware_version"}),
    ("host", "01 06", {"type": "get_pico_unique_id"}),
    ("host", "02 20 07", {"type": "ping"}),
    ("host", "03 02 19 01", {"type": "digital_write", "pin": 25, "value": 1}),
    ("host", "03 0d 09 0a", {"type": "sonar_new"}),
    ("host", "01 0f", {"type": "stop_all_reports"}),
    ("host", "02 1d 32", {"type": "set_scan_delay"}),
    ("pico", "03 05 01 03", {"type": "firmware_version", "major": 1, "minor": 3}),
    ("pico", "03 02 0a 01", {"type": "digital_report", "pin": 10, "value": 1}),
    ("pico", "04 03 1a 04 c9", {"type": "analog_report", "pin": 26, "value": 1225}),
    ("pico", "05 0b 09 0a 00 77", {"type": "sonar_distance", "trig": 9, "echo": 10, "cm": 119}),
    ("pico", "05 0b 09 0a ff fc", {"type": "sonar_distance", "cm": "no_echo"}),
    ("pico", "03 0e 0e 1e", {"type": "encoder_report", "pin_a": 14, "steps": 30}),
    ("pico", "03 0e 0e e2", {"type": "encoder_report", "pin_a": 14, "steps": -30}),
]


def only_item(decoder: Any, data: bytes) -> dict[str, Any]:
    items = decoder.feed(data) + decoder.finish()
    assert len(items) == 1, items
    assert "error" not in items[0], items
    return items[0]


def check(item: dict[str, Any], data: bytes, fields: dict[str, Any]) -> None:
    assert item["offset"] == 0
    assert item["len"] == len(data)
    assert list(item)[:3] == ["offset", "len", "type"]
    for key, value in fields.items():
        assert item[key] == value, key


@pytest.mark.parametrize("text,fields", OMNITILES, ids=[t for t, _ in OMNITILES])
def test_omnitiles(text: str, fields: dict[str, Any]) -> None:
    data = bytes.fromhex(text)
    layouts = "auto" if fields["type"] != "telemetry" else fields["layout"]
    item = only_item(omnitiles.Decoder(layouts=layouts, typed=False), data)
    check(item, data, fields)
    assert omnitiles.encode(item) == data
    # The spec's fields alone are the whole message for commands.
    if fields["type"] != "telemetry":
        assert omnitiles.encode(fields) == data


@pytest.mark.parametrize("text,fields", PIXY2, ids=[t[:40] for t, _ in PIXY2])
def test_pixy2(text: str, fields: dict[str, Any]) -> None:
    data = bytes.fromhex(text)
    item = only_item(pixy2.Decoder(typed=False), data)
    check(item, data, fields)
    assert pixy2.encode(item) == data


@pytest.mark.parametrize("source,text,fields", TELEMETRIX, ids=[t for _, t, _ in TELEMETRIX])
def test_telemetrix(source: str, text: str, fields: dict[str, Any]) -> None:
    data = bytes.fromhex(text)
    item = only_item(telemetrix.Decoder(source=source, typed=False), data)
    check(item, data, fields)
    assert telemetrix.encode(item) == data


def test_telemetrix_probe_zeros_are_padding() -> None:
    items = telemetrix.Decoder(source="host", typed=False).feed(bytes.fromhex("00 00 00 00 00 00 00 01 05"))
    assert [(i["offset"], i["type"]) for i in items] == [(7, "get_firmware_version")]


def test_pixy2_spi_filler_and_doubled_sync() -> None:
    data = bytes.fromhex("01 01 01 af af c1 01 04 00 00 00 00 00 00")
    items = pixy2.Decoder(source="device", typed=False).feed(data)
    assert [(i["offset"], i["type"], i["value"]) for i in items] == [(4, "result", 0)]


def test_omnitiles_brake_buffer_datagram() -> None:
    buffer = bytes.fromhex("a5 32 32 a5 42 42") + bytes(122)
    items = omnitiles.DatagramDecoder(source="host", typed=False).decode(buffer)
    assert items == [
        {"offset": 0, "len": 3, "type": "m1_brake"},
        {"offset": 3, "len": 3, "type": "m2_brake"},
    ]
