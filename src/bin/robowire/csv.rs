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

use crate::export::Topics;
use crate::flatten::{csv_field as quote, Row};
use crate::json_schema::field_info;
use crate::Failure;
use robowire::units::FieldTable;
use std::collections::HashMap;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// One open table: its header and its file.
struct Table {
    kind: String,
    /// The entity cell its rows share (`26` for pin 26), with `--topics entity`.
    entity: Option<String>,
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
}

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
        })
    }

    /// Append `row` (walked with [`Row::walk`]) to its table.
    pub fn write(&mut self, row: &Row) -> Result<(), Failure> {
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
                    && self.tables[i].entity.as_deref() == entity =>
            {
                i
            }
            _ => self.table_for(row, entity.map(str::to_owned))?,
        };
        self.last = Some(i);
        let table = &mut self.tables[i];
        let written = table
            .file
            .write_all(&row.cells)
            .and_then(|()| table.file.write_all(b"\n"));
        written.map_err(|error| failure(&table.path, error))
    }

    fn table_for(&mut self, row: &Row, entity: Option<String>) -> Result<usize, Failure> {
        let kind = row.kind();
        // The table's name: the type, and the entity's key and value.
        let base = match (&entity, self.fields.entity_key(&row.type_name)) {
            (Some(value), Some(key)) => format!("{kind}_{key}{value}"),
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
        self.describe(&path, &kind, row)?;
        self.tables.push(Table {
            kind: kind.clone(),
            entity,
            names: row.names.clone(),
            path,
            file,
        });
        let i = self.tables.len() - 1;
        self.kinds.entry(base).or_default().push(i);
        Ok(i)
    }

    /// Add the columns of the new table at `path` (rows of `kind`, shaped
    /// like `row`) to `units.csv`.
    fn describe(&mut self, path: &Path, kind: &str, row: &Row) -> Result<(), Failure> {
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
        for column in row.columns() {
            let info = field_info(self.fields, kind, &column);
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
