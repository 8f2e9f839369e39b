//! Pixy2 serial packet protocol (SPI, I2C, UART; firmware 3.0.x), both sides
//! of the link.
//!
//! The wire specification is robowire's `protocols/pixy2.md`, written from the
//! Pixy2 porting guide and protocol reference (docs.pixycam.com) and the
//! device's observable behaviour.
//!
//! # Wire layout
//!
//! | form | bytes |
//! |---|---|
//! | no checksum | `ae c1` · type · len · payload\[len\] |
//! | checksum | `af c1` · type · len · sum u16 LE · payload\[len\] |
//!
//! The checksum is the wrapping 16-bit sum of the payload bytes. Integers are
//! little-endian. The host sends requests (even types); the device answers
//! each accepted request with exactly one response (odd types: RESULT 0x01,
//! ERROR 0x03, resolution 0x0d, version 0x0f, blocks 0x21, line features 0x31).
//! The official host sends requests without a checksum; the device always
//! answers with one. Decoders accept both forms in both directions.
//!
//! # Vocabulary
//!
//! | what | name |
//! |---|---|
//! | framing value ([`FrameRules`](crate::FrameRules)) | [`Framing<S>`](Framing), `S` one of [`Host`], [`Device`], [`Both`]; `Framing::new()`, `.checksum_only()` |
//! | decoders | [`HostDecoder`] (responses), [`DeviceDecoder`] (requests), [`BothDecoder`] (both, for captures) |
//! | decoder constructors | [`host_decoder()`], [`device_decoder()`], [`both_decoder()`] (`const fn`); otherwise `HostDecoder::new(Framing::new().checksum_only())` |
//! | buffer sizes | [`HOST_BUFFER`] (528), [`DEVICE_BUFFER`] (144), [`BOTH_BUFFER`] (528) |
//! | longest frame | [`MAX_FRAME_LEN`] (261); each message type's [`Encode::MAX_LEN`](crate::Encode::MAX_LEN) |
//! | host → device | [`Request`] (owns everything) |
//! | device → host | [`Response<'a>`](Response) (zero-copy), owned [`ResponseBuf`] |
//! | either direction | [`Message<'a>`](Message), owned [`MessageBuf`] |
//! | a message and its frame form | [`Envelope<M>`](Envelope) `{ form, body }`, what decoders yield |
//! | one whole frame | `TryFrom<&[u8]>` for every message type and its envelope ([`framing`]) |
//! | errors | [`Error`] (the bytes), [`DeviceError`] (an ERROR packet), [`PairError`] (a response that does not answer) |
//! | names | [`Display`](core::fmt::Display) for every message (`get_blocks sigmap=255 max_blocks=255`); [`Request::NAMES`], [`Response::NAMES`], [`Message::NAMES`]; [`FromStr`](core::str::FromStr) for [`Form`], [`DeviceError`], [`ProgName`] |
//!
//! Decoders:
//!
//! * [`HostDecoder`] accepts responses ([`Envelope`]`<`[`Response`]`>`),
//! * [`DeviceDecoder`] accepts requests ([`Envelope`]`<`[`Request`]`>`), with
//!   the device's 64-byte receive limit and a 144-byte buffer,
//! * [`BothDecoder`] accepts both ([`Envelope`]`<`[`Message`]`>`), for
//!   captures.
//!
//! [`framing`] describes what is rejected where (the decoding policy). A bare
//! [`Request`] encodes without a checksum, as the official host sends it; a
//! bare [`Response`] with one, as the device always answers;
//! `Envelope::new(Form::Checksum, request)` (or `Form::NoChecksum`) picks the
//! form. Decoders yield `Envelope { form, body }`, so every decoded frame
//! re-encodes to its exact bytes.
//!
//! The encoder refuses what the device would refuse: getBlocks with signature
//! map 0 ([`EncodeError::OutOfRange`](crate::EncodeError::OutOfRange); the
//! device answers ERROR −3), a changeProg name over 32 bytes or with a NUL
//! ([`ProgName::new`]), more than 18 blocks, a features payload over 255
//! bytes or an intersection with more than 6 lines. Values the device accepts
//! pass through unchanged, as the field docs say: servo positions above 1000
//! (ignored by the device, still RESULT 0), getRGB coordinates past 315 × 207
//! (clamped), unknown mode bits (ignored), any nonzero byte for lamps,
//! saturate and the getFeatures scope.
//!
//! # Limits
//!
//! Payload ≤ 255 bytes (frame ≤ 261), requests ≤ 64 bytes as the device
//! receives them, ≤ 18 blocks per response. Buffers: 528 bytes for host and
//! both-direction decoders, 144 for device decoders (twice the longest frame
//! and a header: room for the engine's resync verification). Line coordinates
//! are on the 79 × 52 grid, block coordinates in 316 × 208 pixels. Sizes of
//! the decoders on a 64-bit target (the buffer, then 104 bytes of counters
//! and indices, fewer on a 32-bit target): `size_of::<HostDecoder>()` and
//! `size_of::<BothDecoder>()` are 632 bytes, `size_of::<DeviceDecoder>()` 248.
//!
//! # JSON (`serde`)
//!
//! With the `serde` feature every message, [`Envelope`] and [`Error`]
//! serializes as the JSON lines of `robowire decode pixy2` (less `offset` and
//! `len`, which the stream adds) and deserializes from the lines
//! `robowire encode pixy2` reads, with the same checks and messages:
//!
//! ```
//! # #[cfg(feature = "serde")] {
//! use robowire::pixy2::{Envelope, Form, GetBlocks, MessageBuf, Request};
//!
//! let get = Envelope::new(Form::NoChecksum, Request::from(GetBlocks { sigmap: 255, max_blocks: 3 }));
//! let line = r#"{"type":"get_blocks","checksum":false,"sigmap":255,"max_blocks":3}"#;
//! assert_eq!(serde_json::to_string(&get).unwrap(), line);
//! let back = Envelope::new(Form::NoChecksum, MessageBuf::Request(get.body));
//! assert_eq!(serde_json::from_str(line).ok(), Some(back));
//! # }
//! ```
//!
//! # Example: a host asks for blocks
//!
//! ```
//! use robowire::pixy2::{self, GetBlocks, Query};
//! use robowire::Encode;
//!
//! let query = GetBlocks { sigmap: GetBlocks::ALL, max_blocks: 255 };
//! let mut out = [0u8; 8];
//! let n = query.request().encode(&mut out)?;
//! assert_eq!(&out[..n], &[0xae, 0xc1, 0x20, 0x02, 0xff, 0xff]);
//!
//! // The device's answer, after SPI idle filler: one block of signature 1.
//! let mut input: &[u8] = &[
//!     0x01, 0x01, 0xaf, 0xc1, 0x21, 0x0e, 0xb7, 0x01, 0x01, 0x00, 0x64, 0x00,
//!     0x32, 0x00, 0x14, 0x00, 0x0a, 0x00, 0x00, 0x00, 0x03, 0xff,
//! ];
//! let mut decoder = pixy2::host_decoder();
//! let frame = decoder.decode(&mut input).unwrap().unwrap();
//! let blocks = query.answer(frame.message.body).unwrap();
//! let block = blocks.iter().next().unwrap();
//! assert_eq!((block.signature, block.x, block.y, block.age), (1, 100, 50, 255));
//! # Ok::<(), robowire::EncodeError>(())
//! ```
//!
//! # Out of scope
//!
//! Pixy 1.0 compatibility mode (the old `0xaa55` streaming protocol on SPI)
//! and the LEGO firmware's I2C protocol (single-byte commands at address
//! 0x01) are not supported. libpixyusb2's USB transport is not covered, but
//! the frames it builds in host memory (`ae c1` responses) decode.

mod blocks;
mod envelope;
mod error;
mod features;
mod field_info;
pub mod framing;
mod pair;
mod quirk;
mod request;
mod response;
#[cfg(feature = "serde")]
mod serde_impls;
mod table;
mod wire;

pub use blocks::{Block, BlockIter, Blocks, BlocksBuf, MAX_BLOCKS};
pub use envelope::{Envelope, EvenIfRefused, Message, MessageBuf};
pub use error::{DeviceError, Error, Malformed, NameError};
pub use features::{
    Barcode, Element, Elements, FeatureIter, Features, FeaturesBuf, Intersection, IntersectionLine,
    Section, Sections, Vector, FTYPE_BARCODE, FTYPE_INTERSECTION, FTYPE_VECTOR, INTERSECTION_SLOTS,
};
pub use field_info::FIELD_INFO;
pub use framing::{Both, Device, Framing, Host, Side};

pub use pair::{PairError, ProgSwitch, Query};
pub use quirk::Quirk;
pub use request::{
    ChangeProg, GetBlocks, GetFeatures, GetFps, GetResolution, GetRgb, GetVersion, ProgName,
    Request, ReverseVector, SetCameraBrightness, SetDefaultTurn, SetLamp, SetLed, SetMode,
    SetNextTurn, SetServos, SetVector,
};
pub use response::{FirmwareType, Resolution, Response, ResponseBuf, Rgb, Version};
pub use wire::{
    checksum, packet_type, Form, DEVICE_MAX_PAYLOAD, MAX_FRAME_LEN, MAX_PAYLOAD, SYNC_CHECKSUM,
    SYNC_NO_CHECKSUM,
};

use crate::stream::StreamDecoder;

/// Buffer size of host decoders: twice the longest frame (261) and a header,
/// so the engine's resync verification has room.
pub const HOST_BUFFER: usize = 528;
/// Buffer size of device decoders: twice the longest accepted request (6 + 64)
/// and a header.
pub const DEVICE_BUFFER: usize = 144;
/// Buffer size of both-direction decoders, as [`HOST_BUFFER`].
pub const BOTH_BUFFER: usize = HOST_BUFFER;

/// Decodes responses (the host's side).
pub type HostDecoder = StreamDecoder<Framing<Host>, HOST_BUFFER>;
/// Decodes requests (the device's side, or a simulated Pixy2).
pub type DeviceDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER>;
/// Decodes both directions (captures, tooling).
pub type BothDecoder = StreamDecoder<Framing<Both>, BOTH_BUFFER>;

/// A host decoder accepting both frame forms.
pub const fn host_decoder() -> HostDecoder {
    StreamDecoder::new(Framing::new())
}

/// A device decoder accepting both frame forms.
pub const fn device_decoder() -> DeviceDecoder {
    StreamDecoder::new(Framing::new())
}

/// A both-direction decoder accepting both frame forms.
pub const fn both_decoder() -> BothDecoder {
    StreamDecoder::new(Framing::new())
}
