//! Regenerate the sample captures in `tests/data/` from a seeded tile
//! simulator: BLE telemetry (a byte stream and one notification per line),
//! SPI telemetry buffers, and host commands (a byte stream and SPI buffers).
//!
//! ```sh
//! cargo run --example tile_sim -- OUT_DIR       # writes the captures to OUT_DIR
//! cargo run --example tile_sim -- --tests-data  # rewrites tests/data/
//! cargo run --example tile_sim -- --pty         # a live tile on a pseudo-terminal
//! cargo run --example tile_sim -- --help
//! ```
//!
//! `--pty` opens a pseudo-terminal pair, prints the device to open (for
//! example `robowire decode omnitiles --port /dev/pts/3`), and writes the
//! stream `ble_telemetry.bin` begins with, without end: a 53-byte frame and
//! its line noise every 20 ms, as a tile's BLE link does, until Ctrl-C. Bytes
//! nobody reads are dropped, as on a UART with no one listening.
//!
//! The output depends only on the seeds, so it is byte-identical on every run;
//! `tests/sample_data.rs` compares it with the committed files.

mod sim;

#[path = "../common/live_pty.rs"]
mod live_pty;
#[path = "../common/sim_args.rs"]
mod sim_args;

use std::process::ExitCode;
use std::time::Duration;

const USAGE: &str = "\
Usage: cargo run --example tile_sim -- OUT_DIR
       cargo run --example tile_sim -- --tests-data
       cargo run --example tile_sim -- --pty

Writes the seeded sample captures into OUT_DIR (created if needed), or with
--tests-data rewrites the committed ones in tests/data/. The output depends
only on the seeds, so it is byte-identical on every run. --pty streams the
BLE telemetry live on a pseudo-terminal (it prints the device) until Ctrl-C.";

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    match live_pty::asked(USAGE) {
        Some(Ok(())) => {
            let mut stream = sim::LiveTelemetry::new();
            return live_pty::serve(
                "tile",
                "53-byte telemetry every 20 ms",
                "omnitiles",
                Duration::from_millis(20),
                |bytes| Ok(stream.next_into(bytes)?),
            );
        }
        Some(Err(status)) => return Ok(status),
        None => {}
    }
    sim_args::write_captures(USAGE, || {
        sim::captures().map(|captures| captures.into_iter().map(|c| (c.name, c.bytes)).collect())
    })
}
