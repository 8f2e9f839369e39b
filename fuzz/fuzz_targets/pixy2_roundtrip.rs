//! Every frame decoded from arbitrary bytes re-encodes to exactly its wire
//! bytes, borrowed and owned, in both directions (host, device and
//! any-direction decoders); a request the device refuses (getBlocks sigmap
//! 0) through the explicit opt-in; and every frame's JSON line (as `robowire
//! decode pixy2` prints it) reads back and encodes to the same bytes, the
//! refused request through its `quirk` marker.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::pixy2::{self, Envelope, Message, MessageBuf, Request};
use robowire::{Encode, FrameBuf};

/// decode | encode: the frame's JSON line reads back as the tool reads it,
/// the plain encoder refuses it exactly when it is marked, and through the
/// opt-in it encodes to `raw`.
fn same_line(line: serde_json::Result<serde_json::Value>, raw: &[u8]) {
    let line = line.expect("a frame serializes");
    let marked = line.get("quirk").is_some();
    let back: Envelope<MessageBuf> =
        serde_json::from_value(line.clone()).expect("its line reads back");
    assert_eq!(FrameBuf::<261>::encode(&back).is_ok(), !marked, "{line}");
    let frame = FrameBuf::<261>::encode(&back.even_if_refused());
    assert_eq!(&frame.expect("the line encodes")[..], raw, "{line}");
    assert_eq!(marked, back.body.quirk().is_some());
}

fn same<M: Encode>(message: &M, raw: &[u8]) {
    let frame = FrameBuf::<261>::encode(message).expect("a decoded frame encodes");
    assert_eq!(&frame[..], raw);
    assert_eq!(message.encoded_len(), raw.len());
}

/// A request, through the opt-in that also encodes what the device refuses.
fn same_request(request: Envelope<Request>, raw: &[u8]) {
    same(&request.even_if_refused(), raw);
}

fuzz_target!(|data: &[u8]| {
    let mut host = pixy2::host_decoder();
    let mut input = data;
    while let Some(event) = host.decode(&mut input) {
        if let Ok(frame) = event {
            same(&frame.message, frame.raw);
            let owned = Envelope::new(frame.message.form, frame.message.body.to_owned());
            same(&owned, frame.raw);
            assert_eq!(owned.body.as_response(), frame.message.body);
            same_line(serde_json::to_value(frame.message), frame.raw);
        }
    }

    let mut device = pixy2::device_decoder();
    let mut input = data;
    while let Some(event) = device.decode(&mut input) {
        if let Ok(frame) = event {
            same_request(frame.message, frame.raw);
            assert!(frame.raw.len() <= 6 + pixy2::DEVICE_MAX_PAYLOAD);
            same_line(serde_json::to_value(frame.message), frame.raw);
        }
    }

    let mut any = pixy2::both_decoder();
    let mut input = data;
    while let Some(event) = any.decode(&mut input) {
        if let Ok(frame) = event {
            same_line(serde_json::to_value(frame.message), frame.raw);
            if let Message::Request(r) = frame.message.body {
                same_request(Envelope::new(frame.message.form, r), frame.raw);
                continue;
            }
            same(&frame.message, frame.raw);
            let owned = Envelope::new(frame.message.form, frame.message.body.to_owned());
            same(&owned, frame.raw);
        }
    }
});
