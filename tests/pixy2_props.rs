//! Pixy2 property tests: typed strategies for every request and response,
//! round trips both ways in both frame forms, garbage between frames,
//! chunking invariance, and arbitrary bytes.

use proptest::prelude::*;
use robowire::pixy2::{
    self, Barcode, Block, BlocksBuf, Both, ChangeProg, DeviceError, Envelope, Features,
    FeaturesBuf, FirmwareType, Form, Framing, GetBlocks, GetFeatures, GetFps, GetResolution,
    GetRgb, GetVersion, Host, Intersection, IntersectionLine, MessageBuf, ProgName, Request,
    Resolution, ResponseBuf, ReverseVector, Section, SetCameraBrightness, SetDefaultTurn, SetLamp,
    SetLed, SetMode, SetNextTurn, SetServos, SetVector, Vector, Version,
};
use robowire::{Encode, FrameBuf, OwnedEvent, StreamDecoder};

fn form() -> impl Strategy<Value = Form> {
    prop_oneof![Just(Form::NoChecksum), Just(Form::Checksum)]
}

fn prog_name() -> impl Strategy<Value = ProgName> {
    prop_oneof![
        "[a-z_]{0,32}".prop_map(|s| ProgName::new(&s).unwrap()),
        prop::collection::vec(any::<u8>(), 0..=64)
            .prop_map(|p| ProgName::from_payload(&p).unwrap()),
    ]
}

fn request() -> impl Strategy<Value = Request> {
    prop_oneof![
        prog_name().prop_map(|n| ChangeProg(n).into()),
        any::<u8>().prop_map(|reserved| GetResolution { reserved }.into()),
        Just(GetVersion.into()),
        any::<u8>().prop_map(|b| SetCameraBrightness(b).into()),
        any::<(u16, u16)>().prop_map(|(pan, tilt)| SetServos { pan, tilt }.into()),
        any::<(u8, u8, u8)>().prop_map(|(r, g, b)| SetLed { r, g, b }.into()),
        any::<(u8, u8)>().prop_map(|(upper, lower)| SetLamp { upper, lower }.into()),
        Just(GetFps.into()),
        (1..=255u8, any::<u8>())
            .prop_map(|(sigmap, max_blocks)| GetBlocks { sigmap, max_blocks }.into()),
        any::<(u8, u8)>().prop_map(|(scope, features)| GetFeatures { scope, features }.into()),
        any::<u8>().prop_map(|m| SetMode(m).into()),
        any::<u8>().prop_map(|v| SetVector(v).into()),
        any::<i16>().prop_map(|a| SetNextTurn(a).into()),
        any::<i16>().prop_map(|a| SetDefaultTurn(a).into()),
        Just(ReverseVector.into()),
        any::<(u16, u16, u8)>().prop_map(|(x, y, saturate)| GetRgb { x, y, saturate }.into()),
    ]
}

fn block() -> impl Strategy<Value = Block> {
    any::<[u8; 14]>().prop_map(|b| Block::from_bytes(&b))
}

fn vector() -> impl Strategy<Value = Vector> {
    any::<[u8; 6]>().prop_map(|[x0, y0, x1, y1, index, flags]| Vector {
        x0,
        y0,
        x1,
        y1,
        index,
        flags,
    })
}

fn intersection() -> impl Strategy<Value = Intersection> {
    (any::<(u8, u8, u8)>(), 0..=6u8, any::<[(u8, u8, i16); 6]>()).prop_map(
        |((x, y, reserved), n, slots)| Intersection {
            x,
            y,
            n,
            reserved,
            slots: slots.map(|(index, reserved, angle)| IntersectionLine {
                index,
                reserved,
                angle,
            }),
        },
    )
}

fn barcode() -> impl Strategy<Value = Barcode> {
    any::<[u8; 4]>().prop_map(|[x, y, flags, code]| Barcode { x, y, flags, code })
}

/// Device-shaped features, or any valid run of sections (unknown types and
/// any order included).
fn features() -> impl Strategy<Value = FeaturesBuf> {
    let parts = (
        prop::collection::vec(vector(), 0..=8),
        prop::collection::vec(intersection(), 0..=3),
        prop::collection::vec(barcode(), 0..=8),
    )
        .prop_map(|(v, i, b)| FeaturesBuf::from_parts(&v, &i, &b).unwrap());
    let section =
        (any::<u8>(), prop::collection::vec(any::<u8>(), 0..40)).prop_map(|(ftype, mut data)| {
            let ftype = ftype | 0x08; // not a known type: any contents
            data.truncate(40);
            let mut s = vec![ftype, data.len() as u8];
            s.extend(data);
            s
        });
    let raw = prop::collection::vec(section, 0..4)
        .prop_map(|s| FeaturesBuf::from_payload(&s.concat()).unwrap());
    prop_oneof![3 => parts, 1 => raw]
}

fn response() -> impl Strategy<Value = ResponseBuf> {
    prop_oneof![
        any::<i32>().prop_map(ResponseBuf::Result),
        any::<i8>().prop_map(|c| ResponseBuf::Error(DeviceError::from_code(c))),
        any::<(u16, u16)>()
            .prop_map(|(width, height)| ResponseBuf::Resolution(Resolution { width, height })),
        (any::<(u16, u8, u8, u16)>(), any::<[u8; 10]>()).prop_map(|((h, ma, mi, b), t)| {
            ResponseBuf::Version(Version {
                hardware: h,
                firmware_major: ma,
                firmware_minor: mi,
                firmware_build: b,
                firmware_type: FirmwareType(t),
            })
        }),
        prop::collection::vec(block(), 0..=18)
            .prop_map(|b| ResponseBuf::Blocks(BlocksBuf::from_blocks(&b).unwrap())),
        features().prop_map(ResponseBuf::Features),
    ]
}

fn message() -> impl Strategy<Value = Envelope<MessageBuf>> {
    (
        form(),
        prop_oneof![
            request().prop_map(MessageBuf::Request),
            response().prop_map(MessageBuf::Response),
        ],
    )
        .prop_map(|(f, m)| Envelope::new(f, m))
}

fn encode<M: Encode>(m: &M) -> Vec<u8> {
    let frame = FrameBuf::<261>::encode(m).unwrap();
    assert_eq!(frame.len(), m.encoded_len());
    assert!(frame.len() <= M::MAX_LEN);
    frame.to_vec()
}

fn decode_any(input: &[u8], chunk: usize) -> Vec<OwnedEvent<Framing<Both>>> {
    let mut d = pixy2::both_decoder();
    let mut events = Vec::new();
    for piece in input.chunks(chunk.max(1)) {
        events.extend(d.feed(piece));
    }
    events.extend(d.flush());
    let s = d.stats();
    assert_eq!(s.bytes, input.len() as u64);
    assert_eq!(s.bytes, s.frame_bytes + s.skipped);
    events
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn request_round_trips(request in request(), form in form()) {
        let packet = Envelope::new(form, request);
        let wire = encode(&packet);
        let mut d = pixy2::device_decoder();
        let events: Vec<_> = d.feed(&wire).collect();
        prop_assert_eq!(events.len(), 1);
        let frame = events[0].as_ref().unwrap();
        prop_assert_eq!(frame.message, packet);
        prop_assert_eq!(frame.len, wire.len());
        prop_assert_eq!(encode(&frame.message), wire.clone());
        // Both-direction decoders agree.
        let any = decode_any(&wire, wire.len());
        prop_assert_eq!(any.len(), 1);
        prop_assert_eq!(
            any[0].as_ref().unwrap().message,
            Envelope::new(form, MessageBuf::Request(request))
        );
    }

    #[test]
    fn response_round_trips(response in response(), form in form()) {
        let packet = Envelope::new(form, response);
        let wire = encode(&packet);
        let mut d = pixy2::host_decoder();
        let mut input = &wire[..];
        let frame = d.decode(&mut input).unwrap().unwrap();
        prop_assert!(input.is_empty());
        prop_assert_eq!(frame.raw, &wire[..]);
        // Borrowed message re-encodes to the same bytes, and so does its
        // owned copy.
        prop_assert_eq!(encode(&frame.message), wire.clone());
        let owned = Envelope::new(frame.message.form, frame.message.body.to_owned());
        prop_assert_eq!(owned, packet);
        prop_assert_eq!(encode(&owned), wire.clone());
    }

    #[test]
    fn views_and_owned_copies_agree(response in response()) {
        match response {
            ResponseBuf::Blocks(b) => {
                let view = b.view();
                let blocks: Vec<Block> = view.iter().collect();
                prop_assert_eq!(blocks.len(), view.len());
                prop_assert_eq!(BlocksBuf::from_blocks(&blocks).unwrap(), b);
                for (i, block) in blocks.iter().enumerate() {
                    prop_assert_eq!(view.get(i), Some(*block));
                    prop_assert_eq!(Block::from_bytes(&block.to_bytes()), *block);
                }
            }
            ResponseBuf::Features(f) => {
                let view = f.view();
                prop_assert_eq!(Features::new(view.as_bytes()), Ok(view));
                let mut bytes = 0;
                for section in view.sections() {
                    bytes += 2 + match section {
                        Section::Vectors(v) => 6 * v.count(),
                        Section::Intersections(i) => 28 * i.count(),
                        Section::Barcodes(b) => 4 * b.count(),
                        Section::Unknown { data, .. } => data.len(),
                    };
                }
                prop_assert_eq!(bytes, view.as_bytes().len());
                let v: Vec<Vector> = view.vectors().collect();
                let i: Vec<Intersection> = view.intersections().collect();
                let b: Vec<Barcode> = view.barcodes().collect();
                if view.sections().all(|s| !matches!(s, Section::Unknown { .. })) {
                    prop_assert_eq!(FeaturesBuf::from_parts(&v, &i, &b).unwrap(), f);
                }
            }
            _ => {}
        }
    }

    #[test]
    fn garbage_between_frames_never_costs_a_checksummed_frame(
        items in prop::collection::vec(
            (prop::collection::vec(any::<u8>(), 0..24), response()), 1..8),
        chunk in 1usize..80,
    ) {
        let mut wire = Vec::new();
        let mut expected = Vec::new();
        for (garbage, response) in &items {
            wire.extend(garbage);
            expected.push((wire.len() as u64, *response));
            wire.extend(encode(response));
        }
        let mut d = StreamDecoder::<Framing<Host>, 264>::new(Framing::new().checksum_only());
        let mut found = Vec::new();
        for piece in wire.chunks(chunk) {
            found.extend(d.feed(piece).flatten().map(|f| (f.offset, f.message.body)));
        }
        // A frame after garbage whose last byte could start a sync word waits
        // for the next byte (or the end of input) before it is emitted.
        found.extend(d.flush().flatten().map(|f| (f.offset, f.message.body)));
        for frame in &expected {
            prop_assert!(found.contains(frame), "lost {:?}", frame);
        }
    }

    #[test]
    fn chunking_and_push_do_not_change_events(
        items in prop::collection::vec(
            (prop::collection::vec(prop_oneof![any::<u8>(), Just(0xae), Just(0xaf), Just(0xc1)], 0..12),
             message()), 0..6),
        chunk in 1usize..64,
    ) {
        let mut wire = Vec::new();
        for (garbage, m) in &items {
            wire.extend(garbage);
            wire.extend(encode(m));
        }
        let whole = decode_any(&wire, wire.len());
        prop_assert_eq!(&decode_any(&wire, chunk), &whole);
        let mut d = pixy2::both_decoder();
        let mut events = Vec::new();
        for &b in &wire {
            if let Some(e) = d.push(b) {
                events.push(robowire::stream::owned_event::<Framing<Both>>(e));
            }
            while let Some(e) = d.poll() {
                events.push(robowire::stream::owned_event::<Framing<Both>>(e));
            }
        }
        events.extend(d.flush());
        prop_assert_eq!(events, whole);
    }

    #[test]
    fn arbitrary_bytes_decode_without_panic_and_frames_re_encode(
        wire in prop::collection::vec(
            prop_oneof![any::<u8>(), Just(0xae), Just(0xaf), Just(0xc1)], 0..300),
    ) {
        let mut d = pixy2::both_decoder();
        let mut input = &wire[..];
        while let Some(event) = d.decode(&mut input) {
            if let Ok(frame) = event {
                // A request the device refuses (getBlocks sigmap 0) is
                // decoded; encoding it takes the explicit opt-in.
                let again = match frame.message.body {
                    pixy2::Message::Request(r) => FrameBuf::<261>::encode(
                        &Envelope::new(frame.message.form, r).even_if_refused(),
                    ),
                    _ => FrameBuf::<261>::encode(&frame.message),
                }
                .unwrap();
                prop_assert_eq!(&again[..], frame.raw);
            }
        }
        while d.finish().is_some() {}
        let s = d.stats();
        prop_assert_eq!(s.bytes, s.frame_bytes + s.skipped);
    }

    #[test]
    fn arbitrary_feature_payloads_never_panic(payload in prop::collection::vec(any::<u8>(), 0..300)) {
        if let Ok(view) = Features::new(&payload) {
            let owned = view.to_owned();
            prop_assert_eq!(owned.view(), view);
            prop_assert_eq!(
                owned.view().vectors().collect::<Vec<_>>(),
                view.vectors().collect::<Vec<_>>()
            );
            prop_assert!(view.intersections().all(|i| i.lines().len() == usize::from(i.n)));
            let _ = view.barcodes().count() + view.sections().count();
        }
    }
}
