//! A seeded simulation of a Telemetrix session: the sample captures in
//! `tests/data/`.
//!
//! The host follows the start-up of spec §8 (15 zero bytes, the firmware
//! version, FEATURE_CHECK for ids 0..=38, sensor checks for types 0..=10,
//! module checks for types 0..=3, then a PING every 400 ms), configures pins,
//! a sonar, an encoder, two I2C sensors and two modules, and drives an LED,
//! PWM outputs, two bus servos and a PWM expander. The simulated Pico decodes
//! those writes with the library's command decoder, answers them as the
//! mirte 1.3 firmware does, and scans its inputs every 100 ms: a button and a
//! bumper, a potentiometer and a battery divider, a sonar facing an
//! approaching wall, a wheel encoder, an INA226 and a VL53L0X, and the
//! servos' positions (sent from the second core). A little line noise and one
//! frame interleaved byte by byte with a second core's frame are mixed in.
//!
//! Everything is a pure function of the seed, computed with IEEE arithmetic
//! (no `sin`/`cos`), so the captures regenerate byte for byte anywhere.

use robowire::telemetrix::{
    device_decoder, Command, CommandBuf, DeviceDecoder, EncoderKind, HiwonderCommand, List,
    ModuleCommand, ModuleInit, ModuleNew, ModuleReport, ModuleType, Pca9685Channel, Pca9685Command,
    Pca9685Config, PinMode, Pull, Pulls, PwmPin, PwmPins, Report, SensorNew, SensorReading,
    SensorType, ServoMove, ServoPositions, Sonar, SONAR_OUT_OF_RANGE,
};
use robowire::EncodeError;

/// One generated capture: its file name under `tests/data/` and its bytes.
pub struct Capture {
    /// File name.
    pub name: &'static str,
    /// File contents.
    pub bytes: Vec<u8>,
}

/// Every sample capture.
pub fn captures() -> Result<Vec<Capture>, EncodeError> {
    let writes = host_script()?;
    let mut commands = Vec::new();
    for write in &writes {
        hex_line(&mut commands, &write.bytes);
    }
    let reports = Pico::new(0x5eed_7e1e).run(&writes)?;
    Ok(vec![
        Capture {
            name: "telemetrix_commands.hex",
            bytes: commands,
        },
        Capture {
            name: "telemetrix_reports.bin",
            bytes: reports,
        },
    ])
}

/// Milliseconds after which the session ends.
pub const END_MS: u32 = 8000;

/// xorshift64: small, seeded, good enough for sensor jitter and line noise.
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

fn hex_line(out: &mut Vec<u8>, bytes: &[u8]) {
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            out.push(b' ');
        }
        out.extend_from_slice(format!("{b:02x}").as_bytes());
    }
    out.push(b'\n');
}

/// One write of the host: the bytes of one frame (or of the start-up
/// padding), at a time in ms.
struct Write {
    at_ms: u32,
    bytes: Vec<u8>,
}

fn command(at_ms: u32, c: &Command<'_>) -> Result<Write, EncodeError> {
    frame(at_ms, c.to_buf()?)
}

fn frame(at_ms: u32, c: CommandBuf) -> Result<Write, EncodeError> {
    Ok(Write {
        at_ms,
        bytes: c.to_vec(),
    })
}

/// Two servos on the Hiwonder bus (ids 1 and 2), as module 0; a PCA9685 at
/// 0x41, as module 1.
const SERVO_BUS_IDS: [u8; 2] = [1, 2];

/// The host's writes in time order.
fn host_script() -> Result<Vec<Write>, EncodeError> {
    type C<'a> = Command<'a>;
    let mut w = vec![Write {
        at_ms: 0,
        bytes: vec![0; 15],
    }];
    w.push(command(1000, &C::GetFirmwareVersion)?);
    for id in 0..=38u8 {
        let at = 1030 + 30 * u32::from(id);
        w.push(command(at, &C::FeatureCheck { msg_type: id })?);
    }
    for t in 0..=10u8 {
        let check = SensorNew::Check { sensor_type: t };
        w.push(command(2200 + 200 * u32::from(t), &C::SensorNew(check))?);
    }
    for t in 0..=3u8 {
        let check = ModuleNew::Check { module_type: t };
        w.push(command(4400 + 50 * u32::from(t), &C::ModuleNew(check))?);
    }
    for (i, at) in (4600..END_MS).step_by(400).enumerate() {
        w.push(command(at, &C::Ping { counter: i as u8 })?);
    }
    let input = |report| PinMode::DigitalInput {
        pull: Pull::Up,
        report,
    };
    let analog = PinMode::AnalogInput {
        differential: 5,
        report: true,
    };
    let hiwonder = ModuleInit::HiwonderServo {
        uart: 0,
        rx: 1,
        tx: 0,
        bus_ids: &SERVO_BUS_IDS[..],
    };
    let pca9685 = ModuleInit::Pca9685 {
        port: 0,
        config: Some(Pca9685Config {
            addr: 0x41,
            freq_hz: 50,
        }),
    };
    let setup = [
        C::GetUniqueId,
        C::GetId,
        C::SetPinMode {
            pin: 25,
            mode: PinMode::DigitalOutput,
        },
        C::SetPinMode {
            pin: 10,
            mode: input(true),
        },
        C::SetPinMode {
            pin: 11,
            mode: input(true),
        },
        C::SetPinMode {
            pin: 26,
            mode: analog,
        },
        C::SetPinMode {
            pin: 27,
            mode: analog,
        },
        C::SetPinMode {
            pin: 16,
            mode: PinMode::PwmOutput,
        },
        C::SonarNew { trig: 9, echo: 10 },
        C::EncoderNew {
            kind: EncoderKind::Quadrature,
            pin_a: 14,
            pin_b: 15,
            pulls: Some(Pulls {
                up: true,
                down: false,
            }),
        },
        C::I2cBegin {
            port: 0,
            sda: 0,
            scl: 0,
        },
        C::SensorNew(SensorNew::add(0, SensorType::Ina226, &[0, 0x40])?),
        C::SensorNew(SensorNew::add(1, SensorType::Vl53l0x, &[0])?),
        C::ModuleNew(ModuleNew::Add {
            module_num: 0,
            init: hiwonder,
        }),
        C::ModuleNew(ModuleNew::Add {
            module_num: 1,
            init: pca9685,
        }),
    ];
    for (i, c) in setup.iter().enumerate() {
        w.push(command(4610 + 10 * i as u32, c)?);
    }
    // An LED heartbeat.
    for (i, at) in (4800..END_MS).step_by(500).enumerate() {
        let led = C::DigitalWrite {
            pin: 25,
            value: i % 2 == 0,
        };
        w.push(command(at, &led)?);
    }
    let pwm = |pins: &[(u8, u16)]| {
        let pins: Vec<PwmPin> = pins
            .iter()
            .map(|&(pin, value)| PwmPin { pin, value })
            .collect();
        PwmPins::from_slice(&pins).map(C::PwmWrite)
    };
    w.push(command(5000, &pwm(&[(16, 1500)])?)?);
    w.push(command(6500, &pwm(&[(16, 1200), (17, 1800)])?)?);
    let moves = |moves: &[(u8, u16, u16)]| {
        let moves: Vec<ServoMove> = moves
            .iter()
            .map(|&(idx, centideg, time_ms)| ServoMove {
                idx,
                centideg,
                time_ms,
            })
            .collect();
        List::from_slice(&moves).map(HiwonderCommand::SetAngle)
    };
    let both = moves(&[(0, 9000, 800), (1, 15000, 800)])?;
    w.push(frame(5200, C::module_data(0, &both)?)?);
    let channels = [
        Pca9685Channel {
            channel: 0,
            on: 0,
            off: 205,
        },
        Pca9685Channel {
            channel: 1,
            on: 0,
            off: 410,
        },
    ];
    let pca = Pca9685Command {
        channels: List::from_slice(&channels)?,
    };
    w.push(frame(5600, C::module_data(1, &pca)?)?);
    let back = moves(&[(0, 12000, 500)])?;
    w.push(frame(7000, C::module_data(0, &back)?)?);
    // In time order; writes at the same time keep their order.
    w.sort_by_key(|write| write.at_ms);
    Ok(w)
}

/// A bus servo moving linearly towards a target.
#[derive(Clone, Copy)]
struct Servo {
    from: f64,
    to: f64,
    start_ms: u32,
    time_ms: u32,
    /// The position last reported, and when.
    reported: Option<(u16, u32)>,
}

impl Servo {
    fn at(&self, t: u32) -> f64 {
        let done = if self.time_ms == 0 {
            1.0
        } else {
            (f64::from(t.saturating_sub(self.start_ms)) / f64::from(self.time_ms)).min(1.0)
        };
        self.from + (self.to - self.from) * done
    }

    /// The servo reads its position in ticks of 24 centidegrees.
    fn read(&self, t: u32) -> u16 {
        ((self.at(t) / 24.0).round() * 24.0) as u16
    }
}

/// The simulated Pico: what the host configured, the world it measures, and
/// the bytes it has sent.
struct Pico {
    rng: Rng,
    decoder: DeviceDecoder,
    out: Vec<u8>,
    now: u32,
    boot_id: Option<u8>,
    digital: Vec<(u8, Option<bool>)>,
    analog: Vec<(u8, u16, Option<u16>)>,
    sonar: Option<(u8, u8, Option<u16>)>,
    encoder: Option<u8>,
    sensors: Vec<(u8, SensorType)>,
    servos: Vec<Servo>,
    /// A frame of the second core waiting to interleave with the next frame
    /// of the first, and whether that has happened.
    core1: Option<Vec<u8>>,
    interleaved: bool,
}

impl Pico {
    fn new(seed: u64) -> Pico {
        Pico {
            rng: Rng::new(seed),
            decoder: device_decoder(),
            out: Vec::new(),
            now: 0,
            boot_id: None,
            digital: Vec::new(),
            analog: Vec::new(),
            sonar: None,
            encoder: None,
            sensors: Vec::new(),
            servos: Vec::new(),
            core1: None,
            interleaved: false,
        }
    }

    /// Everything the Pico sends while the host writes `writes`.
    fn run(mut self, writes: &[Write]) -> Result<Vec<u8>, EncodeError> {
        let mut next = writes.iter().peekable();
        for t in 0..END_MS {
            self.now = t;
            while let Some(write) = next.next_if(|w| w.at_ms == t) {
                let commands: Vec<_> = self
                    .decoder
                    .feed(&write.bytes)
                    .filter_map(Result::ok)
                    .map(|frame| frame.message)
                    .collect();
                for c in commands {
                    self.execute(&c.message())?;
                }
            }
            if t % 100 == 0 {
                self.scan()?;
            }
        }
        if let Some(frame) = self.core1.take() {
            self.out.extend_from_slice(&frame);
        }
        Ok(self.out)
    }

    /// Send a report from the first core, with now and then a few bytes of
    /// line noise before it.
    fn send(&mut self, report: &Report<'_>) -> Result<(), EncodeError> {
        let frame = report.to_buf()?;
        if self.rng.chance(15) {
            for _ in 0..1 + self.rng.below(4) {
                let b = self.rng.next() as u8;
                self.out.push(b);
            }
        }
        match self.core1.take() {
            // The cores share the UART byte by byte, not frame by frame.
            Some(other) => {
                for i in 0..frame.len().max(other.len()) {
                    self.out.extend(frame.get(i));
                    self.out.extend(other.get(i));
                }
            }
            None => self.out.extend_from_slice(&frame),
        }
        Ok(())
    }

    /// Send a report from the second core (Hiwonder, debug prints).
    fn send_core1(&mut self, report: &Report<'_>) -> Result<(), EncodeError> {
        if !self.interleaved && self.now >= 6000 {
            self.interleaved = true;
            self.core1 = Some(report.to_buf()?.to_vec());
            return Ok(());
        }
        self.out.extend_from_slice(&report.to_buf()?);
        Ok(())
    }

    fn execute(&mut self, c: &Command<'_>) -> Result<(), EncodeError> {
        type R<'a> = Report<'a>;
        match *c {
            Command::GetFirmwareVersion => self.send(&R::FirmwareVersion { major: 1, minor: 3 }),
            Command::FeatureCheck { msg_type } => {
                let extras: &[u8] = match msg_type {
                    1 => &[30, 12, 14, 5, 26, 27, 28, 29, 30],
                    5 => &[1, 3],
                    7 => &[12],
                    10 => &[2],
                    13 => &[4],
                    30 => &[4, 2, 1],
                    _ => &[],
                };
                self.send(&R::Feature {
                    msg_type,
                    supported: msg_type < 39,
                    extras,
                })
            }
            Command::SensorNew(SensorNew::Check { sensor_type }) => {
                let supported = SensorType::from_u8(sensor_type)
                    .is_some_and(|t| !matches!(t, SensorType::Gps | SensorType::Adxl345));
                self.send(&R::SensorSupported {
                    sensor_type,
                    supported,
                })
            }
            Command::SensorNew(SensorNew::Add {
                sensor_num,
                sensor_type,
                ..
            }) => {
                self.sensors.push((sensor_num, sensor_type));
                Ok(())
            }
            Command::ModuleNew(ModuleNew::Check { module_type }) => {
                self.send(&R::ModuleSupported {
                    module_type,
                    supported: ModuleType::from_u8(module_type).is_some(),
                })
            }
            Command::ModuleNew(ModuleNew::Add {
                init: ModuleInit::HiwonderServo { bus_ids, .. },
                ..
            }) => {
                let servo = Servo {
                    from: 12000.0,
                    to: 12000.0,
                    start_ms: 0,
                    time_ms: 0,
                    reported: None,
                };
                self.servos = vec![servo; bus_ids.len()];
                // The second core starts the bus and says so.
                self.send_core1(&R::Debug { id: 30, value: 1 })
            }
            Command::ModuleData {
                module_num: 0,
                data,
            } => {
                if let Ok(HiwonderCommand::SetAngle(moves)) = HiwonderCommand::parse(data) {
                    for m in moves.iter() {
                        let now = self.now;
                        if let Some(servo) = self.servos.get_mut(usize::from(m.idx)) {
                            *servo = Servo {
                                from: servo.at(now),
                                to: f64::from(m.centideg),
                                start_ms: now,
                                time_ms: u32::from(m.time_ms),
                                reported: servo.reported,
                            };
                        }
                    }
                }
                Ok(())
            }
            Command::Ping { counter } => {
                let boot_id = match self.boot_id {
                    Some(id) => id,
                    None => {
                        let id = self.rng.below(100) as u8;
                        self.boot_id = Some(id);
                        id
                    }
                };
                self.send(&R::Pong { counter, boot_id })
            }
            Command::GetUniqueId => self.send(&R::UniqueId {
                id: [0xe6, 0x61, 0x41, 0x04, 0x03, 0x3b, 0, 0],
            }),
            Command::GetId => self.send(&R::Id { id: 0xff }),
            Command::SetPinMode {
                pin,
                mode: PinMode::DigitalInput { report: true, .. },
            } => {
                self.digital.push((pin, None));
                Ok(())
            }
            Command::SetPinMode {
                pin,
                mode:
                    PinMode::AnalogInput {
                        differential,
                        report: true,
                    },
            } => {
                self.analog.push((pin, differential.max(1), None));
                Ok(())
            }
            Command::SonarNew { trig, echo } => {
                self.sonar = Some((trig, echo, None));
                Ok(())
            }
            Command::EncoderNew { pin_a, .. } => {
                self.encoder = Some(pin_a);
                Ok(())
            }
            // Outputs, I2C set-up and the PWM expander send nothing back.
            _ => Ok(()),
        }
    }

    /// What the world looks like to the inputs at `t` ms.
    fn digital_level(pin: u8, t: u32) -> bool {
        let pressed = match pin {
            // A button, pressed twice.
            10 => (5300..5700).contains(&t) || (7200..7400).contains(&t),
            // A bumper, hit once.
            _ => (6150..6350).contains(&t),
        };
        // Pulled up: pressed reads low.
        !pressed
    }

    fn scan(&mut self) -> Result<(), EncodeError> {
        type R<'a> = Report<'a>;
        let t = self.now;
        for i in 0..self.digital.len() {
            let (pin, last) = self.digital[i];
            let high = Self::digital_level(pin, t);
            if last != Some(high) {
                self.digital[i].1 = Some(high);
                self.send(&R::Digital { pin, value: high })?;
            }
        }
        for i in 0..self.analog.len() {
            let (pin, differential, last) = self.analog[i];
            let mean = match pin {
                // A potentiometer turned slowly, then left alone.
                26 => 1200.0 + 0.25 * f64::from(t.min(7000).saturating_sub(4600)),
                // A battery divider.
                _ => 2890.0,
            };
            let value = (mean + self.rng.noise(2.0)).round().clamp(0.0, 4095.0) as u16;
            if last.map_or(true, |l| l.abs_diff(value) >= differential) {
                self.analog[i].2 = Some(value);
                self.send(&R::Analog { pin, value })?;
            }
        }
        if let Some((trig, echo, last)) = self.sonar {
            // A wall approaching from 1.2 m; now and then no echo in time.
            let cm = if self.rng.chance(80) {
                SONAR_OUT_OF_RANGE
            } else {
                let d = 120.0 - 0.02 * f64::from(t.saturating_sub(4600));
                (d + self.rng.noise(0.8)).round() as u16
            };
            if last != Some(cm) {
                self.sonar = Some((trig, echo, Some(cm)));
                self.send(&R::Sonar(Sonar::WithEcho { trig, echo, cm }))?;
            }
        }
        if let Some(pin) = self.encoder {
            let speed = match t {
                ..6500 => 30.0,
                6500..7300 => -18.0,
                _ => 0.0,
            };
            let steps = if speed == 0.0 {
                0
            } else {
                (speed + self.rng.noise(1.5)).round() as i8
            };
            if steps != 0 {
                self.send(&R::Encoder { pin, steps })?;
            }
        }
        let moving = self.servos.iter().any(|s| t < s.start_ms + s.time_ms);
        for i in 0..self.sensors.len() {
            let (sensor_num, sensor_type) = self.sensors[i];
            let reading = match sensor_type {
                // At most every 200 ms.
                SensorType::Ina226 if t % 200 == 0 => {
                    let since = f64::from(t.saturating_sub(4600));
                    let volts = 12.3 - 0.000_05 * since + self.rng.noise(0.004);
                    let mut amps = 0.31 + self.rng.noise(0.01);
                    if moving {
                        amps += 0.45;
                    }
                    if t < 7300 {
                        amps += 0.6;
                    }
                    SensorReading::Ina226 {
                        volts: volts as f32,
                        amps: amps as f32,
                    }
                }
                SensorType::Vl53l0x => SensorReading::Vl53l0x {
                    mm: (410.0 + self.rng.noise(3.0)).round() as u16,
                },
                _ => continue,
            };
            self.send(&R::Sensor {
                sensor_num,
                reading,
            })?;
        }
        // Servo positions: the changed ones, and each at least once a second.
        let mut raw = Vec::new();
        for (idx, servo) in self.servos.iter_mut().enumerate() {
            let centideg = servo.read(t);
            let due = servo
                .reported
                .map_or(true, |(last, at)| last != centideg || t >= at + 1000);
            if due {
                servo.reported = Some((centideg, t));
                raw.push(idx as u8);
                raw.extend_from_slice(&centideg.to_be_bytes());
            }
        }
        if !raw.is_empty() {
            let report = ModuleReport::HiwonderPositions(ServoPositions::from_raw(&raw[..]));
            self.send_core1(&R::Module {
                module_num: 0,
                report,
            })?;
        }
        Ok(())
    }
}
