//! The datagram decoder on arbitrary datagrams (each prefixed by a length
//! byte in the fuzz input): no panic; every frame lies inside its datagram and
//! re-encodes to its bytes; a datagram that is not telemetry decodes exactly
//! as the stream decoder finished at its end; counters add up after each.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::{DatagramDecoder, Framing, Message, Side, BOTH_BUFFER};
use robowire::{FrameBuf, StreamDecoder};
use robowire_fuzz::{omnitiles_framing, with_omnitiles_framing};

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    with_omnitiles_framing!(omnitiles_framing(selector), |framing| run(framing, rest));
});

fn run<S: Side>(framing: Framing<S>, mut rest: &[u8]) {
    let mut datagrams = DatagramDecoder::new(framing);
    let mut base = 0u64;
    while let Some((&len, tail)) = rest.split_first() {
        let (datagram, tail) = tail.split_at(usize::from(len).min(tail.len()));
        rest = tail;
        let events: Vec<_> = datagrams.decode(datagram).collect();
        let mut next = base;
        for event in &events {
            match event {
                Ok(frame) => {
                    assert!(frame.offset >= next, "in order: {events:?}");
                    let at = (frame.offset - base) as usize;
                    assert!(at + frame.len <= datagram.len(), "inside the datagram");
                    let raw = &datagram[at..at + frame.len];
                    let encoded = FrameBuf::<{ Message::MAX_LEN }>::encode(&frame.message)
                        .expect("decoded messages encode");
                    assert_eq!(&*encoded, raw, "re-encodes to its bytes");
                    next = frame.offset + frame.len as u64;
                }
                Err(rejected) => {
                    assert!(rejected.offset >= next, "in order: {events:?}");
                    assert!(((rejected.offset - base) as usize) < datagram.len());
                    next = rejected.offset + 1;
                }
            }
        }
        if !datagram.starts_with(&[0xa5, 0x60]) {
            let mut stream = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
            let mut want: Vec<_> = stream.feed(datagram).collect();
            want.extend(stream.flush());
            let got: Vec<_> = events
                .into_iter()
                .map(|e| {
                    e.map(|mut f| {
                        f.offset -= base;
                        f
                    })
                    .map_err(|mut r| {
                        r.offset -= base;
                        r
                    })
                })
                .collect();
            assert_eq!(got, want, "non-telemetry datagram = finished stream");
        }
        base += datagram.len() as u64;
        let s = datagrams.stats();
        assert_eq!(s.bytes, base);
        assert_eq!(s.bytes, s.frame_bytes + s.skipped, "counters add up: {s:?}");
    }
}
