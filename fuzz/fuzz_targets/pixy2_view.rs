//! Views of arbitrary payloads: blocks and line features iterate without
//! panic, the owned copy equals the view, and typed parsing of any payload as
//! any request or response type either fails cleanly or re-encodes the same
//! payload.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::pixy2::{
    Blocks, Envelope, Features, FeaturesBuf, Form, Intersection, Request, Response, Section,
};
use robowire::{Encode, FrameBuf};

fn payload_of<M: Encode>(message: &M) -> Vec<u8> {
    let frame = FrameBuf::<261>::encode(message).expect("a parsed message encodes");
    frame[4..].to_vec()
}

fuzz_target!(|data: &[u8]| {
    if let Some(view) = Blocks::new(data) {
        let owned = view.to_owned();
        assert_eq!(owned.view(), view);
        assert_eq!(view.iter().count(), view.len());
        assert!(view.iter().eq(owned.iter()));
        assert!(view.iter().rev().eq(owned.iter().rev()));
        for (i, block) in view.iter().enumerate() {
            assert_eq!(view.get(i), Some(block));
            assert_eq!(&block.to_bytes()[..], &data[i * 14..i * 14 + 14]);
        }
        assert_eq!(view.get(view.len()), None);
    }

    if let Ok(view) = Features::new(data) {
        let owned = view.to_owned();
        assert_eq!(owned.view(), view);
        assert_eq!(FeaturesBuf::from_payload(data), Ok(owned));
        assert!(view.vectors().eq(owned.view().vectors()));
        assert!(view.intersections().eq(owned.view().intersections()));
        assert!(view.barcodes().eq(owned.view().barcodes()));
        let mut len = 0;
        for section in view.sections() {
            len += 2 + match section {
                Section::Vectors(v) => 6 * v.count(),
                Section::Intersections(i) => {
                    i.inspect(|x: &Intersection| assert!(x.lines().len() == usize::from(x.n)))
                        .count()
                        * 28
                }
                Section::Barcodes(b) => 4 * b.count(),
                Section::Unknown { data, .. } => data.len(),
            };
        }
        assert_eq!(len, data.len());
    }

    // Any payload as every type, in a whole frame: a clean error or an
    // exact re-encoding.
    if data.len() <= 255 {
        let mut frame = vec![0xae, 0xc1, 0, data.len() as u8];
        frame.extend_from_slice(data);
        for packet_type in 0..=255u8 {
            frame[2] = packet_type;
            if let Ok(r) = Response::try_from(&frame[..]) {
                assert_eq!(payload_of(&Envelope::new(Form::NoChecksum, r)), data);
                assert_eq!(r.to_owned().as_response(), r);
            }
            if let Ok(r) = Request::try_from(&frame[..]) {
                // Decoded requests include what the device refuses (getBlocks
                // with sigmap 0), which encodes only when asked to.
                let envelope = Envelope::new(Form::NoChecksum, r);
                assert_eq!(payload_of(&envelope.even_if_refused()), data);
            }
        }
    }
});
