//! Modules: MODULE_NEW / MODULE_DATA (commands 33/34) and reports 33/34
//! (spec §7).
//!
//! MODULE_DATA does not say which kind of module it is for (the firmware
//! routes it by creation order), so a parsed [`Command::ModuleData`] carries
//! raw bytes; build them with [`Command::module_data`] and read them with the
//! module's `parse` ([`ModuleCommand`]). Reports (34) do carry the module type
//! and are decoded to [`ModuleReport`].

use super::error::{ensure, Error};
use super::kind::{bind_hook, field_type, read_field, write_field, write_row};
use super::list::{List, Payload};
use super::wire::{command_id, Reader, Writer, COMMAND_PAYLOAD_MAX};
use crate::EncodeError;

/// Most bytes of a MODULE_NEW init (LEN 30 less `id, 01, num, type`).
pub const MODULE_INIT_MAX: usize = 26;

/// Module types (spec §7).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModuleType {
    /// 0: PCA9685 PWM expander.
    Pca9685,
    /// 1: Hiwonder serial bus servos.
    HiwonderServo,
    /// 2: shutdown relay.
    ShutdownRelay,
    /// 3: SSD1306 OLED display.
    Ssd1306,
}

impl ModuleType {
    /// The type for a wire value.
    pub const fn from_u8(value: u8) -> Option<Self> {
        match value {
            0 => Some(ModuleType::Pca9685),
            1 => Some(ModuleType::HiwonderServo),
            2 => Some(ModuleType::ShutdownRelay),
            3 => Some(ModuleType::Ssd1306),
            _ => None,
        }
    }

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

/// A module's MODULE_NEW init bytes, by type.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModuleInit<'a> {
    /// `port [, addr, u16 freq_hz]`.
    Pca9685 {
        /// I2C port 0 or 1.
        port: u8,
        /// Address and frequency, or the defaults.
        config: Option<Pca9685Config>,
    },
    /// `uart, rx, tx, count, count × bus_id`.
    HiwonderServo {
        /// UART 0 or 1.
        uart: u8,
        /// RX GPIO (< 30).
        rx: u8,
        /// TX GPIO (< 30).
        tx: u8,
        /// Bus ids of the servos, at most 22; later messages use their index.
        bus_ids: &'a [u8],
    },
    /// `pin, active_level, wait_s`.
    ShutdownRelay {
        /// Relay GPIO (< 30).
        pin: u8,
        /// Level that drives the relay.
        active_high: bool,
        /// Countdown in s.
        wait_s: u8,
    },
    /// `port [, addr]`.
    Ssd1306 {
        /// I2C port 0 or 1.
        port: u8,
        /// 7-bit address (default 0x3C).
        addr: Option<u8>,
    },
}

impl ModuleInit<'_> {
    /// The module type this init is for.
    pub const fn module_type(&self) -> ModuleType {
        match self {
            ModuleInit::Pca9685 { .. } => ModuleType::Pca9685,
            ModuleInit::HiwonderServo { .. } => ModuleType::HiwonderServo,
            ModuleInit::ShutdownRelay { .. } => ModuleType::ShutdownRelay,
            ModuleInit::Ssd1306 { .. } => ModuleType::Ssd1306,
        }
    }
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
            ModuleNew::Add { init, .. } => match init {
                ModuleInit::Pca9685 { config, .. } => 1 + 3 * usize::from(config.is_some()),
                ModuleInit::HiwonderServo { bus_ids, .. } => 4 + bus_ids.len(),
                ModuleInit::ShutdownRelay { .. } => 3,
                ModuleInit::Ssd1306 { addr, .. } => 1 + usize::from(addr.is_some()),
            },
        }
    }

    pub(crate) fn write(&self, w: &mut Writer<'_>) {
        match self {
            ModuleNew::Check { module_type } => w.bytes(&[0, *module_type]),
            ModuleNew::Add { module_num, init } => {
                w.bytes(&[1, *module_num, init.module_type().as_u8()]);
                match init {
                    ModuleInit::Pca9685 { port, config } => {
                        w.u8(*port);
                        if let Some(c) = config {
                            w.u8(c.addr);
                            w.u16(c.freq_hz);
                        }
                    }
                    ModuleInit::HiwonderServo {
                        uart,
                        rx,
                        tx,
                        bus_ids,
                    } => {
                        w.bytes(&[*uart, *rx, *tx, bus_ids.len() as u8]);
                        w.bytes(bus_ids);
                    }
                    ModuleInit::ShutdownRelay {
                        pin,
                        active_high,
                        wait_s,
                    } => {
                        w.u8(*pin);
                        w.flag(*active_high);
                        w.u8(*wait_s);
                    }
                    ModuleInit::Ssd1306 { port, addr } => {
                        w.u8(*port);
                        if let Some(a) = addr {
                            w.u8(*a);
                        }
                    }
                }
            }
        }
    }
}

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
                let init = match module_type {
                    ModuleType::Pca9685 => {
                        let port = r.port()?;
                        let config = if r.remaining() > 0 {
                            let addr = r.u8()?;
                            ensure(addr <= 0x7f, id, "addr")?;
                            Some(Pca9685Config {
                                addr,
                                freq_hz: r.u16()?,
                            })
                        } else {
                            None
                        };
                        ModuleInit::Pca9685 { port, config }
                    }
                    ModuleType::HiwonderServo => {
                        let uart = r.port()?;
                        let (rx, tx) = (r.pin("rx")?, r.pin("tx")?);
                        let count = r.u8()?;
                        ModuleInit::HiwonderServo {
                            uart,
                            rx,
                            tx,
                            bus_ids: r.take(usize::from(count))?,
                        }
                    }
                    ModuleType::ShutdownRelay => ModuleInit::ShutdownRelay {
                        pin: r.pin("pin")?,
                        active_high: r.flag("active_level")?,
                        wait_s: r.u8()?,
                    },
                    ModuleType::Ssd1306 => {
                        let port = r.port()?;
                        let addr = if r.remaining() > 0 {
                            let addr = r.u8()?;
                            ensure(addr <= 0x7f, id, "addr")?;
                            Some(addr)
                        } else {
                            None
                        };
                        ModuleInit::Ssd1306 { port, addr }
                    }
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
/// `custom` rows' by the enum's `write_custom` and `parse_custom`.
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
                    $($n => data_row!(r, id, $n, $enum, $codec $($p)? { $($body)* }),)*
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

/// Parse one row of a module data table after its subtype byte.
macro_rules! data_row {
    ($r:ident, $id:ident, $n:literal, $enum:ident, custom {
        variants $vars:tt parse ($($param:ident),*) { $($body:tt)* } $($hooks:tt)*
    }) => {{
        bind_hook!(($($param),*) = (&mut $r, $id));
        $($body)*
    }};
    ($r:ident, $id:ident, $n:literal, $enum:ident, plain $p:ident {
        $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)?
    }) => {
        $enum::$p { $($f: read_field!($r, $id, $f, $key, $kind $(($($arg)*))?),)* }
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

impl ModuleCommand for HiwonderCommand {
    const MODULE_TYPE: ModuleType = ModuleType::HiwonderServo;

    fn to_data(&self) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError> {
        data_of::<Self>(|w| self.write_data(w))
    }

    fn parse(data: &[u8]) -> Result<Self, Error> {
        Self::parse_data(data)
    }
}

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

impl ModuleCommand for Pca9685Command {
    const MODULE_TYPE: ModuleType = ModuleType::Pca9685;

    fn to_data(&self) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError> {
        data_of::<Self>(|w| {
            for c in &self.channels {
                w.u8(c.channel);
                w.u16(c.on);
                w.u16(c.off);
            }
        })
    }

    fn parse(data: &[u8]) -> Result<Self, Error> {
        let mut r = data_reader(data);
        ensure(!data.is_empty(), r.id(), "channels")?;
        let mut channels = List::new();
        while r.remaining() > 0 {
            let c = Pca9685Channel {
                channel: r.u8()?,
                on: r.u16()?,
                off: r.u16()?,
            };
            ensure(c.channel <= 15, r.id(), "channel")?;
            channels.push(c).map_err(|_| r.bad_length())?;
        }
        Ok(Pca9685Command { channels })
    }
}

super::table::ssd1306_table!(module_data_codec);

impl ModuleCommand for Ssd1306Command {
    const MODULE_TYPE: ModuleType = ModuleType::Ssd1306;

    fn to_data(&self) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError> {
        data_of::<Self>(|w| self.write_data(w))
    }

    fn parse(data: &[u8]) -> Result<Self, Error> {
        Self::parse_data(data)
    }
}

/// Shutdown relay data (module type 2), spec §7.4.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RelayCommand {
    /// `[1]`: start the countdown (and stop PINGs feeding the watchdog).
    Start,
    /// `[0]`: cancel the countdown and re-enable the watchdog.
    Cancel,
}

impl ModuleCommand for RelayCommand {
    const MODULE_TYPE: ModuleType = ModuleType::ShutdownRelay;

    fn to_data(&self) -> Result<Payload<COMMAND_PAYLOAD_MAX>, EncodeError> {
        data_of::<Self>(|w| w.flag(*self == RelayCommand::Start))
    }

    fn parse(data: &[u8]) -> Result<Self, Error> {
        let mut r = data_reader(data);
        let start = r.flag("start")?;
        r.end()?;
        Ok(if start {
            RelayCommand::Start
        } else {
            RelayCommand::Cancel
        })
    }
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

/// The data of a MODULE_REPORT (report 34), by module type and subtype.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModuleReport<'a> {
    /// Hiwonder subtype 0: positions of changed servos (and each at least once
    /// a second).
    HiwonderPositions(ServoPositions<'a>),
    /// Hiwonder subtype 4: ID_VERIFY reply.
    HiwonderIdVerify {
        /// The bus id asked about.
        bus_id: u8,
        /// Whether it answered.
        ok: bool,
    },
    /// Hiwonder subtype 6: RANGE_READ reply.
    HiwonderRange {
        /// Servo index.
        idx: u8,
        /// Lower limit in centidegrees.
        min_cdeg: u16,
        /// Upper limit in centidegrees.
        max_cdeg: u16,
    },
    /// Hiwonder subtype 8: OFFSET_READ reply.
    HiwonderOffset {
        /// Servo index.
        idx: u8,
        /// Offset in centidegrees.
        offset_cdeg: i16,
    },
    /// Hiwonder subtype 11: ADD_SERVO reply.
    HiwonderAdded {
        /// The bus id added.
        bus_id: u8,
        /// Its index.
        idx: u8,
    },
    /// SSD1306: a text or binary transfer completed.
    Ssd1306Done {
        /// Which transfer.
        kind: Ssd1306Done,
        /// Text length, or 1.
        len: u8,
        /// Display x position.
        display_x: u8,
        /// Whether the display is enabled.
        enabled: bool,
    },
    /// SSD1306: a request was refused because the display is disabled.
    Ssd1306Disabled {
        /// Subtype of the refused request, echoed: 0..=3, or whatever a
        /// request carried ([`Quirk::EchoedRequestByte`](super::Quirk::EchoedRequestByte);
        /// the encoder sends 0..=3 only).
        request_sub: u8,
    },
}

impl ModuleReport<'_> {
    /// The module type that sends this report.
    pub const fn module_type(&self) -> ModuleType {
        match self {
            ModuleReport::Ssd1306Done { .. } | ModuleReport::Ssd1306Disabled { .. } => {
                ModuleType::Ssd1306
            }
            _ => ModuleType::HiwonderServo,
        }
    }

    /// Write `type, subtype/data` (after the module number).
    pub(crate) fn write(&self, w: &mut Writer<'_>) {
        w.u8(self.module_type().as_u8());
        match self {
            ModuleReport::HiwonderPositions(p) => {
                w.u8(0);
                w.bytes(p.raw);
            }
            ModuleReport::HiwonderIdVerify { bus_id, ok } => {
                w.bytes(&[4, *bus_id]);
                w.flag(*ok);
            }
            ModuleReport::HiwonderRange {
                idx,
                min_cdeg,
                max_cdeg,
            } => {
                w.bytes(&[6, *idx]);
                w.u16(*min_cdeg);
                w.u16(*max_cdeg);
            }
            ModuleReport::HiwonderOffset { idx, offset_cdeg } => {
                w.bytes(&[8, *idx]);
                w.i16(*offset_cdeg);
            }
            ModuleReport::HiwonderAdded { bus_id, idx } => w.bytes(&[11, *bus_id, *idx]),
            ModuleReport::Ssd1306Done {
                kind,
                len,
                display_x,
                enabled,
            } => {
                let kind = match kind {
                    Ssd1306Done::Text => 1,
                    Ssd1306Done::Binary => 3,
                };
                w.bytes(&[kind, *len, *display_x]);
                w.flag(*enabled);
            }
            ModuleReport::Ssd1306Disabled { request_sub } => w.bytes(&[*request_sub, 254]),
        }
    }
}

impl<'a> ModuleReport<'a> {
    /// Parse `type, …` after the module number.
    pub(crate) fn parse(r: &mut Reader<'a>) -> Result<Self, Error> {
        let id = r.id();
        match ModuleType::from_u8(r.u8()?) {
            Some(ModuleType::HiwonderServo) => Ok(match r.u8()? {
                0 => {
                    let raw = r.rest();
                    if raw.is_empty() || raw.len() % 3 != 0 {
                        return Err(r.bad_length());
                    }
                    ModuleReport::HiwonderPositions(ServoPositions { raw })
                }
                4 => ModuleReport::HiwonderIdVerify {
                    bus_id: r.u8()?,
                    ok: r.flag("ok")?,
                },
                6 => ModuleReport::HiwonderRange {
                    idx: r.u8()?,
                    min_cdeg: r.u16()?,
                    max_cdeg: r.u16()?,
                },
                8 => ModuleReport::HiwonderOffset {
                    idx: r.u8()?,
                    offset_cdeg: r.i16()?,
                },
                11 => ModuleReport::HiwonderAdded {
                    bus_id: r.u8()?,
                    idx: r.u8()?,
                },
                _ => {
                    return Err(Error::OutOfRange {
                        id,
                        field: "subtype",
                    })
                }
            }),
            Some(ModuleType::Ssd1306) => match r.remaining() {
                4 => {
                    let kind = match r.u8()? {
                        1 => Ssd1306Done::Text,
                        3 => Ssd1306Done::Binary,
                        _ => {
                            return Err(Error::OutOfRange {
                                id,
                                field: "msg_type",
                            })
                        }
                    };
                    Ok(ModuleReport::Ssd1306Done {
                        kind,
                        len: r.u8()?,
                        display_x: r.u8()?,
                        enabled: r.flag("enabled")?,
                    })
                }
                2 => {
                    // The firmware echoes the request's subtype byte, whatever
                    // it was: accepted, and flagged as a quirk above 3.
                    let request_sub = r.u8()?;
                    ensure(r.u8()? == 254, id, "disabled marker")?;
                    Ok(ModuleReport::Ssd1306Disabled { request_sub })
                }
                _ => Err(r.bad_length()),
            },
            // PCA9685 and the shutdown relay send no reports.
            _ => Err(Error::OutOfRange {
                id,
                field: "module_type",
            }),
        }
    }
}

/// Whether a report-34 `LEN` is possible given the bytes known so far
/// (`LEN, 34, num, type, subtype, …`). Used to reject early.
pub(crate) fn module_report_len_ok(len: u8, frame: &[u8]) -> bool {
    match (frame.get(3), frame.get(4)) {
        (None, _) => (5..=255).contains(&len),
        (Some(1), None) => len >= 6,
        (Some(1), Some(0)) => len >= 7 && (len - 4) % 3 == 0,
        (Some(1), Some(4 | 11)) => len == 6,
        (Some(1), Some(6)) => len == 9,
        (Some(1), Some(8)) => len == 7,
        (Some(1), Some(_)) => false,
        (Some(3), _) => len == 5 || len == 7,
        (Some(_), _) => false,
    }
}
