//! A host that drives an OmniTiles tile over a serial port with tokio:
//! `robowire::io::tokio::OmniTilesCodec` turns the port into a stream of
//! telemetry and a sink of commands.
//!
//! ```sh
//! # A simulated tile on a pseudo-terminal pair (no hardware needed):
//! cargo run --example omnitiles_host --features tokio-util-07
//! # A real tile (or anything speaking OmniTiles) on a serial port:
//! cargo run --example omnitiles_host --features tokio-util-07 -- /dev/ttyACM0 115200
//! ```
//!
//! Without a port argument the example opens a pseudo-terminal pair with
//! `tokio_serial::SerialStream::pair()` (raw mode, so every byte value passes
//! through) and runs a simulated tile on one end: it obeys commands, moves
//! its actuators and streams 53-byte telemetry every 20 ms, with some line
//! noise and a corrupted frame now and then. The host on the other end runs
//! the same script either way: ping, extend M1 to 60 mm and brake, move M2 to
//! 50 mm, drive the base and brake it, then print the link statistics.

use std::error::Error;
use std::time::Duration;

use futures_util::{SinkExt, StreamExt};
use robowire::io::tokio::{OmniTilesDeviceCodec, OmniTilesHostCodec};
use robowire::omnitiles::{units, Command, Framing, Imu, Layout, Layouts, Motor, Telemetry};
use robowire::FrameBuf;
use tokio::io::{AsyncWriteExt, ReadHalf, WriteHalf};
use tokio_serial::{SerialPortBuilderExt, SerialStream};
use tokio_util::codec::{FramedRead, FramedWrite};

type Result<T> = std::result::Result<T, Box<dyn Error + Send + Sync>>;

#[tokio::main(flavor = "current_thread")]
async fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next() else {
        let (host_end, tile_end) = SerialStream::pair()?;
        println!("host: simulated tile on a pseudo-terminal pair");
        let tile = tokio::spawn(simulated_tile(tile_end));
        let result = host(host_end).await;
        if !tile.is_finished() {
            tile.abort();
        } else if let Ok(Err(e)) = tile.await {
            eprintln!("tile: {e}");
        }
        return result;
    };
    let baud = args.next().map_or(Ok(115_200), |b| b.parse())?;
    println!("host: opening {path} at {baud} baud");
    host(tokio_serial::new(path, baud).open_native_async()?).await
}

/// The host's view of the link: telemetry in, commands out.
struct Link {
    telemetry: FramedRead<ReadHalf<SerialStream>, OmniTilesHostCodec>,
    commands: FramedWrite<WriteHalf<SerialStream>, OmniTilesHostCodec>,
}

impl Link {
    async fn send(&mut self, command: Command) -> Result<()> {
        println!("host: -> {command:?}");
        self.commands.send(command).await?;
        Ok(())
    }

    /// Read telemetry until `done` holds for a frame (or give up).
    async fn until(&mut self, what: &str, done: impl Fn(&Telemetry) -> bool) -> Result<Telemetry> {
        let wait = async {
            while let Some(frame) = self.telemetry.next().await {
                let t = frame?.message;
                if done(&t) {
                    return Ok(t);
                }
            }
            Err("the tile closed the link".into())
        };
        match tokio::time::timeout(Duration::from_secs(5), wait).await {
            Ok(result) => result,
            Err(_) => Err(format!("no telemetry showing {what} within 5 s").into()),
        }
    }
}

fn mm(motor: Motor, raw: Option<u16>) -> f32 {
    raw.map_or(f32::NAN, |raw| units::adc_to_mm(motor, raw))
}

async fn host(port: SerialStream) -> Result<()> {
    let (rx, tx) = tokio::io::split(port);
    // A host accepts telemetry only; naming the one layout the tile sends
    // means every frame is emitted as soon as it is complete.
    let framing = Framing::new().with_layouts(Layouts::only(Layout::Ble53));
    let mut link = Link {
        telemetry: FramedRead::new(rx, OmniTilesHostCodec::new(framing)),
        commands: FramedWrite::new(tx, OmniTilesHostCodec::default()),
    };

    link.send(Command::Ping).await?;
    let t = link.until("a first frame", |_| true).await?;
    println!(
        "host: <- m1 {:.1} mm, m2 {:.1} mm, tof {:?}, imu {:?}",
        mm(Motor::M1, t.m1_pos),
        mm(Motor::M2, t.m2_pos),
        t.tof.flatten(),
        t.imu
    );

    link.send(Command::Extend {
        motor: Motor::M1,
        speed: 255,
    })
    .await?;
    let t = link
        .until("M1 past 60 mm", |t| mm(Motor::M1, t.m1_pos) >= 60.0)
        .await?;
    link.send(Command::Brake { motor: Motor::M1 }).await?;
    println!("host: <- m1 at {:.1} mm", mm(Motor::M1, t.m1_pos));

    let target = units::mm_to_position(Motor::M2, 50.0);
    link.send(Command::SetPosition {
        motor: Motor::M2,
        position: target,
    })
    .await?;
    let t = link
        .until("M2 at 50 mm", |t| {
            (mm(Motor::M2, t.m2_pos) - 50.0).abs() < 1.0
        })
        .await?;
    println!("host: <- m2 at {:.1} mm", mm(Motor::M2, t.m2_pos));

    link.send(Command::BaseVelocity {
        vx: units::duty_to_velocity(0.5),
        vy: 0,
        omega: units::duty_to_velocity(-0.25),
    })
    .await?;
    link.until("a frame", |_| true).await?;
    link.send(Command::BaseBrake).await?;

    let stats = link.telemetry.decoder().stats();
    println!(
        "host: link: {} frames, {} checksum failures, {} other rejections, {} of {} bytes skipped",
        stats.frames, stats.checksum_failures, stats.other_rejections, stats.skipped, stats.bytes
    );
    if let Some(rejected) = link.telemetry.decoder().last_rejected() {
        println!("host: last rejected: {rejected}");
    }
    Ok(())
}

/// A tile: obeys commands and streams 53-byte telemetry every 20 ms.
async fn simulated_tile(port: SerialStream) -> Result<()> {
    const TICK: Duration = Duration::from_millis(20);
    /// Raw position units per tick at full duty (about 100 mm/s on M1).
    const FULL_SPEED: f32 = 55.0;

    let (rx, tx) = tokio::io::split(port);
    let mut commands = FramedRead::new(rx, OmniTilesDeviceCodec::default());
    let mut telemetry = FramedWrite::new(tx, OmniTilesDeviceCodec::default());
    // Raw positions (0..=4095) and what each actuator is doing: a signed duty
    // fraction or a target position.
    let mut pos = [200.0f32, 300.0];
    let mut duty = [0.0f32; 2];
    let mut target: [Option<f32>; 2] = [None; 2];
    let mut ticks = tokio::time::interval(TICK);

    for n in 0u32.. {
        tokio::select! {
            command = commands.next() => {
                let Some(command) = command else { return Ok(()) };
                let command = command?.message;
                let (i, motor) = match command {
                    Command::Extend { motor, .. }
                    | Command::Retract { motor, .. }
                    | Command::Brake { motor }
                    | Command::SetPosition { motor, .. } => (motor as usize, motor),
                    _ => continue, // ping, base: nothing to simulate
                };
                target[i] = None;
                duty[i] = match command {
                    Command::Extend { speed, .. } => f32::from(units::speed_to_duty(speed)) / 50.0,
                    Command::Retract { speed, .. } => -f32::from(units::speed_to_duty(speed)) / 50.0,
                    Command::SetPosition { position, .. } => {
                        let mm = units::position_target_mm(motor, position);
                        target[i] = Some(mm / motor.stroke_mm() * 4095.0);
                        0.0
                    }
                    _ => 0.0,
                };
            }
            _ = ticks.tick() => {
                for i in 0..2 {
                    let step = match target[i] {
                        Some(t) => (t - pos[i]).clamp(-FULL_SPEED, FULL_SPEED),
                        None => duty[i] * FULL_SPEED,
                    };
                    pos[i] = (pos[i] + step).clamp(0.0, 4095.0);
                }
                let t = Telemetry {
                    m1_pos: Some(pos[0] as u16),
                    m2_pos: Some(pos[1] as u16),
                    uwb: Some([Some(1500), Some(2200), None, Some(900 + (n % 50) as u16)]),
                    tof: Some(Some(120)),
                    imu: Some(Imu::from_array([0.02, -0.01, 9.81, 0.0, 0.0, 0.001])),
                    m1_adcs: Some([pos[0] as u16; 4]),
                    m2_adcs: Some([pos[1] as u16; 2]),
                    ..Telemetry::empty(Layout::Ble53)
                };
                match n % 25 {
                    // Line noise between frames, with a false start.
                    7 => telemetry.get_mut().write_all(&[0x00, 0xa5, 0x13, 0xff]).await?,
                    // A frame hit by noise: a checksum error at the host.
                    19 => {
                        let mut bad = FrameBuf::<53>::encode(&t)?.to_vec();
                        bad[20] ^= 0x04;
                        telemetry.get_mut().write_all(&bad).await?;
                    }
                    _ => {}
                }
                telemetry.send(t).await?;
            }
        }
    }
    Ok(())
}
