//! robowire's serde toolkit: byte strings for fixed-capacity buffers
//! ([`FrameBuf`](crate::FrameBuf), the Pixy2 program name and line features),
//! the `f32` form of the JSON schema, and the strict reader ([`Value`],
//! [`Fields`]) that messages' `Deserialize` impls are written with.

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

mod events;
mod prefixed;

mod reader;
mod suggest;
mod value;

pub(crate) use reader::{read_f32, read_int, Fields};
pub(crate) use suggest::unknown_type;
pub(crate) use value::Value;

/// Serialize an `f32` so that it reads back as the same `f32`: a finite value
/// is a number, the shortest decimal that gives back the same `f32` whether it
/// is parsed as an `f32` or as the nearest `f64` then rounded (what most JSON
/// readers do). Infinities are the strings `"inf"` and `"-inf"`; a NaN is
/// `"nan:0x7fc00000"`, its bit pattern, so its sign and payload survive.
/// [`read_f32`] reads all of them. A format that is not human-readable (a
/// binary one, or robowire's Python binding) carries every `f32` as itself.
pub(crate) fn serialize_f32<S: Serializer>(x: f32, serializer: S) -> Result<S::Ok, S::Error> {
    if !serializer.is_human_readable() {
        return serializer.serialize_f32(x);
    }
    if x.is_nan() {
        let mut text = Inline::<16>::new();
        // 4 + 10 characters always fit.
        let _ = fmt::Write::write_fmt(&mut text, format_args!("nan:{:#010x}", x.to_bits()));
        return serializer.serialize_str(text.as_str());
    }
    if x.is_infinite() {
        return serializer.serialize_str(if x > 0.0 { "inf" } else { "-inf" });
    }
    if x.to_bits() & 0x7fff_ffff == SHORTEST_FAILS_THROUGH_F64 {
        // Every f32 is exactly an f64, whose shortest digits read back to
        // exactly that f64 and so to the same f32, with no double rounding.
        serializer.serialize_f64(f64::from(x))
    } else {
        serializer.serialize_f32(x)
    }
}

/// The one finite `f32` magnitude (7.038531e-26) whose shortest decimal digits,
/// read as the nearest `f64` and then rounded to `f32`, give a different
/// `f32`. Found by checking every `f32`:
/// `cargo test --release --features serde --lib every_f32 -- --ignored`.
const SHORTEST_FAILS_THROUGH_F64: u32 = 0x15ae_43fd;

/// A small fixed-capacity string, for formatting without an allocator.
struct Inline<const N: usize> {
    buf: [u8; N],
    len: usize,
}

impl<const N: usize> Inline<N> {
    fn new() -> Self {
        Inline {
            buf: [0; N],
            len: 0,
        }
    }

    fn as_str(&self) -> &str {
        // Only whole `&str`s are ever written into `buf`.
        core::str::from_utf8(&self.buf[..self.len]).unwrap_or("")
    }
}

impl<const N: usize> fmt::Write for Inline<N> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        let slot = self.buf.get_mut(self.len..end).ok_or(fmt::Error)?;
        slot.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct F(f32);

    impl serde::Serialize for F {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            serialize_f32(self.0, serializer)
        }
    }

    fn json(bits: u32) -> alloc::string::String {
        serde_json::to_string(&F(f32::from_bits(bits))).unwrap()
    }

    /// Every finite positive `f32` (the sign does not change the digits):
    /// its shortest digits read back through `f64`, but for one. Minutes in
    /// a release build.
    #[test]
    #[ignore = "exhaustive over every f32: minutes in a release build; run with --ignored"]
    fn every_f32_but_one_reads_back_through_f64() {
        use core::fmt::Write as _;
        let mut text = alloc::string::String::new();
        for bits in 0..0x7f80_0000u32 {
            let x = f32::from_bits(bits);
            text.clear();
            write!(text, "{x:e}").unwrap();
            let back = text.parse::<f64>().unwrap() as f32;
            assert_eq!(
                back.to_bits() == bits,
                bits != SHORTEST_FAILS_THROUGH_F64,
                "{bits:#010x}"
            );
        }
    }

    #[test]
    fn f32_reads_back_through_f64() {
        assert_eq!(json(2.5f32.to_bits()), "2.5");
        assert_eq!(json(0.1f32.to_bits()), "0.1");
        // 7.038531e-26: its shortest f32 digits round wrongly through f64.
        assert_eq!(json(0x15ae_43fd), "7.038530691851209e-26");
        assert_eq!(json(f32::INFINITY.to_bits()), "\"inf\"");
        assert_eq!(json(f32::NEG_INFINITY.to_bits()), "\"-inf\"");
        assert_eq!(json(0xffc0_0001), "\"nan:0xffc00001\"");
        for bits in (0..u32::MAX).step_by(0x0100_0fff) {
            let x = f32::from_bits(bits);
            if x.is_finite() {
                let text = json(bits);
                let back = text.parse::<f64>().unwrap() as f32;
                assert_eq!(back.to_bits(), bits, "{text}");
            }
        }
    }
}
