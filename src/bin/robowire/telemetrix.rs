//! `robowire decode telemetrix` and `robowire encode telemetrix`: options,
//! the choice of decoder, and the help text. The messages, their JSON form
//! and the `--from any` attribution are the library's
//! ([`robowire::telemetrix`]).

use crate::driver::{self, DecodeCommon, Decoded, EncodeCommon, Output, Peer, Printer, Schema};
use crate::input::ByteSource;
use crate::Failure;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, ValueEnum};
use robowire::stream::{OwnedFrame, StreamDecoder};
use robowire::telemetrix::{
    Both, CaptureContext, Command, Device, Dialect, Framing, Host, MessageBuf, ModifyReporting,
    ModuleType, PinMode, Report, SensorType, Side, BOTH_BUFFER,
};
use robowire::units::FieldTable;

/// `names` as a list ending in a full stop, wrapped at 86 columns, every
/// line indented by `indent`.
fn name_list(names: &[&str], indent: &str) -> String {
    let words =
        driver::listed(names, "", ".").map(|word| match word.strip_prefix("feature_request") {
            Some(rest) => format!("feature_request (id 37){rest}"),
            None => word,
        });
    format!(
        "{indent}{}",
        driver::wrap(words, indent.len(), indent.len(), 86)
    )
}

/// `text` wrapped at 80 columns, indented by 2 and then 4 spaces.
fn paragraph(text: &str) -> String {
    format!("  {}", driver::wrap(text.split(' '), 2, 4, 80))
}

/// The JSON schema and the `--from any` rule, printed by `--help` after the
/// options; the type names come from the library.
fn decode_help() -> String {
    format!(
        "\
Output: one JSON object per line, per frame, in input order:
  offset  byte offset of the frame's LEN byte in the input (decoded bytes with --hex)
  len     frame length in bytes (LEN + 1)
  type    the message, in snake case after the spec's names. Commands (host):
{commands}
          Reports (pico; upstream's report 8 is i2c_write_failed, unknown_report
          (id, payload) only with --lenient):
{reports}
Then the fields, named after the spec: numbers as on the wire (signed where the
spec says so), byte strings as arrays of numbers (data, extras, cs_pins, ...),
levels (value, level, cpol, cpha, active_level) as 0/1, flags (report_enable,
auto_show, supported, ok, enabled, pulls.up/down) as true/false. Byte counts
that a byte array already gives are not repeated; read lengths are `n`. A frame
a real peer sends that robowire would not send (a level byte 2, mirte13's digital
modify_reporting, ...) is decoded as the firmware reads it and ends with \"quirk\":
its name, after the frame's bytes the message does not hold (a level byte as value,
an encoder type 3 as kind, PWM trailing bytes as trailing); encode writes such a line
back to exactly that frame, and refuses the frame from a line without the marker.
{modes}
  sonar_distance (mirte13): trig, echo (LEN 5 form only), cm: a number or
    \"no_echo\", \"out_of_range\", \"stale\"; mirte12: trig, m, cm; upstream11:
    trig, cm, hundredths. i2c_read and i2c_write carry msg_id except in
    upstream11; i2c_read_report carries msg_id, or addr in upstream11.
{types}
  sensor_report: sensor_num, sensor_type, reading {{typed fields; floats read back
    as the same f32, \"inf\"/\"-inf\"/\"nan:0x...\" otherwise}}.
  module_report: module_num, module_type, message {{subtype, fields}}.
  sensor_new, module_new: subtype check or add; module_new add has init {{...}};
    mirte12's sensor_new is an add whose settings are the 0 to 6 bytes sent.
  module_data: module_num, then module_type and message {{subtype, fields}} when an
    earlier module_new add (or module_report) in the input named the module's
    type and the bytes parse as its data; otherwise data [bytes].

--from any: a frame is accepted if it is a valid command or a valid report. Some
frames are both (of ids 0, 2, 3, 8, 13, plus 34, 36 in mirte13 and 12 in
upstream11: a digital write is byte for byte a digital report). Such a frame is attributed to the direction of the last frame
that was valid one way only (to reports until there is one), and carries
\"also\": the other reading's type. A frame of unknown id in both directions is corruption; with
--lenient it is an unknown_report only if no command reads it. Use --from host or
--from pico when the capture holds one direction: it is exact, and it rejects
more corruption.

With --errors, rejected candidates are objects with offset and error (no type):
  {{\"offset\":12,\"error\":\"unknown_id\",\"id\":97}}
  {{\"offset\":30,\"error\":\"bad_length\",\"id\":2,\"len_byte\":7}}
  {{\"offset\":41,\"error\":\"out_of_range\",\"id\":3,\"field\":\"value\"}}
  {{\"offset\":90,\"error\":\"truncated\",\"len\":2}}
len_byte is the frame's LEN byte; field names what the firmware never sends.
Every rejection costs one byte: decoding resumes at the next byte. At the end,
one summary line goes to stderr.

{footer}

Examples:
  robowire decode telemetrix --from pico tests/data/telemetrix_reports.bin
  robowire decode telemetrix --from host --hex tests/data/telemetrix_commands.hex
  echo '03 05 01 03' | robowire decode telemetrix --hex",
        footer = driver::DECODE_FOOTER,
        commands = name_list(Command::NAMES, "          "),
        reports = name_list(&Report::NAMES[..Report::NAMES.len() - 1], "          "),
        modes = paragraph(&format!(
            "set_pin_mode mode: {}; modify_reporting action: {}.",
            PinMode::NAMES.join(", "),
            ModifyReporting::NAMES.join(", ")
        )),
        types = paragraph(&format!(
            "sensor_type and module_type are names ({}; {}), or numbers where a check \
             names an unknown type.",
            SensorType::NAMES.join(", "),
            ModuleType::NAMES.join(", ")
        )),
    )
}

const ENCODE_SCHEMA: &str = "\
Input: JSON lines in the schema `robowire decode telemetrix` prints; offset, len
and also are ignored, unknown fields are errors. The type says the direction.
digital_write and digital_report also take `high` (true/false) for `value` in
this release. Blank lines and diagnostic events (objects with error and no type)
are skipped. Frames are encoded for --dialect (the one they were decoded with),
and the encoder refuses what the firmware would mishandle (unknown ids, LEN over
30, pins >= 30, counts over the spec's maxima). A line that carries \"quirk\" (a
real peer's frame, as decode marks it) is encoded to exactly that frame; without
the marker such a frame is refused, and the error names the quirk to add. A malformed line or out-of-range
value is reported with its line number and nothing is written for it; the other
lines are still encoded and the exit status is 2.

Examples:
  robowire decode telemetrix capture.bin | robowire encode telemetrix > same-frames.bin
  echo '{\"type\":\"ping\",\"counter\":7}' | robowire encode telemetrix --hex";

/// Which side's frames to accept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum From {
    /// Commands only (bytes the host sent).
    Host,
    /// Reports only (bytes the Pico sent).
    Pico,
    /// Commands and reports (see "--from any" below).
    Any,
}

/// `--dialect`: one of the library's dialect names.
fn dialect_parser() -> impl TypedValueParser<Value = Dialect> {
    let values = Dialect::ALL.map(|dialect| {
        PossibleValue::new(dialect.name()).help(match dialect {
            Dialect::Mirte13 => "mirte firmware 1.3 (ids 0..=38, sensors, modules)",
            Dialect::Mirte12 => "mirte firmware 1.2",
            Dialect::Upstream11 => "Upstream firmware 1.1 (ids 0..=28)",
        })
    });
    PossibleValuesParser::new(values).try_map(|name| name.parse::<Dialect>())
}

/// `robowire decode telemetrix`.
#[derive(Debug, Args)]
#[command(after_long_help = decode_help())]
pub struct DecodeArgs {
    /// Accept commands (host), reports (pico) or both (any).
    #[arg(long, value_enum, display_order = 1, default_value_t = From::Any)]
    pub from: From,
    /// Firmware dialect.
    #[arg(long, display_order = 2, default_value = "mirte13", value_parser = dialect_parser())]
    pub dialect: Dialect,
    /// Accept report ids the dialect does not define (newer firmware) as
    /// unknown_report, when a valid report follows directly. Not with --from
    /// host.
    #[arg(long, display_order = 5)]
    pub lenient: bool,
    /// With --from host: frame commands exactly as the Pico's firmware does
    /// (a length byte 00 or over 30 is dropped, any other is trusted, never a
    /// rescan), to see what the device ran; a frame that is no valid command
    /// is an error and consumed whole.
    #[arg(long, display_order = 6)]
    pub as_firmware: bool,
    /// The options every decode shares.
    #[command(flatten)]
    pub common: DecodeCommon,
}

/// `robowire encode telemetrix`.
#[derive(Debug, Args)]
#[command(after_long_help = ENCODE_SCHEMA)]
pub struct EncodeArgs {
    /// Firmware dialect to encode for.
    #[arg(long, default_value = "mirte13", value_parser = dialect_parser())]
    pub dialect: Dialect,
    /// The options every encode shares.
    #[command(flatten)]
    pub common: EncodeCommon,
}

/// Run `decode telemetrix`.
pub fn decode(args: &DecodeArgs, out: &mut Output) -> Result<Decoded, Failure> {
    if args.lenient && args.from == From::Host {
        return Err(Failure::Usage(
            "--lenient accepts unknown report ids, which --from host does not decode".to_owned(),
        ));
    }
    if args.as_firmware && args.from != From::Host {
        return Err(Failure::Usage(
            "--as-firmware frames commands as the Pico does; use it with --from host".to_owned(),
        ));
    }
    let mut source = args.common.source()?;
    let mut printer = Printer::new(
        out,
        &args.common,
        Telemetrix {
            dialect: args.dialect,
        },
        match args.from {
            From::Host => Peer::Device,
            From::Pico | From::Any => Peer::Host,
        },
    )?;
    let chunk = args.common.chunk as usize;
    let source = source.as_mut();
    let (dialect, lenient) = (args.dialect, args.lenient);
    match args.from {
        From::Host => {
            let framing = Framing::<Device>::new().with_dialect(dialect);
            let framing = if args.as_firmware {
                framing.as_firmware()
            } else {
                framing
            };
            decode_stream(framing, source, chunk, &mut printer)
        }
        From::Pico => {
            let framing = Framing::<Host>::new().with_dialect(dialect);
            let framing = if lenient { framing.lenient() } else { framing };
            decode_stream(framing, source, chunk, &mut printer)
        }
        From::Any => {
            let framing = Framing::<Both>::new().with_dialect(dialect);
            let framing = if lenient { framing.lenient() } else { framing };
            decode_stream(framing, source, chunk, &mut printer)
        }
    }
}

/// [`driver::decode_annotated`] with a [`CaptureContext`] between the decoder
/// and the printer. The context depends only on the events in order, so the
/// output still does not depend on `chunk`. Every side decodes with room for
/// a lenient unknown report and the frame that must follow it.
fn decode_stream<S: Side>(
    framing: Framing<S>,
    source: &mut dyn ByteSource,
    chunk: usize,
    printer: &mut Printer<'_>,
) -> Result<Decoded, Failure>
where
    S::Owned: Into<MessageBuf>,
{
    let mut context = CaptureContext::new(&framing);
    let decoder = StreamDecoder::<Framing<S>, BOTH_BUFFER>::new(framing);
    driver::decode_annotated(decoder, source, chunk, printer, |event| {
        event.map(|frame| {
            let mut message: MessageBuf = frame.message.into();
            context.annotate(&mut message);
            OwnedFrame {
                offset: frame.offset,
                len: frame.len,
                message,
            }
        })
    })
}

/// Run `encode telemetrix`.
pub fn encode(args: &EncodeArgs, out: &mut Output) -> Result<(), Failure> {
    let protocol = Telemetrix {
        dialect: args.dialect,
    };
    driver::encode_lines(&protocol, &args.common, out)
}

/// Telemetrix as the tool encodes it: lines are read for `dialect` (which
/// fields a type has depends on it).
pub struct Telemetrix {
    dialect: Dialect,
}

impl Schema for Telemetrix {
    type Line = serde_json::Value;
    const FIELDS: &'static FieldTable = &robowire::telemetrix::FIELD_INFO;

    fn encode(&self, line: &serde_json::Value, frame: &mut Vec<u8>) -> Result<(), String> {
        let message = MessageBuf::deserialize_in(line, self.dialect).map_err(|e| e.to_string())?;
        frame.extend_from_slice(&message);
        Ok(())
    }

    fn sent_by(&self, line: &serde_json::Value) -> Option<Peer> {
        let message = MessageBuf::deserialize_in(line, self.dialect).ok()?;
        Some(match message.is_command() {
            true => Peer::Host,
            false => Peer::Device,
        })
    }
}
