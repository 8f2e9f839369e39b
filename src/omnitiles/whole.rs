//! The checks every message's `TryFrom<&[u8]>` shares: one whole frame, its
//! start byte, its length and its checksum. Above the leaves `wire` and
//! `error` only.

use super::error::Error;
use super::wire::{checksum, START};

/// Check the length and the checksum of one whole frame, given the length its
/// id asks for. Shared by every message's `TryFrom`.
pub(super) fn check_whole(frame: &[u8], len: usize) -> Result<(), Error> {
    match frame.len() {
        n if n < len => return Err(Error::Truncated { len: n }),
        n if n > len => return Err(Error::BadLength { len: n }),
        _ => {}
    }
    let (&found, body) = frame.split_last().ok_or(Error::Truncated { len: 0 })?;
    let expected = checksum(body.get(1..).unwrap_or(&[]));
    if expected == found {
        Ok(())
    } else {
        Err(Error::Checksum { expected, found })
    }
}

/// The start byte and id of a whole frame.
pub(super) fn start_and_id(frame: &[u8]) -> Result<u8, Error> {
    match *frame {
        [START, id, ..] => Ok(id),
        [START] | [] => Err(Error::Truncated { len: frame.len() }),
        [found, ..] => Err(Error::BadStart { found }),
    }
}
