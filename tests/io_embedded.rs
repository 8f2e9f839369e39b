//! The embedded-io (blocking and async) packet readers and writers, against
//! in-memory UARTs with short reads and writes, read errors and ends of input.
#![cfg(any(feature = "embedded-io-07", feature = "embedded-io-async-07"))]

mod io_common;

use core::fmt;

use io_common::{engine_events, noisy_commands, noisy_telemetry, Ev, Rng};
use robowire::omnitiles::{both_decoder, device_decoder, Both, BothDecoder, Framing};

/// A UART read or write error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Glitch;

impl fmt::Display for Glitch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("framing error on the line")
    }
}

impl core::error::Error for Glitch {}

impl embedded_io::Error for Glitch {
    fn kind(&self) -> embedded_io::ErrorKind {
        embedded_io::ErrorKind::Other
    }
}

/// Receives `data`, at most `max` bytes per read. It fails once for each
/// offset in `glitches` (on the first read at or past it) and reports the end of the input once at each offset
/// in `ends` (after which more bytes arrive: a new stream).
struct Uart {
    data: Vec<u8>,
    pos: usize,
    max: usize,
    glitches: Vec<usize>,
    ends: Vec<usize>,
    reads: usize,
}

impl Uart {
    fn new(data: Vec<u8>, max: usize) -> Self {
        Uart {
            data,
            pos: 0,
            max,
            glitches: Vec::new(),
            ends: Vec::new(),
            reads: 0,
        }
    }
}

impl embedded_io::ErrorType for Uart {
    type Error = Glitch;
}

#[cfg(feature = "embedded-io-07")]
impl embedded_io::Read for Uart {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Glitch> {
        read_some(self, buf)
    }
}

#[cfg(feature = "embedded-io-async-07")]
impl embedded_io_async::Read for Uart {
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, Glitch> {
        // Make every read a real suspension point.
        tokio::task::yield_now().await;
        read_some(self, buf)
    }
}

fn read_some(uart: &mut Uart, buf: &mut [u8]) -> Result<usize, Glitch> {
    assert!(!buf.is_empty(), "the reader never asks for 0 bytes");
    uart.reads += 1;
    if uart.glitches.first().is_some_and(|&at| at <= uart.pos) {
        uart.glitches.remove(0);
        return Err(Glitch);
    }
    if uart.ends.first() == Some(&uart.pos) {
        uart.ends.remove(0);
        return Ok(0);
    }
    // Never read past the next end of input.
    let until = uart.ends.first().copied().unwrap_or(uart.data.len());
    let n = uart.max.min(buf.len()).min(until - uart.pos);
    buf[..n].copy_from_slice(&uart.data[uart.pos..uart.pos + n]);
    uart.pos += n;
    Ok(n)
}

/// Transmits into `out`, at most `max` bytes per write, failing once `out`
/// holds `fail_at` bytes.
struct Tx {
    out: Vec<u8>,
    max: usize,
    fail_at: usize,
}

impl Tx {
    fn new(max: usize) -> Self {
        Tx {
            out: Vec::new(),
            max,
            fail_at: usize::MAX,
        }
    }

    fn write_some(&mut self, buf: &[u8]) -> Result<usize, Glitch> {
        if self.out.len() >= self.fail_at {
            return Err(Glitch);
        }
        let n = self.max.min(buf.len());
        self.out.extend_from_slice(&buf[..n]);
        Ok(n)
    }
}

impl embedded_io::ErrorType for Tx {
    type Error = Glitch;
}

#[cfg(feature = "embedded-io-07")]
impl embedded_io::Write for Tx {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Glitch> {
        self.write_some(buf)
    }

    fn flush(&mut self) -> Result<(), Glitch> {
        Ok(())
    }
}

#[cfg(feature = "embedded-io-async-07")]
impl embedded_io_async::Write for Tx {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Glitch> {
        tokio::task::yield_now().await;
        self.write_some(buf)
    }

    async fn flush(&mut self) -> Result<(), Glitch> {
        Ok(())
    }
}

/// A noisy stream of commands and telemetry.
fn mixed_input(seed: u64) -> Vec<u8> {
    let mut rng = Rng::new(seed);
    let (mut bytes, _) = noisy_telemetry(&mut rng, 25);
    bytes.extend(noisy_commands(&mut rng, 40).0);
    bytes.extend([0xa5, 0x60, 0x00]); // a truncated frame at the end
    bytes
}

/// The engine's events for `input` split into streams at `ends`, each
/// finished.
fn streams_oracle(framing: Framing<Both>, input: &[u8], ends: &[usize]) -> Vec<Ev> {
    let mut decoder = BothDecoder::new(framing);
    let mut events = Vec::new();
    let mut from = 0;
    for &end in ends.iter().chain([&input.len()]) {
        events.extend(decoder.feed(&input[from..end]));
        events.extend(decoder.flush());
        from = end;
    }
    events
}

#[cfg(feature = "embedded-io-07")]
mod blocking {
    use super::*;
    use robowire::io::embedded_io::{PacketReader, PacketWriter};
    use robowire::io::WriteError;
    use robowire::omnitiles::{Command, Layout, Message, Motor, Telemetry};
    use robowire::{Encode, EncodeError};

    /// Read events until the end of the input, counting read errors.
    fn drain<B: AsRef<[u8]> + AsMut<[u8]>>(
        reader: &mut PacketReader<Uart, Framing<Both>, { robowire::omnitiles::BOTH_BUFFER }, B>,
    ) -> (Vec<Ev>, usize) {
        let (mut events, mut errors) = (Vec::new(), 0);
        loop {
            match reader.read_event() {
                Ok(Some(event)) => events.push(event),
                Ok(None) => return (events, errors),
                Err(Glitch) => errors += 1,
            }
        }
    }

    #[test]
    fn events_match_the_engine_for_any_read_size_and_buffer() {
        let input = mixed_input(3);
        let expected = engine_events(Framing::<Both>::new(), &input);
        assert!(expected.iter().any(|e| e.is_err()) && expected.iter().any(|e| e.is_ok()));
        for max in [1, 2, 3, 5, 8, 53, 64, 1000] {
            for buf_len in [1, 2, 7, 16, 64, 256] {
                let mut buf = vec![0u8; buf_len];
                let uart = Uart::new(input.clone(), max);
                let decoder = both_decoder();
                let mut reader = PacketReader::new(uart, decoder, &mut buf[..]);
                let (events, errors) = drain(&mut reader);
                assert_eq!(errors, 0);
                assert_eq!(events, expected, "reads of {max}, buffer of {buf_len}");
                let reads = reader.get_ref().reads;
                assert!(reads > input.len() / max.min(buf_len), "{reads} reads");
                assert_eq!(reader.stats().bytes, input.len() as u64);
            }
        }
    }

    #[test]
    fn read_errors_are_not_fatal() {
        let input = mixed_input(5);
        let mut uart = Uart::new(input.clone(), 7);
        uart.glitches = vec![0, 1, 100, 101, 400, input.len()];
        let mut reader = PacketReader::new(uart, both_decoder(), [0u8; 16]);
        let (events, errors) = drain(&mut reader);
        assert_eq!(errors, 6);
        assert_eq!(events, engine_events(Framing::<Both>::new(), &input));
    }

    #[test]
    fn each_end_of_input_finishes_a_stream() {
        let input = mixed_input(9);
        // Ends inside frames and between them.
        let ends = vec![30, 31, 200, 202, 203];
        let mut uart = Uart::new(input.clone(), 5);
        uart.ends = ends.clone();
        let mut reader = PacketReader::new(uart, both_decoder(), [0u8; 8]);
        let mut events = Vec::new();
        let mut streams = 0;
        while streams <= ends.len() {
            let (mut stream, errors) = drain(&mut reader);
            assert_eq!(errors, 0);
            events.append(&mut stream);
            streams += 1;
        }
        assert_eq!(
            events,
            streams_oracle(Framing::<Both>::new(), &input, &ends)
        );
        assert_eq!(reader.decoder().buffered(), 0);
        // At the end for good: still `None`, no error.
        assert!(matches!(reader.read_event(), Ok(None)));
    }

    #[test]
    fn read_message_skips_rejections() {
        let input = mixed_input(13);
        let expected = engine_events(Framing::<Both>::new(), &input);
        let mut buf = [0u8; 10];
        let uart = Uart::new(input, 4);
        let mut reader = PacketReader::new(uart, both_decoder(), &mut buf[..]);
        let mut frames = Vec::new();
        while let Some(frame) = reader.read_message().unwrap() {
            frames.push(frame);
        }
        let oracle_frames: Vec<_> = expected.iter().filter_map(|e| e.ok()).collect();
        assert_eq!(frames, oracle_frames);
        let last = expected.iter().rev().find_map(|e| e.err());
        assert_eq!(reader.last_rejected(), last);
        let s = reader.stats();
        let rejections = expected.iter().filter(|e| e.is_err()).count() as u64;
        assert_eq!(
            s.checksum_failures + s.other_rejections + s.malformed,
            rejections
        );
    }

    #[test]
    fn unread_bytes_and_parts() {
        let ping = [0xa5, 0x50, 0x50];
        let input: Vec<u8> = ping.iter().chain(&ping).chain(&[0x00]).copied().collect();
        let uart = Uart::new(input, 100);
        let mut reader = PacketReader::new(uart, device_decoder(), [0u8; 16]);
        let first = reader.read_event().unwrap().unwrap().unwrap();
        assert_eq!(first.message, Command::Ping);
        assert_eq!(reader.unread(), [0xa5, 0x50, 0x50, 0x00]);
        let (uart, decoder, buf) = reader.into_parts();
        assert_eq!(uart.pos, 7);
        assert_eq!(decoder.stats().frames, 1);
        assert_eq!(buf[..7], [0xa5, 0x50, 0x50, 0xa5, 0x50, 0x50, 0x00]);
    }

    #[test]
    #[should_panic(expected = "at least one byte")]
    fn an_empty_buffer_is_refused() {
        let uart = Uart::new(vec![0xa5], 1);
        let _ = PacketReader::new(uart, both_decoder(), [0u8; 0]);
    }

    #[test]
    fn writer_sends_whole_frames_through_short_writes() {
        let messages = [
            Message::Command(Command::BaseVelocity {
                vx: 1,
                vy: -2,
                omega: 3,
            }),
            Message::Telemetry(io_common::telemetry(40)),
            Message::Command(Command::Brake { motor: Motor::M2 }),
        ];
        let mut tx = PacketWriter::<_, 64>::new(Tx::new(3));
        for m in &messages {
            assert_eq!(tx.send(m).unwrap(), m.encoded_len());
        }
        tx.flush().unwrap();
        assert_eq!(tx.into_inner().out, io_common::encoded(&messages));
    }

    #[test]
    fn writer_errors() {
        // The frame does not fit the writer's buffer: nothing is written.
        let mut tx = PacketWriter::<_, 8>::new(Tx::new(64));
        let telemetry = Telemetry::empty(Layout::Spi45);
        let err = tx.send(&telemetry).unwrap_err();
        assert_eq!(
            err,
            WriteError::Encode(EncodeError::BufferTooSmall {
                needed: 45,
                available: 8
            })
        );
        assert_eq!(
            embedded_io::Error::kind(&err),
            embedded_io::ErrorKind::InvalidInput
        );
        assert!(tx.get_ref().out.is_empty());
        // A message that cannot be encoded at all.
        let bad = Telemetry {
            tof: Some(Some(0xffff)),
            ..Telemetry::empty(Layout::UwbTof17)
        };
        let mut tx = PacketWriter::<_, 64>::new(Tx::new(64));
        assert!(matches!(tx.send(&bad), Err(WriteError::Encode(_))));
        assert!(tx.get_ref().out.is_empty());
        // The line fails mid-frame.
        tx.get_mut().fail_at = 4;
        tx.get_mut().max = 2;
        let err = tx.send(&Telemetry::empty(Layout::Pos7)).unwrap_err();
        assert_eq!(err, WriteError::Io(Glitch));
        assert_eq!(
            embedded_io::Error::kind(&err),
            embedded_io::ErrorKind::Other
        );
        assert_eq!(tx.get_ref().out.len(), 4);
        assert!(err.to_string().contains("framing error on the line"));
    }
}

#[cfg(feature = "embedded-io-async-07")]
mod nonblocking {
    use super::*;
    use robowire::io::embedded_io_async::{PacketReader, PacketWriter};
    use robowire::omnitiles::{Command, Message, Motor};
    use robowire::Encode;

    async fn drain<B: AsRef<[u8]> + AsMut<[u8]>>(
        reader: &mut PacketReader<Uart, Framing<Both>, { robowire::omnitiles::BOTH_BUFFER }, B>,
    ) -> (Vec<Ev>, usize) {
        let (mut events, mut errors) = (Vec::new(), 0);
        loop {
            match reader.read_event().await {
                Ok(Some(event)) => events.push(event),
                Ok(None) => return (events, errors),
                Err(Glitch) => errors += 1,
            }
        }
    }

    #[tokio::test]
    async fn events_match_the_engine_for_any_read_size_and_buffer() {
        let input = mixed_input(21);
        let expected = engine_events(Framing::<Both>::new(), &input);
        for max in [1, 3, 8, 64] {
            for buf_len in [1, 7, 64] {
                let mut buf = vec![0u8; buf_len];
                let uart = Uart::new(input.clone(), max);
                let mut reader = PacketReader::new(uart, both_decoder(), &mut buf[..]);
                let (events, errors) = drain(&mut reader).await;
                assert_eq!(errors, 0);
                assert_eq!(events, expected, "reads of {max}, buffer of {buf_len}");
            }
        }
    }

    #[tokio::test]
    async fn errors_and_ends_of_input() {
        let input = mixed_input(23);
        let ends = vec![17, 18, 150];
        let mut uart = Uart::new(input.clone(), 6);
        uart.ends = ends.clone();
        uart.glitches = vec![0, 17, 90];
        let mut reader = PacketReader::new(uart, both_decoder(), [0u8; 12]);
        let (mut events, mut errors) = (Vec::new(), 0);
        for _ in 0..=ends.len() {
            let (mut stream, e) = drain(&mut reader).await;
            events.append(&mut stream);
            errors += e;
        }
        assert_eq!(errors, 3);
        assert_eq!(
            events,
            streams_oracle(Framing::<Both>::new(), &input, &ends)
        );
    }

    #[tokio::test]
    async fn read_message_and_writer_round_trip() {
        let commands = io_common::commands();
        let mut tx = PacketWriter::<_, { Command::MAX_LEN }>::new(Tx::new(2));
        for c in &commands {
            assert_eq!(tx.send(c).await.unwrap(), c.encoded_len());
        }
        tx.flush().await.unwrap();
        let mut wire = tx.into_inner().out;
        wire.insert(0, 0xa5); // a false start
        let uart = Uart::new(wire, 5);
        let mut reader = PacketReader::new(uart, device_decoder(), [0u8; 4]);
        let mut received = Vec::new();
        while let Some(frame) = reader.read_message().await.unwrap() {
            received.push(frame.message);
        }
        assert_eq!(received, commands);
        assert!(reader.last_rejected().is_some());
        let too_long = Message::Command(Command::Extend {
            motor: Motor::M1,
            speed: 1,
        });
        let mut small = PacketWriter::<_, 3>::new(Tx::new(8));
        assert!(small.send(&too_long).await.is_err());
        assert!(small.get_ref().out.is_empty());
    }
}
