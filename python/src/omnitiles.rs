//! `robowire.omnitiles`: the OmniTiles decoders and encoder.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyList, PyString, PyType};
use robowire::omnitiles::{
    Both, DatagramDecoder, Device, Framing, Host, Layouts, Message, Side, BOTH_BUFFER,
    DEVICE_BUFFER, HOST_BUFFER,
};
use robowire::{Stats, StreamDecoder};

use crate::clock::Clock;
use crate::decoder::{generic_alias, not_copyable, PyStreamDecoder};
use crate::engine::{
    append, bad_choice, encode_frame, encode_with, stats_dict, with_bytes, Engine, Form, Items,
    Stream,
};

const SOURCES: &[&str] = &["tile", "host", "any"];

/// The layouts option: `None`, a comma-separated string or a sequence of
/// names, read by the library's `Layouts::from_str`.
fn layouts_of(layouts: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Layouts>> {
    let Some(layouts) = layouts else {
        return Ok(None);
    };
    let text = if let Ok(text) = layouts.cast::<PyString>() {
        text.to_cow()?.into_owned()
    } else {
        layouts.extract::<Vec<String>>()?.join(",")
    };
    let set: Layouts = text
        .parse()
        .map_err(|e| PyValueError::new_err(format!("layouts={text:?}: {e}")))?;
    if set.is_empty() {
        return Err(PyValueError::new_err(format!(
            "layouts={text:?}: name at least one layout"
        )));
    }
    Ok(Some(set))
}

/// What a source decodes, as the tool's `--from` and `--layout` choose it.
enum Choice {
    Tile(Framing<Host>),
    Host(Framing<Device>),
    Any(Framing<Both>),
}

fn choose(source: &str, layouts: Option<&Bound<'_, PyAny>>) -> PyResult<Choice> {
    let layouts = layouts_of(layouts)?;
    match source {
        "tile" => Ok(Choice::Tile(
            Framing::new().with_layouts(layouts.unwrap_or_default()),
        )),
        "any" => Ok(Choice::Any(
            Framing::new().with_layouts(layouts.unwrap_or_default()),
        )),
        "host" if layouts.is_none() => Ok(Choice::Host(Framing::new())),
        "host" => Err(PyValueError::new_err(
            "layouts select telemetry layouts, which source=\"host\" does not accept",
        )),
        other => Err(bad_choice("source", other, SOURCES)),
    }
}

/// A datagram decoder of any side.
trait Datagrams: Send + Sync {
    fn decode(&mut self, datagram: &[u8], items: Items, out: &Bound<'_, PyList>) -> PyResult<()>;
    fn stats(&self) -> Stats;
}

impl<S> Datagrams for DatagramDecoder<S>
where
    S: Side + Send + Sync,
    S::Message: crate::typed::Typed,
    Framing<S>: robowire::FrameRules<Owned = S::Message, Error = robowire::omnitiles::Error>,
{
    fn decode(&mut self, datagram: &[u8], items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        let mut result = Ok(());
        for event in DatagramDecoder::decode(self, datagram) {
            if result.is_ok() {
                result = append::<Framing<S>>(out, event, items);
            }
        }
        result
    }

    fn stats(&self) -> Stats {
        DatagramDecoder::stats(self)
    }
}

fn describe(class: &str, source: &str, layouts: Option<&Bound<'_, PyAny>>, items: Items) -> String {
    let layouts = layouts
        .map(|l| {
            format!(
                ", layouts={}",
                l.repr().map(|r| r.to_string()).unwrap_or_default()
            )
        })
        .unwrap_or_default();
    format!(
        "robowire.omnitiles.{class}(source={source:?}{layouts}{})",
        items.describe()
    )
}

/// The OmniTiles stream decoder (a :class:`robowire.StreamDecoder`): feed it
/// the bytes of a serial link or a capture in chunks of any size.
///
/// ``source`` says who sent the bytes: ``"tile"`` (telemetry only: what a
/// host reads), ``"host"`` (commands only: what a tile reads) or ``"any"``
/// (both, for captures). ``layouts`` names the telemetry layouts to accept, a
/// list or a comma-separated string of ``"pos7"``, ``"uwb15"``,
/// ``"uwbtof17"``, ``"ble53"``, ``"spi45"`` and ``"auto"`` (the four the SDK
/// documents, the default); name the one layout you know for the fastest,
/// surest decoding. ``errors=True`` returns rejected candidates as items;
/// items are typed (a :class:`Telemetry` per telemetry frame, a
/// :class:`robowire.Item` for a command or a rejection); ``typed=False``
/// returns dicts instead. ``typed=True`` (the spelling from before typed items
/// were the default) and ``lazy=True`` are deprecated and warn.
///
/// >>> from robowire import omnitiles
/// >>> d = omnitiles.Decoder(source="host")
/// >>> d.feed(bytes.fromhex("00 a5 30 c8 f8 a5 50"))
/// [Item({'offset': 1, 'len': 4, 'type': 'm1_extend', 'speed': 200})]
/// >>> d.feed(b"\x50")
/// [Item({'offset': 5, 'len': 3, 'type': 'ping'})]
#[pyclass(module = "robowire.omnitiles", name = "Decoder", extends = PyStreamDecoder)]
pub struct OmniDecoder;

#[pymethods]
impl OmniDecoder {
    #[new]
    #[pyo3(signature = (source = "any", layouts = None, errors = false, lazy = false, typed = None, clock = None))]
    fn new(
        source: &str,
        layouts: Option<&Bound<'_, PyAny>>,
        errors: bool,
        lazy: bool,
        typed: Option<bool>,
        clock: Option<Bound<'_, PyAny>>,
        py: Python<'_>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let engine: Box<dyn Engine> = match choose(source, layouts)? {
            Choice::Tile(f) => Stream::boxed(StreamDecoder::<_, HOST_BUFFER>::new(f)),
            Choice::Host(f) => Stream::boxed(StreamDecoder::<_, DEVICE_BUFFER>::new(f)),
            Choice::Any(f) => Stream::boxed(StreamDecoder::<_, BOTH_BUFFER>::new(f)),
        };
        let items = Items::new(py, errors, lazy, typed)?;
        let repr = describe("Decoder", source, layouts, items);
        let base = PyStreamDecoder::new(engine, items, repr, Clock::new(clock)?, py);
        Ok(PyClassInitializer::from(base).add_subclass(OmniDecoder))
    }
}

/// Decodes datagrams whose boundaries the transport keeps: one BLE
/// notification (or write, or SPI buffer) per call to :meth:`decode`. A
/// datagram that is one telemetry frame (possibly zero-padded) is read by its
/// length; anything else is decoded as a short stream that ends with the
/// datagram, so nothing carries over to the next one. Offsets count as if
/// all datagrams were concatenated. Options as for :class:`Decoder`.
///
/// >>> from robowire import omnitiles
/// >>> d = omnitiles.DatagramDecoder(source="host")
/// >>> d.decode(bytes.fromhex("a5 32 32 a5 42 42"))
/// [Item({'offset': 0, 'len': 3, 'type': 'm1_brake'}), Item({'offset': 3, 'len': 3, 'type': 'm2_brake'})]
#[pyclass(module = "robowire.omnitiles", name = "DatagramDecoder")]
pub struct OmniDatagramDecoder {
    inner: Box<dyn Datagrams>,
    items: Items,
    repr: String,
    clock: Clock,
}

#[pymethods]
impl OmniDatagramDecoder {
    #[new]
    #[pyo3(signature = (source = "any", layouts = None, errors = false, lazy = false, typed = None, clock = None))]
    fn new(
        source: &str,
        layouts: Option<&Bound<'_, PyAny>>,
        errors: bool,
        lazy: bool,
        typed: Option<bool>,
        clock: Option<Bound<'_, PyAny>>,
        py: Python<'_>,
    ) -> PyResult<Self> {
        let inner: Box<dyn Datagrams> = match choose(source, layouts)? {
            Choice::Tile(f) => Box::new(DatagramDecoder::new(f)),
            Choice::Host(f) => Box::new(DatagramDecoder::new(f)),
            Choice::Any(f) => Box::new(DatagramDecoder::new(f)),
        };
        let items = Items::new(py, errors, lazy, typed)?;
        let clock = Clock::new(clock)?;
        let repr = describe("DatagramDecoder", source, layouts, items);
        Ok(Self {
            inner,
            items,
            repr: clock.in_repr(py, repr),
            clock,
        })
    }

    /// The items of one whole datagram (``bytes``, ``bytearray`` or
    /// ``memoryview``), in order.
    /// ``t``: the datagram's receive time, which its items carry as ``t``.
    #[pyo3(signature = (datagram, /, t = None))]
    fn decode<'py>(
        &mut self,
        datagram: &Bound<'py, PyAny>,
        t: Option<f64>,
    ) -> PyResult<Bound<'py, PyList>> {
        let t = self.clock.stamp(datagram.py(), t)?;
        let out = PyList::empty(datagram.py());
        let items = Items { t, ..self.items };
        with_bytes(datagram, |bytes| self.inner.decode(bytes, items, &out))??;
        Ok(out)
    }

    /// Link-quality counters over every datagram so far (see
    /// :attr:`robowire.StreamDecoder.stats`).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        stats_dict(py, &self.inner.stats())
    }

    /// Whether rejected candidates are returned as items.
    #[getter]
    fn errors(&self) -> bool {
        self.items.errors
    }

    /// Whether items are :class:`robowire.Item` objects (``lazy=True``,
    /// deprecated).
    #[getter]
    fn lazy(&self) -> bool {
        self.items.form == Form::Lazy
    }

    /// Whether items are typed objects (the default, not ``typed=False``).
    #[getter]
    fn typed(&self) -> bool {
        self.items.form == Form::Typed
    }

    fn __repr__(&self) -> String {
        self.repr.clone()
    }

    /// Refused with a ``TypeError`` that says why, as for
    /// :class:`robowire.StreamDecoder`.
    fn __reduce__(&self) -> PyResult<()> {
        Err(not_copyable(&self.repr))
    }

    /// ``DatagramDecoder[Telemetry]``, for annotations (see
    /// :meth:`robowire.StreamDecoder.__class_getitem__`).
    #[classmethod]
    fn __class_getitem__<'py>(
        cls: &Bound<'py, PyType>,
        item: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        generic_alias(cls, item)
    }
}

/// The frame of one message, a dict in the JSON-lines schema (as the decoders
/// return it; ``offset`` and ``len`` are ignored). Raises ``ValueError``
/// naming the field and its range when the message is not valid.
///
/// >>> from robowire import omnitiles
/// >>> omnitiles.encode({"type": "m1_extend", "speed": 200}).hex(" ")
/// 'a5 30 c8 f8'
#[pyfunction]
#[pyo3(signature = (message, /))]
fn encode<'py>(message: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyBytes>> {
    encode_with(message, encode_frame::<Message>)
}

crate::units::field_info_function!(robowire::omnitiles::FIELD_INFO);

/// `robowire.omnitiles`.
pub fn module(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    let m = PyModule::new(py, "omnitiles")?;
    m.add_class::<OmniDecoder>()?;
    m.add_class::<OmniDatagramDecoder>()?;
    m.add_class::<crate::typed::PyTelemetry>()?;
    m.add_class::<crate::typed::PyImu>()?;
    m.add_function(wrap_pyfunction!(encode, &m)?)?;
    m.add_function(wrap_pyfunction!(field_info, &m)?)?;
    Ok(m)
}
