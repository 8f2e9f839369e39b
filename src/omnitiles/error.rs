//! Why an OmniTiles candidate frame was rejected.

/// A rejected OmniTiles candidate. Never fatal: the decoder has already
/// dropped the candidate's start byte and carries on.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The checksum byte does not match the sum of id and payload. For
    /// telemetry with several layouts enabled it is the longest layout's
    /// checksum that is reported.
    #[error("checksum mismatch: expected {expected:#04x}, found {found:#04x}")]
    Checksum {
        /// The sum computed over id and payload.
        expected: u8,
        /// The checksum byte on the wire.
        found: u8,
    },
    /// The byte after `0xA5` is not an id this decoder accepts (commands,
    /// telemetry or both, as configured).
    #[error("unknown or unaccepted message id {id:#04x}")]
    UnknownId {
        /// The id byte.
        id: u8,
    },
    /// A telemetry candidate whose checksum validated at a shorter enabled
    /// layout, but which no following frame header, end of input or longer
    /// layout confirmed.
    #[error("telemetry length could not be confirmed")]
    Unconfirmed,
    /// The input ended inside a candidate of this many bytes.
    #[error("input ended inside a frame after {len} bytes")]
    Truncated {
        /// Bytes of the candidate that arrived.
        len: usize,
    },
    /// The candidate validated after a resync, but a frame starting inside it
    /// validated too and only that frame is followed by a plausible header: the
    /// candidate was most likely garbage that happened to sum right.
    #[error("a {len}-byte candidate overlapped a confirmed frame and was set aside")]
    Superseded {
        /// The candidate's length.
        len: usize,
    },
}
