//! JSON lines back into Telemetrix messages, in exactly the schema
//! [`describe`](super::describe) writes.

use super::names::{
    dialect_name, COMMAND_TYPES, MODULE_TYPES, PIN_MODES, REPORTING_ACTIONS, REPORT_TYPES,
    SENSOR_TYPES,
};
use crate::json::{read_f32, read_int, Fields};
use robowire::telemetrix::{
    Command, Dialect, EncoderKind, HiwonderCommand, List, ModifyReporting, ModuleInit, ModuleNew,
    ModuleReport, ModuleType, Pca9685Channel, Pca9685Command, Pca9685Config, PinMode, Pull, Pulls,
    PwmPin, PwmPins, RelayCommand, Report, Rgb, SensorNew, SensorReading, SensorType, ServoMove,
    ServoPositions, Sonar, Ssd1306Command, Ssd1306Done, SONAR_NO_ECHO, SONAR_OUT_OF_RANGE,
    SONAR_STALE,
};
use serde_json::Value;

/// The longest byte array a frame can carry.
const MAX_BYTES: usize = 255;

/// Read one JSON object and append the frame it describes, encoded for
/// `dialect`, to `frame`.
pub fn encode(dialect: Dialect, mut fields: Fields<'_>, frame: &mut Vec<u8>) -> Result<(), String> {
    let kind = fields.string("type")?;
    // `also` names the other reading of an ambiguous frame; the bytes are
    // the same either way.
    if let Some(also) = fields.optional("also") {
        let known = also
            .as_str()
            .is_some_and(|t| COMMAND_TYPES.contains(&t) || REPORT_TYPES.contains(&t));
        if !known {
            return Err(format!(
                "field `also` must name a command or report type, found {also}"
            ));
        }
    }
    let mut out = [0u8; 256];
    let encoded = if COMMAND_TYPES.contains(&kind) {
        let command = read_command(kind, &mut fields, dialect)?;
        fields.finish(&format!("for type {kind}"))?;
        command.encode_in(dialect, &mut out)
    } else if REPORT_TYPES.contains(&kind) || kind == "unknown_report" {
        let report = read_report(kind, &mut fields, dialect)?;
        fields.finish(&format!("for type {kind}"))?;
        report.encode_in(dialect, &mut out)
    } else {
        return Err(format!("unknown type `{kind}`"));
    };
    let n =
        encoded.map_err(|e| format!("cannot encode {kind} for {}: {e}", dialect_name(dialect)))?;
    frame.extend_from_slice(&out[..n]);
    Ok(())
}

fn u8_(f: &mut Fields<'_>, key: &str) -> Result<u8, String> {
    f.int(key, 0, 255).map(|v| v as u8)
}

fn u16_(f: &mut Fields<'_>, key: &str) -> Result<u16, String> {
    f.int(key, 0, 65535).map(|v| v as u16)
}

fn i8_(f: &mut Fields<'_>, key: &str) -> Result<i8, String> {
    f.int(key, -128, 127).map(|v| v as i8)
}

fn i16_(f: &mut Fields<'_>, key: &str) -> Result<i16, String> {
    f.int(key, -32768, 32767).map(|v| v as i16)
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
    let t = type_byte(f, "sensor_type", &SENSOR_TYPES)?;
    SensorType::from_u8(t).ok_or_else(|| format!("field `sensor_type` {t} is no known sensor type"))
}

fn module_type(f: &mut Fields<'_>) -> Result<ModuleType, String> {
    let t = type_byte(f, "module_type", &MODULE_TYPES)?;
    ModuleType::from_u8(t).ok_or_else(|| format!("field `module_type` {t} is no known module type"))
}

fn rgb(f: &mut Fields<'_>) -> Result<Rgb, String> {
    Ok(Rgb {
        r: u8_(f, "r")?,
        g: u8_(f, "g")?,
        b: u8_(f, "b")?,
    })
}

/// The members of a command `kind` (one of [`COMMAND_TYPES`]).
fn read_command(
    kind: &str,
    f: &mut Fields<'_>,
    dialect: Dialect,
) -> Result<Command<Vec<u8>>, String> {
    let upstream = dialect == Dialect::Upstream11;
    Ok(match kind {
        "serial_loop_back" => Command::LoopBack {
            byte: u8_(f, "byte")?,
        },
        "set_pin_mode" => {
            let pin = u8_(f, "pin")?;
            let mode = match name(f, "mode", &PIN_MODES)? {
                m @ 0..=2 => PinMode::DigitalInput {
                    pull: [Pull::None, Pull::Up, Pull::Down][m],
                    report: flag(f, "report_enable")?,
                },
                3 => PinMode::DigitalOutput,
                4 => PinMode::PwmOutput,
                _ => PinMode::AnalogInput {
                    differential: u16_(f, "differential")?,
                    report: flag(f, "report_enable")?,
                },
            };
            Command::SetPinMode { pin, mode }
        }
        "digital_write" => Command::DigitalWrite {
            pin: u8_(f, "pin")?,
            high: level(f, "value")?,
        },
        "pwm_write" => {
            let pins = objects(f, "pins", |p| {
                Ok(PwmPin {
                    pin: u8_(p, "pin")?,
                    value: u16_(p, "value")?,
                })
            })?;
            Command::PwmWrite(
                PwmPins::from_slice(&pins)
                    .map_err(|_| format!("field `pins` holds {} pins, at most 9", pins.len()))?,
            )
        }
        "modify_reporting" => {
            let action = name(f, "action", &REPORTING_ACTIONS)?;
            Command::ModifyReporting(match action {
                0 => ModifyReporting::DisableAll,
                1 => ModifyReporting::EnableAnalog {
                    pin: u8_(f, "pin")?,
                },
                2 => ModifyReporting::EnableDigital {
                    pin: u8_(f, "pin")?,
                },
                3 => ModifyReporting::DisableAnalog {
                    pin: u8_(f, "pin")?,
                },
                _ => ModifyReporting::DisableDigital {
                    pin: u8_(f, "pin")?,
                },
            })
        }
        "get_firmware_version" => Command::GetFirmwareVersion,
        "get_pico_unique_id" => Command::GetUniqueId,
        "servo_attach" => {
            let pin = u8_(f, "pin")?;
            let pulse_range = match (f.has("min_us"), f.has("max_us")) {
                (false, false) => None,
                _ => Some((u16_(f, "min_us")?, u16_(f, "max_us")?)),
            };
            Command::ServoAttach { pin, pulse_range }
        }
        "servo_write" => Command::ServoWrite {
            pin: u8_(f, "pin")?,
            pulse_us: u16_(f, "pulse_us")?,
        },
        "servo_detach" => Command::ServoDetach {
            pin: u8_(f, "pin")?,
        },
        "i2c_begin" => Command::I2cBegin {
            port: u8_(f, "port")?,
            sda: u8_(f, "sda")?,
            scl: u8_(f, "scl")?,
        },
        "i2c_read" if upstream => Command::I2cReadUpstream {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            reg: u8_(f, "reg")?,
            len: u8_(f, "n")?,
            no_stop: u8_(f, "no_stop")?,
        },
        "i2c_read" => Command::I2cRead {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            msg_id: u8_(f, "msg_id")?,
            reg: u8_(f, "reg")?,
            len: u8_(f, "n")?,
            no_stop: u8_(f, "no_stop")?,
        },
        "i2c_write" if upstream => Command::I2cWriteUpstream {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            no_stop: u8_(f, "no_stop")?,
            data: bytes(f, "data")?,
        },
        "i2c_write" => Command::I2cWrite {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            msg_id: u8_(f, "msg_id")?,
            no_stop: u8_(f, "no_stop")?,
            data: bytes(f, "data")?,
        },
        "sonar_new" => Command::SonarNew {
            trig: u8_(f, "trig")?,
            echo: u8_(f, "echo")?,
        },
        "dht_new" => Command::DhtNew {
            pin: u8_(f, "pin")?,
        },
        "stop_all_reports" => Command::StopAllReports,
        "enable_all_reports" => Command::EnableAllReports,
        "reset_data" => Command::ResetData,
        "reset_board" => Command::ResetBoard,
        "initialize_neo_pixels" => Command::InitNeoPixels {
            pin: u8_(f, "pin")?,
            count: u8_(f, "count")?,
            rgb: rgb(f)?,
        },
        "show_neo_pixels" => Command::ShowNeoPixels,
        "set_neo_pixel" => Command::SetNeoPixel {
            index: u8_(f, "index")?,
            rgb: rgb(f)?,
            auto_show: flag(f, "auto_show")?,
        },
        "clear_all_neo_pixels" => Command::ClearAllNeoPixels {
            auto_show: if f.has("auto_show") {
                Some(flag(f, "auto_show")?)
            } else {
                None
            },
        },
        "fill_neo_pixels" => Command::FillNeoPixels {
            rgb: rgb(f)?,
            auto_show: flag(f, "auto_show")?,
        },
        "spi_init" => Command::SpiInit {
            port: u8_(f, "port")?,
            pin_a: u8_(f, "pin_a")?,
            pin_b: u8_(f, "pin_b")?,
            clk: u8_(f, "clk")?,
            freq_hz: f.int("freq_hz", 0, i64::from(u32::MAX))? as u32,
            cs_pins: bytes(f, "cs_pins")?,
        },
        "spi_write_blocking" => Command::SpiWrite {
            port: u8_(f, "port")?,
            data: bytes(f, "data")?,
        },
        "spi_read_blocking" => Command::SpiRead {
            port: u8_(f, "port")?,
            len: u8_(f, "n")?,
            tx_fill: u8_(f, "tx_fill")?,
        },
        "spi_set_format" => Command::SpiSetFormat {
            port: u8_(f, "port")?,
            data_bits: u8_(f, "data_bits")?,
            cpol: level(f, "cpol")?,
            cpha: level(f, "cpha")?,
        },
        "spi_cs_control" => Command::SpiCsControl {
            cs_pin: u8_(f, "cs_pin")?,
            high: level(f, "level")?,
        },
        "set_scan_delay" => Command::SetScanDelay {
            delay_ms: u8_(f, "delay_ms")?,
        },
        "encoder_new" => Command::EncoderNew {
            kind: match name(f, "kind", &["single", "quadrature"])? {
                0 => EncoderKind::Single,
                _ => EncoderKind::Quadrature,
            },
            pin_a: u8_(f, "pin_a")?,
            pin_b: u8_(f, "pin_b")?,
            // Only mirte 1.3 has the pulls byte; elsewhere `pulls` is an
            // unknown field.
            pulls: if dialect == Dialect::Mirte13 {
                nested(f, "pulls", |p| {
                    Ok(Pulls {
                        up: flag(p, "up")?,
                        down: flag(p, "down")?,
                    })
                })?
            } else {
                Pulls::default()
            },
        },
        "sensor_new" => Command::SensorNew(match name(f, "subtype", &["check", "add"])? {
            0 => SensorNew::Check {
                sensor_type: type_byte(f, "sensor_type", &SENSOR_TYPES)?,
            },
            _ => SensorNew::Add {
                sensor_num: u8_(f, "sensor_num")?,
                sensor_type: sensor_type(f)?,
                settings: f.array("settings", byte)?,
            },
        }),
        "ping" => Command::Ping {
            counter: u8_(f, "counter")?,
        },
        "module_new" => Command::ModuleNew(match name(f, "subtype", &["check", "add"])? {
            0 => ModuleNew::Check {
                module_type: type_byte(f, "module_type", &MODULE_TYPES)?,
            },
            _ => {
                let module_num = u8_(f, "module_num")?;
                let module_type = module_type(f)?;
                ModuleNew::Add {
                    module_num,
                    init: nested(f, "init", |i| module_init(module_type, i))?,
                }
            }
        }),
        "module_data" => {
            let module_num = u8_(f, "module_num")?;
            if f.has("module_type") {
                let module_type = module_type(f)?;
                nested(f, "message", |m| module_data(module_num, module_type, m))?
            } else {
                Command::ModuleData {
                    module_num,
                    data: bytes(f, "data")?,
                }
            }
        }
        "get_id" => Command::GetId,
        "set_id" => Command::SetId { id: u8_(f, "id")? },
        "feature_request" => Command::FeatureCheck {
            msg_type: u8_(f, "msg_type")?,
        },
        "bootloader_reset" => Command::BootloaderReset,
        other => return Err(format!("unknown type `{other}`")),
    })
}

fn module_init(module_type: ModuleType, f: &mut Fields<'_>) -> Result<ModuleInit<Vec<u8>>, String> {
    Ok(match module_type {
        ModuleType::Pca9685 => ModuleInit::Pca9685 {
            port: u8_(f, "port")?,
            config: match (f.has("addr"), f.has("freq_hz")) {
                (false, false) => None,
                _ => Some(Pca9685Config {
                    addr: u8_(f, "addr")?,
                    freq_hz: u16_(f, "freq_hz")?,
                }),
            },
        },
        ModuleType::HiwonderServo => ModuleInit::HiwonderServo {
            uart: u8_(f, "uart")?,
            rx: u8_(f, "rx")?,
            tx: u8_(f, "tx")?,
            bus_ids: bytes(f, "bus_ids")?,
        },
        ModuleType::ShutdownRelay => ModuleInit::ShutdownRelay {
            pin: u8_(f, "pin")?,
            active_high: level(f, "active_level")?,
            wait_s: u8_(f, "wait_s")?,
        },
        ModuleType::Ssd1306 => ModuleInit::Ssd1306 {
            port: u8_(f, "port")?,
            addr: if f.has("addr") {
                Some(u8_(f, "addr")?)
            } else {
                None
            },
        },
    })
}

/// Typed MODULE_DATA: the module's message, built into the data bytes by the
/// library (which checks it as the module's parser would).
fn module_data(
    module_num: u8,
    module_type: ModuleType,
    f: &mut Fields<'_>,
) -> Result<Command<Vec<u8>>, String> {
    let command = match module_type {
        ModuleType::HiwonderServo => {
            Command::<Vec<u8>>::module_data(module_num, &hiwonder_command(f)?)
        }
        ModuleType::Pca9685 => {
            let channels = objects(f, "channels", |c| {
                Ok(Pca9685Channel {
                    channel: u8_(c, "channel")?,
                    on: u16_(c, "on")?,
                    off: u16_(c, "off")?,
                })
            })?;
            let channels = List::from_slice(&channels)
                .map_err(|_| format!("`channels` holds {}, at most 5", channels.len()))?;
            Command::<Vec<u8>>::module_data(module_num, &Pca9685Command { channels })
        }
        ModuleType::Ssd1306 => Command::<Vec<u8>>::module_data(module_num, &ssd1306_command(f)?),
        ModuleType::ShutdownRelay => {
            let message = match name(f, "subtype", &["start", "cancel"])? {
                0 => RelayCommand::Start,
                _ => RelayCommand::Cancel,
            };
            Command::<Vec<u8>>::module_data(module_num, &message)
        }
    };
    command
        .map(|c| c.map_bytes(|data| data.to_vec()))
        .map_err(|e| e.to_string())
}

const HIWONDER_SUBTYPES: [&str; 11] = [
    "set_angle",
    "enable",
    "id_write",
    "id_verify",
    "range_write",
    "range_read",
    "offset_write",
    "offset_read",
    "voltage_limit_write",
    "motor_mode_write",
    "add_servo",
];

fn hiwonder_command(f: &mut Fields<'_>) -> Result<HiwonderCommand, String> {
    Ok(match name(f, "subtype", &HIWONDER_SUBTYPES)? {
        0 => {
            let moves = objects(f, "moves", |m| {
                Ok(ServoMove {
                    idx: u8_(m, "idx")?,
                    centideg: u16_(m, "centideg")?,
                    time_ms: u16_(m, "time_ms")?,
                })
            })?;
            HiwonderCommand::SetAngle(
                List::from_slice(&moves)
                    .map_err(|_| format!("`moves` holds {}, at most 5", moves.len()))?,
            )
        }
        1 => {
            let enabled = flag(f, "enabled")?;
            let servos = bytes(f, "servos")?;
            HiwonderCommand::Enable {
                enabled,
                servos: List::from_slice(&servos)
                    .map_err(|_| format!("`servos` holds {}, at most 25", servos.len()))?,
            }
        }
        2 => HiwonderCommand::IdWrite {
            new_id: u8_(f, "new_id")?,
        },
        3 => HiwonderCommand::IdVerify {
            bus_id: u8_(f, "bus_id")?,
        },
        4 => HiwonderCommand::RangeWrite {
            idx: u8_(f, "idx")?,
            min_cdeg: u16_(f, "min_cdeg")?,
            max_cdeg: u16_(f, "max_cdeg")?,
        },
        5 => HiwonderCommand::RangeRead {
            idx: u8_(f, "idx")?,
        },
        6 => HiwonderCommand::OffsetWrite {
            idx: u8_(f, "idx")?,
            offset_cdeg: i16_(f, "offset_cdeg")?,
        },
        7 => HiwonderCommand::OffsetRead {
            idx: u8_(f, "idx")?,
        },
        8 => HiwonderCommand::VoltageLimitWrite {
            idx: u8_(f, "idx")?,
            min_mv: u16_(f, "min_mv")?,
            max_mv: u16_(f, "max_mv")?,
        },
        9 => HiwonderCommand::MotorModeWrite {
            idx: u8_(f, "idx")?,
            speed: i16_(f, "speed")?,
        },
        _ => HiwonderCommand::AddServo {
            bus_id: u8_(f, "bus_id")?,
        },
    })
}

fn ssd1306_command(f: &mut Fields<'_>) -> Result<Ssd1306Command, String> {
    let subtypes = ["text", "text_done", "binary", "binary_done"];
    Ok(match name(f, "subtype", &subtypes)? {
        0 => {
            let value = f.value("text")?;
            let text = value
                .as_str()
                .ok_or_else(|| format!("field `text` must be a string, found {value}"))?;
            // One character per byte (ISO 8859-1), as decode writes it.
            let bytes = text
                .chars()
                .map(u8::try_from)
                .collect::<Result<Vec<u8>, _>>()
                .map_err(|_| {
                    format!("field `text` must hold characters U+0000..=U+00FF only, found {value}")
                })?;
            Ssd1306Command::Text(
                List::from_slice(&bytes)
                    .map_err(|_| format!("field `text` holds {} bytes, at most 26", bytes.len()))?,
            )
        }
        1 => Ssd1306Command::TextDone,
        2 => Ssd1306Command::Binary {
            chunk: u8_(f, "chunk")?,
            data: f.array("data", byte)?,
        },
        _ => Ssd1306Command::BinaryDone,
    })
}

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

/// The members of a report `kind` (one of [`REPORT_TYPES`] or
/// `unknown_report`).
fn read_report(
    kind: &str,
    f: &mut Fields<'_>,
    dialect: Dialect,
) -> Result<Report<Vec<u8>>, String> {
    let upstream = dialect == Dialect::Upstream11;
    Ok(match kind {
        "serial_loop_back_report" => Report::LoopBack {
            byte: u8_(f, "byte")?,
        },
        "digital_report" => Report::Digital {
            pin: u8_(f, "pin")?,
            high: level(f, "value")?,
        },
        "analog_report" => Report::Analog {
            pin: u8_(f, "pin")?,
            value: u16_(f, "value")?,
        },
        "firmware_version" => Report::FirmwareVersion {
            major: u8_(f, "major")?,
            minor: u8_(f, "minor")?,
        },
        "pico_unique_id" => Report::UniqueId {
            id: f.array("id", byte)?,
        },
        "i2c_write_report" => Report::I2cWrite {
            port: u8_(f, "port")?,
            msg_id: u8_(f, "msg_id")?,
            result: i8_(f, "result")?,
        },
        "i2c_write_failed" => Report::I2cWriteFailed {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            stale: u8_(f, "stale")?,
        },
        "i2c_read_failed" => Report::I2cReadFailed {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            stale: u8_(f, "stale")?,
        },
        "i2c_read_report" if upstream => Report::I2cReadUpstream {
            port: u8_(f, "port")?,
            addr: u8_(f, "addr")?,
            reg: u8_(f, "reg")?,
            data: bytes(f, "data")?,
        },
        "i2c_read_report" => Report::I2cRead {
            port: u8_(f, "port")?,
            msg_id: u8_(f, "msg_id")?,
            reg: u8_(f, "reg")?,
            data: bytes(f, "data")?,
        },
        "sonar_distance" => Report::Sonar(match dialect {
            Dialect::Mirte13 => {
                let trig = u8_(f, "trig")?;
                if f.has("echo") {
                    Sonar::WithEcho {
                        trig,
                        echo: u8_(f, "echo")?,
                        cm: sonar_cm(f)?,
                    }
                } else {
                    Sonar::TrigOnly {
                        trig,
                        cm: sonar_cm(f)?,
                    }
                }
            }
            Dialect::Mirte12 => Sonar::MetresCm {
                trig: u8_(f, "trig")?,
                m: u8_(f, "m")?,
                cm: u8_(f, "cm")?,
            },
            Dialect::Upstream11 => Sonar::CmHundredths {
                trig: u8_(f, "trig")?,
                cm: u8_(f, "cm")?,
                hundredths: u8_(f, "hundredths")?,
            },
        }),
        "dht_report" => Report::Dht {
            pin: u8_(f, "pin")?,
            humidity: u8_(f, "hum_int")?,
            humidity_hundredths: u8_(f, "hum_hundredths")?,
            temp: i8_(f, "temp_int")?,
            temp_hundredths: i8_(f, "temp_hundredths")?,
        },
        "spi_report" => Report::Spi {
            port: u8_(f, "port")?,
            data: bytes(f, "data")?,
        },
        "encoder_report" => Report::Encoder {
            pin: u8_(f, "pin_a")?,
            steps: i8_(f, "steps")?,
        },
        "sensor_report" => {
            let sensor_num = u8_(f, "sensor_num")?;
            let sensor_type = sensor_type(f)?;
            Report::Sensor {
                sensor_num,
                reading: nested(f, "reading", |r| sensor_reading(sensor_type, r))?,
            }
        }
        "sensor_main_report" => Report::SensorSupported {
            sensor_type: type_byte(f, "sensor_type", &SENSOR_TYPES)?,
            supported: flag(f, "supported")?,
        },
        "pong" => Report::Pong {
            counter: u8_(f, "counter")?,
            boot_id: u8_(f, "boot_id")?,
        },
        "module_main_report" => Report::ModuleSupported {
            module_type: type_byte(f, "module_type", &MODULE_TYPES)?,
            supported: flag(f, "supported")?,
        },
        "module_report" => {
            let module_num = u8_(f, "module_num")?;
            let module_type = module_type(f)?;
            Report::Module {
                module_num,
                report: nested(f, "message", |m| module_report(module_type, m))?,
            }
        }
        "get_id_report" => Report::Id { id: u8_(f, "id")? },
        "set_id_report" => Report::IdSet { id: u8_(f, "id")? },
        "feature_check" => Report::Feature {
            msg_type: u8_(f, "msg_type")?,
            supported: flag(f, "ok")?,
            extras: bytes(f, "extras")?,
        },
        "debug_print" => Report::Debug {
            id: u8_(f, "id")?,
            value: u16_(f, "value")?,
        },
        "unknown_report" => Report::Unknown {
            id: u8_(f, "id")?,
            payload: bytes(f, "payload")?,
        },
        other => return Err(format!("unknown type `{other}`")),
    })
}

fn f32s<const N: usize>(f: &mut Fields<'_>, key: &str) -> Result<[f32; N], String> {
    f.array(key, read_f32)
}

fn i16s<const N: usize>(f: &mut Fields<'_>, key: &str) -> Result<[i16; N], String> {
    f.array(key, |v| read_int(v, -32768, 32767).map(|v| v as i16))
}

fn sensor_reading(sensor_type: SensorType, f: &mut Fields<'_>) -> Result<SensorReading, String> {
    Ok(match sensor_type {
        SensorType::Gps => return Err("GPS sends no readings".to_owned()),
        SensorType::Hx711 => SensorReading::Hx711 {
            raw: f.int("raw", i64::from(i32::MIN), i64::from(i32::MAX))? as i32,
        },
        SensorType::Mpu9250 => SensorReading::Mpu9250 {
            accel: f32s(f, "accel")?,
            gyro: f32s(f, "gyro")?,
            mag: f32s(f, "mag")?,
            quat: f32s(f, "quat")?,
        },
        SensorType::Vl53l0x => SensorReading::Vl53l0x { mm: u16_(f, "mm")? },
        SensorType::Veml6040 => SensorReading::Veml6040 {
            r: u16_(f, "r")?,
            g: u16_(f, "g")?,
            b: u16_(f, "b")?,
            w: u16_(f, "w")?,
        },
        SensorType::Adxl345 => SensorReading::Adxl345 {
            accel: i16s(f, "accel")?,
        },
        SensorType::Ina226 => SensorReading::Ina226 {
            volts: f32_(f, "volts")?,
            amps: f32_(f, "amps")?,
        },
        SensorType::Hmc5883l => SensorReading::Hmc5883l {
            field: f32s(f, "field")?,
        },
        SensorType::As5600 => {
            let value = f.value("angles")?;
            let items = value
                .as_array()
                .ok_or_else(|| format!("field `angles` must be an array, found {value}"))?;
            let mut angles = List::new();
            for (i, item) in items.iter().enumerate() {
                let angle =
                    read_int(item, 0, 65535).map_err(|e| format!("field `angles[{i}]` {e}"))?;
                angles
                    .push(angle as u16)
                    .map_err(|_| format!("field `angles` holds {}, at most 8", items.len()))?;
            }
            SensorReading::As5600 { angles }
        }
        SensorType::Mpu6050 => SensorReading::Mpu6050 {
            accel: i16s(f, "accel")?,
            gyro: i16s(f, "gyro")?,
            temp: i16_(f, "temp")?,
        },
        SensorType::Bno055 => SensorReading::Bno055 {
            gyro: f32s(f, "gyro")?,
            mag: f32s(f, "mag")?,
            accel: f32s(f, "accel")?,
            quat: f32s(f, "quat")?,
            temp: i8_(f, "temp")?,
        },
    })
}

fn module_report(
    module_type: ModuleType,
    f: &mut Fields<'_>,
) -> Result<ModuleReport<Vec<u8>>, String> {
    Ok(match module_type {
        ModuleType::HiwonderServo => {
            let subtypes = ["positions", "id_verify", "range", "offset", "added"];
            match name(f, "subtype", &subtypes)? {
                0 => {
                    let positions = objects(f, "positions", |p| {
                        Ok((u8_(p, "idx")?, u16_(p, "centideg")?))
                    })?;
                    let raw = positions
                        .iter()
                        .flat_map(|&(idx, cdeg)| {
                            let [hi, lo] = cdeg.to_be_bytes();
                            [idx, hi, lo]
                        })
                        .collect();
                    ModuleReport::HiwonderPositions(ServoPositions::from_raw(raw))
                }
                1 => ModuleReport::HiwonderIdVerify {
                    bus_id: u8_(f, "bus_id")?,
                    ok: flag(f, "ok")?,
                },
                2 => ModuleReport::HiwonderRange {
                    idx: u8_(f, "idx")?,
                    min_cdeg: u16_(f, "min_cdeg")?,
                    max_cdeg: u16_(f, "max_cdeg")?,
                },
                3 => ModuleReport::HiwonderOffset {
                    idx: u8_(f, "idx")?,
                    offset_cdeg: i16_(f, "offset_cdeg")?,
                },
                _ => ModuleReport::HiwonderAdded {
                    bus_id: u8_(f, "bus_id")?,
                    idx: u8_(f, "idx")?,
                },
            }
        }
        ModuleType::Ssd1306 => {
            let subtypes = ["text_done", "binary_done", "disabled"];
            match name(f, "subtype", &subtypes)? {
                kind @ (0 | 1) => ModuleReport::Ssd1306Done {
                    kind: if kind == 0 {
                        Ssd1306Done::Text
                    } else {
                        Ssd1306Done::Binary
                    },
                    len: u8_(f, "len")?,
                    display_x: u8_(f, "display_x")?,
                    enabled: flag(f, "enabled")?,
                },
                _ => ModuleReport::Ssd1306Disabled {
                    request_sub: u8_(f, "request_sub")?,
                },
            }
        }
        ModuleType::Pca9685 | ModuleType::ShutdownRelay => {
            return Err(format!(
                "module type {} sends no reports",
                MODULE_TYPES[usize::from(module_type.as_u8())]
            ))
        }
    })
}
