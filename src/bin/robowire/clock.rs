//! Receive times (`"t"`, seconds since the start of the run): read from a
//! monotonic clock as bytes arrive from a port, estimated from the byte
//! offset and the baud rate for a file, or replayed from the index that
//! `--save` wrote beside a capture. A frame's time is when its last byte
//! arrived. Times are kept to the microsecond, as the JSON lines print
//! them, so a replay gives every frame exactly the time it had live.
//!
//! A live run also takes the wall clock once, at its start: the Unix time
//! the MCAP log times count from (the monotonic clock after that, so a
//! clock step during a run moves nothing). The index keeps that start, so
//! a replay's log times are the live ones; `--start` gives it to a file
//! that has none.

use crate::Failure;
use std::collections::VecDeque;
use std::fmt;
use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

/// Bits on the wire per byte at 8N1 (start bit, 8 data bits, stop bit).
pub const BITS_PER_BYTE: f64 = 10.0;

/// How many reads the clock remembers behind the newest: frames are reported
/// soon after their last byte arrives, far fewer reads later than this.
const READS_KEPT: usize = 1 << 16;

/// Where receive times come from.
pub enum Clock {
    /// Bytes arriving now: the time of each read.
    Live {
        /// When the run started.
        start: Instant,
        /// The same moment on the wall clock, in Unix nanoseconds.
        start_unix_ns: u64,
        /// (input offset after the read, seconds) for recent reads.
        reads: VecDeque<(u64, f64)>,
    },
    /// A file: each byte takes [`BITS_PER_BYTE`] bit times at a baud rate.
    Baud {
        /// Seconds per byte.
        per_byte: f64,
    },
    /// A saved capture: the times its index recorded.
    Replay {
        /// The index, read as far as needed.
        index: Index,
        /// (input offset after the read, seconds) read so far and still needed.
        reads: VecDeque<(u64, f64)>,
    },
}

impl Clock {
    /// The live clock, starting now.
    pub fn live() -> Clock {
        let start = Instant::now();
        let since_epoch = SystemTime::now()
            .duration_since(SystemTime::UNIX_EPOCH)
            .unwrap_or_default();
        Clock::Live {
            start,
            start_unix_ns: u64::try_from(since_epoch.as_nanos()).unwrap_or(u64::MAX),
            reads: VecDeque::new(),
        }
    }

    /// The Unix time (ns) of time 0, when it is known: a live run's start,
    /// or the start a replayed index recorded.
    pub fn start_unix_ns(&self) -> Option<u64> {
        match self {
            Clock::Live { start_unix_ns, .. } => Some(*start_unix_ns),
            Clock::Baud { .. } => None,
            Clock::Replay { index, .. } => index.start_unix_ns,
        }
    }

    /// Where the times come from, in words.
    pub fn describe(&self) -> &'static str {
        match self {
            Clock::Live { .. } => "receive time (monotonic clock from a wall-clock start)",
            Clock::Baud { .. } => "estimated from the byte offset at the baud rate",
            Clock::Replay { .. } => "replayed from the capture's .times index",
        }
    }

    /// Estimated times at `baud` bits per second.
    pub fn baud(baud: u32) -> Clock {
        Clock::Baud {
            per_byte: BITS_PER_BYTE / f64::from(baud),
        }
    }

    /// Times replayed from the index at `path`.
    pub fn replay(path: &Path) -> Result<Clock, Failure> {
        Ok(Clock::Replay {
            index: Index::open(path)?,
            reads: VecDeque::new(),
        })
    }

    /// `end` bytes of input have now arrived: the time of that read.
    pub fn arrived(&mut self, end: u64) -> f64 {
        match self {
            Clock::Live { start, reads, .. } => {
                let now = start.elapsed().as_secs_f64();
                if reads.len() == READS_KEPT {
                    reads.pop_front();
                }
                reads.push_back((end, now));
                now
            }
            _ => self.time(end.saturating_sub(1)),
        }
    }

    /// The receive time of the byte at `offset` (the read it came in).
    pub fn time(&mut self, offset: u64) -> f64 {
        match self {
            Clock::Live { reads, .. } => first_after(reads, offset),
            Clock::Baud { per_byte } => (offset + 1) as f64 * *per_byte,
            Clock::Replay { index, reads } => {
                while reads.back().map_or(true, |&(end, _)| end <= offset) {
                    match index.next() {
                        Some(read) => {
                            if reads.len() == READS_KEPT {
                                reads.pop_front();
                            }
                            reads.push_back(read);
                        }
                        None => break,
                    }
                }
                first_after(reads, offset)
            }
        }
    }
}

/// The time of the first read that ends after `offset` (the last known
/// time when none does, 0 before any read).
fn first_after(reads: &VecDeque<(u64, f64)>, offset: u64) -> f64 {
    let i = reads.partition_point(|&(end, _)| end <= offset);
    reads
        .get(i)
        .or(reads.back())
        .map_or(0.0, |&(_, seconds)| seconds)
}

/// The index `--save FILE` writes beside the capture: `FILE.times`.
pub fn index_path(capture: &Path) -> PathBuf {
    let mut name = capture.as_os_str().to_owned();
    name.push(".times");
    PathBuf::from(name)
}

/// A time in seconds as a whole number of microseconds, as printed.
pub fn micros(seconds: f64) -> u64 {
    (seconds * 1e6).round().max(0.0) as u64
}

/// Microseconds as seconds with six decimals (`1.234567`).
pub struct Seconds(pub u64);

impl fmt::Display for Seconds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{:06}", self.0 / 1_000_000, self.0 % 1_000_000)
    }
}

/// The first line of an index.
const INDEX_HEADER: &str = "# robowire receive times: input offset after each read, seconds";

/// The header line that holds the run's start: `# start_unix_ns: N`.
const START_KEY: &str = "# start_unix_ns:";

/// Unix nanoseconds as RFC 3339 UTC (`2026-12-06T03:50:00.123456789Z`).
pub fn rfc3339(unix_ns: u64) -> String {
    let secs = unix_ns / 1_000_000_000;
    let (days, rem) = (secs / 86_400, secs % 86_400);
    // Howard Hinnant's civil_from_days, for days since 1970-01-01.
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}.{:09}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60,
        unix_ns % 1_000_000_000
    )
}

/// `--start TIME`: Unix seconds (`1796529000.25`) or RFC 3339
/// (`2026-12-06T03:50:00Z`, `2026-12-06T04:50:00.5+01:00`), as Unix ns.
pub fn parse_start(text: &str) -> Result<u64, String> {
    let refused = || {
        format!(
            "{text:?}: expected Unix seconds (1796529000.25) or an RFC 3339 time \
             (2026-12-06T03:50:00Z, with an offset such as +01:00 or Z)"
        )
    };
    if let Ok(seconds) = text.parse::<f64>() {
        return (seconds.is_finite() && seconds >= 0.0)
            .then(|| (seconds * 1e9).round() as u64)
            .ok_or_else(refused);
    }
    let (date, time) = text.split_once(['T', 't', ' ']).ok_or_else(refused)?;
    let mut ymd = date.splitn(3, '-').map(|n| n.parse::<i64>().ok());
    let (Some(Some(year)), Some(Some(month)), Some(Some(day))) =
        (ymd.next(), ymd.next(), ymd.next())
    else {
        return Err(refused());
    };
    let (clock, offset) = if let Some(clock) = time.strip_suffix(['Z', 'z']) {
        (clock, 0)
    } else {
        let at = time.rfind(['+', '-']).ok_or_else(refused)?;
        let (clock, zone) = time.split_at(at);
        let sign = if zone.starts_with('-') { -1 } else { 1 };
        let (h, m) = zone[1..].split_once(':').ok_or_else(refused)?;
        let (h, m) = (
            h.parse::<i64>().map_err(|_| refused())?,
            m.parse::<i64>().map_err(|_| refused())?,
        );
        (clock, sign * (h * 3600 + m * 60))
    };
    let (whole, fraction) = clock.split_once('.').unwrap_or((clock, ""));
    let mut hms = whole.splitn(3, ':').map(|n| n.parse::<i64>().ok());
    let (Some(Some(h)), Some(Some(mi)), Some(Some(sec))) = (hms.next(), hms.next(), hms.next())
    else {
        return Err(refused());
    };
    let in_range =
        (1..=12).contains(&month) && (1..=31).contains(&day) && h < 24 && mi < 60 && sec <= 60;
    if !in_range || fraction.len() > 9 || !fraction.bytes().all(|b| b.is_ascii_digit()) {
        return Err(refused());
    }
    let nanos: i64 = format!("{fraction:0<9}").parse().unwrap_or(0);
    // Howard Hinnant's days_from_civil.
    let y = if month <= 2 { year - 1 } else { year };
    let era = y.div_euclid(400);
    let yoe = y.rem_euclid(400);
    let mp = if month > 2 { month - 3 } else { month + 9 };
    let doy = (153 * mp + 2) / 5 + day - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146_097 + doe - 719_468;
    let secs = days * 86_400 + h * 3600 + mi * 60 + sec - offset;
    u64::try_from(secs)
        .ok()
        .and_then(|s| s.checked_mul(1_000_000_000))
        .and_then(|ns| ns.checked_add(nanos as u64))
        .ok_or_else(refused)
}

/// A saved capture's index of receive times, one read per line.
pub struct Index {
    name: String,
    lines: io::Lines<BufReader<File>>,
    number: u64,
    /// The live run's start, from the header (an older robowire wrote none).
    start_unix_ns: Option<u64>,
    /// The first line after the header, read while looking for the start.
    pending: Option<String>,
}

impl Index {
    fn open(path: &Path) -> Result<Index, Failure> {
        let name = path.display().to_string();
        let file = File::open(path).map_err(|error| Failure::Io {
            context: name.clone(),
            error,
        })?;
        let mut index = Index {
            name,
            lines: BufReader::new(file).lines(),
            number: 0,
            start_unix_ns: None,
            pending: None,
        };
        // The header: comment lines before the first read.
        while let Some(Ok(line)) = index.lines.next() {
            match line.strip_prefix(START_KEY) {
                Some(start) => index.start_unix_ns = start.trim().parse().ok(),
                None if line.starts_with('#') => {}
                None => {
                    index.pending = Some(line);
                    break;
                }
            }
            index.number += 1;
        }
        Ok(index)
    }

    /// The next (offset, seconds), skipping comments; a line that does not
    /// read is reported once and ends the index (later frames keep the last time).
    fn next(&mut self) -> Option<(u64, f64)> {
        loop {
            self.number += 1;
            let next = self.pending.take().map(Ok).or_else(|| self.lines.next());
            let line = match next? {
                Ok(line) => line,
                Err(error) => {
                    eprintln!("robowire: {}: {error}", self.name);
                    return None;
                }
            };
            if line.starts_with('#') || line.trim().is_empty() {
                continue;
            }
            let mut words = line.split_whitespace();
            let read = (|| Some((words.next()?.parse().ok()?, words.next()?.parse().ok()?)))();
            if read.is_none() {
                eprintln!(
                    "robowire: {}: line {}: expected an offset and a time in seconds",
                    self.name, self.number
                );
            }
            return read;
        }
    }
}

/// `--save`: the raw bytes as they arrive, and the index of their times.
pub struct Save {
    name: String,
    bytes: BufWriter<File>,
    index_name: String,
    index: BufWriter<File>,
}

impl Save {
    /// Create (or truncate) `path` and its index, whose header holds the
    /// run's start (when known) and `source` (`key: value` lines).
    pub fn create(
        path: &Path,
        start_unix_ns: Option<u64>,
        source: &[(&str, String)],
    ) -> Result<Save, Failure> {
        let index_path = index_path(path);
        let create = |path: &Path| {
            File::create(path)
                .map(|file| BufWriter::with_capacity(64 * 1024, file))
                .map_err(|error| Failure::Io {
                    context: path.display().to_string(),
                    error,
                })
        };
        let mut save = Save {
            name: path.display().to_string(),
            bytes: create(path)?,
            index_name: index_path.display().to_string(),
            index: create(&index_path)?,
        };
        let mut header = format!("{INDEX_HEADER}\n");
        if let Some(start) = start_unix_ns {
            header.push_str(&format!(
                "{START_KEY} {start}\n# start: {}\n",
                rfc3339(start)
            ));
        }
        for (key, value) in source {
            header.push_str(&format!("# {key}: {value}\n"));
        }
        save.index
            .write_all(header.as_bytes())
            .map_err(|e| save.index_failure(e))?;
        Ok(save)
    }

    /// Save `bytes`, which arrived at `seconds` and end at input offset `end`.
    pub fn write(&mut self, bytes: &[u8], end: u64, seconds: f64) -> Result<(), Failure> {
        self.bytes.write_all(bytes).map_err(|e| self.failure(e))?;
        let seconds = Seconds(micros(seconds));
        writeln!(self.index, "{end} {seconds}").map_err(|e| self.index_failure(e))
    }

    /// Write out everything saved so far.
    pub fn flush(&mut self) -> Result<(), Failure> {
        self.bytes.flush().map_err(|e| self.failure(e))?;
        self.index.flush().map_err(|e| self.index_failure(e))
    }

    fn failure(&self, error: io::Error) -> Failure {
        Failure::Io {
            context: self.name.clone(),
            error,
        }
    }

    fn index_failure(&self, error: io::Error) -> Failure {
        Failure::Io {
            context: self.index_name.clone(),
            error,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn start_times_read_as_unix_seconds_or_rfc_3339() {
        let noon = 1_796_558_400_000_000_000; // 2026-12-06T12:00:00Z
        assert_eq!(parse_start("2026-12-06T12:00:00Z"), Ok(noon));
        assert_eq!(parse_start("2026-12-06T13:30:00+01:30"), Ok(noon));
        assert_eq!(parse_start("2026-12-06T07:00:00-05:00"), Ok(noon));
        assert_eq!(
            parse_start("2026-12-06T12:00:00.25Z"),
            Ok(noon + 250_000_000)
        );
        assert_eq!(parse_start("1796558400.5"), Ok(noon + 500_000_000));
        assert_eq!(parse_start("1970-01-01T00:00:00Z"), Ok(0));
        for bad in [
            "",
            "noon",
            "2026-13-01T00:00:00Z",
            "2026-12-06T12:00:00",
            "-5",
            "2026-12-06T12:00Z",
        ] {
            assert!(parse_start(bad).is_err(), "{bad:?}");
        }
        assert_eq!(rfc3339(noon + 1), "2026-12-06T12:00:00.000000001Z");
        assert_eq!(rfc3339(0), "1970-01-01T00:00:00.000000000Z");
        assert_eq!(
            rfc3339(951_782_400_000_000_000),
            "2000-02-29T00:00:00.000000000Z"
        );
    }

    #[test]
    fn times_print_to_the_microsecond_they_are_kept_at() {
        for seconds in [0.0, 0.0000005, 1.2345675, 59.999_999_5, 3_600.000_001] {
            let us = micros(seconds);
            let printed = Seconds(us).to_string();
            assert_eq!(
                micros(printed.parse().unwrap()),
                us,
                "{seconds} → {printed}"
            );
        }
        assert_eq!(Seconds(1_234_567).to_string(), "1.234567");
    }
}
