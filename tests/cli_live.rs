//! `robowire decode --port` and `encode --port` on a pseudo-terminal pair:
//! the tile and Pico simulators write their captures into the master end at
//! a set baud rate, the tool reads the slave end. Ctrl-C, a port that
//! disappears, a missing device, MCAP refused on a terminal.

#![cfg(all(feature = "cli", unix))]

mod cli_common;

#[path = "../examples/pico_sim/sim.rs"]
#[allow(dead_code)]
mod pico_sim;
#[path = "../examples/tile_sim/sim.rs"]
#[allow(dead_code)]
mod tile_sim;

use cli_common::live::{finish, pty_pair, send_at, serial, signal, spawn};
use cli_common::{run, scratch};
use serde_json::Value;
use serialport::SerialPort;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn tile_capture() -> Vec<u8> {
    let captures = tile_sim::captures().unwrap();
    captures
        .into_iter()
        .find(|c| c.name == "ble_telemetry.bin")
        .unwrap()
        .bytes
}

fn pico_capture() -> Vec<u8> {
    let captures = pico_sim::captures().unwrap();
    captures
        .into_iter()
        .find(|c| c.name == "telemetrix_reports.bin")
        .unwrap()
        .bytes
}

/// Wait until `path` holds `len` bytes (the tool has read them all).
fn wait_for_size(path: &Path, len: u64) {
    let deadline = Instant::now() + Duration::from_secs(30);
    while std::fs::metadata(path).map_or(0, |m| m.len()) < len {
        let had = std::fs::metadata(path).map_or(0, |m| m.len());
        assert!(
            Instant::now() < deadline,
            "the tool read {had} of {len} bytes"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The lines of a decode of `bytes` from a file, and the summary line.
fn from_file(protocol: &str, bytes: &[u8], dir: &Path) -> (Vec<Value>, String) {
    let path = dir.join("reference.bin");
    std::fs::write(&path, bytes).unwrap();
    let out = run(
        &["decode", protocol, "--errors", path.to_str().unwrap()],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    (out.json(), out.stderr)
}

/// Decode `bytes` live from a pty at `baud`, end the run with Ctrl-C, and
/// compare with a decode of the same bytes from a file.
fn live_decode(protocol: &str, bytes: &[u8], baud: u32, name: &str) {
    let _one = serial();
    let dir = scratch(&format!("live-{name}"));
    let saved = dir.join("capture.bin");
    let (mut master, slave) = pty_pair();
    let device = slave.name().unwrap();
    let baud_arg = baud.to_string();
    let running = spawn(&[
        "decode",
        protocol,
        "--errors",
        "--port",
        &device,
        "--baud",
        &baud_arg,
        "--save",
        saved.to_str().unwrap(),
    ]);
    send_at(&mut master, bytes, baud);
    wait_for_size(&saved, bytes.len() as u64);
    signal(&running.child, "INT");
    let (code, stdout, stderr) = finish(running);
    assert_eq!(code, Some(0), "{stderr}");
    let (expected, summary) = from_file(protocol, bytes, &dir);
    assert_eq!(stderr, summary, "Ctrl-C ends the run with the summary");
    let lines: Vec<Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), expected.len(), "no frame lost at {baud} baud");
    let mut last = 0.0;
    for (mut line, expected) in lines.into_iter().zip(expected) {
        let t = line
            .as_object_mut()
            .unwrap()
            .remove("t")
            .unwrap()
            .as_f64()
            .unwrap();
        assert!(t >= last, "receive times never go back");
        last = t;
        assert_eq!(line, expected);
    }
    assert_eq!(
        std::fs::read(&saved).unwrap(),
        bytes,
        "the capture is complete"
    );
    // The saved capture replays with the times it was received at.
    let replay = run(
        &[
            "decode",
            protocol,
            "--errors",
            "--timestamps",
            saved.to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(replay.text(), stdout);
    drop(slave);
}

#[test]
fn a_tile_decodes_live_at_a_million_baud() {
    live_decode("omnitiles", &tile_capture(), 1_000_000, "tile");
}

#[test]
fn a_pico_decodes_live_at_115200_baud() {
    live_decode("telemetrix", &pico_capture(), 115_200, "pico");
}

/// A live MCAP recording of the tile's capture with `--save`, stopped with
/// `kill -NAME` after `linger` once the tool has read every byte: the exit
/// status, the recording's and the saved capture's bytes, and the lines a
/// decode of the capture from a file prints.
fn record_and_stop(name: &str, linger: Duration) -> (Option<i32>, Vec<u8>, Vec<u8>, Vec<Value>) {
    let (code, recording, saved, expected, _) = record_and_stop_in(name, name, linger);
    (code, recording, saved, expected)
}

/// [`record_and_stop`] in a directory of its own (named after `label`),
/// and that directory: it holds `tile.mcap`, `tile.bin` and `tile.bin.times`.
fn record_and_stop_in(
    name: &str,
    label: &str,
    linger: Duration,
) -> (Option<i32>, Vec<u8>, Vec<u8>, Vec<Value>, PathBuf) {
    let _one = serial();
    let dir = scratch(&format!("live-stop-{label}"));
    let (recording, saved) = (dir.join("tile.mcap"), dir.join("tile.bin"));
    let bytes = tile_capture();
    let (mut master, slave) = pty_pair();
    let device = slave.name().unwrap();
    let running = spawn(&[
        "decode",
        "omnitiles",
        "--errors",
        "--port",
        &device,
        "--baud",
        "1000000",
        "--format",
        "mcap",
        "-o",
        recording.to_str().unwrap(),
        "--save",
        saved.to_str().unwrap(),
    ]);
    send_at(&mut master, &bytes, 1_000_000);
    wait_for_size(&saved, bytes.len() as u64);
    std::thread::sleep(linger);
    signal(&running.child, name);
    let (code, _, stderr) = finish(running);
    if code.is_some() {
        assert!(stderr.starts_with("robowire: "), "the summary: {stderr}");
    }
    let (expected, _) = from_file("omnitiles", &bytes, &dir);
    drop(slave);
    (
        code,
        std::fs::read(&recording).unwrap(),
        std::fs::read(&saved).unwrap(),
        expected,
        dir,
    )
}

/// The messages of an MCAP file read from its start, as a reader without
/// the summary does (`mcap::MessageStream`), up to the first record that is
/// cut short.
fn messages_read_through(recording: &[u8]) -> Vec<String> {
    mcap::MessageStream::new(recording)
        .unwrap()
        .map_while(Result::ok)
        .map(|message| String::from_utf8(message.data.to_vec()).unwrap())
        .collect()
}

#[test]
fn every_stop_signal_completes_the_recording() {
    // Ctrl-C, `kill`/systemd/`docker stop` (SIGTERM) and a dropped ssh
    // session (SIGHUP) end the run as the end of a file does.
    for signal in ["INT", "TERM", "HUP"] {
        let (code, recording, saved, expected) = record_and_stop(signal, Duration::ZERO);
        assert_eq!(code, Some(0), "SIG{signal}");
        assert_eq!(
            saved,
            tile_capture(),
            "SIG{signal}: the capture is complete"
        );
        let summary = mcap::Summary::read(&recording).unwrap();
        assert!(
            summary.is_some(),
            "SIG{signal}: the recording has its summary"
        );
        assert_eq!(
            messages_read_through(&recording).len(),
            expected.len(),
            "SIG{signal}: every frame and rejection is recorded"
        );
    }
}

#[test]
fn live_log_times_are_unix_time_and_a_replay_reproduces_them() {
    let before = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos() as u64;
    let (code, recording, _, _, dir) = record_and_stop_in("TERM", "times", Duration::ZERO);
    assert_eq!(code, Some(0));
    let after = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos() as u64;
    let times = |bytes: &[u8]| -> Vec<(u64, String)> {
        mcap::MessageStream::new(bytes)
            .unwrap()
            .map(|m| {
                let m = m.unwrap();
                (m.log_time, String::from_utf8(m.data.to_vec()).unwrap())
            })
            .collect()
    };
    let live = times(&recording);
    assert!(live.len() > 100);
    // The metadata record: where and when.
    let summary = mcap::Summary::read(&recording).unwrap().unwrap();
    let index = summary.metadata_indexes.first().expect("a metadata record");
    assert_eq!(index.name, "robowire");
    let metadata = mcap::read::metadata(&recording, index).unwrap().metadata;
    assert_eq!(metadata["protocol"], "omnitiles");
    assert_eq!(metadata["baud"], "1000000");
    assert_eq!(metadata["robowire"], env!("CARGO_PKG_VERSION"));
    assert!(metadata["port"].starts_with("/dev/"));
    let start: u64 = metadata["start_unix_ns"].parse().unwrap();
    assert!((before..=after).contains(&start));
    assert!(metadata["start"].ends_with('Z') && metadata["start"].starts_with("20"));
    for (log_time, data) in &live {
        assert!(
            (before..=after).contains(log_time),
            "{log_time} in {before}..{after}"
        );
        // The log time is the start plus "t", to the nanosecond.
        let t: Value = serde_json::from_str(data).unwrap();
        let micros = (t["t"].as_f64().unwrap() * 1e6).round() as u64;
        assert_eq!(*log_time, start + micros * 1000, "{data}");
    }
    // The index keeps the start; a replay's log times are the live ones.
    let index_text = std::fs::read_to_string(dir.join("tile.bin.times")).unwrap();
    assert!(
        index_text.contains(&format!("# start_unix_ns: {start}\n")),
        "{index_text}"
    );
    let replay = dir.join("replay.mcap");
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--errors",
            "--timestamps",
            "--format",
            "mcap",
            "-o",
            replay.to_str().unwrap(),
            dir.join("tile.bin").to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(times(&std::fs::read(&replay).unwrap()), live);
}

#[test]
fn a_killed_recording_is_readable_up_to_its_last_chunk() {
    // SIGKILL (or a power loss) leaves no summary, but a live recording
    // closes a chunk at least once a second: everything received more than
    // a second before is readable from the file's start.
    let (code, recording, saved, expected) = record_and_stop("KILL", Duration::from_millis(1500));
    assert_eq!(code, None, "killed by the signal");
    assert_eq!(saved, tile_capture(), "--save is written out as it goes");
    assert!(
        mcap::Summary::read(&recording).is_err(),
        "a killed recording has no footer"
    );
    let messages = messages_read_through(&recording);
    assert_eq!(messages.len(), expected.len());
    for (message, line) in messages.iter().zip(&expected) {
        let mut message: Value = serde_json::from_str(message).unwrap();
        message.as_object_mut().unwrap().remove("t");
        assert_eq!(&message, line);
    }
}

#[test]
fn a_port_that_disappears_ends_with_an_error_and_keeps_the_frames() {
    let _one = serial();
    let dir = scratch("live-unplugged");
    let saved = dir.join("capture.bin");
    let bytes = tile_capture();
    let half = &bytes[..bytes.len() / 2];
    let (mut master, slave) = pty_pair();
    let device = slave.name().unwrap();
    let running = spawn(&[
        "decode",
        "omnitiles",
        "--port",
        &device,
        "--baud",
        "1000000",
        "--save",
        saved.to_str().unwrap(),
    ]);
    send_at(&mut master, half, 1_000_000);
    wait_for_size(&saved, half.len() as u64);
    drop(master);
    drop(slave);
    let (code, stdout, stderr) = finish(running);
    assert_eq!(code, Some(1), "{stderr}");
    let stdout = stdout.as_str();
    let error = stderr.lines().last().unwrap();
    assert!(
        error.starts_with(&format!("robowire: {device}: the serial port failed")),
        "{stderr}"
    );
    let (expected, _) = from_file("omnitiles", half, &dir);
    let frames: Vec<&Value> = expected
        .iter()
        .filter(|v| v.get("type").is_some())
        .collect();
    // Everything decoded before the port went away is written; the last
    // frame of the half may still have waited for its confirmation.
    let lines = stdout.lines().count();
    assert!(
        lines + 1 >= frames.len() && lines <= frames.len(),
        "{lines} of {}",
        frames.len()
    );
    assert_eq!(std::fs::read(&saved).unwrap(), half);
}

#[test]
fn a_missing_device_says_so_in_one_line() {
    let _one = serial();
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--port",
            "/dev/robowire-no-such-port",
        ],
        b"",
    );
    assert_eq!(out.code, 1);
    assert_eq!(out.stderr.lines().count(), 1, "{}", out.stderr);
    assert!(
        out.stderr
            .starts_with("robowire: /dev/robowire-no-such-port: cannot open the serial port"),
        "{}",
        out.stderr
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn a_port_with_input_is_a_usage_error() {
    let _one = serial();
    let out = run(
        &["decode", "omnitiles", "--port", "/dev/null", "capture.bin"],
        b"",
    );
    assert_eq!(out.code, 2, "{}", out.stderr);
    // Neither datagram lines nor the firmware's parser read a port.
    for mode in [&["--datagrams"][..], &["--from", "host", "--as-firmware"]] {
        let mut args = vec!["decode", "omnitiles", "--port", "/dev/null"];
        args.extend_from_slice(mode);
        let out = run(&args, b"");
        assert_eq!(out.code, 2, "{args:?}: {}", out.stderr);
        let refused = out.stderr.contains("cannot be used with") && out.stderr.contains("--port");
        assert!(refused, "{}", out.stderr);
    }
}

#[test]
fn what_is_no_serial_port_or_rate_is_refused_in_one_line() {
    let _one = serial();
    let advice = "not a serial port: without --port, decode reads a file named as INPUT and \
                  encode writes to stdout\n";
    let here = env!("CARGO_MANIFEST_DIR");
    let cargo_toml = format!("{here}/Cargo.toml");
    for (device, what) in [
        (cargo_toml.as_str(), "a regular file"),
        (here, "a directory"),
        ("/dev/null", "a device that is no terminal"),
    ] {
        let expected = format!("robowire: {device} is {what}, {advice}");
        let decode = run(&["decode", "omnitiles", "--port", device], b"");
        assert_eq!(
            (decode.code, decode.stderr.as_str()),
            (2, expected.as_str())
        );
        let encode = run(&["encode", "omnitiles", "--port", device], b"");
        assert_eq!(
            (encode.code, encode.stderr.as_str()),
            (2, expected.as_str())
        );
    }
    // A rate of 0 baud is no rate (and would divide the estimated times by 0).
    for verb in ["decode", "encode"] {
        let out = run(
            &[verb, "omnitiles", "--port", "/dev/null", "--baud", "0"],
            b"",
        );
        assert_eq!(out.code, 2);
        assert!(
            out.stderr.contains("invalid value '0' for '--baud <RATE>'"),
            "{}",
            out.stderr
        );
    }
    let out = run(&["decode", "omnitiles", "--timestamps", "--baud", "0"], b"");
    assert_eq!(out.code, 2);
}

#[test]
fn mcap_is_not_written_to_a_terminal() {
    let _one = serial();
    let (_master, slave) = pty_pair();
    let terminal = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(slave.name().unwrap())
        .unwrap();
    let input = cli_common::data_arg("ble_telemetry.bin");
    let out = Command::new(env!("CARGO_BIN_EXE_robowire"))
        .args(["decode", "omnitiles", "--format", "mcap", &input])
        .stdout(Stdio::from(terminal))
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("-o FILE"), "{stderr}");
}

#[test]
fn encode_writes_frames_to_a_port() {
    let _one = serial();
    let (mut master, slave) = pty_pair();
    let device = slave.name().unwrap();
    let lines = run(
        &[
            "decode",
            "omnitiles",
            &cli_common::data_arg("ble_telemetry.bin"),
        ],
        b"",
    );
    let expected = run(&["encode", "omnitiles"], &lines.stdout).stdout;
    // The other end reads while the tool writes: a pty holds only so much,
    // and a writer nobody reads from waits for ever.
    let want = expected.len();
    master.set_timeout(Duration::from_secs(10)).unwrap();
    // The master comes back with the bytes: closing it would hang up the
    // port before the tool has drained it.
    let reader = std::thread::spawn(move || {
        let mut received = vec![0u8; want];
        let read = master.read_exact(&mut received).map(|()| received);
        (read, master)
    });
    let out = run(
        &[
            "encode",
            "omnitiles",
            "--port",
            &device,
            "--baud",
            "1000000",
        ],
        &lines.stdout,
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.is_empty());
    let (read, master) = reader.join().unwrap();
    let received = read.expect("the frames, within 10 s");
    drop(master);
    assert_eq!(received, expected);
    drop(slave);
}

#[test]
fn encode_and_decode_share_one_port() {
    // A decode reads the port while an encode writes requests to it (a
    // Pixy2's, a command back): the port is opened with a shared lock.
    let _one = serial();
    let (mut master, slave) = pty_pair();
    let device = slave.name().unwrap();
    let running = spawn(&["decode", "pixy2", "--port", &device]);
    master.set_timeout(Duration::from_secs(10)).unwrap();
    let out = run(
        &["encode", "pixy2", "--port", &device],
        b"{\"type\":\"get_resolution\"}\n",
    );
    assert_eq!(out.code, 0, "the second run opens the port: {}", out.stderr);
    let mut request = [0u8; 5];
    master.read_exact(&mut request).unwrap();
    assert_eq!(request, [0xae, 0xc1, 0x0c, 0x01, 0x00]);
    // The answer the device gives reaches the decode.
    master
        .write_all(&cli_common::hex("af c1 0d 04 0d 01 3c 01 d0 00"))
        .unwrap();
    std::thread::sleep(Duration::from_millis(300));
    signal(&running.child, "TERM");
    let (code, stdout, _) = finish(running);
    assert_eq!(code, Some(0));
    assert!(stdout.contains("\"type\":\"resolution\""), "{stdout}");
    drop(slave);
}

/// Start `decode omnitiles` on a pty with `extra` options; each stdout line
/// comes out of the channel with the time it was read.
fn spawn_lines(
    device: &str,
    extra: &[&str],
) -> (
    std::process::Child,
    std::sync::mpsc::Receiver<(Instant, String)>,
) {
    use std::io::BufRead;
    let mut child = Command::new(env!("CARGO_BIN_EXE_robowire"))
        .args(["decode", "omnitiles", "--from", "tile", "--port", device])
        .args(extra)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    let (send, lines) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stdout).lines() {
            let Ok(line) = line else { break };
            if send.send((Instant::now(), line)).is_err() {
                break;
            }
        }
    });
    let mut stderr = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    stderr.read_line(&mut first).unwrap();
    assert!(first.starts_with("robowire: reading "), "{first}");
    (child, lines)
}

/// A 7-byte OmniTiles frame with the default layouts may begin a longer
/// one: on a live port the silence after it ends it, within the idle gap
/// (5 ms and 3.5 byte-times by default) plus the time to read and write
/// it, instead of when the next frame arrives. `--idle 0` keeps it until
/// then. Prints the latencies it measured (bytes written → line read).
#[test]
fn a_short_frame_leaves_when_the_line_goes_idle() {
    let _one = serial();
    let pos7 = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
    let (mut master, slave) = pty_pair();
    let device = slave.name().unwrap();
    // The first 256 bytes are held until they show the input is no SPI
    // buffers: whole 53-byte frames first.
    let prime = |master: &mut serialport::TTYPort, lines: &std::sync::mpsc::Receiver<_>| {
        let capture = tile_capture();
        master.write_all(&capture[..53 * 6]).unwrap();
        master.flush().unwrap();
        for _ in 0..6 {
            lines.recv_timeout(Duration::from_secs(5)).unwrap();
        }
    };
    let (mut child, lines) = spawn_lines(&device, &[]);
    prime(&mut master, &lines);
    let mut latencies = Vec::new();
    for _ in 0..20 {
        let sent = Instant::now();
        master.write_all(&pos7).unwrap();
        master.flush().unwrap();
        let (at, line) = lines
            .recv_timeout(Duration::from_secs(5))
            .expect("the frame came out while the line was silent");
        let line: Value = serde_json::from_str(&line).unwrap();
        assert_eq!(line["layout"], "pos7");
        latencies.push(at.duration_since(sent));
        std::thread::sleep(Duration::from_millis(30));
    }
    latencies.sort();
    eprintln!(
        "pos7 on a pty, default idle gap: latency median {:?}, max {:?}",
        latencies[latencies.len() / 2],
        latencies[latencies.len() - 1]
    );
    signal(&child, "INT");
    child.wait().unwrap();

    // --idle 0: the frame waits for the next frame.
    let (mut child, lines) = spawn_lines(&device, &["--idle", "0"]);
    prime(&mut master, &lines);
    master.write_all(&pos7).unwrap();
    master.flush().unwrap();
    assert!(lines.recv_timeout(Duration::from_millis(500)).is_err());
    master.write_all(&pos7).unwrap();
    master.flush().unwrap();
    let (_, line) = lines.recv_timeout(Duration::from_secs(5)).unwrap();
    assert!(line.contains("\"pos7\""), "{line}");
    signal(&child, "INT");
    child.wait().unwrap();
    drop(slave);
}

#[test]
fn an_idle_gap_is_a_number_of_milliseconds_on_a_port() {
    let dir = scratch("idle-options");
    let file = dir.join("pos7.bin");
    std::fs::write(&file, [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22]).unwrap();
    // From a file and from stdin alike.
    for args in [
        &["decode", "omnitiles", "--idle", "3", file.to_str().unwrap()][..],
        &["decode", "omnitiles", "--idle", "3"],
    ] {
        let out = run(args, b"");
        assert_eq!(out.code, 2);
        assert!(out
            .stderr
            .contains("--idle is the silence on a live port: it needs --port"));
    }
    for bad in ["-1", "NaN", "inf", "soon"] {
        let arg = format!("--idle={bad}");
        let out = run(&["decode", "omnitiles", "--port", "/dev/null", &arg], b"");
        assert_eq!(out.code, 2, "{bad}: {}", out.stderr);
        assert!(
            out.stderr.contains(&format!(
                "invalid value '{bad}' for '--idle <MS>': the milliseconds of silence must be a number from 0"
            )),
            "{}",
            out.stderr
        );
    }
}
