//! SVG plot of one experiment: measured replicates (small dots), condition means with
//! ±2 standard errors, and the simulated observable (line through the simulated points),
//! against the condition. Drawn with plotters, written atomically.

use std::path::Path;

use anyhow::{anyhow, Result};
use plotters::prelude::*;

use super::residuals::Dataset;
use crate::io::atomic::write_string_atomic;

/// Plot size, px.
const SIZE: (u32, u32) = (720, 480);
/// Margin added around the data range (fraction of the range).
const PAD: f64 = 0.08;

/// Write the plot of experiment `ei` with predictions `pred` (and optionally a second set,
/// e.g. after a fit) to `path`.
pub fn plot_experiment(
    data: &Dataset,
    ei: usize,
    pred: &[f64],
    second: Option<(&str, &[f64])>,
    title: &str,
    path: &Path,
) -> Result<()> {
    let idx: Vec<usize> = (0..data.obs.len())
        .filter(|&i| data.obs[i].experiment == ei)
        .collect();
    let Some(&first) = idx.first() else {
        return Err(anyhow!("experiment {} has no conditions", ei + 1));
    };
    let experiment = &data.experiments[data.obs[first].experiment];
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &i in &idx {
        let o = &data.obs[i];
        x0 = x0.min(o.x);
        x1 = x1.max(o.x);
        let mut ys: Vec<f64> = o.values.clone();
        ys.push(pred[i]);
        ys.push(o.mean - 2.0 * o.se_mean);
        ys.push(o.mean + 2.0 * o.se_mean);
        if let Some((_, s)) = second {
            ys.push(s[i]);
        }
        for y in ys {
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    let (dx, dy) = ((x1 - x0).max(1e-12) * PAD, (y1 - y0).max(1e-12) * PAD);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        let e = |e: &dyn std::fmt::Debug| anyhow!("plot: {e:?}");
        root.fill(&WHITE).map_err(|x| e(&x))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0 - dx..x1 + dx, y0 - dy..y1 + dy)
            .map_err(|x| e(&x))?;
        chart
            .configure_mesh()
            .x_desc(experiment.condition.1.as_str())
            .y_desc(experiment.observable_label.as_str())
            .draw()
            .map_err(|x| e(&x))?;
        let reps = idx.iter().flat_map(|&i| {
            let o = &data.obs[i];
            o.values.iter().map(move |v| (o.x, *v))
        });
        chart
            .draw_series(reps.map(|p| Circle::new(p, 2, BLUE.mix(0.4).filled())))
            .map_err(|x| e(&x))?
            .label("measured replicates")
            .legend(|(x, y)| Circle::new((x, y), 3, BLUE.filled()));
        chart
            .draw_series(idx.iter().map(|&i| {
                let o = &data.obs[i];
                PathElement::new(
                    vec![
                        (o.x, o.mean - 2.0 * o.se_mean),
                        (o.x, o.mean + 2.0 * o.se_mean),
                    ],
                    BLUE.stroke_width(2),
                )
            }))
            .map_err(|x| e(&x))?
            .label("mean ± 2 SE")
            .legend(|(x, y)| PathElement::new(vec![(x, y - 5), (x, y + 5)], BLUE));
        let line =
            |p: &[f64]| -> Vec<(f64, f64)> { idx.iter().map(|&i| (data.obs[i].x, p[i])).collect() };
        chart
            .draw_series(LineSeries::new(line(pred), RED.stroke_width(2)))
            .map_err(|x| e(&x))?
            .label("simulated")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        if let Some((name, s)) = second {
            chart
                .draw_series(LineSeries::new(line(s), GREEN.stroke_width(2)))
                .map_err(|x| e(&x))?
                .label(name.to_string())
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], GREEN));
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()
            .map_err(|x| e(&x))?;
        root.present().map_err(|x| e(&x))?;
    }
    write_string_atomic(path, &svg)
}
