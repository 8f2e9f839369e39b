//! The frame: its two forms, the checksum, packet type numbers, and the
//! [`Packet`] wrapper that picks a form for encoding and records it when
//! decoding.

use crate::encode::{check_room, Encode, EncodeError};

use super::request::Request;
use super::response::{Response, ResponseBuf};

/// Sync word of the no-checksum form, `ae c1` on the wire.
pub const SYNC_NO_CHECKSUM: u16 = 0xc1ae;
/// Sync word of the checksum form, `af c1` on the wire.
pub const SYNC_CHECKSUM: u16 = 0xc1af;
/// Longest payload the length byte can describe.
pub const MAX_PAYLOAD: usize = 255;
/// Longest frame: checksum header and a 255-byte payload.
pub const MAX_FRAME: usize = 6 + MAX_PAYLOAD;
/// Longest request payload the device receives; longer requests are dropped
/// without an answer (spec §3).
pub const DEVICE_MAX_PAYLOAD: usize = 64;

/// Packet type numbers (spec §4). Requests are even, responses odd.
pub mod packet_type {
    /// Generic result, 4-byte i32 (response).
    pub const RESULT: u8 = 0x01;
    /// changeProg (request).
    pub const CHANGE_PROG: u8 = 0x02;
    /// Generic error, 1-byte i8 code (response).
    pub const ERROR: u8 = 0x03;
    /// getResolution (request).
    pub const GET_RESOLUTION: u8 = 0x0c;
    /// Resolution (response).
    pub const RESOLUTION: u8 = 0x0d;
    /// getVersion (request).
    pub const GET_VERSION: u8 = 0x0e;
    /// Version (response).
    pub const VERSION: u8 = 0x0f;
    /// setCameraBrightness (request).
    pub const SET_CAMERA_BRIGHTNESS: u8 = 0x10;
    /// setServos (request).
    pub const SET_SERVOS: u8 = 0x12;
    /// setLED (request).
    pub const SET_LED: u8 = 0x14;
    /// setLamp (request).
    pub const SET_LAMP: u8 = 0x16;
    /// getFPS (request).
    pub const GET_FPS: u8 = 0x18;
    /// getBlocks (request).
    pub const GET_BLOCKS: u8 = 0x20;
    /// Blocks (response).
    pub const BLOCKS: u8 = 0x21;
    /// getFeatures (request).
    pub const GET_FEATURES: u8 = 0x30;
    /// Line features (response).
    pub const FEATURES: u8 = 0x31;
    /// setMode (request).
    pub const SET_MODE: u8 = 0x36;
    /// setVector (request).
    pub const SET_VECTOR: u8 = 0x38;
    /// setNextTurn (request).
    pub const SET_NEXT_TURN: u8 = 0x3a;
    /// setDefaultTurn (request).
    pub const SET_DEFAULT_TURN: u8 = 0x3c;
    /// reverseVector (request).
    pub const REVERSE_VECTOR: u8 = 0x3e;
    /// getRGB (request).
    pub const GET_RGB: u8 = 0x70;
}

/// The two frame forms (spec §2.1).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Form {
    /// `ae c1` · type · len · payload: what the official host sends.
    NoChecksum,
    /// `af c1` · type · len · checksum u16 LE · payload: what the device
    /// always sends over SPI, I2C and UART.
    Checksum,
}

impl Form {
    /// The form whose sync word starts with `byte`.
    pub const fn from_start_byte(byte: u8) -> Option<Self> {
        match byte {
            0xae => Some(Self::NoChecksum),
            0xaf => Some(Self::Checksum),
            _ => None,
        }
    }

    /// The sync word as it appears on the wire (low byte first).
    pub const fn sync_bytes(self) -> [u8; 2] {
        match self {
            Self::NoChecksum => SYNC_NO_CHECKSUM.to_le_bytes(),
            Self::Checksum => SYNC_CHECKSUM.to_le_bytes(),
        }
    }

    /// Bytes before the payload: 4 or 6.
    pub const fn header_len(self) -> usize {
        match self {
            Self::NoChecksum => 4,
            Self::Checksum => 6,
        }
    }
}

/// The checksum of a payload: the wrapping 16-bit sum of its bytes.
pub fn checksum(payload: &[u8]) -> u16 {
    payload
        .iter()
        .fold(0u16, |sum, &b| sum.wrapping_add(u16::from(b)))
}

/// A message together with the frame form it travels in.
///
/// Decoders yield `Packet`s so that the form is not lost (every decoded frame
/// re-encodes to the same bytes). For encoding, wrap a message to choose its
/// form; a bare [`Request`] encodes in the no-checksum form and a bare
/// [`Response`] in the checksum form.
///
/// ```
/// use robowire::pixy2::{Form, GetFps, Packet, Request};
/// use robowire::Encode;
///
/// let mut out = [0u8; 8];
/// let n = Packet::new(Form::Checksum, Request::from(GetFps)).encode(&mut out)?;
/// assert_eq!(&out[..n], &[0xaf, 0xc1, 0x18, 0x00, 0x00, 0x00]);
/// # Ok::<(), robowire::EncodeError>(())
/// ```
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Packet<M> {
    /// The frame form.
    pub form: Form,
    /// The message.
    pub body: M,
}

impl<M> Packet<M> {
    /// `body` in `form`.
    pub const fn new(form: Form, body: M) -> Self {
        Self { form, body }
    }
}

/// A message of either direction, as an any-direction decoder yields it.
///
/// With the `serde` feature it serializes exactly as [`MessageBuf`] does, and
/// only [`MessageBuf`] deserializes (see [`Response`]).
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message<'a> {
    /// A host → device request.
    Request(Request),
    /// A device → host response.
    Response(Response<'a>),
}

/// The owned form of [`Message`].
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MessageBuf {
    /// A host → device request.
    Request(Request),
    /// A device → host response.
    Response(ResponseBuf),
}

impl Message<'_> {
    /// The owned form.
    pub fn to_owned(&self) -> MessageBuf {
        match self {
            Self::Request(r) => MessageBuf::Request(*r),
            Self::Response(r) => MessageBuf::Response(r.to_owned()),
        }
    }
}

impl MessageBuf {
    /// A borrowed view.
    pub fn as_message(&self) -> Message<'_> {
        match self {
            Self::Request(r) => Message::Request(*r),
            Self::Response(r) => Message::Response(r.as_response()),
        }
    }
}

/// What the shared encoder needs from a message (crate-private).
pub(crate) trait Body {
    fn packet_type(&self) -> u8;
    fn payload_len(&self) -> usize;
    /// Write the payload into `out`, which is exactly `payload_len` long;
    /// reject values the receiver would refuse.
    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError>;
    /// The form used when the message is encoded without a [`Packet`].
    fn default_form(&self) -> Form;
}

/// Encode `body` as one frame of `form` into `out`.
pub(crate) fn encode_body<B: Body + ?Sized>(
    form: Form,
    body: &B,
    out: &mut [u8],
) -> Result<usize, EncodeError> {
    let len = body.payload_len();
    if len > MAX_PAYLOAD {
        return Err(EncodeError::TooLong {
            len,
            max: MAX_PAYLOAD,
        });
    }
    let header = form.header_len();
    let total = header + len;
    check_room(out, total)?;
    let (head, rest) = out.split_at_mut(header);
    let payload = &mut rest[..len];
    body.write_payload(payload)?;
    let [s0, s1] = form.sync_bytes();
    head[0] = s0;
    head[1] = s1;
    head[2] = body.packet_type();
    head[3] = len as u8;
    if form == Form::Checksum {
        head[4..6].copy_from_slice(&checksum(payload).to_le_bytes());
    }
    Ok(total)
}

impl Body for Message<'_> {
    fn packet_type(&self) -> u8 {
        match self {
            Self::Request(r) => r.packet_type(),
            Self::Response(r) => r.packet_type(),
        }
    }
    fn payload_len(&self) -> usize {
        match self {
            Self::Request(r) => Body::payload_len(r),
            Self::Response(r) => Body::payload_len(r),
        }
    }
    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError> {
        match self {
            Self::Request(r) => r.write_payload(out),
            Self::Response(r) => r.write_payload(out),
        }
    }
    fn default_form(&self) -> Form {
        match self {
            Self::Request(r) => r.default_form(),
            Self::Response(r) => r.default_form(),
        }
    }
}

impl Body for MessageBuf {
    fn packet_type(&self) -> u8 {
        self.as_message().packet_type()
    }
    fn payload_len(&self) -> usize {
        Body::payload_len(&self.as_message())
    }
    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError> {
        self.as_message().write_payload(out)
    }
    fn default_form(&self) -> Form {
        self.as_message().default_form()
    }
}

/// `Encode` for a message in its default form and for `Packet<message>`.
macro_rules! impl_encode {
    ($ty:ty, $default_max:expr, $max_payload:expr) => {
        impl Encode for $ty {
            const MAX_LEN: usize = $default_max;
            fn encoded_len(&self) -> usize {
                self.default_form().header_len() + Body::payload_len(self)
            }
            fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
                encode_body(self.default_form(), self, out)
            }
        }

        impl Encode for Packet<$ty> {
            const MAX_LEN: usize = 6 + $max_payload;
            fn encoded_len(&self) -> usize {
                self.form.header_len() + Body::payload_len(&self.body)
            }
            fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
                encode_body(self.form, &self.body, out)
            }
        }
    };
}

impl_encode!(Request, 4 + DEVICE_MAX_PAYLOAD, DEVICE_MAX_PAYLOAD);
impl_encode!(Response<'_>, MAX_FRAME, MAX_PAYLOAD);
impl_encode!(ResponseBuf, MAX_FRAME, MAX_PAYLOAD);
impl_encode!(Message<'_>, MAX_FRAME, MAX_PAYLOAD);
impl_encode!(MessageBuf, MAX_FRAME, MAX_PAYLOAD);
