//! Decode arbitrary bytes; every decoded frame is the input's bytes at its
//! offset, re-encodes to exactly those bytes (also through its JSON line, as
//! `robowire decode | robowire encode` does), and decodes alone (as a
//! datagram, and through the typed `TryFrom<&[u8]>`) to the same message.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::{
    Command, DatagramDecoder, Framing, Message, Side, Telemetry, BOTH_BUFFER,
};
use robowire::{Encode, FrameBuf, StreamDecoder};
use robowire_fuzz::{omnitiles_framing, with_omnitiles_framing};

fuzz_target!(|data: &[u8]| {
    let Some((&selector, input)) = data.split_first() else {
        return;
    };
    with_omnitiles_framing!(omnitiles_framing(selector), |framing| run(framing, input));
});

fn run<S: Side>(framing: Framing<S>, input: &[u8]) {
    let mut decoder = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
    let mut rest = input;
    let mut frames = Vec::new();
    while let Some(event) = decoder.decode(&mut rest) {
        if let Ok(frame) = event {
            frames.push((frame.offset, frame.raw.to_vec(), frame.message));
        }
    }
    while let Some(event) = decoder.finish() {
        if let Ok(frame) = event {
            frames.push((frame.offset, frame.raw.to_vec(), frame.message));
        }
    }
    for (offset, raw, message) in frames {
        let at = offset as usize;
        assert_eq!(
            &input[at..at + raw.len()],
            &raw[..],
            "raw is the input at its offset"
        );
        check_round_trip(&raw, &message.into());
        let mut datagrams = DatagramDecoder::new(framing);
        let alone: Vec<_> = datagrams.decode(&raw).collect();
        assert_eq!(alone.len(), 1, "{raw:02x?} alone: {alone:?}");
        let got = alone[0].as_ref().expect("a valid frame alone decodes");
        assert_eq!((got.offset, got.len, got.message), (0, raw.len(), message));
    }
}

fn check_round_trip(raw: &[u8], message: &Message) {
    assert_eq!(message.encoded_len(), raw.len());
    let encoded =
        FrameBuf::<{ Message::MAX_LEN }>::encode(message).expect("decoded messages encode");
    assert_eq!(&*encoded, raw, "re-encodes to its bytes: {message:?}");
    let mut buf = bytes::BytesMut::new();
    assert_eq!(message.encode_buf(&mut buf), Ok(raw.len()));
    assert_eq!(&buf[..], raw);
    assert_eq!(Message::try_from(raw), Ok(*message));
    // decode | encode: the JSON line reads back to a message of these bytes.
    let line = serde_json::to_string(message).expect("a message serializes");
    let back: Message = serde_json::from_str(&line).expect("its line reads back");
    let encoded = FrameBuf::<{ Message::MAX_LEN }>::encode(&back).expect("the line encodes");
    assert_eq!(&*encoded, raw, "the line {line} encodes to the frame");
    match message {
        Message::Telemetry(t) => {
            assert!(t.is_consistent());
            assert_eq!(Telemetry::try_from(raw), Ok(*t));
        }
        Message::Command(c) => assert_eq!(Command::try_from(raw), Ok(*c)),
    }
}
