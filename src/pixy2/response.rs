//! Device → host responses (spec §4.1–§4.5): the borrowed [`Response`] (blocks
//! and line features are zero-copy views) and its owned form
//! [`ResponseBuf`].

use core::fmt;

use crate::encode::EncodeError;

use super::blocks::{blocks_len_ok, Blocks, BlocksBuf};
use super::error::{DeviceError, Error};
use super::features::{Features, FeaturesBuf, Section};
use super::wire::{packet_type as ty, Body, Form};

/// The firmware type field of a version response: 10 bytes, NUL-padded, not
/// NUL-terminated when all 10 are used. All 10 bytes are kept as received.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct FirmwareType(pub [u8; 10]);

impl FirmwareType {
    /// `general`, the serial firmware.
    pub const GENERAL: Self = Self(*b"general\0\0\0");
    /// `LEGO`, the LEGO firmware (its protocol is out of scope).
    pub const LEGO: Self = Self(*b"LEGO\0\0\0\0\0\0");

    /// `name` NUL-padded; at most 10 bytes.
    pub fn new(name: &str) -> Result<Self, EncodeError> {
        let b = name.as_bytes();
        let mut out = [0u8; 10];
        out.get_mut(..b.len())
            .ok_or(EncodeError::TooLong {
                len: b.len(),
                max: 10,
            })?
            .copy_from_slice(b);
        Ok(Self(out))
    }

    /// The name: bytes up to the first NUL, or all 10.
    pub fn as_bytes(&self) -> &[u8] {
        let end = memchr::memchr(0, &self.0).unwrap_or(self.0.len());
        &self.0[..end]
    }

    /// The name as text, if it is UTF-8.
    pub fn as_str(&self) -> Option<&str> {
        core::str::from_utf8(self.as_bytes()).ok()
    }
}

impl fmt::Debug for FirmwareType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "FirmwareType(\"{}\")", self.as_bytes().escape_ascii())
    }
}

/// The version response (0x0f, 16 bytes).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Version {
    /// Hardware version (e.g. 0x2200).
    pub hardware: u16,
    /// Firmware major version.
    pub firmware_major: u8,
    /// Firmware minor version.
    pub firmware_minor: u8,
    /// Firmware build number.
    pub firmware_build: u16,
    /// Firmware type (`general`, `LEGO`).
    pub firmware_type: FirmwareType,
}

impl Version {
    /// Payload length.
    pub const SIZE: usize = 16;

    fn from_bytes(b: &[u8; Self::SIZE]) -> Self {
        let mut name = [0u8; 10];
        name.copy_from_slice(&b[6..]);
        Self {
            hardware: u16::from_le_bytes([b[0], b[1]]),
            firmware_major: b[2],
            firmware_minor: b[3],
            firmware_build: u16::from_le_bytes([b[4], b[5]]),
            firmware_type: FirmwareType(name),
        }
    }

    fn to_bytes(self) -> [u8; Self::SIZE] {
        let mut b = [0u8; Self::SIZE];
        b[..2].copy_from_slice(&self.hardware.to_le_bytes());
        b[2] = self.firmware_major;
        b[3] = self.firmware_minor;
        b[4..6].copy_from_slice(&self.firmware_build.to_le_bytes());
        b[6..].copy_from_slice(&self.firmware_type.0);
        b
    }
}

/// The resolution response (0x0d): 316 × 208 for blocks and video, 79 × 52
/// (the line grid) in line tracking.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Resolution {
    /// Frame width.
    pub width: u16,
    /// Frame height.
    pub height: u16,
}

/// A colour, as getRGB answers it: RESULT `0x00RRGGBB` (wire bytes B, G, R, 0).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Rgb {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

impl Rgb {
    /// The colour in a RESULT value, if its top byte is 0.
    pub const fn from_result(value: i32) -> Option<Self> {
        let [b, g, r, top] = value.to_le_bytes();
        if top == 0 {
            Some(Self { r, g, b })
        } else {
            None
        }
    }

    /// The RESULT value `0x00RRGGBB`.
    pub const fn to_result(self) -> i32 {
        i32::from_le_bytes([self.b, self.g, self.r, 0])
    }
}

/// Any device → host response, borrowing blocks and line features from the
/// frame.
///
/// One whole frame parses with `Response::try_from(frame)` (either form, the
/// sync word included; a checksum is verified); a response encodes in the
/// checksum form, as the device sends it (wrap it in an
/// [`Envelope`](super::Envelope) to choose).
///
/// Its [`Display`](fmt::Display) form is one line of the JSON words:
/// `error code=busy`, `resolution width=316 height=208`. With the `serde`
/// feature it is the JSON object `robowire` prints and reads, a `type` from
/// [`Response::NAMES`] and the response's fields:
/// `{"type":"error","code":"busy"}`, `{"type":"blocks","blocks":[…]}`,
/// `{"type":"features","sections":[{"vectors":[…]},…]}`. It serializes exactly
/// as [`ResponseBuf`] does, and only [`ResponseBuf`] deserializes ([`Blocks`]
/// has nothing to borrow from a serialized form).
///
/// ```
/// use robowire::pixy2::{DeviceError, Response};
///
/// let frame = [0xaf, 0xc1, 0x03, 0x01, 0xfe, 0x00, 0xfe];
/// let response = Response::try_from(&frame[..])?;
/// assert_eq!(response, Response::Error(DeviceError::Busy));
/// assert_eq!(response.to_string(), "error code=busy");
/// # Ok::<(), robowire::pixy2::Error>(())
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Response<'a> {
    /// 0x01: the generic result, a full i32 (frames per second, getRGB's
    /// colour, changeProg's status, 0 for the setters).
    Result(i32),
    /// 0x03: the device refused or failed the request.
    Error(DeviceError),
    /// 0x0d: getResolution's answer.
    Resolution(Resolution),
    /// 0x0f: getVersion's answer.
    Version(Version),
    /// 0x21: getBlocks's answer.
    Blocks(Blocks<'a>),
    /// 0x31: getFeatures's answer.
    Features(Features<'a>),
}

/// The owned form of [`Response`], with fixed-capacity blocks and features;
/// displays and serializes as [`Response`] does.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResponseBuf {
    /// As [`Response::Result`].
    Result(i32),
    /// As [`Response::Error`].
    Error(DeviceError),
    /// As [`Response::Resolution`].
    Resolution(Resolution),
    /// As [`Response::Version`].
    Version(Version),
    /// As [`Response::Blocks`], owned.
    Blocks(BlocksBuf),
    /// As [`Response::Features`], owned.
    Features(FeaturesBuf),
}

/// Header check for a response: a known type with a length it can have
/// (spec §7.4 item 4). Line features can have any length; their sections are
/// checked once the payload is there.
#[inline]
pub(crate) fn check_response_header(packet_type: u8, len: u8) -> Result<(), Error> {
    // Blocks first: by far the commonest response (the switch below is a
    // jump table the blocks test would otherwise wait for).
    if packet_type == ty::BLOCKS {
        return if blocks_len_ok(len) {
            Ok(())
        } else {
            Err(Error::BadLength { packet_type, len })
        };
    }
    let ok = match packet_type {
        ty::RESULT | ty::RESOLUTION => len == 4,
        ty::ERROR => len == 1,
        ty::VERSION => usize::from(len) == Version::SIZE,
        ty::FEATURES => true,
        _ => return Err(Error::UnknownType { packet_type }),
    };
    if ok {
        Ok(())
    } else {
        Err(Error::BadLength { packet_type, len })
    }
}

/// Whether `packet_type` is a response type.
pub(crate) const fn is_response_type(packet_type: u8) -> bool {
    matches!(
        packet_type,
        ty::RESULT | ty::ERROR | ty::RESOLUTION | ty::VERSION | ty::BLOCKS | ty::FEATURES
    )
}

impl<'a> Response<'a> {
    /// Every response's `type` name, in packet type order.
    pub const NAMES: [&'static str; 6] = [
        "result",
        "error",
        "resolution",
        "version",
        "blocks",
        "features",
    ];

    /// The `type` name (one of [`Response::NAMES`]).
    pub const fn name(&self) -> &'static str {
        Self::NAMES[match self {
            Self::Result(_) => 0,
            Self::Error(_) => 1,
            Self::Resolution(_) => 2,
            Self::Version(_) => 3,
            Self::Blocks(_) => 4,
            Self::Features(_) => 5,
        }]
    }

    /// A getRGB answer: RESULT `0x00RRGGBB`.
    pub const fn rgb(color: Rgb) -> Self {
        Self::Result(color.to_result())
    }

    /// The packet type byte.
    pub const fn packet_type(&self) -> u8 {
        match self {
            Self::Result(_) => ty::RESULT,
            Self::Error(_) => ty::ERROR,
            Self::Resolution(_) => ty::RESOLUTION,
            Self::Version(_) => ty::VERSION,
            Self::Blocks(_) => ty::BLOCKS,
            Self::Features(_) => ty::FEATURES,
        }
    }

    /// The payload length.
    pub const fn payload_len(&self) -> usize {
        match self {
            Self::Result(_) | Self::Resolution(_) => 4,
            Self::Error(_) => 1,
            Self::Version(_) => Version::SIZE,
            Self::Blocks(b) => b.as_bytes().len(),
            Self::Features(f) => f.as_bytes().len(),
        }
    }

    /// Parse a response from its type and payload (blocks and features are
    /// borrowed from `payload`).
    #[inline(always)]
    pub(crate) fn from_payload(packet_type: u8, payload: &'a [u8]) -> Result<Self, Error> {
        // Each arm checks the length its type needs, the same test as
        // `check_response_header` (which the decoder has already passed):
        // nothing is checked twice on the way from the frame to the message.
        let bad_length = || Error::BadLength {
            packet_type,
            len: u8::try_from(payload.len()).unwrap_or(u8::MAX),
        };
        Ok(match packet_type {
            ty::BLOCKS => Self::Blocks(Blocks::new(payload).ok_or_else(bad_length)?),
            ty::RESULT => Self::Result(i32::from_le_bytes(
                payload.try_into().map_err(|_| bad_length())?,
            )),
            ty::ERROR => match *payload {
                [code] => Self::Error(DeviceError::from_code(code as i8)),
                _ => return Err(bad_length()),
            },
            ty::RESOLUTION => match *payload {
                [w0, w1, h0, h1] => Self::Resolution(Resolution {
                    width: u16::from_le_bytes([w0, w1]),
                    height: u16::from_le_bytes([h0, h1]),
                }),
                _ => return Err(bad_length()),
            },
            ty::VERSION => Self::Version(Version::from_bytes(
                payload.try_into().map_err(|_| bad_length())?,
            )),
            ty::FEATURES => {
                // Any length up to 255 is a plausible features header.
                if payload.len() > usize::from(u8::MAX) {
                    return Err(bad_length());
                }
                Self::Features(
                    Features::new(payload)
                        .map_err(|what| Error::Malformed { packet_type, what })?,
                )
            }
            _ => return Err(Error::UnknownType { packet_type }),
        })
    }

    /// The owned form.
    pub fn to_owned(&self) -> ResponseBuf {
        match *self {
            Self::Result(v) => ResponseBuf::Result(v),
            Self::Error(e) => ResponseBuf::Error(e),
            Self::Resolution(r) => ResponseBuf::Resolution(r),
            Self::Version(v) => ResponseBuf::Version(v),
            Self::Blocks(b) => ResponseBuf::Blocks(b.to_owned()),
            Self::Features(f) => ResponseBuf::Features(f.to_owned()),
        }
    }
}

impl ResponseBuf {
    /// The borrowed form.
    pub fn as_response(&self) -> Response<'_> {
        match self {
            Self::Result(v) => Response::Result(*v),
            Self::Error(e) => Response::Error(*e),
            Self::Resolution(r) => Response::Resolution(*r),
            Self::Version(v) => Response::Version(*v),
            Self::Blocks(b) => Response::Blocks(b.view()),
            Self::Features(f) => Response::Features(f.view()),
        }
    }
}

/// The `type` name and the fields as `key=value`; blocks one `{…}` each,
/// line features the element count of each section:
/// `version hardware=8704 firmware_major=3 firmware_minor=0 firmware_build=10
/// firmware_type=general`, `blocks {signature=1 x=100 y=50 width=20 height=10
/// angle=0 index=3 age=255}`, `features vectors=1 intersections=1 barcodes=1`.
impl fmt::Display for Response<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())?;
        match *self {
            Self::Result(value) => write!(f, " value={value}"),
            Self::Error(e) => match e.name() {
                Some(name) => write!(f, " code={name}"),
                None => write!(f, " code={}", e.code()),
            },
            Self::Resolution(Resolution { width, height }) => {
                write!(f, " width={width} height={height}")
            }
            Self::Version(v) => {
                let name = &v.firmware_type.0;
                let end = name.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
                write!(
                    f,
                    " hardware={} firmware_major={} firmware_minor={} firmware_build={} \
                     firmware_type={}",
                    v.hardware,
                    v.firmware_major,
                    v.firmware_minor,
                    v.firmware_build,
                    name[..end].escape_ascii()
                )
            }
            Self::Blocks(blocks) => {
                for b in blocks {
                    write!(
                        f,
                        " {{signature={} x={} y={} width={} height={} angle={} index={} age={}}}",
                        b.signature, b.x, b.y, b.width, b.height, b.angle, b.index, b.age
                    )?;
                }
                Ok(())
            }
            Self::Features(features) => {
                for section in features.sections() {
                    match section {
                        Section::Vectors(v) => write!(f, " vectors={}", v.len())?,
                        Section::Intersections(i) => write!(f, " intersections={}", i.len())?,
                        Section::Barcodes(b) => write!(f, " barcodes={}", b.len())?,
                        Section::Unknown { ftype, data } => {
                            write!(f, " ftype={ftype} data_len={}", data.len())?
                        }
                    }
                }
                Ok(())
            }
        }
    }
}

/// As [`Response`]'s.
impl fmt::Display for ResponseBuf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.as_response(), f)
    }
}

impl<'a> From<&'a ResponseBuf> for Response<'a> {
    fn from(r: &'a ResponseBuf) -> Self {
        r.as_response()
    }
}

impl Body for Response<'_> {
    fn packet_type(&self) -> u8 {
        Response::packet_type(self)
    }

    fn payload_len(&self) -> usize {
        Response::payload_len(self)
    }

    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError> {
        let mut scratch = [0u8; Version::SIZE];
        let src: &[u8] = match self {
            Self::Result(v) => {
                scratch[..4].copy_from_slice(&v.to_le_bytes());
                &scratch[..4]
            }
            Self::Error(e) => {
                scratch[0] = e.code() as u8;
                &scratch[..1]
            }
            Self::Resolution(r) => {
                scratch[..2].copy_from_slice(&r.width.to_le_bytes());
                scratch[2..4].copy_from_slice(&r.height.to_le_bytes());
                &scratch[..4]
            }
            Self::Version(v) => {
                scratch = v.to_bytes();
                &scratch
            }
            Self::Blocks(b) => b.as_bytes(),
            Self::Features(f) => f.as_bytes(),
        };
        let available = out.len();
        out.get_mut(..src.len())
            .ok_or(EncodeError::BufferTooSmall {
                needed: src.len(),
                available,
            })?
            .copy_from_slice(src);
        Ok(())
    }

    fn default_form(&self) -> Form {
        Form::Checksum
    }
}

impl Body for ResponseBuf {
    fn packet_type(&self) -> u8 {
        self.as_response().packet_type()
    }

    fn payload_len(&self) -> usize {
        self.as_response().payload_len()
    }

    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError> {
        self.as_response().write_payload(out)
    }

    fn default_form(&self) -> Form {
        Form::Checksum
    }
}
