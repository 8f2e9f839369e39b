//! The wire's building blocks, shared by every other Pixy2 module and
//! importing none of them: the two sync words and frame forms, the packet
//! type numbers, the length limits, the checksum, and the one routine that
//! writes a header around a payload.

use crate::encode::{check_room, EncodeError};

/// Sync word of the no-checksum form, `ae c1` on the wire.
pub const SYNC_NO_CHECKSUM: u16 = 0xc1ae;
/// Sync word of the checksum form, `af c1` on the wire.
pub const SYNC_CHECKSUM: u16 = 0xc1af;
/// Longest payload the length byte can describe.
pub const MAX_PAYLOAD: usize = 255;
/// Longest frame of either direction: checksum header and a 255-byte payload
/// (261 bytes).
pub const MAX_FRAME_LEN: usize = 6 + MAX_PAYLOAD;
/// Longest request payload the device receives; longer requests are dropped
/// without an answer (spec §3).
pub const DEVICE_MAX_PAYLOAD: usize = 64;

/// Packet type numbers (spec §4). Requests are even, responses odd.
pub mod packet_type {
    /// Generic result, 4-byte i32 (response).
    pub const RESULT: u8 = 0x01;
    /// changeProg (request).
    pub const CHANGE_PROG: u8 = 0x02;
    /// Generic error, 1-byte i8 code (response).
    pub const ERROR: u8 = 0x03;
    /// getResolution (request).
    pub const GET_RESOLUTION: u8 = 0x0c;
    /// Resolution (response).
    pub const RESOLUTION: u8 = 0x0d;
    /// getVersion (request).
    pub const GET_VERSION: u8 = 0x0e;
    /// Version (response).
    pub const VERSION: u8 = 0x0f;
    /// setCameraBrightness (request).
    pub const SET_CAMERA_BRIGHTNESS: u8 = 0x10;
    /// setServos (request).
    pub const SET_SERVOS: u8 = 0x12;
    /// setLED (request).
    pub const SET_LED: u8 = 0x14;
    /// setLamp (request).
    pub const SET_LAMP: u8 = 0x16;
    /// getFPS (request).
    pub const GET_FPS: u8 = 0x18;
    /// getBlocks (request).
    pub const GET_BLOCKS: u8 = 0x20;
    /// Blocks (response).
    pub const BLOCKS: u8 = 0x21;
    /// getFeatures (request).
    pub const GET_FEATURES: u8 = 0x30;
    /// Line features (response).
    pub const FEATURES: u8 = 0x31;
    /// setMode (request).
    pub const SET_MODE: u8 = 0x36;
    /// setVector (request).
    pub const SET_VECTOR: u8 = 0x38;
    /// setNextTurn (request).
    pub const SET_NEXT_TURN: u8 = 0x3a;
    /// setDefaultTurn (request).
    pub const SET_DEFAULT_TURN: u8 = 0x3c;
    /// reverseVector (request).
    pub const REVERSE_VECTOR: u8 = 0x3e;
    /// getRGB (request).
    pub const GET_RGB: u8 = 0x70;
}

/// The two frame forms (spec §2.1).
///
/// Its name ([`Display`](core::fmt::Display), [`FromStr`](core::str::FromStr)
/// and, with the `serde` feature, its serialized form) is `no_checksum` or
/// `checksum`.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Form {
    /// `ae c1` · type · len · payload: what the official host sends.
    NoChecksum,
    /// `af c1` · type · len · checksum u16 LE · payload: what the device
    /// always sends over SPI, I2C and UART.
    Checksum,
}

impl Form {
    /// Both forms, by name.
    pub const NAMES: [&'static str; 2] = ["no_checksum", "checksum"];

    /// The form whose sync word starts with `byte`.
    pub const fn from_start_byte(byte: u8) -> Option<Self> {
        match byte {
            0xae => Some(Self::NoChecksum),
            0xaf => Some(Self::Checksum),
            _ => None,
        }
    }

    /// The sync word as it appears on the wire (low byte first).
    pub const fn sync_bytes(self) -> [u8; 2] {
        match self {
            Self::NoChecksum => SYNC_NO_CHECKSUM.to_le_bytes(),
            Self::Checksum => SYNC_CHECKSUM.to_le_bytes(),
        }
    }

    /// Bytes before the payload: 4 or 6.
    pub const fn header_len(self) -> usize {
        match self {
            Self::NoChecksum => 4,
            Self::Checksum => 6,
        }
    }

    /// The name: `no_checksum` or `checksum`.
    pub const fn name(self) -> &'static str {
        match self {
            Self::NoChecksum => "no_checksum",
            Self::Checksum => "checksum",
        }
    }
}

/// The checksum of a payload: the wrapping 16-bit sum of its bytes.
///
/// ```
/// assert_eq!(robowire::pixy2::checksum(&[0xff, 0xff, 0x02]), 0x0200);
/// ```
#[inline]
pub fn checksum(payload: &[u8]) -> u16 {
    if !VECTOR {
        // Without vector registers the plain loop is the smallest and as fast.
        return payload
            .iter()
            .fold(0u16, |sum, &b| sum.wrapping_add(u16::from(b)));
    }
    // Sixteen u16 lanes, one vector register: each step widens and adds
    // sixteen bytes at once (a single running sum is widened eight bytes at
    // a time and reduced in a tail loop four at a time). The rest, under
    // sixteen bytes, is added eight at a time in a u64 (four u16 lanes) and
    // then byte by byte. Wrapping sums are associative, so the grouping does
    // not change the result.
    let mut lanes = [0u16; 16];
    let mut blocks = payload.chunks_exact(16);
    for block in &mut blocks {
        for (lane, &b) in lanes.iter_mut().zip(block) {
            *lane = lane.wrapping_add(u16::from(b));
        }
    }
    let mut sum = lanes.iter().fold(0u16, |s, &l| s.wrapping_add(l));
    let mut words = blocks.remainder().chunks_exact(8);
    if let Some(word) = words.next().and_then(|w| w.first_chunk::<8>()) {
        const LOW: u64 = 0x00ff_00ff_00ff_00ff;
        let w = u64::from_le_bytes(*word);
        let pairs = (w & LOW) + ((w >> 8) & LOW);
        // The four lanes' total lands in the top lane.
        sum = sum.wrapping_add((pairs.wrapping_mul(0x0001_0001_0001_0001) >> 48) as u16);
    }
    words
        .remainder()
        .iter()
        .fold(sum, |s, &b| s.wrapping_add(u16::from(b)))
}

/// Whether the target has vector registers (SSE2, NEON): where the
/// decoder's wide checksum and inlined fast paths pay for their size.
pub(crate) const VECTOR: bool = cfg!(any(target_feature = "sse2", target_feature = "neon"));

/// What the shared encoder needs from a message (crate-private).
pub(crate) trait Body {
    fn packet_type(&self) -> u8;
    fn payload_len(&self) -> usize;
    /// Write the payload into `out`, which is exactly `payload_len` long;
    /// reject values the receiver would refuse.
    fn write_payload(&self, out: &mut [u8]) -> Result<(), EncodeError>;
    /// The form used when the message is encoded without an envelope.
    fn default_form(&self) -> Form;
}

/// Encode `body` as one frame of `form` into `out`.
pub(crate) fn encode_body<B: Body + ?Sized>(
    form: Form,
    body: &B,
    out: &mut [u8],
) -> Result<usize, EncodeError> {
    let len = body.payload_len();
    if len > MAX_PAYLOAD {
        return Err(EncodeError::TooLong {
            len,
            max: MAX_PAYLOAD,
        });
    }
    let header = form.header_len();
    let total = header + len;
    check_room(out, total)?;
    let (head, rest) = out.split_at_mut(header);
    let payload = &mut rest[..len];
    body.write_payload(payload)?;
    let [s0, s1] = form.sync_bytes();
    head[0] = s0;
    head[1] = s1;
    head[2] = body.packet_type();
    head[3] = len as u8;
    if form == Form::Checksum {
        head[4..6].copy_from_slice(&checksum(payload).to_le_bytes());
    }
    Ok(total)
}
