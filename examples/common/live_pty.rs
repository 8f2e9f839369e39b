//! `--pty` for the simulators: a pseudo-terminal pair whose device a host
//! opens (`robowire decode … --port /dev/pts/3`), written on a fixed period
//! ([`serve`], a tile or a Pico streaming) or in answer to what the host
//! writes ([`respond`], a Pixy2), until the process is stopped. Bytes nobody
//! reads are dropped, as on a UART with no one listening.

use std::process::ExitCode;
use std::time::Duration;

/// Print `what` (the stream, e.g. "53-byte telemetry every 20 ms") and the
/// robowire command that decodes it, then write what `next` appends every
/// `period`.
#[cfg(unix)]
#[allow(dead_code)]
pub fn serve(
    who: &str,
    what: &str,
    protocol: &str,
    period: Duration,
    mut next: impl FnMut(&mut Vec<u8>) -> Result<(), Box<dyn std::error::Error>>,
) -> Result<ExitCode, Box<dyn std::error::Error>> {
    use serialport::{ClearBuffer, SerialPort, TTYPort};
    use std::io::Write;

    let (mut device_end, host) = TTYPort::pair()?;
    let device = host.name().ok_or("the pseudo-terminal has no name")?;
    println!("{who}: {what} on {device} (Ctrl-C stops)");
    println!("{who}: robowire decode {protocol} --port {device}");
    let mut bytes = Vec::new();
    loop {
        // This end keeps the host's side open, so what nobody reads would
        // pile up and arrive all at once later: drop it, as a UART would.
        if host.bytes_to_read()? > 512 {
            host.clear(ClearBuffer::Input)?;
        }
        bytes.clear();
        next(&mut bytes)?;
        device_end.write_all(&bytes)?;
        std::thread::sleep(period);
    }
}

/// Print `what` and the robowire commands that talk to it, then pass what
/// the host writes to `answer` and write what it appends back.
#[cfg(unix)]
#[allow(dead_code)]
pub fn respond(
    who: &str,
    what: &str,
    protocol: &str,
    mut answer: impl FnMut(&[u8], &mut Vec<u8>),
) -> Result<ExitCode, Box<dyn std::error::Error>> {
    use serialport::{ClearBuffer, SerialPort, TTYPort};
    use std::io::{ErrorKind, Read, Write};

    let (mut device_end, host) = TTYPort::pair()?;
    device_end.set_timeout(Duration::from_millis(100))?;
    let device = host.name().ok_or("the pseudo-terminal has no name")?;
    println!("{who}: {what} on {device} (Ctrl-C stops)");
    println!("{who}: robowire decode {protocol} --port {device}");
    println!(
        "{who}: echo '{{\"type\":\"get_version\"}}' | robowire encode {protocol} --port {device}"
    );
    let mut buf = [0u8; 256];
    let mut out = Vec::new();
    loop {
        if host.bytes_to_read()? > 512 {
            host.clear(ClearBuffer::Input)?;
        }
        let n = match device_end.read(&mut buf) {
            Ok(n) => n,
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock) => continue,
            Err(e) => return Err(e.into()),
        };
        out.clear();
        answer(&buf[..n], &mut out);
        device_end.write_all(&out)?;
    }
}

/// `--pty` needs a Unix pseudo-terminal.
#[cfg(not(unix))]
#[allow(dead_code)]
pub fn respond(
    _who: &str,
    _what: &str,
    _protocol: &str,
    _answer: impl FnMut(&[u8], &mut Vec<u8>),
) -> Result<ExitCode, Box<dyn std::error::Error>> {
    Err("--pty needs a Unix pseudo-terminal".into())
}

/// `--pty` needs a Unix pseudo-terminal.
#[cfg(not(unix))]
#[allow(dead_code)]
pub fn serve(
    _who: &str,
    _what: &str,
    _protocol: &str,
    _period: Duration,
    _next: impl FnMut(&mut Vec<u8>) -> Result<(), Box<dyn std::error::Error>>,
) -> Result<ExitCode, Box<dyn std::error::Error>> {
    Err("--pty needs a Unix pseudo-terminal".into())
}

/// Whether the command line is `--pty` (with nothing after it); a usage
/// error with `usage` is `Some(Err(status))`.
pub fn asked(usage: &str) -> Option<Result<(), ExitCode>> {
    if !std::env::args_os().nth(1).is_some_and(|a| a == "--pty") {
        return None;
    }
    Some(match std::env::args().nth(2) {
        Some(extra) => {
            eprintln!("error: unexpected argument `{extra}`\n\n{usage}");
            Err(ExitCode::from(2))
        }
        None => Ok(()),
    })
}
