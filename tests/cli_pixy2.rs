//! `robowire decode pixy2` and `robowire encode pixy2`: the spec's golden
//! vectors, chunking invariance, `--from` and `--checksum-only`, diagnostics,
//! the decode | encode round trip in both forms and both directions,
//! payloads only a lossless schema survives, and malformed input.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{hex, run, Run};

use serde_json::Value;
use std::path::Path;

/// Decode with `args` after `decode pixy2`; the run must succeed.
fn decode(args: &[&str], stdin: &[u8]) -> Run {
    let mut all = vec!["decode", "pixy2"];
    all.extend_from_slice(args);
    let r = run(&all, stdin);
    assert_eq!(r.code, 0, "{args:?}: {}", r.stderr);
    r
}

/// Encode JSON lines; the run must succeed.
fn encode(lines: &[u8]) -> Vec<u8> {
    let r = run(&["encode", "pixy2"], lines);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.stderr, "");
    r.stdout
}

const CAPTURE: &str = "pixy2_conversation.hex";

fn capture_path() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(CAPTURE)
        .to_str()
        .unwrap()
        .to_owned()
}

fn capture_bytes() -> Vec<u8> {
    hex(&std::fs::read_to_string(capture_path()).unwrap())
}

/// A frame of `packet_type` around `payload`, with or without the checksum.
fn frame(checksum: bool, packet_type: u8, payload: &[u8]) -> Vec<u8> {
    let len = u8::try_from(payload.len()).unwrap();
    let mut f = if checksum {
        let sum = payload
            .iter()
            .fold(0u16, |s, &b| s.wrapping_add(u16::from(b)));
        let [s0, s1] = sum.to_le_bytes();
        vec![0xaf, 0xc1, packet_type, len, s0, s1]
    } else {
        vec![0xae, 0xc1, packet_type, len]
    };
    f.extend_from_slice(payload);
    f
}

fn summary(frames: u64, bytes: u64, skipped: u64, checksum: u64, other: u64, bad: u64) -> String {
    cli_common::summary_line([frames, bytes, skipped, checksum, other, bad])
}

// ---------------------------------------------------------------- golden vectors

/// Spec §8.1–§8.4: the documented example, every request, every response,
/// the no-checksum version response, and SPI filler with a doubled first
/// sync byte, as one stream.
const GOLDEN_HEX: &str = "\
ae c1 0e 00
af c1 0f 10 0d 03 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00
ae c1 0c 01 00
ae c1 10 01 80
ae c1 12 04 f4 01 f4 01
ae c1 12 04 00 00 e8 03
ae c1 14 03 ff 00 00
ae c1 16 02 01 00
ae c1 18 00
ae c1 20 02 ff ff
ae c1 20 02 11 03
ae c1 30 02 00 07
ae c1 30 02 01 07
ae c1 36 01 81
ae c1 38 01 03
ae c1 3a 02 a6 ff
ae c1 3c 02 5a 00
ae c1 3e 00
ae c1 70 05 9e 00 68 00 01
ae c1 02 21 6c 69 6e 65 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00
af c1 01 04 00 00 00 00 00 00
af c1 01 04 01 00 01 00 00 00
af c1 01 04 3d 00 3d 00 00 00
af c1 01 04 9c 00 56 34 12 00
af c1 03 01 ff 00 ff
af c1 03 01 fe 00 fe
af c1 03 01 fd 00 fd
af c1 03 01 fc 00 fc
af c1 03 01 fb 00 fb
af c1 03 01 fa 00 fa
af c1 0d 04 0d 01 3c 01 d0 00
af c1 0d 04 83 00 4f 00 34 00
af c1 21 00 00 00
af c1 21 0e b7 01 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff
af c1 21 1c 2c 05 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff 0a 00 c8 00 78 00 28 00 1e 00 d3 ff 07 0c
af c1 31 00 00 00
af c1 31 08 6e 00 01 06 0a 33 28 00 02 00
af c1 31 2c 16 03 01 06 0a 33 28 00 02 00 02 1c 27 14 03 00 02 00 5a 00 05 00 00 00 02 00 a6 ff 00 00 00 00 00 00 00 00 00 00 00 00 04 04 1e 19 00 05
af c1 31 2c 16 03 01 06 0a 33 28 00 02 00 02 1c 27 14 03 00 02 00 a6 ff 05 00 00 00 02 00 5a 00 00 00 00 00 00 00 00 00 00 00 00 00 04 04 1e 19 00 05
ae c1 0f 10 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00
01 01 01 af af c1 01 04 00 00 00 00 00 00
";

const VERSION_FIELDS: &str = r#""hardware":8704,"firmware_major":3,"firmware_minor":0,"firmware_build":10,"firmware_type":"general"}"#;
const BLOCK_1: &str =
    r#"{"signature":1,"x":100,"y":50,"width":20,"height":10,"angle":0,"index":3,"age":255}"#;
const BLOCK_CC: &str =
    r#"{"signature":10,"x":200,"y":120,"width":40,"height":30,"angle":-45,"index":7,"age":12}"#;
const VECTOR: &str = r#"{"vectors":[{"x0":10,"y0":51,"x1":40,"y1":0,"index":2,"flags":0}]}"#;
const BARCODE: &str = r#"{"barcodes":[{"x":30,"y":25,"flags":0,"code":5}]}"#;

fn golden_json() -> Vec<String> {
    let intersection = |a: i16, b: i16| {
        format!(
            r#"{{"intersections":[{{"x":39,"y":20,"lines":[{{"index":2,"angle":{a}}},{{"index":5,"angle":0}},{{"index":2,"angle":{b}}}]}}]}}"#
        )
    };
    let fixed = [
        r#"{"offset":0,"len":4,"type":"get_version","checksum":false}"#.to_owned(),
        format!(r#"{{"offset":4,"len":22,"type":"version","checksum":true,{VERSION_FIELDS}"#),
        r#"{"offset":26,"len":5,"type":"get_resolution","checksum":false}"#.to_owned(),
        r#"{"offset":31,"len":5,"type":"set_camera_brightness","checksum":false,"brightness":128}"#.to_owned(),
        r#"{"offset":36,"len":8,"type":"set_servos","checksum":false,"pan":500,"tilt":500}"#.to_owned(),
        r#"{"offset":44,"len":8,"type":"set_servos","checksum":false,"pan":0,"tilt":1000}"#.to_owned(),
        r#"{"offset":52,"len":7,"type":"set_led","checksum":false,"r":255,"g":0,"b":0}"#.to_owned(),
        r#"{"offset":59,"len":6,"type":"set_lamp","checksum":false,"upper":1,"lower":0}"#.to_owned(),
        r#"{"offset":65,"len":4,"type":"get_fps","checksum":false}"#.to_owned(),
        r#"{"offset":69,"len":6,"type":"get_blocks","checksum":false,"sigmap":255,"max_blocks":255}"#.to_owned(),
        r#"{"offset":75,"len":6,"type":"get_blocks","checksum":false,"sigmap":17,"max_blocks":3}"#.to_owned(),
        r#"{"offset":81,"len":6,"type":"get_features","checksum":false,"scope":0,"features":7}"#.to_owned(),
        r#"{"offset":87,"len":6,"type":"get_features","checksum":false,"scope":1,"features":7}"#.to_owned(),
        r#"{"offset":93,"len":5,"type":"set_mode","checksum":false,"mode":129}"#.to_owned(),
        r#"{"offset":98,"len":5,"type":"set_vector","checksum":false,"index":3}"#.to_owned(),
        r#"{"offset":103,"len":6,"type":"set_next_turn","checksum":false,"angle":-90}"#.to_owned(),
        r#"{"offset":109,"len":6,"type":"set_default_turn","checksum":false,"angle":90}"#.to_owned(),
        r#"{"offset":115,"len":4,"type":"reverse_vector","checksum":false}"#.to_owned(),
        r#"{"offset":119,"len":9,"type":"get_rgb","checksum":false,"x":158,"y":104,"saturate":1}"#.to_owned(),
        r#"{"offset":128,"len":37,"type":"change_prog","checksum":false,"name":"line"}"#.to_owned(),
        r#"{"offset":165,"len":10,"type":"result","checksum":true,"value":0}"#.to_owned(),
        r#"{"offset":175,"len":10,"type":"result","checksum":true,"value":1}"#.to_owned(),
        r#"{"offset":185,"len":10,"type":"result","checksum":true,"value":61}"#.to_owned(),
        // getRGB: 0x00123456, r 0x12, g 0x34, b 0x56.
        r#"{"offset":195,"len":10,"type":"result","checksum":true,"value":1193046}"#.to_owned(),
    ];
    let mut lines: Vec<String> = fixed.into_iter().collect();
    let errors = [
        "general",
        "busy",
        "invalid_request",
        "type_unsupported",
        "button_override",
        "prog_changing",
    ];
    for (i, name) in errors.iter().enumerate() {
        lines.push(format!(
            r#"{{"offset":{},"len":7,"type":"error","checksum":true,"code":"{name}"}}"#,
            205 + 7 * i
        ));
    }
    lines.extend([
        r#"{"offset":247,"len":10,"type":"resolution","checksum":true,"width":316,"height":208}"#.to_owned(),
        r#"{"offset":257,"len":10,"type":"resolution","checksum":true,"width":79,"height":52}"#.to_owned(),
        r#"{"offset":267,"len":6,"type":"blocks","checksum":true,"blocks":[]}"#.to_owned(),
        format!(r#"{{"offset":273,"len":20,"type":"blocks","checksum":true,"blocks":[{BLOCK_1}]}}"#),
        format!(
            r#"{{"offset":293,"len":34,"type":"blocks","checksum":true,"blocks":[{BLOCK_1},{BLOCK_CC}]}}"#
        ),
        r#"{"offset":327,"len":6,"type":"features","checksum":true,"sections":[]}"#.to_owned(),
        format!(r#"{{"offset":333,"len":14,"type":"features","checksum":true,"sections":[{VECTOR}]}}"#),
        format!(
            r#"{{"offset":347,"len":50,"type":"features","checksum":true,"sections":[{VECTOR},{},{BARCODE}]}}"#,
            intersection(90, -90)
        ),
        format!(
            r#"{{"offset":397,"len":50,"type":"features","checksum":true,"sections":[{VECTOR},{},{BARCODE}]}}"#,
            intersection(-90, 90)
        ),
        format!(r#"{{"offset":447,"len":20,"type":"version","checksum":false,{VERSION_FIELDS}"#),
        // After three filler bytes and a doubled 0xaf.
        r#"{"offset":471,"len":10,"type":"result","checksum":true,"value":0}"#.to_owned(),
    ]);
    lines
}

#[test]
fn decode_golden_vectors() {
    let r = decode(&["--hex", "--errors"], GOLDEN_HEX.as_bytes());
    assert_eq!(r.lines(), golden_json());
    assert_eq!(r.stderr, summary(41, 481, 4, 0, 0, 0));
    // The same bytes raw, from a file argument.
    let file = std::env::temp_dir().join(format!("robowire-pixy2-{}.bin", std::process::id()));
    std::fs::write(&file, hex(GOLDEN_HEX)).unwrap();
    let from_file = decode(&[file.to_str().unwrap()], b"");
    std::fs::remove_file(&file).unwrap();
    assert_eq!(from_file.lines(), golden_json());
}

#[test]
fn encode_golden_vectors() {
    let json = golden_json().join("\n");
    let bytes = encode(json.as_bytes());
    // Every frame, without the filler and the doubled sync byte.
    let mut expected = hex(GOLDEN_HEX);
    let filler = hex("01 01 01 af");
    let at = expected.len() - 14;
    assert_eq!(expected[at..at + 4], filler);
    expected.drain(at..at + 4);
    assert_eq!(bytes, expected);
    // Hex output, one frame per line.
    let r = run(&["encode", "pixy2", "--hex"], json.as_bytes());
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.lines().len(), 41);
    assert_eq!(r.lines()[0], "ae c1 0e 00");
    assert_eq!(
        r.lines()[1],
        "af c1 0f 10 0d 03 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00"
    );
}

#[test]
fn encode_by_hand() {
    // offset, len and checksum may be left out: requests are then written
    // without a checksum, responses with one.
    let cases = [
        (
            r#"{"type":"get_blocks","sigmap":255,"max_blocks":255}"#,
            "ae c1 20 02 ff ff",
        ),
        (
            r#"{"type":"set_servos","pan":500,"tilt":500,"checksum":true}"#,
            "af c1 12 04 ea 01 f4 01 f4 01",
        ),
        (r#"{"type":"error","code":"busy"}"#, "af c1 03 01 fe 00 fe"),
        (r#"{"type":"error","code":-2}"#, "af c1 03 01 fe 00 fe"),
        (
            r#"{"type":"result","value":-1,"checksum":false}"#,
            "ae c1 01 04 ff ff ff ff",
        ),
        (
            r#"{"type":"change_prog","name":"video","offset":7,"len":99}"#,
            "ae c1 02 21 76 69 64 65 6f 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00",
        ),
        (r#"{"type":"get_resolution"}"#, "ae c1 0c 01 00"),
        (
            r#"{"type":"features","sections":[{"barcodes":[{"x":1,"y":2,"flags":0,"code":15}]}]}"#,
            "af c1 31 06 1a 00 04 04 01 02 00 0f",
        ),
    ];
    for (line, bytes) in cases {
        let r = run(&["encode", "pixy2", "--hex"], line.as_bytes());
        assert_eq!(r.code, 0, "{line}: {}", r.stderr);
        assert_eq!(r.text(), format!("{bytes}\n"), "{line}");
    }
}

// ---------------------------------------------------------------- the sample capture

/// Option sets worth checking on the sample capture.
const CASES: [&[&str]; 6] = [
    &[],
    &["--from", "host"],
    &["--from", "device"],
    &["--checksum-only"],
    &["--from", "device", "--checksum-only"],
    &["--from", "any", "--checksum-only"],
];

fn decode_capture(extra: &[&str], chunk: &str) -> Run {
    let path = capture_path();
    let mut args = vec!["--hex", "--errors", "--chunk", chunk];
    args.extend_from_slice(extra);
    args.push(&path);
    decode(&args, b"")
}

#[test]
fn chunk_size_does_not_change_the_output() {
    for extra in CASES {
        let whole = decode_capture(extra, "4096");
        assert!(whole.lines().len() > 40, "{extra:?}");
        for chunk in ["1", "2", "5", "13", "100000"] {
            let r = decode_capture(extra, chunk);
            assert!(
                r.stdout == whole.stdout,
                "{extra:?}: --chunk {chunk} differs from --chunk 4096"
            );
            assert_eq!(r.stderr, whole.stderr, "{extra:?} --chunk {chunk}");
        }
        // The same bytes raw, through stdin, one byte at a time.
        let mut args = vec!["--errors", "--chunk", "1"];
        args.extend_from_slice(extra);
        let raw = decode(&args, &capture_bytes());
        assert!(
            raw.stdout == whole.stdout,
            "{extra:?}: raw differs from hex"
        );
        assert_eq!(raw.stderr, whole.stderr);
    }
}

#[test]
fn capture_summary_and_events() {
    let r = decode_capture(&[], "4096");
    assert_eq!(r.stderr, summary(85, 1525, 457, 2, 2, 0));
    let events: Vec<&str> = r
        .lines()
        .into_iter()
        .filter(|l| !l.contains("\"type\""))
        .collect();
    // A request whose bit flipped on the wire, an answer whose bit flipped,
    // a setServos with 3 bytes, a request type no program knows.
    assert_eq!(
        events,
        [
            r#"{"offset":169,"error":"checksum","expected":385,"found":389}"#,
            r#"{"offset":703,"error":"checksum","expected":61,"found":53}"#,
            r#"{"offset":769,"error":"bad_length","packet_type":18,"payload_len":3}"#,
            r#"{"offset":1025,"error":"unknown_type","packet_type":50}"#,
        ]
    );
    let lines = r.lines();
    assert_eq!(
        lines[..4],
        [
            r#"{"offset":0,"len":4,"type":"get_version","checksum":false}"#,
            r#"{"offset":4,"len":7,"type":"error","checksum":true,"code":"busy"}"#,
            r#"{"offset":20,"len":4,"type":"get_version","checksum":false}"#,
            r#"{"offset":24,"len":22,"type":"version","checksum":true,"hardware":8704,"firmware_major":3,"firmware_minor":0,"firmware_build":20,"firmware_type":"general"}"#,
        ]
    );
    // Without --errors only frames are printed, with the same summary.
    let quiet = decode(&["--hex", &capture_path()], b"");
    assert_eq!(quiet.lines().len(), 85);
    assert_eq!(quiet.stderr, r.stderr);
}

/// The `type` of every frame printed.
fn types(r: &Run) -> Vec<String> {
    r.json()
        .iter()
        .filter_map(|v| Some(v.get("type")?.as_str()?.to_owned()))
        .collect()
}

const RESPONSES: [&str; 6] = [
    "result",
    "error",
    "resolution",
    "version",
    "blocks",
    "features",
];

#[test]
fn from_names_who_sent_the_bytes() {
    let any = types(&decode_capture(&[], "4096"));
    let host = types(&decode_capture(&["--from", "host"], "4096"));
    let device = types(&decode_capture(&["--from", "device"], "4096"));
    let requests: Vec<String> = any
        .iter()
        .filter(|t| !RESPONSES.contains(&t.as_str()))
        .cloned()
        .collect();
    let responses: Vec<String> = any
        .iter()
        .filter(|t| RESPONSES.contains(&t.as_str()))
        .cloned()
        .collect();
    assert_eq!((requests.len(), responses.len()), (42, 43));
    // --from host: bytes the host sent, the requests; --from device: the
    // responses. Together they are everything --from any finds.
    assert_eq!(host, requests);
    assert_eq!(device, responses);
    // The other side's frames are rejected by type.
    let r = decode_capture(&["--from", "device"], "4096");
    assert!(r
        .lines()
        .contains(&r#"{"offset":0,"error":"unknown_type","packet_type":14}"#));
    assert_eq!(r.stderr, summary(43, 1525, 839, 1, 45, 0));
}

#[test]
fn checksum_only_ignores_the_other_form() {
    let r = decode_capture(&["--checksum-only"], "4096");
    let frames: Vec<Value> = r
        .json()
        .into_iter()
        .filter(|v| v.get("type").is_some())
        .collect();
    // Every answer, and the four requests the host sent with a checksum.
    assert_eq!(frames.len(), 47);
    assert!(frames.iter().all(|v| v["checksum"] == true));
    let requests: Vec<&str> = frames
        .iter()
        .map(|v| v["type"].as_str().unwrap())
        .filter(|t| !RESPONSES.contains(t))
        .collect();
    assert_eq!(
        requests,
        ["set_lamp", "set_led", "set_camera_brightness", "set_servos"]
    );
    // An ae c1 frame is not even a candidate.
    let r = decode(&["--hex", "--errors", "--checksum-only"], b"ae c1 18 00");
    assert_eq!(r.text(), "");
    assert_eq!(r.stderr, summary(0, 4, 4, 0, 0, 0));
}

// ---------------------------------------------------------------- --errors

#[test]
fn errors_are_reported_as_events() {
    let input = [
        // Junk, then a setServos whose payload holds a getFPS that ends
        // where it ends: the later start wins.
        "00 ae c1 12 04 ae c1 18 00",
        // A stray first sync byte (skipped silently).
        "ae 00",
        // Line features whose checksum is right but whose vector section is
        // 5 bytes: consumed, reported, counted as malformed.
        "af c1 31 07 15 00 01 05 01 02 03 04 05",
        // The same without a checksum: not a frame at all.
        "ae c1 31 02 01 05",
        // A type no program has, setServos with 3 bytes, a version with one
        // payload bit flipped, a changeProg longer than the device takes.
        "ae c1 32 02 00 07",
        "ae c1 12 03 f4 01 f4",
        "af c1 0f 10 0d 03 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 01",
        "ae c1 02 41",
        // An error code the spec does not list, then a frame cut short.
        "af c1 03 01 f9 00 f9",
        "af c1 0d",
    ]
    .join(" ");
    let r = decode(&["--hex", "--errors"], input.as_bytes());
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":1,"error":"superseded","len":8}"#,
            r#"{"offset":5,"len":4,"type":"get_fps","checksum":false}"#,
            r#"{"offset":11,"error":"malformed","packet_type":49,"what":"section_length","ftype":1,"flen":5}"#,
            r#"{"offset":24,"error":"malformed","packet_type":49,"what":"section_past_end","section_offset":0}"#,
            r#"{"offset":30,"error":"unknown_type","packet_type":50}"#,
            r#"{"offset":36,"error":"bad_length","packet_type":18,"payload_len":3}"#,
            r#"{"offset":43,"error":"checksum","expected":781,"found":782}"#,
            r#"{"offset":65,"error":"too_long","packet_type":2,"payload_len":65,"max":64}"#,
            r#"{"offset":69,"len":7,"type":"error","checksum":true,"code":-7}"#,
            r#"{"offset":76,"error":"truncated","len":3}"#,
        ]
    );
    assert_eq!(r.stderr, summary(3, 79, 55, 1, 6, 1));
    // Without --errors: the frames and the same summary.
    let quiet = decode(&["--hex"], input.as_bytes());
    assert_eq!(quiet.lines().len(), 2);
    assert_eq!(quiet.stderr, r.stderr);
    // Diagnostic events are skipped by encode.
    assert_eq!(
        encode(&r.stdout),
        [hex("ae c1 18 00"), hex("af c1 03 01 f9 00 f9")].concat()
    );
}

#[test]
fn blocks_and_sections_errors() {
    // 13 bytes of blocks, and an intersection claiming 7 lines.
    let mut intersection = vec![0x02, 28, 1, 2, 7, 0];
    intersection.extend([0; 24]);
    let input = [
        frame(true, 0x21, &[0; 13]),
        frame(true, 0x31, &intersection),
    ]
    .concat();
    let r = decode(&["--errors"], &input);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"error":"bad_length","packet_type":33,"payload_len":13}"#,
            r#"{"offset":19,"error":"malformed","packet_type":49,"what":"intersection_lines","n":7}"#,
        ]
    );
}

// ---------------------------------------------------------------- round trip

/// Decode `input` with `extra` options, encode the JSON back, and check the
/// bytes are exactly the decoded frames' bytes, in order. Returns the number
/// of frames.
fn round_trip(input: &[u8], extra: &[&str]) -> usize {
    let mut args = vec!["--errors"];
    args.extend_from_slice(extra);
    let decoded = decode(&args, input);
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
    assert!(
        encode(&decoded.stdout) == expected,
        "{extra:?}: round trip differs"
    );
    // And through hex: one line per frame.
    let as_hex = run(&["encode", "pixy2", "--hex"], &decoded.stdout);
    assert_eq!(as_hex.code, 0);
    assert_eq!(as_hex.lines().len(), frames);
    assert_eq!(hex(as_hex.text()), expected);
    frames
}

#[test]
fn decode_then_encode_reproduces_every_frame() {
    let capture = capture_bytes();
    let counts: Vec<usize> = CASES.iter().map(|x| round_trip(&capture, x)).collect();
    assert_eq!(counts, [85, 42, 43, 47, 43, 47]);
    assert_eq!(round_trip(&hex(GOLDEN_HEX), &[]), 41);
}

#[test]
fn both_forms_in_both_directions() {
    // Every golden frame in the other form: requests with a checksum,
    // responses without.
    let flipped: Vec<String> = golden_json()
        .iter()
        .map(|line| {
            let mut v: Value = serde_json::from_str(line).unwrap();
            let checksum = v["checksum"].as_bool().unwrap();
            v["checksum"] = Value::Bool(!checksum);
            v.to_string()
        })
        .collect();
    let bytes = encode(flipped.join("\n").as_bytes());
    assert_eq!(&bytes[..6], hex("af c1 0e 00 00 00"));
    // Decoded, the frames print as the flipped lines (offsets aside) and
    // re-encode to the same bytes, for each side.
    let r = decode(&["--errors"], &bytes);
    let strip = |v: &Value| {
        let mut v = v.clone();
        let map = v.as_object_mut().unwrap();
        map.remove("offset");
        map.remove("len");
        v
    };
    let expected: Vec<Value> = flipped
        .iter()
        .map(|l| strip(&serde_json::from_str(l).unwrap()))
        .collect();
    let got: Vec<Value> = r.json().iter().map(strip).collect();
    assert_eq!(got, expected);
    assert_eq!(round_trip(&bytes, &[]), 41);
    assert_eq!(round_trip(&bytes, &["--from", "host"]), 19);
    assert_eq!(round_trip(&bytes, &["--from", "device"]), 22);
    // The 19 requests and the version response that was ae c1.
    assert_eq!(round_trip(&bytes, &["--checksum-only"]), 20);
}

#[test]
fn payloads_only_a_lossless_schema_survives() {
    // Intersection with a reserved byte, a line's reserved byte and a
    // nonzero slot past its one line.
    let mut crossing = vec![0x02, 28, 40, 20, 1, 9, 2, 3, 5, 0];
    crossing.extend([0; 4]);
    crossing.extend([7, 0, 0xa6, 0xff]);
    crossing.extend([0; 12]);
    let mut sections = vec![0x01, 0];
    sections.extend([0x08, 3, 1, 2, 3]);
    sections.extend([0x01, 6, 1, 2, 3, 4, 5, 6]);
    sections.extend(&crossing);
    let mut odd_version = vec![0x00, 0x22, 3, 0, 10, 0];
    odd_version.extend(b"0123456789");
    let mut binary_version = odd_version.clone();
    binary_version[6..].copy_from_slice(&[0xff, 0xfe, 0, 0, 0, 0, 0, 0, 0, 0]);
    let frames = [
        // changeProg unpadded, with a NUL inside, not UTF-8, empty.
        frame(false, 0x02, b"video"),
        frame(false, 0x02, b"l\0x\0"),
        frame(true, 0x02, &[0xff, 0x00, 0x01]),
        frame(false, 0x02, b""),
        frame(false, 0x0c, &[7]),
        frame(true, 0x0f, &odd_version),
        frame(true, 0x0f, &binary_version),
        frame(true, 0x03, &[0]),
        frame(true, 0x31, &sections),
    ];
    let input = frames.concat();
    let r = decode(&[], &input);
    let fields: Vec<String> = r
        .json()
        .iter()
        .map(|v| {
            let mut v = v.clone();
            let map = v.as_object_mut().unwrap();
            map.remove("offset");
            map.remove("len");
            v.to_string()
        })
        .collect();
    assert_eq!(
        fields,
        [
            r#"{"checksum":false,"name":"video","payload_len":5,"type":"change_prog"}"#,
            r#"{"checksum":false,"name":"l\u0000x","payload_len":4,"type":"change_prog"}"#,
            r#"{"checksum":true,"name":[255,0,1],"payload_len":3,"type":"change_prog"}"#,
            r#"{"checksum":false,"name":"","payload_len":0,"type":"change_prog"}"#,
            r#"{"checksum":false,"reserved":7,"type":"get_resolution"}"#,
            r#"{"checksum":true,"firmware_build":10,"firmware_major":3,"firmware_minor":0,"firmware_type":"0123456789","hardware":8704,"type":"version"}"#,
            r#"{"checksum":true,"firmware_build":10,"firmware_major":3,"firmware_minor":0,"firmware_type":[255,254],"hardware":8704,"type":"version"}"#,
            r#"{"checksum":true,"code":0,"type":"error"}"#,
            concat!(
                r#"{"checksum":true,"sections":[{"vectors":[]},{"data":[1,2,3],"ftype":8},"#,
                r#"{"vectors":[{"flags":6,"index":5,"x0":1,"x1":3,"y0":2,"y1":4}]},"#,
                r#"{"intersections":[{"lines":[{"angle":5,"index":2,"reserved":3}],"reserved":9,"#,
                r#""unused_slots":[{"angle":0,"index":0},{"angle":-90,"index":7},{"angle":0,"index":0},"#,
                r#"{"angle":0,"index":0},{"angle":0,"index":0}],"x":40,"y":20}]}],"type":"features"}"#
            ),
        ]
    );
    assert_eq!(round_trip(&input, &[]), frames.len());
}

// ---------------------------------------------------------------- malformed input

#[test]
fn malformed_json_lines() {
    let many_blocks = format!(
        r#"{{"type":"blocks","blocks":[{}]}}"#,
        vec![BLOCK_1; 19].join(",")
    );
    let vectors = |n: usize| {
        let v = r#"{"x0":1,"y0":2,"x1":3,"y1":4,"index":5,"flags":0}"#;
        format!(r#"{{"vectors":[{}]}}"#, vec![v; n].join(","))
    };
    let too_long_section = format!(r#"{{"type":"features","sections":[{}]}}"#, vectors(43));
    let too_long_payload = format!(
        r#"{{"type":"features","sections":[{},{}]}}"#,
        vectors(42),
        vectors(1)
    );
    let line = |i: i64| format!(r#"{{"index":1,"angle":{i}}}"#);
    let seven_lines = format!(
        r#"{{"type":"features","sections":[{{"intersections":[{{"x":1,"y":2,"lines":[{}]}}]}}]}}"#,
        (0..7).map(line).collect::<Vec<_>>().join(",")
    );
    let unused = format!(
        r#"{{"type":"features","sections":[{{"intersections":[{{"x":1,"y":2,"lines":[{}],"unused_slots":[{}]}}]}}]}}"#,
        line(0),
        line(0)
    );
    let cases: Vec<(String, &str)> = vec![
        (r#"{"sigmap":1}"#.into(), "missing field `type`"),
        (r#"{"type":"get_verison"}"#.into(), "unknown type `get_verison` (did you mean `get_version`?)"),
        (r#"{"type":"get_version","extra":1}"#.into(), "unknown field `extra` for type get_version"),
        (r#"{"type":"get_fps","checksum":1}"#.into(), "field `checksum` must be true or false, found 1"),
        (
            r#"{"type":"get_blocks","sigmap":0,"max_blocks":1}"#.into(),
            "field `sigmap` must be an integer 1..=255, found 0 (the device refuses 0 with ERROR -3; \
             decode marks such a request \"quirk\":\"sigmap_zero\": add that to the line to \
             encode it anyway)",
        ),
        (r#"{"type":"get_blocks","sigmap":1}"#.into(), "missing field `max_blocks`"),
        (
            r#"{"type":"set_servos","pan":65536,"tilt":0}"#.into(),
            "field `pan` must be an integer 0..=65535, found 65536",
        ),
        (
            r#"{"type":"set_next_turn","angle":-32769}"#.into(),
            "field `angle` must be an integer -32768..=32767, found -32769",
        ),
        (
            r#"{"type":"result","value":2147483648}"#.into(),
            "field `value` must be an integer -2147483648..=2147483647, found 2147483648",
        ),
        (
            r#"{"type":"error","code":"bogus"}"#.into(),
            "field `code` `bogus` is no device error name (general, busy, invalid_request, \
             type_unsupported, button_override, prog_changing) or code -128..=127",
        ),
        (
            r#"{"type":"error","code":-129}"#.into(),
            "field `code` must be a device error name or an integer -128..=127, found -129",
        ),
        (
            r#"{"type":"change_prog","name":"line","payload_len":65}"#.into(),
            "field `payload_len` must be an integer 0..=64, found 65",
        ),
        (
            format!(r#"{{"type":"change_prog","name":"{}"}}"#, "x".repeat(34)),
            "field `name` is 34 bytes long, more than the 33-byte payload (give payload_len, up to 64)",
        ),
        (
            r#"{"type":"change_prog","name":[1,256]}"#.into(),
            "field `name` byte must be an integer 0..=255, found 256",
        ),
        (
            r#"{"type":"version","hardware":1,"firmware_major":3,"firmware_minor":0,"firmware_build":1,"firmware_type":"general-xyz"}"#.into(),
            "field `firmware_type` is 11 bytes long, at most 10 fit",
        ),
        (many_blocks, "field `blocks` holds 19 entries, at most 18 fit"),
        (r#"{"type":"blocks","blocks":[{"signature":1}]}"#.into(), "missing field `blocks[0].x`"),
        (
            format!(r#"{{"type":"blocks","blocks":[{}]}}"#, BLOCK_1.replace("}", r#","colour":1}"#)),
            "unknown field `colour` in `blocks[0]`",
        ),
        (r#"{"type":"blocks","blocks":[1]}"#.into(), "field `blocks[0]` must be an object, found 1"),
        (
            r#"{"type":"features","sections":[{}]}"#.into(),
            "field `sections[0]` must have one of vectors, intersections, barcodes or ftype and data",
        ),
        (
            r#"{"type":"features","sections":[{"vectors":[],"barcodes":[]}]}"#.into(),
            "unknown field `barcodes` in `sections[0]`",
        ),
        (
            r#"{"type":"features","sections":[{"ftype":1,"data":[]}]}"#.into(),
            "field `sections[0].ftype` 1 is a known feature type: write its section as vectors, intersections or barcodes",
        ),
        (
            r#"{"type":"features","sections":[{"barcodes":[{"x":1,"y":2,"flags":0,"code":300}]}]}"#.into(),
            "field `sections[0].barcodes[0].code` must be an integer 0..=255, found 300",
        ),
        (too_long_section, "field `sections[0]` is 258 bytes long, at most 255 fit"),
        (too_long_payload, "field `sections` makes a 262-byte payload, at most 255 fit"),
        (seven_lines, "field `sections[0].intersections[0].lines` holds 7 entries, at most 6 fit"),
        (
            unused,
            "field `sections[0].intersections[0].unused_slots` must hold 5 entries (the slots after the lines), found 1",
        ),
    ];
    for (line, message) in &cases {
        let input = format!("{{\"type\":\"get_fps\"}}\n{line}\n{{\"type\":\"reverse_vector\"}}\n");
        let r = run(&["encode", "pixy2", "--hex"], input.as_bytes());
        assert_eq!(r.code, 2, "{line}");
        // Nothing is written for the bad line; the others are encoded.
        assert_eq!(r.text(), "ae c1 18 00\nae c1 3e 00\n", "{line}");
        assert_eq!(
            r.stderr,
            format!("robowire: stdin: line 2: {message}\nrobowire: 1 malformed line\n"),
            "{line}"
        );
    }
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["decode", "pixy2", "--from", "camera"][..],
        &["decode", "pixy2", "--chunk", "0"],
        &["decode", "pixy2", "--layout", "ble53"],
        &["encode", "pixy2", "--checksum-only"],
        &["encode", "pixy2", "--errors"],
    ] {
        let r = run(args, b"");
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert_eq!(r.stdout, b"", "{args:?}");
        assert!(!r.stderr.is_empty(), "{args:?}");
    }
    let r = run(&["decode", "pixy2", "--hex"], b"ae c1 0e 00 zz");
    assert_eq!(r.code, 2);
    assert_eq!(
        r.lines(),
        [r#"{"offset":0,"len":4,"type":"get_version","checksum":false}"#]
    );
}

#[test]
fn empty_input() {
    let r = decode(&[], b"");
    assert_eq!((r.stdout.len(), r.stderr), (0, summary(0, 0, 0, 0, 0, 0)));
    let r = run(&["encode", "pixy2"], b"");
    assert_eq!((r.code, r.stdout.len(), r.stderr.as_str()), (0, 0, ""));
}

#[test]
fn help_documents_the_contract() {
    let r = run(&["decode", "pixy2", "--help"], b"");
    assert_eq!(r.code, 0);
    for needle in [
        "--from <FROM>",
        "host:",
        "device:",
        "--checksum-only",
        "--chunk <N>",
        "--hex",
        "--errors",
        "[INPUT]",
        "checksum  true for the checksum form",
        "get_features",
        "unused_slots",
        r#"{"offset":52,"error":"bad_length","packet_type":18,"payload_len":3}"#,
        "Exit status: 0 on success, 2 on usage errors",
    ] {
        assert!(
            r.text().contains(needle),
            "decode pixy2 --help lacks {needle}"
        );
    }
    let r = run(&["encode", "pixy2", "--help"], b"");
    assert!(r.text().contains("checksum may be left out"));
    let r = run(&["decode", "--help"], b"");
    assert!(r.text().contains("pixy2"));
}

#[test]
fn get_blocks_with_sigmap_zero_decodes_as_the_request_it_is() {
    // What the official host library sends for sigmap 0 (the camera answers
    // ERROR -3); it was rejected as malformed.
    for from in ["host", "any"] {
        let r = decode(
            &["--hex", "--errors", "--from", from],
            b"ae c1 20 02 00 05  af c1 20 02 05 00 00 05",
        );
        assert_eq!(
            r.lines(),
            [
                r#"{"offset":0,"len":6,"type":"get_blocks","checksum":false,"sigmap":0,"max_blocks":5,"quirk":"sigmap_zero"}"#,
                r#"{"offset":6,"len":8,"type":"get_blocks","checksum":true,"sigmap":0,"max_blocks":5,"quirk":"sigmap_zero"}"#,
            ],
            "--from {from}"
        );
    }
}
