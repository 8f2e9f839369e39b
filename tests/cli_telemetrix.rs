//! `robowire decode telemetrix` and `robowire encode telemetrix`: the spec's
//! golden examples both ways and in the upstream dialect, chunking
//! invariance, `--from any`, typed MODULE_DATA, diagnostics, the decode |
//! encode round trip in every dialect, and malformed input.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data, data_arg, hex, run, Run};

use robowire::telemetrix::host_decoder;

fn summary(frames: u64, bytes: u64, skipped: u64, other: u64) -> String {
    cli_common::summary_line([frames, bytes, skipped, 0, other, 0])
}

// ---------------------------------------------------------------- golden examples

/// Spec §12, host → Pico: each frame's bytes and its JSON after `len`. An
/// empty JSON marks bytes that are no frame (the port probe's zeros).
const HOST: [(&str, &str); 29] = [
    ("01 05", r#""type":"get_firmware_version""#),
    ("01 06", r#""type":"get_pico_unique_id""#),
    ("02 20 07", r#""type":"ping","counter":7"#),
    ("01 23", r#""type":"get_id""#),
    ("02 24 05", r#""type":"set_id","id":5"#),
    ("02 25 05", r#""type":"feature_request","msg_type":5"#),
    ("00 00 00 00 00 00 00", ""),
    ("01 05", r#""type":"get_firmware_version""#),
    (
        "03 01 19 01",
        r#""type":"set_pin_mode","pin":25,"mode":"digital_output""#,
    ),
    (
        "03 02 19 01",
        r#""type":"digital_write","pin":25,"value":1"#,
    ),
    (
        "04 01 0A 03 01",
        r#""type":"set_pin_mode","pin":10,"mode":"digital_input_pull_up","report_enable":true"#,
    ),
    (
        "06 01 1A 05 00 05 01",
        r#""type":"set_pin_mode","pin":26,"mode":"analog_input","differential":5,"report_enable":true"#,
    ),
    (
        "04 03 0F 05 DC",
        r#""type":"pwm_write","pins":[{"pin":15,"value":1500}]"#,
    ),
    (
        "07 03 0F 05 DC 10 05 DC",
        r#""type":"pwm_write","pins":[{"pin":15,"value":1500},{"pin":16,"value":1500}]"#,
    ),
    ("03 0D 09 0A", r#""type":"sonar_new","trig":9,"echo":10"#),
    (
        "05 1E 02 0E 0F 01",
        r#""type":"encoder_new","kind":"quadrature","pin_a":14,"pin_b":15,"pulls":{"up":true,"down":false}"#,
    ),
    (
        "04 0A 00 00 00",
        r#""type":"i2c_begin","port":0,"sda":0,"scl":0"#,
    ),
    (
        "08 0C 00 3C 07 02 00 00 AF",
        r#""type":"i2c_write","port":0,"addr":60,"msg_id":7,"no_stop":0,"data":[0,175]"#,
    ),
    (
        "07 0B 00 68 03 75 01 00",
        r#""type":"i2c_read","port":0,"addr":104,"msg_id":3,"reg":117,"n":1,"no_stop":0"#,
    ),
    ("01 0F", r#""type":"stop_all_reports""#),
    ("01 10", r#""type":"enable_all_reports""#),
    ("02 1D 32", r#""type":"set_scan_delay","delay_ms":50"#),
    ("02 00 41", r#""type":"serial_loop_back","byte":65"#),
    (
        "03 1F 00 02",
        r#""type":"sensor_new","subtype":"check","sensor_type":"mpu9250""#,
    ),
    (
        "0A 1F 01 00 06 01 40 00 00 00 00",
        r#""type":"sensor_new","subtype":"add","sensor_num":0,"sensor_type":"ina226","settings":[1,64,0,0,0,0]"#,
    ),
    (
        "03 21 00 01",
        r#""type":"module_new","subtype":"check","module_type":"hiwonder_servo""#,
    ),
    (
        "0A 21 01 00 01 00 01 00 02 01 02",
        r#""type":"module_new","subtype":"add","module_num":0,"module_type":"hiwonder_servo","init":{"uart":0,"rx":1,"tx":0,"bus_ids":[1,2]}"#,
    ),
    // Module 0 was just added as a Hiwonder: its data is typed.
    (
        "09 22 00 01 01 00 2E E0 01 F4",
        r#""type":"module_data","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"set_angle","moves":[{"idx":0,"centideg":12000,"time_ms":500}]}"#,
    ),
    // Module 1 was never added here: raw bytes.
    (
        "07 22 01 03 00 00 01 2C",
        r#""type":"module_data","module_num":1,"data":[3,0,0,1,44]"#,
    ),
];

/// Spec §12, Pico → host. The spec's PONG example has boot_id `BB`, a
/// placeholder for 0..99 (the decoder rejects 187): 0x2A here.
const PICO: [(&str, &str); 25] = [
    (
        "03 05 01 03",
        r#""type":"firmware_version","major":1,"minor":3"#,
    ),
    (
        "09 06 b0 b1 b2 b3 b4 b5 00 00",
        r#""type":"pico_unique_id","id":[176,177,178,179,180,181,0,0]"#,
    ),
    ("03 20 07 2A", r#""type":"pong","counter":7,"boot_id":42"#),
    ("02 23 05", r#""type":"get_id_report","id":5"#),
    ("02 24 05", r#""type":"set_id_report","id":5"#),
    (
        "05 25 05 01 01 03",
        r#""type":"feature_check","msg_type":5,"ok":true,"extras":[1,3]"#,
    ),
    (
        "0C 25 01 01 1E 0C 0E 05 1A 1B 1C 1D 1E",
        r#""type":"feature_check","msg_type":1,"ok":true,"extras":[30,12,14,5,26,27,28,29,30]"#,
    ),
    (
        "06 25 1E 01 04 02 01",
        r#""type":"feature_check","msg_type":30,"ok":true,"extras":[4,2,1]"#,
    ),
    (
        "04 25 0D 01 04",
        r#""type":"feature_check","msg_type":13,"ok":true,"extras":[4]"#,
    ),
    (
        "03 25 20 01",
        r#""type":"feature_check","msg_type":32,"ok":true,"extras":[]"#,
    ),
    (
        "03 25 32 00",
        r#""type":"feature_check","msg_type":50,"ok":false,"extras":[]"#,
    ),
    (
        "04 15 00 02 01",
        r#""type":"sensor_main_report","sensor_type":"mpu9250","supported":true"#,
    ),
    (
        "04 15 00 00 00",
        r#""type":"sensor_main_report","sensor_type":"gps","supported":false"#,
    ),
    (
        "04 21 00 01 01",
        r#""type":"module_main_report","module_type":"hiwonder_servo","supported":true"#,
    ),
    (
        "03 02 0A 01",
        r#""type":"digital_report","pin":10,"value":1"#,
    ),
    (
        "04 03 1A 08 00",
        r#""type":"analog_report","pin":26,"value":2048"#,
    ),
    (
        "05 0B 09 0A 00 64",
        r#""type":"sonar_distance","trig":9,"echo":10,"cm":100"#,
    ),
    (
        "05 0B 09 0A FF FD",
        r#""type":"sonar_distance","trig":9,"echo":10,"cm":"out_of_range""#,
    ),
    (
        "03 0E 0E FD",
        r#""type":"encoder_report","pin_a":14,"steps":-3"#,
    ),
    (
        "04 08 00 07 02",
        r#""type":"i2c_write_report","port":0,"msg_id":7,"result":2"#,
    ),
    (
        "04 08 00 07 FF",
        r#""type":"i2c_write_report","port":0,"msg_id":7,"result":-1"#,
    ),
    (
        "07 0A 00 03 75 01 00 71",
        r#""type":"i2c_read_report","port":0,"msg_id":3,"reg":117,"data":[113]"#,
    ),
    (
        "07 22 00 01 00 00 2E E0",
        r#""type":"module_report","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"positions","positions":[{"idx":0,"centideg":12000}]}"#,
    ),
    ("02 00 41", r#""type":"serial_loop_back_report","byte":65"#),
    (
        "04 63 1E 00 01",
        r#""type":"debug_print","id":30,"value":1"#,
    ),
];

/// Spec §12, upstream dialect, host → Pico.
const UPSTREAM_HOST: [(&str, &str); 1] = [(
    "06 0B 00 68 75 01 00",
    r#""type":"i2c_read","port":0,"addr":104,"reg":117,"n":1,"no_stop":0"#,
)];

/// Spec §12, upstream dialect, Pico → host (and its firmware report, §10).
const UPSTREAM_PICO: [(&str, &str); 3] = [
    (
        "06 0A 00 68 75 01 71",
        r#""type":"i2c_read_report","port":0,"addr":104,"reg":117,"data":[113]"#,
    ),
    (
        "04 0B 09 0C 22",
        r#""type":"sonar_distance","trig":9,"cm":12,"hundredths":34"#,
    ),
    (
        "03 05 01 01",
        r#""type":"firmware_version","major":1,"minor":1"#,
    ),
];

/// Golden examples: each frame's bytes (hex) and its JSON after `len`.
type Examples<'a> = &'a [(&'a str, &'a str)];

/// The examples' bytes as one stream, and the JSON lines decode prints.
fn golden(examples: &[(&str, &str)]) -> (Vec<u8>, Vec<String>) {
    let mut bytes = Vec::new();
    let mut lines = Vec::new();
    for (frame, json) in examples {
        let frame = hex(frame);
        if !json.is_empty() {
            let (offset, len) = (bytes.len(), frame.len());
            lines.push(format!(r#"{{"offset":{offset},"len":{len},{json}}}"#));
        }
        bytes.extend(frame);
    }
    (bytes, lines)
}

fn as_hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x} ")).collect()
}

#[test]
fn decode_golden_examples() {
    let cases: [(Examples, &[&str]); 4] = [
        (&HOST, &["--from", "host"]),
        (&PICO, &["--from", "pico"]),
        (
            &UPSTREAM_HOST,
            &["--from", "host", "--dialect", "upstream11"],
        ),
        (
            &UPSTREAM_PICO,
            &["--from", "pico", "--dialect", "upstream11"],
        ),
    ];
    for (examples, options) in cases {
        let (bytes, expected) = golden(examples);
        let mut args = vec!["decode", "telemetrix", "--errors"];
        args.extend_from_slice(options);
        let r = run(&args, &bytes);
        assert_eq!(r.code, 0, "{options:?}: {}", r.stderr);
        assert_eq!(r.lines(), expected, "{options:?}");
        // Only the port probe's zeros are skipped.
        let skipped: usize = examples
            .iter()
            .filter(|(_, json)| json.is_empty())
            .map(|(frame, _)| hex(frame).len())
            .sum();
        let frames = expected.len() as u64;
        assert_eq!(
            r.stderr,
            summary(frames, bytes.len() as u64, skipped as u64, 0),
            "{options:?}"
        );
        // The same bytes as hex text.
        args.push("--hex");
        let from_hex = run(&args, as_hex(&bytes).as_bytes());
        assert_eq!(from_hex.stdout, r.stdout, "{options:?} --hex");
    }
}

#[test]
fn encode_golden_examples() {
    let cases: [(Examples, &str); 4] = [
        (&HOST, "mirte13"),
        (&PICO, "mirte13"),
        (&UPSTREAM_HOST, "upstream11"),
        (&UPSTREAM_PICO, "upstream11"),
    ];
    for (examples, dialect) in cases {
        // Without offset and len, one line per frame, in hex.
        let mut input = String::new();
        let mut expected = String::new();
        for (frame, json) in examples.iter().filter(|(_, json)| !json.is_empty()) {
            input.push_str(&format!("{{{json}}}\n"));
            expected.push_str(&format!("{}\n", frame.to_lowercase()));
        }
        let r = run(
            &["encode", "telemetrix", "--hex", "--dialect", dialect],
            input.as_bytes(),
        );
        assert_eq!(r.code, 0, "{}", r.stderr);
        assert_eq!(r.text(), expected);
        assert_eq!(r.stderr, "");
    }
}

#[test]
fn firmware_reports_of_each_dialect() {
    for (dialect, minor) in [("mirte13", 3), ("mirte12", 2), ("upstream11", 1)] {
        let r = run(
            &["decode", "telemetrix", "--hex", "--dialect", dialect],
            format!("03 05 01 0{minor}").as_bytes(),
        );
        assert_eq!(
            r.text(),
            format!(
                "{{\"offset\":0,\"len\":4,\"type\":\"firmware_version\",\"major\":1,\"minor\":{minor}}}\n"
            )
        );
    }
    // The mirte 1.2 sonar report: metres and centimetres.
    let r = run(
        &["decode", "telemetrix", "--hex", "--dialect", "mirte12"],
        b"04 0B 09 01 17",
    );
    assert_eq!(
        r.lines(),
        [r#"{"offset":0,"len":5,"type":"sonar_distance","trig":9,"m":1,"cm":23}"#]
    );
}

// ---------------------------------------------------------------- --from any

#[test]
fn from_any_attributes_ambiguous_frames_by_context() {
    // Reports first: a digital report is also a digital write, and is taken
    // as a report until a frame valid one way only says otherwise. Then the
    // host: SET_PIN_MODE is a command only, so the digital write after it
    // is a command. A PONG (a report only) turns it back.
    let input = "03 02 0A 01  03 01 19 01 03 02 19 01  03 20 07 2A 03 02 0A 00";
    let r = run(&["decode", "telemetrix", "--hex"], input.as_bytes());
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":4,"type":"digital_report","also":"digital_write","pin":10,"value":1}"#,
            r#"{"offset":4,"len":4,"type":"set_pin_mode","pin":25,"mode":"digital_output"}"#,
            r#"{"offset":8,"len":4,"type":"digital_write","also":"digital_report","pin":25,"value":1}"#,
            r#"{"offset":12,"len":4,"type":"pong","counter":7,"boot_id":42}"#,
            r#"{"offset":16,"len":4,"type":"digital_report","also":"digital_write","pin":10,"value":0}"#,
        ]
    );
    // The same bytes one way only: no "also", and what the other way cannot
    // read is skipped.
    let host = run(
        &["decode", "telemetrix", "--hex", "--from", "host"],
        input.as_bytes(),
    );
    assert_eq!(host.lines().len(), 4);
    assert!(host.text().contains(r#""type":"digital_write","pin":10"#));
    assert!(!host.text().contains("also"));
    let pico = run(
        &["decode", "telemetrix", "--hex", "--from", "pico"],
        input.as_bytes(),
    );
    assert_eq!(pico.lines().len(), 4);
    assert!(pico.text().contains(r#""type":"digital_report","pin":25"#));
}

/// Drop `"also":…` from JSON lines.
fn without_also(text: &str) -> String {
    text.lines()
        .map(|l| match l.find(r#","also":""#) {
            Some(at) => {
                let end = at + 9 + l[at + 9..].find('"').unwrap() + 1;
                format!("{}{}\n", &l[..at], &l[end..])
            }
            None => format!("{l}\n"),
        })
        .collect()
}

#[test]
fn from_any_on_the_sample_captures() {
    // The host's start-up: every frame as --from host finds it, each
    // ambiguous one (the LED's digital writes) attributed to the host.
    let commands = data_arg("telemetrix_commands.hex");
    let host = run(
        &["decode", "telemetrix", "--hex", "--from", "host", &commands],
        b"",
    );
    let any = run(&["decode", "telemetrix", "--hex", &commands], b"");
    assert_eq!(any.code, 0);
    assert_eq!(without_also(any.text()), host.text());
    assert_eq!(any.text().matches(r#""also":"digital_report""#).count(), 7);
    assert_eq!(any.stderr, host.stderr);
    // The Pico's reports: the frames of --from pico, reports where
    // ambiguous, and one spurious command among corrupted bytes.
    let reports = data_arg("telemetrix_reports.bin");
    let pico = run(&["decode", "telemetrix", "--from", "pico", &reports], b"");
    let any = run(&["decode", "telemetrix", &reports], b"");
    let any_lines = without_also(any.text());
    let extra: Vec<&str> = any_lines
        .lines()
        .filter(|l| !pico.text().lines().any(|p| p == *l))
        .collect();
    assert_eq!(
        extra,
        [r#"{"offset":767,"len":4,"type":"module_data","module_num":26,"data":[0]}"#]
    );
    assert_eq!(any_lines.lines().count(), pico.lines().len() + 1);
    assert!(any.text().matches("\"also\":").count() > 40);
    for line in any.lines() {
        if line.contains("\"also\":") {
            assert!(line.contains("_report\",\"also\""), "{line}");
        }
    }
}

// ---------------------------------------------------------------- module data

#[test]
fn module_data_is_typed_after_module_new() {
    let input = concat!(
        // Module 1 is a PCA9685, module 2 an SSD1306, module 3 a relay.
        "08 21 01 01 00 00 41 00 32  05 21 01 02 03 00  07 21 01 03 02 05 01 0a  ",
        // The spec's PCA9685 data for module 1.
        "07 22 01 03 00 00 01 2C  ",
        // Text "Hi" to the display, then TEXT_DONE.
        "06 22 02 00 02 48 69  03 22 02 01  ",
        // Start the relay's countdown; bytes no module type reads stay raw.
        "03 22 03 01  03 22 03 07  ",
        // After a reset, nothing is known.
        "01 12  07 22 01 03 00 00 01 2C",
    );
    let r = run(
        &["decode", "telemetrix", "--hex", "--from", "host"],
        input.as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    let lines = r.lines();
    assert_eq!(
        lines[0],
        r#"{"offset":0,"len":9,"type":"module_new","subtype":"add","module_num":1,"module_type":"pca9685","init":{"port":0,"addr":65,"freq_hz":50}}"#
    );
    assert_eq!(
        lines[1],
        r#"{"offset":9,"len":6,"type":"module_new","subtype":"add","module_num":2,"module_type":"ssd1306","init":{"port":0}}"#
    );
    assert_eq!(
        lines[2],
        r#"{"offset":15,"len":8,"type":"module_new","subtype":"add","module_num":3,"module_type":"shutdown_relay","init":{"pin":5,"active_level":1,"wait_s":10}}"#
    );
    assert_eq!(
        &lines[3..],
        [
            r#"{"offset":23,"len":8,"type":"module_data","module_num":1,"module_type":"pca9685","message":{"channels":[{"channel":3,"on":0,"off":300}]}}"#,
            r#"{"offset":31,"len":7,"type":"module_data","module_num":2,"module_type":"ssd1306","message":{"subtype":"text","text":"Hi"}}"#,
            r#"{"offset":38,"len":4,"type":"module_data","module_num":2,"module_type":"ssd1306","message":{"subtype":"text_done"}}"#,
            r#"{"offset":42,"len":4,"type":"module_data","module_num":3,"module_type":"shutdown_relay","message":{"subtype":"start"}}"#,
            r#"{"offset":46,"len":4,"type":"module_data","module_num":3,"data":[7]}"#,
            r#"{"offset":50,"len":2,"type":"reset_board"}"#,
            r#"{"offset":52,"len":8,"type":"module_data","module_num":1,"data":[3,0,0,1,44]}"#,
        ]
    );
    // Both forms encode back to the same bytes.
    let back = run(&["encode", "telemetrix"], &r.stdout);
    assert_eq!(back.code, 0, "{}", back.stderr);
    assert_eq!(back.stdout, hex(input));
    // Text is one character per byte, so any byte survives.
    let text = r#"{"type":"module_data","module_num":2,"module_type":"ssd1306","message":{"subtype":"text","text":"\u0000é\"\\"}}"#;
    let r = run(&["encode", "telemetrix", "--hex"], text.as_bytes());
    assert_eq!(r.text(), "08 22 02 00 04 00 e9 22 5c\n");
}

// ---------------------------------------------------------------- sensors and floats

#[test]
fn sensor_readings_are_typed_and_floats_round_trip() {
    // INA226 with awkward floats, an MPU6050, an AS5600 pair and a BNO055.
    let mut frames = Vec::new();
    let mut ina = hex("0b 14 00 06");
    for bits in [0x7fc0_0001u32, 0x15ae_43fd] {
        ina.extend(bits.to_le_bytes());
    }
    frames.push(ina);
    frames.push(hex("11 14 01 09 00 10 ff f0 40 00 00 01 ff ff 00 02 0b b8"));
    frames.push(hex("07 14 02 08 00 00 0f ff"));
    let mut bno = hex("38 14 03 0a");
    for i in 0..13u32 {
        bno.extend((i as f32 * 0.5 - 1.0).to_le_bytes());
    }
    bno.push(0xe7);
    frames.push(bno);
    let input: Vec<u8> = frames.concat();
    let r = run(&["decode", "telemetrix", "--from", "pico"], &input);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":12,"type":"sensor_report","sensor_num":0,"sensor_type":"ina226","reading":{"volts":"nan:0x7fc00001","amps":7.038530691851209e-26}}"#,
            r#"{"offset":12,"len":18,"type":"sensor_report","sensor_num":1,"sensor_type":"mpu6050","reading":{"accel":[16,-16,16384],"gyro":[1,-1,2],"temp":3000}}"#,
            r#"{"offset":30,"len":8,"type":"sensor_report","sensor_num":2,"sensor_type":"as5600","reading":{"angles":[0,4095]}}"#,
            concat!(
                r#"{"offset":38,"len":57,"type":"sensor_report","sensor_num":3,"sensor_type":"bno055","reading":{"gyro":[-1.0,-0.5,0.0],"mag":[0.5,1.0,1.5],"#,
                r#""accel":[2.0,2.5,3.0],"quat":[3.5,4.0,4.5,5.0],"temp":-25}}"#
            ),
        ]
    );
    let back = run(&["encode", "telemetrix"], &r.stdout);
    assert_eq!(back.code, 0, "{}", back.stderr);
    assert_eq!(back.stdout, input);
}

// ---------------------------------------------------------------- chunking

/// The option sets worth checking on each capture.
const CASES: [(&str, &[&str]); 6] = [
    ("telemetrix_reports.bin", &["--from", "pico"]),
    ("telemetrix_reports.bin", &[]),
    ("telemetrix_reports.bin", &["--from", "pico", "--lenient"]),
    ("telemetrix_reports.bin", &["--from", "any", "--lenient"]),
    ("telemetrix_commands.hex", &["--hex", "--from", "host"]),
    ("telemetrix_commands.hex", &["--hex"]),
];

fn decode_file(file: &str, extra: &[&str], chunk: &str) -> Run {
    let path = data_arg(file);
    let mut args = vec!["decode", "telemetrix", "--errors", "--chunk", chunk];
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
        assert!(whole.lines().len() > 80, "{file} {extra:?}");
        for chunk in ["1", "2", "5", "64", "100000"] {
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
fn from_pico_matches_the_library_decoder() {
    let bytes = std::fs::read(data("telemetrix_reports.bin")).unwrap();
    let mut decoder = host_decoder();
    let mut events: Vec<_> = decoder.feed(&bytes).collect();
    events.extend(decoder.flush());
    let frames: Vec<(u64, usize)> = events
        .iter()
        .filter_map(|e| e.as_ref().ok().map(|f| (f.offset, f.len)))
        .collect();
    let rejections: Vec<u64> = events
        .iter()
        .filter_map(|e| e.as_ref().err().map(|r| r.offset))
        .collect();
    let r = decode_file("telemetrix_reports.bin", &["--from", "pico"], "4096");
    let json = r.json();
    let tool_frames: Vec<(u64, usize)> = json
        .iter()
        .filter(|v| v.get("type").is_some())
        .map(|v| {
            (
                v["offset"].as_u64().unwrap(),
                v["len"].as_u64().unwrap() as usize,
            )
        })
        .collect();
    let tool_rejections: Vec<u64> = json
        .iter()
        .filter(|v| v.get("error").is_some())
        .map(|v| v["offset"].as_u64().unwrap())
        .collect();
    assert_eq!(tool_frames, frames);
    assert_eq!(tool_rejections, rejections);
    let stats = decoder.stats();
    assert_eq!(
        r.stderr,
        summary(
            stats.frames,
            stats.bytes,
            stats.skipped,
            stats.other_rejections
        )
    );
    assert_eq!(r.stderr, summary(217, 1283, 20, 17));
}

// ---------------------------------------------------------------- --errors

#[test]
fn errors_are_reported_as_events() {
    // An unknown report id, an impossible LEN for a digital report, an
    // analog value over 4095, padding, a good PONG, padding, and a cut-off
    // frame. Each rejection costs one byte, so the bytes after a bad start
    // are tried as starts too.
    let input = "02 07 01  07 02 0A 01  04 03 1A 10 00  00  03 20 07 2A  00 00  05 0B 09";
    let r = run(
        &[
            "decode",
            "telemetrix",
            "--from",
            "pico",
            "--hex",
            "--errors",
        ],
        input.as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"error":"unknown_id","id":7}"#,
            r#"{"offset":1,"error":"unknown_id","id":1}"#,
            r#"{"offset":2,"error":"unknown_id","id":7}"#,
            r#"{"offset":3,"error":"bad_length","id":2,"len_byte":7}"#,
            r#"{"offset":4,"error":"bad_length","id":10,"len_byte":2}"#,
            r#"{"offset":5,"error":"unknown_id","id":1}"#,
            r#"{"offset":6,"error":"unknown_id","id":4}"#,
            r#"{"offset":7,"error":"out_of_range","id":3,"field":"value"}"#,
            r#"{"offset":8,"error":"unknown_id","id":26}"#,
            r#"{"offset":9,"error":"unknown_id","id":16}"#,
            r#"{"offset":10,"error":"bad_length","id":0,"len_byte":16}"#,
            r#"{"offset":13,"len":4,"type":"pong","counter":7,"boot_id":42}"#,
            r#"{"offset":19,"error":"truncated","len":3}"#,
            r#"{"offset":20,"error":"bad_length","id":9,"len_byte":11}"#,
            r#"{"offset":21,"error":"truncated","len":1}"#,
        ]
    );
    // 14 rejections; skipped: their 14 start bytes and 4 zeros.
    assert_eq!(r.stderr, summary(1, 22, 18, 14));
    // Without --errors the same run prints only the frame and the same summary.
    let quiet = run(
        &["decode", "telemetrix", "--from", "pico", "--hex"],
        input.as_bytes(),
    );
    assert_eq!(quiet.lines().len(), 1);
    assert_eq!(quiet.stderr, r.stderr);
    // Commands: a LEN over 30 is dropped where a frame would start (as the
    // firmware drops it), an unknown id and a pin out of range are rejected.
    let r = run(
        &[
            "decode",
            "telemetrix",
            "--from",
            "host",
            "--hex",
            "--errors",
        ],
        b"1f 02 2a 03 02 1e 01 01 05",
    );
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":1,"error":"unknown_id","id":42}"#,
            r#"{"offset":3,"error":"out_of_range","id":2,"field":"pin"}"#,
            r#"{"offset":4,"error":"bad_length","id":30,"len_byte":2}"#,
            r#"{"offset":5,"error":"bad_length","id":1,"len_byte":30}"#,
            r#"{"offset":6,"error":"bad_length","id":1,"len_byte":1}"#,
            r#"{"offset":7,"len":2,"type":"get_firmware_version"}"#,
        ]
    );
    assert_eq!(r.stderr, summary(1, 9, 7, 5));
}

// ---------------------------------------------------------------- round trip

/// Decode `input` with `extra` options, encode the JSON back in `dialect`,
/// and check the bytes are exactly the decoded frames' bytes, in order.
fn round_trip(input: &[u8], extra: &[&str], dialect: &str) -> usize {
    // Some inputs are decoded from the wrong side on purpose: mostly noise.
    let mut args = vec!["decode", "telemetrix", "--errors", "--allow-noise"];
    args.extend_from_slice(&["--dialect", dialect]);
    args.extend_from_slice(extra);
    let decoded = run(&args, input);
    assert_eq!(decoded.code, 0, "{}", decoded.stderr);
    let mut expected = Vec::new();
    let mut frames = 0;
    // A frame flagged with a quirk (a real peer's, decoded as the firmware
    // reads it) is the encoder's to refuse: it is left out.
    let mut lines = Vec::new();
    for (line, event) in decoded.text().lines().zip(decoded.json()) {
        if event.get("quirk").is_none() {
            lines.extend_from_slice(line.as_bytes());
            lines.push(b'\n');
        }
        if event.get("type").is_some() && event.get("quirk").is_none() {
            let offset = event["offset"].as_u64().unwrap() as usize;
            let len = event["len"].as_u64().unwrap() as usize;
            expected.extend_from_slice(&input[offset..offset + len]);
            frames += 1;
        }
    }
    let encoded = run(&["encode", "telemetrix", "--dialect", dialect], &lines);
    assert_eq!(encoded.code, 0, "{extra:?} {dialect}: {}", encoded.stderr);
    assert!(
        encoded.stdout == expected,
        "{extra:?} {dialect}: round trip differs"
    );
    // And through hex, one frame per line.
    let as_hex = run(
        &["encode", "telemetrix", "--hex", "--dialect", dialect],
        &lines,
    );
    assert_eq!(as_hex.text().lines().count(), frames);
    assert_eq!(hex(as_hex.text()), expected);
    frames
}

#[test]
fn decode_then_encode_reproduces_every_frame() {
    let reports = std::fs::read(data("telemetrix_reports.bin")).unwrap();
    let commands = hex(&std::fs::read_to_string(data("telemetrix_commands.hex")).unwrap());
    let golden: Vec<u8> = [&HOST[..], &PICO, &UPSTREAM_HOST, &UPSTREAM_PICO]
        .iter()
        .flat_map(|examples| golden(examples).0)
        .collect();
    let mut frames = 0;
    for dialect in ["mirte13", "mirte12", "upstream11"] {
        let mut in_dialect = 0;
        for input in [&reports, &commands, &golden] {
            for from in ["host", "pico", "any"] {
                in_dialect += round_trip(input, &["--from", from], dialect);
            }
            in_dialect += round_trip(input, &["--from", "pico", "--lenient"], dialect);
            in_dialect += round_trip(input, &["--lenient"], dialect);
        }
        assert!(in_dialect > 300, "{dialect}: {in_dialect} frames");
        frames += in_dialect;
    }
    assert!(frames > 1500, "{frames} frames");
}

#[test]
fn lenient_decodes_unknown_reports() {
    // Report 40 (unknown to mirte 1.3) between two digital reports.
    let input = "03 02 0A 01  04 28 01 02 03  03 02 0A 00  04 28 09";
    let r = run(
        &[
            "decode",
            "telemetrix",
            "--from",
            "pico",
            "--lenient",
            "--hex",
            "--errors",
        ],
        input.as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":4,"type":"digital_report","pin":10,"value":1}"#,
            r#"{"offset":4,"len":5,"type":"unknown_report","id":40,"payload":[1,2,3]}"#,
            r#"{"offset":9,"len":4,"type":"digital_report","pin":10,"value":0}"#,
            // At the end nothing follows to confirm it.
            r#"{"offset":13,"error":"truncated","len":3}"#,
            r#"{"offset":14,"error":"bad_length","id":9,"len_byte":40}"#,
            r#"{"offset":15,"error":"truncated","len":1}"#,
        ]
    );
    let back = run(&["encode", "telemetrix", "--hex"], &r.stdout);
    assert_eq!(back.text(), "03 02 0a 01\n04 28 01 02 03\n03 02 0a 00\n");
    // Strict: the unknown frame is corruption.
    let strict = run(
        &["decode", "telemetrix", "--from", "pico", "--hex"],
        input.as_bytes(),
    );
    assert!(!strict.text().contains("unknown_report"));
}

// ---------------------------------------------------------------- malformed input

#[test]
fn malformed_json_lines() {
    let cases: &[(&str, &str)] = &[
        (r#"[1,2]"#, "expected a JSON object, found [1,2]"),
        (r#"{"counter":3}"#, "missing field `type`"),
        (r#"{"type":"pling"}"#, "unknown type `pling` (did you mean `ping`?)"),
        (r#"{"type":"ping"}"#, "missing field `counter`"),
        (
            r#"{"type":"ping","counter":256}"#,
            "field `counter` must be an integer 0..=255, found 256",
        ),
        (
            r#"{"type":"ping","counter":1,"boot_id":2}"#,
            "unknown field `boot_id` for type ping",
        ),
        (
            r#"{"type":"digital_write","pin":30,"value":1}"#,
            "field `pin` must be an integer 0..=29, found 30",
        ),
        (
            r#"{"type":"digital_write","pin":3,"value":true}"#,
            "field `value` must be an integer 0..=1, found true",
        ),
        (
            r#"{"type":"set_pin_mode","pin":3,"mode":"digital_input_pull_up","report_enable":1}"#,
            "field `report_enable` must be true or false, found 1",
        ),
        (
            r#"{"type":"set_pin_mode","pin":3,"mode":"input"}"#,
            "field `mode` must be one of digital_input, digital_input_pull_up, digital_input_pull_down, digital_output, pwm_output, analog_input, found \"input\"",
        ),
        (
            r#"{"type":"pwm_write","pins":[{"pin":3,"value":70000}]}"#,
            "in `pins[0]`: field `value` must be an integer 0..=65535, found 70000",
        ),
        (
            r#"{"type":"pwm_write","pins":[{"pin":3,"value":7,"duty":1}]}"#,
            "unknown field `duty` in `pins[0]`",
        ),
        (
            r#"{"type":"i2c_write","port":0,"addr":60,"msg_id":1,"no_stop":0,"data":[1,2,300]}"#,
            "field `data[2]` must be an integer 0..=255, found 300",
        ),
        (
            r#"{"type":"i2c_write","port":0,"addr":60,"msg_id":1,"no_stop":0,"data":[]}"#,
            "cannot encode i2c_write for mirte13: fields do not match the message's layout: \
             the payload length does not fit the message's layout",
        ),
        (
            r#"{"type":"encoder_new","kind":"quadrature","pin_a":14,"pin_b":15}"#,
            "missing field `pulls`",
        ),
        (
            r#"{"type":"encoder_new","kind":"quadrature","pin_a":14,"pin_b":15,"pulls":{"up":true}}"#,
            "in `pulls`: missing field `down`",
        ),
        (
            r#"{"type":"sensor_new","subtype":"add","sensor_num":0,"sensor_type":"bmp280","settings":[0,0,0,0,0,0]}"#,
            "field `sensor_type` must be one of gps, hx711, mpu9250, vl53l0x, veml6040, adxl345, ina226, hmc5883l, as5600, mpu6050, bno055 or a number 0..=255, found \"bmp280\"",
        ),
        (
            r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":"far"}"#,
            "field `cm` must be an integer or \"no_echo\", \"out_of_range\" or \"stale\", found \"far\"",
        ),
        (
            r#"{"type":"sonar_distance","trig":9,"echo":10,"cm":2000}"#,
            "cannot encode sonar_distance for mirte13: cm is out of range",
        ),
        (
            r#"{"type":"sensor_report","sensor_num":0,"sensor_type":"ina226","reading":{"volts":1e39,"amps":0}}"#,
            "in `reading`: field `volts` 1e+39 does not fit in an f32 (write \"inf\" for infinity)",
        ),
        (
            r#"{"type":"module_report","module_num":1,"module_type":"pca9685","message":{}}"#,
            "in `message`: module type pca9685 sends no reports",
        ),
        (
            r#"{"type":"module_data","module_num":0,"module_type":"hiwonder_servo","message":{"subtype":"set_angle","moves":[{"idx":0,"centideg":30000,"time_ms":5}]}}"#,
            "in `message`: centideg is out of range",
        ),
        (
            r#"{"type":"digital_report","also":"mystery","pin":1,"value":0}"#,
            "field `also` must name a command or report type, found \"mystery\"",
        ),
        (
            r#"{"type":"get_id","offset":3,"len":2,"also":"get_id_report","id":1}"#,
            "unknown field `id` for type get_id",
        ),
    ];
    for (line, message) in cases {
        let input = format!("{{\"type\":\"get_id\"}}\n{line}\n{{\"type\":\"bootloader_reset\"}}\n");
        let r = run(&["encode", "telemetrix", "--hex"], input.as_bytes());
        assert_eq!(r.code, 2, "{line}");
        // Nothing is written for the bad line; the others are encoded.
        assert_eq!(r.text(), "01 23\n01 26\n", "{line}");
        assert_eq!(
            r.stderr,
            format!("robowire: stdin: line 2: {message}\nrobowire: 1 malformed line\n"),
            "{line}"
        );
    }
}

#[test]
fn dialects_shape_the_schema() {
    // upstream 1.1 has no msg_id in I2C commands and no PING; mirte 1.2 has
    // no pulls byte.
    let cases: &[(&str, &str, &str)] = &[
        (
            "upstream11",
            r#"{"type":"i2c_read","port":0,"addr":104,"msg_id":3,"reg":117,"n":1,"no_stop":0}"#,
            "unknown field `msg_id` for type i2c_read",
        ),
        (
            "upstream11",
            r#"{"type":"ping","counter":1}"#,
            "cannot encode ping for upstream11: fields do not match the message's layout: \
             the command does not exist in this dialect",
        ),
        (
            "mirte12",
            r#"{"type":"encoder_new","kind":"single","pin_a":14,"pin_b":0,"pulls":{"up":false,"down":false}}"#,
            "unknown field `pulls` for type encoder_new",
        ),
        (
            "mirte13",
            r#"{"type":"i2c_read","port":0,"addr":104,"reg":117,"n":1,"no_stop":0}"#,
            "missing field `msg_id`",
        ),
    ];
    for (dialect, line, message) in cases {
        let r = run(
            &["encode", "telemetrix", "--dialect", dialect],
            line.as_bytes(),
        );
        assert_eq!(r.code, 2, "{line}");
        assert_eq!(r.stdout, b"");
        assert_eq!(
            r.stderr,
            format!("robowire: stdin: line 1: {message}\nrobowire: 1 malformed line\n")
        );
    }
    let r = run(
        &["encode", "telemetrix", "--hex", "--dialect", "mirte12"],
        br#"{"type":"encoder_new","kind":"single","pin_a":14,"pin_b":0}"#,
    );
    assert_eq!(r.text(), "04 1e 01 0e 00\n");
}

#[test]
fn encode_skips_diagnostics_and_blank_lines() {
    let input = concat!(
        r#"{"offset":2,"error":"unknown_id","id":7}"#,
        "\n\n   \n",
        r#"{"type":"ping","counter":7}"#,
        "\r\n"
    );
    let r = run(&["encode", "telemetrix", "--hex"], input.as_bytes());
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(r.text(), "02 20 07\n");
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["decode", "telemetrix", "--from", "tile"][..],
        &["decode", "telemetrix", "--dialect", "mirte14"],
        &["decode", "telemetrix", "--from", "host", "--lenient"],
        &["decode", "telemetrix", "--chunk", "0"],
        &["decode", "telemetrix", "--datagrams"],
        &["encode", "telemetrix", "--from", "host"],
        &["encode", "telemetrix", "--lenient"],
    ] {
        let r = run(args, b"");
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert_eq!(r.stdout, b"", "{args:?}");
        assert!(!r.stderr.is_empty(), "{args:?}");
    }
    let r = run(
        &["decode", "telemetrix", "--from", "host", "--lenient"],
        b"",
    );
    assert_eq!(
        r.stderr,
        "error: --lenient accepts unknown report ids, which --from host does not decode\n\n\
         For more information, try '--help'.\n"
    );
    let r = run(&["decode", "telemetrix", "/nonexistent/capture.bin"], b"");
    assert_eq!(r.code, 1);
}

#[test]
fn empty_input() {
    for from in ["host", "pico", "any"] {
        let r = run(&["decode", "telemetrix", "--from", from], b"");
        assert_eq!(r.code, 0);
        assert_eq!(r.stdout, b"");
        assert_eq!(r.stderr, summary(0, 0, 0, 0));
    }
    let r = run(&["encode", "telemetrix"], b"");
    assert_eq!((r.code, r.stdout.len(), r.stderr.as_str()), (0, 0, ""));
}

#[test]
fn help_documents_the_contract() {
    let r = run(&["decode", "telemetrix", "--help"], b"");
    assert_eq!(r.code, 0);
    for needle in [
        "--from <FROM>",
        "--dialect <DIALECT>",
        "--lenient",
        "--chunk <N>",
        "--hex",
        "--errors",
        "[INPUT]",
        "mirte13",
        "upstream11",
        "--from any: a frame is accepted if it is a valid command or a valid report",
        "\"also\"",
        "feature_request (id 37)",
        r#"{"offset":30,"error":"bad_length","id":2,"len_byte":7}"#,
        "Exit status: 0 on success, 2 on usage errors",
    ] {
        assert!(r.text().contains(needle), "decode --help lacks {needle}");
    }
    let r = run(&["encode", "telemetrix", "--help"], b"");
    assert!(r.text().contains("--dialect <DIALECT>"));
    let top = run(&["decode", "--help"], b"");
    assert!(top.text().contains("telemetrix"));
}

#[test]
fn mirte12_sensors_decode_and_encode_back() {
    // Spec §10.1: the mirte 1.2 Python client's short SENSOR_NEW adding a
    // VEML6040, and its report (R 10000, G 20000, B 30000, W 40000).
    let input = "04 1f 00 04 01  0b 14 00 04 10 27 20 4e 30 75 40 9c";
    let r = run(
        &[
            "decode",
            "telemetrix",
            "--dialect",
            "mirte12",
            "--hex",
            "--errors",
        ],
        input.as_bytes(),
    );
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":5,"type":"sensor_new","subtype":"add","sensor_num":0,"sensor_type":"veml6040","settings":[1]}"#,
            r#"{"offset":5,"len":12,"type":"sensor_report","sensor_num":0,"sensor_type":"veml6040","reading":{"r":10000,"g":20000,"b":30000,"w":40000}}"#,
        ]
    );
    let back = run(
        &["encode", "telemetrix", "--dialect", "mirte12", "--hex"],
        &r.stdout,
    );
    assert_eq!(back.code, 0, "{}", back.stderr);
    assert_eq!(hex(back.text()), hex(input));
    // mirte 1.3 has neither layout: its SENSOR_NEW add is 10 bytes, its
    // VEML6040 reading big-endian.
    let m13 = run(
        &["decode", "telemetrix", "--hex", "--errors"],
        input.as_bytes(),
    );
    assert!(m13.lines()[0].contains(r#""error":"bad_length","id":31"#));
    assert!(!m13.text().contains(r#""r":10000"#), "{}", m13.text());
}

#[test]
fn as_firmware_frames_commands_as_the_pico_does() {
    // PING 7, STOP_ALL_REPORTS, GET_FIRMWARE_VERSION with the 07 lost: the
    // firmware runs PING 1, then waits for 15 bytes (STOP's id as a LEN);
    // the robust decoder finds GET_FIRMWARE_VERSION after resyncing.
    let input = b"02 20 01 0f 01 05";
    let firmware = run(
        &[
            "decode",
            "telemetrix",
            "--from",
            "host",
            "--as-firmware",
            "--hex",
            "--errors",
        ],
        input,
    );
    assert_eq!(firmware.code, 0, "{}", firmware.stderr);
    assert_eq!(
        firmware.lines(),
        [
            r#"{"offset":0,"len":3,"type":"ping","counter":1}"#,
            r#"{"offset":3,"error":"truncated","len":3}"#,
            r#"{"offset":4,"error":"truncated","len":2}"#,
            r#"{"offset":5,"error":"truncated","len":1}"#,
        ]
    );
    let robust = run(&["decode", "telemetrix", "--from", "host", "--hex"], input);
    assert_eq!(
        robust.lines(),
        [
            r#"{"offset":0,"len":3,"type":"ping","counter":1}"#,
            r#"{"offset":4,"len":2,"type":"get_firmware_version"}"#,
        ]
    );
    // A frame the firmware runs although it is no valid command is consumed
    // whole (counted as malformed), never rescanned.
    let r = run(
        &[
            "decode",
            "telemetrix",
            "--from",
            "host",
            "--as-firmware",
            "--hex",
            "--errors",
        ],
        b"00 1f 02 01 19 01 05",
    );
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":2,"error":"bad_length","id":1,"len_byte":2}"#,
            r#"{"offset":5,"len":2,"type":"get_firmware_version"}"#,
        ]
    );
    assert!(r.stderr.contains("1 malformed"), "{}", r.stderr);
    // Only with --from host.
    for from in ["pico", "any"] {
        let r = run(
            &[
                "decode",
                "telemetrix",
                "--from",
                from,
                "--as-firmware",
                "--hex",
            ],
            b"01 05",
        );
        assert_eq!(r.code, 2, "--from {from}");
        assert!(r.stderr.contains("--as-firmware"), "{}", r.stderr);
    }
}
