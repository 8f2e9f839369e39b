//! Host → device requests (spec §4.2–§4.5), one type per request and the
//! [`Request`] enum over all of them.
//!
//! Fields hold the values as the device reads them. The encoder rejects only
//! what the device would refuse with ERROR −3 (getBlocks signature map 0) or
//! drop (a payload over 64 bytes). Values the device accepts are passed
//! through unchanged, as documented on each field: servo positions above 1000
//! (ignored, still RESULT 0), getRGB coordinates past the frame (clamped),
//! mode bits it does not know (ignored), any nonzero byte for on/true.

use core::fmt;
use core::str::FromStr;

use crate::encode::EncodeError;

use super::error::Error;
use super::table::kind_shown;
use super::wire::{packet_type as ty, Body, Form, DEVICE_MAX_PAYLOAD};

/// A program name as sent by changeProg: the raw payload, at most 64 bytes.
///
/// The official host sends the name NUL-padded to 33 bytes
/// ([`ProgName::new`] does the same). The device matches the bytes up to the
/// first NUL as a *prefix* of its program names (`"line"` selects
/// `line_tracking`, an empty name program 0) and does not check the length.
///
/// With the `serde` feature it serializes as its payload bytes, padding
/// included (a byte string; an array of numbers in JSON); deserializing
/// refuses more than 64 bytes. [`FromStr`] is [`ProgName::new`];
/// [`Display`](fmt::Display) writes the name (bytes up to the first NUL,
/// non-ASCII bytes escaped).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct ProgName {
    bytes: [u8; DEVICE_MAX_PAYLOAD],
    len: u8,
}

impl ProgName {
    /// Payload length the official host uses (`PIXY_MAX_PROGNAME`).
    pub const PADDED_LEN: usize = 33;
    /// `color_connected_components` (blocks).
    pub const COLOR_CONNECTED_COMPONENTS: Self = Self::padded(b"color_connected_components");
    /// `line_tracking` (line features).
    pub const LINE_TRACKING: Self = Self::padded(b"line_tracking");
    /// `video` (getRGB).
    pub const VIDEO: Self = Self::padded(b"video");
    /// `pan_tilt_demo`.
    pub const PAN_TILT_DEMO: Self = Self::padded(b"pan_tilt_demo");

    /// `name` NUL-padded to 33 bytes, as the official host sends it. The name
    /// must be at most 32 bytes (a NUL always follows) and contain no NUL.
    pub const fn new(name: &str) -> Result<Self, EncodeError> {
        let b = name.as_bytes();
        if b.len() >= Self::PADDED_LEN {
            return Err(EncodeError::TooLong {
                len: b.len(),
                max: Self::PADDED_LEN - 1,
            });
        }
        let mut i = 0;
        while i < b.len() {
            if b[i] == 0 {
                return Err(EncodeError::OutOfRange {
                    field: "program name (contains NUL)",
                });
            }
            i += 1;
        }
        Ok(Self::padded(b))
    }

    /// Copies at most 32 bytes of `name` into a 33-byte padded payload.
    const fn padded(name: &[u8]) -> Self {
        let mut bytes = [0u8; DEVICE_MAX_PAYLOAD];
        let mut i = 0;
        while i < name.len() && i < Self::PADDED_LEN - 1 {
            bytes[i] = name[i];
            i += 1;
        }
        Self {
            bytes,
            len: Self::PADDED_LEN as u8,
        }
    }

    /// The payload exactly as given (any length up to 64, the device's limit).
    pub fn from_payload(payload: &[u8]) -> Option<Self> {
        if payload.len() > DEVICE_MAX_PAYLOAD {
            return None;
        }
        let mut bytes = [0u8; DEVICE_MAX_PAYLOAD];
        bytes[..payload.len()].copy_from_slice(payload);
        Some(Self {
            bytes,
            len: payload.len() as u8,
        })
    }

    /// The payload bytes, padding included.
    pub fn as_payload(&self) -> &[u8] {
        &self.bytes[..usize::from(self.len)]
    }

    /// The name: the payload up to its first NUL.
    pub fn name(&self) -> &[u8] {
        let p = self.as_payload();
        let end = memchr::memchr(0, p).unwrap_or(p.len());
        &p[..end]
    }

    /// The name as text, if it is UTF-8.
    pub fn as_str(&self) -> Option<&str> {
        core::str::from_utf8(self.name()).ok()
    }
}

impl FromStr for ProgName {
    type Err = EncodeError;

    /// As [`ProgName::new`]: `"line"` is the padded name `line`.
    fn from_str(name: &str) -> Result<Self, EncodeError> {
        Self::new(name)
    }
}

impl fmt::Display for ProgName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name().escape_ascii())
    }
}

impl fmt::Debug for ProgName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ProgName")
            .field("name", &self.name().escape_ascii())
            .field("payload_len", &self.len)
            .finish()
    }
}

/// 0x02 changeProg: switch programs. Answer: RESULT 1 = already running,
/// 0 = switch pending (poll again); ERROR −3 for an unknown name.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ChangeProg(pub ProgName);

/// 0x0c getResolution. Answer: resolution (0x0d).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct GetResolution {
    /// Reserved "type" byte; send 0. Any value is passed through.
    pub reserved: u8,
}

/// 0x0e getVersion (also the ping: ERROR −2 until boot completes). Answer:
/// version (0x0f).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct GetVersion;

/// 0x10 setCameraBrightness. Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetCameraBrightness(pub u8);

/// 0x12 setServos. Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetServos {
    /// Servo 0 (pan), 0..=1000. Larger values are passed through: the device
    /// ignores them and still answers RESULT 0.
    pub pan: u16,
    /// Servo 1 (tilt), 0..=1000, as `pan`.
    pub tilt: u16,
}

impl SetServos {
    /// Largest position the device acts on.
    pub const MAX: u16 = 1000;
}

/// 0x14 setLED: override the RGB LED. Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetLed {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

/// 0x16 setLamp. Nonzero = on; bytes are passed through. Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetLamp {
    /// The two white LEDs on the top edge.
    pub upper: u8,
    /// All channels of the lower RGB LED.
    pub lower: u8,
}

impl SetLamp {
    /// Lamps on or off, sent as 1 or 0.
    pub const fn new(upper: bool, lower: bool) -> Self {
        Self {
            upper: upper as u8,
            lower: lower as u8,
        }
    }
}

/// 0x18 getFPS. Answer: RESULT = frames per second.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct GetFps;

/// 0x20 getBlocks (colour connected components). Answer: blocks (0x21), at
/// most `min(max_blocks, 18)`, largest first; ERROR −2 when no new frame yet.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GetBlocks {
    /// Which signatures: bit k = signature k+1 ([`GetBlocks::SIG1`] …),
    /// bit 7 = every colour code. 0 is what the official host library sends
    /// for an empty map, and the device answers it with ERROR −3: decoders
    /// accept it, the encoder refuses it unless asked with
    /// [`Envelope::even_if_refused`](super::Envelope::even_if_refused).
    pub sigmap: u8,
    /// Most blocks to return; 0 gives an empty list.
    pub max_blocks: u8,
}

impl GetBlocks {
    /// Signature 1.
    pub const SIG1: u8 = 0x01;
    /// Signature 2.
    pub const SIG2: u8 = 0x02;
    /// Signature 3.
    pub const SIG3: u8 = 0x04;
    /// Signature 4.
    pub const SIG4: u8 = 0x08;
    /// Signature 5.
    pub const SIG5: u8 = 0x10;
    /// Signature 6.
    pub const SIG6: u8 = 0x20;
    /// Signature 7.
    pub const SIG7: u8 = 0x40;
    /// Every colour code (signature > 7).
    pub const COLOR_CODES: u8 = 0x80;
    /// Everything.
    pub const ALL: u8 = 0xff;

    /// Whether a block with `signature` can answer this request.
    pub const fn wants(&self, signature: u16) -> bool {
        match signature {
            0 => false,
            1..=7 => self.sigmap & (1 << (signature - 1)) != 0,
            _ => self.sigmap & Self::COLOR_CODES != 0,
        }
    }
}

/// 0x30 getFeatures (line tracking). Answer: line features (0x31); ERROR −2
/// when no new frame yet.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GetFeatures {
    /// 0 = main features ([`GetFeatures::MAIN`]); any nonzero value = all
    /// features (the official host sends [`GetFeatures::ALL`] = 1).
    pub scope: u8,
    /// Which feature types: [`GetFeatures::VECTORS`] | …
    pub features: u8,
}

impl GetFeatures {
    /// `scope`: the main features only.
    pub const MAIN: u8 = 0;
    /// `scope`: every tracked feature.
    pub const ALL: u8 = 1;
    /// `features`: vectors.
    pub const VECTORS: u8 = 0x01;
    /// `features`: intersections.
    pub const INTERSECTIONS: u8 = 0x02;
    /// `features`: barcodes.
    pub const BARCODES: u8 = 0x04;
    /// `features`: all three.
    pub const ALL_FEATURES: u8 = 0x07;
}

/// 0x36 setMode: a bitmap of line-tracking modes. Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetMode(pub u8);

impl SetMode {
    /// Turn at an intersection only after setNextTurn.
    pub const TURN_DELAYED: u8 = 0x01;
    /// The host picks the primary vector with setVector.
    pub const MANUAL_SELECT_VECTOR: u8 = 0x02;
    /// Track a white line on a dark background.
    pub const WHITE_LINE: u8 = 0x80;
}

/// 0x38 setVector: choose the primary vector by tracking index. Answer:
/// RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetVector(pub u8);

/// 0x3a setNextTurn: degrees at the next intersection (0 = straight up the
/// image, +90 = left, −90 = right). Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetNextTurn(pub i16);

/// 0x3c setDefaultTurn: degrees when no next turn is set, as
/// [`SetNextTurn`]. Answer: RESULT 0.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SetDefaultTurn(pub i16);

/// 0x3e reverseVector. Answer: RESULT 0, or ERROR −1 with no primary vector.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ReverseVector;

/// 0x70 getRGB: the colour at a pixel. Answer: RESULT `0x00RRGGBB`.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct GetRgb {
    /// Column, 0..=315 (the device clamps larger values).
    pub x: u16,
    /// Row, 0..=207 (the device clamps larger values).
    pub y: u16,
    /// 1 = saturate the colour, 0 = raw; passed through.
    pub saturate: u8,
}

impl GetRgb {
    /// The pixel at (`x`, `y`), saturated or not.
    pub const fn new(x: u16, y: u16, saturate: bool) -> Self {
        Self {
            x,
            y,
            saturate: saturate as u8,
        }
    }
}

/// The request enum and its codec, from the request table (see
/// [`table`](super::table)).
macro_rules! request_codec {
    ($($(#[$m:meta])* $ty:ident $name:literal $s:ident -> $resp:ident $payload:tt;)*) => {
        /// Any host → device request.
        ///
        /// One whole frame parses with `Request::try_from(frame)` (either form, the
        /// sync word included, held to the device's 64-byte limit); a request
        /// encodes in the no-checksum form, as the official host sends it (wrap it in
        /// an [`Envelope`](super::Envelope) to choose).
        ///
        /// Its [`Display`](fmt::Display) form is one line of the JSON words:
        /// `get_blocks sigmap=255 max_blocks=255`. With the `serde` feature it is the
        /// JSON object `robowire` prints and reads, a `type` from
        /// [`Request::NAMES`] and the request's fields:
        /// `{"type":"get_blocks","sigmap":255,"max_blocks":255}`. Deserializing checks
        /// what the encoder checks, with messages that name the field, and ignores
        /// `offset`, `len` and `checksum` (an [`Envelope`](super::Envelope) reads
        /// `checksum`).
        ///
        /// ```
        /// use robowire::pixy2::{GetBlocks, Request};
        ///
        /// let frame = [0xae, 0xc1, 0x20, 0x02, 0xff, 0x03];
        /// let request = Request::try_from(&frame[..])?;
        /// assert_eq!(request, Request::from(GetBlocks { sigmap: 0xff, max_blocks: 3 }));
        /// assert_eq!(request.to_string(), "get_blocks sigmap=255 max_blocks=3");
        /// # Ok::<(), robowire::pixy2::Error>(())
        /// ```
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Request {
            $($(#[$m])* $s($s),)*
        }

        $(impl From<$s> for Request {
            fn from(r: $s) -> Self {
                Self::$s(r)
            }
        })*

        /// The payload length a request type must have: `Some(None)` = any
        /// length up to the device limit, `None` = not a request type.
        pub(crate) const fn request_len(packet_type: u8) -> Option<Option<u8>> {
            match packet_type {
                $(ty::$ty => Some(payload_size!($payload)),)*
                _ => None,
            }
        }

        impl Request {
            /// Every request's `type` name, in packet type order.
            pub const NAMES: [&'static str; 16] = [$($name),*];

            /// The `type` name (one of [`Request::NAMES`]).
            pub const fn name(&self) -> &'static str {
                match self {
                    $(Self::$s(_) => $name,)*
                }
            }

            /// The packet type byte.
            pub const fn packet_type(&self) -> u8 {
                match self {
                    $(Self::$s(_) => ty::$ty,)*
                }
            }

            /// The type of the successful answer: 0x0d, 0x0f, 0x21 or 0x31 for the
            /// four typed responses, RESULT (0x01) for everything else. ERROR (0x03)
            /// can answer any request.
            pub const fn response_type(&self) -> u8 {
                match self {
                    $(Self::$s(_) => ty::$resp,)*
                }
            }

            /// The payload length.
            pub fn payload_len(&self) -> usize {
                match self {
                    $(Self::$s(_r) => payload_len!(_r, $payload),)*
                }
            }

            /// Parse a request from its type and payload, as the device reads it.
            ///
            /// Errors: an unknown type, a length the type cannot have, a payload over
            /// the device's 64-byte limit.
            pub(crate) fn from_payload(packet_type: u8, payload: &[u8]) -> Result<Self, Error> {
                let len = u8::try_from(payload.len()).map_err(|_| Error::TooLong {
                    packet_type,
                    len: u8::MAX,
                    max: DEVICE_MAX_PAYLOAD as u8,
                })?;
                check_request_header(packet_type, len)?;
                let p = payload;
                Ok(match packet_type {
                    $(ty::$ty => Self::$s(parse_payload!(p, $s, packet_type, len, $payload)),)*
                    _ => return Err(Error::UnknownType { packet_type }),
                })
            }
        }

        /// The `type` name and every field the JSON form carries, as `key=value`:
        /// `set_servos pan=500 tilt=20`, `change_prog name=line`.
        impl fmt::Display for Request {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())?;
                match self {
                    $(Self::$s(_r) => display_payload!(f, _r, $payload),)*
                }
            }
        }

        impl Body for Request {
            fn packet_type(&self) -> u8 {
                Request::packet_type(self)
            }

            fn payload_len(&self) -> usize {
                Request::payload_len(self)
            }

            // `out` is exactly `payload_len` long (`Body`'s contract), and
            // each row's offsets and length come from the same fields.
            fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError> {
                match self {
                    $(Self::$s(_r) => { write_payload!(out, _r, $payload); })*
                }
                Ok(())
            }

            fn default_form(&self) -> Form {
                Form::NoChecksum
            }
        }
    };
}

/// A row's payload length: the sum of its fields', or `None` (any) for a
/// `custom` row.
macro_rules! payload_size {
    (custom) => {
        None
    };
    ($fields:tt) => {
        Some(fields_size!($fields))
    };
}

macro_rules! fields_size {
    ({ $($f:tt : $kind:ident $key:literal),* $(,)? }) => {
        0 $(+ kind_size!($kind))*
    };
}

macro_rules! kind_size {
    (u16) => {
        2
    };
    (i16) => {
        2
    };
    ($kind:ident) => {
        1
    };
}

macro_rules! payload_len {
    ($r:ident, custom) => {
        $r.payload_len()
    };
    ($r:ident, $fields:tt) => {
        fields_size!($fields)
    };
}

macro_rules! parse_payload {
    ($p:ident, $s:ident, $ty:ident, $len:ident, custom) => {
        $s::from_payload($ty, $len, $p)?
    };
    ($p:ident, $s:ident, $ty:ident, $len:ident, { $($fields:tt)* }) => {
        parse_fields!($p, $s, (0), [], $($fields)*)
    };
}

/// A row's struct read field by field at constant offsets (a muncher that
/// sums the sizes of the fields before each).
macro_rules! parse_fields {
    ($p:ident, $s:ident, $at:expr, [$($done:tt)*], $f:tt : $kind:ident $key:literal $(, $($rest:tt)*)?) => {
        parse_fields!($p, $s, ($at + kind_size!($kind)), [$($done)* $f: read_at!($p, $at, $kind),], $($($rest)*)?)
    };
    ($p:ident, $s:ident, $at:expr, [$($done:tt)*], ) => {
        $s { $($done)* }
    };
}

macro_rules! read_at {
    ($p:ident, $at:expr, u16) => {
        u16_at($p, $at)
    };
    ($p:ident, $at:expr, i16) => {
        u16_at($p, $at) as i16
    };
    ($p:ident, $at:expr, $kind:ident) => {
        u8_at($p, $at)
    };
}

macro_rules! display_payload {
    ($f:ident, $r:ident, custom) => {
        $r.fmt_fields($f)
    };
    ($f:ident, $r:ident, { $($field:tt : $kind:ident $key:literal),* $(,)? }) => {{
        $(if kind_shown!($kind, $r.$field) {
            write!($f, concat!(" ", $key, "={}"), $r.$field)?;
        })*
        Ok(())
    }};
}

macro_rules! write_payload {
    ($out:ident, $r:ident, custom) => {
        $r.write_payload($out)
    };
    ($out:ident, $r:ident, { $($fields:tt)* }) => {
        write_fields!($out, $r, (0), $($fields)*)
    };
}

/// A row's fields written at constant offsets (as `parse_fields` reads them).
macro_rules! write_fields {
    ($out:ident, $r:ident, $at:expr, $f:tt : $kind:ident $key:literal $(, $($rest:tt)*)?) => {
        write_at!($out, $at, $r.$f, $kind);
        write_fields!($out, $r, ($at + kind_size!($kind)), $($($rest)*)?)
    };
    ($out:ident, $r:ident, $at:expr, ) => {};
}

macro_rules! write_at {
    ($out:ident, $at:expr, $v:expr, u16) => {
        put_at($out, $at, &$v.to_le_bytes())
    };
    ($out:ident, $at:expr, $v:expr, i16) => {
        put_at($out, $at, &$v.to_le_bytes())
    };
    ($out:ident, $at:expr, $v:expr, sigmap) => {{
        if $v == 0 {
            return Err(EncodeError::OutOfRange {
                field: "getBlocks sigmap (0 is refused by the device)",
            });
        }
        put_at($out, $at, &[$v])
    }};
    ($out:ident, $at:expr, $v:expr, $kind:ident) => {
        put_at($out, $at, &[$v])
    };
}

super::table::request_table!(request_codec);

/// Two bytes at `i`, little-endian (0 past the end: the length is checked
/// first).
fn u16_at(p: &[u8], i: usize) -> u16 {
    match p.get(i..i + 2) {
        Some(&[a, b]) => u16::from_le_bytes([a, b]),
        _ => 0,
    }
}

/// The byte at `i` (0 past the end).
fn u8_at(p: &[u8], i: usize) -> u8 {
    p.get(i).copied().unwrap_or(0)
}

/// Write `bytes` at `i` (nothing past the end: the payload is exactly
/// `payload_len` long).
fn put_at(out: &mut [u8], i: usize, bytes: &[u8]) {
    if let Some(slot) = out.get_mut(i..i + bytes.len()) {
        slot.copy_from_slice(bytes);
    }
}

/// Header check for a request: a known type with a length the device takes.
/// The device drops payloads over 64 before it looks at the type, so that is
/// checked first.
pub(crate) fn check_request_header(packet_type: u8, len: u8) -> Result<(), Error> {
    let Some(exact) = request_len(packet_type) else {
        return Err(Error::UnknownType { packet_type });
    };
    if usize::from(len) > DEVICE_MAX_PAYLOAD {
        return Err(Error::TooLong {
            packet_type,
            len,
            max: DEVICE_MAX_PAYLOAD as u8,
        });
    }
    match exact {
        Some(n) if n != len => Err(Error::BadLength { packet_type, len }),
        _ => Ok(()),
    }
}

/// The `custom` row: a name of any length.
impl ChangeProg {
    fn payload_len(&self) -> usize {
        self.0.as_payload().len()
    }

    fn from_payload(packet_type: u8, len: u8, payload: &[u8]) -> Result<Self, Error> {
        match ProgName::from_payload(payload) {
            Some(name) => Ok(ChangeProg(name)),
            None => Err(Error::BadLength { packet_type, len }),
        }
    }

    fn fmt_fields(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let payload = self.0.as_payload();
        let end = payload.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
        write!(f, " name={}", payload[..end].escape_ascii())?;
        if payload.len() != ProgName::PADDED_LEN {
            write!(f, " payload_len={}", payload.len())?;
        }
        Ok(())
    }

    fn write_payload(&self, out: &mut [u8]) {
        put_at(out, 0, self.0.as_payload());
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for ProgName {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        crate::serde_support::serialize_bytes(self.as_payload(), serializer)
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for ProgName {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut bytes = [0u8; DEVICE_MAX_PAYLOAD];
        let len =
            crate::serde_support::bytes_into(deserializer, &mut bytes, "a Pixy2 program name")?;
        Ok(Self {
            bytes,
            len: len as u8,
        })
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for ProgName {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "ProgName {{ name: {=[u8]:a}, payload_len: {=u8} }}",
            self.name(),
            self.len
        )
    }
}
