//! Telemetrix4RpiPico decoding throughput. One group, `telemetrix`, in bytes
//! per second over the same seeded buffer (about 1 MiB of mirte 1.3 reports:
//! digital, analog, sonar and encoder, 4.6 bytes a frame on average):
//!
//! * `ceiling/sum_bytes`: add up every byte, the floor no parser can beat;
//! * `decode/reports`: stream-decode the whole buffer in one call, typed
//!   (`decode_each`), every message through `black_box`, summing the report
//!   ids;
//! * `decode/reports_chunk64`: the same, fed in 64-byte chunks;
//! * `decode/reports_loop`: the same as a `while let Some(event) =
//!   decoder.decode(&mut input)` loop;
//! * `decode/reports_owned`: the owned path of a host that keeps its
//!   frames: `feed` yields each report as a [`ReportBuf`] (its bytes
//!   copied), kept in a `Vec` reused across iterations;
//! * `decode/messages_owned`: the same through a [`BothDecoder`] (either
//!   direction), each frame a [`MessageBuf`];
//! * `baseline/naive_reports`: the reader a user writes by hand (the mirte
//!   client's): take the length byte, take that many bytes blindly, dispatch
//!   on the report id, with no validation and no resync.
//!
//! Every input is generated from a fixed seed; each benchmark checks once,
//! outside the timing loop, that it finds exactly the generated frames.
//!
//! `ROBOWIRE_BENCH_MIN=200 cargo bench --bench telemetrix` prints the
//! fastest of 200 runs of each row instead of criterion's estimates, with
//! the ratios issue 19 asks for: on the shared 2-core machine criterion's
//! ratios of one tree moved by ±15 % from run to run, the fastest runs by
//! about 1 %, so two trees are compared this way (interleaved, same session).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use robowire::telemetrix::{
    both_decoder, BothDecoder, Error, Framing, Host, HostDecoder, MessageBuf, Report, ReportBuf,
    Sonar,
};
use robowire::Encode;
use robowire::Event;

/// Tiny xorshift generator: seeded, reproducible, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// What a decode found: frames, and the sum of their report ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Found {
    frames: u64,
    ids: u64,
}

impl Found {
    fn add(&mut self, id: u8) {
        self.frames += 1;
        self.ids += u64::from(id);
    }
}

/// About 1 MiB of mirte 1.3 reports: 40 % digital, 30 % analog, 15 % sonar,
/// 15 % encoder. Returns the bytes and what a decoder must find in them.
fn reports() -> (Vec<u8>, Found) {
    let mut rng = Rng(0x5eed_7e1e_3e7a_0001);
    let mut out = Vec::with_capacity(1 << 20);
    let mut frame = [0u8; 16];
    let mut found = Found::default();
    while out.len() < 1 << 20 {
        let report: Report<'_> = match rng.below(20) {
            0..=7 => Report::Digital {
                pin: rng.below(30) as u8,
                value: rng.below(2) == 1,
            },
            8..=13 => Report::Analog {
                pin: 26 + rng.below(5) as u8,
                value: rng.below(4096) as u16,
            },
            14..=16 => Report::Sonar(Sonar::WithEcho {
                trig: rng.below(30) as u8,
                echo: rng.below(30) as u8,
                cm: rng.below(400) as u16,
            }),
            _ => Report::Encoder {
                pin: rng.below(30) as u8,
                steps: 1 + rng.below(100) as i8,
            },
        };
        let n = report.encode(&mut frame).expect("valid report");
        out.extend_from_slice(&frame[..n]);
        found.add(report.id());
    }
    (out, found)
}

/// Count one event's report.
#[inline(always)]
fn take(found: &mut Found, event: Event<'_, Report<'_>, Error>) {
    if let Ok(frame) = event {
        found.add(black_box(&frame.message).id());
    }
}

/// Decode `input` fed in `chunk`-byte pieces, typed, by `decode_each`.
fn decode_all(input: &[u8], chunk: usize) -> Found {
    let mut decoder = HostDecoder::new(Framing::<Host>::new());
    let mut found = Found::default();
    for piece in input.chunks(chunk) {
        decoder.decode_each(piece, |event| take(&mut found, event));
    }
    while let Some(event) = decoder.finish() {
        take(&mut found, event);
    }
    found
}

/// The same as a `decode` loop.
fn decode_loop(input: &[u8], chunk: usize) -> Found {
    let mut decoder = HostDecoder::new(Framing::<Host>::new());
    let mut found = Found::default();
    for piece in input.chunks(chunk) {
        let mut rest = piece;
        while let Some(event) = decoder.decode(&mut rest) {
            take(&mut found, event);
        }
    }
    while let Some(event) = decoder.finish() {
        take(&mut found, event);
    }
    found
}

/// Decode `input` in one `feed`, keeping every owned frame in `kept`
/// (cleared first); ids are read from the kept frames' bytes.
fn feed_all<B: Copy>(
    input: &[u8],
    kept: &mut Vec<B>,
    mut feed: impl FnMut(&[u8], &mut Vec<B>),
    frame: impl Fn(&B) -> &[u8],
) -> Found {
    kept.clear();
    feed(input, kept);
    let mut found = Found::default();
    for buf in kept.iter() {
        found.add(frame(black_box(buf))[1]);
    }
    found
}

/// `feed_all` through a host decoder: every report a [`ReportBuf`].
fn reports_owned(input: &[u8], kept: &mut Vec<ReportBuf>) -> Found {
    let mut decoder = HostDecoder::new(Framing::<Host>::new());
    feed_all(
        input,
        kept,
        |input, kept| {
            kept.extend(decoder.feed(input).flatten().map(|frame| frame.message));
            kept.extend(decoder.flush().flatten().map(|frame| frame.message));
        },
        ReportBuf::frame,
    )
}

/// `feed_all` through a decoder of both directions: every frame a
/// [`MessageBuf`].
fn messages_owned(input: &[u8], kept: &mut Vec<MessageBuf>) -> Found {
    let mut decoder: BothDecoder = both_decoder();
    feed_all(
        input,
        kept,
        |input, kept| {
            kept.extend(decoder.feed(input).flatten().map(|frame| frame.message));
            kept.extend(decoder.flush().flatten().map(|frame| frame.message));
        },
        MessageBuf::frame,
    )
}

/// The fields a hand-written reader pulls out of the reports it knows (read
/// through `black_box`).
#[allow(dead_code)]
#[derive(Debug, Clone, Copy)]
enum NaiveReport {
    Digital { pin: u8, value: u8 },
    Analog { pin: u8, value: u16 },
    Sonar { trig: u8, echo: u8, cm: u16 },
    Encoder { pin: u8, steps: i8 },
    Other { id: u8 },
}

impl NaiveReport {
    fn id(&self) -> u8 {
        match *self {
            NaiveReport::Digital { .. } => 2,
            NaiveReport::Analog { .. } => 3,
            NaiveReport::Sonar { .. } => 11,
            NaiveReport::Encoder { .. } => 14,
            NaiveReport::Other { id } => id,
        }
    }
}

/// The classic hand-written reader, byte at a time (what the mirte client's
/// reader thread does): a length byte, then that many bytes taken blindly,
/// then a dispatch on the report id. No validation, no resync: a lost or
/// extra byte desynchronises it for good.
struct NaiveReader {
    body: [u8; 256],
    need: usize,
    have: usize,
}

impl NaiveReader {
    fn new() -> Self {
        Self {
            body: [0; 256],
            need: 0,
            have: 0,
        }
    }

    fn push(&mut self, byte: u8) -> Option<NaiveReport> {
        if self.need == 0 {
            self.need = usize::from(byte);
            self.have = 0;
            return None;
        }
        self.body[self.have] = byte;
        self.have += 1;
        if self.have < self.need {
            return None;
        }
        self.need = 0;
        let b = &self.body;
        Some(match b[0] {
            2 => NaiveReport::Digital {
                pin: b[1],
                value: b[2],
            },
            3 => NaiveReport::Analog {
                pin: b[1],
                value: u16::from_be_bytes([b[2], b[3]]),
            },
            11 => NaiveReport::Sonar {
                trig: b[1],
                echo: b[2],
                cm: u16::from_be_bytes([b[3], b[4]]),
            },
            14 => NaiveReport::Encoder {
                pin: b[1],
                steps: b[2] as i8,
            },
            id => NaiveReport::Other { id },
        })
    }
}

/// The naive reader over `input` fed in `chunk`-byte pieces.
fn naive_all(input: &[u8], chunk: usize) -> Found {
    let mut reader = NaiveReader::new();
    let mut found = Found::default();
    for piece in input.chunks(chunk) {
        for &byte in piece {
            if let Some(report) = reader.push(byte) {
                found.add(black_box(&report).id());
            }
        }
    }
    found
}

fn sum_bytes(input: &[u8]) -> u64 {
    input
        .iter()
        .fold(0u64, |sum, &byte| sum.wrapping_add(u64::from(byte)))
}

/// One bench row: its name and its run.
type Row<'a> = (&'static str, Box<dyn FnMut() -> Found + 'a>);

/// The group's rows, in the order criterion runs them: each a name and a
/// run over the bench's input returning what it found (the ceiling's sum in
/// `frames`).
fn rows<'a>(
    input: &'a [u8],
    kept_reports: &'a mut Vec<ReportBuf>,
    kept_messages: &'a mut Vec<MessageBuf>,
) -> Vec<Row<'a>> {
    let whole = input.len();
    vec![
        (
            "ceiling/sum_bytes",
            Box::new(move || Found {
                frames: sum_bytes(black_box(input)),
                ids: 0,
            }),
        ),
        (
            "decode/reports",
            Box::new(move || decode_all(black_box(input), whole)),
        ),
        (
            "decode/reports_chunk64",
            Box::new(move || decode_all(black_box(input), 64)),
        ),
        (
            "decode/reports_loop",
            Box::new(move || decode_loop(black_box(input), whole)),
        ),
        (
            "decode/reports_owned",
            Box::new(move || reports_owned(black_box(input), kept_reports)),
        ),
        (
            "decode/messages_owned",
            Box::new(move || messages_owned(black_box(input), kept_messages)),
        ),
        (
            "baseline/naive_reports",
            Box::new(move || naive_all(black_box(input), whole)),
        ),
    ]
}

fn bench(c: &mut Criterion) {
    let (input, generated) = reports();
    let whole = input.len();

    // Each benchmark finds exactly what was generated (checked once).
    assert_eq!(decode_all(&input, whole), generated);
    assert_eq!(decode_all(&input, 64), generated);
    assert_eq!(decode_loop(&input, whole), generated);
    assert_eq!(naive_all(&input, whole), generated);
    let mut kept_reports = Vec::with_capacity(generated.frames as usize);
    let mut kept_messages = Vec::with_capacity(generated.frames as usize);
    assert_eq!(reports_owned(&input, &mut kept_reports), generated);
    assert_eq!(messages_owned(&input, &mut kept_messages), generated);

    if let Some(runs) = min_runs() {
        print_min(rows(&input, &mut kept_reports, &mut kept_messages), runs);
        return;
    }
    let mut group = c.benchmark_group("telemetrix");
    group.throughput(Throughput::Bytes(input.len() as u64));
    for (name, mut run) in rows(&input, &mut kept_reports, &mut kept_messages) {
        group.bench_function(name, |b| b.iter(&mut run));
    }
    group.finish();
}

/// `ROBOWIRE_BENCH_MIN=<runs>`: instead of criterion's estimates, the
/// fastest of `runs` runs of each row (in five interleaved rounds), and the
/// issue 19 ratios. On a shared machine the fastest run is the one least
/// disturbed, so two trees compared this way, one after the other, differ
/// by their code far more than by the machine's load.
fn min_runs() -> Option<u32> {
    std::env::var("ROBOWIRE_BENCH_MIN").ok()?.parse().ok()
}

fn print_min(mut rows: Vec<Row<'_>>, runs: u32) {
    let mut best = vec![f64::MAX; rows.len()];
    for _ in 0..5 {
        for ((_, run), best) in rows.iter_mut().zip(&mut best) {
            for _ in 0..runs.div_ceil(5) {
                let start = std::time::Instant::now();
                black_box(run());
                *best = best.min(start.elapsed().as_secs_f64() * 1e9);
            }
        }
    }
    let ns = |name: &str| {
        rows.iter()
            .position(|(n, _)| *n == name)
            .map_or(f64::NAN, |i| best[i])
    };
    for ((name, _), t) in rows.iter().zip(&best) {
        println!("telemetrix/{name:28} {t:>14.0} ns (fastest of {runs})");
    }
    let reports = ns("decode/reports");
    println!(
        "decode/reports: {:.3} of the ceiling, {:.2}x naive; reports_chunk64 {:.3} of reports",
        ns("ceiling/sum_bytes") / reports,
        ns("baseline/naive_reports") / reports,
        reports / ns("decode/reports_chunk64"),
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
