//! `robowire.omnitiles`: the OmniTiles decoders and encoder.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString};
use robowire::omnitiles::{Decoder, Framing, Layout, Layouts, Packet};

use crate::decoder::PyStreamDecoder;
use crate::engine::{
    append, bad_choice, encode_frame, encode_with, stats_dict, with_bytes, Items, Stream,
};

const SOURCES: &[&str] = &["tile", "host", "any"];

/// The layouts option: `None`, a comma-separated string or a sequence of names.
fn layouts_of(layouts: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Layouts>> {
    let Some(layouts) = layouts else {
        return Ok(None);
    };
    let names: Vec<String> = if let Ok(text) = layouts.cast::<PyString>() {
        text.to_cow()?.split(',').map(str::to_owned).collect()
    } else {
        layouts.extract()?
    };
    let mut set = Layouts::NONE;
    for name in &names {
        let name = name.trim();
        if name == "auto" {
            set = Layouts::DOCUMENTED.iter().fold(set, Layouts::with);
            continue;
        }
        let layout = Layout::from_name(name).ok_or_else(|| {
            bad_choice(
                "a layout",
                name,
                &["pos7", "uwb15", "uwbtof17", "ble53", "spi45", "auto"],
            )
        })?;
        set = set.with(layout);
    }
    if set.is_empty() {
        return Err(PyValueError::new_err(
            "layouts must name at least one layout",
        ));
    }
    Ok(Some(set))
}

/// The framing for `source` and `layouts`.
fn framing(source: &str, layouts: Option<&Bound<'_, PyAny>>) -> PyResult<Framing> {
    let layouts = layouts_of(layouts)?;
    match (source, layouts) {
        ("tile", layouts) => Ok(Framing::telemetry(layouts.unwrap_or_default())),
        ("any", layouts) => Ok(Framing::any(layouts.unwrap_or_default())),
        ("host", None) => Ok(Framing::commands()),
        ("host", Some(_)) => Err(PyValueError::new_err(
            "layouts apply to telemetry: not with source=\"host\"",
        )),
        (other, _) => Err(bad_choice("source", other, SOURCES)),
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

/// Decoder(source="any", layouts=None, errors=False)
/// --
///
/// The OmniTiles stream decoder (a :class:`robowire.StreamDecoder`): feed it
/// the bytes of a serial link or a capture in chunks of any size.
///
/// ``source`` says who sent the bytes: ``"tile"`` (telemetry only: what a
/// host reads), ``"host"`` (commands only: what a tile reads) or ``"any"``
/// (both, for captures). ``layouts`` names the telemetry layouts to accept, a
/// list or a comma-separated string of ``"pos7"``, ``"uwb15"``,
/// ``"uwbtof17"``, ``"ble53"``, ``"spi45"`` and ``"auto"`` (the four the SDK
/// documents, the default); name the one layout you know for the fastest,
/// surest decoding. ``errors=True`` returns rejected candidates as items.
///
/// >>> from robowire import omnitiles
/// >>> d = omnitiles.Decoder(source="host")
/// >>> d.feed(bytes.fromhex("00 a5 30 c8 f8 a5 50"))
/// [{'offset': 1, 'len': 4, 'type': 'm1_extend', 'speed': 200}]
/// >>> d.feed(b"\x50")
/// [{'offset': 5, 'len': 3, 'type': 'ping'}]
#[pyclass(module = "robowire.omnitiles", name = "Decoder", extends = PyStreamDecoder)]
pub struct OmniDecoder;

#[pymethods]
impl OmniDecoder {
    #[new]
    #[pyo3(signature = (source = "any", layouts = None, errors = false, lazy = false))]
    fn new(
        source: &str,
        layouts: Option<&Bound<'_, PyAny>>,
        errors: bool,
        lazy: bool,
    ) -> PyResult<PyClassInitializer<Self>> {
        let framing = framing(source, layouts)?;
        let engine = Stream::boxed(Decoder::new(framing));
        let items = Items { errors, lazy };
        let repr = describe("Decoder", source, layouts, items);
        let base = PyStreamDecoder::new(engine, items, repr);
        Ok(PyClassInitializer::from(base).add_subclass(OmniDecoder))
    }
}

/// DatagramDecoder(source="tile", layouts=None, errors=False)
/// --
///
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
/// [{'offset': 0, 'len': 3, 'type': 'm1_brake'}, {'offset': 3, 'len': 3, 'type': 'm2_brake'}]
#[pyclass(module = "robowire.omnitiles", name = "DatagramDecoder")]
pub struct OmniDatagramDecoder {
    inner: robowire::omnitiles::DatagramDecoder,
    items: Items,
    repr: String,
}

#[pymethods]
impl OmniDatagramDecoder {
    #[new]
    #[pyo3(signature = (source = "tile", layouts = None, errors = false, lazy = false))]
    fn new(
        source: &str,
        layouts: Option<&Bound<'_, PyAny>>,
        errors: bool,
        lazy: bool,
    ) -> PyResult<Self> {
        let framing = framing(source, layouts)?;
        let items = Items { errors, lazy };
        Ok(Self {
            inner: robowire::omnitiles::DatagramDecoder::new(framing),
            items,
            repr: describe("DatagramDecoder", source, layouts, items),
        })
    }

    /// decode(datagram, /)
    /// --
    ///
    /// The items of one whole datagram (``bytes``, ``bytearray`` or
    /// ``memoryview``), in order.
    fn decode<'py>(&mut self, datagram: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(datagram.py());
        let items = self.items;
        with_bytes(datagram, |bytes| {
            let mut result = Ok(());
            for event in self.inner.decode(bytes) {
                if result.is_ok() {
                    result = append::<Framing>(&out, event, items);
                }
            }
            result
        })??;
        Ok(out)
    }

    /// Link-quality counters over every datagram so far (see
    /// :attr:`robowire.StreamDecoder.stats`).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        stats_dict(py, &self.inner.stats())
    }

    /// Whether rejected candidates are returned as items.
    #[getter]
    fn errors(&self) -> bool {
        self.items.errors
    }

    /// Whether items are :class:`robowire.Item` objects.
    #[getter]
    fn lazy(&self) -> bool {
        self.items.lazy
    }

    fn __repr__(&self) -> String {
        self.repr.clone()
    }
}

/// encode(message, /)
/// --
///
/// The frame of one message, a dict in the JSON-lines schema (as the decoders
/// return it; ``offset`` and ``len`` are ignored). Raises ``ValueError``
/// naming the field and its range when the message is not valid.
///
/// >>> from robowire import omnitiles
/// >>> omnitiles.encode({"type": "m1_extend", "speed": 200}).hex(" ")
/// 'a5 30 c8 f8'
#[pyfunction]
fn encode<'py>(message: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyBytes>> {
    encode_with(message, |message: &Packet| encode_frame(message))
}

/// `robowire.omnitiles`.
pub fn module(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    let m = PyModule::new(py, "omnitiles")?;
    m.add_class::<OmniDecoder>()?;
    m.add_class::<OmniDatagramDecoder>()?;
    m.add_function(wrap_pyfunction!(encode, &m)?)?;
    Ok(m)
}
