//! Finding frames: `LEN, id, payload` with no start byte and no checksum
//! (spec §2, §11), for one side of the link or both.

use core::marker::PhantomData;

pub use crate::side::{Both, Device, Host};
use crate::stream::{self, Check};

use super::buf::{CommandBuf, Message, MessageBuf, ReportBuf};
use super::command::{command_len_range, parse_command, Command};
use super::dialect::Dialect;
use super::error::Error;
use super::fast;
use super::module::{ModuleNew, ModuleType};
use super::report::{
    parse_report_full, parse_report_with, report_header_len, report_len_ok, Report,
};
use super::wire::{command_id, report_id, report_known, MAX_COMMAND_LEN};

mod sealed {
    pub trait Sealed {}
}

impl sealed::Sealed for Host {}
impl sealed::Sealed for Device {}
impl sealed::Sealed for Both {}

/// Which frames a [`Framing`] accepts (sealed: [`Host`] decodes reports,
/// [`Device`] commands, [`Both`] either).
pub trait Side: sealed::Sealed + Copy + Eq + core::hash::Hash + core::fmt::Debug + Default {
    /// The message a decoder of this side yields borrowed.
    type Message<'a>: Copy;
    /// Its owned form.
    type Owned;
    /// Whether commands (host → Pico) are accepted.
    const COMMANDS: bool;
    /// Whether reports (Pico → host) are accepted.
    const REPORTS: bool;
    /// Parse one accepted frame.
    fn parse(dialect: Dialect, lenient: bool, frame: &[u8]) -> Result<Self::Message<'_>, Error>;
    /// The common messages read straight from the frame's bytes (see
    /// `FrameRules::parse_common`): none by default.
    #[inline(always)]
    fn parse_common(_dialect: Dialect, _frame: &[u8]) -> Option<Self::Message<'_>> {
        None
    }
    /// The owned form of a message.
    fn to_owned(message: Self::Message<'_>) -> Self::Owned;
    /// The owned form of a message parsed from `frame`, keeping its bytes.
    fn to_owned_from(frame: &[u8], message: Self::Message<'_>) -> Self::Owned;
}

impl Side for Host {
    type Message<'a> = Report<'a>;
    type Owned = ReportBuf;
    const COMMANDS: bool = false;
    const REPORTS: bool = true;

    // The full parse; the engine tries `parse_common` first.
    fn parse(dialect: Dialect, lenient: bool, frame: &[u8]) -> Result<Report<'_>, Error> {
        parse_report_full(dialect, lenient, frame)
    }

    // The reports a Pico streams, inlined into the decoder's loop.
    #[inline(always)]
    fn parse_common(dialect: Dialect, frame: &[u8]) -> Option<Report<'_>> {
        fast::parse(dialect, frame)
    }

    fn to_owned(message: Report<'_>) -> ReportBuf {
        ReportBuf::from_parsed(&message)
    }

    fn to_owned_from(frame: &[u8], message: Report<'_>) -> ReportBuf {
        ReportBuf::from_frame(frame, &message)
    }
}

impl Side for Device {
    type Message<'a> = Command<'a>;
    type Owned = CommandBuf;
    const COMMANDS: bool = true;
    const REPORTS: bool = false;

    fn parse(dialect: Dialect, _lenient: bool, frame: &[u8]) -> Result<Command<'_>, Error> {
        parse_command(dialect, frame)
    }

    fn to_owned(message: Command<'_>) -> CommandBuf {
        CommandBuf::from_parsed(&message)
    }

    fn to_owned_from(frame: &[u8], message: Command<'_>) -> CommandBuf {
        CommandBuf::from_frame(frame, &message)
    }
}

impl Side for Both {
    type Message<'a> = Message<'a>;
    type Owned = MessageBuf;
    const COMMANDS: bool = true;
    const REPORTS: bool = true;

    /// A frame valid both ways reads as the report (see [`CaptureContext`]
    /// to attribute it by what came before); a known command outranks a
    /// lenient unknown report.
    fn parse(dialect: Dialect, lenient: bool, frame: &[u8]) -> Result<Message<'_>, Error> {
        let command = parse_command(dialect, frame);
        let report = parse_report_with(dialect, lenient, frame);
        match (command, report) {
            (Ok(c), Ok(Report::Unknown { .. }) | Err(_)) => Ok(Message::Command(c)),
            (_, Ok(r)) => Ok(Message::Report(r)),
            (Err(_), Err(e)) => Err(e),
        }
    }

    fn to_owned(message: Message<'_>) -> MessageBuf {
        MessageBuf::from(&message)
    }

    fn to_owned_from(frame: &[u8], message: Message<'_>) -> MessageBuf {
        MessageBuf::from_frame(frame, &message)
    }
}

/// Index of the first byte that is not `00`: a `00` length byte is dropped by
/// the firmware, so it never starts a frame.
#[inline(always)]
fn skip_zeros(bytes: &[u8]) -> usize {
    match bytes.first() {
        // The next frame usually starts right here.
        Some(&first) if first != 0 => 0,
        _ => bytes.iter().position(|&b| b != 0).unwrap_or(bytes.len()),
    }
}

/// Telemetrix framing for [`StreamDecoder`](crate::StreamDecoder), for one
/// [`Side`] of the link: [`Host`] decodes reports, [`Device`] commands,
/// [`Both`] either (captures). See the [module docs](super) for what a
/// candidate must satisfy.
///
/// ```
/// use robowire::telemetrix::{Dialect, Framing, HostDecoder};
///
/// let decoder = HostDecoder::new(Framing::new().with_dialect(Dialect::Mirte12));
/// # let _ = decoder;
/// ```
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Framing<S> {
    dialect: Dialect,
    lenient: bool,
    /// Commands framed as the firmware frames them (see
    /// [`Framing::as_firmware`]).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "core::ops::Not::not")
    )]
    firmware: bool,
    #[cfg_attr(feature = "serde", serde(skip))]
    side: PhantomData<S>,
}

impl<S: Side> Framing<S> {
    /// Frames of mirte firmware 1.3; unknown ids are corruption.
    pub const fn new() -> Self {
        Self {
            dialect: Dialect::Mirte13,
            lenient: false,
            firmware: false,
            side: PhantomData,
        }
    }

    /// The same framing for `dialect`.
    pub const fn with_dialect(self, dialect: Dialect) -> Self {
        Self { dialect, ..self }
    }

    /// The dialect.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Whether unknown report ids are accepted (see
    /// [`lenient`](Framing::lenient)).
    pub const fn is_lenient(&self) -> bool {
        self.lenient
    }

    fn check_command(&self, candidate: &[u8], at_end: bool) -> Check<Error> {
        if self.firmware {
            return firmware_frame(candidate, at_end);
        }
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

    #[inline(always)]
    pub(super) fn check_report(&self, c: &[u8], lenient: bool) -> Check<Error> {
        // The common reports: one table load and eight compares.
        if let Some(w) = fast::window(c) {
            if let Some(n) = fast::accept(self.dialect, &w, c.len()) {
                return Check::Frame(n);
            }
        }
        self.check_report_slow(c, lenient)
    }

    /// The common reports cut by the end of a chunk wait for their whole
    /// frame at once; anything else takes the full check (out of line, so
    /// the clean path stays small).
    #[inline(never)]
    fn check_report_slow(&self, c: &[u8], lenient: bool) -> Check<Error> {
        match fast::need(self.dialect, c) {
            Some(n) => Check::Need(n),
            None => self.check_report_full(c, lenient),
        }
    }

    /// Every report, each check in turn (out of line: the table takes the
    /// common ones).
    #[inline(never)]
    pub(super) fn check_report_full(&self, c: &[u8], lenient: bool) -> Check<Error> {
        let (len, rid) = match c {
            [] => return Check::Need(1),
            [0, ..] => return Check::Reject(Error::BadLength { id: 0, len: 0 }),
            [_] => return Check::Need(2),
            [len, rid, ..] => (*len, *rid),
        };
        let total = usize::from(len) + 1;
        if !report_known(self.dialect, rid) {
            return if lenient {
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
        match self.check_report(next, false) {
            Check::Frame(_) => Check::Frame(total),
            Check::Need(n) => Check::Need(total + skip + n),
            Check::Reject(_) => Check::Reject(Error::UnknownId { id: rid }),
        }
    }

    /// Either direction: a frame if either accepts it, rejected if both
    /// reject it, undecided while either still needs bytes. Both read the
    /// same `LEN`, so an accepted frame has one length.
    fn check_both(&self, candidate: &[u8]) -> Check<Error> {
        let command = self.check_command(candidate, false);
        let report = self.check_report(candidate, self.lenient);
        match (command, report) {
            (Check::Frame(n), _) => Check::Frame(n),
            (Check::Need(a), Check::Need(b)) => Check::Need(a.min(b)),
            // A report cannot be complete while the command of the same LEN
            // is not; should it ever be, wait for the command's answer.
            (Check::Need(n), _) | (Check::Reject(_), Check::Need(n)) => Check::Need(n),
            (Check::Reject(_), Check::Frame(n)) => Check::Frame(n),
            // The error of the direction that got further: if the id is
            // unknown as a report, the command's.
            (Check::Reject(c), Check::Reject(Error::UnknownId { .. })) => Check::Reject(c),
            (Check::Reject(_), Check::Reject(r)) => Check::Reject(r),
        }
    }
}

impl Framing<Host> {
    /// Accept report ids the dialect does not define (newer firmware) as
    /// [`Report::Unknown`], skipped by their `LEN`, but only when a valid
    /// known report follows directly (after optional `00` bytes): without a
    /// checksum that is the only sign of being in sync. Use it with a
    /// decoder of [`LENIENT_BUFFER`](super::LENIENT_BUFFER) bytes
    /// ([`LenientHostDecoder`](super::LenientHostDecoder)), which holds both
    /// frames. An unknown frame at the very end of the input is rejected as
    /// truncated.
    pub const fn lenient(self) -> Self {
        Self {
            lenient: true,
            ..self
        }
    }
}

/// The firmware's receiver (spec §2.2, `get_next_command`): after a length
/// byte 1..=30 (`find_start` has dropped `00` and anything above 30, as the
/// firmware does), the next `LEN` bytes are a command, whatever they hold.
/// At the end of the input every candidate lies inside an unfinished frame
/// (a whole one was emitted as soon as it was complete), whose bytes the
/// firmware discards after its 100 ms timeout: none of them is a frame.
fn firmware_frame(candidate: &[u8], at_end: bool) -> Check<Error> {
    if at_end {
        return Check::Need(candidate.len() + 1);
    }
    match candidate.first() {
        None => Check::Need(1),
        Some(&len) => {
            let total = usize::from(len) + 1;
            if candidate.len() < total {
                Check::Need(total)
            } else {
                Check::Frame(total)
            }
        }
    }
}

impl Framing<Device> {
    /// Frame commands exactly as the Pico's firmware does (spec §2.2), to
    /// reconstruct what the device ran: a length byte `00` or above 30 is
    /// dropped, and any other one is trusted: the next `LEN` bytes are one
    /// command, which the firmware runs whatever they hold. Such a frame
    /// that is not a valid command is reported as an error (counted in
    /// [`Stats::malformed`](crate::Stats::malformed)) and consumed whole,
    /// never rescanned, as the firmware never rescans: a byte lost or
    /// inserted makes the decoder lose the same frames the firmware loses
    /// and find the same false ones.
    ///
    /// The default framing is robust instead: it checks every candidate
    /// (id, `LEN`, fields) and resyncs byte by byte, so it finds the frames
    /// the host meant. At the end of the input an unfinished frame is
    /// reported as truncated (once per length byte inside it, as the decoder
    /// looks on), and nothing in it is decoded: the firmware discards it
    /// after 100 ms. What this mode does not model: that timeout inside the
    /// stream (a byte stream has no timing), the
    /// stale bytes a short command reads from the never-cleared buffer, and
    /// the blocking, unchecked receivers of mirte 1.2 and upstream 1.1
    /// (their framing is taken to be mirte 1.3's).
    ///
    /// ```
    /// use robowire::telemetrix::{device_decoder, Command, DeviceDecoder, Framing};
    ///
    /// // PING 7, STOP_ALL_REPORTS, GET_FIRMWARE_VERSION, with the 07 lost.
    /// let bytes = [0x02, 0x20, 0x01, 0x0f, 0x01, 0x05];
    /// // The firmware reads PING 1 (STOP's LEN byte as the counter), then a
    /// // LEN of 15 (STOP's id) that swallows GET_FIRMWARE_VERSION.
    /// let mut firmware = DeviceDecoder::new(Framing::new().as_firmware());
    /// let ran: Vec<_> = firmware.feed(&bytes).flatten().map(|f| f.message).collect();
    /// assert_eq!(ran.len(), 1);
    /// assert_eq!(ran[0].message(), Command::Ping { counter: 1 });
    /// assert!(firmware.flush().next().unwrap().is_err()); // 15 bytes awaited
    /// // The robust decoder resyncs and finds GET_FIRMWARE_VERSION.
    /// let mut robust = device_decoder();
    /// let found: Vec<_> = robust.feed(&bytes).flatten().map(|f| f.message).collect();
    /// assert_eq!(found.len(), 2);
    /// assert_eq!(found[1].message(), Command::GetFirmwareVersion);
    /// ```
    pub const fn as_firmware(self) -> Self {
        Self {
            firmware: true,
            ..self
        }
    }

    /// Whether commands are framed as the firmware frames them (see
    /// [`as_firmware`](Framing::as_firmware)).
    pub const fn is_as_firmware(&self) -> bool {
        self.firmware
    }
}

impl Framing<Both> {
    /// Accept unknown report ids as [`Framing<Host>::lenient`] does, when no
    /// command reads the frame.
    pub const fn lenient(self) -> Self {
        Self {
            lenient: true,
            ..self
        }
    }
}

impl<S: Side> stream::FrameRules for Framing<S> {
    type Error = Error;
    type Message<'a> = S::Message<'a>;
    type Owned = S::Owned;

    /// `LEN` and id: enough to reject an unknown id or an impossible length.
    const HEADER_LEN: usize = 2;

    /// Without a checksum, plausible frames start inside most frames; the
    /// engine's overlap test measured slightly worse recovery here (inserted
    /// garbage 99.93 % instead of 100 % of intact frames), so it is off.
    const VERIFY_AFTER_RESYNC: bool = false;

    #[inline]
    fn find_start(&self, bytes: &[u8]) -> usize {
        if S::REPORTS {
            // Skips `00` only: a LEN over 30 may start a report.
            skip_zeros(bytes)
        } else {
            // Like the firmware, drop length bytes `00` and above 30.
            bytes
                .iter()
                .position(|&b| (1..=MAX_COMMAND_LEN as u8).contains(&b))
                .unwrap_or(bytes.len())
        }
    }

    #[inline]
    fn check(&self, candidate: &[u8], at_end: bool) -> Check<Error> {
        match (S::COMMANDS, S::REPORTS) {
            (true, true) => self.check_both(candidate),
            (true, false) => self.check_command(candidate, at_end),
            _ => self.check_report(candidate, self.lenient),
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

    #[inline(always)]
    fn parse<'a>(&self, frame: &'a [u8]) -> Result<S::Message<'a>, Error> {
        S::parse(self.dialect, self.lenient, frame)
    }

    #[inline(always)]
    fn parse_common<'a>(&self, frame: &'a [u8]) -> Option<S::Message<'a>> {
        S::parse_common(self.dialect, frame)
    }

    fn to_owned(message: S::Message<'_>) -> S::Owned {
        S::to_owned(message)
    }

    fn to_owned_from(frame: &[u8], message: S::Message<'_>) -> S::Owned {
        S::to_owned_from(frame, message)
    }
}

/// What the frames of a capture so far say about the ones that follow, for
/// tools that read a whole conversation (the `robowire` tool uses it):
///
/// * a frame valid both ways (a digital write is byte for byte a digital
///   report) is attributed to the direction of the last frame that was valid
///   one way only (to reports until there is one), and marked as valid the
///   other way too ([`MessageBuf::also`]);
/// * MODULE_NEW (or a module report) tells which type each module number
///   has, so a later MODULE_DATA is typed ([`MessageBuf::module_type`]);
///   RESET_BOARD and BOOTLOADER_RESET forget the modules.
///
/// It depends only on the frames in order, not on how the input was split.
#[derive(Debug, Clone)]
pub struct CaptureContext {
    dialect: Dialect,
    lenient: bool,
    commands: bool,
    reports: bool,
    host_last: bool,
    modules: [Option<ModuleType>; 256],
}

impl CaptureContext {
    /// A context for the frames `framing` accepts.
    pub const fn new<S: Side>(framing: &Framing<S>) -> Self {
        Self {
            dialect: framing.dialect,
            lenient: framing.lenient,
            commands: S::COMMANDS,
            reports: S::REPORTS,
            host_last: false,
            modules: [None; 256],
        }
    }

    /// Attribute `message` (a frame the framing accepted) and type its
    /// MODULE_DATA; learn from it.
    pub fn annotate(&mut self, message: &mut MessageBuf) {
        let frame = message.frame();
        let id = frame.get(1).copied().unwrap_or(0);
        // One direction only: the frame is read the other way only when it
        // may say something about modules.
        let command_matters = self.reports
            || matches!(
                id,
                command_id::MODULE_NEW
                    | command_id::MODULE_DATA
                    | command_id::RESET_BOARD
                    | command_id::BOOTLOADER_RESET
            );
        let command = if self.commands && command_matters {
            parse_command(self.dialect, frame).ok()
        } else {
            None
        };
        let report = if self.reports && (self.commands || id == report_id::MODULE) {
            match parse_report_with(self.dialect, self.lenient, frame) {
                // A known command outranks a lenient unknown report.
                Ok(Report::Unknown { .. }) if command.is_some() => None,
                other => other.ok(),
            }
        } else {
            None
        };
        let (as_command, also) = match (&command, &report) {
            (Some(_), Some(_)) => (self.host_last, true),
            (Some(_), None) => (true, false),
            (None, Some(_)) => (false, false),
            (None, None) if self.commands != self.reports => (self.commands, false),
            (None, None) => return,
        };
        let mut module_type = None;
        if as_command {
            if !also {
                self.host_last = true;
            }
            match command {
                Some(Command::ModuleNew(ModuleNew::Add { module_num, init })) => {
                    self.modules[usize::from(module_num)] = Some(init.module_type());
                }
                // Modules are gone after a reboot.
                Some(Command::ResetBoard | Command::BootloaderReset) => {
                    self.modules = [None; 256];
                }
                Some(Command::ModuleData { module_num, .. }) => {
                    module_type = self.modules[usize::from(module_num)];
                }
                _ => {}
            }
        } else {
            if !also {
                self.host_last = false;
            }
            if let Some(Report::Module { module_num, report }) = report {
                self.modules[usize::from(module_num)] = Some(report.module_type());
            }
        }
        message.attribute(self.dialect, self.lenient, as_command, also);
        message.set_module_type(module_type);
    }
}
