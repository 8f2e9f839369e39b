//! The sensor subsystem: SENSOR_NEW (command 31) and reports 20/21 (spec §6).

use super::dialect::Dialect;
use super::error::{ensure, Error};
use super::kind::{field_type, parse_row, write_field, write_row};
use super::list::List;
use super::table::sensor_readings;
use super::wire::{Reader, Writer};
use crate::EncodeError;

/// `SensorType` with its list and data lengths, from the sensor table.
macro_rules! sensor_types {
    ($($(#[$tm:meta])* $n:literal $t:ident $name:literal
        $(data $lens:tt $(#[$rm:meta])* $codec:ident { $($body:tt)* })?;)*) => {
        /// Sensor types (spec §6).
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum SensorType {
            $($(#[$tm])* $t = $n,)*
        }

        impl SensorType {
            /// Every sensor type, in id order.
            pub const ALL: [SensorType; [$($n),*].len()] = [$(SensorType::$t),*];

            /// The smallest and largest length of this type's report-20 data,
            /// or `None` if it has no report.
            pub(crate) const fn data_len(self) -> Option<(usize, usize)> {
                match self {
                    $(SensorType::$t => data_len!($($lens)?),)*
                }
            }
        }
    };
}

/// A sensor row's data length range, if it has a reading.
macro_rules! data_len {
    ($lens:tt) => {
        Some($lens)
    };
    () => {
        None
    };
}

super::table::sensor_table!(sensor_types);

impl SensorType {
    /// The type for a wire value.
    pub const fn from_u8(value: u8) -> Option<Self> {
        if (value as usize) < Self::ALL.len() {
            Some(Self::ALL[value as usize])
        } else {
            None
        }
    }

    /// The wire value.
    pub const fn as_u8(self) -> u8 {
        self as u8
    }
}

/// SENSOR_NEW (command 31): mirte 1.3's check and add, and mirte 1.2's add
/// (spec §6, §10.1).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SensorNew {
    /// `00, type`: ask whether a type is supported (answered by report 21).
    Check {
        /// Any type value; unknown ones are answered "not supported".
        sensor_type: u8,
    },
    /// `01, num, type, 6 settings bytes`: add a sensor (no reply).
    Add {
        /// Number echoed in its reports.
        sensor_num: u8,
        /// The type.
        sensor_type: SensorType,
        /// Settings, zero-padded to 6 bytes (layouts in [`SensorType`]).
        settings: [u8; 6],
    },
    /// mirte 1.2 only: `num, type, settings…` with no subtype byte and 0 to 6
    /// settings bytes (the firmware clears its buffer, so missing ones read
    /// as 0). Types 0..=6; only the VEML6040 (4, settings `port`) is created.
    /// The mirte 1.2 Python client adds a VEML6040 on port 1 with the short
    /// form `04 1f 00 04 01`.
    AddMirte12 {
        /// Number echoed in its reports.
        sensor_num: u8,
        /// The type, [`SensorType::Gps`]..=[`SensorType::Ina226`].
        sensor_type: SensorType,
        /// The settings bytes sent, at most 6.
        settings: List<u8, 6>,
    },
}

/// The largest sensor type mirte 1.2 names (INA226); higher ones are ignored.
const MIRTE12_MAX_TYPE: u8 = 6;

impl SensorNew {
    /// An `Add` whose settings (at most 6 bytes) are zero-padded.
    pub fn add(
        sensor_num: u8,
        sensor_type: SensorType,
        settings: &[u8],
    ) -> Result<Self, EncodeError> {
        let mut padded = [0u8; 6];
        padded
            .get_mut(..settings.len())
            .ok_or(EncodeError::TooLong {
                len: settings.len(),
                max: 6,
            })?
            .copy_from_slice(settings);
        Ok(SensorNew::Add {
            sensor_num,
            sensor_type,
            settings: padded,
        })
    }

    pub(crate) fn parse(r: &mut Reader<'_>, dialect: Dialect) -> Result<Self, Error> {
        if dialect == Dialect::Mirte12 {
            let sensor_num = r.u8()?;
            let sensor_type = Some(r.u8()?)
                .filter(|&t| t <= MIRTE12_MAX_TYPE)
                .and_then(SensorType::from_u8)
                .ok_or(Error::OutOfRange {
                    id: r.id(),
                    field: "sensor_type",
                })?;
            // Byte by byte rather than `List::from_slice`: a copy of a
            // variable length links `memcpy` (about 700 B on the Pico).
            let mut settings = List::new();
            for &byte in r.rest() {
                settings.push(byte).map_err(|_| r.bad_length())?;
            }
            return Ok(SensorNew::AddMirte12 {
                sensor_num,
                sensor_type,
                settings,
            });
        }
        match r.u8()? {
            0 => Ok(SensorNew::Check {
                sensor_type: r.u8()?,
            }),
            1 => {
                let sensor_num = r.u8()?;
                let sensor_type = SensorType::from_u8(r.u8()?).ok_or(Error::OutOfRange {
                    id: r.id(),
                    field: "sensor_type",
                })?;
                Ok(SensorNew::Add {
                    sensor_num,
                    sensor_type,
                    settings: r.array()?,
                })
            }
            _ => Err(Error::OutOfRange {
                id: r.id(),
                field: "subtype",
            }),
        }
    }

    pub(crate) fn write(&self, w: &mut Writer<'_>) {
        match *self {
            SensorNew::Check { sensor_type } => w.bytes(&[0, sensor_type]),
            SensorNew::Add {
                sensor_num,
                sensor_type,
                settings,
            } => {
                w.bytes(&[1, sensor_num, sensor_type.as_u8()]);
                w.bytes(&settings);
            }
            SensorNew::AddMirte12 {
                sensor_num,
                sensor_type,
                settings,
            } => {
                w.bytes(&[sensor_num, sensor_type.as_u8()]);
                settings.iter().for_each(|&b| w.u8(b));
            }
        }
    }

    /// The dialect whose layout this is.
    pub(crate) const fn dialect(&self) -> Dialect {
        match self {
            SensorNew::AddMirte12 { .. } => Dialect::Mirte12,
            SensorNew::Check { .. } | SensorNew::Add { .. } => Dialect::Mirte13,
        }
    }
}

/// The `SensorReading` enum, from the sensor table: a `plain` row's
/// variant is built from its fields, a `custom` row gives its variant.
macro_rules! sensor_reading_enum {
    (@rows [$($vars:tt)*] $(#[$rm:meta])* $n:literal $t:ident plain {
        $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
    }; $($rest:tt)*) => {
        sensor_reading_enum!(@rows [
            $($vars)* $(#[$rm])* $t { $($(#[$fm])* $f: field_type!($kind $(($($arg)*))?),)* },
        ] $($rest)*);
    };
    (@rows [$($vars:tt)*] $(#[$rm:meta])* $n:literal $t:ident custom {
        variants { $name:ident $fields:tt, } $($pieces:tt)*
    }; $($rest:tt)*) => {
        sensor_reading_enum!(@rows [$($vars)* $(#[$rm])* $name $fields,] $($rest)*);
    };
    (@rows [$($vars:tt)*]) => {
        /// The data of a SENSOR_REPORT (report 20), by sensor type. Integers are
        /// big-endian, floats little-endian (spec §3, §6).
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum SensorReading {
            $($vars)*
        }
    };
    ($($rows:tt)*) => {
        sensor_reading_enum!(@rows [] $($rows)*);
    };
}

super::table::sensor_table!(sensor_readings, sensor_reading_enum);

/// The readings' codec, from the sensor table.
macro_rules! sensor_reading_codec {
    ($($(#[$rm:meta])* $n:literal $t:ident $codec:ident { $($body:tt)* };)*) => {
        impl SensorReading {
            /// The sensor type of this reading.
            pub const fn sensor_type(&self) -> SensorType {
                match self {
                    $(SensorReading::$t { .. } => SensorType::$t,)*
                }
            }

            /// Parse the data after `sensor_num, sensor_type`.
            pub(crate) fn parse(
                r: &mut Reader<'_>,
                sensor_type: SensorType,
                dialect: Dialect,
            ) -> Result<Self, Error> {
                let id = r.id();
                Ok(match sensor_type {
                    $(SensorType::$t => {
                        parse_row!((&mut *r, dialect), r, id, SensorReading, [$t] $codec { $($body)* })
                    })*
                    #[allow(unreachable_patterns)]
                    _ => return Err(Error::OutOfRange { id, field: "sensor_type" }),
                })
            }

            pub(crate) fn write(&self, w: &mut Writer<'_>, dialect: Dialect) {
                match *self {
                    $(SensorReading::$t { .. } => {
                        write_row!(self, (w, dialect), SensorReading, [$t] $codec { $($body)* })
                    })*
                }
            }
        }
    };
}

super::table::sensor_table!(sensor_readings, sensor_reading_codec);
