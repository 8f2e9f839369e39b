//! `robowire.telemetrix`: the Telemetrix4RpiPico decoder and encoder.
//!
//! Decoding goes through the library's [`CaptureContext`], as the `robowire`
//! tool's does: a frame that reads both as a command and as a report is
//! attributed and carries `also`, and MODULE_DATA is typed by an earlier
//! MODULE_NEW. So every item is the tool's line for it.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyList};
use pythonize::Depythonizer;
use robowire::stream::{owned_event, FrameRules, OwnedFrame};
use robowire::telemetrix::{
    Both, CaptureContext, Device, Dialect, Framing, Host, MessageBuf, Side, BOTH_BUFFER,
};
use robowire::{Stats, StreamDecoder};

use crate::array::Tables;
use crate::clock::Clock;
use crate::decoder::PyStreamDecoder;
use crate::engine::{append, bad_choice, decode_events, frames_decoded, Engine, Items, Resolve};

const SOURCES: &[&str] = &["pico", "host", "any"];

/// A Telemetrix stream decoder with the capture context the tool keeps.
/// Every side decodes with the tool's buffer (room for a lenient unknown
/// report and the frame that must follow it).
struct Telemetrix<S: Side> {
    decoder: StreamDecoder<Framing<S>, BOTH_BUFFER>,
    context: CaptureContext,
}

impl<S: Side> Telemetrix<S>
where
    Framing<S>: FrameRules,
{
    fn boxed(framing: Framing<S>) -> Box<dyn Engine>
    where
        Self: Engine + 'static,
    {
        Box::new(Self {
            context: CaptureContext::new(&framing),
            decoder: StreamDecoder::new(framing),
        })
    }
}

impl<S> Telemetrix<S>
where
    S: Side + Send + Sync,
    Framing<S>: FrameRules<Owned = S::Owned, Error = robowire::telemetrix::Error>,
    S::Owned: Into<MessageBuf>,
{
    /// Annotate one event and append it to `out`.
    fn put(
        context: &mut CaptureContext,
        event: robowire::stream::OwnedEvent<Framing<S>>,
        items: Items,
        out: &Bound<'_, PyList>,
    ) -> PyResult<()> {
        let event = event.map(|frame| Self::annotated(context, frame));
        append::<Framing<Both>>(out, event, items)
    }

    /// `frame` as a message of either side, with what the capture so far
    /// tells about it (the tool's line for it).
    fn annotated(
        context: &mut CaptureContext,
        frame: OwnedFrame<S::Owned>,
    ) -> OwnedFrame<MessageBuf> {
        let mut message: MessageBuf = frame.message.into();
        context.annotate(&mut message);
        OwnedFrame {
            offset: frame.offset,
            len: frame.len,
            message,
        }
    }
}

impl<S> Telemetrix<S>
where
    S: Side + Send + Sync,
    Framing<S>: FrameRules<Owned = S::Owned, Error = robowire::telemetrix::Error>,
    S::Owned: Into<MessageBuf>,
{
    /// Append the events that `how` resolves from what is buffered.
    fn resolve(&mut self, how: Resolve, items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        let mut result = Ok(());
        while let Some(event) = how.next(&mut self.decoder) {
            if result.is_ok() {
                result = Self::put(&mut self.context, event, items, out);
            }
        }
        result
    }
}

impl<S> Engine for Telemetrix<S>
where
    S: Side + Send + Sync,
    Framing<S>: FrameRules<Owned = S::Owned, Error = robowire::telemetrix::Error> + Send + Sync,
    S::Owned: Into<MessageBuf> + Send,
{
    fn feed(&mut self, data: &[u8], items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        let context = &mut self.context;
        let mut result = Ok(());
        decode_events(out.py(), &mut self.decoder, data, true, |event| {
            if result.is_ok() {
                result = Self::put(context, event, items, out);
            } else if let Ok(frame) = event {
                // Keep the context in step even after a failure.
                let mut message: MessageBuf = frame.message.into();
                context.annotate(&mut message);
            }
            Ok(())
        })?;
        result
    }

    fn finish(&mut self, items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        self.resolve(Resolve::Finish, items, out)
    }

    fn settle(&mut self, items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        self.resolve(Resolve::Settle, items, out)
    }

    fn count(&mut self, data: &[u8]) -> usize {
        let mut input = data;
        let mut frames = 0;
        while let Some(event) = self.decoder.decode(&mut input) {
            frames += usize::from(event.is_ok());
        }
        frames
    }

    fn feed_table(&mut self, data: &[u8], tables: &mut Tables) -> PyResult<()> {
        let mut input = data;
        let mut result = Ok(());
        tables.frame = frames_decoded(&self.decoder.stats());
        while let Some(event) = self.decoder.decode(&mut input) {
            if let Ok(frame) = owned_event::<Framing<S>>(event) {
                let frame = Self::annotated(&mut self.context, frame);
                if result.is_ok() {
                    result = tables.push_flat(&robowire::telemetrix::FIELD_INFO, &frame);
                }
                tables.frame += 1;
            }
        }
        result
    }

    fn stats(&self) -> Stats {
        self.decoder.stats()
    }

    fn buffered(&self) -> usize {
        self.decoder.buffered()
    }

    fn clear(&mut self) {
        self.decoder.clear();
    }
}

/// The `dialect` option.
fn dialect(name: &str) -> PyResult<Dialect> {
    name.parse()
        .map_err(|e: robowire::telemetrix::UnknownName| PyValueError::new_err(e.to_string()))
}

/// The Telemetrix4RpiPico stream decoder (a :class:`robowire.StreamDecoder`):
/// feed it the bytes of a serial link or a capture in chunks of any size.
///
/// ``source`` says who sent the bytes: ``"pico"`` (reports only: what a
/// host reads), ``"host"`` (commands only: what the Pico reads) or ``"any"``
/// (both, for captures: a frame that reads both ways is attributed to the
/// direction of the last frame that read one way only, and carries
/// ``also``, the other reading's type). ``dialect`` is the firmware:
/// ``"mirte13"`` (mirte 1.3), ``"mirte12"`` or ``"upstream11"`` (upstream
/// 1.1). ``lenient=True`` accepts report ids the dialect does not define as
/// ``unknown_report`` when a valid report follows directly (not with
/// ``source="host"``). ``errors=True`` returns rejected candidates as items;
/// items are objects of each message type's class (``analog_report``:
/// :class:`AnalogReport`, fields as typed attributes, each made
/// from the frame when read); ``typed=False`` returns dicts instead. ``typed=True`` and
/// ``lazy=True`` are deprecated and warn.
///
/// >>> from robowire import telemetrix
/// >>> d = telemetrix.Decoder(source="pico")
/// >>> d.feed(bytes.fromhex("04 03 1a 04 c9 05 0b 09 0a 00 77"))
/// [AnalogReport({'offset': 0, 'len': 5, 'type': 'analog_report', 'pin': 26, 'value': 1225}), SonarDistance({'offset': 5, 'len': 6, 'type': 'sonar_distance', 'trig': 9, 'echo': 10, 'cm': 119})]
#[pyclass(module = "robowire.telemetrix", name = "Decoder", extends = PyStreamDecoder)]
pub struct TmxDecoder;

#[pymethods]
impl TmxDecoder {
    #[new]
    // The Python constructor's keyword options, one argument each.
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (source = "any", dialect = "mirte13", lenient = false, errors = false, lazy = false, typed = None, clock = None))]
    fn new(
        source: &str,
        dialect: &str,
        lenient: bool,
        errors: bool,
        lazy: bool,
        typed: Option<bool>,
        clock: Option<Bound<'_, PyAny>>,
        py: Python<'_>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let name = dialect;
        let dialect = self::dialect(name)?;
        let engine = match source {
            "pico" => {
                let framing = Framing::<Host>::new().with_dialect(dialect);
                Telemetrix::boxed(if lenient { framing.lenient() } else { framing })
            }
            "any" => {
                let framing = Framing::<Both>::new().with_dialect(dialect);
                Telemetrix::boxed(if lenient { framing.lenient() } else { framing })
            }
            "host" if lenient => {
                return Err(PyValueError::new_err(
                    "lenient accepts unknown report ids, which source=\"host\" does not decode",
                ))
            }
            "host" => Telemetrix::boxed(Framing::<Device>::new().with_dialect(dialect)),
            other => return Err(bad_choice("source", other, SOURCES)),
        };
        let items = Items::new(py, errors, lazy, typed)?;
        let lenient = if lenient { ", lenient=True" } else { "" };
        let repr = format!(
            "robowire.telemetrix.Decoder(source={source:?}, dialect={name:?}{lenient}{})",
            items.describe()
        );
        let base = PyStreamDecoder::new(engine, items, repr, Clock::new(clock)?, py);
        Ok(PyClassInitializer::from(base).add_subclass(TmxDecoder))
    }
}

/// The frame of one command or report, a dict in the JSON-lines schema (as
/// the decoder returns it; ``offset``, ``len`` and ``also`` are ignored), for
/// firmware ``dialect`` (which fields a type has depends on it). Raises
/// ``ValueError`` naming the field and its range when the message is not
/// valid.
///
/// >>> from robowire import telemetrix
/// >>> telemetrix.encode({"type": "digital_write", "pin": 25, "value": 1}).hex(" ")
/// '03 02 19 01'
#[pyfunction]
#[pyo3(signature = (message, /, dialect = "mirte13"))]
fn encode<'py>(message: &Bound<'py, PyAny>, dialect: &str) -> PyResult<Bound<'py, PyBytes>> {
    let dialect = self::dialect(dialect)?;
    let message = crate::engine::as_message(message)?;
    let mut input = Depythonizer::from_object(&message);
    let frame = MessageBuf::deserialize_in(&mut input, dialect)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(PyBytes::new(message.py(), &frame))
}

crate::units::field_info_function!(robowire::telemetrix::FIELD_INFO);

/// `robowire.telemetrix`.
pub fn module(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    let m = PyModule::new(py, "telemetrix")?;
    m.add_class::<TmxDecoder>()?;
    m.add_function(wrap_pyfunction!(encode, &m)?)?;
    m.add_function(wrap_pyfunction!(field_info, &m)?)?;
    crate::kinds::telemetrix::add(&m)?;
    Ok(m)
}
