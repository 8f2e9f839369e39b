//! Structured round trip: arbitrary typed messages → encode → decode → equal,
//! alone (typed parsers and the datagram decoder) and as one stream (whole and
//! chunked). On a clean stream the decoder must give back exactly the
//! messages when nothing can be ambiguous: a single telemetry layout, or no
//! `0xA5` inside any frame.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use robowire::omnitiles::{Both, Host};
use robowire::omnitiles::{
    Command, DatagramDecoder, Framing, Imu, Layout, Layouts, Message, Motor, Side, Telemetry,
    BOTH_BUFFER, NO_READING,
};
use robowire::{Encode, FrameBuf, OwnedFrame, StreamDecoder};
use robowire_fuzz::{decode_chunked, Run};

#[derive(Arbitrary, Debug)]
struct Input {
    commands: bool,
    layouts: u8,
    chunk: u8,
    messages: Vec<Spec>,
}

#[derive(Arbitrary, Debug)]
enum Spec {
    Ping,
    Extend(bool, u8),
    Retract(bool, u8),
    Brake(bool),
    SetPosition(bool, u8),
    BaseVelocity(i8, i8, i8),
    BaseBrake,
    Telemetry {
        layout: u8,
        readings: [u16; 7],
        imu: [u32; 6],
        adcs: [u16; 6],
    },
}

fn motor(m2: bool) -> Motor {
    if m2 {
        Motor::M2
    } else {
        Motor::M1
    }
}

fn reading(v: u16) -> Option<u16> {
    Some(v).filter(|&v| v != NO_READING)
}

/// The typed message, or `None` for telemetry when no layout is enabled.
fn build(message: &Spec, layouts: &[Layout]) -> Option<Message> {
    Some(match *message {
        Spec::Ping => Command::Ping.into(),
        Spec::Extend(m, speed) => Command::Extend {
            motor: motor(m),
            speed,
        }
        .into(),
        Spec::Retract(m, speed) => Command::Retract {
            motor: motor(m),
            speed,
        }
        .into(),
        Spec::Brake(m) => Command::Brake { motor: motor(m) }.into(),
        Spec::SetPosition(m, position) => Command::SetPosition {
            motor: motor(m),
            position,
        }
        .into(),
        Spec::BaseVelocity(vx, vy, omega) => Command::BaseVelocity { vx, vy, omega }.into(),
        Spec::BaseBrake => Command::BaseBrake.into(),
        Spec::Telemetry {
            layout,
            readings: r,
            imu,
            adcs: a,
        } => {
            if layouts.is_empty() {
                return None;
            }
            let layout = layouts[usize::from(layout) % layouts.len()];
            let mut t = Telemetry::empty(layout);
            t.m1_pos = reading(r[0]);
            t.m2_pos = reading(r[1]);
            if layout.has_uwb() {
                t.uwb = Some([reading(r[2]), reading(r[3]), reading(r[4]), reading(r[5])]);
            }
            if layout.has_tof() {
                t.tof = Some(reading(r[6]));
            }
            if layout.has_imu_and_adcs() {
                t.imu = Some(Imu::from_array(imu.map(f32::from_bits)));
                t.m1_adcs = Some([a[0], a[1], a[2], a[3]]);
                t.m2_adcs = Some([a[4], a[5]]);
            }
            t.into()
        }
    })
}

fuzz_target!(|input: Input| {
    let enabled: Layouts = Layout::ALL
        .into_iter()
        .enumerate()
        .filter(|(i, _)| input.layouts >> i & 1 == 1)
        .map(|(_, l)| l)
        .collect();
    let commands = input.commands || enabled.is_empty();
    let kinds: Vec<Layout> = enabled.iter().collect();
    let messages: Vec<Message> = input
        .messages
        .iter()
        .filter_map(|m| build(m, &kinds))
        .filter(|p| commands || matches!(p, Message::Telemetry(_)))
        .collect();
    // Commands and no layout is as the device's side; with `Both` it is
    // the same framing.
    if commands {
        run(
            Framing::<Both>::new().with_layouts(enabled),
            &input,
            &messages,
        );
    } else {
        run(
            Framing::<Host>::new().with_layouts(enabled),
            &input,
            &messages,
        );
    }
});

/// Events with the message of either direction.
fn widen<S: Side>(
    run: Run<S::Message, robowire::omnitiles::Error>,
) -> Run<Message, robowire::omnitiles::Error> {
    Run {
        events: run
            .events
            .into_iter()
            .map(|e| {
                e.map(|f| OwnedFrame {
                    offset: f.offset,
                    len: f.len,
                    message: f.message.into(),
                })
            })
            .collect(),
        stats: run.stats,
    }
}

fn run<S: Side>(framing: Framing<S>, input: &Input, messages: &[Message]) {
    let enabled = framing.layouts();

    let mut stream = Vec::new();
    let mut want = Vec::new();
    let mut interior_start = false;
    for message in messages {
        let frame =
            FrameBuf::<{ Message::MAX_LEN }>::encode(message).expect("valid messages encode");
        assert_eq!(frame.len(), message.encoded_len());
        // Alone: the typed parsers and the datagram decoder give it back.
        assert_eq!(Message::try_from(&frame[..]), Ok(*message));
        match message {
            Message::Telemetry(t) => assert_eq!(Telemetry::try_from(&frame[..]), Ok(*t)),
            Message::Command(c) => assert_eq!(Command::try_from(&frame[..]), Ok(*c)),
        }
        let mut datagrams = DatagramDecoder::new(framing);
        let alone: Vec<_> = datagrams
            .decode(&frame)
            .map(|e| {
                e.map(|f| OwnedFrame {
                    offset: f.offset,
                    len: f.len,
                    message: f.message.into(),
                })
            })
            .collect();
        let one = OwnedFrame {
            offset: 0,
            len: frame.len(),
            message: *message,
        };
        assert_eq!(alone, [Ok(one)], "{message:?} as a datagram");

        interior_start |= frame[1..].contains(&0xa5);
        want.push(Ok(OwnedFrame {
            offset: stream.len() as u64,
            ..one
        }));
        stream.extend_from_slice(&frame);
    }

    let whole = widen::<S>(decode_chunked(
        StreamDecoder::<_, BOTH_BUFFER>::new(framing),
        &stream,
        &[stream.len().max(1)],
    ));
    let chunked = widen::<S>(decode_chunked(
        StreamDecoder::<_, BOTH_BUFFER>::new(framing),
        &stream,
        &[usize::from(input.chunk).max(1)],
    ));
    assert_eq!(whole, chunked, "chunk {}", input.chunk);
    if enabled.len() <= 1 || !interior_start {
        assert_eq!(whole.events, want, "clean stream gives back every message");
        assert_eq!(whole.stats.skipped, 0);
    }
}
