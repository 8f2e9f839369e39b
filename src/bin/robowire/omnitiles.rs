//! `robowire decode omnitiles` and `robowire encode omnitiles`.

use crate::driver::{self, DecodeCommon, Decoded, EncodeCommon, Output, Printer, Protocol};
use crate::input::{hex_line, ByteSource, HexBytes, Input, Lines, RawBytes};
use crate::json::{read_f32, read_int, Fields, JsonLine};
use crate::Failure;
use clap::{Args, ValueEnum};
use robowire::omnitiles::{
    Command, DatagramDecoder, Decoder, Error, Framing, Imu, Layout, Layouts, Motor, Packet,
    Telemetry, NO_READING,
};
use robowire::FrameBuf;
use serde_json::Value;

/// The JSON schema, printed by `--help` after the options.
const DECODE_SCHEMA: &str = "\
Output: one JSON object per line, per frame, in input order:
  offset  byte offset of the frame's 0xA5 in the input (decoded bytes with --hex;
          with --datagrams, in the concatenation of all datagrams)
  len     frame length in bytes
  type    ping, m1_extend, m1_retract, m1_brake, m1_set_position, m2_extend,
          m2_retract, m2_brake, m2_set_position, base_velocity, base_brake,
          or telemetry
Command fields: speed (extend, retract: 0..255), position (set-position, the raw
  byte 0..255), vx, vy, omega (base_velocity: -128..127).
Telemetry fields: layout (pos7, uwb15, uwbtof17, spi45, ble53), m1_pos, m2_pos, and
  where the layout carries them uwb (array of 4), tof, imu (object ax, ay, az in
  m/s^2, gx, gy, gz in rad/s), m1_adcs (array of 4), m2_adcs (array of 2).
  A 0xFFFF reading (positions, UWB, ToF) is null; a field the layout does not
  carry is absent. IMU values are numbers that read back as the same f32;
  infinities are \"inf\"/\"-inf\" and a NaN is \"nan:0x7fc00000\" (its bits).
With --errors, rejected candidates are objects with offset and error (no type):
  {\"offset\":12,\"error\":\"checksum\",\"expected\":48,\"found\":47}
  {\"offset\":40,\"error\":\"unknown_id\",\"id\":97}
  {\"offset\":77,\"error\":\"unconfirmed\"}
  {\"offset\":90,\"error\":\"truncated\",\"len\":5}
At the end, one summary line goes to stderr (frames, bytes, bytes skipped,
checksum failures, other rejections).

Exit status: 0 on success, 2 on usage errors and invalid input (bad hex),
1 on I/O errors. A closed stdout pipe ends the run quietly.

Examples:
  robowire decode omnitiles tests/data/ble_telemetry.bin
  robowire decode omnitiles --from tile --layout spi45 tests/data/spi_telemetry.bin
  robowire decode omnitiles --datagrams tests/data/ble_notifications.hex
  echo 'a5 30 c8 f8' | robowire decode omnitiles --hex";

const ENCODE_SCHEMA: &str = "\
Input: JSON lines in the schema `robowire decode omnitiles` prints; offset and len
are ignored, unknown fields are errors. Blank lines and diagnostic events (objects
with error and no type) are skipped. A telemetry line must carry exactly the
fields of its layout. A malformed line or out-of-range value is reported with its
line number and nothing is written for it; the other lines are still encoded and
the exit status is 2.

Examples:
  robowire decode omnitiles capture.bin | robowire encode omnitiles > same-frames.bin
  echo '{\"type\":\"m1_extend\",\"speed\":200}' | robowire encode omnitiles --hex";

/// Which side's frames to accept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Side {
    /// Telemetry only (bytes a tile sent).
    Tile,
    /// Commands only (bytes a host sent).
    Host,
    /// Commands and telemetry.
    Any,
}

/// A telemetry layout name on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LayoutArg {
    /// 7 bytes: positions.
    #[value(name = "pos7")]
    Pos7,
    /// 15 bytes: positions, four UWB ranges.
    #[value(name = "uwb15")]
    Uwb15,
    /// 17 bytes: positions, UWB, ToF.
    #[value(name = "uwbtof17")]
    UwbTof17,
    /// 53 bytes: the BLE notification of current firmware.
    #[value(name = "ble53")]
    Ble53,
    /// 45 bytes: the STM32 to nRF SPI frame.
    #[value(name = "spi45")]
    Spi45,
    /// The four documented layouts: pos7, uwb15, uwbtof17, ble53.
    #[value(name = "auto")]
    Auto,
}

impl LayoutArg {
    fn layouts(self) -> Layouts {
        match self {
            LayoutArg::Pos7 => Layouts::only(Layout::Pos7),
            LayoutArg::Uwb15 => Layouts::only(Layout::Uwb15),
            LayoutArg::UwbTof17 => Layouts::only(Layout::UwbTof17),
            LayoutArg::Ble53 => Layouts::only(Layout::Ble53),
            LayoutArg::Spi45 => Layouts::only(Layout::Spi45),
            LayoutArg::Auto => Layouts::DOCUMENTED,
        }
    }
}

/// `robowire decode omnitiles`.
#[derive(Debug, Args)]
#[command(after_long_help = DECODE_SCHEMA)]
pub struct DecodeArgs {
    /// Accept telemetry (tile), commands (host) or both (any).
    #[arg(long, value_enum, display_order = 1, default_value_t = Side::Any)]
    pub from: Side,
    /// Telemetry layouts to accept, comma-separated [default: auto].
    #[arg(
        long,
        value_enum,
        value_name = "L[,L...]",
        value_delimiter = ',',
        display_order = 2
    )]
    pub layout: Vec<LayoutArg>,
    /// Read hex text where each line is one datagram (one BLE notification,
    /// one write, one SPI buffer) and decode each with the datagram decoder
    /// (implies --hex; not with --chunk).
    #[arg(long, conflicts_with = "chunk", display_order = 5)]
    pub datagrams: bool,
    /// The options every decode shares.
    #[command(flatten)]
    pub common: DecodeCommon,
}

/// `robowire encode omnitiles`.
#[derive(Debug, Args)]
#[command(after_long_help = ENCODE_SCHEMA)]
pub struct EncodeArgs {
    /// The options every encode shares.
    #[command(flatten)]
    pub common: EncodeCommon,
}

impl DecodeArgs {
    /// The framing the options ask for.
    fn framing(&self) -> Result<Framing, Failure> {
        let layouts = if self.layout.is_empty() {
            Layouts::DOCUMENTED
        } else {
            self.layout
                .iter()
                .flat_map(|l| l.layouts().iter())
                .collect()
        };
        Ok(match self.from {
            Side::Tile => Framing::telemetry(layouts),
            Side::Any => Framing::any(layouts),
            Side::Host if self.layout.is_empty() => Framing::commands(),
            Side::Host => {
                return Err(Failure::Usage(
                    "--layout selects telemetry layouts, which --from host does not accept"
                        .to_owned(),
                ))
            }
        })
    }
}

/// Run `decode omnitiles`.
pub fn decode(args: &DecodeArgs, out: &mut Output) -> Result<Decoded, Failure> {
    let framing = args.framing()?;
    let input = Input::open(args.common.input.as_deref())?;
    let mut printer = Printer::new(out, args.common.errors);
    if args.datagrams {
        return decode_datagrams(framing, input, &mut printer);
    }
    let mut source: Box<dyn ByteSource> = if args.common.hex {
        Box::new(HexBytes::new(input))
    } else {
        Box::new(RawBytes(input))
    };
    let chunk = args.common.chunk as usize;
    driver::decode_stream::<OmniTiles, { robowire::omnitiles::BUFFER_LEN }>(
        Decoder::new(framing),
        source.as_mut(),
        chunk,
        &mut printer,
    )
}

/// One datagram per line of hex. A line that is not valid hex is reported and
/// skipped; the run goes on, and [`Decoded::failure`] then says how many
/// lines were skipped.
fn decode_datagrams(
    framing: Framing,
    input: Input,
    printer: &mut Printer<'_>,
) -> Result<Decoded, Failure> {
    let mut decoder = DatagramDecoder::new(framing);
    let mut lines = Lines::new(input);
    let mut datagram = Vec::new();
    let mut bad = 0u64;
    loop {
        // Flush before a read that may wait, so frames go out as lines arrive.
        if !lines.has_buffered() {
            printer.flush()?;
        }
        let (number, line) = match lines.next_line() {
            Ok(Some(line)) => line,
            Ok(None) => break,
            Err(failure) => {
                return Ok(Decoded {
                    stats: decoder.stats(),
                    failure: Some(failure),
                })
            }
        };
        if let Err(message) = hex_line(line, &mut datagram) {
            eprintln!("robowire: {}: line {number}: {message}", lines.name());
            bad += 1;
            continue;
        }
        if datagram.is_empty() {
            continue;
        }
        for event in decoder.decode(&datagram) {
            printer.event::<OmniTiles>(event)?;
        }
    }
    let failure = (bad > 0).then(|| {
        let s = if bad == 1 { "" } else { "s" };
        Failure::Reported(format!("{bad} invalid datagram line{s}"))
    });
    Ok(Decoded {
        stats: decoder.stats(),
        failure,
    })
}

/// Run `encode omnitiles`.
pub fn encode(args: &EncodeArgs, out: &mut Output) -> Result<(), Failure> {
    let input = Input::open(args.common.input.as_deref())?;
    driver::encode_lines::<OmniTiles>(input, args.common.hex, out)
}

/// The OmniTiles protocol as the tool sees it.
pub struct OmniTiles;

impl Protocol for OmniTiles {
    type Framing = Framing;

    fn describe(packet: &Packet, line: &mut JsonLine) {
        match packet {
            Packet::Command(command) => describe_command(command, line),
            Packet::Telemetry(telemetry) => describe_telemetry(telemetry, line),
        }
    }

    fn describe_error(error: &Error, line: &mut JsonLine) {
        match *error {
            Error::Checksum { expected, found } => {
                line.field("error", "checksum");
                line.field("expected", expected);
                line.field("found", found);
            }
            Error::UnknownId { id } => {
                line.field("error", "unknown_id");
                line.field("id", id);
            }
            Error::Unconfirmed => line.field("error", "unconfirmed"),
            Error::Truncated { len } => {
                line.field("error", "truncated");
                line.field("len", len);
            }
            // A rejection this tool does not know yet: its message.
            ref other => {
                line.field("error", "other");
                line.field("message", other.to_string().as_str());
            }
        }
    }

    fn encode(mut fields: Fields<'_>, frame: &mut Vec<u8>) -> Result<(), String> {
        let kind = fields.string("type")?;
        let packet = read_packet(kind, &mut fields)?;
        fields.finish(&format!("for type {kind}"))?;
        let bytes = FrameBuf::<{ Packet::MAX_LEN }>::encode(&packet).map_err(|e| e.to_string())?;
        frame.extend_from_slice(&bytes);
        Ok(())
    }
}

fn describe_command(command: &Command, line: &mut JsonLine) {
    line.field("type", command.name());
    match *command {
        Command::Extend { speed, .. } | Command::Retract { speed, .. } => {
            line.field("speed", speed);
        }
        Command::SetPosition { position, .. } => line.field("position", position),
        Command::BaseVelocity { vx, vy, omega } => {
            line.field("vx", vx);
            line.field("vy", vy);
            line.field("omega", omega);
        }
        Command::Ping | Command::Brake { .. } | Command::BaseBrake => {}
    }
}

fn describe_telemetry(t: &Telemetry, line: &mut JsonLine) {
    line.field("type", "telemetry");
    line.field("layout", t.layout.name());
    line.field("m1_pos", t.m1_pos);
    line.field("m2_pos", t.m2_pos);
    if let Some(uwb) = t.uwb {
        line.array("uwb", uwb);
    }
    if let Some(tof) = t.tof {
        line.field("tof", tof);
    }
    if let Some(imu) = t.imu {
        line.object("imu", |o| {
            for (name, value) in IMU_FIELDS.into_iter().zip(imu.to_array()) {
                o.field(name, value);
            }
        });
    }
    if let Some(adcs) = t.m1_adcs {
        line.array("m1_adcs", adcs);
    }
    if let Some(adcs) = t.m2_adcs {
        line.array("m2_adcs", adcs);
    }
}

/// The IMU object's members, in wire order.
const IMU_FIELDS: [&str; 6] = ["ax", "ay", "az", "gx", "gy", "gz"];

fn read_packet(kind: &str, fields: &mut Fields<'_>) -> Result<Packet, String> {
    use Motor::{M1, M2};
    let speed = |f: &mut Fields<'_>| f.int("speed", 0, 255).map(|v| v as u8);
    let position = |f: &mut Fields<'_>| f.int("position", 0, 255).map(|v| v as u8);
    let signed = |f: &mut Fields<'_>, key| f.int(key, -128, 127).map(|v| v as i8);
    let command = match kind {
        "ping" => Command::Ping,
        "m1_extend" => Command::Extend {
            motor: M1,
            speed: speed(fields)?,
        },
        "m1_retract" => Command::Retract {
            motor: M1,
            speed: speed(fields)?,
        },
        "m1_brake" => Command::Brake { motor: M1 },
        "m1_set_position" => Command::SetPosition {
            motor: M1,
            position: position(fields)?,
        },
        "m2_extend" => Command::Extend {
            motor: M2,
            speed: speed(fields)?,
        },
        "m2_retract" => Command::Retract {
            motor: M2,
            speed: speed(fields)?,
        },
        "m2_brake" => Command::Brake { motor: M2 },
        "m2_set_position" => Command::SetPosition {
            motor: M2,
            position: position(fields)?,
        },
        "base_velocity" => Command::BaseVelocity {
            vx: signed(fields, "vx")?,
            vy: signed(fields, "vy")?,
            omega: signed(fields, "omega")?,
        },
        "base_brake" => Command::BaseBrake,
        "telemetry" => return read_telemetry(fields).map(Packet::Telemetry),
        other => return Err(format!("unknown type `{other}`")),
    };
    Ok(Packet::Command(command))
}

/// A reading: `null` for no reading (`0xFFFF` on the wire) or 0..=65534.
fn read_reading(value: &Value) -> Result<Option<u16>, String> {
    if value.is_null() {
        return Ok(None);
    }
    read_int(value, 0, i64::from(NO_READING) - 1)
        .map(|v| Some(v as u16))
        .map_err(|_| {
            format!(
                "must be null or an integer 0..=65534 (0xFFFF, no reading, is written null), \
                 found {value}"
            )
        })
}

fn read_u16(value: &Value) -> Result<u16, String> {
    read_int(value, 0, 65535).map(|v| v as u16)
}

fn read_telemetry(fields: &mut Fields<'_>) -> Result<Telemetry, String> {
    let name = fields.string("layout")?;
    let layout = Layout::from_name(name).ok_or_else(|| {
        format!("unknown layout `{name}` (expected pos7, uwb15, uwbtof17, spi45 or ble53)")
    })?;
    // A field group must be present exactly when the layout carries it.
    let carried = |fields: &Fields<'_>, key: &str, carries: bool| match (carries, fields.has(key)) {
        (true, true) => Ok(true),
        (false, false) => Ok(false),
        (true, false) => Err(format!("missing field `{key}` (layout {name} carries it)")),
        (false, true) => Err(format!("layout {name} does not carry `{key}`")),
    };
    let reading = |fields: &mut Fields<'_>, key: &str| {
        read_reading(fields.value(key)?).map_err(|e| format!("field `{key}` {e}"))
    };
    let mut t = Telemetry::empty(layout);
    t.m1_pos = reading(fields, "m1_pos")?;
    t.m2_pos = reading(fields, "m2_pos")?;
    if carried(fields, "uwb", layout.has_uwb())? {
        t.uwb = Some(fields.array("uwb", read_reading)?);
    }
    if carried(fields, "tof", layout.has_tof())? {
        t.tof = Some(reading(fields, "tof")?);
    }
    let imu_and_adcs = layout.has_imu_and_adcs();
    if carried(fields, "imu", imu_and_adcs)? {
        let mut imu = fields.object("imu")?;
        let mut values = [0f32; 6];
        for (value, key) in values.iter_mut().zip(IMU_FIELDS) {
            let raw = imu
                .value(key)
                .map_err(|_| format!("missing field `imu.{key}`"))?;
            *value = read_f32(raw).map_err(|e| format!("field `imu.{key}` {e}"))?;
        }
        imu.finish_nested("in `imu`")?;
        t.imu = Some(Imu::from_array(values));
    }
    if carried(fields, "m1_adcs", imu_and_adcs)? {
        t.m1_adcs = Some(fields.array("m1_adcs", read_u16)?);
    }
    if carried(fields, "m2_adcs", imu_and_adcs)? {
        t.m2_adcs = Some(fields.array("m2_adcs", read_u16)?);
    }
    Ok(t)
}
