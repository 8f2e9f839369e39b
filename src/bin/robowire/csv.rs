//! `--format csv -o DIR`: one CSV file per message type in `DIR` (per
//! pin, sensor and module with `--topics entity`, the default:
//! `analog_report_pin26.csv`), nested
//! fields flattened (`imu.ax`, `uwb.0`), `null` an empty cell. A type whose
//! frames come in more than one shape (telemetry of two layouts) gets a file
//! per shape: `telemetry.csv`, `telemetry-2.csv`. Rejections (with
//! `--errors`) go to `rejected-ERROR.csv`. `units.csv` beside them gives
//! each table's columns with their unit and description (from the
//! protocol's field table), one row per column: the tables themselves stay
//! one header row and numbers, as PlotJuggler and pandas read them.
//!
//! A message that reports a list of things (a Pixy2 frame's blocks, its
//! vectors, intersections and barcodes: the lists its field table marks
//! [`rows`](robowire::units::FieldInfo::rows)) is written one row per
//! element, in a table per list (`blocks.csv`, `features_vectors.csv`):
//! the frame's own cells, its index in the run (`frame`), the element's
//! position in its list (`element`) and the element's fields. A frame with
//! no element in a list still gets one row there, `element` and the
//! element's cells empty, so every frame's time is in every table of its
//! type and "nothing seen" is a row, not a gap.

use crate::export::Topics;
use crate::flatten::{columns, csv_field as quote, Row};
use crate::json_schema::field_info;
use crate::Failure;
use robowire::units::{FieldInfo, FieldTable};
use std::collections::HashMap;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// One open table: its header and its file.
struct Table {
    kind: String,
    /// The entity cell its rows share (`26` for pin 26), with `--topics entity`.
    entity: Option<String>,
    /// The list whose elements are its rows (`blocks`), if any.
    list: Option<&'static str>,
    names: String,
    path: PathBuf,
    file: BufWriter<File>,
}

/// The CSV tables of one run.
pub struct Tables {
    dir: PathBuf,
    /// Every table, in the order they were opened.
    tables: Vec<Table>,
    /// The tables of each kind (indices into `tables`).
    kinds: HashMap<String, Vec<usize>>,
    /// The table the previous row went to (rows of one shape come in runs).
    last: Option<usize>,
    /// What the protocol's fields mean.
    fields: &'static FieldTable,
    /// `units.csv`, once a table exists.
    units: Option<BufWriter<File>>,
    /// A table per pin, sensor and module (else per message type).
    by_entity: bool,
    /// The lists written a row per element, by message type (filled as
    /// types are seen, when the protocol has any).
    lists: Option<HashMap<String, Vec<&'static str>>>,
}

/// The index of the element's frame among the run's frames.
static FRAME: FieldInfo = FieldInfo::new("The frame's index among the run's frames, from 0.");

/// The element's position in its frame's list.
static ELEMENT: FieldInfo = FieldInfo::new(
    "The element's position in the frame's list, from 0 (empty: the list is empty).",
);

impl Tables {
    /// Write tables into `dir`, creating it if needed; `fields` gives the
    /// columns' units.
    pub fn create(
        dir: &Path,
        fields: &'static FieldTable,
        topics: Topics,
    ) -> Result<Tables, Failure> {
        fs::create_dir_all(dir).map_err(|error| Failure::Io {
            context: dir.display().to_string(),
            error,
        })?;
        Ok(Tables {
            dir: dir.to_owned(),
            tables: Vec::new(),
            kinds: HashMap::new(),
            last: None,
            fields,
            units: None,
            by_entity: topics == Topics::Entity,
            lists: fields
                .entries
                .iter()
                .any(|(_, _, info)| info.rows)
                .then(HashMap::new),
        })
    }

    /// Append `row` (walked with [`Row::walk`]), the run's frame number
    /// `frame`, to its table, or its elements to their lists' tables.
    pub fn write(&mut self, row: &Row, frame: u64) -> Result<(), Failure> {
        if let Some(lists) = &mut self.lists {
            if !row.type_name.is_empty() {
                let fields = self.fields;
                let lists = lists
                    .entry(row.type_name.clone())
                    .or_insert_with_key(|kind| fields.row_lists(kind).collect());
                if !lists.is_empty() {
                    let lists = lists.clone();
                    return self.write_elements(row, &lists, frame);
                }
            }
        }
        self.put(row, None)
    }

    /// Write each element of `row`'s `lists` as a row of its list's table.
    fn write_elements(
        &mut self,
        row: &Row,
        lists: &[&'static str],
        frame: u64,
    ) -> Result<(), Failure> {
        let columns = row.columns();
        let mut shared = Row::default();
        row.type_name.clone_into(&mut shared.type_name);
        // The elements' cells, in wire order.
        let mut elements: Vec<Element> = Vec::new();
        let mut framed = false;
        for (column, cell) in columns.iter().zip(row.cell_texts()) {
            // `frame` after the time, before the frame's own cells.
            if column == "t" && !framed {
                shared.push_cell(column, cell);
                continue;
            }
            if !framed {
                shared.push_number("frame", frame);
                framed = true;
            }
            match element_of(column, lists) {
                Some((list, element, field)) => match elements.last_mut() {
                    Some(last) if last.0 == list && last.1 == element => last.2.push((field, cell)),
                    _ => elements.push((list, element, vec![(field, cell)])),
                },
                None => shared.push_cell(column, cell),
            }
        }
        let mut out = Row::default();
        for (list_index, &list) in lists.iter().enumerate() {
            let mut position = 0u32;
            for (_, _, cells) in elements.iter().filter(|e| e.0 == list_index) {
                out.clone_from(&shared);
                out.push_number("element", position);
                for (field, cell) in cells {
                    out.push_cell(field, cell);
                }
                self.put(&out, Some(list))?;
                position += 1;
            }
            if position == 0 {
                out.clone_from(&shared);
                out.push_cell("element", b"");
                let members = self.declared_members(&shared, list);
                for member in members {
                    out.push_cell(&member, b"");
                }
                self.put(&out, Some(list))?;
            }
        }
        Ok(())
    }

    /// The element columns of `list`'s table for an empty list in a frame
    /// shaped like `shared`: those of the table already open for it, or else
    /// the element's members the field table declares.
    fn declared_members(&self, shared: &Row, list: &str) -> Vec<String> {
        let lead = format!("{},element", shared.names);
        let open = self.tables.iter().find(|t| {
            t.list == Some(list)
                && shared.is_kind(&t.kind)
                && t.names
                    .strip_prefix(&lead)
                    .is_some_and(|rest| rest.starts_with(','))
        });
        if let Some(table) = open {
            let skip = shared.columns().len() + 1;
            return columns(&table.names).split_off(skip);
        }
        let prefix = format!("{list}.*.");
        self.fields
            .entries
            .iter()
            .filter(|(m, _, info)| *m == shared.type_name && !info.optional && !info.rows)
            .filter_map(|(_, path, _)| path.strip_prefix(&prefix))
            .filter(|member| !member.contains('.'))
            // Leaves only: a nested list (an intersection's lines) has no
            // column of its own.
            .filter(|member| {
                let nested = format!("{prefix}{member}.");
                !self
                    .fields
                    .entries
                    .iter()
                    .any(|(_, p, _)| p.starts_with(&nested))
            })
            .map(str::to_owned)
            .collect()
    }

    /// Append `row` to its table: the table of its kind and entity, or of
    /// `list`'s elements, with its columns.
    fn put(&mut self, row: &Row, list: Option<&'static str>) -> Result<(), Failure> {
        let entity = match self.by_entity {
            true => self
                .fields
                .entity_key(&row.type_name)
                .and_then(|key| row.cell(key)),
            false => None,
        };
        let i = match self.last {
            Some(i)
                if self.tables[i].names == row.names
                    && row.is_kind(&self.tables[i].kind)
                    && self.tables[i].entity.as_deref() == entity
                    && self.tables[i].list == list =>
            {
                i
            }
            _ => self.table_for(row, entity.map(str::to_owned), list)?,
        };
        self.last = Some(i);
        let table = &mut self.tables[i];
        let written = table
            .file
            .write_all(&row.cells)
            .and_then(|()| table.file.write_all(b"\n"));
        written.map_err(|error| failure(&table.path, error))
    }

    fn table_for(
        &mut self,
        row: &Row,
        entity: Option<String>,
        list: Option<&'static str>,
    ) -> Result<usize, Failure> {
        let kind = row.kind();
        // The table's name: the type, and the entity's key and value, or
        // the list's name where it is not the type's (`features_vectors`).
        let list_name = list.and_then(|list| list.rsplit('.').next());
        let base = match (&entity, self.fields.entity_key(&row.type_name), list_name) {
            (_, _, Some(name)) if name != kind => format!("{kind}_{name}"),
            (Some(value), Some(key), None) => format!("{kind}_{key}{value}"),
            _ => kind.clone(),
        };
        let tables = &self.tables;
        let known = self.kinds.get(&base).into_iter().flatten();
        if let Some(&i) = known.clone().find(|&&i| tables[i].names == row.names) {
            return Ok(i);
        }
        let n = known.count();
        let file_name = if n == 0 {
            format!("{}.csv", file_safe(&base))
        } else {
            format!("{}-{}.csv", file_safe(&base), n + 1)
        };
        let path = self.dir.join(file_name);
        let mut file = File::create(&path)
            .map(|file| BufWriter::with_capacity(64 * 1024, file))
            .map_err(|error| failure(&path, error))?;
        writeln!(file, "{}", row.names).map_err(|error| failure(&path, error))?;
        self.describe(&path, &kind, row, list)?;
        self.tables.push(Table {
            kind: kind.clone(),
            entity,
            list,
            names: row.names.clone(),
            path,
            file,
        });
        let i = self.tables.len() - 1;
        self.kinds.entry(base).or_default().push(i);
        Ok(i)
    }

    /// Add the columns of the new table at `path` (rows of `kind`, shaped
    /// like `row`, the elements of `list` if given) to `units.csv`.
    fn describe(
        &mut self,
        path: &Path,
        kind: &str,
        row: &Row,
        list: Option<&str>,
    ) -> Result<(), Failure> {
        let units_path = self.dir.join("units.csv");
        let units = match &mut self.units {
            Some(units) => units,
            None => {
                let mut file = File::create(&units_path)
                    .map(BufWriter::new)
                    .map_err(|error| failure(&units_path, error))?;
                writeln!(file, "table,column,unit,description")
                    .map_err(|error| failure(&units_path, error))?;
                self.units.insert(file)
            }
        };
        let table = path
            .file_stem()
            .map_or(String::new(), |s| s.to_string_lossy().into_owned());
        // An element's fields, as the field table names them (`blocks.0.x`).
        let element = list.map(|list| list.replace('*', "0") + ".0.");
        for column in row.columns() {
            let info = match (column.as_str(), &element) {
                ("frame", Some(_)) => Some(&FRAME),
                ("element", Some(_)) => Some(&ELEMENT),
                (_, Some(element)) => field_info(self.fields, kind, &column)
                    .or_else(|| field_info(self.fields, kind, &format!("{element}{column}"))),
                (_, None) => field_info(self.fields, kind, &column),
            };
            let unit = info.and_then(|i| i.unit).map_or("", |u| u.symbol());
            let description = info.map_or("", |i| i.doc);
            writeln!(
                units,
                "{},{},{},{}",
                quote(&table),
                quote(&column),
                quote(unit),
                quote(description)
            )
            .map_err(|error| failure(&units_path, error))?;
        }
        Ok(())
    }

    /// Write out every table.
    pub fn flush(&mut self) -> Result<(), Failure> {
        if let Some(units) = &mut self.units {
            let path = self.dir.join("units.csv");
            units.flush().map_err(|error| failure(&path, error))?;
        }
        for table in &mut self.tables {
            table
                .file
                .flush()
                .map_err(|error| failure(&table.path, error))?;
        }
        Ok(())
    }
}

/// One element of a frame's list: the list (an index into the frame's
/// lists), the element's path (`blocks.2`) and its `(field, cell)`s.
type Element<'r> = (usize, &'r str, Vec<(&'r str, &'r [u8])>);

/// The list of `lists` (by index) that `column` is a field of an element
/// of, that element (`blocks.2`) and the field's path in it (`x`).
fn element_of<'c>(column: &'c str, lists: &[&str]) -> Option<(usize, &'c str, &'c str)> {
    lists.iter().enumerate().find_map(|(i, list)| {
        let depth = list.split('.').count();
        // The element ends at the dot after its index: the depth-th dot.
        let (end, _) = column.match_indices('.').nth(depth)?;
        let (element, field) = (&column[..end], &column[end + 1..]);
        let mut segments = element.split('.');
        let index = segments.next_back()?;
        let is_index = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
        let matches = list
            .split('.')
            .zip(segments)
            .all(|(want, have)| want == have || (want == "*" && is_index(have)));
        (matches && is_index(index)).then_some((i, element, field))
    })
}

/// `kind` with anything but letters, digits, `-` and `_` replaced by `_`.
fn file_safe(kind: &str) -> String {
    kind.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn failure(path: &Path, error: io::Error) -> Failure {
    Failure::Io {
        context: path.display().to_string(),
        error,
    }
}
