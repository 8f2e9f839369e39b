//! The sensor subsystem: SENSOR_NEW (command 31) and reports 20/21 (spec §6).

use super::dialect::Dialect;
use super::error::{ensure, Error};
use super::list::List;
use super::wire::{Reader, Writer};
use crate::EncodeError;

/// Sensor types (spec §6).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SensorType {
    /// 0: GPS (not supported by the firmware; no report layout).
    Gps,
    /// 1: HX711 load cell. Settings `dout, sck`.
    Hx711,
    /// 2: MPU9250. Settings `port, addr`.
    Mpu9250,
    /// 3: VL53L0X. Settings `port`.
    Vl53l0x,
    /// 4: VEML6040 (address 0x10). Settings `port`.
    Veml6040,
    /// 5: ADXL345 (not registered in the firmware). Settings `port`.
    Adxl345,
    /// 6: INA226. Settings `port, addr` (0x40..=0x4F).
    Ina226,
    /// 7: HMC5883L. Settings `port`.
    Hmc5883l,
    /// 8: AS5600 behind a TCA9548 mux (0x70). Settings `port, channel_mask`.
    As5600,
    /// 9: MPU6050. Settings `port, addr`.
    Mpu6050,
    /// 10: BNO055. Settings `port`.
    Bno055,
}

impl SensorType {
    /// Every sensor type, in id order.
    pub const ALL: [SensorType; 11] = [
        SensorType::Gps,
        SensorType::Hx711,
        SensorType::Mpu9250,
        SensorType::Vl53l0x,
        SensorType::Veml6040,
        SensorType::Adxl345,
        SensorType::Ina226,
        SensorType::Hmc5883l,
        SensorType::As5600,
        SensorType::Mpu6050,
        SensorType::Bno055,
    ];

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

    /// The smallest and largest length of this type's report-20 data, or
    /// `None` if it has no report.
    pub(crate) const fn data_len(self) -> Option<(usize, usize)> {
        Some(match self {
            SensorType::Gps => return None,
            SensorType::Hx711 => (4, 4),
            SensorType::Mpu9250 => (52, 52),
            SensorType::Vl53l0x => (2, 2),
            SensorType::Veml6040 | SensorType::Ina226 => (8, 8),
            SensorType::Adxl345 => (6, 6),
            SensorType::Hmc5883l => (12, 12),
            SensorType::As5600 => (0, 16),
            SensorType::Mpu6050 => (14, 14),
            SensorType::Bno055 => (53, 53),
        })
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

/// The data of a SENSOR_REPORT (report 20), by sensor type. Integers are
/// big-endian, floats little-endian (spec §3, §6).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SensorReading {
    /// HX711: raw `i32`.
    Hx711 {
        /// Raw reading.
        raw: i32,
    },
    /// MPU9250: 13 floats.
    Mpu9250 {
        /// Acceleration x, y, z.
        accel: [f32; 3],
        /// Angular rate x, y, z.
        gyro: [f32; 3],
        /// Magnetic field x, y, z.
        mag: [f32; 3],
        /// Orientation quaternion x, y, z, w.
        quat: [f32; 4],
    },
    /// VL53L0X: distance.
    Vl53l0x {
        /// Distance in mm.
        mm: u16,
    },
    /// VEML6040: colour channels.
    Veml6040 {
        /// Red.
        r: u16,
        /// Green.
        g: u16,
        /// Blue.
        b: u16,
        /// White.
        w: u16,
    },
    /// ADXL345 (never sent by the firmware; layout as the spec describes).
    Adxl345 {
        /// Acceleration x, y, z.
        accel: [i16; 3],
    },
    /// INA226: bus voltage and current.
    Ina226 {
        /// Bus voltage in V.
        volts: f32,
        /// Current in A.
        amps: f32,
    },
    /// HMC5883L: normalised field.
    Hmc5883l {
        /// Field x, y, z.
        field: [f32; 3],
    },
    /// AS5600 behind a mux: one angle per channel set in the mask, lowest
    /// channel first.
    As5600 {
        /// Angles 0..=4095.
        angles: List<u16, 8>,
    },
    /// MPU6050: raw readings.
    Mpu6050 {
        /// Acceleration x, y, z.
        accel: [i16; 3],
        /// Angular rate x, y, z.
        gyro: [i16; 3],
        /// Temperature.
        temp: i16,
    },
    /// BNO055: 13 floats and a temperature.
    Bno055 {
        /// Angular rate x, y, z.
        gyro: [f32; 3],
        /// Magnetic field x, y, z.
        mag: [f32; 3],
        /// Acceleration x, y, z.
        accel: [f32; 3],
        /// Orientation quaternion x, y, z, w.
        quat: [f32; 4],
        /// Temperature in °C.
        temp: i8,
    },
}

fn f32s<const N: usize>(r: &mut Reader<'_>) -> Result<[f32; N], Error> {
    let mut out = [0.0; N];
    for v in &mut out {
        *v = r.f32()?;
    }
    Ok(out)
}

fn i16s<const N: usize>(r: &mut Reader<'_>) -> Result<[i16; N], Error> {
    let mut out = [0; N];
    for v in &mut out {
        *v = r.i16()?;
    }
    Ok(out)
}

impl SensorReading {
    /// The sensor type of this reading.
    pub const fn sensor_type(&self) -> SensorType {
        match self {
            SensorReading::Hx711 { .. } => SensorType::Hx711,
            SensorReading::Mpu9250 { .. } => SensorType::Mpu9250,
            SensorReading::Vl53l0x { .. } => SensorType::Vl53l0x,
            SensorReading::Veml6040 { .. } => SensorType::Veml6040,
            SensorReading::Adxl345 { .. } => SensorType::Adxl345,
            SensorReading::Ina226 { .. } => SensorType::Ina226,
            SensorReading::Hmc5883l { .. } => SensorType::Hmc5883l,
            SensorReading::As5600 { .. } => SensorType::As5600,
            SensorReading::Mpu6050 { .. } => SensorType::Mpu6050,
            SensorReading::Bno055 { .. } => SensorType::Bno055,
        }
    }

    /// Parse the data after `sensor_num, sensor_type`.
    pub(crate) fn parse(
        r: &mut Reader<'_>,
        sensor_type: SensorType,
        dialect: Dialect,
    ) -> Result<Self, Error> {
        Ok(match sensor_type {
            SensorType::Gps => {
                return Err(Error::OutOfRange {
                    id: r.id(),
                    field: "sensor_type",
                })
            }
            SensorType::Hx711 => SensorReading::Hx711 { raw: r.i32()? },
            SensorType::Mpu9250 => SensorReading::Mpu9250 {
                accel: f32s(r)?,
                gyro: f32s(r)?,
                mag: f32s(r)?,
                quat: f32s(r)?,
            },
            SensorType::Vl53l0x => SensorReading::Vl53l0x { mm: r.u16()? },
            // mirte 1.2 sends each colour register low byte first.
            SensorType::Veml6040 if dialect == Dialect::Mirte12 => {
                let mut le = || r.array().map(u16::from_le_bytes);
                SensorReading::Veml6040 {
                    r: le()?,
                    g: le()?,
                    b: le()?,
                    w: le()?,
                }
            }
            SensorType::Veml6040 => SensorReading::Veml6040 {
                r: r.u16()?,
                g: r.u16()?,
                b: r.u16()?,
                w: r.u16()?,
            },
            SensorType::Adxl345 => SensorReading::Adxl345 { accel: i16s(r)? },
            SensorType::Ina226 => SensorReading::Ina226 {
                volts: r.f32()?,
                amps: r.f32()?,
            },
            SensorType::Hmc5883l => SensorReading::Hmc5883l { field: f32s(r)? },
            SensorType::As5600 => {
                let mut angles = List::new();
                while r.remaining() > 0 {
                    let angle = r.u16()?;
                    ensure(angle <= 4095, r.id(), "angle")?;
                    angles.push(angle).map_err(|_| r.bad_length())?;
                }
                SensorReading::As5600 { angles }
            }
            SensorType::Mpu6050 => SensorReading::Mpu6050 {
                accel: i16s(r)?,
                gyro: i16s(r)?,
                temp: r.i16()?,
            },
            SensorType::Bno055 => SensorReading::Bno055 {
                gyro: f32s(r)?,
                mag: f32s(r)?,
                accel: f32s(r)?,
                quat: f32s(r)?,
                temp: r.i8()?,
            },
        })
    }

    pub(crate) fn write(&self, w: &mut Writer<'_>, dialect: Dialect) {
        let floats = |w: &mut Writer<'_>, vs: &[f32]| vs.iter().for_each(|&v| w.f32(v));
        let ints = |w: &mut Writer<'_>, vs: &[i16]| vs.iter().for_each(|&v| w.i16(v));
        match self {
            SensorReading::Hx711 { raw } => w.i32(*raw),
            SensorReading::Mpu9250 {
                accel,
                gyro,
                mag,
                quat,
            } => {
                floats(w, accel);
                floats(w, gyro);
                floats(w, mag);
                floats(w, quat);
            }
            SensorReading::Vl53l0x { mm } => w.u16(*mm),
            SensorReading::Veml6040 { r, g, b, w: white } => {
                for v in [*r, *g, *b, *white] {
                    if dialect == Dialect::Mirte12 {
                        w.bytes(&v.to_le_bytes());
                    } else {
                        w.u16(v);
                    }
                }
            }
            SensorReading::Adxl345 { accel } => ints(w, accel),
            SensorReading::Ina226 { volts, amps } => {
                w.f32(*volts);
                w.f32(*amps);
            }
            SensorReading::Hmc5883l { field } => floats(w, field),
            SensorReading::As5600 { angles } => angles.iter().for_each(|&a| w.u16(a)),
            SensorReading::Mpu6050 { accel, gyro, temp } => {
                ints(w, accel);
                ints(w, gyro);
                w.i16(*temp);
            }
            SensorReading::Bno055 {
                gyro,
                mag,
                accel,
                quat,
                temp,
            } => {
                floats(w, gyro);
                floats(w, mag);
                floats(w, accel);
                floats(w, quat);
                w.i8(*temp);
            }
        }
    }
}
