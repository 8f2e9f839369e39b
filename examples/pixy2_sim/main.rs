//! A simulated Pixy2 answering a host over an in-memory SPI link.
//!
//! The device thread decodes requests with robowire's device decoder and
//! answers in the checksum form (version, resolution, blocks of a moving
//! ball, line features, errors for requests it refuses); the host pairs each
//! answer with its request (`Query::answer`), retries what a host retries
//! (busy, program switches, line noise) and prints what it learns. The run is
//! bounded and seeded: the same conversation every time.
//!
//! ```sh
//! cargo run --example pixy2_sim                   # the host's view
//! cargo run --example pixy2_sim -- CAPTURE.hex    # also write the conversation
//! cargo run --example pixy2_sim -- --tests-data   # rewrite tests/data/pixy2_conversation.hex
//! cargo run --example pixy2_sim -- --pty          # a live Pixy2 on a pseudo-terminal
//! ```
//!
//! `--pty` opens a pseudo-terminal pair, prints the device to open, and
//! answers every request a host writes there as the simulated camera does
//! (its ball, its line features, busy when asked twice in one camera
//! frame), until Ctrl-C: `robowire decode pixy2 --port DEV` shows the
//! answers while `robowire encode pixy2 --port DEV` sends requests.
//!
//! The conversation, one SPI transaction per line, is committed as
//! `tests/data/pixy2_conversation.hex`; `tests/pixy2_sim.rs` checks that it
//! regenerates byte for byte. Decode it with
//! `robowire decode pixy2 --hex tests/data/pixy2_conversation.hex`.

#[path = "../common/live_pty.rs"]
mod live_pty;
mod sim;
#[path = "../common/sim_args.rs"]
mod sim_args;

use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "\
Usage: cargo run --example pixy2_sim [-- CAPTURE.hex]
       cargo run --example pixy2_sim -- --tests-data
       cargo run --example pixy2_sim -- --pty

Runs a seeded conversation between a host and a simulated Pixy2 and prints
what the host learns. With CAPTURE.hex, also writes the conversation (one SPI
transaction per line); --tests-data rewrites tests/data/pixy2_conversation.hex.
--pty answers a host's requests live on a pseudo-terminal (it prints the
device) until Ctrl-C.";

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    match live_pty::asked(USAGE) {
        Some(Ok(())) => {
            let mut camera = sim::Responder::new();
            return live_pty::respond(
                "pixy2",
                "a camera answering every request",
                "pixy2",
                |bytes, out| camera.feed(bytes, &mut |frame| out.extend_from_slice(frame)),
            );
        }
        Some(Err(status)) => return Ok(status),
        None => {}
    }
    let capture = match sim_args::parse(std::env::args_os().skip(1), USAGE, false) {
        sim_args::Request::Write(path) => Some(path),
        sim_args::Request::TestsData => Some(
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/pixy2_conversation.hex"),
        ),
        sim_args::Request::Nothing => None,
        sim_args::Request::Exit(code) => return Ok(code),
    };
    let outcome = sim::run(&mut |line| println!("{line}"))?;
    let device = outcome.device;
    println!(
        "device: {} requests answered, {} dropped; host: {} checksum failures, \
         {} busy, {} program-changing and {} no-response retries",
        device.answered,
        device.dropped,
        outcome.learned.checksum_failures,
        outcome.learned.busy,
        outcome.learned.prog_changing,
        outcome.learned.no_response
    );
    if let Some(path) = capture {
        std::fs::write(&path, &outcome.capture)?;
        println!(
            "{} ({} SPI transactions)",
            path.display(),
            outcome.capture.lines().count()
        );
    }
    Ok(ExitCode::SUCCESS)
}
