//! OmniTiles property tests: typed strategies, round trips both ways, and
//! garbage between frames.

#[path = "support/omnitiles_sides.rs"]
mod sides;

use proptest::prelude::*;
use robowire::omnitiles::{checksum, Command, Imu, Layout, Layouts, Message, Motor, Telemetry};
use robowire::{Encode, FrameBuf};
use sides::{AnyDecoder, AnyFraming};

fn motor() -> impl Strategy<Value = Motor> {
    prop_oneof![Just(Motor::M1), Just(Motor::M2)]
}

fn command() -> impl Strategy<Value = Command> {
    prop_oneof![
        Just(Command::Ping),
        (motor(), any::<u8>()).prop_map(|(motor, speed)| Command::Extend { motor, speed }),
        (motor(), any::<u8>()).prop_map(|(motor, speed)| Command::Retract { motor, speed }),
        motor().prop_map(|motor| Command::Brake { motor }),
        (motor(), any::<u8>())
            .prop_map(|(motor, position)| Command::SetPosition { motor, position }),
        any::<(i8, i8, i8)>().prop_map(|(vx, vy, omega)| Command::BaseVelocity { vx, vy, omega }),
        Just(Command::BaseBrake),
    ]
}

fn layout() -> impl Strategy<Value = Layout> {
    prop::sample::select(Layout::ALL.to_vec())
}

/// A reading: `None` (sent as 0xFFFF) or any other value.
fn reading() -> impl Strategy<Value = Option<u16>> {
    prop_oneof![1 => Just(None), 9 => (0..0xFFFFu16).prop_map(Some)]
}

fn imu() -> impl Strategy<Value = Imu> {
    // Any bit pattern, NaNs and infinities included.
    any::<[u32; 6]>().prop_map(|bits| Imu::from_array(bits.map(f32::from_bits)))
}

fn telemetry_of(layout: Layout) -> impl Strategy<Value = Telemetry> {
    (
        reading(),
        reading(),
        [reading(), reading(), reading(), reading()],
        reading(),
        imu(),
        any::<[u16; 4]>(),
        any::<[u16; 2]>(),
    )
        .prop_map(move |(m1, m2, uwb, tof, imu, a1, a2)| {
            let empty = Telemetry::empty(layout);
            Telemetry {
                layout,
                m1_pos: m1,
                m2_pos: m2,
                uwb: empty.uwb.map(|_| uwb),
                tof: empty.tof.map(|_| tof),
                imu: empty.imu.map(|_| imu),
                m1_adcs: empty.m1_adcs.map(|_| a1),
                m2_adcs: empty.m2_adcs.map(|_| a2),
            }
        })
}

fn telemetry() -> impl Strategy<Value = Telemetry> {
    layout().prop_flat_map(telemetry_of)
}

fn message() -> impl Strategy<Value = Message> {
    prop_oneof![
        command().prop_map(Message::Command),
        telemetry().prop_map(Message::Telemetry)
    ]
}

fn encode(p: &Message) -> Vec<u8> {
    FrameBuf::<53>::encode(p).unwrap().to_vec()
}

fn decode_all(framing: AnyFraming, input: &[u8]) -> Vec<Message> {
    let mut decoder = AnyDecoder::new(framing);
    let mut out: Vec<Message> = decoder
        .feed(input)
        .filter_map(|e| e.ok().map(|f| f.message))
        .collect();
    out.extend(decoder.flush().filter_map(|e| e.ok().map(|f| f.message)));
    out
}

/// A framing that accepts `p` and nothing ambiguous about its length.
fn exact_framing(p: &Message) -> AnyFraming {
    match p {
        Message::Command(_) => sides::commands(),
        Message::Telemetry(t) => sides::both(Layouts::only(t.layout)),
    }
}

fn cases() -> u32 {
    if cfg!(miri) {
        4
    } else {
        256
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn message_to_bytes_to_equal_message(p in message()) {
        let wire = encode(&p);
        prop_assert_eq!(wire.len(), p.encoded_len());
        prop_assert_eq!(decode_all(exact_framing(&p), &wire), vec![p]);
        if let Message::Telemetry(t) = p {
            prop_assert_eq!(Telemetry::try_from(&wire[..]), Ok(t));
        }
        prop_assert_eq!(Message::try_from(&wire[..]), Ok(p));
    }

    #[test]
    fn valid_frame_to_message_to_same_bytes(layout in layout(), body in prop::collection::vec(any::<u8>(), 51)) {
        // Any body with a correct checksum is a valid frame of the layout.
        let len = layout.frame_len();
        let mut frame = vec![0xa5, 0x60];
        frame.extend_from_slice(&body[..len - 3]);
        frame.push(checksum(&frame[1..]));
        let t = Telemetry::try_from(&frame[..]).expect("valid frame");
        prop_assert_eq!(&*FrameBuf::<53>::encode(&t).unwrap(), &frame[..]);
    }

    #[test]
    fn valid_command_frame_to_message_to_same_bytes(id in any::<u8>(), payload in any::<[u8; 3]>()) {
        if let Some(n) = robowire::omnitiles::payload_len(id) {
            let mut frame = vec![0xa5, id];
            frame.extend_from_slice(&payload[..n]);
            frame.push(checksum(&frame[1..]));
            let got = decode_all(sides::commands(), &frame);
            prop_assert_eq!(got.len(), 1);
            prop_assert_eq!(encode(&got[0]), frame);
        }
    }

    #[test]
    fn stream_of_messages_round_trips_at_any_chunking(
        messages in prop::collection::vec(command(), 0..40),
        chunk in 1usize..64,
    ) {
        let wire: Vec<u8> = messages.iter().flat_map(|c| encode(&Message::Command(*c))).collect();
        let mut decoder = AnyDecoder::new(sides::commands());
        let mut got = Vec::new();
        for piece in wire.chunks(chunk) {
            got.extend(decoder.feed(piece).map(|e| e.unwrap().message));
        }
        prop_assert_eq!(decoder.flush().count(), 0);
        let want: Vec<Message> = messages.into_iter().map(Message::Command).collect();
        prop_assert_eq!(got, want);
    }

    #[test]
    fn mixed_layouts_round_trip(messages in prop::collection::vec(telemetry(), 0..20), chunk in 1usize..80) {
        let wire: Vec<u8> = messages.iter().flat_map(|t| encode(&Message::Telemetry(*t))).collect();
        let mut decoder = AnyDecoder::new(sides::telemetry(Layouts::ALL));
        let mut got = Vec::new();
        for piece in wire.chunks(chunk) {
            got.extend(decoder.feed(piece));
        }
        got.extend(decoder.flush());
        let got: Vec<Message> = got.into_iter().map(|e| e.unwrap().message).collect();
        let want: Vec<Message> = messages.into_iter().map(Message::Telemetry).collect();
        prop_assert_eq!(got, want);
    }

    #[test]
    fn garbage_between_frames_never_costs_a_frame(
        layout in layout(),
        frames in prop::collection::vec((any::<u16>(), prop::collection::vec(any::<u8>(), 0..24)), 1..16),
        chunk in 1usize..100,
    ) {
        // Single-layout mode: telemetry of one layout with random garbage
        // between frames (and 0xA5 bytes in it on purpose).
        let mut wire = Vec::new();
        let mut want = Vec::new();
        for (seed, mut garbage) in frames {
            if seed % 3 == 0 {
                garbage.push(0xa5);
            }
            wire.extend_from_slice(&garbage);
            let mut t = Telemetry::empty(layout);
            t.m1_pos = Some(seed % 4096);
            t.m2_pos = Some(seed / 16);
            wire.extend(encode(&Message::Telemetry(t)));
            want.push(Message::Telemetry(t));
        }
        let mut decoder = AnyDecoder::new(sides::telemetry(Layouts::only(layout)));
        let mut got = Vec::new();
        for piece in wire.chunks(chunk) {
            got.extend(decoder.feed(piece).filter_map(|e| e.ok().map(|f| f.message)));
        }
        got.extend(decoder.flush().filter_map(|e| e.ok().map(|f| f.message)));
        // Every frame is recovered in order (a false frame from garbage would
        // show up as an extra element, and is vanishingly unlikely here).
        let mut it = got.iter();
        for w in &want {
            prop_assert!(it.any(|g| g == w), "lost {:?}", w);
        }
    }

    #[test]
    fn arbitrary_bytes_chunking_invariance(
        bytes in prop::collection::vec(prop_oneof![3 => any::<u8>(), 1 => Just(0xa5u8), 1 => Just(0x60u8)], 0..300),
        chunk in 1usize..70,
    ) {
        let run = |chunk: usize| {
            let mut decoder = AnyDecoder::new(sides::both(Layouts::ALL));
            let mut events = Vec::new();
            for piece in bytes.chunks(chunk) {
                events.extend(decoder.feed(piece));
            }
            events.extend(decoder.flush());
            let s = decoder.stats();
            assert_eq!(s.bytes, s.frame_bytes + s.skipped);
            events
        };
        prop_assert_eq!(run(chunk), run(bytes.len().max(1)));
    }
}

#[cfg(feature = "serde")]
proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// The JSON form reads back as the same message, bit for bit (NaNs and
    /// infinities included), and its display is one line.
    #[test]
    fn message_to_json_to_equal_message(p in message()) {
        let json = serde_json::to_string(&p).unwrap();
        prop_assert_eq!(serde_json::from_str::<Message>(&json).unwrap(), p);
        let text = p.to_string();
        prop_assert!(text.starts_with(p.name()) && !text.contains('\n'), "{}", text);
    }

    /// Any frame with a right checksum that `TryFrom` takes, the decoder
    /// takes too, as the same message.
    #[test]
    fn try_from_agrees_with_the_decoder(bytes in prop::collection::vec(any::<u8>(), 0..60)) {
        let mut frame = vec![0xa5];
        frame.extend_from_slice(&bytes);
        if frame.len() > 2 {
            let n = frame.len();
            frame[n - 1] = checksum(&frame[1..n - 1]);
        }
        if let Ok(message) = Message::try_from(&frame[..]) {
            let decoded = decode_all(sides::both(Layouts::only(match message {
                Message::Telemetry(t) => t.layout,
                Message::Command(_) => Layout::Pos7,
            })), &frame);
            prop_assert_eq!(decoded, vec![message]);
        }
    }
}
