//! What a decode writes, beyond today's plain JSON lines: receive times,
//! a saved capture, and the other formats (CSV tables, an MCAP recording).
//! Every format reads frames through the library's `serde` form, so none
//! knows a message type.

use crate::clock::{self, micros, Clock, Save, Seconds};
use crate::csv::Tables;
use crate::driver::{DecodeCommon, LineEncoder};
use crate::flatten::Row;
use crate::json_schema::channel_schema;
use crate::mcap::Recording;
use crate::Failure;
use clap::{Args, ValueEnum};
use robowire::stream::{OwnedFrame, Rejected};
use robowire::units::FieldTable;
use serde::Serialize;
use std::fs::File;
use std::io::{self, BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};

/// The output formats of `decode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One JSON object per line, per frame (stdout, or -o FILE).
    Jsonl,
    /// One CSV file per message type, in the directory -o DIR.
    Csv,
    /// An MCAP recording (Foxglove, PlotJuggler), to -o FILE or a pipe.
    Mcap,
}

/// How an MCAP recording's chunks are compressed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Compression {
    /// Zstandard (the default: what Foxglove and the mcap CLI write).
    Zstd,
    /// LZ4: faster, larger files.
    Lz4,
    /// No compression.
    None,
}

impl Compression {
    /// The `mcap` crate's name for it.
    pub fn for_mcap(self) -> Option<mcap::Compression> {
        match self {
            Compression::Zstd => Some(mcap::Compression::Zstd),
            Compression::Lz4 => Some(mcap::Compression::Lz4),
            Compression::None => None,
        }
    }
}

/// How recordings and tables are split.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Topics {
    /// A topic per thing a robot has: `/PROTOCOL/TYPE/ENTITY` for messages
    /// about a pin, sensor or module (`/telemetrix/sensor_report/0`),
    /// `/PROTOCOL/TYPE` for the others; CSV tables `TYPE_KEYVALUE.csv`.
    Entity,
    /// A topic per message type, `/TYPE`; a CSV table per type.
    Type,
}

/// The options of a `decode` that choose its output.
#[derive(Debug, Args)]
pub struct FormatArgs {
    /// The output format: jsonl (the default), csv (one file per message
    /// type, in -o DIR) or mcap (a recording, to -o FILE or a pipe).
    #[arg(long, value_enum, default_value_t = Format::Jsonl, display_order = 11)]
    pub format: Format,
    /// Where the output goes: a file (jsonl, mcap) or a directory (csv).
    #[arg(short = 'o', long = "output", value_name = "PATH", display_order = 12)]
    pub output: Option<PathBuf>,
    /// How an MCAP recording's chunks are compressed: zstd (the default),
    /// lz4 or none.
    #[arg(long, value_enum, value_name = "CODEC", display_order = 13)]
    pub compression: Option<Compression>,
    /// How MCAP channels and CSV tables are split: a topic per pin, sensor
    /// and module (`/telemetrix/analog_report/26`, the default), or one per
    /// message type (`/analog_report`).
    #[arg(long, value_enum, default_value_t = Topics::Entity, display_order = 14)]
    pub topics: Topics,
    /// Overwrite the -o and --save files (or fill a non-empty -o DIR) if
    /// they exist; without it an existing one is refused before anything is
    /// read.
    #[arg(long, display_order = 15)]
    pub force: bool,
}

impl FormatArgs {
    /// Refuse, unless `--force`, to write over a file that exists: the
    /// output (a non-empty directory for CSV) and a `--save` capture with
    /// its index. Devices and pipes (`/dev/null`) are written as always.
    /// Checked before the input is read, so a file judged whole is not
    /// decoded first.
    pub fn refuse_overwrite(&self, save: Option<&Path>) -> Result<(), Failure> {
        if self.force {
            return Ok(());
        }
        let save_files = save
            .into_iter()
            .flat_map(|path| [path.to_owned(), clock::index_path(path)]);
        for path in self.output.iter().cloned().chain(save_files) {
            let taken = match std::fs::metadata(&path) {
                Ok(meta) if meta.is_dir() => std::fs::read_dir(&path)
                    .is_ok_and(|mut entries| entries.next().is_some())
                    .then_some("is not empty"),
                Ok(meta) => meta.is_file().then_some("exists"),
                Err(_) => None,
            };
            if let Some(what) = taken {
                return Err(Failure::Usage(format!(
                    "{} {what}: robowire does not write over an earlier recording; name \
                     another or add --force",
                    path.display()
                )));
            }
        }
        Ok(())
    }
}

/// What `robowire plot` asks of a decode (nothing without `cli-plot`).
#[cfg(feature = "cli-plot")]
pub type PlotRequest = crate::plot::PlotArgs;
/// What `robowire plot` asks of a decode (nothing without `cli-plot`).
#[cfg(not(feature = "cli-plot"))]
pub type PlotRequest = std::convert::Infallible;

/// Where the formatted events go.
enum Sink {
    /// JSON lines to stdout (`None`) or a file.
    Jsonl(Option<(String, BufWriter<File>)>),
    /// CSV tables.
    Csv(Tables),
    /// An MCAP recording.
    Mcap(Box<Recording>),
    /// A plot, drawn at the end.
    #[cfg(feature = "cli-plot")]
    Plot(Box<crate::plot::Plot>),
}

impl Sink {
    /// The sink `format` asks for; `None` for plain JSON lines on stdout
    /// when `plain` (nothing else to record either).
    fn open(
        format: &FormatArgs,
        plain: bool,
        fields: &'static FieldTable,
    ) -> Result<Option<Sink>, Failure> {
        if format.compression.is_some() && format.format != Format::Mcap {
            return Err(Failure::Usage(
                "--compression is for --format mcap (the other formats are text)".to_owned(),
            ));
        }
        let compression = format.compression.unwrap_or(Compression::Zstd).for_mcap();
        Ok(Some(match (format.format, format.output.as_deref()) {
            (Format::Jsonl, None) if plain => return Ok(None),
            (Format::Jsonl, None) => Sink::Jsonl(None),
            (Format::Jsonl, Some(path)) => {
                Sink::Jsonl(Some((path.display().to_string(), create(path)?)))
            }
            (Format::Csv, Some(dir)) => Sink::Csv(Tables::create(dir, fields, format.topics)?),
            (Format::Csv, None) => {
                return Err(Failure::Usage(
                    "--format csv writes one file per message type: name a directory with -o DIR"
                        .to_owned(),
                ))
            }
            (Format::Mcap, Some(path)) => {
                let file = Box::new(create(path)?);
                Sink::Mcap(Box::new(Recording::create(
                    path.display().to_string(),
                    file,
                    compression,
                )?))
            }
            (Format::Mcap, None) if io::stdout().is_terminal() => {
                return Err(Failure::Usage(MCAP_TERMINAL.to_owned()))
            }
            (Format::Mcap, None) => {
                let out = Box::new(BufWriter::with_capacity(256 * 1024, io::stdout()));
                Sink::Mcap(Box::new(Recording::create(
                    "stdout".to_owned(),
                    out,
                    compression,
                )?))
            }
        }))
    }
}

/// Why `--format mcap` does not write to a terminal.
const MCAP_TERMINAL: &str =
    "--format mcap writes a binary file: name it with -o FILE, or pipe stdout into a program";

/// Create (or truncate) the file at `path`, buffered.
fn create(path: &Path) -> Result<BufWriter<File>, Failure> {
    File::create(path)
        .map(|file| BufWriter::with_capacity(256 * 1024, file))
        .map_err(|error| Failure::Io {
            context: path.display().to_string(),
            error,
        })
}

/// The formats, times and saved capture of one decode; absent for plain
/// JSON lines on stdout without times, which print as they always have.
pub struct Recorder {
    clock: Option<Clock>,
    save: Option<Save>,
    sink: Sink,
    /// Bytes observed so far.
    fed: u64,
    /// Events written so far (the MCAP log time without a clock).
    events: u64,
    /// Rejections among them.
    #[cfg(feature = "cli-plot")]
    rejections: u64,
    /// Frames written so far.
    frames: u64,
    row: Row,
    text: Vec<u8>,
    /// A failure to save bytes, reported with the next event.
    pending: Option<Failure>,
    /// What the protocol's fields mean.
    fields: &'static FieldTable,
    /// The Unix time of time 0 (0 when unknown), for MCAP log times.
    start_unix_ns: u64,
    /// How channels are split.
    topics: Topics,
    /// The topic of the event being written.
    topic: String,
    /// The live Foxglove view, if one is served.
    #[cfg(feature = "cli-foxglove")]
    view: Option<crate::foxglove::LiveView>,
}

impl Recorder {
    /// The recorder `common`'s options (and `plot`, for `robowire plot`)
    /// ask for, if they ask for more than plain JSON lines on stdout;
    /// `encoder` gives a live view the protocol's encoder for commands back.
    pub fn new(
        common: &DecodeCommon,
        plot: Option<PlotRequest>,
        fields: &'static FieldTable,
        encoder: impl FnOnce() -> LineEncoder,
    ) -> Result<Option<Recorder>, Failure> {
        let (live, format) = (&common.live, &common.format);
        let clock = if live.port.is_some() {
            Some(Clock::live())
        } else if live.timestamps {
            let replay = common
                .input
                .as_deref()
                .filter(|p| p.as_os_str() != "-")
                .map(clock::index_path)
                .filter(|index| index.is_file());
            Some(match replay {
                Some(index) => Clock::replay(&index)?,
                None => Clock::baud(live.baud),
            })
        } else {
            None
        };
        let plain = clock.is_none() && live.save.is_none();
        let sink = match plot {
            #[cfg(feature = "cli-plot")]
            Some(plot) if format.format == Format::Jsonl => {
                let output = format.output.as_deref();
                let source = match (&live.port, common.input.as_deref()) {
                    (Some(port), _) => port.clone(),
                    (None, Some(path)) if path.as_os_str() != "-" => {
                        path.file_name().map_or(path.display().to_string(), |n| {
                            n.to_string_lossy().into_owned()
                        })
                    }
                    _ => "stdin".to_owned(),
                };
                let plot = crate::plot::Plot::new(
                    plot,
                    output,
                    clock.is_some(),
                    common.errors,
                    fields,
                    source,
                )?;
                Some(Sink::Plot(Box::new(plot)))
            }
            #[cfg(feature = "cli-plot")]
            Some(_) => {
                return Err(Failure::Usage(
                    "robowire plot draws a picture: leave out --format".to_owned(),
                ))
            }
            _ => Sink::open(format, plain, fields)?,
        };
        let Some(mut sink) = sink else {
            return Ok(None);
        };
        #[cfg(feature = "cli-foxglove")]
        let view = match (common.foxglove.foxglove, &live.port) {
            #[cfg(feature = "cli-plot")]
            (Some(_), _) if matches!(sink, Sink::Plot(_)) => {
                return Err(Failure::Usage(
                    "--foxglove serves a live decode: use it with robowire decode".to_owned(),
                ))
            }
            (Some(addr), Some(port)) => Some(crate::foxglove::LiveView::start(
                &common.foxglove,
                addr,
                fields.protocol,
                (port, live.baud),
                encoder(),
            )?),
            _ => None,
        };
        #[cfg(not(feature = "cli-foxglove"))]
        let _ = encoder;
        let start_unix_ns = live
            .start
            .or_else(|| clock.as_ref().and_then(Clock::start_unix_ns));
        let mut source = vec![
            ("robowire", env!("CARGO_PKG_VERSION").to_owned()),
            ("protocol", fields.protocol.to_owned()),
            (
                "command",
                std::env::args().skip(1).collect::<Vec<_>>().join(" "),
            ),
        ];
        match (&live.port, common.input.as_deref()) {
            (Some(port), _) => {
                source.push(("port", port.clone()));
                source.push(("baud", live.baud.to_string()));
            }
            (None, Some(path)) if path.as_os_str() != "-" => {
                source.push(("input", path.display().to_string()));
            }
            _ => source.push(("input", "stdin".to_owned())),
        }
        source.push((
            "time_source",
            clock
                .as_ref()
                .map_or("none: log times are frame indices", Clock::describe)
                .to_owned(),
        ));
        let save = match live.save.as_deref() {
            Some(path) => Some(Save::create(path, start_unix_ns, &source)?),
            None => None,
        };
        if let Sink::Mcap(recording) = &mut sink {
            let mut metadata = source.clone();
            if let Some(start) = start_unix_ns {
                metadata.push(("start_unix_ns", start.to_string()));
                metadata.push(("start", crate::clock::rfc3339(start)));
            }
            recording.metadata(&metadata)?;
            if clock.is_none() {
                eprintln!(
                    "robowire: {}: no receive times, so the log times are frame indices \
                     (0, 1, 2 … ns): add --timestamps (the capture's .times index, or its \
                     baud rate) and --start TIME for wall-clock times",
                    recording.name()
                );
            } else if start_unix_ns.is_none() {
                eprintln!(
                    "robowire: {}: log times count from 0 (1970 in a viewer): add --start TIME \
                     for wall-clock times",
                    recording.name()
                );
            }
        }
        Ok(Some(Recorder {
            clock,
            save,
            sink,
            fed: 0,
            events: 0,
            #[cfg(feature = "cli-plot")]
            rejections: 0,
            frames: 0,
            row: Row::default(),
            text: Vec::with_capacity(256),
            pending: None,
            fields,
            start_unix_ns: start_unix_ns.unwrap_or(0),
            topics: format.topics,
            topic: String::new(),
            #[cfg(feature = "cli-foxglove")]
            view,
        }))
    }

    /// `bytes` arrived (they are about to be decoded).
    pub fn observe(&mut self, bytes: &[u8]) {
        self.fed += bytes.len() as u64;
        let seconds = match &mut self.clock {
            Some(clock) => clock.arrived(self.fed),
            None => 0.0,
        };
        if let Some(save) = &mut self.save {
            if self.pending.is_none() {
                if let Err(failure) = save.write(bytes, self.fed, seconds) {
                    self.pending = Some(failure);
                }
            }
        }
    }

    /// Write one event; rejections only when `errors`.
    pub fn event<M: Serialize, E: Serialize>(
        &mut self,
        event: Result<OwnedFrame<M>, Rejected<E>>,
        errors: bool,
        stdout: &mut dyn Write,
    ) -> Result<(), Failure> {
        if let Some(failure) = self.pending.take() {
            return Err(failure);
        }
        match event {
            Ok(frame) => {
                let last = (frame.offset + frame.len as u64).saturating_sub(1);
                self.write(&frame, last, true, stdout)
            }
            Err(rejected) if errors => {
                let at = rejected.offset;
                self.write(&rejected, at, false, stdout)
            }
            Err(_) => Ok(()),
        }
    }

    /// Write `event` (a frame, or a rejection), whose last byte is at input
    /// offset `last`.
    fn write<T: Serialize>(
        &mut self,
        event: &T,
        last: u64,
        frame: bool,
        stdout: &mut dyn Write,
    ) -> Result<(), Failure> {
        // Times to the microsecond, as printed: a replay gives the same.
        let micros = self.clock.as_mut().map(|clock| micros(clock.time(last)));
        let seconds = micros.map(|us| us as f64 / 1e6);
        let index = self.events;
        self.events += 1;
        let frame_number = self.frames;
        self.frames += u64::from(frame);
        #[cfg(feature = "cli-plot")]
        if let Sink::Plot(plot) = &mut self.sink {
            // The x axis: the receive time, or the number of frames before.
            let x = seconds.unwrap_or((index - self.rejections) as f64);
            if frame {
                self.row.clear();
                self.row.walk(event).map_err(bug)?;
                plot.frame(&self.row, x);
            } else {
                self.rejections += 1;
                plot.rejected(x);
            }
            return Ok(());
        }
        if let Sink::Csv(tables) = &mut self.sink {
            self.row.clear();
            if let Some(us) = micros {
                self.row.push_number("t", Seconds(us));
            }
            self.row.walk(event).map_err(bug)?;
            tables.write(&self.row, frame_number)?;
            if !self.has_view() {
                return Ok(());
            }
        }
        let channels = matches!(self.sink, Sink::Mcap(_)) || self.has_view();
        let text = &mut self.text;
        text.clear();
        serde_json::to_writer(&mut *text, event).map_err(bug)?;
        if let Some(us) = micros {
            // `{"t":…,` before the event's own members.
            let members = text.split_off(1);
            text.clear();
            let _ = write!(text, "{{\"t\":{}", Seconds(us));
            if members.len() > 1 {
                text.push(b',');
            }
            text.extend_from_slice(&members);
        }
        let kind = match channels.then(|| leading_kind(text, frame)) {
            None => "",
            Some(Some(kind)) => kind,
            Some(None) => {
                self.row.names_of(event).map_err(bug)?;
                match self.row.type_name.as_str() {
                    "" => "rejected",
                    name => name,
                }
            }
        };
        // The time as printed (microseconds) after the start, in Unix
        // nanoseconds; the event's index without times.
        let nanoseconds = micros.map_or(index, |us| {
            self.start_unix_ns.saturating_add(us.saturating_mul(1000))
        });
        let fields = self.fields;
        let topic = &mut self.topic;
        if channels {
            channel_topic(topic, self.topics, fields, kind, text);
        }
        // The channel's JSON Schema, the first time a sink needs it.
        let schema = || {
            let schema = channel_schema(event, kind, fields, seconds.is_some())
                .map_err(|e| Failure::Reported(format!("cannot describe a frame: {e}")))?;
            Ok(serde_json::to_vec(&schema).expect("a JSON value serializes"))
        };
        #[cfg(feature = "cli-foxglove")]
        if let Some(view) = &mut self.view {
            view.log(kind, topic, text, nanoseconds, schema)?;
        }
        match &mut self.sink {
            Sink::Jsonl(file) => {
                text.push(b'\n');
                match file {
                    Some((name, file)) => file.write_all(text).map_err(|error| Failure::Io {
                        context: name.clone(),
                        error,
                    }),
                    None => stdout.write_all(text).map_err(Failure::stdout),
                }
            }
            Sink::Mcap(recording) => recording.write(kind, topic, text, nanoseconds, schema),
            Sink::Csv(_) => Ok(()),
            #[cfg(feature = "cli-plot")]
            Sink::Plot(_) => unreachable!("plot points are taken above"),
        }
    }

    /// Whether a live view is served.
    fn has_view(&self) -> bool {
        #[cfg(feature = "cli-foxglove")]
        return self.view.is_some();
        #[cfg(not(feature = "cli-foxglove"))]
        false
    }

    /// Write out everything so far (before a read that may wait).
    pub fn flush(&mut self) -> Result<(), Failure> {
        if let Some(save) = &mut self.save {
            save.flush()?;
        }
        match &mut self.sink {
            Sink::Jsonl(Some((name, file))) => file.flush().map_err(|error| Failure::Io {
                context: name.clone(),
                error,
            }),
            Sink::Csv(tables) => tables.flush(),
            Sink::Mcap(recording) => recording.flush(),
            _ => Ok(()),
        }
    }

    /// Complete every output: the saved capture, the tables, the recording's summary.
    pub fn finish(&mut self) -> Result<(), Failure> {
        let saved = self.pending.take().map_or(Ok(()), Err);
        let flushed = self.flush();
        #[cfg(feature = "cli-foxglove")]
        if let Some(view) = &mut self.view {
            view.finish();
        }
        let finished = match &mut self.sink {
            Sink::Mcap(recording) => recording.finish(),
            #[cfg(feature = "cli-plot")]
            Sink::Plot(plot) => plot.finish(),
            _ => Ok(()),
        };
        saved.and(flushed).and(finished)
    }
}

/// Set `topic` to the channel of an event of type `kind` printed as `json`:
/// `/TYPE`, or `/PROTOCOL/TYPE` with `/ENTITY` after it for a type that
/// belongs to a pin, sensor or module.
fn channel_topic(topic: &mut String, topics: Topics, fields: &FieldTable, kind: &str, json: &[u8]) {
    topic.clear();
    match topics {
        Topics::Type => topic.extend(["/", kind]),
        Topics::Entity => {
            topic.extend(["/", fields.protocol, "/", kind]);
            let entity = fields
                .entity_key(kind)
                .and_then(|key| top_level_number(json, key));
            if let Some(entity) = entity {
                topic.extend(["/", entity]);
            }
        }
    }
}

/// The channel of an event printed as `json`, read from the line's start
/// when it has the usual shape: `{["t":T,]"offset":N,"len":N,"type":"NAME"`
/// for a frame (its serde form writes `offset`, `len`, then the message,
/// tag first), `rejected` for a rejection. `None` when the start looks
/// otherwise: the caller then walks the event.
fn leading_kind(json: &[u8], frame: bool) -> Option<&str> {
    if !frame {
        return Some("rejected");
    }
    let mut rest = json.strip_prefix(b"{")?;
    if let Some(after) = rest.strip_prefix(b"\"t\":") {
        rest = &after[after.iter().position(|&b| b == b',')? + 1..];
    }
    for key in [&b"\"offset\":"[..], b"\"len\":"] {
        let after = rest.strip_prefix(key)?;
        let digits = after.iter().take_while(|b| b.is_ascii_digit()).count();
        rest = after[digits..].strip_prefix(b",")?;
    }
    let name = rest.strip_prefix(b"\"type\":\"")?;
    let end = name.iter().position(|&b| b == b'"' || b == b'\\')?;
    (name.get(end) == Some(&b'"'))
        .then(|| std::str::from_utf8(&name[..end]).ok())
        .flatten()
}

/// The number member `key` of the JSON object `json` has at its top level
/// (`"pin":26`), as written.
fn top_level_number<'j>(json: &'j [u8], key: &str) -> Option<&'j str> {
    let (mut depth, mut in_string, mut escaped) = (0usize, false, false);
    let mut i = 0;
    while i < json.len() {
        let b = json[i];
        if in_string {
            match b {
                _ if escaped => escaped = false,
                b'\\' => escaped = true,
                b'"' => in_string = false,
                _ => {}
            }
        } else {
            match b {
                b'{' | b'[' => depth += 1,
                b'}' | b']' => depth = depth.saturating_sub(1),
                b'"' if depth == 1 => {
                    let rest = &json[i + 1..];
                    let named = rest
                        .strip_prefix(key.as_bytes())
                        .and_then(|r| r.strip_prefix(b"\":"));
                    if let Some(value) = named {
                        let digits = value
                            .iter()
                            .take_while(|b| b.is_ascii_digit() || **b == b'-')
                            .count();
                        return std::str::from_utf8(&value[..digits])
                            .ok()
                            .filter(|v| !v.is_empty());
                    }
                    in_string = true;
                }
                b'"' => in_string = true,
                _ => {}
            }
        }
        i += 1;
    }
    None
}

/// The library's types always serialize: a failure here is a bug in
/// robowire, reported rather than hidden.
fn bug(error: impl std::fmt::Display) -> Failure {
    Failure::Reported(format!("cannot write an event: {error}"))
}
