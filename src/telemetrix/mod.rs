//! Telemetrix4RpiPico: the serial protocol between a host and the
//! Telemetrix firmware on a Raspberry Pi Pico (RP2040), mirte firmware 1.3 by
//! default, with the older mirte 1.2 and upstream 1.1 dialects
//! ([`Dialect`]).
//!
//! # Wire layout
//!
//! ```text
//! LEN  id  payload…        LEN = bytes after it (id + payload)
//! ```
//!
//! There is no start byte, escaping or checksum. Integers are big-endian,
//! floats little-endian. Commands (host → Pico, [`Command`]) and reports
//! (Pico → host, [`Report`]) have separate id spaces; commands are at most 30
//! bytes after `LEN`.
//!
//! # Messages and their byte fields
//!
//! [`Command<B>`] and [`Report<B>`] are generic over the storage `B` of their
//! variable byte fields (I2C/SPI data, feature extras, module data, servo
//! positions):
//!
//! * parsing borrows from the frame: [`CommandRef`], [`ReportRef`]
//!   (`B = &[u8]`), and so does encoding borrowed data;
//! * the owned form keeps them inline in a [`Payload`] (an array and a
//!   length): [`OwnedCommand`], [`OwnedReport`]; it is what
//!   [`StreamDecoder::feed`](crate::StreamDecoder::feed) yields.
//!
//! Short fixed lists (PWM pins, servo moves, AS5600 angles) are always owned
//! [`List`]s. `as_ref`, `to_owned` and `map_bytes` convert between forms.
//!
//! # Decoding
//!
//! [`ReportDecoder`] (host side) and [`CommandDecoder`] (Pico side) are the
//! shared [`StreamDecoder`] with this protocol's
//! framing. Without a checksum, a candidate is accepted only when its id is
//! known, its `LEN` is the one that id (and its count or sub-type bytes)
//! requires, and its fields are values the sender produces; otherwise the
//! decoder drops one byte and rescans. `00` where a `LEN` would be is
//! skipped, as the firmware does.
//!
//! # Encoding
//!
//! Every message implements [`Encode`] for mirte 1.3;
//! `encode_in(dialect, out)` or [`InDialect`] select another dialect. The
//! encoder writes full payloads and refuses (with an
//! [`EncodeError`]) anything its own decoder would
//! reject: ids the dialect lacks, `LEN` over 30, the per-command maxima, pins
//! ≥ 30.
//!
//! ```
//! use robowire::telemetrix::{Command, Report, ReportDecoder, ReportFraming};
//! use robowire::{Encode, FrameBuf};
//!
//! // Host → Pico: PING with counter 7.
//! let ping = FrameBuf::<31>::encode(&Command::<&[u8]>::Ping { counter: 7 })?;
//! assert_eq!(&ping[..], &[0x02, 0x20, 0x07]);
//!
//! // Pico → host: a PONG and a digital report, split anywhere.
//! let mut decoder = ReportDecoder::new(ReportFraming::new());
//! let mut reports = Vec::new();
//! for chunk in [&[0x03, 0x20][..], &[0x07, 0x2A, 0x03, 0x02, 0x0A, 0x01]] {
//!     for event in decoder.feed(chunk) {
//!         reports.push(event.unwrap().message);
//!     }
//! }
//! assert_eq!(reports[0].as_ref(), Report::Pong { counter: 7, boot_id: 42 });
//! assert_eq!(reports[1].as_ref(), Report::Digital { pin: 10, high: true });
//! # Ok::<(), robowire::EncodeError>(())
//! ```

mod command;
mod dialect;
mod error;
mod framing;
mod list;
mod module;
mod report;
mod sensor;
mod wire;

pub use command::{
    command_id, parse_command, Command, CommandRef, EncoderKind, ModifyReporting, OwnedCommand,
    PinMode, Pull, Pulls, PwmPin, PwmPins, Rgb, COMMAND_PAYLOAD_MAX,
};
pub use dialect::Dialect;
pub use error::Error;
pub use framing::{CommandFraming, ReportFraming};
pub use list::{List, Payload};
pub use module::{
    HiwonderCommand, ModuleCommand, ModuleInit, ModuleNew, ModuleReport, ModuleType,
    Pca9685Channel, Pca9685Command, Pca9685Config, RelayCommand, ServoMove, ServoPosition,
    ServoPositions, Ssd1306Command, Ssd1306Done, MODULE_INIT_MAX,
};
pub use report::{
    parse_report, report_id, OwnedReport, Report, ReportRef, Sonar, SonarReading,
    REPORT_PAYLOAD_MAX, SONAR_NO_ECHO, SONAR_OUT_OF_RANGE, SONAR_STALE,
};
pub use sensor::{SensorNew, SensorReading, SensorType};

use crate::{Encode, EncodeError, StreamDecoder};

/// GPIOs on the RP2040: pins are `0..30`.
pub const PIN_COUNT: u8 = 30;

/// The firmware's `MAX_COMMAND_LENGTH`: the largest `LEN` of a command.
pub const MAX_COMMAND_LEN: usize = 30;

/// Buffer size of [`ReportDecoder`]: the longest report frame (256 bytes).
pub const REPORT_BUFFER: usize = 256;

/// Buffer size of [`CommandDecoder`]: the longest command frame (31 bytes).
pub const COMMAND_BUFFER: usize = 32;

/// Decoder of reports (the host side), for strict framings. Its buffer holds
/// the longest report frame (256 bytes).
pub type ReportDecoder = StreamDecoder<ReportFraming, REPORT_BUFFER>;

/// Decoder of reports for a [`ReportFraming::lenient`] framing: its buffer
/// holds an unknown frame and the known frame that must follow it.
pub type LenientReportDecoder = StreamDecoder<ReportFraming, 512>;

/// Decoder of commands (the Pico side). Its buffer holds the longest command
/// frame (31 bytes).
pub type CommandDecoder = StreamDecoder<CommandFraming, COMMAND_BUFFER>;

/// The host side's decoder, [`ReportDecoder`].
pub type Decoder = ReportDecoder;

/// Whether `pin` names an analog input in `dialect`: GPIO 26..=30 (30 is the
/// temperature sensor) in mirte 1.3, ADC 0..=4 before.
pub(crate) const fn analog_pin_ok(dialect: Dialect, pin: u8) -> bool {
    match dialect {
        Dialect::Mirte13 => pin >= 26 && pin <= 30,
        Dialect::Mirte12 | Dialect::Upstream11 => pin <= 4,
    }
}

/// A message paired with the dialect to encode it for, so that
/// [`FrameBuf::encode`](crate::FrameBuf::encode) and `encode_buf` work for
/// every dialect. Made by `in_dialect` on [`Command`] and [`Report`].
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy)]
pub struct InDialect<'m, M> {
    message: &'m M,
    dialect: Dialect,
}

impl<B: AsRef<[u8]>> Command<B> {
    /// This command, to be encoded for `dialect`.
    pub const fn in_dialect(&self, dialect: Dialect) -> InDialect<'_, Self> {
        InDialect {
            message: self,
            dialect,
        }
    }
}

impl<B: AsRef<[u8]>> Report<B> {
    /// This report, to be encoded for `dialect`.
    pub const fn in_dialect(&self, dialect: Dialect) -> InDialect<'_, Self> {
        InDialect {
            message: self,
            dialect,
        }
    }
}

impl<B: AsRef<[u8]>> Encode for InDialect<'_, Command<B>> {
    const MAX_LEN: usize = MAX_COMMAND_LEN + 1;

    fn encoded_len(&self) -> usize {
        self.message.encoded_len_in(self.dialect)
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.message.encode_in(self.dialect, out)
    }
}

impl<B: AsRef<[u8]>> Encode for InDialect<'_, Report<B>> {
    const MAX_LEN: usize = report::MAX_REPORT_FRAME;

    fn encoded_len(&self) -> usize {
        self.message.encoded_len_in(self.dialect)
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.message.encode_in(self.dialect, out)
    }
}
