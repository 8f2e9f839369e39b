//! Reading and writing fields: big-endian integers, little-endian floats
//! (spec §3).

use super::error::Error;

/// Reads the payload of one frame; running past its end is a length error.
pub(crate) struct Reader<'a> {
    bytes: &'a [u8],
    id: u8,
    len: u8,
}

impl<'a> Reader<'a> {
    pub(crate) const fn new(id: u8, len: u8, payload: &'a [u8]) -> Self {
        Self {
            bytes: payload,
            id,
            len,
        }
    }

    pub(crate) const fn id(&self) -> u8 {
        self.id
    }

    pub(crate) const fn bad_length(&self) -> Error {
        Error::BadLength {
            id: self.id,
            len: self.len,
        }
    }

    pub(crate) const fn remaining(&self) -> usize {
        self.bytes.len()
    }

    pub(crate) fn take(&mut self, n: usize) -> Result<&'a [u8], Error> {
        if n > self.bytes.len() {
            return Err(self.bad_length());
        }
        let (head, tail) = self.bytes.split_at(n);
        self.bytes = tail;
        Ok(head)
    }

    pub(crate) fn array<const N: usize>(&mut self) -> Result<[u8; N], Error> {
        let mut out = [0; N];
        out.copy_from_slice(self.take(N)?);
        Ok(out)
    }

    pub(crate) fn rest(&mut self) -> &'a [u8] {
        core::mem::take(&mut self.bytes)
    }

    pub(crate) fn u8(&mut self) -> Result<u8, Error> {
        Ok(self.array::<1>()?[0])
    }

    pub(crate) fn i8(&mut self) -> Result<i8, Error> {
        Ok(i8::from_be_bytes(self.array()?))
    }

    pub(crate) fn u16(&mut self) -> Result<u16, Error> {
        Ok(u16::from_be_bytes(self.array()?))
    }

    pub(crate) fn i16(&mut self) -> Result<i16, Error> {
        Ok(i16::from_be_bytes(self.array()?))
    }

    pub(crate) fn u32(&mut self) -> Result<u32, Error> {
        Ok(u32::from_be_bytes(self.array()?))
    }

    pub(crate) fn i32(&mut self) -> Result<i32, Error> {
        Ok(i32::from_be_bytes(self.array()?))
    }

    pub(crate) fn f32(&mut self) -> Result<f32, Error> {
        Ok(f32::from_le_bytes(self.array()?))
    }

    /// A flag byte that must be 0 or 1.
    pub(crate) fn flag(&mut self, field: &'static str) -> Result<bool, Error> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(Error::OutOfRange { id: self.id, field }),
        }
    }

    /// A GPIO number, which must be below 30.
    pub(crate) fn pin(&mut self, field: &'static str) -> Result<u8, Error> {
        let pin = self.u8()?;
        super::error::ensure(pin < super::PIN_COUNT, self.id, field)?;
        Ok(pin)
    }

    /// Everything was read.
    pub(crate) fn end(&self) -> Result<(), Error> {
        if self.bytes.is_empty() {
            Ok(())
        } else {
            Err(self.bad_length())
        }
    }
}

/// Writes a frame into a scratch buffer whose size the caller has checked.
pub(crate) struct Writer<'a> {
    out: &'a mut [u8],
    pos: usize,
}

impl<'a> Writer<'a> {
    pub(crate) fn new(out: &'a mut [u8]) -> Self {
        Self { out, pos: 0 }
    }

    pub(crate) const fn len(&self) -> usize {
        self.pos
    }

    pub(crate) fn bytes(&mut self, bytes: &[u8]) {
        let end = self.pos + bytes.len();
        if let Some(slot) = self.out.get_mut(self.pos..end) {
            slot.copy_from_slice(bytes);
        }
        self.pos = end;
    }

    pub(crate) fn u8(&mut self, v: u8) {
        self.bytes(&[v]);
    }

    pub(crate) fn i8(&mut self, v: i8) {
        self.bytes(&v.to_be_bytes());
    }

    pub(crate) fn flag(&mut self, v: bool) {
        self.u8(u8::from(v));
    }

    pub(crate) fn u16(&mut self, v: u16) {
        self.bytes(&v.to_be_bytes());
    }

    pub(crate) fn i16(&mut self, v: i16) {
        self.bytes(&v.to_be_bytes());
    }

    pub(crate) fn u32(&mut self, v: u32) {
        self.bytes(&v.to_be_bytes());
    }

    pub(crate) fn i32(&mut self, v: i32) {
        self.bytes(&v.to_be_bytes());
    }

    pub(crate) fn f32(&mut self, v: f32) {
        self.bytes(&v.to_le_bytes());
    }
}

impl Writer<'_> {
    /// Set byte 0 (`LEN`) to the number of bytes written after it.
    pub(crate) fn patch_len(&mut self) {
        let len = u8::try_from(self.pos.saturating_sub(1)).unwrap_or(u8::MAX);
        if let Some(first) = self.out.first_mut() {
            *first = len;
        }
    }
}
