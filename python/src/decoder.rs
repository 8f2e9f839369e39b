//! `robowire.StreamDecoder`: the Python base class of every protocol's
//! `Decoder`, holding one [`Engine`].

use pyo3::exceptions::{PyImportError, PyTypeError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyList, PyType};

use crate::array::Tables;
use crate::clock::Clock;
use crate::engine::{detached_from_size, stats_dict, with_bytes, Engine, Form, Items};

/// The stream decoder every protocol's ``Decoder`` is: feed it bytes as they
/// arrive, in chunks of any size, and it returns the decoded items.
///
/// Each item is a typed object (:class:`robowire.omnitiles.Telemetry`, a
/// Telemetrix or Pixy2 message class such as
/// :class:`robowire.telemetrix.AnalogReport`, else :class:`robowire.Item`)
/// that reads its fields as attributes, or with
/// ``typed=False`` a dict, in the ``robowire`` command-line tool's JSON-lines
/// schema either way: ``offset`` (of the frame's first byte, counted from the first byte
/// ever fed), ``len`` (the frame's length), then the message's own keys
/// (``type`` first). With ``errors=True``, rejected candidates are items too:
/// ``offset`` then the error's keys (``error`` first, no ``type``). The items
/// never depend on how the bytes were split; call :meth:`finish` at the end of
/// the input to resolve a frame cut short.
///
/// Every constructor takes ``clock=``, a callable returning seconds
/// (``time.monotonic``, ``time.time``, a simulation's clock): each call
/// without a ``t`` then stamps its items with the clock's time, and
/// :meth:`poll` reads it for ``now``. Without one, items carry a time only
/// when the call gives it.
///
/// Construct a protocol's subclass (``robowire.omnitiles.Decoder``, ...), not
/// this class.
#[pyclass(module = "robowire", subclass, name = "StreamDecoder")]
pub struct PyStreamDecoder {
    engine: Box<dyn Engine>,
    items: Items,
    repr: String,
    /// When the last chunk that left bytes buffered arrived, and whether
    /// the caller gave that time (`t=`), until [`Self::poll`] settles: the
    /// rule of `robowire::Idle`, kept here in the caller's float seconds
    /// (any clock) with the gap given per call, which `Idle`'s fixed
    /// integer ticks do not fit.
    held_since: Option<(f64, bool)>,
    /// `clock=`: the receive time of calls without a `t`.
    clock: Clock,
}

impl PyStreamDecoder {
    /// A decoder around `engine` stamping items by `clock`; `repr` is what
    /// `repr()` shows, without the clock.
    pub fn new(
        engine: Box<dyn Engine>,
        items: Items,
        repr: String,
        clock: Clock,
        py: Python<'_>,
    ) -> Self {
        let repr = clock.in_repr(py, repr);
        Self {
            engine,
            items,
            repr,
            held_since: None,
            clock,
        }
    }

    /// After a chunk arrived at `t` (given, or the clock's): the idle
    /// deadline runs from it (else from `time.monotonic()`) while bytes are
    /// held.
    fn received(&mut self, py: Python<'_>, t: Option<f64>) -> PyResult<()> {
        self.held_since = match (self.engine.buffered(), t) {
            (0, _) => None,
            (_, Some(t)) => Some((t, true)),
            (_, None) => Some((self.clock.now(py)?, false)),
        };
        Ok(())
    }

    /// When the held bytes were fed, if that call had a time (`t=` or the
    /// clock): the receive time of a frame they end.
    fn held_time(&self) -> Option<f64> {
        self.held_since.and_then(|(at, given)| given.then_some(at))
    }
}

#[pymethods]
impl PyStreamDecoder {
    /// Decode the next chunk of the stream (``bytes``, ``bytearray`` or
    /// ``memoryview``) and return the items completed by it, in stream order.
    /// A frame cut by the end of the chunk is kept and completed by the next.
    /// ``t``: the time the chunk was received (``time.monotonic()``, or any
    /// clock's seconds), which every item it returns carries as ``t`` (the
    /// first key of its dict form, as in the tool's lines); a frame cut
    /// across chunks has the time of the chunk that completes it. Without
    /// ``t``, a decoder constructed with ``clock=`` reads its clock once per
    /// call. :meth:`finish`, :meth:`settle` and :meth:`poll` without a
    /// ``t`` give a frame they resolve the time its last bytes were fed at,
    /// where that call had one.
    #[pyo3(signature = (data, /, t = None))]
    fn feed<'py>(
        &mut self,
        data: &Bound<'py, PyAny>,
        t: Option<f64>,
    ) -> PyResult<Bound<'py, PyList>> {
        let t = self.clock.stamp(data.py(), t)?;
        let out = PyList::empty(data.py());
        let items = Items { t, ..self.items };
        with_bytes(data, |bytes| self.engine.feed(bytes, items, &out))??;
        self.received(data.py(), t)?;
        Ok(out)
    }

    /// Decode the next chunk as :meth:`feed` does, into numpy structured
    /// arrays instead of items: a dict from message kind (``"telemetry"``,
    /// ``"m1_extend"``, ``"analog_report"``, ...) to a 1-D array with one
    /// record per frame of that kind completed by this chunk, fields
    /// ``offset``, ``len`` and the message's own (flattened, so
    /// ``pandas.DataFrame(array)`` works). Pixy2's blocks and features are a
    /// row each in ``blocks``, ``features_vectors``, ... with the frame's
    /// index (``frame``). Rejections are only counted (:attr:`stats`). Needs
    /// numpy (``pip install robowire[numpy]``).
    ///
    /// ``masked=True`` returns ``numpy.ma.MaskedArray`` tables instead, each
    /// cell masked where it holds no reading: a reading the tile sent as
    /// 0xFFFF, a group the frame's layout does not carry (UWB, ToF, the
    /// IMU, the ADCs), a field the frame does not have. Then
    /// ``a["uwb_3"].mean()`` averages the readings only, and
    /// ``pandas.DataFrame(a)`` has NaN in those cells.
    #[pyo3(signature = (data, /, masked = false))]
    fn feed_array<'py>(
        &mut self,
        data: &Bound<'py, PyAny>,
        masked: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let py = data.py();
        // Import numpy first (once), so that a missing numpy loses no bytes.
        static NUMPY: PyOnceLock<Py<PyModule>> = PyOnceLock::new();
        NUMPY
            .get_or_try_init(py, || py.import("numpy").map(Bound::unbind))
            .map_err(|e| {
                PyImportError::new_err(format!(
                    "feed_array needs numpy (pip install robowire[numpy]): {e}"
                ))
            })?;
        let mut tables = Tables::default();
        let engine = &mut self.engine;
        with_bytes(data, |bytes| {
            detached_from_size(py, bytes.len(), || engine.feed_table(bytes, &mut tables))
        })??;
        tables.into_arrays(py, masked)
    }

    /// Signal the end of the input and return the items that resolves: a
    /// buffered frame that is complete, or (with ``errors=True``) the
    /// rejection of one cut short. The decoder is then empty and can take a new
    /// stream; offsets and counters carry on.
    #[pyo3(signature = (t = None))]
    fn finish<'py>(&mut self, py: Python<'py>, t: Option<f64>) -> PyResult<Bound<'py, PyList>> {
        let t = t.or(self.held_time());
        let out = PyList::empty(py);
        self.held_since = None;
        self.engine.finish(Items { t, ..self.items }, &out)?;
        Ok(out)
    }

    /// The line has gone idle (a pause of a few byte-times, or the end of a
    /// datagram that holds whole frames): return a buffered frame that only
    /// the next byte would otherwise decide, such as a 7, 15 or 17-byte
    /// OmniTiles frame that may be a longer layout's start. An unfinished
    /// frame stays buffered for its rest and nothing is rejected, so it is
    /// safe to call after every read that was followed by silence. Called
    /// between two pieces of one frame, it can take a prefix that happens to
    /// pass as a shorter frame.
    #[pyo3(signature = (t = None))]
    fn settle<'py>(&mut self, py: Python<'py>, t: Option<f64>) -> PyResult<Bound<'py, PyList>> {
        let t = t.or(self.held_time());
        let out = PyList::empty(py);
        self.engine.settle(Items { t, ..self.items }, &out)?;
        Ok(out)
    }

    /// When the line counts as idle after ``idle`` seconds without a byte:
    /// the time of the last :meth:`feed` that left bytes buffered (its
    /// ``t``, else ``time.monotonic()`` then) plus ``idle``, or ``None``
    /// while nothing is held or once :meth:`poll` has settled since. Wait
    /// for the next chunk until then (a read timeout, ``asyncio.wait_for``)
    /// and call :meth:`poll` when it passes without one. A gap of a few
    /// byte-times at the line's baud rate plus the adapter's latency (5 ms
    /// suits most USB serial adapters; an FTDI at its default needs 20)
    /// ends a frame only the next byte would decide, as the tool's live
    /// ports do.
    #[pyo3(signature = (idle, /))]
    fn deadline(&self, idle: f64) -> Option<f64> {
        self.held_since.map(|(at, _)| at + idle)
    }

    /// The idle deadline's check, sans-IO: at ``now`` (default: the
    /// decoder's ``clock``, else ``time.monotonic()``; the clock ``feed``'s
    /// ``t`` used), if
    /// :meth:`deadline` has passed, :meth:`settle` and return its items
    /// (with the last chunk's ``t`` when it was given one), once per
    /// silence; otherwise an empty list.
    #[pyo3(signature = (idle, now = None))]
    fn poll<'py>(
        &mut self,
        py: Python<'py>,
        idle: f64,
        now: Option<f64>,
    ) -> PyResult<Bound<'py, PyList>> {
        let out = PyList::empty(py);
        let Some((at, _)) = self.held_since else {
            return Ok(out);
        };
        let now = match now {
            Some(now) => now,
            None => self.clock.now(py)?,
        };
        if now >= at + idle {
            let t = self.held_time();
            self.held_since = None;
            self.engine.settle(Items { t, ..self.items }, &out)?;
        }
        Ok(out)
    }

    /// Decode ``data`` as :meth:`feed` does but build no items: the number of
    /// frames decoded. For benchmarks (the cost of the items is the
    /// difference).
    #[pyo3(signature = (data, /))]
    fn _count(&mut self, data: &Bound<'_, PyAny>) -> PyResult<usize> {
        let engine = &mut self.engine;
        with_bytes(data, |bytes| {
            detached_from_size(data.py(), bytes.len(), || engine.count(bytes))
        })
    }

    /// Forget a buffered partial frame (its bytes count as skipped), for
    /// example after the link was reopened. Offsets and counters carry on.
    fn clear(&mut self) {
        self.held_since = None;
        self.engine.clear();
    }

    /// Link-quality counters, a new dict on each read, in the words of the
    /// tool's summary line: ``bytes`` (taken so far), ``frames``,
    /// ``frame_bytes``, ``skipped`` (bytes in no frame), ``checksum_failures``,
    /// ``other_rejections`` (superseded candidates included), ``malformed``
    /// (frames whose contents did not parse) and ``superseded``. They add up:
    /// ``bytes == frame_bytes + skipped + buffered``. The old keys
    /// ``checksum_failures`` and ``rejected`` still read, deprecated.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        stats_dict(py, &self.engine.stats())
    }

    /// Bytes held as the start of an unfinished frame.
    #[getter]
    fn buffered(&self) -> usize {
        self.engine.buffered()
    }

    /// Whether rejected candidates are returned as items.
    #[getter]
    fn errors(&self) -> bool {
        self.items.errors
    }

    /// Whether items are :class:`robowire.Item` objects that build their
    /// dict when read, rather than dicts (``lazy=True``, deprecated).
    #[getter]
    fn lazy(&self) -> bool {
        self.items.form == Form::Lazy
    }

    /// Whether items are typed objects (the default, not ``typed=False``): an
    /// :class:`robowire.omnitiles.Telemetry` per telemetry frame, a Telemetrix
    /// or Pixy2 message in its type's class, a :class:`robowire.Item` for an
    /// OmniTiles command and a rejection.
    #[getter]
    fn typed(&self) -> bool {
        self.items.form == Form::Typed
    }

    fn __repr__(&self) -> String {
        self.repr.clone()
    }

    /// Refused with a ``TypeError`` that says why: a decoder is the state of
    /// one live stream (a partial frame, offsets, counters).
    fn __reduce__(&self) -> PyResult<()> {
        Err(not_copyable(&self.repr))
    }

    /// ``Decoder[Telemetry]``: the class with its item type, for annotations
    /// (the type stubs make every decoder generic in its items).
    #[classmethod]
    fn __class_getitem__<'py>(
        cls: &Bound<'py, PyType>,
        item: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        generic_alias(cls, item)
    }
}

/// The error of pickling or copying a decoder.
pub fn not_copyable(repr: &str) -> PyErr {
    PyTypeError::new_err(format!(
        "{repr} cannot be pickled or copied: a decoder is the state of one live stream \
         (a partial frame, offsets, counters); make a new decoder with the same options \
         where it is needed"
    ))
}

/// `types.GenericAlias(cls, item)`, what `list[int]` is.
pub fn generic_alias<'py>(
    cls: &Bound<'py, PyType>,
    item: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let py = cls.py();
    static ALIAS: PyOnceLock<Py<PyType>> = PyOnceLock::new();
    ALIAS
        .import(py, "types", "GenericAlias")?
        .call1((cls, item))
}
