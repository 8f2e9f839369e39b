//! The event helpers of the Telemetrix quirk tests: a frame from its hex
//! bytes, and every event a decoder gives for a stream fed whole.

use robowire::telemetrix::{Error, MessageBuf};
use robowire::{Rejected, StreamDecoder};

pub fn hex(s: &str) -> Vec<u8> {
    s.split_whitespace()
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect()
}

/// An event as the tests compare it.
pub type Ev = Result<(u64, usize, MessageBuf), (u64, Error)>;

/// Every event of `bytes` fed whole: offset, length and the owned message
/// turned into a `MessageBuf`, or offset and error.
pub fn events<F, const N: usize>(mut decoder: StreamDecoder<F, N>, bytes: &[u8]) -> Vec<Ev>
where
    F: robowire::FrameRules<Error = Error>,
    F::Owned: Into<MessageBuf>,
{
    let map = |e: robowire::OwnedEvent<F>| match e {
        Ok(f) => Ok((f.offset, f.len, f.message.into())),
        Err(Rejected { offset, error }) => Err((offset, error)),
    };
    let mut out: Vec<_> = decoder.feed(bytes).map(map).collect();
    out.extend(decoder.flush().map(map));
    out
}
