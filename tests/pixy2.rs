//! Pixy2: golden vectors (spec §8) both directions, resync, chunking
//! invariance, prefixes, corruption, the §8.5 negative cases, pairing and a
//! host loop against a simulated device.

use robowire::pixy2::{
    self, packet_type as ty, Barcode, Block, BlocksBuf, Both, ChangeProg, Device, DeviceError,
    Envelope, Error, FeaturesBuf, Form, Framing, GetBlocks, GetFeatures, GetFps, GetResolution,
    GetRgb, GetVersion, Host, Intersection, IntersectionLine, Malformed, Message, MessageBuf,
    PairError, ProgName, ProgSwitch, Query, Request, Resolution, Response, ResponseBuf,
    ReverseVector, Rgb, Section, SetCameraBrightness, SetDefaultTurn, SetLamp, SetLed, SetMode,
    SetNextTurn, SetServos, SetVector, Side, Vector, Version,
};
use robowire::{Encode, EncodeError, FrameBuf, OwnedEvent, OwnedFrame, Rejected, StreamDecoder};

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

type Ev<S> = OwnedEvent<Framing<S>>;

/// Decode `input` in chunks of `chunk` bytes, then finish; check the counters.
fn decode_chunked<S: Side, const N: usize>(
    framing: Framing<S>,
    input: &[u8],
    chunk: usize,
) -> Vec<Ev<S>> {
    let mut decoder = StreamDecoder::<Framing<S>, N>::new(framing);
    let mut events = Vec::new();
    for piece in input.chunks(chunk.max(1)) {
        events.extend(decoder.feed(piece));
    }
    events.extend(decoder.flush());
    let s = decoder.stats();
    assert_eq!(s.bytes, input.len() as u64);
    assert_eq!(s.bytes, s.frame_bytes + s.skipped, "counters add up");
    events
}

fn host(input: &[u8]) -> Vec<Ev<Host>> {
    decode_chunked::<Host, 264>(Framing::new(), input, input.len())
}

fn device(input: &[u8]) -> Vec<Ev<Device>> {
    decode_chunked::<Device, 72>(Framing::new(), input, input.len())
}

fn any(input: &[u8]) -> Vec<Ev<Both>> {
    decode_chunked::<Both, 264>(Framing::new(), input, input.len())
}

fn frames<M: Clone, E>(events: &[Result<OwnedFrame<M>, E>]) -> Vec<M> {
    events
        .iter()
        .filter_map(|e| e.as_ref().ok().map(|f| f.message.clone()))
        .collect()
}

fn errors<M, E: Clone>(events: &[Result<OwnedFrame<M>, Rejected<E>>]) -> Vec<(u64, E)> {
    events
        .iter()
        .filter_map(|e| e.as_ref().err().map(|r| (r.offset, r.error.clone())))
        .collect()
}

fn encode<M: Encode>(m: &M) -> Vec<u8> {
    let frame = FrameBuf::<261>::encode(m).unwrap();
    assert_eq!(frame.len(), m.encoded_len());
    frame.to_vec()
}

fn plain<M>(body: M) -> Envelope<M> {
    Envelope::new(Form::NoChecksum, body)
}

fn summed<M>(body: M) -> Envelope<M> {
    Envelope::new(Form::Checksum, body)
}

// ---------------------------------------------------------------- requests

fn request_vectors() -> Vec<(String, Request)> {
    let mut change_prog = "ae c1 02 21 6c 69 6e 65".to_string();
    for _ in 0..29 {
        change_prog.push_str(" 00");
    }
    vec![
        ("ae c1 0e 00".into(), GetVersion.into()),
        (
            "ae c1 0c 01 00".into(),
            GetResolution { reserved: 0 }.into(),
        ),
        ("ae c1 10 01 80".into(), SetCameraBrightness(128).into()),
        (
            "ae c1 12 04 f4 01 f4 01".into(),
            SetServos {
                pan: 500,
                tilt: 500,
            }
            .into(),
        ),
        (
            "ae c1 12 04 00 00 e8 03".into(),
            SetServos { pan: 0, tilt: 1000 }.into(),
        ),
        (
            "ae c1 14 03 ff 00 00".into(),
            SetLed { r: 255, g: 0, b: 0 }.into(),
        ),
        ("ae c1 16 02 01 00".into(), SetLamp::new(true, false).into()),
        ("ae c1 18 00".into(), GetFps.into()),
        (
            "ae c1 20 02 ff ff".into(),
            GetBlocks {
                sigmap: GetBlocks::ALL,
                max_blocks: 255,
            }
            .into(),
        ),
        (
            "ae c1 20 02 11 03".into(),
            GetBlocks {
                sigmap: GetBlocks::SIG1 | GetBlocks::SIG5,
                max_blocks: 3,
            }
            .into(),
        ),
        (
            "ae c1 30 02 00 07".into(),
            GetFeatures {
                scope: GetFeatures::MAIN,
                features: GetFeatures::ALL_FEATURES,
            }
            .into(),
        ),
        (
            "ae c1 30 02 01 07".into(),
            GetFeatures {
                scope: GetFeatures::ALL,
                features: GetFeatures::VECTORS | GetFeatures::INTERSECTIONS | GetFeatures::BARCODES,
            }
            .into(),
        ),
        (
            "ae c1 36 01 81".into(),
            SetMode(SetMode::WHITE_LINE | SetMode::TURN_DELAYED).into(),
        ),
        ("ae c1 38 01 03".into(), SetVector(3).into()),
        ("ae c1 3a 02 a6 ff".into(), SetNextTurn(-90).into()),
        ("ae c1 3c 02 5a 00".into(), SetDefaultTurn(90).into()),
        ("ae c1 3e 00".into(), ReverseVector.into()),
        (
            "ae c1 70 05 9e 00 68 00 01".into(),
            GetRgb::new(158, 104, true).into(),
        ),
        (
            change_prog,
            ChangeProg(ProgName::new("line").unwrap()).into(),
        ),
    ]
}

#[test]
fn golden_requests_encode_and_decode() {
    for (bytes, request) in request_vectors() {
        let wire = hex(&bytes);
        assert_eq!(encode(&request), wire, "encode {request:?}");
        assert_eq!(encode(&plain(request)), wire);
        assert_eq!(frames(&device(&wire)), [plain(request)], "{bytes}");
        assert_eq!(
            frames(&any(&wire)),
            [plain(MessageBuf::Request(request))],
            "{bytes}"
        );
        // Requests are not responses: a host decoder does not take them.
        assert_eq!(frames(&host(&wire)), []);
    }
    assert_eq!(hex(&request_vectors()[18].0).len(), 37);
}

#[test]
fn golden_requests_in_checksum_form() {
    for (bytes, request) in request_vectors() {
        let payload = &hex(&bytes)[4..];
        let sum = pixy2::checksum(payload).to_le_bytes();
        let mut wire = vec![0xaf, 0xc1, request.packet_type(), payload.len() as u8];
        wire.extend(sum);
        wire.extend(payload);
        assert_eq!(encode(&summed(request)), wire);
        assert_eq!(frames(&device(&wire)), [summed(request)]);
    }
    // The spec's one fully checksummed request, getFps: sum of nothing is 0.
    assert_eq!(
        encode(&summed(Request::from(GetFps))),
        hex("af c1 18 00 00 00")
    );
}

#[test]
fn change_prog_names() {
    assert_eq!(ProgName::new("line").unwrap().name(), b"line");
    assert_eq!(ProgName::LINE_TRACKING.as_str(), Some("line_tracking"));
    assert_eq!(ProgName::VIDEO.as_payload().len(), 33);
    assert_eq!(
        ProgName::COLOR_CONNECTED_COMPONENTS.name(),
        b"color_connected_components"
    );
    assert_eq!(
        ProgName::new(&"x".repeat(33)),
        Err(EncodeError::TooLong { len: 33, max: 32 })
    );
    assert!(matches!(
        ProgName::new("a\0b"),
        Err(EncodeError::OutOfRange { .. })
    ));
    // The device matches prefixes and does not check the length: any payload
    // up to 64 bytes decodes and re-encodes as it was.
    let wire = hex("ae c1 02 04 6c 69 6e 65");
    let [Ok(OwnedFrame { message, .. })] = &device(&wire)[..] else {
        panic!()
    };
    let Request::ChangeProg(ChangeProg(name)) = message.body else {
        panic!()
    };
    assert_eq!(name.as_payload(), b"line");
    assert_eq!(encode(message), wire);
}

// --------------------------------------------------------------- responses

const VERSION_DOC: &str = "af c1 0f 10 0d 03 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00";
const ONE_BLOCK: &str = "af c1 21 0e b7 01 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff";
const TWO_BLOCKS: &str = "af c1 21 1c 2c 05 01 00 64 00 32 00 14 00 0a 00 00 00 03 ff 0a 00 c8 00 78 00 28 00 1e 00 d3 ff 07 0c";
const ONE_VECTOR: &str = "af c1 31 08 6e 00 01 06 0a 33 28 00 02 00";
const ALL_FEATURES: &str = "af c1 31 2c 16 03 01 06 0a 33 28 00 02 00 02 1c 27 14 03 00 02 00 5a 00 05 00 00 00 02 00 a6 ff 00 00 00 00 00 00 00 00 00 00 00 00 04 04 1e 19 00 05";
const ALL_FEATURES_SORTED: &str = "af c1 31 2c 16 03 01 06 0a 33 28 00 02 00 02 1c 27 14 03 00 02 00 a6 ff 05 00 00 00 02 00 5a 00 00 00 00 00 00 00 00 00 00 00 00 00 04 04 1e 19 00 05";

fn block1() -> Block {
    Block {
        signature: 1,
        x: 100,
        y: 50,
        width: 20,
        height: 10,
        angle: 0,
        index: 3,
        age: 255,
    }
}

fn block_cc() -> Block {
    Block {
        signature: 0o12,
        x: 200,
        y: 120,
        width: 40,
        height: 30,
        angle: -45,
        index: 7,
        age: 12,
    }
}

fn vector() -> Vector {
    Vector {
        x0: 10,
        y0: 51,
        x1: 40,
        y1: 0,
        index: 2,
        flags: 0,
    }
}

fn line(index: u8, angle: i16) -> IntersectionLine {
    IntersectionLine {
        index,
        reserved: 0,
        angle,
    }
}

fn intersection(lines: [IntersectionLine; 3]) -> Intersection {
    let mut slots = [IntersectionLine::default(); 6];
    slots[..3].copy_from_slice(&lines);
    Intersection {
        x: 39,
        y: 20,
        n: 3,
        reserved: 0,
        slots,
    }
}

fn barcode() -> Barcode {
    Barcode {
        x: 30,
        y: 25,
        flags: 0,
        code: 5,
    }
}

fn features(v: &[Vector], i: &[Intersection], b: &[Barcode]) -> ResponseBuf {
    ResponseBuf::Features(FeaturesBuf::from_parts(v, i, b).unwrap())
}

fn response_vectors() -> Vec<(&'static str, ResponseBuf)> {
    let version = Version {
        hardware: 0x2200,
        firmware_major: 3,
        firmware_minor: 0,
        firmware_build: 10,
        firmware_type: pixy2::FirmwareType::GENERAL,
    };
    let err = |c| ResponseBuf::Error(DeviceError::from_code(c));
    vec![
        (VERSION_DOC, ResponseBuf::Version(version)),
        ("af c1 01 04 00 00 00 00 00 00", ResponseBuf::Result(0)),
        ("af c1 01 04 01 00 01 00 00 00", ResponseBuf::Result(1)),
        ("af c1 01 04 3d 00 3d 00 00 00", ResponseBuf::Result(61)),
        (
            "af c1 01 04 9c 00 56 34 12 00",
            Response::rgb(Rgb {
                r: 0x12,
                g: 0x34,
                b: 0x56,
            })
            .to_owned(),
        ),
        ("af c1 03 01 ff 00 ff", err(-1)),
        ("af c1 03 01 fe 00 fe", err(-2)),
        ("af c1 03 01 fd 00 fd", err(-3)),
        ("af c1 03 01 fc 00 fc", err(-4)),
        ("af c1 03 01 fb 00 fb", err(-5)),
        ("af c1 03 01 fa 00 fa", err(-6)),
        (
            "af c1 0d 04 0d 01 3c 01 d0 00",
            ResponseBuf::Resolution(Resolution {
                width: 316,
                height: 208,
            }),
        ),
        (
            "af c1 0d 04 83 00 4f 00 34 00",
            ResponseBuf::Resolution(Resolution {
                width: 79,
                height: 52,
            }),
        ),
        ("af c1 21 00 00 00", ResponseBuf::Blocks(BlocksBuf::new())),
        (
            ONE_BLOCK,
            ResponseBuf::Blocks(BlocksBuf::from_blocks(&[block1()]).unwrap()),
        ),
        (
            TWO_BLOCKS,
            ResponseBuf::Blocks(BlocksBuf::from_blocks(&[block1(), block_cc()]).unwrap()),
        ),
        ("af c1 31 00 00 00", features(&[], &[], &[])),
        (ONE_VECTOR, features(&[vector()], &[], &[])),
        (
            ALL_FEATURES,
            features(
                &[vector()],
                &[intersection([line(2, 90), line(5, 0), line(2, -90)])],
                &[barcode()],
            ),
        ),
        (
            ALL_FEATURES_SORTED,
            features(
                &[vector()],
                &[intersection([line(2, -90), line(5, 0), line(2, 90)])],
                &[barcode()],
            ),
        ),
    ]
}

#[test]
fn golden_responses_encode_and_decode() {
    for (bytes, response) in response_vectors() {
        let wire = hex(bytes);
        assert_eq!(encode(&response), wire, "encode {response:?}");
        assert_eq!(encode(&response.as_response()), wire);
        assert_eq!(encode(&summed(response)), wire);
        assert_eq!(frames(&host(&wire)), [summed(response)], "{bytes}");
        assert_eq!(
            frames(&any(&wire)),
            [summed(MessageBuf::Response(response))]
        );
        assert_eq!(frames(&device(&wire)), [], "responses are not requests");
    }
    assert_eq!(
        hex(ALL_FEATURES)[4..6],
        hex(ALL_FEATURES_SORTED)[4..6],
        "checksum still 0x0316"
    );
}

#[test]
fn golden_version_no_checksum_form_as_libpixyusb2_builds_it() {
    let wire = hex("ae c1 0f 10 00 22 03 00 0a 00 67 65 6e 65 72 61 6c 00 00 00");
    let events = host(&wire);
    let [Ok(OwnedFrame { message, .. })] = &events[..] else {
        panic!("{events:?}")
    };
    assert_eq!(message.form, Form::NoChecksum);
    let ResponseBuf::Version(v) = message.body else {
        panic!()
    };
    assert_eq!(
        (
            v.hardware,
            v.firmware_major,
            v.firmware_minor,
            v.firmware_build
        ),
        (0x2200, 3, 0, 10)
    );
    assert_eq!(v.firmware_type.as_str(), Some("general"));
    assert_eq!(encode(message), wire);
}

#[test]
fn golden_blocks_typed_values() {
    let wire = hex(TWO_BLOCKS);
    let mut input = &wire[..];
    let mut decoder = pixy2::host_decoder();
    let frame = decoder.decode(&mut input).unwrap().unwrap();
    let Response::Blocks(blocks) = frame.message.body else {
        panic!()
    };
    assert_eq!(blocks.len(), 2);
    let all: Vec<Block> = blocks.iter().collect();
    assert_eq!(all, [block1(), block_cc()]);
    assert!(!all[0].is_color_code());
    assert!(all[1].is_color_code());
    assert_eq!(all[1].signature, 10);
    assert_eq!(all[1].angle, -45);
    assert_eq!(blocks.get(1), Some(block_cc()));
    assert_eq!(blocks.get(2), None);
    assert_eq!(blocks.iter().next_back(), Some(block_cc()));
    // Zero-copy: the view borrows the caller's input.
    let range = wire.as_ptr_range();
    assert!(range.contains(&blocks.as_bytes().as_ptr()));
    assert_eq!(blocks.as_bytes(), &wire[6..]);
    let owned = blocks.to_owned();
    assert_eq!(owned.iter().collect::<Vec<_>>(), all);
    assert_eq!(owned.view(), blocks);
}

#[test]
fn golden_features_typed_values() {
    for (bytes, lines) in [
        (ALL_FEATURES, [line(2, 90), line(5, 0), line(2, -90)]),
        (ALL_FEATURES_SORTED, [line(2, -90), line(5, 0), line(2, 90)]),
    ] {
        let wire = hex(bytes);
        let mut input = &wire[..];
        let mut decoder = pixy2::host_decoder();
        let frame = decoder.decode(&mut input).unwrap().unwrap();
        let Response::Features(f) = frame.message.body else {
            panic!()
        };
        assert_eq!(f.vectors().collect::<Vec<_>>(), [vector()]);
        let inter: Vec<Intersection> = f.intersections().collect();
        assert_eq!(inter.len(), 1);
        assert_eq!((inter[0].x, inter[0].y, inter[0].n), (39, 20, 3));
        assert_eq!(inter[0].lines(), &lines);
        assert_eq!(inter[0].slots[3..], [IntersectionLine::default(); 3]);
        assert_eq!(f.barcodes().collect::<Vec<_>>(), [barcode()]);
        let kinds: Vec<&str> = f
            .sections()
            .map(|s| match s {
                Section::Vectors(v) => {
                    assert_eq!(v.len(), 1);
                    "v"
                }
                Section::Intersections(i) => {
                    assert_eq!(i.len(), 1);
                    "i"
                }
                Section::Barcodes(b) => {
                    assert_eq!(b.len(), 1);
                    "b"
                }
                Section::Unknown { .. } => "?",
            })
            .collect();
        assert_eq!(kinds, ["v", "i", "b"]);
        assert!(wire.as_ptr_range().contains(&f.as_bytes().as_ptr()));
    }
}

// ------------------------------------------------------ streams, §8.4/§8.5

#[test]
fn spi_filler_and_doubled_sync_byte() {
    let wire = hex("01 01 01 af af c1 01 04 00 00 00 00 00 00");
    let events = host(&wire);
    // Filler and the doubled first sync byte are skipped silently.
    assert_eq!(
        events,
        [Ok(OwnedFrame {
            offset: 4,
            len: 10,
            message: summed(ResponseBuf::Result(0))
        }),]
    );
    // A checksum-only decoder sees the same.
    let events = decode_chunked::<Host, 264>(Framing::new().checksum_only(), &wire, 3);
    assert_eq!(frames(&events), [summed(ResponseBuf::Result(0))]);
}

#[test]
fn real_trace_line_features_checksum_little_endian() {
    // Request of the trace, then a one-vector answer whose checksum is 0x0093
    // (payload bytes synthesised to give the trace's checksum).
    let request = hex("ae c1 30 02 00 01");
    assert_eq!(
        frames(&device(&request)),
        [plain(Request::from(GetFeatures {
            scope: 0,
            features: GetFeatures::VECTORS
        }))]
    );
    let wire = hex("af c1 31 08 93 00 01 06 28 00 28 33 09 00");
    let [Ok(OwnedFrame { message, .. })] = &host(&wire)[..] else {
        panic!()
    };
    let ResponseBuf::Features(f) = message.body else {
        panic!()
    };
    assert_eq!(f.view().vectors().count(), 1);
}

#[test]
fn one_flipped_payload_bit_is_a_checksum_error_then_resync() {
    let mut wire = hex(ONE_BLOCK);
    wire[10] ^= 0x04;
    wire.extend(hex(TWO_BLOCKS));
    let events = host(&wire);
    assert_eq!(
        errors(&events)[0],
        (
            0,
            Error::Checksum {
                expected: 0x01b7,
                found: 0x01bb
            }
        )
    );
    assert_eq!(frames(&events), [summed(response_vectors()[15].1)]);
    let mut d = pixy2::host_decoder();
    d.feed(&wire).for_each(drop);
    assert_eq!(d.stats().checksum_failures, 1);
    assert_eq!(d.stats().frames, 1);
}

#[test]
fn fake_sync_in_junk_before_a_valid_frame() {
    // `af c1` with a plausible header and a wrong checksum, then `ae c1` with
    // an unknown type, then the real frame right inside the fake one.
    let mut wire = hex("00 af c1 01 04 12 34 ae c1 77");
    wire.extend(hex(ONE_BLOCK));
    let events = host(&wire);
    assert_eq!(
        frames(&events),
        [summed(ResponseBuf::Blocks(
            BlocksBuf::from_blocks(&[block1()]).unwrap()
        ))]
    );
    let errs = errors(&events);
    assert_eq!(errs[0].0, 1);
    assert!(matches!(errs[0].1, Error::Checksum { .. }));
    assert!(errs.contains(&(7, Error::UnknownType { packet_type: 0x77 })));
}

#[test]
fn malformed_line_features() {
    let cases = [
        // flen not a multiple of 6
        (
            "31 07 01 05 0a 33 28 00 02 00 00",
            Malformed::SectionLength { ftype: 1, flen: 5 },
        ),
        // flen running past the payload
        (
            "31 08 01 07 0a 33 28 00 02 00",
            Malformed::SectionPastEnd { offset: 0 },
        ),
        // a lone section type byte at the end
        (
            "31 09 01 06 0a 33 28 00 02 00 04",
            Malformed::SectionPastEnd { offset: 8 },
        ),
    ];
    let mut seven = "31 1e 02 1c 01 02 07 00".to_string();
    for _ in 0..24 {
        seven.push_str(" 00");
    }
    let cases = cases
        .into_iter()
        .map(|(b, m)| (b.to_string(), m))
        .chain([(seven, Malformed::IntersectionLines { n: 7 })]);
    for (body, what) in cases {
        let body = hex(&body);
        let payload = &body[2..];
        let error = Error::Malformed {
            packet_type: ty::FEATURES,
            what,
        };
        assert_eq!(pixy2::Features::new(payload), Err(what));
        // Checksum form: the frame is consumed and reported after parsing.
        let mut wire = vec![0xaf, 0xc1, body[0], body[1]];
        wire.extend(pixy2::checksum(payload).to_le_bytes());
        wire.extend(payload);
        let n = wire.len();
        wire.extend(hex(ONE_VECTOR));
        let events = host(&wire);
        assert_eq!(events[0], Err(Rejected { offset: 0, error }));
        assert_eq!(
            events[1].as_ref().map(|f| f.offset),
            Ok(n as u64),
            "the next frame"
        );
        let mut d = pixy2::host_decoder();
        d.feed(&wire).for_each(drop);
        assert_eq!((d.stats().malformed, d.stats().frames), (1, 2));
        // No-checksum form: rejected in framing, nothing consumed past byte 0.
        let mut wire = vec![0xae, 0xc1];
        wire.extend(&body);
        let events = host(&wire);
        assert_eq!(events[0], Err(Rejected { offset: 0, error }));
        let mut d = pixy2::host_decoder();
        d.feed(&wire).for_each(drop);
        d.flush().for_each(drop);
        assert_eq!((d.stats().malformed, d.stats().frames), (0, 0));
    }
}

#[test]
fn malformed_no_checksum_frame_does_not_hide_a_real_frame_inside() {
    // An `ae c1 31` header whose section runs past the end; a real checksummed
    // frame starts inside its payload.
    let mut wire = hex("ae c1 31 0c 01 0b");
    wire.extend(hex("af c1 01 04 3d 00 3d 00 00 00"));
    let events = host(&wire);
    assert_eq!(
        events[0],
        Err(Rejected {
            offset: 0,
            error: Error::Malformed {
                packet_type: ty::FEATURES,
                what: Malformed::SectionPastEnd { offset: 0 }
            }
        })
    );
    assert_eq!(frames(&events), [summed(ResponseBuf::Result(61))]);
}

#[test]
fn unknown_feature_type_is_reported_not_fatal() {
    let wire = hex("af c1 31 0c dd 01 01 06 0a 33 28 00 02 00 08 02 aa bb");
    let [Ok(OwnedFrame { message, .. })] = &host(&wire)[..] else {
        panic!()
    };
    let ResponseBuf::Features(f) = message.body else {
        panic!()
    };
    let f = f.view();
    let sections: Vec<_> = f.sections().collect();
    assert_eq!(sections.len(), 2);
    assert!(matches!(
        sections[1],
        Section::Unknown {
            ftype: 8,
            data: [0xaa, 0xbb]
        }
    ));
    assert_eq!(f.vectors().collect::<Vec<_>>(), [vector()]);
    assert_eq!(f.barcodes().count(), 0);
    assert_eq!(encode(message), wire);
}

#[test]
fn payload_of_255_bytes_accepted_by_host_dropped_by_device() {
    // 60 barcodes (2 + 240) and an unknown 11-byte section (2 + 11) = 255.
    let mut payload = vec![0x04, 240];
    for i in 0..60u8 {
        payload.extend([i, i, 0, i % 16]);
    }
    payload.extend([0x10, 11]);
    payload.extend([0x5a; 11]);
    assert_eq!(payload.len(), 255);
    let mut wire = hex("af c1 31 ff");
    wire.extend(pixy2::checksum(&payload).to_le_bytes());
    wire.extend(&payload);
    let [Ok(OwnedFrame { message, len, .. })] = &host(&wire)[..] else {
        panic!()
    };
    assert_eq!(*len, 261);
    let ResponseBuf::Features(f) = message.body else {
        panic!()
    };
    assert_eq!(f.view().barcodes().count(), 60);
    assert_eq!(encode(message), wire);

    // The device drops requests over 64 bytes: reported, not decoded.
    let mut request = hex("ae c1 02 41");
    request.extend([0x6c; 65]);
    let events = device(&request);
    assert_eq!(
        events[0],
        Err(Rejected {
            offset: 0,
            error: Error::TooLong {
                packet_type: ty::CHANGE_PROG,
                len: 65,
                max: 64
            }
        })
    );
    assert_eq!(frames(&events), []);
    // 64 is still taken.
    let mut request = hex("ae c1 02 40");
    request.extend([0x6c; 64]);
    assert_eq!(frames(&device(&request)).len(), 1);
}

#[test]
fn impossible_lengths_are_rejected_from_the_header() {
    for (bytes, packet_type, len) in [
        ("af c1 03 02 ff ff fe 01", ty::ERROR, 2),
        ("af c1 01 03 00 00 00 00 00", ty::RESULT, 3),
        ("af c1 01 05 00 00 00 00 00 00 00", ty::RESULT, 5),
        ("af c1 0d 02 00 00 00 00", ty::RESOLUTION, 2),
        ("af c1 0f 07 00 00 00 00 00 00 00 00 00", ty::VERSION, 7),
        ("af c1 21 0d 00 00", ty::BLOCKS, 13),
        ("af c1 21 fc 00 00", ty::BLOCKS, 252),
    ] {
        let wire = hex(bytes);
        let events = host(&wire);
        if len == 252 {
            // 18 blocks is a plausible header: it waits, then is truncated.
            assert_eq!(
                events[0],
                Err(Rejected {
                    offset: 0,
                    error: Error::Truncated { len: 6 }
                })
            );
            continue;
        }
        assert_eq!(
            events[0],
            Err(Rejected {
                offset: 0,
                error: Error::BadLength { packet_type, len }
            }),
            "{bytes}"
        );
    }
    // Requests with the wrong length, as a device decoder sees them.
    for (bytes, packet_type, len) in [
        ("ae c1 12 03 00 00 00", ty::SET_SERVOS, 3),
        ("ae c1 20 01 ff", ty::GET_BLOCKS, 1),
        ("ae c1 0e 01 00", ty::GET_VERSION, 1),
    ] {
        assert_eq!(
            device(&hex(bytes))[0],
            Err(Rejected {
                offset: 0,
                error: Error::BadLength { packet_type, len }
            })
        );
    }
    // Unknown request type and a response type sent to a device.
    assert_eq!(
        errors(&device(&hex("ae c1 32 00"))),
        [(0, Error::UnknownType { packet_type: 0x32 })]
    );
    assert_eq!(
        errors(&device(&hex("af c1 01 04 00 00 00 00 00 00"))),
        [(0, Error::UnknownType { packet_type: 0x01 })]
    );
}

#[test]
fn get_blocks_with_sigmap_zero() {
    // What the official host library sends for sigmap 0; the camera answers
    // ERROR -3. The encoder refuses it unless asked explicitly.
    let request = Request::from(GetBlocks {
        sigmap: 0,
        max_blocks: 5,
    });
    assert!(matches!(
        request.encode(&mut [0u8; 16]),
        Err(EncodeError::OutOfRange { .. })
    ));
    for form in [Form::NoChecksum, Form::Checksum] {
        let envelope = Envelope::new(form, request);
        assert!(envelope.encode(&mut [0u8; 16]).is_err());
        let bytes = FrameBuf::<16>::encode(&envelope.even_if_refused()).unwrap();
        let expected = match form {
            Form::NoChecksum => hex("ae c1 20 02 00 05"),
            Form::Checksum => hex("af c1 20 02 05 00 00 05"),
        };
        assert_eq!(&bytes[..], &expected[..]);
        // Decoded as the request it is, in both forms.
        let events = device(&expected);
        assert_eq!(events.len(), 1, "{form:?}: {events:?}");
        let frame = events[0].unwrap();
        assert_eq!((frame.offset, frame.len), (0, expected.len()));
        assert_eq!(frame.message, envelope);
    }
    // Other requests encode as they always do.
    let fps = Envelope::new(Form::NoChecksum, Request::from(GetFps));
    assert_eq!(
        &FrameBuf::<8>::encode(&fps.even_if_refused()).unwrap()[..],
        &FrameBuf::<8>::encode(&fps).unwrap()[..]
    );
}

#[test]
fn device_errors_keep_unknown_codes() {
    for code in i8::MIN..=i8::MAX {
        let e = DeviceError::from_code(code);
        assert_eq!(e.code(), code);
        assert_eq!(
            matches!(e, DeviceError::Unknown(_)),
            !(-6..=-1).contains(&code)
        );
        let wire = encode(&Response::Error(e));
        assert_eq!(wire, [0xaf, 0xc1, 0x03, 0x01, code as u8, 0x00, code as u8]);
        assert_eq!(frames(&host(&wire)), [summed(ResponseBuf::Error(e))]);
    }
    assert_eq!(DeviceError::from_code(-3), DeviceError::InvalidRequest);
    assert_eq!(DeviceError::from_code(-4), DeviceError::TypeUnsupported);
    assert_eq!(DeviceError::from_code(-7), DeviceError::Unknown(-7));
}

#[test]
fn result_is_a_full_i32() {
    let wire = hex("af c1 01 04 80 00 00 00 00 80");
    assert_eq!(
        frames(&host(&wire)),
        [summed(ResponseBuf::Result(i32::MIN))]
    );
    assert_eq!(GetFps.answer(Response::Result(i32::MIN)), Ok(0x8000_0000));
}

// ------------------------------------------------- chunking, prefixes, push

/// Frames of both directions and forms, with garbage, filler and false syncs.
fn mixed_stream() -> Vec<u8> {
    let mut input = hex("00 ff ae af 01 01");
    for (bytes, _) in response_vectors() {
        input.extend(hex(bytes));
        input.extend(hex("ae c1 af"));
    }
    for (bytes, request) in request_vectors() {
        input.extend(hex(&bytes));
        input.extend(encode(&summed(request)));
        input.extend(hex("01 af af"));
    }
    input.extend(hex("af c1 21 0e 00 00 01 00"));
    input.extend(hex(ONE_VECTOR));
    input.extend(hex("ae c1 31 04 01 06"));
    input.extend(hex("af"));
    input
}

fn check_splits<S: Side, const N: usize>(framing: Framing<S>, input: &[u8])
where
    Ev<S>: PartialEq + std::fmt::Debug,
{
    let whole = decode_chunked::<S, N>(framing, input, input.len());
    assert!(whole.iter().any(|e| e.is_ok()));
    for split in 0..=input.len() {
        let mut decoder = StreamDecoder::<Framing<S>, N>::new(framing);
        let mut events: Vec<Ev<S>> = decoder.feed(&input[..split]).collect();
        events.extend(decoder.feed(&input[split..]));
        events.extend(decoder.flush());
        assert!(events == whole, "split at {split}");
    }
    for chunk in [1, 2, 3, 4, 5, 6, 7, 13, 64, 100, 261] {
        assert!(
            decode_chunked::<S, N>(framing, input, chunk) == whole,
            "chunk {chunk}"
        );
    }
    // push byte at a time, polling after each byte.
    let mut decoder = StreamDecoder::<Framing<S>, N>::new(framing);
    let mut events = Vec::new();
    for &b in input {
        if let Some(e) = decoder.push(b) {
            events.push(robowire::stream::owned_event::<Framing<S>>(e));
        }
        while let Some(e) = decoder.poll() {
            events.push(robowire::stream::owned_event::<Framing<S>>(e));
        }
    }
    events.extend(decoder.flush());
    assert!(events == whole, "push");
}

#[test]
fn every_split_point_and_push_give_the_same_events() {
    let input = mixed_stream();
    check_splits::<Host, 264>(Framing::new(), &input);
    check_splits::<Host, 264>(Framing::new().checksum_only(), &input);
    check_splits::<Device, 72>(Framing::new(), &input);
    check_splits::<Both, 264>(Framing::new(), &input);
    let all = any(&input);
    let n_frames = frames(&all).len();
    assert_eq!(
        n_frames,
        response_vectors().len() + 2 * request_vectors().len() + 1
    );
}

#[test]
fn every_proper_prefix_needs_more() {
    let responses = response_vectors().into_iter().map(|(b, _)| hex(b));
    let requests = request_vectors().into_iter().map(|(b, _)| hex(&b));
    for wire in responses.chain(requests) {
        for cut in 1..wire.len() {
            let mut decoder = pixy2::both_decoder();
            let mut input = &wire[..cut];
            assert!(
                decoder.decode(&mut input).is_none(),
                "{wire:02x?} cut {cut}"
            );
            assert!(input.is_empty());
            assert_eq!(decoder.buffered(), cut);
            assert_eq!(decoder.stats().frames, 0);
            let first = decoder.finish().map(|e| e.map(|_| ()));
            assert_eq!(
                first,
                Some(Err(Rejected {
                    offset: 0,
                    error: Error::Truncated { len: cut }
                }))
            );
        }
    }
}

#[test]
fn sync_split_across_chunks_is_found() {
    let wire = hex(ONE_VECTOR);
    for split in 0..wire.len() {
        let mut d = pixy2::host_decoder();
        let mut events: Vec<_> = d.feed(&wire[..split]).collect();
        events.extend(d.feed(&wire[split..]));
        assert_eq!(events.len(), 1, "split {split}");
        assert!(events[0].is_ok());
    }
}

// -------------------------------------------------------------- corruption

struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

fn random_response(rng: &mut XorShift) -> ResponseBuf {
    match rng.below(5) {
        0 => ResponseBuf::Result(rng.next() as i32),
        1 => ResponseBuf::Error(DeviceError::from_code(rng.next() as i8)),
        2 => {
            let n = rng.below(19) as usize;
            let blocks: Vec<Block> = (0..n)
                .map(|_| {
                    let b = rng.next().to_le_bytes();
                    let c = rng.next().to_le_bytes();
                    let mut w = [0u8; 14];
                    w[..8].copy_from_slice(&b);
                    w[8..].copy_from_slice(&c[..6]);
                    Block::from_bytes(&w)
                })
                .collect();
            ResponseBuf::Blocks(BlocksBuf::from_blocks(&blocks).unwrap())
        }
        3 => {
            let v: Vec<Vector> = (0..rng.below(5))
                .map(|_| {
                    let b = rng.next().to_le_bytes();
                    Vector {
                        x0: b[0],
                        y0: b[1],
                        x1: b[2],
                        y1: b[3],
                        index: b[4],
                        flags: b[5],
                    }
                })
                .collect();
            let b: Vec<Barcode> = (0..rng.below(5))
                .map(|_| {
                    let b = rng.next().to_le_bytes();
                    Barcode {
                        x: b[0],
                        y: b[1],
                        flags: b[2],
                        code: b[3] & 15,
                    }
                })
                .collect();
            features(&v, &[], &b)
        }
        _ => ResponseBuf::Resolution(Resolution {
            width: rng.next() as u16,
            height: rng.next() as u16,
        }),
    }
}

#[test]
fn seeded_corruption_never_costs_an_uncorrupted_frame() {
    for seed in 1..=40u64 {
        let mut rng = XorShift(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let mut wire = Vec::new();
        let mut clean = Vec::new(); // (offset, response) of untouched frames
        for _ in 0..60 {
            for _ in 0..rng.below(6) {
                wire.push(match rng.below(4) {
                    0 => 0xaf,
                    1 => 0xc1,
                    _ => rng.next() as u8,
                });
            }
            let response = random_response(&mut rng);
            let mut bytes = encode(&response);
            if rng.below(4) == 0 {
                let bit = rng.below(bytes.len() as u64 * 8) as usize;
                bytes[bit / 8] ^= 1 << (bit % 8);
            } else {
                clean.push((wire.len() as u64, response));
            }
            wire.extend(bytes);
        }
        // Checksum-only: no unverifiable `ae c1` frame can swallow a real one.
        let events = decode_chunked::<Host, 264>(Framing::new().checksum_only(), &wire, 7);
        let found: Vec<(u64, ResponseBuf)> = events
            .iter()
            .filter_map(|e| e.as_ref().ok().map(|f| (f.offset, f.message.body)))
            .collect();
        for frame in &clean {
            assert!(found.contains(frame), "seed {seed}: lost {frame:?}");
        }
    }
}

// ------------------------------------------------------------ encoder side

#[test]
fn encoder_errors() {
    let r = Request::from(GetFps);
    assert_eq!(
        r.encode(&mut [0u8; 3]),
        Err(EncodeError::BufferTooSmall {
            needed: 4,
            available: 3
        })
    );
    let too_many = [block1(); 19];
    assert_eq!(
        BlocksBuf::from_blocks(&too_many),
        Err(EncodeError::TooLong { len: 266, max: 252 })
    );
    let mut buf = BlocksBuf::from_blocks(&too_many[..18]).unwrap();
    assert_eq!(buf.push(block1()), Err(block1()));
    let mut bad = intersection([line(1, 0), line(2, 0), line(3, 0)]);
    bad.n = 7;
    assert!(matches!(
        FeaturesBuf::from_parts(&[], &[bad], &[]),
        Err(EncodeError::OutOfRange { .. })
    ));
    assert!(matches!(
        FeaturesBuf::from_parts(&[vector(); 43], &[], &[]),
        Err(EncodeError::TooLong { .. })
    ));
    assert!(FeaturesBuf::from_parts(&[vector(); 42], &[], &[]).is_ok());
    assert!(matches!(
        FeaturesBuf::from_parts(&[vector(); 42], &[], &[barcode()]),
        Err(EncodeError::TooLong { .. })
    ));
    assert!(pixy2::FirmwareType::new("01234567890").is_err());
    // Values the device accepts are passed through.
    assert_eq!(
        encode(&Request::from(SetServos {
            pan: 1001,
            tilt: 65535
        })),
        hex("ae c1 12 04 e9 03 ff ff")
    );
    assert_eq!(Request::MAX_LEN, 68);
    assert_eq!(Response::MAX_LEN, 261);
}

// ----------------------------------------------------------------- pairing

#[test]
fn pairing_gives_typed_answers() {
    let version = match response_vectors()[0].1 {
        ResponseBuf::Version(v) => v,
        _ => unreachable!(),
    };
    assert_eq!(GetVersion.answer(Response::Version(version)), Ok(version));
    assert_eq!(
        GetVersion.answer(Response::Error(DeviceError::Busy)),
        Err(PairError::Device(DeviceError::Busy))
    );
    let res = Resolution {
        width: 79,
        height: 52,
    };
    assert_eq!(
        GetResolution::default().answer(Response::Resolution(res)),
        Ok(res)
    );
    assert_eq!(GetFps.answer(Response::Result(61)), Ok(61));
    assert_eq!(
        GetFps.answer(Response::Resolution(res)),
        Err(PairError::WrongType {
            expected: ty::RESULT,
            found: ty::RESOLUTION
        })
    );
    let rgb = Rgb {
        r: 0x12,
        g: 0x34,
        b: 0x56,
    };
    let q = GetRgb::new(158, 104, true);
    assert_eq!(q.answer(Response::Result(0x0012_3456)), Ok(rgb));
    assert_eq!(
        q.answer(Response::Result(0x0112_3456)),
        Err(PairError::UnexpectedResult { value: 0x0112_3456 })
    );
    let cp = ChangeProg(ProgName::LINE_TRACKING);
    assert_eq!(cp.answer(Response::Result(1)), Ok(ProgSwitch::Running));
    assert_eq!(cp.answer(Response::Result(0)), Ok(ProgSwitch::Pending));
    assert_eq!(
        cp.answer(Response::Error(DeviceError::InvalidRequest)),
        Err(PairError::Device(DeviceError::InvalidRequest))
    );
    assert_eq!(
        SetServos { pan: 1, tilt: 2 }.answer(Response::Result(0)),
        Ok(())
    );
    assert_eq!(
        ReverseVector.answer(Response::Error(DeviceError::General)),
        Err(PairError::Device(DeviceError::General))
    );
    assert_eq!(
        SetLamp::new(true, true).answer(Response::Result(3)),
        Err(PairError::UnexpectedResult { value: 3 })
    );
    assert_eq!(
        SetLed::default().answer(Response::Error(DeviceError::Unknown(-9))),
        Err(PairError::Device(DeviceError::Unknown(-9)))
    );

    let two = BlocksBuf::from_blocks(&[block1(), block_cc()]).unwrap();
    let all = GetBlocks {
        sigmap: 0xff,
        max_blocks: 18,
    };
    assert_eq!(all.answer(Response::Blocks(two.view())), Ok(two.view()));
    assert_eq!(
        GetBlocks {
            max_blocks: 1,
            ..all
        }
        .answer(Response::Blocks(two.view())),
        Err(PairError::TooManyBlocks { max: 1, found: 2 })
    );
    assert_eq!(
        GetBlocks {
            sigmap: GetBlocks::SIG1,
            ..all
        }
        .answer(Response::Blocks(two.view())),
        Err(PairError::UnrequestedSignature { signature: 10 })
    );
    assert_eq!(
        GetBlocks {
            sigmap: GetBlocks::COLOR_CODES,
            ..all
        }
        .answer(Response::Blocks(two.view())),
        Err(PairError::UnrequestedSignature { signature: 1 })
    );

    let f = FeaturesBuf::from_parts(&[vector()], &[], &[barcode()]).unwrap();
    let q = GetFeatures {
        scope: GetFeatures::ALL,
        features: GetFeatures::ALL_FEATURES,
    };
    assert_eq!(q.answer(Response::Features(f.view())), Ok(f.view()));
    assert_eq!(
        GetFeatures {
            features: GetFeatures::VECTORS,
            ..q
        }
        .answer(Response::Features(f.view())),
        Err(PairError::UnrequestedFeature {
            ftype: GetFeatures::BARCODES
        })
    );

    // The enum pairs the same way and hands back the response.
    let req = Request::from(GetFps);
    assert_eq!(req.answer(Response::Result(60)), Ok(Response::Result(60)));
    assert_eq!(
        req.answer(Response::Blocks(two.view())),
        Err(PairError::WrongType {
            expected: ty::RESULT,
            found: ty::BLOCKS
        })
    );
    assert_eq!(req.response_type(), ty::RESULT);
    assert_eq!(Request::from(all).response_type(), ty::BLOCKS);
}

// ------------------------------------- a host loop against a simulated Pixy2

/// A simulated device: decodes requests from its input and answers each in
/// checksum form, as §4 and §7.2 describe (a subset of the dispatch).
struct SimPixy {
    decoder: pixy2::DeviceDecoder,
    out: Vec<u8>,
    frames_served: u32,
}

impl SimPixy {
    fn new() -> Self {
        Self {
            decoder: pixy2::device_decoder(),
            out: Vec::new(),
            frames_served: 0,
        }
    }

    fn receive(&mut self, mut bytes: &[u8]) {
        while let Some(event) = self.decoder.decode(&mut bytes) {
            let answer = match event {
                Ok(frame) => match frame.message.body {
                    Request::GetVersion(_) => Response::Version(Version {
                        hardware: 0x2200,
                        firmware_major: 3,
                        firmware_minor: 0,
                        firmware_build: 20,
                        firmware_type: pixy2::FirmwareType::GENERAL,
                    })
                    .to_owned(),
                    Request::GetFps(_) => ResponseBuf::Result(61),
                    // The camera refuses an empty signature map.
                    Request::GetBlocks(GetBlocks { sigmap: 0, .. }) => {
                        ResponseBuf::Error(DeviceError::InvalidRequest)
                    }
                    Request::GetBlocks(q) => {
                        // Every other call: no new frame yet.
                        self.frames_served += 1;
                        if self.frames_served % 2 == 0 {
                            ResponseBuf::Error(DeviceError::Busy)
                        } else {
                            let blocks = [block1(), block_cc()];
                            let n = usize::from(q.max_blocks).min(2);
                            ResponseBuf::Blocks(BlocksBuf::from_blocks(&blocks[..n]).unwrap())
                        }
                    }
                    _ => ResponseBuf::Result(0),
                },
                // Wrong length: −3; unknown type: −4; bad checksum or too
                // long: dropped without an answer.
                Err(Rejected {
                    error: Error::BadLength { .. } | Error::Malformed { .. },
                    ..
                }) => ResponseBuf::Error(DeviceError::InvalidRequest),
                Err(Rejected {
                    error: Error::UnknownType { .. },
                    ..
                }) => ResponseBuf::Error(DeviceError::TypeUnsupported),
                Err(_) => continue,
            };
            // SPI filler and a doubled first sync byte, as some links send.
            self.out.extend([0x01, 0x01, 0xaf]);
            self.out.extend(encode(&answer));
        }
    }
}

/// The README's host loop: send a request, decode until its answer.
fn ask<Q: Query>(
    link: &mut SimPixy,
    decoder: &mut pixy2::HostDecoder,
    query: Q,
) -> Result<ResponseBuf, PairError> {
    let mut buf = [0u8; 72];
    let n = query.request().encode(&mut buf).unwrap();
    link.receive(&buf[..n]);
    let rx = std::mem::take(&mut link.out);
    // Deliver in small chunks, as a UART would.
    for chunk in rx.chunks(5) {
        let mut input = chunk;
        while let Some(event) = decoder.decode(&mut input) {
            if let Ok(frame) = event {
                let body = frame.message.body;
                return query.answer(body).map(|_| body.to_owned());
            }
        }
    }
    panic!("no answer")
}

#[test]
fn host_loop_against_a_simulated_device() {
    let mut link = SimPixy::new();
    let mut decoder = pixy2::host_decoder();
    let ResponseBuf::Version(v) = ask(&mut link, &mut decoder, GetVersion).unwrap() else {
        panic!()
    };
    assert_eq!(v.firmware_build, 20);
    assert_eq!(
        ask(&mut link, &mut decoder, GetFps),
        Ok(ResponseBuf::Result(61))
    );
    let q = GetBlocks {
        sigmap: GetBlocks::ALL,
        max_blocks: 1,
    };
    let ResponseBuf::Blocks(b) = ask(&mut link, &mut decoder, q).unwrap() else {
        panic!()
    };
    assert_eq!(b.iter().collect::<Vec<_>>(), [block1()]);
    assert_eq!(
        ask(&mut link, &mut decoder, q),
        Err(PairError::Device(DeviceError::Busy))
    );
    // Malformed requests reach the simulator as events it can answer, and a
    // getBlocks with sigmap 0 as the request it is.
    link.receive(&hex("ae c1 12 03 00 00 00 ae c1 32 00 ae c1 20 02 00 01"));
    let answers = frames(&host(&std::mem::take(&mut link.out)));
    assert_eq!(
        answers,
        [
            summed(ResponseBuf::Error(DeviceError::InvalidRequest)),
            summed(ResponseBuf::Error(DeviceError::TypeUnsupported)),
            summed(ResponseBuf::Error(DeviceError::InvalidRequest)),
        ]
    );
    assert!(
        decoder.stats().skipped >= 4,
        "filler and doubled sync bytes counted"
    );
}

#[test]
fn any_direction_capture_of_a_conversation() {
    let mut capture = Vec::new();
    capture.extend(encode(&Request::from(GetFps)));
    capture.extend(encode(&Response::Result(61)));
    capture.extend(encode(&Request::from(GetVersion)));
    capture.extend(encode(&Response::Error(DeviceError::Busy)));
    let messages = frames(&any(&capture));
    let kinds: Vec<_> = messages
        .iter()
        .map(|p| match p.body.as_message() {
            Message::Request(r) => r.packet_type(),
            Message::Response(r) => r.packet_type(),
        })
        .collect();
    assert_eq!(kinds, [ty::GET_FPS, ty::RESULT, ty::GET_VERSION, ty::ERROR]);
}
