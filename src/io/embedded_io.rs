//! Blocking packet reader and writer over [`embedded_io`] 0.7 (feature
//! `embedded-io-07`): `no_std`, no allocation.
//!
//! [`PacketReader`] reads from any [`embedded_io::Read`] into a buffer you
//! provide and decodes with any protocol's [`StreamDecoder`]. [`PacketWriter`]
//! encodes any [`Encode`] message into a [`FrameBuf`] on the stack and writes it
//! with [`write_all`](embedded_io::Write::write_all).
//!
//! A firmware command loop over a UART (here a byte slice, which implements
//! `embedded_io::Read`):
//!
//! ```
//! use robowire::io::embedded_io::{PacketReader, PacketWriter};
//! use robowire::omnitiles::{Command, Decoder, Framing, Layout, Motor, Packet, Telemetry};
//!
//! // Noise, then M1 extend at 200, then a ping.
//! let uart_rx: &[u8] = &[0x00, 0xa5, 0xa5, 0x30, 0xc8, 0xf8, 0xa5, 0x50, 0x50];
//! let mut buf = [0u8; 16];
//! let mut rx = PacketReader::new(uart_rx, Decoder::new(Framing::commands()), &mut buf[..]);
//! let mut uart_tx = [0u8; 128];
//! let mut tx = PacketWriter::<_, { Telemetry::MAX_LEN }>::new(&mut uart_tx[..]);
//!
//! let mut commands = 0;
//! while let Some(frame) = rx.read_message()? {
//!     if let Packet::Command(Command::Extend { motor: Motor::M1, speed }) = frame.message {
//!         assert_eq!(speed, 200);
//!     }
//!     commands += 1;
//!     tx.send(&Telemetry { m1_pos: Some(2000), ..Telemetry::empty(Layout::Ble53) })?;
//! }
//! assert_eq!(commands, 2);
//! assert_eq!(rx.stats().skipped, 2); // the 0x00 and the false start `a5`
//! assert_eq!(uart_tx[..2], [0xa5, 0x60]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use embedded_io::{Read, Write};

use super::chunks::{Chunks, Step};
use super::WriteError;
use crate::encode::{Encode, FrameBuf};
use crate::stream::{FrameRules, OwnedEvent, OwnedFrame, Rejected, Stats, StreamDecoder};

/// Reads frames from an [`embedded_io::Read`] through a [`StreamDecoder`],
/// using the buffer `B` (`&mut [u8]`, `[u8; K]`, …) for each read.
///
/// Each read fills at most the whole buffer and is decoded in place (the
/// engine's zero-copy path); only a frame cut by the end of a read is copied
/// into the decoder. A few dozen bytes are plenty; a larger buffer means fewer
/// `read` calls. A read of 0 bytes is the end of the input: the reader then
/// resolves the decoder's buffered candidate ([`StreamDecoder::finish`]) and
/// returns `Ok(None)`, after which it reads again if called again.
#[derive(Debug)]
pub struct PacketReader<R, F: FrameRules, const N: usize, B> {
    io: R,
    chunks: Chunks<F, N, B>,
}

impl<R: Read, F: FrameRules, const N: usize, B: AsRef<[u8]> + AsMut<[u8]>>
    PacketReader<R, F, N, B>
{
    /// A reader decoding `io` with `decoder`, reading into `buf`.
    ///
    /// # Panics
    ///
    /// If `buf` is empty.
    pub fn new(io: R, decoder: StreamDecoder<F, N>, buf: B) -> Self {
        Self {
            io,
            chunks: Chunks::new(decoder, buf),
        }
    }

    /// The next event: a frame, or a rejected candidate (which is not an
    /// error: decoding goes on). `Ok(None)` at the end of the input, once
    /// everything buffered is resolved. A read error leaves the reader as it
    /// was, so it can be called again.
    pub fn read_event(&mut self) -> Result<Option<OwnedEvent<F>>, R::Error> {
        loop {
            match self.chunks.step() {
                Step::Event(event) => return Ok(Some(event)),
                Step::End => return Ok(None),
                Step::Read => {
                    let n = self.io.read(self.chunks.space())?;
                    self.chunks.filled(n);
                }
            }
        }
    }

    /// The next frame, skipping rejected candidates (they are counted in
    /// [`stats`](Self::stats); the latest is kept in
    /// [`last_rejected`](Self::last_rejected)). `Ok(None)` at the end of the
    /// input.
    pub fn read_message(&mut self) -> Result<Option<OwnedFrame<F::Owned>>, R::Error> {
        while let Some(event) = self.read_event()? {
            if let Ok(frame) = event {
                return Ok(Some(frame));
            }
        }
        Ok(None)
    }

    /// The decoder's counters.
    pub fn stats(&self) -> Stats {
        self.chunks.decoder().stats()
    }

    /// The most recent rejected candidate, if any.
    pub fn last_rejected(&self) -> Option<Rejected<F::Error>> {
        self.chunks.last_rejected()
    }

    /// The decoder.
    pub fn decoder(&self) -> &StreamDecoder<F, N> {
        self.chunks.decoder()
    }

    /// The decoder, mutably (for example to [`clear`](StreamDecoder::clear) it).
    pub fn decoder_mut(&mut self) -> &mut StreamDecoder<F, N> {
        self.chunks.decoder_mut()
    }

    /// Bytes read from `io` that the decoder has not taken yet.
    pub fn unread(&self) -> &[u8] {
        self.chunks.unread()
    }

    /// The underlying reader.
    pub fn get_ref(&self) -> &R {
        &self.io
    }

    /// The underlying reader, mutably. Reading from it directly bypasses the
    /// decoder.
    pub fn get_mut(&mut self) -> &mut R {
        &mut self.io
    }

    /// The reader, the decoder and the buffer. Bytes in
    /// [`unread`](Self::unread) are not decoded.
    pub fn into_parts(self) -> (R, StreamDecoder<F, N>, B) {
        let (decoder, buf) = self.chunks.into_parts();
        (self.io, decoder, buf)
    }
}

/// Writes messages to an [`embedded_io::Write`], one frame each, encoding
/// into a [`FrameBuf<N>`] on the stack. `N` must be at least the longest frame
/// you send (each protocol names it, e.g.
/// [`omnitiles::MAX_FRAME_LEN`](crate::omnitiles::MAX_FRAME_LEN)); a longer
/// frame fails with [`EncodeError::BufferTooSmall`](crate::EncodeError::BufferTooSmall)
/// and nothing is written.
///
/// ```
/// use robowire::io::embedded_io::PacketWriter;
/// use robowire::omnitiles::{Command, Motor};
///
/// let mut out = [0u8; 8];
/// let mut tx = PacketWriter::<_, { Command::MAX_LEN }>::new(&mut out[..]);
/// tx.send(&Command::Brake { motor: Motor::M1 })?;
/// tx.send(&Command::Ping)?;
/// assert_eq!(out[..6], [0xa5, 0x32, 0x32, 0xa5, 0x50, 0x50]);
/// # Ok::<(), robowire::io::WriteError<embedded_io::SliceWriteError>>(())
/// ```
#[derive(Debug)]
pub struct PacketWriter<W, const N: usize> {
    io: W,
}

impl<W: Write, const N: usize> PacketWriter<W, N> {
    /// A writer over `io`.
    pub const fn new(io: W) -> Self {
        Self { io }
    }

    /// Encode `message` and write the whole frame. Returns the frame's
    /// length. Does not flush.
    pub fn send<M: Encode + ?Sized>(&mut self, message: &M) -> Result<usize, WriteError<W::Error>> {
        let frame = FrameBuf::<N>::encode(message).map_err(WriteError::Encode)?;
        self.io.write_all(&frame).map_err(WriteError::Io)?;
        Ok(frame.len())
    }

    /// Flush the underlying writer.
    pub fn flush(&mut self) -> Result<(), W::Error> {
        self.io.flush()
    }

    /// The underlying writer.
    pub fn get_ref(&self) -> &W {
        &self.io
    }

    /// The underlying writer, mutably.
    pub fn get_mut(&mut self) -> &mut W {
        &mut self.io
    }

    /// The underlying writer.
    pub fn into_inner(self) -> W {
        self.io
    }
}
