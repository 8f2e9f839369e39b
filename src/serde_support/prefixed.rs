//! Serialize a message or an error as one flat map that begins with the
//! stream's members (`offset`, `len`): the JSON-lines schema of a decoded
//! frame or a rejection, `{"offset":0,"len":4,"type":"m1_extend",...}`,
//! written straight into the output without an intermediate tree.

use core::fmt;

use serde::ser::{
    self, Impossible, Serialize, SerializeMap, SerializeStruct, SerializeStructVariant, Serializer,
};

/// The stream's members that go first: name and value.
pub(crate) type Prefix<'p> = &'p [(&'static str, u64)];

/// Serialize `inner` (a struct, map or struct variant, as every robowire
/// message and error is; or a plain value, written under `fallback`) with
/// `prefix` first.
pub(crate) fn serialize_prefixed<S: Serializer, T: Serialize + ?Sized>(
    serializer: S,
    prefix: Prefix<'_>,
    fallback: &'static str,
    inner: &T,
) -> Result<S::Ok, S::Error> {
    inner.serialize(Prefixed {
        serializer,
        prefix,
        fallback,
    })
}

struct Prefixed<'p, S> {
    serializer: S,
    prefix: Prefix<'p>,
    fallback: &'static str,
}

impl<S: Serializer> Prefixed<'_, S> {
    fn open(self, len: Option<usize>) -> Result<Members<S::SerializeMap>, S::Error> {
        let mut map = self
            .serializer
            .serialize_map(len.map(|n| n + self.prefix.len()))?;
        for (key, value) in self.prefix {
            map.serialize_entry(key, value)?;
        }
        Ok(Members { map })
    }

    /// A value that is not a map: the prefix, then the value under `fallback`.
    fn single<T: Serialize + ?Sized>(self, value: &T) -> Result<S::Ok, S::Error> {
        let fallback = self.fallback;
        let mut members = self.open(Some(1))?;
        members.map.serialize_entry(fallback, value)?;
        members.map.end()
    }
}

/// The map being written, taking the message's own members.
pub(crate) struct Members<M> {
    map: M,
}

impl<M: SerializeMap> SerializeMap for Members<M> {
    type Ok = M::Ok;
    type Error = M::Error;

    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), M::Error> {
        self.map.serialize_key(key)
    }

    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), M::Error> {
        self.map.serialize_value(value)
    }

    fn end(self) -> Result<M::Ok, M::Error> {
        self.map.end()
    }
}

/// Struct fields and struct-variant fields become map entries alike.
macro_rules! fields_as_entries {
    ($($kind:ident),*) => {$(
        impl<M: SerializeMap> $kind for Members<M> {
            type Ok = M::Ok;
            type Error = M::Error;

            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), M::Error> {
                self.map.serialize_entry(key, value)
            }

            fn end(self) -> Result<M::Ok, M::Error> {
                self.map.end()
            }
        }
    )*};
}

fields_as_entries!(SerializeStruct, SerializeStructVariant);

fn unsupported<E: ser::Error>(what: &str) -> E {
    E::custom(format_args!(
        "a frame's message or error must serialize as a map or a single value, not {what}"
    ))
}

macro_rules! single {
    ($($method:ident($ty:ty)),* $(,)?) => {$(
        fn $method(self, v: $ty) -> Result<S::Ok, S::Error> {
            self.single(&v)
        }
    )*};
}

impl<S: Serializer> Serializer for Prefixed<'_, S> {
    type Ok = S::Ok;
    type Error = S::Error;
    type SerializeSeq = Impossible<S::Ok, S::Error>;
    type SerializeTuple = Impossible<S::Ok, S::Error>;
    type SerializeTupleStruct = Impossible<S::Ok, S::Error>;
    type SerializeTupleVariant = Impossible<S::Ok, S::Error>;
    type SerializeMap = Members<S::SerializeMap>;
    type SerializeStruct = Members<S::SerializeMap>;
    type SerializeStructVariant = Members<S::SerializeMap>;

    single! {
        serialize_bool(bool), serialize_i8(i8), serialize_i16(i16), serialize_i32(i32),
        serialize_i64(i64), serialize_u8(u8), serialize_u16(u16), serialize_u32(u32),
        serialize_u64(u64), serialize_f32(f32), serialize_f64(f64), serialize_char(char),
        serialize_str(&str), serialize_bytes(&[u8]),
    }

    fn serialize_none(self) -> Result<S::Ok, S::Error> {
        self.single(&())
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<S::Ok, S::Error> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<S::Ok, S::Error> {
        self.single(&())
    }

    fn serialize_unit_struct(self, _name: &'static str) -> Result<S::Ok, S::Error> {
        self.single(&())
    }

    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<S::Ok, S::Error> {
        self.single(variant)
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<S::Ok, S::Error> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<S::Ok, S::Error> {
        let mut members = self.open(Some(1))?;
        members.map.serialize_entry(variant, value)?;
        members.map.end()
    }

    fn serialize_seq(self, _len: Option<usize>) -> Result<Self::SerializeSeq, S::Error> {
        Err(unsupported("a sequence"))
    }

    fn serialize_tuple(self, _len: usize) -> Result<Self::SerializeTuple, S::Error> {
        Err(unsupported("a tuple"))
    }

    fn serialize_tuple_struct(
        self,
        _name: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeTupleStruct, S::Error> {
        Err(unsupported("a tuple struct"))
    }

    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeTupleVariant, S::Error> {
        Err(unsupported("a tuple variant"))
    }

    fn serialize_map(self, len: Option<usize>) -> Result<Self::SerializeMap, S::Error> {
        self.open(len)
    }

    fn serialize_struct(
        self,
        _name: &'static str,
        len: usize,
    ) -> Result<Self::SerializeStruct, S::Error> {
        self.open(Some(len))
    }

    /// An externally tagged struct variant: its fields, flat. (robowire's
    /// messages and errors are internally tagged, so this is only a fallback.)
    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        len: usize,
    ) -> Result<Self::SerializeStructVariant, S::Error> {
        self.open(Some(len))
    }

    fn collect_str<T: fmt::Display + ?Sized>(self, value: &T) -> Result<S::Ok, S::Error> {
        let fallback = self.fallback;
        let mut members = self.open(Some(1))?;
        members.map.serialize_key(fallback)?;
        members.map.serialize_value(&DisplayAsStr(value))?;
        members.map.end()
    }

    fn is_human_readable(&self) -> bool {
        self.serializer.is_human_readable()
    }
}

struct DisplayAsStr<'a, T: ?Sized>(&'a T);

impl<T: fmt::Display + ?Sized> Serialize for DisplayAsStr<'_, T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self.0)
    }
}
