//! Inputs and the oracle shared by the I/O adapter tests.
#![allow(dead_code)]

use robowire::omnitiles::{
    Both, Command, Framing, Imu, Layout, Motor, Side, Telemetry, BOTH_BUFFER,
};
use robowire::{Encode, FrameBuf, OwnedEvent, OwnedFrame, Rejected, StreamDecoder};

/// An event of an OmniTiles decoder of side `S`.
pub type Ev<S = Both> = OwnedEvent<Framing<S>>;

/// A small deterministic generator (xorshift), so failures reproduce.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed | 1)
    }

    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn byte(&mut self) -> u8 {
        self.next() as u8
    }
}

pub fn frame<M: Encode>(message: &M) -> Vec<u8> {
    FrameBuf::<64>::encode(message).unwrap().to_vec()
}

/// A 53-byte telemetry frame with values from `seed`.
pub fn telemetry(seed: u16) -> Telemetry {
    Telemetry {
        m1_pos: Some(seed % 4096),
        m2_pos: Some(seed.wrapping_mul(7) % 4096),
        uwb: Some([Some(seed), None, Some(1200), Some(seed / 2)]),
        tof: Some(Some(seed % 500)),
        imu: Some(Imu::from_array([0.1, -0.2, 9.81, 0.0, 0.01, seed as f32])),
        m1_adcs: Some([seed % 4096, 1, 2, 3]),
        m2_adcs: Some([4095, seed % 4096]),
        ..Telemetry::empty(Layout::Ble53)
    }
}

pub fn commands() -> Vec<Command> {
    vec![
        Command::Ping,
        Command::Extend {
            motor: Motor::M1,
            speed: 200,
        },
        Command::Retract {
            motor: Motor::M2,
            speed: 0xa5,
        },
        Command::Brake { motor: Motor::M1 },
        Command::SetPosition {
            motor: Motor::M2,
            position: 128,
        },
        Command::BaseVelocity {
            vx: -91,
            vy: 0x60,
            omega: 3,
        },
        Command::BaseBrake,
    ]
}

/// A tile → host stream: 53-byte telemetry with garbage, false starts and a
/// corrupted frame between frames. Returns the bytes and the telemetry that
/// was sent intact.
pub fn noisy_telemetry(rng: &mut Rng, frames: usize) -> (Vec<u8>, Vec<Telemetry>) {
    let mut bytes = Vec::new();
    let mut sent = Vec::new();
    for i in 0..frames {
        let packet = telemetry(i as u16 * 97);
        let mut f = frame(&packet);
        match rng.below(6) {
            0 => bytes.extend((0..rng.below(9)).map(|_| rng.byte())),
            1 => bytes.extend([0xa5, 0x60, rng.byte()]),
            2 => bytes.push(0xa5),
            3 => {
                // A corrupted copy before the good one.
                let mut bad = f.clone();
                let at = 2 + rng.below(bad.len() - 2);
                bad[at] ^= 0x10;
                bytes.extend(bad);
            }
            _ => {}
        }
        bytes.append(&mut f);
        sent.push(packet);
    }
    (bytes, sent)
}

/// A host → tile stream of commands with noise between them.
pub fn noisy_commands(rng: &mut Rng, count: usize) -> (Vec<u8>, Vec<Command>) {
    let all = commands();
    let mut bytes = Vec::new();
    let mut sent = Vec::new();
    for _ in 0..count {
        let packet = all[rng.below(all.len())];
        if rng.below(3) == 0 {
            bytes.extend((0..rng.below(5)).map(|_| rng.byte()));
        }
        bytes.extend(frame(&packet));
        sent.push(packet);
    }
    (bytes, sent)
}

/// The oracle: the engine fed the whole input at once, then finished.
pub fn engine_events<S: Side>(framing: Framing<S>, input: &[u8]) -> Vec<Ev<S>> {
    let mut decoder = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
    let mut events: Vec<Ev<S>> = decoder.feed(input).collect();
    events.extend(decoder.flush());
    events
}

pub fn packets<M: Copy, E>(events: &[Result<OwnedFrame<M>, Rejected<E>>]) -> Vec<M> {
    events
        .iter()
        .filter_map(|e| e.as_ref().ok().map(|f| f.message))
        .collect()
}

pub fn encoded<M: Encode>(messages: &[M]) -> Vec<u8> {
    let mut out = Vec::new();
    for m in messages {
        let mut buf = vec![0; m.encoded_len()];
        let n = m.encode(&mut buf).unwrap();
        out.extend_from_slice(&buf[..n]);
    }
    out
}
