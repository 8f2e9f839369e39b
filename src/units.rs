//! What each field of each message means: its unit, a one-line description,
//! whether `null` marks "no reading", the range the decoder accepts where it
//! is narrower than the wire's integer, the names a string field takes, and
//! whether only some frames carry it. Each protocol declares its fields once,
//! in [`omnitiles::FIELD_INFO`](crate::omnitiles::FIELD_INFO),
//! [`telemetrix::FIELD_INFO`](crate::telemetrix::FIELD_INFO) and
//! [`pixy2::FIELD_INFO`](crate::pixy2::FIELD_INFO); the `robowire` tool's
//! JSON Schemas, CSV unit rows and plot labels and the Python package's items
//! read them from there.
//!
//! Fields are named by their path in the JSON-lines form (the `serde` form):
//! members joined by `.`, array elements by their index (`imu.ax`, `uwb.2`,
//! `blocks.0.x`). A table names every element of an array with `*`
//! (`uwb.*`), and a field every message type has with the message `*`.
//!
//! A unit is declared where the protocol, the device's firmware or its
//! datasheet fixes it; a field whose unit the protocol leaves to a driver
//! library (the Telemetrix MPU9250's and BNO055's floats) has none, rather
//! than a guess.
//!
//! ```
//! use robowire::units::Unit;
//! let uwb = robowire::omnitiles::FIELD_INFO.get("telemetry", "uwb.3").unwrap();
//! assert_eq!(uwb.unit, Some(Unit::Millimetre));
//! assert!(uwb.no_reading);
//! let az = robowire::omnitiles::FIELD_INFO.get("telemetry", "imu.az").unwrap();
//! assert_eq!(az.unit.map(Unit::symbol), Some("m/s²"));
//! ```

use core::fmt;

/// A physical unit (or the count a raw reading is in).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Unit {
    /// Millimetres.
    Millimetre,
    /// Centimetres.
    Centimetre,
    /// Metres per second squared.
    MetrePerSecondSquared,
    /// Radians per second.
    RadianPerSecond,
    /// Degrees of angle.
    Degree,
    /// Hundredths of a degree of angle.
    Centidegree,
    /// Degrees Celsius.
    DegreeCelsius,
    /// Volts.
    Volt,
    /// Amperes.
    Ampere,
    /// Seconds.
    Second,
    /// Milliseconds.
    Millisecond,
    /// Microseconds.
    Microsecond,
    /// Counts of a 12-bit analog-to-digital converter (0..=4095).
    AdcCount,
    /// Counts of an encoder or a rotary sensor.
    Step,
    /// Image pixels.
    Pixel,
    /// Cells of the Pixy2 line tracker's 79 × 52 grid.
    GridCell,
    /// Video frames.
    Frame,
    /// Video frames per second.
    FramePerSecond,
    /// Bytes.
    Byte,
}

impl Unit {
    /// Every unit.
    pub const ALL: [Unit; 19] = [
        Unit::Millimetre,
        Unit::Centimetre,
        Unit::MetrePerSecondSquared,
        Unit::RadianPerSecond,
        Unit::Degree,
        Unit::Centidegree,
        Unit::DegreeCelsius,
        Unit::Volt,
        Unit::Ampere,
        Unit::Second,
        Unit::Millisecond,
        Unit::Microsecond,
        Unit::AdcCount,
        Unit::Step,
        Unit::Pixel,
        Unit::GridCell,
        Unit::Frame,
        Unit::FramePerSecond,
        Unit::Byte,
    ];

    /// The unit's symbol as an axis label or a CSV unit row gives it
    /// (`mm`, `m/s²`, `°C`; raw counts as `ADC counts`, `steps`).
    pub const fn symbol(self) -> &'static str {
        match self {
            Unit::Millimetre => "mm",
            Unit::Centimetre => "cm",
            Unit::MetrePerSecondSquared => "m/s²",
            Unit::RadianPerSecond => "rad/s",
            Unit::Degree => "°",
            Unit::Centidegree => "0.01°",
            Unit::DegreeCelsius => "°C",
            Unit::Volt => "V",
            Unit::Ampere => "A",
            Unit::Second => "s",
            Unit::Millisecond => "ms",
            Unit::Microsecond => "µs",
            Unit::AdcCount => "ADC counts",
            Unit::Step => "steps",
            Unit::Pixel => "px",
            Unit::GridCell => "grid cells",
            Unit::Frame => "frames",
            Unit::FramePerSecond => "frames/s",
            Unit::Byte => "B",
        }
    }
}

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

/// What one field means (see the [module docs](self)). Built with `const`
/// methods: `FieldInfo::new("Distance.").unit(Unit::Millimetre)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct FieldInfo {
    /// One sentence on what the field holds.
    pub doc: &'static str,
    /// Its unit, where one is fixed.
    pub unit: Option<Unit>,
    /// `null` means "no reading" (`0xFFFF` on the OmniTiles wire).
    pub no_reading: bool,
    /// The inclusive range the decoder accepts, where it is narrower than
    /// the wire's integer type.
    pub range: Option<(i64, i64)>,
    /// The names a string field takes (empty: any string).
    pub names: &'static [&'static str],
    /// A type byte: one of `names`, or the byte's number when it names no
    /// known type.
    pub or_number: bool,
    /// Only some frames of the message carry it (a layout's group, a
    /// trailing field, a quirk).
    pub optional: bool,
    /// An object whose members depend on a type the message names (a
    /// sensor's reading, a module's message): none of them is required.
    pub by_type: bool,
    /// Names the thing the message is about (a pin, a sensor, a module):
    /// the tool gives each its own topic (`/telemetrix/analog_report/26`).
    pub entity: bool,
    /// A list whose elements are the things the frame reports (a Pixy2
    /// frame's blocks): the tool's CSV gives each element a row of its own.
    pub rows: bool,
}

impl FieldInfo {
    /// A field described by `doc`, with no unit.
    pub const fn new(doc: &'static str) -> FieldInfo {
        FieldInfo {
            doc,
            unit: None,
            no_reading: false,
            range: None,
            names: &[],
            or_number: false,
            optional: false,
            by_type: false,
            entity: false,
            rows: false,
        }
    }

    /// In `unit`.
    pub const fn unit(mut self, unit: Unit) -> FieldInfo {
        self.unit = Some(unit);
        self
    }

    /// `null` for no reading.
    pub const fn no_reading(mut self) -> FieldInfo {
        self.no_reading = true;
        self
    }

    /// Accepted from `min` to `max` only.
    pub const fn range(mut self, min: i64, max: i64) -> FieldInfo {
        self.range = Some((min, max));
        self
    }

    /// One of `names`.
    pub const fn names(mut self, names: &'static [&'static str]) -> FieldInfo {
        self.names = names;
        self
    }

    /// One of `names`, or a number for a type byte no name covers.
    pub const fn names_or_number(mut self, names: &'static [&'static str]) -> FieldInfo {
        self.names = names;
        self.or_number = true;
        self
    }

    /// An object whose members depend on a type the message names.
    pub const fn by_type(mut self) -> FieldInfo {
        self.by_type = true;
        self
    }

    /// Names the thing the message is about.
    pub const fn entity(mut self) -> FieldInfo {
        self.entity = true;
        self
    }

    /// A list of the things the frame reports, a row each in a table.
    pub const fn rows(mut self) -> FieldInfo {
        self.rows = true;
        self
    }

    /// Carried by some frames only.
    pub const fn optional(mut self) -> FieldInfo {
        self.optional = true;
        self
    }
}

/// A protocol's [`FieldInfo`]s, each under its message type and path.
#[derive(Debug, Clone, Copy)]
pub struct FieldTable {
    /// The protocol's name, as the tool's subcommands name it (`omnitiles`).
    pub protocol: &'static str,
    /// `(message type, path, info)`: `*` as the type matches every message,
    /// `*` as a path segment every array index.
    pub entries: &'static [(&'static str, &'static str, FieldInfo)],
}

impl FieldTable {
    /// The info of field `path` (`imu.ax`, `uwb.2`, `blocks.0.x`) of
    /// message type `message`, if declared. The first matching entry wins,
    /// so a message's own entry goes before a `*` one.
    pub fn get(&self, message: &str, path: &str) -> Option<&'static FieldInfo> {
        self.entries
            .iter()
            .find(|(m, p, _)| (*m == "*" || *m == message) && path_matches(p, path))
            .map(|(_, _, info)| info)
    }
}

impl FieldTable {
    /// The top-level field that names what a `message` is about (its pin,
    /// sensor or module), if the message type has one.
    ///
    /// ```
    /// let key = robowire::telemetrix::FIELD_INFO.entity_key("analog_report");
    /// assert_eq!(key, Some("pin"));
    /// assert_eq!(robowire::telemetrix::FIELD_INFO.entity_key("pong"), None);
    /// ```
    pub fn entity_key(&self, message: &str) -> Option<&'static str> {
        self.entries
            .iter()
            // The flag first: most entries are not entities, and it spares a
            // string comparison per field on every frame of a recording.
            .find(|(m, _, info)| info.entity && *m == message)
            .map(|(_, path, _)| *path)
    }

    /// The lists of a `message` whose elements are the things it reports
    /// (each a [`FieldInfo::rows`] path, `*` for an array index).
    ///
    /// ```
    /// let lists: Vec<_> = robowire::pixy2::FIELD_INFO.row_lists("features").collect();
    /// assert_eq!(lists, ["sections.*.vectors", "sections.*.intersections", "sections.*.barcodes"]);
    /// ```
    pub fn row_lists<'a>(&'a self, message: &'a str) -> impl Iterator<Item = &'static str> + 'a {
        self.entries
            .iter()
            .filter(move |(m, _, info)| info.rows && *m == message)
            .map(|(_, path, _)| *path)
    }
}

/// Whether `pattern` (segments joined by `.`, `*` for any array index)
/// names `path`.
fn path_matches(pattern: &str, path: &str) -> bool {
    let mut want = pattern.split('.');
    let mut have = path.split('.');
    loop {
        match (want.next(), have.next()) {
            (None, None) => return true,
            (Some("*"), Some(segment)) => {
                if segment.is_empty() || !segment.bytes().all(|b| b.is_ascii_digit()) {
                    return false;
                }
            }
            (Some(w), Some(h)) if w == h => {}
            _ => return false,
        }
    }
}

/// The members the stream adds to every frame's JSON line (its `protocol`
/// is empty: every protocol's frames have them).
pub static STREAM_FIELDS: FieldTable = FieldTable {
    protocol: "",
    entries: &[
        (
            "*",
            "offset",
            FieldInfo::new("Byte offset of the frame's first byte in the input.").unit(Unit::Byte),
        ),
        (
            "*",
            "len",
            FieldInfo::new("The frame's length on the wire.").unit(Unit::Byte),
        ),
    ],
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_match_by_segment_with_indices_for_stars() {
        assert!(path_matches("uwb.*", "uwb.3"));
        assert!(path_matches("blocks.*.x", "blocks.12.x"));
        assert!(!path_matches("uwb.*", "uwb"));
        assert!(!path_matches("uwb.*", "uwb.x"));
        assert!(!path_matches("uwb.*", "uwb."));
        assert!(!path_matches("imu.ax", "imu.ax.y"));
        assert!(path_matches("imu.ax", "imu.ax"));
    }

    #[test]
    fn every_unit_has_its_own_symbol() {
        for (i, a) in Unit::ALL.iter().enumerate() {
            for b in &Unit::ALL[i + 1..] {
                assert_ne!(a.symbol(), b.symbol());
            }
        }
    }
}
