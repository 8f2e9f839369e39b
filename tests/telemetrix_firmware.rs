//! Telemetrix `Framing<Device>::as_firmware()`: commands framed exactly as the
//! Pico's firmware frames them (spec §2.2), checked against a reference model
//! written from the spec.

use proptest::prelude::*;
use robowire::telemetrix::{Command, Device, DeviceDecoder, Dialect, Error, Framing};
use robowire::{OwnedEvent, Rejected};

/// What the firmware's `get_next_command` runs, from spec §2.2: a length
/// byte `00` or above 30 is dropped; any other is trusted, and the next `LEN`
/// bytes are one command. Returns the frames (offset, length) and, if the
/// input ends inside one, where it started.
fn reference(bytes: &[u8]) -> (Vec<(u64, usize)>, Option<u64>) {
    let (mut frames, mut i) = (Vec::new(), 0);
    while i < bytes.len() {
        let len = usize::from(bytes[i]);
        if len == 0 || len > 30 {
            i += 1;
            continue;
        }
        if i + 1 + len > bytes.len() {
            return (frames, Some(i as u64));
        }
        frames.push((i as u64, len + 1));
        i += len + 1;
    }
    (frames, None)
}

/// One event as compared: offset, and the frame's length and command if it
/// is one, or the error.
type Ev = (u64, Result<(usize, Vec<u8>), Error>);

fn firmware_events(dialect: Dialect, bytes: &[u8], chunk: usize) -> Vec<Ev> {
    let framing = Framing::<Device>::new().with_dialect(dialect).as_firmware();
    assert!(framing.is_as_firmware());
    let mut decoder = DeviceDecoder::new(framing);
    let mut out = Vec::new();
    let mut keep = |e: OwnedEvent<Framing<Device>>| {
        out.push(match e {
            Ok(f) => (f.offset, Ok((f.len, f.message.frame().to_vec()))),
            Err(Rejected { offset, error }) => (offset, Err(error)),
        })
    };
    for piece in bytes.chunks(chunk.max(1)) {
        decoder.feed(piece).for_each(&mut keep);
    }
    decoder.flush().for_each(&mut keep);
    out
}

/// Check the decoder against the reference on `bytes`.
fn agrees(dialect: Dialect, bytes: &[u8], chunk: usize) -> Result<(), TestCaseError> {
    let (frames, truncated) = reference(bytes);
    let events = firmware_events(dialect, bytes, chunk);
    // At the end, an unfinished frame: reported as truncated, once per
    // length byte in it, and nothing in it decoded.
    let ends = events
        .iter()
        .position(|e| matches!(e.1, Err(Error::Truncated { .. })))
        .unwrap_or(events.len());
    let (body, tail) = events.split_at(ends);
    prop_assert_eq!(tail.first().map(|e| e.0), truncated);
    let all_truncated = tail
        .iter()
        .all(|e| matches!(e.1, Err(Error::Truncated { .. })));
    prop_assert!(all_truncated, "{:?}", tail);
    prop_assert_eq!(body.len(), frames.len(), "{:?} vs {:?}", body, frames);
    for (&(offset, len), (at, got)) in frames.iter().zip(body) {
        prop_assert_eq!(*at, offset);
        let frame = &bytes[offset as usize..offset as usize + len];
        match (Command::parse_in(frame, dialect), got) {
            // A command the decoder reads: the firmware runs it.
            (Ok(_), Ok((n, raw))) => {
                prop_assert_eq!(*n, len);
                prop_assert_eq!(&raw[..], frame);
            }
            // Not a valid command: consumed whole and reported, never rescanned.
            (Err(expected), Err(error)) => prop_assert_eq!(expected, *error),
            (parsed, got) => prop_assert!(false, "{frame:02x?}: {parsed:?} vs {got:?}"),
        }
    }
    Ok(())
}

/// Bytes like a command stream: many small lengths, ids and values.
fn stream() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(prop_oneof![3 => 0u8..=40, 1 => any::<u8>()], 0..400)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn firmware_framing_matches_the_reference_model(
        bytes in stream(),
        chunk in 1usize..64,
        dialect in prop::sample::select(&Dialect::ALL[..]),
    ) {
        agrees(dialect, &bytes, chunk)?;
        // Every split gives the same events.
        prop_assert_eq!(
            firmware_events(dialect, &bytes, chunk),
            firmware_events(dialect, &bytes, bytes.len())
        );
    }
}

#[test]
fn golden_firmware_framing() {
    // Padding and a LEN over 30 are dropped; a frame the robust decoder
    // rejects (SET_PIN_MODE with LEN 2) is what the firmware runs, consumed
    // whole; GET_FIRMWARE_VERSION follows.
    let bytes = [0x00, 0x1f, 0x02, 0x01, 0x19, 0x01, 0x05];
    let events = firmware_events(Dialect::Mirte13, &bytes, bytes.len());
    assert_eq!(
        events,
        [
            (2, Err(Error::BadLength { id: 1, len: 2 })),
            (5, Ok((2, vec![0x01, 0x05]))),
        ]
    );
}
