//! The Telemetrix decode error.

use crate::EncodeError;

/// Why a candidate frame was rejected. Telemetrix has no checksum, so every
/// rejection comes from the frame's shape: an id the dialect does not define, a
/// `LEN` that id cannot have, or a field value the firmware never sends.
///
/// With the `serde` feature it serializes as the `robowire` tool prints a
/// rejection (`{"error":"bad_length","id":2,"len_byte":7}`; `len_byte` is
/// the `LEN` byte) but does not deserialize:
/// [`OutOfRange`](Error::OutOfRange)'s `&'static str` field cannot be read
/// back from input that does not live forever.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The id is not defined for this direction in this dialect.
    #[error("unknown message id {id}")]
    UnknownId {
        /// The id byte.
        id: u8,
    },
    /// The `LEN` byte is impossible for this id (or for its sub-type).
    #[error("length {len} is impossible for message id {id}")]
    BadLength {
        /// The id byte.
        id: u8,
        /// The `LEN` byte (bytes after it).
        len: u8,
    },
    /// A field holds a value the sender never produces (a pin ≥ 30, a flag
    /// other than 0/1, an unknown sub-type, …).
    #[error("message id {id}: {field} is out of range")]
    OutOfRange {
        /// The id byte.
        id: u8,
        /// The field's name.
        field: &'static str,
    },
    /// The input ended inside a candidate frame of `len` bytes.
    #[error("input ended inside a frame after {len} bytes")]
    Truncated {
        /// Bytes of the candidate that were available.
        len: usize,
    },
    /// A plausible candidate found after a resync was set aside: a frame
    /// starting inside it is plausible too, and only that frame is followed by
    /// a plausible header.
    #[error("a {len}-byte candidate overlapped a confirmed frame and was set aside")]
    Superseded {
        /// The candidate's length.
        len: usize,
    },
}

impl Error {
    /// The matching encode error, for a message the encoder refuses because its
    /// own decoder would reject the frame.
    pub(crate) const fn into_encode_error(self) -> EncodeError {
        match self {
            Error::OutOfRange { field, .. } => EncodeError::OutOfRange { field },
            Error::UnknownId { .. } => EncodeError::Inconsistent {
                what: "the message does not exist in this dialect",
            },
            Error::BadLength { .. } | Error::Truncated { .. } | Error::Superseded { .. } => {
                EncodeError::Inconsistent {
                    what: "the payload length does not fit the message's layout",
                }
            }
        }
    }
}

/// `Ok(())` if `ok`, else [`Error::OutOfRange`].
pub(crate) const fn ensure(ok: bool, id: u8, field: &'static str) -> Result<(), Error> {
    if ok {
        Ok(())
    } else {
        Err(Error::OutOfRange { id, field })
    }
}
