//! The one binding over robowire's stream engine, for every protocol.
//!
//! A protocol's Python `Decoder` holds a boxed [`Engine`]: a
//! [`StreamDecoder`] over the protocol's [`FrameRules`], whose owned messages
//! and errors serialize (serde) in the `robowire` tool's JSON-lines schema.
//! Each event becomes a Python dict by pythonizing the library's own
//! [`OwnedFrame`] or [`Rejected`]; nothing here knows any message.

use pyo3::exceptions::{PyDeprecationWarning, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyByteArray, PyBytes, PyDict, PyList, PyMapping, PyString, PyType};
use pythonize::{depythonize, pythonize};
use robowire::stream::{owned_event, FrameRules, OwnedEvent, StreamDecoder};
use robowire::{Encode, Stats};
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::array::{Tables, Tabular};
use crate::item::Item;
use crate::schema::Adapt;
use crate::typed::{untracked, PyTelemetry, Typed};

/// A stream decoder of any protocol, as the Python classes use it.
pub trait Engine: Send + Sync {
    /// Decode `data`, appending the events to `out` as `items` says. All of
    /// `data` is taken even if appending fails.
    fn feed(&mut self, data: &[u8], items: Items, out: &Bound<'_, PyList>) -> PyResult<()>;
    /// End of input: resolve what is buffered, appending the events to `out`.
    fn finish(&mut self, items: Items, out: &Bound<'_, PyList>) -> PyResult<()>;
    /// The line went idle: a buffered frame the layouts left open comes out
    /// (the library's `StreamDecoder::settle`); anything else stays.
    fn settle(&mut self, items: Items, out: &Bound<'_, PyList>) -> PyResult<()>;
    /// Decode `data` without building any Python object; the number of
    /// frames parsed (what a benchmark compares the full path with).
    fn count(&mut self, data: &[u8]) -> usize;
    /// Decode `data` into `tables` (see [`crate::array`]); rejections are
    /// only counted. All of `data` is taken even if a table fails.
    fn feed_table(&mut self, data: &[u8], tables: &mut Tables) -> PyResult<()>;
    /// The counters so far.
    fn stats(&self) -> Stats;
    /// Bytes held as the start of an unfinished candidate.
    fn buffered(&self) -> usize;
    /// Forget a buffered partial candidate (counted as skipped).
    fn clear(&mut self);
}

/// The chunk size from which `feed`, `feed_array` and `_count` decode
/// without the GIL. Releasing and taking it back costs about a microsecond:
/// measured on 4 KiB chunks it slowed `_count` by 15 %, so smaller chunks
/// (a serial port's reads) keep it, and a chunk this large spends less than
/// 1 % of its time on the switch.
pub const DETACH_FROM: usize = 16 * 1024;

/// Events decoded per release of the GIL in `feed`: the owned events waiting
/// for their Python items stay within a few hundred kilobytes.
const BATCH: usize = 4096;

/// Run `work` (a decode that builds no Python object) without the GIL when
/// `len` bytes are worth it ([`DETACH_FROM`]), else with it.
pub fn detached_from_size<T: Send>(
    py: Python<'_>,
    len: usize,
    work: impl Send + FnOnce() -> T,
) -> T {
    if len >= DETACH_FROM {
        py.detach(work)
    } else {
        work()
    }
}

/// Decode all of `data` with `decoder`, handing each owned event to `each`
/// (rejections only with `errors`), which builds its Python object. A chunk
/// of [`DETACH_FROM`] bytes or more is decoded in batches of [`BATCH`]
/// events without the GIL, so that other Python threads run meanwhile, and
/// each batch is then handed out with it. After `each` fails, the rest of
/// `data` is still taken (and its events dropped), and the error returned.
pub fn decode_events<R, const N: usize>(
    py: Python<'_>,
    decoder: &mut StreamDecoder<R, N>,
    data: &[u8],
    errors: bool,
    mut each: impl FnMut(OwnedEvent<R>) -> PyResult<()>,
) -> PyResult<()>
where
    R: FrameRules + Send,
    R::Owned: Send,
    R::Error: Send,
{
    let mut input = data;
    let mut result = Ok(());
    if data.len() < DETACH_FROM {
        while let Some(event) = decoder.decode(&mut input) {
            if result.is_ok() && (errors || event.is_ok()) {
                result = each(owned_event::<R>(event));
            }
        }
        return result;
    }
    loop {
        let batch = py.detach(|| {
            let mut batch = Vec::with_capacity(BATCH);
            while batch.len() < BATCH {
                match decoder.decode(&mut input) {
                    Some(Err(_)) if !errors => {}
                    Some(event) => batch.push(owned_event::<R>(event)),
                    None => break,
                }
            }
            batch
        });
        let full = batch.len() == BATCH;
        for event in batch {
            if result.is_ok() {
                result = each(event);
            }
        }
        if !full {
            return result;
        }
    }
}

/// [`Engine`] for robowire's [`StreamDecoder`] over framing `R`.
pub struct Stream<R, const N: usize>(pub StreamDecoder<R, N>);

/// How the buffered bytes are resolved without new input.
#[derive(Debug, Clone, Copy)]
pub enum Resolve {
    /// End of input (`finish`): everything, a cut frame rejected.
    Finish,
    /// The line went idle (`settle`): only what gives a frame.
    Settle,
}

impl Resolve {
    /// The next owned event this resolves from `decoder`.
    pub fn next<R: FrameRules, const N: usize>(
        self,
        decoder: &mut StreamDecoder<R, N>,
    ) -> Option<OwnedEvent<R>> {
        match self {
            Resolve::Finish => decoder.finish().map(owned_event::<R>),
            Resolve::Settle => decoder.settle().map(owned_event::<R>),
        }
    }
}

impl<R, const N: usize> Stream<R, N>
where
    R: FrameRules,
    R::Owned: Typed,
    R::Error: Serialize + Send + Sync + 'static,
{
    /// Append the events that `how` resolves from what is buffered.
    fn resolve(&mut self, how: Resolve, items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        let mut result = Ok(());
        while let Some(event) = how.next(&mut self.0) {
            if result.is_ok() {
                result = append::<R>(out, event, items);
            }
        }
        result
    }
}

impl<R, const N: usize> Stream<R, N> {
    /// A boxed engine around `decoder`.
    pub fn boxed(decoder: StreamDecoder<R, N>) -> Box<dyn Engine>
    where
        Self: Engine + 'static,
    {
        Box::new(Stream(decoder))
    }
}

impl<R, const N: usize> Engine for Stream<R, N>
where
    R: FrameRules + Send + Sync,
    R::Owned: Typed + Tabular + Send,
    R::Error: Serialize + Send + Sync + 'static,
{
    fn feed(&mut self, data: &[u8], items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        decode_events(out.py(), &mut self.0, data, items.errors, |event| {
            append::<R>(out, event, items)
        })
    }

    fn settle(&mut self, items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        self.resolve(Resolve::Settle, items, out)
    }

    fn finish(&mut self, items: Items, out: &Bound<'_, PyList>) -> PyResult<()> {
        self.resolve(Resolve::Finish, items, out)
    }

    fn count(&mut self, data: &[u8]) -> usize {
        let mut input = data;
        let mut frames = 0;
        while let Some(event) = self.0.decode(&mut input) {
            frames += usize::from(event.is_ok());
        }
        frames
    }

    fn feed_table(&mut self, data: &[u8], tables: &mut Tables) -> PyResult<()> {
        let mut input = data;
        let mut result = Ok(());
        tables.frame = frames_decoded(&self.0.stats());
        while let Some(event) = self.0.decode(&mut input) {
            if let Ok(frame) = owned_event::<R>(event) {
                if result.is_ok() {
                    result = R::Owned::record(&frame, tables);
                }
                tables.frame += 1;
            }
        }
        result
    }

    fn stats(&self) -> Stats {
        self.0.stats()
    }

    fn buffered(&self) -> usize {
        self.0.buffered()
    }

    fn clear(&mut self) {
        self.0.clear();
    }
}

/// What a decoder's items are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// Dicts in the JSON-lines schema (`typed=False`).
    Dict,
    /// [`Item`]s that build their dict when read (`lazy=True`, deprecated).
    Lazy,
    /// Typed items (the default): see [`crate::typed`].
    Typed,
}

/// How many frames a decoder has decoded (those that parsed), from its
/// counters: the index of the next one.
pub fn frames_decoded(stats: &Stats) -> u64 {
    stats.frames.saturating_sub(stats.malformed)
}

/// How a decoder hands out its events.
#[derive(Debug, Clone, Copy)]
pub struct Items {
    /// Rejections are items too.
    pub errors: bool,
    /// What the items are.
    pub form: Form,
    /// The receive time the items of this call carry as ``t`` (seconds, as
    /// the caller's clock gives them), if the caller gave one.
    pub t: Option<f64>,
}

impl Items {
    /// The options `errors`, `lazy` and `typed` of a constructor. Typed
    /// items are the default; `typed=False` gives dicts. `typed=True`, the
    /// spelling from before it was the default, and `lazy=True` warn that
    /// they are deprecated; `lazy` cannot be combined with `typed=True`.
    pub fn new(py: Python<'_>, errors: bool, lazy: bool, typed: Option<bool>) -> PyResult<Self> {
        let form = match (lazy, typed) {
            (false, None) => Form::Typed,
            (false, Some(false)) => Form::Dict,
            (false, Some(true)) => {
                deprecated(
                    py,
                    c"typed=True is deprecated: typed items are the default now, so drop it \
                      (typed=False gives dicts)",
                )?;
                Form::Typed
            }
            (true, None | Some(false)) => {
                deprecated(
                    py,
                    c"lazy=True is deprecated: the default typed items read their fields \
                      without building a dict (robowire.Item for messages without a class)",
                )?;
                Form::Lazy
            }
            (true, Some(true)) => {
                return Err(PyValueError::new_err(
                    "lazy=True and typed=True cannot be combined: drop both for typed items",
                ))
            }
        };
        Ok(Self {
            errors,
            form,
            t: None,
        })
    }

    /// The options as `repr()` shows them: `, errors=True, typed=False`.
    pub fn describe(self) -> String {
        let mut text = String::new();
        if self.errors {
            text.push_str(", errors=True");
        }
        match self.form {
            Form::Typed => {}
            Form::Lazy => text.push_str(", lazy=True"),
            Form::Dict => text.push_str(", typed=False"),
        }
        text
    }
}

/// Warn with a `DeprecationWarning` pointing at the caller's line.
fn deprecated(py: Python<'_>, message: &std::ffi::CStr) -> PyResult<()> {
    PyErr::warn(py, &py.get_type::<PyDeprecationWarning>(), message, 2)
}

/// Append one owned event to `out`: a dict in the JSON-lines schema, an
/// [`Item`] that builds it when read, or a typed item.
pub fn append<R: FrameRules>(
    out: &Bound<'_, PyList>,
    event: OwnedEvent<R>,
    items: Items,
) -> PyResult<()>
where
    R::Owned: Typed,
    R::Error: Serialize + Send + Sync + 'static,
{
    let py = out.py();
    let t = items.t;
    match (event, items.form) {
        (Err(_), _) if !items.errors => Ok(()),
        (Ok(frame), Form::Dict) => out.append(timed_dict(py, t, to_python(py, &frame)?)?),
        (Err(rejected), Form::Dict) => out.append(timed_dict(py, t, to_python(py, &rejected)?)?),
        (Ok(frame), Form::Typed) => out.append(R::Owned::typed(py, frame, t)?),
        (Ok(frame), Form::Lazy) => out.append(untracked(py, Item::new(Box::new(frame), t))?),
        (Err(rejected), Form::Lazy | Form::Typed) => {
            out.append(untracked(py, Item::new(Box::new(rejected), t))?)
        }
    }
}

/// `dict` (an item's dict form) with the receive time `"t"` first, as the
/// tool's lines have it; `dict` itself without one.
pub fn timed_dict<'py>(
    py: Python<'py>,
    t: Option<f64>,
    dict: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let Some(t) = t else {
        return Ok(dict);
    };
    let timed = PyDict::new(py);
    timed.set_item(pyo3::intern!(py, "t"), t)?;
    timed.update(dict.cast::<PyMapping>()?)?;
    Ok(timed.into_any())
}

/// Pythonize a serde value (dicts, lists, ints, floats, strings, None).
pub fn to_python<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    pythonize(py, &Adapt(value)).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The bytes of a `bytes`, `bytearray` or `memoryview` (or any object with a
/// `tobytes()`), refusing `str` and `int` (which `bytes()` would accept).
pub fn with_bytes<T>(data: &Bound<'_, PyAny>, f: impl FnOnce(&[u8]) -> T) -> PyResult<T> {
    if let Ok(bytes) = data.cast::<PyBytes>() {
        return Ok(f(bytes.as_bytes()));
    }
    if let Ok(array) = data.cast::<PyByteArray>() {
        return Ok(f(&array.to_vec()));
    }
    if !data.is_instance_of::<PyString>() && data.hasattr("tobytes")? {
        let copy = data.call_method0("tobytes")?;
        if let Ok(bytes) = copy.cast::<PyBytes>() {
            return Ok(f(bytes.as_bytes()));
        }
    }
    Err(PyTypeError::new_err(format!(
        "expected bytes, bytearray or memoryview, got {}",
        data.get_type().name()?
    )))
}

/// The counters as a `robowire._stats.Stats` dict, in the words of the
/// tool's summary line (the library's `Display` for [`Stats`]):
/// `checksum_failures` is `checksum_failures`, `other_rejections` is `rejected`
/// and `superseded` together.
pub fn stats_dict<'py>(py: Python<'py>, stats: &Stats) -> PyResult<Bound<'py, PyAny>> {
    static STATS: PyOnceLock<Py<PyType>> = PyOnceLock::new();
    let counters = [
        ("bytes", stats.bytes),
        ("frames", stats.frames),
        ("frame_bytes", stats.frame_bytes),
        ("skipped", stats.skipped),
        ("checksum_failures", stats.checksum_failures),
        ("other_rejections", stats.other_rejections),
        ("malformed", stats.malformed),
        ("superseded", stats.superseded),
    ];
    STATS
        .import(py, "robowire._stats", "Stats")?
        .call1((counters.to_vec(),))
}

/// A `ValueError` for an option value that is not one of `allowed`.
pub fn bad_choice(option: &str, value: &str, allowed: &[&str]) -> PyErr {
    PyValueError::new_err(format!(
        "{option} must be one of {}, not {value:?}",
        allowed
            .iter()
            .map(|a| format!("{a:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    ))
}

/// Read `message` (a mapping in the JSON-lines schema, or a typed item) into
/// `M`, validating as the library's `Deserialize` does, and encode it with
/// `write`. Both kinds of failure are a `ValueError` with the library's
/// message.
pub fn encode_with<'py, M: DeserializeOwned>(
    message: &Bound<'py, PyAny>,
    write: impl FnOnce(&M) -> Result<Vec<u8>, String>,
) -> PyResult<Bound<'py, PyBytes>> {
    let message = as_message(message)?;
    let value: M = depythonize(&message).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let frame = write(&value).map_err(PyValueError::new_err)?;
    Ok(PyBytes::new(message.py(), &frame))
}

/// `message` as a mapping to read: a dict or another mapping as it is, a
/// typed item through its `to_dict()`; a `TypeError` for anything else.
pub fn as_message<'py>(message: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    if message.is_instance_of::<PyTelemetry>() {
        let dict = message.call_method0(pyo3::intern!(message.py(), "to_dict"))?;
        return without_time(dict);
    }
    if message.is_instance_of::<PyDict>() || message.cast::<PyMapping>().is_ok() {
        return without_time(message.clone());
    }
    Err(PyTypeError::new_err(format!(
        "expected a message (a dict in the JSON-lines schema, or a decoded item), got {}",
        message.get_type().name()?
    )))
}

/// `message` without its receive time `"t"` (a decoded item's, or a tool
/// line's), which is no part of the frame: a copy if it has one.
fn without_time(message: Bound<'_, PyAny>) -> PyResult<Bound<'_, PyAny>> {
    let key = pyo3::intern!(message.py(), "t");
    if !message.contains(key)? {
        return Ok(message);
    }
    let copy = PyDict::new(message.py());
    copy.update(message.cast::<PyMapping>()?)?;
    copy.del_item(key)?;
    Ok(copy.into_any())
}

/// A message's frame through its [`Encode`] implementation.
pub fn encode_frame<M: Encode>(message: &M) -> Result<Vec<u8>, String> {
    let mut frame = vec![0; message.encoded_len()];
    let n = message.encode(&mut frame).map_err(|e| e.to_string())?;
    frame.truncate(n);
    Ok(frame)
}
