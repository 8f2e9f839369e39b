//! Regenerate the sample captures in `tests/data/` from a seeded tile
//! simulator: BLE telemetry (a byte stream and one notification per line),
//! SPI telemetry buffers, and host commands (a byte stream and SPI buffers).
//!
//! ```sh
//! cargo run --example tile_sim            # writes tests/data/
//! cargo run --example tile_sim -- OUT_DIR # writes elsewhere
//! ```
//!
//! The output depends only on the seeds, so it is byte-identical on every run;
//! `tests/sample_data.rs` compares it with the committed files.

mod sim;

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = match std::env::args_os().nth(1) {
        Some(dir) => PathBuf::from(dir),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data"),
    };
    std::fs::create_dir_all(&dir)?;
    for capture in sim::captures()? {
        let path = dir.join(capture.name);
        std::fs::write(&path, &capture.bytes)?;
        println!("{} ({} bytes)", path.display(), capture.bytes.len());
    }
    Ok(())
}
