//! Finding frames: `LEN, id, payload` with no start byte and no checksum
//! (spec §2, §11).

use super::command::{command_len_range, parse_command, CommandRef, OwnedCommand};
use super::dialect::Dialect;
use super::error::Error;
use super::report::{
    parse_report_with, report_header_len, report_known, report_len_ok, OwnedReport, ReportRef,
};
use super::MAX_COMMAND_LEN;
use crate::stream::{self, Check};

/// Index of the first byte that is not `00`: a `00` length byte is dropped by
/// the firmware, so it never starts a frame.
fn skip_zeros(bytes: &[u8]) -> usize {
    bytes.iter().position(|&b| b != 0).unwrap_or(bytes.len())
}

/// Framing of reports (Pico → host): what a host decodes.
///
/// A candidate is accepted only if its id is a report of the dialect, its
/// `LEN` is possible for that id (exact, or by the count / sub-type bytes of
/// spec §11), and every field is one the firmware sends (pins < 30, flags
/// 0/1, …). Anything else is rejected and the engine resyncs by one byte.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ReportFraming {
    dialect: Dialect,
    lenient: bool,
}

impl ReportFraming {
    /// Reports of mirte firmware 1.3; unknown ids are corruption.
    pub const fn new() -> Self {
        Self {
            dialect: Dialect::Mirte13,
            lenient: false,
        }
    }

    /// The same framing for `dialect`.
    pub const fn with_dialect(self, dialect: Dialect) -> Self {
        Self { dialect, ..self }
    }

    /// Accept report ids the dialect does not define (newer firmware) as
    /// [`Report::Unknown`](super::Report::Unknown), skipped by their `LEN`,
    /// but only when a valid known report follows directly (after optional
    /// `00` bytes): without a checksum that is the only sign of being in
    /// sync. Use it with [`LenientReportDecoder`](super::LenientReportDecoder),
    /// whose buffer holds both frames. An unknown frame at the very end of the
    /// input is rejected as truncated.
    pub const fn lenient(self) -> Self {
        Self {
            lenient: true,
            ..self
        }
    }

    /// The dialect.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Whether unknown ids are accepted.
    pub const fn is_lenient(&self) -> bool {
        self.lenient
    }

    fn check_strict(&self, c: &[u8]) -> Check<Error> {
        let (len, rid) = match c {
            [] => return Check::Need(1),
            [0, ..] => return Check::Reject(Error::BadLength { id: 0, len: 0 }),
            [_] => return Check::Need(2),
            [len, rid, ..] => (*len, *rid),
        };
        let total = usize::from(len) + 1;
        if !report_known(self.dialect, rid) {
            return if self.lenient {
                self.check_unknown(c, rid, total)
            } else {
                Check::Reject(Error::UnknownId { id: rid })
            };
        }
        let known = c.get(..total).unwrap_or(c);
        if !report_len_ok(self.dialect, len, known) {
            return Check::Reject(Error::BadLength { id: rid, len });
        }
        if c.len() < total {
            let header = report_header_len(rid);
            return Check::Need(if c.len() < header { c.len() + 1 } else { total });
        }
        match parse_report_with(self.dialect, false, known) {
            Ok(_) => Check::Frame(total),
            Err(e) => Check::Reject(e),
        }
    }

    /// An unknown id in lenient mode: a frame only if a known frame follows.
    fn check_unknown(&self, c: &[u8], rid: u8, total: usize) -> Check<Error> {
        let Some(rest) = c.get(total..) else {
            return Check::Need(total);
        };
        let skip = skip_zeros(rest);
        let next = rest.get(skip..).unwrap_or(&[]);
        if next.is_empty() {
            return Check::Need(c.len() + 1);
        }
        let strict = Self {
            lenient: false,
            ..*self
        };
        match strict.check_strict(next) {
            Check::Frame(_) => Check::Frame(total),
            Check::Need(n) => Check::Need(total + skip + n),
            Check::Reject(_) => Check::Reject(Error::UnknownId { id: rid }),
        }
    }
}

impl stream::FrameRules for ReportFraming {
    type Error = Error;
    type Message<'a> = ReportRef<'a>;
    type Owned = OwnedReport;

    /// `LEN` and id: enough to reject an unknown id or an impossible length.
    const HEADER_LEN: usize = 2;

    /// Without a checksum, plausible frames start inside most frames; the
    /// engine's overlap test measured slightly worse recovery here (inserted
    /// garbage 99.93 % instead of 100 % of intact frames), so it is off.
    const VERIFY_AFTER_RESYNC: bool = false;

    fn find_start(&self, bytes: &[u8]) -> usize {
        skip_zeros(bytes)
    }

    fn check(&self, candidate: &[u8], _at_end: bool) -> Check<Error> {
        self.check_strict(candidate)
    }

    fn truncated(&self, len: usize) -> Error {
        Error::Truncated { len }
    }

    fn superseded(&self, len: usize) -> Error {
        Error::Superseded { len }
    }

    fn is_checksum_error(&self, _error: &Error) -> bool {
        false
    }

    fn parse<'a>(&self, frame: &'a [u8]) -> Result<ReportRef<'a>, Error> {
        parse_report_with(self.dialect, self.lenient, frame)
    }

    fn to_owned(message: ReportRef<'_>) -> OwnedReport {
        message.to_owned()
    }
}

/// Framing of commands (host → Pico): what a (simulated) Pico decodes.
///
/// Like the firmware, it drops length bytes `00` and above 30 before a frame
/// starts. A candidate is accepted only if its id is a command of the
/// dialect, its `LEN` fits that command, and every field is one the encoder
/// would emit.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CommandFraming {
    dialect: Dialect,
}

impl CommandFraming {
    /// Commands of mirte firmware 1.3.
    pub const fn new() -> Self {
        Self {
            dialect: Dialect::Mirte13,
        }
    }

    /// The same framing for `dialect`.
    pub const fn with_dialect(self, dialect: Dialect) -> Self {
        Self { dialect }
    }

    /// The dialect.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }
}

impl stream::FrameRules for CommandFraming {
    type Error = Error;
    type Message<'a> = CommandRef<'a>;
    type Owned = OwnedCommand;

    /// `LEN` and id: enough to reject an unknown id or an impossible length.
    const HEADER_LEN: usize = 2;

    /// Without a checksum, plausible frames start inside most frames; the
    /// engine's overlap test measured slightly worse recovery here (inserted
    /// garbage 99.93 % instead of 100 % of intact frames), so it is off.
    const VERIFY_AFTER_RESYNC: bool = false;

    fn find_start(&self, bytes: &[u8]) -> usize {
        bytes
            .iter()
            .position(|&b| (1..=MAX_COMMAND_LEN as u8).contains(&b))
            .unwrap_or(bytes.len())
    }

    fn check(&self, candidate: &[u8], _at_end: bool) -> Check<Error> {
        let (len, cid) = match candidate {
            [] => return Check::Need(1),
            [_] => return Check::Need(2),
            [len, cid, ..] => (*len, *cid),
        };
        let Some((min, max)) = command_len_range(self.dialect, cid) else {
            return Check::Reject(Error::UnknownId { id: cid });
        };
        if len < min || len > max {
            return Check::Reject(Error::BadLength { id: cid, len });
        }
        let total = usize::from(len) + 1;
        match candidate.get(..total) {
            None => Check::Need(total),
            Some(frame) => match parse_command(self.dialect, frame) {
                Ok(_) => Check::Frame(total),
                Err(e) => Check::Reject(e),
            },
        }
    }

    fn truncated(&self, len: usize) -> Error {
        Error::Truncated { len }
    }

    fn superseded(&self, len: usize) -> Error {
        Error::Superseded { len }
    }

    fn is_checksum_error(&self, _error: &Error) -> bool {
        false
    }

    fn parse<'a>(&self, frame: &'a [u8]) -> Result<CommandRef<'a>, Error> {
        parse_command(self.dialect, frame)
    }

    fn to_owned(message: CommandRef<'_>) -> OwnedCommand {
        message.to_owned()
    }
}
