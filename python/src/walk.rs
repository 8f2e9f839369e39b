//! The leaves of a value's serde form, for [`crate::columns`]: each leaf's
//! path (members joined by `.`, array elements by their index: `imu.ax`,
//! `data.3`) and its value, written into buffers a [`Walk`] reuses from one
//! frame to the next, so a frame costs no allocation once the buffers have
//! grown.

use std::fmt::{self, Write as _};

use serde::ser::{self, Impossible, Serialize};

/// One leaf value. Text is a span of the walk's (or a table's) text buffer,
/// so a cell is small and `Copy`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Cell {
    Bool(bool),
    /// An unsigned integer and its width in bytes on the wire.
    U(u64, u8),
    /// A signed integer and its width in bytes.
    I(i64, u8),
    F32(f32),
    F64(f64),
    /// Text: start and length in bytes of its span.
    Str(u32, u32),
}

/// The text of the span `start`, `len` of `texts`.
pub fn span(texts: &str, start: u32, len: u32) -> &str {
    let start = start as usize;
    texts.get(start..start + len as usize).unwrap_or("")
}

/// The leaves of one value.
#[derive(Default)]
pub struct Walk {
    /// The path of the member being walked.
    path: String,
    /// Every leaf's path, each followed by `\n`: the value's shape.
    pub names: String,
    /// Every leaf's value (`None`: `null`), in the order of `names`.
    pub cells: Vec<Option<Cell>>,
    /// The text the `Str` cells point into.
    pub texts: String,
    /// The top-level `type`, where the value has one (a span of `texts`).
    pub kind: Option<(u32, u32)>,
}

impl Walk {
    /// Walk `value`, replacing the previous value's leaves.
    pub fn walk<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        self.path.clear();
        self.names.clear();
        self.cells.clear();
        self.texts.clear();
        self.kind = None;
        value.serialize(&mut *self)
    }

    /// The text of a `Str` span.
    pub fn text(&self, start: u32, len: u32) -> &str {
        span(&self.texts, start, len)
    }

    fn leaf(&mut self, cell: Option<Cell>) -> Result<(), WalkError> {
        self.names.push_str(&self.path);
        self.names.push('\n');
        self.cells.push(cell);
        Ok(())
    }

    fn text_leaf(&mut self, text: &str) -> Result<(), WalkError> {
        let span = (self.texts.len() as u32, text.len() as u32);
        self.texts.push_str(text);
        if self.path == "type" {
            self.kind = Some(span);
        }
        self.leaf(Some(Cell::Str(span.0, span.1)))
    }

    /// Walk `value` under the member or index `segment`.
    fn under<T: Serialize + ?Sized>(
        &mut self,
        segment: Segment<'_>,
        value: &T,
    ) -> Result<(), WalkError> {
        let len = self.path.len();
        if len > 0 {
            self.path.push('.');
        }
        match segment {
            Segment::Name(name) => self.path.push_str(name),
            Segment::Index(i) => write!(self.path, "{i}").map_err(|e| WalkError(e.to_string()))?,
        }
        let result = value.serialize(&mut *self);
        self.path.truncate(len);
        result
    }
}

/// Why a value could not be walked.
#[derive(Debug)]
pub struct WalkError(pub String);

impl fmt::Display for WalkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for WalkError {}

impl ser::Error for WalkError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        WalkError(msg.to_string())
    }
}

/// A step of a path: a member's name or an element's index.
#[derive(Clone, Copy)]
enum Segment<'s> {
    Name(&'s str),
    Index(usize),
}

macro_rules! leaves {
    ($($method:ident($ty:ty) => $cell:expr),* $(,)?) => {$(
        fn $method(self, v: $ty) -> Result<(), WalkError> {
            #[allow(clippy::redundant_closure_call)]
            self.leaf(Some(($cell)(v)))
        }
    )*};
}

impl<'a> ser::Serializer for &'a mut Walk {
    type Ok = ();
    type Error = WalkError;
    type SerializeSeq = Elements<'a>;
    type SerializeTuple = Elements<'a>;
    type SerializeTupleStruct = Elements<'a>;
    type SerializeTupleVariant = Impossible<(), WalkError>;
    type SerializeMap = Members<'a>;
    type SerializeStruct = Members<'a>;
    type SerializeStructVariant = Members<'a>;

    /// Floats as numbers (the library writes a non-finite f32 as text
    /// only for a human-readable format).
    fn is_human_readable(&self) -> bool {
        false
    }

    leaves! {
        serialize_bool(bool) => Cell::Bool,
        serialize_i8(i8) => |v| Cell::I(i64::from(v), 1),
        serialize_i16(i16) => |v| Cell::I(i64::from(v), 2),
        serialize_i32(i32) => |v| Cell::I(i64::from(v), 4),
        serialize_i64(i64) => |v| Cell::I(v, 8),
        serialize_u8(u8) => |v| Cell::U(u64::from(v), 1),
        serialize_u16(u16) => |v| Cell::U(u64::from(v), 2),
        serialize_u32(u32) => |v| Cell::U(u64::from(v), 4),
        serialize_u64(u64) => |v| Cell::U(v, 8),
        serialize_f32(f32) => Cell::F32,
        serialize_f64(f64) => Cell::F64,
    }

    fn serialize_char(self, v: char) -> Result<(), WalkError> {
        self.text_leaf(v.encode_utf8(&mut [0; 4]))
    }

    fn serialize_str(self, v: &str) -> Result<(), WalkError> {
        self.text_leaf(v)
    }

    fn serialize_bytes(self, v: &[u8]) -> Result<(), WalkError> {
        for (i, byte) in v.iter().enumerate() {
            self.under(Segment::Index(i), byte)?;
        }
        Ok(())
    }

    fn serialize_none(self) -> Result<(), WalkError> {
        self.leaf(None)
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), WalkError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<(), WalkError> {
        self.leaf(None)
    }

    fn serialize_unit_struct(self, _: &'static str) -> Result<(), WalkError> {
        self.leaf(None)
    }

    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<(), WalkError> {
        self.text_leaf(variant)
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), WalkError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), WalkError> {
        self.under(Segment::Name(variant), value)
    }

    fn serialize_seq(self, _: Option<usize>) -> Result<Elements<'a>, WalkError> {
        Ok(Elements {
            walk: self,
            next: 0,
        })
    }

    fn serialize_tuple(self, _: usize) -> Result<Elements<'a>, WalkError> {
        self.serialize_seq(None)
    }

    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Elements<'a>, WalkError> {
        self.serialize_seq(None)
    }

    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, WalkError> {
        Err(WalkError("a tuple variant has no columns".into()))
    }

    fn serialize_map(self, _: Option<usize>) -> Result<Members<'a>, WalkError> {
        Ok(Members {
            walk: self,
            parent: None,
        })
    }

    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Members<'a>, WalkError> {
        self.serialize_map(None)
    }

    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Members<'a>, WalkError> {
        self.serialize_map(None)
    }
}

/// A sequence's elements, under their indices.
pub struct Elements<'a> {
    walk: &'a mut Walk,
    next: usize,
}

macro_rules! elements {
    ($($kind:ident :: $method:ident),*) => {$(
        impl ser::$kind for Elements<'_> {
            type Ok = ();
            type Error = WalkError;

            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
                self.next += 1;
                self.walk.under(Segment::Index(self.next - 1), value)
            }

            fn end(self) -> Result<(), WalkError> {
                Ok(())
            }
        }
    )*};
}

elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field
);

/// A map's or struct's members, under their names.
pub struct Members<'a> {
    walk: &'a mut Walk,
    /// The path's length before the key being written (between a map's
    /// `serialize_key` and `serialize_value`).
    parent: Option<usize>,
}

impl ser::SerializeMap for Members<'_> {
    type Ok = ();
    type Error = WalkError;

    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), WalkError> {
        let path = &mut self.walk.path;
        self.parent = Some(path.len());
        if !path.is_empty() {
            path.push('.');
        }
        key.serialize(KeyText(path))
    }

    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        let parent = self
            .parent
            .take()
            .ok_or_else(|| WalkError("a map value without its key".into()))?;
        let result = value.serialize(&mut *self.walk);
        self.walk.path.truncate(parent);
        result
    }

    fn end(self) -> Result<(), WalkError> {
        Ok(())
    }
}

macro_rules! members {
    ($($kind:ident),*) => {$(
        impl ser::$kind for Members<'_> {
            type Ok = ();
            type Error = WalkError;

            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), WalkError> {
                self.walk.under(Segment::Name(key), value)
            }

            fn end(self) -> Result<(), WalkError> {
                Ok(())
            }
        }
    )*};
}

members!(SerializeStruct, SerializeStructVariant);

/// Writes a map key (a name, or a number) into `W`: the end of a walk's
/// path, or a field read's comparison with the key it wants.
pub struct KeyText<'p, W: fmt::Write>(pub &'p mut W);

fn not_a_name<T>() -> Result<T, WalkError> {
    Err(WalkError("a map key that is not a name".into()))
}

macro_rules! numeric_keys {
    ($($method:ident($ty:ty)),* $(,)?) => {$(
        fn $method(self, v: $ty) -> Result<(), WalkError> {
            write!(self.0, "{v}").map_err(|e| WalkError(e.to_string()))
        }
    )*};
}

impl<W: fmt::Write> ser::Serializer for KeyText<'_, W> {
    type Ok = ();
    type Error = WalkError;
    type SerializeSeq = Impossible<(), WalkError>;
    type SerializeTuple = Impossible<(), WalkError>;
    type SerializeTupleStruct = Impossible<(), WalkError>;
    type SerializeTupleVariant = Impossible<(), WalkError>;
    type SerializeMap = Impossible<(), WalkError>;
    type SerializeStruct = Impossible<(), WalkError>;
    type SerializeStructVariant = Impossible<(), WalkError>;

    fn serialize_str(self, v: &str) -> Result<(), WalkError> {
        self.0.write_str(v).map_err(|e| WalkError(e.to_string()))
    }

    numeric_keys! {
        serialize_i8(i8), serialize_i16(i16), serialize_i32(i32), serialize_i64(i64),
        serialize_u8(u8), serialize_u16(u16), serialize_u32(u32), serialize_u64(u64),
        serialize_char(char), serialize_bool(bool),
    }

    fn serialize_f32(self, _: f32) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_f64(self, _: f64) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_bytes(self, _: &[u8]) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_none(self) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), WalkError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_unit_struct(self, _: &'static str) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<(), WalkError> {
        self.0
            .write_str(variant)
            .map_err(|e| WalkError(e.to_string()))
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), WalkError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<(), WalkError> {
        not_a_name()
    }

    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, WalkError> {
        not_a_name()
    }

    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, WalkError> {
        not_a_name()
    }

    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, WalkError> {
        not_a_name()
    }

    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, WalkError> {
        not_a_name()
    }

    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, WalkError> {
        not_a_name()
    }

    fn serialize_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStruct, WalkError> {
        not_a_name()
    }

    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, WalkError> {
        not_a_name()
    }
}
