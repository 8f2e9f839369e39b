//! Reading one message's members out of a [`Value`] strictly: every member
//! must be taken by the message's reader (or be one of [`IGNORED`]), ranges
//! are checked, and every error names the field, the range and what it found.
//! Messages' `Deserialize` impls are written with it, so that every format
//! (the command-line tool's JSON lines, a Python dict, …) validates exactly
//! as the encoder does.

use alloc::collections::BTreeMap;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

use super::suggest::may_mean;
use super::Value;

/// Members that the stream adds to a decoded frame (`offset`, `len`) and
/// that reading a message ignores.
pub(crate) const IGNORED: [&str; 2] = ["offset", "len"];

/// Read an `f32` as [`serialize_f32`](super::serialize_f32) writes it: a number
/// (rounded to the nearest `f32` through the nearest `f64`), `"inf"`, `"+inf"`,
/// `"-inf"`, `"nan"` (the quiet NaN `0x7fc00000`) or `"nan:0x…"` with a NaN's
/// bit pattern. A format that has non-finite numbers (a Python `float`) may
/// give them as numbers too; a NaN keeps its sign and the top of its payload.
pub(crate) fn read_f32(value: &Value) -> Result<f32, String> {
    const EXPECTED: &str = "a number, \"inf\", \"-inf\" or \"nan:0x…\"";
    match value {
        Value::F64(wide) if wide.is_nan() => Ok(narrow_nan(*wide)),
        Value::F64(wide) if wide.is_infinite() => Ok(*wide as f32),
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

/// The `f32` NaN with `wide`'s sign and the top 23 bits of its payload (what
/// widening an `f32` NaN to `f64` keeps), bit for bit: `as` may quieten a
/// signalling NaN.
fn narrow_nan(wide: f64) -> f32 {
    let bits = wide.to_bits();
    let sign = ((bits >> 63) as u32) << 31;
    let payload = ((bits >> 29) as u32) & 0x007f_ffff;
    // A payload only in the low 29 bits has no f32 form: the quiet NaN.
    let payload = if payload == 0 { 0x0040_0000 } else { payload };
    f32::from_bits(sign | 0x7f80_0000 | payload)
}

/// Read an integer in `min..=max`.
pub(crate) fn read_int(value: &Value, min: i64, max: i64) -> Result<i64, String> {
    value
        .as_i64()
        .filter(|v| (min..=max).contains(v))
        .ok_or_else(|| format!("must be an integer {min}..={max}, found {value}"))
}

/// The members of one object, read strictly: every member must be taken
/// before [`finish`](Self::finish).
#[derive(Debug)]
pub(crate) struct Fields<'a> {
    map: &'a BTreeMap<String, Value>,
    taken: Vec<&'a str>,
}

impl<'a> Fields<'a> {
    /// The members of `map`.
    pub(crate) fn new(map: &'a BTreeMap<String, Value>) -> Self {
        Fields {
            map,
            taken: Vec::new(),
        }
    }

    /// The members of `value`, which must be an object (`what` names it in
    /// the error, e.g. "a message").
    pub(crate) fn of(value: &'a Value, what: &str) -> Result<Self, String> {
        value
            .as_object()
            .map(Fields::new)
            .ok_or_else(|| format!("expected {what} (a JSON object), found {value}"))
    }

    /// Whether the member `key` is present (`null` counts as present).
    pub(crate) fn has(&self, key: &str) -> bool {
        self.map.contains_key(key)
    }

    /// Take the member `key`, which must be present. When it is missing
    /// and a member not yet taken looks like a misspelling of it, the error
    /// names that member and suggests `key`.
    pub(crate) fn value(&mut self, key: &str) -> Result<&'a Value, String> {
        self.optional(key).ok_or_else(|| {
            let misspelt = self.map.keys().find(|k| {
                !self.taken.contains(&k.as_str())
                    && !IGNORED.contains(&k.as_str())
                    && may_mean(k, key)
            });
            match misspelt {
                Some(k) => format!("unknown field `{k}` (did you mean `{key}`?)"),
                None => format!("missing field `{key}`"),
            }
        })
    }

    /// Take the member `key` if it is present.
    pub(crate) fn optional(&mut self, key: &str) -> Option<&'a Value> {
        let (key, value) = self.map.get_key_value(key)?;
        self.taken.push(key);
        Some(value)
    }

    /// Take the member `key`, which must be a string.
    pub(crate) fn string(&mut self, key: &str) -> Result<&'a str, String> {
        let value = self.value(key)?;
        value
            .as_str()
            .ok_or_else(|| format!("field `{key}` must be a string, found {value}"))
    }

    /// Take the member `key`, an integer in `min..=max`.
    pub(crate) fn int(&mut self, key: &str, min: i64, max: i64) -> Result<i64, String> {
        read_int(self.value(key)?, min, max).map_err(|e| format!("field `{key}` {e}"))
    }

    /// Take the member `key`, which must be an array of exactly `N` elements,
    /// each read by `read`.
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

    /// Take the member `key`, which must be an object; its members are read
    /// strictly too.
    pub(crate) fn object(&mut self, key: &str) -> Result<Fields<'a>, String> {
        let value = self.value(key)?;
        value
            .as_object()
            .map(Fields::new)
            .ok_or_else(|| format!("field `{key}` must be an object, found {value}"))
    }

    /// Fail on the first member (in name order) nobody took, other than
    /// [`IGNORED`] ones; `context` follows the name in the message ("for type
    /// ping").
    pub(crate) fn finish(self, context: &str) -> Result<(), String> {
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
    pub(crate) fn finish_nested(self, context: &str) -> Result<(), String> {
        match self.map.keys().find(|k| !self.taken.contains(&k.as_str())) {
            Some(unknown) => Err(format!("unknown field `{unknown}` {context}")),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    fn object(members: &[(&str, Value)]) -> Value {
        Value::Map(
            members
                .iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect(),
        )
    }

    #[test]
    fn non_finite_numbers_read_bit_for_bit() {
        for bits in [
            0x7fc0_0000u32,
            0xffc0_0001,
            0x7f80_0001,
            0x7f80_0000,
            0xff80_0000,
        ] {
            let wide = f64::from(f32::from_bits(bits));
            // Widening by bits, as a format that has a NaN's payload gives it.
            let wide = if wide.is_nan() {
                let sign = u64::from(bits >> 31) << 63;
                f64::from_bits(sign | 0x7ff0_0000_0000_0000 | u64::from(bits & 0x007f_ffff) << 29)
            } else {
                wide
            };
            assert_eq!(read_f32(&Value::F64(wide)).map(f32::to_bits), Ok(bits));
        }
    }

    #[test]
    fn every_member_must_be_taken_but_offset_and_len() {
        let line = object(&[
            ("offset", Value::U64(3)),
            ("len", Value::U64(4)),
            ("speed", Value::U64(200)),
            ("sped", Value::U64(1)),
        ]);
        let mut fields = Fields::of(&line, "a message").unwrap();
        assert_eq!(fields.int("speed", 0, 255), Ok(200));
        assert_eq!(
            fields.finish("for type m1_extend"),
            Err("unknown field `sped` for type m1_extend".into())
        );
    }

    #[test]
    fn errors_name_the_field_the_range_and_the_value() {
        let line = object(&[
            ("speed", Value::F64(2.5)),
            (
                "uwb",
                Value::Seq(alloc::vec![Value::U64(1), Value::I64(-3)]),
            ),
        ]);
        let mut fields = Fields::of(&line, "a message").unwrap();
        assert_eq!(
            fields.int("speed", 0, 255),
            Err("field `speed` must be an integer 0..=255, found 2.5".into())
        );
        assert_eq!(
            fields.array::<u16, 2>("uwb", |v| read_int(v, 0, 9).map(|n| n as u16)),
            Err("field `uwb[1]` must be an integer 0..=9, found -3".into())
        );
        assert_eq!(fields.value("tof"), Err("missing field `tof`".into()));
    }

    #[test]
    fn a_misspelt_field_is_named_with_a_suggestion() {
        let map = object(&[
            ("type", Value::Str("m1_extend".into())),
            ("sped", Value::U64(200)),
        ]);
        let mut fields = Fields::of(&map, "a message").unwrap();
        fields.string("type").unwrap();
        assert_eq!(
            fields.value("speed"),
            Err("unknown field `sped` (did you mean `speed`?)".into())
        );
        // Nothing like the missing name: the plain error.
        assert_eq!(fields.value("motor"), Err("missing field `motor`".into()));
    }

    #[test]
    fn floats_read_back_every_form() {
        assert_eq!(read_f32(&Value::F64(2.5)), Ok(2.5));
        assert_eq!(read_f32(&Value::Str("-inf".into())), Ok(f32::NEG_INFINITY));
        let nan = read_f32(&Value::Str("nan:0xffc00001".into())).unwrap();
        assert_eq!(nan.to_bits(), 0xffc0_0001);
        assert_eq!(
            read_f32(&Value::F64(1e39)),
            Err("1e+39 does not fit in an f32 (write \"inf\" for infinity)".into())
        );
    }
}
