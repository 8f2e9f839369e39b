//! The optional `serde` and `defmt` derives on the protocol-neutral types.

#[cfg(feature = "serde")]
#[test]
fn serde_round_trips_reports_and_counters() {
    use robowire::omnitiles::{Decoder, Framing};
    use robowire::{EncodeError, Framed, Rejected, Stats};

    let mut decoder = Decoder::new(Framing::commands());
    decoder
        .feed(&[0x00, 0xa5, 0x50, 0x51, 0xa5, 0x50, 0x50])
        .for_each(drop);
    let stats = decoder.stats();
    let json = serde_json::to_string(&stats).unwrap();
    assert_eq!(
        json,
        r#"{"bytes":7,"frames":1,"frame_bytes":3,"skipped":4,"checksum_errors":1,"rejected":0,"malformed":0,"superseded":0}"#
    );
    assert_eq!(serde_json::from_str::<Stats>(&json).unwrap(), stats);

    let framed = Framed {
        offset: 4,
        len: 3,
        message: 7u8,
    };
    let json = serde_json::to_string(&framed).unwrap();
    assert_eq!(json, r#"{"offset":4,"len":3,"message":7}"#);
    assert_eq!(serde_json::from_str::<Framed<u8>>(&json).unwrap(), framed);

    let rejected = Rejected {
        offset: 1,
        error: 9u8,
    };
    let json = serde_json::to_string(&rejected).unwrap();
    assert_eq!(
        serde_json::from_str::<Rejected<u8>>(&json).unwrap(),
        rejected
    );

    let error = EncodeError::BufferTooSmall {
        needed: 6,
        available: 2,
    };
    assert_eq!(
        serde_json::to_string(&error).unwrap(),
        r#"{"BufferTooSmall":{"needed":6,"available":2}}"#
    );
}

/// Compiles only if every type here implements `defmt::Format`.
#[cfg(feature = "defmt")]
#[test]
fn defmt_formats_reports_and_counters() {
    fn format<T: defmt::Format>() -> &'static str {
        core::any::type_name::<T>()
    }
    let names = [
        format::<robowire::Stats>(),
        format::<robowire::Framed<u8>>(),
        format::<robowire::Rejected<u8>>(),
        format::<robowire::EncodeError>(),
        format::<robowire::Check<u8>>(),
        format::<robowire::Frame<'static, u8>>(),
        format::<robowire::FrameBuf<8>>(),
    ];
    assert!(names.iter().all(|n| n.starts_with("robowire::")));
}

#[cfg(all(
    feature = "defmt",
    any(feature = "embedded-io-07", feature = "embedded-io-async-07")
))]
#[test]
fn defmt_formats_write_errors() {
    fn format<T: defmt::Format>() -> &'static str {
        core::any::type_name::<T>()
    }
    assert!(format::<robowire::io::WriteError<u8>>().contains("WriteError"));
}

/// Serialize `value` to JSON, check the text, and read it back.
#[cfg(feature = "serde")]
fn json_round_trip<T>(value: &T, expected: &str)
where
    T: serde::Serialize + serde::de::DeserializeOwned + PartialEq + core::fmt::Debug,
{
    let json = serde_json::to_string(value).unwrap();
    assert_eq!(json, expected);
    assert_eq!(&serde_json::from_str::<T>(&json).unwrap(), value);
}

#[cfg(feature = "serde")]
#[test]
fn serde_engine_types() {
    use robowire::{Check, Frame, FrameBuf};

    json_round_trip(&Check::<u8>::Need(4), r#"{"Need":4}"#);
    json_round_trip(&Check::<u8>::Reject(2), r#"{"Reject":2}"#);

    let frame = Frame {
        offset: 3,
        raw: &[0xa5, 0x50, 0x50][..],
        message: 1u8,
    };
    assert_eq!(
        serde_json::to_string(&frame).unwrap(),
        r#"{"offset":3,"raw":[165,80,80],"message":1}"#
    );

    let buf = FrameBuf::<8>::encode(&robowire::omnitiles::Command::Ping).unwrap();
    json_round_trip(&buf, "[165,80,80]");
    json_round_trip(&FrameBuf::<8>::new(), "[]");
    let too_long = serde_json::from_str::<FrameBuf<2>>("[165,80,80]").unwrap_err();
    assert!(
        too_long.to_string().contains("at most 2 bytes"),
        "{too_long}"
    );
}
