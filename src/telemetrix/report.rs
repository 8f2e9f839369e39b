//! Reports (Pico → host), spec §5.

use super::dialect::Dialect;
use super::error::{ensure, Error};
use super::fast;
use super::kind::{bind_hook, field_type, parse_row, piece, write_field, write_row};
use super::module::{module_report_len_ok, ModuleReport};
use super::quirk::report_quirk;
use super::sensor::{SensorReading, SensorType};
use super::wire::{
    analog_pin_ok, counted, report_known, split_frame, Reader, Writer, I2C_READ_MAX,
    MAX_REPORT_FRAME, SPI_READ_MAX,
};
use crate::encode::check_room;
use crate::{Encode, EncodeError};

/// Sonar distances at or above this (other than the sentinels) are impossible:
/// the firmware gives up after 30 ms of echo, about 517 cm.
const SONAR_CM_LIMIT: u16 = 1000;

/// `report_len_ok`, from the report table's `len` rules.
macro_rules! report_lens {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        /// Whether `len` is possible for a known report, given the frame bytes
        /// known so far (at least `LEN` and id). Never rejects a frame
        /// [`parse_report_with`] accepts.
        pub(crate) fn report_len_ok(dialect: Dialect, len: u8, frame: &[u8]) -> bool {
            let Some(&rid) = frame.get(1) else {
                return true;
            };
            let at = |i: usize| frame.get(i).copied();
            match rid {
                $($n => len_rule!((dialect, len, frame, at), $rlen),)*
                _ => true,
            }
        }

        /// How many frame bytes (counting `LEN` and id) the early `LEN` check
        /// of report `id` looks at.
        pub(crate) const fn report_header_len(id: u8) -> usize {
            match id {
                $($n => len_rule!(header $rlen),)*
                _ => 2,
            }
        }
    };
}

/// A report row's `len` rule: the one `LEN` of a fixed layout, or a closure
/// of the dialect, `LEN`, the frame so far and its byte at an index, after
/// `header(n)` when it looks at more than `LEN` and id (the first `n` bytes);
/// `header` gives that `n`.
macro_rules! len_rule {
    (($dialect:ident, $len:ident, $frame:ident, $at:ident), { $fixed:literal }) => {
        $len == $fixed
    };
    ($ctx:tt, { $(header($n:literal))? |$($param:ident),*| $($body:tt)* }) => {{
        bind_hook!(($($param),*) = $ctx);
        $($body)*
    }};
    (header { header($n:literal) $($rule:tt)* }) => {
        $n
    };
    (header $rule:tt) => {
        2
    };
}

super::table::report_table!(report_lens);

/// The extras a FEATURE_CHECK report carries for a `msg_type` (spec §5).
enum Extras {
    /// One of two lengths (older firmware sent fewer for some ids).
    Len(u8, u8),
    /// 4 bytes, the 4th a count of analog pins that follow.
    Counted,
}

const fn feature_extras(msg_type: u8) -> Extras {
    match msg_type {
        1 => Extras::Counted,
        5 => Extras::Len(2, 2),
        7 => Extras::Len(0, 1),
        10 | 13 => Extras::Len(1, 1),
        30 => Extras::Len(2, 3),
        _ => Extras::Len(0, 0),
    }
}

/// What a sonar reading means.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SonarReading {
    /// A distance, in hundredths of a centimetre.
    Distance {
        /// Distance × 100, in cm.
        hundredths_cm: u32,
    },
    /// `FFFC`: no echo.
    NoEcho,
    /// `FFFD`: echo longer than 30 ms ("+Inf").
    OutOfRange,
    /// `FFFE`: not triggered for more than 1 s ("NaN").
    Stale,
}

/// Sonar `u16` sentinel: no echo.
pub const SONAR_NO_ECHO: u16 = 0xFFFC;
/// Sonar `u16` sentinel: echo longer than 30 ms.
pub const SONAR_OUT_OF_RANGE: u16 = 0xFFFD;
/// Sonar `u16` sentinel: not triggered for more than 1 s.
pub const SONAR_STALE: u16 = 0xFFFE;

/// SONAR_DISTANCE (report 11), in the form the dialect and `LEN` select.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sonar {
    /// mirte 1.3, `LEN` 5: `trig, echo, u16 cm` (or a sentinel).
    WithEcho {
        /// Trigger GPIO.
        trig: u8,
        /// Echo GPIO.
        echo: u8,
        /// Distance in cm, or `SONAR_*` sentinel.
        cm: u16,
    },
    /// mirte 1.3 builds of 2024-09..2025-11, `LEN` 4: `trig, u16 cm`.
    TrigOnly {
        /// Trigger GPIO.
        trig: u8,
        /// Distance in cm, or `SONAR_*` sentinel.
        cm: u16,
    },
    /// mirte 1.2, `LEN` 4: `trig, m, cm` (distance `m·100 + cm`).
    MetresCm {
        /// Trigger GPIO.
        trig: u8,
        /// Metres.
        m: u8,
        /// Centimetres, 0..=99.
        cm: u8,
    },
    /// upstream 1.1, `LEN` 4: `trig, cm, hundredths`.
    CmHundredths {
        /// Trigger GPIO.
        trig: u8,
        /// Centimetres.
        cm: u8,
        /// Hundredths of a centimetre, 0..=99.
        hundredths: u8,
    },
}

impl Sonar {
    /// Trigger GPIO.
    pub const fn trig(&self) -> u8 {
        match *self {
            Sonar::WithEcho { trig, .. }
            | Sonar::TrigOnly { trig, .. }
            | Sonar::MetresCm { trig, .. }
            | Sonar::CmHundredths { trig, .. } => trig,
        }
    }

    /// Echo GPIO, where the form carries it.
    pub const fn echo(&self) -> Option<u8> {
        match *self {
            Sonar::WithEcho { echo, .. } => Some(echo),
            _ => None,
        }
    }

    /// The reading, with the sentinels decoded.
    pub const fn reading(&self) -> SonarReading {
        let cm = match *self {
            Sonar::WithEcho { cm, .. } | Sonar::TrigOnly { cm, .. } => cm,
            Sonar::MetresCm { m, cm, .. } => {
                return SonarReading::Distance {
                    hundredths_cm: (m as u32 * 100 + cm as u32) * 100,
                }
            }
            Sonar::CmHundredths { cm, hundredths, .. } => {
                return SonarReading::Distance {
                    hundredths_cm: cm as u32 * 100 + hundredths as u32,
                }
            }
        };
        match cm {
            SONAR_NO_ECHO => SonarReading::NoEcho,
            SONAR_OUT_OF_RANGE => SonarReading::OutOfRange,
            SONAR_STALE => SonarReading::Stale,
            cm => SonarReading::Distance {
                hundredths_cm: cm as u32 * 100,
            },
        }
    }
}

/// The `Report` enum, from the report table: a `plain` row's variant is
/// built from its fields, a `custom` row gives its variants as written.
macro_rules! report_enum {
    (@rows [$($vars:tt)*]
        $(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt { $name:literal [$p:ident] }
        plain { $($(#[$fm:meta])* $f:ident : $kind:ident $(($($arg:tt)*))? $key:literal),* $(,)? };
        $($rest:tt)*) => {
        report_enum!(@rows [
            $($vars)* $(#[$m])* $p { $($(#[$fm])* $f: field_type!($kind $(($($arg)*))?),)* },
        ] $($rest)*);
    };
    (@rows [$($vars:tt)*]
        $(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt { $($name:literal [$($v:ident),+]),+ }
        custom { variants { $($decl:tt)* } $($hooks:tt)* }; $($rest:tt)*) => {
        report_enum!(@rows [$($vars)* $($decl)*] $($rest)*);
    };
    (@rows [$($vars:tt)*]) => {
        /// A report, Pico → host. Variable byte fields (I2C and SPI data, feature
        /// extras, Hiwonder positions, an unknown report's payload) borrow from the
        /// frame they were parsed from or from the caller;
        /// [`ReportBuf`](super::ReportBuf) is the owned form.
        ///
        /// With the `serde` feature it serializes in the JSON-lines schema of the
        /// `robowire` tool (`{"type":"pong","counter":7,"boot_id":42}`); deserialize
        /// a [`ReportBuf`](super::ReportBuf), which owns its bytes. Sensor floats
        /// that JSON cannot carry are written as `"inf"`, `"-inf"` and
        /// `"nan:0x…"`.
        #[cfg_attr(feature = "defmt", derive(defmt::Format))]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum Report<'a> {
            $($vars)*
            /// A report id the dialect does not define: decoded only by a lenient
            /// [`Framing`](super::Framing) with [`lenient`](super::Framing::lenient).
            Unknown {
                /// The id.
                id: u8,
                /// The payload.
                payload: &'a [u8],
            },
        }
    };
    ($($rows:tt)*) => {
        report_enum!(@rows [] $($rows)*);
    };
}

super::table::report_table!(report_enum);

/// The codec's parts that come from the report table: `Report::id` and
/// every row's payload writer.
macro_rules! report_codec {
    ($($(#[$m:meta])* $n:literal $id:ident in [$($d:ident),+] len $rlen:tt
        { $($name:literal [$($v:ident),+]),+ } $codec:ident { $($body:tt)* };)*) => {
        impl Report<'_> {
            /// The report id.
            pub const fn id(&self) -> u8 {
                match self {
                    $($($(Report::$v { .. })|+)|+ => $n,)*
                    Report::Unknown { id, .. } => *id,
                }
            }

            /// The dialects whose layout this variant has, most recent first
            /// (its row's `home` piece, or the row's dialects): a frame this
            /// report encodes to parses back to it in each of them where it is
            /// valid (an unknown report: where its id is unknown).
            pub(crate) const fn home_dialects(&self) -> &'static [Dialect] {
                match *self {
                    $($($(Report::$v { .. })|+)|+ => {
                        piece!(home (self) expr { &[$(Dialect::$d),+] }, $codec { $($body)* })
                    })*
                    Report::Unknown { .. } => &Dialect::ALL,
                }
            }

            fn write_payload(&self, w: &mut Writer<'_>, dialect: Dialect) {
                match *self {
                    $($($(Report::$v { .. })|+)|+ => {
                        write_row!(self, (w, dialect), Report, [$($($v)+)+] $codec { $($body)* })
                    })*
                    Report::Unknown { payload, .. } => w.bytes(payload),
                }
            }
        }

        /// Parse a report's payload: an arm per row of the report table.
        fn parse_payload<'a>(dialect: Dialect, r: &mut Reader<'a>) -> Result<Report<'a>, Error> {
            let rid = r.id();
            Ok(match rid {
                $($n => parse_row!((dialect, &mut *r, rid), r, rid, Report, [$($($v)+)+] $codec { $($body)* }),)*
                _ => return Err(Error::UnknownId { id: rid }),
            })
        }
    };
}

super::table::report_table!(report_codec);

impl Report<'_> {
    /// Frame length of this report in `dialect`.
    pub fn encoded_len_in(&self, dialect: Dialect) -> usize {
        let mut w = Writer::new(&mut []);
        self.write(&mut w, dialect);
        w.len()
    }

    /// Encode this report for `dialect` into the front of `out`; returns the
    /// frame length. Nothing is written on error.
    pub fn encode_in(&self, dialect: Dialect, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.encode_checked(dialect, out, false)
    }

    /// [`encode_in`](Self::encode_in), which with `even_if_refused` also
    /// emits a frame that has a quirk.
    pub(crate) fn encode_checked(
        &self,
        dialect: Dialect,
        out: &mut [u8],
        even_if_refused: bool,
    ) -> Result<usize, EncodeError> {
        self.check_dialect(dialect)?;
        let n = self.encoded_len_in(dialect);
        if n > MAX_REPORT_FRAME {
            return Err(EncodeError::TooLong {
                len: n - 1,
                max: MAX_REPORT_FRAME - 1,
            });
        }
        check_room(out, n)?;
        let mut scratch = [0u8; MAX_REPORT_FRAME];
        let mut w = Writer::new(&mut scratch);
        self.write(&mut w, dialect);
        let frame = scratch.get(..n).unwrap_or(&[]);
        // The decoder is the one definition of a valid frame.
        let lenient = matches!(self, Report::Unknown { .. });
        parse_report_with(dialect, lenient, frame).map_err(Error::into_encode_error)?;
        // ... nor anything it flags.
        match report_quirk(dialect, frame) {
            Some(quirk) if !even_if_refused => return Err(quirk.into_encode_error(frame)),
            _ => {}
        }
        if let Some(dst) = out.get_mut(..n) {
            dst.copy_from_slice(frame);
        }
        Ok(n)
    }

    fn check_dialect(&self, dialect: Dialect) -> Result<(), EncodeError> {
        let ok = match *self {
            Report::Unknown { id, .. } => !report_known(dialect, id),
            _ => self.home_dialects().contains(&dialect),
        };
        if ok {
            Ok(())
        } else {
            Err(EncodeError::Inconsistent {
                what: "the report does not exist in this dialect",
            })
        }
    }

    /// Write the frame into `out` without checking it; returns its length
    /// (which may exceed `out`, whose bytes past the end are then not
    /// written). The bytes do not depend on the dialect.
    pub(crate) fn write_unchecked(&self, out: &mut [u8]) -> usize {
        let mut w = Writer::new(out);
        self.write(&mut w, Dialect::Mirte13);
        w.len()
    }

    fn write(&self, w: &mut Writer<'_>, dialect: Dialect) {
        w.u8(0);
        w.u8(self.id());
        self.write_payload(w, dialect);
        w.patch_len();
    }
}

impl Encode for Report<'_> {
    const MAX_LEN: usize = MAX_REPORT_FRAME;

    /// The frame length in the default dialect (mirte 1.3).
    fn encoded_len(&self) -> usize {
        self.encoded_len_in(Dialect::Mirte13)
    }

    /// Encode for the default dialect (mirte 1.3); see [`Report::encode_in`]
    /// and [`InDialect`](super::InDialect) for others.
    fn encode(&self, out: &mut [u8]) -> Result<usize, EncodeError> {
        self.encode_in(Dialect::Mirte13, out)
    }
}

/// Parse one complete report frame (`LEN` byte first) for `dialect`, with
/// unknown ids accepted as [`Report::Unknown`] when `lenient`. This is the one
/// definition of a valid report: the decoder accepts exactly what it accepts,
/// and the encoder emits nothing it rejects. The common streamed reports take
/// a fast path (`fast::parse`), which gives exactly what
/// [`parse_report_full`] gives (the fast module's tests check it).
#[inline]
pub(crate) fn parse_report_with(
    dialect: Dialect,
    lenient: bool,
    frame: &[u8],
) -> Result<Report<'_>, Error> {
    match fast::parse(dialect, frame) {
        Some(report) => Ok(report),
        None => parse_report_full(dialect, lenient, frame),
    }
}

/// [`parse_report_with`] for every report, each field checked in turn (out
/// of line: the fast path takes the common ones).
#[inline(never)]
pub(super) fn parse_report_full(
    dialect: Dialect,
    lenient: bool,
    frame: &[u8],
) -> Result<Report<'_>, Error> {
    let (len, rid, payload) = split_frame(frame)?;
    if !report_known(dialect, rid) {
        return if lenient {
            Ok(Report::Unknown { id: rid, payload })
        } else {
            Err(Error::UnknownId { id: rid })
        };
    }
    if !report_len_ok(dialect, len, frame) {
        return Err(Error::BadLength { id: rid, len });
    }
    let mut r = Reader::new(rid, len, payload);
    let report = parse_payload(dialect, &mut r)?;
    r.end()?;
    Ok(report)
}

fn sonar_cm(r: &mut Reader<'_>) -> Result<u16, Error> {
    let cm = r.u16()?;
    let ok = cm < SONAR_CM_LIMIT || (SONAR_NO_ECHO..=SONAR_STALE).contains(&cm);
    ensure(ok, r.id(), "cm")?;
    Ok(cm)
}

impl<'a> Report<'a> {
    /// Parse one complete report frame (`LEN` byte first, nothing after the
    /// frame) of `dialect`; unknown ids are errors.
    /// [`TryFrom<&[u8]>`](#impl-TryFrom%3C%26%5Bu8%5D%3E-for-Report%3C'a%3E)
    /// parses mirte 1.3.
    ///
    /// ```
    /// use robowire::telemetrix::{Dialect, Report, Sonar};
    ///
    /// let sonar = Report::parse_in(&[0x04, 0x0B, 0x09, 0x01, 0x14], Dialect::Mirte12)?;
    /// assert_eq!(sonar, Report::Sonar(Sonar::MetresCm { trig: 9, m: 1, cm: 20 }));
    /// # Ok::<(), robowire::telemetrix::Error>(())
    /// ```
    pub fn parse_in(frame: &'a [u8], dialect: Dialect) -> Result<Self, Error> {
        parse_report_with(dialect, false, frame)
    }

    /// Like [`parse_in`](Self::parse_in), with ids the dialect does not
    /// define read as [`Report::Unknown`] (what a
    /// [`lenient`](super::Framing::lenient) framing accepts).
    pub fn parse_lenient_in(frame: &'a [u8], dialect: Dialect) -> Result<Self, Error> {
        parse_report_with(dialect, true, frame)
    }
}

/// Parse one complete mirte 1.3 report frame (`LEN` byte first); see
/// [`Report::parse_in`] for other dialects.
impl<'a> TryFrom<&'a [u8]> for Report<'a> {
    type Error = Error;

    fn try_from(frame: &'a [u8]) -> Result<Self, Error> {
        parse_report_with(Dialect::Mirte13, false, frame)
    }
}
