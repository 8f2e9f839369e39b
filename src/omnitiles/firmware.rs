//! The tile firmware's own command parser, reproduced byte for byte: what a
//! tile executed, as opposed to every command a robust decoder can find.

use core::iter::FusedIterator;

use crate::stream::{OwnedFrame, Rejected, Stats};

use super::command::Command;
use super::error::Error;
use super::wire::{payload_len, sum8, MAX_COMMAND_LEN, START};

/// What a [`FirmwareParser`] yields: a command the tile executed, or a
/// candidate it consumed without executing it.
pub type FirmwareEvent = Result<OwnedFrame<Command>, Rejected<Error>>;

/// The tile firmware's command parser (`parser.rs`), byte for byte: it tells
/// which commands a tile *executed*, where a [`DeviceDecoder`] finds every
/// command a host *sent*.
///
/// The firmware's parser is a state machine (WaitStart → WaitId →
/// WaitPayload → WaitChecksum; spec §8, item 4) with four rules that a
/// robust decoder breaks on purpose:
///
/// * it never rescans the bytes it consumed for a candidate that failed;
/// * it takes payload bytes blindly, an `a5` among them;
/// * an `a5` in the id slot is consumed as an (unknown) id;
/// * an unknown id returns it to WaitStart without eating the next byte.
///
/// So `76 a5 a5 31 e7 18` is one command to a [`DeviceDecoder`] (M1 retract
/// 231 at offset 2, found by rescanning after the `a5 a5` candidate) and
/// none to a tile, which takes the second `a5` as an unknown id and then
/// skips `31 e7 18` while it waits for a start byte:
///
/// ```
/// use robowire::omnitiles::{device_decoder, Command, Error, FirmwareParser, Motor};
///
/// let input = [0x76, 0xa5, 0xa5, 0x31, 0xe7, 0x18];
///
/// let mut decoder = device_decoder();
/// let found: Vec<_> = decoder.feed(&input).filter_map(Result::ok).collect();
/// assert_eq!(found[0].message, Command::Retract { motor: Motor::M1, speed: 231 });
///
/// let mut tile = FirmwareParser::new();
/// let events: Vec<_> = tile.feed(&input).collect();
/// assert_eq!(events.len(), 1);
/// let rejected = events[0].unwrap_err();
/// assert_eq!((rejected.offset, rejected.error), (1, Error::UnknownId { id: 0xa5 }));
/// assert_eq!(tile.finish(), None);
/// assert_eq!(tile.stats().frames, 0);
/// ```
///
/// Events come out in stream order with stream offsets, as a
/// [`StreamDecoder`](crate::StreamDecoder)'s do: a frame for every command
/// the tile executed, and a rejection for every candidate it consumed without
/// executing it ([`Error::UnknownId`], [`Error::Checksum`], and from
/// [`finish`](FirmwareParser::finish) [`Error::Truncated`]). The state
/// carries over from one [`feed`](FirmwareParser::feed) to the next, as the
/// tile's single parser does across BLE writes and SPI buffers, so the
/// events never depend on how the input is cut. The [`Stats`] add up as a
/// stream decoder's do (`bytes == frame_bytes + skipped + buffered`), every
/// byte of a failed candidate counting as skipped; `superseded` and
/// `malformed` stay 0. It holds at most one command's bytes and allocates
/// nothing.
///
/// [`DeviceDecoder`]: super::DeviceDecoder
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FirmwareParser {
    /// The current candidate's bytes: start, id, payload (0 bytes in
    /// WaitStart, 1 in WaitId, then the id's payload and the checksum).
    candidate: [u8; MAX_COMMAND_LEN],
    len: u8,
    /// Stream offset of the candidate's start byte.
    start: u64,
    stats: Stats,
}

impl FirmwareParser {
    /// A parser in WaitStart, before any byte.
    pub const fn new() -> Self {
        FirmwareParser {
            candidate: [0; MAX_COMMAND_LEN],
            len: 0,
            start: 0,
            stats: Stats::new(),
        }
    }

    /// Parse one byte, as the tile's `push` does. `Some` when the byte ends a
    /// candidate: the command the tile executes, or why it does not.
    pub fn push(&mut self, byte: u8) -> Option<FirmwareEvent> {
        let offset = self.stats.bytes;
        self.stats.bytes += 1;
        match self.len {
            // WaitStart: anything but a start byte is ignored.
            0 => {
                if byte == START {
                    self.candidate[0] = byte;
                    self.len = 1;
                    self.start = offset;
                } else {
                    self.stats.skipped += 1;
                }
                None
            }
            // WaitId: an unknown id (a5 included) is consumed, back to
            // WaitStart.
            1 => {
                if payload_len(byte).is_some() {
                    self.candidate[1] = byte;
                    self.len = 2;
                    return None;
                }
                self.len = 0;
                self.stats.skipped += 2;
                self.stats.other_rejections += 1;
                Some(Err(Rejected {
                    offset: self.start,
                    error: Error::UnknownId { id: byte },
                }))
            }
            // WaitPayload, then WaitChecksum: bytes taken blindly.
            n => {
                let n = usize::from(n);
                self.candidate[n] = byte;
                let total = 3 + payload_len(self.candidate[1]).unwrap_or(0);
                if n + 1 < total {
                    self.len += 1;
                    return None;
                }
                self.len = 0;
                Some(self.complete(total))
            }
        }
    }

    /// A candidate of `total` bytes has its checksum byte: executed or not.
    fn complete(&mut self, total: usize) -> FirmwareEvent {
        let frame = &self.candidate[..total];
        let offset = self.start;
        let expected = sum8(&frame[1..total - 1]);
        let found = frame[total - 1];
        if expected != found {
            self.stats.skipped += total as u64;
            self.stats.checksum_failures += 1;
            return Err(Rejected {
                offset,
                error: Error::Checksum { expected, found },
            });
        }
        // A known id with its payload always parses; were it not to, it
        // would count as malformed, as in a stream decoder.
        self.stats.frames += 1;
        self.stats.frame_bytes += total as u64;
        match Command::parse_framed(frame) {
            Ok(message) => Ok(OwnedFrame {
                offset,
                len: total,
                message,
            }),
            Err(error) => {
                self.stats.malformed += 1;
                Err(Rejected { offset, error })
            }
        }
    }

    /// Parse `input`: an iterator over the events its bytes complete. Bytes
    /// the iterator has not reached when it is dropped are not parsed.
    pub fn feed<'p, 'i>(&'p mut self, input: &'i [u8]) -> FirmwareFeed<'p, 'i> {
        FirmwareFeed {
            parser: self,
            input,
        }
    }

    /// The input ended: a candidate the tile is still in the middle of is
    /// reported as [`Error::Truncated`], and the parser starts over in
    /// WaitStart.
    pub fn finish(&mut self) -> Option<Rejected<Error>> {
        let len = usize::from(core::mem::take(&mut self.len));
        if len == 0 {
            return None;
        }
        self.stats.skipped += len as u64;
        self.stats.other_rejections += 1;
        Some(Rejected {
            offset: self.start,
            error: Error::Truncated { len },
        })
    }

    /// Bytes of an unfinished candidate held (0 in WaitStart).
    pub const fn buffered(&self) -> usize {
        self.len as usize
    }

    /// The counters so far.
    pub const fn stats(&self) -> Stats {
        self.stats
    }

    /// Back to WaitStart with zero counters and offsets, as [`new`](Self::new).
    pub fn clear(&mut self) {
        *self = FirmwareParser::new();
    }
}

impl Default for FirmwareParser {
    fn default() -> Self {
        FirmwareParser::new()
    }
}

/// The events of one [`FirmwareParser::feed`], in stream order.
#[derive(Debug)]
pub struct FirmwareFeed<'p, 'i> {
    parser: &'p mut FirmwareParser,
    input: &'i [u8],
}

impl Iterator for FirmwareFeed<'_, '_> {
    type Item = FirmwareEvent;

    fn next(&mut self) -> Option<FirmwareEvent> {
        loop {
            if self.parser.len == 0 {
                // WaitStart: skip to the next start byte at once.
                let skip = memchr::memchr(START, self.input).unwrap_or(self.input.len());
                self.parser.stats.bytes += skip as u64;
                self.parser.stats.skipped += skip as u64;
                self.input = &self.input[skip..];
            }
            let (&byte, rest) = self.input.split_first()?;
            self.input = rest;
            if let Some(event) = self.parser.push(byte) {
                return Some(event);
            }
        }
    }
}

impl FusedIterator for FirmwareFeed<'_, '_> {}
