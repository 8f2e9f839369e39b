//! The command line the simulators share: `--help`, one output path, and an
//! explicit flag to rewrite the committed captures in `tests/data/`. An
//! argument that looks like an option is never taken as a path.

use std::ffi::OsString;
use std::path::PathBuf;
use std::process::ExitCode;

/// What the command line asks for.
pub enum Request {
    /// Write to this path.
    Write(PathBuf),
    /// Rewrite the committed captures in `tests/data/`.
    TestsData,
    /// No output path (allowed only where `Parse::optional_output` is set).
    Nothing,
    /// Stop now with this status: help was printed, or a usage error was.
    Exit(ExitCode),
}

/// Read the arguments after the program name. `usage` is the text `--help`
/// prints (and a usage error repeats); `output_required` says whether running
/// with no argument is a usage error, so that a bare run never rewrites a
/// committed file.
pub fn parse(
    args: impl IntoIterator<Item = OsString>,
    usage: &str,
    output_required: bool,
) -> Request {
    let args: Vec<OsString> = args.into_iter().collect();
    let fail = |why: String| {
        eprintln!("error: {why}\n\n{usage}");
        Request::Exit(ExitCode::from(2))
    };
    match args.as_slice() {
        [] if output_required => fail("no output given".into()),
        [] => Request::Nothing,
        [one] => match one.to_str() {
            Some("-h" | "--help") => {
                println!("{usage}");
                Request::Exit(ExitCode::SUCCESS)
            }
            Some("--tests-data") => Request::TestsData,
            Some(option) if option.starts_with('-') && option != "-" => fail(format!(
                "unknown option `{option}` (a path that starts with `-` can be written `./{option}`)"
            )),
            _ => Request::Write(PathBuf::from(one)),
        },
        [_, extra, ..] => fail(format!("unexpected argument `{}`", extra.to_string_lossy())),
    }
}

/// The whole `main` of a simulator that writes captures: read the command
/// line, then write each `(file name, bytes)` that `captures` makes into the
/// directory asked for.
#[allow(dead_code)] // pixy2_sim writes one file of its own
pub fn write_captures<E: std::error::Error + 'static>(
    usage: &str,
    captures: impl FnOnce() -> Result<Vec<(&'static str, Vec<u8>)>, E>,
) -> Result<ExitCode, Box<dyn std::error::Error>> {
    let dir = match parse(std::env::args_os().skip(1), usage, true) {
        Request::Write(dir) => dir,
        Request::TestsData => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data"),
        Request::Nothing => return Ok(ExitCode::from(2)),
        Request::Exit(code) => return Ok(code),
    };
    std::fs::create_dir_all(&dir)?;
    for (name, bytes) in captures()? {
        let path = dir.join(name);
        std::fs::write(&path, &bytes)?;
        println!("{} ({} bytes)", path.display(), bytes.len());
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_args(args: &[&str], required: bool) -> Request {
        parse(args.iter().map(OsString::from), "usage", required)
    }

    /// The exit status of an `Exit`, the path of a `Write`, as text.
    fn outcome(request: Request) -> String {
        match request {
            Request::Write(path) => format!("write {}", path.display()),
            Request::TestsData => "tests data".into(),
            Request::Nothing => "nothing".into(),
            Request::Exit(code) if code == ExitCode::SUCCESS => "exit 0".into(),
            Request::Exit(code) if code == ExitCode::from(2) => "exit 2".into(),
            Request::Exit(code) => format!("exit {code:?}"),
        }
    }

    #[test]
    fn options_are_never_paths() {
        for (args, expected) in [
            (&["--help"][..], "exit 0"),
            (&["-h"], "exit 0"),
            (&["--hlep"], "exit 2"),
            (&["-x"], "exit 2"),
            (&["./-x"], "write ./-x"),
            (&["out"], "write out"),
            (&["-"], "write -"),
            (&["--tests-data"], "tests data"),
            (&["a", "b"], "exit 2"),
        ] {
            assert_eq!(outcome(parse_args(args, true)), expected, "{args:?}");
        }
    }

    #[test]
    fn a_bare_run_writes_nothing() {
        assert_eq!(outcome(parse_args(&[], true)), "exit 2");
        assert_eq!(outcome(parse_args(&[], false)), "nothing");
    }
}
