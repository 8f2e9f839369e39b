//! The library's serde form of OmniTiles messages and errors is the command
//! line tool's JSON-lines schema: the lines and messages of `tests/cli.rs`.
#![cfg(feature = "serde")]

use robowire::omnitiles::{Command, Error, Message, Telemetry};
use robowire::{OwnedFrame, Rejected};

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// Every command kind and every telemetry layout: a frame and the line
/// `robowire decode omnitiles` prints for it (`tests/cli.rs`: the golden
/// vectors and the SPI datagram).
const LINES: [(&str, &str); 22] = [
    ("a5 50 50", r#"{"offset":0,"len":3,"type":"ping"}"#),
    (
        "a5 30 c8 f8",
        r#"{"offset":3,"len":4,"type":"m1_extend","speed":200}"#,
    ),
    (
        "a5 30 ff 2f",
        r#"{"offset":7,"len":4,"type":"m1_extend","speed":255}"#,
    ),
    (
        "a5 31 ff 30",
        r#"{"offset":11,"len":4,"type":"m1_retract","speed":255}"#,
    ),
    (
        "a5 40 c8 08",
        r#"{"offset":15,"len":4,"type":"m2_extend","speed":200}"#,
    ),
    (
        "a5 41 c8 09",
        r#"{"offset":19,"len":4,"type":"m2_retract","speed":200}"#,
    ),
    (
        "a5 30 00 30",
        r#"{"offset":23,"len":4,"type":"m1_extend","speed":0}"#,
    ),
    ("a5 32 32", r#"{"offset":27,"len":3,"type":"m1_brake"}"#),
    ("a5 42 42", r#"{"offset":30,"len":3,"type":"m2_brake"}"#),
    (
        "a5 33 80 b3",
        r#"{"offset":33,"len":4,"type":"m1_set_position","position":128}"#,
    ),
    (
        "a5 43 00 43",
        r#"{"offset":37,"len":4,"type":"m2_set_position","position":0}"#,
    ),
    (
        "a5 70 0a fb 14 89",
        r#"{"offset":41,"len":6,"type":"base_velocity","vx":10,"vy":-5,"omega":20}"#,
    ),
    (
        "a5 70 1e 00 00 8e",
        r#"{"offset":47,"len":6,"type":"base_velocity","vx":30,"vy":0,"omega":0}"#,
    ),
    (
        "a5 70 00 e2 00 52",
        r#"{"offset":53,"len":6,"type":"base_velocity","vx":0,"vy":-30,"omega":0}"#,
    ),
    (
        "a5 70 80 7f 00 6f",
        r#"{"offset":59,"len":6,"type":"base_velocity","vx":-128,"vy":127,"omega":0}"#,
    ),
    (
        "a5 70 a5 00 00 15",
        r#"{"offset":65,"len":6,"type":"base_velocity","vx":-91,"vy":0,"omega":0}"#,
    ),
    ("a5 71 71", r#"{"offset":71,"len":3,"type":"base_brake"}"#),
    (
        "a5 60 d0 07 e8 03 22",
        r#"{"offset":74,"len":7,"type":"telemetry","layout":"pos7","m1_pos":2000,"m2_pos":1000}"#,
    ),
    (
        "a5 60 d0 07 e8 03 dc 05 c4 09 ff ff b8 0b 91",
        r#"{"offset":81,"len":15,"type":"telemetry","layout":"uwb15","m1_pos":2000,"m2_pos":1000,"uwb":[1500,2500,null,3000]}"#,
    ),
    (
        "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 70",
        r#"{"offset":96,"len":17,"type":"telemetry","layout":"uwbtof17","m1_pos":2000,"m2_pos":1000,"uwb":[1500,2500,3500,4500],"tof":321}"#,
    ),
    (
        "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 cd cc cc 3d cd cc 4c 3e cd cc 1c 41 \
         0a d7 23 3c 0a d7 a3 bc 8f c2 f5 3c d1 07 d2 07 d3 07 d4 07 e9 03 ea 03 6c",
        concat!(
            r#"{"offset":113,"len":53,"type":"telemetry","layout":"ble53","m1_pos":2000,"m2_pos":1000,"#,
            r#""uwb":[1500,2500,3500,4500],"tof":321,"#,
            r#""imu":{"ax":0.1,"ay":0.2,"az":9.8,"gx":0.01,"gy":-0.02,"gz":0.03},"#,
            r#""m1_adcs":[2001,2002,2003,2004],"m2_adcs":[1001,1002]}"#
        ),
    ),
    (
        "a5 60 d0 07 e8 03 41 01 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 \
         00 00 00 00 d1 07 d2 07 d3 07 d4 07 e9 03 ea 03 a3",
        concat!(
            r#"{"offset":142,"len":45,"type":"telemetry","layout":"spi45","m1_pos":2000,"#,
            r#""m2_pos":1000,"tof":321,"imu":{"ax":0.0,"ay":0.0,"az":0.0,"gx":0.0,"gy":0.0,"gz":0.0},"#,
            r#""m1_adcs":[2001,2002,2003,2004],"m2_adcs":[1001,1002]}"#
        ),
    ),
];

/// The line without its leading `offset` and `len`: the message's own JSON.
fn message_json(line: &str) -> String {
    let rest = line.split_once(r#","type""#).unwrap().1;
    format!(r#"{{"type"{rest}"#)
}

#[test]
fn every_message_kind_is_the_cli_line() {
    for (frame, line) in LINES {
        let bytes = hex(frame);
        let message = Message::try_from(&bytes[..]).unwrap_or_else(|e| panic!("{frame}: {e}"));
        let json = message_json(line);
        assert_eq!(serde_json::to_string(&message).unwrap(), json, "{frame}");
        // The direction's own type writes the same line.
        match message {
            Message::Command(c) => assert_eq!(serde_json::to_string(&c).unwrap(), json),
            Message::Telemetry(t) => assert_eq!(serde_json::to_string(&t).unwrap(), json),
        }
        // The line reads back, with or without `offset` and `len`.
        assert_eq!(
            serde_json::from_str::<Message>(&json).unwrap(),
            message,
            "{json}"
        );
        assert_eq!(
            serde_json::from_str::<Message>(line).unwrap(),
            message,
            "{line}"
        );
        // With the stream's `offset` and `len` it is the CLI's whole line.
        let value: serde_json::Value = serde_json::from_str(line).unwrap();
        let framed = OwnedFrame {
            offset: value["offset"].as_u64().unwrap(),
            len: bytes.len(),
            message,
        };
        assert_eq!(serde_json::to_string(&framed).unwrap(), line);
        assert_eq!(
            serde_json::from_str::<OwnedFrame<Message>>(line).unwrap(),
            framed
        );
    }
}

#[test]
fn names_are_the_type_tags() {
    let mut tags: Vec<String> = LINES
        .iter()
        .map(|(_, line)| {
            let value: serde_json::Value = serde_json::from_str(line).unwrap();
            value["type"].as_str().unwrap().to_owned()
        })
        .collect();
    tags.dedup();
    let mut names: Vec<&str> = Message::NAMES.to_vec();
    names.sort_unstable();
    tags.sort_unstable();
    tags.dedup();
    assert_eq!(tags, names);
    assert_eq!(&Message::NAMES[..11], Command::NAMES);
    for (frame, _) in LINES {
        let message = Message::try_from(&hex(frame)[..]).unwrap();
        assert!(message.to_string().starts_with(message.name()));
    }
}

#[test]
fn awkward_floats_are_the_cli_line() {
    // tests/cli.rs `non_finite_and_awkward_floats_round_trip`.
    let bits: [u32; 6] = [
        0x7fc0_0000,
        0xffc0_0001,
        0x7f80_0000,
        0xff80_0000,
        0x8000_0000,
        0x15ae_43fd,
    ];
    let mut frame = hex("a5 60 d0 07 ff ff dc 05 c4 09 ff ff 94 11 ff ff");
    for b in bits {
        frame.extend(b.to_le_bytes());
    }
    frame.extend(hex("d1 07 d2 07 d3 07 d4 07 ff ff ea 03"));
    let sum = frame[1..].iter().fold(0u8, |s, &b| s.wrapping_add(b));
    frame.push(sum);
    let t = Telemetry::try_from(&frame[..]).unwrap();
    let line = concat!(
        r#"{"type":"telemetry","layout":"ble53","m1_pos":2000,"m2_pos":null,"#,
        r#""uwb":[1500,2500,null,4500],"tof":null,"imu":{"ax":"nan:0x7fc00000","#,
        r#""ay":"nan:0xffc00001","az":"inf","gx":"-inf","gy":-0.0,"#,
        r#""gz":7.038530691851209e-26},"m1_adcs":[2001,2002,2003,2004],"m2_adcs":[65535,1002]}"#
    );
    assert_eq!(serde_json::to_string(&t).unwrap(), line);
    assert_eq!(serde_json::from_str::<Telemetry>(line).unwrap(), t);
}

#[test]
fn errors_are_the_cli_diagnostic_events() {
    // tests/cli.rs `errors_are_reported_as_events`.
    let events = [
        (
            Rejected {
                offset: 2,
                error: Error::Checksum {
                    expected: 248,
                    found: 247,
                },
            },
            r#"{"offset":2,"error":"checksum","expected":248,"found":247}"#,
        ),
        (
            Rejected {
                offset: 6,
                error: Error::UnknownId { id: 153 },
            },
            r#"{"offset":6,"error":"unknown_id","id":153}"#,
        ),
        (
            Rejected {
                offset: 17,
                error: Error::Truncated { len: 3 },
            },
            r#"{"offset":17,"error":"truncated","len":3}"#,
        ),
        (
            Rejected {
                offset: 77,
                error: Error::Unconfirmed,
            },
            r#"{"offset":77,"error":"unconfirmed"}"#,
        ),
    ];
    for (rejected, line) in events {
        assert_eq!(serde_json::to_string(&rejected).unwrap(), line);
        assert_eq!(
            serde_json::from_str::<Rejected<Error>>(line).unwrap(),
            rejected
        );
        assert_eq!(serde_json::from_str::<Error>(line).unwrap(), rejected.error);
    }
}

/// `serde_json::from_str::<Message>` fails with exactly `message`.
fn refused(line: &str, message: &str) {
    let err = serde_json::from_str::<Message>(line).unwrap_err();
    assert_eq!(err.to_string(), message, "{line}");
    // Read from a parsed tree, as the command-line tool does, it is exactly
    // the message.
    let value: serde_json::Value = serde_json::from_str(line).unwrap();
    let err = serde_json::from_value::<Message>(value).unwrap_err();
    assert_eq!(err.to_string(), message, "{line}");
}

#[test]
fn bad_lines_have_the_cli_messages() {
    // tests/cli.rs `malformed_json_lines`, but for the line that is no JSON.
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
            r#"{"type":"m1_extend","sped":200}"#,
            "unknown field `sped` (did you mean `speed`?)",
        ),
        (
            r#"{"type":"m1_extend","speed":200,"sped":200}"#,
            "unknown field `sped` for type m1_extend",
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
        refused(line, message);
    }
}

#[test]
fn bad_telemetry_fields_have_the_cli_messages() {
    // tests/cli.rs `malformed_telemetry_fields`.
    let ble = |imu: &str, m2: &str| {
        format!(
            r#"{{"type":"telemetry","layout":"ble53","m1_pos":1,"m2_pos":2,"uwb":[1,2,3,4],"tof":5,"imu":{imu},"m1_adcs":[1,2,3,4],"m2_adcs":{m2}}}"#
        )
    };
    let good_imu = r#"{"ax":0,"ay":0,"az":9.8,"gx":0,"gy":0,"gz":0}"#;
    assert!(serde_json::from_str::<Message>(&ble(good_imu, "[5,65535]")).is_ok());
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
        (
            ble(good_imu, "[5,65536]"),
            "field `m2_adcs[1]` must be an integer 0..=65535, found 65536",
        ),
    ];
    for (line, message) in &cases {
        refused(line, message);
    }
}
