//! `feed_array` tables for any message, read from its serde form (the
//! JSON-lines schema), as the `robowire` tool's CSV tables are: a table per
//! message `type` (which names the table, so it is no column, as in the
//! OmniTiles tables), a column per leaf field named by its path (`reading.volts`,
//! `data.3`), and for the lists the protocol's field table marks as rows
//! ([`FieldInfo::rows`](robowire::units::FieldInfo), Pixy2's blocks and
//! features) a table per list with a row per element (`blocks`,
//! `features_vectors`, ...). Used for Telemetrix and Pixy2, whose messages
//! are too many and too varied for a hand-written record each (OmniTiles has
//! those: [`crate::array`]).
//!
//! A column's numpy type is the narrowest that holds every value of it in
//! the call (the wire's integer width, `f4` for the wire's floats, `U` for
//! text; a field that is a number or a name, as a sonar's `cm`, is a
//! number column and a `cm.name` text column); a cell a frame does not have (`null`, another shape's field, a
//! longer list's element) is the type's largest integer, NaN, `""` or
//! `False`, and is masked in the `masked=True` tables.

use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::Mutex;

use numpy::PyArrayDescr;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use robowire::units::{FieldInfo, FieldTable};
use serde::Serialize;

use crate::array::records_as;
use crate::walk::{span, Cell, Walk};

/// The tables of one `feed_array` call, in order of first use.
pub struct Flat {
    fields: &'static FieldTable,
    tables: Vec<Table>,
    /// The plan of each frame shape (its type, then its leaves' paths) in
    /// `planned`: worked out once per shape.
    plans: HashMap<String, usize, Fnv>,
    /// The rows a frame of each shape gives.
    planned: Vec<Vec<PlannedRow>>,
    /// Reused for each frame.
    walk: Walk,
    key: String,
}

/// FNV-1a, for the plans' keys: short strings hashed once per frame, where
/// the default SipHash cost more than the lookup it serves.
#[derive(Default, Clone, Copy)]
struct Fnv;

impl std::hash::BuildHasher for Fnv {
    type Hasher = FnvHasher;

    fn build_hasher(&self) -> FnvHasher {
        FnvHasher(0xcbf2_9ce4_8422_2325)
    }
}

struct FnvHasher(u64);

impl std::hash::Hasher for FnvHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// What `fields` declares for `path` of message type `kind`, looked up once
/// per process (a lookup scans the table; `feed_array` asks for every
/// column of every table of every call).
fn field_info(fields: &'static FieldTable, kind: &str, path: &str) -> Option<&'static FieldInfo> {
    type Known = HashMap<(usize, String, String), Option<&'static FieldInfo>>;
    static KNOWN: Mutex<Option<Known>> = Mutex::new(None);
    let key = (
        fields as *const FieldTable as usize,
        kind.to_owned(),
        path.to_owned(),
    );
    let mut known = KNOWN
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    *(known.get_or_insert_with(HashMap::new))
        .entry(key)
        .or_insert_with(|| fields.get(kind, path))
}

/// A listed element's leaves: its list's position among the message's
/// lists, its path, and each field's path in it and leaf index.
type Element<'p> = (usize, &'p str, Vec<(&'p str, usize)>);

/// One row a frame of some shape gives: its table, and each column's
/// source.
struct PlannedRow {
    table: usize,
    cells: Vec<(u32, Source)>,
}

/// Where a planned cell comes from.
#[derive(Clone, Copy)]
enum Source {
    /// The frame's leaf of that index.
    Leaf(usize),
    /// The frame's index among the decoder's frames (`frame`).
    Frame,
    /// The element's position in its list (`element`).
    Element(u64),
    /// Nothing (a list without elements has no `element`).
    Missing,
}

/// The rows of one table, and its columns in order of first appearance.
struct Table {
    name: String,
    /// The message type of its frames.
    kind: String,
    /// The row list whose elements its rows are, if any.
    list: Option<&'static str>,
    columns: Vec<String>,
    index: HashMap<String, u32>,
    /// Every row's cells, by column, one row after another.
    cells: Vec<(u32, Cell)>,
    /// Where each row's cells end in `cells`.
    ends: Vec<usize>,
    /// The text the `Str` cells point into.
    texts: String,
}

impl Table {
    fn column(&mut self, name: &str) -> u32 {
        if let Some(&c) = self.index.get(name) {
            return c;
        }
        let c = self.columns.len() as u32;
        self.columns.push(name.to_owned());
        self.index.insert(name.to_owned(), c);
        c
    }

    /// What the field table declares for column `c`: a field of the frame,
    /// or of an element of the table's list.
    fn info(&self, fields: &'static FieldTable, c: usize) -> Option<&'static FieldInfo> {
        let column = &self.columns[c];
        field_info(fields, &self.kind, column).or_else(|| {
            let list = self.list?.replace('*', "0");
            field_info(fields, &self.kind, &format!("{list}.0.{column}"))
        })
    }

    /// Give each column the field table calls a reading or a name (a
    /// sonar's `cm`: 119, or `"out_of_range"`) a column `<name>.name` for
    /// the names, so that the column itself is numeric (the names missing
    /// there, masked in masked tables) in every call alike.
    fn split_names(&mut self, fields: &'static FieldTable) {
        for c in 0..self.columns.len() {
            let reading = self
                .info(fields, c)
                .is_some_and(|info| info.or_number && info.unit.is_some());
            if !reading {
                continue;
            }
            let names = self.columns.len() as u32;
            self.columns.push(format!("{}.name", self.columns[c]));
            for (col, cell) in &mut self.cells {
                if *col == c as u32 && matches!(cell, Cell::Str(..)) {
                    *col = names;
                }
            }
        }
    }

    /// Whether the field table calls column `c` a type byte: one of its
    /// names, or a number where it names none (text in every call alike).
    fn is_type_byte(&self, fields: &'static FieldTable, c: usize) -> bool {
        self.info(fields, c)
            .is_some_and(|info| info.or_number && info.unit.is_none())
    }

    /// The kind of each column: what holds all its values (a column that is
    /// never set, only nulls: text, all empty).
    fn kinds(&self, fields: &'static FieldTable) -> Vec<Kind> {
        let mut kinds: Vec<Option<Kind>> = vec![None; self.columns.len()];
        for &(c, cell) in &self.cells {
            let kind = &mut kinds[c as usize];
            *kind = Some(kind.map_or(Kind::of(cell), |k| k.join(Kind::of(cell))));
        }
        (kinds.into_iter().enumerate())
            .map(|(c, kind)| match self.is_type_byte(fields, c) {
                true => Kind::Str,
                false => kind.unwrap_or(Kind::Str),
            })
            .collect()
    }

    /// The widest text of each text column, in characters (at least 1).
    fn widths(&self, kinds: &[Kind]) -> Vec<usize> {
        let mut widths = vec![1; kinds.len()];
        for &(c, cell) in &self.cells {
            if kinds[c as usize] == Kind::Str {
                let chars = text(cell, &self.texts).chars().count();
                widths[c as usize] = widths[c as usize].max(chars);
            }
        }
        widths
    }
}

impl Flat {
    /// Empty tables for a protocol whose field table is `fields`.
    pub fn new(fields: &'static FieldTable) -> Self {
        Self {
            fields,
            tables: Vec::new(),
            plans: HashMap::default(),
            planned: Vec::new(),
            walk: Walk::default(),
            key: String::new(),
        }
    }

    /// Add `frame` (an `OwnedFrame`, the decoder's `index`-th frame) to its
    /// type's table, or its listed elements to their lists' tables.
    pub fn push<T: Serialize + ?Sized>(&mut self, frame: &T, index: u64) -> PyResult<()> {
        self.walk
            .walk(frame)
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.0))?;
        let kind = match self.walk.kind {
            Some((start, len)) => self.walk.text(start, len),
            None => "message",
        };
        self.key.clear();
        self.key.push_str(kind);
        self.key.push('\0');
        self.key.push_str(&self.walk.names);
        let plan = match self.plans.get(self.key.as_str()) {
            Some(&plan) => plan,
            None => {
                let kind = kind.to_owned();
                let rows = self.plan(&kind);
                self.planned.push(rows);
                self.plans.insert(self.key.clone(), self.planned.len() - 1);
                self.planned.len() - 1
            }
        };
        let walk = &self.walk;
        for row in &self.planned[plan] {
            let table = &mut self.tables[row.table];
            for &(column, source) in &row.cells {
                let cell = match source {
                    Source::Leaf(i) => walk.cells[i],
                    Source::Frame => Some(Cell::U(index, 8)),
                    Source::Element(position) => Some(Cell::U(position, 4)),
                    Source::Missing => None,
                };
                let cell = match cell {
                    Some(Cell::Str(start, len)) => {
                        let at = table.texts.len() as u32;
                        table.texts.push_str(walk.text(start, len));
                        Cell::Str(at, len)
                    }
                    Some(cell) => cell,
                    None => continue,
                };
                table.cells.push((column, cell));
            }
            table.ends.push(table.cells.len());
        }
        Ok(())
    }

    /// The table named `name` (created for frames of type `kind`, or for
    /// the elements of their `list`).
    fn table(&mut self, name: &str, kind: &str, list: Option<&'static str>) -> usize {
        if let Some(i) = self.tables.iter().position(|t| t.name == name) {
            return i;
        }
        self.tables.push(Table {
            name: name.to_owned(),
            kind: kind.to_owned(),
            list,
            columns: Vec::new(),
            index: HashMap::new(),
            cells: Vec::new(),
            ends: Vec::new(),
            texts: String::new(),
        });
        self.tables.len() - 1
    }

    /// The rows a frame of type `kind` shaped as the walk's gives: a row of
    /// its type's table, or, where the field table marks lists as rows, a
    /// row per element of each list (one with no element for an empty
    /// list), each with the frame's own cells and `frame` after any time.
    fn plan(&mut self, kind: &str) -> Vec<PlannedRow> {
        let names = std::mem::take(&mut self.walk.names);
        let paths: Vec<&str> = names.lines().collect();
        let lists: Vec<&'static str> = self.fields.row_lists(kind).collect();
        let mut rows = Vec::new();
        if lists.is_empty() {
            let table = self.table(kind, kind, None);
            let cells = (paths.iter().enumerate())
                .filter(|&(_, path)| *path != "type")
                .map(|(i, path)| (self.tables[table].column(path), Source::Leaf(i)))
                .collect();
            rows.push(PlannedRow { table, cells });
        } else {
            // The frame's own leaves, and each listed element's, grouped by
            // list and element: (list, element, [(field, leaf)]).
            let mut shared: Vec<(&str, Source)> = Vec::new();
            let mut elements: Vec<Element<'_>> = Vec::new();
            for (i, path) in paths.iter().enumerate() {
                match element_of(path, &lists) {
                    Some((list, element, field)) => match elements.last_mut() {
                        Some(last) if last.0 == list && last.1 == element => {
                            last.2.push((field, i))
                        }
                        _ => elements.push((list, element, vec![(field, i)])),
                    },
                    None if *path == "type" => {}
                    None => shared.push((path, Source::Leaf(i))),
                }
            }
            let at = shared.iter().take_while(|(path, _)| *path == "t").count();
            shared.insert(at, ("frame", Source::Frame));
            for (l, &list) in lists.iter().enumerate() {
                let name: Cow<'_, str> = match list.rsplit('.').next() {
                    Some(name) if name != kind => format!("{kind}_{name}").into(),
                    _ => kind.into(),
                };
                let table = self.table(&name, kind, Some(list));
                let t = &mut self.tables[table];
                let head = |t: &mut Table| -> Vec<(u32, Source)> {
                    shared
                        .iter()
                        .map(|&(path, source)| (t.column(path), source))
                        .collect()
                };
                let mut position = 0;
                for (_, _, fields) in elements.iter().filter(|e| e.0 == l) {
                    let mut cells = head(t);
                    cells.push((t.column("element"), Source::Element(position)));
                    cells.extend(
                        fields
                            .iter()
                            .map(|&(field, i)| (t.column(field), Source::Leaf(i))),
                    );
                    rows.push(PlannedRow { table, cells });
                    position += 1;
                }
                if position == 0 {
                    let mut cells = head(t);
                    cells.push((t.column("element"), Source::Missing));
                    rows.push(PlannedRow { table, cells });
                }
            }
        }
        self.walk.names = names;
        rows
    }

    /// Append each table to `arrays` (name → structured array, or masked
    /// array with `masked`).
    pub fn into_arrays(self, arrays: &Bound<'_, PyDict>, masked: bool) -> PyResult<()> {
        let py = arrays.py();
        for mut table in self.tables {
            table.split_names(self.fields);
            let kinds = table.kinds(self.fields);
            let widths = table.widths(&kinds);
            let dtype: Vec<(&str, String)> = (table.columns.iter())
                .zip(kinds.iter().zip(&widths))
                .map(|(name, (kind, &chars))| (name.as_str(), kind.numpy(chars)))
                .collect();
            let mut records = Vec::new();
            let mut mask = Vec::with_capacity(table.ends.len() * kinds.len());
            let mut row: Vec<Option<Cell>> = vec![None; kinds.len()];
            let mut start = 0;
            for &end in &table.ends {
                row.iter_mut().for_each(|cell| *cell = None);
                for &(c, cell) in &table.cells[start..end] {
                    row[c as usize] = Some(cell);
                }
                start = end;
                for ((kind, &cell), &chars) in kinds.iter().zip(&row).zip(&widths) {
                    kind.pack(cell, &table.texts, chars, &mut records);
                    mask.push(u8::from(cell.is_none()));
                }
            }
            let array = view(py, records, &PyList::new(py, &dtype)?)?;
            let value = if masked {
                let flags = dtype.iter().map(|&(name, _)| (name, "?"));
                let mask = view(py, mask, &PyList::new(py, flags)?)?;
                let kwargs = PyDict::new(py);
                kwargs.set_item("mask", mask)?;
                py.import("numpy.ma")?
                    .getattr("MaskedArray")?
                    .call((array,), Some(&kwargs))?
            } else {
                array
            };
            arrays.set_item(&table.name, value)?;
        }
        Ok(())
    }
}

/// `bytes` (whole records of `fields`) as a numpy structured array.
fn view<'py>(
    py: Python<'py>,
    bytes: Vec<u8>,
    fields: &Bound<'py, PyList>,
) -> PyResult<Bound<'py, PyAny>> {
    records_as(py, bytes, PyArrayDescr::new(py, fields)?.into_any())
}

/// Which list of `lists` (patterns, `*` for an index) `path` is an element
/// of: the list's position, the element's path and the field's path in it.
fn element_of<'p>(path: &'p str, lists: &[&str]) -> Option<(usize, &'p str, &'p str)> {
    let is_index = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    lists.iter().enumerate().find_map(|(i, list)| {
        let depth = list.split('.').count();
        // The element ends at the dot after its index, the depth-th dot.
        let (end, _) = path.match_indices('.').nth(depth)?;
        let (element, field) = (&path[..end], &path[end + 1..]);
        let mut segments = element.split('.');
        let index = segments.next_back()?;
        let matches = list
            .split('.')
            .zip(segments)
            .all(|(want, have)| want == have || (want == "*" && is_index(have)));
        (matches && is_index(index)).then_some((i, element, field))
    })
}

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Bool,
    Int { signed: bool, bytes: u8 },
    Float { bytes: u8 },
    Str,
}

impl Kind {
    fn of(cell: Cell) -> Kind {
        match cell {
            Cell::Bool(_) => Kind::Bool,
            Cell::U(_, bytes) => Kind::Int {
                signed: false,
                bytes,
            },
            Cell::I(_, bytes) => Kind::Int {
                signed: true,
                bytes,
            },
            Cell::F32(_) => Kind::Float { bytes: 4 },
            Cell::F64(_) => Kind::Float { bytes: 8 },
            Cell::Str(..) => Kind::Str,
        }
    }

    /// The kind that holds the values of both.
    fn join(self, other: Kind) -> Kind {
        match (self, other) {
            (Kind::Str, _) | (_, Kind::Str) => Kind::Str,
            (Kind::Float { bytes: a }, Kind::Float { bytes: b }) => Kind::Float { bytes: a.max(b) },
            (Kind::Float { .. }, _) | (_, Kind::Float { .. }) => Kind::Float { bytes: 8 },
            (Kind::Bool, Kind::Bool) => Kind::Bool,
            (Kind::Bool, int) | (int, Kind::Bool) => int,
            (
                Kind::Int {
                    signed: sa,
                    bytes: ba,
                },
                Kind::Int {
                    signed: sb,
                    bytes: bb,
                },
            ) => {
                // An unsigned value beside signed ones needs twice its width.
                let room = |signed: bool, bytes: u8| match (signed, sa || sb) {
                    (false, true) => bytes.saturating_mul(2),
                    _ => bytes,
                };
                Kind::Int {
                    signed: sa || sb,
                    bytes: room(sa, ba).max(room(sb, bb)).min(8),
                }
            }
        }
    }

    /// The numpy type (`chars` wide for text).
    fn numpy(self, chars: usize) -> String {
        match self {
            Kind::Bool => "?".to_owned(),
            Kind::Int { signed, bytes } => {
                let bytes = bytes.next_power_of_two().clamp(1, 8);
                let letter = if signed { 'i' } else { 'u' };
                match bytes {
                    1 => format!("{letter}1"),
                    _ => format!("<{letter}{bytes}"),
                }
            }
            Kind::Float { bytes } => format!("<f{}", if bytes <= 4 { 4 } else { 8 }),
            Kind::Str => format!("<U{chars}"),
        }
    }

    /// Append `cell` in this kind's numpy form (a missing cell: the largest
    /// integer, NaN, `""`, `False`).
    fn pack(self, cell: Option<Cell>, texts: &str, chars: usize, out: &mut Vec<u8>) {
        match self {
            Kind::Bool => out.push(u8::from(matches!(cell, Some(Cell::Bool(true))))),
            Kind::Int { signed, bytes } => {
                let bytes = usize::from(bytes.next_power_of_two().clamp(1, 8));
                let value: i128 = match cell {
                    Some(Cell::U(v, _)) => i128::from(v),
                    Some(Cell::I(v, _)) => i128::from(v),
                    Some(Cell::Bool(b)) => i128::from(b),
                    _ if signed => (1i128 << (bytes * 8 - 1)) - 1,
                    _ => (1i128 << (bytes * 8)) - 1,
                };
                out.extend_from_slice(&value.to_le_bytes()[..bytes]);
            }
            Kind::Float { bytes } => {
                let value = match cell {
                    Some(Cell::F32(v)) => f64::from(v),
                    Some(Cell::F64(v)) => v,
                    Some(Cell::U(v, _)) => v as f64,
                    Some(Cell::I(v, _)) => v as f64,
                    Some(Cell::Bool(b)) => f64::from(u8::from(b)),
                    _ => f64::NAN,
                };
                match (bytes <= 4, cell) {
                    // The wire's f32 bit for bit, signalling NaNs included.
                    (true, Some(Cell::F32(v))) => out.extend_from_slice(&v.to_le_bytes()),
                    (true, _) => out.extend_from_slice(&(value as f32).to_le_bytes()),
                    (false, _) => out.extend_from_slice(&value.to_le_bytes()),
                }
            }
            Kind::Str => {
                let text = cell.map(|cell| text(cell, texts)).unwrap_or_default();
                let mut n = 0;
                for c in text.chars().take(chars) {
                    out.extend_from_slice(&u32::from(c).to_le_bytes());
                    n += 1;
                }
                out.resize(out.len() + 4 * (chars - n), 0);
            }
        }
    }
}

/// A cell as text (for a text column that also holds numbers).
fn text(cell: Cell, texts: &str) -> Cow<'_, str> {
    match cell {
        Cell::Bool(b) => b.to_string().into(),
        Cell::U(v, _) => v.to_string().into(),
        Cell::I(v, _) => v.to_string().into(),
        Cell::F32(v) => v.to_string().into(),
        Cell::F64(v) => v.to_string().into(),
        Cell::Str(start, len) => span(texts, start, len).into(),
    }
}
