//! OmniTiles telemetry read in place: a `TelemetryView` reads every field as
//! the owned `Telemetry` does, and a view decoder finds the same frames,
//! rejections and counters as the host decoder, at any chunking.

use proptest::prelude::*;
use robowire::omnitiles::{
    checksum, host_view_decoder, Framing, Host, HostDecoder, HostViewDecoder, Layout, Layouts,
    Telemetry, TelemetryView, TelemetryViews, START,
};

/// A checked telemetry frame of `layout` with any payload, some readings
/// forced to 0xFFFF ("no reading").
fn frame_of(layout: Layout) -> impl Strategy<Value = Vec<u8>> {
    let body = layout.frame_len() - 3;
    (
        prop::collection::vec(any::<u8>(), body),
        prop::collection::vec(any::<bool>(), body / 2),
    )
        .prop_map(move |(mut payload, absent)| {
            for (i, &absent) in absent.iter().enumerate() {
                if absent && i % 3 == 0 {
                    payload[2 * i] = 0xff;
                    payload[2 * i + 1] = 0xff;
                }
            }
            let mut frame = vec![START, 0x60];
            frame.extend_from_slice(&payload);
            frame.push(checksum(&frame[1..]));
            frame
        })
}

fn frame() -> impl Strategy<Value = Vec<u8>> {
    prop::sample::select(Layout::ALL.to_vec()).prop_flat_map(frame_of)
}

/// Telemetry frames with garbage and bit flips between and inside them.
fn stream() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(
        (
            frame(),
            prop::collection::vec(any::<u8>(), 0..4),
            any::<Option<(usize, u8)>>(),
        ),
        0..12,
    )
    .prop_map(|parts| {
        let mut bytes = Vec::new();
        for (mut frame, garbage, flip) in parts {
            if let Some((at, bit)) = flip.filter(|(at, _)| at % 4 == 0) {
                let at = at % frame.len();
                frame[at] ^= 1 << (bit % 8);
            }
            bytes.extend_from_slice(&garbage);
            bytes.extend_from_slice(&frame);
        }
        bytes
    })
}

/// Every event as (offset, owned message or error), fed in `chunk`-byte pieces.
type Events = Vec<(u64, Result<Telemetry, String>)>;

fn host_events(decoder: &mut HostDecoder, input: &[u8], chunk: usize) -> Events {
    let mut events = Vec::new();
    for mut piece in input.chunks(chunk.max(1)) {
        while let Some(event) = decoder.decode(&mut piece) {
            events.push(match event {
                Ok(frame) => (frame.offset, Ok(frame.message)),
                Err(rejected) => (rejected.offset, Err(rejected.error.to_string())),
            });
        }
    }
    while let Some(event) = decoder.finish() {
        events.push(match event {
            Ok(frame) => (frame.offset, Ok(frame.message)),
            Err(rejected) => (rejected.offset, Err(rejected.error.to_string())),
        });
    }
    events
}

fn view_events(decoder: &mut HostViewDecoder, input: &[u8], chunk: usize) -> Events {
    let mut events = Vec::new();
    let mut push = |event: Result<robowire::Frame<'_, TelemetryView<'_>>, _>| {
        events.push(match event {
            Ok(frame) => {
                assert_eq!(frame.message.as_bytes(), frame.raw);
                (frame.offset, Ok(frame.message.to_telemetry()))
            }
            Err(rejected) => {
                let rejected: robowire::Rejected<robowire::omnitiles::Error> = rejected;
                (rejected.offset, Err(rejected.error.to_string()))
            }
        })
    };
    for mut piece in input.chunks(chunk.max(1)) {
        while let Some(event) = decoder.decode(&mut piece) {
            push(event);
        }
    }
    while let Some(event) = decoder.finish() {
        push(event);
    }
    events
}

fn layouts() -> impl Strategy<Value = Layouts> {
    prop_oneof![
        Just(Layouts::DOCUMENTED),
        Just(Layouts::ALL),
        Just(Layouts::only(Layout::Ble53)),
        Just(Layouts::only(Layout::Pos7).with(Layout::Spi45)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(if cfg!(miri) { 8 } else { 512 }))]

    #[test]
    fn a_view_reads_every_field_as_the_owned_struct(frame in frame()) {
        let view = TelemetryView::try_from(&frame[..]).unwrap();
        let owned = Telemetry::try_from(&frame[..]).unwrap();
        prop_assert_eq!(view.layout(), owned.layout);
        prop_assert_eq!(view.m1_pos(), owned.m1_pos);
        prop_assert_eq!(view.m2_pos(), owned.m2_pos);
        prop_assert_eq!(view.uwb(), owned.uwb);
        prop_assert_eq!(view.tof(), owned.tof);
        prop_assert_eq!(view.imu(), owned.imu);
        prop_assert_eq!(view.m1_adcs(), owned.m1_adcs);
        prop_assert_eq!(view.m2_adcs(), owned.m2_adcs);
        prop_assert_eq!(Telemetry::from(view), owned);
        prop_assert_eq!(view.to_string(), owned.to_string());
        prop_assert_eq!(format!("{view:?}"), format!("{owned:?}"));
    }

    #[test]
    fn a_whole_frame_is_refused_as_the_owned_struct_refuses_it(
        mut frame in frame(),
        cut in any::<prop::sample::Index>(),
        flip in any::<Option<(prop::sample::Index, u8)>>(),
    ) {
        if let Some((at, bit)) = flip {
            let at = at.index(frame.len());
            frame[at] ^= 1 << (bit % 8);
        }
        let frame = &frame[..cut.index(frame.len() + 1)];
        prop_assert_eq!(
            TelemetryView::try_from(frame).map(Telemetry::from),
            Telemetry::try_from(frame)
        );
    }

    #[test]
    fn a_view_decoder_finds_what_the_host_decoder_finds(
        input in stream(),
        layouts in layouts(),
        chunk in 1usize..80,
    ) {
        let framing = Framing::<Host>::new().with_layouts(layouts);
        let mut host = HostDecoder::new(framing);
        let mut views = HostViewDecoder::new(framing.views());
        let expected = host_events(&mut host, &input, usize::MAX);
        prop_assert_eq!(view_events(&mut views, &input, chunk), expected);
        prop_assert_eq!(views.stats(), host.stats());
    }
}

#[test]
fn the_owned_iterators_yield_telemetry() {
    let frame = [0xa5, 0x60, 0xd0, 0x07, 0xff, 0xff, 0x35];
    let mut decoder = host_view_decoder();
    let mut owned: Vec<_> = decoder.feed(&frame).collect();
    owned.extend(decoder.flush());
    assert_eq!(owned.len(), 1);
    let frame = owned[0].as_ref().unwrap();
    assert_eq!((frame.offset, frame.len), (0, 7));
    assert_eq!(frame.message.m1_pos, Some(2000));
    assert_eq!(TelemetryViews::new().framing(), Framing::<Host>::new());
}
