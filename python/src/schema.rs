//! The JSON-lines schema in Python objects: a thin adapter in front of
//! pythonize's serializer, so that a value pythonizes to the tool's line of
//! that value with Python's own values.
//!
//! pythonize already maps maps to dicts, sequences to lists, integers to
//! ints, strings to strs and `None` to `None`. This adapter changes, recursively:
//!
//! * a tuple (how serde writes a fixed-size array such as `uwb: [u16; 4]`) is
//!   a list, as in JSON, not a Python tuple;
//! * an `f32` is the `float` of exactly its value (`0.10000000149011612` for
//!   the wire's `0.1f32`), infinities and NaNs included: the adapter says it
//!   is not human-readable, so the library writes every `f32` as a number
//!   rather than as the JSON text's `"inf"` or `"nan:0x7fc00000"`;
//! * a byte string is a list of ints, as serde_json writes it, not `bytes`.

use serde::ser::{
    Serialize, SerializeMap, SerializeSeq, SerializeStruct, SerializeStructVariant, SerializeTuple,
    SerializeTupleStruct, SerializeTupleVariant, Serializer,
};

/// A value serialized through [`Schema`].
pub struct Adapt<'a, T: ?Sized>(pub &'a T);

impl<T: Serialize + ?Sized> Serialize for Adapt<'_, T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(Schema(serializer))
    }
}

/// The adapter around a serializer (or one of its compound serializers).
pub struct Schema<S>(pub S);

/// `x` as a Python `float`: its exact value, and for a NaN its sign and
/// payload bit for bit (`f64::from` may quieten a signalling NaN).
pub fn exact_f64(x: f32) -> f64 {
    if !x.is_nan() {
        return f64::from(x);
    }
    let bits = x.to_bits();
    let sign = u64::from(bits >> 31) << 63;
    f64::from_bits(sign | 0x7ff0_0000_0000_0000 | (u64::from(bits & 0x007f_ffff) << 29))
}

macro_rules! forward {
    ($($method:ident($($arg:ident: $ty:ty),*)),* $(,)?) => {$(
        fn $method(self, $($arg: $ty),*) -> Result<S::Ok, S::Error> {
            self.0.$method($($arg),*)
        }
    )*};
}

impl<S: Serializer> Serializer for Schema<S> {
    type Ok = S::Ok;
    type Error = S::Error;
    type SerializeSeq = Schema<S::SerializeSeq>;
    type SerializeTuple = Schema<S::SerializeSeq>;
    type SerializeTupleStruct = Schema<S::SerializeSeq>;
    type SerializeTupleVariant = Schema<S::SerializeTupleVariant>;
    type SerializeMap = Schema<S::SerializeMap>;
    type SerializeStruct = Schema<S::SerializeStruct>;
    type SerializeStructVariant = Schema<S::SerializeStructVariant>;

    forward! {
        serialize_bool(v: bool), serialize_i8(v: i8), serialize_i16(v: i16),
        serialize_i32(v: i32), serialize_i64(v: i64), serialize_i128(v: i128),
        serialize_u8(v: u8), serialize_u16(v: u16), serialize_u32(v: u32),
        serialize_u64(v: u64), serialize_u128(v: u128), serialize_f64(v: f64),
        serialize_char(v: char), serialize_str(v: &str), serialize_none(),
        serialize_unit(), serialize_unit_struct(name: &'static str),
        serialize_unit_variant(name: &'static str, index: u32, variant: &'static str),
    }

    fn serialize_f32(self, v: f32) -> Result<S::Ok, S::Error> {
        self.0.serialize_f64(exact_f64(v))
    }

    fn serialize_bytes(self, v: &[u8]) -> Result<S::Ok, S::Error> {
        let mut seq = self.0.serialize_seq(Some(v.len()))?;
        for byte in v {
            seq.serialize_element(byte)?;
        }
        seq.end()
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<S::Ok, S::Error> {
        self.0.serialize_some(&Adapt(value))
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        name: &'static str,
        value: &T,
    ) -> Result<S::Ok, S::Error> {
        self.0.serialize_newtype_struct(name, &Adapt(value))
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        name: &'static str,
        index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<S::Ok, S::Error> {
        self.0
            .serialize_newtype_variant(name, index, variant, &Adapt(value))
    }

    fn serialize_seq(self, len: Option<usize>) -> Result<Self::SerializeSeq, S::Error> {
        self.0.serialize_seq(len).map(Schema)
    }

    fn serialize_tuple(self, len: usize) -> Result<Self::SerializeTuple, S::Error> {
        self.0.serialize_seq(Some(len)).map(Schema)
    }

    fn serialize_tuple_struct(
        self,
        _name: &'static str,
        len: usize,
    ) -> Result<Self::SerializeTupleStruct, S::Error> {
        self.0.serialize_seq(Some(len)).map(Schema)
    }

    fn serialize_tuple_variant(
        self,
        name: &'static str,
        index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Self::SerializeTupleVariant, S::Error> {
        self.0
            .serialize_tuple_variant(name, index, variant, len)
            .map(Schema)
    }

    fn serialize_map(self, len: Option<usize>) -> Result<Self::SerializeMap, S::Error> {
        self.0.serialize_map(len).map(Schema)
    }

    fn serialize_struct(
        self,
        name: &'static str,
        len: usize,
    ) -> Result<Self::SerializeStruct, S::Error> {
        self.0.serialize_struct(name, len).map(Schema)
    }

    fn serialize_struct_variant(
        self,
        name: &'static str,
        index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Self::SerializeStructVariant, S::Error> {
        self.0
            .serialize_struct_variant(name, index, variant, len)
            .map(Schema)
    }

    /// Not human-readable: the library then writes an `f32` as itself, never
    /// as the JSON text's `"inf"` or `"nan:0x…"` strings.
    fn is_human_readable(&self) -> bool {
        false
    }
}

/// Sequence-like compound serializers: elements go through the adapter.
macro_rules! elements {
    ($($kind:ident :: $method:ident),* $(,)?) => {$(
        impl<S: SerializeSeq> $kind for Schema<S> {
            type Ok = S::Ok;
            type Error = S::Error;

            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), S::Error> {
                self.0.serialize_element(&Adapt(value))
            }

            fn end(self) -> Result<S::Ok, S::Error> {
                self.0.end()
            }
        }
    )*};
}

elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
);

impl<S: SerializeTupleVariant> SerializeTupleVariant for Schema<S> {
    type Ok = S::Ok;
    type Error = S::Error;

    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), S::Error> {
        self.0.serialize_field(&Adapt(value))
    }

    fn end(self) -> Result<S::Ok, S::Error> {
        self.0.end()
    }
}

impl<S: SerializeMap> SerializeMap for Schema<S> {
    type Ok = S::Ok;
    type Error = S::Error;

    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), S::Error> {
        self.0.serialize_key(&Adapt(key))
    }

    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), S::Error> {
        self.0.serialize_value(&Adapt(value))
    }

    fn serialize_entry<K: Serialize + ?Sized, V: Serialize + ?Sized>(
        &mut self,
        key: &K,
        value: &V,
    ) -> Result<(), S::Error> {
        self.0.serialize_entry(&Adapt(key), &Adapt(value))
    }

    fn end(self) -> Result<S::Ok, S::Error> {
        self.0.end()
    }
}

macro_rules! fields {
    ($($kind:ident),*) => {$(
        impl<S: $kind> $kind for Schema<S> {
            type Ok = S::Ok;
            type Error = S::Error;

            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), S::Error> {
                self.0.serialize_field(key, &Adapt(value))
            }

            fn skip_field(&mut self, key: &'static str) -> Result<(), S::Error> {
                self.0.skip_field(key)
            }

            fn end(self) -> Result<S::Ok, S::Error> {
                self.0.end()
            }
        }
    )*};
}

fields!(SerializeStruct, SerializeStructVariant);
