//! `FirmwareParser`: the tile's own command parser, byte for byte, checked
//! against a reference model written from the spec's rules (§8, item 4) and
//! against the robust device decoder.

#[path = "support/corruption.rs"]
mod corruption;

use corruption::{command_stream, Corruption};
use proptest::prelude::*;
use robowire::omnitiles::{device_decoder, Command, Error, FirmwareEvent, FirmwareParser, Motor};
use robowire::stream::Rejected;

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// Feed `bytes` in `chunk`-byte pieces (0: whole), then finish.
fn parse(bytes: &[u8], chunk: usize) -> (Vec<FirmwareEvent>, FirmwareParser) {
    let mut parser = FirmwareParser::new();
    let mut events = Vec::new();
    for piece in bytes.chunks(if chunk == 0 {
        bytes.len().max(1)
    } else {
        chunk
    }) {
        events.extend(parser.feed(piece));
        let s = parser.stats();
        assert_eq!(
            s.bytes,
            s.frame_bytes + s.skipped + parser.buffered() as u64,
            "counters add up"
        );
    }
    events.extend(parser.finish().map(Err));
    (events, parser)
}

fn executed(events: &[FirmwareEvent]) -> Vec<(u64, usize, Command)> {
    events
        .iter()
        .filter_map(|e| e.as_ref().ok())
        .map(|f| (f.offset, f.len, f.message))
        .collect()
}

#[test]
fn the_tile_drops_a_command_after_a5_a5_that_the_decoder_finds() {
    // From 5,000 real nRF buffers: `76 a5` then `a5 31 e7 18`.
    let input = hex("76 a5 a5 31 e7 18");
    let retract = Command::Retract {
        motor: Motor::M1,
        speed: 231,
    };
    let mut decoder = device_decoder();
    let mut found: Vec<_> = decoder.feed(&input).collect();
    found.extend(decoder.flush());
    let found: Vec<_> = found
        .into_iter()
        .filter_map(Result::ok)
        .map(|f| (f.offset, f.len, f.message))
        .collect();
    assert_eq!(found, [(2, 4, retract)]);

    for chunk in [0, 1, 2, 3] {
        let (events, parser) = parse(&input, chunk);
        assert_eq!(
            events,
            [Err(Rejected {
                offset: 1,
                error: Error::UnknownId { id: 0xa5 }
            })],
            "chunk {chunk}"
        );
        let s = parser.stats();
        assert_eq!((s.frames, s.skipped, s.other_rejections), (0, 6, 1));
    }
}

#[test]
fn the_firmware_rules_one_by_one() {
    // Payload bytes are taken blindly: the a5 inside is no start.
    let (events, _) = parse(&hex("a5 70 a5 00 00 15 a5 50 50"), 0);
    assert_eq!(
        executed(&events),
        [
            (
                0,
                6,
                Command::BaseVelocity {
                    vx: -91,
                    vy: 0,
                    omega: 0
                }
            ),
            (6, 3, Command::Ping)
        ]
    );
    // No rescan after a failed checksum: `a5 30 a5` fails and the tile
    // goes on after it, so the ping hidden at 2 is never seen.
    let (events, _) = parse(&hex("a5 30 a5 50 50 11"), 0);
    assert_eq!(
        events,
        [Err(Rejected {
            offset: 0,
            error: Error::Checksum {
                expected: 0xd5,
                found: 0x50
            }
        })]
    );
    // The device decoder rescans and finds it.
    let mut decoder = device_decoder();
    let found: Vec<_> = decoder.feed(&hex("a5 30 a5 50 50 11")).collect();
    assert!(found
        .iter()
        .any(|e| matches!(e, Ok(f) if f.message == Command::Ping)));
    // An unknown id (not a5) is consumed, and the byte after it is read in
    // WaitStart: here a start byte.
    let (events, _) = parse(&hex("a5 61 a5 50 50"), 0);
    assert_eq!(executed(&events), [(2, 3, Command::Ping)]);
    // Telemetry's id is no command to the tile.
    let (events, _) = parse(&hex("a5 60 d0 07 e8 03 22"), 0);
    assert_eq!(
        events,
        [Err(Rejected {
            offset: 0,
            error: Error::UnknownId { id: 0x60 }
        })]
    );
    // A candidate cut by the end of input.
    let (events, parser) = parse(&hex("00 a5 70 01"), 1);
    assert_eq!(
        events,
        [Err(Rejected {
            offset: 1,
            error: Error::Truncated { len: 3 }
        })]
    );
    assert_eq!(parser.buffered(), 0);
    // The nRF's brake buffer: both brakes, the padding skipped.
    let mut brake = hex("a5 32 32 a5 42 42");
    brake.resize(128, 0);
    let (events, parser) = parse(&brake, 0);
    assert_eq!(
        executed(&events),
        [
            (0, 3, Command::Brake { motor: Motor::M1 }),
            (3, 3, Command::Brake { motor: Motor::M2 })
        ]
    );
    assert_eq!(parser.stats().skipped, 122);
}

#[test]
fn a_clean_command_stream_is_executed_whole() {
    let stream = command_stream(0xF1F1, 3000, Corruption::Clean);
    let (events, parser) = parse(&stream.bytes, 7);
    assert!(events.iter().all(Result::is_ok));
    let sent: Vec<_> = stream
        .sent
        .iter()
        .map(|s| (s.offset, s.len, s.packet))
        .collect();
    let got: Vec<_> = executed(&events)
        .into_iter()
        .map(|(o, l, c)| (o, l, robowire::omnitiles::Message::Command(c)))
        .collect();
    assert_eq!(got, sent);
    assert_eq!(parser.stats().skipped, 0);
}

#[test]
fn on_noise_the_tile_executes_a_subset_of_what_the_decoder_finds() {
    for (seed, kind) in [
        (0xF1F2, Corruption::Garbage),
        (0xF1F3, Corruption::GarbageEndingInStart),
        (0xF1F4, Corruption::BitFlips),
        (0xF1F5, Corruption::Truncated),
    ] {
        let stream = command_stream(seed, 3000, kind);
        let mut decoder = device_decoder();
        let mut found: Vec<_> = decoder.feed(&stream.bytes).collect();
        found.extend(decoder.flush());
        let found: Vec<_> = found
            .iter()
            .filter_map(|e| e.as_ref().ok())
            .map(|f| (f.offset, f.len, f.message))
            .collect();
        let (events, _) = parse(&stream.bytes, 0);
        let ran = executed(&events);
        assert!(ran.len() <= found.len(), "{}", kind.name());
        // Every command the tile ran is one the decoder found, except
        // where the decoder's resync took a different frame out of noise.
        let extra = ran.iter().filter(|c| !found.contains(c)).count();
        assert!(extra * 100 <= ran.len(), "{}: {extra}", kind.name());
    }
}

// ------------------------------------------------------- reference model

/// Payload length per id, copied from the spec's command table (§3).
fn spec_payload_len(id: u8) -> Option<usize> {
    match id {
        0x30 | 0x31 | 0x33 | 0x40 | 0x41 | 0x43 => Some(1),
        0x32 | 0x42 | 0x50 | 0x71 => Some(0),
        0x70 => Some(3),
        _ => None,
    }
}

/// The tile's parser as the spec states it (§8, item 4): WaitStart →
/// WaitId → WaitPayload → WaitChecksum; no rescan, payload bytes taken
/// blindly, an unknown id (a5 included) back to WaitStart without eating
/// the next byte. Returns (offset, frame bytes) of every executed command.
fn reference(bytes: &[u8]) -> Vec<(u64, Vec<u8>)> {
    #[allow(clippy::enum_variant_names)] // the spec's names for the states
    enum State {
        WaitStart,
        WaitId,
        WaitPayload { need: usize },
        WaitChecksum,
    }
    let mut state = State::WaitStart;
    let mut frame = Vec::new();
    let mut start = 0;
    let mut executed = Vec::new();
    for (i, &byte) in bytes.iter().enumerate() {
        state = match state {
            State::WaitStart if byte == 0xa5 => {
                start = i as u64;
                frame = vec![byte];
                State::WaitId
            }
            State::WaitStart => State::WaitStart,
            State::WaitId => match spec_payload_len(byte) {
                None => State::WaitStart,
                Some(n) => {
                    frame.push(byte);
                    if n == 0 {
                        State::WaitChecksum
                    } else {
                        State::WaitPayload { need: n }
                    }
                }
            },
            State::WaitPayload { need } => {
                frame.push(byte);
                if need == 1 {
                    State::WaitChecksum
                } else {
                    State::WaitPayload { need: need - 1 }
                }
            }
            State::WaitChecksum => {
                let sum = frame[1..].iter().fold(0u8, |s, &b| s.wrapping_add(b));
                if sum == byte {
                    frame.push(byte);
                    executed.push((start, frame.clone()));
                }
                State::WaitStart
            }
        };
    }
    executed
}

/// Bytes where frames, start bytes and command ids are common.
fn wire() -> impl Strategy<Value = Vec<u8>> {
    let piece = prop_oneof![
        3 => Just(vec![0xa5]),
        3 => prop::sample::select(vec![0x30u8, 0x31, 0x32, 0x33, 0x40, 0x41, 0x42, 0x43, 0x50, 0x60, 0x70, 0x71]).prop_map(|id| vec![id]),
        3 => any::<u8>().prop_map(|b| vec![b]),
        1 => Just(vec![0]),
        // A valid command, now and then cut or with a flipped bit.
        4 => (any::<[u8; 3]>(), 0usize..11, 0usize..8, any::<u8>()).prop_map(|(payload, which, cut, flip)| {
            let ids = [0x30u8, 0x31, 0x32, 0x33, 0x40, 0x41, 0x42, 0x43, 0x50, 0x70, 0x71];
            let id = ids[which];
            let n = spec_payload_len(id).unwrap();
            let mut frame = vec![0xa5, id];
            frame.extend_from_slice(&payload[..n]);
            frame.push(frame[1..].iter().fold(0u8, |s, &b| s.wrapping_add(b)));
            if cut < frame.len() && flip < 40 {
                frame.truncate(cut.max(1));
            } else if flip < 60 {
                let at = usize::from(flip) % frame.len();
                frame[at] ^= 1 << (flip % 8);
            }
            frame
        }),
    ];
    prop::collection::vec(piece, 0..120).prop_map(|pieces| pieces.concat())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(if cfg!(miri) { 4 } else { 512 }))]

    #[test]
    fn matches_the_reference_model_at_any_chunking(bytes in wire(), chunk in 0usize..9) {
        let expected = reference(&bytes);
        let (events, parser) = parse(&bytes, chunk);
        let got: Vec<(u64, Vec<u8>)> = events
            .iter()
            .filter_map(|e| e.as_ref().ok())
            .map(|f| (f.offset, bytes[f.offset as usize..][..f.len].to_vec()))
            .collect();
        prop_assert_eq!(&got, &expected);
        // Each executed frame is its command.
        for (event, (_, frame)) in events.iter().filter_map(|e| e.as_ref().ok()).zip(&expected) {
            prop_assert_eq!(Ok(event.message), Command::try_from(&frame[..]));
        }
        let s = parser.stats();
        prop_assert_eq!(s.frames as usize, expected.len());
        prop_assert_eq!(s.bytes as usize, bytes.len());
        prop_assert_eq!(s.bytes, s.frame_bytes + s.skipped);
        // Byte at a time through `push` gives the same events.
        let mut one = FirmwareParser::new();
        let mut pushed: Vec<FirmwareEvent> = bytes.iter().filter_map(|&b| one.push(b)).collect();
        pushed.extend(one.finish().map(Err));
        prop_assert_eq!(pushed, events);
    }
}
