//! An owned tree of whatever a self-describing format holds (JSON's values),
//! so that a message's `Deserialize` impl can read its fields in any order,
//! name the field it rejects, and quote the value it found. Its `Display`
//! writes compact JSON exactly as `serde_json::Value` does, so error messages
//! read the same from every format.

use alloc::collections::BTreeMap;
use alloc::string::String;
use alloc::vec::Vec;
use core::fmt::{self, Write as _};

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};

/// One value of the input.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Value {
    Null,
    Bool(bool),
    /// A non-negative integer.
    U64(u64),
    /// A negative integer.
    I64(i64),
    F64(f64),
    Str(String),
    Seq(Vec<Value>),
    /// Members by name; a repeated name keeps its last value, as JSON readers do.
    Map(BTreeMap<String, Value>),
}

impl Value {
    pub(crate) fn is_null(&self) -> bool {
        matches!(self, Value::Null)
    }

    pub(crate) fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Bool(b) => Some(*b),
            _ => None,
        }
    }

    pub(crate) fn as_u64(&self) -> Option<u64> {
        match self {
            Value::U64(n) => Some(*n),
            _ => None,
        }
    }

    pub(crate) fn as_i64(&self) -> Option<i64> {
        match self {
            Value::U64(n) => i64::try_from(*n).ok(),
            Value::I64(n) => Some(*n),
            _ => None,
        }
    }

    pub(crate) fn as_f64(&self) -> Option<f64> {
        match self {
            Value::U64(n) => Some(*n as f64),
            Value::I64(n) => Some(*n as f64),
            Value::F64(x) => Some(*x),
            _ => None,
        }
    }

    pub(crate) fn as_str(&self) -> Option<&str> {
        match self {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    pub(crate) fn as_array(&self) -> Option<&[Value]> {
        match self {
            Value::Seq(items) => Some(items),
            _ => None,
        }
    }

    pub(crate) fn as_object(&self) -> Option<&BTreeMap<String, Value>> {
        match self {
            Value::Map(map) => Some(map),
            _ => None,
        }
    }
}

impl<'de> Deserialize<'de> for Value {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(ValueVisitor)
    }
}

struct ValueVisitor;

impl<'de> Visitor<'de> for ValueVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any value")
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Value, E> {
        Ok(match u64::try_from(v) {
            Ok(n) => Value::U64(n),
            Err(_) => Value::I64(v),
        })
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Value, E> {
        Ok(Value::U64(v))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Value, E> {
        Ok(Value::F64(v))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Value, E> {
        Ok(Value::Str(v.into()))
    }

    fn visit_string<E: de::Error>(self, v: String) -> Result<Value, E> {
        Ok(Value::Str(v))
    }

    fn visit_bytes<E: de::Error>(self, v: &[u8]) -> Result<Value, E> {
        Ok(Value::Seq(
            v.iter().map(|&b| Value::U64(b.into())).collect(),
        ))
    }

    fn visit_unit<E: de::Error>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_none<E: de::Error>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_some<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        Value::deserialize(deserializer)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element()? {
            items.push(item);
        }
        Ok(Value::Seq(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut members = BTreeMap::new();
        while let Some((key, value)) = map.next_entry::<String, Value>()? {
            members.insert(key, value);
        }
        Ok(Value::Map(members))
    }
}

/// Compact JSON, as `serde_json::Value` writes it.
impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Null => f.write_str("null"),
            Value::Bool(b) => write!(f, "{b}"),
            Value::U64(n) => write!(f, "{n}"),
            Value::I64(n) => write!(f, "{n}"),
            Value::F64(x) => write_f64(*x, f),
            Value::Str(s) => write_str(s, f),
            Value::Seq(items) => {
                f.write_str("[")?;
                for (i, item) in items.iter().enumerate() {
                    if i > 0 {
                        f.write_str(",")?;
                    }
                    write!(f, "{item}")?;
                }
                f.write_str("]")
            }
            Value::Map(members) => {
                f.write_str("{")?;
                for (i, (key, value)) in members.iter().enumerate() {
                    if i > 0 {
                        f.write_str(",")?;
                    }
                    write_str(key, f)?;
                    write!(f, ":{value}")?;
                }
                f.write_str("}")
            }
        }
    }
}

/// A float as serde_json writes one: the shortest digits that read back, in
/// fixed notation for decimal exponents -5..=15 (with `.0` on whole numbers),
/// otherwise as `1.5e+16` / `1.25e-6`; a non-finite value as `null`.
fn write_f64(x: f64, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    if !x.is_finite() {
        return f.write_str("null");
    }
    let mut sci = super::Inline::<40>::new();
    write!(sci, "{x:e}")?;
    let sci = sci.as_str();
    let (mantissa, exponent) = sci.split_once('e').unwrap_or((sci, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if (-5..=15).contains(&exponent) {
        let mut fixed = super::Inline::<40>::new();
        write!(fixed, "{x}")?;
        f.write_str(fixed.as_str())?;
        if !fixed.as_str().contains('.') {
            f.write_str(".0")?;
        }
        Ok(())
    } else if exponent > 0 {
        write!(f, "{mantissa}e+{exponent}")
    } else {
        write!(f, "{mantissa}e{exponent}")
    }
}

/// A JSON string literal, escaped as serde_json escapes.
fn write_str(s: &str, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    f.write_str("\"")?;
    for c in s.chars() {
        match c {
            '"' => f.write_str("\\\"")?,
            '\\' => f.write_str("\\\\")?,
            '\n' => f.write_str("\\n")?,
            '\r' => f.write_str("\\r")?,
            '\t' => f.write_str("\\t")?,
            '\u{8}' => f.write_str("\\b")?,
            '\u{c}' => f.write_str("\\f")?,
            c if (c as u32) < 0x20 => write!(f, "\\u{:04x}", c as u32)?,
            c => write!(f, "{c}")?,
        }
    }
    f.write_str("\"")
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    fn json(x: f64) -> String {
        Value::F64(x).to_string()
    }

    #[test]
    fn floats_print_as_serde_json_prints_them() {
        for (x, text) in [
            (2.5, "2.5"),
            (100.0, "100.0"),
            (1e15, "1000000000000000.0"),
            (1e16, "1e+16"),
            (1.5e16, "1.5e+16"),
            (0.0001, "0.0001"),
            (1e-5, "0.00001"),
            (1e-6, "1e-6"),
            (1.25e-6, "1.25e-6"),
            (1e39, "1e+39"),
            (7.038530691851209e-26, "7.038530691851209e-26"),
            (-0.0, "-0.0"),
            (123456789012345.6, "123456789012345.6"),
        ] {
            assert_eq!(json(x), text, "{x:e}");
        }
    }

    #[test]
    fn containers_and_strings_print_compactly() {
        let mut map = BTreeMap::new();
        map.insert(
            "b".into(),
            Value::Seq(alloc::vec![Value::U64(1), Value::I64(-2)]),
        );
        map.insert("a".into(), Value::Str("x\"\n\u{1}".into()));
        map.insert("c".into(), Value::Null);
        assert_eq!(
            Value::Map(map).to_string(),
            r#"{"a":"x\"\n\u0001","b":[1,-2],"c":null}"#
        );
    }
}

/// A [`Value`] is itself a deserializer, so a reader can hand any part of it
/// to a derived `Deserialize` impl (and the stream's frame types can peel off
/// `offset` and `len` and pass the rest to the message).
impl<'de> Deserializer<'de> for Value {
    type Error = de::value::Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        match self {
            Value::Null => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(b),
            Value::U64(n) => visitor.visit_u64(n),
            Value::I64(n) => visitor.visit_i64(n),
            Value::F64(x) => visitor.visit_f64(x),
            Value::Str(s) => visitor.visit_string(s),
            Value::Seq(items) => {
                let mut seq = de::value::SeqDeserializer::new(items.into_iter());
                let value = visitor.visit_seq(&mut seq)?;
                seq.end()?;
                Ok(value)
            }
            Value::Map(members) => {
                let mut map = de::value::MapDeserializer::new(members.into_iter());
                let value = visitor.visit_map(&mut map)?;
                map.end()?;
                Ok(value)
            }
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        match self {
            Value::Null => visitor.visit_none(),
            other => visitor.visit_some(other),
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        match self {
            // A unit variant by name.
            Value::Str(s) => {
                visitor.visit_enum(de::IntoDeserializer::<Self::Error>::into_deserializer(s))
            }
            other => other.deserialize_any(visitor),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf unit unit_struct newtype_struct seq tuple
        tuple_struct map struct identifier ignored_any
    }
}

impl<'de> de::IntoDeserializer<'de, de::value::Error> for Value {
    type Deserializer = Value;

    fn into_deserializer(self) -> Value {
        self
    }
}

#[cfg(test)]
mod deserializer_tests {
    use super::*;

    #[derive(Debug, PartialEq, serde::Deserialize)]
    #[serde(tag = "type", rename_all = "snake_case")]
    enum Toy {
        Ping,
        Move { speed: u8, at: Option<u16> },
    }

    #[test]
    fn a_value_feeds_derived_impls() {
        let line: Value = serde_json::from_str(r#"{"at":null,"type":"move","speed":7}"#).unwrap();
        assert_eq!(Toy::deserialize(line), Ok(Toy::Move { speed: 7, at: None }));
        let line: Value = serde_json::from_str(r#"{"type":"ping"}"#).unwrap();
        assert_eq!(Toy::deserialize(line), Ok(Toy::Ping));
    }
}
