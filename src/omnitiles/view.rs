//! Telemetry read in place: [`TelemetryView`], and [`TelemetryViews`], the
//! host framing whose decoder yields views instead of owned [`Telemetry`].

use core::fmt;

use super::error::Error;
use super::framing::{Framing, Host};
use super::layout::Layout;
use super::telemetry::{checked_layout, offsets, Imu, Telemetry, M1_ADCS_LEN, NO_READING};
use crate::stream::{Check, FrameRules};

/// A checked telemetry frame whose fields are read on access: the same
/// fields as [`Telemetry`], as methods of the same names, without building
/// the 76-byte struct for every frame.
///
/// A decoder of [`TelemetryViews`] yields views (see
/// [`host_view_decoder`](super::host_view_decoder)); a view also parses one
/// whole frame with `TryFrom<&[u8]>`, checking it as [`Telemetry`] does.
/// [`to_telemetry`](Self::to_telemetry) (or `Telemetry::from`) gives the owned
/// struct.
///
/// ```
/// use robowire::omnitiles::{Layout, Telemetry, TelemetryView};
/// let frame = [0xa5, 0x60, 0xd0, 0x07, 0xff, 0xff, 0x35];
/// let view = TelemetryView::try_from(&frame[..])?;
/// assert_eq!(view.layout(), Layout::Pos7);
/// assert_eq!((view.m1_pos(), view.m2_pos()), (Some(2000), None));
/// assert_eq!(view.uwb(), None); // not carried by the 7-byte layout
/// assert_eq!(view.to_telemetry(), Telemetry::try_from(&frame[..])?);
/// # Ok::<(), robowire::omnitiles::Error>(())
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct TelemetryView<'a> {
    layout: Layout,
    /// The whole frame, `layout`'s length, its checksum verified.
    frame: &'a [u8],
}

impl<'a> TelemetryView<'a> {
    /// Which layout the frame has.
    pub const fn layout(&self) -> Layout {
        self.layout
    }

    /// The frame's bytes, start byte and checksum included.
    pub const fn as_bytes(&self) -> &'a [u8] {
        self.frame
    }

    /// M1 position, raw 0..=4095 (`None` for "no reading").
    pub fn m1_pos(&self) -> Option<u16> {
        self.reading(2)
    }

    /// M2 position, raw 0..=4095.
    pub fn m2_pos(&self) -> Option<u16> {
        self.reading(4)
    }

    /// UWB ranges to anchors 0..=3 in mm, if the layout carries them.
    pub fn uwb(&self) -> Option<[Option<u16>; 4]> {
        let at = offsets(self.layout).uwb?;
        Some(core::array::from_fn(|i| self.reading(at + 2 * i)))
    }

    /// ToF range in mm, if the layout carries it.
    pub fn tof(&self) -> Option<Option<u16>> {
        Some(self.reading(offsets(self.layout).tof?))
    }

    /// The IMU sample, if the layout carries it.
    pub fn imu(&self) -> Option<Imu> {
        let at = offsets(self.layout).imu?;
        Some(Imu::from_array(core::array::from_fn(|i| {
            f32::from_bits(self.u32_at(at + 4 * i))
        })))
    }

    /// M1's four potentiometer channels, raw, if the layout carries them.
    pub fn m1_adcs(&self) -> Option<[u16; 4]> {
        let at = offsets(self.layout).adcs?;
        Some(core::array::from_fn(|i| self.u16_at(at + 2 * i)))
    }

    /// M2's two potentiometer channels, raw, if the layout carries them.
    pub fn m2_adcs(&self) -> Option<[u16; 2]> {
        let at = offsets(self.layout).adcs? + M1_ADCS_LEN;
        Some(core::array::from_fn(|i| self.u16_at(at + 2 * i)))
    }

    /// Every field, as the owned struct.
    pub fn to_telemetry(&self) -> Telemetry {
        Telemetry::parse(self.layout, self.frame)
    }

    /// A frame that passed framing (start byte, telemetry id, a layout's
    /// length and checksum already checked).
    #[inline(always)]
    pub(super) fn framed(frame: &'a [u8]) -> Result<TelemetryView<'a>, Error> {
        match Layout::from_len(frame.len()) {
            Some(layout) => Ok(TelemetryView { layout, frame }),
            None => Err(Error::Truncated { len: frame.len() }),
        }
    }

    fn reading(&self, at: usize) -> Option<u16> {
        Some(self.u16_at(at)).filter(|&v| v != NO_READING)
    }

    // The offsets come from the layout and fit its frame: the fallbacks only
    // keep panic paths out of firmware builds.
    fn u16_at(&self, at: usize) -> u16 {
        match self.frame.get(at..at + 2) {
            Some(&[a, b]) => u16::from_le_bytes([a, b]),
            _ => 0,
        }
    }

    fn u32_at(&self, at: usize) -> u32 {
        match self.frame.get(at..at + 4) {
            Some(&[a, b, c, d]) => u32::from_le_bytes([a, b, c, d]),
            _ => 0,
        }
    }
}

impl<'a> TryFrom<&'a [u8]> for TelemetryView<'a> {
    type Error = Error;

    /// One whole frame, checked as [`Telemetry::try_from`] checks it (the
    /// same errors).
    fn try_from(frame: &'a [u8]) -> Result<TelemetryView<'a>, Error> {
        Ok(TelemetryView {
            layout: checked_layout(frame)?,
            frame,
        })
    }
}

impl From<TelemetryView<'_>> for Telemetry {
    fn from(view: TelemetryView<'_>) -> Telemetry {
        view.to_telemetry()
    }
}

/// As the owned [`Telemetry`] prints.
impl fmt::Debug for TelemetryView<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&self.to_telemetry(), f)
    }
}

/// As the owned [`Telemetry`] displays.
impl fmt::Display for TelemetryView<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.to_telemetry(), f)
    }
}

/// A host's framing ([`Framing<Host>`]: telemetry in a set of layouts) whose
/// decoder yields [`TelemetryView`]s: the same frames at the same offsets,
/// each read in place. The owned form (`feed`, `flush`) is [`Telemetry`].
///
/// ```
/// use robowire::omnitiles::{host_view_decoder, Framing, HostViewDecoder, Layout, Layouts};
///
/// let mut decoder = host_view_decoder();
/// // A 7-byte frame, then the next frame's header, which confirms its length.
/// let mut input = &[0xa5, 0x60, 0xd0, 0x07, 0xff, 0xff, 0x35, 0xa5, 0x60][..];
/// let frame = decoder.decode(&mut input).unwrap().unwrap();
/// assert_eq!((frame.offset, frame.message.m1_pos()), (0, Some(2000)));
///
/// // Views of one layout only:
/// let ble = Framing::new().with_layouts(Layouts::only(Layout::Ble53));
/// let decoder = HostViewDecoder::new(ble.views());
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct TelemetryViews(Framing<Host>);

impl TelemetryViews {
    /// Views of the four documented layouts, as [`Framing::<Host>::new`].
    pub const fn new() -> TelemetryViews {
        TelemetryViews(Framing::new())
    }

    /// The framing that decides where frames are.
    pub const fn framing(&self) -> Framing<Host> {
        self.0
    }
}

impl Framing<Host> {
    /// The same framing, with a decoder yielding [`TelemetryView`]s.
    pub const fn views(self) -> TelemetryViews {
        TelemetryViews(self)
    }
}

impl FrameRules for TelemetryViews {
    type Error = Error;
    type Message<'a> = TelemetryView<'a>;
    type Owned = Telemetry;

    const HEADER_LEN: usize = <Framing<Host> as FrameRules>::HEADER_LEN;

    #[inline]
    fn find_start(&self, bytes: &[u8]) -> usize {
        self.0.find_start(bytes)
    }

    #[inline(always)]
    fn check(&self, candidate: &[u8], at_end: bool) -> Check<Error> {
        self.0.check(candidate, at_end)
    }

    fn truncated(&self, len: usize) -> Error {
        self.0.truncated(len)
    }

    fn superseded(&self, len: usize) -> Error {
        self.0.superseded(len)
    }

    fn is_checksum_error(&self, error: &Error) -> bool {
        self.0.is_checksum_error(error)
    }

    #[inline(always)]
    fn parse<'a>(&self, frame: &'a [u8]) -> Result<TelemetryView<'a>, Error> {
        TelemetryView::framed(frame)
    }

    fn to_owned(message: TelemetryView<'_>) -> Telemetry {
        message.to_telemetry()
    }
}
