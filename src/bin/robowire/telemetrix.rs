//! `robowire decode telemetrix` and `robowire encode telemetrix`.
//!
//! Telemetrix has no checksum and separate id spaces per direction, so the
//! framing is chosen by `--from`: commands (`host`), reports (`pico`), or
//! both (`any`, see [`TmxFraming`]). Between the decoder and the printer a
//! [`Context`] looks at the frames in order: it attributes frames that are
//! valid both ways, and remembers module types so that MODULE_DATA can be
//! printed typed.

mod describe;
mod names;
mod read;

use crate::driver::{DecodeCommon, Decoded, EncodeCommon, Output, Printer, Protocol};
use crate::input::{ByteSource, HexBytes, Input, RawBytes};
use crate::json::{Fields, JsonLine};
use crate::Failure;
use clap::{Args, ValueEnum};
use robowire::stream::{Check, FrameRules, OwnedEvent, StreamDecoder};
use robowire::telemetrix::{
    Command, CommandFraming, Dialect, Error, ModuleNew, ModuleType, OwnedCommand, OwnedReport,
    Report, ReportFraming,
};

/// The JSON schema and the `--from any` rule, printed by `--help` after the
/// options.
const DECODE_SCHEMA: &str = "\
Output: one JSON object per line, per frame, in input order:
  offset  byte offset of the frame's LEN byte in the input (decoded bytes with --hex)
  len     frame length in bytes (LEN + 1)
  type    the message, in snake case after the spec's names. Commands (host):
          serial_loop_back, set_pin_mode, digital_write, pwm_write, modify_reporting,
          get_firmware_version, get_pico_unique_id, servo_attach, servo_write,
          servo_detach, i2c_begin, i2c_read, i2c_write, sonar_new, dht_new,
          stop_all_reports, enable_all_reports, reset_data, reset_board,
          initialize_neo_pixels, show_neo_pixels, set_neo_pixel, clear_all_neo_pixels,
          fill_neo_pixels, spi_init, spi_write_blocking, spi_read_blocking,
          spi_set_format, spi_cs_control, set_scan_delay, encoder_new, sensor_new,
          ping, module_new, module_data, get_id, set_id, feature_request (id 37),
          bootloader_reset.
          Reports (pico): serial_loop_back_report, digital_report, analog_report,
          firmware_version, pico_unique_id, i2c_write_report (upstream:
          i2c_write_failed), i2c_read_failed, i2c_read_report, sonar_distance,
          dht_report, spi_report, encoder_report, sensor_report, sensor_main_report,
          pong, module_main_report, module_report, get_id_report, set_id_report,
          feature_check, debug_print, and with --lenient unknown_report (id, payload).
Then the fields, named after the spec: numbers as on the wire (signed where the
spec says so), byte strings as arrays of numbers (data, extras, cs_pins, ...),
levels (value, level, cpol, cpha, active_level) as 0/1, flags (report_enable,
auto_show, supported, ok, enabled, pulls.up/down) as true/false. Byte counts
that a byte array already gives are not repeated; read lengths are `n`.
  set_pin_mode mode: digital_input, digital_input_pull_up, digital_input_pull_down,
    digital_output, pwm_output, analog_input; modify_reporting action:
    disable_all, enable_analog, enable_digital, disable_analog, disable_digital.
  sonar_distance (mirte13): trig, echo (LEN 5 form only), cm: a number or
    \"no_echo\", \"out_of_range\", \"stale\"; mirte12: trig, m, cm; upstream11:
    trig, cm, hundredths. i2c_read and i2c_write carry msg_id except in
    upstream11; i2c_read_report carries msg_id, or addr in upstream11.
  sensor_type and module_type are names (gps, hx711, mpu9250, vl53l0x, veml6040,
    adxl345, ina226, hmc5883l, as5600, mpu6050, bno055; pca9685, hiwonder_servo,
    shutdown_relay, ssd1306), or numbers where a check names an unknown type.
  sensor_report: sensor_num, sensor_type, reading {typed fields; floats read back
    as the same f32, \"inf\"/\"-inf\"/\"nan:0x...\" otherwise}.
  module_report: module_num, module_type, message {subtype, fields}.
  sensor_new, module_new: subtype check or add; module_new add has init {...}.
  module_data: module_num, then module_type and message {subtype, fields} when an
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
  {\"offset\":12,\"error\":\"unknown_id\",\"id\":97}
  {\"offset\":30,\"error\":\"bad_length\",\"id\":2,\"len_byte\":7}
  {\"offset\":41,\"error\":\"out_of_range\",\"id\":3,\"field\":\"value\"}
  {\"offset\":90,\"error\":\"truncated\",\"len\":2}
len_byte is the frame's LEN byte; field names what the firmware never sends.
Every rejection costs one byte: decoding resumes at the next byte. At the end,
one summary line goes to stderr.

Exit status: 0 on success, 2 on usage errors and invalid input (bad hex),
1 on I/O errors. A closed stdout pipe ends the run quietly.

Examples:
  robowire decode telemetrix --from pico tests/data/telemetrix_reports.bin
  robowire decode telemetrix --from host --hex tests/data/telemetrix_commands.hex
  echo '03 05 01 03' | robowire decode telemetrix --hex";

const ENCODE_SCHEMA: &str = "\
Input: JSON lines in the schema `robowire decode telemetrix` prints; offset, len
and also are ignored, unknown fields are errors. The type says the direction.
Blank lines and diagnostic events (objects with error and no type) are skipped.
Frames are encoded for --dialect (the one they were decoded with), and the
encoder refuses what the firmware would mishandle (unknown ids, LEN over 30,
pins >= 30, counts over the spec's maxima). A malformed line or out-of-range
value is reported with its line number and nothing is written for it; the other
lines are still encoded and the exit status is 2.

Examples:
  robowire decode telemetrix capture.bin | robowire encode telemetrix > same-frames.bin
  echo '{\"type\":\"ping\",\"counter\":7}' | robowire encode telemetrix --hex";

/// Which side's frames to accept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Side {
    /// Commands only (bytes the host sent).
    Host,
    /// Reports only (bytes the Pico sent).
    Pico,
    /// Commands and reports (see "--from any" below).
    Any,
}

/// A firmware dialect on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DialectArg {
    /// mirte firmware 1.3 (ids 0..=38, sensors, modules).
    #[value(name = "mirte13")]
    Mirte13,
    /// mirte firmware 1.2.
    #[value(name = "mirte12")]
    Mirte12,
    /// Upstream firmware 1.1 (ids 0..=28).
    #[value(name = "upstream11")]
    Upstream11,
}

impl DialectArg {
    const fn dialect(self) -> Dialect {
        match self {
            DialectArg::Mirte13 => Dialect::Mirte13,
            DialectArg::Mirte12 => Dialect::Mirte12,
            DialectArg::Upstream11 => Dialect::Upstream11,
        }
    }
}

/// `robowire decode telemetrix`.
#[derive(Debug, Args)]
#[command(after_long_help = DECODE_SCHEMA)]
pub struct DecodeArgs {
    /// Accept commands (host), reports (pico) or both (any).
    #[arg(long, value_enum, display_order = 1, default_value_t = Side::Any)]
    pub from: Side,
    /// Firmware dialect.
    #[arg(long, value_enum, display_order = 2, default_value_t = DialectArg::Mirte13)]
    pub dialect: DialectArg,
    /// Accept report ids the dialect does not define (newer firmware) as
    /// unknown_report, when a valid report follows directly. Not with --from
    /// host.
    #[arg(long, display_order = 5)]
    pub lenient: bool,
    /// The options every decode shares.
    #[command(flatten)]
    pub common: DecodeCommon,
}

/// `robowire encode telemetrix`.
#[derive(Debug, Args)]
#[command(after_long_help = ENCODE_SCHEMA)]
pub struct EncodeArgs {
    /// Firmware dialect to encode for.
    #[arg(long, value_enum, default_value_t = DialectArg::Mirte13)]
    pub dialect: DialectArg,
    /// The options every encode shares.
    #[command(flatten)]
    pub common: EncodeCommon,
}

/// What a frame is, in the direction(s) the framing accepts.
#[derive(Debug, Clone, Copy)]
pub enum Kind {
    /// A command only.
    Command(OwnedCommand),
    /// A report only.
    Report(OwnedReport),
    /// Valid both ways (only with `--from any`): `as_command` is the
    /// direction the [`Context`] attributes it to.
    Both {
        /// The frame read as a command.
        command: OwnedCommand,
        /// The frame read as a report.
        report: OwnedReport,
        /// Print it as the command (else as the report).
        as_command: bool,
    },
}

/// A decoded frame as the tool prints it.
#[derive(Debug, Clone, Copy)]
pub struct Message {
    /// The frame's reading(s).
    pub kind: Kind,
    /// The dialect it was decoded in.
    pub dialect: Dialect,
    /// For MODULE_DATA: the module's type, as the [`Context`] knows it.
    pub module_type: Option<ModuleType>,
}

/// The framing for `--from`: the library's command or report framing, or
/// both at once.
///
/// With `--from any` a candidate is a frame if either framing accepts it,
/// rejected if both reject it, and undecided while either still needs bytes.
/// Both framings read the same `LEN`, so an accepted frame has one length. A
/// known command outranks a lenient unknown report.
#[derive(Debug, Clone, Copy)]
pub struct TmxFraming {
    side: Side,
    commands: CommandFraming,
    reports: ReportFraming,
}

impl TmxFraming {
    /// The framing for `side` in `dialect`; `lenient` applies to reports.
    pub fn new(side: Side, dialect: Dialect, lenient: bool) -> Self {
        let reports = ReportFraming::new().with_dialect(dialect);
        TmxFraming {
            side,
            commands: CommandFraming::new().with_dialect(dialect),
            reports: if lenient { reports.lenient() } else { reports },
        }
    }

    fn message(&self, kind: Kind) -> Message {
        Message {
            kind,
            dialect: self.reports.dialect(),
            module_type: None,
        }
    }

    fn check_any(&self, candidate: &[u8], at_end: bool) -> Check<Error> {
        let command = self.commands.check(candidate, at_end);
        let report = self.reports.check(candidate, at_end);
        match (command, report) {
            (Check::Frame(n), _) => Check::Frame(n),
            (Check::Need(a), Check::Need(b)) => Check::Need(a.min(b)),
            // A report cannot be complete while the command of the same LEN
            // is not; should it ever be, wait for the command's answer.
            (Check::Need(n), _) | (Check::Reject(_), Check::Need(n)) => Check::Need(n),
            (Check::Reject(_), Check::Frame(n)) => Check::Frame(n),
            // Report the error of the direction that got further: if the id
            // is unknown as a report, the command's.
            (Check::Reject(c), Check::Reject(Error::UnknownId { .. })) => Check::Reject(c),
            (Check::Reject(_), Check::Reject(r)) => Check::Reject(r),
        }
    }
}

impl FrameRules for TmxFraming {
    type Error = Error;
    type Message<'a> = Message;
    type Owned = Message;

    const HEADER_LEN: usize = 2;
    // As the library's framings: without a checksum the overlap test costs
    // about as many frames as it saves.
    const VERIFY_AFTER_RESYNC: bool = false;

    fn find_start(&self, bytes: &[u8]) -> usize {
        match self.side {
            Side::Host => self.commands.find_start(bytes),
            // Skips `00` only: a LEN over 30 may start a report.
            Side::Pico | Side::Any => self.reports.find_start(bytes),
        }
    }

    fn check(&self, candidate: &[u8], at_end: bool) -> Check<Error> {
        match self.side {
            Side::Host => self.commands.check(candidate, at_end),
            Side::Pico => self.reports.check(candidate, at_end),
            Side::Any => self.check_any(candidate, at_end),
        }
    }

    fn truncated(&self, len: usize) -> Error {
        self.reports.truncated(len)
    }

    fn superseded(&self, len: usize) -> Error {
        self.reports.superseded(len)
    }

    fn is_checksum_error(&self, _error: &Error) -> bool {
        false
    }

    fn parse(&self, frame: &[u8]) -> Result<Message, Error> {
        let kind = match self.side {
            Side::Host => Kind::Command(self.commands.parse(frame)?.to_owned()),
            Side::Pico => Kind::Report(self.reports.parse(frame)?.to_owned()),
            Side::Any => {
                let command = self.commands.parse(frame);
                let report = self.reports.parse(frame);
                match (command, report) {
                    (Ok(c), Ok(Report::Unknown { .. })) => Kind::Command(c.to_owned()),
                    (Ok(c), Ok(r)) => Kind::Both {
                        command: c.to_owned(),
                        report: r.to_owned(),
                        as_command: false,
                    },
                    (Ok(c), Err(_)) => Kind::Command(c.to_owned()),
                    (Err(_), Ok(r)) => Kind::Report(r.to_owned()),
                    (Err(_), Err(e)) => return Err(e),
                }
            }
        };
        Ok(self.message(kind))
    }

    fn to_owned(message: Message) -> Message {
        message
    }
}

/// What the frames so far say about the ones that follow: the direction of
/// the last frame that was valid one way only, and the module types that
/// MODULE_NEW (or a module report) gave each module number.
pub struct Context {
    host_last: bool,
    modules: [Option<ModuleType>; 256],
}

impl Context {
    fn new() -> Self {
        Context {
            host_last: false,
            modules: [None; 256],
        }
    }

    /// Attribute an ambiguous frame and type MODULE_DATA; learn from the rest.
    fn annotate(&mut self, m: &mut Message) {
        let command = match &mut m.kind {
            Kind::Command(c) => {
                self.host_last = true;
                c
            }
            Kind::Report(r) => {
                self.host_last = false;
                self.learn(r);
                return;
            }
            Kind::Both {
                command,
                report,
                as_command,
            } => {
                *as_command = self.host_last;
                if !self.host_last {
                    self.learn(report);
                    return;
                }
                command
            }
        };
        match *command {
            Command::ModuleNew(ModuleNew::Add { module_num, init }) => {
                self.modules[usize::from(module_num)] = Some(describe::init_type(&init));
            }
            // Modules are gone after a reboot.
            Command::ResetBoard | Command::BootloaderReset => self.modules = [None; 256],
            Command::ModuleData { module_num, .. } => {
                m.module_type = self.modules[usize::from(module_num)];
            }
            _ => {}
        }
    }

    fn learn(&mut self, report: &OwnedReport) {
        if let Report::Module { module_num, report } = report {
            self.modules[usize::from(*module_num)] = Some(report.module_type());
        }
    }
}

/// Run `decode telemetrix`.
pub fn decode(args: &DecodeArgs, out: &mut Output) -> Result<Decoded, Failure> {
    if args.lenient && args.from == Side::Host {
        return Err(Failure::Usage(
            "--lenient accepts unknown report ids, which --from host does not decode".to_owned(),
        ));
    }
    let framing = TmxFraming::new(args.from, args.dialect.dialect(), args.lenient);
    let input = Input::open(args.common.input.as_deref())?;
    let mut printer = Printer::new(out, args.common.errors);
    let mut source: Box<dyn ByteSource> = if args.common.hex {
        Box::new(HexBytes::new(input))
    } else {
        Box::new(RawBytes(input))
    };
    decode_stream(
        // Room for a lenient unknown report and the frame that must follow.
        StreamDecoder::<TmxFraming, 512>::new(framing),
        source.as_mut(),
        args.common.chunk as usize,
        &mut printer,
    )
}

/// [`driver::decode_stream`](crate::driver::decode_stream), with the
/// [`Context`] between the decoder and the printer. The context depends only
/// on the events in order, so the output still does not depend on `chunk`.
fn decode_stream<const N: usize>(
    mut decoder: StreamDecoder<TmxFraming, N>,
    source: &mut dyn ByteSource,
    chunk: usize,
    printer: &mut Printer<'_>,
) -> Result<Decoded, Failure> {
    let mut context = Context::new();
    let mut print = |mut event: OwnedEvent<TmxFraming>, printer: &mut Printer<'_>| {
        if let Ok(frame) = &mut event {
            context.annotate(&mut frame.message);
        }
        printer.event::<Telemetrix>(event)
    };
    let mut buf = vec![0u8; chunk];
    loop {
        let n = match source.fill(&mut buf) {
            Ok(0) => break,
            Ok(n) => n,
            Err(failure) => {
                return Ok(Decoded {
                    stats: decoder.stats(),
                    failure: Some(failure),
                })
            }
        };
        for event in decoder.feed(&buf[..n]) {
            print(event, printer)?;
        }
        // Before a read that may wait, show what has been decoded so far.
        if source.may_wait() {
            printer.flush()?;
        }
    }
    for event in decoder.flush() {
        print(event, printer)?;
    }
    Ok(Decoded {
        stats: decoder.stats(),
        failure: None,
    })
}

/// Run `encode telemetrix`.
pub fn encode(args: &EncodeArgs, out: &mut Output) -> Result<(), Failure> {
    let input = Input::open(args.common.input.as_deref())?;
    let hex = args.common.hex;
    match args.dialect {
        DialectArg::Mirte13 => crate::driver::encode_lines::<Telemetrix>(input, hex, out),
        DialectArg::Mirte12 => crate::driver::encode_lines::<Telemetrix<1>>(input, hex, out),
        DialectArg::Upstream11 => crate::driver::encode_lines::<Telemetrix<2>>(input, hex, out),
    }
}

/// The Telemetrix protocol as the tool sees it. `D` is the dialect that
/// `encode` writes (0 mirte 1.3, 1 mirte 1.2, 2 upstream 1.1): the driver's
/// encode hook takes no options, so the dialect is part of the type.
pub struct Telemetrix<const D: u8 = 0>;

impl<const D: u8> Telemetrix<D> {
    const DIALECT: Dialect = match D {
        1 => Dialect::Mirte12,
        2 => Dialect::Upstream11,
        _ => Dialect::Mirte13,
    };
}

impl<const D: u8> Protocol for Telemetrix<D> {
    type Framing = TmxFraming;

    fn describe(message: &Message, line: &mut JsonLine) {
        describe::message(message, line);
    }

    fn describe_error(error: &Error, line: &mut JsonLine) {
        match *error {
            Error::UnknownId { id } => {
                line.field("error", "unknown_id");
                line.field("id", id);
            }
            Error::BadLength { id, len } => {
                line.field("error", "bad_length");
                line.field("id", id);
                line.field("len_byte", len);
            }
            Error::OutOfRange { id, field } => {
                line.field("error", "out_of_range");
                line.field("id", id);
                line.field("field", field);
            }
            Error::Truncated { len } => {
                line.field("error", "truncated");
                line.field("len", len);
            }
            Error::Superseded { len } => {
                line.field("error", "superseded");
                line.field("len", len);
            }
            // A rejection this tool does not know yet: its message.
            ref other => {
                line.field("error", "other");
                line.field("message", other.to_string().as_str());
            }
        }
    }

    fn encode(fields: Fields<'_>, frame: &mut Vec<u8>) -> Result<(), String> {
        read::encode(Self::DIALECT, fields, frame)
    }
}
