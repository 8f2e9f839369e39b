//! Telemetry layouts: which fields a telemetry frame of a given length carries.

use core::fmt;
use core::str::FromStr;

use super::error::UnknownName;

/// The names [`Layout`] and [`Layouts`] accept, as a phrase for messages.
const LAYOUT_NAMES: &str = "pos7, uwb15, uwbtof17, spi45 or ble53";

/// One telemetry layout. All layouts share the id `0x60` and are told apart only
/// by their total length (spec §4).
///
/// Its name (`Display`, `FromStr`, and the `serde` form) is the command-line
/// tool's: `pos7`, `uwb15`, `uwbtof17`, `spi45`, `ble53`.
///
/// ```
/// use robowire::omnitiles::Layout;
/// assert_eq!("ble53".parse(), Ok(Layout::Ble53));
/// assert_eq!(Layout::UwbTof17.to_string(), "uwbtof17");
/// ```
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Layout {
    /// 7 bytes: motor positions (SDK variant, never emitted by firmware).
    Pos7,
    /// 15 bytes: positions and four UWB ranges (SDK variant).
    Uwb15,
    /// 17 bytes: positions, four UWB ranges and ToF (SDK variant).
    UwbTof17,
    /// 45 bytes: the STM32 → nRF SPI frame (positions, ToF, IMU, ADCs; no UWB).
    Spi45,
    /// 53 bytes: the BLE notification the current firmware emits (everything).
    Ble53,
}

impl Layout {
    /// Every layout, shortest first.
    pub const ALL: [Layout; 5] = [
        Layout::Pos7,
        Layout::Uwb15,
        Layout::UwbTof17,
        Layout::Spi45,
        Layout::Ble53,
    ];

    /// Every layout's [`name`](Self::name), in the order of [`ALL`](Self::ALL).
    pub const NAMES: [&'static str; 5] = ["pos7", "uwb15", "uwbtof17", "spi45", "ble53"];

    /// The frame's total length, start byte and checksum included.
    pub const fn frame_len(self) -> usize {
        match self {
            Layout::Pos7 => 7,
            Layout::Uwb15 => 15,
            Layout::UwbTof17 => 17,
            Layout::Spi45 => 45,
            Layout::Ble53 => 53,
        }
    }

    /// The layout of a frame of exactly `len` bytes, if any.
    pub const fn from_len(len: usize) -> Option<Layout> {
        match len {
            7 => Some(Layout::Pos7),
            15 => Some(Layout::Uwb15),
            17 => Some(Layout::UwbTof17),
            45 => Some(Layout::Spi45),
            53 => Some(Layout::Ble53),
            _ => None,
        }
    }

    /// The short name used by the command-line tool and in JSON output.
    pub const fn name(self) -> &'static str {
        Layout::NAMES[self as usize]
    }

    /// The layout with this [`name`](Self::name).
    pub fn from_name(name: &str) -> Option<Layout> {
        Layout::ALL.into_iter().find(|l| l.name() == name)
    }

    /// Whether the layout carries the four UWB ranges.
    pub const fn has_uwb(self) -> bool {
        matches!(self, Layout::Uwb15 | Layout::UwbTof17 | Layout::Ble53)
    }

    /// Whether the layout carries the ToF range.
    pub const fn has_tof(self) -> bool {
        !matches!(self, Layout::Pos7 | Layout::Uwb15)
    }

    /// Whether the layout carries the IMU sample and the ADC channels.
    pub const fn has_imu_and_adcs(self) -> bool {
        matches!(self, Layout::Spi45 | Layout::Ble53)
    }

    const fn bit(self) -> u8 {
        1 << self as u8
    }
}

impl fmt::Display for Layout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Layout {
    type Err = UnknownName;

    fn from_str(name: &str) -> Result<Layout, UnknownName> {
        Layout::from_name(name).ok_or(UnknownName::new("layout", LAYOUT_NAMES))
    }
}

/// A set of telemetry layouts a decoder accepts.
///
/// ```
/// use robowire::omnitiles::{Layout, Layouts};
/// let ble_only = Layouts::only(Layout::Ble53);
/// assert!(ble_only.contains(Layout::Ble53));
/// assert_eq!(Layouts::DOCUMENTED.len(), 4);
/// assert_eq!(Layouts::DOCUMENTED.longest(), Some(Layout::Ble53));
/// ```
///
/// Its text form (`Display`, `FromStr`) is the command-line tool's `--layout`
/// syntax: layout names separated by commas, where `auto` stands for the four
/// documented layouts ([`Layouts::DOCUMENTED`]). `Display` writes `auto`
/// first when the set holds them, then the other layouts shortest first, and
/// `none` for the empty set (which `FromStr` also reads).
///
/// ```
/// use core::str::FromStr;
/// use robowire::omnitiles::{Layout, Layouts};
/// let layouts = Layouts::from_str("auto,spi45").unwrap();
/// assert_eq!(layouts, Layouts::ALL);
/// assert_eq!(layouts.to_string(), "auto,spi45");
/// assert_eq!("ble53,pos7".parse(), Ok(Layouts::only(Layout::Pos7).with(Layout::Ble53)));
/// assert_eq!(Layouts::only(Layout::Pos7).with(Layout::Ble53).to_string(), "pos7,ble53");
/// assert!(Layouts::from_str("ble52").is_err());
/// ```
///
/// With the `serde` feature a set is written as a number, its bits (bit `i`
/// is [`Layout::ALL`]`[i]`, so [`Layouts::DOCUMENTED`] is `23`), and a number
/// with an undefined bit (above `0x1f`) is refused when deserializing.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Layouts(u8);

impl Layouts {
    /// No layout: telemetry is not accepted.
    pub const NONE: Layouts = Layouts(0);
    /// The four layouts the SDK documents (7, 15, 17, 53 bytes): the default.
    pub const DOCUMENTED: Layouts = Layouts::NONE
        .with(Layout::Pos7)
        .with(Layout::Uwb15)
        .with(Layout::UwbTof17)
        .with(Layout::Ble53);
    /// Every layout, the 45-byte SPI frame included.
    pub const ALL: Layouts = Layouts::DOCUMENTED.with(Layout::Spi45);

    /// Exactly one layout: every frame is then emitted as soon as it is complete.
    pub const fn only(layout: Layout) -> Layouts {
        Layouts(layout.bit())
    }

    /// This set with `layout` added.
    pub const fn with(self, layout: Layout) -> Layouts {
        Layouts(self.0 | layout.bit())
    }

    /// This set with `layout` removed.
    pub const fn without(self, layout: Layout) -> Layouts {
        Layouts(self.0 & !layout.bit())
    }

    /// Whether `layout` is in the set.
    pub const fn contains(self, layout: Layout) -> bool {
        self.0 & layout.bit() != 0
    }

    /// Number of layouts in the set.
    pub const fn len(self) -> usize {
        self.0.count_ones() as usize
    }

    /// The set's bits: bit `i` is [`Layout::ALL`]`[i]`.
    pub(crate) const fn bits(self) -> u8 {
        self.0
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The longest layout in the set.
    pub const fn longest(self) -> Option<Layout> {
        let mut i = Layout::ALL.len();
        while i > 0 {
            i -= 1;
            if self.contains(Layout::ALL[i]) {
                return Some(Layout::ALL[i]);
            }
        }
        None
    }

    /// The layouts in the set, shortest first.
    pub fn iter(self) -> impl Iterator<Item = Layout> {
        Layout::ALL.into_iter().filter(move |l| self.contains(*l))
    }
}

impl fmt::Display for Layouts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("none");
        }
        let mut rest = *self;
        let mut first = true;
        if rest.0 & Layouts::DOCUMENTED.0 == Layouts::DOCUMENTED.0 {
            f.write_str("auto")?;
            rest = Layouts(rest.0 & !Layouts::DOCUMENTED.0);
            first = false;
        }
        for layout in rest.iter() {
            if !first {
                f.write_str(",")?;
            }
            f.write_str(layout.name())?;
            first = false;
        }
        Ok(())
    }
}

impl FromStr for Layouts {
    type Err = UnknownName;

    fn from_str(text: &str) -> Result<Layouts, UnknownName> {
        const EXPECTED: &str = "pos7, uwb15, uwbtof17, spi45, ble53 or auto, separated by commas";
        if text == "none" {
            return Ok(Layouts::NONE);
        }
        text.split(',')
            .try_fold(Layouts::NONE, |set, name| match name {
                "auto" => Ok(Layouts(set.0 | Layouts::DOCUMENTED.0)),
                name => Layout::from_name(name)
                    .map(|layout| set.with(layout))
                    .ok_or(UnknownName::new("layout", EXPECTED)),
            })
    }
}

impl Default for Layouts {
    fn default() -> Self {
        Layouts::DOCUMENTED
    }
}

impl FromIterator<Layout> for Layouts {
    fn from_iter<I: IntoIterator<Item = Layout>>(iter: I) -> Self {
        iter.into_iter().fold(Layouts::NONE, Layouts::with)
    }
}

// Written as the set's bits: 1 = pos7, 2 = uwb15, 4 = uwbtof17, 8 = spi45,
// 16 = ble53. A number with any other bit set is refused, so a deserialized
// set never holds an undefined layout.
#[cfg(feature = "serde")]
impl serde::Serialize for Layouts {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u8(self.0)
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Layouts {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::{Error, Unexpected};
        let bits = <u8 as serde::Deserialize>::deserialize(deserializer)?;
        if bits & !Layouts::ALL.0 != 0 {
            return Err(D::Error::invalid_value(
                Unexpected::Unsigned(bits.into()),
                &"a set of OmniTiles telemetry layouts, 0..=31",
            ));
        }
        Ok(Layouts(bits))
    }
}
