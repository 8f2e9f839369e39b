//! `robowire decode pixy2` and `robowire encode pixy2`: the options, the
//! decoder they choose, and the help text. Messages print and read through
//! the library's serde form (`robowire::pixy2`), which is the schema below.

use crate::driver::{self, DecodeCommon, Decoded, EncodeCommon, Output, Peer, Printer, Schema};
use crate::Failure;
use clap::{Args, ValueEnum};
use robowire::pixy2::{
    self, DeviceError, Envelope, Framing, MessageBuf, Request, Response, Side, MAX_FRAME_LEN,
};
use robowire::units::FieldTable;
use robowire::Encode;

/// The JSON schema, printed by `--help` after the options; the type and
/// device error names come from the library.
fn decode_schema() -> String {
    let footer = driver::DECODE_FOOTER;
    let requests = driver::wrap(driver::listed(&Request::NAMES, "", ""), 22, 12, 80);
    let responses = driver::wrap(driver::listed(&Response::NAMES, "", ""), 23, 12, 80);
    let codes = driver::wrap(driver::listed(&DeviceError::NAMES, "", ""), 49, 2, 70);
    format!(
        "\
Output: one JSON object per line, per frame, in input order:
  offset    byte offset of the frame's first sync byte (0xae or 0xaf) in the input
            (in the decoded bytes with --hex)
  len       frame length in bytes
  type      requests: {requests};
            responses: {responses}
  checksum  true for the checksum form (af c1), false without (ae c1)
Request fields: change_prog name (the payload without its trailing NULs, a NUL
  inside written \\u0000; an array of bytes if it is not UTF-8) and
  payload_len (only when not 33, the official host's padded length);
  get_resolution reserved (only when not 0); set_camera_brightness brightness;
  set_servos pan, tilt; set_led r, g, b; set_lamp upper, lower; get_blocks
  sigmap, max_blocks; get_features scope, features; set_mode mode; set_vector
  index; set_next_turn, set_default_turn angle; get_rgb x, y, saturate.
Response fields: result value (i32); error code ({codes}, or the
  number of any other code); resolution width, height; version hardware,
  firmware_major, firmware_minor, firmware_build, firmware_type (the 10-byte
  field, written as change_prog's name is); blocks blocks (array of objects
  signature, x, y, width, height, angle, index, age); features sections (array, in wire order, of {{\"vectors\":[...]}},
  {{\"intersections\":[...]}}, {{\"barcodes\":[...]}}, or {{\"ftype\":N,\"data\":[...]}}
  for an unknown feature type). A vector is x0, y0, x1, y1, index, flags; a
  barcode x, y, flags, code; an intersection x, y and lines (its n valid lines,
  each index, angle), plus reserved bytes where not 0 and unused_slots (the
  6 - n slots after the lines) where not all zero.
With --errors, rejected candidates are objects with offset and error (no type):
  {{\"offset\":12,\"error\":\"checksum\",\"expected\":781,\"found\":780}}
  {{\"offset\":40,\"error\":\"unknown_type\",\"packet_type\":50}}
  {{\"offset\":52,\"error\":\"bad_length\",\"packet_type\":18,\"payload_len\":3}}
  {{\"offset\":60,\"error\":\"too_long\",\"packet_type\":2,\"payload_len\":65,\"max\":64}}
  {{\"offset\":70,\"error\":\"malformed\",\"packet_type\":49,\"what\":\"section_length\",
   \"ftype\":1,\"flen\":5}}
  {{\"offset\":90,\"error\":\"superseded\",\"len\":10}}
  {{\"offset\":99,\"error\":\"truncated\",\"len\":5}}
At the end, one summary line goes to stderr (frames, bytes, bytes skipped,
checksum failures, other rejections, malformed frames).

{footer}

Examples:
  robowire decode pixy2 --hex tests/data/pixy2_conversation.hex
  robowire decode pixy2 --from device --checksum-only --errors spi_miso.bin
  echo 'ae c1 20 02 ff ff' | robowire decode pixy2 --hex"
    )
}

const ENCODE_SCHEMA: &str = "\
Input: JSON lines in the schema `robowire decode pixy2` prints; offset and len
are ignored, unknown fields are errors. checksum may be left out: requests are
then written without a checksum (as the official host sends them) and
responses with one (as the device always sends them). Fields that decode
prints only when they are not 0 (reserved bytes, unused_slots) or not 33
(change_prog payload_len) may be left out. Blank lines and diagnostic events
(objects with error and no type) are skipped. A malformed line or out-of-range
value is reported with its line number and nothing is written for it; the other
lines are still encoded and the exit status is 2. A request the device refuses
(getBlocks with sigmap 0, which the official host sends) is encoded only from a
line that carries \"quirk\":\"sigmap_zero\", as decode marks it.

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
#[command(after_long_help = decode_schema())]
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
    let mut source = args.common.source()?;
    let mut printer = Printer::new(
        out,
        &args.common,
        Pixy2,
        match args.from {
            Sender::Host => Peer::Device,
            Sender::Device | Sender::Any => Peer::Host,
        },
    )?;
    let source = source.as_mut();
    let chunk = args.common.chunk as usize;
    let only = args.checksum_only;
    match args.from {
        Sender::Host => {
            let decoder = pixy2::DeviceDecoder::new(framing(only));
            driver::decode_stream(decoder, source, chunk, &mut printer)
        }
        Sender::Device => {
            let decoder = pixy2::HostDecoder::new(framing(only));
            driver::decode_stream(decoder, source, chunk, &mut printer)
        }
        Sender::Any => {
            let decoder = pixy2::BothDecoder::new(framing(only));
            driver::decode_stream(decoder, source, chunk, &mut printer)
        }
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
    driver::encode_lines(&Pixy2, &args.common, out)
}

/// The Pixy2 protocol as the tool encodes it. Encoding does not depend on the
/// side: every type name is unique.
pub struct Pixy2;

impl Schema for Pixy2 {
    type Line = Envelope<MessageBuf>;
    const FIELDS: &'static FieldTable = &robowire::pixy2::FIELD_INFO;

    fn encode(&self, line: &Self::Line, frame: &mut Vec<u8>) -> Result<(), String> {
        let mut out = [0u8; MAX_FRAME_LEN];
        let n = match line.body {
            // A request the device refuses reads only from a line that
            // carries its `quirk`: the marker asked for it.
            MessageBuf::Request(request) if request.quirk().is_some() => {
                Envelope::new(line.form, request)
                    .even_if_refused()
                    .encode(&mut out)
            }
            _ => line.encode(&mut out),
        }
        .map_err(|e| e.to_string())?;
        frame.extend_from_slice(&out[..n]);
        Ok(())
    }

    fn sent_by(&self, line: &Self::Line) -> Option<Peer> {
        Some(match line.body {
            MessageBuf::Request(_) => Peer::Host,
            MessageBuf::Response(_) => Peer::Device,
        })
    }
}
