//! Where frames are in a byte stream: sync search, header checks by
//! direction, checksum, and the content checks that decide between "not a
//! frame" and "a frame with a bad payload".
//!
//! Policy (spec §7.4):
//!
//! * Both sync words are found by a sliding search (`memchr` for `0xc1`, then
//!   one byte back). SPI filler (`0x01`), junk and a doubled first sync byte
//!   (`af af c1 …`) are skipped as garbage, silently. A first sync byte at the
//!   end of a chunk is kept as a possible start; if the next chunk shows it
//!   is none, the engine drops it silently too, so the output does not depend
//!   on the chunking.
//! * The header is checked as soon as its bytes are there: a type this side
//!   does not accept is [`Error::UnknownType`], a length the type cannot have
//!   is [`Error::BadLength`], a request over the device's 64-byte limit is
//!   [`Error::TooLong`]. The candidate is rejected before its payload arrives.
//! * Checksum form: the checksum is verified ([`Error::Checksum`]). A frame
//!   whose checksum is right but whose payload is malformed (line sections
//!   that do not fit, an intersection with more than 6 lines, getBlocks with
//!   signature map 0) is consumed and reported as [`Error::Malformed`] after
//!   parsing: its bytes are what the sender sent, so nothing inside it is
//!   rescanned.
//! * No-checksum form: the same content checks run inside framing, so a
//!   malformed payload rejects the candidate and the bytes after its first
//!   byte are rescanned; a real frame that began inside it is found.
//! * Every rejection drops only the candidate's first byte (the engine's
//!   resync by one).

use core::marker::PhantomData;

pub use crate::side::{Both, Device, Host};
use crate::stream::{self, Check};

use super::error::Error;
use super::packet::{checksum, Form, Message, MessageBuf, Packet, DEVICE_MAX_PAYLOAD, MAX_FRAME};
use super::request::{check_request_header, request_len, Request};
use super::response::{check_response_header, is_response_type, Response, ResponseBuf};

mod sealed {
    pub trait Sealed {}
}

/// Which messages a [`Framing`] accepts (sealed: [`Host`], [`Device`],
/// [`Both`]).
pub trait Side: sealed::Sealed + Copy + Eq + core::hash::Hash + core::fmt::Debug + Default {
    /// The message a decoder of this side yields.
    type Message<'a>;
    /// Its owned form.
    type Owned;
    /// Longest frame a candidate can grow to.
    const MAX_FRAME: usize;
    /// Whether `packet_type` is accepted at all.
    fn accepts_type(packet_type: u8) -> bool;
    /// Check the type and length bytes of a header.
    fn check_header(packet_type: u8, len: u8) -> Result<(), Error>;
    /// Parse a payload of `packet_type`.
    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error>;
    /// The owned form of a message.
    fn to_owned(message: Self::Message<'_>) -> Self::Owned;
}

impl sealed::Sealed for Host {}
impl sealed::Sealed for Device {}
impl sealed::Sealed for Both {}

impl Side for Host {
    type Message<'a> = Packet<Response<'a>>;
    type Owned = Packet<ResponseBuf>;
    const MAX_FRAME: usize = MAX_FRAME;

    fn accepts_type(packet_type: u8) -> bool {
        is_response_type(packet_type)
    }

    fn check_header(packet_type: u8, len: u8) -> Result<(), Error> {
        check_response_header(packet_type, len)
    }

    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error> {
        Response::parse(packet_type, payload).map(|body| Packet::new(form, body))
    }

    fn to_owned(message: Self::Message<'_>) -> Self::Owned {
        Packet::new(message.form, message.body.to_owned())
    }
}

impl Side for Device {
    type Message<'a> = Packet<Request>;
    type Owned = Packet<Request>;
    const MAX_FRAME: usize = 6 + DEVICE_MAX_PAYLOAD;

    fn accepts_type(packet_type: u8) -> bool {
        request_len(packet_type).is_some()
    }

    fn check_header(packet_type: u8, len: u8) -> Result<(), Error> {
        check_request_header(packet_type, len)
    }

    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error> {
        Request::parse(packet_type, payload).map(|body| Packet::new(form, body))
    }

    fn to_owned(message: Self::Message<'_>) -> Self::Owned {
        message
    }
}

impl Side for Both {
    type Message<'a> = Packet<Message<'a>>;
    type Owned = Packet<MessageBuf>;
    const MAX_FRAME: usize = MAX_FRAME;

    fn accepts_type(packet_type: u8) -> bool {
        Host::accepts_type(packet_type) || Device::accepts_type(packet_type)
    }

    fn check_header(packet_type: u8, len: u8) -> Result<(), Error> {
        if is_response_type(packet_type) {
            check_response_header(packet_type, len)
        } else {
            check_request_header(packet_type, len)
        }
    }

    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error> {
        let body = if is_response_type(packet_type) {
            Message::Response(Response::parse(packet_type, payload)?)
        } else {
            Message::Request(Request::parse(packet_type, payload)?)
        };
        Ok(Packet::new(form, body))
    }

    fn to_owned(message: Self::Message<'_>) -> Self::Owned {
        Packet::new(message.form, message.body.to_owned())
    }
}

/// Pixy2 framing for [`StreamDecoder`](crate::StreamDecoder), for one
/// [`Side`] of the link.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Framing<S> {
    checksum_only: bool,
    #[cfg_attr(feature = "serde", serde(skip))]
    side: PhantomData<S>,
}

impl<S: Side> Framing<S> {
    /// Accept both frame forms (spec §2.2: decoders accept both).
    pub const fn new() -> Self {
        Self {
            checksum_only: false,
            side: PhantomData,
        }
    }

    /// Accept only the checksum form: `ae c1` is not even a candidate start.
    /// Device responses over SPI, I2C and UART always carry a checksum, so a
    /// serial host loses nothing and no unverifiable frame can be found.
    pub const fn checksum_only(self) -> Self {
        Self {
            checksum_only: true,
            side: PhantomData,
        }
    }

    /// Whether only the checksum form is accepted.
    pub const fn is_checksum_only(&self) -> bool {
        self.checksum_only
    }
}

impl<S: Side> stream::FrameRules for Framing<S> {
    type Error = Error;
    type Message<'a> = S::Message<'a>;
    type Owned = S::Owned;

    /// Sync word, type and length: enough to reject an impossible header.
    const HEADER_LEN: usize = 4;

    /// Both sync words by sliding search: find each `0xc1` with `memchr` and
    /// look one byte back. A first sync byte at the very end may be a start
    /// whose `0xc1` has not arrived yet.
    fn find_start(&self, bytes: &[u8]) -> usize {
        let is_first = |b: u8| b == 0xaf || (b == 0xae && !self.checksum_only);
        let mut from = 1;
        while let Some(i) = bytes
            .get(from..)
            .and_then(|rest| memchr::memchr(0xc1, rest))
        {
            let at = from + i;
            if is_first(bytes[at - 1]) {
                return at - 1;
            }
            from = at + 1;
        }
        match bytes.last() {
            Some(&b) if is_first(b) => bytes.len() - 1,
            _ => bytes.len(),
        }
    }

    fn check(&self, c: &[u8], _at_end: bool) -> Check<Error> {
        let Some(&start) = c.first() else {
            return Check::Need(1);
        };
        let form = match Form::from_start_byte(start) {
            Some(Form::NoChecksum) if self.checksum_only => None,
            other => other,
        };
        let Some(form) = form else {
            return Check::Reject(Error::Sync { found: start });
        };
        let Some(&second) = c.get(1) else {
            return Check::Need(2);
        };
        if second != 0xc1 {
            return Check::Reject(Error::Sync { found: second });
        }
        let Some(&packet_type) = c.get(2) else {
            return Check::Need(3);
        };
        if !S::accepts_type(packet_type) {
            return Check::Reject(Error::UnknownType { packet_type });
        }
        let Some(&len) = c.get(3) else {
            return Check::Need(4);
        };
        if let Err(e) = S::check_header(packet_type, len) {
            return Check::Reject(e);
        }
        let header = form.header_len();
        let total = header + usize::from(len);
        let Some(payload) = c.get(header..total) else {
            return Check::Need(total);
        };
        match form {
            Form::Checksum => {
                let expected = u16::from_le_bytes([c[4], c[5]]);
                let found = checksum(payload);
                if expected != found {
                    return Check::Reject(Error::Checksum { expected, found });
                }
            }
            Form::NoChecksum => {
                // Nothing vouches for these bytes: a payload the type cannot
                // have means this was not a frame (see the module docs).
                if let Err(e) = S::parse(form, packet_type, payload) {
                    return Check::Reject(e);
                }
            }
        }
        Check::Frame(total)
    }

    fn truncated(&self, len: usize) -> Error {
        Error::Truncated { len }
    }

    fn superseded(&self, len: usize) -> Error {
        Error::Superseded { len }
    }

    fn is_checksum_error(&self, error: &Error) -> bool {
        matches!(error, Error::Checksum { .. })
    }

    fn parse<'a>(&self, frame: &'a [u8]) -> Result<S::Message<'a>, Error> {
        let (Some(&start), Some(&packet_type), Some(&len)) =
            (frame.first(), frame.get(2), frame.get(3))
        else {
            return Err(Error::Truncated { len: frame.len() });
        };
        let form = Form::from_start_byte(start).ok_or(Error::Sync { found: start })?;
        let header = form.header_len();
        let payload = frame
            .get(header..header + usize::from(len))
            .ok_or(Error::Truncated { len: frame.len() })?;
        S::parse(form, packet_type, payload)
    }

    fn to_owned(message: S::Message<'_>) -> S::Owned {
        S::to_owned(message)
    }
}
