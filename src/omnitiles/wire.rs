//! The wire's fixed facts: the start byte, the message ids, each command's
//! payload length, the longest frame and the checksum. A leaf: it imports
//! nothing from the other OmniTiles modules, which all build on it.

/// The start byte of every frame.
pub const START: u8 = 0xA5;

/// The longest frame of either direction (the 53-byte BLE telemetry).
pub const MAX_FRAME_LEN: usize = 53;

/// The longest command frame (base velocity: start, id, three bytes, sum).
pub(crate) const MAX_COMMAND_LEN: usize = 6;

/// Message ids (spec §3).
pub mod id {
    /// M1 extend, u8 speed.
    pub const M1_EXTEND: u8 = 0x30;
    /// M1 retract, u8 speed.
    pub const M1_RETRACT: u8 = 0x31;
    /// M1 brake.
    pub const M1_BRAKE: u8 = 0x32;
    /// M1 set position, u8 scaled over the stroke.
    pub const M1_SET_POSITION: u8 = 0x33;
    /// M2 extend, u8 speed.
    pub const M2_EXTEND: u8 = 0x40;
    /// M2 retract, u8 speed.
    pub const M2_RETRACT: u8 = 0x41;
    /// M2 brake.
    pub const M2_BRAKE: u8 = 0x42;
    /// M2 set position, u8 scaled over the stroke.
    pub const M2_SET_POSITION: u8 = 0x43;
    /// Ping (no reply).
    pub const PING: u8 = 0x50;
    /// Telemetry, tile → host only.
    pub const TELEMETRY: u8 = 0x60;
    /// Mecanum base velocity, three i8.
    pub const BASE_VELOCITY: u8 = 0x70;
    /// Brake all four wheels.
    pub const BASE_BRAKE: u8 = 0x71;
}

/// Payload length of a command id, or `None` if the id is no command.
///
/// ```
/// use robowire::omnitiles::{id, payload_len};
/// assert_eq!(payload_len(id::BASE_VELOCITY), Some(3));
/// assert_eq!(payload_len(id::TELEMETRY), None); // telemetry has no fixed length
/// ```
#[inline]
pub const fn payload_len(id: u8) -> Option<usize> {
    // One table load instead of a chain of comparisons on the hot path. The
    // table spans the command ids only (0x30..=0x71), 66 bytes of flash.
    let at = id.wrapping_sub(FIRST_COMMAND) as usize;
    if at >= PAYLOAD_LEN.len() {
        return None;
    }
    match PAYLOAD_LEN[at] {
        NOT_A_COMMAND => None,
        n => Some(n as usize),
    }
}

/// The lowest and highest command ids: [`PAYLOAD_LEN`] covers them.
const FIRST_COMMAND: u8 = id::M1_EXTEND;
const LAST_COMMAND: u8 = id::BASE_BRAKE;

/// [`PAYLOAD_LEN`] entry of an id that is no command.
const NOT_A_COMMAND: u8 = u8::MAX;

/// Payload length by id from [`FIRST_COMMAND`], [`NOT_A_COMMAND`] for ids
/// that are no command.
const PAYLOAD_LEN: [u8; (LAST_COMMAND - FIRST_COMMAND) as usize + 1] = {
    let mut table = [NOT_A_COMMAND; (LAST_COMMAND - FIRST_COMMAND) as usize + 1];
    let mut id = 0;
    while id < 256 {
        if let Some(n) = command_payload_len(id as u8) {
            // Every command id lies in the table's range (checked at compile
            // time: an id outside it fails this index).
            table[id - FIRST_COMMAND as usize] = n as u8;
        }
        id += 1;
    }
    table
};

/// The command table (spec §3) that [`PAYLOAD_LEN`] is built from.
const fn command_payload_len(id: u8) -> Option<usize> {
    match id {
        id::M1_EXTEND | id::M1_RETRACT | id::M1_SET_POSITION => Some(1),
        id::M2_EXTEND | id::M2_RETRACT | id::M2_SET_POSITION => Some(1),
        id::M1_BRAKE | id::M2_BRAKE | id::PING | id::BASE_BRAKE => Some(0),
        id::BASE_VELOCITY => Some(3),
        _ => None,
    }
}

/// The checksum of a frame: the wrapping sum of its id and payload bytes.
///
/// ```
/// assert_eq!(robowire::omnitiles::checksum(&[0x30, 0xc8]), 0xf8);
/// ```
pub fn checksum(id_and_payload: &[u8]) -> u8 {
    id_and_payload.iter().fold(0u8, |s, &b| s.wrapping_add(b))
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

#[cfg(test)]
mod tests {
    use super::{checksum, command_payload_len, payload_len, sum8};

    #[test]
    fn the_payload_table_is_the_command_table() {
        for id in 0..=u8::MAX {
            assert_eq!(payload_len(id), command_payload_len(id), "id {id:#04x}");
        }
    }

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
