//! Where frames are in a byte stream, what is rejected where, and why: the
//! Pixy2 decoding policy.
//!
//! Three decoders, one per side: [`HostDecoder`](super::HostDecoder)
//! (responses), [`DeviceDecoder`](super::DeviceDecoder) (requests, with the
//! device's 64-byte receive limit), [`BothDecoder`](super::BothDecoder) (both,
//! for captures). All accept both forms; `Framing::new().checksum_only()`
//! accepts only `af c1` (right for a serial host: the device always sends a
//! checksum there; then no unverifiable frame can be decoded).
//!
//! | what | where it is caught | event |
//! |---|---|---|
//! | SPI idle filler `0x01`, a doubled first sync byte (`af af c1`), `0xae`/`0xaf` not followed by `0xc1`, other garbage | sync search (`memchr` for `0xc1`, one byte back) | none (counted in [`Stats::skipped`](crate::Stats::skipped)); [`Error::Sync`] is kept for a slice parsed as one frame (`try_from`) |
//! | a type the side does not accept (unknown, or the other direction's) | header, byte 3 | [`Error::UnknownType`] |
//! | a length the type cannot have: RESULT ≠ 4, ERROR ≠ 1, resolution ≠ 4, version ≠ 16, blocks ≠ 14·k (k ≤ 18), request lengths per type | header, byte 4 | [`Error::BadLength`] |
//! | a request payload over 64 bytes (device and both-direction decoders) | header, byte 4 | [`Error::TooLong`] |
//! | checksum mismatch | full frame | [`Error::Checksum`] |
//! | malformed content: line section past the end or not a multiple of its element size, intersection `n` > 6 (a getBlocks with sigmap 0 is a request: the device answers it with ERROR −3) | **no-checksum form**: in framing, the candidate is rejected and everything after its first byte is rescanned. **Checksum form**: after the checksum passed, the frame is consumed and reported ([`Stats::malformed`](crate::Stats::malformed)) | [`Error::Malformed`] |
//! | input ends inside a candidate | `finish`/`flush` | [`Error::Truncated`] |
//!
//! In detail (spec §7.4):
//!
//! * Both sync words are found by a sliding search (`memchr` for `0xc1`, then
//!   one byte back). A first sync byte at the end of a chunk is kept as a
//!   possible start; if the next chunk shows it is none, the engine drops it
//!   silently too, so the output does not depend on the chunking.
//! * The header is checked as soon as its bytes are there: the candidate is
//!   rejected before its payload arrives.
//! * Why content errors split by form: a checksummed frame's bytes are
//!   exactly what the sender sent, so nothing inside it is rescanned; an
//!   `ae c1` frame has nothing vouching for it, so a payload that cannot be
//!   real means it was not a frame, and a real frame that began inside it is
//!   still found.
//! * Every rejection drops only the candidate's first byte (the engine's
//!   resync by one).
//! * Speed: a sync word right at the start and a whole `af c1` header that
//!   the side accepts are answered inline (only the payload sum is left,
//!   and a candidate short of its payload is told its whole length from the
//!   length byte, so the engine checks it once more, when it is complete);
//!   everything else takes the byte-by-byte path described here. Where the
//!   target has no vector registers (a microcontroller) only the latter is
//!   compiled, to save flash. Figures in `docs/performance.md`.
//!
//! Errors stay apart: [`Error`] is what the codec found wrong with bytes;
//! [`DeviceError`](super::DeviceError) (general, busy, invalid request, type
//! unsupported, button override, prog changing, `Unknown(i8)` for any other
//! code) is what the device said in an ERROR packet;
//! [`PairError`](super::PairError) is a response that does not answer the
//! request. RESULT is decoded as the full i32 (getFPS and getRGB read it as
//! u32 / `0x00RRGGBB`).
//!
//! A simulator mirrors the device like this: `BadLength` or `Malformed` on a
//! request → answer ERROR −3; `UnknownType` → ERROR −4; `Checksum`, `TooLong`
//! → no answer. Two differences from the firmware, both deliberate: after
//! dropping a request the decoder rescans the dropped bytes (the firmware
//! does not), and a wrong length is rejected from the header before the
//! checksum is verified (the firmware verifies first, so it silently drops a
//! wrong-length request whose checksum is also wrong).
//!
//! # What cannot be detected
//!
//! * A frame in the no-checksum form is checked only for a plausible type,
//!   length and content. Garbage that happens to hold `ae c1`, a known type
//!   and a plausible length decodes as a frame (and may swallow the start of
//!   a real one). Use [`Framing::checksum_only`] where the sender always uses
//!   the checksum form.
//! * The checksum is a plain sum over the payload: reordered bytes and
//!   compensating errors pass, and the header (type, length) is not covered.
//!   A type flipped to another type with the same length (RESULT ↔
//!   resolution) decodes; [`Query::answer`](super::Query::answer) then
//!   reports [`PairError::WrongType`](super::PairError::WrongType).
//! * Which request a response answers: the protocol has no sequence numbers.
//!   `Query::answer` checks the type and plausibility; a stale answer of the
//!   same type is indistinguishable.
//!
//! # One whole frame
//!
//! `TryFrom<&[u8]>` parses a slice that is exactly one frame, sync word
//! included, with the same checks as the decoder of the message's side
//! ([`Request`]: [`Device`]; [`Response`], [`ResponseBuf`]: [`Host`];
//! [`Message`], [`MessageBuf`]: [`Both`]); an [`Envelope`] of any of them
//! keeps the form. A slice cut short is [`Error::Truncated`], bytes after the
//! frame are [`Error::TrailingBytes`].

use core::marker::PhantomData;

pub use crate::side::{Both, Device, Host};
use crate::stream::{self, Check};

use super::envelope::{Envelope, Message, MessageBuf};
use super::error::Error;
use super::request::{check_request_header, request_len, Request};
use super::response::{check_response_header, is_response_type, Response, ResponseBuf};
use super::wire::{checksum, Form, DEVICE_MAX_PAYLOAD, MAX_FRAME_LEN, VECTOR};

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
    const MAX_FRAME_LEN: usize;
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
    type Message<'a> = Envelope<Response<'a>>;
    type Owned = Envelope<ResponseBuf>;
    const MAX_FRAME_LEN: usize = MAX_FRAME_LEN;

    fn accepts_type(packet_type: u8) -> bool {
        is_response_type(packet_type)
    }

    #[inline]
    fn check_header(packet_type: u8, len: u8) -> Result<(), Error> {
        check_response_header(packet_type, len)
    }

    #[inline(always)]
    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error> {
        Response::from_payload(packet_type, payload).map(|body| Envelope::new(form, body))
    }

    fn to_owned(message: Self::Message<'_>) -> Self::Owned {
        Envelope::new(message.form, message.body.to_owned())
    }
}

impl Side for Device {
    type Message<'a> = Envelope<Request>;
    type Owned = Envelope<Request>;
    const MAX_FRAME_LEN: usize = 6 + DEVICE_MAX_PAYLOAD;

    fn accepts_type(packet_type: u8) -> bool {
        request_len(packet_type).is_some()
    }

    #[inline]
    fn check_header(packet_type: u8, len: u8) -> Result<(), Error> {
        check_request_header(packet_type, len)
    }

    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error> {
        Request::from_payload(packet_type, payload).map(|body| Envelope::new(form, body))
    }

    fn to_owned(message: Self::Message<'_>) -> Self::Owned {
        message
    }
}

impl Side for Both {
    type Message<'a> = Envelope<Message<'a>>;
    type Owned = Envelope<MessageBuf>;
    const MAX_FRAME_LEN: usize = MAX_FRAME_LEN;

    fn accepts_type(packet_type: u8) -> bool {
        Host::accepts_type(packet_type) || Device::accepts_type(packet_type)
    }

    #[inline]
    fn check_header(packet_type: u8, len: u8) -> Result<(), Error> {
        if is_response_type(packet_type) {
            check_response_header(packet_type, len)
        } else {
            check_request_header(packet_type, len)
        }
    }

    fn parse(form: Form, packet_type: u8, payload: &[u8]) -> Result<Self::Message<'_>, Error> {
        let body = if is_response_type(packet_type) {
            Message::Response(Response::from_payload(packet_type, payload)?)
        } else {
            Message::Request(Request::from_payload(packet_type, payload)?)
        };
        Ok(Envelope::new(form, body))
    }

    fn to_owned(message: Self::Message<'_>) -> Self::Owned {
        Envelope::new(message.form, message.body.to_owned())
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

/// Whether `find_start` and `check` answer the common case (a sync word
/// right at the start, a whole checksum-form header) inline before their
/// general paths. Where the target has vector registers (SSE2, NEON: the
/// hosts that decode at memory speed) this is most of the decoder's time
/// saved; on a microcontroller the copies inlined at each of the engine's
/// call sites would cost about 340 bytes of flash for a link that is far
/// slower than either path, so there the general paths are all there is.
const FAST_PATHS: bool = VECTOR;

impl<S: Side> Framing<S> {
    /// Whether `byte` is the first byte of an accepted sync word.
    #[inline(always)]
    fn is_first(&self, byte: u8) -> bool {
        byte == 0xaf || (byte == 0xae && !self.checksum_only)
    }

    /// [`find_start`](stream::FrameRules::find_start) past its first two
    /// bytes: `memchr` for each `0xc1`, one byte back.
    #[inline(never)]
    fn search_start(&self, bytes: &[u8]) -> usize {
        let mut from = 1;
        while let Some(i) = bytes
            .get(from..)
            .and_then(|rest| memchr::memchr(0xc1, rest))
        {
            let at = from + i;
            // `at >= 1`: the search starts at 1. `get` keeps the panic path out.
            if bytes.get(at - 1).is_some_and(|&b| self.is_first(b)) {
                return at - 1;
            }
            from = at + 1;
        }
        match bytes.last() {
            Some(&b) if self.is_first(b) => bytes.len() - 1,
            _ => bytes.len(),
        }
    }

    /// Every candidate the fast path of `check` does not settle: a header
    /// not yet whole, the no-checksum form, or a header to reject (which
    /// error, decided byte by byte).
    #[inline(never)]
    fn check_slow(&self, c: &[u8]) -> Check<Error> {
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
                // The checksum form's header is 6 bytes, all present here.
                let (Some(&lo), Some(&hi)) = (c.get(4), c.get(5)) else {
                    return Check::Need(6);
                };
                let expected = u16::from_le_bytes([lo, hi]);
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
    #[inline(always)]
    fn find_start(&self, bytes: &[u8]) -> usize {
        // The next frame usually starts right here (right after the last
        // one, or at the front of the buffer holding a candidate). Only
        // where the fast paths pay for their size (see `FAST_PATHS`).
        if FAST_PATHS {
            if let Some(&[first, 0xc1]) = bytes.first_chunk::<2>() {
                if self.is_first(first) {
                    return 0;
                }
            }
        }
        self.search_start(bytes)
    }

    #[inline(always)]
    fn check(&self, c: &[u8], _at_end: bool) -> Check<Error> {
        // The common case first: a whole checksum-form header whose type and
        // length the side accepts. Only the payload's sum is left to check,
        // and a candidate still short of its payload is told how many bytes
        // it needs from the header alone (the engine then waits for them
        // without asking again).
        if let (true, Some(&[0xaf, 0xc1, packet_type, len, lo, hi])) =
            (FAST_PATHS, c.first_chunk::<6>())
        {
            if S::check_header(packet_type, len).is_ok() {
                let total = 6 + usize::from(len);
                let Some(payload) = c.get(6..total) else {
                    return Check::Need(total);
                };
                let expected = u16::from_le_bytes([lo, hi]);
                let found = checksum(payload);
                return if expected == found {
                    Check::Frame(total)
                } else {
                    Check::Reject(Error::Checksum { expected, found })
                };
            }
        }
        self.check_slow(c)
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

    #[inline(always)]
    fn parse<'a>(&self, frame: &'a [u8]) -> Result<S::Message<'a>, Error> {
        let Some(&[start, _, packet_type, len]) = frame.first_chunk::<4>() else {
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

/// Parse `frame`, exactly one whole frame of side `S` (see the module docs).
fn parse_frame<S: Side>(frame: &[u8]) -> Result<S::Message<'_>, Error> {
    use stream::FrameRules as _;
    let framing = Framing::<S>::new();
    match framing.check(frame, true) {
        Check::Frame(len) if len == frame.len() => framing.parse(frame),
        Check::Frame(len) => Err(Error::TrailingBytes {
            extra: frame.len() - len,
        }),
        Check::Need(_) => Err(Error::Truncated { len: frame.len() }),
        Check::Reject(e) => Err(e),
    }
}

/// One whole frame as a [`Device`] decoder reads it: either form.
impl TryFrom<&[u8]> for Envelope<Request> {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        parse_frame::<Device>(frame)
    }
}

/// One whole frame as a [`Device`] decoder reads it, its form dropped.
impl TryFrom<&[u8]> for Request {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        parse_frame::<Device>(frame).map(|e| e.body)
    }
}

/// One whole frame as a [`Host`] decoder reads it: either form.
impl<'a> TryFrom<&'a [u8]> for Envelope<Response<'a>> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        parse_frame::<Host>(frame)
    }
}

/// One whole frame as a [`Host`] decoder reads it, its form dropped.
impl<'a> TryFrom<&'a [u8]> for Response<'a> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        parse_frame::<Host>(frame).map(|e| e.body)
    }
}

/// One whole frame as a [`Host`] decoder reads it, owned.
impl TryFrom<&[u8]> for Envelope<ResponseBuf> {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        parse_frame::<Host>(frame).map(Host::to_owned)
    }
}

/// One whole frame as a [`Host`] decoder reads it, owned, its form dropped.
impl TryFrom<&[u8]> for ResponseBuf {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        parse_frame::<Host>(frame).map(|e| e.body.to_owned())
    }
}

/// One whole frame of either direction: either form.
impl<'a> TryFrom<&'a [u8]> for Envelope<Message<'a>> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        parse_frame::<Both>(frame)
    }
}

/// One whole frame of either direction, its form dropped.
impl<'a> TryFrom<&'a [u8]> for Message<'a> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        parse_frame::<Both>(frame).map(|e| e.body)
    }
}

/// One whole frame of either direction, owned.
impl TryFrom<&[u8]> for Envelope<MessageBuf> {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        parse_frame::<Both>(frame).map(Both::to_owned)
    }
}

/// One whole frame of either direction, owned, its form dropped.
impl TryFrom<&[u8]> for MessageBuf {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        parse_frame::<Both>(frame).map(|e| e.body.to_owned())
    }
}
