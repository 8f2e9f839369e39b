//! `decode --port --foxglove`: a WebSocket client speaking the Foxglove
//! protocol (subprotocol `foxglove.sdk.v1`) against the tool on a pty pair.
//! It sees the channels advertised with their schemas, subscribes, and gets
//! message frames equal to the JSON lines; what it publishes back is
//! written to the port only with `--allow-commands`, within the rate limit,
//! and answered with a status message otherwise.

#![cfg(all(feature = "cli-foxglove", unix))]

mod cli_common;

use cli_common::live::{finish, pty_pair, serial, signal, spawn, Running};
use serde_json::{json, Value};
use serialport::{SerialPort, TTYPort};
use std::io::{BufRead, Read};
use std::net::TcpStream;
use std::time::{Duration, Instant};
use tungstenite::client::IntoClientRequest;
use tungstenite::http::HeaderValue;
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

type Socket = WebSocket<MaybeTlsStream<TcpStream>>;

/// The tool on a pty, serving on a free port, and a client connected to it.
struct Session {
    master: TTYPort,
    _slave: TTYPort,
    running: Running,
    socket: Socket,
    /// The server's line on stderr.
    banner: String,
}

fn start(extra: &[&str]) -> Session {
    let (master, slave) = pty_pair();
    let device = slave.name().unwrap();
    let mut args = vec![
        "decode",
        "omnitiles",
        "--port",
        &device,
        "--layout",
        "ble53",
        "--foxglove",
        "0",
    ];
    args.extend_from_slice(extra);
    let mut running = spawn(&args);
    let mut banner = String::new();
    running.stderr.read_line(&mut banner).unwrap();
    let port = banner
        .split("ws://127.0.0.1:")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|port| port.parse::<u16>().ok())
        .unwrap_or_else(|| panic!("no server address in {banner:?}"));
    let mut request = format!("ws://127.0.0.1:{port}")
        .into_client_request()
        .unwrap();
    request.headers_mut().insert(
        "sec-websocket-protocol",
        HeaderValue::from_static("foxglove.sdk.v1"),
    );
    let (socket, response) = tungstenite::connect(request).unwrap();
    assert_eq!(
        response.headers()["sec-websocket-protocol"],
        "foxglove.sdk.v1"
    );
    if let MaybeTlsStream::Plain(stream) = socket.get_ref() {
        stream
            .set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
    }
    let mut session = Session {
        master,
        _slave: slave,
        running,
        socket,
        banner,
    };
    let info = session.next_op("serverInfo");
    let capabilities = info["capabilities"].as_array().unwrap();
    assert!(capabilities.contains(&json!("clientPublish")), "{info}");
    session
}

impl Session {
    /// The next text message whose `op` is `op`, skipping others.
    fn next_op(&mut self, op: &str) -> Value {
        loop {
            match self.socket.read().unwrap() {
                Message::Text(text) => {
                    let value: Value = serde_json::from_str(&text).unwrap();
                    if value["op"] == op {
                        return value;
                    }
                }
                Message::Binary(_) | Message::Ping(_) | Message::Pong(_) => {}
                other => panic!("unexpected {other:?} while waiting for {op}"),
            }
        }
    }

    /// The next status message: its level (0 info, 1 warning, 2 error) and text.
    fn status(&mut self) -> (u64, String) {
        let status = self.next_op("status");
        let level = status["level"].as_u64().unwrap();
        (level, status["message"].as_str().unwrap().to_owned())
    }

    /// The next message-data frame if one arrives within `wait`.
    fn message_within(&mut self, wait: Duration) -> Option<(u32, u64, Vec<u8>)> {
        self.read_timeout(wait);
        let message = loop {
            match self.socket.read() {
                Ok(Message::Binary(data)) => break Some(message_data(&data)),
                Ok(_) => {}
                Err(tungstenite::Error::Io(e))
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                    ) =>
                {
                    break None
                }
                Err(e) => panic!("reading the socket: {e}"),
            }
        };
        self.read_timeout(Duration::from_secs(10));
        message
    }

    fn read_timeout(&mut self, wait: Duration) {
        if let MaybeTlsStream::Plain(stream) = self.socket.get_ref() {
            stream.set_read_timeout(Some(wait)).unwrap();
        }
    }

    /// Subscribe, then write telemetry frames one at a time until the server
    /// sends one to the client, then read what the frames written so far
    /// still send. The subscription is sent again while no frame arrives:
    /// the server can answer a subscription that comes right after the
    /// channel's advertisement with "Unknown channel ID" (seen on a loaded
    /// machine). The number of frames written.
    fn subscribe(&mut self, subscribe: Value, frame: &[u8]) -> usize {
        for written in 1..=100 {
            self.send(subscribe.clone());
            std::io::Write::write_all(&mut self.master, frame).unwrap();
            if self.message_within(Duration::from_millis(500)).is_some() {
                while self.message_within(Duration::from_millis(500)).is_some() {}
                return written;
            }
        }
        panic!("no message in 100 frames after subscribing");
    }

    /// The next message-data frame: subscription id, log time, payload.
    fn next_message(&mut self) -> (u32, u64, Vec<u8>) {
        loop {
            if let Message::Binary(data) = self.socket.read().unwrap() {
                return message_data(&data);
            }
        }
    }

    fn send(&mut self, value: Value) {
        self.socket
            .send(Message::Text(value.to_string().into()))
            .unwrap();
    }

    /// Advertise `topic` as client channel 7 (JSON).
    fn advertise(&mut self, topic: &str) {
        self.send(json!({"op": "advertise", "channels": [
            {"id": 7, "topic": topic, "encoding": "json", "schemaName": "robowire.command"}
        ]}));
    }

    /// Publish `payload` on client channel 7.
    fn publish(&mut self, payload: &str) {
        let mut frame = vec![0x01];
        frame.extend_from_slice(&7u32.to_le_bytes());
        frame.extend_from_slice(payload.as_bytes());
        self.socket.send(Message::Binary(frame.into())).unwrap();
    }

    /// Bytes that arrive on the master end within `wait`.
    fn written(&mut self, wait: Duration) -> Vec<u8> {
        self.master.set_timeout(Duration::from_millis(100)).unwrap();
        let deadline = Instant::now() + wait;
        let mut bytes = Vec::new();
        let mut buf = [0u8; 256];
        while Instant::now() < deadline {
            match self.master.read(&mut buf) {
                Ok(n) => bytes.extend_from_slice(&buf[..n]),
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
                Err(e) => panic!("{e}"),
            }
        }
        bytes
    }

    /// SIGTERM, then the exit status, stdout and the rest of stderr.
    fn stop(mut self) -> (Option<i32>, String, String) {
        let _ = self.socket.close(None);
        signal(&self.running.child, "TERM");
        finish(self.running)
    }
}

/// A message-data frame's subscription id, log time and payload.
fn message_data(data: &[u8]) -> (u32, u64, Vec<u8>) {
    assert_eq!(data[0], 0x01, "opcode MessageData");
    let id = u32::from_le_bytes(data[1..5].try_into().unwrap());
    let time = u64::from_le_bytes(data[5..13].try_into().unwrap());
    (id, time, data[13..].to_vec())
}

fn telemetry() -> Vec<u8> {
    std::fs::read(cli_common::data("ble_telemetry.bin")).unwrap()
}

#[test]
fn a_client_sees_the_channels_and_frames_equal_to_the_json_lines() {
    let _one = serial();
    let mut session = start(&[]);
    assert!(
        session.banner.contains("(commands off)"),
        "{}",
        session.banner
    );
    let frames = telemetry();
    let (first, rest) = frames.split_at(53 * 3);
    std::io::Write::write_all(&mut session.master, first).unwrap();
    let advertised = session.next_op("advertise");
    let channel = &advertised["channels"][0];
    assert_eq!(channel["topic"], "/omnitiles/telemetry", "{advertised}");
    assert_eq!(channel["encoding"], "json");
    assert_eq!(channel["schemaName"], "telemetry");
    assert_eq!(channel["schemaEncoding"], "jsonschema");
    let schema: Value = serde_json::from_str(channel["schema"].as_str().unwrap()).unwrap();
    assert_eq!(
        schema["properties"]["m1_pos"]["unit"], "ADC counts",
        "{schema}"
    );
    let subscribe = json!({"op": "subscribe", "subscriptions": [
        {"id": 3, "channelId": channel["id"]}
    ]});
    let probes = session.subscribe(subscribe, &first[..53]);
    let sent = &rest[..53 * 20];
    std::io::Write::write_all(&mut session.master, sent).unwrap();
    let received: Vec<_> = (0..20).map(|_| session.next_message()).collect();
    std::thread::sleep(Duration::from_millis(200));
    let (code, stdout, _) = session.stop();
    assert_eq!(code, Some(0));
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 3 + probes + 20);
    let lines = &lines[3 + probes..];
    for ((id, log_time, payload), line) in received.iter().zip(lines) {
        assert_eq!(*id, 3);
        assert_eq!(std::str::from_utf8(payload).unwrap(), *line);
        // Unix-time log times (the MCAP's), apart as the lines' "t" are.
        assert!(*log_time > 1_600_000_000_000_000_000, "{log_time}");
        assert_eq!((log_time - received[0].1) % 1000, 0);
    }
    let t = |line: &str| {
        serde_json::from_str::<Value>(line).unwrap()["t"]
            .as_f64()
            .unwrap()
    };
    let (t0, t19) = (t(lines[0]), t(lines[19]));
    let span = (received[19].1 - received[0].1) as f64 / 1e9;
    assert!((span - (t19 - t0)).abs() < 1e-9, "{span} vs {}", t19 - t0);
}

#[test]
fn a_publish_is_refused_while_commands_are_off() {
    let _one = serial();
    let mut session = start(&[]);
    session.advertise("/omnitiles/command");
    session.publish(r#"{"type":"m1_extend","speed":100}"#);
    let (level, message) = session.status();
    assert_eq!(level, 2, "an error: {message}");
    assert!(message.contains("--allow-commands"), "{message}");
    assert!(session.written(Duration::from_millis(500)).is_empty());
    let (code, _, stderr) = session.stop();
    assert_eq!(code, Some(0));
    assert!(
        stderr.contains("0 commands written to the port, 1 refused"),
        "{stderr}"
    );
}

#[test]
fn commands_back_are_encoded_and_written_and_bad_ones_answered() {
    let _one = serial();
    let mut session = start(&["--allow-commands"]);
    assert!(
        session.banner.contains("commands on /omnitiles/command"),
        "{}",
        session.banner
    );
    session.advertise("/omnitiles/command");
    session.publish(r#"{"type":"m1_extend","speed":100}"#);
    assert_eq!(
        session.written(Duration::from_millis(500)),
        [0xa5, 0x30, 0x64, 0x94]
    );
    // Not a message of the protocol, not JSON: a status each, nothing written.
    session.publish(r#"{"type":"m1_extend","speed":300}"#);
    let (level, message) = session.status();
    assert_eq!(level, 2, "{message}");
    assert!(message.contains("not a command"), "{message}");
    session.publish("{not json");
    let (_, message) = session.status();
    assert!(message.contains("not valid JSON"), "{message}");
    // Telemetry is what the tile sends: a valid message, but not a command.
    session.publish(r#"{"type":"telemetry","layout":"pos7","m1_pos":100,"m2_pos":200}"#);
    let (level, message) = session.status();
    assert_eq!(level, 2, "{message}");
    assert!(message.contains("a message the device sends"), "{message}");
    assert!(session.written(Duration::from_millis(300)).is_empty());
    let (code, _, stderr) = session.stop();
    assert_eq!(code, Some(0));
    assert!(
        stderr.contains("1 commands written to the port, 3 refused"),
        "{stderr}"
    );
}

#[test]
fn commands_on_another_topic_or_over_the_rate_are_not_written() {
    let _one = serial();
    let mut session = start(&["--allow-commands", "--command-rate", "2"]);
    session.advertise("/cmd_vel");
    session.publish(r#"{"type":"m1_extend","speed":100}"#);
    let (_, message) = session.status();
    assert!(
        message.contains("commands on /omnitiles/command only"),
        "{message}"
    );
    session.send(json!({"op": "unadvertise", "channelIds": [7]}));
    session.advertise("/omnitiles/command");
    for _ in 0..5 {
        session.publish(r#"{"type":"m1_extend","speed":100}"#);
    }
    let (level, message) = session.status();
    assert_eq!(level, 1, "a warning: {message}");
    assert!(message.contains("--command-rate"), "{message}");
    // The burst of two went out; the other three did not.
    assert_eq!(
        session.written(Duration::from_millis(500)),
        [0xa5, 0x30, 0x64, 0x94].repeat(2)
    );
    let (code, _, _) = session.stop();
    assert_eq!(code, Some(0));
}

#[test]
fn commands_need_the_server_and_the_server_needs_a_port() {
    let out = cli_common::run(&["decode", "omnitiles", "--foxglove"], &telemetry());
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(out.stderr.contains("--port"), "{}", out.stderr);
    let out = cli_common::run(&["decode", "omnitiles", "--allow-commands"], b"");
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(out.stderr.contains("--foxglove"), "{}", out.stderr);
}
