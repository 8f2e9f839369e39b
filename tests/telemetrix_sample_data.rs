//! The Telemetrix sample captures in `tests/data/` are exactly what the
//! simulated session (`examples/pico_sim`) generates, and they look like a
//! host's start-up and a Pico's reports.

#[path = "../examples/pico_sim/sim.rs"]
mod sim;

use robowire::telemetrix::{
    device_decoder, host_decoder, Command, CommandBuf, ModuleReport, Report, ReportBuf,
    SensorReading, Sonar, SONAR_OUT_OF_RANGE,
};
use std::path::Path;

fn data(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn captures_regenerate_byte_for_byte() {
    let captures = sim::captures().unwrap();
    assert_eq!(captures.len(), 2);
    for capture in captures {
        let committed = data(capture.name);
        assert!(
            committed == capture.bytes,
            "tests/data/{} differs from what `cargo run --example pico_sim -- --tests-data` generates",
            capture.name
        );
    }
}

/// Every frame of a decoder's events, and the number of rejections.
fn reports(bytes: &[u8]) -> (Vec<ReportBuf>, usize) {
    let mut decoder = host_decoder();
    let mut events: Vec<_> = decoder.feed(bytes).collect();
    events.extend(decoder.flush());
    let rejected = events.iter().filter(|e| e.is_err()).count();
    let frames = events
        .into_iter()
        .filter_map(|e| e.ok())
        .map(|f| f.message)
        .collect();
    (frames, rejected)
}

fn commands(hex_text: &[u8]) -> Vec<Vec<u8>> {
    std::str::from_utf8(hex_text)
        .unwrap()
        .lines()
        .map(|line| {
            line.split(' ')
                .map(|b| u8::from_str_radix(b, 16).unwrap())
                .collect()
        })
        .collect()
}

#[test]
fn host_start_up_follows_the_spec() {
    let lines = commands(&data("telemetrix_commands.hex"));
    // Spec §8: 15 zero bytes in one write, then one frame per write.
    assert_eq!(lines[0], [0; 15]);
    let mut decoder = device_decoder();
    let mut bufs: Vec<CommandBuf> = Vec::new();
    for line in &lines[1..] {
        let events: Vec<_> = decoder.feed(line).collect();
        assert_eq!(events.len(), 1, "one frame per write: {line:02x?}");
        let frame = events.into_iter().next().unwrap().unwrap();
        assert_eq!(frame.len, line.len());
        bufs.push(frame.message);
    }
    let sent: Vec<Command<'_>> = bufs.iter().map(CommandBuf::message).collect();
    assert_eq!(sent[0], Command::GetFirmwareVersion);
    // FEATURE_CHECK for ids 0..=38, sensor checks 0..=10, module checks 0..=3.
    for (i, c) in sent[1..40].iter().enumerate() {
        assert_eq!(*c, Command::FeatureCheck { msg_type: i as u8 });
    }
    let checks = |want: u8| {
        sent.iter()
            .filter(|c| {
                c.id() == want && matches!(c, Command::SensorNew(_) | Command::ModuleNew(_))
            })
            .count()
    };
    assert_eq!(checks(31), 11 + 2, "11 sensor checks and 2 sensors added");
    assert_eq!(checks(33), 4 + 2, "4 module checks and 2 modules added");
    // Then PINGs every 400 ms, counting up.
    let pings: Vec<u8> = sent
        .iter()
        .filter_map(|c| match c {
            Command::Ping { counter } => Some(*counter),
            _ => None,
        })
        .collect();
    assert_eq!(pings, (0..9).collect::<Vec<u8>>());
    assert!(sent.iter().any(|c| matches!(c, Command::ModuleData { .. })));
}

#[test]
fn reports_are_a_realistic_mix() {
    let (bufs, rejected) = reports(&data("telemetrix_reports.bin"));
    let frames: Vec<Report<'_>> = bufs.iter().map(ReportBuf::message).collect();
    assert_eq!(frames.len(), 217);
    // A little noise: some random bytes and one frame interleaved with a
    // second core's frame.
    assert!((10..=30).contains(&rejected), "{rejected} rejections");
    let count = |f: &dyn Fn(&Report<'_>) -> bool| frames.iter().filter(|r| f(r)).count();
    // Replies to the start-up: the version, 39 feature checks, 11 sensor and
    // 4 module checks, and a PONG for each of the 9 PINGs.
    assert_eq!(frames[0], Report::FirmwareVersion { major: 1, minor: 3 });
    assert_eq!(count(&|r| matches!(r, Report::Feature { .. })), 39);
    assert_eq!(count(&|r| matches!(r, Report::SensorSupported { .. })), 11);
    assert_eq!(count(&|r| matches!(r, Report::ModuleSupported { .. })), 4);
    assert_eq!(count(&|r| matches!(r, Report::Pong { .. })), 9);
    // The button went down and up twice, the bumper once (each input also
    // reports once when it is configured).
    let digital: Vec<(u8, bool)> = frames
        .iter()
        .filter_map(|r| match r {
            Report::Digital { pin, value } => Some((*pin, *value)),
            _ => None,
        })
        .collect();
    assert_eq!(
        digital,
        [
            (10, true),
            (11, true),
            (10, false),
            (10, true),
            (11, false),
            (11, true),
            (10, false),
            (10, true)
        ]
    );
    // Streams of analog, sonar, encoder and sensor reports.
    assert!(count(&|r| matches!(r, Report::Analog { .. })) > 20);
    let mut out_of_range = 0;
    let mut last_cm = u16::MAX;
    for r in &frames {
        match r {
            Report::Sonar(Sonar::WithEcho {
                trig: 9,
                echo: 10,
                cm: SONAR_OUT_OF_RANGE,
            }) => out_of_range += 1,
            Report::Sonar(Sonar::WithEcho { cm, .. }) => {
                // The wall comes closer, give or take the jitter.
                assert!(*cm < last_cm.saturating_add(3), "{cm} after {last_cm}");
                last_cm = *cm;
            }
            Report::Encoder { pin: 14, steps } => assert!((-25..=35).contains(steps)),
            Report::Sensor {
                reading: SensorReading::Ina226 { volts, amps },
                ..
            } => {
                assert!((12.0..12.4).contains(volts), "{volts} V");
                assert!((0.2..1.5).contains(amps), "{amps} A");
            }
            Report::Sensor {
                reading: SensorReading::Vl53l0x { mm },
                ..
            } => assert!((390..430).contains(mm), "{mm} mm"),
            _ => {}
        }
    }
    assert!(out_of_range > 0, "the sonar misses an echo now and then");
    assert!(last_cm < 60, "the wall ends close: {last_cm} cm");
    // The servos move to 9000 and 15000 centidegrees and back.
    let positions: Vec<(u8, u16)> = frames
        .iter()
        .filter_map(|r| match r {
            Report::Module {
                module_num: 0,
                report: ModuleReport::HiwonderPositions(p),
            } => Some(p.iter().map(|p| (p.idx, p.centideg)).collect::<Vec<_>>()),
            _ => None,
        })
        .flatten()
        .collect();
    assert!(positions.contains(&(0, 9000)) && positions.contains(&(1, 15000)));
    assert_eq!(positions.last(), Some(&(0, 12000)));
}
