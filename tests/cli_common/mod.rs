//! What the command-line tests share: running the built binary and reading
//! the sample captures. Each test file uses a subset.
#![allow(dead_code)]

#[cfg(unix)]
pub mod live;

use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

pub struct Run {
    pub code: i32,
    pub stdout: Vec<u8>,
    pub stderr: String,
}

impl Run {
    pub fn text(&self) -> &str {
        std::str::from_utf8(&self.stdout).unwrap()
    }

    pub fn lines(&self) -> Vec<&str> {
        self.text().lines().collect()
    }

    pub fn json(&self) -> Vec<Value> {
        self.text()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect()
    }
}

/// Run the binary with `args`, writing `stdin` to it.
pub fn run(args: &[&str], stdin: &[u8]) -> Run {
    let mut child = Command::new(env!("CARGO_BIN_EXE_robowire"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = child.stdin.take().unwrap();
    let stdin = stdin.to_vec();
    // A thread, so a large input cannot deadlock against a full stdout pipe.
    let writer = std::thread::spawn(move || {
        let _ = input.write_all(&stdin);
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    Run {
        code: out.status.code().unwrap(),
        stdout: out.stdout,
        stderr: String::from_utf8(out.stderr).unwrap(),
    }
}

pub fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

pub fn data_arg(name: &str) -> String {
    data(name).to_str().unwrap().to_owned()
}

pub fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// The summary line a decode prints on stderr, counts of 1 in the singular.
pub fn summary_line(counts: [u64; 6]) -> String {
    let [frames, bytes, skipped, checksum, other, malformed] = counts;
    let s = |n: u64| if n == 1 { "" } else { "s" };
    format!(
        "robowire: {frames} frame{}, {bytes} byte{}, {skipped} byte{} skipped, \
         {checksum} checksum failure{}, {other} other rejection{}, {malformed} malformed\n",
        s(frames),
        s(bytes),
        s(skipped),
        s(checksum),
        s(other),
    )
}

/// A fresh scratch directory for one test, named after the process and `name`.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("robowire-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
