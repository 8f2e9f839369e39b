"""Units and positions in mm on the Python items, from the library's field
tables (the same declarations the tool's MCAP schemas, CSV units and plot
labels read): ``Telemetry.units``, ``Imu.units``, ``m1_pos_mm``,
``m2_pos_mm`` and each protocol's ``field_info``."""

from __future__ import annotations

from robowire import omnitiles, pixy2, telemetrix

from conftest import DATA

POS7 = bytes.fromhex("a5 60 d0 07 ff ff 35")


def test_telemetry_and_imu_say_their_units() -> None:
    assert omnitiles.Telemetry.units == {
        "m1_pos": "ADC counts",
        "m2_pos": "ADC counts",
        "uwb": "mm",
        "tof": "mm",
        "m1_adcs": "ADC counts",
        "m2_adcs": "ADC counts",
    }
    assert omnitiles.Imu.units == {
        "ax": "m/s²",
        "ay": "m/s²",
        "az": "m/s²",
        "gx": "rad/s",
        "gy": "rad/s",
        "gz": "rad/s",
    }


def test_positions_in_mm_are_the_sdks_formula_bit_for_bit() -> None:
    decoder = omnitiles.Decoder()
    items = decoder.feed((DATA / "ble_telemetry.bin").read_bytes()) + decoder.finish()
    telemetry = [t for t in items if isinstance(t, omnitiles.Telemetry)]
    assert len(telemetry) == 298
    for t in telemetry:
        assert t.m1_pos is not None and t.m2_pos is not None
        assert t.m1_pos_mm == t.m1_pos / 4095 * 150
        assert t.m2_pos_mm == t.m2_pos / 4095 * 100
    # No reading: no position in mm either.
    (t,) = omnitiles.Decoder(layouts=["pos7"]).feed(POS7)
    assert t.m1_pos == 2000 and t.m2_pos is None
    assert t.m1_pos_mm == 2000 / 4095 * 150 and t.m2_pos_mm is None


def test_field_info_reads_each_protocols_table() -> None:
    uwb = omnitiles.field_info("telemetry", "uwb.2")
    assert uwb is not None
    assert uwb["unit"] == "mm" and uwb["no_reading"] and uwb["range"] == (0, 65534)
    assert omnitiles.field_info("telemetry", "layout")["names"] == [
        "pos7",
        "uwb15",
        "uwbtof17",
        "spi45",
        "ble53",
    ]
    assert omnitiles.field_info("telemetry", "nope") is None
    volts = telemetrix.field_info("sensor_report", "reading.volts")
    assert volts is not None and volts["unit"] == "V"
    assert telemetrix.field_info("analog_report", "value")["range"] == (0, 4095)
    assert pixy2.field_info("blocks", "blocks.0.x")["unit"] == "px"
    assert pixy2.field_info("blocks", "blocks.0.age")["unit"] == "frames"
