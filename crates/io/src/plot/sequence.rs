//! Storms in sequence (`sequence.png`).

use std::path::Path;

use plotters::prelude::*;

use catena::AppError;

use super::*;

/// What [`sequence`] draws: the arc, each visit's trench (penetration at rest after it, in visit
/// order), the touchdown window, the life along the arc with memory and as laid (years; empty if
/// not run), the accumulated annual-damage contributions at the critical node after each visit
/// (with memory, as laid), and each node's strength factor after the last visit.
pub struct SequencePlot<'a> {
    /// The figure's title.
    pub title: &'a str,
    /// Arc length of every node, m.
    pub arc: &'a [f64],
    /// The as-laid static penetration, m.
    pub as_laid: &'a [f64],
    /// Each visit's trench, m (in order).
    pub trenches: &'a [Vec<f64>],
    /// The arc window of the touchdown zone drawn, m.
    pub window: (f64, f64),
    /// Life along the arc with memory, years.
    pub life_memory: &'a [f64],
    /// Life along the arc as laid, years (empty if not run).
    pub life_as_laid: &'a [f64],
    /// The critical node's accumulated damage after each visit, with memory and as laid.
    pub accumulated: (&'a [f64], &'a [f64]),
    /// Strength factor after the last visit (empty or all 1 without degradation).
    pub strength: &'a [f64],
}

/// The storm sequence's figure (`sequence.png`): the trench's growth (penetration along the
/// touchdown zone after each visit, coloured from light to dark in visit order), the life along the
/// touchdown zone with memory and as laid, and the accumulated damage at the critical node visit
/// by visit; with degradation, the strength factor after the last visit.
pub fn sequence(path: &Path, p: &SequencePlot<'_>) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let degraded = p.strength.iter().any(|&s| s < 1.0);
    let size = (1800, 1000);
    let mut rgb = pixels(size, None);
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let root = root.titled(p.title, ("sans-serif", 22)).map_err(&err)?;
        let areas = root.split_evenly((2, 2));
        let (a0, a1) = p.window;
        let inside: Vec<usize> = (0..p.arc.len())
            .filter(|&i| p.arc[i] >= a0 && p.arc[i] <= a1)
            .collect();
        // The trench's growth.
        let labels = trench_labels(p.trenches.len());
        let series = trench_series(p, &inside, &labels);
        legend_panel(
            &areas[0],
            "trench: penetration at rest after each visit (positive down)",
            (
                "arc length from the top (m)",
                "penetration of the invert (m)",
            ),
            &series,
            &[],
            Some(p.window),
        )
        .map_err(&perr)?;
        // Life along the touchdown zone.
        let log = |v: &[f64]| -> Vec<(f64, f64)> {
            inside
                .iter()
                .filter(|&&i| v.get(i).is_some_and(|x| x.is_finite() && *x > 0.0))
                .map(|&i| (p.arc[i], v[i].log10()))
                .collect()
        };
        let mut lives = vec![Labelled {
            points: log(p.life_memory),
            colour: RGBColor(200, 30, 30),
            label: "with the seabed's memory",
        }];
        if !p.life_as_laid.is_empty() {
            lives.push(Labelled {
                points: log(p.life_as_laid),
                colour: RGBColor(20, 90, 200),
                label: "each visit from the as-laid state",
            });
        }
        legend_panel(
            &areas[1],
            "fatigue life along the touchdown zone",
            ("arc length from the top (m)", "log10 life (years)"),
            &lives,
            &[],
            Some(p.window),
        )
        .map_err(&perr)?;
        // Accumulated damage at the critical node.
        let steps = |v: &[f64]| -> Vec<(f64, f64)> {
            v.iter()
                .enumerate()
                .map(|(k, &d)| ((k + 1) as f64, d))
                .collect()
        };
        let mut acc = vec![Labelled {
            points: steps(p.accumulated.0),
            colour: RGBColor(200, 30, 30),
            label: "with memory",
        }];
        if !p.accumulated.1.is_empty() {
            acc.push(Labelled {
                points: steps(p.accumulated.1),
                colour: RGBColor(20, 90, 200),
                label: "as laid",
            });
        }
        legend_panel(
            &areas[2],
            "annual damage at the critical node, accumulated visit by visit",
            ("visits", "annual damage (1/year)"),
            &acc,
            &[],
            None,
        )
        .map_err(&perr)?;
        let caption = if degraded {
            "strength factor δ after the last visit (1: intact)"
        } else {
            "strength factor δ (no degradation in this scene: intact everywhere)"
        };
        lines_panel(
            &areas[3],
            caption,
            ("arc length from the top (m)", "δ = su / su,intact"),
            &[
                Labelled {
                    points: inside
                        .iter()
                        .filter_map(|&i| p.strength.get(i).map(|&s| (p.arc[i], s)))
                        .collect(),
                    colour: RGBColor(60, 60, 60),
                    label: "",
                },
                // The axis from 0 (remoulded to nothing) to 1 (intact), drawn invisibly.
                Labelled {
                    points: vec![(a0, 0.0), (a0, 1.0)],
                    colour: WHITE,
                    label: "",
                },
            ],
            &[],
            Some(p.window),
            false,
        )
        .map_err(&perr)?;
    }
    write_image(path, &rgb, size)
}

/// The legend's words for each visit's trench: the first and the last are named.
fn trench_labels(n: usize) -> Vec<String> {
    (0..n)
        .map(|k| {
            if k == 0 {
                "after the first visit (light)".to_string()
            } else if k + 1 == n {
                format!("after visit {} (dark)", k + 1)
            } else {
                String::new()
            }
        })
        .collect()
}

/// The as-laid penetration and each visit's trench over the window's nodes, shaded from light
/// (the first visit) to dark (the last).
fn trench_series<'a>(
    p: &SequencePlot<'_>,
    inside: &[usize],
    labels: &'a [String],
) -> Vec<Labelled<'a>> {
    let n = p.trenches.len().max(1);
    let shade = |k: usize| {
        let f = if n > 1 {
            k as f64 / (n - 1) as f64
        } else {
            1.0
        };
        let c = |light: f64, dark: f64| (light + (dark - light) * f) as u8;
        RGBColor(c(170.0, 10.0), c(200.0, 40.0), c(240.0, 120.0))
    };
    let mut series: Vec<Labelled<'a>> = vec![Labelled {
        points: inside
            .iter()
            .map(|&i| (p.arc[i], p.as_laid.get(i).copied().unwrap_or(0.0).max(0.0)))
            .collect(),
        colour: RGBColor(200, 120, 20),
        label: "as laid (statics)",
    }];
    series.extend(p.trenches.iter().enumerate().map(|(k, t)| Labelled {
        points: inside.iter().map(|&i| (p.arc[i], t[i].max(0.0))).collect(),
        colour: shade(k),
        label: labels[k].as_str(),
    }));
    series
}
