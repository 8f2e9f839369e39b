//! The request table: every Pixy2 request (host → device) described once.
//!
//! Each row gives a request's packet type constant, its `type` name in the
//! JSON-lines schema and `Display`, the request's struct (the [`Request`]
//! variant of the same name, with the row's docs), the type of its
//! successful answer, and its payload: `{ field: kind "key", … }`, the
//! struct's fields in wire order (`0` for a tuple struct's one field, `{}`
//! for a unit struct), or `custom` (changeProg's name of any length: its
//! arms are written in `request.rs` and `serde_impls.rs`). The enum, the `From`
//! impls, [`Request::NAMES`], `name`, `packet_type`, `response_type`,
//! `payload_len`, the length table, parse, encode, `Display` and the serde
//! fields and reader come from the rows.
//!
//! | kind       | Rust  | wire                         | JSON, `Display`        |
//! |------------|-------|------------------------------|------------------------|
//! | `u8`       | `u8`  | one byte                     | number                 |
//! | `u16`      | `u16` | two bytes, little-endian     | number                 |
//! | `i16`      | `i16` | two bytes, little-endian     | number                 |
//! | `reserved` | `u8`  | one byte                     | shown only when not 0; absent reads as 0 |
//! | `sigmap`   | `u8`  | one byte; the encoder refuses 0 (ERROR −3) | number; 0 reads only with its quirk marker |
//!
//! A `macro_rules!` table as Telemetrix's (`src/telemetrix/table.rs`, which
//! says why): the structs stay hand-written beside it, with their docs,
//! constants and constructors; the wire layouts stay checked by the golden
//! vectors in `tests/pixy2.rs`.
//!
//! [`Request`]: super::Request
//! [`Request::NAMES`]: super::Request::NAMES

/// Hand the request rows, in packet type order, to `$callback!`.
macro_rules! request_table {
    ($callback:ident) => {
        $callback! {
            /// 0x02 changeProg.
            CHANGE_PROG "change_prog" ChangeProg -> RESULT custom;
            /// 0x0c getResolution.
            GET_RESOLUTION "get_resolution" GetResolution -> RESOLUTION {
                reserved: reserved "reserved",
            };
            /// 0x0e getVersion.
            GET_VERSION "get_version" GetVersion -> VERSION {};
            /// 0x10 setCameraBrightness.
            SET_CAMERA_BRIGHTNESS "set_camera_brightness" SetCameraBrightness -> RESULT
                { 0: u8 "brightness" };
            /// 0x12 setServos.
            SET_SERVOS "set_servos" SetServos -> RESULT { pan: u16 "pan", tilt: u16 "tilt" };
            /// 0x14 setLED.
            SET_LED "set_led" SetLed -> RESULT { r: u8 "r", g: u8 "g", b: u8 "b" };
            /// 0x16 setLamp.
            SET_LAMP "set_lamp" SetLamp -> RESULT { upper: u8 "upper", lower: u8 "lower" };
            /// 0x18 getFPS.
            GET_FPS "get_fps" GetFps -> RESULT {};
            /// 0x20 getBlocks.
            GET_BLOCKS "get_blocks" GetBlocks -> BLOCKS {
                sigmap: sigmap "sigmap",
                max_blocks: u8 "max_blocks",
            };
            /// 0x30 getFeatures.
            GET_FEATURES "get_features" GetFeatures -> FEATURES {
                scope: u8 "scope",
                features: u8 "features",
            };
            /// 0x36 setMode.
            SET_MODE "set_mode" SetMode -> RESULT { 0: u8 "mode" };
            /// 0x38 setVector.
            SET_VECTOR "set_vector" SetVector -> RESULT { 0: u8 "index" };
            /// 0x3a setNextTurn.
            SET_NEXT_TURN "set_next_turn" SetNextTurn -> RESULT { 0: i16 "angle" };
            /// 0x3c setDefaultTurn.
            SET_DEFAULT_TURN "set_default_turn" SetDefaultTurn -> RESULT { 0: i16 "angle" };
            /// 0x3e reverseVector.
            REVERSE_VECTOR "reverse_vector" ReverseVector -> RESULT {};
            /// 0x70 getRGB.
            GET_RGB "get_rgb" GetRgb -> RESULT { x: u16 "x", y: u16 "y", saturate: u8 "saturate" };
        }
    };
}

pub(crate) use request_table;

/// Whether a field is shown in `Display` and JSON: a `reserved` byte only
/// when it is not 0.
macro_rules! kind_shown {
    (reserved, $v:expr) => {
        $v != 0
    };
    ($kind:ident, $v:expr) => {
        true
    };
}

pub(crate) use kind_shown;
