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
mod input;
mod mcap;
mod omnitiles;
mod pixy2;
#[cfg(feature = "cli-plot")]
mod plot;
mod port;
mod telemetrix;

use clap::{Parser, Subcommand};
use robowire::omnitiles::Layout;
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

Exit status: 0 on success, 2 on usage errors and invalid input, 1 on I/O errors.
A closed stdout pipe ends the run quietly. `robowire decode <protocol> --help`
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

/// What a warning after `protocol`'s decode may suggest ([`driver::Hints`]).
fn hints(protocol: &DecodeProtocol) -> driver::Hints {
    let hex = |common: &driver::DecodeCommon| (!common.hex).then_some("--hex");
    match protocol {
        DecodeProtocol::Omnitiles(args) => (
            hex(&args.common)
                .filter(|_| !args.datagrams)
                .map(|_| "--hex, or --datagrams when each line is one datagram"),
            "--from and --layout",
            !args.datagrams
                && args.from != omnitiles::Side::Host
                && !args.layout.iter().any(|set| set.contains(Layout::Spi45)),
        ),
        DecodeProtocol::Pixy2(args) => (hex(&args.common), "--from", false),
        DecodeProtocol::Telemetrix(args) => (hex(&args.common), "--from and --dialect", false),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let mut out = driver::Output::stdout();
    let result = run(&cli.command, &mut out);
    // Frames decoded before a failure are still written, recordings completed.
    let flushed = out.finish();
    let done = match (result, flushed) {
        (Err(Failure::BrokenPipe), _) | (_, Err(Failure::BrokenPipe)) => return ExitCode::SUCCESS,
        (Err(failure), _) | (Ok(_), Err(failure)) => return failure.report(),
        (Ok(done), Ok(())) => done,
    };
    match (done, cli.command.decoding()) {
        (Done::Decoded(decoded), Some(protocol)) => {
            // An input that could not be read at all has nothing to sum up.
            if let (Some(failure @ Failure::Io { .. }), 0) = (&decoded.failure, decoded.stats.bytes)
            {
                return failure.report();
            }
            eprintln!("{}", driver::summary(&decoded.stats));
            if let Some(warning) = driver::warning(&decoded.stats, &out, hints(protocol)) {
                eprintln!("robowire: warning: {warning}");
            }
            match decoded.failure {
                Some(failure) => failure.report(),
                None => ExitCode::SUCCESS,
            }
        }
        _ => ExitCode::SUCCESS,
    }
}
