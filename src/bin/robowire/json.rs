//! JSON lines in both directions: a fast writer for one flat object per line,
//! and strict readers for the fields of a parsed line.
//!
//! Output is written by hand rather than through `serde_json::Value`, so keys
//! come out in the documented order (`offset`, `len`, `type`, then the fields)
//! without allocating per frame. Input is parsed with `serde_json` and read
//! through [`Fields`], which rejects unknown keys and out-of-range values with
//! messages that name the field.

use serde_json::{Map, Value};
use std::io::Write as _;

/// One JSON object being written, reused from line to line.
#[derive(Debug, Default)]
pub struct JsonLine {
    buf: Vec<u8>,
    /// No member has been written yet at the current nesting level.
    first: bool,
}

impl JsonLine {
    /// Start a new object, forgetting the previous one.
    pub fn begin(&mut self) {
        self.buf.clear();
        self.buf.push(b'{');
        self.first = true;
    }

    /// Close the object and return it with its newline.
    pub fn end(&mut self) -> &[u8] {
        self.buf.extend_from_slice(b"}\n");
        &self.buf
    }

    /// Write `"key":`. Keys are fixed identifiers and need no escaping.
    fn key(&mut self, key: &str) {
        debug_assert!(key.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_'));
        if !self.first {
            self.buf.push(b',');
        }
        self.first = false;
        self.buf.push(b'"');
        self.buf.extend_from_slice(key.as_bytes());
        self.buf.extend_from_slice(b"\":");
    }

    /// A member whose value is anything [`Scalar`].
    pub fn field<S: Scalar>(&mut self, key: &str, value: S) {
        self.key(key);
        value.write(&mut self.buf);
    }

    /// A member whose value is an array of scalars.
    pub fn array<S: Scalar>(&mut self, key: &str, values: impl IntoIterator<Item = S>) {
        self.key(key);
        self.buf.push(b'[');
        for (i, value) in values.into_iter().enumerate() {
            if i > 0 {
                self.buf.push(b',');
            }
            value.write(&mut self.buf);
        }
        self.buf.push(b']');
    }

    /// A member whose value is an object of scalars, written by `members`.
    pub fn object(&mut self, key: &str, members: impl FnOnce(&mut JsonLine)) {
        self.key(key);
        self.buf.push(b'{');
        self.first = true;
        members(self);
        self.buf.push(b'}');
        self.first = false;
    }
}

/// A value that can be written as one JSON scalar.
pub trait Scalar {
    /// Append the value's JSON text to `buf`.
    fn write(&self, buf: &mut Vec<u8>);
}

impl Scalar for u64 {
    fn write(&self, buf: &mut Vec<u8>) {
        let mut digits = [0u8; 20];
        let mut i = digits.len();
        let mut v = *self;
        loop {
            i -= 1;
            digits[i] = b'0' + (v % 10) as u8;
            v /= 10;
            if v == 0 {
                break;
            }
        }
        buf.extend_from_slice(&digits[i..]);
    }
}

impl Scalar for i64 {
    fn write(&self, buf: &mut Vec<u8>) {
        if *self < 0 {
            buf.push(b'-');
        }
        self.unsigned_abs().write(buf);
    }
}

macro_rules! widen_scalar {
    ($($t:ty => $wide:ty),*) => {$(
        impl Scalar for $t {
            fn write(&self, buf: &mut Vec<u8>) {
                <$wide>::from(*self).write(buf);
            }
        }
    )*};
}
widen_scalar!(u8 => u64, u16 => u64, u32 => u64, i8 => i64, i16 => i64, i32 => i64);

impl Scalar for usize {
    fn write(&self, buf: &mut Vec<u8>) {
        (*self as u64).write(buf);
    }
}

impl Scalar for bool {
    fn write(&self, buf: &mut Vec<u8>) {
        buf.extend_from_slice(if *self { b"true" } else { b"false" });
    }
}

/// `None` is written `null`.
impl<S: Scalar> Scalar for Option<S> {
    fn write(&self, buf: &mut Vec<u8>) {
        match self {
            Some(value) => value.write(buf),
            None => buf.extend_from_slice(b"null"),
        }
    }
}

/// A string (escaped as JSON requires).
impl Scalar for &str {
    fn write(&self, buf: &mut Vec<u8>) {
        buf.push(b'"');
        for c in self.chars() {
            match c {
                '"' => buf.extend_from_slice(b"\\\""),
                '\\' => buf.extend_from_slice(b"\\\\"),
                c if (c as u32) < 0x20 => {
                    let _ = write!(buf, "\\u{:04x}", c as u32);
                }
                c => {
                    let mut utf8 = [0u8; 4];
                    buf.extend_from_slice(c.encode_utf8(&mut utf8).as_bytes());
                }
            }
        }
        buf.push(b'"');
    }
}

/// An `f32`, written so that it reads back as the same `f32`:
///
/// * a finite value is a JSON number, the shortest decimal that gives back the
///   same `f32` whether it is parsed as an `f32` directly or parsed as the
///   nearest `f64` and then rounded to `f32` (what most JSON readers do); for
///   the rare values where the shortest `f32` digits fail the second test, the
///   digits of the exact value (as an `f64`) are written instead;
/// * `inf` and `-inf` are the strings `"inf"` and `"-inf"`;
/// * a NaN is the string `"nan:0x7fc00000"`, its bit pattern in hex, so its sign
///   and payload survive.
impl Scalar for f32 {
    fn write(&self, buf: &mut Vec<u8>) {
        let x = *self;
        if x.is_nan() {
            let _ = write!(buf, "\"nan:{:#010x}\"", x.to_bits());
            return;
        }
        if x.is_infinite() {
            let text: &[u8] = if x > 0.0 { b"\"inf\"" } else { b"\"-inf\"" };
            buf.extend_from_slice(text);
            return;
        }
        let start = buf.len();
        let shortest = serde_json::to_writer(&mut *buf, &x).is_ok()
            && std::str::from_utf8(&buf[start..])
                .ok()
                .and_then(|text| text.parse::<f64>().ok())
                .is_some_and(|wide| (wide as f32).to_bits() == x.to_bits());
        if !shortest {
            buf.truncate(start);
            // Every f32 is exactly an f64, whose shortest digits parse back to
            // exactly that f64 and so to the same f32 with no double rounding.
            let _ = write!(buf, "{:e}", f64::from(x));
        }
    }
}

/// Read an `f32` written by [`Scalar for f32`](Scalar): a number (rounded to
/// the nearest `f32` through the nearest `f64`), `"inf"`, `"+inf"`, `"-inf"`,
/// `"nan"` (the quiet NaN `0x7fc00000`) or `"nan:0x…"` with a NaN's bit
/// pattern.
pub fn read_f32(value: &Value) -> Result<f32, String> {
    const EXPECTED: &str = "a number, \"inf\", \"-inf\" or \"nan:0x…\"";
    match value {
        Value::Number(n) => {
            let wide = n.as_f64().ok_or_else(|| format!("must be {EXPECTED}"))?;
            let x = wide as f32;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(format!(
                    "{n} does not fit in an f32 (write \"inf\" for infinity)"
                ))
            }
        }
        Value::String(s) => match s.as_str() {
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

/// Read an integer in `min..=max`.
pub fn read_int(value: &Value, min: i64, max: i64) -> Result<i64, String> {
    value
        .as_i64()
        .filter(|v| (min..=max).contains(v))
        .ok_or_else(|| format!("must be an integer {min}..={max}, found {value}"))
}

/// The members of one input line, read strictly: every member must be taken
/// by the protocol (or be one of the ignored ones) before [`finish`](Self::finish).
#[derive(Debug)]
pub struct Fields<'a> {
    map: &'a Map<String, Value>,
    taken: Vec<&'a str>,
}

/// Members that decode prints and encode ignores.
pub const IGNORED: [&str; 2] = ["offset", "len"];

impl<'a> Fields<'a> {
    /// The members of `map`.
    pub fn new(map: &'a Map<String, Value>) -> Self {
        Fields {
            map,
            taken: Vec::new(),
        }
    }

    /// Whether the member `key` is present (`null` counts as present).
    pub fn has(&self, key: &str) -> bool {
        self.map.contains_key(key)
    }

    /// Take the member `key`, which must be present.
    pub fn value(&mut self, key: &str) -> Result<&'a Value, String> {
        self.optional(key)
            .ok_or_else(|| format!("missing field `{key}`"))
    }

    /// Take the member `key` if it is present.
    pub fn optional(&mut self, key: &str) -> Option<&'a Value> {
        let (key, value) = self.map.get_key_value(key)?;
        self.taken.push(key);
        Some(value)
    }

    /// Take the member `key`, which must be a string.
    pub fn string(&mut self, key: &str) -> Result<&'a str, String> {
        let value = self.value(key)?;
        value
            .as_str()
            .ok_or_else(|| format!("field `{key}` must be a string, found {value}"))
    }

    /// Take the member `key`, an integer in `min..=max`.
    pub fn int(&mut self, key: &str, min: i64, max: i64) -> Result<i64, String> {
        read_int(self.value(key)?, min, max).map_err(|e| format!("field `{key}` {e}"))
    }

    /// Take the member `key`, which must be an array of exactly `N` elements,
    /// each read by `read`.
    pub fn array<T: Copy + Default, const N: usize>(
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

    /// Take the member `key`, which must be an object; its members are read
    /// strictly too.
    pub fn object(&mut self, key: &str) -> Result<Fields<'a>, String> {
        let value = self.value(key)?;
        value
            .as_object()
            .map(Fields::new)
            .ok_or_else(|| format!("field `{key}` must be an object, found {value}"))
    }

    /// Fail on the first member nobody took (other than [`IGNORED`] ones).
    pub fn finish(self, context: &str) -> Result<(), String> {
        match self
            .map
            .keys()
            .find(|k| !self.taken.contains(&k.as_str()) && !IGNORED.contains(&k.as_str()))
        {
            Some(unknown) => Err(format!("unknown field `{unknown}` {context}")),
            None => Ok(()),
        }
    }

    /// Like [`finish`](Self::finish) for a nested object, where no member is
    /// ignored.
    pub fn finish_nested(self, context: &str) -> Result<(), String> {
        match self.map.keys().find(|k| !self.taken.contains(&k.as_str())) {
            Some(unknown) => Err(format!("unknown field `{unknown}` {context}")),
            None => Ok(()),
        }
    }
}
