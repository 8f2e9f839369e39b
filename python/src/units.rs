//! The library's field tables (`robowire::units`) in Python: each protocol
//! module's `field_info(type, path)`, and the `units` of the typed items,
//! so a unit is declared once, in the library, for the tool and for Python.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use robowire::units::FieldTable;

/// What field `path` of message type `kind` means, as a dict (`None` if
/// the table declares nothing for it): `unit` (a symbol or `None`), `doc`,
/// `no_reading`, `range` (`(min, max)` or `None`), `names`, `optional`.
pub fn field_info<'py>(
    py: Python<'py>,
    table: &FieldTable,
    kind: &str,
    path: &str,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let Some(info) = table.get(kind, path) else {
        return Ok(None);
    };
    let dict = PyDict::new(py);
    dict.set_item("unit", info.unit.map(|u| u.symbol()))?;
    dict.set_item("doc", info.doc)?;
    dict.set_item("no_reading", info.no_reading)?;
    dict.set_item("range", info.range)?;
    dict.set_item("names", info.names.to_vec())?;
    dict.set_item("optional", info.optional)?;
    Ok(Some(dict))
}

/// `{field: unit symbol}` for the `fields` of message type `kind` that
/// have a unit (an array's unit under its own name: `uwb`, not `uwb.0`).
pub fn units<'py>(
    py: Python<'py>,
    table: &FieldTable,
    kind: &str,
    prefix: &str,
    fields: &[&str],
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    for field in fields {
        let path = format!("{prefix}{field}");
        let unit = table
            .get(kind, &path)
            .and_then(|info| info.unit)
            .or_else(|| table.get(kind, &format!("{path}.0"))?.unit);
        if let Some(unit) = unit {
            dict.set_item(*field, unit.symbol())?;
        }
    }
    Ok(dict)
}

/// Define `field_info(type, path)` for a protocol's table.
macro_rules! field_info_function {
    ($table:expr) => {
        /// What field ``path`` (``"imu.az"``, ``"uwb.2"``) of message type
        /// ``type`` means, from the library's field table: a dict with
        /// ``unit`` (``"mm"``, ``"m/s²"``, or ``None``), ``doc``,
        /// ``no_reading``, ``range``, ``names`` and ``optional``; ``None``
        /// when nothing is declared for it.
        #[pyfunction]
        #[pyo3(signature = (r#type, path, /))]
        fn field_info<'py>(
            py: Python<'py>,
            r#type: &str,
            path: &str,
        ) -> PyResult<Option<Bound<'py, pyo3::types::PyDict>>> {
            crate::units::field_info(py, &$table, r#type, path)
        }
    };
}

pub(crate) use field_info_function;
