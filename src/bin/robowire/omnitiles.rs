//! `robowire decode omnitiles` and `robowire encode omnitiles`: the options,
//! the decoder they choose and the help text. Messages and rejections print
//! and read through the library's serde form.

use crate::driver::{self, DecodeCommon, Decoded, EncodeCommon, Output, Peer, Printer, Schema};
use crate::input::{hex_line, Input, Lines};
use crate::suspicion::SpiCheck;
use crate::Failure;
use clap::{Args, ValueEnum};
use robowire::omnitiles::{
    self, Both, Command, DatagramDecoder, Device, FirmwareParser, Framing, Host, Layout, Layouts,
    Message,
};
use robowire::units::FieldTable;
use robowire::{FrameBuf, StreamDecoder};
use serde::Serialize;

/// The JSON schema, printed by `--help` after the options.
fn decode_help() -> String {
    let footer = driver::DECODE_FOOTER;
    let types = driver::wrap(driver::listed(&Message::NAMES, "or ", ""), 10, 10, 78);
    let layouts = Layout::ALL.map(Layout::name).join(", ");
    format!(
        "\
Output: one JSON object per line, per frame, in input order:
  offset  byte offset of the frame's 0xA5 in the input (decoded bytes with --hex;
          with --datagrams, in the concatenation of all datagrams)
  len     frame length in bytes
  type    {types}
Command fields: speed (extend, retract: 0..255), position (set-position, the raw
  byte 0..255), vx, vy, omega (base_velocity: -128..127).
Telemetry fields: layout ({layouts}), m1_pos, m2_pos, and
  where the layout carries them uwb (array of 4), tof, imu (object ax, ay, az in
  m/s^2, gx, gy, gz in rad/s), m1_adcs (array of 4), m2_adcs (array of 2).
  A 0xFFFF reading (positions, UWB, ToF) is null; a field the layout does not
  carry is absent. IMU values are numbers that read back as the same f32;
  infinities are \"inf\"/\"-inf\" and a NaN is \"nan:0x7fc00000\" (its bits).
With --errors, rejected candidates are objects with offset and error (no type):
  {{\"offset\":12,\"error\":\"checksum\",\"expected\":48,\"found\":47}}
  {{\"offset\":40,\"error\":\"unknown_id\",\"id\":97}}
  {{\"offset\":77,\"error\":\"unconfirmed\"}}
  {{\"offset\":90,\"error\":\"truncated\",\"len\":5}}
  {{\"offset\":95,\"error\":\"superseded\",\"len\":7}}
With --as-firmware (--from host only), frames are the commands the tile's own
parser executes and rejections the candidates it consumes without executing
them (every byte of those counts as skipped).
At the end, one summary line goes to stderr (frames, bytes, bytes skipped,
checksum failures, other rejections).

{footer}

Examples:
  robowire decode omnitiles tests/data/ble_telemetry.bin
  robowire decode omnitiles --from tile --layout spi45 tests/data/spi_telemetry.bin
  robowire decode omnitiles --datagrams tests/data/ble_notifications.hex
  echo 'a5 30 c8 f8' | robowire decode omnitiles --hex
  robowire decode omnitiles --from host --as-firmware tests/data/host_commands.bin"
    )
}

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

/// `robowire decode omnitiles`.
#[derive(Debug, Args)]
#[command(after_long_help = decode_help())]
pub struct DecodeArgs {
    /// Accept telemetry (tile), commands (host) or both (any).
    #[arg(long, value_enum, display_order = 1, default_value_t = Side::Any)]
    pub from: Side,
    /// Telemetry layouts to accept, comma-separated: pos7, uwb15, uwbtof17,
    /// ble53, spi45, or auto for the four documented ones [default: auto].
    #[arg(long, value_name = "L[,L...]", display_order = 2)]
    pub layout: Vec<Layouts>,
    /// Read hex text where each line is one datagram (one BLE notification,
    /// one write, one SPI buffer) and decode each with the datagram decoder
    /// (implies --hex; not with --chunk).
    #[arg(long, conflicts_with_all = ["chunk", "port"], display_order = 5)]
    pub datagrams: bool,
    /// Parse commands as the tile's own firmware does, to see what a tile
    /// executed (only with --from host; not with --datagrams).
    ///
    /// No rescan after a rejected candidate, payload bytes taken blindly, an
    /// 0xA5 in the id slot consumed as an unknown id: prints the commands a
    /// tile executed rather than every command the host sent.
    #[arg(long, conflicts_with_all = ["datagrams", "port", "timestamps", "save"], display_order = 5)]
    pub as_firmware: bool,
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
    /// Whether zero-padded SPI buffers would be misread: telemetry decoded
    /// without `spi45` (as a stream or as datagrams: the padding is skipped
    /// either way and a few buffers read as false short frames). With the
    /// default layouts that is refused (the user did not choose them), with
    /// layouts the user named a warning.
    pub fn spi_check(&self) -> SpiCheck {
        let spi45 = self.layout.iter().any(|set| set.contains(Layout::Spi45));
        if self.from == Side::Host || spi45 {
            SpiCheck::Off
        } else if self.layout.is_empty() {
            SpiCheck::Refuse
        } else {
            SpiCheck::Warn
        }
    }
}

/// Run `decode omnitiles` with the decoder the options ask for.
pub fn decode(args: &DecodeArgs, out: &mut Output) -> Result<Decoded, Failure> {
    let layouts = match args.layout.as_slice() {
        [] => Layouts::DOCUMENTED,
        sets => sets.iter().flat_map(|set| set.iter()).collect(),
    };
    if args.as_firmware && args.from != Side::Host {
        return Err(Failure::Usage(
            "--as-firmware reproduces the tile's command parser: use it with --from host"
                .to_owned(),
        ));
    }
    match args.from {
        Side::Tile => run(args, Framing::<Host>::new().with_layouts(layouts), out),
        Side::Any => run(args, Framing::<Both>::new().with_layouts(layouts), out),
        Side::Host if args.layout.is_empty() && args.as_firmware => run_firmware(args, out),
        Side::Host if args.layout.is_empty() => run(args, Framing::<Device>::new(), out),
        Side::Host => Err(Failure::Usage(
            "--layout selects telemetry layouts, which --from host does not accept".to_owned(),
        )),
    }
}

fn run<S>(args: &DecodeArgs, framing: Framing<S>, out: &mut Output) -> Result<Decoded, Failure>
where
    S: omnitiles::Side<Message: Serialize>,
{
    // Nothing is printed before the input is known not to be SPI buffers.
    let hold = args.spi_check() == SpiCheck::Refuse && !args.common.allow_noise;
    if args.datagrams {
        let input = Input::open(args.common.input.as_deref())?;
        if hold {
            out.hold_for_spi();
        }
        let mut printer = Printer::new(out, &args.common, OmniTiles, writes(args.from))?;
        return decode_datagrams(DatagramDecoder::new(framing), input, &mut printer);
    }
    let mut source = args.common.source()?;
    if hold {
        out.hold_for_spi();
    }
    let mut printer = Printer::new(out, &args.common, OmniTiles, writes(args.from))?;
    // Every side's buffer is the same size.
    let decoder = StreamDecoder::<_, { omnitiles::BOTH_BUFFER }>::new(framing);
    let chunk = args.common.chunk as usize;
    driver::decode_stream(decoder, source.as_mut(), chunk, &mut printer)
}

/// `--as-firmware`: the tile's own command parser over the whole input,
/// `--chunk` bytes at a time (its events never depend on the chunking).
fn run_firmware(args: &DecodeArgs, out: &mut Output) -> Result<Decoded, Failure> {
    let mut source = args.common.source()?;
    let mut printer = Printer::new(out, &args.common, OmniTiles, writes(args.from))?;
    let mut parser = FirmwareParser::new();
    let mut buf = vec![0u8; args.common.chunk as usize];
    loop {
        let n = match source.fill(&mut buf) {
            Ok(0) if source.ended() => break,
            Ok(0) => {
                // A pause on a live port: write out what is held.
                printer.flush()?;
                continue;
            }
            Ok(n) => n,
            Err(failure) => {
                return Ok(Decoded {
                    stats: parser.stats(),
                    failure: Some(failure),
                })
            }
        };
        printer.observe(&buf[..n])?;
        for event in parser.feed(&buf[..n]) {
            printer.event(event)?;
        }
        // Before a read that may wait, show what has been decoded so far.
        if source.may_wait() {
            printer.flush()?;
        }
    }
    if let Some(rejected) = parser.finish() {
        printer.event::<Command, _>(Err(rejected))?;
    }
    Ok(Decoded {
        stats: parser.stats(),
        failure: None,
    })
}

/// One datagram per line of hex. A line that is not valid hex is reported and
/// skipped; the run goes on, and [`Decoded::failure`] then says how many
/// lines were skipped.
fn decode_datagrams<S>(
    mut decoder: DatagramDecoder<S>,
    input: Input,
    printer: &mut Printer<'_>,
) -> Result<Decoded, Failure>
where
    S: omnitiles::Side<Message: Serialize>,
{
    let mut lines = Lines::new(input).quiet(printer.judging());
    let mut datagram = Vec::new();
    let mut bad = 0u64;
    let mut decoded_any = false;
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
        if let Err(message) = hex_line(number, line, &mut datagram) {
            // Binary input is one mistake (the wrong option), not a line each.
            if !decoded_any && line.iter().any(|&b| is_binary(b)) {
                return Err(Failure::Invalid(format!(
                    "{}: line {number} is binary, not hex text: --datagrams reads one \
                     datagram per line of hex; decode raw bytes without --datagrams",
                    lines.name()
                )));
            }
            printer.warn(&format!("{}: {message}", lines.name()));
            bad += 1;
            continue;
        }
        if datagram.is_empty() {
            continue;
        }
        decoded_any = true;
        printer.observe(&datagram)?;
        for event in decoder.decode(&datagram) {
            printer.event(event)?;
        }
    }
    let bad = bad + lines.too_long();
    let failure = (bad > 0).then(|| {
        let s = if bad == 1 { "" } else { "s" };
        Failure::Reported(format!("{bad} invalid datagram line{s}"))
    });
    Ok(Decoded {
        stats: decoder.stats(),
        failure,
    })
}

/// A byte no line of hex text holds: a control character other than tab
/// and carriage return, DEL, or any byte over 0x7f.
fn is_binary(byte: u8) -> bool {
    (byte < 0x20 && byte != b'\t' && byte != b'\r') || byte >= 0x7f
}

/// Run `encode omnitiles`.
pub fn encode(args: &EncodeArgs, out: &mut Output) -> Result<(), Failure> {
    driver::encode_lines(&OmniTiles, &args.common, out)
}

/// The OmniTiles protocol as the tool sees it: a line is a [`Message`].
pub struct OmniTiles;

impl Schema for OmniTiles {
    type Line = Message;
    const FIELDS: &'static FieldTable = &robowire::omnitiles::FIELD_INFO;

    fn encode(&self, line: &Message, frame: &mut Vec<u8>) -> Result<(), String> {
        let bytes = FrameBuf::<{ Message::MAX_LEN }>::encode(line).map_err(|e| e.to_string())?;
        frame.extend_from_slice(&bytes);
        Ok(())
    }

    fn sent_by(&self, line: &Message) -> Option<Peer> {
        Some(match line {
            Message::Command(_) => Peer::Host,
            Message::Telemetry(_) => Peer::Device,
        })
    }
}

/// What a live decode of `from`'s bytes writes back: the other end's messages.
fn writes(from: Side) -> Peer {
    match from {
        Side::Host => Peer::Device,
        Side::Tile | Side::Any => Peer::Host,
    }
}
