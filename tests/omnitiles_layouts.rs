//! The telemetry length policy with several layouts enabled, against the
//! ground truth: zero-padded SPI buffers beside other layouts, and mixed
//! 7/15/17/53 streams with noise (a candidate is taken when exactly one
//! enabled length validates, and confirmed by the next header only when
//! several do).

#[path = "support/corruption.rs"]
mod corruption;

#[allow(dead_code)]
#[path = "../examples/tile_sim/sim.rs"]
mod sim;

use corruption::{decode, score, spi_stream, telemetry_stream, Corruption, Score, Stream};
use robowire::omnitiles::{
    Both, Error, Framing, Host, HostDecoder, Layout, Layouts, Message, Side, Telemetry,
};
use robowire::stream::Rejected;
use robowire::{FrameBuf, StreamDecoder};

/// Chunkings: byte at a time, odd pieces, a BLE MTU, an SPI buffer, whole.
const CHUNKS: &[usize] = if cfg!(miri) {
    &[7, 0]
} else {
    &[1, 7, 128, 244, 0]
};

const DOCUMENTED: [Layout; 4] = [Layout::Pos7, Layout::Uwb15, Layout::UwbTof17, Layout::Ble53];

fn all_chunkings<S: Side<Message: Into<Message>>>(stream: &Stream, framing: Framing<S>) -> Score {
    let whole = score(stream, &decode(framing, &stream.bytes, 0));
    for &chunk in CHUNKS {
        let s = score(stream, &decode(framing, &stream.bytes, chunk));
        assert_eq!(s, whole, "chunk {chunk} differs from the whole stream");
    }
    whole
}

// ------------------------------------------------------------ SPI buffers

/// Every layout set with `spi45` and at least one other layout.
fn sets_with_spi45() -> Vec<Layouts> {
    let mut sets = Vec::new();
    for bits in 0u8..16 {
        let others = [Layout::Pos7, Layout::Uwb15, Layout::UwbTof17, Layout::Ble53];
        let set = others
            .iter()
            .enumerate()
            .filter(|&(i, _)| bits & (1 << i) != 0)
            .fold(Layouts::only(Layout::Spi45), |set, (_, &l)| set.with(l));
        if set.len() > 1 {
            sets.push(set);
        }
    }
    sets
}

/// The frames of a clean SPI capture decoded with `framing` at `chunk`:
/// (offset, len) and messages.
fn spi_frames<S: Side<Message: Into<Message>>>(
    framing: Framing<S>,
    bytes: &[u8],
    chunk: usize,
) -> Vec<(u64, usize, Message)> {
    decode(framing, bytes, chunk)
        .into_iter()
        .map(|f| (f.offset, f.len, f.message))
        .collect()
}

/// What a clean SPI capture holds: one 45-byte frame per 128-byte buffer.
fn spi_truth(bytes: &[u8]) -> Vec<(u64, usize, Message)> {
    bytes
        .chunks(128)
        .enumerate()
        .map(|(i, buffer)| {
            let t = Telemetry::try_from(&buffer[..45]).expect("an SPI frame");
            ((i * 128) as u64, 45, Message::Telemetry(t))
        })
        .collect()
}

#[test]
fn spi_buffers_decode_exactly_beside_any_other_layout() {
    // The tile simulator's buffers (a 45-byte frame, then 83 zeros).
    let buffers = if cfg!(miri) { 40 } else { 5000 };
    let bytes = sim::spi_buffers(0x5b1_0005, buffers).unwrap();
    let truth = spi_truth(&bytes);
    // Buffers whose 53-byte window (frame and 8 zeros) validates too: the
    // 45-byte sum is 0x00 or 0x80 (spec §8, item 3).
    let padded_53 = bytes
        .chunks(128)
        .filter(|b| b[1..52].iter().fold(0u8, |s, &x| s.wrapping_add(x)) == b[52])
        .count();
    assert!(
        cfg!(miri) || padded_53 > 10,
        "{padded_53} ambiguous buffers"
    );
    for set in sets_with_spi45() {
        for &chunk in CHUNKS {
            let host = spi_frames(Framing::<Host>::new().with_layouts(set), &bytes, chunk);
            assert!(host == truth, "{set} from tile, chunk {chunk}");
            let both = spi_frames(Framing::<Both>::new().with_layouts(set), &bytes, chunk);
            assert!(both == truth, "{set} from any, chunk {chunk}");
        }
    }
}

#[test]
fn the_committed_spi_capture_decodes_exactly_beside_other_layouts() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spi_telemetry.bin");
    let bytes = std::fs::read(path).unwrap();
    let truth = spi_truth(&bytes);
    for set in sets_with_spi45() {
        for &chunk in CHUNKS {
            let both = spi_frames(Framing::<Both>::new().with_layouts(set), &bytes, chunk);
            assert!(both == truth, "{set}, chunk {chunk}");
        }
    }
}

#[test]
fn the_issue_example_spi_buffer_is_a_frame() {
    // `a5 60 d0 07 e8 03 41 01 cd cc cc 3d … ea 03 60` then 83 × `00`:
    // rejected as `unconfirmed` with `auto,spi45` before.
    let frame: Vec<u8> = [
        "a5 60 d0 07 e8 03 41 01 cd cc cc 3d cd cc 4c 3e cd cc 1c 41 0a d7 23",
        "3c 0a d7 a3 bc 8f c2 f5 3c d1 07 d2 07 d3 07 d4 07 e9 03 ea 03 60",
    ]
    .join(" ")
    .split(' ')
    .map(|b| u8::from_str_radix(b, 16).unwrap())
    .collect();
    assert_eq!(frame.len(), 45);
    let mut buffer = frame.clone();
    buffer.resize(128, 0);
    let t = Telemetry::try_from(&frame[..]).unwrap();
    for set in sets_with_spi45() {
        let mut decoder = HostDecoder::new(Framing::new().with_layouts(set));
        let events: Vec<_> = decoder.feed(&buffer).collect();
        assert_eq!(events.len(), 1, "{set}: emitted before the end of input");
        let frame = events[0].as_ref().unwrap();
        assert_eq!((frame.offset, frame.len, frame.message), (0, 45, t));
        assert_eq!(decoder.flush().count(), 0);
    }
}

#[test]
fn spi_buffers_with_garbage_beside_other_layouts() {
    // Robustness on noise is no worse than with the documented layouts
    // alone on documented frames (the figures in docs/robustness.md).
    let frames = if cfg!(miri) { 200 } else { 10_000 };
    let set = Layouts::DOCUMENTED.with(Layout::Spi45);
    for (kind, max_lost, max_false) in [
        (Corruption::Clean, 0, 0),
        (Corruption::Garbage, 0, 2),
        (Corruption::BitFlips, 0, 2),
    ] {
        let stream = spi_stream(0x5B10 + kind as u64, frames, kind);
        let s = all_chunkings(&stream, Framing::<Host>::new().with_layouts(set));
        assert!(
            s.lost <= max_lost && s.false_frames <= max_false,
            "{}: {s:?}",
            kind.name()
        );
    }
}

// ------------------------------------------------- mixed documented layouts

/// The goals per 10,000 mixed 7/15/17/53 frames, at any chunking.
#[test]
#[cfg_attr(miri, ignore = "10,000-frame streams")]
fn mixed_layouts_with_noise_meet_the_goals() {
    for (seed, kind, max_lost, max_false) in [
        (0x6A5B_0001, Corruption::Clean, 0, 0),
        (0x6A5B_0002, Corruption::Garbage, 25, 15),
        (0x6A5B_0003, Corruption::BitFlips, 4, 6),
        (0xD0C2, Corruption::Garbage, 25, 15),
        (0xD0C1, Corruption::BitFlips, 4, 6),
    ] {
        let stream = telemetry_stream(seed, 10_000, &DOCUMENTED, kind);
        let s = all_chunkings(&stream, Framing::<Both>::new());
        assert!(
            s.lost <= max_lost && s.false_frames <= max_false,
            "{} (seed {seed:#x}): {s:?}",
            kind.name()
        );
        let host = all_chunkings(&stream, Framing::<Host>::new());
        assert!(
            host.lost <= max_lost && host.false_frames <= max_false,
            "{} (seed {seed:#x}) from tile: {host:?}",
            kind.name()
        );
    }
}

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

fn sum(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0, |s, &b| s.wrapping_add(b))
}

const T7: &str = "a5 60 d0 07 e8 03 22";

#[test]
fn a_short_frame_followed_by_garbage_is_taken_when_only_its_length_validates() {
    let mut input = hex(T7);
    input.extend([0x11; 60]);
    // Only the 7-byte length validates at 0: 15, 17 and 53 do not.
    for len in [15, 17, 53] {
        assert_ne!(sum(&input[1..len - 1]), input[len - 1], "{len}");
    }
    let t = Telemetry::try_from(&hex(T7)[..]).unwrap();
    for &chunk in CHUNKS {
        let frames = decode(Framing::<Both>::new(), &input, chunk);
        assert_eq!(frames.len(), 1, "chunk {chunk}");
        assert_eq!(
            (frames[0].offset, frames[0].len, frames[0].message),
            (0, 7, Message::Telemetry(t))
        );
    }
    // It is decided once the longest enabled length is available.
    let mut decoder = StreamDecoder::<_, 128>::new(Framing::<Both>::new());
    assert_eq!(decoder.feed(&input[..52]).count(), 0);
    assert_eq!(decoder.feed(&input[52..53]).count(), 1);
    // Or when the input ends.
    let mut decoder = StreamDecoder::<_, 128>::new(Framing::<Both>::new());
    assert_eq!(decoder.feed(&input[..20]).count(), 0);
    let flushed: Vec<_> = decoder.flush().collect();
    assert_eq!(flushed[0].as_ref().map(|f| f.len), Ok(7));
}

#[test]
fn two_lengths_that_validate_need_a_header() {
    // A 7-byte frame, then garbage that makes the 15-byte window validate
    // too: which one it is only the next header can say.
    let mut input = hex(T7);
    input.extend([0x11; 7]);
    input.push(sum(&input[1..14]));
    input.extend([0x22; 50]);
    for len in [17, 53] {
        assert_ne!(sum(&input[1..len - 1]), input[len - 1], "{len}");
    }
    let mut decoder = StreamDecoder::<_, 128>::new(Framing::<Both>::new());
    let events: Vec<_> = decoder.feed(&input).collect();
    assert_eq!(
        events[0],
        Err(Rejected {
            offset: 0,
            error: Error::Unconfirmed
        })
    );
    // Followed by a header, the shorter length is the frame.
    let confirmed = [hex(T7), hex(T7)].concat();
    let frames = decode(Framing::<Both>::new(), &confirmed, 0);
    assert_eq!(
        frames.iter().map(|f| (f.offset, f.len)).collect::<Vec<_>>(),
        [(0, 7), (7, 7)]
    );
}

#[test]
fn a_ble53_frame_after_noise_is_not_cut_short() {
    // A 53-byte frame whose first 7 bytes validate as a 7-byte frame: with
    // the 53-byte length validating too, the longest enabled wins.
    let mut t = Telemetry::empty(Layout::Ble53);
    t.m1_pos = Some(0);
    t.m2_pos = Some(0);
    t.uwb = Some([Some(0x0060), Some(1), Some(2), Some(3)]);
    let frame = FrameBuf::<53>::encode(&t).unwrap();
    assert_eq!(&frame[..7], [0xa5, 0x60, 0, 0, 0, 0, 0x60]);
    let mut input = vec![0x13, 0x37];
    input.extend_from_slice(&frame);
    input.extend([0x42; 10]);
    let frames = decode(Framing::<Both>::new(), &input, 0);
    assert_eq!(
        frames.iter().map(|f| (f.offset, f.len)).collect::<Vec<_>>(),
        [(2, 53)]
    );
}

/// A 53-byte frame whose bytes after the 45th are zeros and whose first 45
/// bytes happen to sum right (found by the `omnitiles_structured` fuzz
/// target): with `spi45` beside `ble53`, the zeros look like an SPI buffer's
/// padding. The 53-byte frame is confirmed by the end of input or the next
/// header, so it wins; a real SPI buffer's 53-byte reading is not confirmed.
#[test]
fn a_53_byte_frame_with_a_zero_tail_is_not_taken_for_padding() {
    use robowire::omnitiles::Imu;
    let telemetry = Telemetry {
        layout: Layout::Ble53,
        m1_pos: None,
        m2_pos: None,
        uwb: Some([None, None, Some(16896), Some(8192)]),
        tof: Some(Some(256)),
        imu: Some(Imu {
            ax: 8.0,
            ay: f32::from_bits(0x0101_0101),
            az: 0.0,
            gx: 0.0,
            gy: 0.0,
            gz: 0.0,
        }),
        m1_adcs: Some([0; 4]),
        m2_adcs: Some([0, 0]),
    };
    let frame = FrameBuf::<53>::encode(&telemetry).unwrap();
    assert_eq!(frame[45..53], [0; 8]);
    assert_eq!(
        sum(&frame[1..44]),
        frame[44],
        "the 45-byte prefix sums right"
    );
    let layouts = Layouts::only(Layout::Spi45).with(Layout::Ble53);
    let framing = Framing::<Host>::new().with_layouts(layouts);
    let mut twice = frame.to_vec();
    twice.extend_from_slice(&frame);
    for bytes in [&frame[..], &twice[..]] {
        for chunk in CHUNKS {
            let got = spi_frames(framing, bytes, *chunk);
            assert!(!got.is_empty());
            for (offset, len, message) in got {
                assert_eq!((offset % 53, len), (0, 53), "chunk {chunk}");
                assert_eq!(message, Message::Telemetry(telemetry));
            }
        }
    }
}

// ------------------------------------------------------------ settle (idle line)

/// Each frame of a mixed stream sent on its own, with a pause after it (a
/// BLE notification, or a write followed by silence): `settle` at each
/// pause hands out every frame at once, where without it each short frame
/// waits for the next frame's first byte.
#[test]
fn settle_at_each_pause_hands_out_every_frame_at_once() {
    for corruption in [Corruption::Clean, Corruption::Garbage] {
        let stream = telemetry_stream(7, 400, &DOCUMENTED, corruption);
        let mut decoder =
            StreamDecoder::<_, { robowire::omnitiles::HOST_BUFFER }>::new(Framing::<Host>::new());
        let mut settled = 0;
        let mut starts = stream.sent.iter().map(|s| s.offset as usize).peekable();
        let mut at = 0;
        while at < stream.bytes.len() {
            starts.next_if(|&s| s <= at);
            let end = starts.peek().copied().unwrap_or(stream.bytes.len());
            let mut out: Vec<u64> = decoder
                .feed(&stream.bytes[at..end])
                .filter_map(Result::ok)
                .map(|f| f.offset)
                .collect();
            let before_settle = out.len();
            while let Some(event) = decoder.settle() {
                if let Ok(frame) = event {
                    out.push(frame.offset);
                }
            }
            settled += out.len() - before_settle;
            let stats = decoder.stats();
            assert_eq!(
                stats.bytes,
                stats.frame_bytes + stats.skipped + decoder.buffered() as u64
            );
            // Every intact frame that ends in this piece has left by now.
            for sent in stream.sent.iter().filter(|s| s.intact) {
                let frame_end = sent.offset as usize + sent.len;
                if frame_end > at && frame_end <= end {
                    assert!(
                        out.contains(&sent.offset),
                        "{}: the frame at {} waited past its pause",
                        corruption.name(),
                        sent.offset
                    );
                }
            }
            at = end;
        }
        // Without `settle` these short frames would have waited.
        assert!(settled > 0, "{}", corruption.name());
    }
}

/// `settle` in the middle of a frame keeps its bytes: the frame completes
/// when the rest arrives, and nothing is rejected.
#[test]
fn settle_inside_a_frame_keeps_it() {
    let stream = telemetry_stream(11, 50, &[Layout::Ble53], Corruption::Clean);
    let mut decoder =
        StreamDecoder::<_, { robowire::omnitiles::HOST_BUFFER }>::new(Framing::<Host>::new());
    let mut frames = 0;
    for sent in &stream.sent {
        let frame = &stream.bytes[sent.offset as usize..][..sent.len];
        // Cut before the shortest layout's length, so that no piece ends a
        // frame: after 3 and 6 bytes.
        for piece in [&frame[..3], &frame[3..6], &frame[6..]] {
            frames += decoder.feed(piece).filter(Result::is_ok).count();
            while let Some(event) = decoder.settle() {
                frames += usize::from(event.is_ok());
            }
        }
    }
    assert_eq!(frames, stream.sent.len());
    let stats = decoder.stats();
    assert_eq!(
        (
            stats.checksum_failures,
            stats.other_rejections,
            stats.skipped
        ),
        (0, 0, 0)
    );
}
