//! `robowire decode P | robowire encode P` writes exactly the bytes of the
//! frames decode found, for every protocol, side and dialect: on every sample
//! capture in tests/data, on a stream of the frames real peers send that the
//! encoder refuses without their marker (`quirk`), and on generated noise
//! with those frames inside.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data, run};
use serde_json::Value;

/// The bytes of a capture: hex text for `.hex` files, raw otherwise.
fn capture(name: &str) -> Vec<u8> {
    let bytes = std::fs::read(data(name)).unwrap();
    if name.ends_with(".hex") {
        cli_common::hex(std::str::from_utf8(&bytes).unwrap())
    } else {
        bytes
    }
}

/// Decode `input` with `decode_args`, encode the lines with `encode_args`,
/// and compare with the decoded frames' own bytes. Returns the lines. Some
/// decodes read a capture from the other side on purpose, which is mostly
/// noise: `--allow-noise` keeps their exit status 0, since what is checked
/// here is that every line printed re-encodes.
fn round_trip(decode_args: &[&str], encode_args: &[&str], input: &[u8]) -> Vec<Value> {
    let decode_args = &[decode_args, &["--allow-noise"]].concat()[..];
    let decoded = run(decode_args, input);
    assert_eq!(decoded.code, 0, "{decode_args:?}: {}", decoded.stderr);
    let lines = decoded.json();
    let mut frames = Vec::new();
    for line in &lines {
        let offset = line["offset"].as_u64().unwrap() as usize;
        let len = line["len"].as_u64().unwrap() as usize;
        frames.extend_from_slice(&input[offset..offset + len]);
    }
    let encoded = run(encode_args, &decoded.stdout);
    assert_eq!(
        encoded.code, 0,
        "{decode_args:?} | {encode_args:?}: {}",
        encoded.stderr
    );
    assert!(
        encoded.stdout == frames,
        "{decode_args:?} | {encode_args:?}: {} bytes out, {} bytes of frames",
        encoded.stdout.len(),
        frames.len()
    );
    lines
}

/// Bytes of a small generator (xorshift), the same on every run.
fn noise(seed: u64, n: usize) -> Vec<u8> {
    let mut x = seed | 1;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}

/// `frames` with noise between them, and noise with frames of `frames`
/// written over it at generated places.
fn generated(frames: &[u8]) -> Vec<u8> {
    let mut out = frames.to_vec();
    for seed in 1..=4u64 {
        let mut stream = noise(seed, 4096);
        for (i, at) in noise(seed + 100, 16).iter().enumerate() {
            let at = usize::from(*at) * 15 + i;
            let end = (at + frames.len()).min(stream.len());
            stream[at..end].copy_from_slice(&frames[..end - at]);
        }
        out.extend(stream);
        out.extend_from_slice(frames);
    }
    out
}

/// Whether any line carries `quirk`.
fn has_quirk(lines: &[Value]) -> bool {
    lines.iter().any(|l| l.get("quirk").is_some())
}

#[test]
fn omnitiles_captures_round_trip() {
    for name in [
        "ble_telemetry.bin",
        "host_commands.bin",
        "spi_telemetry.bin",
        "ble_notifications.hex",
        "spi_commands.hex",
    ] {
        let input = capture(name);
        for from in ["tile", "host", "any"] {
            let decode = ["decode", "omnitiles", "--from", from];
            round_trip(&decode, &["encode", "omnitiles"], &input);
            round_trip(&decode, &["encode", "omnitiles"], &generated(&input[..256]));
        }
    }
}

/// getBlocks with sigmap 0 (the official host's empty map; the camera
/// answers ERROR -3) in both forms, amid the capture.
const PIXY2_QUIRKS: &str = "ae c1 20 02 00 00  af c1 20 02 05 00 00 05";

#[test]
fn pixy2_captures_round_trip() {
    let quirks = cli_common::hex(PIXY2_QUIRKS);
    let mut input = capture("pixy2_conversation.hex");
    input.extend_from_slice(&quirks);
    for from in ["host", "device", "any"] {
        let decode = ["decode", "pixy2", "--from", from];
        let lines = round_trip(&decode, &["encode", "pixy2"], &input);
        assert_eq!(has_quirk(&lines), from != "device", "--from {from}");
        round_trip(&decode, &["encode", "pixy2"], &generated(&quirks));
    }
}

/// Every Telemetrix quirk: commands, then the SSD1306 report.
const TELEMETRIX_QUIRKS: &[(&str, &str)] = &[
    (
        "mirte13",
        "03 04 04 02  03 04 02 05  03 02 05 02  03 02 07 ff  05 03 01 00 10 07  \
         06 03 01 00 10 07 08  05 1e 03 02 03 00  05 22 03 03 05 fe",
    ),
    (
        "mirte12",
        "03 04 01 1a  03 04 03 1e  03 02 05 02  04 1e 03 02 03  03 04 00 00",
    ),
    (
        "upstream11",
        "03 04 01 1a  03 04 03 1d  03 02 05 80  03 04 00 00",
    ),
];

#[test]
fn telemetrix_captures_round_trip() {
    for &(dialect, quirks) in TELEMETRIX_QUIRKS {
        let quirks = cli_common::hex(quirks);
        for name in ["telemetrix_commands.hex", "telemetrix_reports.bin"] {
            let mut input = capture(name);
            input.extend_from_slice(&quirks);
            for from in ["host", "pico", "any"] {
                let mut decode = vec!["decode", "telemetrix", "--from", from, "--dialect", dialect];
                let encode = ["encode", "telemetrix", "--dialect", dialect];
                let lines = round_trip(&decode, &encode, &input);
                if from != "pico" {
                    assert!(has_quirk(&lines), "{dialect} --from {from}");
                }
                round_trip(&decode, &encode, &generated(&quirks));
                if from != "host" {
                    decode.push("--lenient");
                    round_trip(&decode, &encode, &input);
                    round_trip(&decode, &encode, &generated(&quirks));
                }
            }
        }
    }
}
