//! An idle deadline for a [`StreamDecoder`], sans-IO: the decoder is told
//! when bytes arrive and asked when to look again, as a QUIC state machine
//! is (quinn-proto's `poll_timeout` and `handle_timeout`), and the caller
//! owns the clock and the waiting.
//!
//! Some frames end where the bytes cannot say so: a 7-byte OmniTiles
//! telemetry frame may be the start of a 15-, 17- or 53-byte one, and only
//! the next byte decides. A sender writes each frame back to back, so a
//! line that stays silent for a few byte-times after such a frame has
//! ended it. [`Idle`] turns that silence into a deadline: after bytes
//! arrive and leave something buffered, [`deadline`](Idle::deadline) is
//! when the line counts as idle; once that time has come without a byte,
//! [`expired`](Idle::expired) says so (once per silence) and the caller
//! takes what [`StreamDecoder::settle`] gives.
//!
//! Times are `u64` ticks of the caller's monotonic clock, in any unit the
//! gap is in too ([`at_baud`](Idle::at_baud) gives a gap in microseconds).
//!
//! ```
//! use robowire::omnitiles::{Framing, Host, HOST_BUFFER};
//! use robowire::{Idle, StreamDecoder};
//! let mut decoder = StreamDecoder::<_, HOST_BUFFER>::new(Framing::<Host>::new());
//! // 3.5 byte-times at 115200 baud, in microseconds.
//! let mut idle = Idle::at_baud(115_200, 3.5);
//! assert_eq!(idle.gap(), 304);
//! let pos7 = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];
//! // At t = 1000 µs the frame arrives; it may be a longer frame's start.
//! assert!(decoder.feed(&pos7).next().is_none());
//! idle.received(1_000, &decoder);
//! assert_eq!(idle.deadline(), Some(1_304));
//! assert!(!idle.expired(1_200)); // not yet: wait until the deadline
//! assert!(idle.expired(1_304)); // silent since: the frame has ended
//! let frame = decoder.settle().unwrap().unwrap();
//! assert_eq!(frame.raw.len(), 7);
//! assert_eq!(idle.deadline(), None); // nothing held: no deadline
//! ```

use crate::stream::{Counter, FrameRules, StreamDecoder};

/// When a line counts as idle: a gap after the last bytes, while the
/// decoder holds some (see the [module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Idle {
    gap: u64,
    /// When the last bytes arrived, while the decoder held bytes after
    /// them and no expiry has been reported since.
    armed_at: Option<u64>,
}

impl Idle {
    /// A line idle after `gap` ticks without a byte.
    pub const fn new(gap: u64) -> Idle {
        Idle {
            gap,
            armed_at: None,
        }
    }

    /// A line idle after `bytes` byte-times without a byte at `baud` (8N1:
    /// ten bits a byte), in microseconds, rounded up and at least 1. Modbus
    /// RTU ends its frames at 3.5 byte-times of silence; a host reading a
    /// USB serial adapter sees the adapter's own latency on top (often 1 to
    /// 16 ms), so a gap under a millisecond only helps a UART read directly.
    pub fn at_baud(baud: u32, bytes: f32) -> Idle {
        let baud = f64::from(baud.max(1));
        let micros = f64::from(bytes.max(0.0)) * 10.0 * 1_000_000.0 / baud;
        // `as` saturates: a gap too large for u64 is u64::MAX.
        let whole = micros as u64;
        let gap = if (whole as f64) < micros {
            whole.saturating_add(1)
        } else {
            whole
        };
        Idle::new(gap.max(1))
    }

    /// The gap, in ticks.
    pub const fn gap(&self) -> u64 {
        self.gap
    }

    /// Bytes arrived at `now` and were fed to `decoder`: while it holds
    /// bytes, the deadline is `now` plus the gap; when it holds none, there
    /// is none.
    pub fn received<F: FrameRules, const N: usize, C: Counter>(
        &mut self,
        now: u64,
        decoder: &StreamDecoder<F, N, C>,
    ) {
        self.armed_at = (decoder.buffered() > 0).then_some(now);
    }

    /// When the line counts as idle if no byte arrives before: the time to
    /// wait until for the next read (`None`: wait as long as you like).
    pub fn deadline(&self) -> Option<u64> {
        self.armed_at.map(|at| at.saturating_add(self.gap))
    }

    /// Whether the deadline has come at `now` (no byte since): then call
    /// [`StreamDecoder::settle`] until it gives `None`. It says so once per
    /// silence: afterwards the deadline is `None` until bytes arrive again,
    /// so a frame still unfinished does not wake the caller in a loop.
    pub fn expired(&mut self, now: u64) -> bool {
        match self.deadline() {
            Some(deadline) if now >= deadline => {
                self.armed_at = None;
                true
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Idle;
    use crate::omnitiles::{Framing, Host, HOST_BUFFER};
    use crate::StreamDecoder;

    const POS7: [u8; 7] = [0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x22];

    #[test]
    fn gaps_at_common_rates() {
        assert_eq!(Idle::at_baud(115_200, 3.5).gap(), 304);
        assert_eq!(Idle::at_baud(9_600, 3.5).gap(), 3_646);
        assert_eq!(Idle::at_baud(1_000_000, 1.0).gap(), 10);
        assert_eq!(Idle::at_baud(u32::MAX, 0.0).gap(), 1);
        assert_eq!(Idle::at_baud(0, 1.0).gap(), 10_000_000);
        assert_eq!(Idle::at_baud(1, f32::MAX).gap(), u64::MAX);
    }

    #[test]
    fn no_deadline_while_nothing_is_held() {
        let mut decoder = StreamDecoder::<_, HOST_BUFFER>::new(Framing::<Host>::new());
        let mut idle = Idle::new(10);
        // A 53-byte frame, the longest layout, is decided by its own bytes.
        let ble53 = {
            let mut f = [0u8; 53];
            f[0] = 0xa5;
            f[1] = 0x60;
            f[52] = f[1..52].iter().fold(0u8, |s, b| s.wrapping_add(*b));
            f
        };
        assert_eq!(decoder.feed(&ble53).count(), 1);
        idle.received(5, &decoder);
        assert_eq!(idle.deadline(), None);
        assert!(!idle.expired(u64::MAX));
    }

    #[test]
    fn one_expiry_per_silence_and_bytes_rearm() {
        let mut decoder = StreamDecoder::<_, HOST_BUFFER>::new(Framing::<Host>::new());
        let mut idle = Idle::new(100);
        // Half a frame: held, and settle leaves it.
        assert!(decoder.feed(&POS7[..4]).next().is_none());
        idle.received(0, &decoder);
        assert!(idle.expired(100));
        assert!(decoder.settle().is_none());
        assert_eq!((idle.deadline(), idle.expired(10_000)), (None, false));
        // Its rest arrives: the deadline is the gap after it.
        assert!(decoder.feed(&POS7[4..]).next().is_none());
        idle.received(10_000, &decoder);
        assert_eq!(idle.deadline(), Some(10_100));
        assert!(!idle.expired(10_099));
        assert!(idle.expired(10_100));
        assert!(decoder.settle().is_some_and(|event| event.is_ok()));
        assert_eq!(decoder.buffered(), 0);
        // A deadline near the end of time saturates.
        assert!(decoder.feed(&POS7).next().is_none());
        idle.received(u64::MAX - 1, &decoder);
        assert_eq!(idle.deadline(), Some(u64::MAX));
    }
}
