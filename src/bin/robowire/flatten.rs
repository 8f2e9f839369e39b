//! A row of cells from any value's `serde` form: nested fields become
//! columns named by their path (`imu.ax`, `uwb.0`), `None` an empty cell.
//! The CSV tables and the plots read frames through this walk, so neither
//! knows any message type; it reuses its buffers, so a row costs no
//! allocation once the first frame of its shape is seen.

use serde::ser::{self, Impossible, Serialize};
use std::fmt::{self, Write as _};

/// One flattened value: the column names and the cells, each joined by
/// commas and CSV-quoted where needed, and the value's kind (its top-level
/// `type`, or `rejected-` and its `error`).
#[derive(Default, Clone)]
pub struct Row {
    /// The header line: column names joined by commas.
    pub names: String,
    /// The cells, joined by commas.
    pub cells: Vec<u8>,
    /// Where each cell starts and ends in `cells`, in column order.
    spans: Vec<(usize, usize)>,
    /// The value of the top-level `type` field, if any.
    pub type_name: String,
    /// The value of the top-level `error` field, if any.
    pub error_name: String,
    /// The path of the field being walked.
    path: String,
    /// Whether to record cells (false: only the top-level names).
    cells_wanted: bool,
}

impl Row {
    /// Start a new row.
    pub fn clear(&mut self) {
        self.names.clear();
        self.cells.clear();
        self.spans.clear();
        self.type_name.clear();
        self.error_name.clear();
        self.path.clear();
    }

    /// Add a cell named `name` holding `value` (text that needs no quotes).
    pub fn push_number(&mut self, name: &str, value: impl fmt::Display) {
        use std::io::Write as _;
        let saved = std::mem::replace(&mut self.path, name.to_owned());
        self.cells_wanted = true;
        self.cell_with(|cells| {
            let _ = write!(cells, "{value}");
        });
        self.path = saved;
    }

    /// Add a cell named `name` holding `cell`, CSV text as [`cells`](Row::cells)
    /// holds it (quoted where needed).
    pub fn push_cell(&mut self, name: &str, cell: &[u8]) {
        let saved = std::mem::replace(&mut self.path, name.to_owned());
        self.cells_wanted = true;
        self.cell_with(|cells| cells.extend_from_slice(cell));
        self.path = saved;
    }

    /// Each cell, as CSV text, in column order.
    pub fn cell_texts(&self) -> impl Iterator<Item = &[u8]> + '_ {
        self.spans
            .iter()
            .map(|&(start, end)| &self.cells[start..end])
    }

    /// Walk `value` into the row, after any cells already pushed.
    pub fn walk<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        self.cells_wanted = true;
        self.path.clear();
        value.serialize(Walker {
            row: self,
            depth: 0,
        })
    }

    /// Read only the top-level `type` and `error` of `value` (the cells are
    /// not formatted).
    pub fn names_of<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        self.clear();
        self.cells_wanted = false;
        value.serialize(Walker {
            row: self,
            depth: 0,
        })
    }

    /// The table a value belongs to: its `type`, or `rejected-ERROR`.
    pub fn kind(&self) -> String {
        if self.type_name.is_empty() {
            format!("rejected-{}", self.error_name)
        } else {
            self.type_name.clone()
        }
    }

    /// Whether [`kind`](Row::kind) is `kind`, without building it.
    pub fn is_kind(&self, kind: &str) -> bool {
        if self.type_name.is_empty() {
            kind.strip_prefix("rejected-") == Some(self.error_name.as_str())
        } else {
            kind == self.type_name
        }
    }

    /// The column names, unquoted.
    pub fn columns(&self) -> Vec<String> {
        columns(&self.names)
    }

    /// The cell of the column `name`, as CSV text, if the row has it.
    #[cfg_attr(not(feature = "cli-plot"), allow(dead_code))]
    pub fn cell(&self, name: &str) -> Option<&str> {
        let i = self.names.split(',').position(|n| n == name)?;
        let &(start, end) = self.spans.get(i)?;
        std::str::from_utf8(&self.cells[start..end]).ok()
    }

    fn cell_with(&mut self, write: impl FnOnce(&mut Vec<u8>)) {
        if !self.names.is_empty() {
            self.names.push(',');
            self.cells.push(b',');
        }
        if needs_quotes(&self.path) {
            self.names.push_str(&quoted(&self.path));
        } else {
            self.names.push_str(&self.path);
        }
        let start = self.cells.len();
        write(&mut self.cells);
        self.spans.push((start, self.cells.len()));
    }

    fn text(&mut self, depth: usize, value: &str) {
        if depth == 1 && self.path == "type" {
            value.clone_into(&mut self.type_name);
        } else if depth == 1 && self.path == "error" {
            value.clone_into(&mut self.error_name);
        }
        if self.cells_wanted {
            self.cell_with(|cells| {
                if needs_quotes(value) {
                    cells.extend_from_slice(quoted(value).as_bytes());
                } else {
                    cells.extend_from_slice(value.as_bytes());
                }
            });
        }
    }
}

/// The column names of header line `names`, unquoted.
pub fn columns(names: &str) -> Vec<String> {
    let mut columns = vec![String::new()];
    let mut quoted = false;
    let mut chars = names.chars().peekable();
    while let Some(c) = chars.next() {
        let column = columns.last_mut().expect("one column at least");
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                column.push('"');
            }
            '"' => quoted = !quoted,
            ',' if !quoted => columns.push(String::new()),
            c => column.push(c),
        }
    }
    columns
}

/// `text` as a CSV field: quoted when it must be.
pub fn csv_field(text: &str) -> std::borrow::Cow<'_, str> {
    if needs_quotes(text) {
        quoted(text).into()
    } else {
        text.into()
    }
}

/// Whether `text` must be quoted as a CSV field: it holds a comma, a quote
/// or a line break.
fn needs_quotes(text: &str) -> bool {
    text.bytes()
        .any(|b| matches!(b, b',' | b'"' | b'\n' | b'\r'))
}

/// `text` as a quoted CSV field, quotes doubled.
fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// Why a value could not be walked (a serializer error of the value's own).
#[derive(Debug)]
pub struct WalkError(String);

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

struct Walker<'r> {
    row: &'r mut Row,
    depth: usize,
}

impl<'r> Walker<'r> {
    /// A number (or a boolean) in serde_json's shortest form, which reads
    /// back as the same value.
    fn number(self, value: impl Serialize) -> Result<(), WalkError> {
        if self.row.cells_wanted {
            self.row.cell_with(|cells| {
                // Writing a number into a Vec cannot fail.
                let _ = serde_json::to_writer(cells, &value);
            });
        }
        Ok(())
    }

    /// A float: non-finite ones (which JSON cannot hold) as `inf`, `-inf`, `NaN`.
    fn float<F: Serialize + fmt::Display>(self, value: F, finite: bool) -> Result<(), WalkError> {
        if finite {
            self.number(value)
        } else {
            ser::Serializer::serialize_str(self, &value.to_string())
        }
    }

    fn nested(self) -> Nested<'r> {
        Nested {
            row: self.row,
            depth: self.depth + 1,
            index: 0,
            key_len: None,
        }
    }
}

/// A sequence, map or struct being walked: its fields go one level down.
struct Nested<'r> {
    row: &'r mut Row,
    depth: usize,
    index: usize,
    /// Length of the path before the current map key, between a key and its value.
    key_len: Option<usize>,
}

impl Nested<'_> {
    /// Walk `value` as the field `name` (skipped when only names are wanted
    /// and it cannot be the top-level `type` or `error`).
    fn field<T: Serialize + ?Sized>(&mut self, name: &str, value: &T) -> Result<(), WalkError> {
        if !self.row.cells_wanted && (self.depth > 1 || !matches!(name, "type" | "error")) {
            return Ok(());
        }
        let len = self.push(name);
        let walked = value.serialize(Walker {
            row: self.row,
            depth: self.depth,
        });
        self.row.path.truncate(len);
        walked
    }

    fn push(&mut self, name: &str) -> usize {
        let len = self.row.path.len();
        if len > 0 {
            self.row.path.push('.');
        }
        self.row.path.push_str(name);
        len
    }

    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        let index = self.index;
        self.index += 1;
        if !self.row.cells_wanted {
            return Ok(());
        }
        let len = self.row.path.len();
        if len > 0 {
            self.row.path.push('.');
        }
        match u8::try_from(index) {
            // Most arrays are short: no formatting machinery for them.
            Ok(digit @ 0..=9) => self.row.path.push(char::from(b'0' + digit)),
            _ => {
                let _ = write!(self.row.path, "{index}");
            }
        }
        let walked = value.serialize(Walker {
            row: self.row,
            depth: self.depth,
        });
        self.row.path.truncate(len);
        walked
    }
}

/// The sequence-like compounds: each element is the next index.
macro_rules! elements {
    ($($trait:ident::$method:ident),*) => {$(
        impl ser::$trait for Nested<'_> {
            type Ok = ();
            type Error = WalkError;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
                self.element(value)
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
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

/// The struct-like compounds: each field is a named column.
macro_rules! fields {
    ($($trait:ident),*) => {$(
        impl ser::$trait for Nested<'_> {
            type Ok = ();
            type Error = WalkError;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), WalkError> {
                self.field(key, value)
            }
            fn end(self) -> Result<(), WalkError> {
                Ok(())
            }
        }
    )*};
}

fields!(SerializeStruct, SerializeStructVariant);

impl ser::SerializeMap for Nested<'_> {
    type Ok = ();
    type Error = WalkError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), WalkError> {
        // The key waits in the path for its value.
        let len = self.row.path.len();
        if len > 0 {
            self.row.path.push('.');
        }
        self.key_len = Some(len);
        key.serialize(KeyName(&mut self.row.path))
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        let len = self.key_len.take().unwrap_or(self.row.path.len());
        let name_start = if len == 0 { 0 } else { len + 1 };
        let top_name = matches!(&self.row.path[name_start..], "type" | "error");
        let walked = if self.row.cells_wanted || (self.depth == 1 && top_name) {
            value.serialize(Walker {
                row: self.row,
                depth: self.depth,
            })
        } else {
            Ok(())
        };
        self.row.path.truncate(len);
        walked
    }
    fn end(self) -> Result<(), WalkError> {
        Ok(())
    }
}

impl<'r> ser::Serializer for Walker<'r> {
    type Ok = ();
    type Error = WalkError;
    type SerializeSeq = Nested<'r>;
    type SerializeTuple = Nested<'r>;
    type SerializeTupleStruct = Nested<'r>;
    type SerializeTupleVariant = Nested<'r>;
    type SerializeMap = Nested<'r>;
    type SerializeStruct = Nested<'r>;
    type SerializeStructVariant = Nested<'r>;

    fn serialize_bool(self, v: bool) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_i8(self, v: i8) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_i16(self, v: i16) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_i32(self, v: i32) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_i64(self, v: i64) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_u8(self, v: u8) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_u16(self, v: u16) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_u32(self, v: u32) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_u64(self, v: u64) -> Result<(), WalkError> {
        self.number(v)
    }
    fn serialize_f32(self, v: f32) -> Result<(), WalkError> {
        self.float(v, v.is_finite())
    }
    fn serialize_f64(self, v: f64) -> Result<(), WalkError> {
        self.float(v, v.is_finite())
    }
    fn serialize_char(self, v: char) -> Result<(), WalkError> {
        self.serialize_str(v.encode_utf8(&mut [0; 4]))
    }
    fn serialize_str(self, v: &str) -> Result<(), WalkError> {
        self.row.text(self.depth, v);
        Ok(())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<(), WalkError> {
        let mut text = String::with_capacity(v.len() * 2);
        for byte in v {
            let _ = write!(text, "{byte:02x}");
        }
        self.serialize_str(&text)
    }
    fn serialize_none(self) -> Result<(), WalkError> {
        if self.row.cells_wanted {
            self.row.cell_with(|_| {});
        }
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), WalkError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), WalkError> {
        self.serialize_none()
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<(), WalkError> {
        self.serialize_none()
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<(), WalkError> {
        self.serialize_str(variant)
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
        self.nested().field(variant, value)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Nested<'r>, WalkError> {
        Ok(self.nested())
    }
    fn serialize_tuple(self, _: usize) -> Result<Nested<'r>, WalkError> {
        Ok(self.nested())
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Nested<'r>, WalkError> {
        Ok(self.nested())
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Nested<'r>, WalkError> {
        let mut nested = self.nested();
        nested.push(variant);
        Ok(nested)
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Nested<'r>, WalkError> {
        Ok(self.nested())
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Nested<'r>, WalkError> {
        Ok(self.nested())
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Nested<'r>, WalkError> {
        let mut nested = self.nested();
        nested.push(variant);
        Ok(nested)
    }
}

/// A map key as text (strings, characters and integers, as JSON has them).
struct KeyName<'s>(&'s mut String);

macro_rules! key_number {
    ($($method:ident: $ty:ty),*) => {$(
        fn $method(self, v: $ty) -> Result<(), WalkError> {
            let _ = write!(self.0, "{v}");
            Ok(())
        }
    )*};
}

impl ser::Serializer for KeyName<'_> {
    type Ok = ();
    type Error = WalkError;
    type SerializeSeq = Impossible<(), WalkError>;
    type SerializeTuple = Impossible<(), WalkError>;
    type SerializeTupleStruct = Impossible<(), WalkError>;
    type SerializeTupleVariant = Impossible<(), WalkError>;
    type SerializeMap = Impossible<(), WalkError>;
    type SerializeStruct = Impossible<(), WalkError>;
    type SerializeStructVariant = Impossible<(), WalkError>;

    key_number!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
        serialize_i64: i64, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
        serialize_u64: u64, serialize_f32: f32, serialize_f64: f64, serialize_char: char,
        serialize_str: &str);

    fn serialize_bytes(self, _: &[u8]) -> Result<(), WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_none(self) -> Result<(), WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), WalkError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<(), WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<(), WalkError> {
        self.0.push_str(variant);
        Ok(())
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
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStruct, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, WalkError> {
        Err(ser::Error::custom("a map key must be text"))
    }
}
