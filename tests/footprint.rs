//! Decoders whose buffer is smaller than a frame (firmware-sized decoders)
//! never panic: they decode what fits, in place or buffered, and skip the rest.

use robowire::omnitiles::{Command, Device, Framing, Host, Layout, Layouts, Motor, Telemetry};
use robowire::{Encode, StreamDecoder};

fn ble53_frame() -> Vec<u8> {
    let mut frame = [0u8; Telemetry::MAX_LEN];
    let n = Telemetry::empty(Layout::Ble53).encode(&mut frame).unwrap();
    frame[..n].to_vec()
}

#[test]
fn push_into_a_decoder_without_a_buffer_skips_the_byte() {
    let mut decoder = StreamDecoder::<_, 0>::new(Framing::<Device>::new());
    for byte in [0xa5, 0x32, 0x32] {
        assert!(decoder.push(byte).is_none());
        assert!(decoder.poll().is_none());
    }
    let stats = decoder.stats();
    assert_eq!((stats.bytes, stats.skipped, stats.frames), (3, 3, 0));
    // In place it still decodes.
    let mut input = &[0xa5, 0x32, 0x32][..];
    let frame = decoder.decode(&mut input).unwrap().unwrap();
    assert_eq!(frame.message, Command::Brake { motor: Motor::M1 });
}

#[test]
fn a_frame_longer_than_the_buffer_after_garbage_decodes_in_place() {
    let framing = Framing::<Host>::new().with_layouts(Layouts::only(Layout::Ble53));
    let mut decoder = StreamDecoder::<_, 16>::new(framing);
    let mut input = vec![0x00];
    input.extend(ble53_frame());
    let mut rest = &input[..];
    let frame = decoder.decode(&mut rest).unwrap().unwrap();
    assert_eq!((frame.offset, frame.len()), (1, 53));
    assert!(decoder.decode(&mut rest).is_none());
}

mod small_buffer {
    use proptest::prelude::*;
    use robowire::omnitiles::{self, Command, Device, Framing, Motor, DEVICE_BUFFER};
    use robowire::stream::{owned_event, OwnedEvent};
    use robowire::{FrameBuf, StreamDecoder};

    type Rules = Framing<Device>;

    fn command() -> impl Strategy<Value = Command> {
        let motor = prop_oneof![Just(Motor::M1), Just(Motor::M2)];
        prop_oneof![
            Just(Command::Ping),
            (motor.clone(), any::<u8>())
                .prop_map(|(motor, speed)| Command::Extend { motor, speed }),
            motor.clone().prop_map(|motor| Command::Brake { motor }),
            (motor, any::<u8>())
                .prop_map(|(motor, position)| Command::SetPosition { motor, position }),
            any::<(i8, i8, i8)>().prop_map(|(vx, vy, omega)| Command::BaseVelocity {
                vx,
                vy,
                omega
            }),
        ]
    }

    /// Commands, garbage rich in start bytes and ids, and corrupted bytes.
    fn stream() -> impl Strategy<Value = Vec<u8>> {
        let piece = prop_oneof![
            4 => command().prop_map(|c| FrameBuf::<6>::encode(&c).unwrap().to_vec()),
            2 => prop::collection::vec(
                prop_oneof![Just(0xa5u8), Just(0x32), Just(0x50), Just(0x70), any::<u8>()],
                1..8
            ),
            1 => (command(), 0usize..6, any::<u8>()).prop_map(|(c, at, x)| {
                let mut frame = FrameBuf::<6>::encode(&c).unwrap().to_vec();
                let at = at % frame.len();
                frame[at] ^= x | 1;
                frame
            }),
            // A false candidate that validates and holds (or reaches into) a
            // real command: a base velocity `a5 70 ..` whose payload byte 2
            // makes the sum come right, with the command starting at byte 3,
            // 4 or 5. Only the resync verification tells them apart.
            2 => (command(), 3usize..6, any::<[u8; 2]>()).prop_map(|(inner, at, free)| {
                let mut bytes = vec![0xa5, 0x70, 0, free[0], free[1]];
                bytes.truncate(at);
                bytes.extend_from_slice(&FrameBuf::<6>::encode(&inner).unwrap());
                bytes[2] = bytes[5]
                    .wrapping_sub(0x70)
                    .wrapping_sub(bytes[3])
                    .wrapping_sub(bytes[4]);
                bytes
            }),
        ];
        prop::collection::vec(piece, 0..40).prop_map(|pieces| pieces.concat())
    }

    fn decode<const N: usize>(
        input: &[u8],
        chunk: usize,
    ) -> (Vec<OwnedEvent<Rules>>, robowire::Stats) {
        let mut decoder = StreamDecoder::<Rules, N>::new(Framing::new());
        let mut events = Vec::new();
        for mut piece in input.chunks(chunk.max(1)) {
            while let Some(event) = decoder.decode(&mut piece) {
                events.push(owned_event::<Rules>(event));
            }
        }
        while let Some(event) = decoder.finish() {
            events.push(owned_event::<Rules>(event));
        }
        (events, decoder.stats())
    }

    fn push(input: &[u8]) -> (Vec<OwnedEvent<Rules>>, robowire::Stats) {
        let mut decoder = omnitiles::device_decoder();
        let mut events = Vec::new();
        for &byte in input {
            if let Some(event) = decoder.push(byte) {
                events.push(owned_event::<Rules>(event));
            }
            while let Some(event) = decoder.poll() {
                events.push(owned_event::<Rules>(event));
            }
        }
        while let Some(event) = decoder.finish() {
            events.push(owned_event::<Rules>(event));
        }
        (events, decoder.stats())
    }

    fn stats_u64<C: robowire::Counter>(stats: robowire::Stats<C>) -> [u64; 8] {
        [
            stats.bytes.to_u64(),
            stats.frames.to_u64(),
            stats.frame_bytes.to_u64(),
            stats.skipped.to_u64(),
            stats.checksum_failures.to_u64(),
            stats.other_rejections.to_u64(),
            stats.malformed.to_u64(),
            stats.superseded.to_u64(),
        ]
    }

    /// Decode with counters of type `C`, byte by byte and in chunks.
    fn decode_counted<C: robowire::Counter>(
        input: &[u8],
        chunk: usize,
    ) -> (Vec<OwnedEvent<Rules>>, [u64; 8], u64) {
        let mut decoder = StreamDecoder::<Rules, DEVICE_BUFFER, C>::new(Framing::new());
        let mut events = Vec::new();
        for mut piece in input.chunks(chunk.max(1)) {
            while let Some(event) = decoder.decode(&mut piece) {
                events.push(owned_event::<Rules>(event));
            }
        }
        while let Some(event) = decoder.finish() {
            events.push(owned_event::<Rules>(event));
        }
        (events, stats_u64(decoder.stats()), decoder.position())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(if cfg!(miri) { 8 } else { 512 }))]

        /// The device decoder's small buffer loses nothing: the same events and
        /// counters as a 128-byte buffer, whole, chunked or byte by byte.
        #[test]
        fn the_device_buffer_decides_as_a_large_one(input in stream(), chunk in 1usize..9) {
            let reference = decode::<128>(&input, usize::MAX);
            prop_assert_eq!(&decode::<DEVICE_BUFFER>(&input, usize::MAX), &reference);
            prop_assert_eq!(&decode::<DEVICE_BUFFER>(&input, chunk), &reference);
            prop_assert_eq!(&push(&input), &reference);
        }

        /// `u32` counters count and place frames as `u64` ones do.
        #[test]
        fn narrow_counters_count_the_same(input in stream(), chunk in 1usize..9) {
            let wide = decode_counted::<u64>(&input, chunk);
            prop_assert_eq!(&decode_counted::<u32>(&input, chunk), &wide);
            prop_assert_eq!(&decode_counted::<u16>(&input, chunk), &wide);
        }
    }
}

#[test]
fn narrow_counters_wrap_around_and_the_offsets_with_them() {
    use robowire::omnitiles::DEVICE_BUFFER;
    let mut decoder = StreamDecoder::<Framing<Device>, DEVICE_BUFFER, u16>::new(Framing::new());
    let garbage = vec![0u8; 65_535];
    let mut input = &garbage[..];
    assert!(decoder.decode(&mut input).is_none());
    assert_eq!(decoder.position(), 65_535);
    let mut input = &[0xa5, 0x50, 0x50][..];
    let frame = decoder.decode(&mut input).unwrap().unwrap();
    assert_eq!((frame.offset, frame.message), (65_535, Command::Ping));
    let stats = decoder.stats();
    assert_eq!((stats.bytes, stats.skipped, stats.frames), (2, 65_535, 1));
    assert_eq!(decoder.position(), 2);
}
