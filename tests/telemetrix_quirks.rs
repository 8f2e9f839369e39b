//! Telemetrix quirks: frames a real host or Pico sends that robowire decodes
//! as the firmware reads them, flags, and encodes only when asked
//! (`even_if_refused`).

use robowire::telemetrix::{
    Both, BothDecoder, Command, CommandBuf, Device, DeviceDecoder, Dialect, Framing, Message,
    MessageBuf, ModifyReporting, Quirk,
};

#[path = "support/telemetrix_events.rs"]
mod telemetrix_events;
use telemetrix_events::{events, hex};

/// The quirk of a decoded command read in the decoder's dialect (a
/// decoder's owned form is read in the first dialect that takes it, mirte
/// 1.3 first; a `CaptureContext` or `parse_in` sets another).
fn quirk_in(dialect: Dialect, m: &MessageBuf) -> Option<Quirk> {
    CommandBuf::parse_in(m.frame(), dialect).unwrap().quirk()
}

/// The mirte 1.2 and upstream 1.1 Python clients send `enable_analog_reporting(26)`
/// unchecked: `03 04 01 1a`. Their firmware indexes its five analog pins with
/// the byte (out of range). Each direction's decoder reads it as that command,
/// flagged, and the next frame is kept, with nothing invented.
#[test]
fn analog_reporting_by_gpio_number_in_mirte12_and_upstream11() {
    let bytes = hex("03 04 01 1a 03 04 00 00");
    for dialect in [Dialect::Mirte12, Dialect::Upstream11] {
        let device = DeviceDecoder::new(Framing::<Device>::new().with_dialect(dialect));
        let both = BothDecoder::new(Framing::<Both>::new().with_dialect(dialect));
        for got in [events(device, &bytes), events(both, &bytes)] {
            let frames: Vec<_> = got
                .iter()
                .map(|e| {
                    let (offset, len, m) = e.as_ref().expect("no rejection");
                    (*offset, *len, m.message(), quirk_in(dialect, m))
                })
                .collect();
            assert_eq!(
                frames,
                [
                    (
                        0,
                        4,
                        Message::Command(Command::ModifyReporting(ModifyReporting::EnableAnalog {
                            pin: 26
                        })),
                        Some(Quirk::AnalogReportingPinNotAdc)
                    ),
                    (
                        4,
                        4,
                        Message::Command(Command::ModifyReporting(ModifyReporting::DisableAll)),
                        None
                    ),
                ],
                "{dialect}"
            );
        }
    }
}

/// The same rule for every pin byte past the ADC numbers (a GPIO number
/// 26..=30 or any other: the clients check none) and both analog types; the
/// ADC numbers 0..=4 carry no quirk. `03 04 01 05` was rejected, and a
/// false `get_firmware_version` found at its offset 2.
#[test]
fn analog_reporting_pin_ranges_in_mirte12_and_upstream11() {
    for dialect in [Dialect::Mirte12, Dialect::Upstream11] {
        for kind in [1u8, 3] {
            for pin in 0..=255u8 {
                let frame = [3, 4, kind, pin];
                let got = events(
                    DeviceDecoder::new(Framing::<Device>::new().with_dialect(dialect)),
                    &frame,
                );
                let decoded = match got.as_slice() {
                    [Ok((0, 4, m))] => Some(quirk_in(dialect, m)),
                    _ => None,
                };
                let expected = match pin {
                    0..=4 => Some(None),
                    _ => Some(Some(Quirk::AnalogReportingPinNotAdc)),
                };
                assert_eq!(decoded, expected, "{dialect} {frame:02x?}: {got:?}");
            }
        }
    }
    // mirte 1.3 numbers analog pins by GPIO: 26..=30 as before, no quirk.
    let got = events(DeviceDecoder::new(Framing::<Device>::new()), &[3, 4, 1, 26]);
    assert!(
        matches!(got.as_slice(), [Ok((0, 4, m))] if quirk_in(Dialect::Mirte13, m).is_none()),
        "{got:?}"
    );
}

/// `even_if_refused` encodes the frames whose only objection is a quirk the
/// message holds, in every dialect where they are a real peer's; the plain
/// encoder still refuses them, and the opt-in refuses what no peer sends.
#[test]
fn even_if_refused_encodes_quirky_frames_exactly() {
    use robowire::telemetrix::{ModuleReport, Report};
    use robowire::{Encode, FrameBuf};

    let digital = Command::ModifyReporting(ModifyReporting::DisableDigital { pin: 2 });
    let analog = Command::ModifyReporting(ModifyReporting::EnableAnalog { pin: 26 });
    for (command, dialect, bytes) in [
        (digital, Dialect::Mirte13, "03 04 04 02"),
        (analog, Dialect::Mirte12, "03 04 01 1a"),
        (analog, Dialect::Upstream11, "03 04 01 1a"),
    ] {
        assert!(FrameBuf::<31>::encode(&command.in_dialect(dialect)).is_err());
        let frame = FrameBuf::<31>::encode(&command.in_dialect(dialect).even_if_refused());
        assert_eq!(frame.unwrap().to_vec(), hex(bytes), "{dialect}");
        let quirk = CommandBuf::parse_in(&hex(bytes), dialect).unwrap().quirk();
        assert!(quirk.is_some(), "{dialect} {bytes}");
    }
    assert_eq!(
        FrameBuf::<31>::encode(&digital.even_if_refused())
            .unwrap()
            .to_vec(),
        hex("03 04 04 02")
    );
    // What is no frame at all stays refused.
    let pin_31 = Command::ModifyReporting(ModifyReporting::EnableAnalog { pin: 31 });
    assert!(
        FrameBuf::<31>::encode(&pin_31.in_dialect(Dialect::Mirte13).even_if_refused()).is_err()
    );

    let disabled = Report::Module {
        module_num: 3,
        report: ModuleReport::Ssd1306Disabled { request_sub: 5 },
    };
    assert!(FrameBuf::<256>::encode(&disabled).is_err());
    let mut out = [0u8; 8];
    let n = disabled.even_if_refused().encode(&mut out).unwrap();
    assert_eq!(&out[..n], &hex("05 22 03 03 05 fe")[..]);
}
