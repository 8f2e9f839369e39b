//! What is dubious in a frame a real peer sends: the decoder accepts the
//! frame (refusing it would lose it and, without a checksum, the frames
//! around it) and flags it; the encoder refuses it.

use super::command::Command;
use super::dialect::Dialect;
use super::kind::piece;
use super::report::Report;
use super::wire::{
    command_id, pixel_buffer, I2C_READ_MAX, MAX_COMMAND_FRAME, MAX_REPORT_FRAME, SPI_READ_MAX,
};
use super::InDialect;
use crate::{Encode, EncodeError};

/// Something dubious in a frame that a real host or Pico sends, which the
/// decoder accepts and flags, and the encoder refuses (spec §4, §4.2, §7.3).
///
/// The decoded message is what the firmware makes of the frame (a level
/// byte 2 is high, trailing PWM bytes are ignored, an encoder type 3 is
/// quadrature); the owned forms keep the frame's own bytes and report the
/// quirk ([`CommandBuf::quirk`](super::CommandBuf::quirk),
/// [`ReportBuf::quirk`](super::ReportBuf::quirk),
/// [`MessageBuf::quirk`](super::MessageBuf::quirk)), which the JSON-lines
/// schema writes as `"quirk":"<name>"` after the message's fields.
///
/// | quirk | frame (example) | dialects | sent by | the firmware |
/// |---|---|---|---|---|
/// | [`DigitalReportingPinMinus26`](Quirk::DigitalReportingPinMinus26) | `03 04 04 02` | mirte 1.3 | the mirte Python client | indexes pin − 26 (spec §4.2) |
/// | [`LevelNotBinary`](Quirk::LevelNotBinary) | `03 02 05 02` | all | a host writing a truthy byte | drives the pin high |
/// | [`PwmTrailingBytes`](Quirk::PwmTrailingBytes) | `05 03 01 00 10 07` | mirte 1.3 | a host with a short last triple | takes `(LEN − 1) / 3` pins |
/// | [`EncoderTypeNot1Or2`](Quirk::EncoderTypeNot1Or2) | `05 1e 03 02 03 00` | mirte 1.3, 1.2 | a host | sets up a quadrature encoder |
/// | [`EchoedRequestByte`](Quirk::EchoedRequestByte) | `05 22 03 03 05 fe` (report) | mirte 1.3 | the Pico | echoes the subtype it did not know |
/// | [`AnalogReportingPinNotAdc`](Quirk::AnalogReportingPinNotAdc) | `03 04 01 1a`, `03 04 01 05` | mirte 1.2, upstream 1.1 | their Python clients (`enable_analog_reporting(26)`, unchecked) | writes past its 5-entry analog pin array; no ADC pin's reporting changes |
/// | [`IgnoredByFirmware`](Quirk::IgnoredByFirmware) | `03 21 00 01`, `07 22 01 03 00 00 01 2c` | mirte 1.2 | the mirte 1.2-era client with modules | does nothing (empty MODULE_NEW and MODULE_DATA handlers), sends no reply |
/// | [`PastFirmwareBuffer`](Quirk::PastFirmwareBuffer) | `07 0b 00 68 00 75 40 00`, `04 1a 00 40 00`, `06 13 1c 96 00 00 00` (mirte 1.3) | all | a host asking for more than the firmware holds (the 1.1 and 1.2 clients check none of these) | writes past a fixed buffer: its 64-entry I2C or SPI report buffer, or its pixel buffer (100 pixels in mirte 1.3, 150 in 1.2 and 1.1) |
/// | [`SpiDataBitsOutOfRange`](Quirk::SpiDataBitsOutOfRange) | `05 1b 00 14 00 00` | all | a host (the 1.1 and 1.2 clients do not check) | sets the SPI frame size from the low 4 bits of `data_bits − 1` (20 bits: 4-bit frames) |
///
/// These rules come from the firmware sources (upstream 1.1
/// `MrYsLab/Telemetrix4RpiPico`, mirte 1.2 `mirte-robot/Telemetrix4RpiPico`
/// tag 0.1.1, mirte 1.3 `ArendJan/Telemetrix4RpiPico`) where the spec gives
/// only the range a careful host keeps to.
///
/// * MODIFY_REPORTING in mirte 1.2 and upstream 1.1: the spec gives their
///   analog pins as ADC numbers 0..=4 (§10). The handler takes the type and
///   the pin byte and, for types 1 and 3, sets the reporting flag of
///   `the_analog_pins[pin]` without a range check, so any byte past 4
///   writes past the 5-entry array: the reporting of ADC 0..=4 does not
///   change, and no analog report of the pin the host meant follows. For
///   types 2 and 4 it indexes the digital pins directly (no `− 26`); type 0
///   ignores the pin. Their clients send the pin byte they are given,
///   unchecked, so the decoder takes an analog pin by its ADC number (no
///   quirk) or any other byte (flagged: a GPIO number 26..=30 is what a
///   host that counts pins as mirte 1.3 does sends), digital pins below 30,
///   and type 0 with pin 0 (what every client sends). SET_PIN_MODE analog
///   needs no such rule: those clients check its ADC number (0..=4).
/// * MODULE_NEW and MODULE_DATA (ids 33, 34) in mirte 1.2: its command
///   table has both, with handlers that return at once. The decoder reads
///   them in mirte 1.3's layout (what the client that sends them writes).
/// * The report buffers of every firmware hold 64 entries: an I2C read of
///   `n` bytes fills `n + 7` of them (mirte; `n + 6` upstream) and an SPI
///   read `n + 4`, unchecked, so a read of more than 57 (I2C) or 60 (SPI)
///   bytes writes past the buffer. The pixel buffer holds 150 pixels in
///   mirte 1.2 and upstream 1.1, whose INITIALIZE_NEO_PIXELS fills `count`
///   pixels and SET_NEO_PIXEL writes pixel `index`, unchecked; mirte 1.3's
///   holds 100, fills `count` of them, and ignores an `index` at or past the
///   count.
/// * SPI_SET_FORMAT passes `data_bits` to the Pico SDK's `spi_set_format`,
///   which checks its 4..=16 range only in builds with parameter assertions
///   (off in the firmware's release builds) and writes `data_bits − 1` into
///   the 4-bit frame-size field.
///
/// ```
/// use robowire::telemetrix::{CommandBuf, Dialect, Quirk};
///
/// // What the mirte Python client sends to disable digital reporting of GPIO 2.
/// let command = CommandBuf::parse_in(&[0x03, 0x04, 0x04, 0x02], Dialect::Mirte13)?;
/// assert_eq!(command.quirk(), Some(Quirk::DigitalReportingPinMinus26));
/// # Ok::<(), robowire::telemetrix::Error>(())
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Quirk {
    /// MODIFY_REPORTING type 2 or 4 (enable or disable a digital pin) in
    /// mirte 1.3, whose firmware indexes the pin as `pin − 26` (spec §4.2).
    DigitalReportingPinMinus26,
    /// DIGITAL_WRITE with a level byte other than 0 or 1: the firmware
    /// drives any non-zero level high.
    LevelNotBinary,
    /// PWM_WRITE (mirte 1.3) with 1 or 2 bytes after the last whole
    /// `pin, u16 value` triple: the firmware takes `(LEN − 1) / 3` pins and
    /// ignores them.
    PwmTrailingBytes,
    /// ENCODER_NEW with type byte 3: the firmware sets up a quadrature
    /// encoder for any type other than 1.
    EncoderTypeNot1Or2,
    /// A report that echoes its request's byte where that byte names no
    /// request: the SSD1306 "display disabled" reply (`request_sub, 254`)
    /// to a MODULE_DATA whose subtype is not 0..=3.
    EchoedRequestByte,
    /// MODIFY_REPORTING type 1 or 3 (enable or disable an analog pin) in
    /// mirte 1.2 or upstream 1.1 with a pin byte past 4 (a GPIO number
    /// 26..=30, or any other byte) where that firmware takes an ADC number
    /// (0..=4): it writes the flag past its five analog pins, and no ADC
    /// pin's reporting changes.
    AnalogReportingPinNotAdc,
    /// MODULE_NEW or MODULE_DATA in mirte 1.2, whose firmware has both in
    /// its command table as empty stubs: the Pico does nothing and sends no
    /// reply.
    IgnoredByFirmware,
    /// A read length, pixel count or pixel index past a fixed buffer of the
    /// firmware, which does not check it: I2C_READ of more than 57 bytes or
    /// SPI_READ_BLOCKING of more than 60 (its 64-entry report buffer),
    /// INITIALIZE_NEO_PIXELS or SET_NEO_PIXEL past its pixel buffer (100
    /// pixels in mirte 1.3, 150 in mirte 1.2 and upstream 1.1). The
    /// firmware writes past the buffer (mirte 1.3 ignores such a pixel
    /// index instead).
    PastFirmwareBuffer,
    /// SPI_SET_FORMAT with `data_bits` outside 4..=16: the firmware hands
    /// it to the Pico SDK unchecked, which sets the frame size from the low
    /// 4 bits of `data_bits − 1` (20 gives 4-bit frames).
    SpiDataBitsOutOfRange,
}

impl Quirk {
    /// Every quirk, in the order of [`Quirk::NAMES`].
    pub const ALL: [Quirk; 9] = [
        Quirk::DigitalReportingPinMinus26,
        Quirk::LevelNotBinary,
        Quirk::PwmTrailingBytes,
        Quirk::EncoderTypeNot1Or2,
        Quirk::EchoedRequestByte,
        Quirk::AnalogReportingPinNotAdc,
        Quirk::IgnoredByFirmware,
        Quirk::PastFirmwareBuffer,
        Quirk::SpiDataBitsOutOfRange,
    ];

    /// The encode error of a message whose frame would have this quirk:
    /// the one the encoder gave before the decoder accepted such frames.
    /// `frame` is the frame's bytes (`LEN` first).
    pub(crate) const fn into_encode_error(self, frame: &[u8]) -> EncodeError {
        match self {
            Quirk::DigitalReportingPinMinus26 => EncodeError::OutOfRange { field: "pin" },
            Quirk::LevelNotBinary => EncodeError::OutOfRange { field: "value" },
            Quirk::PwmTrailingBytes => EncodeError::Inconsistent {
                what: "the payload length does not fit the message's layout",
            },
            Quirk::EncoderTypeNot1Or2 => EncodeError::OutOfRange { field: "type" },
            Quirk::EchoedRequestByte => EncodeError::OutOfRange {
                field: "request_sub",
            },
            Quirk::AnalogReportingPinNotAdc => EncodeError::OutOfRange { field: "pin" },
            Quirk::IgnoredByFirmware => EncodeError::Inconsistent {
                what: "the command does nothing in this dialect's firmware",
            },
            Quirk::PastFirmwareBuffer => EncodeError::OutOfRange {
                // The field past the buffer, by the frame's id.
                field: match frame {
                    [_, command_id::INITIALIZE_NEO_PIXELS, ..] => "count",
                    [_, command_id::SET_NEO_PIXEL, ..] => "index",
                    _ => "len",
                },
            },
            Quirk::SpiDataBitsOutOfRange => EncodeError::OutOfRange { field: "data_bits" },
        }
    }
}

/// [`Quirk::PastFirmwareBuffer`] if the frame's byte `at` is above `max`.
fn past_buffer_at(frame: &[u8], at: usize, max: u8) -> Option<Quirk> {
    frame
        .get(at)
        .filter(|&&byte| byte > max)
        .map(|_| Quirk::PastFirmwareBuffer)
}

/// [`Quirk::IgnoredByFirmware`] in mirte 1.2, whose MODULE_NEW and
/// MODULE_DATA handlers are empty.
fn ignored_in_mirte12(dialect: Dialect) -> Option<Quirk> {
    (dialect == Dialect::Mirte12).then_some(Quirk::IgnoredByFirmware)
}

/// `command_quirk`, from the command table.
macro_rules! command_quirks {
    ($($(#[$m:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+] len $lens:tt
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        quirk_fn!(command_quirk "command"; $($n $codec { $($body)* })*);
    };
}

/// `report_quirk`, from the report table.
macro_rules! report_quirks {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        quirk_fn!(report_quirk "report"; $($n $codec { $($body)* })*);
    };
}

/// The quirk of a frame the decoder accepted: the `quirk` rule of its row.
macro_rules! quirk_fn {
    ($fn:ident $what:literal; $($n:literal $codec:ident $body:tt)*) => {
        #[doc = concat!("The quirk of a ", $what, " frame the decoder accepted in `dialect`, read")]
        /// from its bytes by the `quirk` rule of its table row.
        pub(crate) fn $fn(dialect: Dialect, frame: &[u8]) -> Option<Quirk> {
            match *frame.get(1)? {
                $($n => piece!(quirk (dialect, frame) expr { None }, $codec $body),)*
                _ => None,
            }
        }
    };
}

super::table::command_table!(command_quirks);
super::table::report_table!(report_quirks);

/// A message to be encoded even if its frame has a [`Quirk`]: the frame a
/// real peer sends that the encoder otherwise refuses (`03 04 04 02` in
/// mirte 1.3, `03 04 01 1A` in mirte 1.2). Made by `even_if_refused` on a
/// [`Command`], a [`Report`] (mirte 1.3) or an [`InDialect`]; the shape of
/// [`pixy2::Envelope::even_if_refused`](crate::pixy2::Envelope::even_if_refused).
/// For testing a device, a host or a simulator with what real peers send.
///
/// Everything else is checked as [`Encode`] checks it: the frame must be
/// one the decoder accepts. A quirk that a message cannot express (a level
/// byte 2 is `value: true`, PWM trailing bytes and an encoder type 3 are
/// not in the message) encodes to the plain frame; the owned forms a
/// decoder yields keep the frame's own bytes, and the JSON-lines schema
/// writes those bytes (see the `robowire` tool's docs).
///
/// ```
/// use robowire::telemetrix::{Command, Dialect, ModifyReporting};
/// use robowire::Encode;
///
/// let enable = Command::ModifyReporting(ModifyReporting::EnableAnalog { pin: 26 });
/// let mut out = [0u8; 4];
/// assert!(enable.in_dialect(Dialect::Mirte12).encode(&mut out).is_err());
/// let n = enable.in_dialect(Dialect::Mirte12).even_if_refused().encode(&mut out)?;
/// assert_eq!(&out[..n], &[0x03, 0x04, 0x01, 0x1a]);
/// # Ok::<(), robowire::EncodeError>(())
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy)]
pub struct EvenIfRefused<'m, M> {
    message: &'m M,
    dialect: Dialect,
}

impl<'m, M> InDialect<'m, M> {
    /// This message, encoded for its dialect even if its frame has a
    /// [`Quirk`].
    pub const fn even_if_refused(self) -> EvenIfRefused<'m, M> {
        EvenIfRefused {
            message: self.message,
            dialect: self.dialect,
        }
    }
}

impl<'a> Command<'a> {
    /// This command, encoded for mirte 1.3 even if its frame has a [`Quirk`]
    /// (see [`EvenIfRefused`]).
    pub const fn even_if_refused(&self) -> EvenIfRefused<'_, Self> {
        self.in_dialect(Dialect::Mirte13).even_if_refused()
    }
}

impl<'a> Report<'a> {
    /// This report, encoded for mirte 1.3 even if its frame has a [`Quirk`]
    /// (see [`EvenIfRefused`]).
    pub const fn even_if_refused(&self) -> EvenIfRefused<'_, Self> {
        self.in_dialect(Dialect::Mirte13).even_if_refused()
    }
}

impl Encode for EvenIfRefused<'_, Command<'_>> {
    const MAX_LEN: usize = MAX_COMMAND_FRAME;

    fn encoded_len(&self) -> usize {
        self.message.encoded_len_in(self.dialect)
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.message.encode_checked(self.dialect, out, true)
    }
}

impl Encode for EvenIfRefused<'_, Report<'_>> {
    const MAX_LEN: usize = MAX_REPORT_FRAME;

    fn encoded_len(&self) -> usize {
        self.message.encoded_len_in(self.dialect)
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.message.encode_checked(self.dialect, out, true)
    }
}
