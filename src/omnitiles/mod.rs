//! OmniTiles: the binary protocol between a host and an OmniTiles tile.
//!
//! Every frame is `[0xA5][id][payload][sum]`, where `sum` is the wrapping 8-bit
//! sum of the id and payload bytes. There is no length byte: a command's
//! length follows from its id, and telemetry (id `0x60`, tile → host) is told
//! apart only by its total length — 7, 15, 17 or 53 bytes as the SDK documents,
//! or the firmware's 45-byte SPI frame ([`Layout`]). Wire facts follow the
//! project's specification of the protocol (Clue88/OmniTiles at `094ed61`).
//!
//! * [`Command`] and [`Telemetry`] are the typed messages, [`Packet`] either.
//!   Both implement [`Encode`].
//! * [`Decoder`] decodes a byte stream incrementally (see
//!   [`StreamDecoder`]); [`Framing`] says what it
//!   accepts and documents the telemetry length policy.
//! * [`DatagramDecoder`] decodes runs of bytes whose boundaries are known (BLE
//!   notifications and writes, SPI buffers).
//! * [`units`] converts bytes to duty, millimetres and back.
//!
//! ```
//! use robowire::omnitiles::{Command, Decoder, Framing, Motor, Packet};
//!
//! let mut decoder = Decoder::new(Framing::commands());
//! let mut packets = Vec::new();
//! // Garbage, a false start (a5 a5), and a frame split across two chunks.
//! for chunk in [&[0x00, 0xa5, 0xa5, 0x30][..], &[0xc8, 0xf8, 0xa5, 0x50, 0x50]] {
//!     for event in decoder.feed(chunk) {
//!         match event {
//!             Ok(frame) => packets.push(frame.message),
//!             Err(rejected) => eprintln!("skipped: {rejected}"),
//!         }
//!     }
//! }
//! decoder.flush().for_each(drop);
//! assert_eq!(packets, [
//!     Packet::Command(Command::Extend { motor: Motor::M1, speed: 200 }),
//!     Packet::Command(Command::Ping),
//! ]);
//! assert_eq!(decoder.stats().frames, 2);
//! ```

mod command;
mod datagram;
mod error;
mod framing;
mod layout;
mod telemetry;
pub mod units;

pub use command::{id, payload_len, Command, Motor};
pub use datagram::{Datagram, DatagramDecoder};
pub use error::Error;
pub use framing::Framing;
pub use layout::{Layout, Layouts};
pub use telemetry::{Imu, Telemetry, NO_READING};

use crate::encode::{Encode, EncodeError};
use crate::stream::StreamDecoder;

/// The start byte of every frame.
pub const START: u8 = 0xA5;

/// The longest frame of any kind (the 53-byte BLE telemetry).
pub const MAX_FRAME_LEN: usize = Telemetry::MAX_LEN;

/// Internal buffer size: room for the longest frame, a frame starting inside
/// it and the next header after that (the engine's resync verification).
pub const BUFFER_LEN: usize = 128;

/// The OmniTiles stream decoder.
pub type Decoder = StreamDecoder<Framing, BUFFER_LEN>;

/// The checksum of a frame: the wrapping sum of its id and payload bytes.
///
/// ```
/// assert_eq!(robowire::omnitiles::checksum(&[0x30, 0xc8]), 0xf8);
/// ```
pub fn checksum(id_and_payload: &[u8]) -> u8 {
    id_and_payload.iter().fold(0u8, |s, &b| s.wrapping_add(b))
}

/// Any OmniTiles message.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Packet {
    /// Host → tile.
    Command(Command),
    /// Tile → host.
    Telemetry(Telemetry),
}

impl Packet {
    /// The longest frame any packet encodes to.
    pub const MAX_LEN: usize = MAX_FRAME_LEN;
}

impl From<Command> for Packet {
    fn from(command: Command) -> Self {
        Packet::Command(command)
    }
}

impl From<Telemetry> for Packet {
    fn from(telemetry: Telemetry) -> Self {
        Packet::Telemetry(telemetry)
    }
}

impl Encode for Packet {
    const MAX_LEN: usize = MAX_FRAME_LEN;

    fn encoded_len(&self) -> usize {
        match self {
            Packet::Command(c) => c.encoded_len(),
            Packet::Telemetry(t) => t.encoded_len(),
        }
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        match self {
            Packet::Command(c) => c.encode(out),
            Packet::Telemetry(t) => t.encode(out),
        }
    }
}
