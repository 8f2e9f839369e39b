//! Live serial ports: `--port DEVICE --baud RATE` for `decode` (bytes read
//! as they arrive, frames stamped with their receive time) and for `encode`
//! (frames written to the port). Ctrl-C, SIGTERM and SIGHUP end a live
//! decode as the end of the input does: every frame decoded so far is
//! written, the summary printed, a `--save` capture and a recording
//! completed.

use crate::Failure;
use clap::Args;
use std::io::{self, IsTerminal, Read, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How long a read waits before looking for a stop (Ctrl-C, SIGTERM, SIGHUP) again.
const READ_TIMEOUT: Duration = Duration::from_millis(50);
/// How long a silent port is read before the outputs are written out.
const PAUSE: Duration = Duration::from_millis(200);

/// How long a write may wait for the port to drain before it fails.
const WRITE_TIMEOUT: Duration = Duration::from_secs(10);

/// The options of a `decode` that name where bytes come from and when.
#[derive(Debug, Args)]
pub struct LiveArgs {
    /// Read from the serial port DEVICE (e.g. /dev/ttyACM0) instead of INPUT;
    /// every frame gets its receive time "t" (seconds since the start).
    ///
    /// Ctrl-C (or SIGTERM, SIGHUP) ends the run cleanly: every frame
    /// decoded so far is written, every output completed and the summary
    /// printed.
    #[arg(
        long,
        value_name = "DEVICE",
        conflicts_with = "input",
        display_order = 7
    )]
    pub port: Option<String>,
    /// The port's baud rate (8N1); with --timestamps, the rate the file's
    /// times are estimated at.
    #[arg(
        long,
        value_name = "RATE",
        default_value_t = 115_200,
        value_parser = clap::value_parser!(u32).range(1..),
        display_order = 8
    )]
    pub baud: u32,
    /// Give frames from a file a time "t" too: replayed from INPUT.times
    /// when --save wrote one, otherwise estimated from the byte offset at
    /// --baud (an estimate: it assumes the line was never idle).
    #[arg(long, display_order = 9)]
    pub timestamps: bool,
    /// Save the raw bytes as they arrive to FILE, and their receive times
    /// to FILE.times (so `decode FILE --timestamps` replays them).
    #[arg(long, value_name = "FILE", display_order = 10)]
    pub save: Option<PathBuf>,
    /// The wall-clock time of time 0 for --timestamps: Unix seconds or RFC
    /// 3339 (2026-12-06T03:50:00Z). MCAP log times count from it (a live
    /// run takes it from the system clock; a replayed index keeps it).
    #[arg(
        long,
        value_name = "TIME",
        requires = "timestamps",
        value_parser = crate::clock::parse_start,
        display_order = 11
    )]
    pub start: Option<u64>,
    /// With --port, the milliseconds of silence after which a frame that
    /// only the next byte would decide is taken as ended (a 7-byte
    /// OmniTiles frame that may begin a longer one). The default, 5 ms
    /// plus 3.5 byte-times at --baud, covers a USB serial adapter's
    /// latency on most hosts; an FTDI adapter at its default 16 ms latency
    /// needs 20. 0 waits for the next frame instead.
    #[arg(
        long,
        value_name = "MS",
        value_parser = parse_idle,
        display_order = 12
    )]
    pub idle: Option<f64>,
}

/// `--idle MS`: a finite number of milliseconds from 0.
fn parse_idle(text: &str) -> Result<f64, String> {
    text.parse::<f64>()
        .ok()
        .filter(|ms| ms.is_finite() && *ms >= 0.0)
        .ok_or_else(|| "the milliseconds of silence must be a number from 0".to_owned())
}

impl LiveArgs {
    /// The idle gap of a live port at `--baud` (`None`: `--idle 0`).
    pub fn idle_gap(&self) -> Option<Duration> {
        match self.idle {
            Some(0.0) => None,
            Some(ms) => Some(Duration::from_secs_f64(ms / 1000.0)),
            None => {
                let bytes = robowire::Idle::at_baud(self.baud, 3.5).gap();
                Some(ADAPTER_LATENCY + Duration::from_micros(bytes))
            }
        }
    }
}

/// What the default idle gap allows for a USB serial adapter's latency.
const ADAPTER_LATENCY: Duration = Duration::from_millis(5);

/// The options of an `encode` that send frames to a port.
#[derive(Debug, Args)]
pub struct EncodePort {
    /// Write the frames to the serial port DEVICE instead of stdout.
    #[arg(long, value_name = "DEVICE", conflicts_with = "hex")]
    pub port: Option<String>,
    /// The port's baud rate (8N1).
    #[arg(
        long,
        value_name = "RATE",
        default_value_t = 115_200,
        value_parser = clap::value_parser!(u32).range(1..),
    )]
    pub baud: u32,
}

/// Open `device` at `baud`, 8N1, its reads and writes waiting at most
/// `timeout`, shared with other robowire runs. A missing device, a
/// permission problem or a path that is no serial port is one line.
fn open(
    device: &str,
    baud: u32,
    timeout: Duration,
) -> Result<Box<dyn serialport::SerialPort>, Failure> {
    let builder = serialport::new(device, baud).timeout(timeout);
    // A shared lock, not an exclusive one: `encode --port` may write to the
    // port a `decode --port` is reading (a request, a command back), as
    // two handles in one program would. Another program that asks for the
    // port exclusively is still refused while robowire has it.
    #[cfg(unix)]
    let builder = builder.exclusive(false);
    builder.open().map_err(|error| {
        if let Some(failure) = not_a_port(device) {
            return failure;
        }
        let error = io::Error::from(error);
        let hint = match error.kind() {
            io::ErrorKind::PermissionDenied => {
                " (on Linux, add yourself to the group that owns it, often dialout)"
            }
            _ => "",
        };
        Failure::Io {
            context: format!("{device}: cannot open the serial port{hint}"),
            error,
        }
    })
}

/// Why `device`, which did not open as a serial port, is none: a regular
/// file or a directory, or a device that is no terminal (`/dev/null`); the
/// system's own words for that ("Not a typewriter") would only puzzle.
fn not_a_port(device: &str) -> Option<Failure> {
    let meta = std::fs::metadata(device).ok()?;
    let what = if meta.is_file() {
        "a regular file"
    } else if meta.is_dir() {
        "a directory"
    } else if std::fs::File::open(device).is_ok_and(|file| !file.is_terminal()) {
        "a device that is no terminal"
    } else {
        return None;
    };
    Some(Failure::Invalid(format!(
        "{device} is {what}, not a serial port: without --port, decode reads a file named \
         as INPUT and encode writes to stdout"
    )))
}

/// A serial port as the decode loop reads it: whatever has arrived, waiting
/// at most [`READ_TIMEOUT`] at a time so a stop is seen, and nothing after
/// [`PAUSE`] of silence, so the outputs are written out while the link is
/// quiet.
pub struct PortSource {
    name: String,
    port: Box<dyn serialport::SerialPort>,
    stop: Arc<AtomicBool>,
    idle: Option<Duration>,
}

impl PortSource {
    /// Open `device` and end the run on Ctrl-C, SIGTERM or SIGHUP; the
    /// line counts as idle after `idle` without a byte.
    pub fn open(device: &str, baud: u32, idle: Option<Duration>) -> Result<PortSource, Failure> {
        let port = open(device, baud, READ_TIMEOUT)?;
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        // Only one handler per process: a second `set_handler` cannot happen here.
        ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst)).map_err(|error| {
            Failure::Io {
                context: "cannot catch Ctrl-C, SIGTERM and SIGHUP".to_owned(),
                error: io::Error::other(error),
            }
        })?;
        eprintln!("robowire: reading {device} at {baud} baud; Ctrl-C ends the run");
        Ok(PortSource {
            name: device.to_owned(),
            port,
            stop,
            idle,
        })
    }
}

impl crate::input::ByteSource for PortSource {
    fn fill(&mut self, buf: &mut [u8]) -> Result<usize, Failure> {
        let start = Instant::now();
        loop {
            if self.stop.load(Ordering::SeqCst) || start.elapsed() >= PAUSE {
                return Ok(0);
            }
            match self.port.read(buf) {
                Ok(0) | Err(_) if self.stop.load(Ordering::SeqCst) => return Ok(0),
                Ok(0) => {}
                Ok(n) => return Ok(n),
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::TimedOut | io::ErrorKind::Interrupted
                    ) => {}
                Err(error) => {
                    return Err(Failure::Io {
                        context: format!("{}: the serial port failed (unplugged?)", self.name),
                        error,
                    })
                }
            }
        }
    }

    fn may_wait(&self) -> bool {
        true
    }

    fn ended(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }

    fn idle_gap(&self) -> Option<Duration> {
        self.idle
    }

    fn fill_within(&mut self, buf: &mut [u8], wait: Duration) -> Result<usize, Failure> {
        if wait >= READ_TIMEOUT {
            return self.fill(buf);
        }
        // One read that waits until the deadline, then the usual timeout.
        let set = |port: &mut Box<dyn serialport::SerialPort>, timeout| {
            port.set_timeout(timeout).map_err(|error| Failure::Io {
                context: format!("{}: cannot set the read timeout", self.name),
                error: error.into(),
            })
        };
        set(&mut self.port, wait.max(Duration::from_micros(1)))?;
        let read = self.port.read(buf);
        set(&mut self.port, READ_TIMEOUT)?;
        match read {
            Ok(n) => Ok(n),
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::TimedOut | io::ErrorKind::Interrupted
                ) =>
            {
                Ok(0)
            }
            Err(error) => Err(Failure::Io {
                context: format!("{}: the serial port failed (unplugged?)", self.name),
                error,
            }),
        }
    }
}

/// An `encode` destination on a port: frames are written as they are encoded.
pub struct PortSink {
    name: String,
    port: Box<dyn serialport::SerialPort>,
}

impl PortSink {
    /// Open `device` at `baud` for writing.
    pub fn open(device: &str, baud: u32) -> Result<PortSink, Failure> {
        Ok(PortSink {
            name: device.to_owned(),
            port: open(device, baud, WRITE_TIMEOUT)?,
        })
    }

    /// The port's name, for messages.
    pub fn name(&self) -> &str {
        &self.name
    }
}

impl Write for PortSink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.port.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.port.flush()
    }
}
