//! When a decode's output may be false: the input looks like hex text read as
//! raw bytes, like zero-padded OmniTiles SPI buffers read without the `spi45`
//! layout, or most of it did not decode (the wrong protocol, direction or
//! layout). Each gives a warning after the summary and, unless the user
//! passes `--allow-noise`, exit status [`STATUS`]. A regular file is judged
//! whole before anything is printed (a first pass without output), so a
//! false decode of a file prints nothing; stdin and ports stream and warn at
//! the end. SPI buffers read with the default layouts are refused before
//! anything is printed from any input.
//!
//! The thresholds come from the sample captures in `tests/data` and corrupted
//! copies of them (`tests/cli_noise.rs` measures them, docs/cli.md has the
//! figures): decoded as they should be, at most 4.2 % of their non-zero bytes
//! are skipped and 0.08 candidates per frame rejected; with five times the
//! corruption the tests use, at most 58 % and 5.6; reading one direction of
//! a two-way capture skips up to 66 % (1.1 per frame); decoded with the wrong
//! protocol, direction, layout or dialect, at least 94.8 % are skipped or else
//! 12 candidates per frame rejected.

use robowire::omnitiles::padded_spi_frames;
use robowire::stream::Stats;

/// The exit status of a decode whose output is probably false.
pub const STATUS: u8 = 3;

/// Over this share of the non-zero bytes skipped, in percent, is noise.
pub const SKIPPED_PERCENT: u64 = 80;

/// Over this many rejected candidates per frame is noise.
pub const REJECTIONS_PER_FRAME: u64 = 8;

/// Neither rule applies below this many non-zero bytes (skipped share) or
/// rejections (per frame): a short input proves nothing.
pub const MIN_EVIDENCE: u64 = 64;

/// How much of the input the SPI check reads before the first frame is
/// printed: two 128-byte SPI buffers.
pub const SPI_GATE: usize = 256;

/// How many padded `spi45` frames make an input SPI buffers.
const SPI_FRAMES: usize = 2;

/// Whether zero-padded OmniTiles SPI buffers would be misread, and what to
/// do about them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpiCheck {
    /// Not OmniTiles telemetry as a byte stream, or `spi45` is among the
    /// layouts: nothing to check.
    Off,
    /// Layouts the user named without `spi45`: warn only.
    Warn,
    /// The default layouts: refuse the decode.
    Refuse,
}

/// What a decode's options tell the checks.
#[derive(Debug, Clone, Copy)]
pub struct Hints {
    /// How to read hex text; `None` when the input was read as hex.
    pub hex: Option<&'static str>,
    /// The options that choose what is accepted (`--from and --dialect`).
    pub options: &'static str,
    /// The SPI buffer check.
    pub spi: SpiCheck,
}

/// Why a decode's output may be false.
#[derive(Debug)]
pub struct Suspicion {
    /// The warning: the first of hex text, SPI buffers, noise that applies.
    pub warning: String,
    /// Whether the run ends with [`STATUS`] (unless `--allow-noise`): hex
    /// text, noise, or SPI buffers under [`SpiCheck::Refuse`].
    pub fails: bool,
}

/// What the start of the input (its first 64 KiB, `zeros` the number of `00`
/// bytes in all of it) and the counters say about a decode.
pub fn assess(stats: &Stats, start: &[u8], zeros: u64, hints: Hints) -> Option<Suspicion> {
    let hex = hints.hex.filter(|_| looks_like_hex(start));
    let spi = hints.spi != SpiCheck::Off && spi_buffers(start);
    let noise = is_noise(stats, zeros);
    let warning = if let Some(hex) = hex {
        format!("the input looks like hex text: read it with {hex}")
    } else if spi {
        "the input looks like zero-padded SPI buffers: decode it with --layout spi45".to_owned()
    } else if noise {
        let rejected = rejections(stats);
        let percent = stats.skipped * 100 / stats.bytes.max(1);
        format!(
            "most of the input did not decode ({percent} % skipped, {rejected} candidates \
             rejected, {} frames): check the protocol, {}; frames found this way may be false",
            stats.frames, hints.options
        )
    } else {
        return None;
    };
    let fails = hex.is_some() || noise || (spi && hints.spi == SpiCheck::Refuse);
    Some(Suspicion { warning, fails })
}

/// What is said after the warning when the run ends with [`STATUS`].
pub fn failed() -> String {
    format!(
        "the output is probably false (exit status {STATUS}); --allow-noise accepts it \
         (see docs/cli.md)"
    )
}

/// What is said after the warning when a whole file's decode is probably
/// false: nothing was printed.
pub fn withheld() -> String {
    format!(
        "the output is probably false, so nothing was printed (exit status {STATUS}); \
         --allow-noise prints it (see docs/cli.md)"
    )
}

/// Whether `start` holds zero-padded SPI telemetry buffers.
pub fn spi_buffers(start: &[u8]) -> bool {
    padded_spi_frames(start) >= SPI_FRAMES
}

/// The error for SPI buffers read with the default layouts.
pub fn spi_refusal() -> String {
    format!(
        "the input looks like zero-padded SPI buffers, which the default layouts misread \
         as false short frames: decode it with --layout spi45 (or auto,spi45); nothing was \
         printed (exit status {STATUS}; --allow-noise prints what the default layouts find)"
    )
}

/// Only hex digits, whitespace, commas and `x`, with at least two digits.
fn looks_like_hex(start: &[u8]) -> bool {
    let digits = start.iter().filter(|c| c.is_ascii_hexdigit()).count();
    let text = |c: &u8| c.is_ascii_hexdigit() || b" \t\r\n,xX".contains(c);
    digits >= 2 && start.iter().all(text)
}

fn rejections(stats: &Stats) -> u64 {
    stats.checksum_failures + stats.other_rejections
}

/// Over [`SKIPPED_PERCENT`] of the non-zero bytes skipped (zero padding does
/// not count), or over [`REJECTIONS_PER_FRAME`] rejections per frame, each
/// with at least [`MIN_EVIDENCE`] bytes or rejections.
pub fn is_noise(stats: &Stats, zeros: u64) -> bool {
    let content = stats.bytes.saturating_sub(zeros);
    let skipped = stats.skipped.saturating_sub(zeros);
    let rejected = rejections(stats);
    let mostly_skipped = content >= MIN_EVIDENCE && skipped * 100 > content * SKIPPED_PERCENT;
    let many_rejections =
        rejected >= MIN_EVIDENCE && rejected > REJECTIONS_PER_FRAME * stats.frames;
    mostly_skipped || many_rejections
}
