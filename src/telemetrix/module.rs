//! Modules: MODULE_NEW / MODULE_DATA (commands 33/34) and reports 33/34
//! (spec §7).
//!
//! MODULE_DATA does not say which kind of module it is for (the firmware
//! routes it by creation order), so a parsed [`Command::ModuleData`] carries
//! raw bytes; build them with [`Command::module_data`] and read them with the
//! module's `parse` ([`ModuleCommand`]). Reports (34) do carry the module type
//! and are decoded to [`ModuleReport`].

use super::error::{ensure, Error};
use super::kind::{bind_hook, field_type, parse_row, write_field, write_row};
use super::list::{List, Payload};
use super::wire::{command_id, Reader, Writer, COMMAND_PAYLOAD_MAX};
use crate::EncodeError;

/// Most bytes of a MODULE_NEW init (LEN 30 less `id, 01, num, type`).
pub const MODULE_INIT_MAX: usize = 26;

/// `ModuleType`, `ModuleInit` and `ModuleReport` with their codecs, from
/// the module table.
macro_rules! modules {
    ($($(#[$tm:meta])* $n:literal $t:ident $name:literal
        init {
            variants { $($idecl:tt)* }
            parse ($($ipp:ident),*) { $($ipb:tt)* }
            write ($($iwp:ident),*) { $($iwa:tt)* }
            fields ($($ifp:ident),*) { $($ifa:tt)* }
            read ($($irp:ident),*) { $($irb:tt)* }
        }
        data $data:ident $dsec:tt
        $(reports [$($rv:ident),+ $(,)?] {
            variants { $($rdecl:tt)* }
            len ($($lp:ident),*) { $($lb:tt)* }
            parse ($($rpp:ident),*) { $($rpb:tt)* }
            write ($($rwp:ident),*) { $($rwa:tt)* }
            fields ($($rfp:ident),*) { $($rfa:tt)* }
            read ($($rrp:ident),*) { $($rrb:tt)* }
        })?;)*) => {
        /// Module types (spec §7).
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum ModuleType {
            $($(#[$tm])* $t = $n,)*
        }

        impl ModuleType {
            /// Every module type, in id order.
            pub const ALL: [ModuleType; [$($n),*].len()] = [$(ModuleType::$t),*];

            /// The type for a wire value.
            pub const fn from_u8(value: u8) -> Option<Self> {
                match value {
                    $($n => Some(ModuleType::$t),)*
                    _ => None,
                }
            }
        }

        /// A module's MODULE_NEW init bytes, by type.
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum ModuleInit<'a> {
            $($($idecl)*)*
        }

        impl ModuleInit<'_> {
            /// The module type this init is for.
            pub const fn module_type(&self) -> ModuleType {
                match self {
                    $(ModuleInit::$t { .. } => ModuleType::$t,)*
                }
            }

            /// Write the init bytes (after the type byte).
            fn write(&self, w: &mut Writer<'_>) {
                match *self {
                    $(ModuleInit::$t { .. } => {
                        bind_hook!(($($iwp),*) = (w));
                        match *self {
                            $($iwa)*
                            _ => {}
                        }
                    })*
                }
            }
        }

        $(
            impl ModuleCommand for $data {
                const MODULE_TYPE: ModuleType = ModuleType::$t;

                fn to_data(&self) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError> {
                    data_of::<Self>(|w| module_data!(write (w, self) $dsec))
                }

                fn parse(data: &[u8]) -> Result<Self, Error> {
                    module_data!(parse (data) $dsec)
                }
            }
        )*

        impl<'a> ModuleNew<'a> {
            pub(crate) fn parse(r: &mut Reader<'a>) -> Result<Self, Error> {
                let id = r.id();
                match r.u8()? {
                    0 => Ok(ModuleNew::Check {
                        module_type: r.u8()?,
                    }),
                    1 => {
                        let module_num = r.u8()?;
                        let module_type = ModuleType::from_u8(r.u8()?).ok_or(Error::OutOfRange {
                            id,
                            field: "module_type",
                        })?;
                        // The init bytes after the type byte.
                        let init = match module_type {
                            $(ModuleType::$t => {
                                bind_hook!(($($ipp),*) = (&mut *r, id));
                                $($ipb)*
                            })*
                        };
                        Ok(ModuleNew::Add { module_num, init })
                    }
                    _ => Err(Error::OutOfRange {
                        id,
                        field: "subtype",
                    }),
                }
            }
        }

        /// The data of a MODULE_REPORT (report 34), by module type and subtype.
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum ModuleReport<'a> {
            $($($($rdecl)*)?)*
        }

        impl ModuleReport<'_> {
            /// The module type that sends this report.
            pub const fn module_type(&self) -> ModuleType {
                match self {
                    $($($(ModuleReport::$rv { .. } => ModuleType::$t,)+)?)*
                }
            }

            /// Write `type, subtype/data` (after the module number).
            pub(crate) fn write(&self, w: &mut Writer<'_>) {
                w.u8(self.module_type().as_u8());
                match *self {
                    $($($(ModuleReport::$rv { .. })|+ => {
                        bind_hook!(($($rwp),*) = (w));
                        match *self {
                            $($rwa)*
                            _ => {}
                        }
                    })?)*
                }
            }
        }

        impl<'a> ModuleReport<'a> {
            /// Parse `type, …` after the module number.
            pub(crate) fn parse(r: &mut Reader<'a>) -> Result<Self, Error> {
                let id = r.id();
                Ok(match ModuleType::from_u8(r.u8()?) {
                    $($(Some(ModuleType::$t) => {
                        bind_hook!(($($rpp),*) = (&mut *r, id));
                        $($rpb)*
                    })?)*
                    // The types without reports.
                    _ => return Err(Error::OutOfRange { id, field: "module_type" }),
                })
            }
        }

        /// Whether a report-34 `LEN` is possible given the bytes known so far
        /// (`LEN, 34, num, type, subtype, …`). Used to reject early.
        pub(crate) fn module_report_len_ok(len: u8, frame: &[u8]) -> bool {
            let at = |i: usize| frame.get(i).copied();
            match at(3) {
                None => (5..=255).contains(&len),
                $($(Some($n) => {
                    bind_hook!(($($lp),*) = (len, at));
                    $($lb)*
                })?)*
                // The types without reports.
                Some(_) => false,
            }
        }
    };
}

/// A module's MODULE_DATA codec: from its data table (`table`), or the
/// row's own `parse` and `write` pieces.
macro_rules! module_data {
    (write ($w:ident, $value:ident) table) => {
        $value.write_data($w)
    };
    (parse ($data:ident) table) => {
        Self::parse_data($data)
    };
    (write $ctx:tt { parse $pp:tt $pb:tt write ($($param:ident),*) { $($body:tt)* } $($rest:tt)* }) => {{
        bind_hook!(($($param),*) = $ctx);
        $($body)*
    }};
    (parse ($data:ident) { parse ($($param:ident),*) { $($body:tt)* } $($rest:tt)* }) => {{
        let mut r = data_reader($data);
        let id = r.id();
        let message = {
            bind_hook!(($($param),*) = (&mut r, id));
            $($body)*
        };
        r.end()?;
        Ok(message)
    }};
}

super::table::module_table!(modules);

impl ModuleType {
    /// The wire value.
    pub const fn as_u8(self) -> u8 {
        self as u8
    }
}

/// PCA9685 address and frequency (applied only when both are sent).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Pca9685Config {
    /// 7-bit address (default 0x40).
    pub addr: u8,
    /// PWM frequency in Hz (default 50).
    pub freq_hz: u16,
}

/// MODULE_NEW (command 33).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModuleNew<'a> {
    /// `00, type`: ask whether a type is supported (answered by report 33).
    Check {
        /// Any type value; unknown ones are answered "not supported".
        module_type: u8,
    },
    /// `01, num, type, init`: add a module (no reply).
    Add {
        /// Module number: number modules 0, 1, 2, … in creation order.
        module_num: u8,
        /// Type and init bytes.
        init: ModuleInit<'a>,
    },
}

impl ModuleNew<'_> {
    /// Length of the init bytes (0 for a check).
    pub(crate) fn init_len(&self) -> usize {
        match self {
            ModuleNew::Check { .. } => 0,
            ModuleNew::Add { init, .. } => {
                let mut w = Writer::new(&mut []);
                init.write(&mut w);
                w.len()
            }
        }
    }

    pub(crate) fn write(&self, w: &mut Writer<'_>) {
        match self {
            ModuleNew::Check { module_type } => w.bytes(&[0, *module_type]),
            ModuleNew::Add { module_num, init } => {
                w.bytes(&[1, *module_num, init.module_type().as_u8()]);
                init.write(w);
            }
        }
    }
}

/// The data of a MODULE_DATA command for one kind of module.
pub trait ModuleCommand: Sized {
    /// The module type the data is for.
    const MODULE_TYPE: ModuleType;

    /// The data bytes (1..=28), checked as the module's parser would.
    fn to_data(&self) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError>;

    /// Parse MODULE_DATA bytes sent to a module of this type.
    fn parse(data: &[u8]) -> Result<Self, Error>;
}

/// Write `message`'s data with `write`, then check it with `M::parse`.
fn data_of<M: ModuleCommand>(
    write: impl FnOnce(&mut Writer<'_>),
) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError> {
    let mut scratch = [0u8; COMMAND_PAYLOAD_MAX];
    // The writer counts past the end of `scratch` without writing there, so
    // an overlong message is measured, then refused.
    let mut w = Writer::new(&mut scratch);
    write(&mut w);
    let n = w.len();
    if n > COMMAND_PAYLOAD_MAX {
        return Err(EncodeError::TooLong {
            len: n,
            max: COMMAND_PAYLOAD_MAX,
        });
    }
    let data = scratch.get(..n).unwrap_or(&[]);
    M::parse(data).map_err(Error::into_encode_error)?;
    Payload::from_slice(data)
}

fn data_reader(data: &[u8]) -> Reader<'_> {
    let len = u8::try_from(data.len() + 2).unwrap_or(u8::MAX);
    Reader::new(command_id::MODULE_DATA, len, data)
}

/// A module data table's enum and its data's encode and parse: the `plain`
/// rows' from their fields (a unit variant when a row has none), the
/// `custom` rows' by their `write` and `parse` pieces.
macro_rules! module_data_codec {
    ($(#[$em:meta])* $enum:ident; $($rows:tt)*) => {
        module_data_codec!(@enum [$(#[$em])* $enum] [] $($rows)*);
        module_data_codec!(@codec $enum; $($rows)*);
    };
    (@enum $head:tt [$($vars:tt)*]
        $(#[$vm:meta])* $n:literal $name:literal [$($v:ident),+] plain $p:ident {};
        $($rest:tt)*) => {
        module_data_codec!(@enum $head [$($vars)* $(#[$vm])* $p,] $($rest)*);
    };
    (@enum $head:tt [$($vars:tt)*]
        $(#[$vm:meta])* $n:literal $name:literal [$($v:ident),+] plain $p:ident {
            $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
        }; $($rest:tt)*) => {
        module_data_codec!(@enum $head [
            $($vars)* $(#[$vm])* $p { $($(#[$fm])* $f: field_type!($kind $(($($arg)*))?),)* },
        ] $($rest)*);
    };
    (@enum $head:tt [$($vars:tt)*]
        $(#[$vm:meta])* $n:literal $name:literal [$($v:ident),+]
        custom { variants { $($decl:tt)* } $($hooks:tt)* }; $($rest:tt)*) => {
        module_data_codec!(@enum $head [$($vars)* $($decl)*] $($rest)*);
    };
    (@enum [$(#[$em:meta])* $enum:ident] [$($vars:tt)*]) => {
        $(#[$em])*
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $enum {
            $($vars)*
        }
    };
    (@codec $enum:ident; $($(#[$vm:meta])* $n:literal $name:literal [$($v:ident),+]
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        impl $enum {
            /// The subtype byte, then the row's fields.
            fn write_data(&self, w: &mut Writer<'_>) {
                match *self {
                    $($($enum::$v { .. })|+ => {
                        w.u8($n);
                        write_row!(self, (w), $enum, $codec $($p)? { $($body)* })
                    })*
                }
            }

            /// Parse MODULE_DATA bytes: the subtype byte picks the row.
            fn parse_data(data: &[u8]) -> Result<Self, Error> {
                let mut r = data_reader(data);
                let id = r.id();
                let message = match r.u8()? {
                    $($n => parse_row!((&mut r, id), r, id, $enum, $codec $($p)? { $($body)* }),)*
                    _ => {
                        return Err(Error::OutOfRange {
                            id,
                            field: "subtype",
                        })
                    }
                };
                r.end()?;
                Ok(message)
            }
        }
    };
}

/// Where a Hiwonder servo should move.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ServoMove {
    /// Servo index in the module's list.
    pub idx: u8,
    /// Angle in centidegrees, 0..=24000.
    pub centideg: u16,
    /// Move time in ms.
    pub time_ms: u16,
}

super::table::hiwonder_table!(module_data_codec);

const MAX_CENTIDEG: u16 = 24000;

/// One PCA9685 channel setting.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Pca9685Channel {
    /// Channel 0..=15.
    pub channel: u8,
    /// Tick at which the output turns on.
    pub on: u16,
    /// Tick at which the output turns off.
    pub off: u16,
}

/// PCA9685 data (module type 0), spec §7.2: 1..=5 channel settings,
/// big-endian.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Pca9685Command {
    /// The channels to set.
    pub channels: List<Pca9685Channel, 5>,
}

super::table::ssd1306_table!(module_data_codec);

/// Shutdown relay data (module type 2), spec §7.4.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RelayCommand {
    /// `[1]`: start the countdown (and stop PINGs feeding the watchdog).
    Start,
    /// `[0]`: cancel the countdown and re-enable the watchdog.
    Cancel,
}

/// A Hiwonder servo position in a positions report.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ServoPosition {
    /// Servo index.
    pub idx: u8,
    /// Position in centidegrees (as read from the servo; not range-checked).
    pub centideg: u16,
}

/// The positions of a Hiwonder positions report: `k × {idx, u16 centideg}`,
/// k ≥ 1, kept as the raw bytes of the frame.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ServoPositions<'a> {
    raw: &'a [u8],
}

impl<'a> ServoPositions<'a> {
    /// Wrap raw bytes (3 per servo: `idx, u16 centideg`). They are checked
    /// when encoded.
    pub const fn from_raw(raw: &'a [u8]) -> Self {
        Self { raw }
    }

    /// The raw bytes.
    pub const fn raw(&self) -> &'a [u8] {
        self.raw
    }

    /// Number of positions.
    pub const fn len(&self) -> usize {
        self.raw.len() / 3
    }

    /// Whether there are none (never, in a valid report).
    pub const fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The positions.
    pub fn iter(&self) -> impl Iterator<Item = ServoPosition> + 'a {
        self.raw.chunks_exact(3).map(|c| ServoPosition {
            idx: c[0],
            centideg: u16::from_be_bytes([c[1], c[2]]),
        })
    }
}

/// Completion kind of an SSD1306 report.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Ssd1306Done {
    /// After TEXT_DONE (1).
    Text,
    /// After BINARY_DONE (3).
    Binary,
}
