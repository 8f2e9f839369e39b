//! The messages of both directions together ([`Message`], [`MessageBuf`])
//! and the [`Envelope`] that pairs a message with its frame form.

use core::fmt;
use core::str::FromStr;

use crate::encode::{Encode, EncodeError};

use super::error::NameError;
use super::request::Request;
use super::response::{Response, ResponseBuf};
use super::wire::{encode_body, Body, Form, DEVICE_MAX_PAYLOAD, MAX_FRAME_LEN, MAX_PAYLOAD};

/// A message together with the frame form it travels in.
///
/// Decoders yield `Envelope`s so that the form is not lost (every decoded frame
/// re-encodes to the same bytes). For encoding, wrap a message to choose its
/// form; a bare [`Request`] encodes in the no-checksum form and a bare
/// [`Response`] in the checksum form.
///
/// ```
/// use robowire::pixy2::{Envelope, Form, GetFps, Request};
/// use robowire::Encode;
///
/// let fps = Envelope::new(Form::Checksum, Request::from(GetFps));
/// let mut out = [0u8; 8];
/// let n = fps.encode(&mut out)?;
/// assert_eq!(&out[..n], &[0xaf, 0xc1, 0x18, 0x00, 0x00, 0x00]);
///
/// // One whole frame, sync word included, parses back.
/// assert_eq!(Envelope::try_from(&out[..n]), Ok(fps));
/// assert_eq!(fps.to_string(), "get_fps checksum=true");
/// # Ok::<(), robowire::EncodeError>(())
/// ```
///
/// With the `serde` feature an envelope is its message's JSON object with
/// `checksum` (`true` for [`Form::Checksum`]) right after `type`:
/// `{"type":"get_fps","checksum":true}`, the line `robowire decode pixy2`
/// prints (less `offset` and `len`). When deserializing, `checksum` may be
/// left out: requests then take the no-checksum form, responses the checksum
/// form.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Envelope<M> {
    /// The frame form.
    pub form: Form,
    /// The message.
    pub body: M,
}

impl<M> Envelope<M> {
    /// `body` in `form`.
    pub const fn new(form: Form, body: M) -> Self {
        Self { form, body }
    }
}

/// The message, then ` checksum=true` or ` checksum=false`.
impl<M: fmt::Display> fmt::Display for Envelope<M> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} checksum={}", self.body, self.form == Form::Checksum)
    }
}

/// `no_checksum` or `checksum`.
impl fmt::Display for Form {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Reads the names [`Display`](fmt::Display) writes: `no_checksum`,
/// `checksum`.
impl FromStr for Form {
    type Err = NameError;

    fn from_str(s: &str) -> Result<Self, NameError> {
        match s {
            "no_checksum" => Ok(Self::NoChecksum),
            "checksum" => Ok(Self::Checksum),
            _ => Err(NameError::new("frame form", &Form::NAMES)),
        }
    }
}

/// A message of either direction, as an any-direction decoder yields it.
///
/// With the `serde` feature it serializes as the [`Request`] or [`Response`]
/// it holds, and only [`MessageBuf`] deserializes (see [`Response`]).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message<'a> {
    /// A host → device request.
    Request(Request),
    /// A device → host response.
    Response(Response<'a>),
}

/// The owned form of [`Message`]; serializes as [`Message`] does.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MessageBuf {
    /// A host → device request.
    Request(Request),
    /// A device → host response.
    Response(ResponseBuf),
}

impl Message<'_> {
    /// Every `type` name: the requests' ([`Request::NAMES`]), then the
    /// responses' ([`Response::NAMES`]). No name is used by both directions.
    pub const NAMES: [&'static str; 22] = {
        let mut names = [""; 22];
        let mut i = 0;
        while i < Request::NAMES.len() {
            names[i] = Request::NAMES[i];
            i += 1;
        }
        let mut j = 0;
        while j < Response::NAMES.len() {
            names[i + j] = Response::NAMES[j];
            j += 1;
        }
        names
    };

    /// The `type` name, as in the JSON form.
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Request(r) => r.name(),
            Self::Response(r) => r.name(),
        }
    }
}

/// The request's or the response's one-line form.
impl fmt::Display for Message<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Request(r) => fmt::Display::fmt(r, f),
            Self::Response(r) => fmt::Display::fmt(r, f),
        }
    }
}

/// As [`Message`]'s.
impl fmt::Display for MessageBuf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.as_message(), f)
    }
}

impl From<Request> for MessageBuf {
    fn from(r: Request) -> Self {
        Self::Request(r)
    }
}

impl From<ResponseBuf> for MessageBuf {
    fn from(r: ResponseBuf) -> Self {
        Self::Response(r)
    }
}

impl From<Request> for Message<'_> {
    fn from(r: Request) -> Self {
        Self::Request(r)
    }
}

impl<'a> From<Response<'a>> for Message<'a> {
    fn from(r: Response<'a>) -> Self {
        Self::Response(r)
    }
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

impl Envelope<Request> {
    /// This request, to be encoded even if the device refuses it with an
    /// error: getBlocks with sigmap 0, which the official host library sends
    /// and the camera answers with ERROR −3. For testing a device or a
    /// simulator; [`encode`](Encode::encode) on the envelope itself refuses
    /// it.
    ///
    /// ```
    /// use robowire::pixy2::{Envelope, Form, GetBlocks, Request};
    /// use robowire::Encode;
    ///
    /// let empty = Envelope::new(Form::NoChecksum, Request::from(GetBlocks { sigmap: 0, max_blocks: 5 }));
    /// let mut out = [0u8; 8];
    /// assert!(empty.encode(&mut out).is_err());
    /// let n = empty.even_if_refused().encode(&mut out)?;
    /// assert_eq!(&out[..n], &[0xae, 0xc1, 0x20, 0x02, 0x00, 0x05]);
    /// # Ok::<(), robowire::EncodeError>(())
    /// ```
    pub const fn even_if_refused(self) -> EvenIfRefused {
        EvenIfRefused(self)
    }
}

impl Envelope<MessageBuf> {
    /// This message, to be encoded even if it is a request the device
    /// refuses (see [`Envelope::<Request>::even_if_refused`]); a response
    /// encodes as it does anyway. A line of the JSON-lines schema
    /// deserializes to such a request only when it carries the marker
    /// (`"quirk":"sigmap_zero"`), so encoding every deserialized line
    /// through this is `robowire encode pixy2`.
    pub const fn even_if_refused(self) -> EvenIfRefused<MessageBuf> {
        EvenIfRefused(self)
    }
}

/// A request that encodes even if the device refuses it with an error
/// (getBlocks with sigmap 0); made by [`Envelope::even_if_refused`]. `M` is
/// [`Request`], or [`MessageBuf`] for either direction.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct EvenIfRefused<M = Request>(pub Envelope<M>);

impl Encode for EvenIfRefused<MessageBuf> {
    const MAX_LEN: usize = <Envelope<MessageBuf> as Encode>::MAX_LEN;

    fn encoded_len(&self) -> usize {
        self.0.encoded_len()
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        match self.0.body {
            MessageBuf::Request(request) => {
                EvenIfRefused(Envelope::new(self.0.form, request)).encode(out)
            }
            MessageBuf::Response(_) => self.0.encode(out),
        }
    }
}

impl MessageBuf {
    /// What the device would refuse in this message, if anything: a
    /// request's [`Request::quirk`].
    pub const fn quirk(&self) -> Option<super::Quirk> {
        match self {
            MessageBuf::Request(request) => request.quirk(),
            MessageBuf::Response(_) => None,
        }
    }
}

/// getBlocks with sigmap 0, which [`Request`]'s own encoding refuses.
struct ZeroSigmap {
    max_blocks: u8,
}

impl Body for ZeroSigmap {
    fn packet_type(&self) -> u8 {
        super::wire::packet_type::GET_BLOCKS
    }

    fn payload_len(&self) -> usize {
        2
    }

    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError> {
        match out {
            [sigmap, max_blocks] => {
                *sigmap = 0;
                *max_blocks = self.max_blocks;
                Ok(())
            }
            _ => Err(EncodeError::BufferTooSmall {
                needed: 2,
                available: out.len(),
            }),
        }
    }

    fn default_form(&self) -> Form {
        Form::NoChecksum
    }
}

impl Encode for EvenIfRefused {
    const MAX_LEN: usize = <Envelope<Request> as Encode>::MAX_LEN;

    fn encoded_len(&self) -> usize {
        self.0.encoded_len()
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        match self.0.body {
            Request::GetBlocks(super::request::GetBlocks {
                sigmap: 0,
                max_blocks,
            }) => encode_body(self.0.form, &ZeroSigmap { max_blocks }, out),
            _ => self.0.encode(out),
        }
    }
}

/// `Encode` for a message in its default form and for `Envelope<message>`.
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

        impl Encode for Envelope<$ty> {
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
impl_encode!(Response<'_>, MAX_FRAME_LEN, MAX_PAYLOAD);
impl_encode!(ResponseBuf, MAX_FRAME_LEN, MAX_PAYLOAD);
impl_encode!(Message<'_>, MAX_FRAME_LEN, MAX_PAYLOAD);
impl_encode!(MessageBuf, MAX_FRAME_LEN, MAX_PAYLOAD);
