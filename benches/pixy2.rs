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
//!   straddle a chunk boundary and go through the internal buffer;
//! * `decode/blocks_each`: `decode/blocks` through `decode_each` (each event
//!   handed to a closure) instead of a `decode` loop;
//! * `baseline/naive_blocks`: the parser users write by hand for Pixy2 serial
//!   (a byte-at-a-time state machine: wait for the 16-bit sync, read type and
//!   length, take the payload blindly, check the sum, no rescan after a bad
//!   frame), fed the same buffer in the same chunking as `decode/blocks`, and
//!   summing the same block field.
//!
//! Before the timing loops, every decoder is checked once to find exactly the
//! generated frames (and the naive one the same frames as robowire's).

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

/// What a decoder found: frames, and the sum of every block's x (the work
/// that keeps decoding observable).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Found {
    frames: usize,
    x_sum: u64,
}

/// About 1 MiB of checksummed blocks responses, 18 random blocks each, and
/// what was generated.
fn blocks_stream() -> (Vec<u8>, Found) {
    let mut rng = XorShift(0x05ee_d0fb_10c5);
    let mut out = Vec::with_capacity(1 << 20);
    let mut frame = [0u8; 261];
    let mut generated = Found {
        frames: 0,
        x_sum: 0,
    };
    while out.len() < (1 << 20) {
        let mut blocks = BlocksBuf::new();
        for _ in 0..pixy2::MAX_BLOCKS {
            let a = rng.next().to_le_bytes();
            let b = rng.next().to_le_bytes();
            let mut w = [0u8; Block::SIZE];
            w[..8].copy_from_slice(&a);
            w[8..].copy_from_slice(&b[..6]);
            let block = Block::from_bytes(&w);
            generated.x_sum += u64::from(block.x);
            blocks.push(block).unwrap();
        }
        let n = Response::Blocks(blocks.view()).encode(&mut frame).unwrap();
        out.extend_from_slice(&frame[..n]);
        generated.frames += 1;
    }
    (out, generated)
}

/// Count one decoder event and sum its blocks' x values.
fn take(
    found: &mut Found,
    on_frame: &mut impl FnMut(u64),
    event: robowire::Event<'_, pixy2::Envelope<Response<'_>>, pixy2::Error>,
) {
    if let Ok(frame) = event {
        on_frame(frame.offset);
        found.frames += 1;
        if let Response::Blocks(blocks) = frame.message.body {
            found.x_sum += blocks.iter().map(|b| u64::from(b.x)).sum::<u64>();
        }
        black_box(&frame.message);
    }
}

/// Decode `input` in chunks of `chunk` bytes; call `on_frame` with each
/// frame's offset. The blocks' x values are summed.
fn decode_with(input: &[u8], chunk: usize, mut on_frame: impl FnMut(u64)) -> Found {
    let mut decoder = pixy2::host_decoder();
    let mut found = Found {
        frames: 0,
        x_sum: 0,
    };
    for piece in input.chunks(chunk) {
        let mut rest = piece;
        while let Some(event) = decoder.decode(&mut rest) {
            take(&mut found, &mut on_frame, event);
        }
    }
    while let Some(event) = decoder.finish() {
        take(&mut found, &mut on_frame, event);
    }
    found
}

fn decode(input: &[u8], chunk: usize) -> Found {
    decode_with(input, chunk, |_| {})
}

/// `decode` through `decode_each`.
fn decode_each(input: &[u8], chunk: usize) -> Found {
    let mut decoder = pixy2::host_decoder();
    let mut found = Found {
        frames: 0,
        x_sum: 0,
    };
    let mut on_frame = |_| {};
    for piece in input.chunks(chunk) {
        decoder.decode_each(piece, |event| take(&mut found, &mut on_frame, event));
    }
    while let Some(event) = decoder.finish() {
        take(&mut found, &mut on_frame, event);
    }
    found
}

/// The hand-written Pixy2 serial parser: one state per header byte, the
/// payload copied blindly into a buffer and summed as it arrives, the frame
/// dropped on a bad sum and the search restarted after it (no rescan of its
/// bytes).
struct Naive {
    state: State,
    /// The last byte, for the 16-bit sync word.
    prev: u8,
    checksummed: bool,
    packet_type: u8,
    len: usize,
    expected: u16,
    sum: u16,
    at: usize,
    payload: [u8; 255],
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    Sync,
    Type,
    Len,
    ChecksumLo,
    ChecksumHi,
    Payload,
}

impl Naive {
    fn new() -> Self {
        Self {
            state: State::Sync,
            prev: 0,
            checksummed: false,
            packet_type: 0,
            len: 0,
            expected: 0,
            sum: 0,
            at: 0,
            payload: [0; 255],
        }
    }

    /// Take one byte; a complete frame whose sum checks out is returned as
    /// its type and payload.
    #[inline]
    fn push(&mut self, byte: u8) -> Option<(u8, &[u8])> {
        match self.state {
            State::Sync => {
                let word = u16::from_le_bytes([self.prev, byte]);
                self.prev = byte;
                if word == pixy2::SYNC_CHECKSUM || word == pixy2::SYNC_NO_CHECKSUM {
                    self.checksummed = word == pixy2::SYNC_CHECKSUM;
                    self.state = State::Type;
                }
            }
            State::Type => {
                self.packet_type = byte;
                self.state = State::Len;
            }
            State::Len => {
                self.len = usize::from(byte);
                self.at = 0;
                self.sum = 0;
                self.state = if self.checksummed {
                    State::ChecksumLo
                } else {
                    State::Payload
                };
            }
            State::ChecksumLo => {
                self.expected = u16::from(byte);
                self.state = State::ChecksumHi;
            }
            State::ChecksumHi => {
                self.expected |= u16::from(byte) << 8;
                self.state = State::Payload;
            }
            State::Payload => {
                self.payload[self.at] = byte;
                self.sum = self.sum.wrapping_add(u16::from(byte));
                self.at += 1;
            }
        }
        if self.state == State::Payload && self.at == self.len {
            self.state = State::Sync;
            self.prev = 0;
            if !self.checksummed || self.sum == self.expected {
                return Some((self.packet_type, &self.payload[..self.len]));
            }
        }
        None
    }
}

/// The naive parser over `input` in chunks of `chunk` bytes, summing the
/// same block field as [`decode`].
fn naive_with(input: &[u8], chunk: usize, mut on_frame: impl FnMut(u64)) -> Found {
    let mut parser = Naive::new();
    let mut found = Found {
        frames: 0,
        x_sum: 0,
    };
    let mut offset = 0u64;
    for piece in input.chunks(chunk) {
        for &byte in piece {
            offset += 1;
            let checksummed = parser.checksummed;
            if let Some((packet_type, payload)) = parser.push(byte) {
                let header = if checksummed { 6 } else { 4 };
                on_frame(offset - (header + payload.len()) as u64);
                found.frames += 1;
                if packet_type == pixy2::packet_type::BLOCKS {
                    found.x_sum += black_box(payload)
                        .chunks_exact(Block::SIZE)
                        .map(|b| u64::from(u16::from_le_bytes([b[2], b[3]])))
                        .sum::<u64>();
                }
            }
        }
    }
    found
}

fn naive(input: &[u8], chunk: usize) -> Found {
    naive_with(input, chunk, |_| {})
}

fn bench(c: &mut Criterion) {
    let (input, generated) = blocks_stream();
    let whole = input.len();

    // Each decoder finds exactly what was generated (checked once, outside
    // the timing loops), and the naive parser the same frames as robowire.
    assert_eq!(decode(&input, whole), generated, "decode/blocks");
    assert_eq!(decode(&input, 64), generated, "decode/blocks_chunk64");
    assert_eq!(decode_each(&input, whole), generated, "decode/blocks_each");
    assert_eq!(naive(&input, whole), generated, "baseline/naive_blocks");
    let (mut ours, mut theirs) = (Vec::new(), Vec::new());
    decode_with(&input, whole, |offset| ours.push(offset));
    naive_with(&input, whole, |offset| theirs.push(offset));
    assert_eq!(ours, theirs, "the same frames at the same offsets");

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
        b.iter(|| decode(black_box(&input), whole))
    });
    group.bench_function("decode/blocks_chunk64", |b| {
        b.iter(|| decode(black_box(&input), 64))
    });
    group.bench_function("decode/blocks_each", |b| {
        b.iter(|| decode_each(black_box(&input), whole))
    });
    group.bench_function("baseline/naive_blocks", |b| {
        b.iter(|| naive(black_box(&input), whole))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
