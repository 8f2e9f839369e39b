//! One field of a decoded item, without its dict: the item's serde form is
//! walked (as the dict would be built) but only the value under the asked
//! key is made a Python object, and the walk stops there.
//!
//! Every item serializes as one flat map (`offset`, `len`, then the
//! message's members: the library's prefixed form), so only the top-level
//! map's keys are compared; the value found is exactly the dict's (the same
//! serde value through the same [`to_python`]).

use std::fmt;

use pyo3::prelude::*;
use serde::ser::{
    self, Impossible, Serialize, SerializeMap, SerializeStruct, SerializeStructVariant, Serializer,
};

use crate::engine::to_python;
use crate::walk::KeyText;

/// The value of the top-level key `key` of `value`'s serde map, or `None`
/// where the map has no such key (or `value` is not a map).
pub fn field<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
    key: &str,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let mut pick = Pick {
        py,
        key,
        matched: false,
        found: None,
    };
    match value.serialize(&mut pick) {
        Ok(()) | Err(Stop::Found | Stop::NoFields) => Ok(pick.found),
        Err(Stop::Failed(err)) => Err(err),
        Err(Stop::Custom(message)) => Err(pyo3::exceptions::PyValueError::new_err(message)),
    }
}

/// Why the walk ended early.
#[derive(Debug)]
enum Stop {
    /// The key's value is in `found`: nothing after it is walked.
    Found,
    /// The value is not a map (it has no fields).
    NoFields,
    /// Making the Python value failed.
    Failed(PyErr),
    /// A `Serialize` impl failed.
    Custom(String),
}

impl fmt::Display for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Stop::Found => f.write_str("found"),
            Stop::NoFields => f.write_str("not a map"),
            Stop::Failed(err) => write!(f, "{err}"),
            Stop::Custom(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for Stop {}

impl ser::Error for Stop {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Stop::Custom(msg.to_string())
    }
}

struct Pick<'k, 'py> {
    py: Python<'py>,
    key: &'k str,
    /// The last key given to `serialize_key` was `key`.
    matched: bool,
    found: Option<Bound<'py, PyAny>>,
}

impl Pick<'_, '_> {
    fn take<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Stop> {
        self.found = Some(to_python(self.py, value).map_err(Stop::Failed)?);
        Err(Stop::Found)
    }

    fn entry<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> Result<(), Stop> {
        if key == self.key {
            self.take(value)
        } else {
            Ok(())
        }
    }
}

/// A top-level value that is not a map has no fields.
macro_rules! no_fields {
    ($($method:ident($($ty:ty),*)),* $(,)?) => {$(
        fn $method(self, $(_: $ty),*) -> Result<(), Stop> {
            Ok(())
        }
    )*};
}

impl Serializer for &mut Pick<'_, '_> {
    type Ok = ();
    type Error = Stop;
    type SerializeSeq = Impossible<(), Stop>;
    type SerializeTuple = Impossible<(), Stop>;
    type SerializeTupleStruct = Impossible<(), Stop>;
    type SerializeTupleVariant = Impossible<(), Stop>;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Self;

    no_fields! {
        serialize_bool(bool), serialize_i8(i8), serialize_i16(i16), serialize_i32(i32),
        serialize_i64(i64), serialize_u8(u8), serialize_u16(u16), serialize_u32(u32),
        serialize_u64(u64), serialize_f32(f32), serialize_f64(f64), serialize_char(char),
        serialize_str(&str), serialize_bytes(&[u8]), serialize_none(), serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), Stop> {
        value.serialize(self)
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), Stop> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<(), Stop> {
        Ok(())
    }

    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, Stop> {
        Err(Stop::NoFields)
    }

    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, Stop> {
        Err(Stop::NoFields)
    }

    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, Stop> {
        Err(Stop::NoFields)
    }

    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, Stop> {
        Err(Stop::NoFields)
    }

    fn serialize_map(self, _: Option<usize>) -> Result<Self, Stop> {
        Ok(self)
    }

    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self, Stop> {
        Ok(self)
    }

    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self, Stop> {
        Ok(self)
    }
}

impl SerializeMap for &mut Pick<'_, '_> {
    type Ok = ();
    type Error = Stop;

    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), Stop> {
        let mut rest = Rest(Some(self.key));
        key.serialize(KeyText(&mut rest))
            .map_err(|e| Stop::Custom(e.0))?;
        self.matched = rest.0 == Some("");
        Ok(())
    }

    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Stop> {
        if self.matched {
            self.take(value)
        } else {
            Ok(())
        }
    }

    fn end(self) -> Result<(), Stop> {
        Ok(())
    }
}

macro_rules! fields_are_entries {
    ($($kind:ident),*) => {$(
        impl $kind for &mut Pick<'_, '_> {
            type Ok = ();
            type Error = Stop;

            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), Stop> {
                self.entry(key, value)
            }

            fn end(self) -> Result<(), Stop> {
                Ok(())
            }
        }
    )*};
}

fields_are_entries!(SerializeStruct, SerializeStructVariant);

/// What of the wanted key a key's text has not matched yet (`None`: it
/// differs), compared as the key is written, with no copy of it.
struct Rest<'k>(Option<&'k str>);

impl fmt::Write for Rest<'_> {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        self.0 = self.0.and_then(|rest| rest.strip_prefix(text));
        Ok(())
    }
}
