//! Telemetrix round trip: every frame decoded from arbitrary bytes, command
//! or report, re-encodes to exactly its bytes in the dialect it was decoded
//! in, unless it has a quirk (a real peer's frame, which the encoder
//! refuses); and every frame's JSON line, quirky or not, reads back in that
//! dialect to exactly its bytes (`robowire decode | robowire encode`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use robowire::telemetrix::{
    CommandBuf, Device, DeviceDecoder, Dialect, Framing, Host, HostDecoder, LenientHostDecoder,
    MessageBuf, ReportBuf,
};

/// decode | encode: the owned form read in the decoder's dialect (as the
/// tool's capture context reads it) serializes to a line that reads back,
/// in that dialect, to exactly `raw`.
fn same_line(owned: MessageBuf, dialect: Dialect, raw: &[u8]) {
    let line = serde_json::to_string(&owned).expect("a frame serializes");
    let mut json = serde_json::Deserializer::from_str(&line);
    let back = MessageBuf::deserialize_in(&mut json, dialect).expect("its line reads back");
    assert_eq!(back.frame(), raw, "{line}");
}

const DIALECTS: [Dialect; 3] = [Dialect::Mirte13, Dialect::Mirte12, Dialect::Upstream11];

fuzz_target!(|data: &[u8]| {
    for dialect in DIALECTS {
        let mut out = [0u8; 256];

        let mut commands = DeviceDecoder::new(Framing::<Device>::new().with_dialect(dialect));
        let mut input = data;
        while let Some(event) = commands.decode(&mut input) {
            if let Ok(frame) = event {
                let owned =
                    CommandBuf::parse_in(frame.raw, dialect).expect("a decoded frame parses");
                same_line(owned.into(), dialect, frame.raw);
                let quirk = CommandBuf::parse_in(frame.raw, dialect).map(|c| c.quirk());
                if quirk != Ok(None) {
                    assert!(quirk.is_ok(), "a decoded frame parses");
                    continue;
                }
                let n = frame
                    .message
                    .encode_in(dialect, &mut out)
                    .expect("re-encode command");
                assert_eq!(&out[..n], frame.raw);
                let owned = frame.message.to_buf_in(dialect).expect("own command");
                assert_eq!(owned.frame(), frame.raw);
                // Compared as bytes: a float reading may be a NaN, which
                // is not equal to itself.
                let m = owned
                    .message()
                    .encode_in(dialect, &mut out)
                    .expect("re-encode the owned form");
                assert_eq!(&out[..m], frame.raw);
            }
        }

        let mut reports = HostDecoder::new(Framing::<Host>::new().with_dialect(dialect));
        let mut input = data;
        while let Some(event) = reports.decode(&mut input) {
            if let Ok(frame) = event {
                let owned =
                    ReportBuf::parse_in(frame.raw, dialect, false).expect("a decoded frame parses");
                same_line(owned.into(), dialect, frame.raw);
                let quirk = ReportBuf::parse_in(frame.raw, dialect, false).map(|r| r.quirk());
                if quirk != Ok(None) {
                    assert!(quirk.is_ok(), "a decoded frame parses");
                    continue;
                }
                let n = frame
                    .message
                    .encode_in(dialect, &mut out)
                    .expect("re-encode report");
                assert_eq!(&out[..n], frame.raw);
                let owned = frame.message.to_buf_in(dialect).expect("own report");
                assert_eq!(owned.frame(), frame.raw);
                // Compared as bytes: a float reading may be a NaN, which
                // is not equal to itself.
                let m = owned
                    .message()
                    .encode_in(dialect, &mut out)
                    .expect("re-encode the owned form");
                assert_eq!(&out[..m], frame.raw);
            }
        }

        let lenient = Framing::<Host>::new().with_dialect(dialect).lenient();
        let mut reports = LenientHostDecoder::new(lenient);
        let mut input = data;
        while let Some(event) = reports.decode(&mut input) {
            if let Ok(frame) = event {
                let owned =
                    ReportBuf::parse_in(frame.raw, dialect, true).expect("a decoded frame parses");
                same_line(owned.into(), dialect, frame.raw);
                let quirk = ReportBuf::parse_in(frame.raw, dialect, true).map(|r| r.quirk());
                if quirk != Ok(None) {
                    continue;
                }
                let n = frame
                    .message
                    .encode_in(dialect, &mut out)
                    .expect("re-encode lenient");
                assert_eq!(&out[..n], frame.raw);
            }
        }
    }
});
