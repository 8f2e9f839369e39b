//! What each OmniTiles field means (spec §3 and §4.4): units, "no reading"
//! and ranges, declared once for the tool's schemas, CSV and plots and for
//! the Python items.

use super::layout::Layout;
use crate::units::{FieldInfo, FieldTable, Unit};

/// A reading `0xFFFF` marks as missing: 0..=65534 or `null`.
const fn reading(doc: &'static str) -> FieldInfo {
    FieldInfo::new(doc).no_reading().range(0, 65534)
}

/// A 12-bit ADC channel.
const fn adc(doc: &'static str) -> FieldInfo {
    FieldInfo::new(doc).unit(Unit::AdcCount)
}

/// An IMU value.
const fn imu(doc: &'static str, unit: Unit) -> FieldInfo {
    FieldInfo::new(doc).unit(unit)
}

/// Every OmniTiles field: telemetry (tile → host) and commands (host → tile).
///
/// ```
/// use robowire::omnitiles::FIELD_INFO;
/// use robowire::units::Unit;
/// assert_eq!(FIELD_INFO.get("telemetry", "m1_adcs.2").unwrap().unit, Some(Unit::AdcCount));
/// assert_eq!(FIELD_INFO.get("base_velocity", "vx").unwrap().range, None);
/// ```
pub static FIELD_INFO: FieldTable = FieldTable {
    protocol: "omnitiles",
    entries: &[
        (
            "*",
            "type",
            FieldInfo::new("The message type.").names(&super::Message::NAMES),
        ),
        (
            "telemetry",
            "layout",
            FieldInfo::new("The telemetry layout, known from the frame's length.")
                .names(&Layout::NAMES),
        ),
        (
            "telemetry",
            "m1_pos",
            reading("M1 position, fused 12-bit ADC (mm = raw / 4095 · 150).").unit(Unit::AdcCount),
        ),
        (
            "telemetry",
            "m2_pos",
            reading("M2 position, fused 12-bit ADC (mm = raw / 4095 · 100).").unit(Unit::AdcCount),
        ),
        (
            "telemetry",
            "uwb",
            FieldInfo::new("UWB ranges to anchors 0..3.").optional(),
        ),
        (
            "telemetry",
            "uwb.*",
            reading("UWB range to the anchor of this index.").unit(Unit::Millimetre),
        ),
        (
            "telemetry",
            "tof",
            reading("VL53L0X time-of-flight range.")
                .unit(Unit::Millimetre)
                .optional(),
        ),
        (
            "telemetry",
            "imu",
            FieldInfo::new("LSM6DSV16X sample, sensor frame.").optional(),
        ),
        (
            "telemetry",
            "imu.ax",
            imu(
                "Acceleration x, gravity included.",
                Unit::MetrePerSecondSquared,
            ),
        ),
        (
            "telemetry",
            "imu.ay",
            imu(
                "Acceleration y, gravity included.",
                Unit::MetrePerSecondSquared,
            ),
        ),
        (
            "telemetry",
            "imu.az",
            imu(
                "Acceleration z, gravity included (about +9.8 at rest).",
                Unit::MetrePerSecondSquared,
            ),
        ),
        (
            "telemetry",
            "imu.gx",
            imu("Angular rate about x.", Unit::RadianPerSecond),
        ),
        (
            "telemetry",
            "imu.gy",
            imu("Angular rate about y.", Unit::RadianPerSecond),
        ),
        (
            "telemetry",
            "imu.gz",
            imu("Angular rate about z.", Unit::RadianPerSecond),
        ),
        (
            "telemetry",
            "m1_adcs",
            FieldInfo::new("M1's four ADC channels.").optional(),
        ),
        ("telemetry", "m1_adcs.*", adc("An M1 ADC channel.")),
        (
            "telemetry",
            "m2_adcs",
            FieldInfo::new("M2's two ADC channels.").optional(),
        ),
        ("telemetry", "m2_adcs.*", adc("An M2 ADC channel.")),
        (
            "*",
            "speed",
            FieldInfo::new("Speed byte: the firmware drives duty floor(v / 255 · 50) of 50."),
        ),
        (
            "*",
            "position",
            FieldInfo::new(
                "Set-position byte: target stroke · v / 255 mm (M1 150, M2 100), clamped.",
            ),
        ),
        (
            "base_velocity",
            "vx",
            FieldInfo::new("Base velocity x, −128..127 (−128 → −1.008 of full)."),
        ),
        (
            "base_velocity",
            "vy",
            FieldInfo::new("Base velocity y, −128..127 (−128 → −1.008 of full)."),
        ),
        (
            "base_velocity",
            "omega",
            FieldInfo::new("Base rotation rate, −128..127 (−128 → −1.008 of full)."),
        ),
    ],
};
