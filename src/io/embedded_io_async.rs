//! Async packet reader and writer over [`embedded_io_async`] 0.7 (feature
//! `embedded-io-async-07`): `no_std`, no allocation, for any executor
//! (an Embassy UART, a USB CDC class, an in-memory pipe).
//!
//! The same API as the blocking `io::embedded_io` (feature `embedded-io-07`),
//! with `async` methods.
//!
//! ```
//! use robowire::io::embedded_io_async::{PacketReader, PacketWriter};
//! use robowire::omnitiles::{Command, Decoder, Framing, Packet};
//!
//! async fn serve<R, W>(uart_rx: R, uart_tx: W) -> Result<u64, robowire::io::WriteError<W::Error>>
//! where
//!     R: embedded_io_async::Read,
//!     W: embedded_io_async::Write,
//! {
//!     let mut buf = [0u8; 32];
//!     let mut rx = PacketReader::new(uart_rx, Decoder::new(Framing::commands()), &mut buf[..]);
//!     let mut tx = PacketWriter::<_, { Command::MAX_LEN }>::new(uart_tx);
//!     // Echo every command back; stop at the end of the input or on a read error.
//!     while let Ok(Some(frame)) = rx.read_message().await {
//!         if let Packet::Command(command) = frame.message {
//!             tx.send(&command).await?;
//!         }
//!     }
//!     Ok(rx.stats().frames)
//! }
//!
//! # #[tokio::main(flavor = "current_thread")]
//! # async fn main() {
//! let mut echoed = [0u8; 8];
//! let frames = serve(&[0x17, 0xa5, 0x50, 0x50, 0xa5, 0x71, 0x71][..], &mut echoed[..]).await;
//! assert_eq!(frames.unwrap(), 2);
//! assert_eq!(echoed[..6], [0xa5, 0x50, 0x50, 0xa5, 0x71, 0x71]);
//! # }
//! ```

use embedded_io_async::{Read, Write};

use super::chunks::{Chunks, Step};
use super::WriteError;
use crate::encode::{Encode, FrameBuf};
use crate::stream::{FrameRules, OwnedEvent, OwnedFrame, Rejected, Stats, StreamDecoder};

/// Reads frames from an [`embedded_io_async::Read`] through a
/// [`StreamDecoder`], using the buffer `B` (`&mut [u8]`, `[u8; K]`, …) for each
/// read. Behaves as the blocking `io::embedded_io::PacketReader`: each read is
/// decoded in place, and a read of 0 bytes is the end of the input, which
/// resolves the buffered candidate ([`StreamDecoder::finish`]) and yields
/// `Ok(None)`; the next call reads again.
///
/// [`read_event`](Self::read_event) and [`read_message`](Self::read_message)
/// are as cancel-safe as `io.read`: the only `.await` is that read, and bytes
/// reach the decoder only once it has completed, so dropping the future (a
/// `select` with a timeout) loses no decoded frame and no buffered byte.
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
    pub async fn read_event(&mut self) -> Result<Option<OwnedEvent<F>>, R::Error> {
        loop {
            match self.chunks.step() {
                Step::Event(event) => return Ok(Some(event)),
                Step::End => return Ok(None),
                Step::Read => {
                    let n = self.io.read(self.chunks.space()).await?;
                    self.chunks.filled(n);
                }
            }
        }
    }

    /// The next frame, skipping rejected candidates (they are counted in
    /// [`stats`](Self::stats); the latest is kept in
    /// [`last_rejected`](Self::last_rejected)). `Ok(None)` at the end of the
    /// input.
    pub async fn read_message(&mut self) -> Result<Option<OwnedFrame<F::Owned>>, R::Error> {
        while let Some(event) = self.read_event().await? {
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

/// Writes messages to an [`embedded_io_async::Write`], one frame each,
/// encoding into a [`FrameBuf<N>`] on the stack. `N` must be at least the
/// longest frame you send (each protocol names it, e.g.
/// [`omnitiles::MAX_FRAME_LEN`](crate::omnitiles::MAX_FRAME_LEN)); a longer
/// frame fails with [`EncodeError::BufferTooSmall`](crate::EncodeError::BufferTooSmall)
/// and nothing is written.
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
    pub async fn send<M: Encode + ?Sized>(
        &mut self,
        message: &M,
    ) -> Result<usize, WriteError<W::Error>> {
        let frame = FrameBuf::<N>::encode(message).map_err(WriteError::Encode)?;
        self.io.write_all(&frame).await.map_err(WriteError::Io)?;
        Ok(frame.len())
    }

    /// Flush the underlying writer.
    pub async fn flush(&mut self) -> Result<(), W::Error> {
        self.io.flush().await
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
