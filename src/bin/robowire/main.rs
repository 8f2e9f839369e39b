//! `robowire`: decode captures of robot serial protocols into JSON lines, and
//! encode JSON lines back into frames.
//!
//! The protocol-neutral parts live in [`driver`] (decode and encode loops,
//! output through the library's `serde` form, summary) and [`input`] (files,
//! stdin, hex); each protocol is one module with its options, its choice of
//! decoder and its help text, implementing [`driver::Schema`]. Built only
//! with the `cli` feature.

mod clock;
mod csv;
mod driver;
mod export;
mod flatten;
#[cfg(feature = "cli-foxglove")]
mod foxglove;
mod input;
mod json_schema;
mod mcap;
mod omnitiles;
mod pixy2;
#[cfg(feature = "cli-plot")]
mod plot;
mod port;
mod suspicion;
mod telemetrix;

use clap::{Parser, Subcommand};
use std::io;
use std::process::ExitCode;

const ABOUT: &str = "Decode and encode robot serial protocol captures as JSON lines";

const LONG_ABOUT: &str = "\
Decode and encode robot serial protocol captures as JSON lines.

  robowire decode omnitiles [--from tile|host|any] [--layout L[,L...]] [--chunk N]
                            [--hex] [--datagrams] [--as-firmware] [--errors]
                            [INPUT]
  robowire encode omnitiles [--hex] [INPUT]
  robowire decode pixy2 [--from host|device|any] [--checksum-only] [--chunk N]
                        [--hex] [--errors] [INPUT]
  robowire encode pixy2 [--hex] [INPUT]
  robowire decode telemetrix [--from host|pico|any] [--dialect mirte13|mirte12|upstream11]
                             [--lenient] [--chunk N] [--hex] [--errors] [INPUT]
  robowire encode telemetrix [--dialect D] [--hex] [INPUT]

Every decode also takes [--port DEVICE] [--baud RATE] [--timestamps] [--save FILE]
[--format jsonl|csv|mcap] [-o PATH]; every encode [--port DEVICE] [--baud RATE].

decode prints one JSON object per decoded frame; encode reads the same objects and
writes the frames' bytes, so `robowire decode omnitiles x.bin | robowire encode
omnitiles` reproduces every decoded frame byte for byte. INPUT is a file, or `-`
or absent for stdin. Streams of any size run in constant memory.

Exit status: 0 on success, 2 on usage errors and invalid input, 1 on I/O errors,
3 when a decode's output is probably false (hex text without --hex, mostly noise,
OmniTiles SPI buffers without spi45; a file then prints nothing; --allow-noise
accepts it). A closed stdout
pipe ends the run quietly. `robowire decode <protocol> --help`
documents each protocol's JSON schema.";

#[derive(Debug, Parser)]
#[command(name = "robowire", version, about = ABOUT, long_about = LONG_ABOUT)]
struct Cli {
    #[command(subcommand)]
    command: Verb,
}

#[derive(Debug, Subcommand)]
enum Verb {
    /// Decode a capture into JSON lines, one per frame.
    Decode {
        #[command(subcommand)]
        protocol: DecodeProtocol,
    },
    /// Encode JSON lines (as decode prints them) into frames.
    Encode {
        #[command(subcommand)]
        protocol: EncodeProtocol,
    },
    /// Plot decoded fields over time as PNG or SVG (-o FILE.png, --fields a,b.c).
    #[cfg(feature = "cli-plot")]
    Plot {
        #[command(subcommand)]
        protocol: DecodeProtocol,
        /// What to draw.
        #[command(flatten)]
        plot: plot::PlotArgs,
    },
}

impl Verb {
    /// The protocol a decode or a plot decodes.
    fn decoding(&self) -> Option<&DecodeProtocol> {
        match self {
            Verb::Decode { protocol } => Some(protocol),
            #[cfg(feature = "cli-plot")]
            Verb::Plot { protocol, .. } => Some(protocol),
            Verb::Encode { .. } => None,
        }
    }
}

#[derive(Debug, Subcommand)]
enum DecodeProtocol {
    /// OmniTiles: host commands and tile telemetry (0xA5, id, payload, sum).
    Omnitiles(omnitiles::DecodeArgs),
    /// Pixy2: host requests and device responses (ae c1 / af c1 frames).
    Pixy2(pixy2::DecodeArgs),
    /// Telemetrix4RpiPico: host commands and Pico reports (LEN, id, payload).
    Telemetrix(telemetrix::DecodeArgs),
}

#[derive(Debug, Subcommand)]
enum EncodeProtocol {
    /// OmniTiles: commands and telemetry from JSON lines.
    Omnitiles(omnitiles::EncodeArgs),
    /// Pixy2: requests and responses from JSON lines.
    Pixy2(pixy2::EncodeArgs),
    /// Telemetrix4RpiPico: commands and reports from JSON lines.
    Telemetrix(telemetrix::EncodeArgs),
}

/// Why a run stopped early, and so its exit status.
#[derive(Debug)]
pub enum Failure {
    /// Options that do not go together (exit 2).
    Usage(String),
    /// Input that is not what the options say it is (exit 2).
    Invalid(String),
    /// Problems already reported line by line; this sums them up (exit 2).
    Reported(String),
    /// A decode refused before it printed anything, as its output would be
    /// false (exit 3).
    Refused(String),
    /// Reading or writing failed (exit 1).
    Io {
        /// The file or stream.
        context: String,
        /// What failed.
        error: io::Error,
    },
    /// Whoever reads stdout stopped reading: end quietly (exit 0).
    BrokenPipe,
}

impl Failure {
    /// A failed write to stdout.
    pub fn stdout(error: io::Error) -> Failure {
        if error.kind() == io::ErrorKind::BrokenPipe {
            Failure::BrokenPipe
        } else {
            Failure::Io {
                context: "stdout".to_owned(),
                error,
            }
        }
    }

    fn report(&self) -> ExitCode {
        match self {
            Failure::Usage(message) => {
                eprintln!("error: {message}\n\nFor more information, try '--help'.");
                ExitCode::from(2)
            }
            Failure::Invalid(message) | Failure::Reported(message) => {
                eprintln!("robowire: {message}");
                ExitCode::from(2)
            }
            Failure::Refused(message) => {
                eprintln!("robowire: {message}");
                ExitCode::from(suspicion::STATUS)
            }
            Failure::Io { context, error } => {
                eprintln!("robowire: {context}: {error}");
                ExitCode::from(1)
            }
            Failure::BrokenPipe => ExitCode::SUCCESS,
        }
    }
}

/// What a successful run has to say at the end.
enum Done {
    /// A decode: its summary line for stderr.
    Decoded(driver::Decoded),
    /// An encode: nothing to add.
    Encoded,
}

fn run(verb: &Verb, out: &mut driver::Output) -> Result<Done, Failure> {
    #[cfg(feature = "cli-plot")]
    if let Verb::Plot { plot, .. } = verb {
        out.plot = Some(plot.clone());
    }
    match verb {
        #[cfg(feature = "cli-plot")]
        Verb::Plot { protocol, .. } => decode(protocol, out),
        Verb::Decode { protocol } => decode(protocol, out),
        Verb::Encode { protocol } => match protocol {
            EncodeProtocol::Omnitiles(args) => omnitiles::encode(args, out),
            EncodeProtocol::Pixy2(args) => pixy2::encode(args, out),
            EncodeProtocol::Telemetrix(args) => telemetrix::encode(args, out),
        }
        .map(|()| Done::Encoded),
    }
}

fn decode(protocol: &DecodeProtocol, out: &mut driver::Output) -> Result<Done, Failure> {
    match protocol {
        DecodeProtocol::Omnitiles(args) => omnitiles::decode(args, out),
        DecodeProtocol::Pixy2(args) => pixy2::decode(args, out),
        DecodeProtocol::Telemetrix(args) => telemetrix::decode(args, out),
    }
    .map(Done::Decoded)
}

/// What the checks after `protocol`'s decode may suggest, and the options
/// every decode shares (`--allow-noise` accepts a doubtful decode).
fn hints(protocol: &DecodeProtocol) -> (suspicion::Hints, &driver::DecodeCommon) {
    let hex = |common: &driver::DecodeCommon| (!common.hex).then_some("--hex");
    let (hints, common) = match protocol {
        DecodeProtocol::Omnitiles(args) => (
            suspicion::Hints {
                hex: hex(&args.common)
                    .filter(|_| !args.datagrams)
                    .map(|_| "--hex, or --datagrams when each line is one datagram"),
                options: "--from and --layout",
                spi: args.spi_check(),
            },
            &args.common,
        ),
        DecodeProtocol::Pixy2(args) => (
            suspicion::Hints {
                hex: hex(&args.common),
                options: "--from",
                spi: suspicion::SpiCheck::Off,
            },
            &args.common,
        ),
        DecodeProtocol::Telemetrix(args) => (
            suspicion::Hints {
                hex: hex(&args.common),
                options: "--from and --dialect",
                spi: suspicion::SpiCheck::Off,
            },
            &args.common,
        ),
    };
    (hints, common)
}

/// A regular file is judged whole before anything is printed: decoded once
/// into [`driver::Output::judging`] and, if its output is probably false
/// (and the user did not pass `--allow-noise`), not printed, recorded or
/// plotted at all. The exit status then, or `None` to run the decode that
/// prints (which reports any other problem the first pass met). Stdin and
/// ports are streams: their frames are printed as they come, and the
/// warning follows.
fn judge_whole_file(verb: &Verb) -> Option<ExitCode> {
    let (hints, common) = hints(verb.decoding()?);
    if common.allow_noise || !common.is_whole_file() {
        return None;
    }
    let mut out = driver::Output::judging();
    let Ok(Done::Decoded(decoded)) = run(verb, &mut out) else {
        return None;
    };
    let (start, zeros) = out.observed();
    let suspicion = suspicion::assess(&decoded.stats, start, zeros, hints)?;
    if !suspicion.fails || decoded.failure.is_some() {
        return None;
    }
    eprintln!("{}", driver::summary(&decoded.stats));
    eprintln!("robowire: warning: {}", suspicion.warning);
    eprintln!("robowire: {}", suspicion::withheld());
    Some(ExitCode::from(suspicion::STATUS))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Some(status) = judge_whole_file(&cli.command) {
        return status;
    }
    let mut out = driver::Output::stdout();
    let mut result = run(&cli.command, &mut out);
    // Output still held back at the end (an input shorter than the SPI
    // check's gate) is refused as the gate would have refused it.
    if out.holding() && suspicion::spi_buffers(out.observed().0) {
        result = Err(Failure::Refused(suspicion::spi_refusal()));
    }
    let suspicion = match (&result, cli.command.decoding()) {
        (Ok(Done::Decoded(decoded)), Some(protocol)) => {
            let (start, zeros) = out.observed();
            let (hints, common) = hints(protocol);
            let allow_noise = common.allow_noise;
            suspicion::assess(&decoded.stats, start, zeros, hints).map(|s| (s, allow_noise))
        }
        _ => None,
    };
    // Frames decoded before a failure are still written and recordings
    // completed, but the frames of a refused decode are not printed.
    let flushed = out.finish(matches!(result, Err(Failure::Refused(_))));
    let done = match (result, flushed) {
        (Err(Failure::BrokenPipe), _) | (_, Err(Failure::BrokenPipe)) => return ExitCode::SUCCESS,
        (Err(failure), _) | (Ok(_), Err(failure)) => return failure.report(),
        (Ok(done), Ok(())) => done,
    };
    let Done::Decoded(decoded) = done else {
        return ExitCode::SUCCESS;
    };
    // An input that could not be read at all has nothing to sum up.
    if let (Some(failure @ Failure::Io { .. }), 0) = (&decoded.failure, decoded.stats.bytes) {
        return failure.report();
    }
    eprintln!("{}", driver::summary(&decoded.stats));
    let mut status = ExitCode::SUCCESS;
    if let Some((suspicion, allow_noise)) = suspicion {
        eprintln!("robowire: warning: {}", suspicion.warning);
        if suspicion.fails && !allow_noise {
            eprintln!("robowire: {}", suspicion::failed());
            status = ExitCode::from(suspicion::STATUS);
        }
    }
    match decoded.failure {
        // An input failure's status (1 or 2) says more than the noise's.
        Some(failure) => failure.report(),
        None => status,
    }
}
