//! Regenerate the Telemetrix sample captures in `tests/data/` from a seeded
//! simulation of a host and a Raspberry Pi Pico running the mirte 1.3
//! firmware: the host's start-up and session as hex text (one write per
//! line) and the Pico's reports as raw bytes.
//!
//! ```sh
//! cargo run --example pico_sim            # writes tests/data/
//! cargo run --example pico_sim -- OUT_DIR # writes elsewhere
//! ```
//!
//! The output depends only on the seed, so it is byte-identical on every
//! run; `tests/telemetrix_sample_data.rs` compares it with the committed
//! files.

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
