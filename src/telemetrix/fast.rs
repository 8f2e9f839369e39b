//! The fast paths of the common reports, taken before the full checks.
//!
//! * `check`: a table by report id gives the bytes of a frame (`LEN`, id,
//!   payload) as one range per byte, so accepting a clean frame is two table
//!   loads and eight byte compares (one vector compare), without a branch on
//!   the id; one of those reports cut by the end of a chunk waits for its
//!   whole frame without the full check.
//! * `parse`: the reports a Pico streams (digital, analog, sonar, encoder)
//!   and PONG are read straight from the frame's bytes, each field checked
//!   with one compare, instead of through the field reader.
//!
//! Both are shortcuts, never definitions: what they accept, the full paths
//! accept too, with the same length and the same message (the tests check
//! every table entry and the parse against the full paths); anything else (a
//! longer or rarer report, a sentinel, a value outside the fast range, an id
//! past 63, fewer than 4 bytes) takes the full path, which gives the exact
//! answer, error included.

use super::dialect::Dialect;
use super::report::{Report, Sonar};
use super::wire::report_id as id;

/// The bytes one window holds: the longest frame the table covers (a DHT
/// report, 7 bytes) and one more.
pub(crate) const WINDOW: usize = 8;

/// One report's frame as a range per byte: byte `i` passes when
/// `byte.wrapping_sub(lo[i]) <= span[i]`. Bytes past the frame have span
/// 255 (anything). The unused entry matches nothing: it wants id 0, whose
/// own entry is SERIAL_LOOP_BACK's in every dialect, so no id that reaches
/// the unused entry is 0.
#[derive(Clone, Copy)]
#[repr(C, align(16))]
pub(crate) struct Entry {
    lo: [u8; WINDOW],
    span: [u8; WINDOW],
}

const ANY: (u8, u8) = (0, 255);
/// A GPIO, `0..30`.
const PIN: (u8, u8) = (0, 29);
/// A flag, 0 or 1.
const FLAG: (u8, u8) = (0, 1);
/// Hundredths, `0..100`.
const HUNDREDTHS: (u8, u8) = (0, 99);

const UNUSED: Entry = Entry {
    lo: [0; WINDOW],
    span: [0; WINDOW],
};

/// The entry of report `rid`, `LEN` `len`, with the payload bytes in
/// `ranges` (inclusive).
const fn entry(len: u8, rid: u8, ranges: &[(u8, u8)]) -> Entry {
    let mut lo = [0u8; WINDOW];
    let mut span = [255u8; WINDOW];
    lo[0] = len;
    span[0] = 0;
    lo[1] = rid;
    span[1] = 0;
    let mut i = 0;
    while i < ranges.len() {
        lo[2 + i] = ranges[i].0;
        span[2 + i] = ranges[i].1 - ranges[i].0;
        i += 1;
    }
    Entry { lo, span }
}

/// The table of `dialect`, indexed by the report id's low six bits (the id
/// byte's own range is its exact value, so ids 64 and up never match).
const fn table(dialect: Dialect) -> [Entry; 64] {
    let mirte = dialect.is_mirte();
    let mirte13 = matches!(dialect, Dialect::Mirte13);
    let mut t = [UNUSED; 64];
    t[id::SERIAL_LOOP_BACK as usize] = entry(2, id::SERIAL_LOOP_BACK, &[ANY]);
    t[id::DIGITAL as usize] = entry(3, id::DIGITAL, &[PIN, FLAG]);
    // mirte 1.3 pins are GPIO 26..=30; the ADC numbers of older builds and
    // dialects are 0..=4. Values are 12-bit: the high byte is 0..=15.
    let analog_pin = if mirte13 { (26, 30) } else { (0, 4) };
    t[id::ANALOG as usize] = entry(4, id::ANALOG, &[analog_pin, (0, 15), ANY]);
    t[id::FIRMWARE as usize] = entry(3, id::FIRMWARE, &[ANY, ANY]);
    // Port, then msg_id (mirte) or a 7-bit address (upstream), then a byte.
    let i2c_second = if mirte { ANY } else { (0, 0x7f) };
    t[id::I2C_WRITE as usize] = entry(4, id::I2C_WRITE, &[FLAG, i2c_second, ANY]);
    t[id::SONAR as usize] = match dialect {
        // trig, echo, u16 cm: below 768 cm here (the full path takes the
        // rest of 0..1000 and the sentinels).
        Dialect::Mirte13 => entry(5, id::SONAR, &[PIN, PIN, (0, 2), ANY]),
        // trig, metres, centimetres / trig, centimetres, hundredths.
        Dialect::Mirte12 | Dialect::Upstream11 => entry(4, id::SONAR, &[PIN, ANY, HUNDREDTHS]),
    };
    // pin, humidity, hundredths, temp, hundredths: temperatures of 0 °C and
    // above here (a negative one needs the sign check of the full path).
    t[id::DHT as usize] = entry(6, id::DHT, &[PIN, ANY, HUNDREDTHS, (0, 127), HUNDREDTHS]);
    t[id::I2C_READ_FAILED as usize] = entry(4, id::I2C_READ_FAILED, &[FLAG, (0, 0x7f), ANY]);
    if mirte {
        // Steps are never 0.
        t[id::ENCODER as usize] = entry(3, id::ENCODER, &[PIN, (1, 255)]);
        t[id::PONG as usize] = entry(3, id::PONG, &[ANY, HUNDREDTHS]);
    }
    if mirte13 {
        t[id::SENSOR_MAIN as usize] = entry(4, id::SENSOR_MAIN, &[(0, 0), ANY, FLAG]);
        t[id::MODULE_MAIN as usize] = entry(4, id::MODULE_MAIN, &[(0, 0), ANY, FLAG]);
        t[id::GET_ID as usize] = entry(2, id::GET_ID, &[ANY]);
        t[id::SET_ID as usize] = entry(2, id::SET_ID, &[ANY]);
    }
    t
}

/// A dialect's table, compact: the id's low six bits index `index`, which
/// gives the slot in `entries` (slot 0 is the unused entry): 320 bytes per
/// dialect instead of 1,024 for a flat table, 960 for the three.
struct Compact {
    index: [u8; 64],
    entries: [Entry; SLOTS],
}

/// Slots per dialect: the unused entry and at most 15 reports.
const SLOTS: usize = 16;

const fn compact(table: [Entry; 64]) -> Compact {
    let mut c = Compact {
        index: [0; 64],
        entries: [UNUSED; SLOTS],
    };
    let mut used = 1;
    let mut i = 0;
    while i < 64 {
        if table[i].lo[0] != 0 {
            // Fails the build if a dialect ever has more reports than slots.
            c.entries[used] = table[i];
            c.index[i] = used as u8;
            used += 1;
        }
        i += 1;
    }
    c
}

/// One table per dialect, in [`Dialect`]'s order.
static TABLES: [Compact; 3] = [
    compact(table(Dialect::Mirte13)),
    compact(table(Dialect::Mirte12)),
    compact(table(Dialect::Upstream11)),
];

/// The first [`WINDOW`] bytes of `bytes`, zero past its end, or `None` for
/// fewer than 4 bytes (no frame the table covers is that short but for the
/// 3-byte ones, which the full path takes).
#[inline(always)]
pub(crate) fn window(bytes: &[u8]) -> Option<[u8; WINDOW]> {
    if let Some(w) = bytes.first_chunk::<WINDOW>() {
        return Some(*w);
    }
    // 4..=7 bytes: the first four and the last four, overlapping.
    let head = u32::from_le_bytes(*bytes.first_chunk::<4>()?);
    let tail = u32::from_le_bytes(*bytes.last_chunk::<4>()?);
    let shift = 8 * (bytes.len() - 4) as u32;
    Some((u64::from(head) | u64::from(tail) << shift).to_le_bytes())
}

/// The table entry for report id `rid`.
#[inline(always)]
fn lookup(dialect: Dialect, rid: u8) -> &'static Entry {
    let table = &TABLES[dialect as usize];
    let slot = usize::from(table.index[usize::from(rid & 63)]);
    &table.entries[slot % SLOTS]
}

/// The length of the frame at the start of `w` (a [`window`] of a candidate
/// with `available` bytes) if the table accepts it, without branching on the
/// id.
#[inline(always)]
pub(crate) fn accept(dialect: Dialect, w: &[u8; WINDOW], available: usize) -> Option<usize> {
    let entry = lookup(dialect, w[1]);
    let mut bad = 0u8;
    for ((&byte, &lo), &span) in w.iter().zip(&entry.lo).zip(&entry.span) {
        bad |= u8::from(byte.wrapping_sub(lo) > span);
    }
    let total = usize::from(w[0]) + 1;
    (bad == 0 && total <= available).then_some(total)
}

/// The length `candidate` must reach before it can be decided, if it starts
/// with the `LEN` and id of a table entry and is shorter than that frame
/// (the end of a chunk): the full check waits for the whole frame of these
/// reports whatever the bytes so far hold.
#[inline(always)]
pub(crate) fn need(dialect: Dialect, candidate: &[u8]) -> Option<usize> {
    let (&[len, rid], _) = candidate.split_first_chunk::<2>()?;
    let entry = lookup(dialect, rid);
    let total = usize::from(len) + 1;
    (entry.lo[0] == len && entry.lo[1] == rid && candidate.len() < total).then_some(total)
}

/// The report in `frame` (one whole frame) if it is one of the common
/// reports the table covers, within the table's ranges: the message the full
/// parser gives, checked field by field against the frame's own bytes (a
/// parsed frame is exactly as long as its `LEN` says, so no window is read
/// past it).
#[inline(always)]
pub(crate) fn parse(dialect: Dialect, frame: &[u8]) -> Option<Report<'static>> {
    let mirte = dialect.is_mirte();
    let mirte13 = matches!(dialect, Dialect::Mirte13);
    let pin = |p: u8| p < 30;
    Some(match *frame {
        [3, id::DIGITAL, p, v] if pin(p) && v <= 1 => Report::Digital {
            pin: p,
            value: v != 0,
        },
        [4, id::ANALOG, p, hi, lo]
            if hi <= 15
                && if mirte13 {
                    (26..=30).contains(&p)
                } else {
                    p <= 4
                } =>
        {
            Report::Analog {
                pin: p,
                value: u16::from_be_bytes([hi, lo]),
            }
        }
        [5, id::SONAR, trig, echo, hi, lo] if mirte13 && pin(trig) && pin(echo) && hi <= 2 => {
            Report::Sonar(Sonar::WithEcho {
                trig,
                echo,
                cm: u16::from_be_bytes([hi, lo]),
            })
        }
        [3, id::ENCODER, p, steps] if mirte && pin(p) && steps != 0 => Report::Encoder {
            pin: p,
            steps: steps as i8,
        },
        [3, id::PONG, counter, boot_id] if mirte && boot_id <= 99 => {
            Report::Pong { counter, boot_id }
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    //! The fast paths never change an answer: `check` and the parse give
    //! exactly what the full paths give, for candidates built around every
    //! table entry (each byte swept through all 256 values) and for random
    //! bytes.

    use super::super::framing::{Framing, Host};
    use super::super::report::{parse_report_full, parse_report_with};
    use super::*;

    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn byte(&mut self) -> u8 {
            self.next() as u8
        }
    }

    /// Every prefix of `bytes` gives the same answers on both paths.
    fn agree(dialect: Dialect, bytes: &[u8]) {
        for lenient in [false, true] {
            let framing = Framing::<Host>::new().with_dialect(dialect);
            for end in 0..=bytes.len() {
                let c = &bytes[..end];
                assert_eq!(
                    framing.check_report(c, lenient),
                    framing.check_report_full(c, lenient),
                    "check of {c:02x?} ({dialect:?}, lenient {lenient})"
                );
                assert_eq!(
                    parse_report_with(dialect, lenient, c),
                    parse_report_full(dialect, lenient, c),
                    "parse of {c:02x?} ({dialect:?}, lenient {lenient})"
                );
            }
        }
    }

    /// A byte inside, at the edge of or just outside the range of `entry`'s
    /// byte `i`.
    fn near(rng: &mut Rng, entry: &Entry, i: usize) -> u8 {
        let (lo, hi) = (entry.lo[i], entry.lo[i].wrapping_add(entry.span[i]));
        match rng.next() % 6 {
            0 => lo,
            1 => hi,
            2 => lo.wrapping_sub(1),
            3 => hi.wrapping_add(1),
            4 => lo.wrapping_add((rng.next() % (u64::from(entry.span[i]) + 1)) as u8),
            _ => rng.byte(),
        }
    }

    #[test]
    fn table_entries_agree_with_the_full_paths() {
        let mut rng = Rng(0x7ab1_e5ee_d000_0001);
        let mut accepted = 0;
        let dialects = if cfg!(miri) {
            &Dialect::ALL[..1]
        } else {
            &Dialect::ALL[..]
        };
        for &dialect in dialects {
            for entry in &TABLES[dialect as usize].entries {
                for sweep in 0..WINDOW {
                    // Every value; under Miri, which interprets each
                    // step (CI runs this module there too), a sample.
                    for value in (0..=255u8).step_by(if cfg!(miri) { 255 } else { 1 }) {
                        let mut bytes = [0u8; WINDOW + 2];
                        for (i, b) in bytes.iter_mut().enumerate() {
                            *b = if i < WINDOW {
                                near(&mut rng, entry, i)
                            } else {
                                rng.byte()
                            };
                        }
                        // Mostly the entry's own LEN and id, so the sweep
                        // reaches the payload checks.
                        if rng.next() % 4 != 0 {
                            bytes[0] = entry.lo[0];
                            bytes[1] = entry.lo[1];
                        }
                        bytes[sweep] = value;
                        if accept(dialect, &window(&bytes).unwrap(), bytes.len()).is_some() {
                            accepted += 1;
                        }
                        agree(dialect, &bytes);
                    }
                }
            }
        }
        // The sweep does reach the fast accept.
        assert!(
            accepted > if cfg!(miri) { 10 } else { 10_000 },
            "{accepted}"
        );
    }

    #[test]
    fn random_bytes_agree_with_the_full_paths() {
        let mut rng = Rng(0x0dd_b17e5);
        for _ in 0..if cfg!(miri) { 200 } else { 200_000 } {
            let mut bytes = [0u8; 12];
            for b in &mut bytes {
                *b = rng.byte();
            }
            // A plausible LEN and a low id half the time.
            if rng.next() % 2 == 0 {
                bytes[0] = 2 + (rng.next() % 8) as u8;
                bytes[1] = (rng.next() % 40) as u8;
            }
            let dialect = Dialect::ALL[(rng.next() % 3) as usize];
            agree(dialect, &bytes);
        }
    }

    #[test]
    fn the_window_is_the_bytes_then_zeros() {
        let bytes = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        for len in 0..=bytes.len() {
            let mut expected = [0u8; WINDOW];
            let n = len.min(WINDOW);
            expected[..n].copy_from_slice(&bytes[..n]);
            let got = window(&bytes[..len]);
            assert_eq!(got, (len >= 4).then_some(expected), "{len}");
        }
    }

    #[test]
    fn unused_entries_match_nothing() {
        for dialect in Dialect::ALL {
            // The unused entry wants id 0, whose own entry is used.
            let table = &TABLES[dialect as usize];
            assert_eq!(table.entries[0].lo[1], 0);
            assert_ne!(table.index[usize::from(id::SERIAL_LOOP_BACK)], 0);
            let w = [0u8; WINDOW];
            assert_eq!(accept(dialect, &w, WINDOW), None);
        }
    }
}
