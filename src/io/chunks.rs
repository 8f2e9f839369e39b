//! What the blocking and the async `embedded-io` adapters share: decoding
//! chunks read into a caller's buffer, and the writer's error type.

use core::fmt;

use crate::encode::EncodeError;
use crate::stream::{owned_event, FrameRules, OwnedEvent, Rejected, StreamDecoder};

/// What the reader does next.
pub(crate) enum Step<F: FrameRules> {
    /// An event, decoded from bytes already read.
    Event(OwnedEvent<F>),
    /// The source reported its end and everything buffered has been resolved.
    End,
    /// Every byte read so far has been taken: read more into
    /// [`Chunks::space`] and report it with [`Chunks::filled`].
    Read,
}

/// A [`StreamDecoder`] fed from a caller's buffer, one read at a time.
#[derive(Debug)]
pub(crate) struct Chunks<F: FrameRules, const N: usize, B> {
    decoder: StreamDecoder<F, N>,
    buf: B,
    /// `buf[start..end]` holds bytes read but not yet taken by the decoder.
    start: usize,
    end: usize,
    /// The source reported its end: resolve the buffered candidate.
    at_end: bool,
    last_rejected: Option<Rejected<F::Error>>,
}

impl<F: FrameRules, const N: usize, B: AsRef<[u8]> + AsMut<[u8]>> Chunks<F, N, B> {
    pub(crate) fn new(decoder: StreamDecoder<F, N>, buf: B) -> Self {
        assert!(
            !buf.as_ref().is_empty(),
            "the read buffer must hold at least one byte"
        );
        Self {
            decoder,
            buf,
            start: 0,
            end: 0,
            at_end: false,
            last_rejected: None,
        }
    }

    pub(crate) fn step(&mut self) -> Step<F> {
        let event = if self.at_end {
            let event = self.decoder.finish().map(owned_event::<F>);
            if event.is_none() {
                // Ready for whatever the source gives next.
                self.at_end = false;
                return Step::End;
            }
            event
        } else {
            let mut input = &self.buf.as_ref()[self.start..self.end];
            let before = input.len();
            let event = self.decoder.decode(&mut input).map(owned_event::<F>);
            self.start += before - input.len();
            event
        };
        match event {
            Some(event) => {
                if let Err(rejected) = event {
                    self.last_rejected = Some(rejected);
                }
                Step::Event(event)
            }
            None => {
                // `decode` returns `None` only once it has taken every byte.
                self.start = 0;
                self.end = 0;
                Step::Read
            }
        }
    }

    /// Where the next read goes: the whole buffer (it is empty after
    /// [`Step::Read`]).
    pub(crate) fn space(&mut self) -> &mut [u8] {
        self.buf.as_mut()
    }

    /// `n` bytes were read into [`space`](Self::space); 0 is the end of input.
    pub(crate) fn filled(&mut self, n: usize) {
        if n == 0 {
            self.at_end = true;
        } else {
            self.start = 0;
            self.end = n.min(self.buf.as_ref().len());
        }
    }

    pub(crate) fn decoder(&self) -> &StreamDecoder<F, N> {
        &self.decoder
    }

    pub(crate) fn decoder_mut(&mut self) -> &mut StreamDecoder<F, N> {
        &mut self.decoder
    }

    pub(crate) fn last_rejected(&self) -> Option<Rejected<F::Error>> {
        self.last_rejected
    }

    pub(crate) fn unread(&self) -> &[u8] {
        &self.buf.as_ref()[self.start..self.end]
    }

    pub(crate) fn into_parts(self) -> (StreamDecoder<F, N>, B) {
        (self.decoder, self.buf)
    }
}

/// Why a packet writer could not send a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum WriteError<E> {
    /// The message could not be encoded (nothing was written).
    Encode(EncodeError),
    /// The writer failed; part of the frame may have been written.
    Io(E),
}

impl<E: fmt::Display> fmt::Display for WriteError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::Encode(e) => write!(f, "cannot encode the message: {e}"),
            WriteError::Io(e) => write!(f, "cannot write the frame: {e}"),
        }
    }
}

impl<E: core::error::Error + 'static> core::error::Error for WriteError<E> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            WriteError::Encode(e) => Some(e),
            WriteError::Io(e) => Some(e),
        }
    }
}

/// So that `?` can pass a `WriteError` on wherever an `embedded-io` error is
/// expected: an encoding failure is [`InvalidInput`](embedded_io::ErrorKind::InvalidInput).
impl<E: embedded_io::Error + 'static> embedded_io::Error for WriteError<E> {
    fn kind(&self) -> embedded_io::ErrorKind {
        match self {
            WriteError::Encode(_) => embedded_io::ErrorKind::InvalidInput,
            WriteError::Io(e) => e.kind(),
        }
    }
}
