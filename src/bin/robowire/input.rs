//! Where bytes come from: a file or stdin, read in bounded pieces, as raw
//! bytes, as one hex stream, or line by line (hex datagrams, JSON lines).
//! Nothing here holds more than one chunk or one line in memory.

use crate::Failure;
use std::fs::File;
use std::io::{self, BufRead, BufReader, IsTerminal, Read};
use std::path::Path;
use std::sync::mpsc;
use std::thread;
use std::time::Duration;

/// The longest input line accepted (JSON lines, datagram lines), in bytes.
/// A longer line is an error rather than unbounded memory.
pub const MAX_LINE: usize = 1 << 20;

/// Size of the reads beneath the hex and line readers.
const READ_SIZE: usize = 64 * 1024;

/// An open input and the name to use in messages.
pub struct Input {
    name: String,
    reader: Box<dyn Read>,
    /// A regular file: reads fill the caller's buffer. Otherwise (stdin, a
    /// pipe, a serial device) a read returns what has arrived, so a live
    /// stream is decoded as it comes.
    whole_reads: bool,
    /// A read error that followed bytes already returned.
    pending: Option<io::Error>,
    /// Stdin is a terminal and nothing has been read from it yet.
    terminal: bool,
}

impl Input {
    /// Open `path`, or stdin when it is absent or `-`.
    pub fn open(path: Option<&Path>) -> Result<Input, Failure> {
        match path {
            None => Ok(Input::stdin()),
            Some(p) if p.as_os_str() == "-" => Ok(Input::stdin()),
            Some(p) => {
                let name = p.display().to_string();
                let opened = File::open(p).and_then(|file| {
                    let whole_reads = file.metadata()?.is_file();
                    Ok((file, whole_reads))
                });
                match opened {
                    Ok((file, whole_reads)) => Ok(Input {
                        name,
                        reader: Box::new(file),
                        whole_reads,
                        pending: None,
                        terminal: false,
                    }),
                    Err(error) => Err(Failure::Io {
                        context: name,
                        error,
                    }),
                }
            }
        }
    }

    fn stdin() -> Input {
        Input {
            name: "stdin".to_owned(),
            reader: Box::new(io::stdin().lock()),
            whole_reads: false,
            pending: None,
            terminal: io::stdin().is_terminal(),
        }
    }

    /// One read. The first read from a terminal that stays silent for a
    /// second says on stderr what the tool is waiting for; the thread that
    /// says so ends with that read.
    fn read_some(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if !std::mem::take(&mut self.terminal) {
            return self.reader.read(buf);
        }
        let (arrived, silence) = mpsc::channel::<()>();
        thread::scope(|scope| {
            // Ends when the read returns and `arrived` is dropped, if not before.
            scope.spawn(move || {
                if silence.recv_timeout(Duration::from_secs(1))
                    == Err(mpsc::RecvTimeoutError::Timeout)
                {
                    eprintln!(
                        "robowire: waiting for input on stdin (a terminal): type or paste it \
                         and end it with Ctrl-D, or name an input file"
                    );
                }
            });
            let read = self.reader.read(buf);
            drop(arrived);
            read
        })
    }

    /// The input's name (a path or `stdin`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether a read may wait for bytes that have not arrived yet (stdin, a
    /// pipe, a device), as opposed to a regular file.
    pub fn may_wait(&self) -> bool {
        !self.whole_reads
    }

    fn failure(&self, error: io::Error) -> Failure {
        Failure::Io {
            context: self.name.clone(),
            error,
        }
    }

    /// Read into `buf`: from a regular file until `buf` is full or the file
    /// ends (so `--chunk` pieces are exact), from anything else what one read
    /// returns. `Ok(0)` only at the end of the input.
    fn read_chunk(&mut self, buf: &mut [u8]) -> Result<usize, Failure> {
        if let Some(error) = self.pending.take() {
            return Err(self.failure(error));
        }
        let mut n = 0;
        while n < buf.len() {
            match self.read_some(&mut buf[n..]) {
                Ok(0) => break,
                Ok(k) => {
                    n += k;
                    if !self.whole_reads {
                        break;
                    }
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) if n > 0 => {
                    self.pending = Some(e);
                    break;
                }
                Err(e) => return Err(self.failure(e)),
            }
        }
        Ok(n)
    }
}

/// A stream of bytes to decode, delivered in pieces of the caller's size.
pub trait ByteSource {
    /// Fill `buf` as far as the input allows; `Ok(0)` at the end, or, from
    /// a source that is not [`ended`](Self::ended), after a while with
    /// nothing to read (so the caller can write out what it holds). Bytes
    /// that precede an error are returned first; the error comes on the
    /// next call.
    fn fill(&mut self, buf: &mut [u8]) -> Result<usize, Failure>;

    /// Whether the next [`fill`](Self::fill) may wait for input to arrive.
    fn may_wait(&self) -> bool;

    /// Whether an `Ok(0)` from [`fill`](Self::fill) was the end of the
    /// input, not a pause.
    fn ended(&self) -> bool {
        true
    }

    /// The silence after which the line counts as idle, so that a frame
    /// only the next byte would decide comes out ([`robowire::Idle`]): a
    /// live port's; `None` for a file or a pipe, whose pauses say nothing
    /// about where frames end.
    fn idle_gap(&self) -> Option<Duration> {
        None
    }

    /// [`fill`](Self::fill), waiting at most `wait` for the first byte:
    /// `Ok(0)` after `wait` without one.
    fn fill_within(&mut self, buf: &mut [u8], wait: Duration) -> Result<usize, Failure> {
        let _ = wait;
        self.fill(buf)
    }
}

/// Raw bytes, as they are.
pub struct RawBytes(pub Input);

impl ByteSource for RawBytes {
    fn fill(&mut self, buf: &mut [u8]) -> Result<usize, Failure> {
        self.0.read_chunk(buf)
    }

    fn may_wait(&self) -> bool {
        self.0.may_wait()
    }
}

/// Why hex text is not valid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HexError {
    /// A byte that is no hex digit, separator or `0x` prefix.
    Invalid(u8),
    /// The digits ended in the middle of a byte.
    OddDigits,
}

impl std::fmt::Display for HexError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            HexError::Invalid(b) if b.is_ascii_graphic() => {
                write!(f, "invalid hex digit '{}'", b as char)
            }
            HexError::Invalid(b) => write!(f, "invalid byte {b:#04x} in hex text"),
            HexError::OddDigits => write!(f, "odd number of hex digits"),
        }
    }
}

/// Hex text to bytes, one character at a time. Whitespace and commas separate
/// tokens; a token may begin with `0x` or `0X`, which is ignored. Digits pair
/// up into bytes across separators (`a5 60`, `a560`, `0xa5,0x60` are the same).
#[derive(Debug, Default, Clone, Copy)]
pub struct HexParser {
    /// The first digit of an unfinished byte.
    high: Option<u8>,
    /// Inside a token (not just after a separator).
    in_token: bool,
    /// A `0` began a token: a digit, or the start of a `0x` prefix.
    zero_pending: bool,
}

impl HexParser {
    /// Take one character; returns a completed byte, if any.
    pub fn push(&mut self, c: u8) -> Result<Option<u8>, HexError> {
        if self.zero_pending {
            self.zero_pending = false;
            if c == b'x' || c == b'X' {
                return Ok(None);
            }
            // The `0` was a digit and `c` still needs handling. Two nibbles
            // complete at most one byte, so at most one of these is `Some`.
            let first = self.nibble(0);
            let second = self.push(c)?;
            return Ok(first.or(second));
        }
        if c.is_ascii_whitespace() || c == b',' {
            self.in_token = false;
            return Ok(None);
        }
        let digit = match c {
            b'0'..=b'9' => c - b'0',
            b'a'..=b'f' => c - b'a' + 10,
            b'A'..=b'F' => c - b'A' + 10,
            _ => return Err(HexError::Invalid(c)),
        };
        if !self.in_token {
            self.in_token = true;
            if digit == 0 {
                self.zero_pending = true;
                return Ok(None);
            }
        }
        Ok(self.nibble(digit))
    }

    /// The text ended (a separator is implied); fails if half a byte is left.
    pub fn finish(&mut self) -> Result<Option<u8>, HexError> {
        let byte = if self.zero_pending {
            self.zero_pending = false;
            self.nibble(0)
        } else {
            None
        };
        self.in_token = false;
        if self.high.take().is_some() {
            return Err(HexError::OddDigits);
        }
        Ok(byte)
    }

    fn nibble(&mut self, digit: u8) -> Option<u8> {
        match self.high.take() {
            Some(high) => Some(high << 4 | digit),
            None => {
                self.high = Some(digit);
                None
            }
        }
    }
}

/// A [`HexParser`] that knows where it is, so that `--hex` and
/// `--datagrams` report errors alike: `line L, column C: ...`, an odd number
/// of digits at the digit left without a pair (the last one).
#[derive(Debug, Default, Clone, Copy)]
struct HexCursor {
    parser: HexParser,
    line: u64,
    column: u64,
    /// Where the last digit was, and the digit before it (to undo a `0`
    /// that turns out to begin a `0x` prefix).
    last_digit: (u64, u64),
    before: (u64, u64),
}

impl HexCursor {
    fn push(&mut self, c: u8) -> Result<Option<u8>, String> {
        self.column += 1;
        let at = (self.line, self.column);
        if c.is_ascii_hexdigit() {
            (self.before, self.last_digit) = (self.last_digit, at);
        } else if c == b'x' || c == b'X' {
            self.last_digit = self.before;
        } else if c == b'\n' {
            (self.line, self.column) = (self.line + 1, 0);
        }
        self.parser.push(c).map_err(|e| Self::located(at, e))
    }

    fn finish(&mut self) -> Result<Option<u8>, String> {
        let at = self.last_digit;
        self.parser.finish().map_err(|e| Self::located(at, e))
    }

    fn located((line, column): (u64, u64), error: HexError) -> String {
        format!("line {line}, column {column}: {error}")
    }
}

/// Hex text read as one stream of bytes (`--hex`).
pub struct HexBytes {
    input: Input,
    text: Vec<u8>,
    pos: usize,
    end: usize,
    cursor: HexCursor,
    done: bool,
    error: Option<Failure>,
}

impl HexBytes {
    /// Read `input` as hex text.
    pub fn new(input: Input) -> Self {
        HexBytes {
            input,
            text: vec![0; READ_SIZE],
            pos: 0,
            end: 0,
            cursor: HexCursor {
                line: 1,
                ..HexCursor::default()
            },
            done: false,
            error: None,
        }
    }

    fn invalid(&self, error: String) -> Failure {
        Failure::Invalid(format!("{}: {error}", self.input.name()))
    }
}

impl ByteSource for HexBytes {
    fn fill(&mut self, buf: &mut [u8]) -> Result<usize, Failure> {
        if let Some(error) = self.error.take() {
            return Err(error);
        }
        let mut n = 0;
        while n < buf.len() && !self.done {
            if self.pos == self.end {
                if n > 0 && self.input.may_wait() {
                    // Hand over what has arrived before waiting for more.
                    break;
                }
                self.pos = 0;
                self.end = match self.input.read_chunk(&mut self.text) {
                    Ok(k) => k,
                    Err(failure) => {
                        self.end = 0;
                        self.error = Some(failure);
                        self.done = true;
                        break;
                    }
                };
                if self.end == 0 {
                    self.done = true;
                    match self.cursor.finish() {
                        Ok(Some(byte)) => {
                            buf[n] = byte;
                            n += 1;
                        }
                        Ok(None) => {}
                        Err(e) => self.error = Some(self.invalid(e)),
                    }
                }
                continue;
            }
            let c = self.text[self.pos];
            self.pos += 1;
            match self.cursor.push(c) {
                Ok(Some(byte)) => {
                    buf[n] = byte;
                    n += 1;
                }
                Ok(None) => {}
                Err(e) => {
                    self.error = Some(self.invalid(e));
                    self.done = true;
                }
            }
        }
        match self.error.take() {
            Some(error) if n == 0 => Err(error),
            error => {
                self.error = error;
                Ok(n)
            }
        }
    }

    fn may_wait(&self) -> bool {
        self.input.may_wait()
    }
}

/// Parse line `number` of hex text into `out` (cleared first); the error
/// says where (`line L, column C: ...`).
pub fn hex_line(number: u64, line: &[u8], out: &mut Vec<u8>) -> Result<(), String> {
    out.clear();
    let mut cursor = HexCursor {
        line: number,
        ..HexCursor::default()
    };
    for &c in line {
        out.extend(cursor.push(c)?);
    }
    out.extend(cursor.finish()?);
    Ok(())
}

/// An input read line by line, each line at most [`MAX_LINE`] bytes: a
/// longer line is reported on stderr and skipped, like any bad line.
pub struct Lines {
    reader: BufReader<Input>,
    line: Vec<u8>,
    number: u64,
    name: String,
    too_long: u64,
    /// Count long lines without reporting them ([`Lines::quiet`]).
    quiet: bool,
}

impl Read for Input {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        self.read_some(buf)
    }
}

impl Lines {
    /// Read `input` line by line.
    pub fn new(input: Input) -> Self {
        Lines {
            name: input.name().to_owned(),
            reader: BufReader::with_capacity(READ_SIZE, input),
            line: Vec::new(),
            number: 0,
            too_long: 0,
            quiet: false,
        }
    }

    /// Count lines longer than [`MAX_LINE`] without reporting them (a decode
    /// that only judges its output).
    pub fn quiet(mut self, quiet: bool) -> Self {
        self.quiet = quiet;
        self
    }

    /// How many lines were skipped for being longer than [`MAX_LINE`].
    pub fn too_long(&self) -> u64 {
        self.too_long
    }

    /// The input's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether more input is already buffered, so the next line will not
    /// wait for a read: the time to flush output is when this is false.
    pub fn has_buffered(&self) -> bool {
        !self.reader.buffer().is_empty()
    }

    /// The next line (1-based number, text without its line ending), or
    /// `None` at the end. Lines over [`MAX_LINE`] bytes are reported and
    /// skipped without holding more than that in memory.
    pub fn next_line(&mut self) -> Result<Option<(u64, &[u8])>, Failure> {
        let failure = |error| Failure::Io {
            context: self.name.clone(),
            error,
        };
        // In the rest of a line that is too long.
        let mut skipping = false;
        loop {
            self.line.clear();
            let limit = MAX_LINE as u64 + 1;
            let n = (&mut self.reader)
                .take(limit)
                .read_until(b'\n', &mut self.line)
                .map_err(failure)?;
            if n == 0 {
                return Ok(None);
            }
            let ended = self.line.last() == Some(&b'\n');
            if skipping {
                skipping = !ended;
                continue;
            }
            self.number += 1;
            if ended {
                self.line.pop();
                if self.line.last() == Some(&b'\r') {
                    self.line.pop();
                }
            } else if self.line.len() > MAX_LINE {
                let (name, number) = (&self.name, self.number);
                if !self.quiet {
                    eprintln!("robowire: {name}: line {number}: longer than {MAX_LINE} bytes");
                }
                self.too_long += 1;
                skipping = true;
                continue;
            }
            return Ok(Some((self.number, &self.line)));
        }
    }
}
