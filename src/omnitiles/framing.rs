//! Where OmniTiles frames start and end in a byte stream, for each side of
//! the link. The decoding policy is described in the [module
//! docs](super#what-the-decoders-accept).

use core::marker::PhantomData;

use crate::encode::Encode;
pub use crate::side::{Both, Device, Host};
use crate::stream::{self, Check};

use super::command::Command;
use super::error::Error;
use super::layout::{Layout, Layouts};
use super::message::Message;
use super::telemetry::Telemetry;
use super::wire::{checksum, id, payload_len, sum8, MAX_COMMAND_LEN, MAX_FRAME_LEN, START};

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Host {}
    impl Sealed for super::Device {}
    impl Sealed for super::Both {}
}

/// Which messages a [`Framing`] accepts (sealed: [`Host`] telemetry,
/// [`Device`] commands, [`Both`] either).
pub trait Side:
    sealed::Sealed + Copy + Eq + core::hash::Hash + core::fmt::Debug + Default + 'static
{
    /// The message a decoder of this side yields: [`Telemetry`],
    /// [`Command`] or [`Message`]. Each encodes, and converts into a
    /// [`Message`].
    type Message: Copy + core::fmt::Debug + PartialEq + Encode + Into<Message>;
    /// Whether commands are accepted.
    const COMMANDS: bool;
    /// The telemetry layouts of [`Framing::new`]: the documented four, or
    /// none for [`Device`].
    const DEFAULT_LAYOUTS: Layouts;

    /// Check a candidate whose id byte is `id` (the stream engine's `check`
    /// past the header).
    #[doc(hidden)]
    fn check_id(framing: &Framing<Self>, id: u8, c: &[u8], at_end: bool) -> Check<Error>;

    /// Whether `id` begins a frame this side accepts, given `layouts`.
    #[doc(hidden)]
    fn accepts_id(layouts: Layouts, id: u8) -> bool;

    /// A frame that passed framing as this side's message.
    #[doc(hidden)]
    fn parse(frame: &[u8]) -> Result<Self::Message, Error>;
}

/// A [`Side`] that accepts telemetry, so its [`Framing`] has a set of
/// layouts: [`Host`] and [`Both`] (sealed).
pub trait TelemetrySide: Side {}

impl TelemetrySide for Host {}
impl TelemetrySide for Both {}

impl Side for Host {
    type Message = Telemetry;
    const COMMANDS: bool = false;
    const DEFAULT_LAYOUTS: Layouts = Layouts::DOCUMENTED;

    #[inline(always)]
    fn check_id(framing: &Framing<Host>, id: u8, c: &[u8], at_end: bool) -> Check<Error> {
        if id == id::TELEMETRY && !framing.layouts.is_empty() {
            framing.check_telemetry(c, at_end)
        } else {
            Check::Reject(Error::UnknownId { id })
        }
    }

    #[inline]
    fn accepts_id(layouts: Layouts, id: u8) -> bool {
        id == id::TELEMETRY && !layouts.is_empty()
    }

    #[inline(always)]
    fn parse(frame: &[u8]) -> Result<Telemetry, Error> {
        match frame.get(1) {
            Some(&id::TELEMETRY) => Telemetry::parse_framed(frame),
            id => Err(Error::UnknownId {
                id: id.copied().unwrap_or(0),
            }),
        }
    }
}

impl Side for Device {
    type Message = Command;
    const COMMANDS: bool = true;
    const DEFAULT_LAYOUTS: Layouts = Layouts::NONE;

    #[inline(always)]
    fn check_id(_: &Framing<Device>, id: u8, c: &[u8], at_end: bool) -> Check<Error> {
        check_command(id, c, at_end)
    }

    #[inline]
    fn accepts_id(_: Layouts, id: u8) -> bool {
        payload_len(id).is_some()
    }

    #[inline(always)]
    fn parse(frame: &[u8]) -> Result<Command, Error> {
        Command::parse_framed(frame)
    }
}

impl Side for Both {
    type Message = Message;
    const COMMANDS: bool = true;
    const DEFAULT_LAYOUTS: Layouts = Layouts::DOCUMENTED;

    #[inline(always)]
    fn check_id(framing: &Framing<Both>, id: u8, c: &[u8], at_end: bool) -> Check<Error> {
        if id == id::TELEMETRY && !framing.layouts.is_empty() {
            framing.check_telemetry(c, at_end)
        } else {
            check_command(id, c, at_end)
        }
    }

    #[inline]
    fn accepts_id(layouts: Layouts, id: u8) -> bool {
        Host::accepts_id(layouts, id) || Device::accepts_id(layouts, id)
    }

    #[inline(always)]
    fn parse(frame: &[u8]) -> Result<Message, Error> {
        if frame.get(1) == Some(&id::TELEMETRY) {
            Telemetry::parse_framed(frame).map(Message::Telemetry)
        } else {
            Command::parse_framed(frame).map(Message::Command)
        }
    }
}

/// What an OmniTiles decoder accepts, by side: [`Framing<Host>`] telemetry in
/// a set of layouts (bytes from the tile), [`Framing<Device>`] commands (bytes
/// from the host), [`Framing<Both>`] both. The telemetry length policy is in
/// the [module docs](super#telemetry-length-policy).
///
/// ```
/// use robowire::omnitiles::{Framing, HostDecoder, Layout, Layouts};
/// let decoder = HostDecoder::new(Framing::new().with_layouts(Layouts::only(Layout::Ble53)));
/// assert_eq!(decoder.framing().layouts(), Layouts::only(Layout::Ble53));
/// assert!(!decoder.framing().accepts_commands());
/// ```
///
/// With the `serde` feature a framing is written as its layouts,
/// `{"layouts":23}` (the side is its type); a device framing refuses any
/// layout.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Framing<S> {
    layouts: Layouts,
    side: PhantomData<S>,
}

impl<S: Side> Framing<S> {
    /// The side's default: the four documented layouts for [`Host`] and
    /// [`Both`], commands for [`Device`] and [`Both`].
    pub const fn new() -> Self {
        Framing {
            layouts: S::DEFAULT_LAYOUTS,
            side: PhantomData,
        }
    }

    /// Whether commands are accepted.
    pub const fn accepts_commands(&self) -> bool {
        S::COMMANDS
    }

    /// The telemetry layouts accepted (none for [`Device`]).
    pub const fn layouts(&self) -> Layouts {
        self.layouts
    }

    /// Whether `id` begins a frame this decoder accepts.
    pub fn accepts_id(&self, id: u8) -> bool {
        S::accepts_id(self.layouts, id)
    }

    /// A framing accepting `layouts`, if this side accepts telemetry or
    /// `layouts` is empty.
    #[cfg(feature = "serde")]
    pub(super) fn from_layouts(layouts: Layouts) -> Option<Self> {
        if S::DEFAULT_LAYOUTS.is_empty() && !layouts.is_empty() {
            return None;
        }
        Some(Framing {
            layouts,
            side: PhantomData,
        })
    }

    /// Does what follows a telemetry candidate of `layout` confirm its
    /// length? `Some(true)` yes, `Some(false)` no, `None` cannot tell yet.
    /// Another accepted frame's header confirms any length; zero padding
    /// confirms a 45-byte SPI frame (the rest of its 128-byte buffer).
    fn confirms(&self, layout: Layout, rest: &[u8], at_end: bool) -> Option<bool> {
        match rest {
            [] | [START] if at_end => Some(true),
            [] | [START] => None,
            [START, next, ..] => Some(self.accepts_id(*next)),
            [0, 0, ..] if layout == Layout::Spi45 => Some(true),
            [0] if layout == Layout::Spi45 => at_end.then_some(true),
            _ => Some(false),
        }
    }

    #[inline(always)]
    fn check_telemetry(&self, c: &[u8], at_end: bool) -> Check<Error> {
        let longest = match self.layouts.longest() {
            Some(l) => l,
            None => return Check::Reject(Error::UnknownId { id: id::TELEMETRY }),
        };
        if self.layouts.len() == 1 {
            return check_single(longest, c, at_end);
        }
        self.check_layouts(longest, c, at_end)
    }

    /// Several layouts: the length policy (see the module docs). The lengths
    /// are tried shortest first; one whose sum validates is taken at once
    /// when it is the longest enabled or what follows confirms it, and
    /// otherwise counted. Once every enabled length has been tried (or the
    /// input ends), a candidate at which exactly one length validated is
    /// that frame; with two or more unconfirmed ones it is rejected.
    #[inline(never)]
    fn check_layouts(&self, longest: Layout, c: &[u8], at_end: bool) -> Check<Error> {
        // In the middle of a buffer every length and the two bytes after it
        // are there: test all the sums at once, without a branch per length,
        // and look only at the lengths that validate (usually one).
        if let Some(window) = c.first_chunk::<{ MAX_FRAME_LEN + 2 }>() {
            return self.check_window(longest, window, at_end);
        }
        self.check_lengths(longest, c, at_end)
    }

    /// [`check_layouts`](Self::check_layouts) on a candidate long enough for
    /// every length and what follows it: the same answers, with the sums of
    /// all five lengths computed over constant ranges and tested together.
    #[inline(always)]
    fn check_window(
        &self,
        longest: Layout,
        c: &[u8; MAX_FRAME_LEN + 2],
        at_end: bool,
    ) -> Check<Error> {
        // Running sums over bytes 1.. up to each layout's checksum byte
        // (7, 15, 17, 45 and 53-byte frames).
        let s7 = sum8(&c[1..6]);
        let s15 = s7.wrapping_add(sum8(&c[6..14]));
        let s17 = s15.wrapping_add(sum8(&c[14..16]));
        let s45 = s17.wrapping_add(sum8(&c[16..44]));
        let s53 = s45.wrapping_add(sum8(&c[44..52]));
        let sums = [s7, s15, s17, s45, s53];
        let mut valid = u8::from(s7 == c[6])
            | u8::from(s15 == c[14]) << 1
            | u8::from(s17 == c[16]) << 2
            | u8::from(s45 == c[44]) << 3
            | u8::from(s53 == c[52]) << 4;
        valid &= self.layouts.bits();
        let mut tally = Tally::default();
        while valid != 0 {
            let layout = Layout::ALL[(valid.trailing_zeros() as usize).min(4)];
            valid &= valid - 1;
            if let Some(answer) = tally.validated(self, layout, longest, c, at_end) {
                return answer;
            }
        }
        // Every enabled length was tried; if none validated, the longest
        // failed last.
        let end = longest.frame_len() - 1;
        tally.finish(Error::Checksum {
            expected: sums[(longest as usize).min(4)],
            found: c[end.min(MAX_FRAME_LEN - 1)],
        })
    }

    /// [`check_layouts`](Self::check_layouts) one length at a time, for a
    /// candidate that may end before the longest length.
    fn check_lengths(&self, longest: Layout, c: &[u8], at_end: bool) -> Check<Error> {
        let mut error = Error::Unconfirmed;
        let mut tally = Tally::default();
        // Running sum over bytes 1.. so each length costs only its new bytes.
        let mut sum: u8 = 0;
        let mut summed = 1;
        for layout in Layout::ALL {
            if !self.layouts.contains(layout) {
                continue;
            }
            let len = layout.frame_len();
            if c.len() < len {
                if !at_end {
                    return Check::Need(len);
                }
                // The input ended: longer lengths cannot validate.
                if tally.unconfirmed == 0 {
                    error = Error::Truncated { len: c.len() };
                }
                break;
            }
            sum = sum.wrapping_add(sum8(&c[summed..len - 1]));
            summed = len - 1;
            let found = c[len - 1];
            if sum != found {
                error = Error::Checksum {
                    expected: sum,
                    found,
                };
                continue;
            }
            if let Some(answer) = tally.validated(self, layout, longest, c, at_end) {
                return answer;
            }
        }
        tally.finish(error)
    }
}

/// What the lengths tried so far at one candidate say, under the length
/// policy of [`Framing::check_layouts`].
#[derive(Default)]
struct Tally {
    /// Lengths that validated without confirmation.
    unconfirmed: u8,
    /// The first of them.
    only: usize,
    /// A 45-byte frame confirmed only by the zero padding after it.
    padded: usize,
}

impl Tally {
    /// `layout`'s length validated at `c`: the answer, or `None` to try the
    /// next length.
    #[inline(always)]
    fn validated<S: Side>(
        &mut self,
        framing: &Framing<S>,
        layout: Layout,
        longest: Layout,
        c: &[u8],
        at_end: bool,
    ) -> Option<Check<Error>> {
        let len = layout.frame_len();
        let rest = c.get(len..).unwrap_or(&[]);
        if layout == longest {
            if self.padded == 0 {
                return Some(Check::Frame(len));
            }
            // A 45-byte frame padded with zeros, and a longer frame over the
            // same bytes: the longer one wins only if a header or the end of
            // input confirms it (its tail of zeros looked like padding);
            // otherwise the zeros are the SPI buffer's padding.
            return Some(match framing.confirms(layout, rest, at_end) {
                Some(true) => Check::Frame(len),
                Some(false) => Check::Frame(self.padded),
                None => Check::Need(len + 2),
            });
        }
        match framing.confirms(layout, rest, at_end) {
            Some(true) if layout == Layout::Spi45 && rest.first() == Some(&0) => self.padded = len,
            Some(true) => return Some(Check::Frame(len)),
            Some(false) => {
                if self.unconfirmed == 0 {
                    self.only = len;
                }
                self.unconfirmed += 1;
            }
            None => return Some(Check::Need(len + 2)),
        }
        None
    }

    /// Every enabled length was tried (or the input ended); `error` is what
    /// to say if none validated.
    fn finish(self, error: Error) -> Check<Error> {
        if self.padded != 0 {
            return Check::Frame(self.padded);
        }
        match self.unconfirmed {
            // The only enabled length that validates here.
            1 => Check::Frame(self.only),
            0 => Check::Reject(error),
            // Two or more, and nothing after them says which.
            _ => Check::Reject(Error::Unconfirmed),
        }
    }
}

impl<S: TelemetrySide> Framing<S> {
    /// Accept telemetry in `layouts` (by default the four documented ones).
    /// Name a single layout when you know it: see the [length
    /// policy](super#telemetry-length-policy).
    pub const fn with_layouts(self, layouts: Layouts) -> Self {
        Framing {
            layouts,
            side: PhantomData,
        }
    }
}

impl<S: Side> Default for Framing<S> {
    fn default() -> Self {
        Framing::new()
    }
}

/// A command candidate: its id fixes its length.
#[inline(always)]
fn check_command(id: u8, c: &[u8], at_end: bool) -> Check<Error> {
    let n = match payload_len(id) {
        Some(n) => n,
        None => return Check::Reject(Error::UnknownId { id }),
    };
    let len = 3 + n;
    if c.len() < len {
        return if at_end {
            Check::Reject(Error::Truncated { len: c.len() })
        } else {
            Check::Need(len)
        };
    }
    let frame = &c[..len];
    let expected = match c.first_chunk::<MAX_COMMAND_LEN>() {
        // Enough bytes for the longest command: add the payload without
        // branching on its length (the mix of commands in a stream is
        // unpredictable), masking the bytes past it.
        Some(window) => {
            let word = u32::from_le_bytes([window[2], window[3], window[4], 0]);
            // n is 0, 1 or 3: keep its low n bytes.
            let mask = (1u32 << (8 * n)) - 1;
            let bytes = (word & mask).to_le_bytes();
            id.wrapping_add(bytes[0])
                .wrapping_add(bytes[1])
                .wrapping_add(bytes[2])
        }
        None => checksum(&frame[1..len - 1]),
    };
    let found = frame[len - 1];
    if expected == found {
        Check::Frame(len)
    } else {
        Check::Reject(Error::Checksum { expected, found })
    }
}

/// A single telemetry layout: the candidate is a frame of exactly its length
/// or nothing, and nothing needs confirming.
#[inline(always)]
fn check_single(layout: Layout, c: &[u8], at_end: bool) -> Check<Error> {
    // One fixed-size check per layout, so the sum runs over a constant range.
    match layout {
        Layout::Pos7 => check_fixed::<7>(c, at_end),
        Layout::Uwb15 => check_fixed::<15>(c, at_end),
        Layout::UwbTof17 => check_fixed::<17>(c, at_end),
        Layout::Spi45 => check_fixed::<45>(c, at_end),
        Layout::Ble53 => check_fixed::<53>(c, at_end),
    }
}

#[inline(always)]
fn check_fixed<const L: usize>(c: &[u8], at_end: bool) -> Check<Error> {
    let Some(frame) = c.first_chunk::<L>() else {
        return if at_end {
            Check::Reject(Error::Truncated { len: c.len() })
        } else {
            Check::Need(L)
        };
    };
    let expected = sum8(&frame[1..L - 1]);
    let found = frame[L - 1];
    if expected == found {
        Check::Frame(L)
    } else {
        Check::Reject(Error::Checksum { expected, found })
    }
}

impl<S: Side> stream::FrameRules for Framing<S> {
    type Error = Error;
    type Message<'a> = S::Message;
    type Owned = S::Message;

    /// `a5` and the id: enough to reject an unknown id.
    const HEADER_LEN: usize = 2;

    #[inline]
    fn find_start(&self, bytes: &[u8]) -> usize {
        // On a clean stream the next frame starts right here: skip the scan.
        match bytes.first() {
            Some(&START) => 0,
            // A few bytes (a small decoder buffer): a plain scan. Where the
            // length is known to be small, as in a command decoder's 14-byte
            // buffer, memchr's word-at-a-time search is not linked at all.
            _ if bytes.len() <= 16 => bytes
                .iter()
                .position(|&b| b == START)
                .unwrap_or(bytes.len()),
            _ => memchr::memchr(START, bytes).unwrap_or(bytes.len()),
        }
    }

    #[inline(always)]
    fn check(&self, c: &[u8], at_end: bool) -> Check<Error> {
        let Some(&id) = c.get(1) else {
            return if at_end {
                Check::Reject(Error::Truncated { len: c.len() })
            } else {
                Check::Need(2)
            };
        };
        S::check_id(self, id, c, at_end)
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
    fn parse(&self, frame: &[u8]) -> Result<S::Message, Error> {
        S::parse(frame)
    }

    fn to_owned(message: S::Message) -> S::Message {
        message
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Candidates that often validate at one or more lengths: frames of
    /// random layouts followed by another frame, zero padding or noise, some
    /// with the later frame's sums arranged to collide.
    fn candidates() -> impl Iterator<Item = [u8; MAX_FRAME_LEN + 2]> {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        (0..if cfg!(miri) { 300 } else { 60_000 }).map(move |_| {
            let mut c = [0u8; MAX_FRAME_LEN + 2];
            for b in &mut c {
                *b = next() as u8;
            }
            // A frame (or two overlapping ones) whose sums validate.
            for _ in 0..1 + next() % 2 {
                let layout = Layout::ALL[(next() % 5) as usize];
                let len = layout.frame_len();
                c[0] = START;
                c[1] = id::TELEMETRY;
                if next() % 4 == 0 {
                    c[len..].fill(0);
                }
                c[len - 1] = sum8(&c[1..len - 1]);
                if next() % 3 == 0 && len + 2 <= c.len() {
                    c[len] = START;
                    c[len + 1] = [id::TELEMETRY, 0x30, 0x00][(next() % 3) as usize];
                }
            }
            c
        })
    }

    #[test]
    fn the_window_check_answers_as_the_length_by_length_check() {
        let mut tried = 0;
        for (n, c) in candidates().enumerate() {
            let bits = (n % 32) as u8;
            if bits.count_ones() < 2 {
                continue;
            }
            tried += 1;
            let layouts = Layout::ALL
                .into_iter()
                .enumerate()
                .filter(|(i, _)| bits & 1 << i != 0)
                .fold(Layouts::NONE, |set, (_, l)| set.with(l));
            let framing = Framing::<Both>::new().with_layouts(layouts);
            let longest = layouts.longest().unwrap();
            for at_end in [false, true] {
                assert_eq!(
                    framing.check_window(longest, &c, at_end),
                    framing.check_lengths(longest, &c, at_end),
                    "{layouts:?} at_end {at_end} {c:02x?}"
                );
            }
        }
        assert!(tried > 100);
    }
}
