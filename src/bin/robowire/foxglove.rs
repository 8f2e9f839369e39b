//! `decode --port DEVICE --foxglove [ADDR]`: the live decode served over the
//! Foxglove WebSocket protocol by Foxglove's own SDK (the `foxglove` crate),
//! with the channels, schemas and log times of the MCAP recording, and
//! commands back: JSON lines a client publishes on `/PROTOCOL/command`,
//! encoded as `robowire encode` does and written to the port.
//!
//! Nobody drives a robot by connecting: the server listens on loopback
//! unless an address is given, commands back are refused (with a status
//! message naming the option) unless `--allow-commands` is given, and a
//! rate limit keeps a runaway client from flooding the port. The WebSocket
//! protocol has no authentication of its own (the SDK's server offers none
//! besides TLS, which robowire does not build), so a non-loopback address
//! with commands on is warned about at start.

use crate::driver::LineEncoder;
use crate::port::PortSink;
use crate::Failure;
use clap::Args;
use foxglove::websocket::{Capability, Client, ClientChannel, ServerListener, Status};
use foxglove::{Context, PartialMetadata, RawChannel, Schema, WebSocketServerHandle};
use std::collections::HashMap;
use std::io::Write;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Where `--foxglove` listens when no address is given.
const DEFAULT_ADDR: &str = "127.0.0.1:8765";

/// Messages queued per client before the oldest are dropped: a few seconds
/// of a tile's telemetry, so a client that stalls briefly loses nothing.
const BACKLOG: usize = 8192;

/// The options of a live Foxglove view.
#[derive(Debug, Args)]
pub struct FoxgloveArgs {
    /// Serve the live decode to Foxglove through its WebSocket protocol at ADDR
    /// (HOST:PORT, or a port alone on 127.0.0.1; 127.0.0.1:8765 when
    /// omitted; port 0 picks a free one): the channels, schemas and log
    /// times of the MCAP recording. Needs --port.
    #[arg(
        long,
        value_name = "ADDR",
        num_args = 0..=1,
        default_missing_value = DEFAULT_ADDR,
        value_parser = parse_addr,
        requires = "port",
        display_order = 16
    )]
    pub foxglove: Option<SocketAddr>,
    /// Write to the port the commands a Foxglove client publishes on
    /// /PROTOCOL/command (one JSON line of `robowire encode`'s schema per
    /// message); without it they are refused with a status message.
    #[arg(long, requires = "foxglove", display_order = 17)]
    pub allow_commands: bool,
    /// At most N commands back per second (with a burst of N); the others
    /// are refused with a status message and not written.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 20,
        value_parser = clap::value_parser!(u32).range(1..=100_000),
        requires = "allow_commands",
        display_order = 18
    )]
    pub command_rate: u32,
}

/// `HOST:PORT`, or a port alone on loopback.
fn parse_addr(text: &str) -> Result<SocketAddr, String> {
    if let Ok(port) = text.parse::<u16>() {
        return Ok(SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), port));
    }
    text.parse().map_err(|_| {
        format!("expected HOST:PORT (such as {DEFAULT_ADDR} or 0.0.0.0:8765) or a port number")
    })
}

/// The running server and its channels.
pub struct LiveView {
    context: Arc<Context>,
    server: Option<WebSocketServerHandle>,
    channels: HashMap<String, Arc<RawChannel>>,
    commands: Arc<Commands>,
}

impl LiveView {
    /// Start the server `args` ask for, for `protocol`; `port` and `encode`
    /// write commands back when `--allow-commands` is given.
    pub fn start(
        args: &FoxgloveArgs,
        addr: SocketAddr,
        protocol: &'static str,
        port: (&str, u32),
        encode: LineEncoder,
    ) -> Result<LiveView, Failure> {
        let writer = if args.allow_commands {
            Some(Mutex::new(PortSink::open(port.0, port.1)?))
        } else {
            None
        };
        let commands = Arc::new(Commands {
            topic: format!("/{protocol}/command"),
            encode,
            writer,
            limit: Mutex::new(RateLimit::new(args.command_rate)),
            written: AtomicU64::new(0),
            refused: AtomicU64::new(0),
        });
        let context = Context::new();
        let server = context
            .websocket_server()
            .name(format!("robowire {protocol}"))
            .bind(addr.ip().to_string(), addr.port())
            // Publishing is always offered, so a client that tries while
            // commands are off is told which option turns them on.
            .capabilities([Capability::ClientPublish])
            .supported_encodings(["json"])
            .message_backlog_size(BACKLOG)
            .listener(Arc::clone(&commands) as Arc<dyn ServerListener>)
            .start_blocking()
            .map_err(|error| Failure::Io {
                context: format!("--foxglove {addr}: cannot start the WebSocket server"),
                error: std::io::Error::other(error),
            })?;
        let mode = if args.allow_commands {
            format!(
                "commands on {} written to {} (at most {}/s)",
                commands.topic, port.0, args.command_rate
            )
        } else {
            "commands off".to_owned()
        };
        eprintln!(
            "robowire: Foxglove WebSocket server on ws://{}:{} ({mode})",
            addr.ip(),
            server.port()
        );
        if args.allow_commands && !addr.ip().is_loopback() {
            eprintln!(
                "robowire: warning: --allow-commands on {}: anyone who can reach this address \
                 can write to {} (the WebSocket protocol has no authentication)",
                addr.ip(),
                port.0
            );
        }
        Ok(LiveView {
            context,
            server: Some(server),
            channels: HashMap::new(),
            commands,
        })
    }

    /// Send `json` on `topic` at `nanoseconds` to the clients subscribed to
    /// it; `schema` gives the channel's JSON Schema (its bytes) when it is the first.
    pub fn log(
        &mut self,
        kind: &str,
        topic: &str,
        json: &[u8],
        nanoseconds: u64,
        schema: impl FnOnce() -> Result<Vec<u8>, Failure>,
    ) -> Result<(), Failure> {
        let channel = match self.channels.get(topic) {
            Some(channel) => channel,
            None => {
                let schema = schema()?;
                let channel = self
                    .context
                    .channel_builder(topic)
                    .message_encoding("json")
                    .schema(Schema::new(kind, "jsonschema", schema))
                    .build_raw()
                    .map_err(|error| Failure::Reported(format!("cannot add {topic}: {error}")))?;
                self.channels.entry(topic.to_owned()).or_insert(channel)
            }
        };
        channel.log_with_meta(
            json,
            PartialMetadata {
                log_time: Some(nanoseconds),
            },
        );
        Ok(())
    }

    /// Stop the server (every client is sent what was queued for it first)
    /// and say how many commands went to the port.
    pub fn finish(&mut self) {
        if let Some(server) = self.server.take() {
            server.stop().wait_blocking();
            let written = self.commands.written.load(Ordering::Relaxed);
            let refused = self.commands.refused.load(Ordering::Relaxed);
            if written + refused > 0 {
                eprintln!(
                    "robowire: Foxglove: {written} commands written to the port, {refused} refused"
                );
            }
        }
    }
}

/// What the server does with the messages clients publish.
struct Commands {
    /// The one topic commands are taken on.
    topic: String,
    /// A JSON line into a frame.
    encode: LineEncoder,
    /// The port, when commands are on.
    writer: Option<Mutex<PortSink>>,
    limit: Mutex<RateLimit>,
    written: AtomicU64,
    refused: AtomicU64,
}

impl Commands {
    /// Encode and write one published message, or say why not.
    fn take(&self, channel: &ClientChannel, payload: &[u8]) -> Result<(), Status> {
        let Some(writer) = &self.writer else {
            return Err(Status::error(
                "robowire: commands are off (start robowire with --allow-commands): \
                 nothing was written",
            ));
        };
        if channel.topic != self.topic {
            return Err(Status::error(format!(
                "robowire takes commands on {} only: the message on {} was not written",
                self.topic, channel.topic
            )));
        }
        if channel.encoding != "json" {
            return Err(Status::error(format!(
                "robowire takes JSON commands: the {} message was not written",
                channel.encoding
            )));
        }
        let frame = (self.encode)(payload).map_err(|message| {
            Status::error(format!(
                "robowire: not a command, nothing written: {message}"
            ))
        })?;
        if !self
            .limit
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .admit(Instant::now())
        {
            return Err(Status::warning(
                "robowire: over --command-rate: the command was not written",
            ));
        }
        let mut port = writer.lock().unwrap_or_else(|e| e.into_inner());
        port.write_all(&frame)
            .and_then(|()| port.flush())
            .map_err(|error| {
                Status::error(format!(
                    "robowire: {}: the command could not be written: {error}",
                    port.name()
                ))
            })
    }
}

impl ServerListener for Commands {
    fn on_message_data(&self, client: Client, channel: &ClientChannel, payload: &[u8]) {
        match self.take(channel, payload) {
            Ok(()) => {
                self.written.fetch_add(1, Ordering::Relaxed);
            }
            Err(status) => {
                self.refused.fetch_add(1, Ordering::Relaxed);
                client.send_status(status);
            }
        }
    }
}

/// A token bucket: `rate` commands a second, up to `rate` at once.
struct RateLimit {
    rate: f64,
    tokens: f64,
    last: Option<Instant>,
}

impl RateLimit {
    fn new(rate: u32) -> RateLimit {
        RateLimit {
            rate: f64::from(rate),
            tokens: f64::from(rate),
            last: None,
        }
    }

    /// Whether a command arriving at `now` may go out.
    fn admit(&mut self, now: Instant) -> bool {
        if let Some(last) = self.last {
            let refill = now.saturating_duration_since(last).as_secs_f64() * self.rate;
            self.tokens = (self.tokens + refill).min(self.rate);
        }
        self.last = Some(now);
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            true
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn the_rate_limit_admits_a_burst_then_its_rate() {
        let start = Instant::now();
        let mut limit = RateLimit::new(2);
        assert!(limit.admit(start));
        assert!(limit.admit(start));
        assert!(!limit.admit(start));
        assert!(!limit.admit(start + Duration::from_millis(100)));
        assert!(limit.admit(start + Duration::from_millis(600)));
        assert!(!limit.admit(start + Duration::from_millis(600)));
    }

    #[test]
    fn an_address_is_host_and_port_or_a_port_on_loopback() {
        assert_eq!(parse_addr("9000").unwrap().to_string(), "127.0.0.1:9000");
        assert_eq!(parse_addr("0.0.0.0:1").unwrap().to_string(), "0.0.0.0:1");
        assert!(parse_addr("localhost").is_err());
    }
}
