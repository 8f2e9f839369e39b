//! Decoding datagrams: byte runs whose boundaries the transport already knows
//! (one BLE notification, one 128-byte SPI buffer, one BLE write).

use super::framing::{Both, Device, Framing, Host, Side};
use super::layout::Layout;
use super::wire::{checksum, id, START};
use crate::stream::{owned_event, OwnedEvent, OwnedFrame, Stats, StreamDecoder};

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
/// use robowire::omnitiles::{Command, DeviceDatagramDecoder, Framing, Motor};
/// let mut brake_buffer = [0u8; 128];
/// brake_buffer[..6].copy_from_slice(&[0xa5, 0x32, 0x32, 0xa5, 0x42, 0x42]);
/// // The tile's side: commands only.
/// let mut datagrams = DeviceDatagramDecoder::new(Framing::new());
/// let mut commands = Vec::new();
/// for event in datagrams.decode(&brake_buffer) {
///     commands.push(event.unwrap().message);
/// }
/// assert_eq!(commands, [
///     Command::Brake { motor: Motor::M1 },
///     Command::Brake { motor: Motor::M2 },
/// ]);
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone)]
pub struct DatagramDecoder<S> {
    framing: Framing<S>,
    offset: u64,
    stats: Stats,
}

/// The stream decoder a datagram that is not one whole telemetry frame goes
/// through.
type Engine<S> = StreamDecoder<Framing<S>, { super::BOTH_BUFFER }>;

impl<S: Side> DatagramDecoder<S> {
    /// A datagram decoder accepting what `framing` accepts.
    pub const fn new(framing: Framing<S>) -> Self {
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
    pub fn decode<'d, 'a>(&'d mut self, datagram: &'a [u8]) -> Datagram<'d, 'a, S> {
        let base = self.offset;
        self.offset += datagram.len() as u64;
        let whole = self.whole_telemetry(datagram);
        Datagram {
            engine: Engine::new(self.framing),
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

    fn whole_telemetry(&mut self, datagram: &[u8]) -> Option<OwnedFrame<S::Message>> {
        let layout = self.telemetry_layout(datagram)?;
        let len = layout.frame_len();
        let message = S::parse(&datagram[..len]).ok()?;
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

/// How many zero-padded SPI telemetry buffers `bytes` holds: places where a
/// valid [`Layout::Spi45`] frame is followed by zero padding (eight `00`, or
/// at least one up to the end of `bytes`), as the STM32 hands its 45-byte
/// frame to the nRF in a 128-byte buffer. A stream where they recur was
/// captured on that SPI bus: decode it with `Spi45` among the layouts, or one
/// buffer at a time with a [`DatagramDecoder`]. With the documented layouts
/// its padding is skipped, its frames are lost, a buffer whose checksum byte
/// is `0x00` or `0x80` reads as a false 53-byte frame, and now and then a
/// prefix of a frame validates as a shorter layout (in `tests/data`'s 64
/// buffers: a 53-, a 17- and a 7-byte false frame).
///
/// ```
/// let mut buffer = [0u8; 128];
/// buffer[..7].copy_from_slice(&[0xa5, 0x60, 0xd0, 0x07, 0xe8, 0x03, 0x41]);
/// buffer[44] = robowire::omnitiles::checksum(&buffer[1..44]);
/// assert_eq!(robowire::omnitiles::padded_spi_frames(&buffer.repeat(3)), 3);
/// assert_eq!(robowire::omnitiles::padded_spi_frames(&buffer[..45]), 0);
/// ```
pub fn padded_spi_frames(bytes: &[u8]) -> usize {
    const LEN: usize = Layout::Spi45.frame_len();
    const PADDING: usize = Layout::Ble53.frame_len() - LEN;
    let (mut count, mut i) = (0, 0);
    while i + LEN < bytes.len() {
        let frame = &bytes[i..i + LEN];
        let padding = &bytes[i + LEN..bytes.len().min(i + LEN + PADDING)];
        if frame[..2] == [START, id::TELEMETRY]
            && checksum(&frame[1..LEN - 1]) == frame[LEN - 1]
            && padding.iter().all(|&b| b == 0)
        {
            count += 1;
            i += LEN;
        } else {
            i += 1;
        }
    }
    count
}

/// A datagram decoder on the host's side: telemetry.
pub type HostDatagramDecoder = DatagramDecoder<Host>;
/// A datagram decoder on the device's side: commands.
pub type DeviceDatagramDecoder = DatagramDecoder<Device>;
/// A datagram decoder for both directions.
pub type BothDatagramDecoder = DatagramDecoder<Both>;

/// Iterator over the events of one datagram; see [`DatagramDecoder::decode`].
#[derive(Debug)]
pub struct Datagram<'d, 'a, S: Side> {
    owner: &'d mut DatagramDecoder<S>,
    engine: Engine<S>,
    whole: Option<OwnedFrame<S::Message>>,
    rest: &'a [u8],
    base: u64,
    finished: bool,
}

impl<S: Side> Iterator for Datagram<'_, '_, S> {
    type Item = OwnedEvent<Framing<S>>;

    fn next(&mut self) -> Option<Self::Item> {
        if let Some(frame) = self.whole.take() {
            return Some(Ok(frame));
        }
        if self.finished {
            return None;
        }
        let event = match self.engine.decode(&mut self.rest) {
            Some(event) => Some(owned_event::<Framing<S>>(event)),
            None => self.engine.finish().map(owned_event::<Framing<S>>),
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
impl<S: Side> defmt::Format for Datagram<'_, '_, S> {
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
