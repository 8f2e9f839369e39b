//! The protocol-neutral part of the tool: the decode loop over any
//! [`StreamDecoder`], JSON-lines output through the library's `serde` form,
//! the end-of-run summary, and the encode loop over JSON lines. A protocol
//! plugs in by implementing [`Schema`]; it writes no per-message code.

use crate::export::{FormatArgs, PlotRequest, Recorder};
use crate::input::{ByteSource, HexBytes, Input, Lines, RawBytes};
use crate::port::{EncodePort, LiveArgs, PortSink, PortSource};
use crate::suspicion;
use crate::Failure;
use clap::Args;
use robowire::stream::{
    owned_event, FrameRules, OwnedEvent, OwnedFrame, Rejected, Stats, StreamDecoder,
};
use robowire::units::FieldTable;
use robowire::Idle;
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;
use std::io::{self, BufWriter, StdoutLock, Write};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// What a protocol supplies to the tool when its library types carry the
/// JSON-lines schema (their `serde` form): the decoder's rules, what one input
/// line reads into, and how that becomes a frame. Printing is the library's
/// `Serialize` of [`OwnedFrame`](robowire::OwnedFrame) and
/// [`Rejected`](robowire::Rejected); reading is the message's `Deserialize`,
/// which validates as the encoder does.
pub trait Schema {
    /// What one JSON line (that is not a diagnostic event) deserializes into.
    type Line: DeserializeOwned;

    /// What each field means (units, descriptions), for schemas and labels.
    const FIELDS: &'static FieldTable;

    /// Append the frame of `line` to `frame`; the error names the problem.
    fn encode(&self, line: &Self::Line, frame: &mut Vec<u8>) -> Result<(), String>;

    /// Who sends `line`'s message on the wire (`None`: it is no message).
    fn sent_by(&self, line: &Self::Line) -> Option<Peer>;
}

/// One end of a link: the host (commands, requests) or the device
/// (telemetry, responses, reports).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Peer {
    /// The computer that sends commands and requests.
    Host,
    /// The tile, camera or board that answers.
    Device,
}

/// Options every `decode` subcommand shares.
#[derive(Debug, Args)]
pub struct DecodeCommon {
    /// Feed the decoder N bytes at a time (the output never depends on it).
    ///
    /// From a regular file the pieces are exactly N bytes; from stdin, a pipe
    /// or a device each piece is what has arrived, at most N bytes.
    #[arg(
        long,
        value_name = "N",
        display_order = 3,
        default_value_t = 4096,
        value_parser = clap::value_parser!(u32).range(1..=(1 << 24)),
    )]
    pub chunk: u32,
    /// Read hex text (whitespace, commas and 0x prefixes ignored) as one byte
    /// stream instead of raw bytes.
    #[arg(long, display_order = 4)]
    pub hex: bool,
    /// Exit 0 even when the output is probably false (hex text without
    /// --hex, mostly noise, SPI buffers without spi45); the warning stays.
    ///
    /// Without it such a decode exits with status 3, and prints nothing
    /// from a file named as INPUT (judged whole first) or from OmniTiles SPI
    /// buffers read with the default layouts.
    #[arg(long, display_order = 7)]
    pub allow_noise: bool,
    /// Print rejected candidates too, as objects with `offset` and `error`.
    #[arg(long, display_order = 6)]
    pub errors: bool,
    /// The capture to read; `-` or absent for stdin.
    #[arg(value_name = "INPUT")]
    pub input: Option<PathBuf>,
    /// Live ports, receive times and saved captures.
    #[command(flatten)]
    pub live: LiveArgs,
    /// The output format and destination.
    #[command(flatten)]
    pub format: FormatArgs,
    /// A live Foxglove view, with commands back.
    #[cfg(feature = "cli-foxglove")]
    #[command(flatten)]
    pub foxglove: crate::foxglove::FoxgloveArgs,
}

impl DecodeCommon {
    /// Whether the input is a regular file named on the command line, which
    /// can be read twice: once to judge the decode, once to print it. Stdin
    /// (even redirected from a file), pipes, devices and ports are streams.
    pub fn is_whole_file(&self) -> bool {
        let path = match (&self.input, &self.live.port) {
            (Some(path), None) if path.as_os_str() != "-" => path,
            _ => return false,
        };
        std::fs::metadata(path).is_ok_and(|meta| meta.is_file())
    }

    /// The input, as raw bytes or (with `--hex`) hex text, from a file, stdin
    /// or (with `--port`) a serial port.
    pub fn source(&self) -> Result<Box<dyn ByteSource>, Failure> {
        // Checked here, not with clap's `requires = "port"`: clap drops a
        // requirement on an argument that conflicts with one given, and
        // `--port` conflicts with INPUT, so `--idle 3 FILE` would pass.
        if self.live.idle.is_some() && self.live.port.is_none() {
            return Err(Failure::Invalid(
                "--idle is the silence on a live port: it needs --port".to_owned(),
            ));
        }
        if let Some(device) = &self.live.port {
            let idle = self.live.idle_gap();
            return Ok(Box::new(PortSource::open(device, self.live.baud, idle)?));
        }
        let input = Input::open(self.input.as_deref())?;
        Ok(if self.hex {
            Box::new(HexBytes::new(input))
        } else {
            Box::new(RawBytes(input))
        })
    }
}

/// The end of every decode help text: the summary and the exit status.
pub const DECODE_FOOTER: &str = "\
Exit status: 0 on success, 2 on usage errors and invalid input (bad hex),
1 on I/O errors, 3 when the output is probably false: a warning after the
summary says why (hex text without --hex; most of the input skipped, over 80 %
of its non-zero bytes, or over 8 rejected candidates per frame; OmniTiles SPI
buffers without spi45). A file named as INPUT is judged whole first and then
prints nothing at all, as SPI buffers with the default layouts never do;
stdin and ports print as they go and warn at the end. --allow-noise prints
everything, keeps the warning and exits 0. A closed stdout pipe ends the run
quietly.";

/// Options every `encode` subcommand shares.
#[derive(Debug, Args)]
pub struct EncodeCommon {
    /// Write hex text, one frame per line, instead of raw bytes.
    #[arg(long)]
    pub hex: bool,
    /// JSON lines to read; `-` or absent for stdin.
    #[arg(value_name = "INPUT")]
    pub input: Option<PathBuf>,
    /// A serial port to write the frames to.
    #[command(flatten)]
    pub port: EncodePort,
}

/// Buffered stdout that turns a closed pipe into [`Failure::BrokenPipe`],
/// and what the decoded bytes looked like, for [`suspicion::assess`].
pub struct Output {
    out: BufWriter<StdoutLock<'static>>,
    /// The first 64 KiB of the decoded bytes.
    start: Vec<u8>,
    /// How many of the decoded bytes were `00`.
    zeros: u64,
    /// Output held back until the input's first [`suspicion::SPI_GATE`]
    /// bytes show that it is no SPI buffers ([`Output::hold_for_spi`]).
    held: Option<Vec<u8>>,
    /// Times, a saved capture or another format, when a decode asks for them.
    recorder: Option<Recorder>,
    /// The serial port an encode writes to instead of stdout.
    port: Option<BufWriter<PortSink>>,
    /// What `robowire plot` asks the decode to draw.
    pub plot: Option<PlotRequest>,
    /// A decode run only to judge its output ([`Output::judging`]).
    judging: bool,
}

impl Output {
    /// Lock stdout behind a buffer.
    pub fn stdout() -> Self {
        Output {
            out: BufWriter::with_capacity(64 * 1024, io::stdout().lock()),
            start: Vec::new(),
            zeros: 0,
            held: None,
            recorder: None,
            port: None,
            plot: None,
            judging: false,
        }
    }

    /// An output that writes, records and warns nothing and only observes
    /// the decoded bytes: a whole file is decoded into it first, so that a
    /// probably false decode prints nothing at all.
    pub fn judging() -> Self {
        Output {
            judging: true,
            ..Output::stdout()
        }
    }

    /// Hold back everything written until the start of the input shows
    /// whether it is zero-padded SPI buffers, to be refused with no output
    /// ([`Printer::observe`] decides, or [`Output::finish`] at the end).
    pub fn hold_for_spi(&mut self) {
        self.held = Some(Vec::new());
    }

    /// Write `bytes`.
    pub fn write(&mut self, bytes: &[u8]) -> Result<(), Failure> {
        if self.judging {
            return Ok(());
        }
        if let Some(held) = &mut self.held {
            held.extend_from_slice(bytes);
            return Ok(());
        }
        match &mut self.port {
            Some(port) => port.write_all(bytes).map_err(|e| port_failure(port, e)),
            None => self.out.write_all(bytes).map_err(Failure::stdout),
        }
    }

    /// Write everything still buffered (nothing while output is held back).
    pub fn flush(&mut self) -> Result<(), Failure> {
        if let Some(recorder) = &mut self.recorder {
            recorder.flush()?;
        }
        if let Some(port) = &mut self.port {
            port.flush().map_err(|e| port_failure(port, e))?;
        }
        if self.held.is_some() {
            return Ok(());
        }
        self.out.flush().map_err(Failure::stdout)
    }

    /// Write what was held back and stop holding output.
    fn release(&mut self) -> Result<(), Failure> {
        match self.held.take() {
            Some(held) => self.write(&held),
            None => Ok(()),
        }
    }

    /// At the end of a run: write what was held back, or with `discard`
    /// drop it, complete every output (an MCAP recording's summary, a saved
    /// capture) and write everything still buffered.
    pub fn finish(&mut self, discard: bool) -> Result<(), Failure> {
        if discard {
            self.held = None;
        }
        let released = self.release();
        let finished = self.recorder.as_mut().map_or(Ok(()), Recorder::finish);
        let flushed = self.flush();
        released.and(finished).and(flushed)
    }

    /// What [`suspicion::assess`] reads: the first 64 KiB of the decoded
    /// bytes and how many of them all were `00`.
    pub fn observed(&self) -> (&[u8], u64) {
        (&self.start, self.zeros)
    }

    /// Whether output is still held back.
    pub fn holding(&self) -> bool {
        self.held.is_some()
    }
}

fn port_failure(port: &BufWriter<PortSink>, error: io::Error) -> Failure {
    Failure::Io {
        context: port.get_ref().name().to_owned(),
        error,
    }
}

/// Prints decode events as JSON lines: the library's `serde` form of
/// [`OwnedFrame`] and [`Rejected`].
pub struct Printer<'o> {
    out: &'o mut Output,
    text: Vec<u8>,
    errors: bool,
}

impl<'o> Printer<'o> {
    /// A printer writing to `out` in the format `common` asks for;
    /// rejections are printed with `--errors`. `protocol` describes its
    /// fields to the recording's schemas and encodes the commands a live
    /// view takes back: messages `writes` sends, the other end from the
    /// one decoded (the host's, unless the decode reads a host's bytes).
    pub fn new<P: Schema + Send + Sync + 'static>(
        out: &'o mut Output,
        common: &DecodeCommon,
        protocol: P,
        writes: Peer,
    ) -> Result<Self, Failure> {
        let plot = out.plot.take();
        common
            .format
            .refuse_overwrite(common.live.save.as_deref())?;
        if !out.judging {
            out.recorder =
                Recorder::new(common, plot, P::FIELDS, || line_encoder(protocol, writes))?;
        }
        Ok(Printer {
            out,
            text: Vec::with_capacity(256),
            errors: common.errors,
        })
    }

    /// Print one event.
    pub fn event<M: Serialize, E: Serialize>(
        &mut self,
        event: Result<OwnedFrame<M>, Rejected<E>>,
    ) -> Result<(), Failure> {
        if self.out.judging {
            return Ok(());
        }
        if let Some(recorder) = &mut self.out.recorder {
            // JSON lines with times go to stdout, or wait with the rest.
            let stdout: &mut dyn Write = match &mut self.out.held {
                Some(held) => held,
                None => &mut self.out.out,
            };
            return recorder.event(event, self.errors, stdout);
        }
        let buf = &mut self.text;
        buf.clear();
        let written = match event {
            Ok(frame) => serde_json::to_writer(&mut *buf, &frame),
            Err(rejected) if self.errors => serde_json::to_writer(&mut *buf, &rejected),
            Err(_) => return Ok(()),
        };
        // The library's types always serialize: a failure here is a bug in
        // robowire, reported rather than hidden.
        written.map_err(|e| Failure::Reported(format!("cannot print an event: {e}")))?;
        buf.push(b'\n');
        self.out.write(buf)
    }

    /// Note bytes about to be decoded, for [`suspicion::assess`] and the
    /// recorder. While output is held back, the first
    /// [`suspicion::SPI_GATE`] bytes decide: SPI buffers are
    /// [`Failure::Refused`] (nothing was printed), anything else releases the
    /// output.
    pub fn observe(&mut self, bytes: &[u8]) -> Result<(), Failure> {
        let out = &mut *self.out;
        let room = 64 * 1024 - out.start.len();
        out.start.extend_from_slice(&bytes[..room.min(bytes.len())]);
        out.zeros += bytes.iter().filter(|&&b| b == 0).count() as u64;
        if let Some(recorder) = &mut out.recorder {
            recorder.observe(bytes);
        }
        if out.held.is_some() && out.start.len() >= suspicion::SPI_GATE {
            if suspicion::spi_buffers(&out.start) {
                out.held = None;
                return Err(Failure::Refused(suspicion::spi_refusal()));
            }
            out.release()?;
        }
        Ok(())
    }

    /// Write out everything printed so far (before waiting for input, so a
    /// live stream's frames appear as they arrive).
    pub fn flush(&mut self) -> Result<(), Failure> {
        self.out.flush()
    }

    /// Report a problem with the input on stderr (not while judging: the
    /// decode that prints reports it).
    pub fn warn(&self, message: &str) {
        if !self.out.judging {
            eprintln!("robowire: {message}");
        }
    }

    /// Whether this decode only judges its output ([`Output::judging`]).
    pub fn judging(&self) -> bool {
        self.out.judging
    }
}

/// The end of a decode whose output went through: the counters, and the
/// input problem that stopped or marred it, if any.
#[derive(Debug)]
pub struct Decoded {
    /// The decoder's counters.
    pub stats: Stats,
    /// Why the input could not be read to its end (or which of its lines
    /// were skipped); reported after the summary.
    pub failure: Option<Failure>,
}

/// Decode everything `source` yields, `chunk` bytes at a time, then finish
/// the stream, printing every event with `printer`.
pub fn decode_stream<R, const N: usize>(
    decoder: StreamDecoder<R, N>,
    source: &mut dyn ByteSource,
    chunk: usize,
    printer: &mut Printer<'_>,
) -> Result<Decoded, Failure>
where
    R: FrameRules<Owned: Serialize, Error: Serialize>,
{
    decode_annotated(decoder, source, chunk, printer, |event| event)
}

/// [`decode_stream`], every event going through `annotate` (a protocol's
/// context) on its way to `printer`. An input failure stops the decode (without
/// finishing the stream: the input did not end) and comes back in
/// [`Decoded::failure`]; an output failure is the error.
pub fn decode_annotated<R, const N: usize, M, E>(
    mut decoder: StreamDecoder<R, N>,
    source: &mut dyn ByteSource,
    chunk: usize,
    printer: &mut Printer<'_>,
    mut annotate: impl FnMut(OwnedEvent<R>) -> Result<OwnedFrame<M>, Rejected<E>>,
) -> Result<Decoded, Failure>
where
    R: FrameRules,
    M: Serialize,
    E: Serialize,
{
    let mut buf = vec![0u8; chunk];
    // A live port's silence ends a frame only the next byte would decide.
    let start = Instant::now();
    let micros = || u64::try_from(start.elapsed().as_micros()).unwrap_or(u64::MAX);
    let mut idle = match (source.idle_gap(), printer.judging()) {
        (Some(gap), false) => Some(Idle::new(
            u64::try_from(gap.as_micros()).unwrap_or(u64::MAX),
        )),
        _ => None,
    };
    loop {
        let deadline = idle.and_then(|idle| idle.deadline());
        let read = match deadline {
            Some(at) => {
                let wait = Duration::from_micros(at.saturating_sub(micros()));
                source.fill_within(&mut buf, wait)
            }
            None => source.fill(&mut buf),
        };
        let n = match read {
            Ok(0) if source.ended() => break,
            Ok(0) => {
                if idle.as_mut().is_some_and(|idle| idle.expired(micros())) {
                    while let Some(event) = decoder.settle() {
                        printer.event(annotate(owned_event::<R>(event)))?;
                    }
                }
                // A pause on a live port: write out what is held.
                printer.flush()?;
                continue;
            }
            Ok(n) => n,
            Err(failure) => {
                return Ok(Decoded {
                    stats: decoder.stats(),
                    failure: Some(failure),
                })
            }
        };
        printer.observe(&buf[..n])?;
        if printer.judging() {
            // Judging needs the counters only: no owned frame is built, so
            // the first pass over a file costs a fraction of the second.
            decoder.decode_each(&buf[..n], |_| {});
            continue;
        }
        for event in decoder.feed(&buf[..n]) {
            printer.event(annotate(event))?;
        }
        if let Some(idle) = &mut idle {
            idle.received(micros(), &decoder);
        }
        // Before a read that may wait, show what has been decoded so far.
        if source.may_wait() {
            printer.flush()?;
        }
    }
    for event in decoder.flush() {
        printer.event(annotate(event))?;
    }
    Ok(Decoded {
        stats: decoder.stats(),
        failure: None,
    })
}

/// `words` joined by spaces in lines of at most `width` characters, the first
/// line starting at column `first`, the others indented by `indent` spaces
/// (the lists of names in the help texts).
pub fn wrap<W: AsRef<str>>(
    words: impl IntoIterator<Item = W>,
    first: usize,
    indent: usize,
    width: usize,
) -> String {
    let mut text = String::new();
    let mut column = first;
    for (i, word) in words.into_iter().enumerate() {
        let word = word.as_ref();
        if i > 0 {
            if column + 1 + word.len() > width {
                text.push('\n');
                text.push_str(&" ".repeat(indent));
                column = indent;
            } else {
                text.push(' ');
                column += 1;
            }
        }
        text.push_str(word);
        column += word.len();
    }
    text
}

/// `names` punctuated as a list: a comma after each but the last, which gets
/// `last` before it (`"or "`) and `end` after it.
pub fn listed<'n>(
    names: &'n [&str],
    last: &'n str,
    end: &'n str,
) -> impl Iterator<Item = String> + 'n {
    names.iter().enumerate().map(move |(i, name)| {
        if i + 1 == names.len() {
            format!("{last}{name}{end}")
        } else {
            format!("{name},")
        }
    })
}

/// The one-line summary printed on stderr at the end of a decode.
pub fn summary(stats: &Stats) -> String {
    format!("robowire: {stats}")
}

/// Encode every JSON line of the input with `protocol`, writing raw bytes or,
/// with `--hex`, one line of hex per frame. A malformed line (a line over
/// [`MAX_LINE`](crate::input::MAX_LINE) bytes, not UTF-8, not valid JSON, or
/// no valid message) is reported on stderr with its number, nothing is
/// written for it, and the run goes on; the result is then
/// [`Failure::Reported`]. A UTF-8 byte-order mark is reported and ignored;
/// UTF-16 input stops the run. Blank lines and diagnostic events (objects
/// with `error` and no `type`, as `decode --errors` prints them) are skipped.
pub fn encode_lines<P: Schema>(
    protocol: &P,
    args: &EncodeCommon,
    out: &mut Output,
) -> Result<(), Failure> {
    let hex = args.hex;
    if let Some(device) = &args.port.port {
        let port = PortSink::open(device, args.port.baud)?;
        out.port = Some(BufWriter::with_capacity(4096, port));
    }
    let mut lines = Lines::new(Input::open(args.input.as_deref())?);
    let mut frame = Vec::new();
    let mut text = Vec::new();
    let mut bad = 0u64;
    let name = lines.name().to_owned();
    loop {
        // Flush before a read that may wait, so frames go out as lines arrive.
        if !lines.has_buffered() {
            out.flush()?;
        }
        let Some((number, mut line)) = lines.next_line()? else {
            break;
        };
        if number == 1 {
            if let Some(rest) = line.strip_prefix(b"\xef\xbb\xbf") {
                eprintln!("robowire: {name}: line 1: ignoring a UTF-8 byte-order mark");
                line = rest;
            } else if line.starts_with(b"\xff\xfe") || line.starts_with(b"\xfe\xff") {
                return Err(Failure::Invalid(format!(
                    "{name}: the input is UTF-16 (it starts with a byte-order mark); \
                     JSON lines must be UTF-8"
                )));
            }
        }
        if line.iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        frame.clear();
        match encode_line(protocol, line, &mut frame, None) {
            Ok(()) if frame.is_empty() => continue,
            Ok(()) => {}
            Err((column, message)) => {
                let column = column.map_or(String::new(), |c| format!(", column {c}"));
                eprintln!("robowire: {name}: line {number}{column}: {message}");
                bad += 1;
                continue;
            }
        }
        if hex {
            text.clear();
            for (i, byte) in frame.iter().enumerate() {
                let sep = if i == 0 { "" } else { " " };
                // Writing into a Vec cannot fail.
                let _ = write!(text, "{sep}{byte:02x}");
            }
            text.push(b'\n');
            out.write(&text)?;
        } else {
            out.write(&frame)?;
        }
    }
    let bad = bad + lines.too_long();
    if bad > 0 {
        let s = if bad == 1 { "" } else { "s" };
        return Err(Failure::Reported(format!("{bad} malformed line{s}")));
    }
    Ok(())
}

/// Append the frame of one JSON line to `frame`: nothing for a diagnostic
/// event; with `only`, an error for a message another end sends. The error
/// has the column where the text went wrong, if it did.
fn encode_line<P: Schema>(
    protocol: &P,
    line: &[u8],
    frame: &mut Vec<u8>,
    only: Option<Peer>,
) -> Result<(), (Option<usize>, String)> {
    let Some(line) = read_line::<P::Line>(line)? else {
        return Ok(());
    };
    let sender = protocol.sent_by(&line);
    match (only, sender) {
        (Some(Peer::Host), Some(Peer::Device)) => Err((
            None,
            "a message the device sends, not one written to it: the port takes the host's \
             commands and requests (a decode --from host would take the device's)"
                .to_owned(),
        )),
        (Some(Peer::Device), Some(Peer::Host)) => Err((
            None,
            "a message the host sends: this decode reads the host's bytes (--from host), so \
             the port takes what the device sends"
                .to_owned(),
        )),
        _ => protocol
            .encode(&line, frame)
            .map_err(|message| (None, message)),
    }
}

/// Turns one JSON line into the bytes of its frame, or says why it cannot.
pub type LineEncoder = Box<dyn Fn(&[u8]) -> Result<Vec<u8>, String> + Send + Sync>;

/// `protocol`'s encoder for single lines, as `encode` reads them, taking
/// only the messages `writes` sends: what a command published back from a
/// live view goes through.
pub fn line_encoder<P: Schema + Send + Sync + 'static>(protocol: P, writes: Peer) -> LineEncoder {
    Box::new(move |line| {
        let mut frame = Vec::new();
        encode_line(&protocol, line, &mut frame, Some(writes)).map_err(|(column, message)| {
            match column {
                Some(column) => format!("column {column}: {message}"),
                None => message,
            }
        })?;
        if frame.is_empty() {
            return Err("a diagnostic event (error, no type) has no bytes to write".to_owned());
        }
        Ok(frame)
    })
}

/// One JSON line read into `L`; `None` for a diagnostic event (an object with
/// `error` and no `type`, as `decode --errors` prints them). The error has
/// the column where the text went wrong, if it did.
fn read_line<L: DeserializeOwned>(line: &[u8]) -> Result<Option<L>, (Option<usize>, String)> {
    let text = std::str::from_utf8(line).map_err(|e| {
        let at = e.valid_up_to();
        (
            Some(at + 1),
            format!("not UTF-8 text (byte {:#04x})", line[at]),
        )
    })?;
    let value: Value = serde_json::from_str(text).map_err(|e| {
        // The column goes with the line number, not into serde's message.
        let message = e.to_string();
        let position = format!(" at line {} column {}", e.line(), e.column());
        let message = message.strip_suffix(&position).unwrap_or(&message);
        (Some(e.column()), format!("not valid JSON: {message}"))
    })?;
    let mut value = value;
    let map = match &mut value {
        Value::Object(map) => map,
        other => return Err((None, format!("expected a JSON object, found {other}"))),
    };
    if !map.contains_key("type") && map.contains_key("error") {
        return Ok(None);
    }
    // A receive time (`--port`, `--timestamps`) is not part of the message.
    map.remove("t");
    serde_json::from_value(value)
        .map(Some)
        .map_err(|e| (None, e.to_string()))
}
