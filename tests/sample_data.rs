//! The sample captures in `tests/data/` are exactly what the tile simulator
//! (`examples/tile_sim`) generates, and they look like what a tile sends.

#[path = "../examples/tile_sim/sim.rs"]
mod sim;

use robowire::omnitiles::{DatagramDecoder, Decoder, Framing, Layout, Layouts, Packet, Telemetry};
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
    assert_eq!(captures.len(), 5);
    for capture in captures {
        let committed = data(capture.name);
        assert!(
            committed == capture.bytes,
            "tests/data/{} differs from what `cargo run --example tile_sim -- --tests-data` generates",
            capture.name
        );
    }
}

fn telemetry(framing: Framing, bytes: &[u8]) -> Vec<Telemetry> {
    let mut decoder = Decoder::new(framing);
    let mut events: Vec<_> = decoder.feed(bytes).collect();
    events.extend(decoder.flush());
    events
        .into_iter()
        .filter_map(|event| match event.ok()?.message {
            Packet::Telemetry(t) => Some(t),
            Packet::Command(_) => None,
        })
        .collect()
}

#[test]
fn ble_telemetry_is_realistic() {
    let frames = telemetry(
        Framing::telemetry(Layouts::only(Layout::Ble53)),
        &data("ble_telemetry.bin"),
    );
    // 300 notifications; the line noise corrupts a couple of them.
    assert_eq!(frames.len(), 298);
    let mut no_tof = 0;
    let mut anchor3_unknown = 0;
    for t in &frames {
        // Positions stay inside the clamps: M1 20-115 mm, M2 25-85 mm of
        // 150 and 100 mm strokes (raw 0..4095).
        let m1 = t.m1_pos.unwrap();
        let m2 = t.m2_pos.unwrap();
        assert!((500..=3200).contains(&m1), "m1 {m1}");
        assert!((980..=3520).contains(&m2), "m2 {m2}");
        let uwb = t.uwb.unwrap();
        for d in uwb.iter().flatten() {
            assert!((1500..=6000).contains(d), "uwb {d}");
        }
        anchor3_unknown += usize::from(uwb[3].is_none());
        match t.tof.unwrap() {
            None => no_tof += 1,
            Some(mm) => assert!(mm == 8190 || (250..=650).contains(&mm), "tof {mm}"),
        }
        // Gravity: about 9.8 m/s² in total, mostly along z.
        let imu = t.imu.unwrap();
        let g = (imu.ax * imu.ax + imu.ay * imu.ay + imu.az * imu.az).sqrt();
        assert!((9.6..10.0).contains(&g), "|a| {g}");
        assert!(imu.az > 9.0, "az {}", imu.az);
        assert!(imu.gz.abs() < 0.2, "gz {}", imu.gz);
        // The inverted pots read 3357 - raw.
        let adcs = t.m1_adcs.unwrap();
        assert!((i32::from(adcs[0]) + i32::from(adcs[2]) - 3357).abs() < 30);
    }
    assert!(no_tof > 0, "some ToF read errors (0xFFFF)");
    assert!(
        (60..=80).contains(&anchor3_unknown),
        "anchor 3 unmeasured for the first two seconds: {anchor3_unknown}"
    );
    // The positions move along the strokes.
    let first = frames[0].m1_pos.unwrap();
    assert!(frames
        .iter()
        .any(|t| t.m1_pos.unwrap().abs_diff(first) > 1000));
}

#[test]
fn other_captures_decode() {
    let spi = telemetry(
        Framing::telemetry(Layouts::only(Layout::Spi45)),
        &data("spi_telemetry.bin"),
    );
    assert_eq!(spi.len(), 64);
    assert!(spi.iter().all(|t| t.uwb.is_none() && t.imu.is_some()));

    let mut commands = Decoder::new(Framing::commands());
    let bytes = data("host_commands.bin");
    let count = commands.feed(&bytes).filter(Result::is_ok).count()
        + commands.flush().filter(Result::is_ok).count();
    assert!((230..=240).contains(&count), "{count} commands");

    let mut datagrams = DatagramDecoder::new(Framing::ANY);
    let text = String::from_utf8(data("ble_notifications.hex")).unwrap();
    let mut frames = 0;
    for line in text.lines() {
        let bytes: Vec<u8> = line
            .split(' ')
            .map(|b| u8::from_str_radix(b, 16).unwrap())
            .collect();
        assert_eq!(bytes.len(), 53, "one 53-byte notification per line");
        frames += datagrams.decode(&bytes).filter(Result::is_ok).count();
    }
    assert_eq!(text.lines().count(), 80);
    assert_eq!(frames, 78);
}
