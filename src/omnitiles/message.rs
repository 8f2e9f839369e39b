//! Either direction's message.

use core::fmt;

use super::command::Command;
use super::error::Error;
use super::telemetry::Telemetry;
use super::whole::start_and_id;
use super::wire::{id, MAX_FRAME_LEN};
use crate::encode::{Encode, EncodeError};

/// Any OmniTiles message: what a [`BothDecoder`](super::BothDecoder) yields.
///
/// With the `serde` feature a message is written as its command or telemetry
/// (the command-line tool's JSON line without `offset` and `len`), and a
/// line reads back into a command or telemetry by its `type`.
///
/// ```
/// use robowire::omnitiles::{Command, Message, Motor};
/// let message = Message::try_from(&[0xa5, 0x30, 0xc8, 0xf8][..]).unwrap();
/// assert_eq!(message, Message::Command(Command::Extend { motor: Motor::M1, speed: 200 }));
/// assert_eq!(message.to_string(), "m1_extend speed=200");
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message {
    /// Host → tile.
    Command(Command),
    /// Tile → host.
    Telemetry(Telemetry),
}

impl Message {
    /// The longest frame any message encodes to.
    pub const MAX_LEN: usize = MAX_FRAME_LEN;

    /// Every message's name: the `type` values of the JSON form, the
    /// commands' ([`Command::NAMES`]) then `telemetry`.
    pub const NAMES: [&'static str; 12] = {
        let mut names = ["telemetry"; 12];
        let mut i = 0;
        while i < Command::NAMES.len() {
            names[i] = Command::NAMES[i];
            i += 1;
        }
        names
    };

    /// The message's name: the command's [`name`](Command::name) or
    /// `telemetry`.
    pub const fn name(&self) -> &'static str {
        match self {
            Message::Command(c) => c.name(),
            Message::Telemetry(_) => "telemetry",
        }
    }
}

impl From<Command> for Message {
    fn from(command: Command) -> Self {
        Message::Command(command)
    }
}

impl From<Telemetry> for Message {
    fn from(telemetry: Telemetry) -> Self {
        Message::Telemetry(telemetry)
    }
}

/// One whole frame of either direction, start byte to checksum.
///
/// ```
/// use robowire::omnitiles::{Error, Message};
/// let telemetry = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
/// assert!(matches!(Message::try_from(&telemetry[..]), Ok(Message::Telemetry(_))));
/// assert_eq!(Message::try_from(&[0xa5, 0x99, 0x00][..]), Err(Error::UnknownId { id: 0x99 }));
/// assert_eq!(Message::try_from(&[0x00, 0xa5][..]), Err(Error::BadStart { found: 0x00 }));
/// ```
impl TryFrom<&[u8]> for Message {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Message, Error> {
        if start_and_id(frame)? == id::TELEMETRY {
            Telemetry::try_from(frame).map(Message::Telemetry)
        } else {
            Command::try_from(frame).map(Message::Command)
        }
    }
}

/// The command's or the telemetry's line (`m1_extend speed=200`).
impl fmt::Display for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Message::Command(c) => c.fmt(f),
            Message::Telemetry(t) => t.fmt(f),
        }
    }
}

impl Encode for Message {
    const MAX_LEN: usize = MAX_FRAME_LEN;

    fn encoded_len(&self) -> usize {
        match self {
            Message::Command(c) => c.encoded_len(),
            Message::Telemetry(t) => t.encoded_len(),
        }
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        match self {
            Message::Command(c) => c.encode(out),
            Message::Telemetry(t) => t.encode(out),
        }
    }
}
