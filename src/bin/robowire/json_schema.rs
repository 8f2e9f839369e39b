//! The JSON Schema of an MCAP channel, from the first event on it: its
//! shape as the library serializes it (every member, each integer with the
//! Rust type it has on the wire, so its range is the wire's), and what the
//! protocol's [`FieldTable`] declares (a description and a unit per field,
//! `null` for no reading, a narrower range, the names a string takes, which
//! members only some frames carry). Every member the first event has is
//! `required` unless the table calls it optional; members the first event
//! lacks (another layout's, a quirk's) are allowed, as the schema does not
//! forbid members it does not list.

use crate::flatten::WalkError;
use robowire::units::{FieldInfo, FieldTable, STREAM_FIELDS};
use serde::ser::{self, Impossible, Serialize};
use serde_json::{json, Map, Value};

/// The info of field `path` of a `kind` frame: the protocol's, the
/// stream's (`offset`, `len`) or the tool's (`t`).
pub fn field_info(fields: &FieldTable, kind: &str, path: &str) -> Option<&'static FieldInfo> {
    if path == "t" {
        return Some(&TIME);
    }
    fields
        .get(kind, path)
        .or_else(|| STREAM_FIELDS.get(kind, path))
}

/// The member the tool adds to a timed event.
static TIME: FieldInfo =
    FieldInfo::new("Receive time of the frame's last byte, seconds since the start of the run.")
        .unit(robowire::units::Unit::Second);

/// What an `f32` that JSON cannot hold is written as.
const NON_FINITE: &str = "^(inf|-inf|nan:0x[0-9a-f]{8})$";

/// The schema of channel `kind` (a message `type`, or `rejected`) whose
/// first event is `event`, titled `kind`.
pub fn channel_schema<T: Serialize + ?Sized>(
    event: &T,
    kind: &str,
    fields: &FieldTable,
    timed: bool,
) -> Result<Value, String> {
    let shape = event.serialize(ShapeOf).map_err(|e| e.to_string())?;
    let context = Context {
        kind,
        fields,
        rejected: kind == "rejected",
    };
    let mut schema = context.schema(&shape, "");
    if timed {
        if let Some(properties) = schema["properties"].as_object_mut() {
            let mut with_time = Map::new();
            with_time.insert(
                "t".to_owned(),
                context.annotate(json!({"type": "number"}), Some(&TIME)),
            );
            with_time.append(properties);
            *properties = with_time;
        }
        if let Some(required) = schema["required"].as_array_mut() {
            required.insert(0, Value::from("t"));
        }
    }
    schema["title"] = Value::from(kind);
    schema["$schema"] = Value::from("https://json-schema.org/draft/2020-12/schema");
    Ok(schema)
}

/// The value shape of one serialized event.
#[derive(Debug, Clone, PartialEq)]
enum Shape {
    /// An unsigned integer of this many bits.
    Unsigned(u32),
    /// A signed integer of this many bits.
    Signed(u32),
    Float,
    Bool,
    Text(String),
    Null,
    List(Vec<Shape>),
    Object(Vec<(String, Shape)>),
}

struct Context<'a> {
    kind: &'a str,
    fields: &'a FieldTable,
    /// The rejections' channel: its events are of several kinds.
    rejected: bool,
}

impl Context<'_> {
    fn info(&self, path: &str) -> Option<&'static FieldInfo> {
        if self.rejected {
            return None;
        }
        field_info(self.fields, self.kind, path)
    }

    fn schema(&self, shape: &Shape, path: &str) -> Value {
        let info = self.info(path);
        let schema = match shape {
            Shape::Unsigned(bits) => integer(0, (1i128 << bits) - 1, info),
            Shape::Signed(bits) => integer(-(1i128 << (bits - 1)), (1i128 << (bits - 1)) - 1, info),
            Shape::Float => json!({"type": ["number", "string"], "pattern": NON_FINITE}),
            Shape::Bool => json!({"type": "boolean"}),
            Shape::Text(text) if path == "type" => json!({"const": text}),
            Shape::Text(_) => match info {
                Some(info) if !info.names.is_empty() => json!({"enum": info.names}),
                _ => json!({"type": "string"}),
            },
            // Null in the first event: a reading's range when the table
            // gives one, otherwise nothing is known of it.
            Shape::Null => match info.and_then(|i| i.range) {
                Some((min, max)) => json!({"type": "integer", "minimum": min, "maximum": max}),
                None => json!({}),
            },
            Shape::List(items) => {
                let mut schemas: Vec<Value> = Vec::new();
                for item in items {
                    let item = self.schema(item, &join(path, "0"));
                    if !schemas.contains(&item) {
                        schemas.push(item);
                    }
                }
                match schemas.len() {
                    0 => json!({"type": "array"}),
                    1 => json!({"type": "array", "items": schemas.remove(0)}),
                    _ => json!({"type": "array", "items": {"anyOf": schemas}}),
                }
            }
            Shape::Object(members) => {
                let mut properties = Map::new();
                let mut required = Vec::new();
                let by_type = info.is_some_and(|i| i.by_type);
                for (name, member) in members {
                    let member_path = join(path, name);
                    let optional = by_type || self.info(&member_path).is_some_and(|i| i.optional);
                    let always = !self.rejected || matches!(name.as_str(), "offset" | "error");
                    if always && !optional {
                        required.push(Value::from(name.as_str()));
                    }
                    properties.insert(name.clone(), self.schema(member, &member_path));
                }
                json!({"type": "object", "properties": properties, "required": required})
            }
        };
        let schema = match info {
            Some(info) if info.or_number && !matches!(shape, Shape::List(_)) => {
                let number = match shape {
                    Shape::Unsigned(_) | Shape::Signed(_) => schema,
                    _ => json!({"type": "integer"}),
                };
                json!({"anyOf": [{"enum": info.names}, number]})
            }
            _ => schema,
        };
        let schema = match info {
            Some(info) if info.no_reading => nullable(schema),
            _ => schema,
        };
        self.annotate(schema, info)
    }

    /// `schema` with the field's description and unit.
    fn annotate(&self, mut schema: Value, info: Option<&FieldInfo>) -> Value {
        let Some(info) = info else {
            return schema;
        };
        let mut description = info.doc.to_owned();
        if let Some(unit) = info.unit {
            description.push_str(&format!(" Unit: {unit}."));
            schema["unit"] = Value::from(unit.symbol());
        }
        if info.no_reading {
            description.push_str(" null: no reading.");
        }
        schema["description"] = Value::from(description);
        schema
    }
}

/// An integer schema from `min` to `max`, narrowed to the table's range.
fn integer(min: i128, max: i128, info: Option<&FieldInfo>) -> Value {
    let (min, max) = match info.and_then(|i| i.range) {
        Some((lo, hi)) => (min.max(i128::from(lo)), max.min(i128::from(hi))),
        None => (min, max),
    };
    json!({"type": "integer", "minimum": number(min), "maximum": number(max)})
}

/// An integer of at most 64 bits as a JSON number.
fn number(n: i128) -> Value {
    match (i64::try_from(n), u64::try_from(n)) {
        (Ok(n), _) => Value::from(n),
        (_, Ok(n)) => Value::from(n),
        _ => Value::Null,
    }
}

/// `schema`, or `null`.
fn nullable(mut schema: Value) -> Value {
    match schema.get_mut("type") {
        Some(Value::String(kind)) => {
            let kind = kind.clone();
            schema["type"] = json!([kind, "null"]);
            schema
        }
        Some(Value::Array(kinds)) => {
            kinds.push(Value::from("null"));
            schema
        }
        _ => json!({"anyOf": [schema, {"type": "null"}]}),
    }
}

fn join(path: &str, member: &str) -> String {
    if path.is_empty() {
        member.to_owned()
    } else {
        format!("{path}.{member}")
    }
}

// ----------------------------------------------------------- the shape walk

/// A serializer that keeps the shape of a value: the library writes each
/// `f32` as a number to a serializer that is not human-readable, so the
/// shape tells floats from strings.
struct ShapeOf;

/// A sequence or map being walked.
struct Compound {
    items: Vec<Shape>,
    members: Vec<(String, Shape)>,
    key: Option<String>,
    is_map: bool,
}

impl Compound {
    fn new(is_map: bool) -> Compound {
        Compound {
            items: Vec::new(),
            members: Vec::new(),
            key: None,
            is_map,
        }
    }

    fn done(self) -> Shape {
        if self.is_map {
            Shape::Object(self.members)
        } else {
            Shape::List(self.items)
        }
    }
}

macro_rules! shape_number {
    ($($method:ident($ty:ty) => $shape:expr),* $(,)?) => {$(
        fn $method(self, _: $ty) -> Result<Shape, WalkError> {
            Ok($shape)
        }
    )*};
}

impl ser::Serializer for ShapeOf {
    type Ok = Shape;
    type Error = WalkError;
    type SerializeSeq = Compound;
    type SerializeTuple = Compound;
    type SerializeTupleStruct = Compound;
    type SerializeTupleVariant = Impossible<Shape, WalkError>;
    type SerializeMap = Compound;
    type SerializeStruct = Compound;
    type SerializeStructVariant = Impossible<Shape, WalkError>;

    fn is_human_readable(&self) -> bool {
        false
    }

    shape_number! {
        serialize_bool(bool) => Shape::Bool,
        serialize_i8(i8) => Shape::Signed(8),
        serialize_i16(i16) => Shape::Signed(16),
        serialize_i32(i32) => Shape::Signed(32),
        serialize_i64(i64) => Shape::Signed(64),
        serialize_u8(u8) => Shape::Unsigned(8),
        serialize_u16(u16) => Shape::Unsigned(16),
        serialize_u32(u32) => Shape::Unsigned(32),
        serialize_u64(u64) => Shape::Unsigned(64),
        serialize_f32(f32) => Shape::Float,
        serialize_f64(f64) => Shape::Float,
    }

    fn serialize_char(self, v: char) -> Result<Shape, WalkError> {
        Ok(Shape::Text(v.to_string()))
    }
    fn serialize_str(self, v: &str) -> Result<Shape, WalkError> {
        Ok(Shape::Text(v.to_owned()))
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<Shape, WalkError> {
        Ok(Shape::List(vec![Shape::Unsigned(8); v.len()]))
    }
    fn serialize_none(self) -> Result<Shape, WalkError> {
        Ok(Shape::Null)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<Shape, WalkError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<Shape, WalkError> {
        Ok(Shape::Null)
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<Shape, WalkError> {
        Ok(Shape::Null)
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<Shape, WalkError> {
        Ok(Shape::Text(variant.to_owned()))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<Shape, WalkError> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<Shape, WalkError> {
        Ok(Shape::Object(vec![(
            variant.to_owned(),
            value.serialize(ShapeOf)?,
        )]))
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound, WalkError> {
        Ok(Compound::new(false))
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound, WalkError> {
        Ok(Compound::new(false))
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound, WalkError> {
        Ok(Compound::new(false))
    }
    fn serialize_tuple_variant(
        self,
        name: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, WalkError> {
        Err(ser::Error::custom(format!(
            "{name}: tuple variants are not in the schema"
        )))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound, WalkError> {
        Ok(Compound::new(true))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound, WalkError> {
        Ok(Compound::new(true))
    }
    fn serialize_struct_variant(
        self,
        name: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, WalkError> {
        Err(ser::Error::custom(format!(
            "{name}: struct variants are not in the schema"
        )))
    }
}

impl ser::SerializeSeq for Compound {
    type Ok = Shape;
    type Error = WalkError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        self.items.push(value.serialize(ShapeOf)?);
        Ok(())
    }
    fn end(self) -> Result<Shape, WalkError> {
        Ok(self.done())
    }
}

impl ser::SerializeTuple for Compound {
    type Ok = Shape;
    type Error = WalkError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        ser::SerializeSeq::serialize_element(self, value)
    }
    fn end(self) -> Result<Shape, WalkError> {
        Ok(self.done())
    }
}

impl ser::SerializeTupleStruct for Compound {
    type Ok = Shape;
    type Error = WalkError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        ser::SerializeSeq::serialize_element(self, value)
    }
    fn end(self) -> Result<Shape, WalkError> {
        Ok(self.done())
    }
}

impl ser::SerializeMap for Compound {
    type Ok = Shape;
    type Error = WalkError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), WalkError> {
        match key.serialize(ShapeOf)? {
            Shape::Text(key) => {
                self.key = Some(key);
                Ok(())
            }
            other => Err(ser::Error::custom(format!(
                "a map key that is not a string: {other:?}"
            ))),
        }
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        let key = self.key.take().unwrap_or_default();
        let value = value.serialize(ShapeOf)?;
        // A flattened member written twice keeps its last value, as in JSON.
        self.members.retain(|(k, _)| *k != key);
        self.members.push((key, value));
        Ok(())
    }
    fn end(self) -> Result<Shape, WalkError> {
        Ok(self.done())
    }
}

impl ser::SerializeStruct for Compound {
    type Ok = Shape;
    type Error = WalkError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), WalkError> {
        ser::SerializeMap::serialize_key(self, key)?;
        ser::SerializeMap::serialize_value(self, value)
    }
    fn end(self) -> Result<Shape, WalkError> {
        Ok(self.done())
    }
}
