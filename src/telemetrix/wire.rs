//! The wire level, below every message module: ids, limits, splitting a frame,
//! and reading and writing fields (big-endian integers, little-endian floats;
//! spec §3). It uses only the leaf modules [`Error`] and [`Dialect`].

use super::dialect::Dialect;
use super::error::{ensure, Error};

/// GPIOs on the RP2040: pins are `0..30`.
pub const PIN_COUNT: u8 = 30;

/// The firmware's `MAX_COMMAND_LENGTH`: the largest `LEN` of a command.
pub const MAX_COMMAND_LEN: usize = 30;

/// The longest command frame: `LEN` 30 and the `LEN` byte.
pub const MAX_COMMAND_FRAME: usize = MAX_COMMAND_LEN + 1;

/// The longest report frame: `LEN` 255 and the `LEN` byte.
pub const MAX_REPORT_FRAME: usize = 256;

/// The longest frame of either direction (a report).
pub const MAX_FRAME_LEN: usize = MAX_REPORT_FRAME;

/// Most data bytes of a MODULE_DATA command (`LEN` 30 less `id, module_num`),
/// the longest variable field of a command.
pub const COMMAND_PAYLOAD_MAX: usize = 28;

/// The most bytes an I2C read fits in the firmware's 64-entry report buffer
/// (`n + 7` entries in mirte's report; spec §2.1). More are flagged
/// ([`Quirk::PastFirmwareBuffer`](super::Quirk::PastFirmwareBuffer)).
pub(crate) const I2C_READ_MAX: u8 = 57;

/// The most bytes an SPI read fits in the same buffer (`n + 4` entries).
pub(crate) const SPI_READ_MAX: u8 = 60;

/// The pixels the firmware's pixel buffer holds: 100 in mirte 1.3 (its
/// NeoPixel driver), 150 (`MAXIMUM_NUM_NEOPIXELS`) before.
pub(crate) const fn pixel_buffer(dialect: Dialect) -> u8 {
    match dialect {
        Dialect::Mirte13 => 100,
        Dialect::Mirte12 | Dialect::Upstream11 => 150,
    }
}

/// Whether `pin` names an analog input in `dialect`: GPIO 26..=30 (30 is the
/// temperature sensor) in mirte 1.3, ADC 0..=4 before.
pub(crate) const fn analog_pin_ok(dialect: Dialect, pin: u8) -> bool {
    match dialect {
        Dialect::Mirte13 => pin >= 26 && pin <= 30,
        Dialect::Mirte12 | Dialect::Upstream11 => pin <= 4,
    }
}

/// The id constants, from the command table.
macro_rules! command_ids {
    ($($(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+] len $lens:tt
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        /// Command ids (host → Pico), mirte firmware 1.3 numbering (spec §4).
        pub mod command_id {
            $(
                #[doc = concat!(stringify!($id), ".")]
                pub const $id: u8 = $n;
            )*
        }

        // The rows are in id order, one per id, so that an id indexes the
        // name table.
        const _: () = {
            let ids = [$($n),*];
            let mut i = 0;
            while i < ids.len() {
                assert!(ids[i] as usize == i, "command table rows out of id order");
                i += 1;
            }
        };
    };
}

super::table::command_table!(command_ids);

/// The report id constants and the report dialect table, from the report
/// table.
macro_rules! report_ids {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        /// Report ids (Pico → host), mirte firmware 1.3 numbering (spec §5).
        pub mod report_id {
            $(
                $(#[$m])*
                pub const $id: u8 = $n;
            )*
        }

        /// Whether `dialect` defines report `id` (and robowire covers it there).
        pub(crate) const fn report_known(dialect: Dialect, id: u8) -> bool {
            match id {
                $($n => matches!(dialect, $(Dialect::$d)|+),)*
                _ => false,
            }
        }
    };
}

super::table::report_table!(report_ids);

/// A count byte (`field` in the error when it is below `min`), then that
/// many bytes.
pub(crate) fn counted<'a>(
    r: &mut Reader<'a>,
    field: &'static str,
    min: u8,
) -> Result<&'a [u8], Error> {
    let n = r.u8()?;
    ensure(n >= min, r.id(), field)?;
    r.take(usize::from(n))
}

/// Split a frame into `LEN`, id and payload, checking that `LEN` matches.
pub(crate) fn split_frame(frame: &[u8]) -> Result<(u8, u8, &[u8]), Error> {
    match frame {
        [len, id, payload @ ..] if usize::from(*len) == payload.len() + 1 => {
            Ok((*len, *id, payload))
        }
        [len, id, ..] => Err(Error::BadLength { id: *id, len: *len }),
        _ => Err(Error::Truncated { len: frame.len() }),
    }
}

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

    /// An I2C or UART port: 0 or 1.
    pub(crate) fn port(&mut self) -> Result<u8, Error> {
        let port = self.u8()?;
        super::error::ensure(port <= 1, self.id, "port")?;
        Ok(port)
    }

    /// A 7-bit I2C address.
    pub(crate) fn i2c_addr(&mut self) -> Result<u8, Error> {
        let addr = self.u8()?;
        super::error::ensure(addr <= 0x7f, self.id, "addr")?;
        Ok(addr)
    }

    /// A GPIO number, which must be below 30.
    pub(crate) fn pin(&mut self, field: &'static str) -> Result<u8, Error> {
        let pin = self.u8()?;
        super::error::ensure(pin < PIN_COUNT, self.id, field)?;
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
