//! `--format csv -o DIR`: one CSV file per message type in `DIR`, nested
//! fields flattened (`imu.ax`, `uwb.0`), `null` an empty cell. A type whose
//! frames come in more than one shape (telemetry of two layouts) gets a file
//! per shape: `telemetry.csv`, `telemetry-2.csv`. Rejections (with
//! `--errors`) go to `rejected-ERROR.csv`.

use crate::flatten::Row;
use crate::Failure;
use std::collections::HashMap;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// One open table: its header and its file.
struct Table {
    kind: String,
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
}

impl Tables {
    /// Write tables into `dir`, creating it if needed.
    pub fn create(dir: &Path) -> Result<Tables, Failure> {
        fs::create_dir_all(dir).map_err(|error| Failure::Io {
            context: dir.display().to_string(),
            error,
        })?;
        Ok(Tables {
            dir: dir.to_owned(),
            tables: Vec::new(),
            kinds: HashMap::new(),
            last: None,
        })
    }

    /// Append `row` (walked with [`Row::walk`]) to its table.
    pub fn write(&mut self, row: &Row) -> Result<(), Failure> {
        let i = match self.last {
            Some(i) if self.tables[i].names == row.names && row.is_kind(&self.tables[i].kind) => i,
            _ => self.table_for(row)?,
        };
        self.last = Some(i);
        let table = &mut self.tables[i];
        let written = table
            .file
            .write_all(&row.cells)
            .and_then(|()| table.file.write_all(b"\n"));
        written.map_err(|error| failure(&table.path, error))
    }

    fn table_for(&mut self, row: &Row) -> Result<usize, Failure> {
        let kind = row.kind();
        let tables = &self.tables;
        let known = self.kinds.get(&kind).into_iter().flatten();
        if let Some(&i) = known.clone().find(|&&i| tables[i].names == row.names) {
            return Ok(i);
        }
        let n = known.count();
        let file_name = if n == 0 {
            format!("{}.csv", file_safe(&kind))
        } else {
            format!("{}-{}.csv", file_safe(&kind), n + 1)
        };
        let path = self.dir.join(file_name);
        let mut file = File::create(&path)
            .map(|file| BufWriter::with_capacity(64 * 1024, file))
            .map_err(|error| failure(&path, error))?;
        writeln!(file, "{}", row.names).map_err(|error| failure(&path, error))?;
        self.tables.push(Table {
            kind: kind.clone(),
            names: row.names.clone(),
            path,
            file,
        });
        let i = self.tables.len() - 1;
        self.kinds.entry(kind).or_default().push(i);
        Ok(i)
    }

    /// Write out every table.
    pub fn flush(&mut self) -> Result<(), Failure> {
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
