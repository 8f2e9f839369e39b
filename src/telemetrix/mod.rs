//! Telemetrix4RpiPico: the serial protocol between a host and the
//! Telemetrix firmware on a Raspberry Pi Pico (RP2040), mirte firmware 1.3 by
//! default, with the older mirte 1.2 and upstream 1.1 dialects
//! ([`Dialect`]).
//!
//! # Wire layout
//!
//! ```text
//! LEN  id  payload…        LEN = bytes after it (id + payload)
//! ```
//!
//! There is no start byte, escaping or checksum. Integers are big-endian,
//! floats little-endian. Commands (host → Pico, [`Command`]) and reports
//! (Pico → host, [`Report`]) have separate id spaces; commands are at most 30
//! bytes after `LEN`.
//!
//! # The vocabulary
//!
//! | | host → Pico | Pico → host | either |
//! |---|---|---|---|
//! | message (borrowed) | [`Command<'a>`](Command) | [`Report<'a>`](Report) | [`Message<'a>`](Message) |
//! | owned form | [`CommandBuf`] | [`ReportBuf`] | [`MessageBuf`] |
//! | framing | [`Framing<Device>`](Framing) | [`Framing<Host>`](Framing) | [`Framing<Both>`](Framing) |
//! | decoder | [`DeviceDecoder`] ([`device_decoder()`]) | [`HostDecoder`] ([`host_decoder()`]) | [`BothDecoder`] ([`both_decoder()`]) |
//! | buffer | [`DEVICE_BUFFER`] | [`HOST_BUFFER`] ([`LENIENT_BUFFER`] when lenient) | [`BOTH_BUFFER`] |
//!
//! Buffers: 256 bytes for a host decoder (the longest report frame), 32 for
//! a device decoder (the longest command frame is 31), 512 for a lenient or
//! both-direction decoder (an unknown report and the frame that must follow
//! it). Sizes on a 64-bit target (the buffer, then the engine's counters and
//! indices, fewer on a 32-bit target): `size_of::<HostDecoder>()` is 360
//! bytes, `size_of::<DeviceDecoder>()` 136, `size_of::<BothDecoder>()` and
//! `size_of::<LenientHostDecoder>()` 616. The owned forms hold a whole frame:
//! `CommandBuf` 32 bytes, `ReportBuf` 258, `MessageBuf` 261. To keep many
//! messages in little memory, keep each `MessageBuf`'s frame and its
//! [`Attribution`] (a few bytes), and [`MessageBuf::from_attribution`] gives
//! the message back.
//!
//! Messages borrow their variable byte fields (I2C/SPI data, feature
//! extras, module data, servo positions) from the frame or the caller;
//! short fixed lists (PWM pins, servo moves, AS5600 angles) are owned
//! [`List`]s. The owned forms keep the frame's bytes and parse them on
//! access (`.message()`); `to_buf()` / [`TryFrom`] make one from a message,
//! `From` goes back. One complete frame parses with `TryFrom<&[u8]>` (mirte
//! 1.3) or `parse_in(frame, dialect)`.
//!
//! # Encoding
//!
//! Every message implements [`Encode`] for mirte 1.3;
//! `encode_in(dialect, out)`, `to_buf_in(dialect)` or [`InDialect`] select
//! another dialect. The encoder never emits a frame its own decoder would
//! reject: after writing into a scratch buffer it runs the decoder's parser
//! on the frame and copies it out only if that succeeds. So: no id outside
//! the dialect (there is no raw-id path), no `LEN` over 30, the spec §4
//! maxima (PWM 1..=9 pins, I2C read 1..=57, I2C write 1..=24, SPI write ≤ 27,
//! SPI read ≤ 60, SPI CS ≤ 20, neopixels ≤ 100, module init ≤ 26, module
//! data 1..=28), pins < 30, I2C addresses ≤ 0x7F, ports 0/1, flags 0/1, SPI
//! data bits 4..=16, and always the full payload (SET_PIN_MODE tail,
//! ENCODER_NEW pulls in mirte 1.3, SENSOR_NEW's 6 settings bytes, I2C_READ's
//! 6 bytes). MODIFY_REPORTING for digital pins is refused in mirte 1.3, whose
//! firmware indexes the pin as `pin − 26`.
//!
//! # Decode what a real peer sends: quirks
//!
//! Refusing a frame a real host or Pico sends would lose it and, without a
//! checksum, the frames around it. So the decoder accepts these frames as
//! the firmware reads them and flags them with a [`Quirk`]
//! ([`CommandBuf::quirk`], [`ReportBuf::quirk`], [`MessageBuf::quirk`]; the
//! owned forms keep the frame's own bytes, and the JSON-lines schema adds
//! `"quirk":"<name>"` after the fields); the encoder refuses them unless
//! asked with `even_if_refused()` ([`EvenIfRefused`]), and a JSON line reads
//! back to its quirky frame only when it carries the marker:
//! MODIFY_REPORTING types 2 and 4 in mirte 1.3 (`03 04 04 02`, sent by the
//! mirte Python client), DIGITAL_WRITE levels other than 0/1 (read as high),
//! PWM_WRITE with 1 or 2 bytes after the last whole pin (ignored), ENCODER_NEW
//! type 3 (read as quadrature), the SSD1306 "disabled" report echoing a
//! request subtype above 3 (`05 22 03 03 05 FE`), and in mirte 1.2 and
//! upstream 1.1 MODIFY_REPORTING of an analog pin by its GPIO number
//! (`03 04 01 1A`, sent by those dialects' Python clients); the table and
//! the rules the spec lacks are in [`Quirk`]. On a clean stream of every
//! mirte 1.3 command with full payloads, 10,047 frames, that took the
//! decoder from 284 lost and 38 false frames to none, at any chunking.
//!
//! ```
//! use robowire::telemetrix::{host_decoder, Command, Report};
//!
//! // Host → Pico: PING with counter 7.
//! let ping = Command::Ping { counter: 7 }.to_buf()?;
//! assert_eq!(&ping[..], &[0x02, 0x20, 0x07]);
//!
//! // Pico → host: a PONG and a digital report, split anywhere.
//! let mut decoder = host_decoder();
//! let mut reports = Vec::new();
//! for chunk in [&[0x03, 0x20][..], &[0x07, 0x2A, 0x03, 0x02, 0x0A, 0x01]] {
//!     for event in decoder.feed(chunk) {
//!         reports.push(event.unwrap().message);
//!     }
//! }
//! assert_eq!(reports[0].message(), Report::Pong { counter: 7, boot_id: 42 });
//! assert_eq!(reports[1].message(), Report::Digital { pin: 10, value: true });
//! assert_eq!(reports[1].message().to_string(), "digital_report pin=10 value=1");
//! # Ok::<(), robowire::EncodeError>(())
//! ```
//!
//! The Pico side decodes commands without copying them:
//!
//! ```
//! use robowire::telemetrix::{device_decoder, Command, Report};
//! use robowire::Encode;
//!
//! let mut pico = device_decoder();
//! let mut input = &[0x00, 0x00, 0x02, 0x20, 0x07][..]; // padding, then PING 7
//! while let Some(event) = pico.decode(&mut input) {
//!     if let Command::Ping { counter } = event?.message {
//!         let mut out = [0u8; 4];
//!         let n = Report::Pong { counter, boot_id: 42 }.encode(&mut out)?;
//!         assert_eq!(&out[..n], &[0x03, 0x20, 0x07, 0x2A]);
//!     }
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A host that reads a fast report stream borrowed (not kept) decodes
//! fastest with [`StreamDecoder::decode_each`](crate::StreamDecoder::decode_each):
//! the reports a Pico streams (digital, analog, sonar, encoder, pong) are
//! built straight from their bytes into the event the closure gets, about
//! twice the speed of the `decode` loop on a 64-bit host
//! (`cargo bench --bench telemetrix`, docs/performance.md).
//!
//! ```
//! use robowire::telemetrix::{host_decoder, Report};
//!
//! let mut host = host_decoder();
//! let mut analog = Vec::new();
//! host.decode_each(&[0x03, 0x02, 0x0A, 0x01, 0x04, 0x03, 0x1A, 0x08, 0x00], |event| {
//!     if let Ok(frame) = event {
//!         if let Report::Analog { pin, value } = frame.message {
//!             analog.push((pin, value));
//!         }
//!     }
//! });
//! assert_eq!(analog, [(26, 2048)]);
//! ```
//!
//! # Decoder policy (resync without a checksum)
//!
//! `find_start` skips `00` where a `LEN` would be (the firmware drops it);
//! the command framing also skips `LEN` > 30, as the firmware does. A
//! candidate is then accepted only if **all** of this holds, else the engine
//! drops one byte and rescans (resync by one):
//!
//! | Check | Reports | Commands |
//! |---|---|---|
//! | id | defined in the dialect (unknown = corruption) | defined in the dialect |
//! | `LEN`, from the header | exact per id (0: 2, 2: 3, 3: 4, 5: 3, 6: 9, 8: 4, 9: 4, 12: 6, 14: 3, 21: 4, 32: 3, 33: 4, 35: 2, 36: 2, 99: 4); 11: 4 or 5; 10: `n + 6` (upstream `n + 5`), n 1..=57; 13: `n + 3`, n ≤ 60; 20: by sensor type; 34: by module type and subtype (Hiwonder positions `4 + 3k`); 37: by `msg_type` and `ok` | range per id, then exact by mode / subtype / count |
//! | fields | pins < 30, analog pin 26..=30 (or ADC 0..=4), analog value ≤ 4095, flags 0/1, ports ≤ 1, I2C address ≤ 0x7F, I2C read pad byte `00`, sonar cm < 1000 or a sentinel, DHT hundredths < 100 and signs agreeing, encoder steps ≠ 0, PONG boot id < 100, sensor/module check subtype 0, AS5600 angles ≤ 4095, SSD1306 kind 1/3 and `254` marker | everything the encoder enforces |
//!
//! Variable reports are rejected as soon as their count or sub-type byte
//! arrives, so a false `LEN` does not hold frames back for long. Events carry
//! offsets; [`Stats`](crate::Stats) count frames, skipped bytes and
//! rejections.
//!
//! **Both directions** ([`Framing<Both>`](Framing)): a candidate is a frame
//! if either direction accepts it. Some frames are valid both ways (of ids
//! 0, 2, 3, 8, 13, plus 34, 36 in mirte 1.3 and 12 in upstream 1.1: a
//! digital write is byte for byte a digital report); the decoder reads them
//! as reports, and a [`CaptureContext`] attributes them to the direction of
//! the last frame that was valid one way only.
//!
//! **Firmware-exact mode** (opt-in, commands only):
//! [`Framing::as_firmware`] frames commands as the Pico's firmware does
//! (trust `LEN`, never rescan), to reconstruct what the device ran rather
//! than what the host meant.
//!
//! **Lenient mode** (opt-in, reports only): [`Framing::lenient`] with a
//! [`LenientHostDecoder`] accepts an unknown id as [`Report::Unknown`],
//! skipped by its `LEN`, only when a valid known report follows directly
//! (after optional `00`s): the framing is stateless, and a following frame is
//! the only sign of being in sync. An unknown frame at the very end of the
//! input is reported as truncated.
//!
//! # What cannot be detected without a checksum
//!
//! * Garbage (or a frame from the other core) that happens to form a valid
//!   frame: `03 02` before `02 00 41` reads as DIGITAL pin 2 low, and the
//!   loopback frame's first bytes are swallowed (a test pins this down).
//! * A dropped or changed payload byte when the result is still in range (an
//!   analog value, an I2C/SPI data byte, a sensor float, a counter): the
//!   frame is delivered with the wrong value, and may swallow the next
//!   frame's `LEN` byte.
//! * Frames of unknown ids in strict mode are indistinguishable from garbage
//!   and are resynced over byte by byte.
//!
//! # Limits
//!
//! * Stateful firmware rules are the caller's: ≤ 4 sonars, ≤ 2 DHTs, ≤ 4
//!   encoders, module numbers 0, 1, 2, … in creation order, PING at least
//!   every second (Hiwonder data is dropped unless the last PING is < 2 s
//!   old), one write per frame and ≥ 100 ms of silence before the first.
//! * MODULE_DATA does not say which module type it is for, so a parsed
//!   command carries raw bytes; read them with the module's
//!   [`ModuleCommand::parse`] (or let a [`CaptureContext`] type them).
//! * Hiwonder positions are not range-checked (servos can report past 24000
//!   cdeg); feature-check extras are carried raw.
//!
//! # serde
//!
//! With the `serde` feature, messages, their owned forms and [`Error`]
//! serialize in the JSON-lines schema of the `robowire` tool (a `type` tag,
//! snake_case, the tool's field names), and the owned forms deserialize from
//! it, checked exactly as the encoder checks (deserializing *is* encoding:
//! an owned form holds a valid frame). `MessageBuf::deserialize_in` reads
//! another dialect. Decoders and encoders never allocate; reading JSON does.
//!
//! # Levels and flags
//!
//! A pin level (DIGITAL_WRITE's and DIGITAL_REPORT's `value`, SPI_CS_CONTROL's
//! `high`, JSON `level`, SPI_SET_FORMAT's `cpol` and `cpha`, the relay's
//! `active_high`, JSON `active_level`) is a `bool` in Rust, `true` for high,
//! so that no other value can be held; the
//! JSON schema and [`Display`](core::fmt::Display) write it as the wire does,
//! `0` or `1`, the way the firmware's documentation and a logic analyser show a
//! level. A flag (`report_enable`, `auto_show`, `supported`, …) is `true` or
//! `false` everywhere. So `Command::DigitalWrite { pin: 25, value: true }` is
//! `{"type":"digital_write","pin":25,"value":1}` and `digital_write pin=25
//! value=1`:
//!
//! ```
//! use robowire::telemetrix::Command;
//!
//! let on = Command::DigitalWrite { pin: 25, value: true };
//! assert_eq!(on.to_string(), "digital_write pin=25 value=1");
//! ```
//!
//! # Adding a command
//!
//! Every command is one row of the command table (`src/telemetrix/table.rs`,
//! a `macro_rules!` table): the [`Command`] variant and its docs, the id and
//! its [`command_id`] constant, the `type` name, the dialects, the `LEN` range
//! and the payload. The enum, the ids, the dialect and `LEN` tables, encode,
//! parse, the serde fields, the names and `Display` are expanded from it. To
//! add a command with a fixed layout:
//!
//! 1. Add its row to `command_table!`, at its id (the rows are in id order,
//!    which the build checks):
//!    ```text
//!    /// 39 SET_LED: the board LED on or off (mirte 1.3).
//!    39 SET_LED "set_led" [SetLed] in [Mirte13] len (2, 2)
//!        plain SetLed {
//!            /// Level, `true` for on.
//!            on: level "level",
//!        };
//!    ```
//!    The field kinds (`u8`, `pin`, `range(lo, hi)`, `u16`, `flag`, `level`,
//!    `rgb`) say the Rust type, the check on the wire, the writer and the JSON
//!    form; the string is the field's JSON key.
//! 2. Add its golden vector to `golden_commands_mirte13` in
//!    `tests/telemetrix.rs` (frame ↔ command) and its line to `CASES` in
//!    `tests/schema_telemetrix.rs` (frame ↔ JSON line).
//!
//! A command whose layout depends on its content or its dialect is a
//! `custom` row, and it too is one declaration: the row carries its
//! variants and its code, each piece naming the values it works on as a
//! closure names its parameters (`parse(dialect, r, id)`, `write(w)`,
//! `fields(view, w)`, `read(f, dialect, buf, raw)`, and where needed
//! `check`, `home` and `quirk`; the module docs of `table.rs` say what each
//! is, and docs/telemetrix.md shows a whole row). Reports have a table of
//! their own in the same file (`report_table!`), with rows of the same
//! shape and each report's `LEN` rule: the report ids, the dialect table,
//! [`Report::NAMES`], [`Report::name`], [`Report::id`], the [`Report`]
//! enum, encode, parse, the `LEN` check, the serde fields and reader come
//! from it; the streamed fast path (`fast.rs`) is a shortcut its tests hold
//! to the table's parse. The MODULE_DATA messages that start with a subtype
//! byte ([`HiwonderCommand`], [`Ssd1306Command`]) have a table per module
//! type, the sensors one (`sensor_table!`: [`SensorType`] and
//! [`SensorReading`]) and the module types one (`module_table!`:
//! [`ModuleType`], [`ModuleInit`], [`ModuleReport`]), all in the same file;
//! the field kinds' Rust types, reads and writes are in `kind.rs`, shared by
//! all tables.

mod buf;
mod command;
mod dialect;
mod error;
mod fast;
mod field_info;
mod fields;
mod framing;
mod kind;
mod list;
mod module;
mod names;
mod quirk;
mod report;
#[cfg(feature = "serde")]
mod schema;
mod sensor;
mod table;
mod wire;

pub use buf::{Attribution, CommandBuf, Message, MessageBuf, ReportBuf};
pub use command::{
    Command, EncoderKind, ModifyReporting, PinMode, Pull, Pulls, PwmPin, PwmPins, Rgb,
};
pub use dialect::Dialect;
pub use error::Error;
pub use field_info::FIELD_INFO;
pub use framing::{Both, CaptureContext, Device, Framing, Host, Side};
pub use list::{List, Payload};
pub use module::{
    HiwonderCommand, ModuleCommand, ModuleInit, ModuleNew, ModuleReport, ModuleType,
    Pca9685Channel, Pca9685Command, Pca9685Config, RelayCommand, ServoMove, ServoPosition,
    ServoPositions, Ssd1306Command, Ssd1306Done, MODULE_INIT_MAX,
};
pub use names::UnknownName;
pub use quirk::{EvenIfRefused, Quirk};
pub use report::{Report, Sonar, SonarReading, SONAR_NO_ECHO, SONAR_OUT_OF_RANGE, SONAR_STALE};
pub use sensor::{SensorNew, SensorReading, SensorType};
pub use wire::{
    command_id, report_id, COMMAND_PAYLOAD_MAX, MAX_COMMAND_LEN, MAX_FRAME_LEN, PIN_COUNT,
};

use crate::{Encode, EncodeError, StreamDecoder};

/// Buffer size of a [`HostDecoder`]: the longest report frame (256 bytes).
pub const HOST_BUFFER: usize = wire::MAX_REPORT_FRAME;

/// Buffer size of a [`DeviceDecoder`]: the longest command frame (31 bytes)
/// and one more.
pub const DEVICE_BUFFER: usize = 32;

/// Buffer size of a decoder whose framing is [`lenient`](Framing::lenient):
/// an unknown report and the known frame that must follow it.
pub const LENIENT_BUFFER: usize = 2 * wire::MAX_REPORT_FRAME;

/// Buffer size of a [`BothDecoder`]: room for a lenient unknown report and
/// the frame that must follow it.
pub const BOTH_BUFFER: usize = LENIENT_BUFFER;

/// Decoder of reports (the host side).
pub type HostDecoder = StreamDecoder<Framing<Host>, HOST_BUFFER>;

/// Decoder of reports for a [`lenient`](Framing::lenient) framing.
pub type LenientHostDecoder = StreamDecoder<Framing<Host>, LENIENT_BUFFER>;

/// Decoder of commands (the Pico side, or a simulator of it).
pub type DeviceDecoder = StreamDecoder<Framing<Device>, DEVICE_BUFFER>;

/// Decoder of both directions (captures, sniffers, tooling).
pub type BothDecoder = StreamDecoder<Framing<Both>, BOTH_BUFFER>;

/// A [`HostDecoder`] for mirte 1.3.
pub const fn host_decoder() -> HostDecoder {
    HostDecoder::new(Framing::new())
}

/// A [`DeviceDecoder`] for mirte 1.3.
pub const fn device_decoder() -> DeviceDecoder {
    DeviceDecoder::new(Framing::new())
}

/// A [`BothDecoder`] for mirte 1.3.
pub const fn both_decoder() -> BothDecoder {
    BothDecoder::new(Framing::new())
}

/// A message paired with the dialect to encode it for, so that
/// [`FrameBuf::encode`](crate::FrameBuf::encode) and `encode_buf` work for
/// every dialect. Made by `in_dialect` on [`Command`] and [`Report`].
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy)]
pub struct InDialect<'m, M> {
    message: &'m M,
    dialect: Dialect,
}

impl<'a> Command<'a> {
    /// This command, to be encoded for `dialect`.
    pub const fn in_dialect(&self, dialect: Dialect) -> InDialect<'_, Self> {
        InDialect {
            message: self,
            dialect,
        }
    }
}

impl<'a> Report<'a> {
    /// This report, to be encoded for `dialect`.
    pub const fn in_dialect(&self, dialect: Dialect) -> InDialect<'_, Self> {
        InDialect {
            message: self,
            dialect,
        }
    }
}

impl Encode for InDialect<'_, Command<'_>> {
    const MAX_LEN: usize = wire::MAX_COMMAND_FRAME;

    fn encoded_len(&self) -> usize {
        self.message.encoded_len_in(self.dialect)
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.message.encode_in(self.dialect, out)
    }
}

impl Encode for InDialect<'_, Report<'_>> {
    const MAX_LEN: usize = wire::MAX_REPORT_FRAME;

    fn encoded_len(&self) -> usize {
        self.message.encoded_len_in(self.dialect)
    }

    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.message.encode_in(self.dialect, out)
    }
}
