//! The `serde` form of OmniTiles messages and errors: the `robowire`
//! command-line tool's JSON lines (without the `offset` and `len` the stream
//! adds). Reading checks every field as the encoder needs it, with the tool's
//! messages.

use alloc::format;
use alloc::string::String;
use serde::de::Error as _;
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::command::{Command, Motor};
use super::error::Error;
use super::framing::{Framing, Side};
use super::layout::{Layout, Layouts};
use super::message::Message;
use super::telemetry::{Imu, Telemetry, NO_READING};
use crate::serde_support::{read_f32, read_int, serialize_f32, unknown_type, Fields, Value};

// ------------------------------------------------------------------ writing

impl Serialize for Command {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let fields = match self {
            Command::Extend { .. } | Command::Retract { .. } | Command::SetPosition { .. } => 1,
            Command::BaseVelocity { .. } => 3,
            Command::Ping | Command::Brake { .. } | Command::BaseBrake => 0,
        };
        let mut map = serializer.serialize_map(Some(1 + fields))?;
        map.serialize_entry("type", self.name())?;
        match *self {
            Command::Extend { speed, .. } | Command::Retract { speed, .. } => {
                map.serialize_entry("speed", &speed)?;
            }
            Command::SetPosition { position, .. } => map.serialize_entry("position", &position)?,
            Command::BaseVelocity { vx, vy, omega } => {
                map.serialize_entry("vx", &vx)?;
                map.serialize_entry("vy", &vy)?;
                map.serialize_entry("omega", &omega)?;
            }
            Command::Ping | Command::Brake { .. } | Command::BaseBrake => {}
        }
        map.end()
    }
}

impl Serialize for Telemetry {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let groups = [
            self.uwb.is_some(),
            self.tof.is_some(),
            self.imu.is_some(),
            self.m1_adcs.is_some(),
            self.m2_adcs.is_some(),
        ];
        let len = 4 + groups.iter().filter(|&&g| g).count();
        let mut map = serializer.serialize_map(Some(len))?;
        map.serialize_entry("type", "telemetry")?;
        map.serialize_entry("layout", &self.layout)?;
        map.serialize_entry("m1_pos", &self.m1_pos)?;
        map.serialize_entry("m2_pos", &self.m2_pos)?;
        if let Some(uwb) = &self.uwb {
            map.serialize_entry("uwb", uwb)?;
        }
        if let Some(tof) = &self.tof {
            map.serialize_entry("tof", tof)?;
        }
        if let Some(imu) = &self.imu {
            map.serialize_entry("imu", imu)?;
        }
        if let Some(adcs) = &self.m1_adcs {
            map.serialize_entry("m1_adcs", adcs)?;
        }
        if let Some(adcs) = &self.m2_adcs {
            map.serialize_entry("m2_adcs", adcs)?;
        }
        map.end()
    }
}

/// An `f32` in the schema's form.
struct F32(f32);

impl Serialize for F32 {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_f32(self.0, serializer)
    }
}

impl Serialize for Imu {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(6))?;
        for (name, value) in Imu::NAMES.into_iter().zip(self.to_array()) {
            map.serialize_entry(name, &F32(value))?;
        }
        map.end()
    }
}

impl Serialize for Message {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Message::Command(c) => c.serialize(serializer),
            Message::Telemetry(t) => t.serialize(serializer),
        }
    }
}

impl Serialize for Error {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let (tag, fields): (&str, &[(&str, usize)]) = match *self {
            Error::Checksum { expected, found } => (
                "checksum",
                &[("expected", expected as usize), ("found", found as usize)],
            ),
            Error::UnknownId { id } => ("unknown_id", &[("id", id as usize)]),
            Error::Unconfirmed => ("unconfirmed", &[]),
            Error::Truncated { len } => ("truncated", &[("len", len)]),
            Error::Superseded { len } => ("superseded", &[("len", len)]),
            Error::BadStart { found } => ("bad_start", &[("found", found as usize)]),
            Error::BadLength { len } => ("bad_length", &[("len", len)]),
        };
        let mut map = serializer.serialize_map(Some(1 + fields.len()))?;
        map.serialize_entry("error", tag)?;
        for (key, value) in fields {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

impl<S: Side> Serialize for Framing<S> {
    fn serialize<Z: Serializer>(&self, serializer: Z) -> Result<Z::Ok, Z::Error> {
        let mut map = serializer.serialize_map(Some(1))?;
        map.serialize_entry("layouts", &self.layouts())?;
        map.end()
    }
}

// ------------------------------------------------------------------ reading

impl<'de> Deserialize<'de> for Message {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        read_line(&value, read_message).map_err(D::Error::custom)
    }
}

impl<'de> Deserialize<'de> for Command {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        read_line(&value, |kind, fields| match read_message(kind, fields)? {
            Message::Command(command) => Ok(command),
            Message::Telemetry(_) => Err(format!("type `{kind}` is not a command")),
        })
        .map_err(D::Error::custom)
    }
}

impl<'de> Deserialize<'de> for Telemetry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        read_line(&value, |kind, fields| {
            if kind != "telemetry" && Command::NAMES.contains(&kind) {
                return Err(format!("type `{kind}` is not telemetry"));
            }
            match read_message(kind, fields)? {
                Message::Telemetry(telemetry) => Ok(telemetry),
                Message::Command(_) => Err(format!("type `{kind}` is not telemetry")),
            }
        })
        .map_err(D::Error::custom)
    }
}

impl<'de> Deserialize<'de> for Imu {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        let read = || {
            let fields = value
                .as_object()
                .map(Fields::new)
                .ok_or_else(|| format!("expected a JSON object, found {value}"))?;
            read_imu(fields, "")
        };
        read().map_err(D::Error::custom)
    }
}

impl<'de> Deserialize<'de> for Error {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = Value::deserialize(deserializer)?;
        read_error(&value).map_err(D::Error::custom)
    }
}

impl<'de, S: Side> Deserialize<'de> for Framing<S> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        /// The members as written.
        #[derive(Deserialize)]
        #[serde(rename = "Framing", deny_unknown_fields)]
        struct Members {
            layouts: Layouts,
        }
        let members = Members::deserialize(deserializer)?;
        Framing::<S>::from_layouts(members.layouts).ok_or_else(|| {
            D::Error::custom("a device framing accepts commands only: its layouts must be 0")
        })
    }
}

/// One JSON line: an object with a `type`, read by `read`, and no member
/// left over but `offset` and `len`.
fn read_line<T>(
    value: &Value,
    read: impl FnOnce(&str, &mut Fields<'_>) -> Result<T, String>,
) -> Result<T, String> {
    let map = value
        .as_object()
        .ok_or_else(|| format!("expected a JSON object, found {value}"))?;
    let mut fields = Fields::new(map);
    let kind = fields.string("type")?;
    let message = read(kind, &mut fields)?;
    fields.finish(&format!("for type {kind}"))?;
    Ok(message)
}

fn read_message(kind: &str, fields: &mut Fields<'_>) -> Result<Message, String> {
    use Motor::{M1, M2};
    let speed = |f: &mut Fields<'_>| f.int("speed", 0, 255).map(|v| v as u8);
    let position = |f: &mut Fields<'_>| f.int("position", 0, 255).map(|v| v as u8);
    let signed = |f: &mut Fields<'_>, key| f.int(key, -128, 127).map(|v| v as i8);
    let command = match kind {
        "ping" => Command::Ping,
        "m1_extend" => Command::Extend {
            motor: M1,
            speed: speed(fields)?,
        },
        "m1_retract" => Command::Retract {
            motor: M1,
            speed: speed(fields)?,
        },
        "m1_brake" => Command::Brake { motor: M1 },
        "m1_set_position" => Command::SetPosition {
            motor: M1,
            position: position(fields)?,
        },
        "m2_extend" => Command::Extend {
            motor: M2,
            speed: speed(fields)?,
        },
        "m2_retract" => Command::Retract {
            motor: M2,
            speed: speed(fields)?,
        },
        "m2_brake" => Command::Brake { motor: M2 },
        "m2_set_position" => Command::SetPosition {
            motor: M2,
            position: position(fields)?,
        },
        "base_velocity" => Command::BaseVelocity {
            vx: signed(fields, "vx")?,
            vy: signed(fields, "vy")?,
            omega: signed(fields, "omega")?,
        },
        "base_brake" => Command::BaseBrake,
        "telemetry" => return read_telemetry(fields).map(Message::Telemetry),
        other => return Err(unknown_type(other, &Message::NAMES)),
    };
    Ok(Message::Command(command))
}

/// A reading: `null` for no reading (`0xFFFF` on the wire) or 0..=65534.
fn read_reading(value: &Value) -> Result<Option<u16>, String> {
    if value.is_null() {
        return Ok(None);
    }
    read_int(value, 0, i64::from(NO_READING) - 1)
        .map(|v| Some(v as u16))
        .map_err(|_| {
            format!(
                "must be null or an integer 0..=65534 (0xFFFF, no reading, is written null), \
                 found {value}"
            )
        })
}

fn read_u16(value: &Value) -> Result<u16, String> {
    read_int(value, 0, 65535).map(|v| v as u16)
}

fn read_telemetry(fields: &mut Fields<'_>) -> Result<Telemetry, String> {
    let name = fields.string("layout")?;
    let layout = Layout::from_name(name).ok_or_else(|| {
        format!("unknown layout `{name}` (expected pos7, uwb15, uwbtof17, spi45 or ble53)")
    })?;
    // A field group must be present exactly when the layout carries it.
    let carried = |fields: &Fields<'_>, key: &str, carries: bool| match (carries, fields.has(key)) {
        (true, true) => Ok(true),
        (false, false) => Ok(false),
        (true, false) => Err(format!("missing field `{key}` (layout {name} carries it)")),
        (false, true) => Err(format!("layout {name} does not carry `{key}`")),
    };
    let reading = |fields: &mut Fields<'_>, key: &str| {
        read_reading(fields.value(key)?).map_err(|e| format!("field `{key}` {e}"))
    };
    let mut t = Telemetry::empty(layout);
    t.m1_pos = reading(fields, "m1_pos")?;
    t.m2_pos = reading(fields, "m2_pos")?;
    if carried(fields, "uwb", layout.has_uwb())? {
        t.uwb = Some(fields.array("uwb", read_reading)?);
    }
    if carried(fields, "tof", layout.has_tof())? {
        t.tof = Some(reading(fields, "tof")?);
    }
    let imu_and_adcs = layout.has_imu_and_adcs();
    if carried(fields, "imu", imu_and_adcs)? {
        t.imu = Some(read_imu(fields.object("imu")?, "imu.")?);
    }
    if carried(fields, "m1_adcs", imu_and_adcs)? {
        t.m1_adcs = Some(fields.array("m1_adcs", read_u16)?);
    }
    if carried(fields, "m2_adcs", imu_and_adcs)? {
        t.m2_adcs = Some(fields.array("m2_adcs", read_u16)?);
    }
    Ok(t)
}

/// The IMU object's six members; `path` prefixes their names in messages
/// (`imu.` inside telemetry).
fn read_imu(mut imu: Fields<'_>, path: &str) -> Result<Imu, String> {
    let mut values = [0f32; 6];
    for (value, key) in values.iter_mut().zip(Imu::NAMES) {
        let raw = imu
            .value(key)
            .map_err(|_| format!("missing field `{path}{key}`"))?;
        *value = read_f32(raw).map_err(|e| format!("field `{path}{key}` {e}"))?;
    }
    match path.strip_suffix('.') {
        Some(parent) => imu.finish_nested(&format!("in `{parent}`"))?,
        None => imu.finish_nested("in the IMU sample")?,
    }
    Ok(Imu::from_array(values))
}

/// A diagnostic event: `error` and its fields (`offset` is ignored).
fn read_error(value: &Value) -> Result<Error, String> {
    let map = value
        .as_object()
        .ok_or_else(|| format!("expected a JSON object, found {value}"))?;
    let mut fields = Fields::new(map);
    let tag = fields.string("error")?;
    let byte = |f: &mut Fields<'_>, key| f.int(key, 0, 255).map(|v| v as u8);
    let longest = i64::try_from(usize::MAX).unwrap_or(i64::MAX);
    let len = |f: &mut Fields<'_>| f.int("len", 0, longest).map(|v| v as usize);
    let error = match tag {
        "checksum" => Error::Checksum {
            expected: byte(&mut fields, "expected")?,
            found: byte(&mut fields, "found")?,
        },
        "unknown_id" => Error::UnknownId {
            id: byte(&mut fields, "id")?,
        },
        "unconfirmed" => Error::Unconfirmed,
        "truncated" => Error::Truncated {
            len: len(&mut fields)?,
        },
        "superseded" => Error::Superseded {
            len: len(&mut fields)?,
        },
        "bad_start" => Error::BadStart {
            found: byte(&mut fields, "found")?,
        },
        "bad_length" => Error::BadLength {
            len: len(&mut fields)?,
        },
        other => return Err(format!("unknown error `{other}`")),
    };
    fields.finish(&format!("for error {tag}"))?;
    Ok(error)
}
