//! Inputs the fuzz targets found, kept as regression tests.

use robowire::telemetrix::{Dialect, Framing, HostDecoder};
use robowire::{OwnedEvent, StreamDecoder};

fn events<F: robowire::FrameRules, const N: usize>(
    mut decoder: StreamDecoder<F, N>,
    input: &[u8],
    chunk: usize,
) -> Vec<OwnedEvent<F>> {
    let mut events = Vec::new();
    for piece in input.chunks(chunk) {
        events.extend(decoder.feed(piece));
    }
    events.extend(decoder.flush());
    events
}

/// `telemetrix_stream`: a FEATURE_CHECK report header with `LEN = 255`. Its
/// first bytes were refused as an impossible length, but once the message
/// type and status arrived the length check let any `LEN >= 7` through, so
/// the answer depended on how the bytes were split.
#[test]
fn feature_check_length_is_refused_however_the_bytes_arrive() {
    let input = [0x00, 0x29, 0x79, 0xff, 0x25, 0x01, 0x01, 0x00];
    for dialect in [Dialect::Mirte13, Dialect::Mirte12, Dialect::Upstream11] {
        let framing = Framing::new().with_dialect(dialect);
        let whole = events(HostDecoder::new(framing), &input, input.len());
        for chunk in 1..input.len() {
            assert_eq!(
                events(HostDecoder::new(framing), &input, chunk),
                whole,
                "{dialect:?}, chunk {chunk}"
            );
        }
        if dialect == Dialect::Mirte13 {
            // FEATURE_CHECK is a report in this dialect: refused by length.
            let at_3 = whole
                .iter()
                .find_map(|e| e.as_ref().err().filter(|r| r.offset == 3));
            assert!(
                matches!(
                    at_3.map(|r| r.error),
                    Some(robowire::telemetrix::Error::BadLength { id: 37, len: 255 })
                ),
                "{whole:?}"
            );
        }
    }
}

/// `telemetrix_roundtrip`: an INA226 sensor report whose volts are a NaN.
/// The owned form holds the frame's exact bytes; only its message compares
/// unequal to itself (NaN), so the target now compares bytes.
#[test]
fn a_nan_reading_keeps_its_bytes_in_the_owned_form() {
    let input = [
        0x0b, 0x0a, 0x0b, 0x14, 0x05, 0x06, 0x03, 0x1f, 0xff, 0xff, 0x00, 0xff, 0xff, 0xa3, 0x14,
        0x05,
    ];
    let mut found_nan = false;
    for dialect in [Dialect::Mirte13, Dialect::Mirte12, Dialect::Upstream11] {
        let mut decoder = HostDecoder::new(Framing::new().with_dialect(dialect));
        let mut rest = &input[..];
        while let Some(event) = decoder.decode(&mut rest) {
            let Ok(frame) = event else { continue };
            let owned = frame.message.to_buf_in(dialect).expect("own report");
            assert_eq!(owned.frame(), frame.raw, "{dialect:?}");
            let mut out = [0u8; 256];
            let n = owned
                .message()
                .encode_in(dialect, &mut out)
                .expect("re-encode");
            assert_eq!(&out[..n], frame.raw, "{dialect:?}");
            found_nan |= format!("{:?}", owned.message()).contains("NaN");
        }
    }
    assert!(found_nan, "the input holds a NaN reading");
}
