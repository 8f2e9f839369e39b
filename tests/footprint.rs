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
