//! Arbitrary bytes, fed in chunk sizes taken from the input, give the same
//! events as the whole buffer at once and as one byte at a time; every call
//! consumes no more than it is given; the counters always add up.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::pixy2::{Both, Device, Framing, Host, Side};
use robowire::stream::owned_event;
use robowire::{OwnedEvent, StreamDecoder};

fn counters_add_up<S: Side, const N: usize>(d: &StreamDecoder<Framing<S>, N>) {
    let s = d.stats();
    assert_eq!(s.bytes, s.frame_bytes + s.skipped + d.buffered() as u64);
}

fn whole<S: Side, const N: usize>(
    framing: Framing<S>,
    input: &[u8],
) -> Vec<OwnedEvent<Framing<S>>> {
    let mut d = StreamDecoder::<Framing<S>, N>::new(framing);
    let mut events: Vec<_> = d.feed(input).collect();
    counters_add_up(&d);
    events.extend(d.flush());
    counters_add_up(&d);
    assert_eq!(d.stats().bytes, input.len() as u64);
    events
}

fn chunked<S: Side, const N: usize>(
    framing: Framing<S>,
    input: &[u8],
    sizes: &[u8],
) -> Vec<OwnedEvent<Framing<S>>> {
    let mut d = StreamDecoder::<Framing<S>, N>::new(framing);
    let mut events = Vec::new();
    let mut rest = input;
    let mut i = 0;
    while !rest.is_empty() {
        let size = sizes
            .get(i % sizes.len().max(1))
            .map_or(1, |&s| usize::from(s) + 1);
        i += 1;
        let (chunk, after) = rest.split_at(size.min(rest.len()));
        rest = after;
        let mut left = chunk;
        loop {
            let before = left.len();
            let event = d.decode(&mut left);
            assert!(left.len() <= before, "consumed more than given");
            assert!(chunk.ends_with(left), "remainder is a suffix of the chunk");
            match event {
                Some(e) => events.push(owned_event::<Framing<S>>(e)),
                None => {
                    assert!(left.is_empty(), "None only once the chunk is used up");
                    break;
                }
            }
        }
        counters_add_up(&d);
    }
    while let Some(e) = d.finish() {
        events.push(owned_event::<Framing<S>>(e));
    }
    counters_add_up(&d);
    assert_eq!(d.buffered(), 0);
    events
}

fn pushed<S: Side, const N: usize>(
    framing: Framing<S>,
    input: &[u8],
) -> Vec<OwnedEvent<Framing<S>>> {
    let mut d = StreamDecoder::<Framing<S>, N>::new(framing);
    let mut events = Vec::new();
    for &b in input {
        if let Some(e) = d.push(b) {
            events.push(owned_event::<Framing<S>>(e));
        }
        while let Some(e) = d.poll() {
            events.push(owned_event::<Framing<S>>(e));
        }
        counters_add_up(&d);
    }
    events.extend(d.flush());
    events
}

fn check<S: Side, const N: usize>(framing: Framing<S>, input: &[u8], sizes: &[u8])
where
    OwnedEvent<Framing<S>>: PartialEq + core::fmt::Debug,
{
    let reference = whole::<S, N>(framing, input);
    assert_eq!(chunked::<S, N>(framing, input, sizes), reference);
    assert_eq!(pushed::<S, N>(framing, input), reference);
}

fuzz_target!(|data: &[u8]| {
    // First byte: how many chunk-size bytes follow (0..=15); then the sizes;
    // the rest is the stream.
    let Some((&k, data)) = data.split_first() else {
        return;
    };
    let (sizes, input) = data.split_at(usize::from(k & 15).min(data.len()));
    check::<Host, 264>(Framing::new(), input, sizes);
    check::<Host, 264>(Framing::new().checksum_only(), input, sizes);
    check::<Device, 72>(Framing::new(), input, sizes);
    check::<Both, 264>(Framing::new(), input, sizes);
});
