//! Why an OmniTiles candidate frame was rejected, and why a name did not parse.

/// A rejected OmniTiles candidate. Never fatal: the decoder has already
/// dropped the candidate's start byte and carries on.
///
/// With the `serde` feature an error is written as the command-line tool's
/// diagnostic event (without its `offset`): an `error` tag and the variant's
/// fields, e.g. `{"error":"checksum","expected":248,"found":247}`.
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
    /// A telemetry candidate whose checksum validated at two or more enabled
    /// layouts, none of them the longest enabled, and which no following
    /// frame header (or, after a 45-byte frame, zero padding) or end of input
    /// confirmed at any of them.
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
    /// Parsing one whole frame (`TryFrom<&[u8]>`): it does not begin with the
    /// start byte `0xA5`. The decoders never report it: they only ever look at
    /// candidates that begin with it.
    #[error("a frame begins with 0xa5, not {found:#04x}")]
    BadStart {
        /// The first byte.
        found: u8,
    },
    /// Parsing one whole frame (`TryFrom<&[u8]>`): no message with its id has
    /// its length (bytes after a command, or a telemetry length that is no
    /// layout's). The decoders never report it.
    #[error("no message with this id is {len} bytes long")]
    BadLength {
        /// The frame's length.
        len: usize,
    },
}

/// A name that [`FromStr`](core::str::FromStr) does not know: no
/// [`Layout`](super::Layout), [`Layouts`](super::Layouts) or
/// [`Motor`](super::Motor) has it.
///
/// ```
/// use core::str::FromStr;
/// use robowire::omnitiles::Layout;
/// let err = Layout::from_str("ble52").unwrap_err();
/// assert_eq!(err.to_string(), "unknown layout (expected pos7, uwb15, uwbtof17, spi45 or ble53)");
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, thiserror::Error)]
#[error("unknown {what} (expected {expected})")]
pub struct UnknownName {
    what: &'static str,
    expected: &'static str,
}

impl UnknownName {
    pub(crate) const fn new(what: &'static str, expected: &'static str) -> Self {
        UnknownName { what, expected }
    }

    /// What kind of name was expected: `"layout"` or `"motor"`.
    pub const fn what(&self) -> &'static str {
        self.what
    }

    /// The names that would have been accepted, as a phrase.
    pub const fn expected(&self) -> &'static str {
        self.expected
    }
}
