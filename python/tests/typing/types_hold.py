"""What the type stubs promise, checked by mypy --strict and pyright --strict
(test_types.py); never run. Every line must type-check."""

from __future__ import annotations

import time
from collections.abc import Mapping
from typing import Any, Optional, Union, assert_type

from robowire import Item, Stats, StreamDecoder, omnitiles, pixy2, telemetrix

CHUNK = b"\xa5"

tile = omnitiles.Decoder(source="tile", layouts=["ble53"])
assert_type(tile, omnitiles.Decoder[omnitiles.Telemetry])
assert_type(tile.feed(CHUNK), list[omnitiles.Telemetry])
assert_type(tile.finish(), list[omnitiles.Telemetry])
for t in tile.feed(CHUNK):
    assert_type(t.m1_pos, Optional[int])
    assert_type(t.m1_pos_mm, Optional[float])
    if t.imu is not None:
        assert_type(t.imu.az, float)
    if t.uwb is not None:
        assert_type(t.uwb[3], Optional[int])

assert_type(omnitiles.Decoder(source="tile", errors=True).feed(CHUNK), list[Union[omnitiles.Telemetry, Item]])
assert_type(omnitiles.Decoder(source="host").feed(CHUNK), list[Item])
assert_type(omnitiles.Decoder().feed(CHUNK), list[Union[omnitiles.Telemetry, Item]])
assert_type(omnitiles.Decoder(source="tile", typed=False).feed(CHUNK), list[dict[str, Any]])
assert_type(omnitiles.DatagramDecoder(source="tile").decode(CHUNK), list[omnitiles.Telemetry])
assert_type(omnitiles.DatagramDecoder(typed=False).decode(CHUNK), list[dict[str, Any]])

assert_type(pixy2.Decoder(source="device").feed(CHUNK), list[pixy2.AnyMessage])
assert_type(pixy2.Decoder(errors=True).feed(CHUNK), list[Union[pixy2.AnyMessage, Item]])
assert_type(pixy2.Decoder(typed=False).feed(CHUNK), list[dict[str, Any]])
assert_type(telemetrix.Decoder(source="pico").feed(CHUNK), list[telemetrix.AnyMessage])
assert_type(telemetrix.Decoder(source="pico", typed=False).feed(CHUNK), list[dict[str, Any]])

# A message class per type: narrowed by isinstance or by its type.
for m in telemetrix.Decoder(source="pico").feed(CHUNK):
    assert_type(m.offset, int)
    assert_type(m.t, Optional[float])
    if m.type == "analog_report":
        assert_type(m, telemetrix.AnalogReport)
        assert_type(m.value, int)
    if isinstance(m, telemetrix.SonarDistance):
        assert_type(m.cm, Union[int, str])
        assert_type(m.m, Optional[int])
    fields: Mapping[str, Any] = m
    base: telemetrix.Message = m
for p in pixy2.Decoder(source="device").feed(CHUNK):
    if isinstance(p, pixy2.Blocks):
        assert_type(p.blocks, list[dict[str, Any]])
        assert_type(p.checksum, bool)

# Every decoder is a StreamDecoder of its items.
decoder: StreamDecoder[omnitiles.Telemetry] = tile
stats = tile.stats
assert_type(stats, Stats)
assert_type(stats["checksum_failures"], int)
frame: bytes = omnitiles.encode({"type": "m1_extend", "speed": 200})
info = omnitiles.field_info("telemetry", "imu.az")
if info is not None:
    assert_type(info["unit"], Optional[str])

# The SDK drop-in.
from robowire.omnitiles.sdk import StreamParser, Telemetry as SdkTelemetry

sdk_frames = StreamParser().feed(CHUNK)
assert_type(sdk_frames, list[SdkTelemetry])
for f in sdk_frames:
    assert_type(f.timestamp, float)
    assert_type(f.m1_pos_mm, Optional[float])
    assert_type(f.m1_adcs, tuple[int, ...])
assert_type(tile.settle(), list[omnitiles.Telemetry])

# A receive-time clock, on every decoder.
assert_type(telemetrix.Decoder(source="pico", clock=time.monotonic).feed(CHUNK), list[telemetrix.AnyMessage])
assert_type(omnitiles.DatagramDecoder(source="tile", clock=lambda: 0.0).decode(CHUNK), list[omnitiles.Telemetry])
