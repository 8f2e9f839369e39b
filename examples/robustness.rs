//! Robustness report: seeded OmniTiles streams with known corruption, decoded
//! at several chunkings and scored against the ground truth.
//!
//! `cargo run --release --example robustness [frames]`
//!
//! For every stream the table gives the frames sent, the frames an ideal
//! decoder accepts (it knows the ground truth: exactly the frames sent whole
//! and unaltered), and what robowire's decoder did: uncorrupted frames given
//! back intact, uncorrupted frames lost, and false frames accepted (frames
//! that were not sent intact at that place). The decoder's results are the
//! same at every chunking (1, 7 and 244-byte chunks and the whole stream);
//! a row per chunking is printed only where they differ. A last table puts
//! the device decoder beside `FirmwareParser` (what a tile executes) on
//! corrupted command streams.

#[path = "../tests/support/corruption.rs"]
mod corruption;

use corruption::{
    command_stream, decode, score, spi_stream, telemetry_stream, Corruption, Score, Stream,
};
use std::collections::BTreeMap;

use robowire::omnitiles::{
    Both, Device, FirmwareParser, Framing, Host, Layout, Layouts, Message, Side,
};

const CHUNKS: [(usize, &str); 4] = [(1, "1"), (7, "7"), (244, "244"), (0, "whole")];

fn main() {
    let frames: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20_000);
    let documented = [Layout::Pos7, Layout::Uwb15, Layout::UwbTof17, Layout::Ble53];
    let telemetry_kinds = [
        Corruption::Clean,
        Corruption::BitFlips,
        Corruption::Garbage,
        Corruption::Truncated,
    ];

    println!("{frames} frames per stream; chunkings 1, 7, 244 bytes and whole.\n");
    println!(
        "| stream | decoder | corruption | sent | ideal: accepted | intact | uncorrupted lost | false accepted | chunkings |"
    );
    println!("|---|---|---|---:|---:|---:|---:|---:|---|");
    for (i, kind) in telemetry_kinds.into_iter().enumerate() {
        let stream = telemetry_stream(0xB1E0 + i as u64, frames, &[Layout::Ble53], kind);
        report(
            "telemetry ble53",
            "`Framing<Host>` with `only(Ble53)`",
            kind,
            &stream,
            Framing::<Host>::new().with_layouts(Layouts::only(Layout::Ble53)),
        );
    }
    for (i, kind) in telemetry_kinds.into_iter().enumerate() {
        let stream = telemetry_stream(0xD0C0 + i as u64, frames, &documented, kind);
        report(
            "telemetry 7/15/17/53 mixed",
            "`Framing<Both>` (default)",
            kind,
            &stream,
            Framing::<Both>::new(),
        );
    }
    for (i, kind) in telemetry_kinds.into_iter().enumerate() {
        let stream = spi_stream(0x5B10 + i as u64, frames, kind);
        report(
            "SPI buffers (spi45 + zero padding)",
            "`Framing<Host>` with `auto,spi45`",
            kind,
            &stream,
            Framing::<Host>::new().with_layouts(Layouts::DOCUMENTED.with(Layout::Spi45)),
        );
    }
    for (i, kind) in [
        Corruption::Clean,
        Corruption::GarbageEndingInStart,
        Corruption::Garbage,
        Corruption::BitFlips,
        Corruption::Truncated,
    ]
    .into_iter()
    .enumerate()
    {
        let stream = command_stream(0xC0DE + i as u64, frames, kind);
        report(
            "commands",
            "`Framing<Device>`",
            kind,
            &stream,
            Framing::<Device>::new(),
        );
    }
    firmware_report(frames);
}

/// The robust device decoder against the tile's own parser on the same
/// command stream: commands it finds that the tile never ran, and commands
/// the tile ran that it does not give back.
fn firmware_report(frames: usize) {
    println!("\n{frames} commands per stream: what the device decoder finds against what a tile executes (`FirmwareParser`).\n");
    println!("| corruption | decoder: commands | tile: executed | found, not executed | executed, not found |");
    println!("|---|---:|---:|---:|---:|");
    for (i, kind) in [
        Corruption::Clean,
        Corruption::GarbageEndingInStart,
        Corruption::Garbage,
        Corruption::BitFlips,
        Corruption::Truncated,
    ]
    .into_iter()
    .enumerate()
    {
        let stream = command_stream(0xF1A0 + i as u64, frames, kind);
        let found: BTreeMap<(u64, usize), Message> =
            decode(Framing::<Device>::new(), &stream.bytes, 0)
                .into_iter()
                .map(|f| ((f.offset, f.len), f.message))
                .collect();
        let mut tile = FirmwareParser::new();
        let ran: BTreeMap<(u64, usize), Message> = tile
            .feed(&stream.bytes)
            .filter_map(Result::ok)
            .map(|f| ((f.offset, f.len), Message::Command(f.message)))
            .collect();
        let missing = |a: &BTreeMap<(u64, usize), Message>, b: &BTreeMap<(u64, usize), Message>| {
            a.iter().filter(|(at, m)| b.get(at) != Some(m)).count()
        };
        let (not_run, not_found) = (missing(&found, &ran), missing(&ran, &found));
        println!(
            "| {} | {} | {} | {not_run} | {not_found} |",
            kind.name(),
            found.len(),
            ran.len()
        );
    }
}

fn report<S: Side<Message: Into<Message>>>(
    name: &str,
    decoder: &str,
    kind: Corruption,
    stream: &Stream,
    framing: Framing<S>,
) {
    let scores: Vec<(&str, Score)> = CHUNKS
        .iter()
        .map(|&(chunk, label)| (label, score(stream, &decode(framing, &stream.bytes, chunk))))
        .collect();
    let same = scores.iter().all(|(_, s)| *s == scores[0].1);
    let rows: Vec<(&str, Score)> = if same {
        vec![("all same", scores[0].1)]
    } else {
        scores
    };
    for (label, s) in rows {
        println!(
            "| {name} | {decoder} | {} | {} | {} | {} | {} | {} | {label} |",
            kind.name(),
            s.sent,
            s.ideal,
            s.intact,
            s.lost,
            s.false_frames
        );
    }
}
