//! The report's SVG figures, drawn with `plotters`: the Pareto chart of screening effects,
//! response-surface maps of the Box–Behnken fit, and the measured against the simulated
//! pile profile. Each returns the SVG text; [`super::write_calibration`] writes it
//! atomically.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::calibration::plan::response_surface::ResponseSurface as FittedSurface;
use crate::calibration::plan::screening::Screening;
use crate::calibration::Factor;
use crate::optimize::ResponseSurface;

/// Figure size in pixels.
const SIZE: (u32, u32) = (720, 480);
/// Square figure size for the surface maps.
const SURFACE_SIZE: (u32, u32) = (620, 560);
/// Margin around the plotting area, pixels.
const MARGIN: u32 = 12;
/// Room for axis labels, pixels.
const LABEL_AREA: u32 = 48;
/// Grid cells per side of a surface map.
const SURFACE_CELLS: usize = 48;
/// Colour bands of a surface map (filled contours).
const SURFACE_BANDS: usize = 12;
/// Hue of the lowest band (blue) and of the highest (red), as fractions of the colour wheel.
const HUE_LOW: f64 = 0.66;
const HUE_HIGH: f64 = 0.0;
/// Headroom above the tallest bar or peak, as a fraction.
const HEADROOM: f64 = 0.15;
/// Bar width as a fraction of its slot.
const BAR_FILL: f64 = 0.7;
/// Font size of captions and labels.
const CAPTION_FONT: u32 = 18;
const LABEL_FONT: u32 = 12;

/// A plotting error as a message.
fn plot_error<E: std::fmt::Display>(e: E) -> String {
    format!("cannot draw the figure: {e}")
}

/// Pareto chart: the screening effects |2b| sorted from the largest, significant ones
/// filled, each bar labelled with its factor and p-value.
pub fn pareto(screening: &Screening, unit: &str) -> Result<String, String> {
    let mut rows: Vec<_> = screening.effects.iter().collect();
    rows.sort_by(|a, b| b.effect.abs().total_cmp(&a.effect.abs()));
    let top = rows
        .first()
        .map_or(1.0, |r| r.effect.abs())
        .max(f64::MIN_POSITIVE);
    let n = rows.len() as f64;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let caption = format!(
            "Screening effects |2b| ({unit}); filled: p < {}",
            screening.significance
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", CAPTION_FONT))
            .margin(MARGIN)
            .x_label_area_size(LABEL_AREA / 2)
            .y_label_area_size(LABEL_AREA)
            .build_cartesian_2d(0.0..n, 0.0..top * (1.0 + HEADROOM))
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .disable_x_axis()
            .y_desc(format!("|effect| ({unit})"))
            .draw()
            .map_err(plot_error)?;
        for (i, r) in rows.iter().enumerate() {
            let x0 = i as f64 + 0.5 * (1.0 - BAR_FILL);
            let x1 = x0 + BAR_FILL;
            let h = r.effect.abs();
            let style = if r.significant {
                RED.mix(0.8).filled()
            } else {
                BLACK.mix(0.35).stroke_width(1)
            };
            chart
                .draw_series(std::iter::once(Rectangle::new([(x0, 0.0), (x1, h)], style)))
                .map_err(plot_error)?;
            let label = match r.p {
                Some(p) => format!("{} p={}", r.label, crate::stats::report::format_p(p)),
                None => r.label.clone(),
            };
            let font = ("sans-serif", LABEL_FONT)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Bottom));
            chart
                .draw_series(std::iter::once(Text::new(
                    label,
                    (i as f64 + 0.5, h + 0.02 * top),
                    font,
                )))
                .map_err(plot_error)?;
        }
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

/// The factor pairs to map: among the first three factors by |linear coefficient|.
pub fn surface_pairs(bbd: &FittedSurface) -> Vec<(usize, usize)> {
    let k = bbd.factors.len();
    let mut order: Vec<usize> = (0..k).collect();
    let linear = |i: usize| bbd.anova.coefficients[i + 1].estimate.abs();
    order.sort_by(|&a, &b| linear(b).total_cmp(&linear(a)));
    order.truncate(3);
    order.sort_unstable();
    let mut pairs = Vec::new();
    for (n, &i) in order.iter().enumerate() {
        for &j in &order[n + 1..] {
            pairs.push((i, j));
        }
    }
    pairs
}

/// A banded map of the fitted surface over factors `i` (x axis) and `j` (y axis), in actual
/// units, the other factors at the optimum `at` (coded); design points and the optimum
/// are marked.
pub fn surface_map(
    bbd: &FittedSurface,
    i: usize,
    j: usize,
    at: &[f64],
    target: f64,
    unit: &str,
) -> Result<String, String> {
    let (fi, fj) = (&bbd.factors[i], &bbd.factors[j]);
    let actual = |f: &Factor, x: f64| 0.5 * (f.low + f.high) + x * 0.5 * (f.high - f.low);
    let coded_at = |u: f64, v: f64| {
        let mut x = at.to_vec();
        x[i] = u;
        x[j] = v;
        x
    };
    let cell = 2.0 / SURFACE_CELLS as f64;
    let centre = |n: usize| -1.0 + (n as f64 + 0.5) * cell;
    let surface = bbd.surface();
    let mut values = Vec::with_capacity(SURFACE_CELLS * SURFACE_CELLS);
    for a in 0..SURFACE_CELLS {
        for b in 0..SURFACE_CELLS {
            values.push(surface.predict(&coded_at(centre(a), centre(b))));
        }
    }
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(*v), h.max(*v))
        });
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    let band = |v: f64| {
        ((v - lo) / span * SURFACE_BANDS as f64)
            .floor()
            .min(SURFACE_BANDS as f64 - 1.0)
    };
    let colour = |v: f64| {
        let f = band(v) / (SURFACE_BANDS as f64 - 1.0);
        HSLColor(HUE_LOW + f * (HUE_HIGH - HUE_LOW), 0.75, 0.55)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SURFACE_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let caption = format!(
            "Fitted {} ({unit}) over {} and {}: {:.2} (blue) to {:.2} (red); target {:.2} as dots",
            bbd.model, fi.label, fj.label, lo, hi, target
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", LABEL_FONT))
            .margin(MARGIN)
            .x_label_area_size(LABEL_AREA)
            .y_label_area_size(LABEL_AREA + LABEL_AREA / 2)
            .build_cartesian_2d(fi.low..fi.high, fj.low..fj.high)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{} {} ({})", fi.label, fi.name, fi.unit))
            .y_desc(format!("{} {} ({})", fj.label, fj.name, fj.unit))
            .draw()
            .map_err(plot_error)?;
        let half = 0.5 * cell;
        chart
            .draw_series(
                (0..SURFACE_CELLS)
                    .flat_map(|a| (0..SURFACE_CELLS).map(move |b| (a, b)))
                    .map(|(a, b)| {
                        let v = values[a * SURFACE_CELLS + b];
                        let (u, w) = (centre(a), centre(b));
                        Rectangle::new(
                            [
                                (actual(fi, u - half), actual(fj, w - half)),
                                (actual(fi, u + half), actual(fj, w + half)),
                            ],
                            colour(v).filled(),
                        )
                    }),
            )
            .map_err(plot_error)?;
        // The target level: cells whose band edge the target crosses, as dots.
        chart
            .draw_series(
                (0..SURFACE_CELLS)
                    .flat_map(|a| (0..SURFACE_CELLS).map(move |b| (a, b)))
                    .filter_map(|(a, b)| {
                        let v = values[a * SURFACE_CELLS + b];
                        let right =
                            (a + 1 < SURFACE_CELLS).then(|| values[(a + 1) * SURFACE_CELLS + b]);
                        let up = (b + 1 < SURFACE_CELLS).then(|| values[a * SURFACE_CELLS + b + 1]);
                        let crosses = [right, up]
                            .into_iter()
                            .flatten()
                            .any(|n| (v - target) * (n - target) <= 0.0);
                        crosses.then(|| {
                            Circle::new(
                                (actual(fi, centre(a)), actual(fj, centre(b))),
                                1,
                                BLACK.filled(),
                            )
                        })
                    }),
            )
            .map_err(plot_error)?;
        let mut seen: Vec<(f64, f64)> = Vec::new();
        for r in &bbd.runs {
            let p = (actual(fi, r.coded[i]), actual(fj, r.coded[j]));
            if !seen.contains(&p) {
                seen.push(p);
            }
        }
        chart
            .draw_series(
                seen.into_iter()
                    .map(|p| Circle::new(p, 4, BLACK.stroke_width(1))),
            )
            .map_err(plot_error)?;
        let opt = (actual(fi, at[i]), actual(fj, at[j]));
        chart
            .draw_series(std::iter::once(Cross::new(opt, 7, BLACK.stroke_width(3))))
            .map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

/// Measured against simulated pile: cone profiles of equal base at the measured angle and
/// at the simulated one (a schematic of the two angles, not an image of the pile).
pub fn pile_profiles(measured_deg: f64, simulated_deg: f64) -> Result<String, String> {
    let tallest = measured_deg.max(simulated_deg).to_radians().tan().max(0.1);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let caption = format!(
            "Pile profiles (schematic): measured {measured_deg:.2}° vs simulated {simulated_deg:.2}°"
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", CAPTION_FONT))
            .margin(MARGIN)
            .x_label_area_size(LABEL_AREA)
            .y_label_area_size(LABEL_AREA)
            .build_cartesian_2d(-1.1..1.1, 0.0..tallest * (1.0 + HEADROOM))
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("radius / base radius")
            .y_desc("height / base radius")
            .draw()
            .map_err(plot_error)?;
        for (angle, colour, name) in [
            (measured_deg, BLUE, "measured"),
            (simulated_deg, RED, "simulated"),
        ] {
            let h = angle.to_radians().tan();
            chart
                .draw_series(LineSeries::new(
                    [(-1.0, 0.0), (0.0, h), (1.0, 0.0)],
                    colour.stroke_width(2),
                ))
                .map_err(plot_error)?
                .label(format!("{name} {angle:.2}°"))
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}
