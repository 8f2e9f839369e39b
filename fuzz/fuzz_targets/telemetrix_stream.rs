//! Telemetrix stream oracle: arbitrary bytes, fed in chunk sizes taken from
//! the input, give the same events as the whole buffer at once; no entry point
//! takes more than it was given; the counters add up.
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::telemetrix::{
    Device, DeviceDecoder, Dialect, Framing, Host, HostDecoder, LenientHostDecoder,
};
use robowire::{FrameRules, OwnedEvent, StreamDecoder};

const DIALECTS: [Dialect; 3] = [Dialect::Mirte13, Dialect::Mirte12, Dialect::Upstream11];

/// Decode `input` in chunks of the given sizes (cycled), checking consumption
/// and counters; returns every event.
fn run<F, const N: usize>(
    mut decoder: StreamDecoder<F, N>,
    input: &[u8],
    sizes: &[u8],
) -> Vec<OwnedEvent<F>>
where
    F: FrameRules,
{
    let mut events = Vec::new();
    let mut pos = 0;
    let mut i = 0;
    while pos < input.len() {
        let size = sizes
            .get(i % sizes.len().max(1))
            .map_or(input.len(), |&s| usize::from(s) + 1);
        i += 1;
        let chunk = &input[pos..(pos + size).min(input.len())];
        let mut rest = chunk;
        while let Some(event) = decoder.decode(&mut rest) {
            events.push(event.map(|f| robowire::OwnedFrame {
                offset: f.offset,
                len: f.raw.len(),
                message: F::to_owned(f.message),
            }));
        }
        assert!(rest.is_empty(), "decode left input untaken");
        pos += chunk.len();
        let s = decoder.stats();
        assert!(s.bytes <= input.len() as u64);
        assert_eq!(s.bytes, pos as u64);
        assert_eq!(
            s.bytes,
            s.frame_bytes + s.skipped + decoder.buffered() as u64
        );
    }
    events.extend(decoder.flush());
    let s = decoder.stats();
    assert_eq!(decoder.buffered(), 0);
    assert_eq!(s.bytes, input.len() as u64);
    assert_eq!(s.bytes, s.frame_bytes + s.skipped);
    events
}

/// Where each event was and what it was. Two frames at the same offset with
/// the same length have the same bytes, so the same message (comparing the
/// messages themselves would trip over NaN floats in sensor reports).
fn shape<F: FrameRules>(events: &[OwnedEvent<F>]) -> Vec<Result<(u64, usize), (u64, F::Error)>> {
    events
        .iter()
        .map(|e| match e {
            Ok(f) => Ok((f.offset, f.len)),
            Err(r) => Err((r.offset, r.error)),
        })
        .collect()
}

fn check<F, const N: usize>(make: impl Fn() -> StreamDecoder<F, N>, input: &[u8], sizes: &[u8])
where
    F: FrameRules,
{
    let whole = run(make(), input, &[]);
    let chunked = run(make(), input, sizes);
    assert_eq!(shape::<F>(&whole), shape::<F>(&chunked));
}

fuzz_target!(|data: &[u8]| {
    // First byte: dialect; next up to 8 bytes: chunk sizes; the rest: input.
    let Some((&select, rest)) = data.split_first() else {
        return;
    };
    let dialect = DIALECTS[usize::from(select) % 3];
    let (sizes, input) = rest.split_at(rest.len().min(8));
    let reports = Framing::<Host>::new().with_dialect(dialect);
    check(|| HostDecoder::new(reports), input, sizes);
    check(|| LenientHostDecoder::new(reports.lenient()), input, sizes);
    let commands = Framing::<Device>::new().with_dialect(dialect);
    check(|| DeviceDecoder::new(commands), input, sizes);
});
