//! What the `robowire` binary says on stderr about its input: encode's bad
//! lines (too long, not UTF-8, a byte-order mark, invalid JSON), inputs that
//! cannot be read, where hex text goes wrong, and the warnings about a
//! misleading decode with their exit status 3 (a file judged whole and SPI
//! buffers read with the default layouts: refused with no output).

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data, data_arg, run, scratch, summary_line};

const MAX_LINE: usize = 1 << 20;

// ---------------------------------------------------------------- encode's bad lines

#[test]
fn encode_skips_a_line_over_the_limit_and_goes_on() {
    let long = format!(r#"{{"type":"ping","pad":"{}"}}"#, "x".repeat(MAX_LINE));
    // The long line in the middle, and again as the last line without a newline.
    let input = format!("{{\"type\":\"ping\"}}\n{long}\n{{\"type\":\"base_brake\"}}\n{long}");
    let r = run(&["encode", "omnitiles", "--hex"], input.as_bytes());
    assert_eq!(r.code, 2);
    assert_eq!(r.text(), "a5 50 50\na5 71 71\n");
    assert_eq!(
        r.stderr,
        "robowire: stdin: line 2: longer than 1048576 bytes\n\
         robowire: stdin: line 4: longer than 1048576 bytes\n\
         robowire: 2 malformed lines\n"
    );
    // A line of exactly the limit is read.
    let padded = format!(r#"{{"type":"ping"}}{}"#, " ".repeat(MAX_LINE - 15));
    let r = run(&["encode", "omnitiles", "--hex"], padded.as_bytes());
    assert_eq!((r.code, r.text(), r.stderr.as_str()), (0, "a5 50 50\n", ""));
}

#[test]
fn datagrams_skip_a_line_over_the_limit_and_go_on() {
    let input = format!("a5 50 50\n{}\na5 71 71\n", "0".repeat(MAX_LINE + 2));
    let r = run(&["decode", "omnitiles", "--datagrams"], input.as_bytes());
    assert_eq!(r.code, 2);
    assert_eq!(
        r.lines(),
        [
            r#"{"offset":0,"len":3,"type":"ping"}"#,
            r#"{"offset":3,"len":3,"type":"base_brake"}"#,
        ]
    );
    assert_eq!(
        r.stderr,
        "robowire: stdin: line 2: longer than 1048576 bytes\n".to_owned()
            + &summary_line([2, 6, 0, 0, 0, 0])
            + "robowire: 1 invalid datagram line\n"
    );
}

#[test]
fn encode_says_where_a_line_is_not_utf8_or_not_json() {
    let input = b"{\"type\":\"ping\"}\n{\"type\":\"pi\xffng\"}\n{\"type\":\"ping\"\n{\"type\":\"base_brake\"}\n";
    let r = run(&["encode", "omnitiles", "--hex"], input);
    assert_eq!(r.code, 2);
    assert_eq!(r.text(), "a5 50 50\na5 71 71\n");
    // One position, the tool's: no serde "at line 1 column 14" inside it.
    assert_eq!(
        r.stderr,
        "robowire: stdin: line 2, column 12: not UTF-8 text (byte 0xff)\n\
         robowire: stdin: line 3, column 14: not valid JSON: EOF while parsing an object\n\
         robowire: 2 malformed lines\n"
    );
    for protocol in ["pixy2", "telemetrix"] {
        let r = run(&["encode", protocol], b"\n{\"type\":\"get_fps\" 1}\n");
        assert_eq!((r.code, r.stdout.len()), (2, 0));
        assert_eq!(
            r.stderr,
            "robowire: stdin: line 2, column 19: not valid JSON: \
             expected `,` or `}`\n\
             robowire: 1 malformed line\n"
        );
    }
}

#[test]
fn encode_ignores_a_utf8_byte_order_mark_and_stops_at_utf16() {
    let r = run(
        &["encode", "omnitiles", "--hex"],
        b"\xef\xbb\xbf{\"type\":\"ping\"}\n{\"type\":\"base_brake\"}\n",
    );
    assert_eq!(r.code, 0);
    assert_eq!(r.text(), "a5 50 50\na5 71 71\n");
    assert_eq!(
        r.stderr,
        "robowire: stdin: line 1: ignoring a UTF-8 byte-order mark\n"
    );
    let utf16: Vec<u8> = "\u{feff}{\"type\":\"ping\"}\n"
        .encode_utf16()
        .flat_map(u16::to_le_bytes)
        .collect();
    let r = run(&["encode", "omnitiles", "--hex"], &utf16);
    assert_eq!((r.code, r.stdout.len()), (2, 0));
    assert_eq!(
        r.stderr,
        "robowire: stdin: the input is UTF-16 (it starts with a byte-order mark); \
         JSON lines must be UTF-8\n"
    );
}

// ---------------------------------------------------------------- inputs that cannot be read

#[test]
fn a_directory_fails_before_any_summary() {
    let dir = data_arg("");
    let dir = dir.trim_end_matches('/');
    for args in [
        &["decode", "omnitiles", dir][..],
        &["decode", "omnitiles", "--hex", dir],
        &["decode", "omnitiles", "--datagrams", dir],
        &["decode", "pixy2", dir],
        &["decode", "telemetrix", dir],
        &["encode", "telemetrix", dir],
    ] {
        let r = run(args, b"");
        assert_eq!((r.code, r.stdout.len()), (1, 0), "{args:?}");
        // The system's own words ("Is a directory"), on one line.
        assert!(
            r.stderr.starts_with(&format!("robowire: {dir}: ")),
            "{args:?}"
        );
        assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
    }
}

#[cfg(target_os = "linux")]
#[test]
fn an_unreadable_file_fails_before_any_summary() {
    // Opens, and its first read fails (address 0 is not mapped).
    for args in [
        &["decode", "omnitiles", "/proc/self/mem"][..],
        &["decode", "omnitiles", "--datagrams", "/proc/self/mem"],
    ] {
        let r = run(args, b"");
        assert_eq!((r.code, r.stdout.len()), (1, 0), "{args:?}");
        assert!(
            r.stderr.starts_with("robowire: /proc/self/mem: ") && r.stderr.lines().count() == 1,
            "{args:?}: {}",
            r.stderr
        );
    }
}

#[test]
fn hex_and_datagrams_report_positions_alike() {
    let text = b"a5 50 50\n  0xa5 0x71 7 0x";
    let hex = run(&["decode", "omnitiles", "--hex"], text);
    let datagrams = run(&["decode", "omnitiles", "--datagrams"], text);
    assert_eq!((hex.code, datagrams.code), (2, 2));
    // The last digit has no pair: the `7`, not the `0` of the `0x` after it.
    assert!(hex
        .stderr
        .ends_with("robowire: stdin: line 2, column 13: odd number of hex digits\n"));
    assert!(datagrams
        .stderr
        .starts_with("robowire: stdin: line 2, column 13: odd number of hex digits\n"));
    let text = b"a5 50 50\n a5 7q 71\n";
    let hex = run(&["decode", "omnitiles", "--hex"], text);
    let datagrams = run(&["decode", "omnitiles", "--datagrams"], text);
    assert!(hex
        .stderr
        .ends_with("robowire: stdin: line 2, column 6: invalid hex digit 'q'\n"));
    assert!(datagrams
        .stderr
        .starts_with("robowire: stdin: line 2, column 6: invalid hex digit 'q'\n"));
}

// ---------------------------------------------------------------- warnings

/// The stderr of a decode that warns: the summary, then the warning.
fn warned(counts: [u64; 6], warning: &str) -> String {
    summary_line(counts) + "robowire: warning: " + warning + "\n"
}

/// The stderr of a decode from a stream that warns and exits with status 3.
fn failed(counts: [u64; 6], warning: &str) -> String {
    warned(counts, warning)
        + "robowire: the output is probably false (exit status 3); --allow-noise accepts it \
           (see docs/cli.md)\n"
}

/// The stderr of a decode from a file that warns, prints nothing and exits
/// with status 3: the file is judged whole first.
fn withheld(counts: [u64; 6], warning: &str) -> String {
    warned(counts, warning)
        + "robowire: the output is probably false, so nothing was printed (exit status 3); \
           --allow-noise prints it (see docs/cli.md)\n"
}

/// `args` with `--allow-noise` added.
fn allowing<'a>(args: &[&'a str]) -> Vec<&'a str> {
    [args, &["--allow-noise"]].concat()
}

#[test]
fn hex_text_without_hex_fails() {
    let capture = data_arg("ble_notifications.hex");
    let args = ["decode", "omnitiles", &capture];
    let warning = "the input looks like hex text: read it with --hex, \
                   or --datagrams when each line is one datagram";
    let r = run(&args, b"");
    assert_eq!((r.code, r.stdout.len()), (3, 0));
    assert_eq!(r.stderr, withheld([0, 12720, 12720, 0, 0, 0], warning));
    // Insisting keeps the warning and exits 0.
    let r = run(&allowing(&args), b"");
    assert_eq!((r.code, r.stdout.len()), (0, 0));
    assert_eq!(r.stderr, warned([0, 12720, 12720, 0, 0, 0], warning));
    let r = run(&["decode", "pixy2"], b"0xae, 0xc1, 0x0e, 0x00\n");
    assert_eq!((r.code, r.stdout.len()), (3, 0));
    assert_eq!(
        r.stderr,
        failed(
            [0, 23, 23, 0, 0, 0],
            "the input looks like hex text: read it with --hex"
        )
    );
    // Read as hex, the same text decodes and nothing is said.
    let r = run(&["decode", "pixy2", "--hex"], b"0xae, 0xc1, 0x0e, 0x00\n");
    assert_eq!((r.code, r.lines().len()), (0, 1));
    assert_eq!(r.stderr, summary_line([1, 4, 0, 0, 0, 0]));
}

#[test]
fn the_wrong_protocol_fails() {
    let capture = data_arg("ble_telemetry.bin");
    let args = ["decode", "telemetrix", &capture];
    let warning = "most of the input did not decode (96 % skipped, 15052 candidates rejected, \
                   70 frames): check the protocol, --from and --dialect; frames found this way \
                   may be false";
    // From a file, judged whole, the 70 false frames are not printed.
    let r = run(&args, b"");
    assert_eq!((r.code, r.lines().len()), (3, 0));
    assert_eq!(r.stderr, withheld([70, 15920, 15325, 0, 15052, 0], warning));
    // From a stream they are printed as they come; the status says they are
    // noise.
    let bytes = std::fs::read(&capture).unwrap();
    let r = run(&["decode", "telemetrix"], &bytes);
    assert_eq!((r.code, r.lines().len()), (3, 70));
    assert_eq!(r.stderr, failed([70, 15920, 15325, 0, 15052, 0], warning));
    let allowed = run(&allowing(&args), b"");
    assert_eq!((allowed.code, &allowed.stdout), (0, &r.stdout));
    assert_eq!(
        allowed.stderr,
        warned([70, 15920, 15325, 0, 15052, 0], warning)
    );
    let r = run(&["decode", "pixy2", &capture], b"");
    assert_eq!((r.code, r.stdout.len()), (3, 0));
    assert_eq!(
        r.stderr,
        withheld(
            [0, 15920, 15920, 0, 0, 0],
            "most of the input did not decode (100 % skipped, 0 candidates rejected, 0 frames): \
             check the protocol, --from; frames found this way may be false"
        )
    );
    // The right protocol with the wrong direction.
    let commands = data_arg("host_commands.bin");
    let r = run(&["decode", "omnitiles", "--from", "tile", &commands], b"");
    assert_eq!((r.code, r.stdout.len()), (3, 0));
    assert!(r.stderr.contains(
        "0 frames): check the protocol, --from and --layout; frames found this way may be false\n"
    ));
    // The wrong layout: 5 false frames among 53-byte telemetry, printed
    // from a stream only.
    let r = run(&["decode", "omnitiles", "--layout", "pos7", &capture], b"");
    assert_eq!((r.code, r.lines().len()), (3, 0));
    let r = run(&["decode", "omnitiles", "--layout", "pos7"], &bytes);
    assert_eq!((r.code, r.lines().len()), (3, 5));
}

#[test]
fn a_false_decode_of_a_file_records_nothing() {
    // The recording and the JSON lines with times are not written either.
    let dir = scratch("withheld");
    let mcap = dir.join("false.mcap");
    let capture = data_arg("ble_telemetry.bin");
    let args = ["decode", "telemetrix", "--timestamps", "-o"];
    let r = run(
        &[&args[..], &[mcap.to_str().unwrap(), &capture]].concat(),
        b"",
    );
    assert_eq!((r.code, r.stdout.len()), (3, 0));
    assert!(r.stderr.ends_with(
        ", so nothing was printed (exit status 3); --allow-noise \
                               prints it (see docs/cli.md)\n"
    ));
    assert!(!mcap.exists());
    let r = run(
        &[
            &args[..],
            &[mcap.to_str().unwrap(), &capture, "--allow-noise"],
        ]
        .concat(),
        b"",
    );
    assert_eq!(r.code, 0);
    assert!(mcap.exists());
}

#[test]
fn a_file_judged_whole_reports_its_bad_lines_once() {
    // The first pass reads the file quietly; the one that prints reports.
    let dir = scratch("judged");
    let file = dir.join("datagrams.hex");
    let long = "0".repeat(MAX_LINE + 2);
    std::fs::write(&file, format!("a5 50 50\na5 7g\n{long}\na5 71 71\n")).unwrap();
    let name = file.to_str().unwrap();
    let r = run(&["decode", "omnitiles", "--datagrams", name], b"");
    assert_eq!((r.code, r.lines().len()), (2, 2));
    assert_eq!(
        r.stderr,
        format!(
            "robowire: {name}: line 2, column 5: invalid hex digit 'g'\n\
             robowire: {name}: line 3: longer than 1048576 bytes\n"
        ) + &summary_line([2, 6, 0, 0, 0, 0])
            + "robowire: 2 invalid datagram lines\n"
    );
}

#[test]
fn datagrams_of_binary_input_say_so_once() {
    let capture = data_arg("ble_telemetry.bin");
    let expected = format!(
        "robowire: {capture}: line 1 is binary, not hex text: --datagrams reads one datagram \
         per line of hex; decode raw bytes without --datagrams\n"
    );
    let r = run(&["decode", "omnitiles", "--datagrams", &capture], b"");
    assert_eq!((r.code, r.stdout.len(), r.stderr), (2, 0, expected));
    // From stdin alike, and a binary line after good ones is one bad line.
    let bytes = std::fs::read(&capture).unwrap();
    let r = run(&["decode", "omnitiles", "--datagrams"], &bytes);
    assert_eq!(r.code, 2);
    assert!(
        r.stderr.starts_with("robowire: stdin: line 1 is binary"),
        "{}",
        r.stderr
    );
    let r = run(
        &["decode", "omnitiles", "--datagrams"],
        b"a5 50 50\n\x00\xa5\x50\n",
    );
    assert_eq!((r.code, r.lines().len()), (2, 1));
    assert!(
        r.stderr.ends_with("robowire: 1 invalid datagram line\n"),
        "{}",
        r.stderr
    );
}

#[test]
fn noise_alone_and_zero_padding_do_not_warn() {
    // A little noise is not worth a warning, nor is zero padding (SPI
    // command buffers are mostly padding).
    let r = run(&["decode", "omnitiles"], &[0x55; 63]);
    assert_eq!((r.code, r.stderr), (0, summary_line([0, 63, 63, 0, 0, 0])));
    let r = run(&["decode", "omnitiles"], &[0x55; 64]);
    assert_eq!(r.code, 3);
    let spi = data_arg("spi_commands.hex");
    let r = run(
        &["decode", "omnitiles", "--from", "host", "--datagrams", &spi],
        b"",
    );
    assert_eq!(
        (r.code, r.stderr),
        (0, summary_line([44, 5120, 4953, 0, 0, 0]))
    );
    let r = run(
        &["decode", "omnitiles", "--from", "host", "--hex", &spi],
        b"",
    );
    assert_eq!(
        (r.code, r.stderr),
        (0, summary_line([44, 5120, 4953, 0, 0, 0]))
    );
}

/// The error for SPI buffers read with the default layouts.
const SPI_REFUSAL: &str = "robowire: the input looks like zero-padded SPI buffers, which the \
    default layouts misread as false short frames: decode it with --layout spi45 (or \
    auto,spi45); nothing was printed (exit status 3; --allow-noise prints what the default \
    layouts find)\n";

#[test]
fn spi_buffers_with_the_default_layouts_are_refused() {
    let capture = data_arg("spi_telemetry.bin");
    let bytes = std::fs::read(data("spi_telemetry.bin")).unwrap();
    // Nothing printed, whatever the chunking (the check reads the first 256
    // bytes before anything goes out), from a file or a pipe, and an input
    // too short for that check is refused at its end.
    for from in ["any", "tile"] {
        for chunk in ["1", "100", "4096"] {
            let r = run(
                &[
                    "decode",
                    "omnitiles",
                    "--from",
                    from,
                    "--chunk",
                    chunk,
                    &capture,
                ],
                b"",
            );
            assert_eq!((r.code, r.stdout.len()), (3, 0), "{from} {chunk}");
            assert_eq!(r.stderr, SPI_REFUSAL);
        }
    }
    let r = run(&["decode", "omnitiles", "--chunk", "7"], &bytes);
    assert_eq!(
        (r.code, r.stdout.len(), r.stderr.as_str()),
        (3, 0, SPI_REFUSAL)
    );
    let r = run(&["decode", "omnitiles"], &bytes[..200]);
    assert_eq!(
        (r.code, r.stdout.len(), r.stderr.as_str()),
        (3, 0, SPI_REFUSAL)
    );
    // The same bytes as hex text.
    let text: String = bytes.iter().map(|b| format!("{b:02x} ")).collect();
    let r = run(&["decode", "omnitiles", "--hex"], text.as_bytes());
    assert_eq!(
        (r.code, r.stdout.len(), r.stderr.as_str()),
        (3, 0, SPI_REFUSAL)
    );
    // Insisting prints the three false frames (one 53-byte frame, two short
    // prefixes that are the only length validating where they start) and
    // exits 0; naming the layouts exits 3, as mostly noise, and prints them
    // from a stream only.
    let warning = "the input looks like zero-padded SPI buffers: decode it with --layout spi45";
    let counts = [3, 8192, 8115, 61, 15, 0];
    let r = run(&["decode", "omnitiles", "--allow-noise", &capture], b"");
    assert_eq!((r.code, r.lines().len()), (0, 3));
    assert!(r.lines()[2].contains(r#""layout":"ble53""#));
    assert_eq!(r.stderr, warned(counts, warning));
    let r = run(&["decode", "omnitiles", "--layout=auto", &capture], b"");
    assert_eq!((r.code, r.lines().len()), (3, 0));
    assert_eq!(r.stderr, withheld(counts, warning));
    let r = run(&["decode", "omnitiles", "--layout=auto"], &bytes);
    assert_eq!((r.code, r.lines().len()), (3, 3));
    assert_eq!(r.stderr, failed(counts, warning));
    // One buffer per line is refused alike: the default layouts misread each.
    let lines: String = bytes
        .chunks(128)
        .map(|buffer| {
            buffer
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect::<String>()
                + "\n"
        })
        .collect();
    let r = run(&["decode", "omnitiles", "--datagrams"], lines.as_bytes());
    assert_eq!(
        (r.code, r.stdout.len(), r.stderr.as_str()),
        (3, 0, SPI_REFUSAL)
    );
    // With spi45 among the layouts, nothing is said.
    let r = run(&["decode", "omnitiles", "--layout", "spi45", &capture], b"");
    assert_eq!((r.code, r.lines().len()), (0, 64));
    assert_eq!(r.stderr, summary_line([64, 8192, 5312, 0, 0, 0]));
    let r = run(
        &["decode", "omnitiles", "--layout", "auto,spi45", &capture],
        b"",
    );
    assert_eq!((r.code, r.lines().len()), (0, 64));
    let r = run(
        &["decode", "omnitiles", "--datagrams", "--layout", "spi45"],
        lines.as_bytes(),
    );
    assert_eq!((r.code, r.lines().len()), (0, 64));
}

#[test]
fn a_decode_that_is_no_spi_buffers_is_not_held_back() {
    // A live stream: the first frame comes out before the input ends, as soon
    // as the check has seen 256 bytes.
    use std::io::{BufRead, BufReader, Write};
    use std::process::{Command, Stdio};
    let bytes = std::fs::read(data("ble_telemetry.bin")).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_robowire"))
        .args(["decode", "omnitiles", "--chunk", "64"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(&bytes[..300]).unwrap();
    stdin.flush().unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    assert!(
        line.starts_with(r#"{"offset":0,"len":53,"type":"telemetry""#),
        "{line}"
    );
    drop(stdin);
    assert_eq!(child.wait().unwrap().code(), Some(0));
}

/// A pseudo-terminal for the child's stdin, from the C library.
#[cfg(target_os = "linux")]
mod pty {
    use std::ffi::CStr;
    use std::fs::{File, OpenOptions};
    use std::os::fd::AsRawFd;
    use std::os::raw::{c_char, c_int};

    extern "C" {
        fn unlockpt(fd: c_int) -> c_int;
        fn ptsname_r(fd: c_int, buf: *mut c_char, len: usize) -> c_int;
    }

    /// The controlling side and the terminal.
    pub fn open() -> (File, File) {
        let ptmx = OpenOptions::new()
            .read(true)
            .write(true)
            .open("/dev/ptmx")
            .unwrap();
        let mut name = [0 as c_char; 128];
        // SAFETY: `ptmx` is an open pseudo-terminal master and `name` is a
        // writable buffer of the length given.
        let path = unsafe {
            assert_eq!(unlockpt(ptmx.as_raw_fd()), 0);
            assert_eq!(
                ptsname_r(ptmx.as_raw_fd(), name.as_mut_ptr(), name.len()),
                0
            );
            CStr::from_ptr(name.as_ptr()).to_str().unwrap().to_owned()
        };
        let terminal = OpenOptions::new()
            .read(true)
            .write(true)
            .open(path)
            .unwrap();
        (ptmx, terminal)
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_silent_terminal_on_stdin_is_told_to_type() {
    use std::io::{BufRead, BufReader, Read, Write};
    use std::process::{Command, Stdio};

    let spawn = |terminal| {
        Command::new(env!("CARGO_BIN_EXE_robowire"))
            .args(["decode", "omnitiles", "--hex"])
            .stdin(Stdio::from(terminal))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    // Nothing typed: the tool says what it waits for, and then decodes what
    // comes as usual.
    let (mut ptmx, terminal) = pty::open();
    let mut child = spawn(terminal);
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let (sender, notice) = std::sync::mpsc::channel();
    let reader = std::thread::spawn(move || {
        let mut line = String::new();
        stderr.read_line(&mut line).unwrap();
        sender.send(line).unwrap();
        let mut rest = String::new();
        stderr.read_to_string(&mut rest).unwrap();
        rest
    });
    // Not a measurement: a bound, so that a tool that never says it fails
    // the test instead of hanging it.
    let notice = notice.recv_timeout(std::time::Duration::from_secs(60));
    if notice.is_err() {
        child.kill().unwrap();
    }
    assert_eq!(
        notice.unwrap(),
        "robowire: waiting for input on stdin (a terminal): type or paste it and end it \
         with Ctrl-D, or name an input file\n"
    );
    // A line, then end of input (Ctrl-D at the start of a line).
    ptmx.write_all(b"a5 50 50\n\x04").unwrap();
    let rest = reader.join().unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(out.stdout, b"{\"offset\":0,\"len\":3,\"type\":\"ping\"}\n");
    assert_eq!(rest, summary_line([1, 3, 0, 0, 0, 0]));
    // Input already there: no notice.
    let (mut ptmx, terminal) = pty::open();
    ptmx.write_all(b"a5 50 50\n\x04").unwrap();
    let out = spawn(terminal).wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(out.stdout, b"{\"offset\":0,\"len\":3,\"type\":\"ping\"}\n");
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        summary_line([1, 3, 0, 0, 0, 0])
    );
}
