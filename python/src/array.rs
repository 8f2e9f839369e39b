//! `feed_array`: the frames of a chunk as numpy structured arrays, one per
//! message kind, built in Rust (records packed into one buffer that numpy
//! then owns and views with the kind's dtype, through the `numpy` crate).
//!
//! OmniTiles has a record per message kind written here (telemetry and
//! every command); Telemetrix and Pixy2 tables are read from the messages'
//! serde form ([`crate::columns`]).

use std::collections::BTreeMap;

use numpy::{npyffi, PyArray1, PyArrayDescr, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyList};
use robowire::omnitiles::{Command, Message, Telemetry, NO_READING};
use robowire::stream::OwnedFrame;
use robowire::units::FieldTable;

use crate::columns::Flat;

/// The packed records of one message kind, and its numpy dtype.
struct Table {
    /// `(name, numpy type)` of each field, in record order.
    dtype: &'static [(&'static str, &'static str)],
    records: Vec<u8>,
}

/// The tables a `feed_array` call fills, by message kind.
#[derive(Default)]
pub struct Tables {
    tables: BTreeMap<&'static str, Table>,
    /// The tables read from the serde form, for protocols without records.
    flat: Option<Flat>,
    /// The index of the frame being recorded among the decoder's frames.
    pub frame: u64,
}

impl Tables {
    /// The record buffer of `kind`, created with `dtype` on first use.
    fn table(
        &mut self,
        kind: &'static str,
        dtype: &'static [(&'static str, &'static str)],
    ) -> &mut Vec<u8> {
        &mut self
            .tables
            .entry(kind)
            .or_insert_with(|| Table {
                dtype,
                records: Vec::new(),
            })
            .records
    }

    /// Add `frame` (the decoder's [`frame`](Self::frame)-th) to the
    /// serde-form tables of a protocol whose field table is `fields`.
    pub fn push_flat<T: serde::Serialize + ?Sized>(
        &mut self,
        fields: &'static FieldTable,
        frame: &T,
    ) -> PyResult<()> {
        let index = self.frame;
        (self.flat.get_or_insert_with(|| Flat::new(fields))).push(frame, index)
    }

    /// The tables as a dict of numpy structured arrays, by kind (with
    /// `masked`, masked arrays: see [`masked`]).
    pub fn into_arrays(self, py: Python<'_>, masked: bool) -> PyResult<Bound<'_, PyDict>> {
        let arrays = PyDict::new(py);
        if let Some(flat) = self.flat {
            flat.into_arrays(&arrays, masked)?;
        }
        for (kind, table) in self.tables {
            let dtype = dtype_of(py, kind, table.dtype)?;
            let array = records_as(py, table.records, dtype)?;
            match masked {
                true => arrays.set_item(kind, self::masked(kind, &array)?)?,
                false => arrays.set_item(kind, array)?,
            }
        }
        Ok(arrays)
    }
}

/// `records` (whole records of `dtype`) as a numpy structured array that
/// owns them.
pub fn records_as<'py>(
    py: Python<'py>,
    records: Vec<u8>,
    dtype: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let bytes = PyArray1::<u8>::from_vec(py, records);
    // SAFETY: `bytes` is a contiguous 1-D u8 array whose length is a whole
    // number of records of `dtype`, so the view is valid; PyArray_View
    // steals the reference to the descriptor it is given (a new one here)
    // and returns a new reference or NULL.
    unsafe {
        let descr = dtype.into_ptr().cast::<npyffi::PyArray_Descr>();
        let view = npyffi::PY_ARRAY_API.PyArray_View(
            py,
            bytes.as_array_ptr(),
            descr,
            std::ptr::null_mut(),
        );
        Bound::from_owned_ptr_or_err(py, view)
    }
}

/// The numpy dtype of each kind, made once.
static DTYPES: PyOnceLock<Py<PyDict>> = PyOnceLock::new();

/// The numpy dtype of `kind`, whose fields are `fields`.
fn dtype_of<'py>(
    py: Python<'py>,
    kind: &'static str,
    fields: &[(&str, &str)],
) -> PyResult<Bound<'py, PyAny>> {
    let cache = DTYPES.get_or_init(py, || PyDict::new(py).unbind()).bind(py);
    if let Some(dtype) = cache.get_item(kind)? {
        return Ok(dtype);
    }
    let spec = PyList::new(py, fields.iter().copied())?;
    let dtype = PyArrayDescr::new(py, &spec)?.into_any();
    cache.set_item(kind, &dtype)?;
    Ok(dtype)
}

/// A message that has tables.
pub trait Tabular: Sized {
    /// Append `frame`'s record to its kind's table.
    fn record(frame: &OwnedFrame<Self>, tables: &mut Tables) -> PyResult<()>;
}

/// The dtype of the `telemetry` table. `len` tells the layout (7, 15, 17, 45
/// or 53 bytes); a field the layout does not carry, like a reading the tile
/// sent as no reading, is 65535 (integers) or NaN (IMU values).
pub const TELEMETRY_DTYPE: &[(&str, &str)] = &[
    ("offset", "<u8"),
    ("len", "u1"),
    ("m1_pos", "<u2"),
    ("m2_pos", "<u2"),
    ("uwb_0", "<u2"),
    ("uwb_1", "<u2"),
    ("uwb_2", "<u2"),
    ("uwb_3", "<u2"),
    ("tof", "<u2"),
    ("ax", "<f4"),
    ("ay", "<f4"),
    ("az", "<f4"),
    ("gx", "<f4"),
    ("gy", "<f4"),
    ("gz", "<f4"),
    ("m1_adcs_0", "<u2"),
    ("m1_adcs_1", "<u2"),
    ("m1_adcs_2", "<u2"),
    ("m1_adcs_3", "<u2"),
    ("m2_adcs_0", "<u2"),
    ("m2_adcs_1", "<u2"),
];

/// The lengths of the layouts that carry the IMU and the ADCs (45, 53).
const WITH_IMU: (u8, u8) = (45, 53);

/// `array` (a table of message kind `kind`) as a `numpy.ma.MaskedArray`
/// whose mask marks every cell without a reading: an `Option` reading stored
/// as 65535 (no reading, or its group not carried), and the IMU and ADC
/// cells of a layout that carries none (by `len`: their values, NaN and
/// 65535, could be real samples). Commands have no such cells.
pub fn masked<'py>(kind: &str, array: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let py = array.py();
    let numpy = py.import("numpy")?;
    let ma = py.import("numpy.ma")?;
    if kind != "telemetry" {
        return ma.getattr("MaskedArray")?.call1((array,));
    }
    let names: Vec<&str> = TELEMETRY_DTYPE.iter().map(|&(name, _)| name).collect();
    let mask_dtype = PyList::new(py, names.iter().map(|&name| (name, "?")))?;
    let mask = numpy.call_method1("zeros", (array.len()?, mask_dtype))?;
    let lacks_imu = numpy
        .call_method1("isin", (array.get_item("len")?, WITH_IMU))?
        .call_method0("__invert__")?;
    for &(name, _) in TELEMETRY_DTYPE {
        let cells = if READINGS.contains(&name) {
            array
                .get_item(name)?
                .call_method1("__eq__", (NO_READING,))?
        } else if name.contains("_adcs_") || IMU.contains(&name) {
            lacks_imu.clone()
        } else {
            continue;
        };
        mask.set_item(name, cells)?;
    }
    let kwargs = PyDict::new(py);
    kwargs.set_item("mask", mask)?;
    ma.getattr("MaskedArray")?.call((array,), Some(&kwargs))
}

/// The telemetry fields that are `Option` readings (65535: none).
const READINGS: [&str; 7] = [
    "m1_pos", "m2_pos", "uwb_0", "uwb_1", "uwb_2", "uwb_3", "tof",
];

/// The IMU fields of the telemetry table.
const IMU: [&str; 6] = ["ax", "ay", "az", "gx", "gy", "gz"];

/// Bytes of one telemetry record.
const TELEMETRY_RECORD: usize = 8 + 1 + 2 * 7 + 4 * 6 + 2 * 6;

const COMMAND: &[(&str, &str)] = &[("offset", "<u8"), ("len", "u1")];
const SPEED: &[(&str, &str)] = &[("offset", "<u8"), ("len", "u1"), ("speed", "u1")];
const POSITION: &[(&str, &str)] = &[("offset", "<u8"), ("len", "u1"), ("position", "u1")];
const VELOCITY: &[(&str, &str)] = &[
    ("offset", "<u8"),
    ("len", "u1"),
    ("vx", "i1"),
    ("vy", "i1"),
    ("omega", "i1"),
];

impl Tabular for Telemetry {
    fn record(frame: &OwnedFrame<Self>, tables: &mut Tables) -> PyResult<()> {
        let t = &frame.message;
        let out = tables.table("telemetry", TELEMETRY_DTYPE);
        out.reserve(TELEMETRY_RECORD);
        out.extend_from_slice(&frame.offset.to_le_bytes());
        out.push(frame.len as u8);
        let u16s = |out: &mut Vec<u8>, values: &[Option<u16>]| {
            for v in values {
                out.extend_from_slice(&v.unwrap_or(NO_READING).to_le_bytes());
            }
        };
        let uwb = t.uwb.unwrap_or([None; 4]);
        u16s(out, &[t.m1_pos, t.m2_pos]);
        u16s(out, &uwb);
        u16s(out, &[t.tof.flatten()]);
        let imu = t.imu.map_or([f32::NAN; 6], |imu| imu.to_array());
        for x in imu {
            out.extend_from_slice(&x.to_bits().to_le_bytes());
        }
        let m1 = t.m1_adcs.unwrap_or([NO_READING; 4]);
        let m2 = t.m2_adcs.unwrap_or([NO_READING; 2]);
        for v in m1.iter().chain(&m2) {
            out.extend_from_slice(&v.to_le_bytes());
        }
        Ok(())
    }
}

impl Tabular for Command {
    fn record(frame: &OwnedFrame<Self>, tables: &mut Tables) -> PyResult<()> {
        let c = &frame.message;
        let (dtype, fields): (_, &[u8]) = match *c {
            Command::Extend { speed, .. } | Command::Retract { speed, .. } => (SPEED, &[speed]),
            Command::SetPosition { position, .. } => (POSITION, &[position]),
            Command::BaseVelocity { vx, vy, omega } => {
                (VELOCITY, &[vx as u8, vy as u8, omega as u8])
            }
            Command::Ping | Command::Brake { .. } | Command::BaseBrake => (COMMAND, &[]),
        };
        let out = tables.table(c.name(), dtype);
        out.extend_from_slice(&frame.offset.to_le_bytes());
        out.push(frame.len as u8);
        out.extend_from_slice(fields);
        Ok(())
    }
}

impl Tabular for Message {
    fn record(frame: &OwnedFrame<Self>, tables: &mut Tables) -> PyResult<()> {
        let (offset, len) = (frame.offset, frame.len);
        match frame.message {
            Message::Telemetry(message) => Telemetry::record(
                &OwnedFrame {
                    offset,
                    len,
                    message,
                },
                tables,
            ),
            Message::Command(message) => Command::record(
                &OwnedFrame {
                    offset,
                    len,
                    message,
                },
                tables,
            ),
        }
    }
}

/// Pixy2 tables come from the serde form, with a table per row list.
macro_rules! pixy2_tables {
    ($($message:ty),*) => {$(
        impl Tabular for robowire::pixy2::Envelope<$message> {
            fn record(frame: &OwnedFrame<Self>, tables: &mut Tables) -> PyResult<()> {
                tables.push_flat(&robowire::pixy2::FIELD_INFO, frame)
            }
        }
    )*};
}

pixy2_tables!(
    robowire::pixy2::ResponseBuf,
    robowire::pixy2::Request,
    robowire::pixy2::MessageBuf
);
