//! A request a real host sends that the device refuses with an error: the
//! decoders accept it and the serde form marks it; the encoder refuses it
//! unless asked ([`Envelope::even_if_refused`](super::Envelope::even_if_refused)).

use core::fmt;

use super::request::{GetBlocks, Request};

/// Something in a request a real host sends that the device refuses with an
/// error: decoders accept the frame, the JSON-lines schema writes
/// `"quirk":"<name>"` after its fields, and the encoder refuses it unless
/// asked with [`Envelope::even_if_refused`](super::Envelope::even_if_refused)
/// (the shape of [`telemetrix::Quirk`](crate::telemetrix::Quirk)).
///
/// ```
/// use robowire::pixy2::{GetBlocks, Quirk, Request};
///
/// // What the official host library sends for an empty signature map.
/// let empty = Request::from(GetBlocks { sigmap: 0, max_blocks: 5 });
/// assert_eq!(empty.quirk(), Some(Quirk::SigmapZero));
/// assert_eq!(Quirk::SigmapZero.name(), "sigmap_zero");
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Quirk {
    /// getBlocks with signature map 0, which the device answers with
    /// ERROR −3.
    SigmapZero,
}

impl Quirk {
    /// Every quirk.
    pub const ALL: [Quirk; 1] = [Quirk::SigmapZero];

    /// Every quirk's [`name`](Self::name), in the order of [`ALL`](Self::ALL).
    pub const NAMES: [&'static str; 1] = ["sigmap_zero"];

    /// The name the JSON-lines schema writes (snake case).
    pub const fn name(self) -> &'static str {
        Quirk::NAMES[self as usize]
    }
}

impl fmt::Display for Quirk {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Request {
    /// What the device would refuse in this request, if anything (see
    /// [`Quirk`]).
    pub const fn quirk(&self) -> Option<Quirk> {
        match self {
            Request::GetBlocks(GetBlocks { sigmap: 0, .. }) => Some(Quirk::SigmapZero),
            _ => None,
        }
    }
}
