//! `robowire decode --format csv` and `--format mcap`: the files read back
//! with the `csv` and `mcap` crates hold exactly what the JSON lines say, on
//! every sample capture of every protocol; `--timestamps` and its replay.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data, data_arg, run, scratch};
use serde_json::Value;
use std::collections::HashMap;
use std::path::Path;

/// The sample captures, with the arguments that decode them.
/// The sample captures exported, with the options that decode them right
/// (SPI buffers need their layout: the default ones are refused on them).
const CAPTURES: [(&str, &str, &[&str]); 4] = [
    ("omnitiles", "ble_telemetry.bin", &[]),
    (
        "omnitiles",
        "spi_telemetry.bin",
        &["--layout", "auto,spi45"],
    ),
    ("omnitiles", "host_commands.bin", &[]),
    ("telemetrix", "telemetrix_reports.bin", &[]),
];

/// The JSON lines of a plain decode (with `extra` options).
fn json_lines(protocol: &str, capture: &str, extra: &[&str]) -> Vec<String> {
    let input = data_arg(capture);
    let mut args = vec!["decode", protocol, "--errors", &input];
    args.extend_from_slice(extra);
    let out = run(&args, b"");
    assert_eq!(out.code, 0, "{}", out.stderr);
    out.lines().into_iter().map(str::to_owned).collect()
}

/// The table a JSON event belongs to: its type, or `rejected-ERROR`.
fn kind(value: &Value) -> String {
    match value.get("type") {
        Some(t) => t.as_str().unwrap().to_owned(),
        None => format!("rejected-{}", value["error"].as_str().unwrap()),
    }
}

/// `value` flattened as the CSV format promises: nested names joined with
/// dots, array elements by index, null empty.
fn flatten(prefix: &str, value: &Value, out: &mut Vec<(String, Value)>) {
    let name = |key: &str| {
        if prefix.is_empty() {
            key.to_owned()
        } else {
            format!("{prefix}.{key}")
        }
    };
    match value {
        Value::Object(members) => {
            for (key, member) in members {
                flatten(&name(key), member, out);
            }
        }
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                flatten(&name(&i.to_string()), item, out);
            }
        }
        leaf => out.push((prefix.to_owned(), leaf.clone())),
    }
}

/// A CSV cell holds `value`: the same text, the same number, or empty for null.
fn same_cell(cell: &str, value: &Value) -> bool {
    match value {
        Value::Null => cell.is_empty(),
        Value::String(s) => cell == s,
        Value::Bool(b) => cell == b.to_string(),
        Value::Number(n) => cell.parse::<f64>().ok() == n.as_f64(),
        _ => false,
    }
}

#[test]
fn csv_tables_hold_every_json_line() {
    for (protocol, capture, options) in CAPTURES {
        let dir = scratch(&format!("export-csv-{capture}"));
        let dir_arg = dir.to_str().unwrap();
        let input = data_arg(capture);
        let args = [
            "decode", protocol, "--errors", "--format", "csv", "-o", dir_arg, &input,
        ];
        let out = run(&[&args[..], options].concat(), b"");
        assert_eq!(out.code, 0, "{}", out.stderr);
        assert!(out.stdout.is_empty());
        // Every row of every table, by (kind, offset); the file name says the kind.
        let mut rows: HashMap<(String, u64), (Vec<String>, Vec<String>)> = HashMap::new();
        let mut count = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let stem = path.file_stem().unwrap().to_str().unwrap().to_owned();
            if stem == "units" {
                continue;
            }
            let kind = match stem.rsplit_once('-') {
                Some((kind, n)) if n.parse::<u32>().is_ok() => kind.to_owned(),
                _ => stem.clone(),
            };
            let mut reader = csv::Reader::from_path(&path).unwrap();
            let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
            let type_column = header.iter().position(|h| h == "type");
            for record in reader.records() {
                let record = record.unwrap();
                let cells: Vec<String> = record.iter().map(String::from).collect();
                let offset = cells[0].parse().unwrap();
                // A table per pin or sensor: its rows' type is in the row.
                let kind = type_column.map_or(kind.clone(), |c| cells[c].clone());
                assert!(stem.starts_with(&kind), "{stem}: a {kind} row");
                rows.insert((kind, offset), (header.clone(), cells));
                count += 1;
            }
        }
        let lines = json_lines(protocol, capture, options);
        assert_eq!(count, lines.len(), "{capture}: one row per JSON line");
        for line in &lines {
            let value: Value = serde_json::from_str(line).unwrap();
            let offset = value["offset"].as_u64().unwrap();
            let (header, cells) = &rows[&(kind(&value), offset)];
            let mut expected = Vec::new();
            flatten("", &value, &mut expected);
            // serde_json's maps are sorted by key; the CSV keeps the serde order.
            let mut named: Vec<(&String, &String)> = header.iter().zip(cells).collect();
            named.sort();
            expected.sort_by(|a, b| a.0.cmp(&b.0));
            assert_eq!(named.len(), expected.len(), "{capture}: {line}");
            for ((name, cell), (want_name, want)) in named.iter().zip(&expected) {
                assert_eq!(*name, want_name, "{capture}: {line}");
                assert!(
                    same_cell(cell, want),
                    "{capture}: {name} = {cell:?}, want {want}"
                );
            }
        }
    }
}

#[test]
fn csv_units_name_every_column_of_every_table() {
    for (protocol, capture, options) in CAPTURES {
        let dir = scratch(&format!("export-csv-units-{capture}"));
        let input = data_arg(capture);
        let args = [
            "decode",
            protocol,
            "--errors",
            "--timestamps",
            "--format",
            "csv",
            "-o",
            dir.to_str().unwrap(),
            &input,
        ];
        let out = run(&[&args[..], options].concat(), b"");
        assert_eq!(out.code, 0, "{}", out.stderr);
        let mut units: HashMap<String, Vec<(String, String)>> = HashMap::new();
        let mut reader = csv::Reader::from_path(dir.join("units.csv")).unwrap();
        assert_eq!(
            reader.headers().unwrap(),
            vec!["table", "column", "unit", "description"]
        );
        for record in reader.records() {
            let record = record.unwrap();
            units
                .entry(record[0].to_owned())
                .or_default()
                .push((record[1].to_owned(), record[2].to_owned()));
        }
        let mut tables = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let stem = path.file_stem().unwrap().to_str().unwrap().to_owned();
            if stem == "units" {
                continue;
            }
            tables += 1;
            let mut reader = csv::Reader::from_path(&path).unwrap();
            let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
            let described: Vec<&String> = units[&stem].iter().map(|(c, _)| c).collect();
            assert_eq!(
                described,
                header.iter().collect::<Vec<_>>(),
                "{capture} {stem}"
            );
        }
        assert_eq!(units.len(), tables, "{capture}");
        if capture == "ble_telemetry.bin" {
            let text = std::fs::read_to_string(dir.join("units.csv")).unwrap();
            assert!(text.contains("\ntelemetry,imu.az,m/s²,"), "{text}");
            assert!(text.contains("\ntelemetry,uwb.3,mm,"), "{text}");
        }
        assert_eq!(
            units
                .values()
                .flatten()
                .filter(|(c, u)| c == "t" && u == "s")
                .count(),
            tables
        );
    }
}

#[test]
fn csv_keeps_nested_fields_in_serde_order_and_nulls_empty() {
    let dir = scratch("export-csv-order");
    let input = data_arg("ble_telemetry.bin");
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--format",
            "csv",
            "-o",
            dir.to_str().unwrap(),
            &input,
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    let mut reader = csv::Reader::from_path(dir.join("telemetry.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        header[..12],
        [
            "offset", "len", "type", "layout", "m1_pos", "m2_pos", "uwb.0", "uwb.1", "uwb.2",
            "uwb.3", "tof", "imu.ax"
        ]
    );
    let first = reader.records().next().unwrap().unwrap();
    assert_eq!(&first[9], "", "uwb[3] is null in the first frame");
}

/// Every row of the tables in `dir` whose name starts with `prefix`, by the
/// `frame` they belong to, each as its column → cell map.
fn rows_by_frame(dir: &Path, prefix: &str) -> HashMap<u64, Vec<HashMap<String, String>>> {
    let mut rows: HashMap<u64, Vec<HashMap<String, String>>> = HashMap::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let stem = path.file_stem().unwrap().to_str().unwrap();
        let table = stem.rsplit_once('-').map_or(stem, |(table, _)| table);
        if table != prefix {
            continue;
        }
        let mut reader = csv::Reader::from_path(&path).unwrap();
        let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
        for record in reader.records() {
            let row: HashMap<String, String> = header
                .iter()
                .cloned()
                .zip(record.unwrap().iter().map(String::from))
                .collect();
            rows.entry(row["frame"].parse().unwrap())
                .or_default()
                .push(row);
        }
    }
    for frame in rows.values_mut() {
        frame.sort_by_key(|row| row["element"].parse::<u64>().ok());
    }
    rows
}

#[test]
fn pixy2_lists_are_a_row_per_element_with_the_frame_index() {
    let dir = scratch("export-csv-pixy2");
    // The sample conversation, then a frame with no blocks and one with no features.
    let mut capture = std::fs::read_to_string(data("pixy2_conversation.hex")).unwrap();
    capture.push_str("af c1 21 00 00 00\naf c1 31 00 00 00\n");
    let input = dir.join("conversation.hex");
    std::fs::write(&input, capture).unwrap();
    let input = input.to_str().unwrap();
    let tables = dir.join("tables");
    let args = ["decode", "pixy2", "--hex", "--format", "csv", "-o"];
    let out = run(
        &[&args[..], &[tables.to_str().unwrap(), input]].concat(),
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    let lines = run(&["decode", "pixy2", "--hex", input], b"").json();
    let blocks = rows_by_frame(&tables, "blocks");
    let lists = ["vectors", "intersections", "barcodes"]
        .map(|list| (list, rows_by_frame(&tables, &format!("features_{list}"))));
    let mut seen = [0; 2];
    for (frame, line) in lines.iter().enumerate() {
        let frame = frame as u64;
        // The frame's elements of each list, in wire order.
        let elements: Vec<(&HashMap<u64, _>, Vec<&Value>)> = match line["type"].as_str() {
            Some("blocks") => {
                seen[0] += 1;
                vec![(&blocks, line["blocks"].as_array().unwrap().iter().collect())]
            }
            Some("features") => {
                seen[1] += 1;
                let sections = line["sections"].as_array().unwrap();
                lists
                    .iter()
                    .map(|(list, rows)| {
                        (
                            rows,
                            sections
                                .iter()
                                .filter_map(|s| s.get(list))
                                .flat_map(|l| l.as_array().unwrap())
                                .collect(),
                        )
                    })
                    .collect()
            }
            _ => {
                assert!(!blocks.contains_key(&frame), "{line}");
                continue;
            }
        };
        for (rows, elements) in elements {
            let rows = &rows[&frame];
            assert_eq!(rows.len(), elements.len().max(1), "{line}");
            for row in rows {
                assert_eq!(row["offset"], line["offset"].to_string(), "{line}");
                assert_eq!(row["type"], line["type"].as_str().unwrap());
            }
            if elements.is_empty() {
                assert!(
                    rows[0].iter().all(|(column, cell)| cell.is_empty()
                        || ["frame", "offset", "len", "type", "checksum"]
                            .contains(&column.as_str())),
                    "{rows:?}"
                );
            }
            for (i, (row, element)) in rows.iter().zip(elements).enumerate() {
                assert_eq!(row["element"], i.to_string());
                let mut fields = Vec::new();
                flatten("", element, &mut fields);
                for (name, value) in fields {
                    assert!(
                        same_cell(&row[&name], &value),
                        "{line}: {name} = {}",
                        row[&name]
                    );
                }
            }
        }
    }
    assert_eq!(seen, [7, 7], "the sample's and the added frames");
    assert_eq!(blocks[&(lines.len() as u64 - 2)][0]["element"], "");
    let units = std::fs::read_to_string(tables.join("units.csv")).unwrap();
    assert!(units.contains("blocks,x,px,Centre column."), "{units}");
    assert!(units.contains("features_vectors,x0,grid cells,"), "{units}");
}

#[test]
fn csv_needs_a_directory() {
    let input = data_arg("ble_telemetry.bin");
    let out = run(&["decode", "omnitiles", "--format", "csv", &input], b"");
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("-o DIR"), "{}", out.stderr);
}

/// Every message of an MCAP file: (topic, schema name, schema, log time, data).
fn mcap_messages(bytes: &[u8]) -> Vec<(String, String, Value, u64, String)> {
    mcap::MessageStream::new(bytes)
        .unwrap()
        .map(|message| {
            let message = message.unwrap();
            let schema = message.channel.schema.clone().unwrap();
            assert_eq!(schema.encoding, "jsonschema");
            assert_eq!(message.channel.message_encoding, "json");
            (
                message.channel.topic.clone(),
                schema.name.clone(),
                serde_json::from_slice(&schema.data).unwrap(),
                message.log_time,
                String::from_utf8(message.data.to_vec()).unwrap(),
            )
        })
        .collect()
}

/// `value` is valid for `schema` (the subset of JSON Schema the derived
/// schemas use: `type`, `properties`, `items`), and the first value of each
/// type has every member listed.
fn check_schema(schema: &Value, value: &Value, all_listed: bool, line: &str) {
    let json_type = match value {
        Value::Null => "null",
        Value::Bool(_) => "boolean",
        Value::Number(n) if n.is_f64() => "number",
        Value::Number(_) => "integer",
        Value::String(_) => "string",
        Value::Array(_) => "array",
        Value::Object(_) => "object",
    };
    if let Some(types) = schema.get("type") {
        let allowed = |t: &Value| t == json_type || (t == "number" && json_type == "integer");
        let ok = match types {
            Value::Array(types) => types.iter().any(allowed),
            one => allowed(one),
        };
        assert!(ok, "{value} is not a {types}: {line}");
    }
    match value {
        Value::Object(members) => {
            let properties = &schema["properties"];
            for (key, member) in members {
                match properties.get(key) {
                    Some(property) => check_schema(property, member, all_listed, line),
                    None => assert!(!all_listed, "{key} is not in the schema: {line}"),
                }
            }
        }
        Value::Array(items) => {
            for item in items {
                check_schema(&schema["items"], item, all_listed, line);
            }
        }
        _ => {}
    }
}

#[test]
fn mcap_messages_are_the_json_lines() {
    for (protocol, capture, options) in CAPTURES {
        let dir = scratch(&format!("export-mcap-{capture}"));
        let path = dir.join("out.mcap");
        let input = data_arg(capture);
        let args = [
            "decode",
            protocol,
            "--errors",
            "--format",
            "mcap",
            "-o",
            path.to_str().unwrap(),
            &input,
        ];
        let out = run(&[&args[..], options].concat(), b"");
        assert_eq!(out.code, 0, "{}", out.stderr);
        let messages = mcap_messages(&std::fs::read(&path).unwrap());
        let lines = json_lines(protocol, capture, options);
        assert_eq!(messages.len(), lines.len(), "{capture}");
        let mut seen = std::collections::HashSet::new();
        for (i, ((topic, schema_name, schema, log_time, data), line)) in
            messages.iter().zip(&lines).enumerate()
        {
            assert_eq!(data, line);
            let value: Value = serde_json::from_str(line).unwrap();
            let kind = value
                .get("type")
                .map_or("rejected", |t| t.as_str().unwrap());
            // A topic per pin, sensor and module, a topic per type otherwise.
            let table = match protocol {
                "telemetrix" => &robowire::telemetrix::FIELD_INFO,
                _ => &robowire::omnitiles::FIELD_INFO,
            };
            let expected = match table.entity_key(kind) {
                Some(key) => format!("/{protocol}/{kind}/{}", value[key]),
                None => format!("/{protocol}/{kind}"),
            };
            assert_eq!(topic, &expected, "{line}");
            assert_eq!(schema_name, kind);
            let first = seen.insert(topic.clone());
            check_schema(schema, &value, first, line);
            assert_eq!(
                *log_time, i as u64,
                "without times, the log time is the index"
            );
        }
    }
}

#[test]
fn a_file_without_times_says_so_and_start_gives_wall_clock_log_times() {
    let dir = scratch("export-mcap-start");
    let input = data_arg("ble_telemetry.bin");
    let untimed = dir.join("untimed.mcap");
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--format",
            "mcap",
            "-o",
            untimed.to_str().unwrap(),
            &input,
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(
        out.stderr
            .contains("no receive times, so the log times are frame indices")
            && out.stderr.contains("--timestamps")
            && out.stderr.contains("--start TIME"),
        "{}",
        out.stderr
    );
    let timed = dir.join("timed.mcap");
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--timestamps",
            "--start",
            "2026-12-06T12:00:00Z",
            "--format",
            "mcap",
            "-o",
            timed.to_str().unwrap(),
            &input,
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(!out.stderr.contains("log times"), "{}", out.stderr);
    let bytes = std::fs::read(&timed).unwrap();
    let start = 1_796_558_400_000_000_000u64;
    for (_, _, _, log_time, data) in mcap_messages(&bytes) {
        let t: Value = serde_json::from_str(&data).unwrap();
        let micros = (t["t"].as_f64().unwrap() * 1e6).round() as u64;
        assert_eq!(log_time, start + micros * 1000);
    }
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    let metadata = mcap::read::metadata(&bytes, &summary.metadata_indexes[0])
        .unwrap()
        .metadata;
    assert_eq!(metadata["start"], "2026-12-06T12:00:00.000000000Z");
    assert_eq!(
        metadata["time_source"],
        "estimated from the byte offset at the baud rate"
    );
    assert!(metadata["input"].ends_with("ble_telemetry.bin"));
    // --start needs a time source.
    let out = run(&["decode", "omnitiles", "--start", "0", &input], b"");
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("--timestamps"), "{}", out.stderr);
}

#[test]
fn topics_type_keeps_a_channel_per_message_type() {
    let dir = scratch("export-mcap-topics");
    let input = data_arg("telemetrix_reports.bin");
    let topics = |extra: &[&str], name: &str| {
        let path = dir.join(name);
        let args = [
            &[
                "decode",
                "telemetrix",
                "--format",
                "mcap",
                "-o",
                path.to_str().unwrap(),
            ][..],
            extra,
            &[&input],
        ]
        .concat();
        let out = run(&args, b"");
        assert_eq!(out.code, 0, "{}", out.stderr);
        let mut topics: Vec<String> = mcap_messages(&std::fs::read(&path).unwrap())
            .into_iter()
            .map(|m| m.0)
            .collect();
        topics.sort();
        topics.dedup();
        topics
    };
    let by_entity = topics(&[], "entity.mcap");
    for topic in [
        "/telemetrix/analog_report/26",
        "/telemetrix/analog_report/27",
        "/telemetrix/digital_report/10",
        "/telemetrix/sensor_report/0",
        "/telemetrix/sensor_report/1",
        "/telemetrix/pong",
    ] {
        assert!(
            by_entity.contains(&topic.to_owned()),
            "{topic}: {by_entity:?}"
        );
    }
    let by_type = topics(&["--topics", "type"], "type.mcap");
    assert!(
        by_type.contains(&"/analog_report".to_owned()),
        "{by_type:?}"
    );
    assert!(
        by_type.contains(&"/sensor_report".to_owned()),
        "{by_type:?}"
    );
    assert!(
        by_type.iter().all(|t| t.matches('/').count() == 1),
        "{by_type:?}"
    );
}

#[test]
fn mcap_log_times_are_the_receive_times() {
    let dir = scratch("export-mcap-times");
    let path = dir.join("out.mcap");
    let input = data_arg("ble_telemetry.bin");
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--timestamps",
            "--baud",
            "9600",
            "--format",
            "mcap",
            "-o",
            path.to_str().unwrap(),
            &input,
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    let messages = mcap_messages(&std::fs::read(&path).unwrap());
    let lines = json_lines(
        "omnitiles",
        "ble_telemetry.bin",
        &["--timestamps", "--baud", "9600"],
    );
    let lines: Vec<&String> = lines.iter().filter(|l| l.contains("\"type\"")).collect();
    assert_eq!(messages.len(), lines.len());
    for ((_, _, _, log_time, data), line) in messages.iter().zip(lines) {
        assert_eq!(data, line);
        let value: Value = serde_json::from_str(line).unwrap();
        let t = value["t"].as_f64().unwrap();
        assert_eq!(*log_time, (t * 1e9).round() as u64);
    }
}

#[test]
fn mcap_to_a_pipe_is_a_complete_file() {
    let input = data_arg("telemetrix_reports.bin");
    let out = run(&["decode", "telemetrix", "--format", "mcap", &input], b"");
    assert_eq!(out.code, 0, "{}", out.stderr);
    let frames = json_lines("telemetrix", "telemetrix_reports.bin", &[])
        .iter()
        .filter(|l| l.contains("\"type\""))
        .count();
    assert_eq!(mcap_messages(&out.stdout).len(), frames);
}

/// `--timestamps` on a file: the end of each frame at 10 bits per byte.
#[test]
fn timestamps_estimate_from_the_baud_rate() {
    let lines = json_lines(
        "omnitiles",
        "ble_telemetry.bin",
        &["--timestamps", "--baud", "115200"],
    );
    let plain = json_lines("omnitiles", "ble_telemetry.bin", &[]);
    assert_eq!(lines.len(), plain.len());
    for (line, plain) in lines.iter().zip(&plain) {
        let mut value: Value = serde_json::from_str(line).unwrap();
        let t = value
            .as_object_mut()
            .unwrap()
            .remove("t")
            .unwrap()
            .as_f64()
            .unwrap();
        assert_eq!(value, serde_json::from_str::<Value>(plain).unwrap());
        let end = match value.get("len") {
            Some(len) => value["offset"].as_u64().unwrap() + len.as_u64().unwrap(),
            None => value["offset"].as_u64().unwrap() + 1,
        };
        let want = end as f64 * 10.0 / 115_200.0;
        assert!((t - want).abs() < 1e-6, "{t} vs {want}: {line}");
    }
}

/// A `--save`d capture replays with the times of its index, and the lines
/// with times encode back to the same frames.
#[test]
fn a_saved_capture_replays_with_its_times() {
    let dir = scratch("export-save");
    let saved = dir.join("capture.bin");
    let input = std::fs::read(cli_common::data("ble_telemetry.bin")).unwrap();
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--timestamps",
            "--baud",
            "57600",
            "--chunk",
            "1",
            "--save",
            saved.to_str().unwrap(),
        ],
        &input,
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(std::fs::read(&saved).unwrap(), input);
    let index = std::fs::read_to_string(Path::new(&format!("{}.times", saved.display()))).unwrap();
    assert!(index.starts_with("# robowire receive times"));
    // Replay: the same lines, times and all, now from the index.
    let replay = run(
        &[
            "decode",
            "omnitiles",
            "--timestamps",
            saved.to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(replay.code, 0, "{}", replay.stderr);
    assert_eq!(replay.text(), out.text());
    // Lines with "t" encode as lines without it do.
    let encoded = run(&["encode", "omnitiles"], &replay.stdout);
    let plain = run(
        &["decode", "omnitiles", &data_arg("ble_telemetry.bin")],
        b"",
    );
    let encoded_plain = run(&["encode", "omnitiles"], &plain.stdout);
    assert_eq!(encoded.code, 0, "{}", encoded.stderr);
    assert_eq!(encoded.stdout, encoded_plain.stdout);
}

/// SPI buffers read with the default layouts are refused in every format:
/// the MCAP recording is complete and holds no message, exit status 3.
#[test]
fn refused_spi_buffers_record_nothing() {
    let dir = scratch("export-spi-refused");
    let path = dir.join("out.mcap");
    let input = data_arg("spi_telemetry.bin");
    let out = run(
        &[
            "decode",
            "omnitiles",
            "--format",
            "mcap",
            "-o",
            path.to_str().unwrap(),
            &input,
        ],
        b"",
    );
    assert_eq!(out.code, 3, "{}", out.stderr);
    assert!(out.stderr.contains("--layout spi45"), "{}", out.stderr);
    assert!(mcap_messages(&std::fs::read(&path).unwrap()).is_empty());
}

#[test]
fn an_earlier_recording_is_not_written_over_without_force() {
    let dir = scratch("export-force");
    let input = data_arg("ble_telemetry.bin");
    let mcap = dir.join("tile.mcap");
    let mcap = mcap.to_str().unwrap();
    let args = [
        "decode",
        "omnitiles",
        "--format",
        "mcap",
        "-o",
        mcap,
        &input,
    ];
    assert_eq!(run(&args, b"").code, 0);
    let first = std::fs::read(mcap).unwrap();
    let again = run(&args, b"");
    assert_eq!(again.code, 2);
    assert!(
        again.stderr.starts_with(&format!(
            "error: {mcap} exists: robowire does not write over an earlier recording; \
             name another or add --force\n"
        )),
        "a usage error: {}",
        again.stderr
    );
    assert_eq!(std::fs::read(mcap).unwrap(), first, "the file is untouched");
    assert_eq!(run(&[&args[..], &["--force"]].concat(), b"").code, 0);
    // A CSV directory that holds files, and a --save capture's index.
    let tables = dir.join("tables");
    let tables = tables.to_str().unwrap();
    let csv = [
        "decode",
        "omnitiles",
        "--format",
        "csv",
        "-o",
        tables,
        &input,
    ];
    assert_eq!(run(&csv, b"").code, 0);
    let again = run(&csv, b"");
    assert_eq!(again.code, 2);
    assert!(
        again.stderr.contains("tables is not empty"),
        "{}",
        again.stderr
    );
    let save = dir.join("capture.bin");
    std::fs::write(dir.join("capture.bin.times"), b"").unwrap();
    let saving = [
        "decode",
        "omnitiles",
        "--timestamps",
        "--save",
        save.to_str().unwrap(),
        &input,
    ];
    let refused = run(&saving, b"");
    assert_eq!(refused.code, 2);
    assert!(refused.stderr.contains("capture.bin.times exists"));
    assert!(
        !save.exists(),
        "nothing is written when one output is refused"
    );
    // A device is written as always.
    let null = ["decode", "omnitiles", "-o", "/dev/null", &input];
    assert_eq!(run(&null, b"").code, 0);
}

/// The compression of every chunk of an MCAP file (`""` for none).
fn chunk_compressions(bytes: &[u8]) -> Vec<String> {
    mcap::read::LinearReader::new(bytes)
        .unwrap()
        .filter_map(|record| match record.unwrap() {
            mcap::records::Record::Chunk { header, .. } => Some(header.compression),
            _ => None,
        })
        .collect()
}

#[test]
fn mcap_chunks_are_zstd_unless_asked_otherwise() {
    let dir = scratch("export-compression");
    let input = data_arg("ble_telemetry.bin");
    let mut recorded = Vec::new();
    for (asked, written) in [(None, "zstd"), (Some("lz4"), "lz4"), (Some("none"), "")] {
        let path = dir.join(format!("{written}.mcap"));
        let mut args = vec!["decode", "omnitiles", "--format", "mcap", "-o"];
        args.extend([path.to_str().unwrap(), &input]);
        if let Some(asked) = asked {
            args.extend(["--compression", asked]);
        }
        let out = run(&args, b"");
        assert_eq!(out.code, 0, "{}", out.stderr);
        let bytes = std::fs::read(&path).unwrap();
        let chunks = chunk_compressions(&bytes);
        assert!(!chunks.is_empty());
        assert!(chunks.iter().all(|c| c == written), "{asked:?}: {chunks:?}");
        recorded.push((bytes.len(), mcap_messages(&bytes)));
    }
    let (zstd, lz4, none) = (&recorded[0], &recorded[1], &recorded[2]);
    assert_eq!(zstd.1, none.1, "the same messages, however compressed");
    assert_eq!(lz4.1, none.1);
    assert!(zstd.0 * 3 < none.0, "zstd {} B, none {} B", zstd.0, none.0);
    // The other formats are text: --compression is refused there.
    let out = run(
        &["decode", "omnitiles", "--compression", "lz4", &input],
        b"",
    );
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("--compression is for --format mcap"));
}
