//! `--format mcap`: an MCAP recording (the ROS 2 and Foxglove file format)
//! with one channel per topic (`/PROTOCOL/TYPE/ENTITY` for a pin's, a
//! sensor's or a module's messages, `/PROTOCOL/TYPE` for the others,
//! rejections on `/PROTOCOL/rejected`; `/TYPE` with `--topics type`), JSON
//! message encoding, each message exactly the JSON line
//! the default format prints. Each channel's JSON Schema comes from
//! [`json_schema`](crate::json_schema): exact types, units and descriptions
//! from the protocol's field table. Log and publish times are the receive
//! time in nanoseconds when there is one (`--port`, `--timestamps`),
//! otherwise the frame's index. A live run closes a chunk at least once a
//! second, so a recording cut short (SIGKILL, a power loss) is readable up to
//! its last second from its start, without the summary.

use crate::Failure;
use mcap::records::MessageHeader;
use mcap::write::{NoSeek, WriteOptions, Writer};
use std::collections::{BTreeMap, HashMap};
use std::io::{self, Write};
use std::time::{Duration, Instant};

/// How long a chunk stays open on a live run: a recording cut short (a
/// killed process, a power loss) is readable up to its last closed chunk.
const CHUNK_PERIOD: Duration = Duration::from_millis(800);

/// An MCAP recording being written.
pub struct Recording {
    name: String,
    writer: Option<Writer<NoSeek<Box<dyn Write>>>>,
    /// Each topic's channel and its next sequence number.
    channels: HashMap<String, (u16, u32)>,
    /// When the open chunk got its first message.
    chunk_opened: Option<Instant>,
}

impl Recording {
    /// Start a recording on `out`, called `name` in messages, its chunks
    /// compressed with `compression`. The writer never seeks, so `out` may
    /// be a pipe.
    pub fn create(
        name: String,
        out: Box<dyn Write>,
        compression: Option<mcap::Compression>,
    ) -> Result<Recording, Failure> {
        let options = WriteOptions::new()
            .compression(compression)
            // One thread at level 1: the writer is fed one message at a
            // time, and the default (level 3 on a thread per core) cost
            // 2.4x the CPU of level 1 for a larger file (measured).
            .compression_threads(0)
            .compression_level(1)
            .profile("")
            .library(concat!("robowire ", env!("CARGO_PKG_VERSION")))
            .disable_seeking(true);
        let writer = options
            .create(NoSeek::new(out))
            .map_err(|error| failure(&name, error))?;
        Ok(Recording {
            name,
            writer: Some(writer),
            channels: HashMap::new(),
            chunk_opened: None,
        })
    }

    /// Record `json` (one JSON object: a frame, or a rejection when `kind`
    /// is `rejected`) on `topic` at `nanoseconds`; `schema` gives the JSON
    /// Schema of its channel (its bytes) when it is the first on it.
    pub fn write(
        &mut self,
        kind: &str,
        topic: &str,
        json: &[u8],
        nanoseconds: u64,
        schema: impl FnOnce() -> Result<Vec<u8>, Failure>,
    ) -> Result<(), Failure> {
        let Some(writer) = self.writer.as_mut() else {
            return Ok(());
        };
        let (channel, sequence) = match self.channels.get_mut(topic) {
            Some(entry) => entry,
            None => {
                let schema = schema()?;
                let schema_id = writer
                    .add_schema(kind, "jsonschema", &schema)
                    .map_err(|error| failure(&self.name, error))?;
                let channel = writer
                    .add_channel(schema_id, topic, "json", &BTreeMap::new())
                    .map_err(|error| failure(&self.name, error))?;
                self.channels
                    .entry(topic.to_owned())
                    .or_insert((channel, 0))
            }
        };
        let header = MessageHeader {
            channel_id: *channel,
            sequence: *sequence,
            log_time: nanoseconds,
            publish_time: nanoseconds,
        };
        *sequence = sequence.wrapping_add(1);
        self.chunk_opened.get_or_insert_with(Instant::now);
        writer
            .write_to_known_channel(&header, json)
            .map_err(|error| failure(&self.name, error))
    }

    /// The recording's name in messages (its path, or `stdout`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Write the `robowire` metadata record: where and when the frames
    /// came from.
    pub fn metadata(&mut self, entries: &[(&str, String)]) -> Result<(), Failure> {
        let Some(writer) = self.writer.as_mut() else {
            return Ok(());
        };
        let metadata = mcap::records::Metadata {
            name: "robowire".to_owned(),
            metadata: entries
                .iter()
                .map(|(key, value)| ((*key).to_owned(), value.clone()))
                .collect(),
        };
        writer
            .write_metadata(&metadata)
            .map_err(|error| failure(&self.name, error))
    }

    /// Close the open chunk and write it out if it has been open for
    /// [`CHUNK_PERIOD`] (called before a read that may wait, so a live
    /// recording is complete up to the last second or so at any time).
    pub fn flush(&mut self) -> Result<(), Failure> {
        let (Some(writer), Some(opened)) = (self.writer.as_mut(), self.chunk_opened) else {
            return Ok(());
        };
        if opened.elapsed() < CHUNK_PERIOD {
            return Ok(());
        }
        self.chunk_opened = None;
        writer.flush().map_err(|error| failure(&self.name, error))
    }

    /// Write the summary and the footer: the recording is complete.
    pub fn finish(&mut self) -> Result<(), Failure> {
        let Some(mut writer) = self.writer.take() else {
            return Ok(());
        };
        writer
            .finish()
            .map_err(|error| failure(&self.name, error))?;
        writer
            .into_inner()
            .into_inner()
            .flush()
            .map_err(|error| io_failure(&self.name, error))
    }
}

fn failure(name: &str, error: mcap::McapError) -> Failure {
    match error {
        mcap::McapError::Io(error) => io_failure(name, error),
        other => io_failure(name, io::Error::other(other)),
    }
}

fn io_failure(name: &str, error: io::Error) -> Failure {
    if name == "stdout" {
        Failure::stdout(error)
    } else {
        Failure::Io {
            context: name.to_owned(),
            error,
        }
    }
}
