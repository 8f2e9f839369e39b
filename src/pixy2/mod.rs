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
//! # Sides
//!
//! * [`HostDecoder`] accepts responses ([`Packet`]`<`[`Response`]`>`),
//! * [`DeviceDecoder`] accepts requests ([`Packet`]`<`[`Request`]`>`), with the
//!   device's 64-byte receive limit and a 72-byte buffer,
//! * [`Decoder`] accepts both ([`Packet`]`<`[`Message`]`>`), for captures.
//!
//! [`framing`] describes what is rejected where. A bare [`Request`] encodes
//! without a checksum, a bare [`Response`] with one; [`Packet`] picks a form.
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
mod error;
mod features;
pub mod framing;
mod packet;
mod pair;
mod request;
mod response;

pub use blocks::{Block, BlockIter, Blocks, BlocksBuf, MAX_BLOCKS};
pub use error::{DeviceError, Error, Malformed};
pub use features::{
    Barcode, Element, Elements, FeatureIter, Features, FeaturesBuf, Intersection, IntersectionLine,
    Section, Sections, Vector, FTYPE_BARCODE, FTYPE_INTERSECTION, FTYPE_VECTOR, INTERSECTION_SLOTS,
};
pub use framing::{Both, Device, Framing, Host, Side};

/// The old name of [`Both`].
#[deprecated(since = "0.2.0", note = "renamed to `Both` (`robowire::side::Both`)")]
pub type Any = Both;
pub use packet::{
    checksum, packet_type, Form, Message, MessageBuf, Packet, DEVICE_MAX_PAYLOAD, MAX_FRAME,
    MAX_PAYLOAD, SYNC_CHECKSUM, SYNC_NO_CHECKSUM,
};
pub use pair::{PairError, ProgSwitch, Query};
pub use request::{
    ChangeProg, GetBlocks, GetFeatures, GetFps, GetResolution, GetRgb, GetVersion, ProgName,
    Request, ReverseVector, SetCameraBrightness, SetDefaultTurn, SetLamp, SetLed, SetMode,
    SetNextTurn, SetServos, SetVector,
};
pub use response::{FirmwareType, Resolution, Response, ResponseBuf, Rgb, Version};

use crate::stream::StreamDecoder;

/// Buffer size of host and any-direction decoders: twice the longest frame
/// (261) and a header, so the engine's resync verification has room.
pub const HOST_BUFFER: usize = 528;
/// Buffer size of device decoders: twice the longest accepted request (6 + 64)
/// and a header.
pub const DEVICE_BUFFER: usize = 144;

/// Decodes responses (the host's side).
pub type HostDecoder = StreamDecoder<Framing<Host>, HOST_BUFFER>;
/// Decodes requests (the device's side, or a simulated Pixy2).
pub type DeviceDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER>;
/// Decodes both directions (captures, tooling).
pub type Decoder = StreamDecoder<Framing<Both>, HOST_BUFFER>;

/// A host decoder accepting both frame forms.
pub const fn host_decoder() -> HostDecoder {
    StreamDecoder::new(Framing::new())
}

/// A device decoder accepting both frame forms.
pub const fn device_decoder() -> DeviceDecoder {
    StreamDecoder::new(Framing::new())
}

/// An any-direction decoder accepting both frame forms.
pub const fn decoder() -> Decoder {
    StreamDecoder::new(Framing::new())
}
