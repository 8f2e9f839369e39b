//! Commands (host → Pico), spec §4.

use super::dialect::Dialect;
use super::error::{ensure, Error};
use super::kind::{check_row, field_type, parse_row, piece, write_field, write_row};
use super::list::List;
use super::module::{ModuleNew, MODULE_INIT_MAX};
use super::quirk::command_quirk;
use super::sensor::SensorNew;
use super::wire::{
    analog_pin_ok, counted, split_frame, Reader, Writer, COMMAND_PAYLOAD_MAX, MAX_COMMAND_FRAME,
    MAX_COMMAND_LEN, PIN_COUNT,
};
use crate::encode::check_room;
use crate::{Encode, EncodeError};

/// The codec's parts that come from the command table: the dialect and
/// `LEN` tables, `Command::id`, and every row's payload writer.
macro_rules! command_codec {
    ($($(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+] len $lens:tt
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        /// Whether `dialect` defines command `id` (and robowire covers it there).
        pub(crate) const fn command_known(dialect: Dialect, id: u8) -> bool {
            match id {
                $($n => matches!(dialect, $(Dialect::$d)|+),)*
                _ => false,
            }
        }

        /// The smallest and largest `LEN` a command can have, or `None` for
        /// an unknown id. Used to reject a candidate from its first two bytes.
        pub(crate) const fn command_len_range(dialect: Dialect, id: u8) -> Option<(u8, u8)> {
            if !command_known(dialect, id) {
                return None;
            }
            Some(match id {
                $($n => len_range!(dialect, $lens),)*
                _ => return None,
            })
        }

        impl Command<'_> {
            /// The command id.
            pub const fn id(&self) -> u8 {
                match self {
                    $($(Command::$v { .. })|+ => $n,)*
                }
            }

            /// The encoder's checks of this command in `dialect` beyond its id's
            /// dialects: its row's `check` piece (a variant's own dialects, the
            /// spec's maxima of byte fields), or a `plain` row's field maxima.
            fn check_row(&self, dialect: Dialect) -> Result<(), EncodeError> {
                match *self {
                    $($(Command::$v { .. })|+ => {
                        check_row!(self, dialect, Command, $codec $($p)? { $($body)* })
                    })*
                }
            }

            /// The dialects whose layout this variant has, most recent first
            /// (its row's `home` piece, or the row's dialects): a frame this
            /// command encodes to parses back to it in each of them where it
            /// is valid.
            pub(crate) const fn home_dialects(&self) -> &'static [Dialect] {
                match *self {
                    $($(Command::$v { .. })|+ => {
                        piece!(home (self) expr { &[$(Dialect::$d),+] }, $codec $($p)? { $($body)* })
                    })*
                }
            }

            fn write_payload(&self, w: &mut Writer<'_>) {
                match *self {
                    $($(Command::$v { .. })|+ => {
                        write_row!(self, (w), Command, $codec $($p)? { $($body)* })
                    })*
                }
            }
        }

        /// Parse a command's payload: an arm per row of the command table,
        /// in one `match` so that the Pico links one compact function.
        fn parse_payload<'a>(dialect: Dialect, r: &mut Reader<'a>) -> Result<Command<'a>, Error> {
            let cmd = r.id();
            Ok(match cmd {
                $($n => parse_row!((dialect, &mut *r, cmd), r, cmd, Command, $codec $($p)? { $($body)* }),)*
                _ => return Err(Error::UnknownId { id: cmd }),
            })
        }
    };
}

/// A row's `LEN` range: one pair, or a `match` on the dialect.
macro_rules! len_range {
    ($dialect:ident, ($lo:literal, $hi:literal)) => {
        ($lo, $hi)
    };
    ($dialect:ident, { $($arms:tt)* }) => {
        match $dialect { $($arms)* }
    };
}

super::table::command_table!(command_codec);

/// Pull resistor of a digital input (SET_PIN_MODE modes 0, 3, 4).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Pull {
    /// No pull (mode 0).
    #[default]
    None,
    /// Pull-up (mode 3).
    Up,
    /// Pull-down (mode 4).
    Down,
}

/// A pin mode with its SET_PIN_MODE tail (spec §4.1).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PinMode {
    /// Digital input (modes 0/3/4, tail `report_enable`).
    DigitalInput {
        /// Pull resistor.
        pull: Pull,
        /// Report changes.
        report: bool,
    },
    /// Digital output (mode 1).
    DigitalOutput,
    /// PWM output at 50 Hz, TOP 19999 (mode 2).
    PwmOutput,
    /// Analog input (mode 5, tail `u16 differential, report_enable`). The pin
    /// is a GPIO number 26..=30 in mirte 1.3, an ADC number 0..=4 before.
    AnalogInput {
        /// Smallest change that is reported (the firmware clamps it to ≥ 1).
        differential: u16,
        /// Report changes.
        report: bool,
    },
}

/// One pin of a PWM_WRITE.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct PwmPin {
    /// GPIO number (< 30).
    pub pin: u8,
    /// Level, 0..=19999 (≥ 19999 is fully on).
    pub value: u16,
}

/// The pins of a PWM_WRITE: 1..=9 in mirte 1.3, exactly 1 in older dialects.
pub type PwmPins = List<PwmPin, 9>;

/// MODIFY_REPORTING (spec §4.2).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModifyReporting {
    /// Disable all analog and digital reporting (type 0, pin 0).
    DisableAll,
    /// Enable an analog pin (type 1).
    EnableAnalog {
        /// GPIO 26..=30 (mirte 1.3) or ADC 0..=4 (older).
        pin: u8,
    },
    /// Enable a digital pin (type 2). Not in mirte 1.3, whose firmware indexes
    /// the pin as `pin - 26`; use [`PinMode::DigitalInput`]'s `report` there.
    EnableDigital {
        /// GPIO number (< 30).
        pin: u8,
    },
    /// Disable an analog pin (type 3).
    DisableAnalog {
        /// GPIO 26..=30 (mirte 1.3) or ADC 0..=4 (older).
        pin: u8,
    },
    /// Disable a digital pin (type 4). Not in mirte 1.3 (see
    /// [`EnableDigital`](Self::EnableDigital)).
    DisableDigital {
        /// GPIO number (< 30).
        pin: u8,
    },
}

/// A colour for the neopixel commands.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Rgb {
    /// Red.
    pub r: u8,
    /// Green.
    pub g: u8,
    /// Blue.
    pub b: u8,
}

/// Encoder kind of ENCODER_NEW.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EncoderKind {
    /// Single pin (1); `pin_b` must be 0.
    Single,
    /// Quadrature (2).
    Quadrature,
}

/// Pull resistors of ENCODER_NEW's pins (mirte 1.3 only; bit 0 up, bit 1 down).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Pulls {
    /// Pull-ups.
    pub up: bool,
    /// Pull-downs.
    pub down: bool,
}

/// The `Command` enum, from the command table: a `plain` row's variant is
/// built from its fields (a unit variant when it has none), a `custom` row
/// gives its variants as written.
macro_rules! command_enum {
    (@rows [$($vars:tt)*]
        $(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+]
        len $lens:tt plain $p:ident {}; $($rest:tt)*) => {
        command_enum!(@rows [$($vars)* $(#[$vm])* $p,] $($rest)*);
    };
    (@rows [$($vars:tt)*]
        $(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+]
        len $lens:tt plain $p:ident {
            $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
        }; $($rest:tt)*) => {
        command_enum!(@rows [
            $($vars)* $(#[$vm])* $p { $($(#[$fm])* $f: field_type!($kind $(($($arg)*))?),)* },
        ] $($rest)*);
    };
    (@rows [$($vars:tt)*]
        $(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+]
        len $lens:tt custom { variants { $($decl:tt)* } $($hooks:tt)* }; $($rest:tt)*) => {
        command_enum!(@rows [$($vars)* $($decl)*] $($rest)*);
    };
    (@rows [$($vars:tt)*]) => {
        /// A command, host → Pico. Variable byte fields (I2C and SPI data, chip
        /// selects, MODULE_NEW bus ids, MODULE_DATA) borrow from the frame they were
        /// parsed from or from the caller; [`CommandBuf`](super::CommandBuf) is the
        /// owned form.
        ///
        /// Every variant is encoded with its full payload (the firmware never clears
        /// its command buffer); the encoder refuses values the firmware would
        /// mishandle (pins ≥ 30, counts above the spec §4 maxima, ids the dialect does
        /// not define).
        ///
        /// With the `serde` feature it serializes in the JSON-lines schema of the
        /// `robowire` tool (`{"type":"ping","counter":7}`); deserialize a
        /// [`CommandBuf`](super::CommandBuf), which owns its bytes.
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        // A word-sized tag: the variants' byte fields then start word-aligned,
        // so the Pico moves an event with whole-word loads instead of calling
        // `memcpy` for an odd run of bytes after a one-byte tag (its command
        // decoder links no `memcpy`: size/report.py). The invalid tag values
        // are still a niche: `Result<Command, Error>` is no larger.
        #[repr(u32)]
        pub enum Command<'a> {
            $($vars)*
        }
    };
    ($($rows:tt)*) => {
        command_enum!(@rows [] $($rows)*);
    };
}

super::table::command_table!(command_enum);

impl<'a> Command<'a> {
    /// Frame length of this command in `dialect`.
    pub fn encoded_len_in(&self, _dialect: Dialect) -> usize {
        let mut w = Writer::new(&mut []);
        self.write(&mut w);
        w.len()
    }

    /// Encode this command for `dialect` into the front of `out`; returns the
    /// frame length. Nothing is written on error.
    pub fn encode_in(&self, dialect: Dialect, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.encode_checked(dialect, out, false)
    }

    /// [`encode_in`](Self::encode_in), which with `even_if_refused` also
    /// emits a frame that has a quirk.
    pub(crate) fn encode_checked(
        &self,
        dialect: Dialect,
        out: &mut [u8],
        even_if_refused: bool,
    ) -> Result<usize, EncodeError> {
        if !command_known(dialect, self.id()) {
            return Err(EncodeError::Inconsistent {
                what: "the command does not exist in this dialect",
            });
        }
        self.check_row(dialect)?;
        let n = self.encoded_len_in(dialect);
        if n > MAX_COMMAND_FRAME {
            return Err(EncodeError::TooLong {
                len: n - 1,
                max: MAX_COMMAND_LEN,
            });
        }
        check_room(out, n)?;
        let mut scratch = [0u8; MAX_COMMAND_FRAME];
        let mut w = Writer::new(&mut scratch);
        self.write(&mut w);
        let frame = scratch.get(..n).unwrap_or(&[]);
        // The decoder is the one definition of a valid frame: the encoder
        // emits nothing it would reject.
        parse_command(dialect, frame).map_err(Error::into_encode_error)?;
        // ... nor anything it flags: those frames are a real host's, never
        // what robowire sends.
        match command_quirk(dialect, frame) {
            Some(quirk) if !even_if_refused => return Err(quirk.into_encode_error(frame)),
            _ => {}
        }
        if let Some(dst) = out.get_mut(..n) {
            dst.copy_from_slice(frame);
        }
        Ok(n)
    }

    /// Write the frame into `out` without checking it; returns its length
    /// (which may exceed `out`, whose bytes past the end are then not
    /// written). The bytes do not depend on the dialect.
    pub(crate) fn write_unchecked(&self, out: &mut [u8]) -> usize {
        let mut w = Writer::new(out);
        self.write(&mut w);
        w.len()
    }

    /// Write the whole frame; `LEN` is filled in once the payload is written.
    fn write(&self, w: &mut Writer<'_>) {
        w.u8(0);
        w.u8(self.id());
        self.write_payload(w);
        w.patch_len();
    }
}

impl Encode for Command<'_> {
    const MAX_LEN: usize = MAX_COMMAND_FRAME;

    /// The frame length in the default dialect (mirte 1.3).
    fn encoded_len(&self) -> usize {
        self.encoded_len_in(Dialect::Mirte13)
    }

    /// Encode for the default dialect (mirte 1.3); see
    /// [`Command::encode_in`] and [`InDialect`](super::InDialect) for others.
    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.encode_in(Dialect::Mirte13, out)
    }
}

/// Parse one complete command frame (`LEN` byte first) for `dialect`. This is
/// the one definition of a valid command: the decoder accepts exactly what it
/// accepts, and the encoder emits nothing it rejects.
pub(crate) fn parse_command(dialect: Dialect, frame: &[u8]) -> Result<Command<'_>, Error> {
    let (len, cmd, payload) = split_frame(frame)?;
    let Some((min, max)) = command_len_range(dialect, cmd) else {
        return Err(Error::UnknownId { id: cmd });
    };
    if len < min || len > max {
        return Err(Error::BadLength { id: cmd, len });
    }
    let mut r = Reader::new(cmd, len, payload);
    let command = parse_payload(dialect, &mut r)?;
    r.end()?;
    Ok(command)
}

/// An I2C command's layout in `dialect`: mirte's carries `msg_id`,
/// upstream's does not.
fn i2c_layout(mirte_layout: bool, dialect: Dialect) -> Result<(), EncodeError> {
    match (mirte_layout, dialect.is_mirte()) {
        (true, false) => Err(EncodeError::Inconsistent {
            what: "upstream firmware takes I2C commands without msg_id",
        }),
        (false, true) => Err(EncodeError::Inconsistent {
            what: "mirte firmware takes I2C commands with msg_id",
        }),
        _ => Ok(()),
    }
}

/// A byte list of `len` bytes where the spec allows at most `max`.
fn at_most(len: usize, max: usize) -> Result<(), EncodeError> {
    if len > max {
        Err(EncodeError::TooLong { len, max })
    } else {
        Ok(())
    }
}

fn rgb(r: &mut Reader<'_>) -> Result<Rgb, Error> {
    let [r_, g, b] = r.array()?;
    Ok(Rgb { r: r_, g, b })
}

impl<'a> Command<'a> {
    /// Parse one complete command frame (`LEN` byte first, nothing after the
    /// frame) of `dialect`. [`TryFrom<&[u8]>`](#impl-TryFrom%3C%26%5Bu8%5D%3E-for-Command%3C'a%3E)
    /// parses mirte 1.3.
    ///
    /// ```
    /// use robowire::telemetrix::{Command, Dialect};
    ///
    /// let ping = Command::parse_in(&[0x02, 0x20, 0x07], Dialect::Mirte12)?;
    /// assert_eq!(ping, Command::Ping { counter: 7 });
    /// # Ok::<(), robowire::telemetrix::Error>(())
    /// ```
    pub fn parse_in(frame: &'a [u8], dialect: Dialect) -> Result<Self, Error> {
        parse_command(dialect, frame)
    }
}

/// Parse one complete mirte 1.3 command frame (`LEN` byte first); see
/// [`Command::parse_in`] for other dialects.
impl<'a> TryFrom<&'a [u8]> for Command<'a> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        parse_command(Dialect::Mirte13, frame)
    }
}
