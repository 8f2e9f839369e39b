//! `robowire plot PROTOCOL INPUT --fields a,b.c -o plot.png`: the chosen
//! fields over time (receive time with `--port` or `--timestamps`, the frame
//! index otherwise), with axes and a legend, as PNG or SVG through
//! `plotters`. With `--errors` every rejected candidate is a red tick on the
//! time axis, so a flaky link shows where it failed. Fields are read
//! through the same walk of the library's serde form as the CSV tables.

use crate::flatten::Row;
use crate::Failure;
use clap::Args;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use std::path::{Path, PathBuf};

/// The options of `robowire plot` besides those of a decode.
#[derive(Debug, Clone, Args)]
pub struct PlotArgs {
    /// The fields to draw, comma-separated, as the CSV columns name them
    /// (`m1_pos,m2_pos,imu.az`, `uwb.0`).
    #[arg(long, value_name = "F[,F...]", value_delimiter = ',', global = true)]
    pub fields: Vec<String>,
    /// The picture's size in pixels.
    #[arg(long, value_name = "WxH", default_value = "1200x600", value_parser = size, global = true)]
    pub size: (u32, u32),
    /// A TrueType font for the labels [default: DejaVu Sans, Liberation
    /// Sans or Arial, where the system has one].
    #[arg(long, value_name = "FILE.ttf", global = true)]
    pub font: Option<PathBuf>,
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

/// The points of one run, collected as frames are decoded.
pub struct Plot {
    args: PlotArgs,
    output: PathBuf,
    svg: bool,
    /// The x axis is the receive time (else the frame index).
    timed: bool,
    /// One series per field: (x, y).
    series: Vec<Vec<(f64, f64)>>,
    /// Where candidates were rejected.
    rejected: Vec<f64>,
    /// The columns of the first frame, to name them if a field is missing.
    columns: Option<String>,
}

impl Plot {
    /// A plot into `output` (`.png` or `.svg`); `timed` when frames carry times.
    pub fn new(args: PlotArgs, output: Option<&Path>, timed: bool) -> Result<Plot, Failure> {
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
        if args.fields.is_empty() {
            return Err(Failure::Usage(
                "robowire plot needs --fields, e.g. --fields m1_pos,m2_pos,imu.az".to_owned(),
            ));
        }
        load_font(args.font.as_deref())?;
        Ok(Plot {
            series: vec![Vec::new(); args.fields.len()],
            args,
            output: output.to_owned(),
            svg,
            timed,
            rejected: Vec::new(),
            columns: None,
        })
    }

    /// A frame walked into `row`, at `x`.
    pub fn frame(&mut self, row: &Row, x: f64) {
        if self.columns.is_none() {
            self.columns = Some(row.names.clone());
        }
        for (field, series) in self.args.fields.iter().zip(&mut self.series) {
            if let Some(y) = row.cell(field).and_then(|cell| cell.parse::<f64>().ok()) {
                if y.is_finite() {
                    series.push((x, y));
                }
            }
        }
    }

    /// A rejected candidate at `x`.
    pub fn rejected(&mut self, x: f64) {
        self.rejected.push(x);
    }

    /// Draw the picture.
    pub fn finish(&mut self) -> Result<(), Failure> {
        if let Some(i) = self.series.iter().position(Vec::is_empty) {
            let columns = self.columns.as_deref().unwrap_or("none: no frame decoded");
            return Err(Failure::Invalid(format!(
                "no frame has a number in field {:?}; the first frame's fields are {columns}",
                self.args.fields[i]
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

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let points = self.series.iter().flatten();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(x, y) in points {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        for &x in &self.rejected {
            (x0, x1) = (x0.min(x), x1.max(x));
        }
        if x1 <= x0 {
            x1 = x0 + 1.0;
        }
        let pad = if y1 > y0 { (y1 - y0) * 0.05 } else { 1.0 };
        let (y0, y1) = (y0 - pad, y1 + pad);
        let error = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|e| error(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(72)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| error(&e))?;
        let x_desc = if self.timed {
            "receive time (s)"
        } else {
            "frame index"
        };
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .draw()
            .map_err(|e| error(&e))?;
        for (i, (field, series)) in self.args.fields.iter().zip(&self.series).enumerate() {
            let color = SERIES_COLORS[i % SERIES_COLORS.len()].to_rgba();
            chart
                .draw_series(LineSeries::new(
                    series.iter().copied(),
                    color.stroke_width(2),
                ))
                .map_err(|e| error(&e))?
                .label(field.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        if !self.rejected.is_empty() {
            let tick = (y1 - y0) * 0.04;
            let ticks = self
                .rejected
                .iter()
                .map(|&x| PathElement::new(vec![(x, y0), (x, y0 + tick)], RED.stroke_width(2)));
            chart
                .draw_series(ticks)
                .map_err(|e| error(&e))?
                .label("rejected")
                .legend(|(x, y)| PathElement::new(vec![(x + 10, y - 6), (x + 10, y + 6)], RED));
        }
        chart
            .configure_series_labels()
            .label_font(("sans-serif", 14))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| error(&e))?;
        root.present().map_err(|e| error(&e))
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
