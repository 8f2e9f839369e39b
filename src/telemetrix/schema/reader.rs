//! The JSON reader the schema's `Deserialize` impls use: an owned `Value`
//! and strict `Fields`, with the `robowire` tool's messages.
//!
//! It has the signatures of the crate's shared `serde_support` reader (a port
//! of the tool's `json.rs`), so that the impls move to it unchanged.

use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt;

use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Serializer;

/// A JSON value, owned.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Value {
    Null,
    Bool(bool),
    U64(u64),
    I64(i64),
    F64(f64),
    Str(String),
    Seq(Vec<Value>),
    /// Members sorted by key, as `serde_json`'s map keeps them.
    Map(Vec<(String, Value)>),
}

impl Value {
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

    pub(crate) fn as_object(&self) -> Option<&[(String, Value)]> {
        match self {
            Value::Map(members) => Some(members),
            _ => None,
        }
    }

    pub(crate) fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Bool(b) => Some(*b),
            _ => None,
        }
    }

    pub(crate) fn as_i64(&self) -> Option<i64> {
        match *self {
            Value::U64(u) => i64::try_from(u).ok(),
            Value::I64(i) => Some(i),
            _ => None,
        }
    }

    pub(crate) fn as_f64(&self) -> Option<f64> {
        match *self {
            Value::U64(u) => Some(u as f64),
            Value::I64(i) => Some(i as f64),
            Value::F64(f) => Some(f),
            _ => None,
        }
    }
}

/// Compact JSON, as `serde_json` writes its `Value`.
impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Null => f.write_str("null"),
            Value::Bool(b) => write!(f, "{b}"),
            Value::U64(u) => write!(f, "{u}"),
            Value::I64(i) => write!(f, "{i}"),
            Value::F64(x) => write_f64(f, *x),
            Value::Str(s) => write_str(f, s),
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
                    write_str(f, key)?;
                    write!(f, ":{value}")?;
                }
                f.write_str("}")
            }
        }
    }
}

fn write_str(f: &mut fmt::Formatter<'_>, s: &str) -> fmt::Result {
    f.write_str("\"")?;
    for c in s.chars() {
        match c {
            '"' => f.write_str("\\\"")?,
            '\\' => f.write_str("\\\\")?,
            '\n' => f.write_str("\\n")?,
            '\r' => f.write_str("\\r")?,
            '\t' => f.write_str("\\t")?,
            c if (c as u32) < 0x20 => write!(f, "\\u{:04x}", c as u32)?,
            c => write!(f, "{c}")?,
        }
    }
    f.write_str("\"")
}

/// A finite `f64` the way `serde_json` prints it: the shortest digits,
/// `1.5`, `2.0`, `1e+39`, `1e-7`.
fn write_f64(f: &mut fmt::Formatter<'_>, x: f64) -> fmt::Result {
    let abs = x.abs();
    if abs == 0.0 || (1e-5..1e16).contains(&abs) {
        if x == (x as i64) as f64 {
            write!(f, "{x:.1}")
        } else {
            write!(f, "{x}")
        }
    } else {
        let text = format!("{x:e}");
        match text.split_once('e') {
            Some((mantissa, exp)) if !exp.starts_with('-') => write!(f, "{mantissa}e+{exp}"),
            _ => f.write_str(&text),
        }
    }
}

impl<'de> Deserialize<'de> for Value {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ValueVisitor;

        impl<'de> Visitor<'de> for ValueVisitor {
            type Value = Value;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("any JSON value")
            }

            fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
                Ok(Value::Bool(v))
            }

            fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
                Ok(if v >= 0 {
                    Value::U64(v as u64)
                } else {
                    Value::I64(v)
                })
            }

            fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
                Ok(Value::U64(v))
            }

            fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
                Ok(Value::F64(v))
            }

            fn visit_str<E>(self, v: &str) -> Result<Value, E> {
                Ok(Value::Str(v.to_string()))
            }

            fn visit_string<E>(self, v: String) -> Result<Value, E> {
                Ok(Value::Str(v))
            }

            fn visit_none<E>(self) -> Result<Value, E> {
                Ok(Value::Null)
            }

            fn visit_unit<E>(self) -> Result<Value, E> {
                Ok(Value::Null)
            }

            fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
                Value::deserialize(d)
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
                let mut items = Vec::new();
                while let Some(item) = seq.next_element()? {
                    items.push(item);
                }
                Ok(Value::Seq(items))
            }

            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
                let mut members: Vec<(String, Value)> = Vec::new();
                while let Some((key, value)) = map.next_entry::<String, Value>()? {
                    match members.binary_search_by(|(k, _)| k.as_str().cmp(&key)) {
                        Ok(i) => members[i].1 = value,
                        Err(i) => members.insert(i, (key, value)),
                    }
                }
                Ok(Value::Map(members))
            }
        }

        deserializer.deserialize_any(ValueVisitor)
    }
}

/// Read an `f32`: a number (rounded to the nearest `f32` through the nearest
/// `f64`), `"inf"`, `"+inf"`, `"-inf"`, `"nan"` (the quiet NaN `0x7fc00000`)
/// or `"nan:0x…"` with a NaN's bit pattern.
pub(crate) fn read_f32(value: &Value) -> Result<f32, String> {
    const EXPECTED: &str = "a number, \"inf\", \"-inf\" or \"nan:0x…\"";
    match value {
        Value::U64(_) | Value::I64(_) | Value::F64(_) => {
            let wide = value.as_f64().unwrap_or(f64::NAN);
            let x = wide as f32;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(format!(
                    "{value} does not fit in an f32 (write \"inf\" for infinity)"
                ))
            }
        }
        Value::Str(s) => match s.as_str() {
            "inf" | "+inf" => Ok(f32::INFINITY),
            "-inf" => Ok(f32::NEG_INFINITY),
            "nan" => Ok(f32::from_bits(0x7fc0_0000)),
            other => other
                .strip_prefix("nan:0x")
                .filter(|hex| hex.len() == 8)
                .and_then(|hex| u32::from_str_radix(hex, 16).ok())
                .map(f32::from_bits)
                .filter(|x| x.is_nan())
                .ok_or_else(|| format!("must be {EXPECTED} (a NaN's 8 hex digits), found {value}")),
        },
        other => Err(format!("must be {EXPECTED}, found {other}")),
    }
}

/// Write an `f32` so that it reads back as the same `f32`: a finite value as
/// the shortest `f32` digits when they survive being read as an `f64` and
/// rounded, else as the exact value's `f64` digits; infinities as `"inf"` and
/// `"-inf"`; a NaN as `"nan:0x…"` with its bit pattern.
pub(crate) fn serialize_f32<S: Serializer>(x: f32, serializer: S) -> Result<S::Ok, S::Error> {
    if x.is_nan() {
        return serializer.collect_str(&format_args!("nan:{:#010x}", x.to_bits()));
    }
    if x.is_infinite() {
        return serializer.serialize_str(if x > 0.0 { "inf" } else { "-inf" });
    }
    let shortest = format!("{x}");
    let survives = shortest
        .parse::<f64>()
        .is_ok_and(|wide| (wide as f32).to_bits() == x.to_bits());
    if survives {
        serializer.serialize_f32(x)
    } else {
        serializer.serialize_f64(f64::from(x))
    }
}

/// Read an integer in `min..=max`.
pub(crate) fn read_int(value: &Value, min: i64, max: i64) -> Result<i64, String> {
    value
        .as_i64()
        .filter(|v| (min..=max).contains(v))
        .ok_or_else(|| format!("must be an integer {min}..={max}, found {value}"))
}

/// Members that the tool prints and reading ignores.
pub(crate) const IGNORED: [&str; 2] = ["offset", "len"];

/// The members of one object, read strictly: every member must be taken
/// before [`finish`](Self::finish).
pub(crate) struct Fields<'a> {
    map: &'a [(String, Value)],
    taken: Vec<&'a str>,
}

impl<'a> Fields<'a> {
    pub(crate) fn new(map: &'a [(String, Value)]) -> Self {
        Fields {
            map,
            taken: Vec::new(),
        }
    }

    fn get(&self, key: &str) -> Option<&'a (String, Value)> {
        self.map.iter().find(|(k, _)| k == key)
    }

    pub(crate) fn has(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    pub(crate) fn value(&mut self, key: &str) -> Result<&'a Value, String> {
        self.optional(key)
            .ok_or_else(|| format!("missing field `{key}`"))
    }

    pub(crate) fn optional(&mut self, key: &str) -> Option<&'a Value> {
        let (key, value) = self.get(key)?;
        self.taken.push(key);
        Some(value)
    }

    pub(crate) fn string(&mut self, key: &str) -> Result<&'a str, String> {
        let value = self.value(key)?;
        value
            .as_str()
            .ok_or_else(|| format!("field `{key}` must be a string, found {value}"))
    }

    pub(crate) fn int(&mut self, key: &str, min: i64, max: i64) -> Result<i64, String> {
        read_int(self.value(key)?, min, max).map_err(|e| format!("field `{key}` {e}"))
    }

    pub(crate) fn array<T: Copy + Default, const N: usize>(
        &mut self,
        key: &str,
        read: impl Fn(&Value) -> Result<T, String>,
    ) -> Result<[T; N], String> {
        let value = self.value(key)?;
        let items = value
            .as_array()
            .filter(|items| items.len() == N)
            .ok_or_else(|| format!("field `{key}` must be an array of {N}, found {value}"))?;
        let mut out = [T::default(); N];
        for (i, (slot, item)) in out.iter_mut().zip(items).enumerate() {
            *slot = read(item).map_err(|e| format!("field `{key}[{i}]` {e}"))?;
        }
        Ok(out)
    }

    pub(crate) fn object(&mut self, key: &str) -> Result<Fields<'a>, String> {
        let value = self.value(key)?;
        value
            .as_object()
            .map(Fields::new)
            .ok_or_else(|| format!("field `{key}` must be an object, found {value}"))
    }

    pub(crate) fn finish(self, context: &str) -> Result<(), String> {
        match self
            .map
            .iter()
            .map(|(k, _)| k.as_str())
            .find(|k| !self.taken.contains(k) && !IGNORED.contains(k))
        {
            Some(unknown) => Err(format!("unknown field `{unknown}` {context}")),
            None => Ok(()),
        }
    }

    pub(crate) fn finish_nested(self, context: &str) -> Result<(), String> {
        match self
            .map
            .iter()
            .map(|(k, _)| k.as_str())
            .find(|k| !self.taken.contains(k))
        {
            Some(unknown) => Err(format!("unknown field `{unknown}` {context}")),
            None => Ok(()),
        }
    }
}
