//! `robowire plot PROTOCOL INPUT --fields a,b.c -o plot.png`: the chosen
//! fields over time (receive time with `--port` or `--timestamps`, the frame
//! index otherwise), as PNG or SVG through `plotters`: a title (protocol,
//! source, frames, span), one panel per unit with the unit on its y axis
//! (from the protocol's field table), whole-number ticks for integer
//! fields, and a legend. A field is selected as a CSV column (`imu.az`),
//! within one message type (`analog_report.value`) and among the frames
//! whose other fields match (`analog_report[pin=26].value`). With `--errors`
//! every rejected candidate is a red tick on the time axis (ticks that fall
//! on one pixel column are one, labelled with their count), so a flaky link
//! shows where it failed; `--errors` alone draws the rejections so far.
//! Fields are read through the same walk of the library's serde form as the
//! CSV tables.

use crate::flatten::Row;
use crate::json_schema::field_info;
use crate::Failure;
use clap::Args;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use robowire::units::{FieldTable, Unit};
use std::path::{Path, PathBuf};

/// The options of `robowire plot` besides those of a decode.
#[derive(Debug, Clone, Args)]
pub struct PlotArgs {
    /// The series to draw, comma-separated: a field as the CSV columns name
    /// it (`m1_pos`, `imu.az`, `uwb.0`), of one message type (`analog_report.value`),
    /// of the frames whose other fields match (`analog_report[pin=26].value`).
    #[arg(long, value_name = "F[,F...]", value_delimiter = ',', global = true)]
    pub fields: Vec<String>,
    /// One panel per unit (the default: positions in ADC counts apart from
    /// accelerations in m/s²), or one panel for every series.
    #[arg(long, value_enum, default_value_t = Panels::Unit, global = true)]
    pub panels: Panels,
    /// The picture's size in pixels.
    #[arg(long, value_name = "WxH", default_value = "1200x600", value_parser = size, global = true)]
    pub size: (u32, u32),
    /// A TrueType font for the labels [default: DejaVu Sans, Liberation
    /// Sans or Arial, where the system has one].
    #[arg(long, value_name = "FILE.ttf", global = true)]
    pub font: Option<PathBuf>,
}

/// How series share panels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Panels {
    /// One panel per unit, each with its own y axis.
    Unit,
    /// Every series in one panel.
    One,
}

fn size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or("expected WIDTHxHEIGHT, e.g. 1200x600")?;
    let parse = |n: &str| {
        n.parse::<u32>()
            .ok()
            .filter(|n| (64..=10_000).contains(n))
            .ok_or(format!("{n}: expected 64 to 10000 pixels"))
    };
    Ok((parse(w)?, parse(h)?))
}

/// Fonts the labels are drawn with when `--font` is not given.
const FONTS: [&str; 7] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "/Library/Fonts/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

/// The series' colors: distinct, none of them the red of the rejection ticks.
const SERIES_COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
];

/// One `--fields` selector: `[TYPE[KEY=VALUE]...].FIELD` or `FIELD`.
#[derive(Debug, Clone, PartialEq)]
struct Selector {
    /// As written: the series' name.
    text: String,
    /// The message type and the field within it, when the text starts with
    /// a type name (`analog_report.value`).
    typed: Option<(String, String)>,
    /// Other fields the frame must have, with these cells.
    filters: Vec<(String, String)>,
}

impl Selector {
    /// Read `text`; `types` are the protocol's message types.
    fn parse(text: &str, types: &[&str]) -> Result<Selector, String> {
        let head = text.split(['.', '[']).next().unwrap_or("");
        let is_type = types.contains(&head);
        let Some(rest) = text.strip_prefix(head).filter(|r| r.starts_with('[')) else {
            let typed = match text.split_once('.') {
                Some((kind, field)) if is_type && !field.is_empty() => {
                    Some((kind.to_owned(), field.to_owned()))
                }
                _ => None,
            };
            return Ok(Selector {
                text: text.to_owned(),
                typed,
                filters: Vec::new(),
            });
        };
        if !is_type {
            return Err(format!(
                "{text}: a filter follows a message type ({head:?} is none: {})",
                types.join(", ")
            ));
        }
        let mut filters = Vec::new();
        let mut rest = rest;
        while let Some(inner) = rest.strip_prefix('[') {
            let (filter, after) = inner
                .split_once(']')
                .ok_or_else(|| format!("{text}: a `[` without its `]`"))?;
            let (key, value) = filter
                .split_once('=')
                .filter(|(k, v)| !k.is_empty() && !v.is_empty())
                .ok_or_else(|| format!("{text}: a filter is [FIELD=VALUE], e.g. [pin=26]"))?;
            filters.push((key.to_owned(), value.to_owned()));
            rest = after;
        }
        let field = rest
            .strip_prefix('.')
            .filter(|f| !f.is_empty())
            .ok_or_else(|| format!("{text}: the field comes after the filters: {head}[…].FIELD"))?;
        Ok(Selector {
            text: text.to_owned(),
            typed: Some((head.to_owned(), field.to_owned())),
            filters,
        })
    }

    /// The column of `row` this selector reads, if the row is one of its.
    fn column<'s>(&'s self, row: &Row) -> Option<&'s str> {
        let typed = self
            .typed
            .as_ref()
            .filter(|(kind, _)| *kind == row.type_name);
        let matches = |(key, value): &(String, String)| {
            row.cell(key).map(|c| c.trim_matches('"')) == Some(value.as_str())
        };
        match typed {
            Some((_, field)) if self.filters.iter().all(matches) && row.cell(field).is_some() => {
                Some(field)
            }
            _ if self.filters.is_empty() && row.cell(&self.text).is_some() => Some(&self.text),
            _ => None,
        }
    }
}

/// One series: its points and what the field table says of them.
struct Series {
    selector: Selector,
    points: Vec<(f64, f64)>,
    /// The unit of the field, known from its first point.
    unit: Option<Unit>,
    /// Every value so far is a whole number.
    integer: bool,
}

/// The points of one run, collected as frames are decoded.
pub struct Plot {
    args: PlotArgs,
    output: PathBuf,
    svg: bool,
    /// The x axis is the receive time (else the frame index).
    timed: bool,
    /// What the protocol's fields mean.
    fields: &'static FieldTable,
    /// Where the frames came from, for the title.
    source: String,
    series: Vec<Series>,
    /// Where candidates were rejected.
    rejected: Vec<f64>,
    /// Frames seen.
    frames: u64,
    /// The columns of the first frame, to name them if a field is missing.
    columns: Option<String>,
}

impl Plot {
    /// A plot into `output` (`.png` or `.svg`) of frames from `source`;
    /// `timed` when frames carry times, `errors` when rejections are drawn.
    pub fn new(
        args: PlotArgs,
        output: Option<&Path>,
        timed: bool,
        errors: bool,
        fields: &'static FieldTable,
        source: String,
    ) -> Result<Plot, Failure> {
        let output = output.ok_or_else(|| {
            Failure::Usage("robowire plot needs -o FILE.png or -o FILE.svg".to_owned())
        })?;
        let extension = output
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let svg = match extension.as_deref() {
            Some("png") => false,
            Some("svg") => true,
            _ => {
                return Err(Failure::Usage(format!(
                    "{}: the plot is written as PNG or SVG: name it FILE.png or FILE.svg",
                    output.display()
                )))
            }
        };
        if args.fields.is_empty() && !errors {
            return Err(Failure::Usage(
                "robowire plot needs --fields (e.g. --fields m1_pos,m2_pos,imu.az), \
                 or --errors alone to plot the rejections"
                    .to_owned(),
            ));
        }
        let types = fields.get("*", "type").map_or(&[][..], |info| info.names);
        let series = args
            .fields
            .iter()
            .map(|text| {
                Ok(Series {
                    selector: Selector::parse(text, types).map_err(Failure::Usage)?,
                    points: Vec::new(),
                    unit: None,
                    integer: true,
                })
            })
            .collect::<Result<_, Failure>>()?;
        load_font(args.font.as_deref())?;
        Ok(Plot {
            series,
            args,
            output: output.to_owned(),
            svg,
            timed,
            fields,
            source,
            rejected: Vec::new(),
            frames: 0,
            columns: None,
        })
    }

    /// A frame walked into `row`, at `x`.
    pub fn frame(&mut self, row: &Row, x: f64) {
        if self.columns.is_none() {
            self.columns = Some(row.names.clone());
        }
        self.frames += 1;
        for series in &mut self.series {
            let Some(column) = series.selector.column(row) else {
                continue;
            };
            let Some(cell) = row.cell(column) else {
                continue;
            };
            let Some(y) = cell.parse::<f64>().ok().filter(|y| y.is_finite()) else {
                continue;
            };
            if series.points.is_empty() {
                series.unit = field_info(self.fields, &row.type_name, column).and_then(|i| i.unit);
            }
            series.integer &= !cell.contains(['.', 'e', 'E']);
            series.points.push((x, y));
        }
    }

    /// A rejected candidate at `x`.
    pub fn rejected(&mut self, x: f64) {
        self.rejected.push(x);
    }

    /// Draw the picture.
    pub fn finish(&mut self) -> Result<(), Failure> {
        if let Some(series) = self.series.iter().find(|s| s.points.is_empty()) {
            let columns = self.columns.as_deref().unwrap_or("none: no frame decoded");
            return Err(Failure::Invalid(format!(
                "no frame has a number in field {:?}; the first frame's fields are {columns}",
                series.selector.text
            )));
        }
        let drawn = if self.svg {
            let root = SVGBackend::new(&self.output, self.args.size).into_drawing_area();
            self.draw(root)
        } else {
            let root = BitMapBackend::new(&self.output, self.args.size).into_drawing_area();
            self.draw(root)
        };
        drawn.map_err(|message| Failure::Io {
            context: self.output.display().to_string(),
            error: std::io::Error::other(message),
        })
    }

    /// The panels: indices into `series`, grouped by unit (or all in one).
    fn panels(&self) -> Vec<Vec<usize>> {
        let mut panels: Vec<(Option<Unit>, Vec<usize>)> = Vec::new();
        for (i, series) in self.series.iter().enumerate() {
            let key = match self.args.panels {
                Panels::Unit => series.unit,
                Panels::One => None,
            };
            match panels.iter_mut().find(|(unit, _)| *unit == key) {
                Some((_, members)) => members.push(i),
                None => panels.push((key, vec![i])),
            }
        }
        panels.into_iter().map(|(_, members)| members).collect()
    }

    /// The title: protocol, source, frames and span.
    fn title(&self, (x0, x1): (f64, f64)) -> String {
        let span = if self.timed {
            format!("{x0:.2}–{x1:.2} s")
        } else {
            format!("frames {x0:.0}–{x1:.0}")
        };
        let rejected = if self.rejected.is_empty() {
            String::new()
        } else {
            format!(", {} rejected", self.rejected.len())
        };
        format!(
            "{}: {}, {} frames{rejected}, {span}",
            self.fields.protocol, self.source, self.frames
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let error = |e: &dyn std::fmt::Display| e.to_string();
        let (mut x0, mut x1) = (f64::MAX, f64::MIN);
        for &(x, _) in self.series.iter().flat_map(|s| &s.points) {
            (x0, x1) = (x0.min(x), x1.max(x));
        }
        for &x in &self.rejected {
            (x0, x1) = (x0.min(x), x1.max(x));
        }
        if x0 > x1 {
            (x0, x1) = (0.0, 1.0);
        }
        let title = self.title((x0, x1));
        if x1 <= x0 {
            x1 = x0 + 1.0;
        }
        root.fill(&WHITE).map_err(|e| error(&e))?;
        let root = root
            .titled(&title, ("sans-serif", 20))
            .map_err(|e| error(&e))?;
        let panels = self.panels();
        let x_desc = if self.timed {
            "receive time (s)"
        } else {
            "frame index"
        };
        // With --errors alone, one panel: the rejections so far.
        let count = panels.len().max(1);
        let areas = root.split_evenly((count, 1));
        if panels.is_empty() {
            let steps: Vec<(f64, f64)> = self
                .rejected
                .iter()
                .enumerate()
                .flat_map(|(i, &x)| [(x, i as f64), (x, i as f64 + 1.0)])
                .collect();
            let panel = Panel {
                label: "rejections so far".to_owned(),
                series: vec![("rejections so far".to_owned(), steps, RED)],
                integer: true,
                x_desc: Some(x_desc),
                timed: self.timed,
            };
            return panel
                .draw(&areas[0], (x0, x1), &self.rejected)
                .and_then(|()| root.present().map_err(|e| error(&e)));
        }
        let mut color = 0;
        for (i, (members, area)) in panels.iter().zip(&areas).enumerate() {
            let units: Vec<&str> = members
                .iter()
                .map(|&m| self.series[m].unit.map_or("value", Unit::symbol))
                .fold(Vec::new(), |mut all, u| {
                    if !all.contains(&u) {
                        all.push(u);
                    }
                    all
                });
            let series = members
                .iter()
                .map(|&m| {
                    let s = &self.series[m];
                    let name = match s.unit {
                        Some(unit) => format!("{} ({unit})", s.selector.text),
                        None => s.selector.text.clone(),
                    };
                    color += 1;
                    (
                        name,
                        s.points.clone(),
                        SERIES_COLORS[(color - 1) % SERIES_COLORS.len()],
                    )
                })
                .collect();
            let panel = Panel {
                label: units.join(", "),
                series,
                integer: members.iter().all(|&m| self.series[m].integer),
                x_desc: (i + 1 == count).then_some(x_desc),
                timed: self.timed,
            };
            panel.draw(area, (x0, x1), &self.rejected)?;
        }
        root.present().map_err(|e| error(&e))
    }
}

/// A series as a panel draws it: its legend entry, points and color.
type Line = (String, Vec<(f64, f64)>, RGBColor);

/// One panel of the picture: its series over the shared x range.
struct Panel {
    /// The y axis's label: the unit(s).
    label: String,
    series: Vec<Line>,
    /// Every value is whole: ticks are whole numbers.
    integer: bool,
    /// The x axis's label, on the bottom panel only.
    x_desc: Option<&'static str>,
    /// The x axis is time (else a frame index, ticked in whole numbers).
    timed: bool,
}

impl Panel {
    fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (x0, x1): (f64, f64),
        rejected: &[f64],
    ) -> Result<(), String> {
        let error = |e: &dyn std::fmt::Display| e.to_string();
        let (mut y0, mut y1) = (f64::MAX, f64::MIN);
        for &(_, y) in self.series.iter().flat_map(|(_, points, _)| points) {
            (y0, y1) = (y0.min(y), y1.max(y));
        }
        if y0 > y1 {
            (y0, y1) = (0.0, 1.0);
        }
        let pad = if y1 > y0 { (y1 - y0) * 0.05 } else { 1.0 };
        let (y0, y1) = (y0 - pad, y1 + pad);
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(if self.x_desc.is_some() { 44 } else { 24 })
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| error(&e))?;
        // Whole-number ticks for integer fields: at most one per unit.
        let y_labels = if self.integer {
            ((y1 - y0).floor() as usize + 1).clamp(2, 10)
        } else {
            10
        };
        let whole = |y: &f64| format!("{y:.0}");
        // As many decimals as a tenth of the range needs.
        let decimals = (-((y1 - y0) / 10.0).log10().floor()).clamp(0.0, 9.0) as usize;
        let plain = move |y: &f64| format!("{y:.decimals$}");
        let index = |x: &f64| format!("{x:.0}");
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(&self.label)
            .y_labels(y_labels)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16));
        if self.integer {
            mesh.y_label_formatter(&whole);
        } else {
            mesh.y_label_formatter(&plain);
        }
        if let Some(x_desc) = self.x_desc {
            mesh.x_desc(x_desc);
        }
        if !self.timed {
            mesh.x_label_formatter(&index);
        }
        mesh.draw().map_err(|e| error(&e))?;
        for (name, points, color) in &self.series {
            let color = color.to_rgba();
            // Whole-number readings hold until the next one: steps.
            let points: Vec<(f64, f64)> = if self.integer {
                let held = points.windows(2).map(|w| (w[1].0, w[0].1));
                let mut steps = Vec::with_capacity(points.len() * 2);
                steps.extend(points.first().copied());
                for (hold, &next) in held.zip(&points[1..]) {
                    steps.push(hold);
                    steps.push(next);
                }
                steps
            } else {
                points.clone()
            };
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(|e| error(&e))?
                .label(name.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        if !rejected.is_empty() {
            // Rejections within one pixel column are one tick, labelled
            // with their count when there are several.
            let width = f64::from(area.dim_in_pixel().0.max(1));
            let bin = (x1 - x0) / width;
            let mut ticks: Vec<(f64, usize)> = Vec::new();
            for &x in rejected {
                match ticks.last_mut() {
                    Some((at, n)) if (x - *at).abs() <= bin => *n += 1,
                    _ => ticks.push((x, 1)),
                }
            }
            let tick = (y1 - y0) * 0.04;
            let marks = ticks.iter().map(|&(x, _)| {
                PathElement::new(vec![(x, y0), (x, y0 + tick)], RED.stroke_width(2))
            });
            chart
                .draw_series(marks)
                .map_err(|e| error(&e))?
                .label(format!("rejected ({})", rejected.len()))
                .legend(|(x, y)| PathElement::new(vec![(x + 10, y - 6), (x + 10, y + 6)], RED));
            let counts = ticks.iter().filter(|(_, n)| *n > 1).map(|&(x, n)| {
                Text::new(
                    format!("{n}"),
                    (x, y0 + tick * 1.3),
                    ("sans-serif", 12).into_font().color(&RED),
                )
            });
            chart.draw_series(counts).map_err(|e| error(&e))?;
        }
        chart
            .configure_series_labels()
            .label_font(("sans-serif", 14))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| error(&e))
    }
}

/// Register the labels' font as `sans-serif`: `--font`, or the first of
/// [`FONTS`] the system has.
fn load_font(font: Option<&Path>) -> Result<(), Failure> {
    let bytes = match font {
        Some(path) => std::fs::read(path).map_err(|error| Failure::Io {
            context: path.display().to_string(),
            error,
        })?,
        None => FONTS
            .iter()
            .find_map(|path| std::fs::read(path).ok())
            .ok_or_else(|| {
                Failure::Usage(
                    "no font for the labels found (DejaVu Sans, Liberation Sans, Arial): \
                     name a TrueType font with --font FILE.ttf"
                        .to_owned(),
                )
            })?,
    };
    // Registered once per run, for the whole run.
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    register_font("sans-serif", FontStyle::Normal, bytes).map_err(|_| {
        Failure::Invalid(format!(
            "{}: not a TrueType font",
            font.map_or("the system font".into(), |p| p.display().to_string())
        ))
    })
}
