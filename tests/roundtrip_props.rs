//! `decode | encode` as a property, through the library's serde form (what
//! the `robowire` tool prints and reads): on streams built from pieces of
//! the sample captures in tests/data, the frames real peers send that the
//! encoder refuses without their `quirk` marker, and noise, every decoded
//! frame's JSON line reads back and encodes to exactly the input's bytes at
//! its offset, for every protocol, side and Telemetrix dialect.

#![cfg(feature = "serde")]

use proptest::prelude::*;
use robowire::stream::StreamDecoder;
use robowire::{omnitiles, pixy2, telemetrix, FrameBuf, FrameRules, OwnedEvent};
use serde::Serialize;

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// A sample capture's bytes.
fn capture(name: &str) -> Vec<u8> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    let bytes = std::fs::read(path).unwrap();
    if name.ends_with(".hex") {
        hex(std::str::from_utf8(&bytes).unwrap())
    } else {
        bytes
    }
}

/// The sources streams are cut from: every capture, and the quirky frames.
fn sources() -> Vec<Vec<u8>> {
    let mut sources: Vec<Vec<u8>> = [
        "ble_notifications.hex",
        "ble_telemetry.bin",
        "host_commands.bin",
        "pixy2_conversation.hex",
        "spi_commands.hex",
        "spi_telemetry.bin",
        "telemetrix_commands.hex",
        "telemetrix_reports.bin",
    ]
    .into_iter()
    .map(capture)
    .collect();
    sources.push(hex(
        // Telemetrix: mirte 1.3's, mirte 1.2's and upstream 1.1's quirks,
        // the SSD1306 echo; Pixy2 getBlocks with sigmap 0 in both forms.
        "03 04 04 02  03 02 05 02  05 03 01 00 10 07  06 03 01 00 10 07 08  05 1e 03 02 03 00 \
         05 22 03 03 05 fe  03 04 01 1a  03 04 03 1e  04 1e 03 02 03 \
         ae c1 20 02 00 00  af c1 20 02 05 00 00 05",
    ));
    sources
}

/// Every frame a decoder finds in `input`: offset, length, owned message.
fn frames<F: FrameRules, const N: usize>(
    mut decoder: StreamDecoder<F, N>,
    input: &[u8],
) -> Vec<(usize, usize, F::Owned)> {
    let mut out = Vec::new();
    let mut keep = |event: OwnedEvent<F>| {
        if let Ok(frame) = event {
            out.push((frame.offset as usize, frame.len, frame.message));
        }
    };
    decoder.feed(input).for_each(&mut keep);
    decoder.flush().for_each(&mut keep);
    out
}

/// Telemetrix as the tool runs it: a capture context gives each frame the
/// decoder's dialect and direction before it is printed.
fn telemetrix_side<S: telemetrix::Side>(framing: telemetrix::Framing<S>, input: &[u8])
where
    S::Owned: Into<telemetrix::MessageBuf>,
{
    let dialect = framing.dialect();
    let mut context = telemetrix::CaptureContext::new(&framing);
    let decoder = StreamDecoder::<_, { telemetrix::BOTH_BUFFER }>::new(framing);
    for (offset, len, owned) in frames(decoder, input) {
        let mut message: telemetrix::MessageBuf = owned.into();
        context.annotate(&mut message);
        let line = serde_json::to_string(&message).unwrap();
        let mut json = serde_json::Deserializer::from_str(&line);
        let back = telemetrix::MessageBuf::deserialize_in(&mut json, dialect)
            .unwrap_or_else(|e| panic!("{dialect} {line}: {e}"));
        assert_eq!(
            back.frame(),
            &input[offset..offset + len],
            "{dialect} {line}"
        );
    }
}

/// Pixy2 as the tool encodes a line: through the opt-in, which only a
/// marked line can ask for (the plain encoder refuses exactly those).
fn pixy2_side<S: pixy2::Side>(framing: pixy2::Framing<S>, input: &[u8])
where
    S::Owned: Serialize,
{
    let decoder = StreamDecoder::<_, { pixy2::BOTH_BUFFER }>::new(framing);
    for (offset, len, owned) in frames(decoder, input) {
        let line = serde_json::to_string(&owned).unwrap();
        let back: pixy2::Envelope<pixy2::MessageBuf> = serde_json::from_str(&line).unwrap();
        let marked = line.contains(r#""quirk":"sigmap_zero""#);
        assert_eq!(back.body.quirk().is_some(), marked, "{line}");
        assert_eq!(FrameBuf::<261>::encode(&back).is_ok(), !marked, "{line}");
        let frame = FrameBuf::<261>::encode(&back.even_if_refused()).unwrap();
        assert_eq!(&frame[..], &input[offset..offset + len], "{line}");
    }
}

fn omnitiles_side<S: omnitiles::Side>(framing: omnitiles::Framing<S>, input: &[u8])
where
    S::Message: Into<omnitiles::Message>,
{
    let decoder = StreamDecoder::<_, { omnitiles::BOTH_BUFFER }>::new(framing);
    for (offset, len, owned) in frames(decoder, input) {
        let message: omnitiles::Message = owned.into();
        let line = serde_json::to_string(&message).unwrap();
        let back: omnitiles::Message = serde_json::from_str(&line).unwrap();
        let frame = FrameBuf::<{ omnitiles::Message::MAX_LEN }>::encode(&back).unwrap();
        assert_eq!(&frame[..], &input[offset..offset + len], "{line}");
    }
}

fn every_protocol_and_side(input: &[u8]) {
    for dialect in telemetrix::Dialect::ALL {
        use telemetrix::{Both, Device, Framing, Host};
        telemetrix_side(Framing::<Device>::new().with_dialect(dialect), input);
        telemetrix_side(Framing::<Host>::new().with_dialect(dialect), input);
        telemetrix_side(
            Framing::<Host>::new().with_dialect(dialect).lenient(),
            input,
        );
        telemetrix_side(Framing::<Both>::new().with_dialect(dialect), input);
        telemetrix_side(
            Framing::<Both>::new().with_dialect(dialect).lenient(),
            input,
        );
    }
    pixy2_side(pixy2::Framing::<pixy2::Host>::new(), input);
    pixy2_side(pixy2::Framing::<pixy2::Device>::new(), input);
    pixy2_side(pixy2::Framing::<pixy2::Both>::new(), input);
    omnitiles_side(omnitiles::Framing::<omnitiles::Device>::new(), input);
    omnitiles_side(omnitiles::Framing::<omnitiles::Host>::new(), input);
    omnitiles_side(omnitiles::Framing::<omnitiles::Both>::new(), input);
}

#[test]
fn every_capture_whole() {
    for source in sources() {
        every_protocol_and_side(&source);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Pieces of the captures and quirks, with noise between them.
    #[test]
    fn cut_and_mixed_streams(
        pieces in prop::collection::vec(
            (any::<prop::sample::Index>(), any::<prop::sample::Index>(), 1usize..96,
             prop::collection::vec(any::<u8>(), 0..8)),
            1..12,
        )
    ) {
        let sources = sources();
        let mut input = Vec::new();
        for (source, start, len, noise) in pieces {
            let source = source.get(&sources);
            let start = start.index(source.len());
            input.extend_from_slice(&source[start..(start + len).min(source.len())]);
            input.extend_from_slice(&noise);
        }
        every_protocol_and_side(&input);
    }
}
