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

#[test]
fn plot_errors_say_what_to_do() {
    let input = data_arg("ble_telemetry.bin");
    let dir = scratch("plot-errors");
    let png = dir.join("p.png");
    let png = png.to_str().unwrap();
    let cases: [(&[&str], i32, &str); 4] = [
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
