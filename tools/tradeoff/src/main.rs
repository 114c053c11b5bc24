//! Speed against error: how far each render setting is from a reference
//! image, and what it costs.
//!
//! `cargo run --release -p tradeoff [WIDTH HEIGHT]` (default 320x240).
//! For each benchmark scene (evaluated once) it renders a reference (256
//! stratified samples on a 16x16 grid, no skips), then for every
//! setting the median time of 3 renders and the error of its image against
//! the reference: RMSE in 8-bit levels, and the share of pixels more than 1
//! and more than 2 levels off (largest channel difference); last, adaptive
//! 16 with the pixels an ideal detector would refine ([`ideal_pixels`]),
//! to show how far a better detector could go. It writes the
//! tables into `BENCHMARKS.md` (between the markers [`BEGIN`] and [`END`])
//! and the plot (RMSE against time, both logarithmic, with each scene's
//! Pareto front and the adaptive goal) to `benches/tradeoff.png`.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use image::RgbImage;
use plotters::prelude::*;
use rayrepl::lang::{Interpreter, Limits, SourceMap, parse_file};
use rayrepl::render::{RenderControl, RenderOptions, SceneGeometry, Skips, render, render_refining};
use rayrepl::scene::Scene;

/// The benchmark scenes measured (sponge5, 3.2 million boxes, is left out:
/// its evaluation alone takes longer than this whole run).
const SCENES: [&str; 4] = ["solar", "sponge4", "spheres100k", "scales"];

/// The line after which the report goes in `BENCHMARKS.md`.
const BEGIN: &str = "<!-- tradeoff: begin (written by `cargo run --release -p tradeoff`) -->";
/// The line before which the report ends in `BENCHMARKS.md`.
const END: &str = "<!-- tradeoff: end -->";

/// Timed renders per setting; the median is reported.
const RUNS: usize = 3;

/// A family of settings: one colour in the plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Family {
    Samples,
    Adaptive,
    Skips,
    Depth,
    Ideal,
}

impl Family {
    const ALL: [Family; 5] = [Family::Samples, Family::Adaptive, Family::Skips, Family::Depth, Family::Ideal];

    fn name(self) -> &'static str {
        match self {
            Family::Samples => "uniform samples",
            Family::Adaptive => "adaptive samples",
            Family::Skips => "skips (4 samples)",
            Family::Depth => "depth (1 sample)",
            Family::Ideal => IDEAL,
        }
    }

    fn colour(self) -> RGBColor {
        match self {
            Family::Samples => RGBColor(31, 119, 180),
            Family::Adaptive => RGBColor(214, 39, 40),
            Family::Skips => RGBColor(44, 160, 44),
            Family::Depth => RGBColor(148, 103, 189),
            Family::Ideal => RGBColor(90, 90, 90),
        }
    }
}

/// One setting to measure.
struct Setting {
    family: Family,
    label: String,
    options: RenderOptions,
}

/// How far an image is from the reference.
#[derive(Debug, Clone, Copy)]
struct Error {
    /// Root mean square difference over all channels, in 8-bit levels.
    rmse: f64,
    /// Share of pixels whose largest channel difference is above 1 level.
    over1: f64,
    /// Share of pixels whose largest channel difference is above 2 levels.
    over2: f64,
}

/// One measured setting.
struct Row {
    scene: &'static str,
    family: Family,
    label: String,
    time: Duration,
    /// Primary rays per pixel (shows how many pixels adaptive sampling refined).
    rays_per_pixel: f64,
    error: Error,
}

fn main() {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<u32>().ok());
    let width = args.next().flatten().unwrap_or(320);
    let height = args.next().flatten().unwrap_or(240);
    let base = RenderOptions { width, height, ..RenderOptions::default() };
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let mut rows = Vec::new();
    for name in SCENES {
        let scene = match evaluate(&root.join(format!("benches/scenes/{name}.ray"))) {
            Ok(scene) => scene,
            Err(e) => {
                eprintln!("{name}: {e}");
                std::process::exit(1);
            }
        };
        let prepared = SceneGeometry::new(&scene);
        let reference_options = RenderOptions { samples: 256, skips: Skips::none(), ..base };
        let (reference, reference_time, _) = render_once(&scene, &prepared, &reference_options);
        eprintln!("{name}: reference in {:.2} s", reference_time.as_secs_f64());
        let (mut one_sample, mut uniform16) = (None, None);
        for setting in settings(base) {
            let (image, time, rays_per_pixel) = median(|| render_once(&scene, &prepared, &setting.options));
            let error = compare(&image, &reference);
            match setting.label.as_str() {
                "1 samples" => one_sample = Some(image),
                "16 samples" => uniform16 = Some(image),
                _ => {}
            }
            rows.push(Row { scene: name, family: setting.family, label: setting.label, time, rays_per_pixel, error });
        }
        let (one_sample, uniform16) = (one_sample.expect("measured"), uniform16.expect("measured"));
        let ideal = ideal_pixels(&one_sample, &uniform16, &reference);
        let options = RenderOptions { samples: 16, adaptive: true, ..base };
        let (image, time, rays_per_pixel) = median(|| {
            let (image, stats) = render_refining(&scene, &prepared, &options, &ideal, &RenderControl::default())
                .expect("nothing cancels it");
            (image, stats.elapsed, stats.rays.primary as f64 / ideal.len() as f64)
        });
        let error = compare(&image, &reference);
        rows.push(Row { scene: name, family: Family::Ideal, label: IDEAL.to_string(), time, rays_per_pixel, error });
        for row in rows.iter().filter(|r| r.scene == name) {
            eprintln!(
                "{name:12} {:28} {:9.4} s  rmse {:7.3}  >1 {:6.2}%  >2 {:6.2}%",
                row.label,
                row.time.as_secs_f64(),
                row.error.rmse,
                100.0 * row.error.over1,
                100.0 * row.error.over2
            );
        }
    }
    let md = root.join("BENCHMARKS.md");
    if let Err(e) = write_between_markers(&md, &markdown(&rows, width, height)) {
        eprintln!("cannot update {}: {e}", md.display());
        std::process::exit(1);
    }
    let png = root.join("benches/tradeoff.png");
    if let Err(e) = plot(&rows, &png) {
        eprintln!("cannot draw {}: {e}", png.display());
        std::process::exit(1);
    }
    eprintln!("wrote {} and {}", md.display(), png.display());
}

/// Replaces what lies between the lines [`BEGIN`] and [`END`] of the file at
/// `path` with `report`, keeping the rest of the file.
fn write_between_markers(path: &Path, report: &str) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let (Some(begin), Some(end)) = (text.find(BEGIN), text.find(END)) else {
        return Err(format!("the markers `{BEGIN}` and `{END}` are missing"));
    };
    let head = &text[..begin + BEGIN.len()];
    let updated = format!("{head}\n\n{}\n{}", report.trim_end(), &text[end..]);
    std::fs::write(path, updated).map_err(|e| e.to_string())
}

/// Parses and evaluates a scene file at time 0.
fn evaluate(path: &Path) -> Result<Scene, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut sources = SourceMap::new();
    let id = sources.add(path.display().to_string(), text.clone(), 0);
    let program = parse_file(id, &text).map_err(|d| d.message)?;
    let mut interpreter = Interpreter::new(0.0, Limits::default());
    interpreter.run(&program).map_err(|d| d.message)?;
    Ok(interpreter.into_scene())
}

/// Every setting measured, around the defaults `base`.
fn settings(base: RenderOptions) -> Vec<Setting> {
    let mut all = Vec::new();
    for samples in [1, 4, 16, 64] {
        all.push(Setting {
            family: Family::Samples,
            label: format!("{samples} samples"),
            options: RenderOptions { samples, ..base },
        });
    }
    for samples in [4, 16, 64] {
        all.push(Setting {
            family: Family::Adaptive,
            label: format!("adaptive {samples}"),
            options: RenderOptions { samples, adaptive: true, ..base },
        });
    }
    let all_on = Skips::all();
    let skips = [
        ("all skips on", all_on),
        ("all skips off", Skips::none()),
        ("back_facing_light off", Skips { back_facing_light: false, ..all_on }),
        ("zero_ks off", Skips { zero_ks: false, ..all_on }),
    ];
    for (label, skips) in skips {
        all.push(Setting {
            family: Family::Skips,
            label: label.to_string(),
            options: RenderOptions { samples: 4, skips, ..base },
        });
    }
    for depth in 1..=10 {
        all.push(Setting {
            family: Family::Depth,
            label: format!("depth {depth}"),
            options: RenderOptions { depth, ..base },
        });
    }
    all
}

/// The label of the ideal-pixels row.
const IDEAL: &str = "adaptive 16, ideal pixels";

/// The pixels an ideal detector would have adaptive 16 refine, one flag per
/// pixel: knowing the reference, it ranks the pixels by how much 16 samples
/// lower their squared error against the 1-sample render (the first pass's
/// bytes), and takes the fewest, best first, that bring the image's total
/// down to uniform 16's. Its time shows how far a better detector alone
/// could take adaptive 16.
fn ideal_pixels(one_sample: &RgbImage, uniform16: &RgbImage, reference: &RgbImage) -> Vec<bool> {
    let squared = |image: &RgbImage| -> Vec<f64> {
        image
            .pixels()
            .zip(reference.pixels())
            .map(|(p, q)| p.0.iter().zip(q.0).map(|(&a, b)| (f64::from(a) - f64::from(b)).powi(2)).sum())
            .collect()
    };
    let (before, after) = (squared(one_sample), squared(uniform16));
    let target: f64 = after.iter().sum();
    let mut order: Vec<usize> = (0..before.len()).collect();
    let gain = |k: usize| before[k] - after[k];
    order.sort_by(|&a, &b| gain(b).total_cmp(&gain(a)).then(a.cmp(&b)));
    let mut total: f64 = before.iter().sum();
    let mut refined = vec![false; before.len()];
    for k in order {
        if total <= target {
            break;
        }
        refined[k] = true;
        total -= gain(k);
    }
    refined
}

/// One render, its wall-clock time and its primary rays per pixel.
fn render_once(scene: &Scene, prepared: &SceneGeometry, options: &RenderOptions) -> (RgbImage, Duration, f64) {
    let (image, stats) = render(scene, prepared, options, &RenderControl::default()).expect("nothing cancels it");
    let pixels = f64::from(options.width) * f64::from(options.height);
    (image, stats.elapsed, stats.rays.primary as f64 / pixels)
}

/// The image of [`RUNS`] renders by `render_once` (all the same) and their
/// median time.
fn median(render_once: impl Fn() -> (RgbImage, Duration, f64)) -> (RgbImage, Duration, f64) {
    let mut times = Vec::with_capacity(RUNS);
    let mut last = None;
    for _ in 0..RUNS {
        let (image, time, rays) = render_once();
        times.push(time);
        last = Some((image, rays));
    }
    times.sort();
    let (image, rays) = last.expect("RUNS > 0");
    (image, times[RUNS / 2], rays)
}

/// The error of `image` against `reference` (same size).
fn compare(image: &RgbImage, reference: &RgbImage) -> Error {
    let mut squares = 0.0;
    let (mut over1, mut over2) = (0usize, 0usize);
    for (p, q) in image.pixels().zip(reference.pixels()) {
        let mut largest = 0;
        for (a, b) in p.0.iter().zip(q.0) {
            let d = a.abs_diff(b);
            squares += f64::from(d) * f64::from(d);
            largest = largest.max(d);
        }
        over1 += usize::from(largest > 1);
        over2 += usize::from(largest > 2);
    }
    let pixels = (image.width() * image.height()).max(1) as f64;
    Error { rmse: (squares / (3.0 * pixels)).sqrt(), over1: over1 as f64 / pixels, over2: over2 as f64 / pixels }
}

/// The first line of `/proc/cpuinfo` naming the CPU model.
fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, model)| model.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".to_string())
}

/// The output of a command, trimmed (empty if it cannot run).
fn command_output(program: &str, args: &[&str]) -> String {
    std::process::Command::new(program)
        .args(args)
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}

/// The row `label` against uniform 16 on one scene: time ratio, RMSE ratio,
/// and both errors.
fn adaptive_verdict(rows: &[Row], scene: &str, label: &str) -> Option<(f64, f64, Error, Error)> {
    let find = |label: &str| rows.iter().find(|r| r.scene == scene && r.label == label);
    let (adaptive, uniform) = (find(label)?, find("16 samples")?);
    Some((
        adaptive.time.as_secs_f64() / uniform.time.as_secs_f64(),
        adaptive.error.rmse / uniform.error.rmse.max(1e-12),
        adaptive.error,
        uniform.error,
    ))
}

/// The report: machine, method, the verdict on adaptive sampling, the table.
fn markdown(rows: &[Row], width: u32, height: u32) -> String {
    let mut s = String::new();
    let threads = rayon::current_num_threads();
    let _ = writeln!(
        s,
        "Measured by `cargo run --release -p tradeoff` on {} ({} cores by `nproc`, {threads} rayon threads), \
         {}. Images are {width}x{height}. Each scene is evaluated once; each setting is rendered {RUNS} times and \
         the median wall-clock time is shown (other work shared the machine, so small times are noisy; load \
         average at the end of the run: {}).\n",
        cpu_model(),
        command_output("nproc", &[]),
        command_output("date", &["-u", "+%Y-%m-%d %H:%M UTC"]),
        std::fs::read_to_string("/proc/loadavg")
            .map(|l| l.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
            .unwrap_or_default(),
    );
    let _ = writeln!(
        s,
        "The reference of each scene is rendered with 256 stratified samples per pixel (16x16 grid), every skip \
         off, at the default depth 5. Error is against it: **RMSE** over all channels in 8-bit levels, and \
         the share of pixels whose largest channel difference is more than 1 (**>1**) and more than 2 (**>2**) \
         levels. Unless the row says otherwise: depth 5, all skips on, 1 sample.\n"
    );
    let _ = writeln!(
        s,
        "- **Skips** never change a byte (each has a test), so their rows show time only; they are measured at 4 \
         samples so that the times are long enough to compare.\n\
         - **Depth** rows are compared with the same depth-5 reference: depth above 5 is a different image from \
         the one SPEC 6 asks for, so its \"error\" measures how much deeper reflections still change.\n\
         - **Adaptive N** (`--samples N --adaptive`) renders every pixel at its centre, then renders again with N \
         samples only the pixels that may differ from their centre: on an edge (a neighbour's centre ray met other \
         surfaces or lights, and its colour differs by more than 2 levels), on a bend of the colour (second \
         differences above 6 levels), or on an object under 2 pixels wide.\n"
    );
    let _ = writeln!(s, "### Adaptive 16 against uniform 16\n");
    let _ = writeln!(
        s,
        "Goal: the error of uniform 16 samples in at most half its time.\n\n\
         | scene | time adaptive / uniform | RMSE adaptive / uniform | >2 adaptive | >2 uniform | met | ideal pixels: time, RMSE / uniform |\n\
         |---|---:|---:|---:|---:|---|---|"
    );
    for scene in SCENES {
        if let (Some((time, rmse, a, u)), Some((ideal_time, ideal_rmse, ..))) =
            (adaptive_verdict(rows, scene, "adaptive 16"), adaptive_verdict(rows, scene, IDEAL))
        {
            let met = time <= 0.5 && rmse <= 1.0;
            let _ = writeln!(
                s,
                "| {scene} | {time:.2} | {rmse:.2} | {:.2}% | {:.2}% | {} | {ideal_time:.2}, {ideal_rmse:.2} |",
                100.0 * a.over2,
                100.0 * u.over2,
                if met { "yes" } else { "no" }
            );
        }
    }
    let _ = writeln!(
        s,
        "\n\"Met\" means at most half the time and at most the RMSE of uniform 16. The last column is the same \
         adaptive 16 render with the pixels to refine chosen by an ideal detector that knows the reference: the \
         fewest pixels, those whose error 16 samples lower most, that bring the image to uniform 16's error. It \
         shows what the detector leaves on the table: where this time is above 0.5 too, a better choice of pixels \
         alone does not reach the goal.\n"
    );
    let _ = writeln!(s, "### All settings\n");
    let _ = writeln!(
        s,
        "| scene | setting | time (ms) | primary rays / pixel | RMSE | >1 | >2 |\n|---|---|---:|---:|---:|---:|---:|"
    );
    for row in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {:.1} | {:.2} | {:.3} | {:.2}% | {:.2}% |",
            row.scene,
            row.label,
            1000.0 * row.time.as_secs_f64(),
            row.rays_per_pixel,
            row.error.rmse,
            100.0 * row.error.over1,
            100.0 * row.error.over2
        );
    }
    let _ = writeln!(
        s,
        "\n`benches/tradeoff.png`: one panel per scene; RMSE against the reference \
         (8-bit levels, log scale; an exact match is drawn at 0.01) against the median render time (ms, log scale), \
         one point per setting, coloured by family. The dashed black line is the Pareto front (no other setting \
         is both faster and more accurate); the shaded box is the adaptive goal, at most half the time of uniform \
         16 and at most its RMSE."
    );
    s
}

/// Registers a sans-serif font for the plot's text, if the system has one.
fn register_font() -> bool {
    const CANDIDATES: [&str; 3] = [
        "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
        "/usr/share/fonts/TTF/DejaVuSans.ttf",
        "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    ];
    CANDIDATES.iter().any(|path| match std::fs::read(path) {
        // The font lives as long as the process: plotters keeps it.
        Ok(bytes) => plotters::style::register_font("sans-serif", FontStyle::Normal, bytes.leak()).is_ok(),
        Err(_) => false,
    })
}

/// The points no other point beats in both time and error, from the fastest
/// to the most accurate, joined as a staircase.
fn pareto_front(mut points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for (time, error) in points {
        if front.last().is_none_or(|&(_, best)| error < best) {
            if let Some(&(_, best)) = front.last() {
                front.push((time, best));
            }
            front.push((time, error));
        }
    }
    front
}

/// Draws RMSE against time, one panel per scene, to `path`.
fn plot(rows: &[Row], path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let text = register_font();
    if !text {
        eprintln!("no DejaVuSans.ttf found: the plot has no text (see BENCHMARKS.md for its axes)");
    }
    let root = BitMapBackend::new(path, (1400, 1000)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((2, 2));
    for (panel, scene) in panels.iter().zip(SCENES) {
        let points: Vec<&Row> = rows.iter().filter(|r| r.scene == scene).collect();
        let ms = |r: &Row| 1000.0 * r.time.as_secs_f64().max(1e-6);
        let rmse = |r: &Row| r.error.rmse.max(0.01);
        let (t_min, t_max) = points.iter().fold((f64::MAX, 0f64), |(lo, hi), r| (lo.min(ms(r)), hi.max(ms(r))));
        let e_max = points.iter().fold(0.1f64, |hi, r| hi.max(rmse(r)));
        let mut builder = ChartBuilder::on(panel);
        builder.margin(12);
        if text {
            builder.caption(scene, ("sans-serif", 24)).x_label_area_size(40).y_label_area_size(60);
        }
        // Room above the highest point for the legend, which would otherwise
        // hide the points in the upper right.
        let mut chart =
            builder.build_cartesian_2d((t_min * 0.7..t_max * 1.4).log_scale(), (0.008..e_max * 60.0).log_scale())?;
        let mut mesh = chart.configure_mesh();
        if text {
            mesh.x_labels(6)
                .x_label_formatter(&|t| format!("{t:.0}"))
                .x_desc("median time (ms)")
                .y_desc("RMSE (8-bit levels)");
        } else {
            mesh.x_labels(0).y_labels(0);
        }
        mesh.draw()?;
        if let Some(uniform) = points.iter().find(|r| r.label == "16 samples") {
            let goal = [(t_min * 0.7, 0.008), (ms(uniform) / 2.0, rmse(uniform))];
            let drawn = chart.draw_series([Rectangle::new(goal, RGBColor(44, 160, 44).mix(0.15).filled())])?;
            if text {
                drawn.label("goal of adaptive 16").legend(|(x, y)| {
                    Rectangle::new([(x + 2, y - 5), (x + 14, y + 5)], RGBColor(44, 160, 44).mix(0.3).filled())
                });
            }
        }
        let front = pareto_front(points.iter().map(|r| (ms(r), rmse(r))).collect());
        let drawn = chart.draw_series(DashedLineSeries::new(front, 6, 4, BLACK.stroke_width(1)))?;
        if text {
            drawn.label("Pareto front").legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK));
        }
        for family in Family::ALL {
            let colour = family.colour();
            let mut series: Vec<(f64, f64)> =
                points.iter().filter(|r| r.family == family).map(|r| (ms(r), rmse(r))).collect();
            if matches!(family, Family::Samples | Family::Adaptive) {
                series.sort_by(|a, b| a.0.total_cmp(&b.0));
                chart.draw_series(LineSeries::new(series.clone(), colour.stroke_width(1)))?;
            }
            let drawn = chart.draw_series(series.iter().map(|&p| Circle::new(p, 5, colour.filled())))?;
            if text {
                drawn.label(family.name()).legend(move |(x, y)| Circle::new((x + 8, y), 5, colour.filled()));
            }
        }
        if text {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .label_font(("sans-serif", 16))
                .draw()?;
        }
    }
    root.present()?;
    Ok(())
}
