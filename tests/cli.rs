//! The `robowire` binary: golden vectors, chunking invariance, datagrams,
//! diagnostics, the decode | encode round trip, malformed input, exit codes.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data, data_arg, hex, run, Run};

use std::io::{Read, Write};
use std::process::{Command, Stdio};

fn summary(frames: u64, bytes: u64, skipped: u64, checksum: u64, other: u64) -> String {
    cli_common::summary_line([frames, bytes, skipped, checksum, other, 0])
}

// ---------------------------------------------------------------- golden vectors

/// The specification's golden vectors, commands then telemetry, as one stream.
const GOLDEN_HEX: &str = "\
a5 50 50  a5 30 c8 f8  a5 30 ff 2f  a5 31 ff 30  a5 40 c8 08  a5 41 c8 09
a5 30 00 30  a5 32 32  a5 42 42  a5 33 80 b3  a5 43 00 43  a5 70 0a fb 14 89
a5 70 1e 00 00 8e  a5 70 00 e2 00 52  a5 70 80 7f 00 6f  a5 70 a5 00 00 15  a5 71 71
a5 60 d0 07 e8 03 22
a5 60 d0 07 e8 03 dc 05 c4 09 ff ff b8 0b 91
a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 70
a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 cd cc cc 3d cd cc 4c 3e cd cc 1c 41
0a d7 23 3c 0a d7 a3 bc 8f c2 f5 3c d1 07 d2 07 d3 07 d4 07 e9 03 ea 03 6c
";

const GOLDEN_JSON: [&str; 21] = [
    r#"{"offset":0,"len":3,"type":"ping"}"#,
    r#"{"offset":3,"len":4,"type":"m1_extend","speed":200}"#,
    r#"{"offset":7,"len":4,"type":"m1_extend","speed":255}"#,
    r#"{"offset":11,"len":4,"type":"m1_retract","speed":255}"#,
    r#"{"offset":15,"len":4,"type":"m2_extend","speed":200}"#,
    r#"{"offset":19,"len":4,"type":"m2_retract","speed":200}"#,
    r#"{"offset":23,"len":4,"type":"m1_extend","speed":0}"#,
    r#"{"offset":27,"len":3,"type":"m1_brake"}"#,
    r#"{"offset":30,"len":3,"type":"m2_brake"}"#,
    r#"{"offset":33,"len":4,"type":"m1_set_position","position":128}"#,
    r#"{"offset":37,"len":4,"type":"m2_set_position","position":0}"#,
    r#"{"offset":41,"len":6,"type":"base_velocity","vx":10,"vy":-5,"omega":20}"#,
    r#"{"offset":47,"len":6,"type":"base_velocity","vx":30,"vy":0,"omega":0}"#,
    r#"{"offset":53,"len":6,"type":"base_velocity","vx":0,"vy":-30,"omega":0}"#,
    r#"{"offset":59,"len":6,"type":"base_velocity","vx":-128,"vy":127,"omega":0}"#,
    r#"{"offset":65,"len":6,"type":"base_velocity","vx":-91,"vy":0,"omega":0}"#,
    r#"{"offset":71,"len":3,"type":"base_brake"}"#,
    r#"{"offset":74,"len":7,"type":"telemetry","layout":"pos7","m1_pos":2000,"m2_pos":1000}"#,
    r#"{"offset":81,"len":15,"type":"telemetry","layout":"uwb15","m1_pos":2000,"m2_pos":1000,"uwb":[1500,2500,null,3000]}"#,
    r#"{"offset":96,"len":17,"type":"telemetry","layout":"uwbtof17","m1_pos":2000,"m2_pos":1000,"uwb":[1500,2500,3500,4500],"tof":321}"#,
    concat!(
        r#"{"offset":113,"len":53,"type":"telemetry","layout":"ble53","m1_pos":2000,"m2_pos":1000,"#,
        r#""uwb":[1500,2500,3500,4500],"tof":321,"#,
        r#""imu":{"ax":0.1,"ay":0.2,"az":9.8,"gx":0.01,"gy":-0.02,"gz":0.03},"#,
        r#""m1_adcs":[2001,2002,2003,2004],"m2_adcs":[1001,1002]}"#
    ),
];

#[test]
fn decode_golden_vectors() {
    let r = run(&["decode", "omnitiles", "--hex"], GOLDEN_HEX.as_bytes());
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.lines(), GOLDEN_JSON);
    assert_eq!(r.stderr, summary(21, 166, 0, 0, 0));
    // The same bytes raw, from a file argument and from `-`.
    let raw = hex(GOLDEN_HEX);
    let file = std::env::temp_dir().join(format!("robowire-golden-{}.bin", std::process::id()));
    std::fs::write(&file, &raw).unwrap();
    let from_file = run(&["decode", "omnitiles", file.to_str().unwrap()], b"");
    std::fs::remove_file(&file).unwrap();
    assert_eq!(from_file.lines(), GOLDEN_JSON);
    assert_eq!(
        run(&["decode", "omnitiles", "-"], &raw).lines(),
        GOLDEN_JSON
    );
}

#[test]
fn encode_golden_vectors() {
    let input = GOLDEN_JSON.join("\n");
    let r = run(&["encode", "omnitiles"], input.as_bytes());
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.stdout, hex(GOLDEN_HEX));
    assert_eq!(r.stderr, "");
    // Hex output: one frame per line; offset and len are not needed.
    let r = run(
        &["encode", "omnitiles", "--hex"],
        concat!(
            r#"{"type":"m1_extend","speed":200}"#,
            "\n",
            r#"{"type":"base_velocity","vx":-91,"vy":0,"omega":0,"offset":999,"len":1}"#,
            "\n"
        )
        .as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.text(), "a5 30 c8 f8\na5 70 a5 00 00 15\n");
}

#[test]
fn hex_input_syntax() {
    // Whitespace, commas and 0x prefixes are ignored; digits pair up across them.
    for text in [
        "a5 30 c8 f8",
        "A530C8F8",
        "0xa5, 0x30, 0xC8, 0XF8",
        "a5 3\n0c8f8\n",
        "0xa530 c8f8",
    ] {
        let r = run(&["decode", "omnitiles", "--hex"], text.as_bytes());
        assert_eq!(r.code, 0, "{text}: {}", r.stderr);
        assert_eq!(
            r.lines(),
            [r#"{"offset":0,"len":4,"type":"m1_extend","speed":200}"#],
            "{text}"
        );
    }
    // A lone 0 is a digit, not a prefix.
    let r = run(&["decode", "omnitiles", "--hex"], b"a5 43 0 0 43");
    assert_eq!(
        r.lines(),
        [r#"{"offset":0,"len":4,"type":"m2_set_position","position":0}"#]
    );
}

// ---------------------------------------------------------------- chunking

/// The framings worth checking on each capture.
const CASES: [(&str, &[&str]); 7] = [
    ("ble_telemetry.bin", &[]),
    (
        "ble_telemetry.bin",
        &["--from", "tile", "--layout", "ble53"],
    ),
    (
        "ble_telemetry.bin",
        &["--from", "tile", "--layout", "pos7,uwb15,ble53,spi45"],
    ),
    ("host_commands.bin", &[]),
    ("host_commands.bin", &["--from", "host"]),
    (
        "spi_telemetry.bin",
        &["--from", "tile", "--layout", "spi45"],
    ),
    ("spi_telemetry.bin", &["--layout", "auto,spi45"]),
];

fn decode_file(file: &str, extra: &[&str], chunk: &str) -> Run {
    let path = data_arg(file);
    let mut args = vec!["decode", "omnitiles", "--errors", "--chunk", chunk];
    args.extend_from_slice(extra);
    args.push(&path);
    let r = run(&args, b"");
    assert_eq!(r.code, 0, "{args:?}: {}", r.stderr);
    r
}

#[test]
fn chunk_size_does_not_change_the_output() {
    for (file, extra) in CASES {
        let whole = decode_file(file, extra, "4096");
        assert!(whole.lines().len() > 20, "{file} {extra:?}");
        for chunk in ["1", "2", "7", "53", "100000"] {
            let r = decode_file(file, extra, chunk);
            assert!(
                r.stdout == whole.stdout,
                "{file} {extra:?}: --chunk {chunk} differs from --chunk 4096"
            );
            assert_eq!(r.stderr, whole.stderr, "{file} {extra:?} --chunk {chunk}");
        }
    }
}

#[test]
fn hex_stream_equals_raw_bytes() {
    // ble_notifications.hex read as one stream is the notifications back to back.
    let text = std::fs::read_to_string(data("ble_notifications.hex")).unwrap();
    let raw = hex(&text);
    let path = data_arg("ble_notifications.hex");
    let from_hex = run(&["decode", "omnitiles", "--errors", "--hex", &path], b"");
    let from_raw = run(&["decode", "omnitiles", "--errors"], &raw);
    assert_eq!(from_hex.code, 0);
    assert_eq!(from_hex.stdout, from_raw.stdout);
    assert_eq!(from_hex.stderr, from_raw.stderr);
    let chunked = run(
        &[
            "decode",
            "omnitiles",
            "--errors",
            "--hex",
            "--chunk",
            "3",
            &path,
        ],
        b"",
    );
    assert_eq!(chunked.stdout, from_raw.stdout);
}

// ---------------------------------------------------------------- sample captures

#[test]
fn ble_capture_summary_and_first_frame() {
    let r = decode_file(
        "ble_telemetry.bin",
        &["--from", "tile", "--layout", "ble53"],
        "4096",
    );
    let frames = r.json();
    let (events, telemetry): (Vec<_>, Vec<_>) =
        frames.iter().partition(|v| v.get("error").is_some());
    assert_eq!(telemetry.len(), 298);
    assert!(events.iter().all(|e| e.get("type").is_none()));
    assert_eq!(r.stderr, summary(298, 15920, 126, 2, 7));
    assert_eq!(
        r.lines()[0],
        concat!(
            r#"{"offset":0,"len":53,"type":"telemetry","layout":"ble53","m1_pos":1104,"m2_pos":2852,"#,
            r#""uwb":[4579,3151,3112,null],"tof":448,"imu":{"ax":-1.4454993,"ay":-0.01436521,"#,
            r#""az":9.686341,"gx":-0.004261058,"gy":0.0010652645,"gz":0.08841695},"#,
            r#""m1_adcs":[1103,1107,2255,2252],"m2_adcs":[2854,2851]}"#
        )
    );
    // Without --errors only frames are printed.
    let quiet = run(
        &[
            "decode",
            "omnitiles",
            "--from",
            "tile",
            "--layout",
            "ble53",
            &data_arg("ble_telemetry.bin"),
        ],
        b"",
    );
    assert_eq!(
        quiet.json(),
        telemetry.into_iter().cloned().collect::<Vec<_>>()
    );
}

#[test]
fn from_selects_the_direction() {
    let tile_on_commands = run(
        &[
            "decode",
            "omnitiles",
            "--from",
            "tile",
            &data_arg("host_commands.bin"),
        ],
        b"",
    );
    // Nothing decodes: the wrong direction's status.
    assert_eq!(tile_on_commands.code, 3);
    assert_eq!(tile_on_commands.text(), "");
    let host = run(
        &[
            "decode",
            "omnitiles",
            "--from",
            "host",
            &data_arg("host_commands.bin"),
        ],
        b"",
    );
    let types: Vec<String> = host
        .json()
        .iter()
        .map(|v| v["type"].as_str().unwrap().to_owned())
        .collect();
    assert_eq!(types.len(), 234);
    assert!(types.iter().all(|t| t != "telemetry"));
    assert_eq!(&types[..3], ["ping", "base_velocity", "m1_retract"]);
    // The 45-byte SPI frame is not a documented layout: only --layout spi45
    // decodes it. The documented layouts find three false frames: the SPI
    // frame at 5376 has the sum 0x80, so its 53-byte window (frame plus
    // padding) sums to 2 x 0x80 = 0x00, which the padding byte matches; at
    // 1280 and 5120 a 17- and a 7-byte prefix validate by chance, each the
    // only documented length that does there. Named explicitly, the
    // documented layouts print them from a stream (with the default ones the
    // tool refuses the input: tests/cli_messages.rs); nearly all the input is
    // skipped, so from a file, judged whole, nothing is printed.
    let spi = data_arg("spi_telemetry.bin");
    let args = ["decode", "omnitiles", "--from", "tile", "--layout", "auto"];
    let file = run(&[&args[..], &[&spi]].concat(), b"");
    assert_eq!((file.code, file.text()), (3, ""));
    let default = run(&args, &std::fs::read(&spi).unwrap());
    assert_eq!(default.code, 3);
    let false_frames: Vec<(u64, u64)> = default
        .json()
        .iter()
        .map(|f| (f["offset"].as_u64().unwrap(), f["len"].as_u64().unwrap()))
        .collect();
    assert_eq!(false_frames, [(1280, 17), (5120, 7), (5376, 53)]);
    let spi45 = run(
        &[
            "decode",
            "omnitiles",
            "--from",
            "tile",
            "--layout",
            "spi45",
            &spi,
        ],
        b"",
    );
    let frames = spi45.json();
    assert_eq!(frames.len(), 64);
    assert!(frames
        .iter()
        .enumerate()
        .all(|(i, f)| f["offset"] == 128 * i
            && f["len"] == 45
            && f["layout"] == "spi45"
            && f.get("uwb").is_none()
            && f["imu"]["az"].as_f64().unwrap() > 9.0));
}

// ---------------------------------------------------------------- datagrams

#[test]
fn datagrams() {
    let r = run(
        &[
            "decode",
            "omnitiles",
            "--datagrams",
            "--errors",
            &data_arg("ble_notifications.hex"),
        ],
        b"",
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let events = r.json();
    assert_eq!(events.len(), 80);
    // Offsets count through the concatenated datagrams: line n starts at 53 n.
    for (i, e) in events.iter().enumerate() {
        assert_eq!(e["offset"], 53 * i, "line {}", i + 1);
    }
    let errors: Vec<&str> = r
        .lines()
        .into_iter()
        .filter(|l| l.contains("error"))
        .collect();
    assert_eq!(
        errors,
        [
            r#"{"offset":1643,"error":"checksum","expected":193,"found":185}"#,
            r#"{"offset":3551,"error":"checksum","expected":197,"found":189}"#,
        ]
    );
    assert_eq!(r.stderr, summary(78, 4240, 106, 2, 0));
    // Before the nRF's first SPI frame: zeros where the STM32's fields go.
    assert_eq!(
        r.lines()[0],
        concat!(
            r#"{"offset":0,"len":53,"type":"telemetry","layout":"ble53","m1_pos":0,"m2_pos":0,"#,
            r#""uwb":[4629,3133,3064,null],"tof":0,"#,
            r#""imu":{"ax":0.0,"ay":0.0,"az":0.0,"gx":0.0,"gy":0.0,"gz":0.0},"#,
            r#""m1_adcs":[0,0,0,0],"m2_adcs":[0,0]}"#
        )
    );
}

#[test]
fn datagrams_with_padding_and_several_commands() {
    // The nRF's brake buffer, a BLE write holding two commands, a 7-byte
    // notification, and a 45-byte SPI frame in its zero-padded buffer.
    let mut spi = hex("a5 60 d0 07 e8 03 41 01");
    spi.extend([0; 24]);
    spi.extend(hex("d1 07 d2 07 d3 07 d4 07 e9 03 ea 03"));
    let sum = spi[1..].iter().fold(0u8, |s, &b| s.wrapping_add(b));
    spi.push(sum);
    spi.extend([0; 83]);
    let spi_line: Vec<String> = spi.iter().map(|b| format!("{b:02x}")).collect();
    let input = format!(
        "a5 32 32 a5 42 42{}\n\na5 30 c8 f8 a5 50 50\na5 60 d0 07 e8 03 22\n{}\n",
        " 00".repeat(122),
        spi_line.join(" ")
    );
    let r = run(
        &[
            "decode",
            "omnitiles",
            "--datagrams",
            "--layout",
            "auto,spi45",
        ],
        input.as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":3,"type":"m1_brake"}"#,
            r#"{"offset":3,"len":3,"type":"m2_brake"}"#,
            r#"{"offset":128,"len":4,"type":"m1_extend","speed":200}"#,
            r#"{"offset":132,"len":3,"type":"ping"}"#,
            r#"{"offset":135,"len":7,"type":"telemetry","layout":"pos7","m1_pos":2000,"m2_pos":1000}"#,
            concat!(
                r#"{"offset":142,"len":45,"type":"telemetry","layout":"spi45","m1_pos":2000,"#,
                r#""m2_pos":1000,"tof":321,"imu":{"ax":0.0,"ay":0.0,"az":0.0,"gx":0.0,"gy":0.0,"gz":0.0},"#,
                r#""m1_adcs":[2001,2002,2003,2004],"m2_adcs":[1001,1002]}"#
            ),
        ]
    );
    assert_eq!(r.stderr, summary(6, 270, 205, 0, 0));
}

#[test]
fn datagram_line_that_is_not_hex() {
    let r = run(
        &["decode", "omnitiles", "--datagrams"],
        b"a5 50 50\na5 5g 50\na5 71 71\na5 7\n",
    );
    assert_eq!(r.code, 2);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":3,"type":"ping"}"#,
            r#"{"offset":3,"len":3,"type":"base_brake"}"#,
        ]
    );
    assert_eq!(
        r.stderr,
        "robowire: stdin: line 2, column 5: invalid hex digit 'g'\n\
         robowire: stdin: line 4, column 4: odd number of hex digits\n"
            .to_owned()
            + &summary(2, 6, 0, 0, 0)
            + "robowire: 2 invalid datagram lines\n"
    );
}

// ---------------------------------------------------------------- --errors

#[test]
fn errors_are_reported_as_events() {
    // Garbage, a bad checksum, an unknown id, a good frame, a command with a
    // 0xA5 payload byte, and a frame cut by the end of the input.
    let input = "00 11 a5 30 c8 f7 a5 99 a5 50 50 a5 70 a5 00 00 15 a5 30 c8";
    let r = run(
        &["decode", "omnitiles", "--hex", "--errors"],
        input.as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":2,"error":"checksum","expected":248,"found":247}"#,
            r#"{"offset":6,"error":"unknown_id","id":153}"#,
            r#"{"offset":8,"len":3,"type":"ping"}"#,
            r#"{"offset":11,"len":6,"type":"base_velocity","vx":-91,"vy":0,"omega":0}"#,
            r#"{"offset":17,"error":"truncated","len":3}"#,
        ]
    );
    assert_eq!(r.stderr, summary(2, 20, 11, 1, 2));
    // Without --errors the same run prints only the frames and the same summary.
    let r = run(&["decode", "omnitiles", "--hex"], input.as_bytes());
    assert_eq!(r.lines().len(), 2);
    assert_eq!(r.stderr, summary(2, 20, 11, 1, 2));
}

// ---------------------------------------------------------------- round trip

/// Decode `input` with `extra` options, encode the JSON back, and check the
/// bytes are exactly the decoded frames' bytes, in order.
fn round_trip(input: &[u8], extra: &[&str]) -> usize {
    let mut args = vec!["decode", "omnitiles", "--errors"];
    args.extend_from_slice(extra);
    let decoded = run(&args, input);
    assert_eq!(decoded.code, 0, "{}", decoded.stderr);
    let mut expected = Vec::new();
    let mut frames = 0;
    for event in decoded.json() {
        if event.get("type").is_some() {
            let offset = event["offset"].as_u64().unwrap() as usize;
            let len = event["len"].as_u64().unwrap() as usize;
            expected.extend_from_slice(&input[offset..offset + len]);
            frames += 1;
        }
    }
    let encoded = run(&["encode", "omnitiles"], &decoded.stdout);
    assert_eq!(encoded.code, 0, "{}", encoded.stderr);
    assert!(encoded.stdout == expected, "{extra:?}: round trip differs");
    // And through hex.
    let as_hex = run(&["encode", "omnitiles", "--hex"], &decoded.stdout);
    assert_eq!(as_hex.text().lines().count(), frames);
    assert_eq!(hex(as_hex.text()), expected);
    frames
}

#[test]
fn decode_then_encode_reproduces_every_frame() {
    let mut frames = 0;
    for (file, extra) in CASES {
        let input = std::fs::read(data(file)).unwrap();
        frames += round_trip(&input, extra);
    }
    assert!(frames > 1000, "{frames} frames");
    // The datagram captures, read as streams.
    for file in ["ble_notifications.hex", "spi_commands.hex"] {
        let input = hex(&std::fs::read_to_string(data(file)).unwrap());
        assert!(round_trip(&input, &[]) > 20, "{file}");
    }
    assert_eq!(round_trip(&hex(GOLDEN_HEX), &[]), 21);
}

/// A BLE frame whose IMU values are awkward for JSON.
fn awkward_frame(imu_bits: [u32; 6]) -> Vec<u8> {
    let mut frame = hex("a5 60 d0 07 ff ff dc 05 c4 09 ff ff 94 11 ff ff");
    for bits in imu_bits {
        frame.extend(bits.to_le_bytes());
    }
    frame.extend(hex("d1 07 d2 07 d3 07 d4 07 ff ff ea 03"));
    let sum = frame[1..].iter().fold(0u8, |s, &b| s.wrapping_add(b));
    frame.push(sum);
    frame
}

#[test]
fn non_finite_and_awkward_floats_round_trip() {
    let bits = [
        0x7fc0_0000, // NaN
        0xffc0_0001, // a negative NaN with a payload
        0x7f80_0000, // inf
        0xff80_0000, // -inf
        0x8000_0000, // -0.0
        0x15ae_43fd, // 7.038531e-26: its shortest digits round wrongly through f64
    ];
    let frame = awkward_frame(bits);
    let r = run(&["decode", "omnitiles"], &frame);
    assert_eq!(
        r.text(),
        concat!(
            r#"{"offset":0,"len":53,"type":"telemetry","layout":"ble53","m1_pos":2000,"m2_pos":null,"#,
            r#""uwb":[1500,2500,null,4500],"tof":null,"imu":{"ax":"nan:0x7fc00000","#,
            r#""ay":"nan:0xffc00001","az":"inf","gx":"-inf","gy":-0.0,"#,
            r#""gz":7.038530691851209e-26},"m1_adcs":[2001,2002,2003,2004],"m2_adcs":[65535,1002]}"#,
            "\n"
        )
    );
    // Every finite value reads back as the same f32, also through f64.
    let gz = r.json()[0]["imu"]["gz"].as_f64().unwrap();
    assert_eq!((gz as f32).to_bits(), 0x15ae_43fd);
    // The shortest f32 digits would not: that is why the longer form is used.
    assert_ne!(
        ("7.038531e-26".parse::<f64>().unwrap() as f32).to_bits(),
        0x15ae_43fd
    );
    assert_eq!(
        "7.038531e-26".parse::<f32>().unwrap().to_bits(),
        0x15ae_43fd
    );
    let back = run(&["encode", "omnitiles"], &r.stdout);
    assert_eq!(back.code, 0, "{}", back.stderr);
    assert_eq!(back.stdout, frame);
}

#[test]
fn floats_read_back_exactly() {
    // A spread of bit patterns, including subnormals and the extremes.
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut patterns = vec![
        0x0000_0001,
        0x007f_ffff,
        0x0080_0000,
        0x7f7f_ffff,
        0xff7f_ffff,
    ];
    let mut input = String::new();
    for _ in 0..200 {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        patterns.push(rng as u32);
    }
    for chunk in patterns.chunks(6) {
        let mut six = [0u32; 6];
        six[..chunk.len()].copy_from_slice(chunk);
        input.extend(awkward_frame(six).iter().map(|b| format!("{b:02x} ")));
    }
    let r = run(
        &[
            "decode",
            "omnitiles",
            "--hex",
            "--from",
            "tile",
            "--layout",
            "ble53",
        ],
        input.as_bytes(),
    );
    let mut seen = 0;
    for (frame, chunk) in r.json().iter().zip(patterns.chunks(6)) {
        for (key, &bits) in ["ax", "ay", "az", "gx", "gy", "gz"].iter().zip(chunk) {
            let value = &frame["imu"][key];
            if let Some(wide) = value.as_f64() {
                assert_eq!((wide as f32).to_bits(), bits, "{key} {value}");
                seen += 1;
            }
        }
    }
    assert!(seen > 190, "{seen} finite values checked");
    let back = run(&["encode", "omnitiles", "--hex"], &r.stdout);
    assert_eq!(hex(back.text()), hex(&input));
}

#[test]
fn encode_skips_diagnostics_and_blank_lines() {
    let input = concat!(
        r#"{"offset":2,"error":"checksum","expected":248,"found":247}"#,
        "\n\n   \n",
        r#"{"type":"ping"}"#,
        "\r\n"
    );
    let r = run(&["encode", "omnitiles", "--hex"], input.as_bytes());
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.text(), "a5 50 50\n");
}

// ---------------------------------------------------------------- malformed input

#[test]
fn malformed_json_lines() {
    let cases: &[(&str, &str)] = &[
        (r#"[1,2]"#, "expected a JSON object, found [1,2]"),
        (r#"{"speed":3}"#, "missing field `type`"),
        (
            r#"{"type":"m3_extend"}"#,
            "unknown type `m3_extend` (did you mean `m1_extend` or `m2_extend`?); the types are \
             `ping`, `m1_extend`, `m1_retract`, `m1_brake`, `m1_set_position`, `m2_extend`, \
             `m2_retract`, `m2_brake`, `m2_set_position`, `base_velocity`, `base_brake` and \
             `telemetry`",
        ),
        (r#"{"type":"m1_extend"}"#, "missing field `speed`"),
        (
            r#"{"type":"m1_extend","sped":200}"#,
            "unknown field `sped` (did you mean `speed`?)",
        ),
        (
            r#"{"type":"m1_extend","speed":256}"#,
            "field `speed` must be an integer 0..=255, found 256",
        ),
        (
            r#"{"type":"m1_extend","speed":2.5}"#,
            "field `speed` must be an integer 0..=255, found 2.5",
        ),
        (
            r#"{"type":"m1_extend","speed":"10"}"#,
            "field `speed` must be an integer 0..=255, found \"10\"",
        ),
        (
            r#"{"type":"base_velocity","vx":0,"vy":-129,"omega":0}"#,
            "field `vy` must be an integer -128..=127, found -129",
        ),
        (
            r#"{"type":"ping","speed":1}"#,
            "unknown field `speed` for type ping",
        ),
        (
            r#"{"type":"telemetry","layout":"pos9","m1_pos":1,"m2_pos":2}"#,
            "unknown layout `pos9` (expected pos7, uwb15, uwbtof17, spi45 or ble53)",
        ),
        (
            r#"{"type":"telemetry","layout":"pos7","m1_pos":65535,"m2_pos":2}"#,
            "field `m1_pos` must be null or an integer 0..=65534 (0xFFFF, no reading, is written null), found 65535",
        ),
        (
            r#"{"type":"telemetry","layout":"pos7","m1_pos":1,"m2_pos":2,"tof":3}"#,
            "layout pos7 does not carry `tof`",
        ),
        (
            r#"{"type":"telemetry","layout":"uwbtof17","m1_pos":1,"m2_pos":2,"uwb":[1,2,3,4]}"#,
            "missing field `tof` (layout uwbtof17 carries it)",
        ),
        (
            r#"{"type":"telemetry","layout":"uwb15","m1_pos":1,"m2_pos":2,"uwb":[1,2,3]}"#,
            "field `uwb` must be an array of 4, found [1,2,3]",
        ),
        (
            r#"{"type":"telemetry","layout":"uwb15","m1_pos":1,"m2_pos":2,"uwb":[1,2,-3,4]}"#,
            "field `uwb[2]` must be null or an integer 0..=65534 (0xFFFF, no reading, is written null), found -3",
        ),
    ];
    for (line, message) in cases {
        let input = format!("{{\"type\":\"ping\"}}\n{line}\n{{\"type\":\"base_brake\"}}\n");
        let r = run(&["encode", "omnitiles", "--hex"], input.as_bytes());
        assert_eq!(r.code, 2, "{line}");
        // Nothing is written for the bad line; the others are encoded.
        assert_eq!(r.text(), "a5 50 50\na5 71 71\n", "{line}");
        assert_eq!(
            r.stderr,
            format!("robowire: stdin: line 2: {message}\nrobowire: 1 malformed line\n"),
            "{line}"
        );
    }
}

#[test]
fn malformed_telemetry_fields() {
    let ble = |imu: &str, m2: &str| {
        format!(
            r#"{{"type":"telemetry","layout":"ble53","m1_pos":1,"m2_pos":2,"uwb":[1,2,3,4],"tof":5,"imu":{imu},"m1_adcs":[1,2,3,4],"m2_adcs":{m2}}}"#
        )
    };
    let good_imu = r#"{"ax":0,"ay":0,"az":9.8,"gx":0,"gy":0,"gz":0}"#;
    let good = run(
        &["encode", "omnitiles", "--hex"],
        ble(good_imu, "[5,65535]").as_bytes(),
    );
    assert_eq!(good.code, 0, "{}", good.stderr);
    assert_eq!(hex(good.text()).len(), 53);
    let cases = [
        (
            ble(r#"{"ax":0,"ay":0,"az":1e39,"gx":0,"gy":0,"gz":0}"#, "[5,6]"),
            "field `imu.az` 1e+39 does not fit in an f32 (write \"inf\" for infinity)",
        ),
        (
            ble(r#"{"ax":0,"ay":0,"az":"nan:0x7f800000","gx":0,"gy":0,"gz":0}"#, "[5,6]"),
            "field `imu.az` must be a number, \"inf\", \"-inf\" or \"nan:0x…\" (a NaN's 8 hex digits), found \"nan:0x7f800000\"",
        ),
        (
            ble(r#"{"ax":0,"ay":0,"gx":0,"gy":0,"gz":0}"#, "[5,6]"),
            "missing field `imu.az`",
        ),
        (
            ble(r#"{"ax":0,"ay":0,"az":0,"gx":0,"gy":0,"gz":0,"gw":0}"#, "[5,6]"),
            "unknown field `gw` in `imu`",
        ),
        (ble(good_imu, "[5,65536]"), "field `m2_adcs[1]` must be an integer 0..=65535, found 65536"),
    ];
    for (line, message) in cases {
        let r = run(&["encode", "omnitiles"], line.as_bytes());
        assert_eq!(r.code, 2, "{line}");
        assert_eq!(r.stdout, b"", "{line}");
        assert_eq!(
            r.stderr,
            format!("robowire: stdin: line 1: {message}\nrobowire: 1 malformed line\n")
        );
    }
}

#[test]
fn bad_hex_stops_the_decode() {
    let r = run(
        &["decode", "omnitiles", "--hex"],
        b"a5 50 50\na5 71 71 zz a5 50 50\n",
    );
    assert_eq!(r.code, 2);
    // Frames before the bad digit are printed.
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":3,"type":"ping"}"#,
            r#"{"offset":3,"len":3,"type":"base_brake"}"#,
        ]
    );
    assert_eq!(
        r.stderr,
        summary(2, 6, 0, 0, 0) + "robowire: stdin: line 2, column 10: invalid hex digit 'z'\n"
    );
    let odd = run(&["decode", "omnitiles", "--hex"], b"a5 50 50 a\n");
    assert_eq!(odd.code, 2);
    assert!(odd
        .stderr
        .ends_with("robowire: stdin: line 1, column 10: odd number of hex digits\n"));
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["decode", "omnitiles", "--chunk", "0"][..],
        &["decode", "omnitiles", "--chunk", "x"],
        &["decode", "omnitiles", "--layout", "ble52"],
        &["decode", "omnitiles", "--from", "robot"],
        &["decode", "omnitiles", "--bogus"],
        &["decode", "omnitiles", "--datagrams", "--chunk", "5"],
        &["decode", "omnitiles", "--from", "host", "--layout", "ble53"],
        &["decode", "pixy3"],
        &["encode", "omnitiles", "--errors"],
        &["decode"],
        &[],
    ] {
        let r = run(args, b"");
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert_eq!(r.stdout, b"", "{args:?}");
        assert!(!r.stderr.is_empty(), "{args:?}");
    }
    let r = run(
        &["decode", "omnitiles", "--from", "host", "--layout", "ble53"],
        b"",
    );
    assert_eq!(
        r.stderr,
        "error: --layout selects telemetry layouts, which --from host does not accept\n\n\
         For more information, try '--help'.\n"
    );
}

#[test]
fn io_errors_exit_1() {
    let r = run(&["decode", "omnitiles", "/nonexistent/capture.bin"], b"");
    assert_eq!(r.code, 1);
    assert!(
        r.stderr.starts_with("robowire: /nonexistent/capture.bin: "),
        "{}",
        r.stderr
    );
    let r = run(&["encode", "omnitiles", "/nonexistent/frames.jsonl"], b"");
    assert_eq!(r.code, 1);
}

#[test]
fn empty_input() {
    for args in [
        &["decode", "omnitiles"][..],
        &["decode", "omnitiles", "--hex"],
        &["decode", "omnitiles", "--datagrams"],
    ] {
        let r = run(args, b"");
        assert_eq!(r.code, 0, "{args:?}");
        assert_eq!(r.stdout, b"");
        assert_eq!(r.stderr, summary(0, 0, 0, 0, 0));
    }
    let r = run(&["encode", "omnitiles"], b"");
    assert_eq!((r.code, r.stdout.len(), r.stderr.as_str()), (0, 0, ""));
}

#[test]
fn help_documents_the_contract() {
    let r = run(&["decode", "omnitiles", "--help"], b"");
    assert_eq!(r.code, 0);
    for needle in [
        "--from <FROM>",
        "--layout <L[,L...]>",
        "--chunk <N>",
        "--hex",
        "--datagrams",
        "--errors",
        "[INPUT]",
        "pos7",
        "uwbtof17",
        "spi45",
        "auto",
        r#"{"offset":12,"error":"checksum","expected":48,"found":47}"#,
        "\"nan:0x7fc00000\"",
        "Exit status: 0 on success, 2 on usage errors",
    ] {
        assert!(r.text().contains(needle), "decode --help lacks {needle}");
    }
    let top = run(&["--help"], b"");
    assert!(top
        .text()
        .contains("robowire encode omnitiles [--hex] [INPUT]"));
}

#[test]
fn closed_stdout_is_quiet() {
    // Enough output to overflow the pipe and the tool's own buffer.
    let capture = std::fs::read(data("ble_telemetry.bin")).unwrap();
    let big: Vec<u8> = capture.repeat(20);
    let mut child = Command::new(env!("CARGO_BIN_EXE_robowire"))
        .args(["decode", "omnitiles", "--errors"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        let _ = input.write_all(&big);
    });
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 100];
    stdout.read_exact(&mut first).unwrap();
    assert!(first.starts_with(br#"{"offset":0,"len":53,"type":"telemetry""#));
    drop(stdout);
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    let status = child.wait().unwrap();
    writer.join().unwrap();
    assert_eq!(status.code(), Some(0));
    assert_eq!(stderr, "");
}
