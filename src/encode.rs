//! What every protocol's encoder shares: the [`Encode`] trait, its error type
//! and [`FrameBuf`], a fixed-size owned frame.

use core::fmt;
use core::ops::Deref;

/// Why a message could not be encoded. Nothing is written when encoding fails.
// Serialize only: the `&'static str` fields cannot be deserialized.
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum EncodeError {
    /// The output buffer is shorter than the frame.
    #[error("output buffer too small: the frame needs {needed} bytes, {available} available")]
    BufferTooSmall {
        /// Bytes the frame needs.
        needed: usize,
        /// Bytes the buffer has.
        available: usize,
    },
    /// A field holds a value the protocol cannot carry or the receiver would
    /// mishandle.
    #[error("{field} is out of range")]
    OutOfRange {
        /// The field's name.
        field: &'static str,
    },
    /// The payload is longer than the protocol or the receiver allows.
    #[error("payload of {len} bytes is longer than the {max}-byte limit")]
    TooLong {
        /// The payload's length.
        len: usize,
        /// The limit.
        max: usize,
    },
    /// The message's fields do not match its declared shape (for example a
    /// telemetry field that its layout does not carry).
    #[error("fields do not match the message's layout: {what}")]
    Inconsistent {
        /// What does not match.
        what: &'static str,
    },
}

/// A message that can be written as one frame.
pub trait Encode {
    /// The longest frame any message of this type encodes to.
    const MAX_LEN: usize;

    /// The exact length of this message's frame.
    fn encoded_len(&self) -> usize;

    /// Write the frame into the front of `out` and return its length. On error
    /// nothing meaningful is written.
    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError>;

    /// Append the frame to a [`bytes::BufMut`].
    #[cfg(feature = "bytes")]
    fn encode_buf<B: bytes::BufMut + ?Sized>(&self, buf: &mut B) -> Result<usize, EncodeError> {
        let mut frame = FrameBuf::<MAX_FRAME_BUF>::new();
        let n = frame.fill_with(|out| self.encode(out))?;
        if buf.remaining_mut() < n {
            return Err(EncodeError::BufferTooSmall {
                needed: n,
                available: buf.remaining_mut(),
            });
        }
        buf.put_slice(&frame);
        Ok(n)
    }
}

/// A reference encodes as the message it points to, so sinks that take
/// messages by value (a codec's `Encoder`) also take `&message`.
impl<T: Encode + ?Sized> Encode for &T {
    const MAX_LEN: usize = T::MAX_LEN;

    fn encoded_len(&self) -> usize {
        (**self).encoded_len()
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        (**self).encode(out)
    }
}

/// Size of the scratch frame [`Encode::encode_buf`] uses: the longest frame of
/// any protocol here (a Pixy2 frame: 6-byte header and 255-byte payload).
#[cfg(feature = "bytes")]
const MAX_FRAME_BUF: usize = 261;

/// Check that `out` can hold `needed` bytes.
pub(crate) fn check_room(out: &[u8], needed: usize) -> Result<(), EncodeError> {
    if out.len() < needed {
        Err(EncodeError::BufferTooSmall {
            needed,
            available: out.len(),
        })
    } else {
        Ok(())
    }
}

/// An owned frame of at most `N` bytes, dereferencing to its bytes.
///
/// With the `serde` feature it is written as its bytes (a byte string; an
/// array of numbers in JSON); deserializing refuses more than `N` bytes. With
/// `defmt` it prints its bytes in hex.
#[derive(Clone, Copy)]
pub struct FrameBuf<const N: usize> {
    bytes: [u8; N],
    len: usize,
}

impl<const N: usize> FrameBuf<N> {
    /// An empty frame.
    pub const fn new() -> Self {
        Self {
            bytes: [0; N],
            len: 0,
        }
    }

    /// Encode `message` into a new frame.
    pub fn encode<M: Encode + ?Sized>(message: &M) -> Result<Self, EncodeError> {
        let mut frame = Self::new();
        frame.fill_with(|out| message.encode(out))?;
        Ok(frame)
    }

    fn fill_with(
        &mut self,
        write: impl FnOnce(&mut [u8]) -> Result<usize, EncodeError>,
    ) -> Result<usize, EncodeError> {
        self.len = write(&mut self.bytes)?;
        Ok(self.len)
    }
}

impl<const N: usize> Default for FrameBuf<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Deref for FrameBuf<N> {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

impl<const N: usize> AsRef<[u8]> for FrameBuf<N> {
    fn as_ref(&self) -> &[u8] {
        self
    }
}

impl<const N: usize> PartialEq for FrameBuf<N> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<const N: usize> Eq for FrameBuf<N> {}

impl<const N: usize> fmt::Debug for FrameBuf<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "FrameBuf(")?;
        for (i, b) in self.iter().enumerate() {
            if i > 0 {
                write!(f, " ")?;
            }
            write!(f, "{b:02x}")?;
        }
        write!(f, ")")
    }
}

#[cfg(feature = "serde")]
impl<const N: usize> serde::Serialize for FrameBuf<N> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        crate::serde_support::serialize_bytes(&**self, serializer)
    }
}

#[cfg(feature = "serde")]
impl<'de, const N: usize> serde::Deserialize<'de> for FrameBuf<N> {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut frame = Self::new();
        frame.len = crate::serde_support::bytes_into(deserializer, &mut frame.bytes, "a frame")?;
        Ok(frame)
    }
}

#[cfg(feature = "defmt")]
impl<const N: usize> defmt::Format for FrameBuf<N> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "FrameBuf({=[u8]:02x})", &**self)
    }
}
