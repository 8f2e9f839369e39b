//! Telemetry: tile → host.

use core::fmt;

use super::error::Error;
use super::layout::Layout;
use super::whole::{check_whole, start_and_id};
use super::wire::{checksum, id, MAX_FRAME_LEN, START};
use crate::encode::{check_room, Encode, EncodeError};

/// The `u16` value that means "no reading" in positions, UWB ranges and ToF.
pub const NO_READING: u16 = 0xFFFF;

/// One IMU sample: acceleration in m/s² (gravity included) and angular rate in
/// rad/s, in the sensor's frame.
///
/// Equality compares bit patterns, so a sample with NaNs equals itself and a
/// decoded sample equals the one that was encoded, bit for bit.
///
/// With the `serde` feature a sample is the command-line tool's `imu`
/// object, `{"ax":0.1,"ay":0.2,"az":9.8,"gx":0.01,"gy":-0.02,"gz":0.03}`:
/// each value is a number that reads back as the same `f32` (also through
/// `f64`), or for the values JSON has no number for the strings `"inf"`,
/// `"-inf"` and `"nan:0x7fc00000"` (a NaN's bits), so every bit pattern
/// survives.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, Default)]
pub struct Imu {
    /// Acceleration along x, m/s².
    pub ax: f32,
    /// Acceleration along y, m/s².
    pub ay: f32,
    /// Acceleration along z, m/s² (≈ +9.8 at rest).
    pub az: f32,
    /// Angular rate about x, rad/s.
    pub gx: f32,
    /// Angular rate about y, rad/s.
    pub gy: f32,
    /// Angular rate about z, rad/s.
    pub gz: f32,
}

impl Imu {
    /// The six values' names in wire order, as in the JSON form.
    pub const NAMES: [&'static str; 6] = ["ax", "ay", "az", "gx", "gy", "gz"];

    /// The six values in wire order: ax, ay, az, gx, gy, gz.
    pub const fn to_array(self) -> [f32; 6] {
        [self.ax, self.ay, self.az, self.gx, self.gy, self.gz]
    }

    /// A sample from six values in wire order.
    pub const fn from_array([ax, ay, az, gx, gy, gz]: [f32; 6]) -> Imu {
        Imu {
            ax,
            ay,
            az,
            gx,
            gy,
            gz,
        }
    }
}

impl PartialEq for Imu {
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (self.to_array(), other.to_array());
        a.iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())
    }
}

impl Eq for Imu {}

/// A telemetry frame's contents.
///
/// Readings that can be missing are `Option`s: `None` is the wire's `0xFFFF`
/// ("no reading": no feedback, anchor never measured, no ToF sensor). Groups
/// that a layout does not carry are `None` one level up, so "not carried" and
/// "no reading" stay distinct: `tof == None` means the layout has no ToF field,
/// `tof == Some(None)` means the tile sent `0xFFFF`.
///
/// ```
/// use robowire::omnitiles::{Layout, Telemetry};
/// let frame = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
/// let t = Telemetry::try_from(&frame[..]).unwrap();
/// assert_eq!(t.layout, Layout::Pos7);
/// assert_eq!((t.m1_pos, t.m2_pos), (Some(2000), Some(1000)));
/// assert_eq!(t.uwb, None); // not carried by the 7-byte layout
/// assert_eq!(t.to_string(), "telemetry layout=pos7 m1_pos=2000 m2_pos=1000");
/// ```
///
/// With the `serde` feature telemetry is written as the command-line tool's
/// JSON line for it, without `offset` and `len`: `type` (`"telemetry"`),
/// `layout`, `m1_pos`, `m2_pos`, then the groups the layout carries; a
/// `0xFFFF` reading is `null` and a group the layout does not carry is absent
/// (so `tof: None` and `tof: Some(None)` stay distinct). Deserializing
/// accepts exactly the groups of the layout, with the tool's messages, and
/// gives only telemetry that encodes.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Telemetry {
    /// Which layout the frame had.
    pub layout: Layout,
    /// M1 position, raw 0..=4095 (see [`units::adc_to_mm`](super::units::adc_to_mm)).
    pub m1_pos: Option<u16>,
    /// M2 position, raw 0..=4095.
    pub m2_pos: Option<u16>,
    /// UWB ranges to anchors 0..=3 in mm (15, 17 and 53-byte layouts).
    pub uwb: Option<[Option<u16>; 4]>,
    /// ToF range in mm (17, 45 and 53-byte layouts).
    pub tof: Option<Option<u16>>,
    /// IMU sample (45 and 53-byte layouts).
    pub imu: Option<Imu>,
    /// M1's four potentiometer channels, raw 0..=4095 (45 and 53-byte layouts).
    pub m1_adcs: Option<[u16; 4]>,
    /// M2's two potentiometer channels, raw 0..=4095 (45 and 53-byte layouts).
    pub m2_adcs: Option<[u16; 2]>,
}

/// Where each field group sits in a layout (offsets from the start byte).
pub(super) struct Offsets {
    pub(super) uwb: Option<usize>,
    pub(super) tof: Option<usize>,
    pub(super) imu: Option<usize>,
    pub(super) adcs: Option<usize>,
}

pub(super) const fn offsets(layout: Layout) -> Offsets {
    match layout {
        Layout::Pos7 => Offsets {
            uwb: None,
            tof: None,
            imu: None,
            adcs: None,
        },
        Layout::Uwb15 => Offsets {
            uwb: Some(6),
            tof: None,
            imu: None,
            adcs: None,
        },
        Layout::UwbTof17 => Offsets {
            uwb: Some(6),
            tof: Some(14),
            imu: None,
            adcs: None,
        },
        Layout::Spi45 => Offsets {
            uwb: None,
            tof: Some(6),
            imu: Some(8),
            adcs: Some(32),
        },
        Layout::Ble53 => Offsets {
            uwb: Some(6),
            tof: Some(14),
            imu: Some(16),
            adcs: Some(40),
        },
    }
}

/// Bytes the M1 ADC channels take; M2's follow them.
pub(super) const M1_ADCS_LEN: usize = 8;

#[inline(always)]
fn u16_at<const L: usize>(frame: &[u8; L], at: usize) -> u16 {
    u16::from_le_bytes([frame[at], frame[at + 1]])
}

#[inline(always)]
fn reading_at<const L: usize>(frame: &[u8; L], at: usize) -> Option<u16> {
    Some(u16_at(frame, at)).filter(|&v| v != NO_READING)
}

#[inline(always)]
fn f32_at<const L: usize>(frame: &[u8; L], at: usize) -> f32 {
    f32::from_bits(u32::from_le_bytes([
        frame[at],
        frame[at + 1],
        frame[at + 2],
        frame[at + 3],
    ]))
}

/// Read a frame of `layout`, which is `L` bytes long. Inlined per layout so
/// that `offsets(layout)` folds to constants.
#[inline(always)]
fn parse_fixed<const L: usize>(layout: Layout, frame: &[u8]) -> Telemetry {
    let padded: [u8; L];
    let frame: &[u8; L] = match frame.first_chunk::<L>() {
        Some(frame) => frame,
        // Framing only passes frames of the layout's length; a shorter slice
        // reads as zero-padded rather than panicking.
        None => {
            padded = zero_padded(frame);
            &padded
        }
    };
    let at = offsets(layout);
    Telemetry {
        layout,
        m1_pos: reading_at(frame, 2),
        m2_pos: reading_at(frame, 4),
        uwb: at
            .uwb
            .map(|o| core::array::from_fn(|i| reading_at(frame, o + 2 * i))),
        tof: at.tof.map(|o| reading_at(frame, o)),
        imu: at
            .imu
            .map(|o| Imu::from_array(core::array::from_fn(|i| f32_at(frame, o + 4 * i)))),
        m1_adcs: at
            .adcs
            .map(|o| core::array::from_fn(|i| u16_at(frame, o + 2 * i))),
        m2_adcs: at
            .adcs
            .map(|o| core::array::from_fn(|i| u16_at(frame, o + M1_ADCS_LEN + 2 * i))),
    }
}

#[cold]
fn zero_padded<const L: usize>(frame: &[u8]) -> [u8; L] {
    let mut padded = [0; L];
    let n = frame.len().min(L);
    padded[..n].copy_from_slice(&frame[..n]);
    padded
}

fn put_u16(out: &mut [u8], at: usize, value: u16) {
    // The offsets come from the layout and fit its frame; `get_mut` only
    // keeps a panic path out of firmware builds.
    if let Some(dst) = out.get_mut(at..at + 2) {
        dst.copy_from_slice(&value.to_le_bytes());
    }
}

/// Write a reading, refusing `Some(0xFFFF)`: it would come back as `None`.
fn put_reading(
    out: &mut [u8],
    at: usize,
    value: Option<u16>,
    field: &'static str,
) -> Result<(), EncodeError> {
    match value {
        Some(NO_READING) => Err(EncodeError::OutOfRange { field }),
        Some(v) => {
            put_u16(out, at, v);
            Ok(())
        }
        None => {
            put_u16(out, at, NO_READING);
            Ok(())
        }
    }
}

impl Telemetry {
    /// The longest telemetry frame (the 53-byte BLE layout).
    pub const MAX_LEN: usize = MAX_FRAME_LEN;

    /// A frame that passed framing (start byte, telemetry id, a layout's
    /// length and checksum already checked) as telemetry.
    #[inline(always)]
    pub(crate) fn parse_framed(frame: &[u8]) -> Result<Telemetry, Error> {
        let layout = Layout::from_len(frame.len()).ok_or(Error::Truncated { len: frame.len() })?;
        Ok(Telemetry::parse(layout, frame))
    }

    /// Read the fields of `frame`, which has `layout`'s length.
    #[inline(always)]
    pub(crate) fn parse(layout: Layout, frame: &[u8]) -> Telemetry {
        // One fixed-size reader per layout: every offset below is then a
        // constant into a fixed array, so the reads need no bounds checks.
        match layout {
            Layout::Pos7 => parse_fixed::<7>(Layout::Pos7, frame),
            Layout::Uwb15 => parse_fixed::<15>(Layout::Uwb15, frame),
            Layout::UwbTof17 => parse_fixed::<17>(Layout::UwbTof17, frame),
            Layout::Spi45 => parse_fixed::<45>(Layout::Spi45, frame),
            Layout::Ble53 => parse_fixed::<53>(Layout::Ble53, frame),
        }
    }

    /// A telemetry message of `layout` with every carried reading absent
    /// (`0xFFFF`), a zero IMU sample and zero ADCs: a starting point to fill.
    pub const fn empty(layout: Layout) -> Telemetry {
        let at = offsets(layout);
        Telemetry {
            layout,
            m1_pos: None,
            m2_pos: None,
            uwb: if at.uwb.is_some() {
                Some([None; 4])
            } else {
                None
            },
            tof: if at.tof.is_some() { Some(None) } else { None },
            imu: if at.imu.is_some() {
                Some(Imu::from_array([0.0; 6]))
            } else {
                None
            },
            m1_adcs: if at.adcs.is_some() {
                Some([0; 4])
            } else {
                None
            },
            m2_adcs: if at.adcs.is_some() {
                Some([0; 2])
            } else {
                None
            },
        }
    }

    /// Whether every field group is present exactly when the layout carries it.
    pub const fn is_consistent(&self) -> bool {
        let at = offsets(self.layout);
        at.uwb.is_some() == self.uwb.is_some()
            && at.tof.is_some() == self.tof.is_some()
            && at.imu.is_some() == self.imu.is_some()
            && at.adcs.is_some() == self.m1_adcs.is_some()
            && at.adcs.is_some() == self.m2_adcs.is_some()
    }
}

impl Encode for Telemetry {
    const MAX_LEN: usize = Telemetry::MAX_LEN;

    fn encoded_len(&self) -> usize {
        self.layout.frame_len()
    }

    /// Encode the frame. Fails with [`EncodeError::Inconsistent`] when a field
    /// group is present that the layout does not carry (or missing that it
    /// does), and with [`EncodeError::OutOfRange`] for `Some(0xFFFF)`, which
    /// would decode as `None`.
    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        let len = self.layout.frame_len();
        check_room(out, len)?;
        if !self.is_consistent() {
            return Err(EncodeError::Inconsistent {
                what: "a field group is present exactly when the layout carries it",
            });
        }
        let Some(out) = out.get_mut(..len) else {
            return Err(EncodeError::BufferTooSmall {
                needed: len,
                available: out.len(),
            });
        };
        let at = offsets(self.layout);
        put_u16(out, 0, u16::from_le_bytes([START, id::TELEMETRY]));
        put_reading(out, 2, self.m1_pos, "m1_pos")?;
        put_reading(out, 4, self.m2_pos, "m2_pos")?;
        if let (Some(o), Some(uwb)) = (at.uwb, self.uwb) {
            for (i, d) in uwb.into_iter().enumerate() {
                put_reading(out, o + 2 * i, d, "uwb")?;
            }
        }
        if let (Some(o), Some(tof)) = (at.tof, self.tof) {
            put_reading(out, o, tof, "tof")?;
        }
        if let (Some(o), Some(imu)) = (at.imu, self.imu) {
            for (i, v) in imu.to_array().into_iter().enumerate() {
                if let Some(dst) = out.get_mut(o + 4 * i..o + 4 * i + 4) {
                    dst.copy_from_slice(&v.to_bits().to_le_bytes());
                }
            }
        }
        if let (Some(o), Some(m1), Some(m2)) = (at.adcs, self.m1_adcs, self.m2_adcs) {
            for (i, v) in m1.into_iter().enumerate() {
                put_u16(out, o + 2 * i, v);
            }
            for (i, v) in m2.into_iter().enumerate() {
                put_u16(out, o + M1_ADCS_LEN + 2 * i, v);
            }
        }
        if let [_, body @ .., sum] = out {
            *sum = checksum(body);
        }
        Ok(len)
    }
}

/// One whole telemetry frame, start byte to checksum, whose length is a
/// layout's: nothing before it and nothing after it.
///
/// ```
/// use robowire::omnitiles::{Error, Telemetry};
/// let frame = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
/// assert!(Telemetry::try_from(&frame[..]).is_ok());
/// assert_eq!(Telemetry::try_from(&frame[..6]), Err(Error::BadLength { len: 6 }));
/// assert_eq!(Telemetry::try_from(&[0xa5, 0x50, 0x50][..]), Err(Error::UnknownId { id: 0x50 }));
/// ```
impl TryFrom<&[u8]> for Telemetry {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Telemetry, Error> {
        Ok(Telemetry::parse(checked_layout(frame)?, frame))
    }
}

/// The layout of one whole telemetry frame, after checking its start byte,
/// id, length and checksum.
pub(super) fn checked_layout(frame: &[u8]) -> Result<Layout, Error> {
    let id = start_and_id(frame)?;
    if id != id::TELEMETRY {
        return Err(Error::UnknownId { id });
    }
    let layout = Layout::from_len(frame.len()).ok_or(Error::BadLength { len: frame.len() })?;
    check_whole(frame, layout.frame_len())?;
    Ok(layout)
}

/// A reading for `Display`: the number, or `null` for no reading.
struct Reading(Option<u16>);

impl fmt::Display for Reading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(v) => write!(f, "{v}"),
            None => f.write_str("null"),
        }
    }
}

/// `[a,b,…]`, each item written by `item`.
fn list<T: Copy>(
    f: &mut fmt::Formatter<'_>,
    items: &[T],
    item: impl Fn(&mut fmt::Formatter<'_>, T) -> fmt::Result,
) -> fmt::Result {
    f.write_str("[")?;
    for (i, &x) in items.iter().enumerate() {
        if i > 0 {
            f.write_str(",")?;
        }
        item(f, x)?;
    }
    f.write_str("]")
}

/// One line with the JSON form's words: `telemetry`, then `field=value` pairs
/// for the fields the layout carries, `null` for no reading:
/// `telemetry layout=uwb15 m1_pos=2000 m2_pos=1000 uwb=[1500,2500,null,3000]`.
/// IMU values are Rust's `f32` forms (`0.1`, `inf`, `NaN`).
impl fmt::Display for Telemetry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "telemetry layout={} m1_pos={} m2_pos={}",
            self.layout,
            Reading(self.m1_pos),
            Reading(self.m2_pos)
        )?;
        if let Some(uwb) = self.uwb {
            f.write_str(" uwb=")?;
            list(f, &uwb, |f, d| write!(f, "{}", Reading(d)))?;
        }
        if let Some(tof) = self.tof {
            write!(f, " tof={}", Reading(tof))?;
        }
        if let Some(imu) = self.imu {
            f.write_str(" imu={")?;
            for (i, (name, v)) in Imu::NAMES.iter().zip(imu.to_array()).enumerate() {
                let sep = if i == 0 { "" } else { "," };
                write!(f, "{sep}{name}={v}")?;
            }
            f.write_str("}")?;
        }
        if let Some(adcs) = self.m1_adcs {
            f.write_str(" m1_adcs=")?;
            list(f, &adcs, |f, v| write!(f, "{v}"))?;
        }
        if let Some(adcs) = self.m2_adcs {
            f.write_str(" m2_adcs=")?;
            list(f, &adcs, |f, v| write!(f, "{v}"))?;
        }
        Ok(())
    }
}
