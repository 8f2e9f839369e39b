//! Oracles shared by robowire's fuzz targets.
//!
//! [`check_stream`] holds the streaming engine's contract for any protocol's
//! framing: the same input gives the same events and counters however it is
//! fed (whole, in the chunk sizes taken from the fuzz input, byte at a time
//! through `push`/`poll`, or through the `feed`/`flush` iterators); every call
//! consumes at most its input; every frame's bytes are the input's bytes at its
//! offset; event offsets only move forward; and the counters add up after
//! every call (`bytes == frame_bytes + skipped + buffered`). A new protocol's
//! stream target only has to pick a framing and call it.

use std::fmt::Debug;

use robowire::omnitiles::{Both, Device, Framing, Host, Layout, Layouts};
use robowire::stream::{owned_event, FrameRules, OwnedEvent, StreamDecoder};

/// An OmniTiles framing of any side, as [`omnitiles_framing`] picks it.
#[derive(Debug, Clone, Copy)]
pub enum OmniTilesFraming {
    /// Telemetry in a set of layouts (possibly none).
    Host(Framing<Host>),
    /// Commands.
    Device(Framing<Device>),
    /// Commands and telemetry in a non-empty set of layouts.
    Both(Framing<Both>),
}

/// An OmniTiles framing chosen by one fuzz byte: bit 0 accepts commands, bits
/// 1..=5 pick the telemetry layouts (in `Layout::ALL` order). Commands and no
/// layout is the device's side.
pub fn omnitiles_framing(selector: u8) -> OmniTilesFraming {
    let layouts: Layouts = Layout::ALL
        .into_iter()
        .enumerate()
        .filter(|(i, _)| selector >> (i + 1) & 1 == 1)
        .map(|(_, l)| l)
        .collect();
    match (selector & 1 == 1, layouts.is_empty()) {
        (true, true) => OmniTilesFraming::Device(Framing::new()),
        (true, false) => OmniTilesFraming::Both(Framing::new().with_layouts(layouts)),
        (false, _) => OmniTilesFraming::Host(Framing::new().with_layouts(layouts)),
    }
}

/// `$body` with `$f` bound to the framing of whichever side
/// `$framing` ([`OmniTilesFraming`]) holds.
#[macro_export]
macro_rules! with_omnitiles_framing {
    ($framing:expr, |$f:ident| $body:expr) => {
        match $framing {
            $crate::OmniTilesFraming::Host($f) => $body,
            $crate::OmniTilesFraming::Device($f) => $body,
            $crate::OmniTilesFraming::Both($f) => $body,
        }
    };
}

/// Split a fuzz input into a selector byte, chunk sizes and the stream: byte 0
/// is the selector, byte 1 (mod 8) counts the chunk-size bytes that follow.
pub fn split_input(data: &[u8]) -> Option<(u8, &[u8], &[u8])> {
    let (&selector, rest) = data.split_first()?;
    let (&count, rest) = rest.split_first()?;
    let count = usize::from(count % 8).min(rest.len());
    let (sizes, stream) = rest.split_at(count);
    Some((selector, sizes, stream))
}

/// What one way of feeding the input produced.
#[derive(Debug, PartialEq)]
pub struct Run<O, E> {
    /// The owned events, in order.
    pub events: Vec<Result<robowire::OwnedFrame<O>, robowire::Rejected<E>>>,
    /// The counters after the final `finish`.
    pub stats: robowire::Stats,
}

/// Decode `input` with `decode()` in chunks of the given sizes (cycled; a
/// size of 0 feeds an empty chunk; all zero means one byte at a time), then
/// `finish()`, checking consumption, frame bytes and counters on every call.
pub fn decode_chunked<F, const N: usize>(
    mut decoder: StreamDecoder<F, N>,
    input: &[u8],
    sizes: &[usize],
) -> Run<F::Owned, F::Error>
where
    F: FrameRules,
    F::Owned: Debug,
{
    let all_zero = sizes.iter().all(|&s| s == 0);
    let mut events = Vec::new();
    let mut pos = 0;
    let mut round = 0;
    while pos < input.len() {
        let size = if all_zero {
            1
        } else {
            sizes[round % sizes.len()]
        };
        round += 1;
        let end = (pos + size).min(input.len());
        let chunk = &input[pos..end];
        let mut rest = chunk;
        loop {
            let before = rest.len();
            let event = decoder.decode(&mut rest).map(owned_event::<F>);
            assert!(rest.len() <= before, "consumed more than the input");
            let taken = chunk.len() - rest.len();
            if !rest.is_empty() {
                assert_eq!(
                    rest.as_ptr(),
                    chunk[taken..].as_ptr(),
                    "rest is a suffix of the chunk"
                );
            }
            check_counters(&decoder, (pos + taken) as u64);
            match event {
                Some(event) => {
                    check_event(&event, input);
                    events.push(event);
                }
                None => {
                    assert!(rest.is_empty(), "None only once the chunk is used up");
                    break;
                }
            }
        }
        pos = end;
    }
    finish(&mut decoder, input, &mut events);
    let stats = decoder.stats();
    check_order(&events);
    Run { events, stats }
}

/// Decode `input` one byte at a time through `push`, draining `poll` after
/// each byte, then `finish()`.
pub fn decode_pushed<F, const N: usize>(
    mut decoder: StreamDecoder<F, N>,
    input: &[u8],
) -> Run<F::Owned, F::Error>
where
    F: FrameRules,
    F::Owned: Debug,
{
    let mut events = Vec::new();
    for (i, &byte) in input.iter().enumerate() {
        if let Some(event) = decoder.push(byte).map(owned_event::<F>) {
            check_event(&event, input);
            events.push(event);
        }
        while let Some(event) = decoder.poll().map(owned_event::<F>) {
            check_event(&event, input);
            events.push(event);
        }
        check_counters(&decoder, i as u64 + 1);
    }
    finish(&mut decoder, input, &mut events);
    let stats = decoder.stats();
    check_order(&events);
    Run { events, stats }
}

/// Decode `input` through the owned-event iterators `feed` and `flush`.
pub fn decode_fed<F, const N: usize>(
    mut decoder: StreamDecoder<F, N>,
    input: &[u8],
) -> Run<F::Owned, F::Error>
where
    F: FrameRules,
{
    let mut events: Vec<_> = decoder.feed(input).collect();
    events.extend(decoder.flush());
    Run {
        events,
        stats: decoder.stats(),
    }
}

fn finish<F, const N: usize>(
    decoder: &mut StreamDecoder<F, N>,
    input: &[u8],
    events: &mut Vec<OwnedEvent<F>>,
) where
    F: FrameRules,
    F::Owned: Debug,
{
    let mut rounds = 0;
    while let Some(event) = decoder.finish().map(owned_event::<F>) {
        check_event(&event, input);
        events.push(event);
        rounds += 1;
        assert!(rounds <= N + 1, "finish terminates");
    }
    assert_eq!(decoder.buffered(), 0, "finish empties the decoder");
    check_counters(decoder, input.len() as u64);
}

fn check_counters<F: FrameRules, const N: usize>(decoder: &StreamDecoder<F, N>, taken: u64) {
    let s = decoder.stats();
    assert_eq!(s.bytes, taken, "bytes counts what was taken");
    assert_eq!(decoder.position(), taken);
    assert_eq!(
        s.bytes,
        s.frame_bytes + s.skipped + decoder.buffered() as u64,
        "counters add up: {s:?}, buffered {}",
        decoder.buffered()
    );
    assert!(
        decoder.buffered() < N.max(1),
        "buffer never full between calls"
    );
    assert!(s.malformed <= s.frames);
}

fn check_event<O: Debug, E: Debug>(
    event: &Result<robowire::OwnedFrame<O>, robowire::Rejected<E>>,
    input: &[u8],
) {
    match event {
        Ok(frame) => {
            assert!(frame.len > 0, "frames are not empty");
            assert!(
                frame.offset as usize + frame.len <= input.len(),
                "frame inside the input: {frame:?}"
            );
        }
        Err(rejected) => assert!((rejected.offset as usize) < input.len()),
    }
}

/// Events move forward: after a frame the next event starts past it, after a
/// rejection past its first byte.
fn check_order<O: Debug, E: Debug>(
    events: &[Result<robowire::OwnedFrame<O>, robowire::Rejected<E>>],
) {
    let mut next = 0u64;
    for event in events {
        let (offset, len) = match event {
            Ok(f) => (f.offset, f.len as u64),
            Err(r) => (r.offset, 1),
        };
        assert!(offset >= next, "events out of order: {events:?}");
        next = offset + len;
    }
}

/// Every oracle of the engine for one input: whole-buffer `decode`, the
/// chunk sizes taken from the fuzz input, byte-at-a-time `push`/`poll` and the
/// `feed`/`flush` iterators all give the same events and counters. Returns the
/// whole-buffer run.
pub fn check_stream<F, const N: usize>(
    new: impl Fn() -> StreamDecoder<F, N>,
    input: &[u8],
    sizes: &[u8],
) -> Run<F::Owned, F::Error>
where
    F: FrameRules + Clone,
    F::Owned: Debug + PartialEq,
{
    let whole = decode_chunked(new(), input, &[input.len().max(1)]);
    let sizes: Vec<usize> = sizes.iter().map(|&s| usize::from(s)).collect();
    if !sizes.is_empty() {
        let chunked = decode_chunked(new(), input, &sizes);
        assert_eq!(whole, chunked, "chunked in {sizes:?}");
    }
    let pushed = decode_pushed(new(), input);
    assert_eq!(whole, pushed, "byte at a time through push");
    let fed = decode_fed(new(), input);
    assert_eq!(whole, fed, "feed/flush iterators");
    check_settle(new(), input, &sizes);
    whole
}

/// `settle` after every chunk: it rejects nothing, keeps the counters
/// adding up, and gives exactly the frame `finish` would give at that point
/// (or nothing where `finish` would reject).
pub fn check_settle<F, const N: usize>(mut decoder: StreamDecoder<F, N>, input: &[u8], sizes: &[usize])
where
    F: FrameRules + Clone,
    F::Owned: Debug + PartialEq,
{
    let sizes: &[usize] = if sizes.iter().all(|&s| s == 0) { &[1] } else { sizes };
    let mut pos = 0;
    for &size in sizes.iter().cycle() {
        if pos >= input.len() {
            break;
        }
        let end = (pos + size.max(1)).min(input.len());
        for event in decoder.feed(&input[pos..end]) {
            check_event(&event, input);
        }
        pos = end;
        loop {
            let mut probe = decoder.clone();
            let expected = probe.finish().map(owned_event::<F>).and_then(Result::ok);
            let failures = decoder.stats().checksum_failures + decoder.stats().other_rejections;
            let settled = decoder.settle().map(owned_event::<F>);
            check_counters(&decoder, pos as u64);
            assert_eq!(
                failures,
                decoder.stats().checksum_failures + decoder.stats().other_rejections,
                "settle rejected something"
            );
            let Some(event) = settled else { break };
            check_event(&event, input);
            match event {
                Ok(frame) => assert_eq!(Some(frame), expected, "settle and finish differ"),
                Err(rejected) => panic!("settle gave a rejection: {rejected:?}"),
            }
        }
    }
}
