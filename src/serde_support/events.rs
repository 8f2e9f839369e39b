//! The stream's events in the JSON-lines schema: a decoded frame is its
//! message's map with `offset` and `len` first, a rejection its error's map
//! with `offset` first.

use serde::de::{Deserialize, DeserializeOwned, Deserializer, Error as _};
use serde::{Serialize, Serializer};

use super::prefixed::serialize_prefixed;
use super::Value;
use crate::stream::{Frame, OwnedFrame, Rejected};

impl<M: Serialize> Serialize for Frame<'_, M> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let prefix = [("offset", self.offset), ("len", self.raw.len() as u64)];
        serialize_prefixed(serializer, &prefix, "message", &self.message)
    }
}

impl<M: Serialize> Serialize for OwnedFrame<M> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let prefix = [("offset", self.offset), ("len", self.len as u64)];
        serialize_prefixed(serializer, &prefix, "message", &self.message)
    }
}

impl<E: Serialize> Serialize for Rejected<E> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serialize_prefixed(serializer, &[("offset", self.offset)], "error", &self.error)
    }
}

/// Take the unsigned integer member `key` out of `members`.
fn take_u64<E: serde::de::Error>(
    members: &mut alloc::collections::BTreeMap<alloc::string::String, Value>,
    key: &str,
) -> Result<u64, E> {
    let value = members
        .remove(key)
        .ok_or_else(|| E::missing_field_named(key))?;
    value.as_u64().ok_or_else(|| {
        E::custom(format_args!(
            "field `{key}` must be an unsigned integer, found {value}"
        ))
    })
}

trait MissingField: serde::de::Error {
    fn missing_field_named(key: &str) -> Self {
        Self::custom(format_args!("missing field `{key}`"))
    }
}

impl<E: serde::de::Error> MissingField for E {}

/// Read what is left of an event once the stream's members are taken: the
/// whole object (a message or an internally tagged error), or, for a value
/// that serialized as a single value, the member `fallback` alone.
fn read_rest<T: DeserializeOwned>(
    members: alloc::collections::BTreeMap<alloc::string::String, Value>,
    fallback: &str,
) -> Result<T, serde::de::value::Error> {
    let single = match (members.len(), members.get(fallback)) {
        (1, Some(value)) => Some(value.clone()),
        _ => None,
    };
    T::deserialize(Value::Map(members)).or_else(|as_object| match single {
        Some(value) => T::deserialize(value).map_err(|_| as_object),
        None => Err(as_object),
    })
}

/// Reads what [`Serialize`] writes: `offset`, `len`, and the message's own
/// members (the message reads the rest of the object).
impl<'de, M: DeserializeOwned> Deserialize<'de> for OwnedFrame<M> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let Value::Map(mut members) = Value::deserialize(deserializer)? else {
            return Err(D::Error::custom("expected a decoded frame (an object)"));
        };
        let offset = take_u64(&mut members, "offset")?;
        let len = take_u64(&mut members, "len")?;
        let len = usize::try_from(len).map_err(D::Error::custom)?;
        let message = read_rest(members, "message").map_err(D::Error::custom)?;
        Ok(OwnedFrame {
            offset,
            len,
            message,
        })
    }
}

/// Reads what [`Serialize`] writes: `offset` and the error's own members.
impl<'de, E: DeserializeOwned> Deserialize<'de> for Rejected<E> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let Value::Map(mut members) = Value::deserialize(deserializer)? else {
            return Err(D::Error::custom("expected a rejection (an object)"));
        };
        let offset = take_u64(&mut members, "offset")?;
        let error = read_rest(members, "error").map_err(D::Error::custom)?;
        Ok(Rejected { offset, error })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(tag = "type", rename_all = "snake_case")]
    enum Toy {
        Ping,
        Move { speed: u8 },
    }

    #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(tag = "error", rename_all = "snake_case")]
    enum ToyError {
        Checksum { expected: u8, found: u8 },
        Unconfirmed,
    }

    #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
    #[serde(rename_all = "snake_case")]
    enum Plain {
        Short,
    }

    fn round_trip<T: Serialize + DeserializeOwned + PartialEq + core::fmt::Debug>(
        value: T,
        json: &str,
    ) {
        assert_eq!(serde_json::to_string(&value).unwrap(), json);
        assert_eq!(
            serde_json::from_str::<T>(json).map_err(|e| e.to_string()),
            Ok(value)
        );
    }

    #[test]
    fn frames_put_offset_and_len_first() {
        let frame = OwnedFrame {
            offset: 12,
            len: 4,
            message: Toy::Move { speed: 200 },
        };
        round_trip(frame, r#"{"offset":12,"len":4,"type":"move","speed":200}"#);
        let ping = OwnedFrame {
            offset: 0,
            len: 3,
            message: Toy::Ping,
        };
        round_trip(ping, r#"{"offset":0,"len":3,"type":"ping"}"#);
        let borrowed = Frame {
            offset: 5,
            raw: &[1, 2, 3][..],
            message: Toy::Ping,
        };
        assert_eq!(
            serde_json::to_string(&borrowed).unwrap(),
            r#"{"offset":5,"len":3,"type":"ping"}"#
        );
    }

    #[test]
    fn rejections_put_offset_first() {
        let checksum = Rejected {
            offset: 2,
            error: ToyError::Checksum {
                expected: 248,
                found: 247,
            },
        };
        round_trip(
            checksum,
            r#"{"offset":2,"error":"checksum","expected":248,"found":247}"#,
        );
        let unit = Rejected {
            offset: 7,
            error: ToyError::Unconfirmed,
        };
        round_trip(unit, r#"{"offset":7,"error":"unconfirmed"}"#);
        let plain = Rejected {
            offset: 1,
            error: Plain::Short,
        };
        round_trip(plain, r#"{"offset":1,"error":"short"}"#);
    }

    #[test]
    fn a_message_that_is_not_a_map_is_refused_clearly() {
        let frame = OwnedFrame {
            offset: 0,
            len: 1,
            message: [1u8, 2],
        };
        let error = serde_json::to_string(&frame).unwrap_err().to_string();
        assert!(error.contains("must serialize as a map"), "{error}");
    }
}
