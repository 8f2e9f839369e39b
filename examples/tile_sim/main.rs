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

#[path = "../common/sim_args.rs"]
mod sim_args;

use std::process::ExitCode;

const USAGE: &str = "\
Usage: cargo run --example tile_sim -- OUT_DIR
       cargo run --example tile_sim -- --tests-data
       cargo run --example tile_sim -- --pty

Writes the seeded sample captures into OUT_DIR (created if needed), or with
--tests-data rewrites the committed ones in tests/data/. The output depends
only on the seeds, so it is byte-identical on every run. --pty streams the
BLE telemetry live on a pseudo-terminal (it prints the device) until Ctrl-C.";

fn main() -> Result<ExitCode, Box<dyn std::error::Error>> {
    if std::env::args_os().nth(1).is_some_and(|a| a == "--pty") {
        if let Some(extra) = std::env::args().nth(2) {
            eprintln!("error: unexpected argument `{extra}`\n\n{USAGE}");
            return Ok(ExitCode::from(2));
        }
        return live();
    }
    sim_args::write_captures(USAGE, || {
        sim::captures().map(|captures| captures.into_iter().map(|c| (c.name, c.bytes)).collect())
    })
}

/// A live tile on a pseudo-terminal: BLE telemetry every 20 ms until Ctrl-C.
#[cfg(unix)]
fn live() -> Result<ExitCode, Box<dyn std::error::Error>> {
    use serialport::{ClearBuffer, SerialPort, TTYPort};
    use std::io::Write;
    use std::time::Duration;

    let (mut tile, host) = TTYPort::pair()?;
    let device = host.name().ok_or("the pseudo-terminal has no name")?;
    println!("tile: 53-byte telemetry every 20 ms on {device} (Ctrl-C stops)");
    println!("tile: robowire decode omnitiles --port {device}");
    let mut stream = sim::LiveTelemetry::new();
    let mut bytes = Vec::new();
    loop {
        // This end keeps the host's side open, so what nobody reads would
        // pile up and arrive all at once later: drop it, as a UART would.
        if host.bytes_to_read()? > 512 {
            host.clear(ClearBuffer::Input)?;
        }
        bytes.clear();
        stream.next_into(&mut bytes)?;
        tile.write_all(&bytes)?;
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[cfg(not(unix))]
fn live() -> Result<ExitCode, Box<dyn std::error::Error>> {
    Err("--pty needs a Unix pseudo-terminal".into())
}
