//! `robowire decode omnitiles --from host --as-firmware`: the tile's own
//! command parser, against the default robust decode.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data_arg, run};
use serde_json::{json, Value};

fn decode(args: &[&str], stdin: &[u8]) -> Vec<Value> {
    let mut all = vec!["decode", "omnitiles"];
    all.extend_from_slice(args);
    let r = run(&all, stdin);
    assert_eq!(r.code, 0, "{args:?}: {}", r.stderr);
    r.json()
}

#[test]
fn as_firmware_drops_what_the_tile_drops() {
    let input = b"76 a5 a5 31 e7 18\n";
    let robust = decode(&["--from", "host", "--hex", "--errors"], input);
    assert_eq!(
        robust,
        [
            json!({"offset":1,"error":"unknown_id","id":165}),
            json!({"offset":2,"len":4,"type":"m1_retract","speed":231}),
        ]
    );
    for chunk in ["1", "2", "4096"] {
        let tile = decode(
            &[
                "--from",
                "host",
                "--hex",
                "--errors",
                "--as-firmware",
                "--chunk",
                chunk,
            ],
            input,
        );
        assert_eq!(
            tile,
            [json!({"offset":1,"error":"unknown_id","id":165})],
            "chunk {chunk}"
        );
    }
    // Without --errors nothing is printed; the summary counts it all as
    // skipped.
    let r = run(
        &[
            "decode",
            "omnitiles",
            "--from",
            "host",
            "--hex",
            "--as-firmware",
        ],
        input,
    );
    assert_eq!((r.code, r.stdout.as_slice()), (0, &b""[..]));
    assert!(r.stderr.contains("0 frames"), "{}", r.stderr);
    assert!(r.stderr.contains("6 bytes skipped"), "{}", r.stderr);
}

#[test]
fn as_firmware_on_a_capture_is_chunking_invariant() {
    let path = data_arg("host_commands.bin");
    let robust = decode(&["--from", "host", &path], b"");
    let whole = decode(&["--from", "host", "--as-firmware", "--errors", &path], b"");
    for chunk in ["1", "7", "128"] {
        let chunked = decode(
            &[
                "--from",
                "host",
                "--as-firmware",
                "--errors",
                "--chunk",
                chunk,
                &path,
            ],
            b"",
        );
        assert_eq!(chunked, whole, "chunk {chunk}");
    }
    let executed: Vec<&Value> = whole.iter().filter(|v| v.get("type").is_some()).collect();
    assert!(executed.len() <= robust.len());
    assert!(
        executed.len() * 10 >= robust.len() * 9,
        "{}",
        executed.len()
    );
}

#[test]
fn as_firmware_is_only_for_host_bytes() {
    for args in [
        &["decode", "omnitiles", "--as-firmware"][..],
        &["decode", "omnitiles", "--from", "tile", "--as-firmware"],
        &["decode", "omnitiles", "--from", "any", "--as-firmware"],
        &[
            "decode",
            "omnitiles",
            "--from",
            "host",
            "--as-firmware",
            "--datagrams",
        ],
    ] {
        let r = run(args, b"a5 50 50\n");
        assert_eq!(r.code, 2, "{args:?}");
        assert!(r.stdout.is_empty());
        assert!(r.stderr.contains("--as-firmware"), "{args:?}: {}", r.stderr);
    }
    let help = run(&["decode", "omnitiles", "--help"], b"");
    assert!(String::from_utf8_lossy(&help.stdout).contains("--as-firmware"));
}
