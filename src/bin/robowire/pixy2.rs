//! `robowire decode pixy2` and `robowire encode pixy2`.
//!
//! Every decoded frame prints with `checksum` (its frame form) and every field
//! of its payload, reserved bytes included where they are not zero, so that
//! `encode` rebuilds the exact bytes.

use std::marker::PhantomData;

use crate::driver::{self, DecodeCommon, Decoded, EncodeCommon, Output, Printer, Protocol};
use crate::input::{ByteSource, HexBytes, Input, RawBytes};
use crate::json::{read_int, Fields, JsonLine};
use crate::Failure;
use clap::{Args, ValueEnum};
use robowire::pixy2::{
    Barcode, Block, BlocksBuf, Both, ChangeProg, Device, DeviceError, Element, Error, FeaturesBuf,
    FirmwareType, Form, Framing, GetBlocks, GetFeatures, GetFps, GetResolution, GetRgb, GetVersion,
    Host, Intersection, IntersectionLine, Malformed, MessageBuf, Packet, ProgName, Request,
    Resolution, Response, ResponseBuf, ReverseVector, Section, SetCameraBrightness, SetDefaultTurn,
    SetLamp, SetLed, SetMode, SetNextTurn, SetServos, SetVector, Side, Vector, Version,
    DEVICE_BUFFER, DEVICE_MAX_PAYLOAD, FTYPE_BARCODE, FTYPE_INTERSECTION, FTYPE_VECTOR,
    HOST_BUFFER, INTERSECTION_SLOTS, MAX_BLOCKS, MAX_FRAME, MAX_PAYLOAD,
};
use robowire::stream::StreamDecoder;
use robowire::Encode;
use serde_json::Value;

/// The JSON schema, printed by `--help` after the options.
const DECODE_SCHEMA: &str = "\
Output: one JSON object per line, per frame, in input order:
  offset    byte offset of the frame's first sync byte (0xae or 0xaf) in the input
            (in the decoded bytes with --hex)
  len       frame length in bytes
  type      requests: change_prog, get_resolution, get_version,
            set_camera_brightness, set_servos, set_led, set_lamp, get_fps,
            get_blocks, get_features, set_mode, set_vector, set_next_turn,
            set_default_turn, reverse_vector, get_rgb;
            responses: result, error, resolution, version, blocks, features
  checksum  true for the checksum form (af c1), false without (ae c1)
Request fields: change_prog name (the payload without its trailing NULs, a NUL
  inside written \\u0000; an array of bytes if it is not UTF-8) and
  payload_len (only when not 33, the official host's padded length);
  get_resolution reserved (only when not 0); set_camera_brightness brightness;
  set_servos pan, tilt; set_led r, g, b; set_lamp upper, lower; get_blocks
  sigmap, max_blocks; get_features scope, features; set_mode mode; set_vector
  index; set_next_turn, set_default_turn angle; get_rgb x, y, saturate.
Response fields: result value (i32); error code (general, busy,
  invalid_request, type_unsupported, button_override, prog_changing, or the
  number of any other code); resolution width, height; version hardware,
  firmware_major, firmware_minor, firmware_build, firmware_type (the 10-byte
  field, written as change_prog's name is); blocks blocks (array of objects
  signature, x, y, width, height, angle, index, age); features sections (array, in wire order, of {\"vectors\":[...]},
  {\"intersections\":[...]}, {\"barcodes\":[...]}, or {\"ftype\":N,\"data\":[...]}
  for an unknown feature type). A vector is x0, y0, x1, y1, index, flags; a
  barcode x, y, flags, code; an intersection x, y and lines (its n valid lines,
  each index, angle), plus reserved bytes where not 0 and unused_slots (the
  6 - n slots after the lines) where not all zero.
With --errors, rejected candidates are objects with offset and error (no type):
  {\"offset\":12,\"error\":\"checksum\",\"expected\":781,\"found\":780}
  {\"offset\":40,\"error\":\"unknown_type\",\"packet_type\":50}
  {\"offset\":52,\"error\":\"bad_length\",\"packet_type\":18,\"payload_len\":3}
  {\"offset\":60,\"error\":\"too_long\",\"packet_type\":2,\"payload_len\":65,\"max\":64}
  {\"offset\":70,\"error\":\"malformed\",\"packet_type\":49,\"what\":\"section_length\",
   \"ftype\":1,\"flen\":5}
  {\"offset\":90,\"error\":\"superseded\",\"len\":10}
  {\"offset\":99,\"error\":\"truncated\",\"len\":5}
At the end, one summary line goes to stderr (frames, bytes, bytes skipped,
checksum failures, other rejections, malformed frames).

Exit status: 0 on success, 2 on usage errors and invalid input (bad hex),
1 on I/O errors. A closed stdout pipe ends the run quietly.

Examples:
  robowire decode pixy2 --hex tests/data/pixy2_conversation.hex
  robowire decode pixy2 --from device --checksum-only --errors spi_miso.bin
  echo 'ae c1 20 02 ff ff' | robowire decode pixy2 --hex";

const ENCODE_SCHEMA: &str = "\
Input: JSON lines in the schema `robowire decode pixy2` prints; offset and len
are ignored, unknown fields are errors. checksum may be left out: requests are
then written without a checksum (as the official host sends them) and
responses with one (as the device always sends them). Fields that decode
prints only when they are not 0 (reserved bytes, unused_slots) or not 33
(change_prog payload_len) may be left out. Blank lines and diagnostic events
(objects with error and no type) are skipped. A malformed line or out-of-range
value is reported with its line number and nothing is written for it; the other
lines are still encoded and the exit status is 2.

Examples:
  robowire decode pixy2 capture.bin | robowire encode pixy2 > same-frames.bin
  echo '{\"type\":\"get_blocks\",\"sigmap\":255,\"max_blocks\":255}' | robowire encode pixy2 --hex
  echo '{\"type\":\"error\",\"code\":\"busy\"}' | robowire encode pixy2 --hex";

/// Who sent the bytes being decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Sender {
    /// Requests only (bytes a host sent; what the device decodes).
    Host,
    /// Responses only (bytes a device sent; what the host decodes).
    Device,
    /// Requests and responses.
    Any,
}

/// `robowire decode pixy2`.
#[derive(Debug, Args)]
#[command(after_long_help = DECODE_SCHEMA)]
pub struct DecodeArgs {
    /// Accept requests (host), responses (device) or both (any): who sent the
    /// bytes. Requests are held to the device's 64-byte receive limit.
    #[arg(long, value_enum, display_order = 1, default_value_t = Sender::Any)]
    pub from: Sender,
    /// Accept only the checksum form (af c1), as a Pixy2 always answers over
    /// SPI, I2C and UART: then no unverifiable frame can be decoded.
    #[arg(long, display_order = 2)]
    pub checksum_only: bool,
    /// The options every decode shares.
    #[command(flatten)]
    pub common: DecodeCommon,
}

/// `robowire encode pixy2`.
#[derive(Debug, Args)]
#[command(after_long_help = ENCODE_SCHEMA)]
pub struct EncodeArgs {
    /// The options every encode shares.
    #[command(flatten)]
    pub common: EncodeCommon,
}

/// Run `decode pixy2`.
pub fn decode(args: &DecodeArgs, out: &mut Output) -> Result<Decoded, Failure> {
    let input = Input::open(args.common.input.as_deref())?;
    let mut printer = Printer::new(out, args.common.errors);
    let mut source: Box<dyn ByteSource> = if args.common.hex {
        Box::new(HexBytes::new(input))
    } else {
        Box::new(RawBytes(input))
    };
    let source = source.as_mut();
    let chunk = args.common.chunk as usize;
    let only = args.checksum_only;
    match args.from {
        Sender::Host => driver::decode_stream::<Pixy2<Device>, DEVICE_BUFFER>(
            StreamDecoder::new(framing(only)),
            source,
            chunk,
            &mut printer,
        ),
        Sender::Device => driver::decode_stream::<Pixy2<Host>, HOST_BUFFER>(
            StreamDecoder::new(framing(only)),
            source,
            chunk,
            &mut printer,
        ),
        Sender::Any => driver::decode_stream::<Pixy2<Both>, HOST_BUFFER>(
            StreamDecoder::new(framing(only)),
            source,
            chunk,
            &mut printer,
        ),
    }
}

fn framing<S: Side>(checksum_only: bool) -> Framing<S> {
    if checksum_only {
        Framing::new().checksum_only()
    } else {
        Framing::new()
    }
}

/// Run `encode pixy2`.
pub fn encode(args: &EncodeArgs, out: &mut Output) -> Result<(), Failure> {
    let input = Input::open(args.common.input.as_deref())?;
    // Encoding does not depend on the side: every type name is unique.
    driver::encode_lines::<Pixy2<Both>>(input, args.common.hex, out)
}

/// The Pixy2 protocol as the tool sees it, decoding the messages of side `S`.
pub struct Pixy2<S>(PhantomData<S>);

impl<S: Side> Protocol for Pixy2<S>
where
    S::Owned: Describe,
{
    type Framing = Framing<S>;

    fn describe(message: &S::Owned, line: &mut JsonLine) {
        message.describe(line);
    }

    fn describe_error(error: &Error, line: &mut JsonLine) {
        describe_error(error, line);
    }

    fn encode(fields: Fields<'_>, frame: &mut Vec<u8>) -> Result<(), String> {
        encode_frame(fields, frame)
    }
}

// ---------------------------------------------------------------- names

const REQUEST_NAMES: [&str; 16] = [
    "change_prog",
    "get_resolution",
    "get_version",
    "set_camera_brightness",
    "set_servos",
    "set_led",
    "set_lamp",
    "get_fps",
    "get_blocks",
    "get_features",
    "set_mode",
    "set_vector",
    "set_next_turn",
    "set_default_turn",
    "reverse_vector",
    "get_rgb",
];

fn request_name(request: &Request) -> &'static str {
    let i = match request {
        Request::ChangeProg(_) => 0,
        Request::GetResolution(_) => 1,
        Request::GetVersion(_) => 2,
        Request::SetCameraBrightness(_) => 3,
        Request::SetServos(_) => 4,
        Request::SetLed(_) => 5,
        Request::SetLamp(_) => 6,
        Request::GetFps(_) => 7,
        Request::GetBlocks(_) => 8,
        Request::GetFeatures(_) => 9,
        Request::SetMode(_) => 10,
        Request::SetVector(_) => 11,
        Request::SetNextTurn(_) => 12,
        Request::SetDefaultTurn(_) => 13,
        Request::ReverseVector(_) => 14,
        Request::GetRgb(_) => 15,
    };
    REQUEST_NAMES[i]
}

fn response_name(response: &Response<'_>) -> &'static str {
    match response {
        Response::Result(_) => "result",
        Response::Error(_) => "error",
        Response::Resolution(_) => "resolution",
        Response::Version(_) => "version",
        Response::Blocks(_) => "blocks",
        Response::Features(_) => "features",
    }
}

/// The device's error codes by name (after `SER_ERROR_*`).
const DEVICE_ERRORS: [(&str, DeviceError); 6] = [
    ("general", DeviceError::General),
    ("busy", DeviceError::Busy),
    ("invalid_request", DeviceError::InvalidRequest),
    ("type_unsupported", DeviceError::TypeUnsupported),
    ("button_override", DeviceError::ButtonOverride),
    ("prog_changing", DeviceError::ProgChanging),
];

// ---------------------------------------------------------------- decode

/// A decoded message of any side, printed after `offset` and `len`.
pub trait Describe {
    /// Write `type`, `checksum` and the fields.
    fn describe(&self, line: &mut JsonLine);
}

impl Describe for Packet<Request> {
    fn describe(&self, line: &mut JsonLine) {
        describe_request(&self.body, self.form, line);
    }
}

impl Describe for Packet<ResponseBuf> {
    fn describe(&self, line: &mut JsonLine) {
        describe_response(&self.body.as_response(), self.form, line);
    }
}

impl Describe for Packet<MessageBuf> {
    fn describe(&self, line: &mut JsonLine) {
        match &self.body {
            MessageBuf::Request(r) => describe_request(r, self.form, line),
            MessageBuf::Response(r) => describe_response(&r.as_response(), self.form, line),
        }
    }
}

fn head(line: &mut JsonLine, name: &str, form: Form) {
    line.field("type", name);
    line.field("checksum", form == Form::Checksum);
}

/// A reserved byte, written only when it is not zero.
fn reserved(line: &mut JsonLine, value: u8) {
    if value != 0 {
        line.field("reserved", value);
    }
}

/// A NUL-padded text field: the bytes without their trailing NULs, as a
/// string (a NUL inside is `\u0000`), or as an array of bytes if they are not
/// UTF-8.
fn text(line: &mut JsonLine, key: &str, bytes: &[u8]) {
    let end = bytes.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
    match std::str::from_utf8(&bytes[..end]) {
        Ok(s) => line.field(key, s),
        Err(_) => line.array(key, bytes[..end].iter().copied()),
    }
}

fn describe_request(request: &Request, form: Form, line: &mut JsonLine) {
    head(line, request_name(request), form);
    match *request {
        Request::ChangeProg(ChangeProg(ref name)) => {
            let payload = name.as_payload();
            text(line, "name", payload);
            if payload.len() != ProgName::PADDED_LEN {
                line.field("payload_len", payload.len());
            }
        }
        Request::GetResolution(GetResolution { reserved: r }) => reserved(line, r),
        Request::GetVersion(_) | Request::GetFps(_) | Request::ReverseVector(_) => {}
        Request::SetCameraBrightness(SetCameraBrightness(b)) => line.field("brightness", b),
        Request::SetServos(SetServos { pan, tilt }) => {
            line.field("pan", pan);
            line.field("tilt", tilt);
        }
        Request::SetLed(SetLed { r, g, b }) => {
            line.field("r", r);
            line.field("g", g);
            line.field("b", b);
        }
        Request::SetLamp(SetLamp { upper, lower }) => {
            line.field("upper", upper);
            line.field("lower", lower);
        }
        Request::GetBlocks(GetBlocks { sigmap, max_blocks }) => {
            line.field("sigmap", sigmap);
            line.field("max_blocks", max_blocks);
        }
        Request::GetFeatures(GetFeatures { scope, features }) => {
            line.field("scope", scope);
            line.field("features", features);
        }
        Request::SetMode(SetMode(mode)) => line.field("mode", mode),
        Request::SetVector(SetVector(index)) => line.field("index", index),
        Request::SetNextTurn(SetNextTurn(angle))
        | Request::SetDefaultTurn(SetDefaultTurn(angle)) => {
            line.field("angle", angle);
        }
        Request::GetRgb(GetRgb { x, y, saturate }) => {
            line.field("x", x);
            line.field("y", y);
            line.field("saturate", saturate);
        }
    }
}

fn describe_response(response: &Response<'_>, form: Form, line: &mut JsonLine) {
    head(line, response_name(response), form);
    match *response {
        Response::Result(value) => line.field("value", value),
        Response::Error(error) => match DEVICE_ERRORS.iter().find(|(_, e)| *e == error) {
            Some((name, _)) => line.field("code", *name),
            None => line.field("code", error.code()),
        },
        Response::Resolution(Resolution { width, height }) => {
            line.field("width", width);
            line.field("height", height);
        }
        Response::Version(v) => {
            line.field("hardware", v.hardware);
            line.field("firmware_major", v.firmware_major);
            line.field("firmware_minor", v.firmware_minor);
            line.field("firmware_build", v.firmware_build);
            text(line, "firmware_type", &v.firmware_type.0);
        }
        Response::Blocks(blocks) => line.objects("blocks", blocks.iter(), describe_block),
        Response::Features(features) => {
            line.objects(
                "sections",
                features.sections(),
                |o, section| match section {
                    Section::Vectors(v) => o.objects("vectors", v, describe_vector),
                    Section::Intersections(i) => {
                        o.objects("intersections", i, describe_intersection)
                    }
                    Section::Barcodes(b) => o.objects("barcodes", b, describe_barcode),
                    Section::Unknown { ftype, data } => {
                        o.field("ftype", ftype);
                        o.array("data", data.iter().copied());
                    }
                },
            );
        }
    }
}

fn describe_block(o: &mut JsonLine, b: Block) {
    o.field("signature", b.signature);
    o.field("x", b.x);
    o.field("y", b.y);
    o.field("width", b.width);
    o.field("height", b.height);
    o.field("angle", b.angle);
    o.field("index", b.index);
    o.field("age", b.age);
}

fn describe_vector(o: &mut JsonLine, v: Vector) {
    o.field("x0", v.x0);
    o.field("y0", v.y0);
    o.field("x1", v.x1);
    o.field("y1", v.y1);
    o.field("index", v.index);
    o.field("flags", v.flags);
}

fn describe_barcode(o: &mut JsonLine, b: Barcode) {
    o.field("x", b.x);
    o.field("y", b.y);
    o.field("flags", b.flags);
    o.field("code", b.code);
}

fn describe_intersection(o: &mut JsonLine, i: Intersection) {
    o.field("x", i.x);
    o.field("y", i.y);
    reserved(o, i.reserved);
    // A view never holds more than six lines.
    let n = usize::from(i.n).min(INTERSECTION_SLOTS);
    let (lines, unused) = i.slots.split_at(n);
    o.objects("lines", lines.iter().copied(), describe_line);
    if unused.iter().any(|s| *s != IntersectionLine::default()) {
        o.objects("unused_slots", unused.iter().copied(), describe_line);
    }
}

fn describe_line(o: &mut JsonLine, l: IntersectionLine) {
    o.field("index", l.index);
    o.field("angle", l.angle);
    reserved(o, l.reserved);
}

fn describe_error(error: &Error, line: &mut JsonLine) {
    match *error {
        Error::Checksum { expected, found } => {
            line.field("error", "checksum");
            line.field("expected", expected);
            line.field("found", found);
        }
        Error::Sync { found } => {
            line.field("error", "sync");
            line.field("found", found);
        }
        Error::UnknownType { packet_type } => {
            line.field("error", "unknown_type");
            line.field("packet_type", packet_type);
        }
        Error::BadLength { packet_type, len } => {
            line.field("error", "bad_length");
            line.field("packet_type", packet_type);
            line.field("payload_len", len);
        }
        Error::TooLong {
            packet_type,
            len,
            max,
        } => {
            line.field("error", "too_long");
            line.field("packet_type", packet_type);
            line.field("payload_len", len);
            line.field("max", max);
        }
        Error::Truncated { len } => {
            line.field("error", "truncated");
            line.field("len", len);
        }
        Error::Superseded { len } => {
            line.field("error", "superseded");
            line.field("len", len);
        }
        Error::Malformed { packet_type, what } => {
            line.field("error", "malformed");
            line.field("packet_type", packet_type);
            describe_malformed(&what, line);
        }
        // A rejection this tool does not know yet: its message.
        ref other => {
            line.field("error", "other");
            line.field("message", other.to_string().as_str());
        }
    }
}

fn describe_malformed(what: &Malformed, line: &mut JsonLine) {
    match *what {
        Malformed::SectionPastEnd { offset } => {
            line.field("what", "section_past_end");
            line.field("section_offset", offset);
        }
        Malformed::SectionLength { ftype, flen } => {
            line.field("what", "section_length");
            line.field("ftype", ftype);
            line.field("flen", flen);
        }
        Malformed::IntersectionLines { n } => {
            line.field("what", "intersection_lines");
            line.field("n", n);
        }
        Malformed::TooLong { len } => {
            line.field("what", "too_long");
            line.field("payload_len", len);
        }
        Malformed::BlocksLength { len } => {
            line.field("what", "blocks_length");
            line.field("payload_len", len);
        }
        Malformed::ZeroSigmap => line.field("what", "zero_sigmap"),
        ref other => {
            line.field("what", "other");
            line.field("message", other.to_string().as_str());
        }
    }
}

// ---------------------------------------------------------------- encode

fn encode_frame(fields: Fields<'_>, frame: &mut Vec<u8>) -> Result<(), String> {
    let mut top = Obj {
        fields,
        path: String::new(),
    };
    let kind = top.fields.string("type")?;
    // Type names are unique across the two directions.
    let message = if REQUEST_NAMES.contains(&kind) {
        MessageBuf::Request(read_request(kind, &mut top)?)
    } else {
        MessageBuf::Response(read_response(kind, &mut top)?)
    };
    let form = match top.fields.optional("checksum") {
        None => match message {
            MessageBuf::Request(_) => Form::NoChecksum,
            MessageBuf::Response(_) => Form::Checksum,
        },
        Some(Value::Bool(true)) => Form::Checksum,
        Some(Value::Bool(false)) => Form::NoChecksum,
        Some(other) => {
            return Err(format!(
                "field `checksum` must be true or false, found {other}"
            ))
        }
    };
    top.fields.finish(&format!("for type {kind}"))?;
    let mut out = [0u8; MAX_FRAME];
    let n = Packet::new(form, message)
        .encode(&mut out)
        .map_err(|e| e.to_string())?;
    frame.extend_from_slice(&out[..n]);
    Ok(())
}

/// An object's members read strictly, with their path for messages
/// (`blocks[2].x`); the top level has an empty path.
struct Obj<'a> {
    fields: Fields<'a>,
    path: String,
}

impl<'a> Obj<'a> {
    fn name(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_owned()
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

    /// A text field as [`text`] writes it: a string or an array of bytes, at
    /// most `max` bytes.
    fn text(&mut self, key: &str, max: usize) -> Result<Vec<u8>, String> {
        let name = self.name(key);
        let value = self.value(key)?;
        let bytes = match value {
            Value::String(s) => s.as_bytes().to_vec(),
            Value::Array(_) => self.bytes(key)?,
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
        value
            .as_array()
            .ok_or_else(|| format!("field `{name}` must be an array of bytes, found {value}"))?
            .iter()
            .map(|b| read_int(b, 0, 255).map(|v| v as u8))
            .collect::<Result<Vec<u8>, String>>()
            .map_err(|e| format!("field `{name}` byte {e}"))
    }

    /// Fail on a member nobody took.
    fn finish(self) -> Result<(), String> {
        self.fields.finish_nested(&format!("in `{}`", self.path))
    }
}

fn read_request(kind: &str, f: &mut Obj<'_>) -> Result<Request, String> {
    Ok(match kind {
        "change_prog" => {
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
            Request::ChangeProg(ChangeProg(name))
        }
        "get_resolution" => Request::GetResolution(GetResolution {
            reserved: f.u8_or_zero("reserved")?,
        }),
        "get_version" => Request::GetVersion(GetVersion),
        "set_camera_brightness" => {
            Request::SetCameraBrightness(SetCameraBrightness(f.u8("brightness")?))
        }
        "set_servos" => Request::SetServos(SetServos {
            pan: f.u16("pan")?,
            tilt: f.u16("tilt")?,
        }),
        "set_led" => Request::SetLed(SetLed {
            r: f.u8("r")?,
            g: f.u8("g")?,
            b: f.u8("b")?,
        }),
        "set_lamp" => Request::SetLamp(SetLamp {
            upper: f.u8("upper")?,
            lower: f.u8("lower")?,
        }),
        "get_fps" => Request::GetFps(GetFps),
        "get_blocks" => {
            let sigmap = f.value("sigmap")?;
            let sigmap = read_int(sigmap, 1, 255)
                .map_err(|e| format!("field `sigmap` {e} (the device refuses 0 with ERROR -3)"))?
                as u8;
            Request::GetBlocks(GetBlocks {
                sigmap,
                max_blocks: f.u8("max_blocks")?,
            })
        }
        "get_features" => Request::GetFeatures(GetFeatures {
            scope: f.u8("scope")?,
            features: f.u8("features")?,
        }),
        "set_mode" => Request::SetMode(SetMode(f.u8("mode")?)),
        "set_vector" => Request::SetVector(SetVector(f.u8("index")?)),
        "set_next_turn" => Request::SetNextTurn(SetNextTurn(f.i16("angle")?)),
        "set_default_turn" => Request::SetDefaultTurn(SetDefaultTurn(f.i16("angle")?)),
        "reverse_vector" => Request::ReverseVector(ReverseVector),
        "get_rgb" => Request::GetRgb(GetRgb {
            x: f.u16("x")?,
            y: f.u16("y")?,
            saturate: f.u8("saturate")?,
        }),
        other => return Err(format!("unknown type `{other}`")),
    })
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
        "features" => ResponseBuf::Features(read_features(f)?),
        other => return Err(format!("unknown type `{other}`")),
    })
}

/// A device error code: its name, or any code as a number.
fn read_device_error(value: &Value) -> Result<DeviceError, String> {
    if let Some(name) = value.as_str() {
        return DEVICE_ERRORS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, e)| *e)
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

/// The sections of a features response, in order, into the exact payload.
fn read_features(f: &mut Obj<'_>) -> Result<FeaturesBuf, String> {
    let mut payload = Vec::new();
    for mut section in f.objects("sections", MAX_PAYLOAD / 2)? {
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
            "field `sections` makes a {}-byte payload, at most {MAX_PAYLOAD} fit",
            payload.len()
        ));
    }
    FeaturesBuf::from_payload(&payload).map_err(|e| format!("field `sections`: {e}"))
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
