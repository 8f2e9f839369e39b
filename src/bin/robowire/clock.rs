//! Receive times (`"t"`, seconds since the start of the run): read from a
//! monotonic clock as bytes arrive from a port, estimated from the byte
//! offset and the baud rate for a file, or replayed from the index that
//! `--save` wrote beside a capture. A frame's time is when its last byte
//! arrived.

use crate::Failure;
use std::collections::VecDeque;
use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

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
        Clock::Live {
            start: Instant::now(),
            reads: VecDeque::new(),
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
            Clock::Live { start, reads } => {
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

/// The first line of an index.
const INDEX_HEADER: &str = "# robowire receive times: input offset after each read, seconds";

/// A saved capture's index of receive times, one read per line.
pub struct Index {
    name: String,
    lines: io::Lines<BufReader<File>>,
    number: u64,
}

impl Index {
    fn open(path: &Path) -> Result<Index, Failure> {
        let name = path.display().to_string();
        let file = File::open(path).map_err(|error| Failure::Io {
            context: name.clone(),
            error,
        })?;
        Ok(Index {
            name,
            lines: BufReader::new(file).lines(),
            number: 0,
        })
    }

    /// The next (offset, seconds), skipping comments; a line that does not
    /// read is reported once and ends the index (later frames keep the last time).
    fn next(&mut self) -> Option<(u64, f64)> {
        loop {
            self.number += 1;
            let line = match self.lines.next()? {
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
    /// Create (or truncate) `path` and its index.
    pub fn create(path: &Path) -> Result<Save, Failure> {
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
        writeln!(save.index, "{INDEX_HEADER}").map_err(|e| save.index_failure(e))?;
        Ok(save)
    }

    /// Save `bytes`, which arrived at `seconds` and end at input offset `end`.
    pub fn write(&mut self, bytes: &[u8], end: u64, seconds: f64) -> Result<(), Failure> {
        self.bytes.write_all(bytes).map_err(|e| self.failure(e))?;
        writeln!(self.index, "{end} {seconds:.6}").map_err(|e| self.index_failure(e))
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
