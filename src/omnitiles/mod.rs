//! OmniTiles: the binary protocol between a host and an OmniTiles tile.
//!
//! Every frame is `[0xA5][id][payload][sum]`, where `sum` is the wrapping 8-bit
//! sum of the id and payload bytes. There is no length byte: a command's
//! length follows from its id, and telemetry (id `0x60`, tile → host) is told
//! apart only by its total length — 7, 15, 17 or 53 bytes as the SDK documents,
//! or the firmware's 45-byte SPI frame ([`Layout`]). Wire facts follow the
//! project's specification of the protocol (Clue88/OmniTiles at `094ed61`).
//!
//! | | host (decodes telemetry) | device (decodes commands) | both (captures) |
//! |---|---|---|---|
//! | framing | [`Framing<Host>`] | [`Framing<Device>`] | [`Framing<Both>`] |
//! | stream decoder | [`HostDecoder`], [`host_decoder()`] | [`DeviceDecoder`], [`device_decoder()`] | [`BothDecoder`], [`both_decoder()`] |
//! | buffer | [`HOST_BUFFER`] | [`DEVICE_BUFFER`] | [`BOTH_BUFFER`] |
//! | message | [`Telemetry`] | [`Command`] | [`Message`] |
//! | datagrams | [`HostDatagramDecoder`] | [`DeviceDatagramDecoder`] | [`BothDatagramDecoder`] |
//!
//! * [`Command`], [`Telemetry`] and [`Message`] (either) are the typed
//!   messages; they own everything. Each implements [`Encode`] (longest frame
//!   [`MAX_FRAME_LEN`]), `TryFrom<&[u8]>` for one whole frame, and `Display`.
//! * The stream decoders decode a byte stream incrementally (see
//!   [`StreamDecoder`]); [`Framing`] says what they accept.
//! * [`DatagramDecoder`] decodes runs of bytes whose boundaries are known (BLE
//!   notifications and writes, SPI buffers).
//! * [`FirmwareParser`] parses commands as the tile's firmware does, to tell
//!   what a tile executed (see [below](#what-a-tile-executed)).
//! * [`Layout`], [`Layouts`] and [`Motor`] have names (`FromStr`, `Display`):
//!   `ble53`, `auto,spi45`, `m1`.
//! * [`units`] converts bytes to duty, millimetres and back.
//! * With the `serde` feature every message and [`Error`] is written and read
//!   as the `robowire` command-line tool's JSON lines:
//!   `{"type":"m1_extend","speed":200}`.
//!
//! ```
//! use robowire::omnitiles::{device_decoder, Command, Motor};
//!
//! let mut decoder = device_decoder();
//! let mut commands = Vec::new();
//! // Garbage, a false start (a5 a5), and a frame split across two chunks.
//! for chunk in [&[0x00, 0xa5, 0xa5, 0x30][..], &[0xc8, 0xf8, 0xa5, 0x50, 0x50]] {
//!     for event in decoder.feed(chunk) {
//!         match event {
//!             Ok(frame) => commands.push(frame.message),
//!             Err(rejected) => eprintln!("skipped: {rejected}"),
//!         }
//!     }
//! }
//! decoder.flush().for_each(drop);
//! assert_eq!(commands, [Command::Extend { motor: Motor::M1, speed: 200 }, Command::Ping]);
//! assert_eq!(decoder.stats().frames, 2);
//! ```
//!
//! A host names the layouts its tile sends:
//!
//! ```
//! use robowire::omnitiles::{Framing, HostDecoder, Layout, Layouts};
//!
//! let mut decoder = HostDecoder::new(Framing::new().with_layouts(Layouts::only(Layout::Pos7)));
//! let mut input: &[u8] = &[0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
//! let frame = decoder.decode(&mut input).unwrap().unwrap();
//! assert_eq!(frame.message.m1_pos, Some(2000));
//! ```
//!
//! # What the decoders accept
//!
//! [`Framing<Device>`] accepts commands (a tile's view of the link),
//! [`Framing<Host>`] telemetry in a set of layouts (a host's view) and
//! [`Framing<Both>`] both. The telemetry layouts are
//! [`Layouts::DOCUMENTED`] (7, 15, 17 and 53 bytes) unless
//! [`with_layouts`](Framing::with_layouts) names others: any subset, such as
//! [`Layouts::ALL`] or [`Layouts::only`]`(Layout::Ble53)`. A device framing
//! has no layouts, and its decoder contains no telemetry code.
//!
//! # Telemetry length policy
//!
//! With several layouts enabled a candidate can validate at more than one
//! length (there is no length byte and the sum is 8 bits). The decoder is
//! deterministic:
//!
//! 1. It tries the enabled lengths **shortest first**.
//! 2. Length `L` is accepted at once when its sum validates **and** it is
//!    confirmed: `L` is the longest enabled layout; or the two bytes after
//!    it are another accepted frame's header (`a5 60`, or `a5` and a command
//!    id when commands are accepted); or `L` is 45 (`spi45`) and the two
//!    bytes after it are `00 00`, the zero padding of an SPI buffer; or the
//!    input ends exactly at `L` (or at `L + 1` with a lone `a5`), which only
//!    [`finish`](crate::StreamDecoder::finish) and
//!    [`flush`](crate::StreamDecoder::flush) can say.
//! 3. Otherwise it moves on to the next length. Once every enabled length
//!    has been tried (the longest enabled length is available) or the input
//!    has ended, a candidate at which **exactly one** enabled length
//!    validated is a frame of that length, confirmed or not.
//! 4. When two or more lengths validated and none is confirmed, the
//!    candidate is rejected ([`Error::Unconfirmed`]); when none validated,
//!    with the longest layout's [`Error::Checksum`] (or [`Error::Truncated`]
//!    at the end of input). The decoder then resyncs by one byte.
//!
//! Consequences: a frame of the longest enabled layout is emitted as soon as
//! it is complete; a shorter one as soon as the next frame's first two bytes
//! confirm it, or else once the longest enabled length is available (a short
//! frame followed by garbage is kept when its length is the only one that
//! validates there, which is the common case); with a single layout enabled
//! every frame is emitted as soon as it is complete and nothing needs
//! confirming. Zero-padded SPI buffers decode exactly with any layout set
//! that includes `spi45`. On a clean stream of any mix of the enabled
//! layouts, at any chunking, there are no false and no lost frames, with
//! one exception the wire format cannot rule out: a longer frame whose own
//! bytes validate as a shorter layout followed by an `a5 60` header is taken
//! as the shorter frame. For instance a 53-byte frame whose bytes 1..=5 sum
//! to byte 6 and whose bytes 7 and 8 are `a5 60` (m1 = m2 = 0 and UWB d0 =
//! `0xA560`, d1 = `0x0060`) is taken as a 7-byte frame, and likewise at 15
//! and 17 bytes; for random contents that is about one frame in 2^24, pinned
//! by a test. On a noisy stream a frame that is followed by garbage and
//! validates at two lengths is dropped ([`Error::Unconfirmed`]), and a
//! corrupted frame whose first bytes happen to validate at a shorter length
//! is taken as that shorter, false frame (about one corrupted frame in a
//! hundred; the measured figures are in `docs/robustness.md`). Name a single
//! layout when you know it: then neither can happen.
//!
//! # What a tile executed
//!
//! The stream decoders are robust: after a rejected candidate they rescan its
//! bytes, so they find every frame a peer sent. A tile's own command parser
//! does not, and executes fewer commands on a noisy link. [`FirmwareParser`]
//! reproduces that parser byte for byte (no rescan, payload bytes taken
//! blindly, an `a5` in the id slot consumed as an unknown id), so a capture
//! of the host's bytes tells what the tile did; `robowire decode omnitiles
//! --from host --as-firmware` uses it. It is opt-in: robust decoding stays
//! the default.
//!
//! # Datagrams
//!
//! [`DatagramDecoder`] decodes byte runs whose boundaries are known (a BLE
//! notification, a 128-byte SPI buffer, a BLE write). A datagram that starts
//! `a5 60` is one telemetry frame of the enabled layout with exactly its
//! length, or else of the shortest enabled layout whose checksum validates
//! with only zero padding after it (an SPI buffer). Anything else — the nRF's
//! brake buffer `a5 32 32 a5 42 42` + 122 × `00`, several commands in one
//! write — goes through the stream decoder finished at the datagram's end, so
//! every command comes out and nothing leaks into the next datagram.

mod command;
mod datagram;
mod error;
mod field_info;
mod firmware;
mod framing;
mod layout;
mod message;
#[cfg(feature = "serde")]
mod schema;
mod telemetry;
pub mod units;
mod view;
mod whole;
mod wire;

pub use command::{Command, Motor};
pub use datagram::{
    padded_spi_frames, BothDatagramDecoder, Datagram, DatagramDecoder, DeviceDatagramDecoder,
    HostDatagramDecoder,
};
pub use error::{Error, UnknownName};
pub use field_info::FIELD_INFO;
pub use firmware::{FirmwareEvent, FirmwareFeed, FirmwareParser};
pub use framing::{Both, Device, Framing, Host, Side, TelemetrySide};
pub use layout::{Layout, Layouts};
pub use message::Message;
pub use telemetry::{Imu, Telemetry, NO_READING};
pub use view::{TelemetryView, TelemetryViews};
pub use wire::{checksum, id, payload_len, MAX_FRAME_LEN, START};

#[cfg(doc)]
use crate::encode::Encode;
use crate::stream::StreamDecoder;

/// Buffer size of a [`HostDecoder`]: room for the longest frame, a frame
/// starting inside it and the next header after that (the engine's resync
/// verification).
pub const HOST_BUFFER: usize = 128;
/// Buffer size of a [`DeviceDecoder`]: sized from the framing. A command
/// candidate is at most 6 bytes, so 14 hold a candidate, a command starting
/// inside it and the header after that, all the engine's resync verification
/// reads (128 before 0.2).
pub const DEVICE_BUFFER: usize =
    2 * wire::MAX_COMMAND_LEN + <Framing<Device> as crate::stream::FrameRules>::HEADER_LEN;
/// Buffer size of a [`BothDecoder`].
pub const BOTH_BUFFER: usize = 128;

/// Decodes telemetry (the host's side).
pub type HostDecoder = StreamDecoder<Framing<Host>, HOST_BUFFER>;
/// Decodes commands (the tile's side, or a simulated tile).
pub type DeviceDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER>;
/// Decodes both directions (captures, tooling).
pub type BothDecoder = StreamDecoder<Framing<Both>, BOTH_BUFFER>;

/// A host decoder accepting telemetry in the four documented layouts.
pub const fn host_decoder() -> HostDecoder {
    StreamDecoder::new(Framing::new())
}

/// Decodes telemetry as [`TelemetryView`]s, read in place (the host's side,
/// where frames come faster than a struct per frame is worth building).
pub type HostViewDecoder = StreamDecoder<TelemetryViews, HOST_BUFFER>;

/// A host decoder yielding [`TelemetryView`]s of the four documented layouts.
pub const fn host_view_decoder() -> HostViewDecoder {
    StreamDecoder::new(TelemetryViews::new())
}

/// A device decoder: commands.
pub const fn device_decoder() -> DeviceDecoder {
    StreamDecoder::new(Framing::new())
}

/// A decoder of both directions: commands and telemetry in the four
/// documented layouts.
pub const fn both_decoder() -> BothDecoder {
    StreamDecoder::new(Framing::new())
}
