//! The documentation's own checks: the README stays a front page, no code block
//! hides lines, every relative link and anchor resolves, every guide with Rust
//! examples is compiled as a doctest, the feature tables list every feature,
//! the interrupt handler shown in docs/embedded.md is the firmware example's,
//! the tokio example's dependency list and the tool's messages and exit
//! statuses docs/cli.md quotes are the code's.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// README.md and every docs/*.md, by path relative to the crate root.
fn markdown_files() -> BTreeMap<PathBuf, String> {
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("README.md"), read(&root().join("README.md")));
    for entry in fs::read_dir(root().join("docs")).expect("docs/ exists") {
        let path = entry.expect("a directory entry").path();
        if path.extension().is_some_and(|e| e == "md") {
            let relative = path
                .strip_prefix(root())
                .expect("under the root")
                .to_path_buf();
            files.insert(relative, read(&path));
        }
    }
    files
}

/// A fenced code block: its info string and its lines.
struct Block<'a> {
    info: &'a str,
    lines: Vec<&'a str>,
}

fn code_blocks(markdown: &str) -> Vec<Block<'_>> {
    let mut blocks = Vec::new();
    let mut current: Option<Block<'_>> = None;
    for line in markdown.lines() {
        match (&mut current, line.strip_prefix("```")) {
            (None, Some(info)) => {
                current = Some(Block {
                    info: info.trim(),
                    lines: Vec::new(),
                })
            }
            (Some(_), Some(_)) => blocks.extend(current.take()),
            (Some(block), None) => block.lines.push(line),
            (None, None) => {}
        }
    }
    assert!(current.is_none(), "an unclosed code block");
    blocks
}

/// Whether rustdoc treats a block with this info string as Rust.
fn is_rust(info: &str) -> bool {
    info.is_empty() || info.split(',').any(|word| word.trim() == "rust")
}

/// The text outside code blocks.
fn prose(markdown: &str) -> String {
    let mut out = String::new();
    let mut in_code = false;
    for line in markdown.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
        } else if !in_code {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces to
/// hyphens; repeated headings get `-1`, `-2`, ….
fn anchors(markdown: &str) -> Vec<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = Vec::new();
    for line in prose(markdown).lines() {
        let Some(title) = line.strip_prefix('#') else {
            continue;
        };
        let title = title.trim_start_matches('#').trim();
        let slug: String = title
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let n = seen.entry(slug.clone()).or_insert(0);
        out.push(if *n == 0 {
            slug.clone()
        } else {
            format!("{slug}-{n}")
        });
        *n += 1;
    }
    out
}

/// The targets of inline links `[text](target)` outside code blocks.
fn links(markdown: &str) -> Vec<String> {
    let text = prose(markdown);
    let mut out = Vec::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        if let Some(end) = rest.find(')') {
            out.push(rest[..end].to_string());
            rest = &rest[end..];
        }
    }
    out
}

#[test]
fn the_readme_is_a_front_page() {
    let readme = read(&root().join("README.md"));
    let lines = readme.lines().count();
    assert!(
        lines <= 250,
        "README.md has {lines} lines; the details belong in docs/"
    );
    for section in [
        "cargo add robowire",
        "## OmniTiles",
        "## Pixy2",
        "## Telemetrix4RpiPico",
    ] {
        assert!(readme.contains(section), "README.md lacks {section:?}");
    }
    for guide in [
        "docs/cli.md",
        "docs/embedded.md",
        "docs/performance.md",
        "docs/robustness.md",
    ] {
        assert!(
            readme.contains(&format!("]({guide})")),
            "README.md does not link {guide}"
        );
    }
}

#[test]
fn no_code_block_hides_lines() {
    for (path, text) in markdown_files() {
        for block in code_blocks(&text).into_iter().filter(|b| is_rust(b.info)) {
            for line in &block.lines {
                let trimmed = line.trim_start();
                // `#[attr]` and `#![attr]` are Rust; `# x` and a lone `#` are hidden lines.
                let hidden = trimmed == "#" || trimmed.starts_with("# ");
                assert!(
                    !hidden,
                    "{}: a hidden doctest line: {line:?}",
                    path.display()
                );
            }
        }
    }
}

#[test]
fn every_relative_link_and_anchor_resolves() {
    let files = markdown_files();
    for (path, text) in &files {
        let dir = path.parent().unwrap_or(Path::new(""));
        for link in links(text) {
            if link.starts_with("http://") || link.starts_with("https://") {
                continue;
            }
            let (file, anchor) = match link.split_once('#') {
                Some((file, anchor)) => (file, Some(anchor)),
                None => (link.as_str(), None),
            };
            let target = if file.is_empty() {
                path.clone()
            } else {
                dir.join(file)
            };
            let on_disk = root().join(&target);
            assert!(
                on_disk.exists(),
                "{}: the link {link:?} leads nowhere",
                path.display()
            );
            if let Some(anchor) = anchor {
                let target_text = read(&on_disk);
                assert!(
                    anchors(&target_text).iter().any(|a| a == anchor),
                    "{}: no heading in {} has the anchor #{anchor}",
                    path.display(),
                    target.display()
                );
            }
        }
    }
}

#[test]
fn every_page_with_rust_examples_is_a_doctest() {
    let lib = read(&root().join("src/lib.rs"));
    for (path, text) in markdown_files() {
        let compiled = code_blocks(&text)
            .iter()
            .any(|b| is_rust(b.info) && !b.info.contains("ignore"));
        if compiled {
            let include = format!("#[doc = include_str!(\"../{}\")]", path.display());
            assert!(
                lib.contains(&include),
                "src/lib.rs does not compile {}",
                path.display()
            );
        }
    }
}

#[test]
fn the_feature_tables_list_every_feature() {
    let manifest = read(&root().join("Cargo.toml"));
    let features = manifest
        .split("[features]")
        .nth(1)
        .expect("a [features] table")
        .split("\n[")
        .next()
        .unwrap_or_default();
    let names: Vec<&str> = features
        .lines()
        .filter_map(|line| line.split_once(" = ").map(|(name, _)| name.trim()))
        .filter(|name| *name != "default")
        .collect();
    assert!(names.len() >= 7, "features found: {names:?}");
    let readme = read(&root().join("README.md"));
    let lib = read(&root().join("src/lib.rs"));
    for name in names {
        let row = format!("| `{name}` |");
        assert!(
            readme.contains(&row),
            "README.md's feature table lacks `{name}`"
        );
        assert!(
            lib.contains(&format!("//! {row}")),
            "the crate docs' feature table lacks `{name}`"
        );
    }
}

#[test]
fn the_embedded_guide_shows_the_firmware_example() {
    let guide = read(&root().join("docs/embedded.md"));
    let (_, after) = guide
        .split_once("<!-- firmware -->")
        .expect("the firmware marker");
    let block = &code_blocks(after)[0];
    let firmware = read(&root().join("examples/firmware/src/main.rs"));
    let mut rest = firmware.lines().map(str::trim);
    for line in block
        .lines
        .iter()
        .map(|l| l.trim())
        .filter(|l| !l.is_empty())
    {
        assert!(
            rest.any(|f| f == line),
            "docs/embedded.md shows a line that examples/firmware/src/main.rs does not have \
             (or not in this order): {line:?}"
        );
    }
}

/// docs/embedded.md shows the firmware example's project files for a crates.io
/// user (the crate does not contain the example): each block is the file, with
/// the path dependency on robowire replaced by this release's version.
#[test]
fn the_embedded_guide_shows_the_firmware_project_files() {
    let guide = read(&root().join("docs/embedded.md"));
    let version = env!("CARGO_PKG_VERSION");
    let release = version.rsplit_once('.').map_or(version, |(minor, _)| minor);
    let mut shown = 0;
    for (marker, rest) in guide
        .split("<!-- firmware project: ")
        .skip(1)
        .filter_map(|part| part.split_once(" -->"))
    {
        let block = &code_blocks(rest)[0];
        let file = read(&root().join("examples/firmware").join(marker));
        let mut lines = file.lines();
        for line in &block.lines {
            let line = line.replace(
                &format!("robowire = {{ version = \"{release}\","),
                "robowire = { path = \"../..\",",
            );
            assert!(
                lines.any(|l| l == line),
                "docs/embedded.md shows a line of {marker} that examples/firmware/{marker} \
                 does not have (or not in this order): {line:?}"
            );
        }
        shown += 1;
    }
    assert_eq!(
        shown, 4,
        "Cargo.toml, .cargo/config.toml, memory.x and build.rs"
    );
}

/// The words of `text` separated by single spaces (prose wrapped anyhow).
fn words(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[test]
fn the_tokio_example_lists_the_dependencies_it_needs() {
    // Each `cargo add NAME@V --features A,B` of docs/integrations.md names a
    // crate the example's own build (Cargo.toml) has with those features.
    let guide = read(&root().join("docs/integrations.md"));
    let manifest = read(&root().join("Cargo.toml"));
    let mut added = Vec::new();
    for line in guide.lines().filter_map(|l| l.strip_prefix("cargo add ")) {
        let line = line.split('#').next().unwrap();
        let mut parts = line.split_whitespace();
        let name = parts.next().unwrap().split('@').next().unwrap();
        let features: Vec<&str> = parts
            .skip_while(|&p| p != "--features")
            .nth(1)
            .map_or(Vec::new(), |f| f.split(',').collect());
        added.push(name.to_owned());
        if name == "robowire" {
            continue;
        }
        let entry = manifest
            .lines()
            .find(|l| l.starts_with(&format!("{name} = ")))
            .unwrap_or_else(|| panic!("Cargo.toml has no {name}"));
        for feature in features {
            assert!(
                entry.contains(&format!("\"{feature}\"")),
                "{name}: Cargo.toml does not build the example with {feature}: {entry}"
            );
        }
    }
    assert_eq!(added, ["robowire", "tokio", "tokio-util", "futures-util"]);
    // And the example uses what they bring.
    for import in [
        "use futures_util::{SinkExt, StreamExt};",
        "use tokio_util::codec::Framed;",
    ] {
        assert!(guide.contains(import), "{import}");
    }
}

#[test]
fn the_export_benchmark_runs_as_often_as_the_docs_say() {
    let script = read(&root().join("benches/cli_export.py"));
    let runs = script
        .split("\"--runs\", type=int, default=")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .expect("the script's default --runs");
    let cli = words(&read(&root().join("docs/cli.md")));
    assert!(
        cli.contains(&format!("interleaved, best of {runs} (CPU time")),
        "docs/cli.md does not say best of {runs}"
    );
    // The binary it builds lands where cargo puts it (release_binary.py).
    assert!(script.contains("from release_binary import release_binary"));
    let builder = read(&root().join("benches/release_binary.py"));
    assert!(builder.contains("os.environ.get(\"CARGO_TARGET_DIR\""));
}

/// docs/cli.md's claims about what the tool does, checked by running it.
#[cfg(feature = "cli")]
mod cli_claims {
    use super::{read, root};
    use std::process::{Command, Output};

    fn cli_md() -> String {
        read(&root().join("docs/cli.md"))
    }

    /// `robowire ARGS` from the crate root (the docs' paths are relative to it).
    fn robowire(args: &str) -> Output {
        robowire_with(args, "")
    }

    /// Every `` `decode …` (N [false ]frame[s], exit status S) `` in the text
    /// (a space or a line break before the parenthesis): the arguments, N and
    /// S.
    fn frame_claims(text: &str) -> Vec<(String, usize, i32)> {
        let mut claims = Vec::new();
        for (i, _) in text.match_indices("`decode ") {
            let rest = &text[i + 1..];
            let Some(end) = rest.find('`') else { continue };
            let args = rest[..end].to_owned();
            let after = &rest[end + 1..];
            let Some(claim) = after
                .strip_prefix(' ')
                .or_else(|| after.strip_prefix('\n'))
                .and_then(|a| a.strip_prefix('('))
            else {
                continue;
            };
            let claim = &claim[..claim.find(')').expect("a closing parenthesis")];
            let words: Vec<&str> = claim
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|w| !w.is_empty())
                .collect();
            let frames = words[0].parse().unwrap_or_else(|_| panic!("{claim:?}"));
            let status = words
                .windows(3)
                .find(|w| w[..2] == ["exit", "status"])
                .map(|w| w[2].parse().unwrap())
                .unwrap_or_else(|| panic!("{args}: {claim:?} gives no exit status"));
            claims.push((args.replace('\n', " "), frames, status));
        }
        claims
    }

    #[test]
    fn the_frame_counts_and_statuses_are_the_tools() {
        let claims = frame_claims(&cli_md());
        // The warnings table, SPI refusal and sample-capture paragraphs.
        assert!(claims.len() >= 7, "{claims:?}");
        for (args, frames, status) in claims {
            let out = robowire(&args);
            let lines = out.stdout.iter().filter(|&&b| b == b'\n').count();
            assert_eq!(
                (lines, out.status.code()),
                (frames, Some(status)),
                "docs/cli.md: `{args}`: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }

    #[test]
    fn the_false_spi_frames_are_the_tools() {
        let out = robowire(
            "decode omnitiles --from tile --layout auto --allow-noise tests/data/spi_telemetry.bin",
        );
        let lens: Vec<String> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(|line| {
                let (_, rest) = line.split_once("\"len\":").expect("a len");
                rest.split(',').next().unwrap().to_owned()
            })
            .collect();
        let claim = format!(
            "three false frames of {} and {} bytes",
            lens[..2].join(", "),
            lens[2]
        );
        assert_eq!(lens.len(), 3);
        assert!(
            cli_md().replace('\n', " ").contains(&claim),
            "docs/cli.md lacks {claim:?}"
        );
    }

    #[test]
    fn the_exit_status_table_is_the_tools() {
        let text = cli_md();
        let (_, table) = text
            .split_once("| status | when | for example |")
            .expect("the exit status table");
        let mut statuses = Vec::new();
        for row in table.lines().skip(2).take_while(|l| l.starts_with('|')) {
            let cells: Vec<&str> = row.split(" | ").collect();
            let status: i32 = cells[0]
                .trim_start_matches("| **")
                .trim_end_matches("**")
                .parse()
                .unwrap_or_else(|_| panic!("{row}"));
            let example = cells.last().unwrap().trim_end_matches(" |");
            let args = example.trim_matches('`');
            let out = robowire(args);
            assert_eq!(out.status.code(), Some(status), "docs/cli.md: `{args}`");
            statuses.push(status);
        }
        assert_eq!(statuses, [0, 1, 2, 3]);
        // The tool's own help says the same.
        let help = robowire("--help");
        let help = String::from_utf8(help.stdout).unwrap();
        for status in [
            "0 on success",
            "2 on usage errors",
            "1 on I/O errors",
            "3 when",
        ] {
            assert!(help.contains(status), "--help lacks {status:?}");
        }
    }

    /// `robowire ARGS` with `stdin` as its input.
    fn robowire_with(args: &str, stdin: &str) -> Output {
        use std::io::Write;
        use std::process::Stdio;
        let mut child = Command::new(env!("CARGO_BIN_EXE_robowire"))
            .args(args.split_whitespace())
            .current_dir(root())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        child
            .stdin
            .take()
            .unwrap()
            .write_all(stdin.as_bytes())
            .unwrap();
        child.wait_with_output().unwrap()
    }

    #[test]
    fn the_messages_quoted_are_the_tools() {
        let text = super::words(&cli_md());
        // A whole file judged probably false prints nothing and says so.
        let out = robowire("decode telemetrix tests/data/ble_telemetry.bin");
        let stderr = String::from_utf8(out.stderr).unwrap();
        let withheld = stderr.lines().last().unwrap();
        let withheld = withheld.strip_prefix("robowire: ").unwrap();
        let quoted = withheld.strip_suffix(" (see docs/cli.md)").unwrap();
        assert!(text.contains(quoted), "docs/cli.md lacks {quoted:?}");
        // Pixy2's getBlocks with signature map 0, as the encode example's
        // fourth line.
        let out = robowire_with(
            "encode pixy2",
            r#"{"type":"get_blocks","sigmap":0,"max_blocks":3}"#,
        );
        let stderr = String::from_utf8(out.stderr).unwrap();
        let refusal = stderr.lines().next().unwrap().replace("line 1:", "line 4:");
        assert!(
            cli_md().lines().any(|l| l == refusal),
            "docs/cli.md does not show {refusal:?}"
        );
        // The binary-input line of --datagrams.
        let out = robowire("decode omnitiles --datagrams tests/data/ble_telemetry.bin");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(
            stderr.contains("line 1 is binary, not hex text: "),
            "{stderr}"
        );
        assert!(text.contains("`line 1 is binary, not hex text: …`"));
    }

    #[test]
    fn the_spi_refusal_and_the_thresholds_are_the_tools() {
        let text = cli_md();
        let out = robowire("decode omnitiles tests/data/spi_telemetry.bin");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert!(
            text.lines().any(|l| l == stderr.trim_end()),
            "docs/cli.md does not show the refusal: {stderr}"
        );
        // The thresholds the help text gives are those docs/cli.md gives.
        let help = robowire("decode omnitiles --help");
        let help = String::from_utf8(help.stdout).unwrap().replace('\n', " ");
        let percent = help
            .split("over ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .expect("a share in the help text");
        let rule = format!("over {percent} % of the bytes that are not `00` skipped");
        assert!(text.contains(&rule), "docs/cli.md lacks {rule:?}");
        assert!(help.contains("over 8 rejected candidates per frame"));
        assert!(text.contains("or over 8 rejected candidates per frame"));
    }
}

/// docs/performance.md describes the present: short, no history of commits
/// and sessions, and every bench row it quotes is a row the benches have.
#[test]
fn the_performance_guide_quotes_the_benches_as_they_are() {
    let guide = read(&root().join("docs/performance.md"));
    let lines = guide.lines().count();
    assert!(lines <= 350, "docs/performance.md has {lines} lines");
    for history in ["commit `", "| before", "session of"] {
        assert!(
            !guide.to_lowercase().contains(history),
            "docs/performance.md speaks of history ({history:?})"
        );
    }
    let benches: String = ["omnitiles", "pixy2", "telemetrix"]
        .iter()
        .map(|b| read(&root().join(format!("benches/{b}.rs"))))
        .collect();
    let mut quoted = 0;
    for row in guide.lines().filter_map(|l| l.strip_prefix("| `")) {
        let id = row.split('`').next().unwrap_or_default();
        if id.contains('/') {
            assert!(
                benches.contains(&format!("\"{id}\"")),
                "docs/performance.md quotes a bench row `{id}` that no bench has"
            );
            quoted += 1;
        }
    }
    assert_eq!(quoted, 25, "every row of the three groups, once");
}
