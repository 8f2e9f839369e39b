//! Regenerate the Telemetrix sample captures in `tests/data/` from a seeded
//! simulation of a host and a Raspberry Pi Pico running the mirte 1.3
//! firmware: the host's start-up and session as hex text (one write per
//! line) and the Pico's reports as raw bytes.
//!
//! ```sh
//! cargo run --example pico_sim -- OUT_DIR       # writes the captures to OUT_DIR
//! cargo run --example pico_sim -- --tests-data  # rewrites tests/data/
//! cargo run --example pico_sim -- --pty         # a live Pico on a pseudo-terminal
//! cargo run --example pico_sim -- --help
//! ```
//!
//! `--pty` opens a pseudo-terminal pair, prints the device to open (for
//! example `robowire decode telemetrix --port /dev/pts/3`), and writes the
//! simulated Pico's reports (`telemetrix_reports.bin`) over and over, at the
//! pace of the 8-second session they come from, until Ctrl-C.
//!
//! The output depends only on the seed, so it is byte-identical on every
//! run; `tests/telemetrix_sample_data.rs` compares it with the committed
//! files.

mod sim;

#[path = "../common/live_pty.rs"]
mod live_pty;
#[path = "../common/sim_args.rs"]
mod sim_args;

use std::process::ExitCode;
use std::time::Duration;

const USAGE: &str = "\
Usage: cargo run --example pico_sim -- OUT_DIR
       cargo run --example pico_sim -- --tests-data
       cargo run --example pico_sim -- --pty

Writes the seeded sample captures into OUT_DIR (created if needed), or with
--tests-data rewrites the committed ones in tests/data/. The output depends
only on the seeds, so it is byte-identical on every run. --pty streams the
Pico's reports live on a pseudo-terminal (it prints the device) until Ctrl-C.";

/// How often the live Pico writes.
const PERIOD: Duration = Duration::from_millis(20);

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    match live_pty::asked(USAGE) {
        Some(Ok(())) => {
            let captures = sim::captures()?;
            let reports = captures
                .into_iter()
                .find(|c| c.name == "telemetrix_reports.bin")
                .ok_or("the simulation has no reports")?
                .bytes;
            // The session's bytes spread over its length, PERIOD at a time.
            let per_write =
                (reports.len() * PERIOD.as_millis() as usize / sim::END_MS as usize).max(1);
            let mut at = 0;
            return live_pty::serve(
                "pico",
                "mirte 1.3 reports of the simulated session, repeated",
                "telemetrix",
                PERIOD,
                |bytes| {
                    for _ in 0..per_write {
                        bytes.push(reports[at]);
                        at = (at + 1) % reports.len();
                    }
                    Ok(())
                },
            );
        }
        Some(Err(status)) => return Ok(status),
        None => {}
    }
    sim_args::write_captures(USAGE, || {
        sim::captures().map(|captures| captures.into_iter().map(|c| (c.name, c.bytes)).collect())
    })
}
