//! The one streaming engine shared by every protocol.
//!
//! A protocol describes its framing through the [`FrameRules`] trait: where a frame
//! may start, and — given the bytes from a candidate start — whether they are a
//! frame of length `n`, not a frame, or not enough to tell yet. [`StreamDecoder`]
//! does everything else, once, for all protocols:
//!
//! * **resync by one**: a failed candidate (bad checksum, unknown id, impossible
//!   length) costs only its first byte; every byte after it (including bytes
//!   that were buffered as its payload) is scanned again, so a frame that began
//!   inside a failed candidate is never lost;
//! * **zero-copy fast path**: a frame that lies wholly inside the caller's chunk is
//!   parsed in place; only a frame that straddles two chunks is copied into the
//!   fixed internal buffer of `N` bytes;
//! * **explicit consumption**: [`StreamDecoder::decode`] advances the caller's
//!   `&mut &[u8]` past exactly the bytes it has taken;
//! * **chunking invariance**: the same input gives the same frames and the same
//!   rejections however it is split, once [`StreamDecoder::finish`] has been called
//!   at the end of the input;
//! * **resync verification**: a candidate found after garbage is accepted only
//!   when no valid frame starts inside it, or when what follows confirms it (a
//!   plausible header or the end of input); otherwise it is set aside
//!   (superseded), so garbage that happens to sum right does not swallow the real
//!   frame after it. Candidates directly after a frame are trusted, so a clean
//!   stream is never delayed (details on [`StreamDecoder`]);
//! * **errors are events**: a bad candidate is reported as a [`Rejected`] event
//!   and decoding goes on; [`Stats`] counts frames, skipped bytes, checksum
//!   failures and other rejections, for watching link quality.
//!
//! The engine never allocates and every constructor is `const`, so a decoder can
//! live in a `static`.
//!
//! # Feeding a decoder
//!
//! * [`StreamDecoder::decode`] takes a chunk (`&mut &[u8]`) and returns the next
//!   event, borrowing the frame in place when it can; call it until it returns
//!   `None`.
//! * [`StreamDecoder::push`] takes one byte (for interrupt handlers); then call
//!   [`StreamDecoder::poll`] until it returns `None`, because a rejection can
//!   reveal frames among the bytes already buffered.
//! * [`StreamDecoder::feed`] and [`StreamDecoder::flush`] are iterators of owned
//!   events ([`OwnedFrame`] or [`Rejected`]), for code that collects or sends
//!   messages on.
//! * [`StreamDecoder::finish`] (or `flush`) at the end of the input resolves the
//!   buffered candidate: a frame that only the end could confirm comes out, a cut
//!   frame is reported as truncated.
//!
//! # Writing the frame rules of a new protocol
//!
//! A protocol module provides a framing value that implements [`FrameRules`],
//! usually `Framing<S>` with a side marker `S` from [`crate::side`] (`Host`
//! decodes what the device sends, `Device` what the host sends, `Both` either),
//! and type aliases of [`StreamDecoder`] for each side with a buffer constant.
//! The engine then gives it every decoder, the `io` adapters and the fuzzing
//! oracles (`fuzz/src/lib.rs`: `check_stream` works for any framing).
//!
//! * [`find_start`](FrameRules::find_start) returns the first index where a frame
//!   could start (a start byte or sync word, or any byte for a protocol without
//!   one). A sync word cut by the end of the input must still be returned.
//! * [`check`](FrameRules::check) looks at the bytes from a candidate start and
//!   answers [`Check::Need`] (with the least total it needs before the answer
//!   can change), [`Check::Frame`] (a valid frame of this length) or
//!   [`Check::Reject`]. Reject as early as the bytes allow: an impossible id or
//!   length from the header, so garbage is not held for a whole frame's length.
//!   Answers must be *consistent*: once `check` has said `Frame` or `Reject` for
//!   some bytes, it says the same for any longer input that starts with them.
//!   Chunking invariance rests on this, and the fuzz oracles test it.
//! * [`HEADER_LEN`](FrameRules::HEADER_LEN) is how many bytes `check` needs to
//!   reject an impossible header; the resync verification reads that many bytes
//!   after a candidate to decide whether a plausible frame follows it.
//! * [`VERIFY_AFTER_RESYNC`](FrameRules::VERIFY_AFTER_RESYNC): keep it `true`
//!   with a checksum. Without one (Telemetrix), plausible frames inside frames
//!   are so common that verifying costs about as many real frames as it saves.
//! * [`parse`](FrameRules::parse) builds the message from a frame `check`
//!   accepted. An error here consumes the frame and counts it as malformed: use
//!   it for contents that are wrong although the integrity check passed. Contents
//!   that show the candidate cannot be a frame at all (no checksum vouches for
//!   it) belong in `check`, as a rejection, so its bytes are rescanned.
//! * [`truncated`](FrameRules::truncated), [`superseded`](FrameRules::superseded)
//!   and [`is_checksum_error`](FrameRules::is_checksum_error) map the engine's
//!   own outcomes to the protocol's `Error`.
//! * Size the decoder's buffer at about twice the longest frame plus
//!   `HEADER_LEN`, so the resync verification has room for a candidate, a frame
//!   starting inside it and the header after that.
//!
//! # Writing fast frame rules
//!
//! What the engine does, and what a framing can do, to keep decoding near memory
//! speed (the figures are in `docs/performance.md`):
//!
//! * **One parse site.** `decode` resolves a candidate to a small step (an
//!   offset and a slice, in place or in the buffer) and parses it in one place,
//!   so the message is built once, straight into the returned event. Before, each
//!   path built its own event and LLVM copied ~100-byte events where the paths
//!   joined, with narrow stores followed by wide loads (store-forwarding stalls:
//!   45–70 % of the samples on single `movaps` instructions).
//! * **Inlined hot path.** `decode`, the in-place step, the fast path of
//!   candidate resolution and the counted parse are `#[inline(always)]`, so the
//!   decoder runs inside the caller's loop; the buffered step, the resync
//!   verification (only after a resync) and dropping consumed bytes stay out of
//!   line. A protocol's `check`, `parse` and `find_start` should be `#[inline]`
//!   (they are called across crates) — OmniTiles' `check` is `#[inline(always)]`.
//! * **A short path for small messages (64-bit hosts).** A message of at most
//!   64 bytes found where the input starts, with the decoder synced, is parsed
//!   straight into the returned event (or its start buffered), skipping the
//!   general step's enum of outcomes; larger messages keep the one parse site,
//!   where they are faster. On 64-bit hosts the buffered step is also kept out
//!   of line (inlined, it cost the in-place loop registers and copies).
//!   Microcontrollers keep one compact path: the size report's rows do not
//!   change.
//! * **An event built where it is read.** [`decode_each`](StreamDecoder::decode_each)
//!   hands each event to a closure from the place it is built, so no path
//!   joins another before the caller reads it; with the framing's
//!   [`parse_common`](FrameRules::parse_common) shortcut, the common message
//!   is built straight from the frame's bytes into that event. The `decode`
//!   loop returns its event, which every path of `decode` must write to one
//!   place: a message of 64 bytes (Telemetrix's `Report`) built with narrow
//!   stores is then copied with wide loads (store-forwarding stalls, half of
//!   the loop's samples), which `decode_each` avoids: 2.4–2.6× the loop on
//!   the Telemetrix reports bench. The frame the previous chunk cut is
//!   completed first, from the bytes the framing asked for when it was kept
//!   (not the whole chunk appended to the buffer and scanned there, as the
//!   general step does): 6 % off the chunked Telemetrix row.
//! * **Buffer fast paths.** A buffered frame that was all the buffer held empties
//!   the buffer when it is emitted (no copy, no rescan on the next call).
//! * **A byte path for firmware.** `push` and `poll` resolve the stored bytes
//!   on a path of their own (no input slice to hand back) that parses in one
//!   place, so a firmware fed by a receive interrupt links neither the
//!   in-place step nor two copies of the parser. A buffer of up to 32 bytes
//!   is shifted whole, a constant count, so no `memmove` is linked; and no
//!   step can panic (slices are taken with `get`), which the size report
//!   (`size/report.py`) checks on the final binaries.
//! * **What a framing can do** (as OmniTiles does): answer `find_start` from the
//!   first byte when it is a start byte before calling `memchr` (the next frame
//!   usually starts right there); read fixed-size frames through
//!   `first_chunk::<L>()` so every field read has a constant offset (no bounds
//!   checks); sum fixed ranges so LLVM unrolls and vectorises; replace an
//!   unpredictable `match` on a message id by a table built at compile time;
//!   avoid branching on a length that varies frame to frame (the OmniTiles
//!   command checksum masks the payload instead).
//!
//! OmniTiles specifics: telemetry parsing dispatches per layout to a fixed-size
//! reader; `check` with a single layout sums a fixed range; the multi-layout
//! search stays out of line and adds eight bytes at a time; the command payload
//! length is a 256-entry table built from the command list at compile time.
//!
//! What is left: a frame cut by a chunk boundary goes through the buffer, and
//! reading it right after it was written costs a store-forwarding stall; the
//! measurements and what limits each row are in `docs/performance.md`.

use core::fmt;

/// What a [`FrameRules`] says about the bytes that begin at a candidate start.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check<E> {
    /// The bytes are a prefix of something that could still become a frame; the
    /// answer cannot change before at least this many bytes (counted from the
    /// candidate start) are available.
    Need(usize),
    /// A complete, valid frame of this many bytes starts here.
    Frame(usize),
    /// No frame starts here: the engine drops the candidate's first byte and
    /// rescans everything after it.
    Reject(E),
}

/// A protocol's framing rules: everything the engine needs to find frames.
///
/// Implementations must be *consistent*: once [`check`](FrameRules::check) has
/// answered [`Check::Frame`] or [`Check::Reject`] for some bytes, it must give the
/// same answer for any longer input that starts with those bytes (when `at_end`
/// is false). The engine's chunking invariance rests on this.
pub trait FrameRules {
    /// Why a candidate was rejected or a frame could not be parsed.
    type Error: Copy + fmt::Debug + Eq;
    /// The typed message parsed from a valid frame; it may borrow the frame.
    type Message<'a>;
    /// An owned form of [`Message`](FrameRules::Message), for iterators and for
    /// keeping a message after its bytes are gone.
    type Owned;

    /// Bytes from a candidate start that are enough for [`check`](FrameRules::check)
    /// to reject an impossible header (start, id or type, length). The engine
    /// reads this many bytes after a frame to tell whether another frame
    /// plausibly follows it (see [`StreamDecoder`]'s resync verification).
    const HEADER_LEN: usize;

    /// Whether the engine verifies candidates found after a resync against
    /// overlapping frames (see [`StreamDecoder`]). Worth it with a checksum,
    /// which makes a valid frame inside another rare; without one, plausible
    /// frames inside frames are so common that the test costs about as many
    /// real frames as it saves.
    const VERIFY_AFTER_RESYNC: bool = true;

    /// The index of the first byte in `bytes` at which a frame could start, or
    /// `bytes.len()` if none can. A start that cannot be confirmed from `bytes`
    /// alone (a multi-byte sync word cut by the end of `bytes`) must be returned.
    fn find_start(&self, bytes: &[u8]) -> usize;

    /// Examine `candidate`, whose first byte was returned by
    /// [`find_start`](FrameRules::find_start). `at_end` says no more bytes will
    /// follow `candidate`, so [`Check::Need`] is then taken as truncation.
    fn check(&self, candidate: &[u8], at_end: bool) -> Check<Self::Error>;

    /// The error reported when the input ends inside a candidate of `len` bytes.
    fn truncated(&self, len: usize) -> Self::Error;

    /// The error reported for a candidate of `len` bytes that validated but
    /// was set aside because a frame overlapping it is confirmed by what
    /// follows it and the candidate is not (see [`StreamDecoder`]).
    fn superseded(&self, len: usize) -> Self::Error;

    /// Whether `error` is an integrity failure (counted in
    /// [`Stats::checksum_failures`]).
    fn is_checksum_error(&self, error: &Self::Error) -> bool;

    /// Parse a frame that [`check`](FrameRules::check) accepted. An error here
    /// consumes the frame (its integrity checked out, its contents did not).
    fn parse<'a>(&self, frame: &'a [u8]) -> Result<Self::Message<'a>, Self::Error>;

    /// The message of `frame` (one that [`check`](FrameRules::check)
    /// accepted) when it is one of the common messages the framing reads
    /// without the general parse, else `None` (the default: every frame
    /// takes [`parse`](FrameRules::parse)). A shortcut, never a definition:
    /// for any `Some(message)`, `parse` returns `Ok(message)`.
    /// The decoder tries it before `parse` (so `parse` may be the full
    /// parse alone), and [`StreamDecoder::decode_each`] builds such a
    /// message straight into the event it hands over.
    #[inline(always)]
    fn parse_common<'a>(&self, frame: &'a [u8]) -> Option<Self::Message<'a>> {
        let _ = frame;
        None
    }

    /// Turn a parsed message into its owned form.
    fn to_owned(message: Self::Message<'_>) -> Self::Owned;

    /// Turn a message parsed from `frame` (its bytes) into its owned form.
    /// By default [`to_owned`](FrameRules::to_owned); an owned form that
    /// keeps the frame's bytes copies `frame`, so that nothing the parse
    /// read leniently is lost.
    fn to_owned_from(frame: &[u8], message: Self::Message<'_>) -> Self::Owned {
        let _ = frame;
        Self::to_owned(message)
    }
}

/// A decoded frame: where it was in the stream, its bytes and its message.
///
/// With the `serde` feature it serializes in the JSON-lines schema of the
/// `robowire` tool, as [`OwnedFrame`] does: `offset`, `len`, then the
/// message's own members (`raw` is not written).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame<'a, M> {
    /// Offset of the frame's first byte, counted from the first byte the decoder
    /// was ever given.
    pub offset: u64,
    /// The frame's bytes on the wire.
    pub raw: &'a [u8],
    /// The typed message.
    pub message: M,
}

impl<M> Frame<'_, M> {
    /// The frame's length in bytes.
    pub const fn len(&self) -> usize {
        self.raw.len()
    }

    /// Always false: a frame has at least one byte. Present for API symmetry.
    pub const fn is_empty(&self) -> bool {
        self.raw.is_empty()
    }
}

/// An owned decoded message with its place in the stream, as the
/// [`Feed`] and [`Flush`] iterators yield it.
///
/// With the `serde` feature it is one flat object, the JSON-lines schema of
/// the `robowire` tool: `offset`, `len`, then the message's own members
/// (`{"offset":0,"len":4,"type":"m1_extend","speed":200}`).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct OwnedFrame<M> {
    /// Offset of the frame's first byte, as in [`Frame::offset`].
    pub offset: u64,
    /// The frame's length in bytes.
    pub len: usize,
    /// The typed message.
    pub message: M,
}

/// A rejected candidate or an unparseable frame, with its stream offset.
///
/// With the `serde` feature it is one flat object: `offset`, then the
/// error's own members (`{"offset":2,"error":"checksum","expected":248,"found":247}`).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rejected<E> {
    /// Offset of the candidate's first byte, as in [`Frame::offset`].
    pub offset: u64,
    /// What was wrong.
    pub error: E,
}

impl<E: fmt::Display> fmt::Display for Rejected<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at byte {}: {}", self.offset, self.error)
    }
}

impl<E: fmt::Display + fmt::Debug> core::error::Error for Rejected<E> {}

/// One thing the decoder found: a frame, or a rejected candidate. Rejections are
/// never fatal; the decoder has already moved past them.
pub type Event<'a, M, E> = Result<Frame<'a, M>, Rejected<E>>;

/// Link-quality counters. They always add up:
/// `bytes == frame_bytes + skipped + buffered` (see [`StreamDecoder::buffered`]).
///
/// `C` is their integer type, the decoder's choice (see [`Counter`]): `u64`
/// by default, `u32` or `u16` where RAM and code are scarce. Narrow counters
/// wrap around, and so do the stream offsets the decoder reports with them.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Stats<C = u64> {
    /// Bytes taken from the caller's input.
    pub bytes: C,
    /// Frames that passed framing (parsed or not).
    pub frames: C,
    /// Bytes that belonged to those frames.
    pub frame_bytes: C,
    /// Bytes that belonged to no frame: garbage between frames and the first
    /// byte of every rejected candidate.
    pub skipped: C,
    /// Candidates rejected for a bad checksum (`checksum_errors` before
    /// 0.3).
    #[cfg_attr(feature = "serde", serde(alias = "checksum_errors"))]
    pub checksum_failures: C,
    /// Candidates rejected for any other reason (unknown id, impossible length,
    /// truncation at the end of input), the `superseded` ones included
    /// (serde reads 0.2's `rejected`, which left them out, into it).
    #[cfg_attr(feature = "serde", serde(alias = "rejected"))]
    pub other_rejections: C,
    /// Frames whose integrity was fine but whose contents did not parse.
    pub malformed: C,
    /// Candidates that validated after a resync but were set aside for an
    /// overlapping frame that what follows confirmed (counted in
    /// `other_rejections` too).
    pub superseded: C,
}

impl Stats {
    /// All counters zero.
    pub const fn new() -> Stats {
        Stats::zero()
    }
}

impl<C: Counter> Stats<C> {
    /// All counters zero, of any [`Counter`] type (`Stats::<u32>::zero()`).
    pub const fn zero() -> Stats<C> {
        Stats {
            bytes: C::ZERO,
            frames: C::ZERO,
            frame_bytes: C::ZERO,
            skipped: C::ZERO,
            checksum_failures: C::ZERO,
            other_rejections: C::ZERO,
            malformed: C::ZERO,
            superseded: C::ZERO,
        }
    }

    /// Add another decoder's counters to these.
    pub fn add(&mut self, other: &Stats<C>) {
        self.bytes = self.bytes.sum(other.bytes);
        self.frames = self.frames.sum(other.frames);
        self.frame_bytes = self.frame_bytes.sum(other.frame_bytes);
        self.skipped = self.skipped.sum(other.skipped);
        self.checksum_failures = self.checksum_failures.sum(other.checksum_failures);
        self.other_rejections = self.other_rejections.sum(other.other_rejections);
        self.malformed = self.malformed.sum(other.malformed);
        self.superseded = self.superseded.sum(other.superseded);
    }

    /// [`checksum_failures`](Stats::checksum_failures), under its 0.2 name.
    #[deprecated(since = "0.3.0", note = "read the field `checksum_failures`")]
    pub fn checksum_errors(&self) -> C {
        self.checksum_failures
    }

    /// The 0.2 count of other rejections, without the superseded
    /// candidates: [`other_rejections`](Stats::other_rejections) less
    /// [`superseded`](Stats::superseded).
    #[deprecated(
        since = "0.3.0",
        note = "read the field `other_rejections` (which counts superseded candidates too)"
    )]
    pub fn rejected(&self) -> C {
        self.other_rejections.less(self.superseded)
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for u16 {}
    impl Sealed for u32 {}
    impl Sealed for u64 {}
}

/// The integer type of a decoder's [`Stats`] and of the stream offset it
/// keeps: `u64` (the default), `u32` or `u16` (sealed).
///
/// On a 32-bit microcontroller `u32` counters halve the counters' RAM (32
/// bytes instead of 64) and their code (one add instead of an add with
/// carry); they wrap after 4 GiB, and the offsets in events wrap with them.
///
/// ```
/// use robowire::omnitiles::{Device, Framing, DEVICE_BUFFER};
/// use robowire::StreamDecoder;
///
/// let mut decoder: StreamDecoder<Framing<Device>, DEVICE_BUFFER, u32> =
///     StreamDecoder::new(Framing::new());
/// let mut input = &[0xa5, 0x50, 0x50][..];
/// while decoder.decode(&mut input).is_some() {}
/// let frames: u32 = decoder.stats().frames;
/// assert_eq!(frames, 1);
/// ```
pub trait Counter:
    sealed::Sealed + Copy + Eq + Ord + Default + core::hash::Hash + fmt::Debug + fmt::Display + 'static
{
    /// Zero.
    const ZERO: Self;
    /// `self + n`, wrapping.
    #[doc(hidden)]
    fn plus(self, n: usize) -> Self;
    /// `self + other`, wrapping.
    #[doc(hidden)]
    fn sum(self, other: Self) -> Self;
    /// `self - other`, wrapping.
    #[doc(hidden)]
    fn less(self, other: Self) -> Self;
    /// The value as a `u64` (an offset in an event).
    fn to_u64(self) -> u64;
}

macro_rules! counter {
    ($($t:ty),*) => {$(
        impl Counter for $t {
            const ZERO: $t = 0;
            #[inline(always)]
            fn plus(self, n: usize) -> $t {
                self.wrapping_add(n as $t)
            }
            #[inline(always)]
            fn sum(self, other: $t) -> $t {
                self.wrapping_add(other)
            }
            #[inline(always)]
            fn less(self, other: $t) -> $t {
                self.wrapping_sub(other)
            }
            #[inline(always)]
            fn to_u64(self) -> u64 {
                self as u64
            }
        }
    )*};
}

counter!(u16, u32, u64);

/// One line, as the `robowire` tool's summary prints it:
/// `2 frames, 20 bytes, 11 bytes skipped, 1 checksum failure, 2 other
/// rejections, 0 malformed`, the words of the fields (a count of 1 takes the
/// singular).
///
/// ```
/// let mut stats = robowire::Stats::new();
/// (stats.frames, stats.bytes, stats.frame_bytes, stats.skipped) = (1, 4, 3, 1);
/// assert_eq!(
///     stats.to_string(),
///     "1 frame, 4 bytes, 1 byte skipped, 0 checksum failures, 0 other rejections, 0 malformed"
/// );
/// ```
impl<C: Counter> fmt::Display for Stats<C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = |n: u64| if n == 1 { "" } else { "s" };
        write!(
            f,
            "{} frame{}, {} byte{}, {} byte{} skipped, {} checksum failure{}, \
             {} other rejection{}, {} malformed",
            self.frames,
            s(self.frames.to_u64()),
            self.bytes,
            s(self.bytes.to_u64()),
            self.skipped,
            s(self.skipped.to_u64()),
            self.checksum_failures,
            s(self.checksum_failures.to_u64()),
            self.other_rejections,
            s(self.other_rejections.to_u64()),
            self.malformed
        )
    }
}

/// The protocol-neutral incremental decoder. `N` is the capacity of the internal
/// buffer that holds a frame straddling two chunks; it must be at least the
/// longest candidate the framing can ask for, and about twice that for the
/// resync verification below to have room.
///
/// # Resync verification
///
/// A weak check (an 8-bit sum, or none) lets garbage validate by chance, and a
/// false frame that reaches into a real one would swallow it. So a candidate
/// found after skipped bytes or a rejection is accepted at once only if no start
/// inside it begins another valid frame. If one does, the candidate is kept
/// only when it is *confirmed*: followed by a plausible header
/// ([`FrameRules::HEADER_LEN`] bytes that `check` does not reject) or by the end
/// of input, and the inner frame does not end exactly where it ends (then
/// nothing after them can tell them apart, and the later start wins: garbage
/// before a frame is likelier than a frame at a payload's tail). Otherwise it
/// is set aside ([`FrameRules::superseded`]) and the
/// decoder resyncs by one, so the frame inside it is found. A candidate at the
/// very start of the stream or directly after a frame is trusted, so a clean
/// stream is never delayed or slowed by this.
///
/// `C` is the integer type of the counters and the stream offset (see
/// [`Counter`]): `u64` unless you name another.
#[derive(Debug, Clone)]
pub struct StreamDecoder<F, const N: usize, C = u64> {
    framing: F,
    buf: [u8; N],
    /// Bytes of the current candidate held in `buf` (from previous inputs).
    len: usize,
    /// Bytes at the front of `buf` to drop before the next call: the frame that
    /// the last returned event borrowed.
    pending_drop: usize,
    /// Stream offset of `buf[0]`.
    buf_offset: C,
    /// The buffered candidate cannot resolve before it has this many bytes.
    need: usize,
    /// Whether the next candidate starts right where the last frame ended (or
    /// at the very start of the stream). Any other candidate (one after
    /// skipped bytes or a rejection) is verified against overlapping frames
    /// before it is accepted.
    synced: bool,
    stats: Stats<C>,
}

impl<F: FrameRules, const N: usize, C: Counter> StreamDecoder<F, N, C> {
    /// A decoder with empty state using `framing`.
    pub const fn new(framing: F) -> Self {
        Self {
            framing,
            buf: [0; N],
            len: 0,
            pending_drop: 0,
            buf_offset: C::ZERO,
            need: 0,
            synced: true,
            stats: Stats::zero(),
        }
    }

    /// The framing rules in use.
    pub const fn framing(&self) -> &F {
        &self.framing
    }

    /// The counters so far.
    pub const fn stats(&self) -> Stats<C> {
        self.stats
    }

    /// Bytes held in the internal buffer as the start of an unfinished candidate.
    pub const fn buffered(&self) -> usize {
        self.len - self.pending_drop
    }

    /// Stream offset of the next byte the decoder will take (it wraps with
    /// narrow [`Counter`]s).
    pub fn position(&self) -> u64 {
        self.stats.bytes.to_u64()
    }

    /// Forget any buffered partial candidate (counting it as skipped) and keep
    /// the counters and stream position.
    pub fn clear(&mut self) {
        self.apply_pending_drop();
        self.stats.skipped = self.stats.skipped.plus(self.len);
        if self.len > 0 {
            self.synced = false;
        }
        self.len = 0;
        self.need = 0;
    }

    /// Take bytes from the front of `input` until an event is found or the input
    /// is used up; `input` is advanced past every byte taken. Returns `None` when
    /// all of `input` has been taken (a trailing partial frame is kept inside).
    ///
    /// Call it in a loop, `while let Some(event) = decoder.decode(&mut input)`;
    /// [`decode_each`](Self::decode_each) does the same loop faster.
    // Inlined into the caller's loop: the event is then built where the caller
    // reads it, not returned through memory (see `emit`).
    #[inline(always)]
    pub fn decode<'a, 'i: 'a>(
        &'a mut self,
        input: &mut &'i [u8],
    ) -> Option<Event<'a, F::Message<'a>, F::Error>> {
        self.apply_pending_drop();
        // The clean stream's path, for messages of up to a cache line (a
        // larger message is better built at `emit`'s one parse site).
        // Measured: this path makes commands, telemetry views and Pixy2
        // responses 10-40 % faster, and 76-byte OmniTiles telemetry 10-17 %
        // slower.
        let small = core::mem::size_of::<F::Message<'i>>() <= 64;
        if small {
            match self.clean_step(input) {
                Clean::Frame { offset, raw } => {
                    return Some(parse_counted(&self.framing, &mut self.stats, offset, raw))
                }
                Clean::Kept => return None,
                Clean::General => {}
            }
        }
        let step = if self.len > 0 {
            self.step_buffered(input)
        } else {
            self.step_in_place(input)
        };
        self.emit(step)
    }

    /// Decode all of `input`, handing each event to `on_event` in stream
    /// order: the events of `while let Some(event) = decoder.decode(&mut
    /// input)`, and as there a trailing partial frame is kept for the next
    /// call (or [`finish`](Self::finish)).
    ///
    /// Faster than that loop: each event is built where `on_event` reads it,
    /// and a message the framing reads by its
    /// [`parse_common`](FrameRules::parse_common) shortcut (the reports a
    /// Telemetrix Pico streams) is built straight from the frame's bytes,
    /// so a large message enum is never copied between the decoder's paths
    /// (`cargo bench --bench telemetrix`: 2.4–2.6× the loop; docs/performance.md).
    ///
    /// ```
    /// use robowire::telemetrix::{host_decoder, Report};
    ///
    /// let mut decoder = host_decoder();
    /// let mut pins = Vec::new();
    /// // Two digital reports, the second cut by the end of the chunk.
    /// decoder.decode_each(&[0x03, 0x02, 0x05, 0x01, 0x03, 0x02], |event| {
    ///     if let Ok(frame) = event {
    ///         if let Report::Digital { pin, .. } = frame.message {
    ///             pins.push(pin);
    ///         }
    ///     }
    /// });
    /// decoder.decode_each(&[0x07, 0x00], |event| {
    ///     if let Ok(frame) = event {
    ///         if let Report::Digital { pin, .. } = frame.message {
    ///             pins.push(pin);
    ///         }
    ///     }
    /// });
    /// assert_eq!(pins, [5, 7]);
    /// ```
    #[inline(always)]
    pub fn decode_each(
        &mut self,
        mut input: &[u8],
        mut on_event: impl FnMut(Event<'_, F::Message<'_>, F::Error>),
    ) {
        self.apply_pending_drop();
        // A frame the clean path kept at the end of the previous chunk:
        // completed from the front of this one.
        if let Some((offset, n)) = self.complete_kept(&mut input) {
            let raw = prefix(&self.buf, n);
            deliver(&self.framing, &mut self.stats, offset, raw, &mut on_event);
        }
        loop {
            self.apply_pending_drop();
            // The clean stream's path, whatever the message's size: its event
            // goes to `on_event` from here, so nothing is copied.
            match self.clean_step(&mut input) {
                Clean::Frame { offset, raw } => {
                    deliver(&self.framing, &mut self.stats, offset, raw, &mut on_event);
                    continue;
                }
                Clean::Kept => return,
                Clean::General => {}
            }
            // Anything else (a frame cut by the previous chunk, a resync, a
            // rejection) takes `decode`'s general step.
            match self.decode(&mut input) {
                Some(event) => on_event(event),
                None => return,
            }
        }
    }

    /// The clean stream's path: the next frame starts at the front of
    /// `input`, nothing is buffered and the stream is in sync. A frame wholly
    /// inside `input` is taken (without the general step's enum of outcomes);
    /// one that runs past its end is buffered. Anything else is left to the
    /// general step, which asks the framing again. Only on 64-bit hosts: on
    /// a microcontroller its second copy of the framing and parser costs
    /// flash (about 380 B in the size report's decode row).
    #[inline(always)]
    fn clean_step<'i>(&mut self, input: &mut &'i [u8]) -> Clean<'i> {
        let data: &'i [u8] = input;
        if cfg!(target_pointer_width = "64")
            && self.len == 0
            && (self.synced || !F::VERIFY_AFTER_RESYNC)
            && !data.is_empty()
            && self.framing.find_start(data) == 0
        {
            let offset = self.stats.bytes;
            match self.framing.check(data, false) {
                Check::Frame(n) if n > 0 => {
                    if let Some((raw, rest)) = data.split_at_checked(n) {
                        self.stats.bytes = offset.plus(n);
                        self.synced = true;
                        *input = rest;
                        return Clean::Frame {
                            offset: offset.to_u64(),
                            raw,
                        };
                    }
                }
                Check::Need(n) if data.len() < N => {
                    self.keep_tail(data, n.max(data.len() + 1), offset);
                    self.stats.bytes = offset.plus(data.len());
                    *input = &[];
                    return Clean::Kept;
                }
                _ => {}
            }
        }
        Clean::General
    }

    /// The clean stream's frame cut by the end of the last chunk, completed
    /// from the front of `input`: the bytes it still needs (what the framing
    /// asked for when it was kept) are appended, and the framing is asked
    /// again, on the frame's bytes only, until it answers. Returns the
    /// frame's offset and length, emitted from the front of the buffer as
    /// the general step emits a buffered frame, or `None` with nothing changed (no frame
    /// kept, the stream not in sync, too little input, or anything but a
    /// frame of exactly the bytes given), for the general step to decide.
    /// By the framing's consistency the answer is the one the general step
    /// would give on the whole input. Only on 64-bit hosts, as
    /// [`clean_step`](Self::clean_step).
    #[inline(always)]
    fn complete_kept(&mut self, input: &mut &[u8]) -> Option<(u64, usize)> {
        let stored = self.len;
        // (In sync, or never verified: as `resolve` asks.)
        if !cfg!(target_pointer_width = "64")
            || stored == 0
            || (!self.synced && F::VERIFY_AFTER_RESYNC)
        {
            return None;
        }
        let data: &[u8] = input;
        let mut have = stored;
        let mut want = self.need.max(stored + 1);
        let n = loop {
            // The bytes `have..want` (`want <= N`), if the input holds them.
            let more = data.get(have - stored..want - stored)?;
            copy_into(&mut self.buf, have, more);
            have = want;
            let frame = prefix(&self.buf, have);
            if self.framing.find_start(frame) != 0 {
                return None;
            }
            match self.framing.check(frame, false) {
                Check::Frame(n) if n == have => break n,
                Check::Need(n) if n > have && n <= N => want = n,
                _ => return None,
            }
        };
        let used = n - stored;
        *input = data.get(used..).unwrap_or(&[]);
        self.stats.bytes = self.stats.bytes.plus(used);
        self.len = n;
        Some((self.emit_buffered(n), n))
    }

    /// Feed one byte (for interrupt handlers). The byte is always taken. It
    /// completes at most one event; a rejection can reveal further events among
    /// the bytes already buffered, so call [`poll`](Self::poll) until it returns
    /// `None` before the next `push`.
    pub fn push(&mut self, byte: u8) -> Option<Event<'_, F::Message<'_>, F::Error>> {
        self.apply_pending_drop();
        let at = self.stats.bytes;
        self.stats.bytes = at.plus(1);
        if self.len == 0 {
            if self.framing.find_start(&[byte]) > 0 {
                self.stats.skipped = self.stats.skipped.plus(1);
                self.synced = false;
                return None;
            }
            self.buf_offset = at;
            self.need = 0;
        }
        // `len < N` holds between calls: a full buffer is always resolved.
        // (Only a decoder without a buffer, `N == 0`, has no room: it can
        // decode in place only, so the byte is skipped.)
        let Some(slot) = self.buf.get_mut(self.len) else {
            self.stats.skipped = self.stats.skipped.plus(1);
            self.synced = false;
            return None;
        };
        *slot = byte;
        self.len += 1;
        // The byte path: resolve the stored bytes only, without the general
        // step's handling of an input slice.
        self.next_stored()
    }

    /// Collect the events that need no further input (after [`push`](Self::push)
    /// or a rejection): the same as [`decode`](Self::decode) with an empty input.
    pub fn poll(&mut self) -> Option<Event<'_, F::Message<'_>, F::Error>> {
        self.apply_pending_drop();
        if self.len == 0 {
            return None;
        }
        self.next_stored()
    }

    /// The byte path's one place to resolve and parse (`push` and `poll`
    /// share it, so a firmware links the message parser once).
    fn next_stored(&mut self) -> Option<Event<'_, F::Message<'_>, F::Error>> {
        let step = self.step_stored();
        self.emit(step)
    }

    /// Decode a whole chunk: an iterator of owned events. Every byte of `input`
    /// is taken once the iterator is exhausted (a trailing partial frame is
    /// buffered). Dropping the iterator early leaves the untaken bytes
    /// untaken: [`Feed::remaining`] tells which.
    pub fn feed<'d, 'i>(&'d mut self, input: &'i [u8]) -> Feed<'d, 'i, F, N, C> {
        Feed {
            decoder: self,
            input,
        }
    }

    /// End of input as an iterator: the owned events of [`finish`](Self::finish).
    pub fn flush(&mut self) -> Flush<'_, F, N, C> {
        Flush { decoder: self }
    }

    /// Signal the end of the input: resolve whatever is buffered. Call it in a
    /// loop until it returns `None`; the decoder is then empty and can take a new
    /// stream (counters and position carry on).
    pub fn finish(&mut self) -> Option<Event<'_, F::Message<'_>, F::Error>> {
        self.apply_pending_drop();
        if self.len == 0 {
            return None;
        }
        let error = match self.resolve(self.stored(self.len), true) {
            Verdict::Frame(n) => return self.emit(Step::Buffered(n)),
            Verdict::Need(_) => self.reject_kind(self.framing.truncated(self.len)),
            Verdict::Reject(error) => self.reject_kind(error),
            Verdict::Superseded(n) => self.supersede_kind(n),
        };
        let step = self.reject_buffered(error);
        self.emit(step)
    }

    /// The line has gone idle: resolve what is buffered as the end of input
    /// would, but only where that gives a frame, and keep anything else. A
    /// frame whose end the framing left open (a short OmniTiles telemetry
    /// layout that may be a longer one's prefix, which only the next byte
    /// decides) comes out now instead of when the next frame starts; an
    /// unfinished frame stays buffered for the rest of its bytes, and
    /// nothing is rejected. Call it in a loop until it returns `None`.
    ///
    /// Call it only when the silence says a frame has ended (a few
    /// byte-times with no byte at the line's baud rate, or the end of a
    /// datagram that holds whole frames): a sender writes each frame back
    /// to back, so a short frame taken at a pause is no prefix. Called
    /// between two pieces of one frame, it can take that frame's prefix
    /// where the prefix happens to pass as a shorter frame.
    ///
    /// ```
    /// use robowire::omnitiles::{Framing, Host, HOST_BUFFER};
    /// use robowire::StreamDecoder;
    /// let mut decoder = StreamDecoder::<_, HOST_BUFFER>::new(Framing::<Host>::new());
    /// let pos7 = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
    /// // 7 bytes may be the start of a 15, 17 or 53-byte frame: buffered.
    /// assert!(decoder.feed(&pos7).next().is_none());
    /// assert!(decoder.settle().is_some_and(|event| event.is_ok()));
    /// assert_eq!(decoder.buffered(), 0);
    /// // Half a frame stays buffered for its rest.
    /// assert!(decoder.feed(&pos7[..4]).next().is_none());
    /// assert!(decoder.settle().is_none());
    /// assert_eq!(decoder.buffered(), 4);
    /// ```
    pub fn settle(&mut self) -> Option<Event<'_, F::Message<'_>, F::Error>> {
        self.apply_pending_drop();
        if self.len == 0 {
            return None;
        }
        match self.resolve(self.stored(self.len), true) {
            Verdict::Frame(n) => {
                // What follows the frame is judged afresh when it completes.
                self.need = 0;
                self.emit(Step::Buffered(n))
            }
            Verdict::Need(_) | Verdict::Reject(_) | Verdict::Superseded(_) => None,
        }
    }

    #[inline(always)]
    fn apply_pending_drop(&mut self) {
        let n = self.pending_drop;
        if n > 0 {
            self.drop_front(n);
        }
    }

    /// Remove the emitted frame at the front of the buffer.
    fn drop_front(&mut self, n: usize) {
        self.pending_drop = 0;
        self.buf_offset = self.buf_offset.plus(n);
        if n >= self.len {
            self.len = 0;
            return;
        }
        self.shift_out(n, self.len);
        self.len -= n;
        self.realign_buffer();
    }

    /// Make `buf[0]` a candidate start again after its front was removed.
    fn realign_buffer(&mut self) {
        let skip = self.framing.find_start(self.stored(self.len));
        if skip > 0 {
            self.synced = false;
            self.shift_out(skip, self.len);
            self.len -= skip.min(self.len);
            self.buf_offset = self.buf_offset.plus(skip);
            self.stats.skipped = self.stats.skipped.plus(skip);
        }
    }

    /// The first `len` bytes of the buffer (`len <= N` always holds; the
    /// fallback only keeps panic paths out of the binary).
    #[inline(always)]
    fn stored(&self, len: usize) -> &[u8] {
        prefix(&self.buf, len)
    }

    /// Move `buf[from..len]` to the front of the buffer.
    #[inline]
    fn shift_out(&mut self, from: usize, len: usize) {
        if N <= SMALL_BUFFER {
            // A small buffer moves whole, a constant count of bytes: cheaper
            // than a call, and no `memmove` is linked.
            for i in 0..N {
                self.buf[i] = self.buf.get(i + from).copied().unwrap_or(0);
            }
        } else if from <= len && len <= N {
            self.buf.copy_within(from..len, 0);
        }
    }

    /// The framing's answer for a candidate, with the resync verification.
    #[inline(always)]
    fn resolve(&self, c: &[u8], at_end: bool) -> Verdict<F::Error> {
        let n = match self.framing.check(c, at_end) {
            Check::Frame(n) if n > 0 && n <= c.len() => n,
            Check::Frame(n) | Check::Need(n) => return Verdict::Need(n.max(c.len() + 1)),
            Check::Reject(e) => return Verdict::Reject(e),
        };
        if self.synced || !F::VERIFY_AFTER_RESYNC {
            return Verdict::Frame(n);
        }
        self.verify(c, n, at_end)
    }

    /// The resync verification of a frame of `n` bytes at the start of `c`
    /// (out of line: a clean stream never needs it).
    #[inline(never)]
    fn verify(&self, c: &[u8], n: usize, at_end: bool) -> Verdict<F::Error> {
        // Verification looks at no more than the buffer could hold, so its
        // answer is the same whether the bytes arrived in one chunk or many.
        let at_end = at_end && c.len() <= N;
        let c = prefix_of(c, N);
        if n > c.len() {
            // A frame longer than the buffer (found in place) could never
            // wait for what follows it: accept it, as `wait_or_accept` would.
            return Verdict::Frame(n);
        }
        let mut p = 1;
        while p < n {
            p += self.framing.find_start(&c[p..n]);
            if p >= n {
                break;
            }
            let inner_end = match self.framing.check(&c[p..], at_end) {
                Check::Frame(m) if m > 0 && p + m <= c.len() => p + m,
                Check::Frame(m) | Check::Need(m) if !at_end => {
                    return self.wait_or_accept(n, p + m)
                }
                // At the end of input an unfinished inner candidate is no frame.
                Check::Frame(_) | Check::Need(_) | Check::Reject(_) => {
                    p += 1;
                    continue;
                }
            };
            // A frame starts inside the candidate. If both end together, what
            // follows cannot tell them apart: the later start wins (garbage
            // before a frame is likelier than a frame at a payload's tail).
            // Otherwise keep the candidate only if what follows confirms it.
            if inner_end == n {
                return Verdict::Superseded(n);
            }
            if inner_end > n {
                // The candidate ends inside the inner frame, so whatever
                // confirms it is the inner frame's own bytes: the inner frame
                // wins if what follows it confirms it.
                match self.confirmed(c, inner_end, at_end) {
                    Ok(true) => return Verdict::Superseded(n),
                    Ok(false) => {}
                    Err(need) => return self.wait_or_accept(n, need),
                }
            }
            return match self.confirmed(c, n, at_end) {
                Ok(true) => Verdict::Frame(n),
                Ok(false) => Verdict::Superseded(n),
                Err(need) => self.wait_or_accept(n, need),
            };
        }
        Verdict::Frame(n)
    }

    /// Is the frame `c[..end]` followed by a plausible header or the end of
    /// input? `Err(n)`: cannot tell before `c` has `n` bytes.
    fn confirmed(&self, c: &[u8], end: usize, at_end: bool) -> Result<bool, usize> {
        // `end <= c.len()` where this is called; an empty rest otherwise.
        let after = c.get(end..).unwrap_or(&[]);
        let header_len = F::HEADER_LEN.max(1);
        if after.len() < header_len {
            // At the end of input only the end itself confirms: a header cut
            // short by it is no frame.
            return if at_end {
                Ok(after.is_empty())
            } else {
                Err(end + header_len)
            };
        }
        let header = &after[..header_len];
        Ok(self.framing.find_start(header) == 0
            && !matches!(self.framing.check(header, false), Check::Reject(_)))
    }

    /// Wait for `need` bytes if the buffer can hold them; otherwise accept the
    /// frame of `n` bytes unverified rather than stall.
    fn wait_or_accept(&self, n: usize, need: usize) -> Verdict<F::Error> {
        if need <= N {
            Verdict::Need(need)
        } else {
            Verdict::Frame(n)
        }
    }

    /// Turn a step into the event it stands for. This is the one place a
    /// frame is parsed: the in-place and buffered paths meet here on a small
    /// value (an offset and a slice), so the message is built once, straight
    /// into the returned event, instead of on each path and then copied where
    /// they join.
    #[inline(always)]
    fn emit<'a>(
        &'a mut self,
        step: Step<'a, F::Error>,
    ) -> Option<Event<'a, F::Message<'a>, F::Error>> {
        let (offset, raw) = match step {
            Step::Done => return None,
            Step::Rejected(rejected) => return Some(Err(rejected)),
            Step::InPlace { offset, raw } => (offset, raw),
            Step::Buffered(n) => (self.emit_buffered(n), prefix(&self.buf, n)),
        };
        Some(parse_counted(&self.framing, &mut self.stats, offset, raw))
    }

    /// The frame of `n` bytes at the front of the buffer is handed over:
    /// returns its offset. The event borrows the bytes until the next call.
    #[inline(always)]
    fn emit_buffered(&mut self, n: usize) -> u64 {
        let offset = self.buf_offset.to_u64();
        self.need = 0;
        self.synced = true;
        if n >= self.len {
            // The frame is all the buffer holds: the buffer is empty from now
            // on (nothing overwrites the bytes before the next call).
            self.len = 0;
            self.buf_offset = self.buf_offset.plus(n);
        } else {
            // Later bytes stay: the frame is dropped on the next call.
            self.pending_drop = n;
        }
        offset
    }

    /// No candidate is buffered: find the next one in `input` and resolve it
    /// in place if it lies wholly inside.
    #[inline(always)]
    fn step_in_place<'i>(&mut self, input: &mut &'i [u8]) -> Step<'i, F::Error> {
        let data: &'i [u8] = input;
        let pos = self.framing.find_start(data);
        self.stats.skipped = self.stats.skipped.plus(pos);
        if pos > 0 {
            self.synced = false;
        }
        if pos >= data.len() {
            self.stats.bytes = self.stats.bytes.plus(data.len());
            *input = &[];
            return Step::Done;
        }
        let offset = self.stats.bytes.plus(pos);
        let candidate = data.get(pos..).unwrap_or(&[]);
        let error = match self.resolve(candidate, false) {
            // (`n <= candidate.len()` for a frame: `split_at_checked` only
            // keeps a panic path out of the binary.)
            Verdict::Frame(n) => match candidate.split_at_checked(n) {
                Some((raw, rest)) => {
                    self.stats.bytes = self.stats.bytes.plus(pos + n);
                    *input = rest;
                    self.synced = true;
                    return Step::InPlace {
                        offset: offset.to_u64(),
                        raw,
                    };
                }
                None => self.reject_kind(self.framing.truncated(candidate.len())),
            },
            Verdict::Need(n) if candidate.len() < N => {
                self.keep_tail(candidate, n, offset);
                self.stats.bytes = self.stats.bytes.plus(data.len());
                *input = &[];
                return Step::Done;
            }
            // The framing asks for more than the buffer holds: a framing bug,
            // but never a reason to stall.
            Verdict::Need(_) => self.reject_kind(self.framing.truncated(candidate.len())),
            Verdict::Reject(error) => self.reject_kind(error),
            Verdict::Superseded(n) => self.supersede_kind(n),
        };
        self.synced = false;
        self.stats.skipped = self.stats.skipped.plus(1);
        self.stats.bytes = self.stats.bytes.plus(pos + 1);
        *input = data.get(pos + 1..).unwrap_or(&[]);
        Step::Rejected(Rejected {
            offset: offset.to_u64(),
            error,
        })
    }

    /// Keep `candidate`, the rest of the input (shorter than the buffer), as
    /// the buffered start of a frame that cannot resolve before `need` bytes.
    /// Only a frame that straddles the end of the input is copied.
    #[inline(always)]
    fn keep_tail(&mut self, candidate: &[u8], need: usize, offset: C) {
        if let Some(front) = self.buf.get_mut(..candidate.len()) {
            front.copy_from_slice(candidate);
        }
        self.len = candidate.len();
        self.need = need.min(N);
        self.buf_offset = offset;
    }

    /// A candidate is buffered and no input is offered (`push`, `poll`):
    /// resolve the stored bytes. This is [`step_buffered`](Self::step_buffered)
    /// with an empty input, without its input handling.
    fn step_stored<'i>(&mut self) -> Step<'i, F::Error> {
        let mut stored = self.len;
        // A start that could not be confirmed (a sync word cut in two) may
        // turn out to be none now: drop it silently, as `step_buffered` does.
        let skip = self.framing.find_start(self.stored(stored));
        if skip > 0 {
            self.shift_out(skip, stored);
            self.buf_offset = self.buf_offset.plus(skip);
            self.stats.skipped = self.stats.skipped.plus(skip);
            self.synced = false;
            self.need = 0;
            stored -= skip.min(stored);
            self.len = stored;
            if stored == 0 {
                return Step::Done;
            }
        }
        if stored < self.need {
            return Step::Done;
        }
        let error = match self.resolve(self.stored(stored), false) {
            Verdict::Frame(n) => return Step::Buffered(n),
            Verdict::Need(n) if stored < N => {
                self.need = n.min(N);
                return Step::Done;
            }
            Verdict::Need(_) => self.reject_kind(self.framing.truncated(stored)),
            Verdict::Reject(error) => self.reject_kind(error),
            Verdict::Superseded(n) => self.supersede_kind(n),
        };
        self.reject_buffered(error)
    }

    /// A candidate is buffered: add input bytes to it until it resolves.
    ///
    /// On 64-bit hosts it stays out of line, with its own copy of the
    /// in-place step for when the buffer turns out to hold no candidate: a
    /// frame straddles chunks at most once per chunk, and inlined into the
    /// caller's loop this path costs the in-place path registers and copies
    /// of the message (measured: 15 % more instructions and 25 % more time
    /// per 53-byte frame decoded in place). On
    /// microcontrollers the compiler decides, which keeps one copy of the
    /// in-place step (1.2 KB less flash in the size report's decode row).
    #[cfg_attr(target_pointer_width = "64", inline(never))]
    fn step_buffered<'i>(&mut self, input: &mut &'i [u8]) -> Step<'i, F::Error> {
        if self.len == 0 {
            return self.step_in_place(input);
        }
        let data: &'i [u8] = input;
        let mut stored = self.len;
        let take = data.len().min(N - stored);
        // Append input tentatively: bytes the candidate does not use are given
        // back to the caller.
        if let Some(tail) = self.buf.get_mut(stored..stored + take) {
            tail.copy_from_slice(&data[..take]);
        }
        let total = stored + take;
        // A start that could not be confirmed at the end of the last chunk (a
        // sync word cut in two) may turn out to be none: drop it silently, as
        // `find_start` would have if the bytes had come in one chunk.
        let skip = self.framing.find_start(self.stored(total)).min(stored);
        if skip > 0 {
            self.shift_out(skip, total);
            self.buf_offset = self.buf_offset.plus(skip);
            self.stats.skipped = self.stats.skipped.plus(skip);
            self.synced = false;
            self.need = 0;
            stored -= skip;
            self.len = stored;
            if stored == 0 {
                return self.step_in_place(input);
            }
        }
        let total = stored + take;
        if total < self.need {
            // Cannot resolve yet: keep everything without asking the framing.
            self.len = total;
            self.stats.bytes = self.stats.bytes.plus(take);
            *input = &data[take..];
            return Step::Done;
        }
        match self.resolve(self.stored(total), false) {
            Verdict::Frame(n) => {
                let used = n.saturating_sub(stored).min(take);
                self.stats.bytes = self.stats.bytes.plus(used);
                *input = &data[used..];
                // Stored bytes past the frame stay buffered (possible only
                // after a rejection shifted the buffer).
                self.len = n.max(stored);
                Step::Buffered(n)
            }
            Verdict::Need(n) if total < N => {
                self.stats.bytes = self.stats.bytes.plus(take);
                *input = &data[take..];
                self.len = total;
                self.need = n.min(N);
                Step::Done
            }
            Verdict::Need(_) => {
                let error = self.reject_kind(self.framing.truncated(total));
                self.reject_buffered(error)
            }
            Verdict::Reject(error) => {
                let error = self.reject_kind(error);
                self.reject_buffered(error)
            }
            Verdict::Superseded(n) => {
                let error = self.supersede_kind(n);
                self.reject_buffered(error)
            }
        }
    }

    /// Reject the buffered candidate: drop its first byte only and realign on
    /// the next candidate start among the stored bytes.
    fn reject_buffered<'i>(&mut self, error: F::Error) -> Step<'i, F::Error> {
        let offset = self.buf_offset.to_u64();
        self.need = 0;
        self.synced = false;
        self.stats.skipped = self.stats.skipped.plus(1);
        self.shift_out(1, self.len);
        self.len = self.len.saturating_sub(1);
        self.buf_offset = self.buf_offset.plus(1);
        self.realign_buffer();
        Step::Rejected(Rejected { offset, error })
    }

    /// Count a rejection by its kind and hand the error back.
    fn reject_kind(&mut self, error: F::Error) -> F::Error {
        if self.framing.is_checksum_error(&error) {
            self.stats.checksum_failures = self.stats.checksum_failures.plus(1);
        } else {
            self.stats.other_rejections = self.stats.other_rejections.plus(1);
        }
        error
    }

    /// Count a superseded candidate of `n` bytes and make its error.
    fn supersede_kind(&mut self, n: usize) -> F::Error {
        self.stats.superseded = self.stats.superseded.plus(1);
        self.stats.other_rejections = self.stats.other_rejections.plus(1);
        self.framing.superseded(n)
    }
}

/// The first `len` bytes of `bytes`, or all of them.
#[inline(always)]
fn prefix_of(bytes: &[u8], len: usize) -> &[u8] {
    bytes.get(..len).unwrap_or(bytes)
}

/// The first `len` bytes of `buf`, or all of it (`len <= N` always holds
/// where this is called; the fallback keeps panic paths out of the binary).
#[inline(always)]
fn prefix<const N: usize>(buf: &[u8; N], len: usize) -> &[u8] {
    buf.get(..len).unwrap_or(buf)
}

/// Copy `src` into `buf` at `at`, if it fits. Up to 8 bytes (the rest of a
/// frame a chunk cut) are moved with two overlapping loads and stores, or
/// three single bytes, without a call to `memcpy`: measured, 3 % off
/// Telemetrix `decode/reports_chunk64` against `copy_from_slice` there.
#[inline(always)]
fn copy_into<const N: usize>(buf: &mut [u8; N], at: usize, src: &[u8]) {
    let Some(dst) = buf.get_mut(at..).and_then(|b| b.get_mut(..src.len())) else {
        return;
    };
    let len = src.len();
    if len > 8 {
        dst.copy_from_slice(src);
    } else if len >= 4 {
        let (head, tail) = (&src[..4], &src[len - 4..]);
        dst[..4].copy_from_slice(head);
        dst[len - 4..].copy_from_slice(tail);
    } else if len > 0 {
        // First, middle and last: every byte of 1 to 3.
        dst[0] = src[0];
        dst[len / 2] = src[len / 2];
        dst[len - 1] = src[len - 1];
    }
}

/// Count and parse a frame: the framing's shortcut first, then the full parse.
#[inline(always)]
fn parse_counted<'a, F: FrameRules, C: Counter>(
    framing: &F,
    stats: &mut Stats<C>,
    offset: u64,
    raw: &'a [u8],
) -> Event<'a, F::Message<'a>, F::Error> {
    count_frame(stats, raw);
    let parsed = match framing.parse_common(raw) {
        Some(message) => Ok(message),
        None => framing.parse(raw),
    };
    frame_event(stats, offset, raw, parsed)
}

/// Count and parse a frame, handing its event to `on_event` from the place
/// it is built: the framing's shortcut first, then the full parse (two call
/// sites, so the two messages never meet in one place to be copied from).
#[inline(always)]
fn deliver<F: FrameRules, C: Counter>(
    framing: &F,
    stats: &mut Stats<C>,
    offset: u64,
    raw: &[u8],
    on_event: &mut impl FnMut(Event<'_, F::Message<'_>, F::Error>),
) {
    count_frame(stats, raw);
    match framing.parse_common(raw) {
        Some(message) => on_event(Ok(Frame {
            offset,
            raw,
            message,
        })),
        None => on_event(frame_event(stats, offset, raw, framing.parse(raw))),
    }
}

/// Count a frame and its bytes.
#[inline(always)]
fn count_frame<C: Counter>(stats: &mut Stats<C>, raw: &[u8]) {
    stats.frames = stats.frames.plus(1);
    stats.frame_bytes = stats.frame_bytes.plus(raw.len());
}

/// The event of a counted frame's parse (a failed parse counts as malformed).
#[inline(always)]
fn frame_event<'a, M, E, C: Counter>(
    stats: &mut Stats<C>,
    offset: u64,
    raw: &'a [u8],
    parsed: Result<M, E>,
) -> Event<'a, M, E> {
    match parsed {
        Ok(message) => Ok(Frame {
            offset,
            raw,
            message,
        }),
        Err(error) => {
            stats.malformed = stats.malformed.plus(1);
            Err(Rejected { offset, error })
        }
    }
}

/// Turn a borrowed event into its owned form (what [`Feed`] and [`Flush`] yield).
pub fn owned_event<F: FrameRules>(event: Event<'_, F::Message<'_>, F::Error>) -> OwnedEvent<F> {
    event.map(|frame| OwnedFrame {
        offset: frame.offset,
        len: frame.raw.len(),
        message: F::to_owned_from(frame.raw, frame.message),
    })
}

/// The owned event type of framing `F`, as [`Feed`] and [`Flush`] yield it.
pub type OwnedEvent<F> =
    Result<OwnedFrame<<F as FrameRules>::Owned>, Rejected<<F as FrameRules>::Error>>;

/// Iterator over the events in one chunk; see [`StreamDecoder::feed`].
#[derive(Debug)]
pub struct Feed<'d, 'i, F, const N: usize, C = u64> {
    decoder: &'d mut StreamDecoder<F, N, C>,
    input: &'i [u8],
}

impl<F, const N: usize, C> Feed<'_, '_, F, N, C> {
    /// The bytes of the chunk not taken yet.
    pub const fn remaining(&self) -> &[u8] {
        self.input
    }
}

impl<F: FrameRules, const N: usize, C: Counter> Iterator for Feed<'_, '_, F, N, C> {
    type Item = OwnedEvent<F>;

    fn next(&mut self) -> Option<Self::Item> {
        self.decoder.decode(&mut self.input).map(owned_event::<F>)
    }
}

/// Iterator over the events at the end of input; see [`StreamDecoder::flush`].
#[derive(Debug)]
pub struct Flush<'d, F, const N: usize, C = u64> {
    decoder: &'d mut StreamDecoder<F, N, C>,
}

impl<F: FrameRules, const N: usize, C: Counter> Iterator for Flush<'_, F, N, C> {
    type Item = OwnedEvent<F>;

    fn next(&mut self) -> Option<Self::Item> {
        self.decoder.finish().map(owned_event::<F>)
    }
}

/// The engine's decision for a candidate: the framing's, refined by the resync
/// verification.
/// What one step of decoding found, before any frame is parsed.
enum Step<'a, E> {
    /// Every byte offered was taken; nothing to report yet.
    Done,
    /// A candidate was rejected.
    Rejected(Rejected<E>),
    /// A frame wholly inside the caller's input.
    InPlace { offset: u64, raw: &'a [u8] },
    /// A frame of this many bytes at the front of the internal buffer.
    Buffered(usize),
}

/// What the clean stream's path found (see `StreamDecoder::clean_step`).
enum Clean<'a> {
    /// A frame wholly inside the input, taken.
    Frame { offset: u64, raw: &'a [u8] },
    /// The input ends inside a frame, now buffered.
    Kept,
    /// Neither: the general step decides.
    General,
}

/// Buffers up to this size are moved whole (see `shift_out`).
const SMALL_BUFFER: usize = 32;

enum Verdict<E> {
    Need(usize),
    Frame(usize),
    Reject(E),
    Superseded(usize),
}
