//! serde: the JSON-lines schema of the `robowire` tool is the serde form of
//! every message, owned form and error. Serializing walks the fields of
//! [`fields`](super::fields); deserializing reads them strictly (unknown
//! fields, out-of-range values and wrong types are errors that name the
//! field) and encodes, so a deserialized owned form holds a valid frame.

use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt;

use serde::de::{self, Deserialize, Deserializer};
use serde::ser::{Serialize, SerializeMap, SerializeSeq, Serializer};

use super::buf::{CommandBuf, Message, MessageBuf, ReportBuf};
use super::command::{
    Command, EncoderKind, ModifyReporting, PinMode, Pull, Pulls, PwmPin, PwmPins, Rgb,
};
use super::dialect::Dialect;
use super::error::Error;
use super::fields::{Visit, Width, V, W};
use super::kind::{bind_hook, piece};
use super::list::List;
use super::module::{
    HiwonderCommand, ModuleCommand, ModuleInit, ModuleNew, ModuleReport, ModuleType,
    Pca9685Channel, Pca9685Command, Pca9685Config, RelayCommand, ServoMove, ServoPositions,
    Ssd1306Command, Ssd1306Done,
};
use super::quirk::Quirk;
use super::report::{Report, Sonar, SONAR_NO_ECHO, SONAR_OUT_OF_RANGE, SONAR_STALE};
use super::sensor::{SensorNew, SensorReading, SensorType};
use super::table::sensor_readings;
use super::wire::{
    pixel_buffer, COMMAND_PAYLOAD_MAX, I2C_READ_MAX, MAX_REPORT_FRAME, PIN_COUNT, SPI_READ_MAX,
};
use crate::serde_support::{read_f32, read_int, serialize_f32, unknown_type, Fields, Value};
use crate::Encode;

// ---------------------------------------------------------------- Serialize

/// The fields of a [`Visit`] as a map.
struct Fields_<'a>(&'a dyn Visit);

impl Serialize for Fields_<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        let mut result = Ok(());
        self.0.visit(&mut W(&mut |key, value| {
            if result.is_ok() {
                result = map.serialize_entry(key, &Field(value));
            }
        }));
        result?;
        map.end()
    }
}

/// One field value.
struct Field<'a>(V<'a>);

/// An `f32` in the schema's form.
struct F32(f32);

impl Serialize for F32 {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_f32(self.0, serializer)
    }
}

/// Bytes as characters U+0000..=U+00FF.
struct Latin1<'a>(&'a [u8]);

impl fmt::Display for Latin1<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0
            .iter()
            .try_for_each(|&b| fmt::Write::write_char(f, char::from(b)))
    }
}

impl Serialize for Field<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            // The Rust type of the wire's field, for a schema (the JSON
            // text is the same).
            V::U(v, Width::W8) => serializer.serialize_u8(v as u8),
            V::U(v, Width::W16) => serializer.serialize_u16(v as u16),
            V::U(v, Width::W32) => serializer.serialize_u32(v as u32),
            V::I(v, Width::W8) => serializer.serialize_i8(v as i8),
            V::I(v, Width::W16) => serializer.serialize_i16(v as i16),
            V::I(v, Width::W32) => serializer.serialize_i32(v as i32),
            V::Bool(v) => serializer.serialize_bool(v),
            V::Str(v) => serializer.serialize_str(v),
            V::F32(v) => serialize_f32(v, serializer),
            V::Bytes(v) => serializer.collect_seq(v),
            V::U16s(v) => serializer.collect_seq(v),
            V::I16s(v) => serializer.collect_seq(v),
            V::F32s(v) => serializer.collect_seq(v.iter().map(|&x| F32(x))),
            V::Latin1(v) => serializer.collect_str(&Latin1(v)),
            V::Obj(o) => Fields_(o).serialize(serializer),
            V::Objs(items) => {
                let mut seq = serializer.serialize_seq(None)?;
                let mut result = Ok(());
                items.visit_each(&mut |o| {
                    if result.is_ok() {
                        result = seq.serialize_element(&Fields_(o));
                    }
                });
                result?;
                seq.end()
            }
        }
    }
}

macro_rules! serialize_fields {
    ($($ty:ty),*) => {$(
        /// The JSON-lines schema: `type`, then the fields.
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                Fields_(self).serialize(serializer)
            }
        }
    )*};
}

serialize_fields!(
    Command<'_>,
    Report<'_>,
    Message<'_>,
    CommandBuf,
    ReportBuf,
    MessageBuf
);

/// The schema's diagnostic: `error` (snake case) and the details.
/// `len_byte` is a frame's `LEN` byte.
impl Serialize for Error {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        match *self {
            Error::UnknownId { id } => {
                map.serialize_entry("error", "unknown_id")?;
                map.serialize_entry("id", &id)?;
            }
            Error::BadLength { id, len } => {
                map.serialize_entry("error", "bad_length")?;
                map.serialize_entry("id", &id)?;
                map.serialize_entry("len_byte", &len)?;
            }
            Error::OutOfRange { id, field } => {
                map.serialize_entry("error", "out_of_range")?;
                map.serialize_entry("id", &id)?;
                map.serialize_entry("field", field)?;
            }
            Error::Truncated { len } => {
                map.serialize_entry("error", "truncated")?;
                map.serialize_entry("len", &len)?;
            }
            Error::Superseded { len } => {
                map.serialize_entry("error", "superseded")?;
                map.serialize_entry("len", &len)?;
            }
        }
        map.end()
    }
}

macro_rules! serde_by_name {
    ($($ty:ty),*) => {$(
        /// Its name.
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                serializer.serialize_str(self.name())
            }
        }

        /// Its name.
        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                let value = Value::deserialize(deserializer)?;
                value
                    .as_str()
                    .and_then(|s| s.parse().ok())
                    .ok_or_else(|| {
                        de::Error::custom(format!(
                            "must be one of {}, found {value}",
                            <$ty>::NAMES.join(", ")
                        ))
                    })
            }
        }
    )*};
}

serde_by_name!(Dialect, SensorType, ModuleType, EncoderKind);

// ---------------------------------------------------------------- Deserialize

/// Which messages a line may hold.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Want {
    Commands,
    Reports,
    Any,
}

/// Read one JSON object of the schema and encode it for `dialect`. A line
/// without `quirk` whose frame would have one is refused, and the error
/// names the quirk that allows it.
fn read_line(value: &Value, dialect: Dialect, want: Want) -> Result<MessageBuf, String> {
    read_marked(value, dialect, want).map_err(|error| {
        let Some(map) = value.as_object().filter(|map| !map.contains_key("quirk")) else {
            return error;
        };
        let marked = |quirk: Quirk| {
            let mut map = map.clone();
            map.insert("quirk".into(), Value::Str(quirk.name().into()));
            read_marked(&Value::Map(map), dialect, want).is_ok()
        };
        match Quirk::ALL.into_iter().find(|&quirk| marked(quirk)) {
            Some(quirk) => format!(
                "{error} (a frame a real peer sends, which decode marks \"quirk\":\"{quirk}\": \
                 add that to the line to encode it anyway)"
            ),
            None => error,
        }
    })
}

/// What a line with a `quirk` says beyond its message: the quirk, and the
/// bytes of the frame the message does not hold (see `fields::with_quirk`).
struct Raw {
    quirk: Option<Quirk>,
    /// A byte of the frame, by index, as the line gives it.
    byte: Option<(usize, u8)>,
    /// Bytes after the message's payload.
    trailing: Vec<u8>,
}

/// [`read_line`] without the hint.
fn read_marked(value: &Value, dialect: Dialect, want: Want) -> Result<MessageBuf, String> {
    let map = value
        .as_object()
        .ok_or_else(|| format!("expected a JSON object, found {value}"))?;
    let mut fields = Fields::new(map);
    let kind = fields.string("type")?;
    // `also` names the other reading of an ambiguous frame; the bytes are
    // the same either way.
    if let Some(also) = fields.optional("also") {
        let known = also.as_str().is_some_and(|t| {
            Command::NAMES.contains(&t) || Report::NAMES[..Report::NAMES.len() - 1].contains(&t)
        });
        if !known {
            return Err(format!(
                "field `also` must name a command or report type, found {also}"
            ));
        }
    }
    // A frame flagged with a quirk came from a real peer: the marker is the
    // opt-in to encode it.
    let quirk = match fields.optional("quirk") {
        None => None,
        Some(quirk) => Some(quirk.as_str().and_then(|q| q.parse().ok()).ok_or_else(|| {
            format!(
                "field `quirk` must be one of {}, found {quirk}",
                Quirk::NAMES.join(", ")
            )
        })?),
    };
    let mut raw = Raw {
        quirk,
        byte: None,
        trailing: Vec::new(),
    };
    let mut bytes = Vec::new();
    let encoded = if Command::NAMES.contains(&kind) && want != Want::Reports {
        let command = read_command(kind, &mut fields, dialect, &mut bytes, &mut raw)?;
        fields.finish(&format!("for type {kind}"))?;
        match quirk {
            None => command
                .to_buf_in(dialect)
                .map(MessageBuf::from)
                .map_err(|e| e.to_string()),
            Some(_) => encode_marked(command.in_dialect(dialect).even_if_refused(), &raw, |f| {
                CommandBuf::parse_in(f, dialect).map(Into::into)
            }),
        }
    } else if Report::NAMES.contains(&kind) && want != Want::Commands {
        let report = read_report(kind, &mut fields, dialect, &mut bytes)?;
        fields.finish(&format!("for type {kind}"))?;
        let lenient = matches!(report, Report::Unknown { .. });
        match quirk {
            None => report
                .to_buf_in(dialect)
                .map(MessageBuf::from)
                .map_err(|e| e.to_string()),
            Some(_) => encode_marked(report.in_dialect(dialect).even_if_refused(), &raw, |f| {
                ReportBuf::parse_in(f, dialect, lenient).map(Into::into)
            }),
        }
    } else {
        let names = match want {
            Want::Commands => Command::NAMES,
            Want::Reports => Report::NAMES,
            Want::Any => Message::NAMES,
        };
        return Err(unknown_type(kind, names));
    };
    let encoded = encoded.map_err(|e| format!("cannot encode {kind} for {dialect}: {e}"))?;
    check_marked(encoded, quirk, dialect)
}

/// The frame of a marked line: `encoder`'s, with the bytes the line gives
/// put in (see [`Raw::apply`]), as the decoder parses it.
fn encode_marked<E: Encode>(
    encoder: E,
    raw: &Raw,
    parse: impl FnOnce(&[u8]) -> Result<MessageBuf, Error>,
) -> Result<MessageBuf, String> {
    let mut out = [0u8; MAX_REPORT_FRAME];
    let n = encoder.encode(&mut out).map_err(|e| e.to_string())?;
    parse(raw.apply(&mut out, n)).map_err(|e| e.to_string())
}

/// `encoded`, if its frame has the quirk the line says (none or one).
fn check_marked(
    encoded: MessageBuf,
    quirk: Option<Quirk>,
    dialect: Dialect,
) -> Result<MessageBuf, String> {
    let found = encoded.quirk();
    match (quirk, found) {
        (None, _) => Ok(encoded),
        (Some(said), Some(found)) if said == found => Ok(encoded),
        (Some(said), Some(other)) => Err(format!(
            "the line says \"quirk\":\"{said}\", but its frame for {dialect} has `{other}`"
        )),
        (Some(said), None) => Err(format!(
            "the line says \"quirk\":\"{said}\", but its frame for {dialect} has no quirk: \
             leave `quirk` out"
        )),
    }
}

impl Raw {
    /// The frame of `out[..n]` with the line's own bytes put in (`LEN`
    /// counts the trailing ones).
    fn apply<'o>(&self, out: &'o mut [u8], n: usize) -> &'o [u8] {
        if let Some((at, byte)) = self.byte {
            if let Some(slot) = out.get_mut(at).filter(|_| at < n) {
                *slot = byte;
            }
        }
        let end = (n + self.trailing.len()).min(out.len());
        if let Some(dst) = out.get_mut(n..end) {
            dst.copy_from_slice(&self.trailing[..end - n]);
        }
        if let Some(len) = out.first_mut() {
            *len = len.wrapping_add(self.trailing.len() as u8);
        }
        &out[..end]
    }

    /// Whether the line's quirk is `quirk`.
    fn is(&self, quirk: Quirk) -> bool {
        self.quirk == Some(quirk)
    }
}

fn read_as<'de, D: Deserializer<'de>>(
    deserializer: D,
    dialect: Dialect,
    want: Want,
) -> Result<MessageBuf, D::Error> {
    let value = Value::deserialize(deserializer)?;
    read_line(&value, dialect, want).map_err(de::Error::custom)
}

impl MessageBuf {
    /// Deserialize a command or report of the JSON-lines schema, encoded
    /// for `dialect` (`Deserialize` reads mirte 1.3). Which fields a type
    /// has depends on the dialect: upstream 1.1's I2C commands have no
    /// `msg_id`, only mirte 1.3's `encoder_new` has `pulls`, and so on.
    ///
    /// ```
    /// use robowire::telemetrix::{Dialect, MessageBuf};
    ///
    /// let line = r#"{"type":"i2c_read","port":0,"addr":104,"reg":117,"n":1,"no_stop":0}"#;
    /// let mut json = serde_json::Deserializer::from_str(line);
    /// let message = MessageBuf::deserialize_in(&mut json, Dialect::Upstream11)?;
    /// assert_eq!(&message[..], &[0x06, 0x0B, 0x00, 0x68, 0x75, 0x01, 0x00]);
    /// # Ok::<(), serde_json::Error>(())
    /// ```
    pub fn deserialize_in<'de, D: Deserializer<'de>>(
        deserializer: D,
        dialect: Dialect,
    ) -> Result<Self, D::Error> {
        read_as(deserializer, dialect, Want::Any)
    }
}

/// A command or report of the JSON-lines schema, encoded for mirte 1.3 (see
/// [`MessageBuf::deserialize_in`]). `offset` and `len` are ignored.
impl<'de> Deserialize<'de> for MessageBuf {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_as(deserializer, Dialect::Mirte13, Want::Any)
    }
}

impl CommandBuf {
    /// Deserialize a command of the JSON-lines schema, encoded for
    /// `dialect` (see [`MessageBuf::deserialize_in`]).
    pub fn deserialize_in<'de, D: Deserializer<'de>>(
        deserializer: D,
        dialect: Dialect,
    ) -> Result<Self, D::Error> {
        let message = read_as(deserializer, dialect, Want::Commands)?;
        CommandBuf::parse_in(message.frame(), dialect).map_err(de::Error::custom)
    }
}

/// A command of the JSON-lines schema, encoded for mirte 1.3.
impl<'de> Deserialize<'de> for CommandBuf {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        CommandBuf::deserialize_in(deserializer, Dialect::Mirte13)
    }
}

impl ReportBuf {
    /// Deserialize a report of the JSON-lines schema, encoded for `dialect`
    /// (see [`MessageBuf::deserialize_in`]).
    pub fn deserialize_in<'de, D: Deserializer<'de>>(
        deserializer: D,
        dialect: Dialect,
    ) -> Result<Self, D::Error> {
        let message = read_as(deserializer, dialect, Want::Reports)?;
        let lenient = matches!(message.message(), Message::Report(Report::Unknown { .. }));
        ReportBuf::parse_in(message.frame(), dialect, lenient).map_err(de::Error::custom)
    }
}

/// A report of the JSON-lines schema, encoded for mirte 1.3.
impl<'de> Deserialize<'de> for ReportBuf {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        ReportBuf::deserialize_in(deserializer, Dialect::Mirte13)
    }
}

/// The longest byte array a frame can carry.
const MAX_BYTES: usize = MAX_REPORT_FRAME - 1;

fn u8_(f: &mut Fields<'_>, key: &str) -> Result<u8, String> {
    f.int(key, 0, 255).map(|v| v as u8)
}

fn u16_(f: &mut Fields<'_>, key: &str) -> Result<u16, String> {
    f.int(key, 0, 65535).map(|v| v as u16)
}

fn i8_(f: &mut Fields<'_>, key: &str) -> Result<i8, String> {
    f.int(key, -128, 127).map(|v| v as i8)
}

/// Encoder steps: a signed byte, never 0.
fn steps_(f: &mut Fields<'_>, key: &str) -> Result<i8, String> {
    match i8_(f, key)? {
        0 => Err(format!(
            "field `{key}` must not be 0: the firmware reports an encoder only when it moved \
             (-128..=-1 or 1..=127)"
        )),
        steps => Ok(steps),
    }
}

fn i16_(f: &mut Fields<'_>, key: &str) -> Result<i16, String> {
    f.int(key, -32768, 32767).map(|v| v as i16)
}

/// An integer `min..=max` that fits a byte.
fn ranged(f: &mut Fields<'_>, key: &str, min: u8, max: u8) -> Result<u8, String> {
    f.int(key, i64::from(min), i64::from(max)).map(|v| v as u8)
}

/// A GPIO number, `0..=29`.
/// A length or index the firmware holds up to `max`: any byte from `min`
/// on a line marked [`Quirk::PastFirmwareBuffer`].
fn past_buffer(f: &mut Fields<'_>, key: &str, min: u8, max: u8, raw: &Raw) -> Result<u8, String> {
    let max = if raw.is(Quirk::PastFirmwareBuffer) {
        u8::MAX
    } else {
        max
    };
    ranged(f, key, min, max)
}

fn pin_(f: &mut Fields<'_>, key: &str) -> Result<u8, String> {
    ranged(f, key, 0, PIN_COUNT - 1)
}

/// An analog pin `pin`: GPIO 26..=30 in mirte 1.3, ADC 0..=4 before.
fn analog_pin(f: &mut Fields<'_>, dialect: Dialect) -> Result<u8, String> {
    match dialect {
        Dialect::Mirte13 => ranged(f, "pin", 26, 30),
        Dialect::Mirte12 | Dialect::Upstream11 => ranged(f, "pin", 0, 4),
    }
}

/// The pin of MODIFY_REPORTING's analog types: [`analog_pin`], or in mirte
/// 1.2 and upstream 1.1 with the quirk that allows it the GPIO number
/// 26..=30 those dialects' clients send.
fn reporting_analog_pin(f: &mut Fields<'_>, dialect: Dialect, raw: &Raw) -> Result<u8, String> {
    if raw.is(Quirk::AnalogReportingPinNotAdc) {
        u8_(f, "pin")
    } else {
        analog_pin(f, dialect)
    }
}

/// A flag: `true` or `false`.
fn flag(f: &mut Fields<'_>, key: &str) -> Result<bool, String> {
    let value = f.value(key)?;
    value
        .as_bool()
        .ok_or_else(|| format!("field `{key}` must be true or false, found {value}"))
}

/// A level: 0 or 1.
fn level(f: &mut Fields<'_>, key: &str) -> Result<bool, String> {
    f.int(key, 0, 1).map(|v| v == 1)
}

/// The level of a digital write or report: `value` (0 or 1), or, for one
/// release, the Rust field's name `high` (`true`/`false` or 0/1).
fn digital_value(f: &mut Fields<'_>) -> Result<bool, String> {
    if !f.has("value") && f.has("high") {
        let value = f.value("high")?;
        return match (value.as_bool(), value.as_i64()) {
            (Some(high), _) => Ok(high),
            (None, Some(v @ (0 | 1))) => Ok(v == 1),
            _ => Err(format!(
                "field `high` must be true, false, 0 or 1, found {value}"
            )),
        };
    }
    level(f, "value")
}

fn f32_(f: &mut Fields<'_>, key: &str) -> Result<f32, String> {
    read_f32(f.value(key)?).map_err(|e| format!("field `{key}` {e}"))
}

fn byte(value: &Value) -> Result<u8, String> {
    read_int(value, 0, 255).map(|v| v as u8)
}

/// An array of bytes.
fn bytes(f: &mut Fields<'_>, key: &str) -> Result<Vec<u8>, String> {
    let value = f.value(key)?;
    let items = value
        .as_array()
        .filter(|items| items.len() <= MAX_BYTES)
        .ok_or_else(|| {
            format!("field `{key}` must be an array of at most {MAX_BYTES} bytes, found {value}")
        })?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| byte(item).map_err(|e| format!("field `{key}[{i}]` {e}")))
        .collect()
}

/// An array of bytes kept in `buf`, borrowed for the message being read
/// (every message has at most one, its last field).
fn bytes_in<'b>(f: &mut Fields<'_>, key: &str, buf: &'b mut Vec<u8>) -> Result<&'b [u8], String> {
    *buf = bytes(f, key)?;
    Ok(buf)
}

/// An array of objects, each read by `read`.
fn objects<T>(
    f: &mut Fields<'_>,
    key: &str,
    mut read: impl FnMut(&mut Fields<'_>) -> Result<T, String>,
) -> Result<Vec<T>, String> {
    let value = f.value(key)?;
    let items = value
        .as_array()
        .filter(|items| items.len() <= MAX_BYTES)
        .ok_or_else(|| format!("field `{key}` must be an array of objects, found {value}"))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let map = item
                .as_object()
                .ok_or_else(|| format!("field `{key}[{i}]` must be an object, found {item}"))?;
            let mut fields = Fields::new(map);
            let value = read(&mut fields).map_err(|e| format!("in `{key}[{i}]`: {e}"))?;
            fields.finish_nested(&format!("in `{key}[{i}]`"))?;
            Ok(value)
        })
        .collect()
}

/// A nested object, read by `read` and then checked for unknown members.
fn nested<T>(
    f: &mut Fields<'_>,
    key: &str,
    read: impl FnOnce(&mut Fields<'_>) -> Result<T, String>,
) -> Result<T, String> {
    let mut fields = f.object(key)?;
    let value = read(&mut fields).map_err(|e| format!("in `{key}`: {e}"))?;
    fields.finish_nested(&format!("in `{key}`"))?;
    Ok(value)
}

/// One of `names`, as a string; returns its index.
fn name(f: &mut Fields<'_>, key: &str, names: &[&str]) -> Result<usize, String> {
    let value = f.value(key)?;
    value
        .as_str()
        .and_then(|s| names.iter().position(|n| *n == s))
        .ok_or_else(|| {
            format!(
                "field `{key}` must be one of {}, found {value}",
                names.join(", ")
            )
        })
}

/// A type byte: one of `names`, or a number 0..=255.
fn type_byte(f: &mut Fields<'_>, key: &str, names: &[&str]) -> Result<u8, String> {
    let value = f.value(key)?;
    if let Some(s) = value.as_str() {
        if let Some(i) = names.iter().position(|n| *n == s) {
            return Ok(i as u8);
        }
    } else if let Ok(v) = read_int(value, 0, 255) {
        return Ok(v as u8);
    }
    Err(format!(
        "field `{key}` must be one of {} or a number 0..=255, found {value}",
        names.join(", ")
    ))
}

fn sensor_type(f: &mut Fields<'_>) -> Result<SensorType, String> {
    let t = type_byte(f, "sensor_type", SensorType::NAMES)?;
    SensorType::from_u8(t).ok_or_else(|| format!("field `sensor_type` {t} is no known sensor type"))
}

fn module_type(f: &mut Fields<'_>) -> Result<ModuleType, String> {
    let t = type_byte(f, "module_type", ModuleType::NAMES)?;
    ModuleType::from_u8(t).ok_or_else(|| format!("field `module_type` {t} is no known module type"))
}

fn rgb(f: &mut Fields<'_>) -> Result<Rgb, String> {
    Ok(Rgb {
        r: u8_(f, "r")?,
        g: u8_(f, "g")?,
        b: u8_(f, "b")?,
    })
}

/// The members of a `plain` row's command, from the command table (a
/// `custom` row's are read by [`read_command`]).
/// The members of a command `kind` (one of [`Command::NAMES`]), from the
/// command table: a `plain` row's by their kinds, a `custom` row's by its
/// `read` code.
macro_rules! command_reader {
    ($($(#[$vm:meta])* $n:literal $id:ident $name:literal [$($v:ident),+] in [$($d:ident),+] len $lens:tt
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        fn read_command<'b>(
            kind: &str,
            f: &mut Fields<'_>,
            dialect: Dialect,
            buf: &'b mut Vec<u8>,
            raw: &mut Raw,
        ) -> Result<Command<'b>, String> {
            Ok(match kind {
                $($name => read_row!(f, buf, Command (f, dialect, buf, raw), $codec $($p)? { $($body)* }),)*
                other => return Err(format!("unknown type `{other}`")),
            })
        }
    };
}

/// Read a row's members as an `$enum`: a `plain` row's by their kinds (a
/// report row names its variant in brackets), a `custom` row's by its
/// `read` code, its parameters bound to the values in `$ctx`.
macro_rules! read_row {
    ($fields:ident, $buf:ident, $enum:ident $ctx:tt, $([$($vs:ident)+])? custom {
        variants $vars:tt parse $pp:tt $pb:tt write $wp:tt $wb:tt fields $fp:tt $fb:tt
        read ($($param:ident),*) { $($body:tt)* } $($hooks:tt)*
    }) => {{
        bind_hook!(($($param),*) = $ctx);
        $($body)*
    }};
    ($fields:ident, $buf:ident, $enum:ident $ctx:tt, [$p:ident] plain $body:tt) => {
        read_row!($fields, $buf, $enum $ctx, plain $p $body)
    };
    ($fields:ident, $buf:ident, $enum:ident $ctx:tt,
        plain $p:ident { $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)? }) => {
        $enum::$p { $($f: read_member!($fields, $buf, $key, $kind $(($($arg)*))?),)* }
    };
}

/// Read one member of a `plain` row.
macro_rules! read_member {
    ($fields:ident, $buf:ident, $key:literal, counted_pins $args:tt) => {
        bytes_in($fields, $key, $buf)?
    };
    ($fields:ident, $buf:ident, $key:literal, nonzero_u32) => {
        $fields.int($key, 1, i64::from(u32::MAX))? as u32
    };
    ($fields:ident, $buf:ident, $key:literal, trailing_u16_pair($a:literal, $b:literal)) => {
        match ($fields.has($a), $fields.has($b)) {
            (false, false) => None,
            _ => Some((u16_($fields, $a)?, u16_($fields, $b)?)),
        }
    };
    ($fields:ident, $buf:ident, $key:literal, counted($count:literal $(, $max:literal)?)) => {
        bytes_in($fields, $key, $buf)?
    };
    ($fields:ident, $buf:ident, $key:literal, trailing_flag) => {
        if $fields.has($key) {
            Some(flag($fields, $key)?)
        } else {
            None
        }
    };
    ($fields:ident, $buf:ident, $key:literal, u8) => {
        u8_($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, rest) => {
        bytes_in($fields, $key, $buf)?
    };
    ($fields:ident, $buf:ident, $key:literal, array $args:tt) => {
        $fields.array($key, byte)?
    };
    ($fields:ident, $buf:ident, $key:literal, u16) => {
        u16_($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, u16_max($max:literal)) => {
        $fields.int($key, 0, $max)? as u16
    };
    ($fields:ident, $buf:ident, $key:literal, i16) => {
        i16_($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, type_check($($names:tt)*)) => {
        type_byte($fields, $key, $($names)*)?
    };
    ($fields:ident, $buf:ident, $key:literal, i8) => {
        i8_($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, i32) => {
        $fields.int($key, i64::from(i32::MIN), i64::from(i32::MAX))? as i32
    };
    ($fields:ident, $buf:ident, $key:literal, f32) => {
        f32_($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, f32s($n:literal)) => {
        f32s::<$n>($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, i16s($n:literal)) => {
        i16s::<$n>($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, pin) => {
        pin_($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, flag) => {
        flag($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, level) => {
        level($fields, $key)?
    };
    ($fields:ident, $buf:ident, $key:literal, rgb) => {
        rgb($fields)?
    };
    ($fields:ident, $buf:ident, $key:literal, range($lo:literal, $hi:literal)) => {
        ranged($fields, $key, $lo, $hi)?
    };
}

super::table::command_table!(command_reader);

/// The members of a report `kind` (one of [`Report::NAMES`]), from the
/// report table as for commands, and an unknown report's.
macro_rules! report_reader {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        fn read_report<'b>(
            kind: &str,
            f: &mut Fields<'_>,
            dialect: Dialect,
            buf: &'b mut Vec<u8>,
        ) -> Result<Report<'b>, String> {
            Ok(match kind {
                $($($name)|+ => read_row!(f, buf, Report (f, dialect, buf, kind), [$($($v)+)+] $codec { $($body)* }),)*
                "unknown_report" => Report::Unknown {
                    id: u8_(f, "id")?,
                    payload: bytes_in(f, "payload", buf)?,
                },
                other => return Err(format!("unknown type `{other}`")),
            })
        }
    };
}

super::table::report_table!(report_reader);

impl SensorNew {
    /// SENSOR_NEW's members (`subtype` and the subtype's fields).
    fn read_members(f: &mut Fields<'_>, dialect: Dialect) -> Result<Self, String> {
        Ok(match name(f, "subtype", &["check", "add"])? {
            0 => SensorNew::Check {
                sensor_type: type_byte(f, "sensor_type", SensorType::NAMES)?,
            },
            // mirte 1.2's own layout: the settings bytes sent, 0 to 6.
            _ if dialect == Dialect::Mirte12 => {
                let sensor_num = u8_(f, "sensor_num")?;
                let sensor_type = sensor_type(f)?;
                let settings = bytes(f, "settings")?;
                SensorNew::AddMirte12 {
                    sensor_num,
                    sensor_type,
                    settings: List::from_slice(&settings).map_err(|_| {
                        format!(
                            "field `settings` must be an array of at most 6 bytes, found {} bytes",
                            settings.len()
                        )
                    })?,
                }
            }
            _ => SensorNew::Add {
                sensor_num: u8_(f, "sensor_num")?,
                sensor_type: sensor_type(f)?,
                settings: f.array("settings", byte)?,
            },
        })
    }
}

impl<'b> ModuleNew<'b> {
    /// MODULE_NEW's members (`subtype` and the subtype's fields); the init's
    /// bytes are read into `buf`.
    fn read_members(f: &mut Fields<'_>, buf: &'b mut Vec<u8>) -> Result<Self, String> {
        Ok(match name(f, "subtype", &["check", "add"])? {
            0 => ModuleNew::Check {
                module_type: type_byte(f, "module_type", ModuleType::NAMES)?,
            },
            _ => {
                let module_num = u8_(f, "module_num")?;
                let module_type = module_type(f)?;
                ModuleNew::Add {
                    module_num,
                    init: nested(f, "init", move |i| module_init(module_type, i, buf))?,
                }
            }
        })
    }
}

/// The JSON members of a module's init and reports, from the module table.
macro_rules! module_readers {
    ($($(#[$tm:meta])* $n:literal $t:ident $name:literal
        init $init:tt data $data:ident $dsec:tt
        $(reports [$($rv:ident),+ $(,)?] $reports:tt)?;)*) => {
        fn module_init<'b>(
            module_type: ModuleType,
            f: &mut Fields<'_>,
            buf: &'b mut Vec<u8>,
        ) -> Result<ModuleInit<'b>, String> {
            Ok(match module_type {
                $(ModuleType::$t => {
                    piece!(read (f, buf) expr { compile_error!("an init without read") }, $init)
                })*
            })
        }

        fn module_report<'b>(
            module_type: ModuleType,
            f: &mut Fields<'_>,
            buf: &'b mut Vec<u8>,
        ) -> Result<ModuleReport<'b>, String> {
            Ok(match module_type {
                $($(ModuleType::$t => {
                    piece!(read (f, buf) expr { compile_error!("reports without read") }, $reports)
                })?)*
                // The types without reports.
                _ => return Err(format!("module type {module_type} sends no reports")),
            })
        }

        /// Typed MODULE_DATA: the module's message, built into the data bytes
        /// by the module (which checks it as its parser would).
        fn module_data(
            module_type: ModuleType,
            f: &mut Fields<'_>,
        ) -> Result<List<u8, COMMAND_PAYLOAD_MAX>, String> {
            let data = match module_type {
                $(ModuleType::$t => module_data_members!(f, $data, $dsec).to_data(),)*
            };
            data.map_err(|e| e.to_string())
        }
    };
}

/// A module's MODULE_DATA members: its data table's, or the row's `read`.
macro_rules! module_data_members {
    ($f:ident, $data:ident, table) => {
        $data::read_members($f)?
    };
    ($f:ident, $data:ident, $section:tt) => {
        piece!(read ($f) expr { compile_error!("data without read") }, $section)
    };
}

super::table::module_table!(module_readers);

/// A module data table's serde reader: `subtype` names the row, whose
/// members are read by their kind (a `custom` row's by its `read` piece).
macro_rules! module_data_reader {
    ($(#[$em:meta])* $enum:ident; $($(#[$vm:meta])* $n:literal $name:literal [$($v:ident),+]
        $codec:ident $($p:ident)? { $($body:tt)* };)*) => {
        impl $enum {
            /// The data's members (`subtype` and the row's fields).
            fn read_members(f: &mut Fields<'_>) -> Result<Self, String> {
                const SUBTYPES: &[&str] = &[$($name),*];
                let subtype = SUBTYPES
                    .get(name(f, "subtype", SUBTYPES)?)
                    .copied()
                    .unwrap_or_default();
                // `read_member!` takes the buffer the byte-list kinds read
                // into; no module data row has one.
                let _buf: &mut Vec<u8> = &mut Vec::new();
                Ok(match subtype {
                    $($name => read_row!(f, _buf, $enum (f), $codec $($p)? { $($body)* }),)*
                    other => return Err(format!("unknown subtype `{other}`")),
                })
            }
        }
    };
}

super::table::hiwonder_table!(module_data_reader);
super::table::ssd1306_table!(module_data_reader);

/// A mirte 1.3 sonar distance: centimetres, or a sentinel's name.
fn sonar_cm(f: &mut Fields<'_>) -> Result<u16, String> {
    let value = f.value("cm")?;
    match value.as_str() {
        Some("no_echo") => Ok(SONAR_NO_ECHO),
        Some("out_of_range") => Ok(SONAR_OUT_OF_RANGE),
        Some("stale") => Ok(SONAR_STALE),
        _ => read_int(value, 0, 65535).map(|v| v as u16).map_err(|_| {
            format!(
                "field `cm` must be an integer or \"no_echo\", \"out_of_range\" or \"stale\", \
                 found {value}"
            )
        }),
    }
}

fn f32s<const N: usize>(f: &mut Fields<'_>, key: &str) -> Result<[f32; N], String> {
    f.array(key, read_f32)
}

fn i16s<const N: usize>(f: &mut Fields<'_>, key: &str) -> Result<[i16; N], String> {
    f.array(key, |v| read_int(v, -32768, 32767).map(|v| v as i16))
}

/// A sensor reading's members, from the sensor table.
macro_rules! sensor_reading_reader {
    ($($(#[$rm:meta])* $n:literal $t:ident $codec:ident { $($body:tt)* };)*) => {
        fn sensor_reading(sensor_type: SensorType, f: &mut Fields<'_>) -> Result<SensorReading, String> {
            // `read_member!` takes the buffer the byte-list kinds read into;
            // no reading has one.
            let _buf: &mut Vec<u8> = &mut Vec::new();
            Ok(match sensor_type {
                $(SensorType::$t => read_row!(f, _buf, SensorReading (f), [$t] $codec { $($body)* }),)*
                #[allow(unreachable_patterns)]
                _ => return Err(format!("sensor type `{}` sends no readings", sensor_type.name())),
            })
        }
    };
}

super::table::sensor_table!(sensor_readings, sensor_reading_reader);
