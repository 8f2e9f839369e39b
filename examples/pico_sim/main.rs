//! Regenerate the Telemetrix sample captures in `tests/data/` from a seeded
//! simulation of a host and a Raspberry Pi Pico running the mirte 1.3
//! firmware: the host's start-up and session as hex text (one write per
//! line) and the Pico's reports as raw bytes.
//!
//! ```sh
//! cargo run --example pico_sim -- OUT_DIR       # writes the captures to OUT_DIR
//! cargo run --example pico_sim -- --tests-data  # rewrites tests/data/
//! cargo run --example pico_sim -- --help
//! ```
//!
//! The output depends only on the seed, so it is byte-identical on every
//! run; `tests/telemetrix_sample_data.rs` compares it with the committed
//! files.

mod sim;

#[path = "../common/sim_args.rs"]
mod sim_args;

use std::process::ExitCode;

const USAGE: &str = "\
Usage: cargo run --example pico_sim -- OUT_DIR
       cargo run --example pico_sim -- --tests-data

Writes the seeded sample captures into OUT_DIR (created if needed), or with
--tests-data rewrites the committed ones in tests/data/. The output depends
only on the seeds, so it is byte-identical on every run.";

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    sim_args::write_captures(USAGE, || {
        sim::captures().map(|captures| captures.into_iter().map(|c| (c.name, c.bytes)).collect())
    })
}
