//! Seeded corruption: what the OmniTiles decoder loses and what it invents,
//! against the ground truth of generated streams.

#[path = "support/corruption.rs"]
mod corruption;

use corruption::{command_stream, decode, score, telemetry_stream, Corruption};
use robowire::omnitiles::{Framing, Layout, Layouts};

/// Enough frames for a few dozen corrupted ones at 1 % (a few under Miri,
/// an interpreter, where the byte-at-a-time chunking is left out too).
const FRAMES: usize = if cfg!(miri) { 200 } else { 3000 };
const CHUNKS: &[usize] = if cfg!(miri) {
    &[7, 244, 0]
} else {
    &[1, 7, 244, 0]
};

fn ble53_only() -> Framing {
    Framing::telemetry(Layouts::only(Layout::Ble53))
}

#[test]
fn single_layout_bit_flips_lose_no_uncorrupted_frame() {
    let stream = telemetry_stream(0xF11B5, FRAMES, &[Layout::Ble53], Corruption::BitFlips);
    assert!(
        stream.sent.iter().any(|s| !s.intact),
        "some frames corrupted"
    );
    for &chunk in CHUNKS {
        let s = score(&stream, &decode(ble53_only(), &stream.bytes, chunk));
        assert_eq!((s.lost, s.false_frames), (0, 0), "chunk {chunk}: {s:?}");
        assert_eq!(s.intact, s.ideal);
        assert!(s.ideal < s.sent);
    }
}

#[test]
fn single_layout_garbage_runs_lose_no_uncorrupted_frame() {
    let stream = telemetry_stream(0x6A2BA6E, FRAMES, &[Layout::Ble53], Corruption::Garbage);
    assert!(stream.bytes.len() > FRAMES * 53, "garbage was inserted");
    for &chunk in CHUNKS {
        let s = score(&stream, &decode(ble53_only(), &stream.bytes, chunk));
        assert_eq!((s.lost, s.false_frames), (0, 0), "chunk {chunk}: {s:?}");
        assert_eq!(s.intact, FRAMES);
    }
}

#[test]
fn single_layout_truncated_frames_lose_a_frame_only_to_a_false_one() {
    // A cut frame's window runs into the next frame; its 8-bit sum then
    // validates about once in 256, and that false frame swallows the start of
    // the next one. Nothing else is lost, at any chunking.
    let stream = telemetry_stream(0x7A0C, FRAMES, &[Layout::Ble53], Corruption::Truncated);
    let cut = stream.sent.iter().filter(|s| !s.intact).count();
    assert!(cut > FRAMES / 40, "{cut} frames cut");
    let whole = score(&stream, &decode(ble53_only(), &stream.bytes, 0));
    assert!(whole.lost <= whole.false_frames, "{whole:?}");
    assert!(whole.false_frames * 64 <= cut, "{whole:?}");
    for &chunk in CHUNKS {
        let s = score(&stream, &decode(ble53_only(), &stream.bytes, chunk));
        assert_eq!(s, whole, "chunk {chunk}");
    }
}

#[test]
fn garbage_ending_in_start_byte_before_commands_loses_nothing() {
    let stream = command_stream(0xA5A5, FRAMES, Corruption::GarbageEndingInStart);
    assert!(stream.bytes.len() > stream.sent.iter().map(|s| s.len).sum::<usize>());
    for &chunk in CHUNKS {
        let s = score(&stream, &decode(Framing::commands(), &stream.bytes, chunk));
        assert_eq!(s.lost, 0, "chunk {chunk}: {s:?}");
        assert_eq!(s.intact, FRAMES);
    }
}

#[test]
fn clean_streams_decode_exactly() {
    let documented = [Layout::Pos7, Layout::Uwb15, Layout::UwbTof17, Layout::Ble53];
    let telemetry = telemetry_stream(0xC1EA, FRAMES, &[Layout::Ble53], Corruption::Clean);
    let commands = command_stream(0xC1EB, FRAMES, Corruption::Clean);
    let mixed = telemetry_stream(0xC1EC, FRAMES, &documented, Corruption::Clean);
    for (stream, framing) in [
        (&telemetry, ble53_only()),
        (&commands, Framing::commands()),
        (&mixed, Framing::ANY),
    ] {
        for &chunk in CHUNKS {
            let s = score(stream, &decode(framing, &stream.bytes, chunk));
            assert_eq!(
                (s.intact, s.lost, s.false_frames),
                (FRAMES, 0, 0),
                "chunk {chunk}"
            );
        }
    }
}
