//! robowire's decoders and encoders for Python: the extension module
//! `robowire._robowire`, re-exported by the pure-Python package `robowire`.
//!
//! One generic binding ([`engine`]) drives robowire's stream engine for every
//! protocol and turns each event into a dict by pythonizing the library's own
//! serde form (the `robowire` tool's JSON-lines schema), or into a typed item
//! ([`typed`]).

mod array;
mod clock;
mod columns;
mod compact;
mod decoder;
mod engine;
mod item;
mod kinds;
mod omnitiles;
mod pick;
mod pixy2;
mod schema;
mod sdk;
mod telemetrix;
mod typed;
mod units;
mod walk;

use pyo3::prelude::*;

/// Add `sub` to `parent` and register it as `robowire.<name>` so that
/// `import robowire._robowire.<name>` style imports work too.
fn add_submodule(parent: &Bound<'_, PyModule>, sub: &Bound<'_, PyModule>) -> PyResult<()> {
    parent.add_submodule(sub)?;
    let name = sub.name()?;
    parent
        .py()
        .import("sys")?
        .getattr("modules")?
        .set_item(format!("robowire._robowire.{name}"), sub)?;
    Ok(())
}

#[pymodule]
fn _robowire(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<decoder::PyStreamDecoder>()?;
    m.add_class::<item::Item>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    add_submodule(m, &omnitiles::module(py)?)?;
    add_submodule(m, &pixy2::module(py)?)?;
    add_submodule(m, &telemetrix::module(py)?)?;
    add_submodule(m, &sdk::module(py)?)?;
    Ok(())
}
