//! `clock=`: the receive-time clock a decoder stamps its items with when
//! `feed` is given no `t`, and the time `poll` checks the idle deadline at.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;

/// A decoder's clock: the caller's callable, or none (items carry a time
/// only when the call gives one; the idle deadline runs on
/// `time.monotonic()`).
pub struct Clock(Option<Py<PyAny>>);

impl Clock {
    /// `clock`, which must be callable (a `TypeError` otherwise).
    pub fn new(clock: Option<Bound<'_, PyAny>>) -> PyResult<Self> {
        match clock {
            Some(clock) if clock.is_callable() => Ok(Self(Some(clock.unbind()))),
            Some(_) => Err(PyTypeError::new_err(
                "clock must be a callable that returns seconds (time.monotonic)",
            )),
            None => Ok(Self(None)),
        }
    }

    /// The receive time of a call: `t` when given, else the clock's time
    /// now, else none.
    pub fn stamp(&self, py: Python<'_>, t: Option<f64>) -> PyResult<Option<f64>> {
        match (t, &self.0) {
            (Some(t), _) => Ok(Some(t)),
            (None, Some(clock)) => Ok(Some(clock.call0(py)?.extract(py)?)),
            (None, None) => Ok(None),
        }
    }

    /// The time now: the clock's, else `time.monotonic()`.
    pub fn now(&self, py: Python<'_>) -> PyResult<f64> {
        match self.stamp(py, None)? {
            Some(now) => Ok(now),
            None => monotonic(py),
        }
    }

    /// A decoder's `repr` (`Decoder(source="tile")`) with the clock as the
    /// last option: `Decoder(source="tile", clock=<built-in function
    /// monotonic>)`.
    pub fn in_repr(&self, py: Python<'_>, repr: String) -> String {
        let (Some(clock), Some(head)) = (&self.0, repr.strip_suffix(')')) else {
            return repr;
        };
        match clock.bind(py).repr() {
            Ok(text) => format!("{head}, clock={text})"),
            Err(_) => format!("{head}, clock=...)"),
        }
    }
}

/// Python's `time.monotonic()`.
fn monotonic(py: Python<'_>) -> PyResult<f64> {
    static MONOTONIC: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    MONOTONIC
        .import(py, "time", "monotonic")?
        .call0()?
        .extract()
}
