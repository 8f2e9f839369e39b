//! Decoding datagrams: byte runs whose boundaries the transport already knows
//! (one BLE notification, one 128-byte SPI buffer, one BLE write).

use super::framing::{parse_frame, Framing};
use super::layout::Layout;
use super::{checksum, id, Decoder, Packet, START};
use crate::stream::{owned_event, OwnedEvent, OwnedFrame, Stats};

/// Decodes one datagram at a time. Because the datagram's length is known, a
/// telemetry layout is picked by it: a datagram that starts `a5 60` is one
/// telemetry frame of the enabled layout with exactly its length, or else of
/// the shortest enabled layout whose checksum validates and after which only
/// zero padding follows (the SPI buffer: 45 bytes + 83 × `00`). Anything else
/// — several commands back to back, commands followed by padding, garbage —
/// goes through the stream decoder, finished at the datagram's end, so all
/// commands come out and no state leaks into the next datagram.
///
/// Offsets count from the first byte of the first datagram, as if all
/// datagrams were concatenated.
///
/// ```
/// use robowire::omnitiles::{Command, DatagramDecoder, Framing, Motor, Packet};
/// let mut brake_buffer = [0u8; 128];
/// brake_buffer[..6].copy_from_slice(&[0xa5, 0x32, 0x32, 0xa5, 0x42, 0x42]);
/// let mut datagrams = DatagramDecoder::new(Framing::commands());
/// let packets: Vec<Packet> = datagrams
///     .decode(&brake_buffer)
///     .map(|event| event.unwrap().message)
///     .collect();
/// assert_eq!(packets, [
///     Packet::Command(Command::Brake { motor: Motor::M1 }),
///     Packet::Command(Command::Brake { motor: Motor::M2 }),
/// ]);
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub struct DatagramDecoder {
    framing: Framing,
    offset: u64,
    stats: Stats,
}

impl DatagramDecoder {
    /// A datagram decoder accepting what `framing` accepts.
    pub const fn new(framing: Framing) -> Self {
        Self {
            framing,
            offset: 0,
            stats: Stats::new(),
        }
    }

    /// The counters over every datagram so far.
    pub const fn stats(&self) -> Stats {
        self.stats
    }

    /// The events in one datagram, in order.
    pub fn decode<'d, 'a>(&'d mut self, datagram: &'a [u8]) -> Datagram<'d, 'a> {
        let base = self.offset;
        self.offset += datagram.len() as u64;
        let whole = self.whole_telemetry(datagram);
        Datagram {
            engine: Decoder::new(self.framing),
            owner: self,
            rest: if whole.is_some() { &[] } else { datagram },
            whole,
            base,
            finished: false,
        }
    }

    /// The layout of a datagram that is exactly one telemetry frame, possibly
    /// zero-padded.
    fn telemetry_layout(&self, datagram: &[u8]) -> Option<Layout> {
        if !matches!(datagram, [START, id::TELEMETRY, ..]) {
            return None;
        }
        let layouts = self.framing.layouts();
        let valid = |layout: Layout| {
            let len = layout.frame_len();
            checksum(&datagram[1..len - 1]) == datagram[len - 1]
        };
        if let Some(exact) = Layout::from_len(datagram.len()).filter(|l| layouts.contains(*l)) {
            return Some(exact).filter(|l| valid(*l));
        }
        layouts.iter().find(|l| {
            l.frame_len() < datagram.len()
                && datagram[l.frame_len()..].iter().all(|&b| b == 0)
                && valid(*l)
        })
    }

    fn whole_telemetry(&mut self, datagram: &[u8]) -> Option<OwnedFrame<Packet>> {
        let layout = self.telemetry_layout(datagram)?;
        let len = layout.frame_len();
        let message = parse_frame(&datagram[..len]).ok()?;
        self.stats.bytes += datagram.len() as u64;
        self.stats.frames += 1;
        self.stats.frame_bytes += len as u64;
        self.stats.skipped += (datagram.len() - len) as u64;
        Some(OwnedFrame {
            offset: self.offset - datagram.len() as u64,
            len,
            message,
        })
    }
}

/// Iterator over the events of one datagram; see [`DatagramDecoder::decode`].
#[derive(Debug)]
pub struct Datagram<'d, 'a> {
    owner: &'d mut DatagramDecoder,
    engine: Decoder,
    whole: Option<OwnedFrame<Packet>>,
    rest: &'a [u8],
    base: u64,
    finished: bool,
}

impl Iterator for Datagram<'_, '_> {
    type Item = OwnedEvent<Framing>;

    fn next(&mut self) -> Option<Self::Item> {
        if let Some(frame) = self.whole.take() {
            return Some(Ok(frame));
        }
        if self.finished {
            return None;
        }
        let event = match self.engine.decode(&mut self.rest) {
            Some(event) => Some(owned_event::<Framing>(event)),
            None => self.engine.finish().map(owned_event::<Framing>),
        };
        let Some(event) = event else {
            self.finished = true;
            self.owner.stats.add(&self.engine.stats());
            return None;
        };
        Some(
            event
                .map(|mut f| {
                    f.offset += self.base;
                    f
                })
                .map_err(|mut r| {
                    r.offset += self.base;
                    r
                }),
        )
    }
}

#[cfg(feature = "defmt")]
impl defmt::Format for Datagram<'_, '_> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "Datagram {{ base: {=u64}, unread: {=usize}, finished: {=bool} }}",
            self.base,
            self.rest.len(),
            self.finished
        )
    }
}
