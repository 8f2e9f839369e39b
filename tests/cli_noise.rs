//! Where the tool's "mostly noise" rule (exit status 3) draws the line, and
//! the margin on each side, measured through the binary: every sample capture
//! decoded as docs/cli.md says, the same captures corrupted as the corruption
//! tests corrupt streams (at the tests' 5 % and at five times that), and every
//! capture decoded with the wrong protocol, direction, layout or dialect.
//! `cargo test --features cli --test cli_noise -- --nocapture` prints the
//! figures docs/cli.md quotes.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data, run};

/// A capture and how it is read: raw bytes, or hex text turned into bytes
/// (so that corruption hits bytes, not digits).
fn capture(name: &str) -> Vec<u8> {
    let bytes = std::fs::read(data(name)).unwrap();
    if !name.ends_with(".hex") {
        return bytes;
    }
    let text = String::from_utf8(bytes).unwrap();
    let digits: String = text
        .split(|c: char| c.is_whitespace() || c == ',')
        .map(|token| token.trim_start_matches("0x"))
        .collect();
    (0..digits.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&digits[i..i + 2], 16).unwrap())
        .collect()
}

/// One decode's figures, from its summary line and its input.
#[derive(Debug, Clone, Copy)]
struct Figures {
    code: i32,
    frames: u64,
    /// Skipped non-zero bytes, in percent of the non-zero bytes (the rule's
    /// measure: zero padding does not count).
    skipped: f64,
    rejections_per_frame: f64,
}

fn decode(args: &[&str], input: &[u8]) -> Figures {
    let args = [&["decode"], args].concat();
    let r = run(&args, input);
    let summary = r
        .stderr
        .lines()
        .find(|l| l.contains(" skipped, "))
        .unwrap_or_else(|| panic!("{args:?}: no summary in {:?}", r.stderr));
    let numbers: Vec<u64> = summary
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    let [frames, bytes, skipped, checksum, other, _] = numbers[..] else {
        panic!("{summary}")
    };
    let zeros = input.iter().filter(|&&b| b == 0).count() as u64;
    let content = bytes.saturating_sub(zeros).max(1) as f64;
    Figures {
        code: r.code,
        frames,
        skipped: skipped.saturating_sub(zeros) as f64 * 100.0 / content,
        rejections_per_frame: (checksum + other) as f64 / frames.max(1) as f64,
    }
}

/// Every sample capture with the options that decode it right (docs/cli.md's
/// tables), as a byte stream.
const RIGHT: &[(&str, &[&str])] = &[
    ("ble_telemetry.bin", &["omnitiles"]),
    (
        "ble_telemetry.bin",
        &["omnitiles", "--from", "tile", "--layout", "ble53"],
    ),
    ("ble_notifications.hex", &["omnitiles"]),
    (
        "spi_telemetry.bin",
        &["omnitiles", "--from", "tile", "--layout", "spi45"],
    ),
    (
        "spi_telemetry.bin",
        &["omnitiles", "--layout", "auto,spi45"],
    ),
    ("host_commands.bin", &["omnitiles", "--from", "host"]),
    ("host_commands.bin", &["omnitiles"]),
    ("spi_commands.hex", &["omnitiles", "--from", "host"]),
    ("pixy2_conversation.hex", &["pixy2"]),
    ("telemetrix_reports.bin", &["telemetrix", "--from", "pico"]),
    ("telemetrix_reports.bin", &["telemetrix"]),
    ("telemetrix_commands.hex", &["telemetrix", "--from", "host"]),
    ("telemetrix_commands.hex", &["telemetrix"]),
];

/// A seeded generator (xorshift), so the corrupted copies never change.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }
}

/// The corruption tests' kinds, each `count` times at random places: a run of
/// 1..=32 random bytes inserted, one bit flipped, a run of 1..=8 bytes lost.
fn corrupt(bytes: &[u8], kind: usize, count: usize, rng: &mut Rng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for _ in 0..count {
        let at = rng.below(out.len() + 1);
        match kind {
            0 => {
                let garbage: Vec<u8> = (0..1 + rng.below(32))
                    .map(|_| rng.below(256) as u8)
                    .collect();
                out.splice(at..at, garbage);
            }
            1 if at < out.len() => out[at] ^= 1 << rng.below(8),
            2 => {
                let end = out.len().min(at + 1 + rng.below(8));
                out.drain(at..end);
            }
            _ => {}
        }
    }
    out
}

const KINDS: [&str; 3] = ["garbage runs", "bit flips", "dropped runs"];

/// The largest skipped share and rejections per frame among `figures`.
fn worst(figures: &[Figures]) -> (f64, f64) {
    figures.iter().fold((0.0, 0.0), |(s, r), f| {
        (s.max(f.skipped), r.max(f.rejections_per_frame))
    })
}

#[test]
fn right_decodes_exit_0_even_corrupted() {
    let mut clean = Vec::new();
    let mut corrupted = [Vec::new(), Vec::new()];
    let mut rng = Rng(0x2100_15e0_0000_0001);
    for &(name, args) in RIGHT {
        let bytes = capture(name);
        let f = decode(args, &bytes);
        assert_eq!(f.code, 0, "{name} {args:?}: {f:?}");
        clean.push(f);
        for (level, percent) in [5, 25].into_iter().enumerate() {
            for (kind, kind_name) in KINDS.iter().enumerate() {
                let count = (f.frames as usize * percent / 100).max(1);
                let input = corrupt(&bytes, kind, count, &mut rng);
                let c = decode(args, &input);
                assert_eq!(c.code, 0, "{name} {args:?}, {percent} % {kind_name}: {c:?}");
                corrupted[level].push(c);
            }
        }
    }
    let (skipped, rejections) = worst(&clean);
    println!(
        "sample captures: at most {skipped:.1} % skipped, {rejections:.2} rejections per frame"
    );
    for (level, percent) in [5, 25].into_iter().enumerate() {
        let (skipped, rejections) = worst(&corrupted[level]);
        println!(
            "corrupted at {percent} % of frames: at most {skipped:.1} % skipped, \
             {rejections:.2} rejections per frame"
        );
    }
    // The margin below the thresholds (80 %, 8 per frame): docs/cli.md.
    let (skipped, rejections) = worst(&clean);
    assert!(skipped < 5.0 && rejections < 0.1, "{skipped} {rejections}");
    let (skipped, rejections) = worst(&corrupted[1]);
    assert!(skipped < 65.0 && rejections < 6.0, "{skipped} {rejections}");
}

#[test]
fn filtering_one_direction_is_no_noise() {
    // A two-way Pixy2 conversation read for one side, or for the checksum
    // form only, skips the other frames: a choice, not noise.
    let bytes = capture("pixy2_conversation.hex");
    for option in [
        &["--from", "host"][..],
        &["--from", "device"],
        &["--checksum-only"],
    ] {
        let f = decode(&[&["pixy2"][..], option].concat(), &bytes);
        assert_eq!(f.code, 0, "{option:?}: {f:?}");
        println!(
            "pixy2 {option:?}: {:.1} % skipped, {:.2} rejections per frame",
            f.skipped, f.rejections_per_frame
        );
        assert!(f.skipped < 70.0 && f.rejections_per_frame < 1.5, "{f:?}");
    }
}

#[test]
fn wrong_decodes_exit_3() {
    let captures = [
        "ble_telemetry.bin",
        "ble_notifications.hex",
        "spi_telemetry.bin",
        "host_commands.bin",
        "spi_commands.hex",
        "pixy2_conversation.hex",
        "telemetrix_reports.bin",
        "telemetrix_commands.hex",
    ];
    let protocols: [(&str, &[&[&str]]); 3] = [
        (
            "omnitiles",
            &[&[], &["--from", "host"], &["--from", "tile"]],
        ),
        ("pixy2", &[&[], &["--from", "host"], &["--from", "device"]]),
        (
            "telemetrix",
            &[&[], &["--from", "host"], &["--from", "pico"]],
        ),
    ];
    let protocol_of = |name: &str| match name.split('_').next() {
        Some("pixy2") => "pixy2",
        Some("telemetrix") => "telemetrix",
        _ => "omnitiles",
    };
    let mut wrong: Vec<(Vec<&str>, &str)> = Vec::new();
    for name in captures {
        for (protocol, sides) in protocols {
            if protocol != protocol_of(name) {
                for side in sides {
                    wrong.push(([&[protocol][..], side].concat(), name));
                }
            }
        }
    }
    // The right protocol, read the wrong way.
    for layout in ["pos7", "uwb15", "uwbtof17", "spi45"] {
        wrong.push((vec!["omnitiles", "--layout", layout], "ble_telemetry.bin"));
    }
    for layout in ["pos7", "uwb15", "uwbtof17", "ble53", "auto"] {
        wrong.push((vec!["omnitiles", "--layout", layout], "spi_telemetry.bin"));
    }
    wrong.push((vec!["omnitiles", "--from", "host"], "ble_telemetry.bin"));
    wrong.push((vec!["omnitiles", "--from", "tile"], "host_commands.bin"));
    wrong.push((
        vec!["telemetrix", "--from", "host"],
        "telemetrix_reports.bin",
    ));
    wrong.push((
        vec!["telemetrix", "--from", "pico"],
        "telemetrix_commands.hex",
    ));
    for dialect in ["mirte12", "upstream11"] {
        wrong.push((
            vec!["telemetrix", "--from", "pico", "--dialect", dialect],
            "telemetrix_reports.bin",
        ));
    }
    let (mut least_skipped, mut least_rejections) = (f64::MAX, f64::MAX);
    for (args, name) in &wrong {
        let f = decode(args, &capture(name));
        assert_eq!(f.code, 3, "{name} {args:?}: {f:?}");
        // The margin above the thresholds (80 %, 8 per frame): each is far
        // over one of them (docs/cli.md).
        assert!(
            f.skipped > 94.0 || f.rejections_per_frame > 12.0,
            "{name} {args:?}: {f:?}"
        );
        least_skipped = least_skipped.min(f.skipped);
        if f.frames > 0 {
            least_rejections = least_rejections.min(f.rejections_per_frame);
        }
    }
    println!(
        "{} wrong decodes: at least {least_skipped:.1} % skipped; where frames were found, at \
         least {least_rejections:.2} rejections per frame",
        wrong.len()
    );
    assert!(wrong.len() > 50);
}

#[test]
fn allow_noise_keeps_the_output_and_exits_0() {
    let bytes = capture("ble_telemetry.bin");
    for args in [
        &["pixy2"][..],
        &["telemetrix"],
        &["omnitiles", "--layout", "pos7"],
    ] {
        let args = [&["decode"], args].concat();
        let plain = run(&args, &bytes);
        let allowed = run(&[&args[..], &["--allow-noise"]].concat(), &bytes);
        assert_eq!((plain.code, allowed.code), (3, 0), "{args:?}");
        assert_eq!(plain.stdout, allowed.stdout);
        assert!(allowed
            .stderr
            .contains("robowire: warning: most of the input did not decode"));
        assert!(!allowed.stderr.contains("exit status 3"));
    }
}
