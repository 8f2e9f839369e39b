//! The names of messages and enumerated values: snake case after the spec's
//! names, the words of the JSON-lines schema, `Display` and `FromStr`. Each
//! list exists here only.

use core::fmt;
use core::str::FromStr;

use super::buf::Message;
use super::command::{Command, EncoderKind, ModifyReporting, PinMode, Pull};
use super::dialect::Dialect;
use super::module::ModuleType;
use super::quirk::Quirk;
use super::report::Report;
use super::sensor::SensorType;

/// A name that is none of the names a type accepts (from `FromStr`).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("unknown {what} name; expected one of {expected}")]
pub struct UnknownName {
    /// What was being named (`"dialect"`, `"sensor type"`, …).
    pub what: &'static str,
    /// The accepted names, comma-separated.
    pub expected: &'static str,
}

/// A name from `names`, or [`UnknownName`].
fn lookup(
    names: &[&str],
    name: &str,
    what: &'static str,
    expected: &'static str,
) -> Result<usize, UnknownName> {
    names
        .iter()
        .position(|n| *n == name)
        .ok_or(UnknownName { what, expected })
}

macro_rules! named {
    ($ty:ty, $what:literal, $names:expr, $expected:expr, $all:expr) => {
        impl $ty {
            /// Every name, in wire-value order.
            pub const NAMES: &'static [&'static str] = &$names;

            /// The name (as `Display` writes it and `FromStr` reads it).
            pub const fn name(self) -> &'static str {
                Self::NAMES[self as usize]
            }
        }

        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl FromStr for $ty {
            type Err = UnknownName;

            fn from_str(s: &str) -> Result<Self, UnknownName> {
                let i = lookup(Self::NAMES, s, $what, $expected)?;
                $all.get(i).copied().ok_or(UnknownName {
                    what: $what,
                    expected: $expected,
                })
            }
        }
    };
}

named!(
    Dialect,
    "dialect",
    ["mirte13", "mirte12", "upstream11"],
    "mirte13, mirte12, upstream11",
    Dialect::ALL
);

/// `SensorType`'s names, from the sensor table.
macro_rules! sensor_names {
    ($($(#[$tm:meta])* $n:literal $t:ident $name:literal
        $(data $lens:tt $(#[$rm:meta])* $codec:ident { $($body:tt)* })?;)*) => {
        named!(SensorType, "sensor type", [$($name),*], join_names!($($name),*), SensorType::ALL);
    };
}

/// Names joined by `", "`, at compile time.
macro_rules! join_names {
    ($first:literal $(, $rest:literal)*) => {
        concat!($first $(, ", ", $rest)*)
    };
}

super::table::sensor_table!(sensor_names);

/// `ModuleType`'s names, from the module table.
macro_rules! module_names {
    ($($(#[$tm:meta])* $n:literal $t:ident $name:literal
        init $init:tt data $data:ident $dsec:tt $(reports $rvs:tt $reports:tt)?;)*) => {
        named!(ModuleType, "module type", [$($name),*], join_names!($($name),*), ModuleType::ALL);
    };
}

super::table::module_table!(module_names);

named!(
    EncoderKind,
    "encoder kind",
    ["single", "quadrature"],
    "single, quadrature",
    [EncoderKind::Single, EncoderKind::Quadrature]
);

named!(
    Quirk,
    "quirk",
    [
        "digital_reporting_pin_minus_26",
        "level_not_binary",
        "pwm_trailing_bytes",
        "encoder_type_not_1_or_2",
        "echoed_request_byte",
        "analog_reporting_pin_not_adc",
        "ignored_by_firmware",
        "past_firmware_buffer",
        "spi_data_bits_out_of_range",
    ],
    "digital_reporting_pin_minus_26, level_not_binary, pwm_trailing_bytes, \
     encoder_type_not_1_or_2, echoed_request_byte, analog_reporting_pin_not_adc, \
     ignored_by_firmware, past_firmware_buffer, spi_data_bits_out_of_range",
    Quirk::ALL
);

impl PinMode {
    /// The names of the modes (the schema's `mode`), in the order of
    /// [`name`](Self::name)'s cases: wire modes 0, 3, 4, 1, 2, 5.
    pub const NAMES: &'static [&'static str] = &[
        "digital_input",
        "digital_input_pull_up",
        "digital_input_pull_down",
        "digital_output",
        "pwm_output",
        "analog_input",
    ];

    /// The mode's name.
    pub const fn name(&self) -> &'static str {
        Self::NAMES[match self {
            PinMode::DigitalInput {
                pull: Pull::None, ..
            } => 0,
            PinMode::DigitalInput { pull: Pull::Up, .. } => 1,
            PinMode::DigitalInput {
                pull: Pull::Down, ..
            } => 2,
            PinMode::DigitalOutput => 3,
            PinMode::PwmOutput => 4,
            PinMode::AnalogInput { .. } => 5,
        }]
    }
}

impl ModifyReporting {
    /// The names of the actions (the schema's `action`), by the wire's type
    /// byte.
    pub const NAMES: &'static [&'static str] = &[
        "disable_all",
        "enable_analog",
        "enable_digital",
        "disable_analog",
        "disable_digital",
    ];

    /// The action's name.
    pub const fn name(&self) -> &'static str {
        Self::NAMES[match self {
            ModifyReporting::DisableAll => 0,
            ModifyReporting::EnableAnalog { .. } => 1,
            ModifyReporting::EnableDigital { .. } => 2,
            ModifyReporting::DisableAnalog { .. } => 3,
            ModifyReporting::DisableDigital { .. } => 4,
        }]
    }
}

/// The command names, from the command table.
macro_rules! command_names {
    ($($(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+] len $lens:tt
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        impl Command<'_> {
            /// Every command `type`, in id order (ids 0..=38). The command with id
            /// 37 is `feature_request` (the report is `feature_check`), so that
            /// every name names one direction.
            pub const NAMES: &'static [&'static str] = &[$($name),*];
        }
    };
}

super::table::command_table!(command_names);

impl Command<'_> {
    /// This command's `type`.
    pub const fn name(&self) -> &'static str {
        Self::NAMES[self.id() as usize]
    }
}

/// The report names, from the report table.
macro_rules! report_names {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        impl Report<'_> {
            /// Every report `type` (upstream's report 8 is `i2c_write_failed`);
            /// `unknown_report` last, for a lenient framing's unknown ids.
            pub const NAMES: &'static [&'static str] = &[$($($name,)+)* "unknown_report"];

            /// This report's `type`.
            pub const fn name(&self) -> &'static str {
                match self {
                    $($($(Report::$v { .. })|+ => $name,)+)*
                    Report::Unknown { .. } => "unknown_report",
                }
            }
        }
    };
}

super::table::report_table!(report_names);

/// `a` then `b`, in a const context.
const fn concat<const N: usize>(a: &[&'static str], b: &[&'static str]) -> [&'static str; N] {
    let mut out = [""; N];
    let mut i = 0;
    while i < N {
        out[i] = if i < a.len() { a[i] } else { b[i - a.len()] };
        i += 1;
    }
    out
}

/// Every message `type`: the commands', then the reports'.
const MESSAGE_NAMES: [&str; Command::NAMES.len() + Report::NAMES.len()] =
    concat(Command::NAMES, Report::NAMES);

impl Message<'_> {
    /// Every message `type`: [`Command::NAMES`], then [`Report::NAMES`]. No
    /// name is in both: a `type` says the direction.
    pub const NAMES: &'static [&'static str] = &MESSAGE_NAMES;

    /// This message's `type`.
    pub const fn name(&self) -> &'static str {
        match self {
            Message::Command(c) => c.name(),
            Message::Report(r) => r.name(),
        }
    }
}
