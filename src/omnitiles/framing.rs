//! Where OmniTiles frames start and end in a byte stream.

use super::command::{payload_len, Command};
use super::layout::{Layout, Layouts};
use super::telemetry::Telemetry;
use super::{checksum, id, Error, Packet, START};
use crate::stream::{self, Check};

/// What an OmniTiles decoder accepts: commands (bytes from the host),
/// telemetry in a set of layouts (bytes from the tile), or both.
///
/// # Telemetry length policy
///
/// Telemetry has no length byte and one id for every layout, so with several
/// layouts enabled a candidate can validate at more than one length. The
/// decoder tries the enabled lengths shortest first and accepts length `L`
/// when the 8-bit sum validates at `L` **and** the length is confirmed:
///
/// * `L` is the longest enabled layout (emitted as soon as it is complete), or
/// * the bytes after it begin another accepted frame (`a5` and an accepted id,
///   e.g. `a5 60`), or
/// * the input ends exactly at `L` (or at `L + 1` with a lone `a5`), which only
///   [`finish`](crate::StreamDecoder::finish) can say.
///
/// A shorter frame therefore waits for two more bytes (the next header). With
/// a single layout there is nothing to confirm: every frame is emitted as
/// soon as it is complete. On a clean stream of any mix of the enabled layouts
/// this gives no false and no lost frames, except where a frame's own bytes
/// look like a shorter frame and a header: a 53-byte frame whose bytes 1..=5
/// sum to byte 6 and whose bytes 7 and 8 are `a5 60` (for instance m1 = m2 =
/// 0 and UWB d0 = `0xA560`, d1 = `0x0060`) is taken as a 7-byte frame, and
/// likewise at 15 and 17 bytes; for random contents that is about one frame
/// in 2^24. In noise, a short frame followed by garbage is dropped
/// ([`Error::Unconfirmed`]) rather than guessed at. Name a single layout when
/// you know it.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Framing {
    commands: bool,
    layouts: Layouts,
}

impl Framing {
    /// Accept commands and telemetry in the four documented layouts.
    pub const ANY: Framing = Framing::any(Layouts::DOCUMENTED);

    /// Accept commands only: a tile's view of the link (`--from host`).
    pub const fn commands() -> Framing {
        Framing {
            commands: true,
            layouts: Layouts::NONE,
        }
    }

    /// Accept telemetry in `layouts` only: a host's view (`--from tile`).
    pub const fn telemetry(layouts: Layouts) -> Framing {
        Framing {
            commands: false,
            layouts,
        }
    }

    /// Accept commands and telemetry in `layouts`.
    pub const fn any(layouts: Layouts) -> Framing {
        Framing {
            commands: true,
            layouts,
        }
    }

    /// Whether commands are accepted.
    pub const fn accepts_commands(&self) -> bool {
        self.commands
    }

    /// The telemetry layouts accepted.
    pub const fn layouts(&self) -> Layouts {
        self.layouts
    }

    /// Whether `id` begins a frame this decoder accepts.
    pub const fn accepts_id(&self, id: u8) -> bool {
        if id == id::TELEMETRY {
            !self.layouts.is_empty()
        } else {
            self.commands && payload_len(id).is_some()
        }
    }

    /// Does what follows a telemetry candidate confirm its length?
    /// `Some(true)` yes, `Some(false)` no, `None` cannot tell yet.
    fn confirms(&self, rest: &[u8], at_end: bool) -> Option<bool> {
        match rest {
            [] if at_end => Some(true),
            [] => None,
            [START] if at_end => Some(true),
            [START] => None,
            [START, next, ..] => Some(self.accepts_id(*next)),
            _ => Some(false),
        }
    }

    #[inline(always)]
    fn check_telemetry(&self, c: &[u8], at_end: bool) -> Check<Error> {
        let longest = match self.layouts.longest() {
            Some(l) => l,
            None => return Check::Reject(Error::UnknownId { id: id::TELEMETRY }),
        };
        if self.layouts.len() == 1 {
            return check_single(longest, c, at_end);
        }
        self.check_layouts(longest, c, at_end)
    }

    /// Several layouts: try them shortest first (see the length policy).
    #[inline(never)]
    fn check_layouts(&self, longest: Layout, c: &[u8], at_end: bool) -> Check<Error> {
        let mut error = Error::Unconfirmed;
        let mut unconfirmed = false;
        // Running sum over bytes 1.. so each length costs only its new bytes.
        let mut sum: u8 = 0;
        let mut summed = 1;
        for layout in Layout::ALL {
            if !self.layouts.contains(layout) {
                continue;
            }
            let len = layout.frame_len();
            if c.len() < len {
                return if at_end {
                    Check::Reject(Error::Truncated { len: c.len() })
                } else {
                    Check::Need(len)
                };
            }
            sum = sum.wrapping_add(sum8(&c[summed..len - 1]));
            summed = len - 1;
            let found = c[len - 1];
            if sum != found {
                error = Error::Checksum {
                    expected: sum,
                    found,
                };
                continue;
            }
            if layout == longest {
                return Check::Frame(len);
            }
            match self.confirms(&c[len..], at_end) {
                Some(true) => return Check::Frame(len),
                Some(false) => unconfirmed = true,
                None => return Check::Need(len + 2),
            }
        }
        // A shorter layout that validated says more than the longest one's
        // checksum: a frame was probably here, followed by garbage.
        Check::Reject(if unconfirmed {
            Error::Unconfirmed
        } else {
            error
        })
    }
}

/// A single telemetry layout: the candidate is a frame of exactly its length
/// or nothing, and nothing needs confirming.
#[inline(always)]
fn check_single(layout: Layout, c: &[u8], at_end: bool) -> Check<Error> {
    // One fixed-size check per layout, so the sum runs over a constant range.
    match layout {
        Layout::Pos7 => check_fixed::<7>(c, at_end),
        Layout::Uwb15 => check_fixed::<15>(c, at_end),
        Layout::UwbTof17 => check_fixed::<17>(c, at_end),
        Layout::Spi45 => check_fixed::<45>(c, at_end),
        Layout::Ble53 => check_fixed::<53>(c, at_end),
    }
}

#[inline(always)]
fn check_fixed<const L: usize>(c: &[u8], at_end: bool) -> Check<Error> {
    let Some(frame) = c.first_chunk::<L>() else {
        return if at_end {
            Check::Reject(Error::Truncated { len: c.len() })
        } else {
            Check::Need(L)
        };
    };
    let expected = sum8(&frame[1..L - 1]);
    let found = frame[L - 1];
    if expected == found {
        Check::Frame(L)
    } else {
        Check::Reject(Error::Checksum { expected, found })
    }
}

/// The wrapping 8-bit sum of `bytes`, eight bytes at a time: each `u64` word
/// is split into its even and odd bytes as four 16-bit lanes, the lanes are
/// accumulated (up to 128 words cannot overflow a lane), and the lanes are
/// folded at the end. Equal to `bytes.iter().fold(0, u8::wrapping_add)`.
#[inline(always)]
pub(crate) fn sum8(bytes: &[u8]) -> u8 {
    const LANES: u64 = 0x00ff_00ff_00ff_00ff;
    let mut total: u8 = 0;
    let mut words = bytes.chunks_exact(8);
    let mut acc: u64 = 0;
    let mut in_acc = 0;
    for word in words.by_ref() {
        let mut w = [0u8; 8];
        w.copy_from_slice(word);
        let w = u64::from_le_bytes(w);
        acc += (w & LANES) + ((w >> 8) & LANES);
        in_acc += 1;
        if in_acc == 128 {
            total = total.wrapping_add(fold_lanes(acc));
            acc = 0;
            in_acc = 0;
        }
    }
    total = total.wrapping_add(fold_lanes(acc));
    words
        .remainder()
        .iter()
        .fold(total, |s, &b| s.wrapping_add(b))
}

/// The sum of four 16-bit lanes, modulo 256.
#[inline(always)]
fn fold_lanes(acc: u64) -> u8 {
    let acc = (acc & 0x0000_ffff_0000_ffff) + ((acc >> 16) & 0x0000_ffff_0000_ffff);
    (acc + (acc >> 32)) as u8
}

impl Default for Framing {
    fn default() -> Self {
        Framing::ANY
    }
}

impl stream::FrameRules for Framing {
    type Error = Error;
    type Message<'a> = Packet;
    type Owned = Packet;

    /// `a5` and the id: enough to reject an unknown id.
    const HEADER_LEN: usize = 2;

    #[inline]
    fn find_start(&self, bytes: &[u8]) -> usize {
        // On a clean stream the next frame starts right here: skip the scan.
        match bytes.first() {
            Some(&START) => 0,
            _ => memchr::memchr(START, bytes).unwrap_or(bytes.len()),
        }
    }

    #[inline(always)]
    fn check(&self, c: &[u8], at_end: bool) -> Check<Error> {
        let Some(&id) = c.get(1) else {
            return if at_end {
                Check::Reject(Error::Truncated { len: c.len() })
            } else {
                Check::Need(2)
            };
        };
        if id == id::TELEMETRY && !self.layouts.is_empty() {
            return self.check_telemetry(c, at_end);
        }
        let n = match payload_len(id) {
            Some(n) if self.commands => n,
            _ => return Check::Reject(Error::UnknownId { id }),
        };
        let len = 3 + n;
        if c.len() < len {
            return if at_end {
                Check::Reject(Error::Truncated { len: c.len() })
            } else {
                Check::Need(len)
            };
        }
        let frame = &c[..len];
        let expected = match c.first_chunk::<{ Command::MAX_LEN }>() {
            // Enough bytes for the longest command: add the payload without
            // branching on its length (the mix of commands in a stream is
            // unpredictable), masking the bytes past it.
            Some(window) => {
                let word = u32::from_le_bytes([window[2], window[3], window[4], 0]);
                // n is 0, 1 or 3: keep its low n bytes.
                let mask = (1u32 << (8 * n)) - 1;
                let bytes = (word & mask).to_le_bytes();
                id.wrapping_add(bytes[0])
                    .wrapping_add(bytes[1])
                    .wrapping_add(bytes[2])
            }
            None => checksum(&frame[1..len - 1]),
        };
        let found = frame[len - 1];
        if expected == found {
            Check::Frame(len)
        } else {
            Check::Reject(Error::Checksum { expected, found })
        }
    }

    fn truncated(&self, len: usize) -> Error {
        Error::Truncated { len }
    }

    fn superseded(&self, len: usize) -> Error {
        Error::Superseded { len }
    }

    fn is_checksum_error(&self, error: &Error) -> bool {
        matches!(error, Error::Checksum { .. })
    }

    #[inline(always)]
    fn parse(&self, frame: &[u8]) -> Result<Packet, Error> {
        parse_frame(frame)
    }

    fn to_owned(message: Packet) -> Packet {
        message
    }
}

/// Turn a frame that passed framing (start byte, accepted id, length and
/// checksum already checked) into a packet.
#[inline(always)]
pub(crate) fn parse_frame(frame: &[u8]) -> Result<Packet, Error> {
    let id = frame.get(1).copied().unwrap_or(0);
    if id == id::TELEMETRY {
        let layout = Layout::from_len(frame.len()).ok_or(Error::Truncated { len: frame.len() })?;
        return Ok(Packet::Telemetry(Telemetry::parse(layout, frame)));
    }
    frame
        .get(2..frame.len().saturating_sub(1))
        .and_then(|payload| Command::from_parts(id, payload))
        .map(Packet::Command)
        .ok_or(Error::UnknownId { id })
}

#[cfg(test)]
mod tests {
    use super::{checksum, sum8};

    #[test]
    fn sum8_equals_the_bytewise_sum() {
        // Lengths across the 8-byte words, the remainder and the 128-word
        // lane flush, over bytes that make the lanes carry.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let bytes: [u8; 1100] = core::array::from_fn(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 24) as u8 | 0x80
        });
        let lengths = (0..=80).chain([127 * 8, 128 * 8, 128 * 8 + 1, 129 * 8 + 7, 1100]);
        for len in lengths {
            for start in [0, 1, 3] {
                let slice = &bytes[start..start + len.min(1100 - start)];
                assert_eq!(sum8(slice), checksum(slice), "len {len} from {start}");
            }
        }
        assert_eq!(sum8(&[0xff; 1100]), (1100u32 * 0xff % 256) as u8);
    }
}
