//! `robowire plot`: a PNG of the requested size with the series, the axes
//! and the rejection ticks drawn; SVG; the errors a user can make.

mod cli_common;

use cli_common::{data_arg, run, scratch};

/// The PNG's size and its pixels as RGB(A) rows.
fn read_png(path: &std::path::Path) -> (u32, u32, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).unwrap();
    pixels.truncate(info.buffer_size());
    (info.width, info.height, info.color_type.samples(), pixels)
}

fn count(pixels: &[u8], samples: usize, want: impl Fn(&[u8]) -> bool) -> usize {
    pixels.chunks(samples).filter(|p| want(p)).count()
}

#[test]
fn a_png_of_the_requested_size_with_the_series_and_the_rejections() {
    let dir = scratch("plot-png");
    let png = dir.join("plot.png");
    let input = data_arg("ble_telemetry.bin");
    let out = run(
        &[
            "plot",
            "omnitiles",
            &input,
            "--fields",
            "m1_pos,m2_pos",
            "--errors",
            "--size",
            "800x400",
            "-o",
            png.to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.is_empty());
    assert!(
        out.stderr.starts_with("robowire: 298 frames"),
        "{}",
        out.stderr
    );
    let (width, height, samples, pixels) = read_png(&png);
    assert_eq!((width, height), (800, 400));
    let white = count(&pixels, samples, |p| p[..3] == [255, 255, 255]);
    let total = (width * height) as usize;
    assert!(white > total / 2, "mostly background: {white} of {total}");
    // The two series in their colors, the rejection ticks in red, text and axes in dark grey.
    let near = |c: [u8; 3]| move |p: &[u8]| p[..3].iter().zip(c).all(|(a, b)| a.abs_diff(b) < 40);
    let blue = count(&pixels, samples, near([31, 119, 180]));
    let green = count(&pixels, samples, near([44, 160, 44]));
    let red = count(&pixels, samples, near([255, 0, 0]));
    let dark = count(&pixels, samples, |p| p[..3].iter().all(|&c| c < 80));
    assert!(
        blue > 1000 && green > 1000,
        "series drawn: {blue} blue, {green} green pixels"
    );
    assert!(red > 50, "rejections marked: {red} red pixels");
    assert!(dark > 1000, "axes and labels drawn: {dark} dark pixels");
    // Without --errors, no red ticks.
    let plain = dir.join("plain.png");
    let out = run(
        &[
            "plot",
            "omnitiles",
            &input,
            "--fields",
            "m1_pos,m2_pos",
            "--size",
            "800x400",
            "-o",
            plain.to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    let (_, _, samples, pixels) = read_png(&plain);
    assert!(count(&pixels, samples, near([255, 0, 0])) < red / 4);
}

#[test]
fn an_svg_names_the_fields_and_the_time_axis() {
    let dir = scratch("plot-svg");
    let svg = dir.join("plot.svg");
    let out = run(
        &[
            "plot",
            "telemetrix",
            &data_arg("telemetrix_reports.bin"),
            "--timestamps",
            "--fields",
            "value",
            "-o",
            svg.to_str().unwrap(),
        ],
        b"",
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"), "{}", &text[..80]);
    // Text elements hold their text on a line of its own.
    assert!(
        text.lines().any(|l| l.trim() == "value"),
        "the legend names the field"
    );
    assert!(
        text.lines().any(|l| l.trim() == "receive time (s)"),
        "the x axis is time"
    );
    assert!(text.contains("<polyline"));
}

/// The text lines of an SVG plot (plotters writes each text on a line of its own).
fn svg_texts(args: &[&str], name: &str) -> Vec<String> {
    let dir = scratch(name);
    let svg = dir.join("plot.svg");
    let out = run(&[args, &["-o", svg.to_str().unwrap()]].concat(), b"");
    assert_eq!(out.code, 0, "{args:?}: {}", out.stderr);
    let text = std::fs::read_to_string(&svg).unwrap();
    text.lines().map(|l| l.trim().to_owned()).collect()
}

#[test]
fn a_plot_has_a_title_a_panel_per_unit_and_units_on_its_axes() {
    let input = data_arg("ble_telemetry.bin");
    let lines = svg_texts(
        &[
            "plot",
            "omnitiles",
            &input,
            "--timestamps",
            "--fields",
            "m1_pos,m2_pos,imu.az",
            "--errors",
        ],
        "plot-units",
    );
    let has = |t: &str| lines.iter().any(|l| l == t);
    assert!(
        has("omnitiles: ble_telemetry.bin, 298 frames, 9 rejected, 0.00–1.38 s"),
        "the title says protocol, source, frames and span"
    );
    assert!(has("ADC counts") && has("m/s²"), "one y axis per unit");
    assert!(has("m1_pos (ADC counts)") && has("imu.az (m/s²)"));
    assert!(has("rejected (9)"), "the legend counts the rejections");
    assert!(has("2"), "coincident rejections are counted on their tick");
    // One panel: both units on its axis.
    let one = svg_texts(
        &[
            "plot",
            "omnitiles",
            &input,
            "--fields",
            "m1_pos,imu.az",
            "--panels",
            "one",
        ],
        "plot-one-panel",
    );
    assert!(one.iter().any(|l| l == "ADC counts, m/s²"), "{one:?}");
}

#[test]
fn selectors_pick_a_message_type_and_an_entity_and_integers_tick_whole() {
    let input = data_arg("telemetrix_reports.bin");
    let lines = svg_texts(
        &[
            "plot",
            "telemetrix",
            &input,
            "--fields",
            "analog_report[pin=26].value,digital_report[pin=10].value",
        ],
        "plot-selectors",
    );
    let has = |t: &str| lines.iter().any(|l| l == t);
    assert!(has("analog_report[pin=26].value (ADC counts)"));
    assert!(has("digital_report[pin=10].value"));
    // Tick labels are whole numbers: integer fields, a frame-index axis.
    let numbers: Vec<&String> = lines.iter().filter(|l| l.parse::<f64>().is_ok()).collect();
    assert!(numbers.len() > 10, "{numbers:?}");
    assert!(numbers.iter().all(|n| !n.contains('.')), "{numbers:?}");
    // The digital panel holds 0 and 1 only: its ticks are 0 and 1.
    assert!(has("0") && has("1"));
    // The analog series is pin 26 alone (1225..1800): pin 27's 2890 would
    // lift the axis past 2800, as it does without the filter.
    let top = |lines: &[String]| {
        lines
            .iter()
            .filter_map(|l| l.parse::<i64>().ok())
            .max()
            .unwrap()
    };
    assert!(top(&lines) < 2000, "{lines:?}");
    let both = svg_texts(
        &[
            "plot",
            "telemetrix",
            &input,
            "--fields",
            "analog_report.value",
        ],
        "plot-selectors-both",
    );
    let axis: Vec<i64> = both
        .iter()
        .filter_map(|l| l.parse().ok())
        .filter(|&n| n >= 1000)
        .collect();
    assert!(axis.iter().any(|&n| n >= 2800), "{axis:?}");
}

#[test]
fn errors_alone_plot_the_rejections_so_far() {
    let input = data_arg("ble_telemetry.bin");
    let lines = svg_texts(
        &["plot", "omnitiles", &input, "--errors"],
        "plot-errors-alone",
    );
    assert!(lines.iter().any(|l| l == "rejections so far"));
    assert!(
        lines.iter().any(|l| l == "9"),
        "the count reaches 9: {lines:?}"
    );
}

#[test]
fn plot_errors_say_what_to_do() {
    let input = data_arg("ble_telemetry.bin");
    let dir = scratch("plot-errors");
    let png = dir.join("p.png");
    let png = png.to_str().unwrap();
    let cases: [(&[&str], i32, &str); 6] = [
        (
            &[
                "plot",
                "omnitiles",
                &input,
                "--fields",
                "nope[pin=1].x",
                "-o",
                png,
            ],
            2,
            "a filter follows a message type",
        ),
        (
            &[
                "plot",
                "omnitiles",
                &input,
                "--fields",
                "telemetry[layout=ble53",
                "-o",
                png,
            ],
            2,
            "without its `]`",
        ),
        (
            &["plot", "omnitiles", &input, "-o", png],
            2,
            "needs --fields",
        ),
        (
            &["plot", "omnitiles", &input, "--fields", "m1_pos"],
            2,
            "needs -o FILE.png",
        ),
        (
            &[
                "plot",
                "omnitiles",
                &input,
                "--fields",
                "m1_pos",
                "-o",
                "p.gif",
            ],
            2,
            "PNG or SVG",
        ),
        (
            &["plot", "omnitiles", &input, "--fields", "nope", "-o", png],
            2,
            "the first frame's fields are offset,len,type",
        ),
    ];
    for (args, code, message) in cases {
        let out = run(args, b"");
        assert_eq!(out.code, code, "{args:?}: {}", out.stderr);
        assert!(out.stderr.contains(message), "{args:?}: {}", out.stderr);
    }
}
