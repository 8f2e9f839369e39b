//! `no_std`, allocation-free, sans-IO codecs for three small robot serial
//! protocols: **OmniTiles**, **Pixy2** and **Telemetrix4RpiPico**.
//!
//! robowire does no I/O of its own: you hand it bytes, it hands you typed
//! messages (and says exactly how many bytes it took); you hand it a message,
//! it writes a frame into your buffer. It runs in Cortex-M firmware with no heap,
//! in tokio hosts and in capture tools; the `robowire` command-line tool
//! (feature `cli`) decodes captures to JSON lines and encodes them back. The
//! three protocols share one streaming engine ([`stream`]): resync by one byte
//! after any failed candidate, zero-copy parsing of frames inside the caller's
//! chunk, the same result however the input is split, and rejected candidates
//! reported as events, never as the end of a stream. The library never
//! allocates and has no `unsafe` code.
//!
//! # Modules
//!
//! | module | what |
//! |---|---|
//! | [`omnitiles`] | OmniTiles: `0xA5`, id, payload, 8-bit sum; commands to a tile, telemetry of five layouts back |
//! | [`pixy2`] | Pixy2 serial packets (SPI, I2C, UART): requests and responses, with and without checksum |
//! | [`telemetrix`] | Telemetrix4RpiPico: `LEN`, id, payload, no checksum; three firmware dialects |
//! | [`stream`] | the engine: [`StreamDecoder`], the [`FrameRules`] trait a protocol implements, [`Frame`], [`OwnedFrame`], [`Rejected`], [`Stats`]; notes for writing a new protocol |
//! | [`side`] | the side markers [`Host`](side::Host), [`Device`](side::Device), [`Both`](side::Both) |
//! | [`encode`] | [`Encode`], [`EncodeError`], [`FrameBuf`]: one encoding interface for every message |
//! | [`io`] | optional adapters: tokio-util codec, `embedded-io` and `embedded-io-async` reader and writer |
//!
//! Each protocol module documents its wire format and its decoding policy: what
//! is rejected where, and what the wire format cannot detect.
//!
//! # One vocabulary
//!
//! The three protocol modules use the same names for the same things; only the
//! message enums keep each protocol's own words. A *host* decoder decodes what
//! the device sends, a *device* decoder what the host sends, a *both* decoder
//! either (captures).
//!
//! | concept | `omnitiles` | `pixy2` | `telemetrix` |
//! |---|---|---|---|
//! | message host → device | `Command` | `Request` | `Command<'a>` |
//! | message device → host | `Telemetry` (read in place: `TelemetryView<'a>`, from a `HostViewDecoder`) | `Response<'a>` | `Report<'a>` |
//! | either direction | `Message` | `Message<'a>` | `Message<'a>` |
//! | owned form (what `feed` yields) | the messages themselves | `Request`, `ResponseBuf`, `MessageBuf` | `CommandBuf`, `ReportBuf`, `MessageBuf` |
//! | frame form wrapper | — | `Envelope<M> { form, body }` | — |
//! | framing value ([`FrameRules`]) | `Framing<S>` | `Framing<S>` | `Framing<S>` |
//! | its side `S` | `Host`, `Device`, `Both` | `Host`, `Device`, `Both` | `Host`, `Device`, `Both` |
//! | its options (`const fn`, builder style) | `with_layouts` | `checksum_only` | `with_dialect`, `lenient` |
//! | decoders | `HostDecoder`, `DeviceDecoder`, `BothDecoder` | the same | the same |
//! | `const fn` constructors (default framing) | `host_decoder()`, `device_decoder()`, `both_decoder()` | the same | the same |
//! | decoder buffer sizes | `HOST_BUFFER`, `DEVICE_BUFFER`, `BOTH_BUFFER` | the same | the same |
//! | longest frame | `MAX_FRAME_LEN`; per message type [`Encode::MAX_LEN`] | the same | the same |
//! | parse one whole frame | `TryFrom<&[u8]>` on each message type | the same | the same (mirte 1.3; `parse_in` for other dialects) |
//! | error | `Error` | `Error` (and `DeviceError`, `PairError`) | `Error` |
//! | names (`Display`, `FromStr`) | every message; `Layout`, `Layouts`, `Motor` | every message; `Form` | every message; `Dialect`, pin modes |
//!
//! Shared by all: [`StreamDecoder`] (every decoder is one), [`OwnedFrame`] and
//! [`Rejected`] (its events), [`Stats`], [`Encode`] and [`FrameBuf`]. Nothing in
//! robowire is called `Decoder`, `Encoder` or `Framed`, so its names import
//! next to `tokio_util::codec`'s without a clash.
//!
//! # Example
//!
//! ```
//! use robowire::omnitiles::{self, Command, Motor};
//! use robowire::Encode;
//!
//! // A host encodes a command...
//! let mut out = [0u8; omnitiles::MAX_FRAME_LEN];
//! let n = Command::Extend { motor: Motor::M1, speed: 200 }.encode(&mut out).unwrap();
//!
//! // ...and a tile decodes it, in two reads: line noise, then the frame.
//! let mut tile = omnitiles::device_decoder();
//! for mut read in [&[0x00, 0xa5][..], &out[..n]] {
//!     while let Some(event) = tile.decode(&mut read) {
//!         match event {
//!             Ok(frame) => assert_eq!(frame.message, Command::Extend { motor: Motor::M1, speed: 200 }),
//!             Err(rejected) => println!("skipped: {rejected}"), // the false start `a5 a5`
//!         }
//!     }
//! }
//! assert_eq!(tile.stats().frames, 1);
//! ```
//!
//! # Features
//!
//! All off by default, all additive.
//!
//! | feature | adds | `no_std` |
//! |---|---|---|
//! | `bytes` | [`Encode::encode_buf`] into any `bytes::BufMut` | yes |
//! | `tokio-util-07` | `io::tokio`: a `tokio_util::codec` decoder and encoder for every protocol and side | no (std) |
//! | `embedded-io-07` | `io::embedded_io`: blocking `PacketReader` and `PacketWriter` | yes |
//! | `embedded-io-async-07` | `io::embedded_io_async`: the same with `async` methods | yes |
//! | `serde` | `Serialize`/`Deserialize` for every message, error and frame, in the CLI's JSON-lines schema (turns on `serde/alloc`; the codecs still never allocate) | yes |
//! | `defmt` | `defmt::Format` for every public type, for logging from firmware | yes |
//! | `cli` | the `robowire` command-line tool (turns on `serde`) | no (std) |
//! | `cli-plot` | `robowire plot`: PNG and SVG plots (turns on `cli`) | no (std) |
//! | `cli-foxglove` | `decode --port --foxglove`: live in Foxglove, commands back (turns on `cli`; Rust 1.88) | no (std) |
//!
//! The library needs Rust 1.81; the `cli` tool needs 1.85.
//!
//! # More documentation
//!
//! In the repository's `docs/` folder: protocol guides (`omnitiles.md`,
//! `pixy2.md`, `telemetrix.md`), `embedded.md` (firmware: `push`/`poll` in an
//! interrupt handler, buffer sizes, code size), `integrations.md` (tokio,
//! embedded-io, serde, defmt), `cli.md` (the command-line tool's manual),
//! `performance.md` and `robustness.md` (measured results). `README.md` is the
//! front page; `CHANGELOG.md` lists every rename with its old name.

#![no_std]
#![cfg_attr(docsrs, feature(doc_cfg))]
#![deny(missing_docs)]
#![forbid(unsafe_code)]

#[cfg(feature = "serde")]
extern crate alloc;
#[cfg(feature = "tokio-util-07")]
extern crate std;

pub mod encode;
pub mod idle;
pub mod io;
pub mod omnitiles;
pub mod pixy2;
#[cfg(feature = "serde")]
mod serde_support;
pub mod side;
pub mod stream;
pub mod telemetrix;
pub mod units;

pub use encode::{Encode, EncodeError, FrameBuf};
pub use idle::Idle;
pub use stream::{
    Check, Counter, Event, Feed, Flush, Frame, FrameRules, OwnedEvent, OwnedFrame, Rejected, Stats,
    StreamDecoder,
};

// The front page and the guides in docs/ are compiled as doctests, each under
// the features its examples need, so plain `cargo test` passes too.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

#[cfg(doctest)]
#[doc = include_str!("../docs/omnitiles.md")]
struct OmniTilesGuideDoctests;

#[cfg(doctest)]
#[doc = include_str!("../docs/pixy2.md")]
struct Pixy2GuideDoctests;

#[cfg(doctest)]
#[doc = include_str!("../docs/telemetrix.md")]
struct TelemetrixGuideDoctests;

#[cfg(all(doctest, feature = "embedded-io-07"))]
#[doc = include_str!("../docs/embedded.md")]
struct EmbeddedGuideDoctests;

#[cfg(all(doctest, feature = "tokio-util-07", feature = "serde"))]
#[doc = include_str!("../docs/integrations.md")]
struct IntegrationsGuideDoctests;
