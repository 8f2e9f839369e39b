//! Live runs on a pseudo-terminal pair: the tool on the slave end, the test
//! writing a peer's bytes into the master end.

use serialport::TTYPort;
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStderr, Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// One test at a time: a pty pair's descriptors are inherited by every
/// process spawned while they are open, and a master end held open by
/// another test's child would never hang up.
pub static SERIAL: Mutex<()> = Mutex::new(());

pub fn serial() -> std::sync::MutexGuard<'static, ()> {
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

/// A pty pair whose descriptors the tool does not inherit (`TTYPort::pair`
/// opens them without close-on-exec): closing the master hangs the port up.
pub fn pty_pair() -> (TTYPort, TTYPort) {
    use std::os::fd::AsRawFd;
    let (master, slave) = TTYPort::pair().unwrap();
    for fd in [master.as_raw_fd(), slave.as_raw_fd()] {
        // SAFETY: fcntl on descriptors these ports own, changing only their flags.
        let set = unsafe { libc::fcntl(fd, libc::F_SETFD, libc::FD_CLOEXEC) };
        assert_eq!(set, 0);
    }
    (master, slave)
}

/// The tool running on a port: its stdout is read as it comes (a full pipe
/// would stop it), its stderr after its first line.
pub struct Running {
    pub child: Child,
    pub stdout: std::thread::JoinHandle<Vec<u8>>,
    pub stderr: BufReader<ChildStderr>,
}

/// Start the tool on a port and wait until it has opened it (its first
/// line on stderr says so).
pub fn spawn(args: &[&str]) -> Running {
    let mut child = Command::new(env!("CARGO_BIN_EXE_robowire"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = child.stdout.take().unwrap();
    let stdout = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        out.read_to_end(&mut bytes).unwrap();
        bytes
    });
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    stderr.read_line(&mut line).unwrap();
    assert!(line.starts_with("robowire: reading "), "{line}");
    assert!(line.ends_with("baud; Ctrl-C ends the run\n"), "{line}");
    Running {
        child,
        stdout,
        stderr,
    }
}

/// The tool's exit status, stdout and the rest of its stderr.
pub fn finish(mut running: Running) -> (Option<i32>, String, String) {
    let status = running.child.wait().unwrap();
    let stdout = running.stdout.join().unwrap();
    let mut rest = String::new();
    running.stderr.read_to_string(&mut rest).unwrap();
    (status.code(), String::from_utf8(stdout).unwrap(), rest)
}

/// Write `bytes` into `master` as a line at `baud` (8N1) would deliver
/// them: 1 ms of bytes at a time.
pub fn send_at(master: &mut TTYPort, bytes: &[u8], baud: u32) {
    let per_ms = (baud as usize / 10 / 1000).max(1);
    let start = Instant::now();
    for (i, piece) in bytes.chunks(per_ms).enumerate() {
        master.write_all(piece).unwrap();
        let due = start + Duration::from_millis(i as u64 + 1);
        if let Some(wait) = due.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
    }
    master.flush().unwrap();
}

/// Send `child` the signal `name` (`INT` is Ctrl-C).
pub fn signal(child: &Child, name: &str) {
    let status = Command::new("kill")
        .args([&format!("-{name}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}
