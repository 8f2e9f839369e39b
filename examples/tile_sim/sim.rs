//! A seeded OmniTiles tile simulator: the sample captures in `tests/data/`.
//!
//! Everything is a pure function of the seeds below, computed with IEEE
//! arithmetic and `sqrt` only (no `sin`/`cos`, whose last bit may differ
//! between C libraries), so the captures regenerate byte for byte anywhere.
//! `tests/sample_data.rs` checks that against the committed files.

use robowire::omnitiles::{Command, Imu, Layout, Motor, Telemetry};
use robowire::{Encode, EncodeError, FrameBuf};

/// One generated capture: its file name under `tests/data/` and its bytes.
pub struct Capture {
    /// File name.
    pub name: &'static str,
    /// File contents.
    pub bytes: Vec<u8>,
}

/// Every sample capture.
pub fn captures() -> Result<Vec<Capture>, EncodeError> {
    Ok(vec![
        Capture {
            name: "ble_telemetry.bin",
            bytes: ble_telemetry()?,
        },
        Capture {
            name: "ble_notifications.hex",
            bytes: ble_notifications()?,
        },
        Capture {
            name: "spi_telemetry.bin",
            bytes: spi_telemetry()?,
        },
        Capture {
            name: "host_commands.bin",
            bytes: host_commands()?,
        },
        Capture {
            name: "spi_commands.hex",
            bytes: spi_commands()?,
        },
    ])
}

/// xorshift64: small, seeded, good enough for line noise and sensor jitter.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(seed | 1)
    }

    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }

    /// Uniform in `0..n`.
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    /// True with probability `per_mille`/1000.
    fn chance(&mut self, per_mille: u64) -> bool {
        self.below(1000) < per_mille
    }

    fn byte(&mut self) -> u8 {
        self.next() as u8
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Roughly normal, mean 0, standard deviation `sigma` (sum of four uniforms).
    fn noise(&mut self, sigma: f64) -> f64 {
        let sum: f64 = (0..4).map(|_| self.unit()).sum();
        (sum - 2.0) * sigma * 1.732_050_807_568_877_2
    }
}

/// An actuator following a sequence of targets at constant speed.
struct Actuator {
    stroke_mm: f64,
    min_mm: f64,
    max_mm: f64,
    mm: f64,
    target: f64,
    speed_mm_per_tick: f64,
}

impl Actuator {
    fn step(&mut self, rng: &mut Rng) {
        let delta = self.target - self.mm;
        if delta.abs() <= self.speed_mm_per_tick {
            self.mm = self.target;
            // Dwell a little, then pick a new target along the stroke.
            if rng.chance(40) {
                self.target = self.min_mm + rng.unit() * (self.max_mm - self.min_mm);
            }
        } else {
            self.mm += self.speed_mm_per_tick * delta.signum();
        }
    }

    /// The pot reading for this position, 12 bits.
    fn raw(&self) -> f64 {
        self.mm / self.stroke_mm * 4095.0
    }
}

/// Anchor positions in metres (x, y, z), one per room corner.
const ANCHORS: [(f64, f64, f64); 4] = [
    (0.0, 0.0, 2.1),
    (5.0, 0.0, 2.1),
    (5.0, 4.0, 2.1),
    (0.0, 4.0, 2.1),
];

/// cos and sin of the base's turn per tick (a 1.2 m circle at about 0.1 m/s,
/// 40 ticks per second: 0.1 / 1.2 / 40 rad).
const TURN_COS: f64 = 0.999_997_829_861_896;
const TURN_SIN: f64 = 0.002_083_331_826_292_766;
/// Yaw rate of that circle, rad/s.
const YAW_RATE: f64 = 0.083_333_333_333_333_34;

/// Accelerometer and gyroscope LSBs (±2 g, ±2000 dps).
const ACCEL_LSB: f32 = 5.985_504e-4;
const GYRO_LSB: f32 = 1.065_264_5e-3;

/// The simulated tile: two actuators on a mecanum base driving a circle.
struct Tile {
    rng: Rng,
    tick: u32,
    m1: Actuator,
    m2: Actuator,
    /// Position on the circle relative to its centre, metres.
    circle: (f64, f64),
    /// Last UWB range per anchor: ranges stick when an anchor is lost.
    uwb: [Option<u16>; 4],
    tof: Option<u16>,
}

impl Tile {
    fn new(seed: u64) -> Tile {
        Tile {
            rng: Rng::new(seed),
            tick: 0,
            m1: Actuator {
                stroke_mm: 150.0,
                min_mm: 20.0,
                max_mm: 115.0,
                mm: 40.0,
                target: 100.0,
                speed_mm_per_tick: 0.5,
            },
            m2: Actuator {
                stroke_mm: 100.0,
                min_mm: 25.0,
                max_mm: 85.0,
                mm: 70.0,
                target: 30.0,
                speed_mm_per_tick: 0.35,
            },
            circle: (1.2, 0.0),
            uwb: [None; 4],
            tof: None,
        }
    }

    /// Advance 25 ms (40 Hz) and report a full telemetry sample (the BLE
    /// layout); other layouts take their fields from it.
    fn step(&mut self) -> Telemetry {
        self.tick += 1;
        let rng = &mut self.rng;
        self.m1.step(rng);
        self.m2.step(rng);
        let (x, y) = self.circle;
        self.circle = (x * TURN_COS - y * TURN_SIN, x * TURN_SIN + y * TURN_COS);

        // Pots: M1 has four (the last two inverted), M2 two; the position is
        // the mean of the channels, an inverted one counting as 3357 - raw.
        let pot =
            |rng: &mut Rng, raw: f64| (raw + rng.noise(3.0)).round().clamp(0.0, 4095.0) as u16;
        let m1_raw = self.m1.raw();
        let m1_adcs = [
            pot(rng, m1_raw),
            pot(rng, m1_raw),
            pot(rng, 3357.0 - m1_raw),
            pot(rng, 3357.0 - m1_raw),
        ];
        let m1_pos = (u32::from(m1_adcs[0])
            + u32::from(m1_adcs[1])
            + u32::from(3357u16.saturating_sub(m1_adcs[2]))
            + u32::from(3357u16.saturating_sub(m1_adcs[3])))
            / 4;
        let m2_raw = self.m2.raw();
        let m2_adcs = [pot(rng, m2_raw), pot(rng, m2_raw)];
        let m2_pos = (u32::from(m2_adcs[0]) + u32::from(m2_adcs[1])) / 2;

        // UWB: ranges to the four anchors with about 4 cm of jitter. Anchor 3
        // is out of reach for the first two seconds (never measured: 0xFFFF),
        // and any anchor misses a round now and then (the old value sticks).
        let (px, py, pz) = (2.5 + x, 2.0 + y, 0.15);
        for (i, &(ax, ay, az)) in ANCHORS.iter().enumerate() {
            if (i == 3 && self.tick < 80) || rng.chance(30) {
                continue;
            }
            let d = ((px - ax) * (px - ax) + (py - ay) * (py - ay) + (pz - az) * (pz - az)).sqrt();
            self.uwb[i] = Some((d * 1000.0 + rng.noise(40.0)).round().max(0.0) as u16);
        }

        // ToF: read every 100 ms; an object 30-60 cm away, out of range
        // (about 8190) now and then, and a rare read error (0xFFFF).
        if self.tick % 4 == 1 {
            self.tof = if rng.chance(20) {
                None
            } else if rng.chance(60) {
                Some(8190)
            } else {
                let mm = 450.0 + 150.0 * (y / 1.2) + rng.noise(6.0);
                Some(mm.round() as u16)
            };
        }

        // IMU: gravity on a plate tilted by the actuators' difference (over a
        // 200 mm baseline), the base's centripetal pull, and sensor noise;
        // values quantised to the sensor's LSB as the firmware scales them.
        let slope = (self.m1.mm - self.m2.mm) / 200.0;
        let norm = (1.0 + slope * slope).sqrt();
        let g = 9.806_65;
        let centripetal = 0.1 * YAW_RATE;
        let quantise = |v: f64, lsb: f32| (v / f64::from(lsb)).round() as i16 as f32 * lsb;
        let imu = Imu {
            ax: quantise(g * slope / norm + rng.noise(0.02), ACCEL_LSB),
            ay: quantise(centripetal + rng.noise(0.02), ACCEL_LSB),
            az: quantise(g / norm + rng.noise(0.02), ACCEL_LSB),
            gx: quantise(rng.noise(0.004), GYRO_LSB),
            gy: quantise(rng.noise(0.004), GYRO_LSB),
            gz: quantise(YAW_RATE + rng.noise(0.004), GYRO_LSB),
        };

        Telemetry {
            layout: Layout::Ble53,
            m1_pos: Some(m1_pos as u16),
            m2_pos: Some(m2_pos as u16),
            uwb: Some(self.uwb),
            tof: Some(self.tof),
            imu: Some(imu),
            m1_adcs: Some(m1_adcs),
            m2_adcs: Some(m2_adcs),
        }
    }
}

/// The same sample in another layout (its fields, where it carries them).
fn in_layout(full: &Telemetry, layout: Layout) -> Telemetry {
    let mut t = Telemetry::empty(layout);
    t.m1_pos = full.m1_pos;
    t.m2_pos = full.m2_pos;
    if layout.has_uwb() {
        t.uwb = full.uwb;
    }
    if layout.has_tof() {
        t.tof = full.tof;
    }
    if layout.has_imu_and_adcs() {
        t.imu = full.imu;
        t.m1_adcs = full.m1_adcs;
        t.m2_adcs = full.m2_adcs;
    }
    t
}

fn frame(message: &impl Encode) -> Result<FrameBuf<53>, EncodeError> {
    FrameBuf::encode(message)
}

/// Line noise: now and then a few random bytes (a start byte among them at
/// times) between frames, and now and then a flipped bit inside a frame.
fn noisy(
    rng: &mut Rng,
    out: &mut Vec<u8>,
    frame: &[u8],
    gaps_per_mille: u64,
    flips_per_mille: u64,
) {
    if rng.chance(gaps_per_mille) {
        for _ in 0..1 + rng.below(4) {
            let b = if rng.chance(250) { 0xa5 } else { rng.byte() };
            out.push(b);
        }
    }
    let start = out.len();
    out.extend_from_slice(frame);
    if rng.chance(flips_per_mille) {
        let at = start + rng.below(frame.len() as u64) as usize;
        out[at] ^= 1 << rng.below(8);
    }
}

fn hex_line(out: &mut Vec<u8>, bytes: &[u8]) {
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            out.push(b' ');
        }
        out.extend_from_slice(format!("{b:02x}").as_bytes());
    }
    out.push(b'\n');
}

/// Concatenated 53-byte BLE notifications, as a host logs them, with a
/// little line noise.
fn ble_telemetry() -> Result<Vec<u8>, EncodeError> {
    let mut tile = Tile::new(0x0d1e_5ea5);
    let mut rng = Rng::new(0x5eed_0001);
    let mut out = Vec::new();
    for _ in 0..300 {
        let t = tile.step();
        noisy(&mut rng, &mut out, &frame(&t)?, 30, 10);
    }
    Ok(out)
}

/// The tile and line noise of `ble_telemetry.bin`, without end: one frame
/// (with the noise around it) per call, for a live link (`tile_sim --pty`).
#[allow(dead_code)] // tests/sample_data.rs includes this file for the captures only
pub struct LiveTelemetry {
    tile: Tile,
    rng: Rng,
}

#[allow(dead_code)]
impl LiveTelemetry {
    /// The stream `ble_telemetry.bin` begins with.
    pub fn new() -> LiveTelemetry {
        LiveTelemetry {
            tile: Tile::new(0x0d1e_5ea5),
            rng: Rng::new(0x5eed_0001),
        }
    }

    /// Append the next frame, and the noise around it, to `out`.
    pub fn next_into(&mut self, out: &mut Vec<u8>) -> Result<(), EncodeError> {
        let t = self.tile.step();
        noisy(&mut self.rng, out, &frame(&t)?, 30, 10);
        Ok(())
    }
}

/// One BLE notification per line, as a BLE sniffer or the SDK logs them.
/// The first notifications come before the nRF's first SPI frame (positions
/// 0, nothing else measured yet); a few later ones are corrupted.
fn ble_notifications() -> Result<Vec<u8>, EncodeError> {
    let mut tile = Tile::new(0x0b1e_0002);
    let mut rng = Rng::new(0x5eed_0002);
    let mut out = Vec::new();
    for i in 0..80 {
        let mut t = tile.step();
        if i < 3 {
            // The nRF has no SPI frame yet: zeros where the STM32's fields go.
            t = Telemetry {
                m1_pos: Some(0),
                m2_pos: Some(0),
                tof: Some(Some(0)),
                uwb: t.uwb,
                ..Telemetry::empty(Layout::Ble53)
            };
        }
        let mut bytes = frame(&t)?.to_vec();
        if rng.chance(40) {
            let at = rng.below(bytes.len() as u64) as usize;
            bytes[at] ^= 1 << rng.below(8);
        }
        hex_line(&mut out, &bytes);
    }
    Ok(out)
}

/// STM32 → nRF SPI buffers: a 45-byte frame zero-padded to 128 bytes.
fn spi_telemetry() -> Result<Vec<u8>, EncodeError> {
    spi_buffers(0x5b1_0003, 64)
}

/// `count` SPI buffers of a tile seeded with `seed`: each a 45-byte frame
/// zero-padded to 128 bytes, as the STM32 sends them to the nRF.
pub fn spi_buffers(seed: u64, count: usize) -> Result<Vec<u8>, EncodeError> {
    let mut tile = Tile::new(seed);
    let mut out = Vec::with_capacity(count * 128);
    for _ in 0..count {
        let t = in_layout(&tile.step(), Layout::Spi45);
        let mut buffer = [0u8; 128];
        buffer[..45].copy_from_slice(&frame(&t)?);
        out.extend_from_slice(&buffer);
    }
    Ok(out)
}

/// A host session's commands: what the SDK and the GUI send.
fn session(rng: &mut Rng, count: usize) -> Vec<Command> {
    use Motor::{M1, M2};
    let mut commands = vec![Command::Ping];
    while commands.len() < count {
        let command = match rng.below(12) {
            0 => Command::Ping,
            1 => Command::Extend {
                motor: M1,
                speed: [255, 200, 128][rng.below(3) as usize],
            },
            2 => Command::Retract {
                motor: M1,
                speed: [255, 200, 128][rng.below(3) as usize],
            },
            3 => Command::Brake { motor: M1 },
            4 => Command::SetPosition {
                motor: M1,
                position: rng.byte(),
            },
            5 => Command::Extend {
                motor: M2,
                speed: [255, 180, 90][rng.below(3) as usize],
            },
            6 => Command::Retract {
                motor: M2,
                speed: [255, 180, 90][rng.below(3) as usize],
            },
            7 => Command::Brake { motor: M2 },
            8 => Command::SetPosition {
                motor: M2,
                position: rng.byte(),
            },
            // The GUI's arrows at 30 % and its rotation buttons.
            9 | 10 => {
                let [vx, vy, omega] = [
                    [30, 0, 0],
                    [-30, 0, 0],
                    [0, 30, 0],
                    [0, -30, 0],
                    [0, 0, 30],
                    [0, 0, -30],
                    [21, 21, 0],
                ][rng.below(7) as usize];
                Command::BaseVelocity { vx, vy, omega }
            }
            _ => Command::BaseBrake,
        };
        commands.push(command);
    }
    commands
}

/// The command stream a tile's UART would see, with a little line noise.
fn host_commands() -> Result<Vec<u8>, EncodeError> {
    let mut rng = Rng::new(0x5eed_0004);
    let mut out = Vec::new();
    for command in session(&mut rng, 240) {
        noisy(&mut rng, &mut out, &frame(&command)?, 30, 10);
    }
    Ok(out)
}

/// nRF → STM32 SPI buffers, one per line: each BLE write zero-padded to 128
/// bytes (one command per write, as the SDK sends them, and now and then a
/// write holding several), and the nRF's brake buffer after a disconnect.
fn spi_commands() -> Result<Vec<u8>, EncodeError> {
    let mut rng = Rng::new(0x5eed_0005);
    let commands = session(&mut rng, 40);
    let mut out = Vec::new();
    let mut rest = &commands[..];
    while !rest.is_empty() {
        let take = if rng.chance(150) {
            3.min(rest.len())
        } else {
            1
        };
        let mut buffer = [0u8; 128];
        let mut n = 0;
        for command in &rest[..take] {
            let f = frame(command)?;
            buffer[n..n + f.len()].copy_from_slice(&f);
            n += f.len();
        }
        rest = &rest[take..];
        hex_line(&mut out, &buffer);
        if rng.chance(80) {
            let mut brake = [0u8; 128];
            brake[..6].copy_from_slice(&[0xa5, 0x32, 0x32, 0xa5, 0x42, 0x42]);
            hex_line(&mut out, &brake);
        }
    }
    Ok(out)
}
