//! Seeded OmniTiles streams with known corruption, and a scorer that compares
//! what a decoder found with the ground truth. Shared by
//! `tests/omnitiles_corruption.rs` and `examples/robustness.rs`.

#![allow(dead_code)]

use robowire::omnitiles::{
    Command, Framing, Imu, Layout, Message, Motor, Side, Telemetry, BOTH_BUFFER, NO_READING,
};
use robowire::{FrameBuf, OwnedFrame, StreamDecoder};

/// A tiny xorshift generator: reproducible streams without a dependency.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    pub fn byte(&mut self) -> u8 {
        self.next() as u8
    }
    /// True with probability `percent` / 100.
    pub fn percent(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }
    fn reading(&mut self) -> Option<u16> {
        Some(self.next() as u16).filter(|&v| v != NO_READING)
    }
}

/// What happens to the frames of a stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corruption {
    /// Nothing.
    Clean,
    /// One bit flipped in 1 % of the frames.
    BitFlips,
    /// A run of 1–32 random bytes before 5 % of the frames.
    Garbage,
    /// 5 % of the frames cut short (only a proper prefix is sent).
    Truncated,
    /// Before 5 % of the frames, 0–7 random bytes and then `0xA5`.
    GarbageEndingInStart,
}

impl Corruption {
    pub fn name(self) -> &'static str {
        match self {
            Corruption::Clean => "clean",
            Corruption::BitFlips => "1 % bit flips",
            Corruption::Garbage => "5 % garbage runs",
            Corruption::Truncated => "5 % truncated",
            Corruption::GarbageEndingInStart => "5 % garbage ending in a5",
        }
    }
}

/// One frame as sent.
#[derive(Debug, Clone, Copy)]
pub struct Sent {
    pub offset: u64,
    pub len: usize,
    pub packet: Message,
    /// Sent whole and unaltered: an ideal decoder accepts exactly these.
    pub intact: bool,
}

/// A generated stream and its ground truth.
pub struct Stream {
    pub bytes: Vec<u8>,
    pub sent: Vec<Sent>,
}

pub fn telemetry(rng: &mut Rng, layout: Layout) -> Telemetry {
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
        t.m1_adcs = Some([(); 4].map(|_| rng.next() as u16 % 4096));
        t.m2_adcs = Some([(); 2].map(|_| rng.next() as u16 % 4096));
    }
    t
}

pub fn command(rng: &mut Rng) -> Command {
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

/// `count` packets from `next`, corrupted as `corruption` says.
pub fn generate(
    seed: u64,
    count: usize,
    corruption: Corruption,
    next: impl FnMut(&mut Rng) -> Message,
) -> Stream {
    generate_padded(seed, count, corruption, 0, next)
}

/// [`generate`], each frame followed by zeros up to `pad` bytes from its
/// start (an SPI buffer: `pad` 128).
pub fn generate_padded(
    seed: u64,
    count: usize,
    corruption: Corruption,
    pad: usize,
    mut next: impl FnMut(&mut Rng) -> Message,
) -> Stream {
    let mut rng = Rng(seed);
    let (mut bytes, mut sent) = (Vec::new(), Vec::new());
    for _ in 0..count {
        let packet = next(&mut rng);
        let mut frame = FrameBuf::<{ Message::MAX_LEN }>::encode(&packet)
            .unwrap()
            .to_vec();
        let mut intact = true;
        match corruption {
            Corruption::Clean => {}
            Corruption::BitFlips => {
                if rng.percent(1) {
                    let at = rng.below(frame.len() as u64) as usize;
                    frame[at] ^= 1 << rng.below(8);
                    intact = false;
                }
            }
            Corruption::Garbage => {
                if rng.percent(5) {
                    for _ in 0..1 + rng.below(32) {
                        bytes.push(rng.byte());
                    }
                }
            }
            Corruption::Truncated => {
                if rng.percent(5) {
                    let keep = 1 + rng.below(frame.len() as u64 - 1) as usize;
                    frame.truncate(keep);
                    intact = false;
                }
            }
            Corruption::GarbageEndingInStart => {
                if rng.percent(5) {
                    for _ in 0..rng.below(8) {
                        bytes.push(rng.byte());
                    }
                    bytes.push(0xa5);
                }
            }
        }
        sent.push(Sent {
            offset: bytes.len() as u64,
            len: frame.len(),
            packet,
            intact,
        });
        let start = bytes.len();
        bytes.extend_from_slice(&frame);
        bytes.resize(bytes.len().max(start + pad), 0);
    }
    Stream { bytes, sent }
}

/// SPI buffers: 45-byte telemetry frames, each zero-padded to 128 bytes
/// (garbage goes before a buffer, a cut frame is still padded).
pub fn spi_stream(seed: u64, count: usize, corruption: Corruption) -> Stream {
    generate_padded(seed, count, corruption, 128, |rng| {
        Message::Telemetry(telemetry(rng, Layout::Spi45))
    })
}

/// Telemetry frames with layouts drawn from `layouts`.
pub fn telemetry_stream(
    seed: u64,
    count: usize,
    layouts: &[Layout],
    corruption: Corruption,
) -> Stream {
    generate(seed, count, corruption, |rng| {
        let layout = layouts[rng.below(layouts.len() as u64) as usize];
        Message::Telemetry(telemetry(rng, layout))
    })
}

/// Mixed commands.
pub fn command_stream(seed: u64, count: usize, corruption: Corruption) -> Stream {
    generate(seed, count, corruption, |rng| {
        Message::Command(command(rng))
    })
}

/// Decode `bytes` fed in `chunk`-byte pieces (0: whole), then finish.
pub fn decode<S>(framing: Framing<S>, bytes: &[u8], chunk: usize) -> Vec<OwnedFrame<Message>>
where
    S: Side<Message: Into<Message>>,
{
    let mut decoder = StreamDecoder::<_, BOTH_BUFFER>::new(framing);
    let mut frames = Vec::new();
    let chunk = if chunk == 0 {
        bytes.len().max(1)
    } else {
        chunk
    };
    for piece in bytes.chunks(chunk) {
        frames.extend(decoder.feed(piece).filter_map(Result::ok).map(widen));
    }
    frames.extend(decoder.flush().filter_map(Result::ok).map(widen));
    frames
}

/// A frame with its message as either direction's.
fn widen<M: Into<Message>>(frame: OwnedFrame<M>) -> OwnedFrame<Message> {
    OwnedFrame {
        offset: frame.offset,
        len: frame.len,
        message: frame.message.into(),
    }
}

/// How a decoder did against the ground truth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Score {
    /// Frames sent.
    pub sent: usize,
    /// Frames sent intact: what an ideal decoder accepts.
    pub ideal: usize,
    /// Intact frames the decoder gave back (right place, right message).
    pub intact: usize,
    /// Intact frames it did not give back.
    pub lost: usize,
    /// Frames it accepted that were not sent intact at that place.
    pub false_frames: usize,
}

pub fn score(stream: &Stream, decoded: &[OwnedFrame<Message>]) -> Score {
    let mut intact = 0;
    let mut false_frames = 0;
    let mut sent = stream.sent.iter().filter(|s| s.intact).peekable();
    for frame in decoded {
        while sent.peek().is_some_and(|s| s.offset < frame.offset) {
            sent.next();
        }
        match sent.peek() {
            Some(s)
                if s.offset == frame.offset && s.len == frame.len && s.packet == frame.message =>
            {
                intact += 1;
                sent.next();
            }
            _ => false_frames += 1,
        }
    }
    let ideal = stream.sent.iter().filter(|s| s.intact).count();
    Score {
        sent: stream.sent.len(),
        ideal,
        intact,
        lost: ideal - intact,
        false_frames,
    }
}
