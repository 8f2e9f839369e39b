//! The two kinds of error kept apart: what the codec found wrong with bytes
//! ([`Error`], [`Malformed`]) and what the device said went wrong
//! ([`DeviceError`], carried by an ERROR packet); and [`NameError`], a name
//! that names nothing.

use core::fmt;
use core::str::FromStr;

/// Why a candidate frame was rejected or a frame's payload could not be parsed.
///
/// These are the codec's own findings about the bytes. They are events: the
/// decoder reports them and goes on. What the *device* reports in an ERROR
/// packet is a [`DeviceError`] inside a successfully decoded
/// [`Response::Error`](super::Response::Error).
///
/// With the `serde` feature an error is an object with an `error` tag and its
/// details, as `robowire decode pixy2 --errors` prints it:
/// `{"error":"checksum","expected":781,"found":780}`,
/// `{"error":"bad_length","packet_type":18,"payload_len":3}`,
/// `{"error":"malformed","packet_type":49,"what":"section_length","ftype":1,"flen":5}`.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A sync start byte (`0xae` or `0xaf`) not followed by `0xc1`.
    #[error("sync start byte not followed by 0xc1 (found 0x{found:02x})")]
    Sync {
        /// The byte found where `0xc1` belongs.
        found: u8,
    },
    /// A packet type this decoder does not accept (unknown, or a message of
    /// the other direction).
    #[error("packet type 0x{packet_type:02x} is not accepted by this decoder")]
    UnknownType {
        /// The type byte.
        packet_type: u8,
    },
    /// A payload length the packet type cannot have (spec §4, §7.4 item 4).
    #[error("packet type 0x{packet_type:02x} cannot carry a {len}-byte payload")]
    BadLength {
        /// The type byte.
        packet_type: u8,
        /// The length byte.
        len: u8,
    },
    /// A request longer than the device's receive limit: the device drops it
    /// without answering (spec §3, §7.2).
    #[error("request of {len} payload bytes exceeds the device's {max}-byte receive limit")]
    TooLong {
        /// The type byte.
        packet_type: u8,
        /// The length byte.
        len: u8,
        /// The limit (64).
        max: u8,
    },
    /// The payload does not add up to the checksum in the header.
    #[error("checksum mismatch: header says 0x{expected:04x}, payload sums to 0x{found:04x}")]
    Checksum {
        /// The checksum field of the header.
        expected: u16,
        /// The wrapping 16-bit sum of the payload bytes.
        found: u16,
    },
    /// The input ended inside a candidate frame.
    #[error("input ended inside a {len}-byte candidate frame")]
    Truncated {
        /// Bytes of the candidate that were available.
        len: usize,
    },
    /// A candidate found after a resync validated, but a frame starting inside
    /// it validated too and only that frame is followed by a plausible header
    /// (the engine's resync verification): the candidate was set aside.
    #[error("a {len}-byte candidate overlapped a confirmed frame and was set aside")]
    Superseded {
        /// The candidate's length.
        len: usize,
    },
    /// A slice given as one whole frame (`TryFrom<&[u8]>`) goes on past the
    /// frame its header describes.
    #[error("{extra} bytes follow the frame")]
    TrailingBytes {
        /// Bytes after the frame's end.
        extra: usize,
    },
    /// The header and (if present) the checksum are fine but the payload's
    /// contents are not (spec §7.4 item 5, §4.3).
    #[error("packet type 0x{packet_type:02x}: {what}")]
    Malformed {
        /// The type byte.
        packet_type: u8,
        /// What is wrong with the payload.
        what: Malformed,
    },
}

/// What is wrong inside a payload whose length fits its type.
///
/// With the `serde` feature: an object with a `what` tag and its details
/// (`{"what":"intersection_lines","n":7}`), the part of an
/// [`Error::Malformed`] after its `packet_type`.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Malformed {
    /// A line-features section header or body runs past the payload end.
    #[error("line feature section at payload offset {offset} runs past the payload end")]
    SectionPastEnd {
        /// Offset of the section's type byte within the payload.
        offset: usize,
    },
    /// A known line-features section whose length is not a multiple of its
    /// element size (6, 28 or 4).
    #[error(
        "line feature section type {ftype} has length {flen}, not a multiple of its element size"
    )]
    SectionLength {
        /// The section's feature type.
        ftype: u8,
        /// The section's length byte.
        flen: u8,
    },
    /// An intersection that claims more than its six line slots.
    #[error("intersection claims {n} lines, at most 6 fit")]
    IntersectionLines {
        /// The claimed number of lines.
        n: u8,
    },
    /// A line-features payload longer than the 255 bytes a packet can carry.
    #[error("line features payload of {len} bytes is longer than 255")]
    TooLong {
        /// The payload length.
        len: usize,
    },
    /// A blocks payload that is not a whole number (at most 18) of 14-byte
    /// blocks.
    #[error("blocks payload of {len} bytes is not 14 * k bytes with k <= 18")]
    BlocksLength {
        /// The payload length.
        len: usize,
    },
    /// getBlocks with an empty signature map: the device answers ERROR −3
    /// rather than an empty list (spec §4.3). No longer produced by the
    /// decoders, which read such a request as the
    /// [`GetBlocks`](super::GetBlocks) it is.
    #[error("getBlocks with signature map 0 (the device answers ERROR -3)")]
    ZeroSigmap,
}

/// An error code the device sent in an ERROR (0x03) packet (spec §5).
///
/// These are the device's `SER_ERROR_*` codes. The official host library
/// reuses −3 and −4 for its own local failures; robowire never does: local
/// failures are [`Error`]s.
///
/// The six known codes have names ([`DeviceError::NAMES`], after
/// `SER_ERROR_*`): `general`, `busy`, `invalid_request`, `type_unsupported`,
/// `button_override`, `prog_changing`. [`FromStr`] reads a name or any code
/// as a number; with the `serde` feature a known code is its name, any other
/// code its number (`"busy"`, `-7`), as in the `code` of an ERROR response.
/// [`Display`](fmt::Display) is the error message (`device error -2: busy`).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
pub enum DeviceError {
    /// −1: general failure (e.g. reverseVector with no primary vector).
    #[error("device error -1: general failure")]
    General,
    /// −2: busy: no new frame since the last get, or getVersion during boot.
    #[error("device error -2: busy")]
    Busy,
    /// −3: invalid request: wrong length, signature map 0, unknown program name.
    #[error("device error -3: invalid request")]
    InvalidRequest,
    /// −4: no handler for the request type.
    #[error("device error -4: request type unsupported")]
    TypeUnsupported,
    /// −5: the user holds the button (program-range requests only).
    #[error("device error -5: button override")]
    ButtonOverride,
    /// −6: a program switch is in progress, or no program runs yet.
    #[error("device error -6: program changing")]
    ProgChanging,
    /// Any other code, preserved as sent. [`DeviceError::from_code`] never
    /// produces this for −1..=−6.
    #[error("device error {0}: unknown code")]
    Unknown(i8),
}

impl DeviceError {
    /// The names of the six known codes, −1 to −6.
    pub const NAMES: [&'static str; 6] = [
        "general",
        "busy",
        "invalid_request",
        "type_unsupported",
        "button_override",
        "prog_changing",
    ];

    /// The name of a known code; `None` for [`DeviceError::Unknown`].
    pub const fn name(self) -> Option<&'static str> {
        match self {
            Self::Unknown(_) => None,
            // −1..=−6 map to 0..=5.
            known => Some(Self::NAMES[(-1 - known.code() as i16) as usize]),
        }
    }

    /// The error for a code as sent on the wire.
    pub const fn from_code(code: i8) -> Self {
        match code {
            -1 => Self::General,
            -2 => Self::Busy,
            -3 => Self::InvalidRequest,
            -4 => Self::TypeUnsupported,
            -5 => Self::ButtonOverride,
            -6 => Self::ProgChanging,
            other => Self::Unknown(other),
        }
    }

    /// The code as sent on the wire.
    pub const fn code(self) -> i8 {
        match self {
            Self::General => -1,
            Self::Busy => -2,
            Self::InvalidRequest => -3,
            Self::TypeUnsupported => -4,
            Self::ButtonOverride => -5,
            Self::ProgChanging => -6,
            Self::Unknown(code) => code,
        }
    }
}

/// Reads a name of [`DeviceError::NAMES`] or a code as a decimal number
/// (`busy`, `-2`, `-7`).
impl FromStr for DeviceError {
    type Err = NameError;

    fn from_str(s: &str) -> Result<Self, NameError> {
        if let Some(i) = Self::NAMES.iter().position(|n| *n == s) {
            return Ok(Self::from_code(-1 - i as i8));
        }
        s.parse::<i8>()
            .map(Self::from_code)
            .map_err(|_| NameError::new("device error", &Self::NAMES))
    }
}

/// A name that names nothing, from a `FromStr` of a Pixy2 type.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NameError {
    what: &'static str,
    names: &'static [&'static str],
}

impl NameError {
    pub(crate) const fn new(what: &'static str, names: &'static [&'static str]) -> Self {
        Self { what, names }
    }

    /// What was being named (`"frame form"`, `"device error"` …).
    pub const fn what(&self) -> &'static str {
        self.what
    }

    /// The names that would have been accepted.
    pub const fn names(&self) -> &'static [&'static str] {
        self.names
    }
}

impl fmt::Display for NameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "no {} is called that (expected ", self.what)?;
        for (i, name) in self.names.iter().enumerate() {
            let sep = if i == 0 { "" } else { ", " };
            write!(f, "{sep}{name}")?;
        }
        f.write_str(")")
    }
}

impl core::error::Error for NameError {}
