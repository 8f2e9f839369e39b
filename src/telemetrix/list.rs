//! [`List`]: a fixed-capacity, allocation-free list, and [`Payload`], a list of
//! bytes. They hold the variable parts of owned messages.

use core::fmt;
use core::hash::{Hash, Hasher};
use core::ops::Deref;

use crate::EncodeError;

/// Up to `N` items of `T` stored inline (an array and a length). Only the first
/// `len` items count: equality, hashing and `Debug` ignore the rest.
///
/// With the `serde` feature a list serializes as the sequence of its items
/// (a [`Payload`] as a sequence of numbers, like `&[u8]`); deserializing
/// refuses more than `N` items. With `defmt` it prints its items.
#[derive(Clone, Copy)]
pub struct List<T, const N: usize> {
    items: [T; N],
    len: usize,
}

/// Up to `N` bytes stored inline: the owned form of a variable byte field.
pub type Payload<const N: usize> = List<u8, N>;

impl<T: Copy + Default, const N: usize> List<T, N> {
    /// An empty list.
    pub fn new() -> Self {
        Self {
            items: [T::default(); N],
            len: 0,
        }
    }

    /// A list holding a copy of `items`, or [`EncodeError::TooLong`] if there are
    /// more than `N`.
    pub fn from_slice(items: &[T]) -> Result<Self, EncodeError> {
        let mut list = Self::new();
        let slot = list
            .items
            .get_mut(..items.len())
            .ok_or(EncodeError::TooLong {
                len: items.len(),
                max: N,
            })?;
        slot.copy_from_slice(items);
        list.len = items.len();
        Ok(list)
    }

    /// Append `item`, or [`EncodeError::TooLong`] if the list is full.
    pub fn push(&mut self, item: T) -> Result<(), EncodeError> {
        let slot = self
            .items
            .get_mut(self.len)
            .ok_or(EncodeError::TooLong { len: N + 1, max: N })?;
        *slot = item;
        self.len += 1;
        Ok(())
    }
}

impl<T, const N: usize> List<T, N> {
    /// The capacity `N`.
    pub const CAPACITY: usize = N;

    /// The items.
    pub fn as_slice(&self) -> &[T] {
        self.items.get(..self.len).unwrap_or(&[])
    }

    /// Empty the list.
    pub fn clear(&mut self) {
        self.len = 0;
    }
}

impl<T: Copy + Default, const N: usize> Default for List<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T, const N: usize> Deref for List<T, N> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T, const N: usize> AsRef<[T]> for List<T, N> {
    fn as_ref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: PartialEq, const N: usize> PartialEq for List<T, N> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Eq, const N: usize> Eq for List<T, N> {}

impl<T: Hash, const N: usize> Hash for List<T, N> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.as_slice().hash(state);
    }
}

impl<T: fmt::Debug, const N: usize> fmt::Debug for List<T, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

impl<'a, T, const N: usize> IntoIterator for &'a List<T, N> {
    type Item = &'a T;
    type IntoIter = core::slice::Iter<'a, T>;

    fn into_iter(self) -> Self::IntoIter {
        self.as_slice().iter()
    }
}

#[cfg(feature = "serde")]
impl<T: serde::Serialize, const N: usize> serde::Serialize for List<T, N> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.as_slice())
    }
}

#[cfg(feature = "serde")]
impl<'de, T, const N: usize> serde::Deserialize<'de> for List<T, N>
where
    T: serde::Deserialize<'de> + Copy + Default,
{
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ListVisitor<T, const N: usize>(core::marker::PhantomData<T>);

        impl<'de, T, const N: usize> serde::de::Visitor<'de> for ListVisitor<T, N>
        where
            T: serde::Deserialize<'de> + Copy + Default,
        {
            type Value = List<T, N>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a sequence of at most {N} items")
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<List<T, N>, A::Error> {
                let mut list = List::new();
                while let Some(item) = seq.next_element()? {
                    if list.push(item).is_err() {
                        return Err(serde::de::Error::invalid_length(N + 1, &self));
                    }
                }
                Ok(list)
            }
        }

        deserializer.deserialize_seq(ListVisitor::<T, N>(core::marker::PhantomData))
    }
}

#[cfg(feature = "defmt")]
impl<T: defmt::Format, const N: usize> defmt::Format for List<T, N> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(f, "{=[?]}", self.as_slice())
    }
}
