//! Colour connected components: the blocks response (0x21, spec §4.3) as a
//! zero-copy view ([`Blocks`]) and as an owned fixed-capacity copy
//! ([`BlocksBuf`]).

use core::fmt;
use core::iter::FusedIterator;

use crate::encode::EncodeError;

/// One detected block, 14 bytes on the wire.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Block {
    /// 1..=7 for a plain signature; above 7 a colour code: one octal digit
    /// per stripe (stripes 1 and 2 give 0o12 = 10), up to 0o77777.
    pub signature: u16,
    /// Centre column, 0..=315.
    pub x: u16,
    /// Centre row, 0..=207.
    pub y: u16,
    /// Width, 0..=316.
    pub width: u16,
    /// Height, 0..=208.
    pub height: u16,
    /// Colour codes only (else 0): degrees −180..=180, first stripe to last,
    /// y axis up.
    pub angle: i16,
    /// Tracking index, new for each new track; wraps.
    pub index: u8,
    /// Frames this block has been tracked; saturates at 255.
    pub age: u8,
}

impl Block {
    /// Bytes per block on the wire.
    pub const SIZE: usize = 14;

    /// Whether this block is a colour-code detection (signature > 7).
    pub const fn is_color_code(&self) -> bool {
        self.signature > 7
    }

    /// Read a block from its wire bytes.
    pub const fn from_bytes(b: &[u8; Self::SIZE]) -> Self {
        Self {
            signature: u16::from_le_bytes([b[0], b[1]]),
            x: u16::from_le_bytes([b[2], b[3]]),
            y: u16::from_le_bytes([b[4], b[5]]),
            width: u16::from_le_bytes([b[6], b[7]]),
            height: u16::from_le_bytes([b[8], b[9]]),
            angle: i16::from_le_bytes([b[10], b[11]]),
            index: b[12],
            age: b[13],
        }
    }

    /// The block's wire bytes.
    pub const fn to_bytes(&self) -> [u8; Self::SIZE] {
        let [s0, s1] = self.signature.to_le_bytes();
        let [x0, x1] = self.x.to_le_bytes();
        let [y0, y1] = self.y.to_le_bytes();
        let [w0, w1] = self.width.to_le_bytes();
        let [h0, h1] = self.height.to_le_bytes();
        let [a0, a1] = self.angle.to_le_bytes();
        [
            s0, s1, x0, x1, y0, y1, w0, w1, h0, h1, a0, a1, self.index, self.age,
        ]
    }

    fn from_chunk(chunk: &[u8]) -> Option<Self> {
        chunk.first_chunk::<{ Self::SIZE }>().map(Self::from_bytes)
    }
}

/// Most blocks one response carries: floor(255 / 14).
pub const MAX_BLOCKS: usize = 18;
const MAX_BYTES: usize = MAX_BLOCKS * Block::SIZE;

/// Whether a blocks payload may be `len` bytes long: a whole number of
/// blocks (a length byte cannot exceed 18 of them: 19 · 14 > 255). On a
/// `u8` this is a multiply and a rotate, not a division.
#[inline(always)]
pub(crate) const fn blocks_len_ok(len: u8) -> bool {
    len % Block::SIZE as u8 == 0
}

/// A blocks payload, borrowed: 14·k bytes, k ≤ 18, read on demand.
///
/// With the `serde` feature it serializes as a sequence of [`Block`]s, as
/// [`BlocksBuf`] does. It does not deserialize: its blocks are decoded from
/// wire bytes, so there is nothing in a serialized form to borrow; deserialize
/// a [`BlocksBuf`] (or a [`ResponseBuf`](super::ResponseBuf)) instead.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Blocks<'a> {
    bytes: &'a [u8],
}

impl<'a> Blocks<'a> {
    /// A view of `payload`, if it is a whole number (at most 18) of blocks.
    #[inline]
    pub const fn new(payload: &'a [u8]) -> Option<Self> {
        if payload.len() <= MAX_BYTES && blocks_len_ok(payload.len() as u8) {
            Some(Self { bytes: payload })
        } else {
            None
        }
    }

    /// The payload bytes.
    pub const fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// Number of blocks.
    pub const fn len(&self) -> usize {
        self.bytes.len() / Block::SIZE
    }

    /// Whether there are no blocks.
    pub const fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// The `i`th block (largest first, as the device sorts them).
    pub fn get(&self, i: usize) -> Option<Block> {
        let start = i.checked_mul(Block::SIZE)?;
        Block::from_chunk(self.bytes.get(start..start + Block::SIZE)?)
    }

    /// Iterate the blocks.
    pub fn iter(&self) -> BlockIter<'a> {
        BlockIter::new(self.bytes)
    }

    /// An owned copy.
    pub fn to_owned(&self) -> BlocksBuf {
        let mut buf = BlocksBuf::new();
        let n = self.bytes.len().min(MAX_BYTES);
        buf.bytes[..n].copy_from_slice(&self.bytes[..n]);
        buf.len = n as u8;
        buf
    }
}

impl fmt::Debug for Blocks<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl<'a> IntoIterator for Blocks<'a> {
    type Item = Block;
    type IntoIter = BlockIter<'a>;
    fn into_iter(self) -> BlockIter<'a> {
        self.iter()
    }
}

impl<'a> IntoIterator for &Blocks<'a> {
    type Item = Block;
    type IntoIter = BlockIter<'a>;
    fn into_iter(self) -> BlockIter<'a> {
        self.iter()
    }
}

/// Iterator over the blocks of a [`Blocks`] view or a [`BlocksBuf`].
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub struct BlockIter<'a> {
    /// The blocks not yet taken: a whole number of them.
    bytes: &'a [u8],
}

impl<'a> BlockIter<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        // A view always holds whole blocks; a partial one would be ignored.
        let whole = bytes.len() - bytes.len() % Block::SIZE;
        Self {
            bytes: bytes.get(..whole).unwrap_or(&[]),
        }
    }
}

impl Iterator for BlockIter<'_> {
    type Item = Block;

    #[inline]
    fn next(&mut self) -> Option<Block> {
        let (block, rest) = self.bytes.split_first_chunk::<{ Block::SIZE }>()?;
        self.bytes = rest;
        Some(Block::from_bytes(block))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.bytes.len() / Block::SIZE;
        (n, Some(n))
    }

    /// Two blocks per step, each read at constant offsets: a loop over a
    /// view (`blocks.iter().map(..).sum()`) runs half as many iterations,
    /// with no length test per block.
    #[inline]
    fn fold<B, F: FnMut(B, Block) -> B>(self, init: B, mut f: F) -> B {
        let mut acc = init;
        let mut rest = self.bytes;
        while let Some((pair, tail)) = rest.split_first_chunk::<{ 2 * Block::SIZE }>() {
            let (first, second) = pair.split_at(Block::SIZE);
            if let (Some(first), Some(second)) = (
                first.first_chunk::<{ Block::SIZE }>(),
                second.first_chunk::<{ Block::SIZE }>(),
            ) {
                acc = f(acc, Block::from_bytes(first));
                acc = f(acc, Block::from_bytes(second));
            }
            rest = tail;
        }
        if let Some(last) = rest.first_chunk::<{ Block::SIZE }>() {
            acc = f(acc, Block::from_bytes(last));
        }
        acc
    }
}

impl DoubleEndedIterator for BlockIter<'_> {
    #[inline]
    fn next_back(&mut self) -> Option<Block> {
        let (rest, block) = self.bytes.split_last_chunk::<{ Block::SIZE }>()?;
        self.bytes = rest;
        Some(Block::from_bytes(block))
    }
}

impl ExactSizeIterator for BlockIter<'_> {}
impl FusedIterator for BlockIter<'_> {}

/// An owned blocks payload: up to 18 blocks in a fixed array (no allocation).
///
/// With the `serde` feature it serializes as a sequence of [`Block`]s;
/// deserializing refuses more than 18.
#[derive(Clone, Copy)]
pub struct BlocksBuf {
    bytes: [u8; MAX_BYTES],
    len: u8,
}

impl BlocksBuf {
    /// No blocks.
    pub const fn new() -> Self {
        Self {
            bytes: [0; MAX_BYTES],
            len: 0,
        }
    }

    /// The blocks of `blocks`, in order; at most 18.
    pub fn from_blocks(blocks: &[Block]) -> Result<Self, EncodeError> {
        let mut buf = Self::new();
        for block in blocks {
            buf.push(*block).map_err(|_| EncodeError::TooLong {
                len: blocks.len() * Block::SIZE,
                max: MAX_BYTES,
            })?;
        }
        Ok(buf)
    }

    /// Append a block; gives it back when 18 are already held.
    pub fn push(&mut self, block: Block) -> Result<(), Block> {
        let start = usize::from(self.len);
        match self.bytes.get_mut(start..start + Block::SIZE) {
            Some(slot) => {
                slot.copy_from_slice(&block.to_bytes());
                self.len += Block::SIZE as u8;
                Ok(())
            }
            None => Err(block),
        }
    }

    /// The borrowed view: the [`Blocks`] a decoded frame gives, to iterate
    /// or index (`view` throughout robowire, as
    /// [`FeaturesBuf::view`](super::FeaturesBuf::view); searching the docs for
    /// `as_blocks` finds it, and the compiler suggests it for `as_blocks()`).
    ///
    /// ```
    /// use robowire::pixy2::{Block, BlocksBuf};
    ///
    /// let mut buf = BlocksBuf::new();
    /// buf.push(Block::from_bytes(&[1, 0, 160, 0, 100, 0, 20, 0, 10, 0, 0, 0, 3, 9])).unwrap();
    /// let blocks = buf.view();
    /// assert_eq!(blocks.len(), 1);
    /// assert_eq!(blocks.iter().next().unwrap().x, 160);
    /// ```
    #[doc(alias = "as_blocks")]
    pub fn view(&self) -> Blocks<'_> {
        Blocks {
            bytes: &self.bytes[..usize::from(self.len)],
        }
    }

    /// Number of blocks.
    pub const fn len(&self) -> usize {
        self.len as usize / Block::SIZE
    }

    /// Whether there are no blocks.
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The `i`th block.
    pub fn get(&self, i: usize) -> Option<Block> {
        self.view().get(i)
    }

    /// Iterate the blocks.
    pub fn iter(&self) -> BlockIter<'_> {
        self.view().iter()
    }
}

impl Default for BlocksBuf {
    fn default() -> Self {
        Self::new()
    }
}

impl PartialEq for BlocksBuf {
    fn eq(&self, other: &Self) -> bool {
        self.view() == other.view()
    }
}

impl Eq for BlocksBuf {}

impl fmt::Debug for BlocksBuf {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.view().fmt(f)
    }
}

impl<'a> IntoIterator for &'a BlocksBuf {
    type Item = Block;
    type IntoIter = BlockIter<'a>;
    fn into_iter(self) -> BlockIter<'a> {
        self.iter()
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Blocks<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.iter())
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for BlocksBuf {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serde::Serialize::serialize(&self.view(), serializer)
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for BlocksBuf {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct BlocksVisitor;

        impl<'de> serde::de::Visitor<'de> for BlocksVisitor {
            type Value = BlocksBuf;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a sequence of at most {MAX_BLOCKS} Pixy2 blocks")
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<BlocksBuf, A::Error> {
                let mut buf = BlocksBuf::new();
                while let Some(block) = seq.next_element::<Block>()? {
                    if buf.push(block).is_err() {
                        return Err(serde::de::Error::invalid_length(MAX_BLOCKS + 1, &self));
                    }
                }
                Ok(buf)
            }
        }

        deserializer.deserialize_seq(BlocksVisitor)
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for Blocks<'_> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "[");
        for (i, block) in self.iter().enumerate() {
            if i > 0 {
                defmt::write!(f, ", ");
            }
            defmt::write!(f, "{}", block);
        }
        defmt::write!(f, "]");
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for BlocksBuf {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::Format::format(&self.view(), f)
    }
}
