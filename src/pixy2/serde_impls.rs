//! The `serde` form of Pixy2 messages, envelopes and errors: the JSON-lines
//! schema of `robowire decode pixy2` / `robowire encode pixy2`.
//!
//! Every message is one object: `type` (a name of [`Request::NAMES`] or
//! [`Response::NAMES`]), then, in an [`Envelope`], `checksum`, then the
//! fields. Reserved bytes are written only when they are not zero, a
//! changeProg `payload_len` only when it is not 33, intersection
//! `unused_slots` only when one of them is not all zero. NUL-padded text (a
//! program name, the firmware type) is a string without its trailing NULs,
//! or an array of bytes if it is not UTF-8.
//!
//! Reading is strict, through [`Fields`]: every member must be known (`offset`
//! and `len` are ignored), every value in range, and the message names the
//! field by its path (`sections[0].barcodes[0].code`).

use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;

use serde::de::{Deserialize, Deserializer, Error as _};
use serde::ser::{Serialize, SerializeMap, Serializer};

use crate::encode::Encode;
use crate::serde_support::{read_int, unknown_type, Fields, Value};

use super::blocks::{Block, BlocksBuf, MAX_BLOCKS};
use super::envelope::{Envelope, Message, MessageBuf};
use super::error::{DeviceError, Error, Malformed};
use super::features::{
    Element, Features, FeaturesBuf, Intersection, IntersectionLine, Section, FTYPE_BARCODE,
    FTYPE_INTERSECTION, FTYPE_VECTOR, INTERSECTION_SLOTS,
};
use super::quirk::Quirk;
use super::request::{
    ChangeProg, GetBlocks, GetFeatures, GetFps, GetResolution, GetRgb, GetVersion, ProgName,
    Request, ReverseVector, SetCameraBrightness, SetDefaultTurn, SetLamp, SetLed, SetMode,
    SetNextTurn, SetServos, SetVector,
};
use super::response::{FirmwareType, Resolution, Response, ResponseBuf, Version};
use super::table::kind_shown;
use super::wire::{Form, DEVICE_MAX_PAYLOAD, MAX_FRAME_LEN, MAX_PAYLOAD};

// ---------------------------------------------------------------- serialize

/// NUL-padded text: the bytes without their trailing NULs, as a string (a
/// NUL inside stays), or as an array of bytes if they are not UTF-8.
struct Text<'a>(&'a [u8]);

impl Serialize for Text<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let end = self.0.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
        let bytes = &self.0[..end];
        match core::str::from_utf8(bytes) {
            Ok(s) => serializer.serialize_str(s),
            Err(_) => serializer.collect_seq(bytes),
        }
    }
}

/// A sequence of elements, written as it is iterated.
struct Seq<I>(I);

impl<I> Serialize for Seq<I>
where
    I: Iterator + Clone,
    I::Item: Serialize,
{
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.0.clone())
    }
}

/// The message's `type`, `checksum` when the form is known, then its fields.
fn serialize_request<S: Serializer>(
    request: &Request,
    checksum: Option<bool>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let mut map = serializer.serialize_map(None)?;
    map.serialize_entry("type", request.name())?;
    if let Some(checksum) = checksum {
        map.serialize_entry("checksum", &checksum)?;
    }
    serialize_payload(request, &mut map)?;
    // What the device refuses is marked: the marker lets the line encode.
    if let Some(quirk) = request.quirk() {
        map.serialize_entry("quirk", quirk.name())?;
    }
    map.end()
}

fn serialize_response<S: Serializer>(
    response: &Response<'_>,
    checksum: Option<bool>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    let mut map = serializer.serialize_map(None)?;
    map.serialize_entry("type", response.name())?;
    if let Some(checksum) = checksum {
        map.serialize_entry("checksum", &checksum)?;
    }
    match *response {
        Response::Result(value) => map.serialize_entry("value", &value)?,
        Response::Error(error) => map.serialize_entry("code", &error)?,
        Response::Resolution(Resolution { width, height }) => {
            map.serialize_entry("width", &width)?;
            map.serialize_entry("height", &height)?;
        }
        Response::Version(v) => {
            map.serialize_entry("hardware", &v.hardware)?;
            map.serialize_entry("firmware_major", &v.firmware_major)?;
            map.serialize_entry("firmware_minor", &v.firmware_minor)?;
            map.serialize_entry("firmware_build", &v.firmware_build)?;
            map.serialize_entry("firmware_type", &Text(&v.firmware_type.0))?;
        }
        Response::Blocks(ref blocks) => map.serialize_entry("blocks", blocks)?,
        Response::Features(ref features) => map.serialize_entry("sections", features)?,
    }
    map.end()
}

/// As `robowire decode pixy2` prints it, without `checksum`:
/// `{"type":"set_servos","pan":500,"tilt":20}`.
impl Serialize for Request {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_request(self, None, serializer)
    }
}

/// As `robowire decode pixy2` prints it, without `checksum`:
/// `{"type":"error","code":"busy"}`.
impl Serialize for Response<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_response(self, None, serializer)
    }
}

/// As [`Response`].
impl Serialize for ResponseBuf {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_response(&self.as_response(), None, serializer)
    }
}

/// As the request or response it holds.
impl Serialize for Message<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Request(r) => serialize_request(r, None, serializer),
            Self::Response(r) => serialize_response(r, None, serializer),
        }
    }
}

/// As the request or response it holds.
impl Serialize for MessageBuf {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.as_message().serialize(serializer)
    }
}

fn checksum_of(form: Form) -> Option<bool> {
    Some(form == Form::Checksum)
}

/// The request with `checksum` after `type`.
impl Serialize for Envelope<Request> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_request(&self.body, checksum_of(self.form), serializer)
    }
}

/// The response with `checksum` after `type`.
impl Serialize for Envelope<Response<'_>> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_response(&self.body, checksum_of(self.form), serializer)
    }
}

/// The response with `checksum` after `type`.
impl Serialize for Envelope<ResponseBuf> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_response(&self.body.as_response(), checksum_of(self.form), serializer)
    }
}

/// The message with `checksum` after `type`: a line of `robowire decode
/// pixy2` less `offset` and `len`.
impl Serialize for Envelope<Message<'_>> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let checksum = checksum_of(self.form);
        match &self.body {
            Message::Request(r) => serialize_request(r, checksum, serializer),
            Message::Response(r) => serialize_response(r, checksum, serializer),
        }
    }
}

/// As [`Envelope<Message>`].
impl Serialize for Envelope<MessageBuf> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        Envelope::new(self.form, self.body.as_message()).serialize(serializer)
    }
}

/// `"no_checksum"` or `"checksum"`.
impl Serialize for Form {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// A known code's name (`"busy"`), any other code its number (`-7`).
impl Serialize for DeviceError {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.name() {
            Some(name) => serializer.serialize_str(name),
            None => serializer.serialize_i8(self.code()),
        }
    }
}

/// The sections in wire order, each `{"vectors":[…]}`,
/// `{"intersections":[…]}`, `{"barcodes":[…]}` or, for a feature type this
/// codec does not know, `{"ftype":8,"data":[1,2,3]}`.
impl Serialize for Features<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.sections())
    }
}

/// As [`Features`].
impl Serialize for FeaturesBuf {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.view().serialize(serializer)
    }
}

/// One member naming the kind, holding the elements; an unknown kind is
/// `ftype` and `data`.
impl Serialize for Section<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        match self {
            Section::Vectors(v) => map.serialize_entry("vectors", &Seq(v.clone()))?,
            Section::Intersections(i) => map.serialize_entry("intersections", &Seq(i.clone()))?,
            Section::Barcodes(b) => map.serialize_entry("barcodes", &Seq(b.clone()))?,
            Section::Unknown { ftype, data } => {
                map.serialize_entry("ftype", ftype)?;
                map.serialize_entry("data", &Seq(data.iter()))?;
            }
        }
        map.end()
    }
}

/// `x`, `y`, `reserved` (only when not 0), `lines` (the `n` valid lines) and
/// `unused_slots` (the slots after them, only when one is not all zero).
impl Serialize for Intersection {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("x", &self.x)?;
        map.serialize_entry("y", &self.y)?;
        if self.reserved != 0 {
            map.serialize_entry("reserved", &self.reserved)?;
        }
        let n = usize::from(self.n).min(INTERSECTION_SLOTS);
        let (lines, unused) = self.slots.split_at(n);
        map.serialize_entry("lines", lines)?;
        if unused.iter().any(|s| *s != IntersectionLine::default()) {
            map.serialize_entry("unused_slots", unused)?;
        }
        map.end()
    }
}

/// `index`, `angle` and `reserved` (only when not 0).
impl Serialize for IntersectionLine {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("index", &self.index)?;
        map.serialize_entry("angle", &self.angle)?;
        if self.reserved != 0 {
            map.serialize_entry("reserved", &self.reserved)?;
        }
        map.end()
    }
}

/// `{"error":"checksum","expected":781,"found":780}` and so on: the `error`
/// tag, then the details.
impl Serialize for Error {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        match *self {
            Error::Checksum { expected, found } => {
                map.serialize_entry("error", "checksum")?;
                map.serialize_entry("expected", &expected)?;
                map.serialize_entry("found", &found)?;
            }
            Error::Sync { found } => {
                map.serialize_entry("error", "sync")?;
                map.serialize_entry("found", &found)?;
            }
            Error::UnknownType { packet_type } => {
                map.serialize_entry("error", "unknown_type")?;
                map.serialize_entry("packet_type", &packet_type)?;
            }
            Error::BadLength { packet_type, len } => {
                map.serialize_entry("error", "bad_length")?;
                map.serialize_entry("packet_type", &packet_type)?;
                map.serialize_entry("payload_len", &len)?;
            }
            Error::TooLong {
                packet_type,
                len,
                max,
            } => {
                map.serialize_entry("error", "too_long")?;
                map.serialize_entry("packet_type", &packet_type)?;
                map.serialize_entry("payload_len", &len)?;
                map.serialize_entry("max", &max)?;
            }
            Error::Truncated { len } => {
                map.serialize_entry("error", "truncated")?;
                map.serialize_entry("len", &len)?;
            }
            Error::Superseded { len } => {
                map.serialize_entry("error", "superseded")?;
                map.serialize_entry("len", &len)?;
            }
            Error::TrailingBytes { extra } => {
                map.serialize_entry("error", "trailing_bytes")?;
                map.serialize_entry("extra", &extra)?;
            }
            Error::Malformed { packet_type, what } => {
                map.serialize_entry("error", "malformed")?;
                map.serialize_entry("packet_type", &packet_type)?;
                malformed_entries(&what, &mut map)?;
            }
        }
        map.end()
    }
}

fn malformed_entries<M: SerializeMap>(what: &Malformed, map: &mut M) -> Result<(), M::Error> {
    match *what {
        Malformed::SectionPastEnd { offset } => {
            map.serialize_entry("what", "section_past_end")?;
            map.serialize_entry("section_offset", &offset)
        }
        Malformed::SectionLength { ftype, flen } => {
            map.serialize_entry("what", "section_length")?;
            map.serialize_entry("ftype", &ftype)?;
            map.serialize_entry("flen", &flen)
        }
        Malformed::IntersectionLines { n } => {
            map.serialize_entry("what", "intersection_lines")?;
            map.serialize_entry("n", &n)
        }
        Malformed::TooLong { len } => {
            map.serialize_entry("what", "too_long")?;
            map.serialize_entry("payload_len", &len)
        }
        Malformed::BlocksLength { len } => {
            map.serialize_entry("what", "blocks_length")?;
            map.serialize_entry("payload_len", &len)
        }
        Malformed::ZeroSigmap => map.serialize_entry("what", "zero_sigmap"),
    }
}

/// `{"what":"intersection_lines","n":7}`: the `what` tag, then the details.
impl Serialize for Malformed {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        malformed_entries(self, &mut map)?;
        map.end()
    }
}

// ---------------------------------------------------------------- deserialize

/// An object's members read strictly, with their path for messages
/// (`blocks[2].x`); the top level has an empty path.
struct Obj<'a> {
    fields: Fields<'a>,
    path: String,
}

impl<'a> Obj<'a> {
    fn top(value: &'a Value, what: &str) -> Result<Self, String> {
        Ok(Obj {
            fields: Fields::of(value, what)?,
            path: String::new(),
        })
    }

    fn name(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    fn value(&mut self, key: &str) -> Result<&'a Value, String> {
        let name = self.name(key);
        self.fields
            .optional(key)
            .ok_or_else(|| format!("missing field `{name}`"))
    }

    fn int(&mut self, key: &str, min: i64, max: i64) -> Result<i64, String> {
        let value = self.value(key)?;
        read_int(value, min, max).map_err(|e| format!("field `{}` {e}", self.name(key)))
    }

    fn u8(&mut self, key: &str) -> Result<u8, String> {
        self.int(key, 0, 255).map(|v| v as u8)
    }

    fn u16(&mut self, key: &str) -> Result<u16, String> {
        self.int(key, 0, 65535).map(|v| v as u16)
    }

    fn i16(&mut self, key: &str) -> Result<i16, String> {
        self.int(key, -32768, 32767).map(|v| v as i16)
    }

    /// A byte that may be left out when it is zero.
    fn u8_or_zero(&mut self, key: &str) -> Result<u8, String> {
        if self.fields.has(key) {
            self.u8(key)
        } else {
            Ok(0)
        }
    }

    /// An array of at most `max` objects.
    fn objects(&mut self, key: &str, max: usize) -> Result<Vec<Obj<'a>>, String> {
        let name = self.name(key);
        let value = self.value(key)?;
        objects_of(value, &name, max)
    }

    /// A text field as [`Text`] writes it: a string or an array of bytes, at
    /// most `max` bytes.
    fn text(&mut self, key: &str, max: usize) -> Result<Vec<u8>, String> {
        let name = self.name(key);
        let value = self.value(key)?;
        let bytes = match value {
            Value::Str(s) => s.as_bytes().to_vec(),
            Value::Seq(_) => bytes_of(value, &name)?,
            other => {
                return Err(format!(
                    "field `{name}` must be a string or an array of bytes, found {other}"
                ))
            }
        };
        if bytes.len() > max {
            return Err(format!(
                "field `{name}` is {} bytes long, at most {max} fit",
                bytes.len()
            ));
        }
        Ok(bytes)
    }

    /// An array of bytes.
    fn bytes(&mut self, key: &str) -> Result<Vec<u8>, String> {
        let name = self.name(key);
        let value = self.value(key)?;
        bytes_of(value, &name)
    }

    /// Fail on a member nobody took.
    fn finish(self) -> Result<(), String> {
        if self.path.is_empty() {
            self.fields.finish_nested("in the object")
        } else {
            self.fields.finish_nested(&format!("in `{}`", self.path))
        }
    }
}

/// `value`, named `name`, as an array of at most `max` objects.
fn objects_of<'a>(value: &'a Value, name: &str, max: usize) -> Result<Vec<Obj<'a>>, String> {
    let items = value
        .as_array()
        .ok_or_else(|| format!("field `{name}` must be an array, found {value}"))?;
    if items.len() > max {
        return Err(format!(
            "field `{name}` holds {} entries, at most {max} fit",
            items.len()
        ));
    }
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let path = format!("{name}[{i}]");
            item.as_object()
                .map(|map| Obj {
                    fields: Fields::new(map),
                    path: path.clone(),
                })
                .ok_or_else(|| format!("field `{path}` must be an object, found {item}"))
        })
        .collect()
}

/// `value`, named `name`, as an array of bytes.
fn bytes_of(value: &Value, name: &str) -> Result<Vec<u8>, String> {
    value
        .as_array()
        .ok_or_else(|| format!("field `{name}` must be an array of bytes, found {value}"))?
        .iter()
        .map(|b| read_int(b, 0, 255).map(|v| v as u8))
        .collect::<Result<Vec<u8>, String>>()
        .map_err(|e| format!("field `{name}` byte {e}"))
}

/// One line: the message and the form its `checksum` names, if it has one.
/// The order of the checks is the command-line tool's: `type`, the fields,
/// `checksum`, then members nobody took, then what the encoder refuses.
fn read_message(value: &Value) -> Result<(Option<Form>, MessageBuf), String> {
    let mut top = Obj::top(value, "a Pixy2 message")?;
    let kind = top.fields.string("type")?;
    let quirk = match top.fields.optional("quirk") {
        None => None,
        Some(quirk) => Some(
            Quirk::ALL
                .into_iter()
                .find(|q| quirk.as_str() == Some(q.name()))
                .ok_or_else(|| format!("field `quirk` must be sigmap_zero, found {quirk}"))?,
        ),
    };
    // Type names are unique across the two directions.
    let message = if Request::NAMES.contains(&kind) {
        let request = read_request(kind, &mut top, quirk)?;
        if quirk.is_some() && request.quirk() != quirk {
            return Err(format!(
                "the line says \"quirk\", but the device takes this {kind}: leave `quirk` out"
            ));
        }
        MessageBuf::Request(request)
    } else if quirk.is_some() {
        return Err(format!("field `quirk` is for requests, not {kind}"));
    } else {
        MessageBuf::Response(read_response(kind, &mut top)?)
    };
    let form = match top.fields.optional("checksum") {
        None => None,
        Some(Value::Bool(true)) => Some(Form::Checksum),
        Some(Value::Bool(false)) => Some(Form::NoChecksum),
        Some(other) => {
            return Err(format!(
                "field `checksum` must be true or false, found {other}"
            ))
        }
    };
    top.fields.finish(&format!("for type {kind}"))?;
    let default = match message {
        MessageBuf::Request(_) => Form::NoChecksum,
        MessageBuf::Response(_) => Form::Checksum,
    };
    let mut out = [0u8; MAX_FRAME_LEN];
    // A refused request got here only marked, and so asked for.
    Envelope::new(form.unwrap_or(default), message)
        .even_if_refused()
        .encode(&mut out)
        .map_err(|e| e.to_string())?;
    Ok((form, message))
}

/// A request's fields and its serde reader, from the request table (see
/// `table.rs`).
macro_rules! request_serde {
    ($($(#[$m:meta])* $ty:ident $name:literal $s:ident -> $resp:ident $payload:tt;)*) => {
        /// The request's fields after `type` (and `checksum`).
        fn serialize_payload<M: SerializeMap>(request: &Request, map: &mut M) -> Result<(), M::Error> {
            match request {
                $(Request::$s(_r) => serialize_fields!(map, _r, $payload),)*
            }
        }

        /// The request of type `kind` from its members.
        fn read_request(kind: &str, f: &mut Obj<'_>, quirk: Option<Quirk>) -> Result<Request, String> {
            Ok(match kind {
                $($name => Request::$s(read_fields!(f, quirk, $s, $payload)),)*
                other => return Err(format!("unknown type `{other}`")),
            })
        }
    };
}

macro_rules! serialize_fields {
    ($map:ident, $r:ident, custom) => {
        $r.serialize_fields($map)
    };
    ($map:ident, $r:ident, { $($f:tt : $kind:ident $key:literal),* $(,)? }) => {{
        $(if kind_shown!($kind, $r.$f) {
            $map.serialize_entry($key, &$r.$f)?;
        })*
        Ok(())
    }};
}

macro_rules! read_fields {
    ($obj:ident, $quirk:ident, $s:ident, custom) => {
        $s::read_fields($obj)?
    };
    ($obj:ident, $quirk:ident, $s:ident, { $($f:tt : $kind:ident $key:literal),* $(,)? }) => {
        $s { $($f: read_member!($obj, $quirk, $kind, $key),)* }
    };
}

macro_rules! read_member {
    ($obj:ident, $quirk:ident, u8, $key:literal) => {
        $obj.u8($key)?
    };
    ($obj:ident, $quirk:ident, u16, $key:literal) => {
        $obj.u16($key)?
    };
    ($obj:ident, $quirk:ident, i16, $key:literal) => {
        $obj.i16($key)?
    };
    ($obj:ident, $quirk:ident, reserved, $key:literal) => {
        $obj.u8_or_zero($key)?
    };
    ($obj:ident, $quirk:ident, sigmap, $key:literal) => {
        read_sigmap($obj, $quirk)?
    };
}

super::table::request_table!(request_serde);

/// getBlocks' signature map: 0 only with its quirk marker.
fn read_sigmap(f: &mut Obj<'_>, quirk: Option<Quirk>) -> Result<u8, String> {
    let sigmap = f.value("sigmap")?;
    Ok(if quirk == Some(Quirk::SigmapZero) {
        read_int(sigmap, 0, 255).map_err(|e| format!("field `sigmap` {e}"))?
    } else {
        read_int(sigmap, 1, 255).map_err(|e| {
            format!(
                "field `sigmap` {e} (the device refuses 0 with ERROR -3; decode marks \
                 such a request \"quirk\":\"sigmap_zero\": add that to the line to \
                 encode it anyway)"
            )
        })?
    } as u8)
}

/// The `custom` row: a name of any length, padded to `payload_len`.
impl ChangeProg {
    fn serialize_fields<M: SerializeMap>(&self, map: &mut M) -> Result<(), M::Error> {
        let payload = self.0.as_payload();
        map.serialize_entry("name", &Text(payload))?;
        if payload.len() != ProgName::PADDED_LEN {
            map.serialize_entry("payload_len", &payload.len())?;
        }
        Ok(())
    }

    fn read_fields(f: &mut Obj<'_>) -> Result<Self, String> {
        let max = DEVICE_MAX_PAYLOAD;
        let len = if f.fields.has("payload_len") {
            f.int("payload_len", 0, max as i64)? as usize
        } else {
            ProgName::PADDED_LEN
        };
        let name = f.text("name", max)?;
        if name.len() > len {
            return Err(format!(
                "field `name` is {} bytes long, more than the {len}-byte payload \
                 (give payload_len, up to {max})",
                name.len()
            ));
        }
        let mut payload = name;
        payload.resize(len, 0);
        // At most 64 bytes, so this cannot fail.
        let name = ProgName::from_payload(&payload)
            .ok_or_else(|| format!("a payload of {len} bytes is longer than {max}"))?;
        Ok(ChangeProg(name))
    }
}

fn read_response(kind: &str, f: &mut Obj<'_>) -> Result<ResponseBuf, String> {
    Ok(match kind {
        "result" => ResponseBuf::Result(f.int("value", i32::MIN.into(), i32::MAX.into())? as i32),
        "error" => ResponseBuf::Error(read_device_error(f.value("code")?)?),
        "resolution" => ResponseBuf::Resolution(Resolution {
            width: f.u16("width")?,
            height: f.u16("height")?,
        }),
        "version" => {
            let hardware = f.u16("hardware")?;
            let firmware_major = f.u8("firmware_major")?;
            let firmware_minor = f.u8("firmware_minor")?;
            let firmware_build = f.u16("firmware_build")?;
            let mut name = [0u8; 10];
            let bytes = f.text("firmware_type", name.len())?;
            name[..bytes.len()].copy_from_slice(&bytes);
            ResponseBuf::Version(Version {
                hardware,
                firmware_major,
                firmware_minor,
                firmware_build,
                firmware_type: FirmwareType(name),
            })
        }
        "blocks" => {
            let mut buf = BlocksBuf::new();
            for mut b in f.objects("blocks", MAX_BLOCKS)? {
                let block = Block {
                    signature: b.u16("signature")?,
                    x: b.u16("x")?,
                    y: b.u16("y")?,
                    width: b.u16("width")?,
                    height: b.u16("height")?,
                    angle: b.i16("angle")?,
                    index: b.u8("index")?,
                    age: b.u8("age")?,
                };
                b.finish()?;
                // At most MAX_BLOCKS objects were read.
                buf.push(block)
                    .map_err(|_| format!("more than {MAX_BLOCKS} blocks"))?;
            }
            ResponseBuf::Blocks(buf)
        }
        "features" => {
            let value = f.value("sections")?;
            ResponseBuf::Features(read_sections(value, &f.name("sections"))?)
        }
        other => return Err(unknown_type(other, &Message::NAMES)),
    })
}

/// A device error code: its name, or any code as a number.
fn read_device_error(value: &Value) -> Result<DeviceError, String> {
    if let Some(name) = value.as_str() {
        return DeviceError::NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| DeviceError::from_code(-1 - i as i8))
            .ok_or_else(|| {
                format!(
                    "field `code` `{name}` is no device error name (general, busy, \
                     invalid_request, type_unsupported, button_override, prog_changing) \
                     or code -128..=127"
                )
            });
    }
    read_int(value, -128, 127)
        .map(|code| DeviceError::from_code(code as i8))
        .map_err(|_| {
            format!(
                "field `code` must be a device error name or an integer -128..=127, found {value}"
            )
        })
}

/// The sections of a features response (`value`, named `name`), in order,
/// into the exact payload.
fn read_sections(value: &Value, name: &str) -> Result<FeaturesBuf, String> {
    let mut payload = Vec::new();
    for mut section in objects_of(value, name, MAX_PAYLOAD / 2)? {
        let start = payload.len();
        payload.extend([0, 0]);
        let ftype = if section.fields.has("vectors") {
            for mut v in section.objects("vectors", MAX_PAYLOAD)? {
                payload.extend([
                    v.u8("x0")?,
                    v.u8("y0")?,
                    v.u8("x1")?,
                    v.u8("y1")?,
                    v.u8("index")?,
                    v.u8("flags")?,
                ]);
                v.finish()?;
            }
            FTYPE_VECTOR
        } else if section.fields.has("intersections") {
            for mut i in section.objects("intersections", MAX_PAYLOAD)? {
                payload.extend(read_intersection(&mut i)?);
                i.finish()?;
            }
            FTYPE_INTERSECTION
        } else if section.fields.has("barcodes") {
            for mut b in section.objects("barcodes", MAX_PAYLOAD)? {
                payload.extend([b.u8("x")?, b.u8("y")?, b.u8("flags")?, b.u8("code")?]);
                b.finish()?;
            }
            FTYPE_BARCODE
        } else if section.fields.has("ftype") {
            let ftype = section.u8("ftype")?;
            if [FTYPE_VECTOR, FTYPE_INTERSECTION, FTYPE_BARCODE].contains(&ftype) {
                return Err(format!(
                    "field `{}` {ftype} is a known feature type: write its section as \
                     vectors, intersections or barcodes",
                    section.name("ftype")
                ));
            }
            payload.extend(section.bytes("data")?);
            ftype
        } else {
            return Err(format!(
                "field `{}` must have one of vectors, intersections, barcodes or ftype and data",
                section.path
            ));
        };
        let flen = payload.len() - start - 2;
        let flen = u8::try_from(flen).map_err(|_| {
            format!(
                "field `{}` is {flen} bytes long, at most 255 fit",
                section.path
            )
        })?;
        payload[start] = ftype;
        payload[start + 1] = flen;
        section.finish()?;
    }
    if payload.len() > MAX_PAYLOAD {
        return Err(format!(
            "field `{name}` makes a {}-byte payload, at most {MAX_PAYLOAD} fit",
            payload.len()
        ));
    }
    FeaturesBuf::from_payload(&payload).map_err(|e| format!("field `{name}`: {e}"))
}

/// Bytes of one intersection on the wire.
const INTERSECTION_LEN: usize = <Intersection as Element>::SIZE;

fn read_intersection(i: &mut Obj<'_>) -> Result<[u8; INTERSECTION_LEN], String> {
    let x = i.u8("x")?;
    let y = i.u8("y")?;
    let reserved = i.u8_or_zero("reserved")?;
    let mut slots = [IntersectionLine::default(); INTERSECTION_SLOTS];
    let lines = i.objects("lines", INTERSECTION_SLOTS)?;
    let n = lines.len();
    for (slot, l) in slots.iter_mut().zip(lines) {
        *slot = read_line(l)?;
    }
    if i.fields.has("unused_slots") {
        let path = i.name("unused_slots");
        let unused = i.objects("unused_slots", INTERSECTION_SLOTS - n)?;
        if unused.len() != INTERSECTION_SLOTS - n {
            return Err(format!(
                "field `{path}` must hold {} entries (the slots after the lines), found {}",
                INTERSECTION_SLOTS - n,
                unused.len()
            ));
        }
        for (slot, l) in slots[n..].iter_mut().zip(unused) {
            *slot = read_line(l)?;
        }
    }
    let mut out = [0u8; INTERSECTION_LEN];
    out[..4].copy_from_slice(&[x, y, n as u8, reserved]);
    for (slot, bytes) in slots.iter().zip(out[4..].chunks_exact_mut(4)) {
        let [a0, a1] = slot.angle.to_le_bytes();
        bytes.copy_from_slice(&[slot.index, slot.reserved, a0, a1]);
    }
    Ok(out)
}

fn read_line(mut l: Obj<'_>) -> Result<IntersectionLine, String> {
    let line = IntersectionLine {
        index: l.u8("index")?,
        angle: l.i16("angle")?,
        reserved: l.u8_or_zero("reserved")?,
    };
    l.finish()?;
    Ok(line)
}

/// Read the buffered input with `read`, turning its message into `D`'s error.
fn read_with<'de, D: Deserializer<'de>, T>(
    deserializer: D,
    read: impl FnOnce(&Value) -> Result<T, String>,
) -> Result<T, D::Error> {
    let value = Value::deserialize(deserializer)?;
    read(&value).map_err(D::Error::custom)
}

/// A line of `robowire encode pixy2`; `checksum` may be left out (requests
/// then take the no-checksum form, responses the checksum form).
impl<'de> Deserialize<'de> for Envelope<MessageBuf> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            let (form, body) = read_message(value)?;
            let form = form.unwrap_or(match body {
                MessageBuf::Request(_) => Form::NoChecksum,
                MessageBuf::Response(_) => Form::Checksum,
            });
            Ok(Envelope::new(form, body))
        })
    }
}

/// A message of either direction; `checksum` is read and dropped (as
/// `offset` and `len` are).
impl<'de> Deserialize<'de> for MessageBuf {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| read_message(value).map(|(_, m)| m))
    }
}

fn request_of(message: MessageBuf) -> Result<Request, String> {
    match message {
        MessageBuf::Request(r) => Ok(r),
        MessageBuf::Response(r) => Err(format!(
            "type `{}` is a response, not a request",
            r.as_response().name()
        )),
    }
}

fn response_of(message: MessageBuf) -> Result<ResponseBuf, String> {
    match message {
        MessageBuf::Response(r) => Ok(r),
        MessageBuf::Request(r) => Err(format!("type `{}` is a request, not a response", r.name())),
    }
}

/// A request; `checksum` is read and dropped (as `offset` and `len` are).
impl<'de> Deserialize<'de> for Request {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| request_of(read_message(value)?.1))
    }
}

/// A response; `checksum` is read and dropped (as `offset` and `len` are).
impl<'de> Deserialize<'de> for ResponseBuf {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| response_of(read_message(value)?.1))
    }
}

/// A request and its form; `checksum` may be left out (the no-checksum form).
impl<'de> Deserialize<'de> for Envelope<Request> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            let (form, body) = read_message(value)?;
            Ok(Envelope::new(
                form.unwrap_or(Form::NoChecksum),
                request_of(body)?,
            ))
        })
    }
}

/// A response and its form; `checksum` may be left out (the checksum form).
impl<'de> Deserialize<'de> for Envelope<ResponseBuf> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            let (form, body) = read_message(value)?;
            Ok(Envelope::new(
                form.unwrap_or(Form::Checksum),
                response_of(body)?,
            ))
        })
    }
}

/// `"no_checksum"` or `"checksum"`.
impl<'de> Deserialize<'de> for Form {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            value
                .as_str()
                .and_then(|name| name.parse().ok())
                .ok_or_else(|| {
                    format!("a frame form is \"no_checksum\" or \"checksum\", found {value}")
                })
        })
    }
}

/// A name of [`DeviceError::NAMES`] or a code, -128..=127.
impl<'de> Deserialize<'de> for DeviceError {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, read_device_error)
    }
}

/// The sections as [`Features`] writes them, checked as a features response
/// is.
impl<'de> Deserialize<'de> for FeaturesBuf {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| read_sections(value, "sections"))
    }
}

/// As [`Intersection`]'s `Serialize` writes it.
impl<'de> Deserialize<'de> for Intersection {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            let mut obj = Obj::top(value, "an intersection")?;
            let bytes = read_intersection(&mut obj)?;
            obj.finish()?;
            Intersection::read(&bytes).ok_or_else(|| "not an intersection".to_string())
        })
    }
}

/// As [`IntersectionLine`]'s `Serialize` writes it.
impl<'de> Deserialize<'de> for IntersectionLine {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            read_line(Obj::top(value, "an intersection line")?)
        })
    }
}

/// As [`Error`]'s `Serialize` writes it.
impl<'de> Deserialize<'de> for Error {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            let mut f = Obj::top(value, "a Pixy2 error")?;
            let kind = f.fields.string("error")?;
            let error = match kind {
                "checksum" => Error::Checksum {
                    expected: f.u16("expected")?,
                    found: f.u16("found")?,
                },
                "sync" => Error::Sync {
                    found: f.u8("found")?,
                },
                "unknown_type" => Error::UnknownType {
                    packet_type: f.u8("packet_type")?,
                },
                "bad_length" => Error::BadLength {
                    packet_type: f.u8("packet_type")?,
                    len: f.u8("payload_len")?,
                },
                "too_long" => Error::TooLong {
                    packet_type: f.u8("packet_type")?,
                    len: f.u8("payload_len")?,
                    max: f.u8("max")?,
                },
                "truncated" => Error::Truncated {
                    len: f.usize("len")?,
                },
                "superseded" => Error::Superseded {
                    len: f.usize("len")?,
                },
                "trailing_bytes" => Error::TrailingBytes {
                    extra: f.usize("extra")?,
                },
                "malformed" => Error::Malformed {
                    packet_type: f.u8("packet_type")?,
                    what: read_malformed(&mut f)?,
                },
                other => return Err(format!("unknown error `{other}`")),
            };
            f.fields.finish(&format!("for error {kind}"))?;
            Ok(error)
        })
    }
}

fn read_malformed(f: &mut Obj<'_>) -> Result<Malformed, String> {
    let what = f.fields.string("what")?;
    Ok(match what {
        "section_past_end" => Malformed::SectionPastEnd {
            offset: f.usize("section_offset")?,
        },
        "section_length" => Malformed::SectionLength {
            ftype: f.u8("ftype")?,
            flen: f.u8("flen")?,
        },
        "intersection_lines" => Malformed::IntersectionLines { n: f.u8("n")? },
        "too_long" => Malformed::TooLong {
            len: f.usize("payload_len")?,
        },
        "blocks_length" => Malformed::BlocksLength {
            len: f.usize("payload_len")?,
        },
        "zero_sigmap" => Malformed::ZeroSigmap,
        other => return Err(format!("unknown malformation `{other}`")),
    })
}

/// As [`Malformed`]'s `Serialize` writes it.
impl<'de> Deserialize<'de> for Malformed {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        read_with(deserializer, |value| {
            let mut f = Obj::top(value, "a Pixy2 payload problem")?;
            let what = read_malformed(&mut f)?;
            f.finish()?;
            Ok(what)
        })
    }
}

impl Obj<'_> {
    fn usize(&mut self, key: &str) -> Result<usize, String> {
        let max = i64::try_from(usize::MAX).unwrap_or(i64::MAX);
        self.int(key, 0, max).map(|v| v as usize)
    }
}
