//! Commands (host → Pico), spec §4.

use super::dialect::Dialect;
use super::error::{ensure, Error};
use super::list::{List, Payload};
use super::module::ModuleNew;
use super::sensor::SensorNew;
use super::wire::{Reader, Writer};
use super::{analog_pin_ok, MAX_COMMAND_LEN};
use crate::encode::check_room;
use crate::{Encode, EncodeError};

/// Command ids (host → Pico), mirte firmware 1.3 numbering (spec §4).
pub mod command_id {
    /// SERIAL_LOOP_BACK.
    pub const SERIAL_LOOP_BACK: u8 = 0;
    /// SET_PIN_MODE.
    pub const SET_PIN_MODE: u8 = 1;
    /// DIGITAL_WRITE.
    pub const DIGITAL_WRITE: u8 = 2;
    /// PWM_WRITE.
    pub const PWM_WRITE: u8 = 3;
    /// MODIFY_REPORTING.
    pub const MODIFY_REPORTING: u8 = 4;
    /// GET_FIRMWARE_VERSION.
    pub const GET_FIRMWARE_VERSION: u8 = 5;
    /// GET_PICO_UNIQUE_ID.
    pub const GET_PICO_UNIQUE_ID: u8 = 6;
    /// SERVO_ATTACH.
    pub const SERVO_ATTACH: u8 = 7;
    /// SERVO_WRITE.
    pub const SERVO_WRITE: u8 = 8;
    /// SERVO_DETACH.
    pub const SERVO_DETACH: u8 = 9;
    /// I2C_BEGIN.
    pub const I2C_BEGIN: u8 = 10;
    /// I2C_READ.
    pub const I2C_READ: u8 = 11;
    /// I2C_WRITE.
    pub const I2C_WRITE: u8 = 12;
    /// SONAR_NEW.
    pub const SONAR_NEW: u8 = 13;
    /// DHT_NEW.
    pub const DHT_NEW: u8 = 14;
    /// STOP_ALL_REPORTS.
    pub const STOP_ALL_REPORTS: u8 = 15;
    /// ENABLE_ALL_REPORTS.
    pub const ENABLE_ALL_REPORTS: u8 = 16;
    /// RESET_DATA.
    pub const RESET_DATA: u8 = 17;
    /// RESET_BOARD.
    pub const RESET_BOARD: u8 = 18;
    /// INITIALIZE_NEO_PIXELS.
    pub const INITIALIZE_NEO_PIXELS: u8 = 19;
    /// SHOW_NEO_PIXELS.
    pub const SHOW_NEO_PIXELS: u8 = 20;
    /// SET_NEO_PIXEL.
    pub const SET_NEO_PIXEL: u8 = 21;
    /// CLEAR_ALL_NEO_PIXELS.
    pub const CLEAR_ALL_NEO_PIXELS: u8 = 22;
    /// FILL_NEO_PIXELS.
    pub const FILL_NEO_PIXELS: u8 = 23;
    /// SPI_INIT.
    pub const SPI_INIT: u8 = 24;
    /// SPI_WRITE_BLOCKING.
    pub const SPI_WRITE_BLOCKING: u8 = 25;
    /// SPI_READ_BLOCKING.
    pub const SPI_READ_BLOCKING: u8 = 26;
    /// SPI_SET_FORMAT.
    pub const SPI_SET_FORMAT: u8 = 27;
    /// SPI_CS_CONTROL.
    pub const SPI_CS_CONTROL: u8 = 28;
    /// SET_SCAN_DELAY.
    pub const SET_SCAN_DELAY: u8 = 29;
    /// ENCODER_NEW.
    pub const ENCODER_NEW: u8 = 30;
    /// SENSOR_NEW.
    pub const SENSOR_NEW: u8 = 31;
    /// PING.
    pub const PING: u8 = 32;
    /// MODULE_NEW.
    pub const MODULE_NEW: u8 = 33;
    /// MODULE_DATA.
    pub const MODULE_DATA: u8 = 34;
    /// GET_ID.
    pub const GET_ID: u8 = 35;
    /// SET_ID.
    pub const SET_ID: u8 = 36;
    /// FEATURE_CHECK.
    pub const FEATURE_CHECK: u8 = 37;
    /// BOOTLOADER_RESET.
    pub const BOOTLOADER_RESET: u8 = 38;
}

use command_id as id;

/// Whether `dialect` defines command `id` (and robowire covers it there).
pub(crate) const fn command_known(dialect: Dialect, id: u8) -> bool {
    match dialect {
        Dialect::Mirte13 => id <= id::BOOTLOADER_RESET,
        Dialect::Mirte12 => id <= id::PING && id != id::SENSOR_NEW,
        Dialect::Upstream11 => id <= id::SPI_CS_CONTROL,
    }
}

/// The smallest and largest `LEN` a command can have, or `None` for an unknown
/// id. Used to reject a candidate from its first two bytes.
pub(crate) const fn command_len_range(dialect: Dialect, id: u8) -> Option<(u8, u8)> {
    if !command_known(dialect, id) {
        return None;
    }
    let up = matches!(dialect, Dialect::Upstream11);
    Some(match id {
        id::SET_PIN_MODE => (3, 6),
        id::PWM_WRITE if matches!(dialect, Dialect::Mirte13) => (4, 28),
        id::PWM_WRITE => (4, 4),
        id::SERVO_ATTACH => (2, 6),
        id::SERVO_WRITE | id::I2C_BEGIN | id::SPI_READ_BLOCKING => (4, 4),
        id::I2C_READ if up => (6, 6),
        id::I2C_READ => (7, 7),
        id::I2C_WRITE if up => (6, 30),
        id::I2C_WRITE => (7, 30),
        id::SPI_INIT => (10, 30),
        id::SPI_WRITE_BLOCKING => (3, 30),
        id::INITIALIZE_NEO_PIXELS | id::SET_NEO_PIXEL => (6, 6),
        id::CLEAR_ALL_NEO_PIXELS => (1, 2),
        id::FILL_NEO_PIXELS | id::SPI_SET_FORMAT => (5, 5),
        id::ENCODER_NEW if matches!(dialect, Dialect::Mirte12) => (4, 4),
        id::ENCODER_NEW => (5, 5),
        id::SENSOR_NEW => (3, 10),
        id::MODULE_NEW => (3, 30),
        id::MODULE_DATA => (2, 30),
        id::DIGITAL_WRITE | id::MODIFY_REPORTING | id::SONAR_NEW | id::SPI_CS_CONTROL => (3, 3),
        id::SERIAL_LOOP_BACK
        | id::SERVO_DETACH
        | id::DHT_NEW
        | id::SET_SCAN_DELAY
        | id::PING
        | id::SET_ID
        | id::FEATURE_CHECK => (2, 2),
        _ => (1, 1),
    })
}

/// Pull resistor of a digital input (SET_PIN_MODE modes 0, 3, 4).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EncoderKind {
    /// Single pin (1); `pin_b` must be 0.
    Single,
    /// Quadrature (2).
    Quadrature,
}

/// Pull resistors of ENCODER_NEW's pins (mirte 1.3 only; bit 0 up, bit 1 down).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Pulls {
    /// Pull-ups.
    pub up: bool,
    /// Pull-downs.
    pub down: bool,
}

/// A command, host → Pico. `B` holds the variable byte fields: `&[u8]` when
/// parsed from a frame (see [`CommandRef`]) or for encoding borrowed data,
/// [`Payload`] in the owned form ([`OwnedCommand`]).
///
/// Every variant is encoded with its full payload (the firmware never clears
/// its command buffer); the encoder refuses values the firmware would
/// mishandle (pins ≥ 30, counts above the spec §4 maxima, ids the dialect does
/// not define).
///
/// With the `serde` feature, byte fields serialize as sequences of numbers
/// whether `B` is `&[u8]` or a [`Payload`], so a [`CommandRef`] and its
/// [`OwnedCommand`] serialize alike. Deserialize an [`OwnedCommand`]: its
/// fields refuse more bytes than they hold. A [`CommandRef`] deserializes only
/// from formats that hand out borrowed bytes (postcard, bincode; not JSON).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Command<B> {
    /// 0 SERIAL_LOOP_BACK: the Pico echoes `byte` in report 0.
    LoopBack {
        /// The byte to echo.
        byte: u8,
    },
    /// 1 SET_PIN_MODE.
    SetPinMode {
        /// GPIO number (< 30), or the analog pin for [`PinMode::AnalogInput`].
        pin: u8,
        /// Mode and tail.
        mode: PinMode,
    },
    /// 2 DIGITAL_WRITE.
    DigitalWrite {
        /// GPIO number (< 30).
        pin: u8,
        /// Level.
        high: bool,
    },
    /// 3 PWM_WRITE (k pins at once in mirte 1.3).
    PwmWrite(PwmPins),
    /// 4 MODIFY_REPORTING.
    ModifyReporting(ModifyReporting),
    /// 5 GET_FIRMWARE_VERSION: answered by report 5.
    GetFirmwareVersion,
    /// 6 GET_PICO_UNIQUE_ID: answered by report 6.
    GetUniqueId,
    /// 7 SERVO_ATTACH (sets PWM mode).
    ServoAttach {
        /// GPIO number (< 30).
        pin: u8,
        /// The ignored `u16 min_us, u16 max_us` that some hosts append.
        pulse_range: Option<(u16, u16)>,
    },
    /// 8 SERVO_WRITE.
    ServoWrite {
        /// GPIO number (< 30).
        pin: u8,
        /// Pulse width in µs.
        pulse_us: u16,
    },
    /// 9 SERVO_DETACH (a no-op in the firmware).
    ServoDetach {
        /// GPIO number (< 30).
        pin: u8,
    },
    /// 10 I2C_BEGIN. `port == sda == scl` selects the port's default pins.
    I2cBegin {
        /// 0 or 1.
        port: u8,
        /// SDA GPIO (< 30).
        sda: u8,
        /// SCL GPIO (< 30).
        scl: u8,
    },
    /// 11 I2C_READ, mirte layout: answered by report 10 or 9, or not at all
    /// when the register write fails.
    I2cRead {
        /// 0 or 1.
        port: u8,
        /// 7-bit address.
        addr: u8,
        /// Echoed in the reply.
        msg_id: u8,
        /// Register written before the read.
        reg: u8,
        /// Bytes to read, 1..=57.
        len: u8,
        /// 0 (stop), 1 (no stop), or 254 (skip the register write, no stop).
        no_stop: u8,
    },
    /// 11 I2C_READ, upstream layout (no `msg_id`).
    I2cReadUpstream {
        /// 0 or 1.
        port: u8,
        /// 7-bit address.
        addr: u8,
        /// Register written before the read.
        reg: u8,
        /// Bytes to read, 1..=57.
        len: u8,
        /// 0 or 1.
        no_stop: u8,
    },
    /// 12 I2C_WRITE, mirte layout: answered by report 8.
    I2cWrite {
        /// 0 or 1.
        port: u8,
        /// 7-bit address.
        addr: u8,
        /// Echoed in the reply.
        msg_id: u8,
        /// 0 or 1.
        no_stop: u8,
        /// 1..=24 bytes.
        data: B,
    },
    /// 12 I2C_WRITE, upstream layout (no `msg_id`).
    I2cWriteUpstream {
        /// 0 or 1.
        port: u8,
        /// 7-bit address.
        addr: u8,
        /// 0 or 1.
        no_stop: u8,
        /// 1..=25 bytes.
        data: B,
    },
    /// 13 SONAR_NEW (`trig == echo`: single-pin sonar). At most 4 are used.
    SonarNew {
        /// Trigger GPIO (< 30).
        trig: u8,
        /// Echo GPIO (< 30).
        echo: u8,
    },
    /// 14 DHT_NEW. At most 2 are used.
    DhtNew {
        /// GPIO number (< 30).
        pin: u8,
    },
    /// 15 STOP_ALL_REPORTS.
    StopAllReports,
    /// 16 ENABLE_ALL_REPORTS.
    EnableAllReports,
    /// 17 RESET_DATA (a no-op).
    ResetData,
    /// 18 RESET_BOARD.
    ResetBoard,
    /// 19 INITIALIZE_NEO_PIXELS: fills and shows.
    InitNeoPixels {
        /// GPIO number (< 30).
        pin: u8,
        /// Number of pixels, ≤ 100.
        count: u8,
        /// Fill colour.
        rgb: Rgb,
    },
    /// 20 SHOW_NEO_PIXELS.
    ShowNeoPixels,
    /// 21 SET_NEO_PIXEL.
    SetNeoPixel {
        /// Pixel index (< 100).
        index: u8,
        /// Colour.
        rgb: Rgb,
        /// Show at once.
        auto_show: bool,
    },
    /// 22 CLEAR_ALL_NEO_PIXELS (always shows).
    ClearAllNeoPixels {
        /// The ignored `auto_show` byte some hosts append.
        auto_show: Option<bool>,
    },
    /// 23 FILL_NEO_PIXELS.
    FillNeoPixels {
        /// Colour.
        rgb: Rgb,
        /// Show at once.
        auto_show: bool,
    },
    /// 24 SPI_INIT.
    SpiInit {
        /// 0 or 1.
        port: u8,
        /// MISO or MOSI GPIO (< 30).
        pin_a: u8,
        /// MOSI or MISO GPIO (< 30).
        pin_b: u8,
        /// Clock GPIO (< 30).
        clk: u8,
        /// Clock frequency in Hz (≥ 1).
        freq_hz: u32,
        /// Chip-select GPIOs (each < 30), at most 20.
        cs_pins: B,
    },
    /// 25 SPI_WRITE_BLOCKING.
    SpiWrite {
        /// 0 or 1.
        port: u8,
        /// At most 27 bytes.
        data: B,
    },
    /// 26 SPI_READ_BLOCKING: answered by report 13.
    SpiRead {
        /// 0 or 1.
        port: u8,
        /// Bytes to read, ≤ 60.
        len: u8,
        /// Byte clocked out while reading.
        tx_fill: u8,
    },
    /// 27 SPI_SET_FORMAT.
    SpiSetFormat {
        /// 0 or 1.
        port: u8,
        /// 4..=16.
        data_bits: u8,
        /// Clock polarity.
        cpol: bool,
        /// Clock phase.
        cpha: bool,
    },
    /// 28 SPI_CS_CONTROL.
    SpiCsControl {
        /// GPIO number (< 30).
        cs_pin: u8,
        /// Level.
        high: bool,
    },
    /// 29 SET_SCAN_DELAY (mirte only).
    SetScanDelay {
        /// Scan period in ms.
        delay_ms: u8,
    },
    /// 30 ENCODER_NEW (mirte only). At most 4 are used.
    EncoderNew {
        /// Single or quadrature.
        kind: EncoderKind,
        /// GPIO A (< 30).
        pin_a: u8,
        /// GPIO B (< 30); 0 for [`EncoderKind::Single`].
        pin_b: u8,
        /// Pull resistors (must be none in mirte 1.2, which lacks the byte).
        pulls: Pulls,
    },
    /// 31 SENSOR_NEW (mirte 1.3).
    SensorNew(SensorNew),
    /// 32 PING (mirte only): answered by report 32.
    Ping {
        /// Echoed in the reply.
        counter: u8,
    },
    /// 33 MODULE_NEW (mirte 1.3).
    ModuleNew(ModuleNew<B>),
    /// 34 MODULE_DATA (mirte 1.3): build typed data with
    /// [`Command::module_data`], read it with the module's `parse`.
    ModuleData {
        /// Module number (modules are numbered 0, 1, 2, … in creation order).
        module_num: u8,
        /// 1..=28 bytes for the module.
        data: B,
    },
    /// 35 GET_ID (mirte 1.3): answered by report 35.
    GetId,
    /// 36 SET_ID (mirte 1.3): answered by report 36.
    SetId {
        /// The id to save.
        id: u8,
    },
    /// 37 FEATURE_CHECK (mirte 1.3): answered by report 37.
    FeatureCheck {
        /// The command id asked about.
        msg_type: u8,
    },
    /// 38 BOOTLOADER_RESET (mirte 1.3).
    BootloaderReset,
}

/// A command borrowing its variable fields from a frame or the caller.
pub type CommandRef<'a> = Command<&'a [u8]>;

/// Capacity of [`OwnedCommand`]'s byte fields: the longest variable field
/// (MODULE_DATA's data).
pub const COMMAND_PAYLOAD_MAX: usize = 28;

/// A command owning its variable fields.
pub type OwnedCommand = Command<Payload<COMMAND_PAYLOAD_MAX>>;

impl<B> Command<B> {
    /// The command id.
    pub const fn id(&self) -> u8 {
        match self {
            Command::LoopBack { .. } => id::SERIAL_LOOP_BACK,
            Command::SetPinMode { .. } => id::SET_PIN_MODE,
            Command::DigitalWrite { .. } => id::DIGITAL_WRITE,
            Command::PwmWrite(_) => id::PWM_WRITE,
            Command::ModifyReporting(_) => id::MODIFY_REPORTING,
            Command::GetFirmwareVersion => id::GET_FIRMWARE_VERSION,
            Command::GetUniqueId => id::GET_PICO_UNIQUE_ID,
            Command::ServoAttach { .. } => id::SERVO_ATTACH,
            Command::ServoWrite { .. } => id::SERVO_WRITE,
            Command::ServoDetach { .. } => id::SERVO_DETACH,
            Command::I2cBegin { .. } => id::I2C_BEGIN,
            Command::I2cRead { .. } | Command::I2cReadUpstream { .. } => id::I2C_READ,
            Command::I2cWrite { .. } | Command::I2cWriteUpstream { .. } => id::I2C_WRITE,
            Command::SonarNew { .. } => id::SONAR_NEW,
            Command::DhtNew { .. } => id::DHT_NEW,
            Command::StopAllReports => id::STOP_ALL_REPORTS,
            Command::EnableAllReports => id::ENABLE_ALL_REPORTS,
            Command::ResetData => id::RESET_DATA,
            Command::ResetBoard => id::RESET_BOARD,
            Command::InitNeoPixels { .. } => id::INITIALIZE_NEO_PIXELS,
            Command::ShowNeoPixels => id::SHOW_NEO_PIXELS,
            Command::SetNeoPixel { .. } => id::SET_NEO_PIXEL,
            Command::ClearAllNeoPixels { .. } => id::CLEAR_ALL_NEO_PIXELS,
            Command::FillNeoPixels { .. } => id::FILL_NEO_PIXELS,
            Command::SpiInit { .. } => id::SPI_INIT,
            Command::SpiWrite { .. } => id::SPI_WRITE_BLOCKING,
            Command::SpiRead { .. } => id::SPI_READ_BLOCKING,
            Command::SpiSetFormat { .. } => id::SPI_SET_FORMAT,
            Command::SpiCsControl { .. } => id::SPI_CS_CONTROL,
            Command::SetScanDelay { .. } => id::SET_SCAN_DELAY,
            Command::EncoderNew { .. } => id::ENCODER_NEW,
            Command::SensorNew(_) => id::SENSOR_NEW,
            Command::Ping { .. } => id::PING,
            Command::ModuleNew(_) => id::MODULE_NEW,
            Command::ModuleData { .. } => id::MODULE_DATA,
            Command::GetId => id::GET_ID,
            Command::SetId { .. } => id::SET_ID,
            Command::FeatureCheck { .. } => id::FEATURE_CHECK,
            Command::BootloaderReset => id::BOOTLOADER_RESET,
        }
    }

    /// The same command with its byte fields converted by `f`.
    pub fn map_bytes<C>(self, mut f: impl FnMut(B) -> C) -> Command<C> {
        match self {
            Command::I2cWrite {
                port,
                addr,
                msg_id,
                no_stop,
                data,
            } => Command::I2cWrite {
                port,
                addr,
                msg_id,
                no_stop,
                data: f(data),
            },
            Command::I2cWriteUpstream {
                port,
                addr,
                no_stop,
                data,
            } => Command::I2cWriteUpstream {
                port,
                addr,
                no_stop,
                data: f(data),
            },
            Command::SpiInit {
                port,
                pin_a,
                pin_b,
                clk,
                freq_hz,
                cs_pins,
            } => Command::SpiInit {
                port,
                pin_a,
                pin_b,
                clk,
                freq_hz,
                cs_pins: f(cs_pins),
            },
            Command::SpiWrite { port, data } => Command::SpiWrite {
                port,
                data: f(data),
            },
            Command::ModuleNew(m) => Command::ModuleNew(m.map_bytes(f)),
            Command::ModuleData { module_num, data } => Command::ModuleData {
                module_num,
                data: f(data),
            },
            // Every other variant has no byte field: `plain` copies it.
            other => other.plain().unwrap_or(Command::ResetData),
        }
    }

    /// A copy of a variant without byte fields (`None` for the others).
    fn plain<C>(&self) -> Option<Command<C>> {
        Some(match *self {
            Command::LoopBack { byte } => Command::LoopBack { byte },
            Command::SetPinMode { pin, mode } => Command::SetPinMode { pin, mode },
            Command::DigitalWrite { pin, high } => Command::DigitalWrite { pin, high },
            Command::PwmWrite(p) => Command::PwmWrite(p),
            Command::ModifyReporting(m) => Command::ModifyReporting(m),
            Command::GetFirmwareVersion => Command::GetFirmwareVersion,
            Command::GetUniqueId => Command::GetUniqueId,
            Command::ServoAttach { pin, pulse_range } => Command::ServoAttach { pin, pulse_range },
            Command::ServoWrite { pin, pulse_us } => Command::ServoWrite { pin, pulse_us },
            Command::ServoDetach { pin } => Command::ServoDetach { pin },
            Command::I2cBegin { port, sda, scl } => Command::I2cBegin { port, sda, scl },
            Command::I2cRead {
                port,
                addr,
                msg_id,
                reg,
                len,
                no_stop,
            } => Command::I2cRead {
                port,
                addr,
                msg_id,
                reg,
                len,
                no_stop,
            },
            Command::I2cReadUpstream {
                port,
                addr,
                reg,
                len,
                no_stop,
            } => Command::I2cReadUpstream {
                port,
                addr,
                reg,
                len,
                no_stop,
            },
            Command::SonarNew { trig, echo } => Command::SonarNew { trig, echo },
            Command::DhtNew { pin } => Command::DhtNew { pin },
            Command::StopAllReports => Command::StopAllReports,
            Command::EnableAllReports => Command::EnableAllReports,
            Command::ResetData => Command::ResetData,
            Command::ResetBoard => Command::ResetBoard,
            Command::InitNeoPixels { pin, count, rgb } => {
                Command::InitNeoPixels { pin, count, rgb }
            }
            Command::ShowNeoPixels => Command::ShowNeoPixels,
            Command::SetNeoPixel {
                index,
                rgb,
                auto_show,
            } => Command::SetNeoPixel {
                index,
                rgb,
                auto_show,
            },
            Command::ClearAllNeoPixels { auto_show } => Command::ClearAllNeoPixels { auto_show },
            Command::FillNeoPixels { rgb, auto_show } => Command::FillNeoPixels { rgb, auto_show },
            Command::SpiRead { port, len, tx_fill } => Command::SpiRead { port, len, tx_fill },
            Command::SpiSetFormat {
                port,
                data_bits,
                cpol,
                cpha,
            } => Command::SpiSetFormat {
                port,
                data_bits,
                cpol,
                cpha,
            },
            Command::SpiCsControl { cs_pin, high } => Command::SpiCsControl { cs_pin, high },
            Command::SetScanDelay { delay_ms } => Command::SetScanDelay { delay_ms },
            Command::EncoderNew {
                kind,
                pin_a,
                pin_b,
                pulls,
            } => Command::EncoderNew {
                kind,
                pin_a,
                pin_b,
                pulls,
            },
            Command::SensorNew(s) => Command::SensorNew(s),
            Command::Ping { counter } => Command::Ping { counter },
            Command::GetId => Command::GetId,
            Command::SetId { id } => Command::SetId { id },
            Command::FeatureCheck { msg_type } => Command::FeatureCheck { msg_type },
            Command::BootloaderReset => Command::BootloaderReset,
            Command::I2cWrite { .. }
            | Command::I2cWriteUpstream { .. }
            | Command::SpiInit { .. }
            | Command::SpiWrite { .. }
            | Command::ModuleNew(_)
            | Command::ModuleData { .. } => return None,
        })
    }
}

impl<B: AsRef<[u8]>> Command<B> {
    /// A borrowed view of this command.
    pub fn as_ref(&self) -> CommandRef<'_> {
        match self {
            Command::I2cWrite {
                port,
                addr,
                msg_id,
                no_stop,
                data,
            } => Command::I2cWrite {
                port: *port,
                addr: *addr,
                msg_id: *msg_id,
                no_stop: *no_stop,
                data: data.as_ref(),
            },
            Command::I2cWriteUpstream {
                port,
                addr,
                no_stop,
                data,
            } => Command::I2cWriteUpstream {
                port: *port,
                addr: *addr,
                no_stop: *no_stop,
                data: data.as_ref(),
            },
            Command::SpiInit {
                port,
                pin_a,
                pin_b,
                clk,
                freq_hz,
                cs_pins,
            } => Command::SpiInit {
                port: *port,
                pin_a: *pin_a,
                pin_b: *pin_b,
                clk: *clk,
                freq_hz: *freq_hz,
                cs_pins: cs_pins.as_ref(),
            },
            Command::SpiWrite { port, data } => Command::SpiWrite {
                port: *port,
                data: data.as_ref(),
            },
            Command::ModuleNew(m) => Command::ModuleNew(m.as_ref()),
            Command::ModuleData { module_num, data } => Command::ModuleData {
                module_num: *module_num,
                data: data.as_ref(),
            },
            other => other.plain().unwrap_or(Command::ResetData),
        }
    }

    /// An owned copy (byte fields copied into [`Payload`]s).
    pub fn to_owned(&self) -> OwnedCommand {
        self.as_ref().map_bytes(Payload::truncating)
    }

    /// Frame length of this command in `dialect`.
    pub fn encoded_len_in(&self, dialect: Dialect) -> usize {
        let mut w = Writer::new(&mut []);
        self.write(&mut w, dialect);
        w.len()
    }

    /// Encode this command for `dialect` into the front of `out`; returns the
    /// frame length. Nothing is written on error.
    pub fn encode_in(&self, dialect: Dialect, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.check_dialect(dialect)?;
        self.check_sizes()?;
        let n = self.encoded_len_in(dialect);
        if n > MAX_COMMAND_LEN + 1 {
            return Err(EncodeError::TooLong {
                len: n - 1,
                max: MAX_COMMAND_LEN,
            });
        }
        check_room(out, n)?;
        let mut scratch = [0u8; MAX_COMMAND_LEN + 1];
        let mut w = Writer::new(&mut scratch);
        self.write(&mut w, dialect);
        let frame = scratch.get(..n).unwrap_or(&[]);
        // The decoder is the one definition of a valid frame: the encoder
        // emits nothing it would reject.
        parse_command(dialect, frame).map_err(Error::into_encode_error)?;
        if let Some(dst) = out.get_mut(..n) {
            dst.copy_from_slice(frame);
        }
        Ok(n)
    }

    fn check_dialect(&self, dialect: Dialect) -> Result<(), EncodeError> {
        if !command_known(dialect, self.id()) {
            return Err(EncodeError::Inconsistent {
                what: "the command does not exist in this dialect",
            });
        }
        let mirte = dialect.is_mirte();
        match self {
            Command::I2cRead { .. } | Command::I2cWrite { .. } if !mirte => {
                Err(EncodeError::Inconsistent {
                    what: "upstream firmware takes I2C commands without msg_id",
                })
            }
            Command::I2cReadUpstream { .. } | Command::I2cWriteUpstream { .. } if mirte => {
                Err(EncodeError::Inconsistent {
                    what: "mirte firmware takes I2C commands with msg_id",
                })
            }
            Command::PwmWrite(pins) if dialect != Dialect::Mirte13 && pins.len() > 1 => {
                Err(EncodeError::TooLong {
                    len: pins.len(),
                    max: 1,
                })
            }
            Command::EncoderNew { pulls, .. }
                if dialect == Dialect::Mirte12 && *pulls != Pulls::default() =>
            {
                Err(EncodeError::Inconsistent {
                    what: "mirte 1.2 firmware has no encoder pull setting",
                })
            }
            _ => Ok(()),
        }
    }

    /// The per-command maxima of spec §4 for byte fields.
    fn check_sizes(&self) -> Result<(), EncodeError> {
        let (len, max) = match self {
            Command::I2cWrite { data, .. } => (data.as_ref().len(), 24),
            Command::I2cWriteUpstream { data, .. } => (data.as_ref().len(), 25),
            Command::SpiInit { cs_pins, .. } => (cs_pins.as_ref().len(), 20),
            Command::SpiWrite { data, .. } => (data.as_ref().len(), 27),
            Command::ModuleData { data, .. } => (data.as_ref().len(), COMMAND_PAYLOAD_MAX),
            Command::ModuleNew(m) => (m.init_len(), super::module::MODULE_INIT_MAX),
            _ => return Ok(()),
        };
        if len > max {
            Err(EncodeError::TooLong { len, max })
        } else {
            Ok(())
        }
    }

    /// Write the whole frame; `LEN` is filled in once the payload is written.
    fn write(&self, w: &mut Writer<'_>, dialect: Dialect) {
        w.u8(0);
        w.u8(self.id());
        self.write_payload(w, dialect);
        w.patch_len();
    }

    fn write_payload(&self, w: &mut Writer<'_>, dialect: Dialect) {
        match self {
            Command::LoopBack { byte } => w.u8(*byte),
            Command::SetPinMode { pin, mode } => {
                w.u8(*pin);
                match *mode {
                    PinMode::DigitalInput { pull, report } => {
                        w.u8(match pull {
                            Pull::None => 0,
                            Pull::Up => 3,
                            Pull::Down => 4,
                        });
                        w.flag(report);
                    }
                    PinMode::DigitalOutput => w.u8(1),
                    PinMode::PwmOutput => w.u8(2),
                    PinMode::AnalogInput {
                        differential,
                        report,
                    } => {
                        w.u8(5);
                        w.u16(differential);
                        w.flag(report);
                    }
                }
            }
            Command::DigitalWrite { pin, high } => {
                w.u8(*pin);
                w.flag(*high);
            }
            Command::PwmWrite(pins) => {
                for p in pins {
                    w.u8(p.pin);
                    w.u16(p.value);
                }
            }
            Command::ModifyReporting(m) => {
                let (kind, pin) = match *m {
                    ModifyReporting::DisableAll => (0, 0),
                    ModifyReporting::EnableAnalog { pin } => (1, pin),
                    ModifyReporting::EnableDigital { pin } => (2, pin),
                    ModifyReporting::DisableAnalog { pin } => (3, pin),
                    ModifyReporting::DisableDigital { pin } => (4, pin),
                };
                w.u8(kind);
                w.u8(pin);
            }
            Command::ServoAttach { pin, pulse_range } => {
                w.u8(*pin);
                if let Some((min, max)) = pulse_range {
                    w.u16(*min);
                    w.u16(*max);
                }
            }
            Command::ServoWrite { pin, pulse_us } => {
                w.u8(*pin);
                w.u16(*pulse_us);
            }
            Command::ServoDetach { pin } | Command::DhtNew { pin } => w.u8(*pin),
            Command::I2cBegin { port, sda, scl } => w.bytes(&[*port, *sda, *scl]),
            Command::I2cRead {
                port,
                addr,
                msg_id,
                reg,
                len,
                no_stop,
            } => w.bytes(&[*port, *addr, *msg_id, *reg, *len, *no_stop]),
            Command::I2cReadUpstream {
                port,
                addr,
                reg,
                len,
                no_stop,
            } => w.bytes(&[*port, *addr, *reg, *len, *no_stop]),
            Command::I2cWrite {
                port,
                addr,
                msg_id,
                no_stop,
                data,
            } => {
                let data = data.as_ref();
                w.bytes(&[*port, *addr, *msg_id, data.len() as u8, *no_stop]);
                w.bytes(data);
            }
            Command::I2cWriteUpstream {
                port,
                addr,
                no_stop,
                data,
            } => {
                let data = data.as_ref();
                w.bytes(&[*port, *addr, data.len() as u8, *no_stop]);
                w.bytes(data);
            }
            Command::SonarNew { trig, echo } => w.bytes(&[*trig, *echo]),
            Command::StopAllReports
            | Command::EnableAllReports
            | Command::ResetData
            | Command::ResetBoard
            | Command::ShowNeoPixels
            | Command::GetFirmwareVersion
            | Command::GetUniqueId
            | Command::GetId
            | Command::BootloaderReset => {}
            Command::InitNeoPixels { pin, count, rgb } => {
                w.bytes(&[*pin, *count, rgb.r, rgb.g, rgb.b]);
            }
            Command::SetNeoPixel {
                index,
                rgb,
                auto_show,
            } => {
                w.bytes(&[*index, rgb.r, rgb.g, rgb.b]);
                w.flag(*auto_show);
            }
            Command::ClearAllNeoPixels { auto_show } => {
                if let Some(a) = auto_show {
                    w.flag(*a);
                }
            }
            Command::FillNeoPixels { rgb, auto_show } => {
                w.bytes(&[rgb.r, rgb.g, rgb.b]);
                w.flag(*auto_show);
            }
            Command::SpiInit {
                port,
                pin_a,
                pin_b,
                clk,
                freq_hz,
                cs_pins,
            } => {
                w.bytes(&[*port, *pin_a, *pin_b, *clk]);
                w.u32(*freq_hz);
                let cs = cs_pins.as_ref();
                w.u8(cs.len() as u8);
                w.bytes(cs);
            }
            Command::SpiWrite { port, data } => {
                let data = data.as_ref();
                w.bytes(&[*port, data.len() as u8]);
                w.bytes(data);
            }
            Command::SpiRead { port, len, tx_fill } => w.bytes(&[*port, *len, *tx_fill]),
            Command::SpiSetFormat {
                port,
                data_bits,
                cpol,
                cpha,
            } => {
                w.bytes(&[*port, *data_bits]);
                w.flag(*cpol);
                w.flag(*cpha);
            }
            Command::SpiCsControl { cs_pin, high } => {
                w.u8(*cs_pin);
                w.flag(*high);
            }
            Command::SetScanDelay { delay_ms } => w.u8(*delay_ms),
            Command::EncoderNew {
                kind,
                pin_a,
                pin_b,
                pulls,
            } => {
                w.u8(match kind {
                    EncoderKind::Single => 1,
                    EncoderKind::Quadrature => 2,
                });
                w.bytes(&[*pin_a, *pin_b]);
                if dialect == Dialect::Mirte13 {
                    w.u8(u8::from(pulls.up) | (u8::from(pulls.down) << 1));
                }
            }
            Command::SensorNew(s) => s.write(w),
            Command::Ping { counter } => w.u8(*counter),
            Command::ModuleNew(m) => m.write(w),
            Command::ModuleData { module_num, data } => {
                w.u8(*module_num);
                w.bytes(data.as_ref());
            }
            Command::SetId { id } => w.u8(*id),
            Command::FeatureCheck { msg_type } => w.u8(*msg_type),
        }
    }
}

impl<B: AsRef<[u8]>> Encode for Command<B> {
    const MAX_LEN: usize = MAX_COMMAND_LEN + 1;

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

/// Split a frame into `LEN`, id and payload, checking that `LEN` matches.
pub(crate) fn split_frame(frame: &[u8]) -> Result<(u8, u8, &[u8]), Error> {
    match frame {
        [len, id, payload @ ..] if usize::from(*len) == payload.len() + 1 => {
            Ok((*len, *id, payload))
        }
        [len, id, ..] => Err(Error::BadLength { id: *id, len: *len }),
        _ => Err(Error::Truncated { len: frame.len() }),
    }
}

/// Parse one complete command frame (`LEN` byte first) for `dialect`. This is
/// the one definition of a valid command: the decoder accepts exactly what it
/// accepts, and the encoder emits nothing it rejects.
pub fn parse_command(dialect: Dialect, frame: &[u8]) -> Result<CommandRef<'_>, Error> {
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

fn port(r: &mut Reader<'_>) -> Result<u8, Error> {
    let port = r.u8()?;
    ensure(port <= 1, r.id(), "port")?;
    Ok(port)
}

fn i2c_addr(r: &mut Reader<'_>) -> Result<u8, Error> {
    let addr = r.u8()?;
    ensure(addr <= 0x7f, r.id(), "addr")?;
    Ok(addr)
}

fn rgb(r: &mut Reader<'_>) -> Result<Rgb, Error> {
    let [r_, g, b] = r.array()?;
    Ok(Rgb { r: r_, g, b })
}

/// A count byte followed by that many bytes.
fn counted<'a>(r: &mut Reader<'a>, field: &'static str, min: u8) -> Result<&'a [u8], Error> {
    let n = r.u8()?;
    ensure(n >= min, r.id(), field)?;
    r.take(usize::from(n))
}

fn parse_payload<'a>(dialect: Dialect, r: &mut Reader<'a>) -> Result<CommandRef<'a>, Error> {
    let cmd = r.id();
    Ok(match cmd {
        id::SERIAL_LOOP_BACK => Command::LoopBack { byte: r.u8()? },
        id::SET_PIN_MODE => {
            let pin = r.u8()?;
            let mode = match r.u8()? {
                m @ (0 | 3 | 4) => PinMode::DigitalInput {
                    pull: match m {
                        3 => Pull::Up,
                        4 => Pull::Down,
                        _ => Pull::None,
                    },
                    report: r.flag("report_enable")?,
                },
                1 => PinMode::DigitalOutput,
                2 => PinMode::PwmOutput,
                5 => PinMode::AnalogInput {
                    differential: r.u16()?,
                    report: r.flag("report_enable")?,
                },
                _ => {
                    return Err(Error::OutOfRange {
                        id: cmd,
                        field: "mode",
                    })
                }
            };
            let pin_ok = match mode {
                PinMode::AnalogInput { .. } => analog_pin_ok(dialect, pin),
                _ => pin < super::PIN_COUNT,
            };
            ensure(pin_ok, cmd, "pin")?;
            Command::SetPinMode { pin, mode }
        }
        id::DIGITAL_WRITE => Command::DigitalWrite {
            pin: r.pin("pin")?,
            high: r.flag("value")?,
        },
        id::PWM_WRITE => {
            let mut pins = PwmPins::new();
            while r.remaining() > 0 {
                let pin = PwmPin {
                    pin: r.pin("pin")?,
                    value: r.u16()?,
                };
                pins.push(pin).map_err(|_| r.bad_length())?;
            }
            Command::PwmWrite(pins)
        }
        id::MODIFY_REPORTING => {
            let kind = r.u8()?;
            let pin = r.u8()?;
            let digital_ok = dialect != Dialect::Mirte13 && pin < super::PIN_COUNT;
            let m = match kind {
                0 if pin == 0 => ModifyReporting::DisableAll,
                1 if analog_pin_ok(dialect, pin) => ModifyReporting::EnableAnalog { pin },
                3 if analog_pin_ok(dialect, pin) => ModifyReporting::DisableAnalog { pin },
                2 if digital_ok => ModifyReporting::EnableDigital { pin },
                4 if digital_ok => ModifyReporting::DisableDigital { pin },
                0..=4 => {
                    return Err(Error::OutOfRange {
                        id: cmd,
                        field: "pin",
                    })
                }
                _ => {
                    return Err(Error::OutOfRange {
                        id: cmd,
                        field: "type",
                    })
                }
            };
            Command::ModifyReporting(m)
        }
        id::GET_FIRMWARE_VERSION => Command::GetFirmwareVersion,
        id::GET_PICO_UNIQUE_ID => Command::GetUniqueId,
        id::SERVO_ATTACH => {
            let pin = r.pin("pin")?;
            let pulse_range = if r.remaining() > 0 {
                Some((r.u16()?, r.u16()?))
            } else {
                None
            };
            Command::ServoAttach { pin, pulse_range }
        }
        id::SERVO_WRITE => Command::ServoWrite {
            pin: r.pin("pin")?,
            pulse_us: r.u16()?,
        },
        id::SERVO_DETACH => Command::ServoDetach { pin: r.pin("pin")? },
        id::I2C_BEGIN => Command::I2cBegin {
            port: port(r)?,
            sda: r.pin("sda")?,
            scl: r.pin("scl")?,
        },
        id::I2C_READ if dialect.is_mirte() => {
            let (port, addr, msg_id, reg) = (port(r)?, i2c_addr(r)?, r.u8()?, r.u8()?);
            let len = r.u8()?;
            ensure((1..=57).contains(&len), cmd, "len")?;
            let no_stop = r.u8()?;
            ensure(matches!(no_stop, 0 | 1 | 254), cmd, "no_stop")?;
            Command::I2cRead {
                port,
                addr,
                msg_id,
                reg,
                len,
                no_stop,
            }
        }
        id::I2C_READ => {
            let (port, addr, reg) = (port(r)?, i2c_addr(r)?, r.u8()?);
            let len = r.u8()?;
            ensure((1..=57).contains(&len), cmd, "len")?;
            let no_stop = r.u8()?;
            ensure(no_stop <= 1, cmd, "no_stop")?;
            Command::I2cReadUpstream {
                port,
                addr,
                reg,
                len,
                no_stop,
            }
        }
        id::I2C_WRITE if dialect.is_mirte() => {
            let (port, addr, msg_id) = (port(r)?, i2c_addr(r)?, r.u8()?);
            let n = r.u8()?;
            ensure(n >= 1, cmd, "len")?;
            let no_stop = r.u8()?;
            ensure(no_stop <= 1, cmd, "no_stop")?;
            Command::I2cWrite {
                port,
                addr,
                msg_id,
                no_stop,
                data: r.take(usize::from(n))?,
            }
        }
        id::I2C_WRITE => {
            let (port, addr) = (port(r)?, i2c_addr(r)?);
            let n = r.u8()?;
            ensure(n >= 1, cmd, "len")?;
            let no_stop = r.u8()?;
            ensure(no_stop <= 1, cmd, "no_stop")?;
            Command::I2cWriteUpstream {
                port,
                addr,
                no_stop,
                data: r.take(usize::from(n))?,
            }
        }
        id::SONAR_NEW => Command::SonarNew {
            trig: r.pin("trig")?,
            echo: r.pin("echo")?,
        },
        id::DHT_NEW => Command::DhtNew { pin: r.pin("pin")? },
        id::STOP_ALL_REPORTS => Command::StopAllReports,
        id::ENABLE_ALL_REPORTS => Command::EnableAllReports,
        id::RESET_DATA => Command::ResetData,
        id::RESET_BOARD => Command::ResetBoard,
        id::INITIALIZE_NEO_PIXELS => {
            let pin = r.pin("pin")?;
            let count = r.u8()?;
            ensure(count <= 100, cmd, "count")?;
            Command::InitNeoPixels {
                pin,
                count,
                rgb: rgb(r)?,
            }
        }
        id::SHOW_NEO_PIXELS => Command::ShowNeoPixels,
        id::SET_NEO_PIXEL => {
            let index = r.u8()?;
            ensure(index < 100, cmd, "index")?;
            Command::SetNeoPixel {
                index,
                rgb: rgb(r)?,
                auto_show: r.flag("auto_show")?,
            }
        }
        id::CLEAR_ALL_NEO_PIXELS => Command::ClearAllNeoPixels {
            auto_show: if r.remaining() > 0 {
                Some(r.flag("auto_show")?)
            } else {
                None
            },
        },
        id::FILL_NEO_PIXELS => Command::FillNeoPixels {
            rgb: rgb(r)?,
            auto_show: r.flag("auto_show")?,
        },
        id::SPI_INIT => {
            let port = port(r)?;
            let (pin_a, pin_b, clk) = (r.pin("pin_a")?, r.pin("pin_b")?, r.pin("clk")?);
            let freq_hz = r.u32()?;
            ensure(freq_hz >= 1, cmd, "freq_hz")?;
            let cs_pins = counted(r, "cs count", 0)?;
            ensure(cs_pins.iter().all(|&p| p < super::PIN_COUNT), cmd, "cs_pin")?;
            Command::SpiInit {
                port,
                pin_a,
                pin_b,
                clk,
                freq_hz,
                cs_pins,
            }
        }
        id::SPI_WRITE_BLOCKING => Command::SpiWrite {
            port: port(r)?,
            data: counted(r, "len", 0)?,
        },
        id::SPI_READ_BLOCKING => {
            let port = port(r)?;
            let len = r.u8()?;
            ensure(len <= 60, cmd, "len")?;
            Command::SpiRead {
                port,
                len,
                tx_fill: r.u8()?,
            }
        }
        id::SPI_SET_FORMAT => {
            let port = port(r)?;
            let data_bits = r.u8()?;
            ensure((4..=16).contains(&data_bits), cmd, "data_bits")?;
            Command::SpiSetFormat {
                port,
                data_bits,
                cpol: r.flag("cpol")?,
                cpha: r.flag("cpha")?,
            }
        }
        id::SPI_CS_CONTROL => Command::SpiCsControl {
            cs_pin: r.pin("cs_pin")?,
            high: r.flag("level")?,
        },
        id::SET_SCAN_DELAY => Command::SetScanDelay { delay_ms: r.u8()? },
        id::ENCODER_NEW => {
            let kind = match r.u8()? {
                1 => EncoderKind::Single,
                2 => EncoderKind::Quadrature,
                _ => {
                    return Err(Error::OutOfRange {
                        id: cmd,
                        field: "type",
                    })
                }
            };
            let pin_a = r.pin("pin_a")?;
            let pin_b = r.pin("pin_b")?;
            ensure(kind == EncoderKind::Quadrature || pin_b == 0, cmd, "pin_b")?;
            let pulls = if dialect == Dialect::Mirte13 {
                let bits = r.u8()?;
                ensure(bits <= 3, cmd, "pulls")?;
                Pulls {
                    up: bits & 1 != 0,
                    down: bits & 2 != 0,
                }
            } else {
                Pulls::default()
            };
            Command::EncoderNew {
                kind,
                pin_a,
                pin_b,
                pulls,
            }
        }
        id::SENSOR_NEW => Command::SensorNew(SensorNew::parse(r)?),
        id::PING => Command::Ping { counter: r.u8()? },
        id::MODULE_NEW => Command::ModuleNew(ModuleNew::parse(r)?),
        id::MODULE_DATA => {
            let module_num = r.u8()?;
            let data = r.rest();
            ensure(!data.is_empty(), cmd, "data")?;
            Command::ModuleData { module_num, data }
        }
        id::GET_ID => Command::GetId,
        id::SET_ID => Command::SetId { id: r.u8()? },
        id::FEATURE_CHECK => Command::FeatureCheck { msg_type: r.u8()? },
        id::BOOTLOADER_RESET => Command::BootloaderReset,
        _ => return Err(Error::UnknownId { id: cmd }),
    })
}
