//! Frames that the mirte 1.2 and upstream 1.1 firmwares and their clients
//! exchange, which robowire 0.2 refused: each decodes from its bytes, in its
//! dialect, as that firmware's handler reads it, at its offset, with its
//! neighbours kept and nothing invented; its JSON line re-encodes to the same
//! bytes; and the plain encoder still refuses what the firmware mishandles.

use robowire::telemetrix::{
    Both, BothDecoder, Command, CommandBuf, Device, DeviceDecoder, Dialect, Framing, Host,
    HostDecoder, ModifyReporting, Quirk, Report, ReportBuf, Rgb,
};
use robowire::Encode;

#[path = "support/telemetrix_events.rs"]
mod telemetrix_events;
use telemetrix_events::{events, hex};

/// A command `frame` between two GET_FIRMWARE_VERSIONs, fed to the device
/// and both-ways decoders of `dialect`: exactly three frames at their
/// offsets, no rejection. Returns the middle frame, read in `dialect`.
fn command_between_neighbours(dialect: Dialect, frame: &str) -> CommandBuf {
    let frame = hex(frame);
    let mut bytes = hex("01 05");
    bytes.extend_from_slice(&frame);
    bytes.extend_from_slice(&hex("01 05"));
    let device = DeviceDecoder::new(Framing::<Device>::new().with_dialect(dialect));
    let both = BothDecoder::new(Framing::<Both>::new().with_dialect(dialect));
    for got in [events(device, &bytes), events(both, &bytes)] {
        let spans: Vec<_> = got
            .iter()
            .map(|e| match e {
                Ok((offset, len, _)) => (*offset, *len),
                Err(e) => panic!("{dialect} {frame:02x?}: rejected {e:?}"),
            })
            .collect();
        let n = frame.len();
        assert_eq!(
            spans,
            [(0, 2), (2, n), (2 + n as u64, 2)],
            "{dialect} {frame:02x?}"
        );
    }
    CommandBuf::parse_in(&frame, dialect).unwrap()
}

/// Upstream 1.1 sends I2C_READ_FAILED (`port, addr`, one stale byte) when an
/// I2C read fails, and its client handles it.
#[test]
fn upstream11_i2c_read_failed() {
    let dialect = Dialect::Upstream11;
    let mut bytes = hex("04 09 00 40 00");
    bytes.extend_from_slice(&hex("03 05 01 01"));
    let host = HostDecoder::new(Framing::<Host>::new().with_dialect(dialect));
    let got = events(host, &bytes);
    let frames: Vec<_> = got
        .iter()
        .map(|e| {
            let (offset, len, m) = e.as_ref().expect("no rejection");
            (*offset, *len, m.frame().to_vec())
        })
        .collect();
    assert_eq!(
        frames,
        [(0, 5, hex("04 09 00 40 00")), (5, 4, hex("03 05 01 01"))]
    );
    let report = ReportBuf::parse_in(&bytes[..5], dialect, false).unwrap();
    assert_eq!(
        report.message(),
        Report::I2cReadFailed {
            port: 0,
            addr: 0x40,
            stale: 0
        }
    );
    assert_eq!(report.quirk(), None);
}

/// Mirte 1.2's command table has MODULE_NEW and MODULE_DATA as empty stubs:
/// the 1.2-era client with modules sends them, in mirte 1.3's layout.
#[test]
fn mirte12_modules_are_commands_the_firmware_ignores() {
    for frame in ["03 21 00 01", "07 22 01 03 00 00 01 2c"] {
        let command = command_between_neighbours(Dialect::Mirte12, frame);
        assert!(
            matches!(
                command.message(),
                Command::ModuleNew(_) | Command::ModuleData { .. }
            ),
            "{command:?}"
        );
        assert_eq!(command.quirk(), Some(Quirk::IgnoredByFirmware), "{frame}");
        // The same frame in mirte 1.3 is a plain command.
        let command = command_between_neighbours(Dialect::Mirte13, frame);
        assert_eq!(command.quirk(), None, "{frame}");
    }
    let data = Command::ModuleData {
        module_num: 1,
        data: &[3, 0, 0, 1, 0x2c],
    };
    let mut out = [0u8; 16];
    assert!(data.in_dialect(Dialect::Mirte12).encode(&mut out).is_err());
    let n = data
        .in_dialect(Dialect::Mirte12)
        .even_if_refused()
        .encode(&mut out)
        .unwrap();
    assert_eq!(out[..n], hex("07 22 01 03 00 00 01 2c"));
}

/// Analog reporting on a pin past the 5 ADC numbers (5..=25 or ≥ 31): the
/// 1.1/1.2 clients send it unchecked. `03 04 01 05` was rejected, and a
/// false `get_firmware_version` found at offset 2.
#[test]
fn analog_reporting_past_the_adc_numbers() {
    for dialect in [Dialect::Mirte12, Dialect::Upstream11] {
        for (frame, pin) in [("03 04 01 05", 5), ("03 04 03 19", 25), ("03 04 01 1f", 31)] {
            let command = command_between_neighbours(dialect, frame);
            let expected = if frame.starts_with("03 04 01") {
                ModifyReporting::EnableAnalog { pin }
            } else {
                ModifyReporting::DisableAnalog { pin }
            };
            assert_eq!(
                command.message(),
                Command::ModifyReporting(expected),
                "{dialect}"
            );
            assert_eq!(
                command.quirk(),
                Some(Quirk::AnalogReportingPinNotAdc),
                "{dialect}"
            );
        }
    }
}

/// Reads and pixel counts past the firmware's fixed buffers, and SPI data
/// bits the Pico SDK does not take: decoded as sent, flagged.
#[test]
fn past_buffers_and_spi_bits() {
    let cases: &[(Dialect, &str, Command<'static>, Option<Quirk>)] = &[
        (
            Dialect::Mirte12,
            "07 0b 00 68 00 75 40 00",
            Command::I2cRead {
                port: 0,
                addr: 0x68,
                msg_id: 0,
                reg: 0x75,
                len: 64,
                no_stop: 0,
            },
            Some(Quirk::PastFirmwareBuffer),
        ),
        (
            Dialect::Upstream11,
            "06 0b 00 68 75 40 00",
            Command::I2cReadUpstream {
                port: 0,
                addr: 0x68,
                reg: 0x75,
                len: 64,
                no_stop: 0,
            },
            Some(Quirk::PastFirmwareBuffer),
        ),
        (
            Dialect::Upstream11,
            "04 1a 00 40 00",
            Command::SpiRead {
                port: 0,
                len: 64,
                tx_fill: 0,
            },
            Some(Quirk::PastFirmwareBuffer),
        ),
        (
            Dialect::Mirte12,
            "06 13 1c 96 00 00 00",
            Command::InitNeoPixels {
                pin: 28,
                count: 150,
                rgb: Rgb { r: 0, g: 0, b: 0 },
            },
            None,
        ),
        (
            Dialect::Mirte13,
            "06 13 1c 96 00 00 00",
            Command::InitNeoPixels {
                pin: 28,
                count: 150,
                rgb: Rgb { r: 0, g: 0, b: 0 },
            },
            Some(Quirk::PastFirmwareBuffer),
        ),
        (
            Dialect::Upstream11,
            "06 15 95 01 02 03 01",
            Command::SetNeoPixel {
                index: 149,
                rgb: Rgb { r: 1, g: 2, b: 3 },
                auto_show: true,
            },
            None,
        ),
        (
            Dialect::Upstream11,
            "06 15 96 01 02 03 01",
            Command::SetNeoPixel {
                index: 150,
                rgb: Rgb { r: 1, g: 2, b: 3 },
                auto_show: true,
            },
            Some(Quirk::PastFirmwareBuffer),
        ),
        (
            Dialect::Mirte12,
            "05 1b 00 14 00 00",
            Command::SpiSetFormat {
                port: 0,
                data_bits: 20,
                cpol: false,
                cpha: false,
            },
            Some(Quirk::SpiDataBitsOutOfRange),
        ),
    ];
    for (dialect, frame, expected, expected_quirk) in cases {
        let command = command_between_neighbours(*dialect, frame);
        assert_eq!(&command.message(), expected, "{dialect} {frame}");
        assert_eq!(&command.quirk(), expected_quirk, "{dialect} {frame}");
        // The plain encoder refuses a flagged frame; asked, it writes the
        // frame exactly.
        let mut out = [0u8; 32];
        let plain = expected.in_dialect(*dialect).encode(&mut out);
        assert_eq!(plain.is_ok(), expected_quirk.is_none(), "{dialect} {frame}");
        let n = expected
            .in_dialect(*dialect)
            .even_if_refused()
            .encode(&mut out)
            .unwrap();
        assert_eq!(out[..n], hex(frame), "{dialect} {frame}");
    }
}

/// Each frame's JSON line (with its `quirk`) reads back to the same bytes.
#[cfg(feature = "serde")]
#[test]
fn every_line_re_encodes() {
    use robowire::telemetrix::MessageBuf;
    let cases = [
        (Dialect::Mirte12, "03 21 00 01"),
        (Dialect::Mirte12, "07 22 01 03 00 00 01 2c"),
        (Dialect::Mirte12, "03 04 01 05"),
        (Dialect::Upstream11, "03 04 03 1f"),
        (Dialect::Mirte12, "07 0b 00 68 00 75 40 00"),
        (Dialect::Upstream11, "06 0b 00 68 75 40 00"),
        (Dialect::Upstream11, "04 1a 00 40 00"),
        (Dialect::Mirte12, "06 13 1c 96 00 00 00"),
        (Dialect::Mirte13, "06 13 1c 96 00 00 00"),
        (Dialect::Upstream11, "06 15 96 01 02 03 01"),
        (Dialect::Mirte12, "05 1b 00 14 00 00"),
    ];
    for (dialect, frame) in cases {
        let bytes = hex(frame);
        let message = MessageBuf::from(CommandBuf::parse_in(&bytes, dialect).unwrap());
        let line = serde_json::to_string(&message).unwrap();
        let mut json = serde_json::Deserializer::from_str(&line);
        let back = MessageBuf::deserialize_in(&mut json, dialect).unwrap();
        assert_eq!(back.frame(), &bytes[..], "{dialect} {line}");
        // Without its quirk marker, the line is refused and told which.
        if let Some(quirk) = message.quirk() {
            let marker = format!(",\"quirk\":\"{quirk}\"");
            let plain = line.replace(&marker, "");
            let mut json = serde_json::Deserializer::from_str(&plain);
            let error = MessageBuf::deserialize_in(&mut json, dialect).unwrap_err();
            assert!(error.to_string().contains(&marker[1..]), "{error}");
        }
    }
    let report = MessageBuf::from(
        ReportBuf::parse_in(&hex("04 09 00 40 00"), Dialect::Upstream11, false).unwrap(),
    );
    let line = serde_json::to_string(&report).unwrap();
    let mut json = serde_json::Deserializer::from_str(&line);
    let back = MessageBuf::deserialize_in(&mut json, Dialect::Upstream11).unwrap();
    assert_eq!(back.frame(), &hex("04 09 00 40 00")[..], "{line}");
}
