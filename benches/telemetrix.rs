//! Telemetrix4RpiPico decoding throughput: a realistic ~1 MiB mix of digital,
//! analog, sonar and encoder reports, against the ceiling of summing every
//! byte of the same buffer.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use robowire::telemetrix::{Framing, Host, HostDecoder, Report, Sonar};
use robowire::Encode;

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

/// About 1 MiB of mirte 1.3 reports: 40 % digital, 30 % analog, 15 % sonar,
/// 15 % encoder.
fn reports() -> Vec<u8> {
    let mut rng = Rng(0x5eed_7e1e_3e7a_0001);
    let mut out = Vec::with_capacity(1 << 20);
    let mut frame = [0u8; 16];
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
    }
    out
}

fn decode_all(input: &[u8], chunk: usize) -> u64 {
    let mut decoder = HostDecoder::new(Framing::<Host>::new());
    let mut frames = 0u64;
    for piece in input.chunks(chunk) {
        let mut rest = piece;
        while let Some(event) = decoder.decode(&mut rest) {
            if let Ok(frame) = event {
                frames += u64::from(frame.message.id());
            }
        }
    }
    while decoder.finish().is_some() {}
    frames
}

fn bench(c: &mut Criterion) {
    let input = reports();
    let mut group = c.benchmark_group("telemetrix");
    group.throughput(Throughput::Bytes(input.len() as u64));
    group.bench_function("ceiling/sum_bytes", |b| {
        b.iter(|| {
            black_box(&input)
                .iter()
                .fold(0u64, |sum, &byte| sum.wrapping_add(u64::from(byte)))
        })
    });
    group.bench_function("decode/reports", |b| {
        b.iter(|| decode_all(black_box(&input), input.len()))
    });
    group.bench_function("decode/reports_chunk64", |b| {
        b.iter(|| decode_all(black_box(&input), 64))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
