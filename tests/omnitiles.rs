//! OmniTiles: golden vectors, resync, chunking invariance, layouts, datagrams.

#[path = "support/omnitiles_sides.rs"]
mod sides;

use robowire::omnitiles::{
    units, BothDatagramDecoder, Command, Error, Framing, HostDatagramDecoder, Imu, Layout, Layouts,
    Message, Motor, Telemetry,
};
use robowire::{Encode, FrameBuf, OwnedFrame, Rejected};
use sides::{any, commands, telemetry, AnyDecoder, AnyFraming, Ev};

fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// Decode `input` fed in chunks of `chunk` bytes, then finish.
fn decode_chunked(framing: AnyFraming, input: &[u8], chunk: usize) -> Vec<Ev> {
    let mut decoder = AnyDecoder::new(framing);
    let mut events = Vec::new();
    for piece in input.chunks(chunk.max(1)) {
        events.extend(decoder.feed(piece));
    }
    events.extend(decoder.flush());
    let s = decoder.stats();
    assert_eq!(s.bytes, input.len() as u64);
    assert_eq!(s.bytes, s.frame_bytes + s.skipped, "counters add up");
    events
}

fn decode(framing: AnyFraming, input: &[u8]) -> Vec<Ev> {
    decode_chunked(framing, input, input.len())
}

fn packets(events: &[Ev]) -> Vec<Message> {
    events
        .iter()
        .filter_map(|e| e.as_ref().ok().map(|f| f.message))
        .collect()
}

fn cmd(c: Command) -> Message {
    Message::Command(c)
}

const M1: Motor = Motor::M1;
const M2: Motor = Motor::M2;

fn command_vectors() -> Vec<(&'static str, Command)> {
    vec![
        ("a5 50 50", Command::Ping),
        (
            "a5 30 c8 f8",
            Command::Extend {
                motor: M1,
                speed: 200,
            },
        ),
        (
            "a5 30 ff 2f",
            Command::Extend {
                motor: M1,
                speed: 255,
            },
        ),
        (
            "a5 31 ff 30",
            Command::Retract {
                motor: M1,
                speed: 255,
            },
        ),
        (
            "a5 40 c8 08",
            Command::Extend {
                motor: M2,
                speed: 200,
            },
        ),
        (
            "a5 41 c8 09",
            Command::Retract {
                motor: M2,
                speed: 200,
            },
        ),
        (
            "a5 30 00 30",
            Command::Extend {
                motor: M1,
                speed: 0,
            },
        ),
        ("a5 32 32", Command::Brake { motor: M1 }),
        ("a5 42 42", Command::Brake { motor: M2 }),
        (
            "a5 33 80 b3",
            Command::SetPosition {
                motor: M1,
                position: 128,
            },
        ),
        (
            "a5 43 00 43",
            Command::SetPosition {
                motor: M2,
                position: 0,
            },
        ),
        (
            "a5 70 0a fb 14 89",
            Command::BaseVelocity {
                vx: 10,
                vy: -5,
                omega: 20,
            },
        ),
        (
            "a5 70 1e 00 00 8e",
            Command::BaseVelocity {
                vx: 30,
                vy: 0,
                omega: 0,
            },
        ),
        (
            "a5 70 00 e2 00 52",
            Command::BaseVelocity {
                vx: 0,
                vy: -30,
                omega: 0,
            },
        ),
        (
            "a5 70 80 7f 00 6f",
            Command::BaseVelocity {
                vx: -128,
                vy: 127,
                omega: 0,
            },
        ),
        (
            "a5 70 a5 00 00 15",
            Command::BaseVelocity {
                vx: -91,
                vy: 0,
                omega: 0,
            },
        ),
        ("a5 71 71", Command::BaseBrake),
    ]
}

const T7: &str = "a5 60 d0 07 e8 03 22";
const T15: &str = "a5 60 d0 07 e8 03 dc 05 c4 09 ff ff b8 0b 91";
const T17: &str = "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 70";
const T53: &str = "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 cd cc cc 3d cd cc 4c 3e \
                   cd cc 1c 41 0a d7 23 3c 0a d7 a3 bc 8f c2 f5 3c d1 07 d2 07 d3 07 d4 07 \
                   e9 03 ea 03 6c";

fn golden_imu() -> Imu {
    Imu {
        ax: 0.1,
        ay: 0.2,
        az: 9.8,
        gx: 0.01,
        gy: -0.02,
        gz: 0.03,
    }
}

fn telemetry_vectors() -> Vec<(&'static str, Telemetry)> {
    let base = |layout| Telemetry {
        m1_pos: Some(2000),
        m2_pos: Some(1000),
        ..Telemetry::empty(layout)
    };
    let uwb = Some([Some(1500), Some(2500), Some(3500), Some(4500)]);
    vec![
        (T7, base(Layout::Pos7)),
        (
            T15,
            Telemetry {
                uwb: Some([Some(1500), Some(2500), None, Some(3000)]),
                ..base(Layout::Uwb15)
            },
        ),
        (
            T17,
            Telemetry {
                uwb,
                tof: Some(Some(321)),
                ..base(Layout::UwbTof17)
            },
        ),
        (
            T53,
            Telemetry {
                uwb,
                tof: Some(Some(321)),
                imu: Some(golden_imu()),
                m1_adcs: Some([2001, 2002, 2003, 2004]),
                m2_adcs: Some([1001, 1002]),
                ..base(Layout::Ble53)
            },
        ),
    ]
}

#[test]
fn golden_commands_encode_and_decode() {
    for (bytes, command) in command_vectors() {
        let wire = hex(bytes);
        assert_eq!(
            &*FrameBuf::<6>::encode(&command).unwrap(),
            &wire[..],
            "{bytes}"
        );
        assert_eq!(command.encoded_len(), wire.len());
        for framing in [commands(), any()] {
            let events = decode(framing, &wire);
            assert_eq!(
                events,
                [Ok(OwnedFrame {
                    offset: 0,
                    len: wire.len(),
                    message: cmd(command)
                })],
                "{bytes}"
            );
        }
        // A telemetry-only decoder does not accept commands.
        assert_eq!(packets(&decode(telemetry(Layouts::ALL), &wire)), []);
    }
}

#[test]
fn golden_telemetry_encode_and_decode() {
    for (bytes, telemetry) in telemetry_vectors() {
        let wire = hex(bytes);
        assert_eq!(
            &*FrameBuf::<53>::encode(&telemetry).unwrap(),
            &wire[..],
            "{bytes}"
        );
        assert_eq!(Telemetry::try_from(&wire[..]).ok(), Some(telemetry));
        for framing in [any(), sides::telemetry(Layouts::only(telemetry.layout))] {
            assert_eq!(
                packets(&decode(framing, &wire)),
                [Message::Telemetry(telemetry)],
                "{bytes}"
            );
        }
    }
}

#[test]
fn golden_telemetry_units() {
    let t = Telemetry::try_from(&hex(T7)[..]).ok().unwrap();
    assert!((units::adc_to_mm(M1, t.m1_pos.unwrap()) - 73.26).abs() < 0.01);
    assert!((units::adc_to_mm(M2, t.m2_pos.unwrap()) - 24.42).abs() < 0.01);
    assert!((units::position_to_mm(M1, 128) - 75.29).abs() < 0.01);
    assert_eq!(units::position_target_mm(M2, 0), 25.0);
    assert_eq!(units::position_target_mm(M1, 33), 20.0);
    assert_eq!(units::position_target_mm(M1, 34), 20.0);
    assert!(units::position_target_mm(M1, 35) > 20.0);
    assert_eq!(units::position_target_mm(M1, 196), 115.0);
    assert!(units::position_target_mm(M1, 195) < 115.0);
    assert_eq!(units::position_target_mm(M2, 63), 25.0);
    assert!(units::position_target_mm(M2, 64) > 25.0);
    assert_eq!(units::position_target_mm(M2, 217), 85.0);
    assert!(units::position_target_mm(M2, 216) < 85.0);
    assert_eq!(units::speed_to_duty(5), 0);
    assert_eq!(units::speed_to_duty(6), 1);
    assert_eq!(units::speed_to_duty(255), 50);
    assert_eq!(units::duty_to_speed(1.0), 255);
    assert_eq!(units::duty_to_speed(f32::NAN), 0);
    assert!((units::velocity_to_duty(-128) + 1.0079).abs() < 1e-3);
    assert_eq!(units::duty_to_velocity(0.3), 38);
    assert_eq!(units::duty_to_velocity(-2.0), -128);
    for v in 0..=255u8 {
        assert_eq!(units::mm_to_position(M1, units::position_to_mm(M1, v)), v);
        assert_eq!(units::mm_to_position(M2, units::position_to_mm(M2, v)), v);
        assert_eq!(units::duty_to_speed(f32::from(v) / 255.0), v);
    }
    for v in -127..=127i8 {
        assert_eq!(units::duty_to_velocity(units::velocity_to_duty(v)), v);
    }
}

#[test]
fn resync_by_one() {
    let extend = cmd(Command::Extend {
        motor: M1,
        speed: 200,
    });
    let events = decode(any(), &hex("a5 a5 30 c8 f8"));
    assert_eq!(
        events[0],
        Err(Rejected {
            offset: 0,
            error: Error::UnknownId { id: 0xa5 }
        })
    );
    assert_eq!(
        events[1],
        Ok(OwnedFrame {
            offset: 1,
            len: 4,
            message: extend
        })
    );
    assert_eq!(events.len(), 2);

    // The failed candidate a5 30 a5 32 swallowed the start of M1 brake.
    let events = decode(any(), &hex("a5 30 a5 32 32"));
    assert_eq!(
        events,
        [
            Err(Rejected {
                offset: 0,
                error: Error::Checksum {
                    expected: 0xd5,
                    found: 0x32
                }
            }),
            Ok(OwnedFrame {
                offset: 2,
                len: 3,
                message: cmd(Command::Brake { motor: M1 })
            }),
        ]
    );
}

#[test]
fn start_byte_inside_payload_and_checksum_is_data() {
    // Payload byte a5, and a checksum of a5 (0x30 + 0x75).
    let input = hex("a5 70 a5 00 00 15 a5 30 75 a5");
    assert_eq!(
        packets(&decode(any(), &input)),
        [
            cmd(Command::BaseVelocity {
                vx: -91,
                vy: 0,
                omega: 0
            }),
            cmd(Command::Extend {
                motor: M1,
                speed: 0x75
            }),
        ]
    );
}

#[test]
fn garbage_ending_in_start_byte_before_a_command_loses_nothing() {
    for garbage in [
        "a5",
        "00 a5",
        "13 37 a5",
        "a5 a5 a5",
        "a5 33 a5",
        "a5 70 a5 a5",
    ] {
        let mut input = hex(garbage);
        input.extend(hex("a5 32 32 a5 71 71"));
        let got = packets(&decode(commands(), &input));
        assert_eq!(
            got,
            [cmd(Command::Brake { motor: M1 }), cmd(Command::BaseBrake)],
            "{garbage}"
        );
    }
}

/// A multi-frame input with garbage between frames.
fn mixed_stream() -> Vec<u8> {
    let mut input = hex("00 ff a5");
    for (bytes, _) in command_vectors() {
        input.extend(hex(bytes));
        input.extend(hex("a5 13"));
    }
    input.extend(hex(T53));
    input.extend(hex("a5 60 00"));
    input.extend(hex(T53));
    input
}

#[test]
fn every_split_point_gives_the_same_events() {
    let input = mixed_stream();
    for framing in [any(), commands(), telemetry(Layouts::only(Layout::Ble53))] {
        let whole = decode(framing, &input);
        assert!(!packets(&whole).is_empty());
        // Under Miri (an interpreter) every fifth split point: the same code
        // paths at a fraction of the cost.
        let step = if cfg!(miri) { 5 } else { 1 };
        for split in (0..=input.len()).step_by(step) {
            let mut decoder = AnyDecoder::new(framing);
            let mut events: Vec<Ev> = decoder.feed(&input[..split]).collect();
            events.extend(decoder.feed(&input[split..]));
            events.extend(decoder.flush());
            assert_eq!(events, whole, "split at {split}");
        }
        for chunk in [1, 2, 3, 5, 7, 53, 64, 100] {
            assert_eq!(
                decode_chunked(framing, &input, chunk),
                whole,
                "chunk {chunk}"
            );
        }
    }
}

#[test]
fn push_equals_whole_decode() {
    let input = mixed_stream();
    for framing in [any(), commands()] {
        let mut decoder = AnyDecoder::new(framing);
        let mut events = Vec::new();
        for &b in &input {
            if let Some(e) = decoder.push(b) {
                events.push(e);
            }
            while let Some(e) = decoder.poll() {
                events.push(e);
            }
        }
        events.extend(decoder.flush());
        assert_eq!(events, decode(framing, &input));
    }
}

#[test]
fn every_proper_prefix_needs_more() {
    let commands = command_vectors().into_iter().map(|(b, _)| (b, commands()));
    let telemetry = [T7, T15, T17, T53].map(|b| (b, telemetry(Layouts::ALL)));
    for (bytes, framing) in commands.chain(telemetry) {
        let wire = hex(bytes);
        for framing in [any(), framing] {
            for cut in 1..wire.len() {
                let mut decoder = AnyDecoder::new(framing);
                let mut input = &wire[..cut];
                assert!(decoder.decode(&mut input).is_none(), "{bytes} cut at {cut}");
                assert!(input.is_empty(), "prefix fully taken");
                assert_eq!(decoder.buffered(), cut);
                assert_eq!(decoder.stats().frames, 0);
            }
        }
    }
}

#[test]
fn truncated_frame_is_reported_at_finish_and_rescanned() {
    // A truncated extend whose bytes hold a complete brake.
    let input = hex("a5 70 a5 32 32");
    assert_eq!(
        decode(commands(), &input),
        [
            Err(Rejected {
                offset: 0,
                error: Error::Truncated { len: 5 }
            }),
            Ok(OwnedFrame {
                offset: 2,
                len: 3,
                message: cmd(Command::Brake { motor: M1 })
            }),
        ]
    );
}

#[test]
fn zero_copy_fast_path_borrows_the_input() {
    let input = hex("00 a5 32 32 a5 40");
    let mut decoder = robowire::omnitiles::both_decoder();
    let mut rest = &input[..];
    let frame = decoder.decode(&mut rest).unwrap().unwrap();
    assert_eq!(frame.raw.as_ptr(), input[1..].as_ptr(), "decoded in place");
    assert_eq!(frame.offset, 1);
    assert_eq!(rest, &input[4..]);
    assert!(decoder.decode(&mut rest).is_none());
    assert!(rest.is_empty());
    assert_eq!(decoder.buffered(), 2, "only the straddling frame is copied");
}

#[test]
fn checksum_failures_are_counted() {
    let input = hex("a5 30 c8 f7 a5 50 50 a5 99 a5 42 43");
    let events = decode(any(), &input);
    assert_eq!(packets(&events), [cmd(Command::Ping)]);
    let mut decoder = AnyDecoder::new(any());
    decoder.feed(&input).for_each(drop);
    let s = decoder.stats();
    assert_eq!(
        (s.frames, s.checksum_failures, s.other_rejections),
        (1, 2, 1)
    );
    assert_eq!(s.frame_bytes, 3);
    assert_eq!(s.skipped, input.len() as u64 - 3);
}

// --- telemetry layouts ----------------------------------------------------

fn sample(layout: Layout, seed: u16) -> Telemetry {
    let mut t = Telemetry::empty(layout);
    t.m1_pos = Some(seed % 4096);
    t.m2_pos = if seed % 7 == 0 {
        None
    } else {
        Some((seed * 3) % 4096)
    };
    if t.uwb.is_some() {
        t.uwb = Some([
            Some(1000 + seed),
            None,
            Some(seed.wrapping_mul(31)),
            Some(7),
        ]);
        if t.uwb.unwrap()[2] == Some(0xffff) {
            t.uwb = Some([None; 4]);
        }
    }
    if t.tof.is_some() {
        t.tof = Some(Some(seed % 8191));
    }
    if t.imu.is_some() {
        t.imu = Some(Imu {
            ax: f32::from(seed) * 0.01,
            az: 9.81,
            gz: -0.5,
            ..Imu::default()
        });
        t.m1_adcs = Some([seed % 4096, 1, 2, 4095]);
        t.m2_adcs = Some([3, seed % 4000]);
    }
    t
}

fn encode_all(messages: &[Telemetry]) -> Vec<u8> {
    messages
        .iter()
        .flat_map(|m| FrameBuf::<53>::encode(m).unwrap().to_vec())
        .collect()
}

#[test]
fn mixed_layouts_on_a_clean_stream_give_no_false_and_no_lost_frames() {
    for layouts in [
        Layouts::DOCUMENTED,
        Layouts::ALL,
        Layouts::NONE.with(Layout::Pos7).with(Layout::Spi45),
    ] {
        let kinds: Vec<Layout> = layouts.iter().collect();
        let count = if cfg!(miri) { 40 } else { 400 };
        let messages: Vec<Telemetry> = (0..count)
            .map(|i| sample(kinds[(i as usize * 7 + i as usize / 3) % kinds.len()], i))
            .collect();
        let input = encode_all(&messages);
        let want: Vec<Message> = messages.iter().copied().map(Message::Telemetry).collect();
        for chunk in [1, 7, 20, 53, 244, input.len()] {
            let events = decode_chunked(telemetry(layouts), &input, chunk);
            assert!(
                events.iter().all(|e| e.is_ok()),
                "no rejections on a clean stream"
            );
            assert_eq!(packets(&events), want, "chunk {chunk}");
        }
    }
}

#[test]
fn longest_layout_is_emitted_as_soon_as_complete() {
    let frame = hex(T53);
    let mut decoder = AnyDecoder::new(any());
    let events: Vec<Ev> = decoder.feed(&frame).collect();
    assert_eq!(events.len(), 1, "no flush needed");
    // A shorter layout waits for the next header...
    let short = hex(T17);
    let mut decoder = AnyDecoder::new(any());
    assert_eq!(decoder.feed(&short).count(), 0);
    assert_eq!(decoder.feed(&[0xa5]).count(), 0);
    assert_eq!(decoder.feed(&[0x60]).count(), 1, "confirmed by a5 60");
    // ...unless it is the only layout enabled.
    let mut decoder = AnyDecoder::new(telemetry(Layouts::only(Layout::UwbTof17)));
    assert_eq!(decoder.feed(&short).count(), 1);
}

#[test]
fn spi_buffer_with_one_45_byte_frame() {
    let mut t = sample(Layout::Spi45, 42);
    t.tof = Some(None);
    let frame = FrameBuf::<53>::encode(&t).unwrap();
    assert_eq!(frame.len(), 45);
    let mut buffer = [0u8; 128];
    buffer[..45].copy_from_slice(&frame);
    // Datagram: picked by length, padding tolerated.
    let mut datagrams = HostDatagramDecoder::new(Framing::new().with_layouts(Layouts::ALL));
    let events: Vec<_> = datagrams.decode(&buffer).collect();
    assert_eq!(
        events,
        [Ok(OwnedFrame {
            offset: 0,
            len: 45,
            message: t
        })]
    );
    assert_eq!(datagrams.stats().skipped, 83);
    // Stream: with the SPI layout alone.
    let events = decode(telemetry(Layouts::only(Layout::Spi45)), &buffer);
    assert_eq!(packets(&events), [Message::Telemetry(t)]);
}

#[test]
fn spi_padding_trap_does_not_fool_the_datagram_decoder() {
    // Find a 45-byte frame whose sum is 0x00, so a 53-byte window over it and
    // its padding also validates (spec §8.3).
    let t = (0..4096u16)
        .map(|i| sample(Layout::Spi45, i))
        .find(|t| FrameBuf::<53>::encode(t).unwrap()[44] == 0)
        .expect("some sample sums to zero");
    let mut buffer = [0u8; 128];
    buffer[..45].copy_from_slice(&FrameBuf::<53>::encode(&t).unwrap());
    let mut datagrams = HostDatagramDecoder::new(Framing::new().with_layouts(Layouts::ALL));
    let messages: Vec<Telemetry> = datagrams
        .decode(&buffer)
        .map(|e| e.unwrap().message)
        .collect();
    assert_eq!(messages, [t]);
}

#[test]
fn datagrams() {
    let mut brake = [0u8; 128];
    brake[..6].copy_from_slice(&hex("a5 32 32 a5 42 42"));
    let mut d = BothDatagramDecoder::new(Framing::new());
    let events: Vec<Ev> = d.decode(&brake).collect();
    assert_eq!(
        events,
        [
            Ok(OwnedFrame {
                offset: 0,
                len: 3,
                message: cmd(Command::Brake { motor: M1 })
            }),
            Ok(OwnedFrame {
                offset: 3,
                len: 3,
                message: cmd(Command::Brake { motor: M2 })
            }),
        ]
    );
    // Each BLE notification is one frame; offsets continue across datagrams.
    let mut events = Vec::new();
    for (bytes, _) in telemetry_vectors() {
        events.extend(d.decode(&hex(bytes)));
    }
    let offsets: Vec<u64> = events.iter().map(|e| e.as_ref().unwrap().offset).collect();
    assert_eq!(offsets, [128, 135, 150, 167]);
    // A 17-byte datagram is decoded as the 17-byte layout, not as 7 + garbage.
    let t17 = Telemetry::try_from(&hex(T17)[..]).ok().unwrap();
    assert_eq!(
        packets(&d.decode(&hex(T17)).collect::<Vec<_>>()),
        [Message::Telemetry(t17)]
    );
    // A corrupt command is reported; the one after it still comes out.
    let events: Vec<Ev> = d.decode(&hex("a5 30 c8 f7 a5 50 50")).collect();
    assert_eq!(events.len(), 2);
    assert!(matches!(
        events[0],
        Err(Rejected {
            error: Error::Checksum { .. },
            ..
        })
    ));
    assert_eq!(packets(&events), [cmd(Command::Ping)]);
    // A half command at the end of a datagram does not leak into the next one.
    assert!(d.decode(&hex("a5 30")).all(|e| e.is_err()));
    assert_eq!(packets(&d.decode(&hex("c8 f8")).collect::<Vec<_>>()), []);
}

#[test]
fn sentinels_and_absent_fields() {
    let mut t = Telemetry::empty(Layout::Ble53);
    t.m1_pos = None;
    t.m2_pos = Some(0);
    let wire = FrameBuf::<53>::encode(&t).unwrap();
    assert_eq!(&wire[2..6], [0xff, 0xff, 0x00, 0x00]);
    let back = Telemetry::try_from(&wire[..]).ok().unwrap();
    assert_eq!(back.m1_pos, None);
    assert_eq!(back.uwb, Some([None; 4]));
    assert_eq!(back.tof, Some(None));
    assert_eq!(
        Telemetry::try_from(&hex(T7)[..]).ok().unwrap().tof,
        None,
        "not carried"
    );
}

#[test]
fn encoder_errors() {
    let mut small = [0u8; 3];
    assert_eq!(
        Command::Extend {
            motor: M1,
            speed: 1
        }
        .encode(&mut small),
        Err(robowire::EncodeError::BufferTooSmall {
            needed: 4,
            available: 3
        })
    );
    let mut out = [0u8; 53];
    let mut t = Telemetry::empty(Layout::Pos7);
    t.m1_pos = Some(0xffff);
    assert_eq!(
        t.encode(&mut out),
        Err(robowire::EncodeError::OutOfRange { field: "m1_pos" })
    );
    let mut t = Telemetry::empty(Layout::Pos7);
    t.tof = Some(Some(1));
    assert!(matches!(
        t.encode(&mut out),
        Err(robowire::EncodeError::Inconsistent { .. })
    ));
}

#[test]
fn nan_bit_patterns_round_trip() {
    let mut t = sample(Layout::Ble53, 3);
    t.imu = Some(Imu {
        ax: f32::from_bits(0x7fc0_1234),
        gy: f32::from_bits(0xffff_ffff),
        ..Imu::default()
    });
    let wire = FrameBuf::<53>::encode(&t).unwrap();
    let back = Telemetry::try_from(&wire[..]).ok().unwrap();
    assert_eq!(back, t);
    assert_eq!(back.imu.unwrap().ax.to_bits(), 0x7fc0_1234);
    assert_eq!(&*FrameBuf::<53>::encode(&back).unwrap(), &*wire);
}

#[test]
fn garbage_that_sums_right_does_not_swallow_a_real_frame() {
    let brake = cmd(Command::Brake { motor: M1 });
    let extend = cmd(Command::Extend {
        motor: M2,
        speed: 200,
    });
    // `a5 70 eb a5 32 32` is a valid base-velocity frame made of garbage and
    // the real brake that follows it; both end at the same byte.
    let input = hex("13 a5 70 eb a5 32 32 a5 71 71");
    for chunk in 1..=input.len() {
        let events = decode_chunked(commands(), &input, chunk);
        assert_eq!(
            events,
            [
                Err(Rejected {
                    offset: 1,
                    error: Error::Superseded { len: 6 }
                }),
                Ok(OwnedFrame {
                    offset: 4,
                    len: 3,
                    message: brake
                }),
                Ok(OwnedFrame {
                    offset: 7,
                    len: 3,
                    message: cmd(Command::BaseBrake)
                }),
            ],
            "chunk {chunk}"
        );
    }
    // `a5 70 00 2b a5 40` sums right and ends inside the real M2 extend.
    let input = hex("13 a5 70 00 2b a5 40 c8 08 a5 71 71");
    assert_eq!(
        packets(&decode(commands(), &input)),
        [extend, cmd(Command::BaseBrake)]
    );
    let mut decoder = AnyDecoder::new(commands());
    let rejections = decoder.feed(&input).filter(|e| e.is_err()).count() as u64;
    assert_eq!(decoder.stats().superseded, 1);
    // The superseded candidate is one of the other rejections: every
    // rejection event is counted once.
    let s = decoder.stats();
    assert_eq!(s.checksum_failures + s.other_rejections, rejections);
    assert!(s.other_rejections >= 1);
    // Right after a frame the same bytes are trusted: a clean stream is
    // never delayed.
    let input = hex("a5 50 50 a5 70 eb a5 32 32");
    assert_eq!(
        packets(&decode(commands(), &input)),
        [
            cmd(Command::Ping),
            cmd(Command::BaseVelocity {
                vx: -21,
                vy: -91,
                omega: 0x32
            })
        ]
    );
}

#[cfg(feature = "bytes")]
#[test]
fn encode_into_bufmut() {
    let mut buf = bytes::BytesMut::new();
    for (wire, command) in command_vectors() {
        let before = buf.len();
        let n = command.encode_buf(&mut buf).unwrap();
        assert_eq!(&buf[before..], &hex(wire)[..]);
        assert_eq!(n, hex(wire).len());
    }
    let (_, t) = telemetry_vectors().pop().unwrap();
    let mut small = [0u8; 10];
    let mut slice: &mut [u8] = &mut small;
    assert_eq!(
        t.encode_buf(&mut slice),
        Err(robowire::EncodeError::BufferTooSmall {
            needed: 53,
            available: 10
        })
    );
}

#[test]
fn short_frame_followed_by_garbage_is_kept_when_only_its_length_validates() {
    let mut input = hex(T7);
    input.extend([0x11; 60]);
    // 7 is the only enabled length whose sum validates at 0 (was rejected
    // as unconfirmed before).
    let events = decode(any(), &input);
    assert_eq!(
        packets(&events),
        [Message::Telemetry(
            Telemetry::try_from(&hex(T7)[..]).ok().unwrap()
        )]
    );
    // With its layout alone it needs no confirmation either.
    let events = decode(telemetry(Layouts::only(Layout::Pos7)), &input);
    assert_eq!(
        packets(&events),
        [Message::Telemetry(
            Telemetry::try_from(&hex(T7)[..]).ok().unwrap()
        )]
    );
}

// --- the 0.2 vocabulary ---------------------------------------------------

#[test]
fn messages_display_as_one_line_of_json_words() {
    let lines = [
        (Command::Ping, "ping"),
        (
            Command::Extend {
                motor: M1,
                speed: 200,
            },
            "m1_extend speed=200",
        ),
        (
            Command::Retract {
                motor: M2,
                speed: 7,
            },
            "m2_retract speed=7",
        ),
        (Command::Brake { motor: M2 }, "m2_brake"),
        (
            Command::SetPosition {
                motor: M1,
                position: 128,
            },
            "m1_set_position position=128",
        ),
        (
            Command::BaseVelocity {
                vx: 10,
                vy: -5,
                omega: 20,
            },
            "base_velocity vx=10 vy=-5 omega=20",
        ),
        (Command::BaseBrake, "base_brake"),
    ];
    for (command, line) in lines {
        assert_eq!(command.to_string(), line);
        assert_eq!(Message::Command(command).to_string(), line);
        assert_eq!(command.name(), line.split(' ').next().unwrap());
    }
    let t15 = Telemetry::try_from(&hex(T15)[..]).unwrap();
    assert_eq!(
        t15.to_string(),
        "telemetry layout=uwb15 m1_pos=2000 m2_pos=1000 uwb=[1500,2500,null,3000]"
    );
    let t53 = Telemetry::try_from(&hex(T53)[..]).unwrap();
    assert_eq!(
        Message::Telemetry(t53).to_string(),
        "telemetry layout=ble53 m1_pos=2000 m2_pos=1000 uwb=[1500,2500,3500,4500] tof=321 \
         imu={ax=0.1,ay=0.2,az=9.8,gx=0.01,gy=-0.02,gz=0.03} m1_adcs=[2001,2002,2003,2004] \
         m2_adcs=[1001,1002]"
    );
}

#[test]
fn names_parse_and_display_back() {
    use robowire::omnitiles::UnknownName;
    for layout in Layout::ALL {
        assert_eq!(layout.to_string().parse(), Ok(layout));
    }
    for motor in Motor::ALL {
        assert_eq!(motor.to_string().parse(), Ok(motor));
    }
    // Every set of layouts displays as text that parses back to it.
    for bits in 0..32u8 {
        let set: Layouts = Layout::ALL
            .into_iter()
            .enumerate()
            .filter(|(i, _)| bits >> i & 1 == 1)
            .map(|(_, l)| l)
            .collect();
        let text = set.to_string();
        assert_eq!(text.parse(), Ok(set), "{text}");
    }
    assert_eq!("auto".parse(), Ok(Layouts::DOCUMENTED));
    assert_eq!(Layouts::DOCUMENTED.to_string(), "auto");
    assert_eq!(
        "spi45,auto".parse::<Layouts>().unwrap().to_string(),
        "auto,spi45"
    );
    assert_eq!("none".parse(), Ok(Layouts::NONE));
    for bad in ["", "ble52", "auto,", "BLE53", " pos7"] {
        let err: UnknownName = bad.parse::<Layouts>().unwrap_err();
        assert_eq!(err.what(), "layout", "{bad:?}");
    }
    assert_eq!(
        "m3".parse::<Motor>().unwrap_err().to_string(),
        "unknown motor (expected m1 or m2)"
    );
    assert!("Ble53".parse::<Layout>().is_err());
}

#[test]
fn try_from_takes_exactly_one_whole_frame() {
    for (bytes, command) in command_vectors() {
        let wire = hex(bytes);
        assert_eq!(Command::try_from(&wire[..]), Ok(command), "{bytes}");
        assert_eq!(Message::try_from(&wire[..]), Ok(Message::Command(command)));
        // Short, long, corrupted, or the other direction's type: an error.
        let n = wire.len();
        assert_eq!(
            Command::try_from(&wire[..n - 1]),
            Err(Error::Truncated { len: n - 1 })
        );
        let mut long = wire.clone();
        long.push(0);
        assert_eq!(
            Command::try_from(&long[..]),
            Err(Error::BadLength { len: n + 1 })
        );
        let mut bad = wire.clone();
        bad[n - 1] ^= 1;
        assert!(matches!(
            Command::try_from(&bad[..]),
            Err(Error::Checksum { .. })
        ));
        assert_eq!(
            Telemetry::try_from(&wire[..]),
            Err(Error::UnknownId { id: wire[1] })
        );
    }
    for (bytes, telemetry) in telemetry_vectors() {
        let wire = hex(bytes);
        assert_eq!(Telemetry::try_from(&wire[..]), Ok(telemetry), "{bytes}");
        assert_eq!(
            Message::try_from(&wire[..]),
            Ok(Message::Telemetry(telemetry))
        );
        assert_eq!(
            Command::try_from(&wire[..]),
            Err(Error::UnknownId { id: 0x60 })
        );
        let n = wire.len();
        assert_eq!(
            Telemetry::try_from(&wire[..n - 1]),
            Err(Error::BadLength { len: n - 1 })
        );
    }
    assert_eq!(Message::try_from(&[][..]), Err(Error::Truncated { len: 0 }));
    assert_eq!(
        Message::try_from(&[0xa5][..]),
        Err(Error::Truncated { len: 1 })
    );
    assert_eq!(
        Message::try_from(&[0x5a, 0x50, 0x50][..]),
        Err(Error::BadStart { found: 0x5a })
    );
    assert_eq!(
        Message::try_from(&[0xa5, 0x99, 0x99][..]),
        Err(Error::UnknownId { id: 0x99 })
    );
}

#[test]
fn each_side_yields_its_own_messages() {
    use robowire::omnitiles::{both_decoder, device_decoder, host_decoder, Both, Device, Host};
    use robowire::omnitiles::{BothDecoder, DeviceDecoder, HostDecoder};
    // The constructors are const: a decoder can be a static's initial value.
    const DEVICE: DeviceDecoder = device_decoder();
    const HOST: HostDecoder = host_decoder();
    const BOTH: BothDecoder = both_decoder();
    let input = mixed_stream();
    let both = decode(any(), &input);

    let mut host = HOST;
    let mut telemetry: Vec<Telemetry> = host
        .feed(&input)
        .filter_map(|e| e.ok().map(|f| f.message))
        .collect();
    telemetry.extend(host.flush().filter_map(|e| e.ok().map(|f| f.message)));
    let mut device = DEVICE;
    let mut commands: Vec<Command> = device
        .feed(&input)
        .filter_map(|e| e.ok().map(|f| f.message))
        .collect();
    commands.extend(device.flush().filter_map(|e| e.ok().map(|f| f.message)));
    // On a clean mixed stream each side finds exactly its direction's frames.
    let want_telemetry: Vec<Telemetry> = packets(&both)
        .into_iter()
        .filter_map(|m| match m {
            Message::Telemetry(t) => Some(t),
            Message::Command(_) => None,
        })
        .collect();
    let want_commands: Vec<Command> = packets(&both)
        .into_iter()
        .filter_map(|m| match m {
            Message::Command(c) => Some(c),
            Message::Telemetry(_) => None,
        })
        .collect();
    assert!(!want_telemetry.is_empty() && !want_commands.is_empty());
    assert_eq!(telemetry, want_telemetry);
    assert_eq!(commands, want_commands);
    // Each rejects the other direction's id.
    let mut device = DEVICE;
    let rejected = device.feed(&hex(T7)).next().unwrap().unwrap_err();
    assert_eq!(rejected.error, Error::UnknownId { id: 0x60 });
    let mut host = HOST;
    let rejected = host.feed(&hex("a5 50 50")).next().unwrap().unwrap_err();
    assert_eq!(rejected.error, Error::UnknownId { id: 0x50 });
    // The defaults.
    assert_eq!(BOTH.framing().layouts(), Layouts::DOCUMENTED);
    assert_eq!(HOST.framing().layouts(), Layouts::DOCUMENTED);
    assert_eq!(DEVICE.framing().layouts(), Layouts::NONE);
    assert_eq!(Framing::<Both>::default(), Framing::new());
    assert!(Framing::<Device>::new().accepts_commands());
    assert!(!Framing::<Host>::new().accepts_commands());
    assert!(Framing::<Device>::new().accepts_id(0x50));
    assert!(!Framing::<Device>::new().accepts_id(0x60));
}
