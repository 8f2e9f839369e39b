//! The protocols' field tables (`FIELD_INFO`: units, descriptions, ranges)
//! name fields that exist: every entry's message type is one of the
//! protocol's, and its path is a field of a message the tool prints, from
//! the sample captures and from lines of the rarer messages encoded and
//! decoded back. A declared range holds every value seen.

#![cfg(feature = "cli")]

mod cli_common;

use cli_common::{data_arg, run};
use robowire::units::FieldTable;
use serde_json::Value;

/// Every `(type, path, value)` leaf and inner member of `value`.
fn paths(value: &Value, path: &str, out: &mut Vec<(String, Value)>) {
    if !path.is_empty() {
        out.push((path.to_owned(), value.clone()));
    }
    let join = |member: &str| {
        if path.is_empty() {
            member.to_owned()
        } else {
            format!("{path}.{member}")
        }
    };
    match value {
        Value::Object(members) => {
            for (name, member) in members {
                paths(member, &join(name), out);
            }
        }
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                paths(item, &join(&i.to_string()), out);
            }
        }
        _ => {}
    }
}

/// The messages the tool prints for `protocol`: its sample captures, and
/// `lines` encoded and decoded back.
fn messages(
    protocol: &str,
    captures: &[(&str, &[&str])],
    lines: &str,
    options: &[&str],
) -> Vec<Value> {
    let mut all = Vec::new();
    for (capture, extra) in captures {
        let input = data_arg(capture);
        let mut args = vec!["decode", protocol];
        args.extend_from_slice(extra);
        args.push(&input);
        let decoded = run(&args, b"");
        assert_eq!(decoded.code, 0, "{args:?}: {}", decoded.stderr);
        all.extend(decoded.json());
    }
    let encoded = run(&[&["encode", protocol], options].concat(), lines.as_bytes());
    assert_eq!(encoded.code, 0, "encode: {}", encoded.stderr);
    let decode = [&["decode", protocol, "--allow-noise"], options].concat();
    let decoded = run(&decode, &encoded.stdout);
    assert_eq!(decoded.code, 0, "decode: {}", decoded.stderr);
    let decoded = decoded.json();
    assert_eq!(decoded.len(), lines.lines().count(), "{lines}");
    all.extend(decoded);
    all
}

fn check(table: &FieldTable, names: &[&str], messages: &[Value]) {
    let mut seen: Vec<(String, String, Value)> = Vec::new();
    for message in messages {
        let kind = message["type"].as_str().expect("a type").to_owned();
        let mut fields = Vec::new();
        paths(message, "", &mut fields);
        seen.extend(fields.into_iter().map(|(p, v)| (kind.clone(), p, v)));
    }
    let mut unseen = Vec::new();
    for (message, pattern, info) in table.entries {
        assert!(
            *message == "*" || names.contains(message),
            "`{message}` is not a message type"
        );
        let matching: Vec<_> = seen
            .iter()
            .filter(|(kind, path, _)| {
                (*message == "*" || message == kind)
                    && table.get(kind, path).is_some_and(|i| std::ptr::eq(i, info))
            })
            .collect();
        if matching.is_empty() {
            unseen.push(format!("{message} {pattern}"));
        }
        if let Some((min, max)) = info.range {
            for (kind, path, value) in matching {
                if let Some(n) = value.as_i64() {
                    assert!((min..=max).contains(&n), "{kind} {path} = {n}");
                }
            }
        }
    }
    assert!(
        unseen.is_empty(),
        "no message printed has these fields: {unseen:?}"
    );
}

#[test]
fn omnitiles_fields_exist() {
    let lines = "{\"type\":\"telemetry\",\"layout\":\"uwbtof17\",\"m1_pos\":1,\"m2_pos\":null,\
                 \"uwb\":[1,2,null,4],\"tof\":null}\n";
    let messages = messages(
        "omnitiles",
        &[("ble_telemetry.bin", &[]), ("host_commands.bin", &[])],
        lines,
        &[],
    );
    check(
        &robowire::omnitiles::FIELD_INFO,
        &robowire::omnitiles::Message::NAMES,
        &messages,
    );
}

#[test]
fn pixy2_fields_exist() {
    let lines = concat!(
        "{\"type\":\"get_resolution\",\"reserved\":3}\n",
        "{\"type\":\"set_mode\",\"mode\":1}\n",
        "{\"type\":\"get_blocks\",\"sigmap\":0,\"max_blocks\":1,\"quirk\":\"sigmap_zero\"}\n",
        "{\"type\":\"set_vector\",\"index\":2}\n",
        "{\"type\":\"features\",\"sections\":[{\"intersections\":[{\"x\":4,\"y\":5,\"reserved\":1,",
        "\"lines\":[{\"index\":1,\"angle\":90,\"reserved\":2}],",
        "\"unused_slots\":[{\"index\":3,\"angle\":0},{\"index\":0,\"angle\":0},",
        "{\"index\":0,\"angle\":0},{\"index\":0,\"angle\":0},{\"index\":0,\"angle\":0}]}]},",
        "{\"ftype\":8,\"data\":[1,2]}]}\n",
    );
    let messages = messages(
        "pixy2",
        &[("pixy2_conversation.hex", &["--hex"])],
        lines,
        &[],
    );
    check(
        &robowire::pixy2::FIELD_INFO,
        &robowire::pixy2::Message::NAMES,
        &messages,
    );
}

#[test]
fn telemetrix_fields_exist() {
    let lines = concat!(
        "{\"type\":\"serial_loop_back_report\",\"byte\":7}\n",
        "{\"type\":\"i2c_write_report\",\"port\":0,\"msg_id\":1,\"result\":-1}\n",
        "{\"type\":\"i2c_read_report\",\"port\":1,\"msg_id\":2,\"reg\":3,\"data\":[4,5]}\n",
        "{\"type\":\"dht_report\",\"pin\":2,\"hum_int\":40,\"hum_hundredths\":5,",
        "\"temp_int\":-3,\"temp_hundredths\":-50}\n",
        "{\"type\":\"set_id_report\",\"id\":3}\n",
        "{\"type\":\"i2c_read_failed\",\"port\":0,\"addr\":16,\"stale\":0}\n",
        "{\"type\":\"pwm_write\",\"pins\":[{\"pin\":15,\"value\":1500}],\"trailing\":[16,5],",
        "\"quirk\":\"pwm_trailing_bytes\"}\n",
        "{\"type\":\"sensor_report\",\"sensor_num\":0,\"sensor_type\":\"hx711\",\"reading\":{\"raw\":-5}}\n",
        "{\"type\":\"sensor_report\",\"sensor_num\":1,\"sensor_type\":\"as5600\",\"reading\":{\"angles\":[0,4095]}}\n",
        "{\"type\":\"sensor_report\",\"sensor_num\":2,\"sensor_type\":\"bno055\",\"reading\":{",
        "\"gyro\":[0,0,0],\"mag\":[0,0,0],\"accel\":[0,0,9.8],\"quat\":[0,0,0,1],\"temp\":21}}\n",
        "{\"type\":\"sensor_report\",\"sensor_num\":3,\"sensor_type\":\"hmc5883l\",\"reading\":{\"field\":[1,2,3]}}\n",
        "{\"type\":\"sensor_report\",\"sensor_num\":4,\"sensor_type\":\"veml6040\",\"reading\":",
        "{\"r\":1,\"g\":2,\"b\":3,\"w\":4}}\n",
        "{\"type\":\"module_report\",\"module_num\":0,\"module_type\":\"hiwonder_servo\",",
        "\"message\":{\"subtype\":\"range\",\"idx\":1,\"min_cdeg\":0,\"max_cdeg\":24000}}\n",
        "{\"type\":\"module_report\",\"module_num\":0,\"module_type\":\"hiwonder_servo\",",
        "\"message\":{\"subtype\":\"offset\",\"idx\":1,\"offset_cdeg\":-30}}\n",
        "{\"type\":\"set_scan_delay\",\"delay_ms\":10}\n",
        "{\"type\":\"module_data\",\"module_num\":0,\"module_type\":\"hiwonder_servo\",\"message\":",
        "{\"subtype\":\"set_angle\",\"moves\":[{\"idx\":0,\"centideg\":12000,\"time_ms\":500}]}}\n",
    );
    let mut all = messages(
        "telemetrix",
        &[
            ("telemetrix_reports.bin", &[]),
            ("telemetrix_commands.hex", &["--hex"]),
        ],
        lines,
        &[],
    );
    // The older dialects' sonar reports.
    let sonar = |line: &str, dialect| messages("telemetrix", &[], line, &["--dialect", dialect]);
    all.extend(sonar(
        "{\"type\":\"sonar_distance\",\"trig\":9,\"m\":1,\"cm\":20}\n",
        "mirte12",
    ));
    all.extend(sonar(
        "{\"type\":\"sonar_distance\",\"trig\":9,\"cm\":12,\"hundredths\":34}\n",
        "upstream11",
    ));
    check(
        &robowire::telemetrix::FIELD_INFO,
        robowire::telemetrix::Message::NAMES,
        &all,
    );
}
