//! Regenerate the sample captures in `tests/data/` from a seeded tile
//! simulator: BLE telemetry (a byte stream and one notification per line),
//! SPI telemetry buffers, and host commands (a byte stream and SPI buffers).
//!
//! ```sh
//! cargo run --example tile_sim -- OUT_DIR       # writes the captures to OUT_DIR
//! cargo run --example tile_sim -- --tests-data  # rewrites tests/data/
//! cargo run --example tile_sim -- --help
//! ```
//!
//! The output depends only on the seeds, so it is byte-identical on every run;
//! `tests/sample_data.rs` compares it with the committed files.

mod sim;

#[path = "../common/sim_args.rs"]
mod sim_args;

use std::process::ExitCode;

const USAGE: &str = "\
Usage: cargo run --example tile_sim -- OUT_DIR
       cargo run --example tile_sim -- --tests-data

Writes the seeded sample captures into OUT_DIR (created if needed), or with
--tests-data rewrites the committed ones in tests/data/. The output depends
only on the seeds, so it is byte-identical on every run.";

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    sim_args::write_captures(USAGE, || {
        sim::captures().map(|captures| captures.into_iter().map(|c| (c.name, c.bytes)).collect())
    })
}
