//! Pixy2 decoding throughput. Needs `harness = false` in Cargo.toml:
//!
//! ```toml
//! [[bench]]
//! name = "pixy2"
//! harness = false
//! ```
//!
//! One group, `pixy2`, in bytes per second over the same seeded buffer (about
//! 1 MiB of blocks responses with 18 blocks each, 258 bytes per frame):
//!
//! * `ceiling/sum_bytes`: add up every byte (wrapping u16, the checksum's own
//!   arithmetic, which vectorises best), the floor no validating parser can
//!   beat;
//! * `decode/blocks`: stream-decode the whole buffer in one call and iterate
//!   every block;
//! * `decode/blocks_chunk64`: the same, fed in 64-byte chunks, so most frames
//!   straddle a chunk boundary and go through the internal buffer.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use robowire::pixy2::{self, Block, BlocksBuf, Response};
use robowire::Encode;

/// A tiny xorshift so the data is the same on every run without a rand crate.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

/// About 1 MiB of checksummed blocks responses, 18 random blocks each.
fn blocks_stream() -> Vec<u8> {
    let mut rng = XorShift(0x05ee_d0fb_10c5);
    let mut out = Vec::with_capacity(1 << 20);
    let mut frame = [0u8; 261];
    while out.len() < (1 << 20) {
        let mut blocks = BlocksBuf::new();
        for _ in 0..pixy2::MAX_BLOCKS {
            let a = rng.next().to_le_bytes();
            let b = rng.next().to_le_bytes();
            let mut w = [0u8; Block::SIZE];
            w[..8].copy_from_slice(&a);
            w[8..].copy_from_slice(&b[..6]);
            blocks.push(Block::from_bytes(&w)).unwrap();
        }
        let n = Response::Blocks(blocks.view()).encode(&mut frame).unwrap();
        out.extend_from_slice(&frame[..n]);
    }
    out
}

/// Decode `input` in chunks of `chunk` bytes; the sum of the blocks' x values
/// keeps the work observable.
fn decode(input: &[u8], chunk: usize) -> u64 {
    let mut decoder = pixy2::host_decoder();
    let mut acc = 0u64;
    for piece in input.chunks(chunk) {
        let mut rest = piece;
        while let Some(event) = decoder.decode(&mut rest) {
            if let Ok(frame) = event {
                if let Response::Blocks(blocks) = frame.message.body {
                    acc += blocks.iter().map(|b| u64::from(b.x)).sum::<u64>();
                }
            }
        }
    }
    acc
}

fn bench(c: &mut Criterion) {
    let input = blocks_stream();
    let mut group = c.benchmark_group("pixy2");
    group.throughput(Throughput::Bytes(input.len() as u64));
    group.bench_function("ceiling/sum_bytes", |b| {
        b.iter(|| {
            black_box(&input)
                .iter()
                .fold(0u16, |s, &x| s.wrapping_add(u16::from(x)))
        })
    });
    group.bench_function("decode/blocks", |b| {
        b.iter(|| decode(black_box(&input), input.len()))
    });
    group.bench_function("decode/blocks_chunk64", |b| {
        b.iter(|| decode(black_box(&input), 64))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
