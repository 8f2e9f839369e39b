//! The owned forms: [`CommandBuf`], [`ReportBuf`] and [`MessageBuf`] keep a
//! frame's bytes and parse them on access, so one message type per direction
//! serves borrowed and owned use alike.

use core::fmt;
use core::hash::{Hash, Hasher};
use core::ops::Deref;

use super::command::{parse_command, Command};
use super::dialect::Dialect;
use super::error::Error;
use super::module::{ModuleCommand, ModuleType};
use super::quirk::{command_quirk, report_quirk, Quirk};
use super::report::{parse_report_with, Report};
use super::wire::{report_known, split_frame};
use super::wire::{MAX_COMMAND_FRAME, MAX_FRAME_LEN, MAX_REPORT_FRAME};
use crate::{Encode, EncodeError};

/// The frame at the front of `bytes`: its first byte is `LEN`.
fn frame_of(bytes: &[u8]) -> &[u8] {
    let len = usize::from(bytes.first().copied().unwrap_or(0)) + 1;
    bytes.get(..len).unwrap_or(&[])
}

/// Copy a whole frame into a zeroed array, or `None` if it does not fit.
fn copy_frame<const N: usize>(frame: &[u8]) -> Option<[u8; N]> {
    let mut bytes = [0; N];
    bytes.get_mut(..frame.len())?.copy_from_slice(frame);
    Some(bytes)
}

/// The message a parse of valid bytes cannot fail to give; only a broken
/// invariant could make [`CommandBuf::message`] reach for it.
const NO_COMMAND: Command<'static> = Command::GetFirmwareVersion;

/// See [`NO_COMMAND`].
const NO_REPORT: Report<'static> = Report::LoopBack { byte: 0 };

/// The first of `command`'s home dialects that reads `frame`, its bytes, as
/// `command`; else the first that accepts it.
fn command_dialect(command: &Command<'_>, frame: &[u8]) -> Dialect {
    let home = command.home_dialects().iter().copied();
    home.clone()
        .find(|&d| parse_command(d, frame).as_ref() == Ok(command))
        .or_else(|| home.clone().find(|&d| parse_command(d, frame).is_ok()))
        .unwrap_or_default()
}

/// The first of `report`'s home dialects that accepts `frame`, its bytes,
/// and whether it must be read leniently (an unknown report).
fn report_dialect(report: &Report<'_>, frame: &[u8]) -> (Dialect, bool) {
    match *report {
        Report::Unknown { id, .. } => (
            Dialect::ALL
                .into_iter()
                .find(|&d| !report_known(d, id))
                .unwrap_or_default(),
            true,
        ),
        // The first that reads the frame as `report` (a mirte 1.2 VEML6040
        // reading is little-endian, mirte 1.3's big-endian), else the first
        // that accepts it.
        _ => {
            let home = report.home_dialects().iter().copied();
            let dialect = home
                .clone()
                .find(|&d| parse_report_with(d, false, frame).as_ref() == Ok(report))
                .or_else(|| {
                    home.clone()
                        .find(|&d| parse_report_with(d, false, frame).is_ok())
                })
                .unwrap_or_default();
            (dialect, false)
        }
    }
}

/// An owned command: the bytes of one valid command frame and the dialect it
/// is valid in. [`message`](Self::message) parses it on access (it cannot
/// fail: every way to make a `CommandBuf` checks the bytes); it dereferences
/// to the frame's bytes and encodes as them.
///
/// It is what a [`DeviceDecoder`](super::DeviceDecoder)'s `feed` and
/// `flush` yield.
///
/// ```
/// use robowire::telemetrix::Command;
///
/// let ping = Command::Ping { counter: 7 }.to_buf()?;
/// assert_eq!(&ping[..], &[0x02, 0x20, 0x07]);
/// assert_eq!(ping.message(), Command::Ping { counter: 7 });
/// # Ok::<(), robowire::EncodeError>(())
/// ```
#[derive(Clone, Copy)]
pub struct CommandBuf {
    bytes: [u8; MAX_COMMAND_FRAME],
    dialect: Dialect,
}

impl CommandBuf {
    /// Encode `command` for mirte 1.3.
    pub fn new(command: &Command<'_>) -> Result<Self, EncodeError> {
        Self::new_in(command, Dialect::Mirte13)
    }

    /// Encode `command` for `dialect`.
    pub fn new_in(command: &Command<'_>, dialect: Dialect) -> Result<Self, EncodeError> {
        let mut bytes = [0; MAX_COMMAND_FRAME];
        command.encode_in(dialect, &mut bytes)?;
        Ok(Self { bytes, dialect })
    }

    /// Copy one complete command frame of `dialect`, checked as
    /// [`Command::parse_in`] checks it.
    pub fn parse_in(frame: &[u8], dialect: Dialect) -> Result<Self, Error> {
        parse_command(dialect, frame)?;
        let bytes = copy_frame(frame).ok_or(Error::BadLength {
            id: frame.get(1).copied().unwrap_or(0),
            len: frame.first().copied().unwrap_or(0),
        })?;
        Ok(Self { bytes, dialect })
    }

    /// The owned form of a command parsed from a frame (which always
    /// re-encodes): its bytes, valid in the first of its home dialects that
    /// accepts them.
    pub(crate) fn from_parsed(command: &Command<'_>) -> Self {
        let mut bytes = [0; MAX_COMMAND_FRAME];
        command.write_unchecked(&mut bytes);
        let dialect = command_dialect(command, frame_of(&bytes));
        Self { bytes, dialect }
    }

    /// The owned form of `command`, parsed from `frame`: the frame's own
    /// bytes (a quirky frame is kept as it was), valid in the first of the
    /// command's home dialects that accepts them.
    pub(crate) fn from_frame(frame: &[u8], command: &Command<'_>) -> Self {
        match copy_frame(frame) {
            Some(bytes) => Self {
                bytes,
                dialect: command_dialect(command, frame),
            },
            None => Self::from_parsed(command),
        }
    }

    /// The command.
    pub fn message(&self) -> Command<'_> {
        parse_command(self.dialect, self.frame()).unwrap_or(NO_COMMAND)
    }

    /// What is dubious in the frame read in [`dialect`](Self::dialect), if
    /// anything: it came from a real host and the encoder would refuse it
    /// (see [`Quirk`]). A decoder's owned form has the first of the
    /// command's dialects that reads the bytes as that command, mirte 1.3
    /// first; a [`CaptureContext`](super::CaptureContext) sets the
    /// decoder's.
    pub fn quirk(&self) -> Option<Quirk> {
        command_quirk(self.dialect, self.frame())
    }

    /// The frame's bytes.
    pub fn frame(&self) -> &[u8] {
        frame_of(&self.bytes)
    }

    /// The dialect the frame is valid in.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }
}

/// An owned report: the bytes of one valid report frame and the dialect it
/// is valid in (an unknown report: lenient). Like [`CommandBuf`], it parses
/// on access ([`message`](Self::message)), dereferences to the frame's bytes
/// and encodes as them. It is what a [`HostDecoder`](super::HostDecoder)'s
/// `feed` and `flush` yield.
///
/// ```
/// use robowire::telemetrix::Report;
///
/// let pong = Report::Pong { counter: 7, boot_id: 42 }.to_buf()?;
/// assert_eq!(&pong[..], &[0x03, 0x20, 0x07, 0x2A]);
/// # Ok::<(), robowire::EncodeError>(())
/// ```
#[derive(Clone, Copy)]
pub struct ReportBuf {
    bytes: [u8; MAX_REPORT_FRAME],
    dialect: Dialect,
    lenient: bool,
}

impl ReportBuf {
    /// Encode `report` for mirte 1.3.
    pub fn new(report: &Report<'_>) -> Result<Self, EncodeError> {
        Self::new_in(report, Dialect::Mirte13)
    }

    /// Encode `report` for `dialect`.
    pub fn new_in(report: &Report<'_>, dialect: Dialect) -> Result<Self, EncodeError> {
        let mut bytes = [0; MAX_REPORT_FRAME];
        report.encode_in(dialect, &mut bytes)?;
        let lenient = matches!(report, Report::Unknown { .. });
        Ok(Self {
            bytes,
            dialect,
            lenient,
        })
    }

    /// Copy one complete report frame of `dialect`, checked as
    /// [`Report::parse_in`] (or, when `lenient`,
    /// [`Report::parse_lenient_in`]) checks it.
    pub fn parse_in(frame: &[u8], dialect: Dialect, lenient: bool) -> Result<Self, Error> {
        parse_report_with(dialect, lenient, frame)?;
        let bytes = copy_frame(frame).ok_or(Error::Truncated { len: frame.len() })?;
        Ok(Self {
            bytes,
            dialect,
            lenient,
        })
    }

    /// See [`CommandBuf::from_parsed`].
    pub(crate) fn from_parsed(report: &Report<'_>) -> Self {
        let mut bytes = [0; MAX_REPORT_FRAME];
        report.write_unchecked(&mut bytes);
        let (dialect, lenient) = report_dialect(report, frame_of(&bytes));
        Self {
            bytes,
            dialect,
            lenient,
        }
    }

    /// See [`CommandBuf::from_frame`].
    pub(crate) fn from_frame(frame: &[u8], report: &Report<'_>) -> Self {
        match copy_frame(frame) {
            Some(bytes) => {
                let (dialect, lenient) = report_dialect(report, frame);
                Self {
                    bytes,
                    dialect,
                    lenient,
                }
            }
            None => Self::from_parsed(report),
        }
    }

    /// The report.
    pub fn message(&self) -> Report<'_> {
        parse_report_with(self.dialect, self.lenient, self.frame()).unwrap_or(NO_REPORT)
    }

    /// What is dubious in the frame read in [`dialect`](Self::dialect), if
    /// anything: it came from a real Pico and the encoder would refuse it
    /// (see [`Quirk`]).
    pub fn quirk(&self) -> Option<Quirk> {
        report_quirk(self.dialect, self.frame())
    }

    /// The frame's bytes.
    pub fn frame(&self) -> &[u8] {
        frame_of(&self.bytes)
    }

    /// The dialect the frame is valid in.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }
}

/// A command or a report: what a [`BothDecoder`](super::BothDecoder) yields
/// borrowed, and one complete frame of either direction.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Message<'a> {
    /// Host → Pico.
    Command(Command<'a>),
    /// Pico → host.
    Report(Report<'a>),
}

impl<'a> Message<'a> {
    /// Parse one complete frame of `dialect`: a report if it is a valid
    /// report (some frames are valid both ways: a digital write is byte for
    /// byte a digital report), else a command.
    pub fn parse_in(frame: &'a [u8], dialect: Dialect) -> Result<Self, Error> {
        match parse_report_with(dialect, false, frame) {
            Ok(report) => Ok(Message::Report(report)),
            Err(report_error) => match parse_command(dialect, frame) {
                Ok(command) => Ok(Message::Command(command)),
                Err(command_error) => Err(match report_error {
                    Error::UnknownId { .. } => command_error,
                    other => other,
                }),
            },
        }
    }
}

/// [`Message::parse_in`] for mirte 1.3.
impl<'a> TryFrom<&'a [u8]> for Message<'a> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        Message::parse_in(frame, Dialect::Mirte13)
    }
}

/// Which reading of a [`MessageBuf`]'s frame it stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Direction {
    Command,
    Report,
}

/// How a [`MessageBuf`] reads its frame: everything it keeps beside the
/// bytes (the dialect, leniency, direction, [`also`](MessageBuf::also) and
/// [`module_type`](MessageBuf::module_type)). With the frame's bytes it is the
/// whole message in a few bytes, for a host that keeps many messages: a
/// `MessageBuf` has room for the longest frame, 256 bytes, where most are 4
/// to 6. [`MessageBuf::from_attribution`] gives the message back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Attribution {
    dialect: Dialect,
    lenient: bool,
    direction: Direction,
    also: bool,
    module_type: Option<ModuleType>,
}

impl Attribution {
    /// The dialect the frame is read in.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Whether the frame is attributed to the host (a command).
    pub const fn is_command(&self) -> bool {
        matches!(self.direction, Direction::Command)
    }
}

/// An owned [`Message`]: the bytes of one frame, the direction it is read
/// in, and what a [`CaptureContext`](super::CaptureContext) found out about
/// it: whether the frame is valid the other way too ([`also`](Self::also)),
/// and the type of the module a MODULE_DATA command goes to
/// ([`module_type`](Self::module_type)), with which it serializes typed.
/// It is what a [`BothDecoder`](super::BothDecoder)'s `feed` and `flush`
/// yield.
#[derive(Clone, Copy)]
pub struct MessageBuf {
    bytes: [u8; MAX_FRAME_LEN],
    dialect: Dialect,
    lenient: bool,
    direction: Direction,
    also: bool,
    module_type: Option<ModuleType>,
}

impl MessageBuf {
    fn with(bytes: &[u8], dialect: Dialect, lenient: bool, direction: Direction) -> Self {
        let mut all = [0; MAX_FRAME_LEN];
        if let Some(dst) = all.get_mut(..bytes.len()) {
            dst.copy_from_slice(bytes);
        }
        Self {
            bytes: all,
            dialect,
            lenient,
            direction,
            also: false,
            module_type: None,
        }
    }

    /// Copy one complete frame of `dialect`, read as [`Message::parse_in`]
    /// reads it.
    pub fn parse_in(frame: &[u8], dialect: Dialect) -> Result<Self, Error> {
        let direction = match Message::parse_in(frame, dialect)? {
            Message::Command(_) => Direction::Command,
            Message::Report(_) => Direction::Report,
        };
        Ok(Self::with(frame, dialect, false, direction))
    }

    /// How the frame is read: with [`frame`](Self::frame), all of the
    /// message (see [`Attribution`]).
    pub const fn attribution(&self) -> Attribution {
        Attribution {
            dialect: self.dialect,
            lenient: self.lenient,
            direction: self.direction,
            also: self.also,
            module_type: self.module_type,
        }
    }

    /// The message of `frame` read as `attribution` says: the
    /// [`frame`](Self::frame) and [`attribution`](Self::attribution) of a
    /// `MessageBuf` give it back. `frame` must be one whole frame (its `LEN`
    /// byte, an id and `LEN` − 1 bytes more; else [`Error::BadLength`] or
    /// [`Error::Truncated`]); its content is read as the
    /// `MessageBuf` it came from read it, without a new check.
    ///
    /// ```
    /// use robowire::telemetrix::{Message, MessageBuf, Report};
    ///
    /// let analog = MessageBuf::try_from(&[0x04, 0x03, 0x1A, 0x01, 0xF4][..])?;
    /// let (frame, attribution) = (analog.frame().to_vec(), analog.attribution());
    /// let again = MessageBuf::from_attribution(&frame, attribution)?;
    /// assert_eq!(again, analog);
    /// assert!(matches!(again.message(), Message::Report(Report::Analog { pin: 26, value: 500 })));
    /// # Ok::<(), robowire::telemetrix::Error>(())
    /// ```
    pub fn from_attribution(frame: &[u8], attribution: Attribution) -> Result<Self, Error> {
        split_frame(frame)?;
        let mut message = Self::with(
            frame,
            attribution.dialect,
            attribution.lenient,
            attribution.direction,
        );
        message.also = attribution.also;
        message.module_type = attribution.module_type;
        Ok(message)
    }

    /// The message, in the direction the frame is attributed to.
    pub fn message(&self) -> Message<'_> {
        match self.direction {
            Direction::Command => Message::Command(self.command_reading().unwrap_or(NO_COMMAND)),
            Direction::Report => Message::Report(self.report_reading().unwrap_or(NO_REPORT)),
        }
    }

    /// What is dubious in the frame read in its direction, if anything (see
    /// [`Quirk`]).
    pub fn quirk(&self) -> Option<Quirk> {
        match self.direction {
            Direction::Command => command_quirk(self.dialect, self.frame()),
            Direction::Report => report_quirk(self.dialect, self.frame()),
        }
    }

    /// The owned form of `message`, parsed from `frame`: the frame's own
    /// bytes (see [`CommandBuf::from_frame`]).
    pub(crate) fn from_frame(frame: &[u8], message: &Message<'_>) -> Self {
        match message {
            Message::Command(c) => CommandBuf::from_frame(frame, c).into(),
            Message::Report(r) => ReportBuf::from_frame(frame, r).into(),
        }
    }

    /// The frame read the other way, when a
    /// [`CaptureContext`](super::CaptureContext) found it valid both ways.
    pub fn also(&self) -> Option<Message<'_>> {
        if !self.also {
            return None;
        }
        match self.direction {
            Direction::Command => self.report_reading().map(Message::Report),
            Direction::Report => self.command_reading().map(Message::Command),
        }
    }

    /// For a MODULE_DATA command: the module's type, where a
    /// [`CaptureContext`](super::CaptureContext) saw the MODULE_NEW (or a
    /// report) that gave it.
    pub const fn module_type(&self) -> Option<ModuleType> {
        self.module_type
    }

    /// Whether the frame is attributed to the host (a command).
    pub const fn is_command(&self) -> bool {
        matches!(self.direction, Direction::Command)
    }

    /// The frame's bytes.
    pub fn frame(&self) -> &[u8] {
        frame_of(&self.bytes)
    }

    /// The dialect the frame is read in.
    pub const fn dialect(&self) -> Dialect {
        self.dialect
    }

    fn command_reading(&self) -> Option<Command<'_>> {
        parse_command(self.dialect, self.frame()).ok()
    }

    fn report_reading(&self) -> Option<Report<'_>> {
        parse_report_with(self.dialect, self.lenient, self.frame()).ok()
    }

    /// Re-read the frame in `dialect` as `direction`, valid the other way
    /// too when `also` (see [`CaptureContext`](super::CaptureContext)).
    pub(crate) fn attribute(
        &mut self,
        dialect: Dialect,
        lenient: bool,
        as_command: bool,
        also: bool,
    ) {
        self.dialect = dialect;
        self.lenient = lenient;
        self.direction = if as_command {
            Direction::Command
        } else {
            Direction::Report
        };
        self.also = also;
    }

    pub(crate) fn set_module_type(&mut self, module_type: Option<ModuleType>) {
        self.module_type = module_type;
    }
}

impl From<CommandBuf> for MessageBuf {
    fn from(command: CommandBuf) -> Self {
        Self::with(command.frame(), command.dialect, false, Direction::Command)
    }
}

impl From<ReportBuf> for MessageBuf {
    fn from(report: ReportBuf) -> Self {
        Self::with(
            report.frame(),
            report.dialect,
            report.lenient,
            Direction::Report,
        )
    }
}

impl From<&Message<'_>> for MessageBuf {
    /// The owned form of a parsed message (as a [`BothDecoder`](super::BothDecoder)
    /// makes it). A message that does not encode (one built by hand with a
    /// value out of range) gives a frame that reads as something else: use
    /// [`CommandBuf::new`] or [`ReportBuf::new`] to be told.
    fn from(message: &Message<'_>) -> Self {
        let mut bytes = [0; MAX_FRAME_LEN];
        let (dialect, lenient, direction) = match message {
            Message::Command(c) => {
                c.write_unchecked(&mut bytes);
                let dialect = command_dialect(c, frame_of(&bytes));
                (dialect, false, Direction::Command)
            }
            Message::Report(r) => {
                r.write_unchecked(&mut bytes);
                let (dialect, lenient) = report_dialect(r, frame_of(&bytes));
                (dialect, lenient, Direction::Report)
            }
        };
        Self {
            bytes,
            dialect,
            lenient,
            direction,
            also: false,
            module_type: None,
        }
    }
}

impl<'a> From<&'a CommandBuf> for Command<'a> {
    fn from(buf: &'a CommandBuf) -> Self {
        buf.message()
    }
}

impl<'a> From<&'a ReportBuf> for Report<'a> {
    fn from(buf: &'a ReportBuf) -> Self {
        buf.message()
    }
}

impl<'a> From<&'a MessageBuf> for Message<'a> {
    fn from(buf: &'a MessageBuf) -> Self {
        buf.message()
    }
}

impl TryFrom<&Command<'_>> for CommandBuf {
    type Error = EncodeError;

    /// [`CommandBuf::new`].
    fn try_from(command: &Command<'_>) -> Result<Self, EncodeError> {
        Self::new(command)
    }
}

impl TryFrom<&Report<'_>> for ReportBuf {
    type Error = EncodeError;

    /// [`ReportBuf::new`].
    fn try_from(report: &Report<'_>) -> Result<Self, EncodeError> {
        Self::new(report)
    }
}

/// [`CommandBuf::parse_in`] for mirte 1.3.
impl TryFrom<&[u8]> for CommandBuf {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        Self::parse_in(frame, Dialect::Mirte13)
    }
}

/// [`ReportBuf::parse_in`] for mirte 1.3, strict.
impl TryFrom<&[u8]> for ReportBuf {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        Self::parse_in(frame, Dialect::Mirte13, false)
    }
}

/// [`MessageBuf::parse_in`] for mirte 1.3.
impl TryFrom<&[u8]> for MessageBuf {
    type Error = Error;

    fn try_from(frame: &[u8]) -> Result<Self, Error> {
        Self::parse_in(frame, Dialect::Mirte13)
    }
}

impl Command<'_> {
    /// This command as an owned frame, encoded for mirte 1.3
    /// ([`CommandBuf::new`]).
    pub fn to_buf(&self) -> Result<CommandBuf, EncodeError> {
        CommandBuf::new(self)
    }

    /// This command as an owned frame, encoded for `dialect`.
    pub fn to_buf_in(&self, dialect: Dialect) -> Result<CommandBuf, EncodeError> {
        CommandBuf::new_in(self, dialect)
    }

    /// A MODULE_DATA command carrying `message` for module `module_num`,
    /// encoded for mirte 1.3 (the only dialect with modules).
    ///
    /// ```
    /// use robowire::telemetrix::{Command, HiwonderCommand, List, ServoMove};
    ///
    /// let moves = List::from_slice(&[ServoMove { idx: 0, centideg: 12000, time_ms: 500 }])?;
    /// let angle = Command::module_data(0, &HiwonderCommand::SetAngle(moves))?;
    /// assert_eq!(&angle[..], &[0x09, 0x22, 0x00, 0x01, 0x01, 0x00, 0x2E, 0xE0, 0x01, 0xF4]);
    /// # Ok::<(), robowire::EncodeError>(())
    /// ```
    pub fn module_data<M: ModuleCommand>(
        module_num: u8,
        message: &M,
    ) -> Result<CommandBuf, EncodeError> {
        let data = message.to_data()?;
        Command::ModuleData {
            module_num,
            data: &data,
        }
        .to_buf()
    }
}

impl Report<'_> {
    /// This report as an owned frame, encoded for mirte 1.3
    /// ([`ReportBuf::new`]).
    pub fn to_buf(&self) -> Result<ReportBuf, EncodeError> {
        ReportBuf::new(self)
    }

    /// This report as an owned frame, encoded for `dialect`.
    pub fn to_buf_in(&self, dialect: Dialect) -> Result<ReportBuf, EncodeError> {
        ReportBuf::new_in(self, dialect)
    }
}

macro_rules! buf_common {
    ($buf:ty, $max:expr) => {
        impl Deref for $buf {
            type Target = [u8];

            fn deref(&self) -> &[u8] {
                self.frame()
            }
        }

        impl AsRef<[u8]> for $buf {
            fn as_ref(&self) -> &[u8] {
                self.frame()
            }
        }

        /// Two owned messages are equal when their frames and messages are.
        impl PartialEq for $buf {
            fn eq(&self, other: &Self) -> bool {
                self.frame() == other.frame() && self.message() == other.message()
            }
        }

        impl Hash for $buf {
            fn hash<H: Hasher>(&self, state: &mut H) {
                self.frame().hash(state);
            }
        }

        impl fmt::Debug for $buf {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_tuple(stringify!($buf))
                    .field(&self.message())
                    .finish()
            }
        }

        #[cfg(feature = "defmt")]
        impl defmt::Format for $buf {
            fn format(&self, f: defmt::Formatter<'_>) {
                defmt::write!(f, "{}({})", stringify!($buf), self.message())
            }
        }

        /// Writes the frame's bytes (already encoded and checked).
        impl Encode for $buf {
            const MAX_LEN: usize = $max;

            fn encoded_len(&self) -> usize {
                self.frame().len()
            }

            fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
                let frame = self.frame();
                crate::encode::check_room(out, frame.len())?;
                if let Some(dst) = out.get_mut(..frame.len()) {
                    dst.copy_from_slice(frame);
                }
                Ok(frame.len())
            }
        }
    };
}

buf_common!(CommandBuf, MAX_COMMAND_FRAME);
buf_common!(ReportBuf, MAX_REPORT_FRAME);
buf_common!(MessageBuf, MAX_FRAME_LEN);

impl Eq for CommandBuf {}

macro_rules! buf_eq_message {
    ($buf:ty, $message:ident) => {
        /// An owned message equals the message it holds.
        impl PartialEq<$message<'_>> for $buf {
            fn eq(&self, other: &$message<'_>) -> bool {
                self.message() == *other
            }
        }

        /// A message equals an owned message that holds it.
        impl PartialEq<$buf> for $message<'_> {
            fn eq(&self, other: &$buf) -> bool {
                *self == other.message()
            }
        }

        impl $buf {
            /// The frame's id byte.
            pub fn id(&self) -> u8 {
                self.frame().get(1).copied().unwrap_or(0)
            }
        }
    };
}

buf_eq_message!(CommandBuf, Command);
buf_eq_message!(ReportBuf, Report);
