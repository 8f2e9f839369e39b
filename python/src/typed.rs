//! Typed items (the default): one light Python object per decoded frame.
//!
//! OmniTiles telemetry, the frame a host reads at rate, is a
//! [`PyTelemetry`] holding the library's `Copy` [`Telemetry`]: creating one
//! is a single allocation the garbage collector does not track, and each
//! attribute builds its Python value only when read. A Telemetrix or Pixy2
//! message is in its type's class ([`kinds`]), a subclass of
//! [`robowire.Item`](crate::item::Item), as OmniTiles commands and
//! rejections are: a field read alone is made from the frame, the dict
//! only for iteration and comparison.

use pyo3::basic::CompareOp;
use std::hash::{DefaultHasher, Hash, Hasher};

use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyIterator, PyList, PyString, PyTuple};
use robowire::omnitiles::{Imu, Message, Telemetry};
use robowire::stream::OwnedFrame;
use serde::Serialize;

use crate::compact::CompactMessage;
use crate::engine::{encode_frame, timed_dict, to_python};
use crate::item::Item;
use crate::kinds;
use crate::schema::exact_f64;

/// A new Python object of class `T`, not tracked by the garbage collector.
///
/// For the item classes, which have no `__traverse__`: the collector can
/// find nothing through them (an `Item`'s dict, once built, is not visited
/// either way), so tracking them only makes every collection walk over each
/// item a host keeps.
pub fn untracked<T: pyo3::PyClass + Into<PyClassInitializer<T>>>(
    py: Python<'_>,
    value: T,
) -> PyResult<Bound<'_, PyAny>> {
    untracked_init(py, value.into())
}

/// [`untracked`] for an initializer (a subclass's, as the message classes').
pub fn untracked_init<T: pyo3::PyClass>(
    py: Python<'_>,
    init: PyClassInitializer<T>,
) -> PyResult<Bound<'_, PyAny>> {
    let item = Bound::new(py, init)?;
    // SAFETY: `item` is a live object of a GC type (PyO3 gives every class
    // one); untracking it only keeps the collector from visiting it, and its
    // deallocation may untrack it again.
    unsafe { pyo3::ffi::PyObject_GC_UnTrack(item.as_ptr().cast()) };
    Ok(item.into_any())
}

/// How a library message becomes a typed item.
pub trait Typed: Serialize + Send + Sync + Sized + 'static {
    /// The typed item of `frame`, received at `t`: an [`Item`] unless a
    /// message has a class.
    fn typed(
        py: Python<'_>,
        frame: OwnedFrame<Self>,
        t: Option<f64>,
    ) -> PyResult<Bound<'_, PyAny>> {
        untracked(py, Item::new(Box::new(frame), t))
    }
}

impl Typed for Telemetry {
    fn typed(
        py: Python<'_>,
        frame: OwnedFrame<Self>,
        t: Option<f64>,
    ) -> PyResult<Bound<'_, PyAny>> {
        let mut item = PyTelemetry::from(frame);
        item.t = t;
        untracked(py, item)
    }
}

impl Typed for Message {
    fn typed(
        py: Python<'_>,
        frame: OwnedFrame<Self>,
        t: Option<f64>,
    ) -> PyResult<Bound<'_, PyAny>> {
        match frame.message {
            Message::Telemetry(telemetry) => Telemetry::typed(
                py,
                OwnedFrame {
                    offset: frame.offset,
                    len: frame.len,
                    message: telemetry,
                },
                t,
            ),
            Message::Command(_) => untracked(py, Item::new(Box::new(frame), t)),
        }
    }
}

impl Typed for robowire::omnitiles::Command {}
/// A message's `type` name, which picks its class ([`kinds`]).
trait TypeName {
    fn type_name(&self) -> &'static str;
}

impl TypeName for robowire::telemetrix::MessageBuf {
    // A parse of the frame: kept out of line, so that `typed` stays small
    // enough for the engines' loops to inline (see `compact`).
    #[inline(never)]
    fn type_name(&self) -> &'static str {
        self.message().name()
    }
}

impl TypeName for robowire::pixy2::Request {
    fn type_name(&self) -> &'static str {
        self.name()
    }
}

impl TypeName for robowire::pixy2::ResponseBuf {
    fn type_name(&self) -> &'static str {
        self.as_response().name()
    }
}

impl TypeName for robowire::pixy2::MessageBuf {
    fn type_name(&self) -> &'static str {
        match self {
            Self::Request(request) => request.type_name(),
            Self::Response(response) => response.type_name(),
        }
    }
}

impl<B: TypeName> TypeName for robowire::pixy2::Envelope<B> {
    fn type_name(&self) -> &'static str {
        self.body.type_name()
    }
}

/// The item of `frame` with the whole frame boxed, and its `type`. Inlined
/// into `append`, the frame moves once, into its box: a call would copy the
/// few hundred bytes of a `ResponseBuf` again.
#[inline(always)]
fn boxed<M: TypeName + Serialize + Send + Sync + 'static>(
    frame: OwnedFrame<M>,
    t: Option<f64>,
) -> (&'static str, Item) {
    let frame = Box::new(frame);
    (frame.message.type_name(), Item::new(frame, t))
}

/// The item of a Telemetrix `frame`, kept in a few bytes in the item
/// ([`CompactMessage`]), and its `type`.
#[inline(always)]
fn compact(
    frame: OwnedFrame<robowire::telemetrix::MessageBuf>,
    t: Option<f64>,
) -> (&'static str, Item) {
    let item = Item::compact(CompactMessage::new(&frame), t);
    (frame.message.type_name(), item)
}

/// Messages with a class per `type`: each item (made by `$keep`) in its
/// type's class of the protocol (`$wrap`).
macro_rules! classed {
    ($($message:ty => $wrap:path, $keep:ident;)*) => {$(
        impl Typed for $message {
            #[inline(always)]
            fn typed(
                py: Python<'_>,
                frame: OwnedFrame<Self>,
                t: Option<f64>,
            ) -> PyResult<Bound<'_, PyAny>> {
                let (name, item) = $keep(frame, t);
                $wrap(py, name, item)
            }
        }
    )*};
}

classed!(
    robowire::telemetrix::MessageBuf => kinds::telemetrix::wrap, compact;
    robowire::pixy2::Envelope<robowire::pixy2::ResponseBuf> => kinds::pixy2::wrap, boxed;
    robowire::pixy2::Envelope<robowire::pixy2::Request> => kinds::pixy2::wrap, boxed;
    robowire::pixy2::Envelope<robowire::pixy2::MessageBuf> => kinds::pixy2::wrap, boxed;
);

/// The answer of `__richcmp__` for `op` when the items are `equal` (`None`:
/// the other object is of no type this one compares with).
pub fn compared(py: Python<'_>, equal: Option<bool>, op: CompareOp) -> PyResult<Py<PyAny>> {
    let answer = match (op, equal) {
        (CompareOp::Eq, Some(equal)) => equal,
        (CompareOp::Ne, Some(equal)) => !equal,
        _ => return Ok(py.NotImplemented()),
    };
    Ok(answer.into_pyobject(py)?.to_owned().into_any().unbind())
}

/// A Python hash of `value` (Rust's `DefaultHasher`, which is not seeded
/// per process: the same item hashes alike in every run, as an int does).
pub fn hash_of<T: Hash>(value: &T) -> u64 {
    let mut hasher = DefaultHasher::new();
    value.hash(&mut hasher);
    hasher.finish()
}

/// The bytes of `telemetry`'s frame. Every byte of each layout is a field
/// (a reading can never be `Some(0xFFFF)`), so encoding the fields gives
/// back the bytes received, checksum included.
pub fn frame_bytes(telemetry: &Telemetry) -> PyResult<Vec<u8>> {
    encode_frame(telemetry).map_err(PyValueError::new_err)
}

/// The keys of a telemetry item, in the dict form's order (`t` only when
/// the item has a receive time).
const TELEMETRY_KEYS: [&str; 12] = [
    "t", "offset", "len", "type", "layout", "m1_pos", "m2_pos", "uwb", "tof", "imu", "m1_adcs",
    "m2_adcs",
];

/// `key` as a name, if it is a `str` (a mapping may be asked about any object).
fn name_of<'py>(key: &Bound<'py, PyAny>) -> Option<pyo3::pybacked::PyBackedStr> {
    key.extract().ok()
}

/// One OmniTiles telemetry frame (a decoder's default item). Attributes: ``offset``,
/// ``len``, ``type`` (``"telemetry"``), ``layout`` (``"ble53"``, ...),
/// ``m1_pos``, ``m2_pos``, ``uwb`` (a tuple of four), ``tof``, ``imu`` (an
/// :class:`Imu`), ``m1_adcs`` (four), ``m2_adcs`` (two). A reading the tile
/// sent as ``0xFFFF`` is ``None``, and so is a group the frame's layout does
/// not carry (``"tof" in t`` tells them apart; ``t["tof"]`` raises
/// ``KeyError`` for a group not carried, as the dict form has no such key).
///
/// A read-only mapping: ``t["m1_pos"]`` reads a field by name, iteration and
/// ``len`` go over the keys, :meth:`to_dict` gives the dict a ``typed=False``
/// decoder returns, and ``==`` compares with another item or with
/// that dict.
#[pyclass(module = "robowire.omnitiles", name = "Telemetry", frozen)]
pub struct PyTelemetry {
    offset: u64,
    len: usize,
    telemetry: Telemetry,
    /// The receive time the caller gave `feed`, if any.
    t: Option<f64>,
}

impl From<OwnedFrame<Telemetry>> for PyTelemetry {
    fn from(frame: OwnedFrame<Telemetry>) -> Self {
        Self {
            offset: frame.offset,
            len: frame.len,
            telemetry: frame.message,
            t: None,
        }
    }
}

/// A `u16` reading, `None` for "no reading".
fn reading(py: Python<'_>, value: Option<u16>) -> Bound<'_, PyAny> {
    match value {
        Some(v) => v
            .into_pyobject(py)
            .map(Bound::into_any)
            .unwrap_or_else(|e| match e {}),
        None => py.None().into_bound(py),
    }
}

fn tuple_of<'py, T: IntoPyObject<'py> + Copy>(
    py: Python<'py>,
    values: &[T],
) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyTuple::new(py, values.iter().copied())?.into_any())
}

impl PyTelemetry {
    /// The value of field `key`, `None` where the key is not this item's.
    fn field<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        let t = &self.telemetry;
        Ok(Some(match key {
            "t" => match self.t {
                Some(t) => t.into_pyobject(py)?.into_any(),
                None => return Ok(None),
            },
            "offset" => self.offset.into_pyobject(py)?.into_any(),
            "len" => self.len.into_pyobject(py)?.into_any(),
            "type" => pyo3::intern!(py, "telemetry").clone().into_any(),
            "layout" => PyString::intern(py, t.layout.name()).into_any(),
            "m1_pos" => reading(py, t.m1_pos),
            "m2_pos" => reading(py, t.m2_pos),
            "uwb" => match &t.uwb {
                Some(uwb) => PyTuple::new(py, uwb.iter().map(|&r| reading(py, r)))?.into_any(),
                None => return Ok(None),
            },
            "tof" => match t.tof {
                Some(tof) => reading(py, tof),
                None => return Ok(None),
            },
            "imu" => match t.imu {
                Some(imu) => Bound::new(py, PyImu::from(imu))?.into_any(),
                None => return Ok(None),
            },
            "m1_adcs" => match &t.m1_adcs {
                Some(adcs) => tuple_of(py, adcs)?,
                None => return Ok(None),
            },
            "m2_adcs" => match &t.m2_adcs {
                Some(adcs) => tuple_of(py, adcs)?,
                None => return Ok(None),
            },
            _ => return Ok(None),
        }))
    }

    /// A group field: its value, or `None` where the layout does not carry it.
    fn group<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        Ok(self
            .field(py, key)?
            .unwrap_or_else(|| py.None().into_bound(py)))
    }

    /// The frame's bytes, as received (see [`frame_bytes`]).
    fn wire(&self) -> PyResult<Vec<u8>> {
        frame_bytes(&self.telemetry)
    }

    /// The frame in the library's form, for the dict form.
    fn frame(&self) -> OwnedFrame<Message> {
        OwnedFrame {
            offset: self.offset,
            len: self.len,
            message: Message::Telemetry(self.telemetry),
        }
    }
}

#[pymethods]
impl PyTelemetry {
    /// Offset of the frame's first byte in the stream.
    #[getter]
    fn offset(&self) -> u64 {
        self.offset
    }

    /// The receive time given to the ``feed`` (or ``settle``, ``finish``)
    /// call that returned the item (``t=...``), or ``None``.
    #[getter]
    fn t(&self) -> Option<f64> {
        self.t
    }

    /// The frame's length in bytes (7, 15, 17, 45 or 53).
    #[getter]
    fn len(&self) -> usize {
        self.len
    }

    /// The frame's bytes as they were received, start byte to checksum.
    #[getter]
    fn raw<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        Ok(PyBytes::new(py, &self.wire()?))
    }

    /// ``"telemetry"``.
    #[getter]
    fn r#type<'py>(&self, py: Python<'py>) -> Bound<'py, PyString> {
        pyo3::intern!(py, "telemetry").clone()
    }

    /// The frame's layout: ``"pos7"``, ``"uwb15"``, ``"uwbtof17"``,
    /// ``"spi45"`` or ``"ble53"``.
    #[getter]
    fn layout<'py>(&self, py: Python<'py>) -> Bound<'py, PyString> {
        PyString::intern(py, self.telemetry.layout.name())
    }

    /// M1 position, raw 0..4095, or ``None`` (no reading).
    #[getter]
    fn m1_pos(&self) -> Option<u16> {
        self.telemetry.m1_pos
    }

    /// M2 position, raw 0..4095, or ``None`` (no reading).
    #[getter]
    fn m2_pos(&self) -> Option<u16> {
        self.telemetry.m2_pos
    }

    /// M1 position in mm along its 150 mm stroke, ``m1_pos / 4095 * 150``
    /// as the OmniTiles SDK computes it (bit for bit), or ``None``.
    #[getter]
    fn m1_pos_mm(&self) -> Option<f64> {
        let raw = self.telemetry.m1_pos?;
        Some(robowire::omnitiles::units::adc_to_mm_f64(
            robowire::omnitiles::Motor::M1,
            raw,
        ))
    }

    /// M2 position in mm along its 100 mm stroke, ``m2_pos / 4095 * 100``
    /// as the OmniTiles SDK computes it (bit for bit), or ``None``.
    #[getter]
    fn m2_pos_mm(&self) -> Option<f64> {
        let raw = self.telemetry.m2_pos?;
        Some(robowire::omnitiles::units::adc_to_mm_f64(
            robowire::omnitiles::Motor::M2,
            raw,
        ))
    }

    /// The unit of each field that has one, from the library's field table:
    /// ``{"m1_pos": "ADC counts", "uwb": "mm", "tof": "mm", ...}`` (the
    /// IMU's are :attr:`Imu.units`).
    #[classattr]
    fn units(py: Python<'_>) -> PyResult<Bound<'_, pyo3::types::PyDict>> {
        crate::units::units(
            py,
            &robowire::omnitiles::FIELD_INFO,
            "telemetry",
            "",
            &["m1_pos", "m2_pos", "uwb", "tof", "m1_adcs", "m2_adcs"],
        )
    }

    /// UWB ranges to anchors 0..3 in mm, a tuple of four (each ``None`` for
    /// no reading), or ``None`` if the layout carries none.
    #[getter]
    fn uwb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.group(py, "uwb")
    }

    /// ToF range in mm, or ``None`` (no reading, or not carried).
    #[getter]
    fn tof(&self) -> Option<u16> {
        self.telemetry.tof.flatten()
    }

    /// The IMU sample (an :class:`Imu`), or ``None`` if not carried.
    #[getter]
    fn imu(&self) -> Option<PyImu> {
        self.telemetry.imu.map(PyImu::from)
    }

    /// M1's four potentiometer channels, raw 0..4095, or ``None``.
    #[getter]
    fn m1_adcs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.group(py, "m1_adcs")
    }

    /// M2's two potentiometer channels, raw 0..4095, or ``None``.
    #[getter]
    fn m2_adcs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.group(py, "m2_adcs")
    }

    /// The item's keys, as in the dict form (groups the layout carries only).
    fn keys(&self, py: Python<'_>) -> PyResult<Vec<&'static str>> {
        let mut keys = Vec::with_capacity(TELEMETRY_KEYS.len());
        for key in TELEMETRY_KEYS {
            if self.field(py, key)?.is_some() {
                keys.push(key);
            }
        }
        Ok(keys)
    }

    /// The value of ``key``, or ``default`` where the item has no such key.
    #[pyo3(signature = (key, default = None, /))]
    fn get<'py>(
        &self,
        py: Python<'py>,
        key: &str,
        default: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        Ok(match self.field(py, key)? {
            Some(value) => value,
            None => default.unwrap_or_else(|| py.None().into_bound(py)),
        })
    }

    /// The item as the dict a ``typed=False`` decoder returns (lists, an ``imu``
    /// dict).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        timed_dict(py, self.t, to_python(py, &self.frame())?)
    }

    fn __getitem__<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        self.field(py, key)?
            .ok_or_else(|| PyKeyError::new_err(key.to_owned()))
    }

    /// The values of :meth:`keys`, in that order.
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        self.keys(py)?
            .into_iter()
            .map(|key| self.group(py, key))
            .collect()
    }

    /// The ``(key, value)`` pairs of :meth:`keys`, in that order.
    fn items<'py>(&self, py: Python<'py>) -> PyResult<Vec<(&'static str, Bound<'py, PyAny>)>> {
        self.keys(py)?
            .into_iter()
            .map(|key| Ok((key, self.group(py, key)?)))
            .collect()
    }

    fn __contains__(&self, py: Python<'_>, key: &Bound<'_, PyAny>) -> PyResult<bool> {
        match name_of(key) {
            Some(key) => Ok(self.field(py, &key)?.is_some()),
            None => Ok(false),
        }
    }

    /// The number of keys (the frame's length in bytes is ``len``).
    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(self.keys(py)?.len())
    }

    /// Iterates over the keys, as a mapping does.
    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyIterator>> {
        PyList::new(py, self.keys(py)?)?.as_any().try_iter()
    }

    fn __richcmp__<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PyAny>,
        op: CompareOp,
    ) -> PyResult<Py<PyAny>> {
        let equal = if let Ok(other) = other.cast::<PyTelemetry>() {
            let other = other.get();
            Some(
                (
                    self.offset,
                    self.len,
                    self.telemetry,
                    self.t.map(f64::to_bits),
                ) == (
                    other.offset,
                    other.len,
                    other.telemetry,
                    other.t.map(f64::to_bits),
                ),
            )
        } else if other.is_instance_of::<PyDict>() {
            Some(self.to_dict(py)?.eq(other)?)
        } else {
            None
        };
        compared(py, equal, op)
    }

    /// Hashable, as an immutable value: equal items (the same offset and
    /// frame bytes) hash alike.
    fn __hash__(&self) -> PyResult<u64> {
        Ok(hash_of(&(
            self.offset,
            self.wire()?,
            self.t.map(f64::to_bits),
        )))
    }

    /// Pickles as its offset and frame bytes, exactly (NaN payloads too).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.get();
        let rebuild = slf.get_type().getattr(pyo3::intern!(py, "_from_frame"))?;
        let args = (this.offset, PyBytes::new(py, &this.wire()?), this.t);
        PyTuple::new(py, [rebuild, args.into_pyobject(py)?.into_any()])
    }

    /// The item itself: it is immutable.
    fn __copy__(slf: Bound<'_, Self>) -> Bound<'_, Self> {
        slf
    }

    /// The item itself: it is immutable and holds no Python object.
    fn __deepcopy__<'py>(slf: Bound<'py, Self>, _memo: &Bound<'py, PyAny>) -> Bound<'py, Self> {
        slf
    }

    /// The item of one whole telemetry ``frame`` at ``offset`` (what
    /// unpickling calls); ``ValueError`` if it is no telemetry frame.
    #[staticmethod]
    #[pyo3(signature = (offset, frame, t = None))]
    fn _from_frame(offset: u64, frame: &[u8], t: Option<f64>) -> PyResult<Self> {
        let telemetry =
            Telemetry::try_from(frame).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self {
            offset,
            len: frame.len(),
            telemetry,
            t,
        })
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let mut parts = Vec::new();
        for key in self.keys(py)? {
            if key != "type" {
                parts.push(format!("{key}={}", self.group(py, key)?.repr()?));
            }
        }
        Ok(format!("Telemetry({})", parts.join(", ")))
    }
}

/// One IMU sample of a :class:`Telemetry` item: ``ax``, ``ay``, ``az``
/// (m/s², gravity included) and ``gx``, ``gy``, ``gz`` (rad/s), each the
/// exact value of the wire's ``f32`` as a ``float`` (NaN and infinities
/// included). ``imu["az"]`` and :meth:`to_dict` as for the item; ``==``
/// compares bit patterns (a NaN sample equals itself) or with a dict.
#[pyclass(module = "robowire.omnitiles", name = "Imu", frozen)]
pub struct PyImu {
    imu: Imu,
    /// Acceleration along x, m/s².
    #[pyo3(get)]
    ax: f64,
    /// Acceleration along y, m/s².
    #[pyo3(get)]
    ay: f64,
    /// Acceleration along z, m/s² (about +9.8 at rest).
    #[pyo3(get)]
    az: f64,
    /// Angular rate about x, rad/s.
    #[pyo3(get)]
    gx: f64,
    /// Angular rate about y, rad/s.
    #[pyo3(get)]
    gy: f64,
    /// Angular rate about z, rad/s.
    #[pyo3(get)]
    gz: f64,
}

impl From<Imu> for PyImu {
    fn from(imu: Imu) -> Self {
        let [ax, ay, az, gx, gy, gz] = imu.to_array().map(exact_f64);
        Self {
            imu,
            ax,
            ay,
            az,
            gx,
            gy,
            gz,
        }
    }
}

impl PyImu {
    /// The six values' bit patterns, what equality compares.
    fn bits(&self) -> [u32; 6] {
        self.imu.to_array().map(f32::to_bits)
    }

    fn value(&self, key: &str) -> Option<f64> {
        Imu::NAMES
            .iter()
            .position(|&name| name == key)
            .map(|i| exact_f64(self.imu.to_array()[i]))
    }
}

#[pymethods]
impl PyImu {
    /// The unit of each value: ``{"ax": "m/s²", ..., "gz": "rad/s"}``,
    /// from the library's field table.
    #[classattr]
    fn units(py: Python<'_>) -> PyResult<Bound<'_, pyo3::types::PyDict>> {
        crate::units::units(
            py,
            &robowire::omnitiles::FIELD_INFO,
            "telemetry",
            "imu.",
            &Imu::NAMES,
        )
    }

    /// The six names, in wire order.
    fn keys(&self) -> [&'static str; 6] {
        Imu::NAMES
    }

    /// The sample as the dict form's ``imu`` dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.imu)
    }

    fn __getitem__(&self, key: &str) -> PyResult<f64> {
        self.value(key)
            .ok_or_else(|| PyKeyError::new_err(key.to_owned()))
    }

    /// The six values, in wire order.
    fn values(&self) -> [f64; 6] {
        self.imu.to_array().map(exact_f64)
    }

    /// The six ``(name, value)`` pairs, in wire order.
    fn items(&self) -> Vec<(&'static str, f64)> {
        Imu::NAMES.into_iter().zip(self.values()).collect()
    }

    fn __contains__(&self, key: &Bound<'_, PyAny>) -> bool {
        name_of(key).is_some_and(|key| self.value(&key).is_some())
    }

    fn __len__(&self) -> usize {
        Imu::NAMES.len()
    }

    /// Iterates over the six names, as a mapping does.
    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyIterator>> {
        PyList::new(py, Imu::NAMES)?.as_any().try_iter()
    }

    fn __richcmp__<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PyAny>,
        op: CompareOp,
    ) -> PyResult<Py<PyAny>> {
        let equal = if let Ok(other) = other.cast::<PyImu>() {
            Some(self.imu == other.get().imu)
        } else if other.is_instance_of::<PyDict>() {
            Some(self.to_dict(py)?.eq(other)?)
        } else {
            None
        };
        compared(py, equal, op)
    }

    /// Hashable: equal samples (the same bit patterns) hash alike.
    fn __hash__(&self) -> u64 {
        hash_of(&self.bits())
    }

    /// Pickles as the six values' bit patterns, exactly.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let rebuild = slf.get_type().getattr(pyo3::intern!(py, "_from_bits"))?;
        let args = (slf.get().bits(),).into_pyobject(py)?.into_any();
        PyTuple::new(py, [rebuild, args])
    }

    /// The sample itself: it is immutable.
    fn __copy__(slf: Bound<'_, Self>) -> Bound<'_, Self> {
        slf
    }

    /// The sample itself: it is immutable and holds no Python object.
    fn __deepcopy__<'py>(slf: Bound<'py, Self>, _memo: &Bound<'py, PyAny>) -> Bound<'py, Self> {
        slf
    }

    /// The sample whose six ``f32`` values have these bit patterns (what
    /// unpickling calls).
    #[staticmethod]
    fn _from_bits(bits: [u32; 6]) -> Self {
        Self::from(Imu::from_array(bits.map(f32::from_bits)))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let mut parts = Vec::new();
        for (name, value) in Imu::NAMES.iter().zip(self.imu.to_array()) {
            let value = exact_f64(value).into_pyobject(py)?;
            parts.push(format!("{name}={}", value.repr()?));
        }
        Ok(format!("Imu({})", parts.join(", ")))
    }
}
