//! The tokio-util codec, end to end over `tokio::io::duplex`.
#![cfg(feature = "tokio-util-07")]

mod io_common;

use std::io;

use bytes::BytesMut;
use futures_util::{SinkExt, StreamExt};
use io_common::{
    encoded, engine_events, frame, noisy_commands, noisy_telemetry, packets, telemetry, Ev, Rng,
};
use robowire::io::tokio::{
    Events, FrameCodec, OmniTilesCodec, OmniTilesDeviceCodec, OmniTilesHostCodec,
};
use robowire::omnitiles::{
    Both, Command, Error, Framing, Host, HostDecoder, Layout, Layouts, Message, Motor, Side,
    Telemetry,
};
use robowire::Rejected;
use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream};
use tokio_util::codec::{Decoder as _, Framed, FramedRead, FramedWrite};

const BLE53: Framing<Host> = Framing::new().with_layouts(Layouts::only(Layout::Ble53));

/// The read end of a pipe that a task fills with `bytes`, `chunk` bytes per
/// write, then closes.
fn pipe(bytes: Vec<u8>, chunk: usize, capacity: usize) -> DuplexStream {
    let (mut tx, rx) = tokio::io::duplex(capacity);
    tokio::spawn(async move {
        for piece in bytes.chunks(chunk) {
            tx.write_all(piece).await.unwrap();
            tokio::task::yield_now().await;
        }
    });
    rx
}

async fn read_events<S: Side>(
    framing: Framing<S>,
    bytes: Vec<u8>,
    chunk: usize,
    capacity: usize,
) -> Vec<Ev<S>> {
    let codec = FrameCodec::<_, 128, _>::new(framing).events();
    FramedRead::new(pipe(bytes, chunk, capacity), codec)
        .map(|item| item.expect("the codec never fails"))
        .collect()
        .await
}

#[tokio::test]
async fn events_match_the_engine_at_any_chunking() {
    let mut rng = Rng::new(7);
    let (telemetry, sent) = noisy_telemetry(&mut rng, 60);
    let (commands, _) = noisy_commands(&mut rng, 60);
    let mixed: Vec<u8> = telemetry.iter().chain(&commands).copied().collect();
    async fn check<S: Side>(framing: Framing<S>, input: &[u8]) {
        let expected = engine_events(framing, input);
        assert!(expected.iter().any(|e| e.is_err()), "the input has noise");
        for (chunk, capacity) in [(1, 1), (3, 8), (7, 64), (53, 16), (64, 64), (4096, 4096)] {
            let events = read_events(framing, input.to_vec(), chunk, capacity).await;
            assert_eq!(events, expected, "chunk {chunk}, pipe capacity {capacity}");
        }
    }
    check(BLE53, &telemetry).await;
    check(Framing::<Both>::new(), &mixed).await;
    // With the layout named, every intact frame comes through the noise.
    assert_eq!(packets(&engine_events(BLE53, &telemetry)), sent);
}

#[tokio::test]
async fn messages_skip_rejections_and_count_them() {
    let (input, sent) = noisy_telemetry(&mut Rng::new(11), 80);
    let mut oracle = HostDecoder::new(BLE53);
    let oracle_events: Vec<Ev<Host>> = oracle.feed(&input).collect();
    oracle.flush().for_each(drop);
    let last_oracle_rejection = oracle_events.iter().rev().find_map(|e| e.err());

    let mut reader = FramedRead::new(pipe(input, 5, 32), OmniTilesHostCodec::new(BLE53));
    let mut received = Vec::new();
    while let Some(item) = reader.next().await {
        received.push(item.unwrap().message);
    }
    assert_eq!(received, sent);
    let stats = reader.decoder().stats();
    assert_eq!(stats, oracle.stats());
    assert!(stats.checksum_failures > 0 && stats.skipped > 0);
    assert_eq!(reader.decoder().last_rejected(), last_oracle_rejection);
}

#[tokio::test]
async fn end_of_input_confirms_a_short_frame_and_rejects_a_truncated_tail() {
    // Any documented layout: a 7-byte frame is confirmed only by the next
    // header or by the end of the input.
    let pos7 = Message::Telemetry(Telemetry {
        m1_pos: Some(2000),
        m2_pos: Some(1000),
        ..Telemetry::empty(Layout::Pos7)
    });
    let ping = Message::Command(Command::Ping);
    let mut input = frame(&ping);
    input.extend(frame(&pos7));

    let mut codec = OmniTilesCodec::default();
    let mut buf = BytesMut::from(&input[..]);
    assert_eq!(codec.decode(&mut buf).unwrap().unwrap().message, ping);
    assert!(
        codec.decode(&mut buf).unwrap().is_none(),
        "not confirmed yet"
    );
    assert!(buf.is_empty(), "the codec takes every byte it sees");
    assert_eq!(codec.decode_eof(&mut buf).unwrap().unwrap().message, pos7);
    assert!(codec.decode_eof(&mut buf).unwrap().is_none());

    // A truncated frame (its header confirms the 7-byte frame) and garbage
    // at the end: rejections, not errors.
    input.extend([0xa5, 0x60, 0x01, 0x02]);
    let events = read_events(Framing::<Both>::new(), input.clone(), 4, 8).await;
    assert_eq!(packets(&events), [ping, pos7]);
    let offset = input.len() as u64 - 4;
    assert_eq!(
        events.last().unwrap(),
        &Err(Rejected {
            offset,
            error: Error::Truncated { len: 4 }
        })
    );
    assert_eq!(events, engine_events(Framing::<Both>::new(), &input));

    let mut reader = FramedRead::new(pipe(input, 4, 8), OmniTilesCodec::default());
    let mut received = Vec::new();
    while let Some(item) = reader.next().await {
        received.push(item.expect("trailing garbage is no error").message);
    }
    assert_eq!(received, [ping, pos7]);
    assert_eq!(reader.decoder().decoder().buffered(), 0);
}

#[tokio::test]
async fn after_the_end_a_codec_takes_a_new_stream() {
    let mut codec = OmniTilesDeviceCodec::default().events();
    let mut buf = BytesMut::from(&[0xa5, 0x30, 0xc8][..]); // cut short
    assert!(codec.decode(&mut buf).unwrap().is_none());
    let rejected = codec.decode_eof(&mut buf).unwrap().unwrap();
    assert_eq!(rejected.unwrap_err().error, Error::Truncated { len: 3 });
    assert!(codec.decode_eof(&mut buf).unwrap().is_none());
    buf.extend_from_slice(&[0xa5, 0x50, 0x50]);
    let frame = codec.decode(&mut buf).unwrap().unwrap().unwrap();
    assert_eq!((frame.offset, frame.message), (3, Command::Ping));
}

#[tokio::test]
async fn encoder_writes_frames_and_refuses_what_it_cannot_encode() {
    let (host, mut tile) = tokio::io::duplex(4096);
    let mut writer = FramedWrite::new(host, OmniTilesCodec::default());
    let commands = io_common::commands();
    for &c in &commands {
        writer.send(c).await.unwrap();
    }
    // 0xFFFF would read back as "no reading": refused, nothing written.
    let bad = Telemetry {
        m1_pos: Some(0xffff),
        ..Telemetry::empty(Layout::Pos7)
    };
    let err = writer.send(bad).await.unwrap_err();
    assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
    let good = telemetry(5);
    writer.send(Message::Telemetry(good)).await.unwrap();
    drop(writer);

    let mut wire = Vec::new();
    tile.read_to_end(&mut wire).await.unwrap();
    let mut expected = encoded(&commands);
    expected.extend(encoded(&[good]));
    assert_eq!(wire, expected);
}

#[tokio::test]
async fn host_and_tile_over_framed() {
    let (host_io, tile_io) = tokio::io::duplex(64);
    let tile = tokio::spawn(async move {
        // A tile answers every command with a telemetry frame.
        let mut link = Framed::new(tile_io, OmniTilesDeviceCodec::default());
        let mut m1 = 0u16;
        while let Some(frame) = link.next().await {
            if let Command::Extend { speed, .. } = frame.unwrap().message {
                m1 += u16::from(speed);
            }
            let reply = Telemetry {
                m1_pos: Some(m1),
                ..Telemetry::empty(Layout::Ble53)
            };
            link.send(reply).await.unwrap();
        }
        link.codec().stats().frames
    });

    let codec: FrameCodec<Framing<Host>, 64, Events> = FrameCodec::new(BLE53).events();
    let mut link = Framed::new(host_io, codec);
    for speed in [10, 20, 30] {
        let extend = Command::Extend {
            motor: Motor::M1,
            speed,
        };
        link.send(extend).await.unwrap();
        let reply = link.next().await.unwrap().unwrap().unwrap();
        let t = reply.message;
        assert_eq!(reply.len, 53);
        assert_eq!(t.m1_pos, Some([10, 30, 60][usize::from(speed / 10 - 1)]));
    }
    drop(link);
    assert_eq!(tile.await.unwrap(), 3);
}
