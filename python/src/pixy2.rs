//! `robowire.pixy2`: the Pixy2 decoder and encoder.

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use robowire::pixy2::{
    Both, Device, Envelope, Framing, Host, MessageBuf, BOTH_BUFFER, DEVICE_BUFFER, HOST_BUFFER,
};
use robowire::StreamDecoder;

use crate::clock::Clock;
use crate::decoder::PyStreamDecoder;
use crate::engine::{bad_choice, encode_frame, encode_with, Engine, Items, Stream};

const SOURCES: &[&str] = &["device", "host", "any"];

/// `framing`, with only the checksum form accepted if asked.
fn framing<S: robowire::pixy2::Side>(checksum_only: bool) -> Framing<S> {
    if checksum_only {
        Framing::new().checksum_only()
    } else {
        Framing::new()
    }
}

/// The engine for `source`, with the buffer the tool uses for it.
fn engine(source: &str, checksum_only: bool) -> PyResult<Box<dyn Engine>> {
    Ok(match source {
        "device" => Stream::boxed(StreamDecoder::<_, HOST_BUFFER>::new(framing::<Host>(
            checksum_only,
        ))),
        "host" => Stream::boxed(StreamDecoder::<_, DEVICE_BUFFER>::new(framing::<Device>(
            checksum_only,
        ))),
        "any" => Stream::boxed(StreamDecoder::<_, BOTH_BUFFER>::new(framing::<Both>(
            checksum_only,
        ))),
        other => return Err(bad_choice("source", other, SOURCES)),
    })
}

/// The Pixy2 stream decoder (a :class:`robowire.StreamDecoder`): feed it the
/// bytes of a serial link or a capture in chunks of any size.
///
/// ``source`` says who sent the bytes: ``"device"`` (responses only: what a
/// host reads), ``"host"`` (requests only, held to the device's 64-byte
/// receive limit: what a Pixy2 reads) or ``"any"`` (both, for captures).
/// ``checksum_only=True`` accepts only the checksum form (``af c1``), as a
/// Pixy2 always answers over SPI, I2C and UART: then no unverifiable frame
/// can be decoded. ``errors=True`` returns rejected candidates as items;
/// items are objects of each message type's class (``blocks``:
/// :class:`Blocks`, fields as typed attributes, each made
/// from the frame when read); ``typed=False`` returns dicts instead. ``typed=True`` and
/// ``lazy=True`` are deprecated and warn.
///
/// >>> from robowire import pixy2
/// >>> d = pixy2.Decoder(source="device")
/// >>> d.feed(bytes.fromhex("af c1 01 04 3d 00 3d 00 00 00"))
/// [Result({'offset': 0, 'len': 10, 'type': 'result', 'checksum': True, 'value': 61})]
#[pyclass(module = "robowire.pixy2", name = "Decoder", extends = PyStreamDecoder)]
pub struct Pixy2Decoder;

#[pymethods]
impl Pixy2Decoder {
    #[new]
    #[pyo3(signature = (source = "any", checksum_only = false, errors = false, lazy = false, typed = None, clock = None))]
    fn new(
        source: &str,
        checksum_only: bool,
        errors: bool,
        lazy: bool,
        typed: Option<bool>,
        clock: Option<Bound<'_, PyAny>>,
        py: Python<'_>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let engine = engine(source, checksum_only)?;
        let items = Items::new(py, errors, lazy, typed)?;
        let checksum_only = if checksum_only {
            ", checksum_only=True"
        } else {
            ""
        };
        let repr = format!(
            "robowire.pixy2.Decoder(source={source:?}{checksum_only}{})",
            items.describe()
        );
        let base = PyStreamDecoder::new(engine, items, repr, Clock::new(clock)?, py);
        Ok(PyClassInitializer::from(base).add_subclass(Pixy2Decoder))
    }
}

/// The frame of one request or response, a dict in the JSON-lines schema (as
/// the decoder returns it; ``offset`` and ``len`` are ignored). ``checksum``
/// picks the frame form (``True``: ``af c1``; absent: the form the message
/// usually travels in). Raises ``ValueError`` naming the field and its range
/// when the message is not valid.
///
/// >>> from robowire import pixy2
/// >>> pixy2.encode({"type": "set_servos", "pan": 500, "tilt": 500}).hex(" ")
/// 'ae c1 12 04 f4 01 f4 01'
#[pyfunction]
#[pyo3(signature = (message, /))]
fn encode<'py>(message: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyBytes>> {
    // Every line the decoder prints encodes: a marked quirk (sigmap 0) is
    // the opt-in, as in `robowire encode pixy2`.
    encode_with(message, |m: &Envelope<MessageBuf>| {
        encode_frame(&(*m).even_if_refused())
    })
}

crate::units::field_info_function!(robowire::pixy2::FIELD_INFO);

/// `robowire.pixy2`.
pub fn module(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    let m = PyModule::new(py, "pixy2")?;
    m.add_class::<Pixy2Decoder>()?;
    m.add_function(wrap_pyfunction!(encode, &m)?)?;
    m.add_function(wrap_pyfunction!(field_info, &m)?)?;
    crate::kinds::pixy2::add(&m)?;
    Ok(m)
}
