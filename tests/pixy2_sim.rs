//! The simulated Pixy2 (`examples/pixy2_sim`): the conversation regenerates
//! the committed capture byte for byte, the host learns what the simulated
//! camera shows, and every answer in the capture answers the request before
//! it.

#[path = "../examples/pixy2_sim/sim.rs"]
mod sim;

use robowire::pixy2::{self, DeviceError, MessageBuf, PairError, Query, Request, ResponseBuf, Rgb};
use std::path::Path;

const CAPTURE: &str = "pixy2_conversation.hex";

fn committed() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(CAPTURE);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn hex(text: &str) -> Vec<u8> {
    text.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

fn run() -> (sim::Outcome, Vec<String>) {
    let mut said = Vec::new();
    let outcome = sim::run(&mut |line| said.push(line.to_owned())).unwrap();
    (outcome, said)
}

#[test]
fn conversation_regenerates_the_capture() {
    let (outcome, _) = run();
    assert!(
        outcome.capture == committed(),
        "tests/data/{CAPTURE} differs from what \
         `cargo run --example pixy2_sim -- tests/data/{CAPTURE}` writes"
    );
    // And the run is the same every time, threads notwithstanding.
    assert_eq!(run().0.capture, outcome.capture);
}

#[test]
fn host_learns_what_the_camera_shows() {
    let (outcome, said) = run();
    let learned = &outcome.learned;
    let version = learned.version.unwrap();
    assert_eq!(
        (
            version.hardware,
            version.firmware_major,
            version.firmware_build,
            version.firmware_type.as_str()
        ),
        (0x2200, 3, 20, Some("general"))
    );
    let resolutions: Vec<(u16, u16)> = learned
        .resolutions
        .iter()
        .map(|r| (r.width, r.height))
        .collect();
    assert_eq!(resolutions, [(316, 208), (79, 52)]);
    assert_eq!(learned.fps, Some(61));

    // The ball is in every blocks answer, moving down and to the right.
    assert_eq!(learned.ball.len(), 6);
    assert_eq!(learned.blocks_per_frame.len(), 6);
    assert!(learned
        .blocks_per_frame
        .iter()
        .all(|&n| (2..=3).contains(&n)));
    for pair in learned.ball.windows(2) {
        assert!(pair[1].0 > pair[0].0 && pair[1].1 > pair[0].1, "{pair:?}");
    }

    // Line features: an intersection (main mode reports it once, all mode
    // again), barcode 5 (main mode reports it when it is validated again),
    // and the primary vector reversed once the line is back in view.
    assert_eq!(learned.intersections, [vec![-90, 0, 90], vec![-90, 0, 90]]);
    assert_eq!(learned.barcodes, [5, 5, 5]);
    assert_eq!(learned.reversals, [false, true]);
    let last = learned.vectors.last().unwrap();
    assert_eq!((last.y0, last.y1), (0, 51));
    assert!(learned.vectors.iter().any(|v| v.flags == 0x04));

    assert_eq!(
        learned.rgb,
        Some(Rgb {
            r: 54,
            g: 255,
            b: 109
        })
    );
    assert_eq!(
        learned.refused,
        [DeviceError::InvalidRequest, DeviceError::TypeUnsupported]
    );

    // Retries: booting, no new frame, program switches, and the two lost to
    // line noise (a request the device dropped, an answer that failed its
    // checksum).
    assert!(learned.busy >= 5, "{}", learned.busy);
    assert_eq!(learned.prog_changing, 3);
    assert_eq!(learned.no_response, 2);
    assert_eq!(learned.checksum_failures, 1);
    assert_eq!(outcome.device.dropped, 1);
    assert!(said.iter().any(|l| l.contains("checksum mismatch")));
    assert!(said.iter().any(|l| l == "program: line_tracking"));
}

#[test]
fn every_answer_in_the_capture_answers_the_request_before_it() {
    let bytes = hex(&committed());
    let mut decoder = pixy2::both_decoder();
    let mut events: Vec<_> = decoder.feed(&bytes).collect();
    events.extend(decoder.flush());
    let mut pending: Option<Request> = None;
    let (mut requests, mut paired, mut refused) = (0, 0, 0);
    let mut orphans = Vec::new();
    for event in events {
        let Ok(frame) = event else { continue };
        match frame.message.body {
            MessageBuf::Request(request) => {
                requests += 1;
                pending = Some(request);
            }
            MessageBuf::Response(response) => match pending.take() {
                Some(request) => match request.answer(response.as_response()) {
                    Ok(_) => paired += 1,
                    Err(PairError::Device(_)) => refused += 1,
                    Err(e) => panic!("{request:?} answered by {response:?}: {e}"),
                },
                // The answer to bytes that were no valid request.
                None => orphans.push(response),
            },
        }
    }
    // One request failed its checksum (the device dropped it), one answer
    // failed its checksum (the host asked again); the two byte sequences
    // that are no valid request got ERROR answers of their own.
    let stats = decoder.stats();
    assert_eq!(stats.checksum_failures, 2);
    assert_eq!(requests, 42);
    assert_eq!(paired, 29);
    // Booting, no new frame yet, program switches, no line to reverse.
    assert_eq!(refused, 12);
    assert_eq!(
        orphans,
        [
            ResponseBuf::Error(DeviceError::InvalidRequest),
            ResponseBuf::Error(DeviceError::TypeUnsupported)
        ]
    );
}
