//! SVG figures in the paper's layout: mean and standard deviation of the rotation and
//! translation errors per method against the sweep level.

use super::{SummaryRow, Sweep};
use plotters::prelude::*;
use std::path::Path;

/// Renders the four panels (mean rotation, mean translation, std rotation, std translation)
/// to an SVG string.
pub fn render_svg(sweep: Sweep, rows: &[SummaryRow]) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1200, 800)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root
            .titled(&format!("sweep: {}", sweep.name()), ("sans-serif", 22))
            .map_err(|e| e.to_string())?;
        let panels = root.split_evenly((2, 2));
        let mut methods: Vec<&str> = Vec::new();
        for r in rows {
            if !methods.contains(&r.method.as_str()) {
                methods.push(&r.method);
            }
        }
        type Getter = fn(&SummaryRow) -> f64;
        let specs: [(&str, Getter); 4] = [
            ("mean rotation error (deg)", |r| r.rot_mean),
            ("mean translation error (deg)", |r| r.trans_mean),
            ("std rotation error (deg)", |r| r.rot_std),
            ("std translation error (deg)", |r| r.trans_std),
        ];
        let (xmin, xmax) = rows
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), r| {
                (a.min(r.level), b.max(r.level))
            });
        let (xmin, xmax) = if xmin.is_finite() {
            (xmin, xmax.max(xmin + 1e-9))
        } else {
            (0.0, 1.0)
        };
        for (panel, (title, get)) in panels.iter().zip(specs) {
            let ymax = rows
                .iter()
                .map(get)
                .filter(|v| v.is_finite())
                .fold(0.0f64, f64::max);
            let ymax = if ymax > 0.0 { ymax * 1.1 } else { 1.0 };
            let mut chart = ChartBuilder::on(panel)
                .caption(title, ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(50)
                .build_cartesian_2d(xmin..xmax, 0.0..ymax)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc(sweep.axis_label())
                .draw()
                .map_err(|e| e.to_string())?;
            for (mi, m) in methods.iter().enumerate() {
                let color = Palette99::pick(mi).to_rgba();
                let pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.method == *m)
                    .map(|r| (r.level, get(r)))
                    .filter(|p| p.1.is_finite())
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(m.to_string())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                    });
                chart
                    .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
                    .map_err(|e| e.to_string())?;
            }
            chart
                .configure_series_labels()
                .border_style(BLACK)
                .background_style(WHITE.mix(0.8))
                .draw()
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// Renders and writes the figure atomically.
pub fn write_svg(path: &Path, sweep: Sweep, rows: &[SummaryRow]) -> std::io::Result<()> {
    let svg = render_svg(sweep, rows).map_err(std::io::Error::other)?;
    super::write_output(path, svg.as_bytes(), &[])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_every_method() {
        let rows: Vec<SummaryRow> = Sweep::Angular
            .levels()
            .iter()
            .flat_map(|l| {
                ["gsrp", "grsrp+"].map(|m| SummaryRow {
                    level: l.value,
                    method: m.into(),
                    rot_mean: l.value,
                    rot_std: 0.1,
                    rot_median: l.value,
                    trans_mean: 2.0 * l.value,
                    trans_std: 0.2,
                    trans_median: 1.0,
                    seconds_median: 1e-3,
                    failures: 0,
                })
            })
            .collect();
        let svg = render_svg(Sweep::Angular, &rows).unwrap();
        assert!(svg.starts_with("<svg"));
        assert!(svg.contains("gsrp") && svg.contains("grsrp+"));
    }
}
