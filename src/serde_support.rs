//! Helpers shared by the manual `serde` impls of robowire's fixed-capacity
//! byte buffers ([`FrameBuf`](crate::FrameBuf), the Pixy2 program name and
//! line features).

use core::fmt;

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Serializer;

/// Serialize `bytes` as a byte string (`serialize_bytes`): compact in binary
/// formats, an array of numbers in JSON.
pub(crate) fn serialize_bytes<S: Serializer, B: AsRef<[u8]> + ?Sized>(
    bytes: &B,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.serialize_bytes(bytes.as_ref())
}

/// Deserialize a byte string, or a sequence of bytes (JSON), into `buf` and
/// return its length. More bytes than `buf` holds is an `invalid_length` error
/// that names `what`.
pub(crate) fn bytes_into<'de, D: Deserializer<'de>>(
    deserializer: D,
    buf: &mut [u8],
    what: &'static str,
) -> Result<usize, D::Error> {
    deserializer.deserialize_bytes(BytesInto { buf, what })
}

struct BytesInto<'b> {
    buf: &'b mut [u8],
    what: &'static str,
}

impl<'de> Visitor<'de> for BytesInto<'_> {
    type Value = usize;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} of at most {} bytes", self.what, self.buf.len())
    }

    fn visit_bytes<E: de::Error>(self, v: &[u8]) -> Result<usize, E> {
        if v.len() > self.buf.len() {
            return Err(E::invalid_length(v.len(), &self));
        }
        self.buf[..v.len()].copy_from_slice(v);
        Ok(v.len())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<usize, A::Error> {
        let mut len = 0;
        while let Some(byte) = seq.next_element::<u8>()? {
            if len == self.buf.len() {
                return Err(de::Error::invalid_length(len + 1, &self));
            }
            self.buf[len] = byte;
            len += 1;
        }
        Ok(len)
    }
}
