"""A user's mistakes the type stubs catch: mypy --strict and pyright --strict
must each report an error on every line marked ``# mistake`` and on no other
(test_types.py); never run."""

from __future__ import annotations

from robowire import omnitiles, pixy2, telemetrix
from robowire.omnitiles.sdk import StreamParser

tile = omnitiles.Decoder(source="tile")
for t in tile.feed(b""):
    az: float = t.imu.az  # mistake: imu is None in the 7, 15 and 17-byte layouts
    pos: int = t.m1_pos  # mistake: 0xFFFF (no reading) is None
    imu: int = t.imu  # mistake: an Imu, not an int
    t.m1_pos = 5  # mistake: items are read-only
    tof_cm = t.tof / 10  # mistake: tof may be None

dicts = omnitiles.Decoder(source="tile", typed=False)
for d in dicts.feed(b""):
    d.m1_pos  # mistake: a dict has keys, not attributes

stats = tile.stats
checksum = stats["checksum_errors"]  # mistake: the 0.2 name, deprecated
omnitiles.Decoder(source="pico")  # mistake: the Pico is telemetrix's source
telemetrix.Decoder(dialect="mirte14")  # mistake: no such dialect
tile.feed("a5 30 c8 f8")  # mistake: text, not bytes
for frame in StreamParser().feed(b""):
    mm: float = frame.m1_pos_mm  # mistake: None for a 0xFFFF position, unlike the SDK
for m in telemetrix.Decoder(source="pico").feed(b""):
    if isinstance(m, telemetrix.AnalogReport):
        volts: str = m.value  # mistake: an ADC count is an int
    if m.type == "sonar_distance":
        metres: int = m.m  # mistake: only mirte 1.2 reports whole metres
for p in pixy2.Decoder(source="device").feed(b""):
    width: int = p.width  # mistake: only a resolution response has a width
omnitiles.Decoder(source="tile", typed=True)  # mistake: deprecated, typed items are the default
telemetrix.Decoder(lazy=True)  # mistake: deprecated, items read a field without a dict
pixy2.Decoder(clock=1.5)  # mistake: a clock is a callable that returns seconds
