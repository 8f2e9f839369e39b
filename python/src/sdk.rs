//! `robowire.omnitiles.sdk`: a drop-in for the OmniTiles SDK's stream parser
//! (`omnitiles.protocol.StreamParser` and its `Telemetry`), decoding with
//! robowire's engine.
//!
//! The field names, types and meanings are the SDK's (its
//! `sdk/src/omnitiles/telemetry.py`, Clue88/OmniTiles): `timestamp`,
//! `m1_pos_adc`, `m2_pos_adc`, `m1_pos_mm`, `m2_pos_mm`, `m1_adcs`, `m2_adcs`
//! (empty tuples when the layout has none), `uwb_mm`, `tof_mm`, `imu`, `raw`.
//! Where robowire differs it says so in docs/python.md: a position of
//! 0xFFFF is `None` (the SDK keeps 65535 and 2400 mm), no false short frame
//! at a chunk boundary and no stall on a stray 0xA5.

use pyo3::basic::CompareOp;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyList, PyTuple};
use robowire::omnitiles::units::ADC_FULL_SCALE;
use robowire::omnitiles::{Framing, Host, Telemetry, HOST_BUFFER};
use robowire::stream::OwnedFrame;
use robowire::StreamDecoder;

use crate::clock::Clock;
use crate::engine::{decode_events, stats_dict, with_bytes, Resolve};
use crate::typed::{compared, frame_bytes, hash_of, untracked, PyImu};

/// How ADC counts become millimetres: ``adc / adc_max * stroke`` in
/// Python's float arithmetic, as the SDK computes it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Scale {
    adc_max: f64,
    m1_stroke_mm: f64,
    m2_stroke_mm: f64,
}

impl Scale {
    fn mm(self, adc: Option<u16>, stroke: f64) -> Option<f64> {
        adc.map(|adc| f64::from(adc) / self.adc_max * stroke)
    }
}

/// One telemetry frame with the OmniTiles SDK's fields (its ``Telemetry``
/// dataclass): ``timestamp`` (the receive time, seconds of the parser's
/// clock), ``m1_pos_adc``, ``m2_pos_adc`` (raw 0..4095), ``m1_pos_mm``,
/// ``m2_pos_mm`` (``adc / 4095 * 150`` and ``* 100``), ``m1_adcs`` and
/// ``m2_adcs`` (tuples, empty when the layout has none), ``uwb_mm`` (four
/// ranges, each ``None`` when invalid, or ``None``), ``tof_mm``, ``imu``
/// (``ax ay az`` in m/s², ``gx gy gz`` in rad/s, or ``None``) and ``raw``
/// (the frame's bytes). Unlike the SDK, a position the tile sent as 0xFFFF
/// (no reading) is ``None``, and so is its ``_mm``. Also ``offset`` (of the
/// frame's first byte in the stream) and ``layout``.
///
/// Immutable; ``==`` compares every field, equal items hash alike, and it
/// pickles and copies.
#[pyclass(module = "robowire.omnitiles.sdk", name = "Telemetry", frozen)]
pub struct SdkTelemetry {
    timestamp: f64,
    offset: u64,
    telemetry: Telemetry,
    m1_pos_mm: Option<f64>,
    m2_pos_mm: Option<f64>,
}

impl SdkTelemetry {
    fn new(frame: OwnedFrame<Telemetry>, timestamp: f64, scale: Scale) -> Self {
        let t = frame.message;
        Self {
            timestamp,
            offset: frame.offset,
            m1_pos_mm: scale.mm(t.m1_pos, scale.m1_stroke_mm),
            m2_pos_mm: scale.mm(t.m2_pos, scale.m2_stroke_mm),
            telemetry: t,
        }
    }

    /// The frame's bytes, as received.
    fn wire(&self) -> PyResult<Vec<u8>> {
        frame_bytes(&self.telemetry)
    }

    /// Everything `==` compares, as bits.
    fn identity(&self) -> PyResult<Identity> {
        Ok((
            self.timestamp.to_bits(),
            self.offset,
            self.wire()?,
            self.m1_pos_mm.map(f64::to_bits),
            self.m2_pos_mm.map(f64::to_bits),
        ))
    }
}

/// A [`SdkTelemetry`]'s fields as bits: time, offset, frame, millimetres.
type Identity = (u64, u64, Vec<u8>, Option<u64>, Option<u64>);

/// `values` as a tuple, empty for a group the layout does not carry.
fn tuple_or_empty<'py>(py: Python<'py>, values: Option<&[u16]>) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, values.unwrap_or(&[]).iter().copied())
}

#[pymethods]
impl SdkTelemetry {
    /// Receive time: the parser's clock (``time.monotonic()`` by default,
    /// as the SDK) read once per ``feed`` call, when its bytes arrived.
    #[getter]
    fn timestamp(&self) -> f64 {
        self.timestamp
    }

    /// Raw 12-bit ADC reading of the M1 feedback potentiometer, or ``None``
    /// (0xFFFF: no reading).
    #[getter]
    fn m1_pos_adc(&self) -> Option<u16> {
        self.telemetry.m1_pos
    }

    /// Raw 12-bit ADC reading of the M2 feedback potentiometer, or ``None``.
    #[getter]
    fn m2_pos_adc(&self) -> Option<u16> {
        self.telemetry.m2_pos
    }

    /// M1 position in mm, ``m1_pos_adc / 4095 * 150``, or ``None``.
    #[getter]
    fn m1_pos_mm(&self) -> Option<f64> {
        self.m1_pos_mm
    }

    /// M2 position in mm, ``m2_pos_adc / 4095 * 100``, or ``None``.
    #[getter]
    fn m2_pos_mm(&self) -> Option<f64> {
        self.m2_pos_mm
    }

    /// The four M1 potentiometer readings, or ``()`` if not reported.
    #[getter]
    fn m1_adcs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        tuple_or_empty(py, self.telemetry.m1_adcs.as_ref().map(|a| &a[..]))
    }

    /// The two M2 potentiometer readings, or ``()`` if not reported.
    #[getter]
    fn m2_adcs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        tuple_or_empty(py, self.telemetry.m2_adcs.as_ref().map(|a| &a[..]))
    }

    /// Ranges to anchors 0..3 in mm (each ``None`` when invalid), or
    /// ``None`` if not reported.
    #[getter]
    fn uwb_mm<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyTuple>>> {
        self.telemetry
            .uwb
            .map(|uwb| PyTuple::new(py, uwb))
            .transpose()
    }

    /// Time-of-flight range in mm, or ``None``.
    #[getter]
    fn tof_mm(&self) -> Option<u16> {
        self.telemetry.tof.flatten()
    }

    /// The IMU sample (``ax ay az`` m/s², ``gx gy gz`` rad/s), or ``None``.
    #[getter]
    fn imu(&self) -> Option<PyImu> {
        self.telemetry.imu.map(PyImu::from)
    }

    /// The frame's bytes, start byte to checksum.
    #[getter]
    fn raw<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        Ok(PyBytes::new(py, &self.wire()?))
    }

    /// Offset of the frame's first byte in the stream (robowire's addition).
    #[getter]
    fn offset(&self) -> u64 {
        self.offset
    }

    /// The frame's layout: ``"pos7"``, ``"uwb15"``, ``"uwbtof17"`` or
    /// ``"ble53"`` (robowire's addition).
    #[getter]
    fn layout(&self) -> &'static str {
        self.telemetry.layout.name()
    }

    fn __richcmp__(&self, other: &Bound<'_, PyAny>, op: CompareOp) -> PyResult<Py<PyAny>> {
        let equal = match other.cast::<SdkTelemetry>() {
            Ok(other) => Some(self.identity()? == other.get().identity()?),
            Err(_) => None,
        };
        compared(other.py(), equal, op)
    }

    fn __hash__(&self) -> PyResult<u64> {
        Ok(hash_of(&self.identity()?))
    }

    /// Pickles as its time, offset, frame bytes and millimetres, exactly.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.get();
        let rebuild = slf.get_type().getattr(pyo3::intern!(py, "_rebuild"))?;
        let args = (
            this.timestamp,
            this.offset,
            PyBytes::new(py, &this.wire()?),
            this.m1_pos_mm,
            this.m2_pos_mm,
        );
        PyTuple::new(py, [rebuild, args.into_pyobject(py)?.into_any()])
    }

    /// What unpickling calls.
    #[staticmethod]
    fn _rebuild(
        timestamp: f64,
        offset: u64,
        raw: &[u8],
        m1_pos_mm: Option<f64>,
        m2_pos_mm: Option<f64>,
    ) -> PyResult<Self> {
        let telemetry =
            Telemetry::try_from(raw).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self {
            timestamp,
            offset,
            telemetry,
            m1_pos_mm,
            m2_pos_mm,
        })
    }

    fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
        let mut parts = Vec::new();
        for name in [
            "timestamp",
            "m1_pos_adc",
            "m2_pos_adc",
            "m1_pos_mm",
            "m2_pos_mm",
            "m1_adcs",
            "m2_adcs",
            "uwb_mm",
            "tof_mm",
            "imu",
        ] {
            parts.push(format!("{name}={}", slf.getattr(name)?.repr()?));
        }
        Ok(format!("Telemetry({})", parts.join(", ")))
    }
}

/// A drop-in for the OmniTiles SDK's ``StreamParser``: ``feed(data)`` takes
/// the bytes as they arrive and returns the :class:`Telemetry` frames they
/// complete, decoded by robowire's engine (every layout the SDK knows: 7,
/// 15, 17 and 53 bytes). ``clock`` gives each frame's ``timestamp`` (read
/// once per ``feed``; ``time.monotonic`` by default, as the SDK).
/// ``m1_stroke_mm``, ``m2_stroke_mm`` and ``adc_max`` are the SDK's
/// hardware constants, for a tile built otherwise.
///
/// A chunk that is exactly one frame (one BLE notification, as the SDK's
/// transport delivers them) gives that frame at once, short layouts
/// included. Otherwise a 7, 15 or 17-byte frame at the very end of a chunk
/// may be the start of a longer one, and it comes out of the next ``feed``
/// (its first byte decides), or of :meth:`settle` when the caller knows the
/// line went quiet: robowire does not guess there, which is how the SDK
/// takes false short frames at chunk boundaries.
#[pyclass(module = "robowire.omnitiles.sdk", name = "StreamParser")]
pub struct StreamParser {
    decoder: StreamDecoder<Framing<Host>, HOST_BUFFER>,
    /// `clock=`, else `time.monotonic()` (`Clock::now`).
    clock: Clock,
    scale: Scale,
}

impl StreamParser {
    /// Hand out every buffered frame the framing left open.
    fn settle_into(&mut self, timestamp: f64, out: &Bound<'_, PyList>) -> PyResult<()> {
        let py = out.py();
        let mut result = Ok(());
        while let Some(event) = Resolve::Settle.next(&mut self.decoder) {
            if let (Ok(frame), true) = (event, result.is_ok()) {
                let item = SdkTelemetry::new(frame, timestamp, self.scale);
                result = out.append(untracked(py, item)?);
            }
        }
        result
    }

    fn now(&self, py: Python<'_>) -> PyResult<f64> {
        self.clock.now(py)
    }
}

#[pymethods]
impl StreamParser {
    #[new]
    #[pyo3(signature = (clock = None, *, m1_stroke_mm = 150.0, m2_stroke_mm = 100.0, adc_max = f64::from(ADC_FULL_SCALE)))]
    fn new(
        clock: Option<Bound<'_, PyAny>>,
        m1_stroke_mm: f64,
        m2_stroke_mm: f64,
        adc_max: f64,
    ) -> PyResult<Self> {
        let clock = Clock::new(clock)?;
        if adc_max.is_nan() || adc_max <= 0.0 {
            return Err(PyValueError::new_err("adc_max must be positive"));
        }
        Ok(Self {
            decoder: StreamDecoder::new(Framing::new()),
            clock,
            scale: Scale {
                adc_max,
                m1_stroke_mm,
                m2_stroke_mm,
            },
        })
    }

    /// Decode the next chunk (``bytes``, ``bytearray`` or ``memoryview``);
    /// the frames it completes, in stream order. Corrupt frames are skipped
    /// (counted in :attr:`stats`).
    #[pyo3(signature = (data, /))]
    fn feed<'py>(&mut self, data: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyList>> {
        let py = data.py();
        let timestamp = self.now(py)?;
        let out = PyList::empty(py);
        let was_empty = self.decoder.buffered() == 0;
        let scale = self.scale;
        let whole = with_bytes(data, |bytes| {
            decode_events(py, &mut self.decoder, bytes, false, |event| match event {
                Ok(frame) => out.append(untracked(py, SdkTelemetry::new(frame, timestamp, scale))?),
                Err(_) => Ok(()),
            })?;
            Ok::<_, PyErr>(bytes.len())
        })??;
        // The chunk is one candidate from its first byte to its last: a
        // datagram that is one frame, which the SDK's users get at once.
        if was_empty && whole > 0 && self.decoder.buffered() == whole {
            self.settle_into(timestamp, &out)?;
        }
        Ok(out)
    }

    /// The line went quiet: return a buffered short frame that only the
    /// next byte would otherwise decide (see the class's documentation).
    fn settle<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let timestamp = self.now(py)?;
        let out = PyList::empty(py);
        self.settle_into(timestamp, &out)?;
        Ok(out)
    }

    /// Link-quality counters, as :attr:`robowire.StreamDecoder.stats`
    /// (robowire's addition: the SDK drops corrupt frames silently).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        stats_dict(py, &self.decoder.stats())
    }

    /// Bytes held as the start of an unfinished frame.
    #[getter]
    fn buffered(&self) -> usize {
        self.decoder.buffered()
    }

    fn __repr__(&self) -> String {
        "robowire.omnitiles.sdk.StreamParser()".to_owned()
    }
}

/// The `robowire._robowire.sdk` module.
pub fn module(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    let m = PyModule::new(py, "sdk")?;
    m.add_class::<StreamParser>()?;
    m.add_class::<SdkTelemetry>()?;
    Ok(m)
}
