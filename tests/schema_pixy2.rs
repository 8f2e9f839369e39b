//! The library's serde form of Pixy2 messages is the JSON-lines schema of
//! `robowire decode pixy2` / `robowire encode pixy2`: for every request and
//! response kind, `serde_json` writes exactly the tool's line (less `offset`
//! and `len`), the line reads back to the same message, and a bad line is
//! refused with the tool's message. The lines are those tests/cli_pixy2.rs
//! pins.

#![cfg(feature = "serde")]

use robowire::pixy2::{
    Envelope, Error, Form, Malformed, Message, MessageBuf, Request, Response, ResponseBuf,
};
use robowire::Encode;

/// A frame in hex and the tool's line for it, less `offset` and `len`: the
/// spec's golden vectors, then payloads only a lossless schema survives.
const CASES: &[(&str, &str)] = &[
    (
        "ae c1 0e 00",
        r#"{"type":"get_version","checksum":false}"#,
    ),
    (
        "af c1 0f 10 0d 03 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00",
        r#"{"type":"version","checksum":true,"hardware":8704,"firmware_major":3,"firmware_minor":0,"firmware_build":10,"firmware_type":"general"}"#,
    ),
    (
        "ae c1 0c 01 00",
        r#"{"type":"get_resolution","checksum":false}"#,
    ),
    (
        "ae c1 10 01 80",
        r#"{"type":"set_camera_brightness","checksum":false,"brightness":128}"#,
    ),
    (
        "ae c1 12 04 f4 01 f4 01",
        r#"{"type":"set_servos","checksum":false,"pan":500,"tilt":500}"#,
    ),
    (
        "ae c1 12 04 00 00 e8 03",
        r#"{"type":"set_servos","checksum":false,"pan":0,"tilt":1000}"#,
    ),
    (
        "ae c1 14 03 ff 00 00",
        r#"{"type":"set_led","checksum":false,"r":255,"g":0,"b":0}"#,
    ),
    (
        "ae c1 16 02 01 00",
        r#"{"type":"set_lamp","checksum":false,"upper":1,"lower":0}"#,
    ),
    (
        "ae c1 18 00",
        r#"{"type":"get_fps","checksum":false}"#,
    ),
    (
        "ae c1 20 02 ff ff",
        r#"{"type":"get_blocks","checksum":false,"sigmap":255,"max_blocks":255}"#,
    ),
    (
        "ae c1 20 02 11 03",
        r#"{"type":"get_blocks","checksum":false,"sigmap":17,"max_blocks":3}"#,
    ),
    (
        "ae c1 30 02 00 07",
        r#"{"type":"get_features","checksum":false,"scope":0,"features":7}"#,
    ),
    (
        "ae c1 30 02 01 07",
        r#"{"type":"get_features","checksum":false,"scope":1,"features":7}"#,
    ),
    (
        "ae c1 36 01 81",
        r#"{"type":"set_mode","checksum":false,"mode":129}"#,
    ),
    (
        "ae c1 38 01 03",
        r#"{"type":"set_vector","checksum":false,"index":3}"#,
    ),
    (
        "ae c1 3a 02 a6 ff",
        r#"{"type":"set_next_turn","checksum":false,"angle":-90}"#,
    ),
    (
        "ae c1 3c 02 5a 00",
        r#"{"type":"set_default_turn","checksum":false,"angle":90}"#,
    ),
    (
        "ae c1 3e 00",
        r#"{"type":"reverse_vector","checksum":false}"#,
    ),
    (
        "ae c1 70 05 9e 00 68 00 01",
        r#"{"type":"get_rgb","checksum":false,"x":158,"y":104,"saturate":1}"#,
    ),
    (
        "ae c1 02 21 6c 69 6e 65 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00",
        r#"{"type":"change_prog","checksum":false,"name":"line"}"#,
    ),
    (
        "af c1 01 04 00 00 00 00 00 00",
        r#"{"type":"result","checksum":true,"value":0}"#,
    ),
    (
        "af c1 01 04 01 00 01 00 00 00",
        r#"{"type":"result","checksum":true,"value":1}"#,
    ),
    (
        "af c1 01 04 3d 00 3d 00 00 00",
        r#"{"type":"result","checksum":true,"value":61}"#,
    ),
    (
        "af c1 01 04 9c 00 56 34 12 00",
        r#"{"type":"result","checksum":true,"value":1193046}"#,
    ),
    (
        "af c1 03 01 ff 00 ff",
        r#"{"type":"error","checksum":true,"code":"general"}"#,
    ),
    (
        "af c1 03 01 fe 00 fe",
        r#"{"type":"error","checksum":true,"code":"busy"}"#,
    ),
    (
        "af c1 03 01 fd 00 fd",
        r#"{"type":"error","checksum":true,"code":"invalid_request"}"#,
    ),
    (
        "af c1 03 01 fc 00 fc",
        r#"{"type":"error","checksum":true,"code":"type_unsupported"}"#,
    ),
    (
        "af c1 03 01 fb 00 fb",
        r#"{"type":"error","checksum":true,"code":"button_override"}"#,
    ),
    (
        "af c1 03 01 fa 00 fa",
        r#"{"type":"error","checksum":true,"code":"prog_changing"}"#,
    ),
    (
        "af c1 0d 04 0d 01 3c 01 d0 00",
        r#"{"type":"resolution","checksum":true,"width":316,"height":208}"#,
    ),
    (
        "af c1 0d 04 83 00 4f 00 34 00",
        r#"{"type":"resolution","checksum":true,"width":79,"height":52}"#,
    ),
    (
        "af c1 21 00 00 00",
        r#"{"type":"blocks","checksum":true,"blocks":[]}"#,
    ),
    (
        "af c1 21 0e b7 01 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff",
        r#"{"type":"blocks","checksum":true,"blocks":[{"signature":1,"x":100,"y":50,"width":20,"height":10,"angle":0,"index":3,"age":255}]}"#,
    ),
    (
        "af c1 21 1c 2c 05 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff 0a 00 c8 00 78 00 28 00 1e 00 d3 ff 07 0c",
        r#"{"type":"blocks","checksum":true,"blocks":[{"signature":1,"x":100,"y":50,"width":20,"height":10,"angle":0,"index":3,"age":255},{"signature":10,"x":200,"y":120,"width":40,"height":30,"angle":-45,"index":7,"age":12}]}"#,
    ),
    (
        "af c1 31 00 00 00",
        r#"{"type":"features","checksum":true,"sections":[]}"#,
    ),
    (
        "af c1 31 08 6e 00 01 06 0a 33 28 00 02 00",
        r#"{"type":"features","checksum":true,"sections":[{"vectors":[{"x0":10,"y0":51,"x1":40,"y1":0,"index":2,"flags":0}]}]}"#,
    ),
    (
        "af c1 31 2c 16 03 01 06 0a 33 28 00 02 00 02 1c 27 14 03 00 02 00 5a 00 05 00 00 00 02 00 a6 ff 00 00 00 00 00 00 00 00 00 00 00 00 04 04 1e 19 00 05",
        r#"{"type":"features","checksum":true,"sections":[{"vectors":[{"x0":10,"y0":51,"x1":40,"y1":0,"index":2,"flags":0}]},{"intersections":[{"x":39,"y":20,"lines":[{"index":2,"angle":90},{"index":5,"angle":0},{"index":2,"angle":-90}]}]},{"barcodes":[{"x":30,"y":25,"flags":0,"code":5}]}]}"#,
    ),
    (
        "af c1 31 2c 16 03 01 06 0a 33 28 00 02 00 02 1c 27 14 03 00 02 00 a6 ff 05 00 00 00 02 00 5a 00 00 00 00 00 00 00 00 00 00 00 00 00 04 04 1e 19 00 05",
        r#"{"type":"features","checksum":true,"sections":[{"vectors":[{"x0":10,"y0":51,"x1":40,"y1":0,"index":2,"flags":0}]},{"intersections":[{"x":39,"y":20,"lines":[{"index":2,"angle":-90},{"index":5,"angle":0},{"index":2,"angle":90}]}]},{"barcodes":[{"x":30,"y":25,"flags":0,"code":5}]}]}"#,
    ),
    (
        "ae c1 0f 10 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00",
        r#"{"type":"version","checksum":false,"hardware":8704,"firmware_major":3,"firmware_minor":0,"firmware_build":10,"firmware_type":"general"}"#,
    ),
    (
        "af c1 01 04 00 00 00 00 00 00",
        r#"{"type":"result","checksum":true,"value":0}"#,
    ),
    (
        "ae c1 02 05 76 69 64 65 6f",
        r#"{"type":"change_prog","checksum":false,"name":"video","payload_len":5}"#,
    ),
    (
        "ae c1 02 04 6c 00 78 00",
        r#"{"type":"change_prog","checksum":false,"name":"l\u0000x","payload_len":4}"#,
    ),
    (
        "af c1 02 03 00 01 ff 00 01",
        r#"{"type":"change_prog","checksum":true,"name":[255,0,1],"payload_len":3}"#,
    ),
    (
        "ae c1 02 00",
        r#"{"type":"change_prog","checksum":false,"name":"","payload_len":0}"#,
    ),
    (
        "ae c1 0c 01 07",
        r#"{"type":"get_resolution","checksum":false,"reserved":7}"#,
    ),
    (
        "af c1 0f 10 3c 02 00 22 03 00 0a 00 30 31 32 33 34 35 36 37 38 39",
        r#"{"type":"version","checksum":true,"hardware":8704,"firmware_major":3,"firmware_minor":0,"firmware_build":10,"firmware_type":"0123456789"}"#,
    ),
    (
        "af c1 0f 10 2c 02 00 22 03 00 0a 00 ff fe 00 00 00 00 00 00 00 00",
        r#"{"type":"version","checksum":true,"hardware":8704,"firmware_major":3,"firmware_minor":0,"firmware_build":10,"firmware_type":[255,254]}"#,
    ),
    (
        "af c1 03 01 00 00 00",
        r#"{"type":"error","checksum":true,"code":0}"#,
    ),
    (
        "af c1 03 01 f9 00 f9",
        r#"{"type":"error","checksum":true,"code":-7}"#,
    ),
    (
        "af c1 31 2d 48 02 01 00 08 03 01 02 03 01 06 01 02 03 04 05 06 02 1c 28 14 01 09 02 03 05 00 00 00 00 00 07 00 a6 ff 00 00 00 00 00 00 00 00 00 00 00 00",
        r#"{"type":"features","checksum":true,"sections":[{"vectors":[]},{"ftype":8,"data":[1,2,3]},{"vectors":[{"x0":1,"y0":2,"x1":3,"y1":4,"index":5,"flags":6}]},{"intersections":[{"x":40,"y":20,"reserved":9,"lines":[{"index":2,"angle":5,"reserved":3}],"unused_slots":[{"index":0,"angle":0},{"index":7,"angle":-90},{"index":0,"angle":0},{"index":0,"angle":0},{"index":0,"angle":0}]}]}]}"#,
    ),
];

const BLOCK_1: &str =
    r#"{"signature":1,"x":100,"y":50,"width":20,"height":10,"angle":0,"index":3,"age":255}"#;

fn bytes(hex: &str) -> Vec<u8> {
    hex.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

#[test]
fn every_kind_serializes_as_the_command_line_prints_it() {
    let mut seen = Vec::new();
    for &(hex, line) in CASES {
        let frame = bytes(hex);
        let envelope = Envelope::<MessageBuf>::try_from(&frame[..]).unwrap();
        assert_eq!(serde_json::to_string(&envelope).unwrap(), line, "{hex}");
        // The borrowed form writes the same.
        let view = Envelope::<Message<'_>>::try_from(&frame[..]).unwrap();
        assert_eq!(serde_json::to_string(&view).unwrap(), line, "{hex}");
        // The line reads back to the same message, which encodes to the frame.
        let back: Envelope<MessageBuf> = serde_json::from_str(line).unwrap();
        assert_eq!(back, envelope, "{line}");
        let mut out = [0u8; robowire::pixy2::MAX_FRAME_LEN];
        let n = back.encode(&mut out).unwrap();
        assert_eq!(out[..n], frame[..], "{line}");
        // Each direction on its own, as its decoder yields it.
        match envelope.body {
            MessageBuf::Request(request) => {
                let typed = Envelope::<Request>::try_from(&frame[..]).unwrap();
                assert_eq!(serde_json::to_string(&typed).unwrap(), line);
                let back: Envelope<Request> = serde_json::from_str(line).unwrap();
                assert_eq!(back, typed);
                // A bare request has no checksum member, and ignores one.
                let bare = serde_json::to_string(&request).unwrap();
                assert_eq!(bare, without_checksum(line));
                assert_eq!(serde_json::from_str::<Request>(line).unwrap(), request);
                assert_eq!(serde_json::from_str::<Request>(&bare).unwrap(), request);
                seen.push(request.name());
            }
            MessageBuf::Response(response) => {
                let typed = Envelope::<ResponseBuf>::try_from(&frame[..]).unwrap();
                assert_eq!(serde_json::to_string(&typed).unwrap(), line);
                let back: Envelope<ResponseBuf> = serde_json::from_str(line).unwrap();
                assert_eq!(back, typed);
                let borrowed = Envelope::<Response<'_>>::try_from(&frame[..]).unwrap();
                assert_eq!(serde_json::to_string(&borrowed).unwrap(), line);
                let bare = serde_json::to_string(&response).unwrap();
                assert_eq!(bare, without_checksum(line));
                assert_eq!(serde_json::from_str::<ResponseBuf>(line).unwrap(), response);
                assert_eq!(
                    serde_json::from_str::<ResponseBuf>(&bare).unwrap(),
                    response
                );
                seen.push(response.as_response().name());
            }
        }
        // `type` is the message's name.
        let value: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(value["type"], *seen.last().unwrap(), "{line}");
        let message = serde_json::to_string(&envelope.body).unwrap();
        assert_eq!(message, without_checksum(line));
        assert_eq!(
            serde_json::from_str::<MessageBuf>(&message).unwrap(),
            envelope.body
        );
    }
    // Every type name of both directions is covered.
    for name in Message::NAMES {
        assert!(seen.contains(&name), "no case for {name}");
    }
}

fn without_checksum(line: &str) -> String {
    line.replacen(r#","checksum":true"#, "", 1)
        .replacen(r#","checksum":false"#, "", 1)
}

#[test]
fn checksum_may_be_left_out_and_offset_and_len_are_ignored() {
    let get = r#"{"type":"get_blocks","sigmap":255,"max_blocks":255,"offset":3,"len":6}"#;
    let read: Envelope<MessageBuf> = serde_json::from_str(get).unwrap();
    assert_eq!(read.form, Form::NoChecksum);
    let busy = r#"{"type":"error","code":"busy"}"#;
    let read: Envelope<MessageBuf> = serde_json::from_str(busy).unwrap();
    assert_eq!(read.form, Form::Checksum);
    let read: Envelope<ResponseBuf> = serde_json::from_str(busy).unwrap();
    assert_eq!(read.form, Form::Checksum);
    // The wrong direction is named.
    let err = serde_json::from_str::<Request>(busy).unwrap_err();
    assert_message(&err, "type `error` is a response, not a request", busy);
    let err = serde_json::from_str::<Envelope<ResponseBuf>>(get).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("type `get_blocks` is a request, not a response"),
        "{err}"
    );
}

/// `message`, then nothing or the position `serde_json::from_str` adds.
fn assert_message(err: &serde_json::Error, message: &str, line: &str) {
    let text = err.to_string();
    let rest = text
        .strip_prefix(message)
        .unwrap_or_else(|| panic!("{line}: {text:?} is not {message:?}"));
    assert!(
        rest.is_empty() || rest.starts_with(" at line 1 column "),
        "{line}: {text:?}"
    );
}

#[test]
fn bad_lines_are_refused_with_the_command_line_messages() {
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
        let err = serde_json::from_str::<Envelope<MessageBuf>>(line).unwrap_err();
        assert_message(&err, message, line);
        // Without a position when read from a tree, as the tool reads it.
        let value: serde_json::Value = serde_json::from_str(line).unwrap();
        let err = serde_json::from_value::<Envelope<MessageBuf>>(value).unwrap_err();
        assert_eq!(err.to_string(), *message, "{line}");
        // The bare message checks the same.
        let err = serde_json::from_str::<MessageBuf>(line).unwrap_err();
        assert_message(&err, message, line);
    }
}

#[test]
fn errors_serialize_as_the_command_line_prints_them() {
    let cases = [
        (
            Error::Checksum {
                expected: 385,
                found: 389,
            },
            r#"{"error":"checksum","expected":385,"found":389}"#,
        ),
        (
            Error::BadLength {
                packet_type: 18,
                len: 3,
            },
            r#"{"error":"bad_length","packet_type":18,"payload_len":3}"#,
        ),
        (
            Error::UnknownType { packet_type: 50 },
            r#"{"error":"unknown_type","packet_type":50}"#,
        ),
        (
            Error::TooLong {
                packet_type: 2,
                len: 65,
                max: 64,
            },
            r#"{"error":"too_long","packet_type":2,"payload_len":65,"max":64}"#,
        ),
        (
            Error::Malformed {
                packet_type: 49,
                what: Malformed::SectionLength { ftype: 1, flen: 5 },
            },
            r#"{"error":"malformed","packet_type":49,"what":"section_length","ftype":1,"flen":5}"#,
        ),
        (
            Error::Malformed {
                packet_type: 49,
                what: Malformed::SectionPastEnd { offset: 0 },
            },
            r#"{"error":"malformed","packet_type":49,"what":"section_past_end","section_offset":0}"#,
        ),
        (
            Error::Malformed {
                packet_type: 49,
                what: Malformed::IntersectionLines { n: 7 },
            },
            r#"{"error":"malformed","packet_type":49,"what":"intersection_lines","n":7}"#,
        ),
        (
            Error::Malformed {
                packet_type: 32,
                what: Malformed::ZeroSigmap,
            },
            r#"{"error":"malformed","packet_type":32,"what":"zero_sigmap"}"#,
        ),
        (
            Error::Malformed {
                packet_type: 49,
                what: Malformed::TooLong { len: 300 },
            },
            r#"{"error":"malformed","packet_type":49,"what":"too_long","payload_len":300}"#,
        ),
        (
            Error::Malformed {
                packet_type: 33,
                what: Malformed::BlocksLength { len: 13 },
            },
            r#"{"error":"malformed","packet_type":33,"what":"blocks_length","payload_len":13}"#,
        ),
        (
            Error::Superseded { len: 8 },
            r#"{"error":"superseded","len":8}"#,
        ),
        (
            Error::Truncated { len: 3 },
            r#"{"error":"truncated","len":3}"#,
        ),
        (Error::Sync { found: 0 }, r#"{"error":"sync","found":0}"#),
        (
            Error::TrailingBytes { extra: 2 },
            r#"{"error":"trailing_bytes","extra":2}"#,
        ),
    ];
    for (error, line) in cases {
        assert_eq!(serde_json::to_string(&error).unwrap(), line);
        assert_eq!(
            serde_json::from_str::<Error>(line).unwrap(),
            error,
            "{line}"
        );
    }
    let err = serde_json::from_str::<Error>(r#"{"error":"checksum","expected":1}"#).unwrap_err();
    assert_message(&err, "missing field `found`", "checksum");
    let err = serde_json::from_str::<Error>(r#"{"error":"sync","found":1,"extra":2}"#).unwrap_err();
    assert_message(&err, "unknown field `extra` for error sync", "sync");
}

/// What a decoder prints, through the stream's frames and rejections.
#[test]
fn decoded_events_print_as_the_command_line_lines() {
    let mut decoder = robowire::pixy2::both_decoder();
    let input = bytes("ae c1 18 00 af c1 03 01 fe 00 ff ae c1 12 03 f4 01 f4");
    let mut events: Vec<_> = decoder.feed(&input).collect();
    events.extend(decoder.flush());
    let lines: Vec<String> = events
        .iter()
        .map(|event| match event {
            Ok(frame) => serde_json::to_string(frame).unwrap(),
            Err(rejected) => serde_json::to_string(rejected).unwrap(),
        })
        .collect();
    assert_eq!(
        lines,
        [
            r#"{"offset":0,"len":4,"type":"get_fps","checksum":false}"#,
            r#"{"offset":4,"error":"checksum","expected":254,"found":255}"#,
            r#"{"offset":11,"error":"bad_length","packet_type":18,"payload_len":3}"#,
        ]
    );
}
