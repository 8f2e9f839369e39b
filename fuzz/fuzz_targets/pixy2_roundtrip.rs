//! Every frame decoded from arbitrary bytes re-encodes to exactly its wire
//! bytes, borrowed and owned, in both directions (host, device and
//! any-direction decoders).
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::pixy2::{self, Envelope};
use robowire::{Encode, FrameBuf};

fn same<M: Encode>(message: &M, raw: &[u8]) {
    let frame = FrameBuf::<261>::encode(message).expect("a decoded frame encodes");
    assert_eq!(&frame[..], raw);
    assert_eq!(message.encoded_len(), raw.len());
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
        }
    }

    let mut device = pixy2::device_decoder();
    let mut input = data;
    while let Some(event) = device.decode(&mut input) {
        if let Ok(frame) = event {
            same(&frame.message, frame.raw);
            assert!(frame.raw.len() <= 6 + pixy2::DEVICE_MAX_PAYLOAD);
        }
    }

    let mut any = pixy2::both_decoder();
    let mut input = data;
    while let Some(event) = any.decode(&mut input) {
        if let Ok(frame) = event {
            same(&frame.message, frame.raw);
            let owned = Envelope::new(frame.message.form, frame.message.body.to_owned());
            same(&owned, frame.raw);
        }
    }
});
