//! A [`tokio_util::codec`] decoder and encoder for every protocol (feature
//! `tokio-util-07`, needs `std`).
//!
//! [`FrameCodec<F, N>`](FrameCodec) wraps a [`StreamDecoder<F, N>`] and
//! implements [`Decoder`] and [`Encoder<M>`] for every [`Encode`] message `M`,
//! so a serial port, a TCP stream or a `tokio::io::duplex` pipe becomes a
//! `Stream` of packets and a `Sink` of messages with `FramedRead`,
//! `FramedWrite` or `Framed`.
//!
//! `FramedRead` ends the stream at the first `Err`, so a rejected candidate
//! (bad checksum, unknown id, garbage) is never an error here. What the stream
//! yields is chosen by the codec's last type parameter:
//!
//! * [`Messages`] (the default): [`OwnedFrame`] messages only; rejections are
//!   counted in [`stats`](FrameCodec::stats) and the latest is kept in
//!   [`last_rejected`](FrameCodec::last_rejected);
//! * [`Events`] ([`FrameCodec::events`]): every [`OwnedEvent`], frames and
//!   rejections alike.
//!
//! At the end of the input, `decode_eof` resolves the candidate still buffered
//! with [`StreamDecoder::finish`]: a complete frame comes out, trailing garbage
//! or a truncated frame is a rejection like any other (an event, or a count),
//! never an error. The codec then takes a new stream, should the source
//! produce more bytes after its end.
//!
//! Every protocol has aliases: [`OmniTilesHostCodec`], [`OmniTilesDeviceCodec`]
//! and [`OmniTilesCodec`] (both directions), [`Pixy2HostCodec`] and
//! [`Pixy2DeviceCodec`], [`TelemetrixHostCodec`] and [`TelemetrixPicoCodec`].
//!
//! ```
//! use futures_util::{SinkExt, StreamExt};
//! use robowire::io::tokio::{OmniTilesDeviceCodec, OmniTilesHostCodec};
//! use robowire::omnitiles::{Command, Motor};
//! use tokio_util::codec::{FramedRead, FramedWrite};
//!
//! # #[tokio::main(flavor = "current_thread")]
//! # async fn main() -> std::io::Result<()> {
//! let (host, tile) = tokio::io::duplex(64);
//! let mut to_tile = FramedWrite::new(host, OmniTilesHostCodec::default());
//! let mut at_tile = FramedRead::new(tile, OmniTilesDeviceCodec::default());
//!
//! to_tile.send(Command::Extend { motor: Motor::M1, speed: 200 }).await?;
//! to_tile.send(Command::Ping).await?;
//! drop(to_tile); // end of input
//!
//! let mut received = Vec::new();
//! while let Some(frame) = at_tile.next().await {
//!     received.push(frame?.message);
//! }
//! assert_eq!(received, [Command::Extend { motor: Motor::M1, speed: 200 }, Command::Ping]);
//! # Ok(())
//! # }
//! ```

use core::fmt;
use core::marker::PhantomData;
use std::io;

use bytes::{Buf, BytesMut};
use tokio_util::codec::{Decoder, Encoder};

use crate::encode::Encode;
use crate::stream::{
    owned_event, FrameRules, OwnedEvent, OwnedFrame, Rejected, Stats, StreamDecoder,
};

/// The OmniTiles host-side codec: yields telemetry
/// ([`OwnedFrame<Telemetry>`](crate::omnitiles::Telemetry)) in the documented
/// layouts by default, and encodes commands.
pub type OmniTilesHostCodec<Y = Messages> = FrameCodec<
    crate::omnitiles::Framing<crate::omnitiles::Host>,
    { crate::omnitiles::HOST_BUFFER },
    Y,
>;

/// The OmniTiles tile-side codec (a simulated tile): yields commands
/// ([`OwnedFrame<Command>`](crate::omnitiles::Command)) and encodes telemetry.
pub type OmniTilesDeviceCodec<Y = Messages> = FrameCodec<
    crate::omnitiles::Framing<crate::omnitiles::Device>,
    { crate::omnitiles::DEVICE_BUFFER },
    Y,
>;

/// The OmniTiles codec for both directions: `FramedRead::new(port,
/// OmniTilesCodec::default())` yields [`OwnedFrame<Message>`](crate::omnitiles::Message),
/// commands and telemetry in the documented layouts.
pub type OmniTilesCodec<Y = Messages> = FrameCodec<
    crate::omnitiles::Framing<crate::omnitiles::Both>,
    { crate::omnitiles::BOTH_BUFFER },
    Y,
>;

/// The Pixy2 host-side codec: yields responses
/// ([`Envelope<ResponseBuf>`](crate::pixy2::Envelope)) and encodes requests.
pub type Pixy2HostCodec<Y = Messages> =
    FrameCodec<crate::pixy2::Framing<crate::pixy2::Host>, { crate::pixy2::HOST_BUFFER }, Y>;

/// The Pixy2 device-side codec (a simulated Pixy2): yields requests and
/// encodes responses.
pub type Pixy2DeviceCodec<Y = Messages> =
    FrameCodec<crate::pixy2::Framing<crate::pixy2::Device>, { crate::pixy2::DEVICE_BUFFER }, Y>;

/// The Telemetrix host-side codec: yields reports
/// ([`ReportBuf`](crate::telemetrix::ReportBuf)) and encodes commands.
pub type TelemetrixHostCodec<Y = Messages> = FrameCodec<
    crate::telemetrix::Framing<crate::side::Host>,
    { crate::telemetrix::HOST_BUFFER },
    Y,
>;

/// The Telemetrix Pico-side codec (a simulated board): yields commands and
/// encodes reports.
pub type TelemetrixPicoCodec<Y = Messages> = FrameCodec<
    crate::telemetrix::Framing<crate::side::Device>,
    { crate::telemetrix::DEVICE_BUFFER },
    Y,
>;

/// A [`Decoder`] and [`Encoder`] for framing `F` with a decoder buffer of `N`
/// bytes; `Y` chooses what the decoder yields ([`Messages`] or [`Events`]).
pub struct FrameCodec<F: FrameRules, const N: usize, Y = Messages> {
    decoder: StreamDecoder<F, N>,
    last_rejected: Option<Rejected<F::Error>>,
    yields: PhantomData<fn() -> Y>,
}

/// The codec yields [`OwnedFrame`] messages and counts rejections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Messages {}

/// The codec yields every [`OwnedEvent`]: frames and rejections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Events {}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Messages {}
    impl Sealed for super::Events {}
}

/// What a [`FrameCodec`] yields for each decoded event: implemented by
/// [`Messages`] and [`Events`] only.
pub trait Yields<F: FrameRules>: sealed::Sealed {
    /// The decoder's `Item`.
    type Item;

    /// The item for `event`, or `None` to skip it.
    #[doc(hidden)]
    fn item(event: OwnedEvent<F>) -> Option<Self::Item>;
}

impl<F: FrameRules> Yields<F> for Messages {
    type Item = OwnedFrame<F::Owned>;

    fn item(event: OwnedEvent<F>) -> Option<Self::Item> {
        event.ok()
    }
}

impl<F: FrameRules> Yields<F> for Events {
    type Item = OwnedEvent<F>;

    fn item(event: OwnedEvent<F>) -> Option<Self::Item> {
        Some(event)
    }
}

impl<F: FrameRules, const N: usize> FrameCodec<F, N, Messages> {
    /// A codec decoding with `framing`, yielding messages.
    pub const fn new(framing: F) -> Self {
        Self::from_decoder(StreamDecoder::new(framing))
    }

    /// A codec around an existing decoder (its state and counters carry on),
    /// yielding messages.
    pub const fn from_decoder(decoder: StreamDecoder<F, N>) -> Self {
        Self {
            decoder,
            last_rejected: None,
            yields: PhantomData,
        }
    }
}

impl<F: FrameRules, const N: usize, Y> FrameCodec<F, N, Y> {
    /// The same codec, yielding every event (frames and rejections).
    ///
    /// ```
    /// use robowire::io::tokio::OmniTilesDeviceCodec;
    /// use tokio_util::codec::Decoder;
    ///
    /// let mut codec = OmniTilesDeviceCodec::default().events();
    /// // A ping with a bad checksum, then a good one.
    /// let mut bytes = bytes::BytesMut::from(&[0xa5, 0x50, 0x51, 0xa5, 0x50, 0x50][..]);
    /// assert!(codec.decode(&mut bytes)?.unwrap().is_err());
    /// assert!(codec.decode(&mut bytes)?.unwrap().is_ok());
    /// assert_eq!(codec.stats().checksum_failures, 1);
    /// # Ok::<(), std::io::Error>(())
    /// ```
    pub fn events(self) -> FrameCodec<F, N, Events> {
        self.yielding()
    }

    /// The same codec, yielding messages only.
    pub fn messages(self) -> FrameCodec<F, N, Messages> {
        self.yielding()
    }

    fn yielding<Z>(self) -> FrameCodec<F, N, Z> {
        FrameCodec {
            decoder: self.decoder,
            last_rejected: self.last_rejected,
            yields: PhantomData,
        }
    }

    /// The decoder's counters: frames, skipped bytes, checksum failures and
    /// other rejections.
    pub fn stats(&self) -> Stats {
        self.decoder.stats()
    }

    /// The most recent rejected candidate, if any.
    pub fn last_rejected(&self) -> Option<Rejected<F::Error>> {
        self.last_rejected
    }

    /// The framing rules in use.
    pub fn framing(&self) -> &F {
        self.decoder.framing()
    }

    /// The decoder.
    pub fn decoder(&self) -> &StreamDecoder<F, N> {
        &self.decoder
    }

    /// The decoder, mutably.
    pub fn decoder_mut(&mut self) -> &mut StreamDecoder<F, N> {
        &mut self.decoder
    }

    /// The decoder, with its state and counters.
    pub fn into_decoder(self) -> StreamDecoder<F, N> {
        self.decoder
    }
}

impl<F: FrameRules, const N: usize, Y: Yields<F>> FrameCodec<F, N, Y> {
    fn keep(&mut self, event: OwnedEvent<F>) -> Option<Y::Item> {
        if let Err(rejected) = event {
            self.last_rejected = Some(rejected);
        }
        Y::item(event)
    }
}

impl<F: FrameRules + Default, const N: usize> Default for FrameCodec<F, N, Messages> {
    fn default() -> Self {
        Self::new(F::default())
    }
}

impl<F: FrameRules + Clone, const N: usize, Y> Clone for FrameCodec<F, N, Y> {
    fn clone(&self) -> Self {
        Self {
            decoder: self.decoder.clone(),
            last_rejected: self.last_rejected,
            yields: PhantomData,
        }
    }
}

impl<F: FrameRules + fmt::Debug, const N: usize, Y> fmt::Debug for FrameCodec<F, N, Y> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FrameCodec")
            .field("decoder", &self.decoder)
            .field("last_rejected", &self.last_rejected)
            .finish()
    }
}

impl<F: FrameRules, const N: usize, Y: Yields<F>> Decoder for FrameCodec<F, N, Y> {
    type Item = Y::Item;
    type Error = io::Error;

    /// Decode from `src`, taking every byte it looks at: a partial frame moves
    /// into the decoder's own buffer, so `src` never grows without bound.
    /// Never fails.
    fn decode(&mut self, src: &mut BytesMut) -> io::Result<Option<Y::Item>> {
        loop {
            let mut input: &[u8] = src;
            let before = input.len();
            let event = self.decoder.decode(&mut input).map(owned_event::<F>);
            let taken = before - input.len();
            src.advance(taken);
            match event {
                // Every byte has been taken.
                None => return Ok(None),
                Some(event) => {
                    if let Some(item) = self.keep(event) {
                        return Ok(Some(item));
                    }
                }
            }
        }
    }

    /// Decode what is left, then resolve the buffered candidate with
    /// [`StreamDecoder::finish`]. Never fails: trailing garbage or a truncated
    /// frame is a rejection.
    fn decode_eof(&mut self, src: &mut BytesMut) -> io::Result<Option<Y::Item>> {
        if let Some(item) = self.decode(src)? {
            return Ok(Some(item));
        }
        while let Some(event) = self.decoder.finish().map(owned_event::<F>) {
            if let Some(item) = self.keep(event) {
                return Ok(Some(item));
            }
        }
        Ok(None)
    }
}

impl<F: FrameRules, const N: usize, Y, M: Encode> Encoder<M> for FrameCodec<F, N, Y> {
    type Error = io::Error;

    /// Append `message`'s frame to `dst`. An [`EncodeError`](crate::EncodeError)
    /// becomes an [`io::ErrorKind::InvalidInput`] error and appends nothing.
    fn encode(&mut self, message: M, dst: &mut BytesMut) -> io::Result<()> {
        let start = dst.len();
        dst.resize(start + message.encoded_len(), 0);
        match message.encode(&mut dst[start..]) {
            Ok(n) => {
                dst.truncate(start + n);
                Ok(())
            }
            Err(e) => {
                dst.truncate(start);
                Err(io::Error::new(io::ErrorKind::InvalidInput, e))
            }
        }
    }
}
