//! `robowire.Item`: a decoded item kept in Rust until Python reads it, for
//! decoders' default typed items (messages without a class of their own)
//! and for the deprecated `lazy=True`.

use pyo3::basic::CompareOp;
use pyo3::exceptions::{PyAttributeError, PyKeyError};
use pyo3::ffi;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyIterator, PyString, PyTuple, PyType};
use robowire::stream::{OwnedFrame, Rejected};
use serde::Serialize;

use crate::compact::CompactMessage;
use crate::engine::{timed_dict, to_python};
use crate::kinds;
use crate::pick::field;
use crate::typed::untracked;

/// The names of `Item`'s own attributes, which fields do not shadow.
const METHODS: [&str; 6] = ["offset", "to_dict", "get", "keys", "values", "items"];

/// A frame or a rejection, type-erased.
pub trait Erased: Send + Sync {
    /// Offset of the first byte in the stream.
    fn offset(&self) -> u64;
    /// The item as a dict in the JSON-lines schema.
    fn to_python<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>>;
    /// The value of that dict's `key`, made without the dict (`None`: no
    /// such key).
    fn field<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>>;
}

impl<M: Serialize + Send + Sync> Erased for OwnedFrame<M> {
    fn offset(&self) -> u64 {
        self.offset
    }

    fn to_python<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, self)
    }

    fn field<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        field(py, self, key)
    }
}

impl<E: Serialize + Send + Sync> Erased for Rejected<E> {
    fn offset(&self) -> u64 {
        self.offset
    }

    fn to_python<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, self)
    }

    fn field<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        field(py, self, key)
    }
}

/// An item rebuilt from its dict (unpickled): the dict is the item.
struct Unpickled {
    offset: u64,
    dict: Py<PyDict>,
}

impl Erased for Unpickled {
    fn offset(&self) -> u64 {
        self.offset
    }

    fn to_python<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        Ok(self.dict.bind(py).clone().into_any())
    }

    fn field<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.dict.bind(py).get_item(key)
    }
}

/// What an [`Item`] holds: a Telemetrix message in place (the commonest
/// item kept by the million; a short frame needs no allocation of its own),
/// anything else boxed.
enum Event {
    Compact(CompactMessage),
    Boxed(Box<dyn Erased>),
}

impl Event {
    fn erased(&self) -> &dyn Erased {
        match self {
            Self::Compact(message) => message,
            Self::Boxed(event) => event.as_ref(),
        }
    }
}

/// A decoded item that builds its dict only when it is first iterated or
/// compared (a field read alone is made from the frame in Rust): what a
/// decoder returns by default for every message without a class
/// of its own (all but OmniTiles telemetry) and for rejections, and what the
/// deprecated ``lazy=True`` returns for everything. Fields read as attributes
/// (``item.speed``) or as keys. It is a read-only mapping with
/// the same keys and values as the dict a ``typed=False`` decoder returns
/// (``item["type"]``, ``item.get("tof")``, ``dict(item)``, ``item ==
/// {...}``); :meth:`to_dict` gives a plain dict. Items that are never read
/// cost almost nothing, so a host that looks at one frame in a hundred, or
/// only at :attr:`offset`, goes several times faster.
#[pyclass(module = "robowire", name = "Item", frozen, mapping, subclass)]
pub struct Item {
    event: Event,
    /// The receive time, the dict's `"t"` (first) when there is one.
    t: Option<f64>,
    dict: PyOnceLock<Py<PyDict>>,
    /// The fields that read as `None` as attributes when the frame lacks
    /// them (a message class's optional ones; none for a plain `Item`).
    optional: [&'static [&'static str]; 2],
    /// A message class's `type`, as a Python string made once per class:
    /// the commonest read (a dispatch on the type) needs no walk of the
    /// frame.
    kind: Option<&'static Py<PyString>>,
}

impl Item {
    /// An item around `event`, received at `t` if the caller gave a time.
    pub fn new(event: Box<dyn Erased>, t: Option<f64>) -> Self {
        Self::with(Event::Boxed(event), t)
    }

    /// An item around a Telemetrix message, received at `t`.
    pub fn compact(message: CompactMessage, t: Option<f64>) -> Self {
        Self::with(Event::Compact(message), t)
    }

    fn with(event: Event, t: Option<f64>) -> Self {
        Self {
            event,
            t,
            dict: PyOnceLock::new(),
            optional: [&[], &[]],
            kind: None,
        }
    }

    /// The item of a message class: its `type` (`kind`, the frame's own)
    /// and the fields `common` and `own` that read as `None` when the frame
    /// lacks them.
    pub fn classed(
        self,
        kind: &'static Py<PyString>,
        common: &'static [&'static str],
        own: &'static [&'static str],
    ) -> Self {
        Self {
            optional: [common, own],
            kind: Some(kind),
            ..self
        }
    }

    fn dict<'py>(&self, py: Python<'py>) -> PyResult<&Bound<'py, PyDict>> {
        let dict = self.dict.get_or_try_init(py, || {
            let dict = timed_dict(py, self.t, self.event.erased().to_python(py)?)?;
            Ok::<_, PyErr>(dict.cast_into::<PyDict>()?.unbind())
        })?;
        Ok(dict.bind(py))
    }

    /// The value under `key`: from the dict once it is built, else read
    /// from the event alone (one field made, no dict).
    fn lookup<'py>(
        &self,
        py: Python<'py>,
        key: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        match key.cast::<PyString>() {
            Ok(name) => self.named(py, name, &name.to_cow()?),
            Err(_) => self.dict(py)?.get_item(key),
        }
    }

    /// The value under the string key `key` (whose text is `name`): from
    /// the dict once it is built, else from the event alone.
    fn named<'py>(
        &self,
        py: Python<'py>,
        key: &Bound<'py, PyString>,
        name: &str,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        if let Some(dict) = self.dict.get(py) {
            return dict.bind(py).get_item(key);
        }
        match (name, self.t, self.kind) {
            ("t", Some(t), _) => Ok(Some(t.into_pyobject(py)?.into_any())),
            ("type", _, Some(kind)) => Ok(Some(kind.bind(py).clone().into_any())),
            _ => self.event.erased().field(py, name),
        }
    }
}

#[pymethods]
impl Item {
    /// Offset of the item's first byte in the stream (no dict is built).
    #[getter]
    fn offset(&self) -> u64 {
        self.event.erased().offset()
    }

    /// The item as a new plain dict in the JSON-lines schema.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.dict(py)?.copy()
    }

    /// The value of ``key``, or ``default`` where the item has no such key.
    #[pyo3(signature = (key, default = None, /))]
    fn get<'py>(
        &self,
        py: Python<'py>,
        key: &Bound<'py, PyAny>,
        default: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        Ok(match self.lookup(py, key)? {
            Some(value) => value,
            None => default.unwrap_or_else(|| py.None().into_bound(py)),
        })
    }

    /// The keys, in schema order (``offset`` first).
    fn keys<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.dict(py)?.call_method0("keys")
    }

    /// The values, in schema order.
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.dict(py)?.call_method0("values")
    }

    /// The ``(key, value)`` pairs, in schema order.
    fn items<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.dict(py)?.call_method0("items")
    }

    /// A field by attribute (``item.speed``), as ``item["speed"]``. Looked
    /// up before the class's attributes (one dict lookup, no exception on
    /// the way), except for dunder names and the methods.
    fn __getattribute__<'py>(
        slf: &Bound<'py, Self>,
        name: &Bound<'py, PyString>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let item = slf.get();
        let text = name.to_cow()?;
        let own = text.starts_with("__") || METHODS.contains(&&*text);
        if !own {
            if let Some(value) = item.named(py, name, &text)? {
                return Ok(value);
            }
            if item.optional.iter().any(|fields| fields.contains(&&*text)) {
                return Ok(py.None().into_bound(py));
            }
        }
        // SAFETY: both pointers are live objects for the call, which
        // returns a new reference or NULL with an exception set.
        unsafe {
            Bound::from_owned_ptr_or_err(
                py,
                ffi::PyObject_GenericGetAttr(slf.as_ptr(), name.as_ptr()),
            )
        }
    }

    /// The error for an attribute the item does not have (PyO3 calls this
    /// when `__getattribute__` raises `AttributeError`).
    fn __getattr__(&self, py: Python<'_>, name: &Bound<'_, PyString>) -> PyResult<()> {
        let dict = self.dict(py)?;
        let kind = match dict.get_item("type")? {
            Some(kind) => kind,
            None => dict
                .get_item("error")?
                .unwrap_or_else(|| py.None().into_bound(py)),
        };
        Err(PyAttributeError::new_err(format!(
            "{kind} item has no field {name}"
        )))
    }

    fn __getitem__<'py>(
        &self,
        py: Python<'py>,
        key: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.lookup(py, key)?
            .ok_or_else(|| PyKeyError::new_err(key.clone().unbind()))
    }

    fn __contains__(&self, py: Python<'_>, key: &Bound<'_, PyAny>) -> PyResult<bool> {
        Ok(self.lookup(py, key)?.is_some())
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(self.dict(py)?.len())
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyIterator>> {
        self.dict(py)?.as_any().try_iter()
    }

    fn __richcmp__<'py>(
        &self,
        py: Python<'py>,
        other: &Bound<'py, PyAny>,
        op: CompareOp,
    ) -> PyResult<Py<PyAny>> {
        let other = match other.cast::<Item>() {
            Ok(item) => item.get().dict(py)?.clone().into_any(),
            Err(_) if other.is_instance_of::<PyDict>() => other.clone(),
            Err(_) => return Ok(py.NotImplemented()),
        };
        match op {
            CompareOp::Eq | CompareOp::Ne => Ok(self.dict(py)?.rich_compare(other, op)?.unbind()),
            _ => Ok(py.NotImplemented()),
        }
    }

    fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
        let dict = slf.get().dict(slf.py())?.repr()?;
        Ok(format!("{}({dict})", slf.get_type().name()?))
    }

    /// Pickles (and copies) as its dict: the copy is equal to the item and
    /// to that dict. Unhashable, as the dict it equals is.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let rebuild = slf.get_type().getattr(pyo3::intern!(py, "_from_dict"))?;
        let args = (slf.get().to_dict(py)?,).into_pyobject(py)?.into_any();
        PyTuple::new(py, [rebuild, args])
    }

    /// The item whose dict is ``dict`` (what unpickling calls): its
    /// ``offset`` key is the item's offset, and its class ``cls`` (a
    /// message class: the one of the dict's ``type``).
    #[classmethod]
    fn _from_dict<'py>(
        cls: &Bound<'py, PyType>,
        dict: Bound<'py, PyDict>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = cls.py();
        let offset = dict
            .get_item(pyo3::intern!(py, "offset"))?
            .ok_or_else(|| PyKeyError::new_err("offset"))?
            .extract()?;
        let kind: Option<String> = match dict.get_item(pyo3::intern!(py, "type"))? {
            Some(kind) => kind.extract().ok(),
            None => None,
        };
        let item = Self::new(
            Box::new(Unpickled {
                offset,
                dict: dict.unbind(),
            }),
            None,
        );
        let kind = kind.as_deref().unwrap_or("");
        if kinds::telemetrix::owns(cls) {
            kinds::telemetrix::wrap(py, kind, item)
        } else if kinds::pixy2::owns(cls) {
            kinds::pixy2::wrap(py, kind, item)
        } else {
            untracked(py, item)
        }
    }
}
