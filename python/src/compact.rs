//! A Telemetrix message kept in a few bytes: what a typed item holds.
//!
//! The library's [`MessageBuf`] has room for the longest frame (256 bytes)
//! where a report a host reads at rate is 4 to 6, so keeping one per item
//! cost a 280-byte allocation and its copies per frame. An item keeps the
//! frame's bytes and its [`Attribution`] in place (a short frame with no
//! allocation at all), and rebuilds the `MessageBuf` on the stack when a
//! field is read.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use robowire::stream::OwnedFrame;
use robowire::telemetrix::{Attribution, MessageBuf};

use crate::engine::to_python;
use crate::item::Erased;
use crate::pick::field;

/// Frames up to this long (every report but the long I2C, SPI, module and
/// debug ones) are kept inline; longer ones in a heap slice of their size.
const INLINE: usize = 14;

/// A frame's bytes.
enum Bytes {
    Inline { len: u8, bytes: [u8; INLINE] },
    Heap(Box<[u8]>),
}

impl Bytes {
    fn new(frame: &[u8]) -> Self {
        let mut bytes = [0; INLINE];
        match (bytes.get_mut(..frame.len()), u8::try_from(frame.len())) {
            (Some(inline), Ok(len)) => {
                inline.copy_from_slice(frame);
                Self::Inline { len, bytes }
            }
            _ => Self::Heap(frame.into()),
        }
    }

    fn get(&self) -> &[u8] {
        match self {
            Self::Inline { len, bytes } => bytes.get(..usize::from(*len)).unwrap_or_default(),
            Self::Heap(bytes) => bytes,
        }
    }
}

/// A decoded Telemetrix frame: its offset, bytes and attribution.
pub struct CompactMessage {
    offset: u64,
    attribution: Attribution,
    bytes: Bytes,
}

impl CompactMessage {
    /// `frame` kept small.
    pub fn new(frame: &OwnedFrame<MessageBuf>) -> Self {
        Self {
            offset: frame.offset,
            attribution: frame.message.attribution(),
            bytes: Bytes::new(frame.message.frame()),
        }
    }

    /// The frame as the decoder gave it.
    fn frame(&self) -> PyResult<OwnedFrame<MessageBuf>> {
        let bytes = self.bytes.get();
        let message = MessageBuf::from_attribution(bytes, self.attribution)
            // Unreachable: the bytes are those of a `MessageBuf`'s frame.
            .map_err(|error| PyValueError::new_err(error.to_string()))?;
        Ok(OwnedFrame {
            offset: self.offset,
            len: bytes.len(),
            message,
        })
    }
}

impl Erased for CompactMessage {
    fn offset(&self) -> u64 {
        self.offset
    }

    fn to_python<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.frame()?)
    }

    fn field<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        field(py, &self.frame()?, key)
    }
}
