//! Decode arbitrary bytes; every decoded frame is the input's bytes at its
//! offset, re-encodes to exactly those bytes, and decodes alone (as a datagram,
//! and through the typed `from_frame`/`from_parts`) to the same message.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::{Command, DatagramDecoder, Decoder, Packet, Telemetry};
use robowire::{Encode, FrameBuf};
use robowire_fuzz::omnitiles_framing;

fuzz_target!(|data: &[u8]| {
    let Some((&selector, input)) = data.split_first() else {
        return;
    };
    let framing = omnitiles_framing(selector);
    let mut decoder = Decoder::new(framing);
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
        check_round_trip(&raw, &message);
        let mut datagrams = DatagramDecoder::new(framing);
        let alone: Vec<_> = datagrams.decode(&raw).collect();
        assert_eq!(alone.len(), 1, "{raw:02x?} alone: {alone:?}");
        let got = alone[0].as_ref().expect("a valid frame alone decodes");
        assert_eq!((got.offset, got.len, got.message), (0, raw.len(), message));
    }
});

fn check_round_trip(raw: &[u8], message: &Packet) {
    assert_eq!(message.encoded_len(), raw.len());
    let encoded =
        FrameBuf::<{ Packet::MAX_LEN }>::encode(message).expect("decoded messages encode");
    assert_eq!(&*encoded, raw, "re-encodes to its bytes: {message:?}");
    let mut buf = bytes::BytesMut::new();
    assert_eq!(message.encode_buf(&mut buf), Ok(raw.len()));
    assert_eq!(&buf[..], raw);
    match message {
        Packet::Telemetry(t) => {
            assert!(t.is_consistent());
            assert_eq!(Telemetry::from_frame(raw), Some(*t));
        }
        Packet::Command(c) => {
            assert_eq!(
                Command::from_parts(raw[1], &raw[2..raw.len() - 1]),
                Some(*c)
            );
        }
    }
}
