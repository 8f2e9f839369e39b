//! OmniTiles decoder and encoder throughput, with the ceiling in the same group.
//!
//! `cargo bench --bench omnitiles`. Every input is generated from a fixed seed;
//! each benchmark checks once, outside the timing loop, that it finds exactly
//! the frames that were generated.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use robowire::omnitiles::{
    Both, Command, Device, Framing, Host, HostViewDecoder, Imu, Layout, Layouts, Motor, Side,
    Telemetry, TelemetryViews, BOTH_BUFFER, NO_READING,
};
use robowire::Encode;
use robowire::{Event, StreamDecoder};

const MIB: usize = 1 << 20;

/// A tiny xorshift generator: reproducible data without a dependency.
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
    fn u16(&mut self) -> u16 {
        self.next() as u16
    }
    fn byte(&mut self) -> u8 {
        self.next() as u8
    }
    fn reading(&mut self) -> Option<u16> {
        Some(self.u16()).filter(|&v| v != NO_READING)
    }
}

fn telemetry(rng: &mut Rng, layout: Layout) -> Telemetry {
    let mut t = Telemetry::empty(layout);
    t.m1_pos = rng.reading();
    t.m2_pos = rng.reading();
    if layout.has_uwb() {
        t.uwb = Some([rng.reading(), rng.reading(), rng.reading(), rng.reading()]);
    }
    if layout.has_tof() {
        t.tof = Some(rng.reading());
    }
    if layout.has_imu_and_adcs() {
        let mut imu = [0f32; 6];
        for v in &mut imu {
            *v = (rng.below(40_000) as f32 - 20_000.0) * 1e-3;
        }
        t.imu = Some(Imu::from_array(imu));
        t.m1_adcs = Some([(); 4].map(|_| rng.u16() % 4096));
        t.m2_adcs = Some([(); 2].map(|_| rng.u16() % 4096));
    }
    t
}

fn command(rng: &mut Rng) -> Command {
    let motor = if rng.below(2) == 0 {
        Motor::M1
    } else {
        Motor::M2
    };
    match rng.below(7) {
        0 => Command::Ping,
        1 => Command::Extend {
            motor,
            speed: rng.byte(),
        },
        2 => Command::Retract {
            motor,
            speed: rng.byte(),
        },
        3 => Command::Brake { motor },
        4 => Command::SetPosition {
            motor,
            position: rng.byte(),
        },
        5 => Command::BaseVelocity {
            vx: rng.byte() as i8,
            vy: rng.byte() as i8,
            omega: rng.byte() as i8,
        },
        _ => Command::BaseBrake,
    }
}

/// Messages and their encoding, up to `limit` bytes.
fn encode_until<M: Encode>(limit: usize, mut next: impl FnMut() -> M) -> (Vec<M>, Vec<u8>) {
    let (mut messages, mut bytes) = (Vec::new(), Vec::with_capacity(limit));
    let mut out = [0u8; 64];
    loop {
        let message = next();
        let n = message.encode(&mut out).unwrap();
        if bytes.len() + n > limit {
            return (messages, bytes);
        }
        bytes.extend_from_slice(&out[..n]);
        messages.push(message);
    }
}

/// 1 MiB of 53-byte telemetry frames.
fn ble53() -> (Vec<Telemetry>, Vec<u8>) {
    let mut rng = Rng(0x0B1E_5353);
    encode_until(MIB, || telemetry(&mut rng, Layout::Ble53))
}

/// 1 MiB of the four documented layouts, mixed.
fn mixed() -> (Vec<Telemetry>, Vec<u8>) {
    let mut rng = Rng(0x00A1_1707);
    let kinds = [Layout::Pos7, Layout::Uwb15, Layout::UwbTof17, Layout::Ble53];
    encode_until(MIB, || {
        let layout = kinds[rng.below(4) as usize];
        telemetry(&mut rng, layout)
    })
}

/// 1 MiB of mixed commands.
fn commands() -> (Vec<Command>, Vec<u8>) {
    let mut rng = Rng(0xC0_3A4D);
    encode_until(MIB, || command(&mut rng))
}

/// About 1 MiB of 53-byte telemetry: before 5 % of the frames a garbage run
/// (1–64 random bytes), and one bit flipped in 1 % of the frames. Returns the
/// bytes and the number of frames left intact.
fn noisy() -> (Vec<u8>, usize) {
    let mut rng = Rng(0x0005_F11B);
    let mut bytes = Vec::with_capacity(MIB + MIB / 16);
    let mut out = [0u8; 53];
    let mut intact = 0;
    while bytes.len() < MIB {
        if rng.below(100) < 5 {
            for _ in 0..1 + rng.below(64) {
                bytes.push(rng.byte());
            }
        }
        telemetry(&mut rng, Layout::Ble53).encode(&mut out).unwrap();
        if rng.below(100) < 1 {
            out[rng.below(53) as usize] ^= 1 << rng.below(8);
        } else {
            intact += 1;
        }
        bytes.extend_from_slice(&out);
    }
    (bytes, intact)
}

/// Count one event's frame, its message through `black_box`.
#[inline(always)]
fn take<M>(frames: &mut usize, event: Event<'_, M, robowire::omnitiles::Error>) {
    if let Ok(frame) = event {
        black_box(&frame.message);
        *frames += 1;
    }
}

/// Decode `input` fed in `chunk`-byte pieces; count the frames.
fn decode<S: Side>(framing: Framing<S>, input: &[u8], chunk: usize) -> usize {
    let mut decoder = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
    let mut frames = 0;
    for mut piece in input.chunks(chunk) {
        while let Some(event) = decoder.decode(&mut piece) {
            take(&mut frames, event);
        }
    }
    while let Some(event) = decoder.finish() {
        take(&mut frames, event);
    }
    frames
}

/// `decode` through `decode_each` (each event handed to a closure).
fn decode_each<S: Side>(framing: Framing<S>, input: &[u8], chunk: usize) -> usize {
    let mut decoder = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
    let mut frames = 0;
    for piece in input.chunks(chunk) {
        decoder.decode_each(piece, |event| take(&mut frames, event));
    }
    while let Some(event) = decoder.finish() {
        take(&mut frames, event);
    }
    frames
}

/// The same with telemetry read in place: each frame's view, and the three
/// readings a position loop reads from it (both positions and the ToF range),
/// go through `black_box`.
fn decode_views(framing: TelemetryViews, input: &[u8], chunk: usize) -> usize {
    let mut decoder = HostViewDecoder::new(framing);
    let mut frames = 0;
    let mut consume = |view: &robowire::omnitiles::TelemetryView<'_>| {
        black_box(view);
        black_box((view.m1_pos(), view.m2_pos(), view.tof()));
        frames += 1;
    };
    for mut piece in input.chunks(chunk) {
        while let Some(event) = decoder.decode(&mut piece) {
            if let Ok(frame) = event {
                consume(&frame.message);
            }
        }
    }
    while let Some(event) = decoder.finish() {
        if let Ok(frame) = event {
            consume(&frame.message);
        }
    }
    frames
}

/// The same through the single-byte entry point.
fn push<S: Side>(framing: Framing<S>, input: &[u8]) -> usize {
    let mut decoder = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
    let mut frames = 0;
    for &byte in input {
        if let Some(Ok(frame)) = decoder.push(byte) {
            black_box(&frame.message);
            frames += 1;
        }
        while let Some(event) = decoder.poll() {
            if let Ok(frame) = event {
                black_box(&frame.message);
                frames += 1;
            }
        }
    }
    while let Some(event) = decoder.finish() {
        if let Ok(frame) = event {
            black_box(&frame.message);
            frames += 1;
        }
    }
    frames
}

/// The baseline: the classic hand-written byte-at-a-time parser a tile's
/// firmware uses for commands. It waits for the start byte, takes the id,
/// reads the payload its id implies blindly, checks the sum and dispatches;
/// after a bad frame it waits for the next start byte, with no rescan of the
/// bytes it consumed (so it can lose a frame after garbage, which robowire
/// does not).
fn naive_commands(input: &[u8]) -> usize {
    enum State {
        Start,
        Id,
        Payload,
        Sum,
    }
    let mut state = State::Start;
    let (mut id, mut want, mut have, mut sum) = (0u8, 0usize, 0usize, 0u8);
    let mut payload = [0u8; 3];
    let mut frames = 0;
    for &byte in input {
        match state {
            State::Start => {
                if byte == 0xA5 {
                    state = State::Id;
                }
            }
            State::Id => {
                id = byte;
                sum = byte;
                have = 0;
                want = match byte {
                    0x32 | 0x42 | 0x50 | 0x71 => 0,
                    0x30 | 0x31 | 0x33 | 0x40 | 0x41 | 0x43 => 1,
                    0x70 => 3,
                    _ => {
                        state = State::Start;
                        continue;
                    }
                };
                state = if want == 0 {
                    State::Sum
                } else {
                    State::Payload
                };
            }
            State::Payload => {
                payload[have] = byte;
                sum = sum.wrapping_add(byte);
                have += 1;
                if have == want {
                    state = State::Sum;
                }
            }
            State::Sum => {
                state = State::Start;
                if byte != sum {
                    continue;
                }
                let motor = if id & 0xF0 == 0x30 {
                    Motor::M1
                } else {
                    Motor::M2
                };
                let command = match id {
                    0x30 | 0x40 => Command::Extend {
                        motor,
                        speed: payload[0],
                    },
                    0x31 | 0x41 => Command::Retract {
                        motor,
                        speed: payload[0],
                    },
                    0x32 | 0x42 => Command::Brake { motor },
                    0x33 | 0x43 => Command::SetPosition {
                        motor,
                        position: payload[0],
                    },
                    0x50 => Command::Ping,
                    0x70 => Command::BaseVelocity {
                        vx: payload[0] as i8,
                        vy: payload[1] as i8,
                        omega: payload[2] as i8,
                    },
                    _ => Command::BaseBrake,
                };
                black_box(&command);
                frames += 1;
            }
        }
    }
    frames
}

fn encode_all<M: Encode>(messages: &[M], out: &mut [u8]) -> usize {
    let mut at = 0;
    for message in messages {
        at += message.encode(&mut out[at..]).unwrap();
    }
    at
}

fn sum_bytes(input: &[u8]) -> u64 {
    input.iter().map(|&b| u64::from(b)).sum()
}

fn omnitiles(c: &mut Criterion) {
    let (ble_messages, ble) = ble53();
    let (mixed_messages, mixed) = mixed();
    let (command_messages, commands) = commands();
    let (noisy, noisy_intact) = noisy();
    let ble53_only = Framing::<Host>::new().with_layouts(Layouts::only(Layout::Ble53));

    // Each benchmark finds exactly what was generated (checked once).
    let whole = usize::MAX;
    assert_eq!(decode(ble53_only, &ble, whole), ble_messages.len());
    assert_eq!(decode(ble53_only, &ble, 244), ble_messages.len());
    assert_eq!(decode_each(ble53_only, &ble, whole), ble_messages.len());
    assert_eq!(
        decode_each(Framing::<Device>::new(), &commands, whole),
        command_messages.len()
    );
    assert_eq!(
        decode_views(ble53_only.views(), &ble, whole),
        ble_messages.len()
    );
    assert_eq!(
        decode(Framing::<Both>::new(), &mixed, whole),
        mixed_messages.len()
    );
    assert_eq!(
        decode(Framing::<Device>::new(), &commands, whole),
        command_messages.len()
    );
    assert_eq!(
        push(Framing::<Device>::new(), &commands),
        command_messages.len()
    );
    assert_eq!(naive_commands(&commands), command_messages.len());
    assert_eq!(decode(ble53_only, &noisy, whole), noisy_intact);
    let mut out = vec![0u8; MIB];
    assert_eq!(encode_all(&ble_messages, &mut out), ble.len());
    assert_eq!(&out[..ble.len()], &ble[..]);
    assert_eq!(encode_all(&command_messages, &mut out), commands.len());
    assert_eq!(&out[..commands.len()], &commands[..]);
    assert_eq!(
        decode(Framing::<Both>::new(), &mixed, 244),
        mixed_messages.len(),
        "mixed layouts at BLE chunking"
    );

    let mut group = c.benchmark_group("omnitiles");
    let bytes = |n: usize| Throughput::Bytes(n as u64);

    group.throughput(bytes(ble.len()));
    group.bench_function("ceiling/sum_bytes", |b| {
        b.iter(|| sum_bytes(black_box(&ble)))
    });
    group.bench_function("decode/ble53", |b| {
        b.iter(|| decode(ble53_only, black_box(&ble), whole))
    });
    group.bench_function("decode/ble53_chunk244", |b| {
        b.iter(|| decode(ble53_only, black_box(&ble), 244))
    });
    group.bench_function("decode/ble53_each", |b| {
        b.iter(|| decode_each(ble53_only, black_box(&ble), whole))
    });
    group.bench_function("decode/ble53_view", |b| {
        b.iter(|| decode_views(ble53_only.views(), black_box(&ble), whole))
    });

    group.throughput(bytes(mixed.len()));
    group.bench_function("decode/auto_mixed", |b| {
        b.iter(|| decode(Framing::<Both>::new(), black_box(&mixed), whole))
    });

    group.throughput(bytes(commands.len()));
    group.bench_function("decode/commands", |b| {
        b.iter(|| decode(Framing::<Device>::new(), black_box(&commands), whole))
    });

    group.bench_function("decode/commands_each", |b| {
        b.iter(|| decode_each(Framing::<Device>::new(), black_box(&commands), whole))
    });
    group.bench_function("baseline/naive_commands", |b| {
        b.iter(|| naive_commands(black_box(&commands)))
    });

    group.throughput(bytes(noisy.len()));
    group.bench_function("decode/noisy", |b| {
        b.iter(|| decode(ble53_only, black_box(&noisy), whole))
    });

    group.throughput(bytes(commands.len()));
    group.bench_function("push/commands", |b| {
        b.iter(|| push(Framing::<Device>::new(), black_box(&commands)))
    });

    group.throughput(bytes(ble.len()));
    group.bench_function("encode/ble53", |b| {
        b.iter(|| encode_all(black_box(&ble_messages), &mut out))
    });
    group.throughput(bytes(commands.len()));
    group.bench_function("encode/commands", |b| {
        b.iter(|| encode_all(black_box(&command_messages), &mut out))
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(30);
    targets = omnitiles
}
criterion_main!(benches);
