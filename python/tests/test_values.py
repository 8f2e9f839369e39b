"""Items hold Python's own values: an f32 is the float of exactly its value
(NaN and infinities included, bit for bit), a 0xFFFF reading is None, and
such items encode back to their frames and match the tool's text."""

from __future__ import annotations

import json
import math
import struct
import subprocess
from pathlib import Path

import pytest

from robowire import omnitiles

from conftest import assert_same_item, cli_binary, f32_bits

# ax, ay, az, gx, gy, gz as f32 bit patterns: the quiet NaN, a signalling NaN
# with its sign set, both infinities, negative zero, the smallest subnormal.
IMU_BITS = [0x7FC00000, 0xFF800001, 0x7F800000, 0xFF800000, 0x80000000, 0x00000001]


def ble53(imu_bits: list[int], uwb: list[int], tof: int) -> bytes:
    payload = struct.pack("<2H", 2000, 0xFFFF) + struct.pack("<4H", *uwb) + struct.pack("<H", tof)
    payload += struct.pack("<6I", *imu_bits) + struct.pack("<6H", 1, 2, 3, 4, 5, 6)
    body = bytes([0x60]) + payload
    return bytes([0xA5]) + body + bytes([sum(body) & 0xFF])


FRAME = ble53(IMU_BITS, [1500, 0xFFFF, 3500, 4500], 0xFFFF)


def test_f32_is_its_exact_value() -> None:
    frame = ble53([0x3DCCCCCD] * 6, [1, 2, 3, 4], 5)  # 0.1f32
    (item,) = omnitiles.Decoder(source="tile", layouts="ble53", typed=False).feed(frame)
    assert item["imu"]["ax"] == 0.10000000149011612
    assert type(item["imu"]["ax"]) is float


def test_non_finite_and_no_reading_are_python_values() -> None:
    assert len(FRAME) == 53
    (item,) = omnitiles.Decoder(source="tile", layouts="ble53", typed=False).feed(FRAME)
    imu = item["imu"]
    assert [f32_bits(imu[k]) for k in ("ax", "ay", "az", "gx", "gy", "gz")] == IMU_BITS
    assert all(isinstance(v, float) for v in imu.values())
    assert math.isnan(imu["ax"]) and math.isnan(imu["ay"])
    assert imu["az"] == math.inf and imu["gx"] == -math.inf
    assert imu["gy"] == 0.0 and math.copysign(1.0, imu["gy"]) == -1.0
    assert imu["gz"] == 2.0**-149
    assert item["m2_pos"] is None and item["tof"] is None
    assert item["uwb"] == [1500, None, 3500, 4500]


def test_native_values_encode_back_bit_for_bit() -> None:
    (item,) = omnitiles.Decoder(source="tile", layouts="ble53", typed=False).feed(FRAME)
    assert omnitiles.encode(item) == FRAME


@pytest.mark.skipif(cli_binary() is None, reason="ROBOWIRE_CLI does not name the robowire tool")
def test_native_values_are_the_tools_text(tmp_path: Path) -> None:
    capture = tmp_path / "nan.bin"
    capture.write_bytes(FRAME)
    run = subprocess.run(
        [str(cli_binary()), "decode", "omnitiles", "--from", "tile", "--layout", "ble53", str(capture)],
        capture_output=True,
        check=True,
    )
    (line,) = [json.loads(text) for text in run.stdout.decode().splitlines()]
    assert line["imu"]["ax"] == "nan:0x7fc00000" and line["imu"]["az"] == "inf"
    (item,) = omnitiles.Decoder(source="tile", layouts="ble53", typed=False).feed(FRAME)
    assert_same_item(item, line)


def test_encode_refuses_a_float_out_of_f32_range() -> None:
    (item,) = omnitiles.Decoder(source="tile", layouts="ble53", typed=False).feed(FRAME)
    item["imu"]["az"] = 1e39
    with pytest.raises(ValueError, match="imu.az"):
        omnitiles.encode(item)
