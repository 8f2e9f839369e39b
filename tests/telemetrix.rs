//! Telemetrix4RpiPico: golden vectors of spec §12 in both directions, stream
//! behaviour (chunking, prefixes, byte-at-a-time) and measured recovery from
//! corruption.

use robowire::telemetrix::{
    Command, CommandBuf, Device, DeviceDecoder, Dialect, EncoderKind, Error, Framing,
    HiwonderCommand, Host, HostDecoder, List, ModuleInit, ModuleNew, ModuleReport, ModuleType,
    Pca9685Channel, Pca9685Command, PinMode, Pull, Pulls, PwmPin, PwmPins, Report, ReportBuf,
    SensorNew, SensorReading, SensorType, ServoMove, ServoPositions, Sonar, SonarReading,
};
use robowire::{Encode, EncodeError, FrameBuf, Rejected, StreamDecoder};

const M13: Dialect = Dialect::Mirte13;
const M12: Dialect = Dialect::Mirte12;
const UP: Dialect = Dialect::Upstream11;

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// An event as the tests compare it: offset, length and owned message, or
/// offset and error.
type Ev<M> = Result<(u64, usize, M), (u64, Error)>;

fn collect<F, const N: usize>(dec: &mut StreamDecoder<F, N>, chunks: &[&[u8]]) -> Vec<Ev<F::Owned>>
where
    F: robowire::FrameRules<Error = Error>,
{
    let mut out = Vec::new();
    let map = |e: robowire::OwnedEvent<F>| match e {
        Ok(f) => Ok((f.offset, f.len, f.message)),
        Err(Rejected { offset, error }) => Err((offset, error)),
    };
    for chunk in chunks {
        let mut feed = dec.feed(chunk);
        out.extend(feed.by_ref().map(map));
        assert!(feed.remaining().is_empty());
    }
    out.extend(dec.flush().map(map));
    out
}

fn decode_reports(dialect: Dialect, bytes: &[u8]) -> Vec<Ev<ReportBuf>> {
    collect(
        &mut HostDecoder::new(Framing::<Host>::new().with_dialect(dialect)),
        &[bytes],
    )
}

fn decode_commands(dialect: Dialect, bytes: &[u8]) -> Vec<Ev<CommandBuf>> {
    collect(
        &mut DeviceDecoder::new(Framing::<Device>::new().with_dialect(dialect)),
        &[bytes],
    )
}

fn encode_command(dialect: Dialect, c: &Command<'_>) -> Vec<u8> {
    let frame = FrameBuf::<31>::encode(&c.in_dialect(dialect)).unwrap();
    assert_eq!(frame.len(), c.encoded_len_in(dialect));
    frame.to_vec()
}

fn encode_report(dialect: Dialect, r: &Report<'_>) -> Vec<u8> {
    let frame = FrameBuf::<256>::encode(&r.in_dialect(dialect)).unwrap();
    assert_eq!(frame.len(), r.encoded_len_in(dialect));
    frame.to_vec()
}

/// Golden command: encodes to `bytes`, and `bytes` decode to exactly it.
fn golden_command(dialect: Dialect, bytes: &str, c: Command<'_>) {
    let bytes = hex(bytes);
    assert_eq!(encode_command(dialect, &c), bytes, "encode {c:?}");
    let events = decode_commands(dialect, &bytes);
    assert_eq!(events.len(), 1, "{events:?}");
    let (offset, len, ref got) = events[0].unwrap();
    assert_eq!((offset, len), (0, bytes.len()));
    assert_eq!(got.message(), c);
}

/// Golden report: encodes to `bytes`, and `bytes` decode to exactly it.
fn golden_report(dialect: Dialect, bytes: &str, r: Report<'_>) {
    let bytes = hex(bytes);
    assert_eq!(encode_report(dialect, &r), bytes, "encode {r:?}");
    let events = decode_reports(dialect, &bytes);
    assert_eq!(events.len(), 1, "{events:?}");
    let (offset, len, ref got) = events[0].unwrap();
    assert_eq!((offset, len), (0, bytes.len()));
    assert_eq!(got.message(), r);
}

fn pwm(pins: &[(u8, u16)]) -> PwmPins {
    let mut list = PwmPins::new();
    for &(pin, value) in pins {
        list.push(PwmPin { pin, value }).unwrap();
    }
    list
}

#[test]
fn golden_commands_mirte13() {
    golden_command(M13, "01 05", Command::GetFirmwareVersion);
    golden_command(M13, "01 06", Command::GetUniqueId);
    golden_command(M13, "02 20 07", Command::Ping { counter: 7 });
    golden_command(M13, "01 23", Command::GetId);
    golden_command(M13, "02 24 05", Command::SetId { id: 5 });
    golden_command(M13, "02 25 05", Command::FeatureCheck { msg_type: 5 });
    golden_command(
        M13,
        "03 01 19 01",
        Command::SetPinMode {
            pin: 25,
            mode: PinMode::DigitalOutput,
        },
    );
    golden_command(
        M13,
        "03 02 19 01",
        Command::DigitalWrite {
            pin: 25,
            value: true,
        },
    );
    golden_command(
        M13,
        "04 01 0A 03 01",
        Command::SetPinMode {
            pin: 10,
            mode: PinMode::DigitalInput {
                pull: Pull::Up,
                report: true,
            },
        },
    );
    golden_command(
        M13,
        "06 01 1A 05 00 05 01",
        Command::SetPinMode {
            pin: 26,
            mode: PinMode::AnalogInput {
                differential: 5,
                report: true,
            },
        },
    );
    golden_command(M13, "04 03 0F 05 DC", Command::PwmWrite(pwm(&[(15, 1500)])));
    golden_command(
        M13,
        "07 03 0F 05 DC 10 05 DC",
        Command::PwmWrite(pwm(&[(15, 1500), (16, 1500)])),
    );
    golden_command(M13, "03 0D 09 0A", Command::SonarNew { trig: 9, echo: 10 });
    golden_command(
        M13,
        "05 1E 02 0E 0F 01",
        Command::EncoderNew {
            kind: EncoderKind::Quadrature,
            pin_a: 14,
            pin_b: 15,
            pulls: Some(Pulls {
                up: true,
                down: false,
            }),
        },
    );
    golden_command(
        M13,
        "04 0A 00 00 00",
        Command::I2cBegin {
            port: 0,
            sda: 0,
            scl: 0,
        },
    );
    golden_command(
        M13,
        "08 0C 00 3C 07 02 00 00 AF",
        Command::I2cWrite {
            port: 0,
            addr: 0x3C,
            msg_id: 7,
            no_stop: 0,
            data: &[0x00, 0xAF],
        },
    );
    golden_command(
        M13,
        "07 0B 00 68 03 75 01 00",
        Command::I2cRead {
            port: 0,
            addr: 0x68,
            msg_id: 3,
            reg: 0x75,
            len: 1,
            no_stop: 0,
        },
    );
    golden_command(M13, "01 0F", Command::StopAllReports);
    golden_command(M13, "01 10", Command::EnableAllReports);
    golden_command(M13, "02 1D 32", Command::SetScanDelay { delay_ms: 50 });
    golden_command(M13, "02 00 41", Command::LoopBack { byte: b'A' });
    golden_command(
        M13,
        "03 1F 00 02",
        Command::SensorNew(SensorNew::Check { sensor_type: 2 }),
    );
    golden_command(
        M13,
        "0A 1F 01 00 06 01 40 00 00 00 00",
        Command::SensorNew(SensorNew::add(0, SensorType::Ina226, &[1, 0x40]).unwrap()),
    );
    golden_command(
        M13,
        "03 21 00 01",
        Command::ModuleNew(ModuleNew::Check { module_type: 1 }),
    );
    golden_command(
        M13,
        "0A 21 01 00 01 00 01 00 02 01 02",
        Command::ModuleNew(ModuleNew::Add {
            module_num: 0,
            init: ModuleInit::HiwonderServo {
                uart: 0,
                rx: 1,
                tx: 0,
                bus_ids: &[1, 2],
            },
        }),
    );
    golden_command(
        M13,
        "09 22 00 01 01 00 2E E0 01 F4",
        Command::ModuleData {
            module_num: 0,
            data: &hex("01 01 00 2E E0 01 F4"),
        },
    );
    golden_command(
        M13,
        "07 22 01 03 00 00 01 2C",
        Command::ModuleData {
            module_num: 1,
            data: &hex("03 00 00 01 2C"),
        },
    );
}

#[test]
fn golden_module_data_is_typed() {
    let angle = HiwonderCommand::SetAngle(
        List::from_slice(&[ServoMove {
            idx: 0,
            centideg: 12000,
            time_ms: 500,
        }])
        .unwrap(),
    );
    let cmd = Command::module_data(0, &angle).unwrap();
    assert_eq!(cmd.to_vec(), hex("09 22 00 01 01 00 2E E0 01 F4"));
    let Command::ModuleData { data, .. } = cmd.message() else {
        panic!("{cmd:?}")
    };
    assert_eq!(
        <HiwonderCommand as robowire::telemetrix::ModuleCommand>::parse(data),
        Ok(angle)
    );

    let pca = Pca9685Command {
        channels: List::from_slice(&[Pca9685Channel {
            channel: 3,
            on: 0,
            off: 300,
        }])
        .unwrap(),
    };
    let cmd = Command::module_data(1, &pca).unwrap();
    assert_eq!(cmd.to_vec(), hex("07 22 01 03 00 00 01 2C"));
    let Command::ModuleData { data, .. } = cmd.message() else {
        panic!("{cmd:?}")
    };
    assert_eq!(
        <Pca9685Command as robowire::telemetrix::ModuleCommand>::parse(data),
        Ok(pca)
    );
}

/// The PCA9685 has channels 0..=15 (spec §7.2): 15 is encoded and read,
/// 16 is refused by both, and data without a channel is refused.
#[test]
fn pca9685_channels_stop_at_15() {
    use robowire::telemetrix::ModuleCommand;
    let pca = |channel| Pca9685Command {
        channels: List::from_slice(&[Pca9685Channel {
            channel,
            on: 0,
            off: 300,
        }])
        .unwrap(),
    };
    let data = pca(15).to_data().unwrap();
    assert_eq!(&data[..], &hex("0F 00 00 01 2C")[..]);
    assert_eq!(Pca9685Command::parse(&data), Ok(pca(15)));
    assert_eq!(
        pca(16).to_data(),
        Err(EncodeError::OutOfRange { field: "channel" })
    );
    assert!(matches!(
        Pca9685Command::parse(&hex("10 00 00 01 2C")),
        Err(Error::OutOfRange {
            field: "channel",
            ..
        })
    ));
    assert!(matches!(
        Pca9685Command::parse(&[]),
        Err(Error::OutOfRange {
            field: "channels",
            ..
        })
    ));
}

#[test]
fn golden_port_probe_zeros_are_skipped() {
    let events = decode_commands(M13, &hex("00 00 00 00 00 00 00 01 05"));
    assert_eq!(
        events,
        vec![Ok((7, 2, Command::GetFirmwareVersion.to_buf().unwrap()))]
    );
    let mut dec = DeviceDecoder::new(Framing::<Device>::new());
    let _ = collect(&mut dec, &[&hex("00 00 00 00 00 00 00 01 05")]);
    let stats = dec.stats();
    assert_eq!(
        (stats.skipped, stats.frames, stats.other_rejections),
        (7, 1, 0)
    );
}

#[test]
fn golden_reports_mirte13() {
    golden_report(
        M13,
        "03 05 01 03",
        Report::FirmwareVersion { major: 1, minor: 3 },
    );
    golden_report(
        M13,
        "09 06 b0 b1 b2 b3 b4 b5 00 00",
        Report::UniqueId {
            id: [0xb0, 0xb1, 0xb2, 0xb3, 0xb4, 0xb5, 0, 0],
        },
    );
    // The spec writes the boot id as a placeholder `BB` (0..99); 42 = 0x2A.
    golden_report(
        M13,
        "03 20 07 2A",
        Report::Pong {
            counter: 7,
            boot_id: 42,
        },
    );
    golden_report(M13, "02 23 05", Report::Id { id: 5 });
    golden_report(M13, "02 24 05", Report::IdSet { id: 5 });
    let feature = |msg_type: u8, supported: bool, extras: &'static [u8]| Report::Feature {
        msg_type,
        supported,
        extras,
    };
    golden_report(M13, "05 25 05 01 01 03", feature(5, true, &[1, 3]));
    golden_report(
        M13,
        "0C 25 01 01 1E 0C 0E 05 1A 1B 1C 1D 1E",
        feature(
            1,
            true,
            &[0x1E, 0x0C, 0x0E, 5, 0x1A, 0x1B, 0x1C, 0x1D, 0x1E],
        ),
    );
    golden_report(M13, "06 25 1E 01 04 02 01", feature(30, true, &[4, 2, 1]));
    golden_report(M13, "04 25 0D 01 04", feature(13, true, &[4]));
    golden_report(M13, "03 25 20 01", feature(32, true, &[]));
    golden_report(M13, "03 25 32 00", feature(0x32, false, &[]));
    golden_report(
        M13,
        "04 15 00 02 01",
        Report::SensorSupported {
            sensor_type: 2,
            supported: true,
        },
    );
    golden_report(
        M13,
        "04 15 00 00 00",
        Report::SensorSupported {
            sensor_type: 0,
            supported: false,
        },
    );
    golden_report(
        M13,
        "04 21 00 01 01",
        Report::ModuleSupported {
            module_type: 1,
            supported: true,
        },
    );
    golden_report(
        M13,
        "03 02 0A 01",
        Report::Digital {
            pin: 10,
            value: true,
        },
    );
    golden_report(
        M13,
        "04 03 1A 08 00",
        Report::Analog {
            pin: 26,
            value: 2048,
        },
    );
    let sonar = |cm| {
        Report::Sonar(Sonar::WithEcho {
            trig: 9,
            echo: 10,
            cm,
        })
    };
    golden_report(M13, "05 0B 09 0A 00 64", sonar(100));
    golden_report(M13, "05 0B 09 0A FF FD", sonar(0xFFFD));
    golden_report(M13, "03 0E 0E FD", Report::Encoder { pin: 14, steps: -3 });
    let i2c_write = |result| Report::I2cWrite {
        port: 0,
        msg_id: 7,
        result,
    };
    golden_report(M13, "04 08 00 07 02", i2c_write(2));
    golden_report(M13, "04 08 00 07 FF", i2c_write(-1));
    golden_report(
        M13,
        "07 0A 00 03 75 01 00 71",
        Report::I2cRead {
            port: 0,
            msg_id: 3,
            reg: 0x75,
            data: &[0x71],
        },
    );
    golden_report(
        M13,
        "07 22 00 01 00 00 2E E0",
        Report::Module {
            module_num: 0,
            report: ModuleReport::HiwonderPositions(ServoPositions::from_raw(&[0, 0x2E, 0xE0])),
        },
    );
    golden_report(M13, "02 00 41", Report::LoopBack { byte: b'A' });
    golden_report(M13, "04 63 1E 00 01", Report::Debug { id: 30, value: 1 });
}

#[test]
fn golden_report_meanings() {
    let events = decode_reports(M13, &hex("05 0B 09 0A FF FD 05 0B 09 0A 00 64"));
    let readings: Vec<_> = events
        .iter()
        .map(|e| match e.as_ref().unwrap().2.message() {
            Report::Sonar(s) => s.reading(),
            ref other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        readings,
        [
            SonarReading::OutOfRange,
            SonarReading::Distance {
                hundredths_cm: 10000
            }
        ]
    );
    let events = decode_reports(M13, &hex("07 22 00 01 00 00 2E E0"));
    let Report::Module {
        report: ModuleReport::HiwonderPositions(p),
        ..
    } = events[0].as_ref().unwrap().2.message()
    else {
        panic!("{events:?}")
    };
    let positions: Vec<_> = p.iter().map(|p| (p.idx, p.centideg)).collect();
    assert_eq!(positions, [(0, 12000)]);
    assert_eq!(
        events[0].as_ref().unwrap().2.message(),
        Report::Module {
            module_num: 0,
            report: ModuleReport::HiwonderPositions(ServoPositions::from_raw(&[0, 0x2E, 0xE0][..]))
        }
    );
    // The boot id is 0..=99: the placeholder `BB` read as hex is no PONG.
    assert!(decode_reports(M13, &hex("03 20 07 BB"))
        .iter()
        .all(|e| e.is_err()));
}

#[test]
fn golden_firmware_reports_other_dialects() {
    golden_report(
        M12,
        "03 05 01 02",
        Report::FirmwareVersion { major: 1, minor: 2 },
    );
    golden_report(
        UP,
        "03 05 01 01",
        Report::FirmwareVersion { major: 1, minor: 1 },
    );
    assert_eq!(Dialect::from_firmware_version(1, 2), Some(M12));
    assert_eq!(M13.firmware_version(), (1, 3));
}

#[test]
fn golden_mirte12_sensors() {
    // Spec §10.1: the mirte 1.2 Python client adds a VEML6040 on port 1 with
    // the short form (num 0, type 4, one settings byte).
    let veml = Command::SensorNew(SensorNew::AddMirte12 {
        sensor_num: 0,
        sensor_type: SensorType::Veml6040,
        settings: List::from_slice(&[1]).unwrap(),
    });
    golden_command(M12, "04 1f 00 04 01", veml);
    // No settings, and all six.
    golden_command(
        M12,
        "03 1f 02 04",
        Command::SensorNew(SensorNew::AddMirte12 {
            sensor_num: 2,
            sensor_type: SensorType::Veml6040,
            settings: List::new(),
        }),
    );
    golden_command(
        M12,
        "09 1f 01 06 01 40 00 00 00 00",
        Command::SensorNew(SensorNew::AddMirte12 {
            sensor_num: 1,
            sensor_type: SensorType::Ina226,
            settings: List::from_slice(&[1, 0x40, 0, 0, 0, 0]).unwrap(),
        }),
    );
    // The report: 4 × u16 little-endian R, G, B, W.
    golden_report(
        M12,
        "0b 14 00 04 10 27 20 4e 30 75 40 9c",
        Report::Sensor {
            sensor_num: 0,
            reading: SensorReading::Veml6040 {
                r: 10000,
                g: 20000,
                b: 30000,
                w: 40000,
            },
        },
    );
    // Each layout in its own dialect only.
    assert!(veml.to_buf_in(M13).is_err());
    assert!(Command::SensorNew(SensorNew::Check { sensor_type: 4 })
        .to_buf_in(M12)
        .is_err());
    // Types above 6, more than 6 settings bytes and other sensors' reports
    // are not mirte 1.2's.
    for bad in [
        "04 1f 00 07 01",
        "0a 1f 00 04 01 02 03 04 05 06 07",
        "07 14 00 01 00 00 00 01",
        "0a 14 00 04 10 27 20 4e 30 75 40",
    ] {
        let frame = hex(bad);
        assert!(
            Command::parse_in(&frame, M12).is_err() && Report::parse_in(&frame, M12).is_err(),
            "{bad}"
        );
    }
    // The owned form of a decoded report keeps mirte 1.2's reading.
    let bytes = hex("0b 14 00 04 10 27 20 4e 30 75 40 9c");
    let events = decode_reports(M12, &bytes);
    let (_, _, ref owned) = events[0].unwrap();
    assert_eq!(owned.dialect(), M12);
    assert_eq!(&owned[..], &bytes[..]);
}

#[test]
fn golden_upstream() {
    golden_command(
        UP,
        "06 0B 00 68 75 01 00",
        Command::I2cReadUpstream {
            port: 0,
            addr: 0x68,
            reg: 0x75,
            len: 1,
            no_stop: 0,
        },
    );
    golden_report(
        UP,
        "06 0A 00 68 75 01 71",
        Report::I2cReadUpstream {
            port: 0,
            addr: 0x68,
            reg: 0x75,
            data: &[0x71],
        },
    );
    let sonar = Sonar::CmHundredths {
        trig: 9,
        cm: 12,
        hundredths: 34,
    };
    golden_report(UP, "04 0B 09 0C 22", Report::Sonar(sonar));
    assert_eq!(
        sonar.reading(),
        SonarReading::Distance {
            hundredths_cm: 1234
        }
    );
}

#[test]
fn dialect_layouts_differ_where_spec_10_says() {
    // mirte 1.2: sonar as metres and centimetres, encoder without pulls.
    golden_report(
        M12,
        "04 0B 09 01 17",
        Report::Sonar(Sonar::MetresCm {
            trig: 9,
            m: 1,
            cm: 23,
        }),
    );
    golden_command(
        M12,
        "04 1E 01 05 00",
        Command::EncoderNew {
            kind: EncoderKind::Single,
            pin_a: 5,
            pin_b: 0,
            pulls: None,
        },
    );
    // mirte 1.3 builds of 2024-09..2025-11: sonar without the echo pin.
    golden_report(
        M13,
        "04 0B 09 00 64",
        Report::Sonar(Sonar::TrigOnly { trig: 9, cm: 100 }),
    );
    // Analog pins are ADC numbers before mirte 1.3.
    golden_command(
        M12,
        "06 01 00 05 00 05 01",
        Command::SetPinMode {
            pin: 0,
            mode: PinMode::AnalogInput {
                differential: 5,
                report: true,
            },
        },
    );
    // upstream: I2C write without msg_id; report 8 is I2C_WRITE_FAILED.
    golden_command(
        UP,
        "07 0C 00 3C 02 00 00 AF",
        Command::I2cWriteUpstream {
            port: 0,
            addr: 0x3C,
            no_stop: 0,
            data: &[0x00, 0xAF],
        },
    );
    golden_report(
        UP,
        "04 08 01 3C 00",
        Report::I2cWriteFailed {
            port: 1,
            addr: 0x3C,
            stale: 0,
        },
    );
}

#[test]
fn encoder_refuses_what_firmware_mishandles() {
    let enc = |d: Dialect, c: Command<'_>| c.encode_in(d, &mut [0u8; 64]);
    let range = |field| Err(EncodeError::OutOfRange { field });
    let not_here = Err(EncodeError::Inconsistent {
        what: "the command does not exist in this dialect",
    });
    // Ids the dialect lacks: PING upstream, GET_ID in mirte 1.2.
    assert_eq!(enc(UP, Command::Ping { counter: 1 }), not_here);
    assert_eq!(enc(M12, Command::GetId), not_here);
    // Ids the firmware has as empty stubs: MODULE_DATA in mirte 1.2.
    assert_eq!(
        enc(
            M12,
            Command::ModuleData {
                module_num: 0,
                data: &[1]
            }
        ),
        Err(EncodeError::Inconsistent {
            what: "the command does nothing in this dialect's firmware"
        })
    );
    // Pins ≥ 30.
    assert_eq!(
        enc(
            M13,
            Command::DigitalWrite {
                pin: 30,
                value: true
            }
        ),
        range("pin")
    );
    // Per-command maxima.
    assert_eq!(
        enc(
            M13,
            Command::I2cWrite {
                port: 0,
                addr: 1,
                msg_id: 0,
                no_stop: 0,
                data: &[0; 25]
            }
        ),
        Err(EncodeError::TooLong { len: 25, max: 24 })
    );
    assert_eq!(
        enc(
            M13,
            Command::I2cRead {
                port: 0,
                addr: 1,
                msg_id: 0,
                reg: 0,
                len: 58,
                no_stop: 0
            }
        ),
        range("len")
    );
    assert_eq!(
        enc(
            M13,
            Command::SpiWrite {
                port: 0,
                data: &[0; 28]
            }
        ),
        Err(EncodeError::TooLong { len: 28, max: 27 })
    );
    assert_eq!(
        enc(
            M13,
            Command::ModuleData {
                module_num: 0,
                data: &[0; 29]
            }
        ),
        Err(EncodeError::TooLong { len: 29, max: 28 })
    );
    assert_eq!(
        enc(
            M13,
            Command::InitNeoPixels {
                pin: 2,
                count: 101,
                rgb: Default::default()
            }
        ),
        range("count")
    );
    // Multi-pin PWM exists only in mirte 1.3.
    assert_eq!(
        enc(M12, Command::PwmWrite(pwm(&[(1, 2), (3, 4)]))),
        Err(EncodeError::TooLong { len: 2, max: 1 })
    );
    // MODIFY_REPORTING digital indexes pin − 26 in mirte 1.3.
    assert_eq!(
        enc(
            M13,
            Command::ModifyReporting(robowire::telemetrix::ModifyReporting::EnableDigital {
                pin: 3
            })
        ),
        range("pin")
    );
    // Analog pins by dialect.
    let analog = |pin| Command::SetPinMode {
        pin,
        mode: PinMode::AnalogInput {
            differential: 1,
            report: true,
        },
    };
    assert_eq!(enc(M13, analog(0)), range("pin"));
    assert_eq!(enc(M12, analog(26)), range("pin"));
    assert_eq!(enc(M13, analog(30)), Ok(7));
    // The I2C layout must match the dialect.
    assert!(enc(
        UP,
        Command::I2cWrite {
            port: 0,
            addr: 1,
            msg_id: 0,
            no_stop: 0,
            data: &[1]
        }
    )
    .is_err());
    // Module init at most 26 bytes (Hiwonder: 4 + 22 ids).
    let hiwonder = |n: usize| {
        enc(
            M13,
            Command::ModuleNew(ModuleNew::Add {
                module_num: 0,
                init: ModuleInit::HiwonderServo {
                    uart: 0,
                    rx: 1,
                    tx: 0,
                    bus_ids: &[1u8; 30][..n],
                },
            }),
        )
    };
    assert_eq!(hiwonder(22), Ok(31));
    assert_eq!(hiwonder(23), Err(EncodeError::TooLong { len: 27, max: 26 }));
    // Output buffer too small: nothing written.
    let mut out = [0xEEu8; 2];
    assert_eq!(
        Command::Ping { counter: 1 }.encode(&mut out),
        Err(EncodeError::BufferTooSmall {
            needed: 3,
            available: 2
        })
    );
    assert_eq!(out, [0xEE; 2]);
    // Sensor settings are at most 6 bytes.
    assert_eq!(
        SensorNew::add(0, SensorType::Hx711, &[0; 7]),
        Err(EncodeError::TooLong { len: 7, max: 6 })
    );
    assert_eq!(ModuleType::from_u8(3), Some(ModuleType::Ssd1306));
}

#[test]
fn report_encoder_refuses_what_decoder_rejects() {
    let enc = |d: Dialect, r: Report<'_>| r.encode_in(d, &mut [0u8; 300]);
    assert!(enc(M13, Report::Encoder { pin: 1, steps: 0 }).is_err());
    assert!(enc(
        M13,
        Report::Pong {
            counter: 0,
            boot_id: 100
        }
    )
    .is_err());
    assert!(enc(
        M13,
        Report::Unknown {
            id: 2,
            payload: &[0, 1]
        }
    )
    .is_err());
    assert_eq!(
        enc(
            M13,
            Report::Unknown {
                id: 7,
                payload: &[1]
            }
        ),
        Ok(3)
    );
    assert!(enc(
        UP,
        Report::Sonar(Sonar::WithEcho {
            trig: 1,
            echo: 2,
            cm: 3
        })
    )
    .is_err());
    assert!(enc(
        M13,
        Report::Sonar(Sonar::WithEcho {
            trig: 1,
            echo: 2,
            cm: 1000
        })
    )
    .is_err());
    assert!(enc(
        M13,
        Report::Module {
            module_num: 0,
            report: ModuleReport::HiwonderPositions(ServoPositions::from_raw(&[1, 2][..]))
        }
    )
    .is_err());
    let positions = ServoPositions::from_raw(&[0, 0x2E, 0xE0]);
    let owned: ReportBuf = Report::Module {
        module_num: 0,
        report: ModuleReport::HiwonderPositions(positions),
    }
    .to_buf()
    .unwrap();
    assert_eq!(owned.to_vec(), hex("07 22 00 01 00 00 2E E0"));
}

/// Every golden report frame of spec §12 (mirte 1.3), with the spec's `BB`
/// boot id replaced by a valid one.
const REPORT_FRAMES: &[&str] = &[
    "03 05 01 03",
    "09 06 b0 b1 b2 b3 b4 b5 00 00",
    "03 20 07 2A",
    "02 23 05",
    "02 24 05",
    "05 25 05 01 01 03",
    "0C 25 01 01 1E 0C 0E 05 1A 1B 1C 1D 1E",
    "06 25 1E 01 04 02 01",
    "04 25 0D 01 04",
    "03 25 20 01",
    "03 25 32 00",
    "04 15 00 02 01",
    "04 15 00 00 00",
    "04 21 00 01 01",
    "03 02 0A 01",
    "04 03 1A 08 00",
    "05 0B 09 0A 00 64",
    "05 0B 09 0A FF FD",
    "03 0E 0E FD",
    "04 08 00 07 02",
    "04 08 00 07 FF",
    "07 0A 00 03 75 01 00 71",
    "07 22 00 01 00 00 2E E0",
    "02 00 41",
    "04 63 1E 00 01",
];

const COMMAND_FRAMES: &[&str] = &[
    "01 05",
    "02 20 07",
    "04 01 0A 03 01",
    "06 01 1A 05 00 05 01",
    "07 03 0F 05 DC 10 05 DC",
    "05 1E 02 0E 0F 01",
    "08 0C 00 3C 07 02 00 00 AF",
    "07 0B 00 68 03 75 01 00",
    "0A 1F 01 00 06 01 40 00 00 00 00",
    "0A 21 01 00 01 00 01 00 02 01 02",
    "09 22 00 01 01 00 2E E0 01 F4",
];

/// The golden frames joined with garbage (including `00` runs and bytes that
/// look like length bytes) between them.
fn garbage_stream(frames: &[&str]) -> Vec<u8> {
    let garbage = [
        &[][..],
        &[0x00, 0x00],
        &[0xFF, 0x07],
        &[0x05],
        &[0x22, 0x01],
        &[0x03, 0x40],
    ];
    let mut out = Vec::new();
    for (i, f) in frames.iter().enumerate() {
        out.extend_from_slice(garbage[i % garbage.len()]);
        out.extend(hex(f));
    }
    out.extend_from_slice(&[0x09, 0x06, 0xb0]);
    out
}

#[test]
fn every_golden_report_is_found_in_garbage() {
    let input = garbage_stream(REPORT_FRAMES);
    let frames: Vec<Vec<u8>> = decode_reports(M13, &input)
        .into_iter()
        .filter_map(Result::ok)
        .map(|(offset, len, _)| input[offset as usize..offset as usize + len].to_vec())
        .collect();
    let expected: Vec<Vec<u8>> = REPORT_FRAMES.iter().map(|f| hex(f)).collect();
    assert_eq!(frames, expected);
}

#[test]
fn every_golden_command_is_found_in_garbage() {
    let input = garbage_stream(COMMAND_FRAMES);
    let frames: Vec<Vec<u8>> = decode_commands(M13, &input)
        .into_iter()
        .filter_map(Result::ok)
        .map(|(offset, len, _)| input[offset as usize..offset as usize + len].to_vec())
        .collect();
    let expected: Vec<Vec<u8>> = COMMAND_FRAMES.iter().map(|f| hex(f)).collect();
    assert_eq!(frames, expected);
}

#[test]
fn garbage_that_forms_a_valid_frame_is_not_detectable() {
    // Without a checksum, `03 02` followed by a loopback frame `02 00 41`
    // reads as DIGITAL pin 2 low, and the loopback frame is lost.
    let events = decode_reports(M13, &hex("03 02 02 00 41"));
    let frames: Vec<_> = events.into_iter().filter_map(Result::ok).collect();
    assert_eq!(frames.len(), 1);
    assert_eq!((frames[0].0, frames[0].1), (0, 4));
    assert_eq!(
        frames[0].2.message(),
        Report::Digital {
            pin: 2,
            value: false
        }
    );
}

#[test]
fn chunking_invariance_reports() {
    let input = garbage_stream(REPORT_FRAMES);
    let whole = decode_reports(M13, &input);
    assert!(whole.iter().filter(|e| e.is_ok()).count() >= REPORT_FRAMES.len());
    for i in 0..=input.len() {
        let mut dec = HostDecoder::new(Framing::<Host>::new());
        let (a, b) = input.split_at(i);
        assert_eq!(collect(&mut dec, &[a, b]), whole, "split at {i}");
    }
    // Three pieces, every pair of split points over a shorter input.
    let short = &input[..80];
    let whole = decode_reports(M13, short);
    for i in 0..=short.len() {
        for j in i..=short.len() {
            let mut dec = HostDecoder::new(Framing::<Host>::new());
            let parts = [&short[..i], &short[i..j], &short[j..]];
            assert_eq!(collect(&mut dec, &parts), whole, "split at {i}, {j}");
        }
    }
}

#[test]
fn chunking_invariance_commands() {
    let input = garbage_stream(COMMAND_FRAMES);
    let whole = decode_commands(M13, &input);
    for i in 0..=input.len() {
        for j in (i..=input.len()).step_by(7) {
            let mut dec = DeviceDecoder::new(Framing::<Device>::new());
            let parts = [&input[..i], &input[i..j], &input[j..]];
            assert_eq!(collect(&mut dec, &parts), whole, "split at {i}, {j}");
        }
    }
}

#[test]
fn every_proper_prefix_is_incomplete() {
    for f in REPORT_FRAMES {
        let frame = hex(f);
        for n in 1..frame.len() {
            let mut dec = HostDecoder::new(Framing::<Host>::new());
            let mut input = &frame[..n];
            assert!(dec.decode(&mut input).is_none(), "{f} prefix {n}");
            assert_eq!(dec.buffered(), n);
            let first = dec.finish().map(|e| e.map(|f| f.offset));
            assert_eq!(
                first,
                Some(Err(Rejected {
                    offset: 0,
                    error: Error::Truncated { len: n }
                })),
                "{f} prefix {n}"
            );
        }
    }
    for f in COMMAND_FRAMES {
        let frame = hex(f);
        for n in 1..frame.len() {
            let mut dec = DeviceDecoder::new(Framing::<Device>::new());
            let mut input = &frame[..n];
            assert!(dec.decode(&mut input).is_none(), "{f} prefix {n}");
            let first = dec.finish().map(|e| e.map(|f| f.offset));
            assert_eq!(
                first,
                Some(Err(Rejected {
                    offset: 0,
                    error: Error::Truncated { len: n }
                }))
            );
        }
    }
}

#[test]
fn push_byte_at_a_time_equals_whole() {
    let input = garbage_stream(REPORT_FRAMES);
    let whole = decode_reports(M13, &input);
    let mut dec = HostDecoder::new(Framing::<Host>::new());
    let mut got = Vec::new();
    let map = |e: robowire::Event<'_, Report<'_>, Error>| match e {
        Ok(f) => Ok((f.offset, f.raw.len(), f.message.to_buf().unwrap())),
        Err(r) => Err((r.offset, r.error)),
    };
    for &b in &input {
        if let Some(e) = dec.push(b) {
            got.push(map(e));
        }
        while let Some(e) = dec.poll() {
            got.push(map(e));
        }
    }
    while let Some(e) = dec.finish() {
        got.push(map(e));
    }
    assert_eq!(got, whole);
    let stats = dec.stats();
    assert_eq!(stats.bytes, input.len() as u64);
    assert_eq!(stats.bytes, stats.frame_bytes + stats.skipped);
}

#[test]
fn lenient_mode_skips_unknown_ids_only_before_a_known_frame() {
    // Id 7 (never sent) and id 0x50: unknown in mirte 1.3.
    let input = hex("02 07 01  03 02 0A 01  04 50 01 02 03  00 00  02 00 41  03 51 01 02");
    let strict = decode_reports(M13, &input);
    assert_eq!(strict.iter().filter(|e| e.is_ok()).count(), 2);
    let mut dec = robowire::telemetrix::LenientHostDecoder::new(Framing::<Host>::new().lenient());
    let events = collect(&mut dec, &[&input]);
    let oks: Vec<_> = events
        .iter()
        .filter_map(|e| e.as_ref().ok())
        .map(|(o, l, m)| (*o, *l, m.id()))
        .collect();
    // The trailing unknown frame has no known frame after it: truncated.
    assert_eq!(oks, [(0, 3, 7), (3, 4, 2), (7, 5, 0x50), (14, 3, 0)]);
    assert!(matches!(
        events[1].as_ref().unwrap().2.message(),
        Report::Digital {
            pin: 10,
            value: true
        }
    ));
    assert_eq!(
        events[0].as_ref().unwrap().2.message(),
        Report::Unknown {
            id: 7,
            payload: &[1][..]
        }
    );
}

// ---------------------------------------------------------------------------
// Corruption: measured recovery against an ideal decoder.

/// Tiny xorshift generator: seeded, reproducible.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn byte(&mut self) -> u8 {
        self.next() as u8
    }
}

/// A realistic core-0 report (digital, analog, sonar, encoder, PONG, I2C,
/// sensor) or a core-1 one (Hiwonder positions, DEBUG_PRINT).
fn random_report(rng: &mut Rng, core1: bool) -> Vec<u8> {
    let r: Report<'_> = if core1 {
        match rng.below(3) {
            0 => Report::Debug {
                id: 30,
                value: rng.next() as u16,
            },
            _ => {
                let k = 1 + rng.below(4) as usize;
                let raw: Vec<u8> = (0..k)
                    .flat_map(|i| {
                        let c = (rng.below(24001) as u16).to_be_bytes();
                        [i as u8, c[0], c[1]]
                    })
                    .collect();
                let report = Report::Module {
                    module_num: 0,
                    report: ModuleReport::HiwonderPositions(ServoPositions::from_raw(&raw[..])),
                };
                return encode_report(M13, &report);
            }
        }
    } else {
        match rng.below(8) {
            0 | 1 => Report::Digital {
                pin: rng.below(30) as u8,
                value: rng.below(2) == 1,
            },
            2 | 3 => Report::Analog {
                pin: 26 + rng.below(5) as u8,
                value: rng.below(4096) as u16,
            },
            4 => Report::Sonar(Sonar::WithEcho {
                trig: rng.below(30) as u8,
                echo: rng.below(30) as u8,
                cm: rng.below(400) as u16,
            }),
            5 => Report::Encoder {
                pin: rng.below(30) as u8,
                steps: (1 + rng.below(40) as i8) * if rng.below(2) == 0 { 1 } else { -1 },
            },
            6 => Report::Pong {
                counter: rng.byte(),
                boot_id: rng.below(100) as u8,
            },
            _ => {
                let data = [rng.byte(), rng.byte()];
                return encode_report(
                    M13,
                    &Report::I2cRead {
                        port: 0,
                        msg_id: rng.byte(),
                        reg: rng.byte(),
                        data: &data,
                    },
                );
            }
        }
    };
    encode_report(M13, &r)
}

/// Where a byte came from: frame `f`'s byte `i`, or garbage.
#[derive(Clone, Copy, PartialEq)]
enum Tag {
    Frame(usize, usize),
    Garbage,
}

struct Tagged {
    bytes: Vec<u8>,
    tags: Vec<Tag>,
    /// Frame lengths, by frame number.
    lens: Vec<usize>,
}

impl Tagged {
    fn frames(rng: &mut Rng, n: usize, core1: bool, first: usize) -> Self {
        let mut t = Tagged {
            bytes: Vec::new(),
            tags: Vec::new(),
            lens: vec![0; first],
        };
        for f in first..first + n {
            let frame = random_report(rng, core1);
            t.lens.push(frame.len());
            for (i, b) in frame.into_iter().enumerate() {
                t.bytes.push(b);
                t.tags.push(Tag::Frame(f, i));
            }
        }
        t
    }

    /// Start offsets of frames whose bytes are all present, contiguous and in
    /// order: what an ideal decoder (one that knew the corruption) recovers.
    fn intact(&self) -> Vec<(u64, usize)> {
        let mut out = Vec::new();
        for (pos, tag) in self.tags.iter().enumerate() {
            if let Tag::Frame(f, 0) = *tag {
                let len = self.lens[f];
                let whole = (0..len).all(|i| self.tags.get(pos + i) == Some(&Tag::Frame(f, i)));
                if whole {
                    out.push((pos as u64, len));
                }
            }
        }
        out
    }
}

struct Recovery {
    ideal: usize,
    recovered: usize,
    spurious: usize,
}

fn measure(t: &Tagged) -> Recovery {
    let intact = t.intact();
    let mut dec = HostDecoder::new(Framing::<Host>::new());
    let found: Vec<(u64, usize)> = collect(&mut dec, &[&t.bytes])
        .into_iter()
        .filter_map(Result::ok)
        .map(|(o, l, _)| (o, l))
        .collect();
    let recovered = intact.iter().filter(|f| found.contains(f)).count();
    Recovery {
        ideal: intact.len(),
        recovered,
        spurious: found.iter().filter(|f| !intact.contains(f)).count(),
    }
}

fn report(name: &str, r: &Recovery) -> f64 {
    let share = r.recovered as f64 / r.ideal as f64;
    println!(
        "{name}: recovered {}/{} intact frames ({:.2}%), spurious frames {}",
        r.recovered,
        r.ideal,
        share * 100.0,
        r.spurious
    );
    share
}

const FRAMES: usize = 20_000;

#[test]
fn corruption_inserted_garbage() {
    let mut rng = Rng(0x7e1e_3e7a_1c00_0001);
    let mut t = Tagged::frames(&mut rng, FRAMES, false, 0);
    // 1000 bursts of 1..=8 random bytes at random places (often inside frames).
    for _ in 0..1000 {
        let at = rng.below(t.bytes.len() as u64 + 1) as usize;
        for _ in 0..1 + rng.below(8) {
            t.bytes.insert(at, rng.byte());
            t.tags.insert(at, Tag::Garbage);
        }
    }
    let r = measure(&t);
    let share = report("inserted garbage", &r);
    assert!(r.ideal > FRAMES - 1000);
    // Measured: 100.00 %, 283 spurious frames.
    assert!(share >= 0.995, "recovered only {share}");
    assert!(r.spurious <= 320, "{} spurious frames", r.spurious);
}

#[test]
fn corruption_dropped_bytes() {
    let mut rng = Rng(0x0d20_99ed_b17e_5eed);
    let mut t = Tagged::frames(&mut rng, FRAMES, false, 0);
    for _ in 0..1000 {
        let at = rng.below(t.bytes.len() as u64) as usize;
        t.bytes.remove(at);
        t.tags.remove(at);
    }
    let r = measure(&t);
    let share = report("dropped bytes", &r);
    // Measured: 98.64 %, 401 spurious frames.
    assert!(share >= 0.98, "recovered only {share}");
    assert!(r.spurious <= 450, "{} spurious frames", r.spurious);
}

#[test]
fn corruption_two_cores_interleaved() {
    let mut rng = Rng(0x2c0e_5000_1eaf_0042);
    let mut t = Tagged::frames(&mut rng, FRAMES, false, 0);
    let core1 = Tagged::frames(&mut rng, 2000, true, FRAMES);
    t.lens.extend_from_slice(&core1.lens[FRAMES..]);
    // Each core-1 frame lands at a random byte of core 0's stream; a third of
    // them are themselves split by a run of core-0 bytes.
    let mut pos = 0;
    for f in 0..2000 {
        let start = core1
            .tags
            .iter()
            .position(|&g| g == Tag::Frame(FRAMES + f, 0))
            .unwrap();
        let len = core1.lens[FRAMES + f];
        pos = (pos + 1 + rng.below(2 * t.bytes.len() as u64 / 2000) as usize).min(t.bytes.len());
        let split = if rng.below(3) == 0 {
            1 + rng.below(len as u64 - 1) as usize
        } else {
            len
        };
        let gap = 1 + rng.below(6) as usize;
        for i in 0..len {
            let at = if i < split { pos + i } else { pos + i + gap };
            let at = at.min(t.bytes.len());
            t.bytes.insert(at, core1.bytes[start + i]);
            t.tags.insert(at, core1.tags[start + i]);
        }
        pos += len + gap;
    }
    let r = measure(&t);
    let share = report("two cores interleaved", &r);
    // Measured: 98.26 %, 1115 spurious frames.
    assert!(share >= 0.975, "recovered only {share}");
    assert!(r.spurious <= 1250, "{} spurious frames", r.spurious);
}
