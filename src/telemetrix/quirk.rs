//! What is dubious in a frame a real peer sends: the decoder accepts the
//! frame (refusing it would lose it and, without a checksum, the frames
//! around it) and flags it; the encoder refuses it.

use super::dialect::Dialect;
use super::wire::{command_id as cid, report_id as rid};
use crate::EncodeError;

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
}

impl Quirk {
    /// Every quirk.
    pub const ALL: [Quirk; 5] = [
        Quirk::DigitalReportingPinMinus26,
        Quirk::LevelNotBinary,
        Quirk::PwmTrailingBytes,
        Quirk::EncoderTypeNot1Or2,
        Quirk::EchoedRequestByte,
    ];

    /// The name the JSON-lines schema writes (snake case).
    pub const fn name(self) -> &'static str {
        match self {
            Quirk::DigitalReportingPinMinus26 => "digital_reporting_pin_minus_26",
            Quirk::LevelNotBinary => "level_not_binary",
            Quirk::PwmTrailingBytes => "pwm_trailing_bytes",
            Quirk::EncoderTypeNot1Or2 => "encoder_type_not_1_or_2",
            Quirk::EchoedRequestByte => "echoed_request_byte",
        }
    }

    /// The encode error of a message whose frame would have this quirk:
    /// the one the encoder gave before the decoder accepted such frames.
    pub(crate) const fn into_encode_error(self) -> EncodeError {
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
        }
    }
}

impl core::fmt::Display for Quirk {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// The quirk of a command frame the decoder accepted in `dialect`, read
/// from its bytes.
pub(crate) fn command_quirk(dialect: Dialect, frame: &[u8]) -> Option<Quirk> {
    match *frame {
        [3, cid::MODIFY_REPORTING, 2 | 4, _] if dialect == Dialect::Mirte13 => {
            Some(Quirk::DigitalReportingPinMinus26)
        }
        [3, cid::DIGITAL_WRITE, _, value] if value > 1 => Some(Quirk::LevelNotBinary),
        [len, cid::PWM_WRITE, ..] if len.wrapping_sub(1) % 3 != 0 => Some(Quirk::PwmTrailingBytes),
        [_, cid::ENCODER_NEW, kind, ..] if !matches!(kind, 1 | 2) => {
            Some(Quirk::EncoderTypeNot1Or2)
        }
        _ => None,
    }
}

/// The quirk of a report frame the decoder accepted in `dialect`, read from
/// its bytes.
pub(crate) fn report_quirk(dialect: Dialect, frame: &[u8]) -> Option<Quirk> {
    match *frame {
        // MODULE_REPORT, SSD1306 (type 3), display disabled.
        [5, rid::MODULE, _, 3, sub, 254] if dialect == Dialect::Mirte13 && sub > 3 => {
            Some(Quirk::EchoedRequestByte)
        }
        _ => None,
    }
}
