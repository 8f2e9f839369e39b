//! Line tracking: the line features response (0x31, spec §4.4) as a zero-copy
//! view ([`Features`]) and an owned fixed-capacity copy ([`FeaturesBuf`]).
//!
//! The payload is a run of sections `[ftype][flen][flen bytes]`. Coordinates
//! are on the 79 × 52 line grid (x 0..=78, y 0..=51), not in pixels. A view
//! exists only for a payload whose sections fit exactly, whose known sections
//! are whole numbers of elements and whose intersections have at most six
//! lines, so every iterator below is infallible.

use core::fmt;
use core::iter::FusedIterator;
use core::marker::PhantomData;
use core::slice::ChunksExact;

use crate::encode::EncodeError;

use super::error::Malformed;
use super::wire::MAX_PAYLOAD;

mod sealed {
    pub trait Sealed {}
}

/// A line feature element with a fixed wire layout (sealed: implemented by
/// [`Vector`], [`Intersection`] and [`Barcode`]).
pub trait Element: Copy + sealed::Sealed {
    /// The section type (`ftype`) that carries this element.
    const FTYPE: u8;
    /// Bytes per element.
    const SIZE: usize;
    /// Read an element from exactly [`SIZE`](Element::SIZE) bytes.
    fn read(bytes: &[u8]) -> Option<Self>;
    /// Write the element into exactly [`SIZE`](Element::SIZE) bytes.
    fn write(&self, out: &mut [u8]);
}

/// Feature type of a vector section.
pub const FTYPE_VECTOR: u8 = 0x01;
/// Feature type of an intersection section.
pub const FTYPE_INTERSECTION: u8 = 0x02;
/// Feature type of a barcode section.
pub const FTYPE_BARCODE: u8 = 0x04;

/// A tracked line segment, tail (x0, y0) to head (x1, y1). 6 bytes.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Vector {
    /// Tail column.
    pub x0: u8,
    /// Tail row.
    pub y0: u8,
    /// Head column.
    pub x1: u8,
    /// Head row.
    pub y1: u8,
    /// Tracking index.
    pub index: u8,
    /// Main mode: [`Vector::INTERSECTION_PRESENT`] or 0. All mode: the tracker
    /// state (0 valid, 1 trailing, 2 leading, 3 invalid).
    pub flags: u8,
}

impl Vector {
    /// Main-mode flag: the frame also has an intersection.
    pub const INTERSECTION_PRESENT: u8 = 0x04;
    /// All-mode flag bit: the vector is not (or no longer) valid.
    pub const INVALID: u8 = 0x02;
}

impl sealed::Sealed for Vector {}
impl Element for Vector {
    const FTYPE: u8 = FTYPE_VECTOR;
    const SIZE: usize = 6;
    fn read(b: &[u8]) -> Option<Self> {
        let &[x0, y0, x1, y1, index, flags] = b else {
            return None;
        };
        Some(Self {
            x0,
            y0,
            x1,
            y1,
            index,
            flags,
        })
    }
    fn write(&self, out: &mut [u8]) {
        out.copy_from_slice(&[self.x0, self.y0, self.x1, self.y1, self.index, self.flags]);
    }
}

/// One line leaving an intersection. 4 bytes.
///
/// With the `serde` feature: `{"index":2,"angle":90}`, with `reserved` only
/// when it is not 0.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct IntersectionLine {
    /// The line's tracking index.
    pub index: u8,
    /// Reserved byte, kept as received.
    pub reserved: u8,
    /// Degrees from the intersection outward: 0 up the image, +90 left,
    /// −90 right, ±180 down.
    pub angle: i16,
}

/// Line slots an intersection always carries.
pub const INTERSECTION_SLOTS: usize = 6;

/// An intersection with its lines. 28 bytes: x, y, n, reserved and six line
/// slots (slots ≥ n are zero when the device sends them).
///
/// With the `serde` feature: `x`, `y`, `reserved` (only when not 0), `lines`
/// (the `n` valid lines) and `unused_slots` (the `6 - n` slots after them,
/// only when one is not all zero), as `robowire decode pixy2` prints it.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Intersection {
    /// Column.
    pub x: u8,
    /// Row.
    pub y: u8,
    /// Valid lines, at most 6 (more is refused by the encoder and by views).
    pub n: u8,
    /// Reserved byte, kept as received.
    pub reserved: u8,
    /// All six slots as sent; [`Intersection::lines`] gives the valid ones.
    pub slots: [IntersectionLine; INTERSECTION_SLOTS],
}

impl Intersection {
    /// The `n` valid lines (the device sorts them by ascending angle).
    pub fn lines(&self) -> &[IntersectionLine] {
        &self.slots[..usize::from(self.n).min(INTERSECTION_SLOTS)]
    }
}

impl sealed::Sealed for Intersection {}
impl Element for Intersection {
    const FTYPE: u8 = FTYPE_INTERSECTION;
    const SIZE: usize = 28;
    fn read(b: &[u8]) -> Option<Self> {
        let (&[x, y, n, reserved], rest) = b.split_first_chunk::<4>()?;
        if rest.len() != 4 * INTERSECTION_SLOTS {
            return None;
        }
        let mut slots = [IntersectionLine::default(); INTERSECTION_SLOTS];
        for (slot, c) in slots.iter_mut().zip(rest.chunks_exact(4)) {
            if let &[index, reserved, a0, a1] = c {
                *slot = IntersectionLine {
                    index,
                    reserved,
                    angle: i16::from_le_bytes([a0, a1]),
                };
            }
        }
        Some(Self {
            x,
            y,
            n,
            reserved,
            slots,
        })
    }
    fn write(&self, out: &mut [u8]) {
        out[..4].copy_from_slice(&[self.x, self.y, self.n, self.reserved]);
        for (slot, c) in self.slots.iter().zip(out[4..].chunks_exact_mut(4)) {
            let [a0, a1] = slot.angle.to_le_bytes();
            c.copy_from_slice(&[slot.index, slot.reserved, a0, a1]);
        }
    }
}

/// A detected barcode. 4 bytes.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Barcode {
    /// Column.
    pub x: u8,
    /// Row.
    pub y: u8,
    /// 0 in main mode; the tracker state in all mode.
    pub flags: u8,
    /// The code, 0..=15.
    pub code: u8,
}

impl sealed::Sealed for Barcode {}
impl Element for Barcode {
    const FTYPE: u8 = FTYPE_BARCODE;
    const SIZE: usize = 4;
    fn read(b: &[u8]) -> Option<Self> {
        let &[x, y, flags, code] = b else {
            return None;
        };
        Some(Self { x, y, flags, code })
    }
    fn write(&self, out: &mut [u8]) {
        out.copy_from_slice(&[self.x, self.y, self.flags, self.code]);
    }
}

const fn element_size(ftype: u8) -> Option<usize> {
    match ftype {
        FTYPE_VECTOR => Some(6),
        FTYPE_INTERSECTION => Some(28),
        FTYPE_BARCODE => Some(4),
        _ => None,
    }
}

/// Check a features payload (spec §7.4 item 5).
fn validate(payload: &[u8]) -> Result<(), Malformed> {
    if payload.len() > MAX_PAYLOAD {
        return Err(Malformed::TooLong { len: payload.len() });
    }
    let mut offset = 0;
    while offset < payload.len() {
        let (ftype, flen) = match payload.get(offset..offset + 2) {
            Some(&[t, l]) => (t, l),
            _ => return Err(Malformed::SectionPastEnd { offset }),
        };
        let start = offset + 2;
        let Some(data) = payload.get(start..start + usize::from(flen)) else {
            return Err(Malformed::SectionPastEnd { offset });
        };
        if let Some(size) = element_size(ftype) {
            if data.len() % size != 0 {
                return Err(Malformed::SectionLength { ftype, flen });
            }
        }
        if ftype == FTYPE_INTERSECTION {
            for element in data.chunks_exact(Intersection::SIZE) {
                let n = element.get(2).copied().unwrap_or(0);
                if usize::from(n) > INTERSECTION_SLOTS {
                    return Err(Malformed::IntersectionLines { n });
                }
            }
        }
        offset = start + data.len();
    }
    Ok(())
}

/// Split the next section off `rest`; `None` at the end (or, defensively, on
/// a section that does not fit, which a validated payload never has).
fn next_section<'a>(rest: &mut &'a [u8]) -> Option<(u8, &'a [u8])> {
    let (&[ftype, flen], tail) = rest.split_first_chunk::<2>()?;
    let Some((data, after)) = tail.split_at_checked(usize::from(flen)) else {
        *rest = &[];
        return None;
    };
    *rest = after;
    Some((ftype, data))
}

/// A validated line features payload, borrowed.
///
/// With the `serde` feature it serializes as its sections in wire order,
/// as `robowire decode pixy2` prints a features response's `sections`:
/// `[{"vectors":[…]},{"intersections":[…]},{"barcodes":[…]}]`, a section of a
/// type this codec does not know as `{"ftype":8,"data":[…]}`. Unknown
/// sections and reserved bytes survive. Only [`FeaturesBuf`] deserializes.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Features<'a> {
    bytes: &'a [u8],
}

impl<'a> Features<'a> {
    /// A view of `payload` after checking its sections.
    pub fn new(payload: &'a [u8]) -> Result<Self, Malformed> {
        validate(payload)?;
        Ok(Self { bytes: payload })
    }

    /// The payload bytes.
    pub const fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// Whether nothing was detected (an empty payload).
    pub const fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// The sections in wire order (the device sends vectors, intersections,
    /// barcodes, omitting empty ones). Unknown feature types are yielded as
    /// [`Section::Unknown`], not skipped silently.
    pub fn sections(&self) -> Sections<'a> {
        Sections { rest: self.bytes }
    }

    /// Every vector, across sections.
    pub fn vectors(&self) -> FeatureIter<'a, Vector> {
        FeatureIter::new(self.bytes)
    }

    /// Every intersection, across sections.
    pub fn intersections(&self) -> FeatureIter<'a, Intersection> {
        FeatureIter::new(self.bytes)
    }

    /// Every barcode, across sections.
    pub fn barcodes(&self) -> FeatureIter<'a, Barcode> {
        FeatureIter::new(self.bytes)
    }

    /// An owned copy.
    pub fn to_owned(&self) -> FeaturesBuf {
        let mut buf = FeaturesBuf::new();
        let n = self.bytes.len().min(MAX_PAYLOAD);
        buf.bytes[..n].copy_from_slice(&self.bytes[..n]);
        buf.len = n as u8;
        buf
    }
}

impl fmt::Debug for Features<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.sections()).finish()
    }
}

/// One section of a line features payload.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub enum Section<'a> {
    /// A vector section (ftype 1).
    Vectors(Elements<'a, Vector>),
    /// An intersection section (ftype 2).
    Intersections(Elements<'a, Intersection>),
    /// A barcode section (ftype 4).
    Barcodes(Elements<'a, Barcode>),
    /// A section of a type this codec does not know, reported as is.
    Unknown {
        /// The feature type byte.
        ftype: u8,
        /// The section's bytes.
        data: &'a [u8],
    },
}

/// Iterator over the sections of a [`Features`] view.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub struct Sections<'a> {
    rest: &'a [u8],
}

impl<'a> Iterator for Sections<'a> {
    type Item = Section<'a>;

    fn next(&mut self) -> Option<Section<'a>> {
        let (ftype, data) = next_section(&mut self.rest)?;
        Some(match ftype {
            FTYPE_VECTOR => Section::Vectors(Elements::new(data)),
            FTYPE_INTERSECTION => Section::Intersections(Elements::new(data)),
            FTYPE_BARCODE => Section::Barcodes(Elements::new(data)),
            _ => Section::Unknown { ftype, data },
        })
    }
}

impl FusedIterator for Sections<'_> {}

/// Iterator over the elements of one section.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub struct Elements<'a, T> {
    chunks: ChunksExact<'a, u8>,
    _element: PhantomData<T>,
}

impl<'a, T: Element> Elements<'a, T> {
    fn new(data: &'a [u8]) -> Self {
        Self {
            chunks: data.chunks_exact(T::SIZE),
            _element: PhantomData,
        }
    }
}

impl<T: Element> Iterator for Elements<'_, T> {
    type Item = T;

    fn next(&mut self) -> Option<T> {
        self.chunks.next().and_then(T::read)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.chunks.size_hint()
    }
}

impl<T: Element> ExactSizeIterator for Elements<'_, T> {}
impl<T: Element> FusedIterator for Elements<'_, T> {}

/// Iterator over every element of one kind, across all its sections.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub struct FeatureIter<'a, T> {
    rest: &'a [u8],
    current: Elements<'a, T>,
}

impl<'a, T: Element> FeatureIter<'a, T> {
    fn new(payload: &'a [u8]) -> Self {
        Self {
            rest: payload,
            current: Elements::new(&[]),
        }
    }
}

impl<T: Element> Iterator for FeatureIter<'_, T> {
    type Item = T;

    fn next(&mut self) -> Option<T> {
        loop {
            if let Some(element) = self.current.next() {
                return Some(element);
            }
            let (ftype, data) = next_section(&mut self.rest)?;
            if ftype == T::FTYPE {
                self.current = Elements::new(data);
            }
        }
    }
}

impl<T: Element> FusedIterator for FeatureIter<'_, T> {}

/// An owned line features payload in a fixed 255-byte array (no allocation).
/// It keeps the exact bytes, so it re-encodes to what was received.
///
/// With the `serde` feature it serializes as [`Features`] does, its
/// sections. Deserializing refuses a payload over 255 bytes and one that
/// [`Features::new`] rejects, with messages that name the field.
#[derive(Clone, Copy)]
pub struct FeaturesBuf {
    bytes: [u8; MAX_PAYLOAD],
    len: u8,
}

impl FeaturesBuf {
    /// No features (an empty payload).
    pub const fn new() -> Self {
        Self {
            bytes: [0; MAX_PAYLOAD],
            len: 0,
        }
    }

    /// Build a payload as the device does: a vector section, an intersection
    /// section and a barcode section, each omitted when empty.
    ///
    /// Errors: a section over 255 bytes or a payload over 255 bytes
    /// ([`EncodeError::TooLong`]), an intersection with more than six lines
    /// ([`EncodeError::OutOfRange`]).
    pub fn from_parts(
        vectors: &[Vector],
        intersections: &[Intersection],
        barcodes: &[Barcode],
    ) -> Result<Self, EncodeError> {
        if intersections
            .iter()
            .any(|i| usize::from(i.n) > INTERSECTION_SLOTS)
        {
            return Err(EncodeError::OutOfRange {
                field: "intersection line count n (at most 6)",
            });
        }
        let mut buf = Self::new();
        buf.append(vectors)?;
        buf.append(intersections)?;
        buf.append(barcodes)?;
        Ok(buf)
    }

    fn append<T: Element>(&mut self, elements: &[T]) -> Result<(), EncodeError> {
        if elements.is_empty() {
            return Ok(());
        }
        let flen = elements.len() * T::SIZE;
        let start = usize::from(self.len);
        let end = start + 2 + flen;
        if flen > usize::from(u8::MAX) || end > MAX_PAYLOAD {
            return Err(EncodeError::TooLong {
                len: end,
                max: MAX_PAYLOAD,
            });
        }
        self.bytes[start] = T::FTYPE;
        self.bytes[start + 1] = flen as u8;
        for (e, out) in elements
            .iter()
            .zip(self.bytes[start + 2..end].chunks_exact_mut(T::SIZE))
        {
            e.write(out);
        }
        self.len = end as u8;
        Ok(())
    }

    /// A copy of `payload` after checking it as [`Features::new`] does.
    pub fn from_payload(payload: &[u8]) -> Result<Self, Malformed> {
        Features::new(payload).map(|f| f.to_owned())
    }

    /// The borrowed view (`as_features` in a docs search, and in the
    /// compiler's suggestions).
    #[doc(alias = "as_features")]
    pub fn view(&self) -> Features<'_> {
        Features {
            bytes: &self.bytes[..usize::from(self.len)],
        }
    }
}

impl Default for FeaturesBuf {
    fn default() -> Self {
        Self::new()
    }
}

impl PartialEq for FeaturesBuf {
    fn eq(&self, other: &Self) -> bool {
        self.view() == other.view()
    }
}

impl Eq for FeaturesBuf {}

impl fmt::Debug for FeaturesBuf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.view().fmt(f)
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for Features<'_> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "[");
        for (i, section) in self.sections().enumerate() {
            if i > 0 {
                defmt::write!(f, ", ");
            }
            defmt::write!(f, "{}", section);
        }
        defmt::write!(f, "]");
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for FeaturesBuf {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::Format::format(&self.view(), f)
    }
}
