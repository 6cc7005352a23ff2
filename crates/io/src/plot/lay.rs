//! A lay (`lay.png`): the as-laid embedment along the route against the self-weight embedment and
//! the static embedment with force concentration, the touchdown's track, the top tension and the
//! payout, and the contact episodes per point of the pipe.

use std::path::Path;

use plotters::prelude::*;

use catena::run::lay::LayRun;
use catena::AppError;

use super::*;

/// Draws `lay.png`.
pub fn lay(path: &Path, r: &LayRun) -> Result<(), AppError> {
    init_fonts();
    let err = plot_err(path);
    let perr = plot_err::<String>(path);
    let size = (1800, 1100);
    let mut rgb = pixels(size, None);
    let s = &r.summary;
    let n = &r.nodes;
    let laid: Vec<usize> = (0..n.kp.len())
        .filter(|&g| n.as_laid[g].is_finite())
        .collect();
    let kp_range = laid
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &g| {
            (a.min(n.kp[g]), b.max(n.kp[g]))
        });
    let kp_range = if kp_range.0 < kp_range.1 {
        kp_range
    } else {
        (0.0, 1.0)
    };
    let flat = |v: f64| vec![(kp_range.0, v * 1e3), (kp_range.1, v * 1e3)];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let title = format!("{} — the lay", r.statics.scene.title);
        let root = root.titled(&title, ("sans-serif", 22)).map_err(&err)?;
        let areas = root.split_evenly((2, 2));
        legend_panel(
            &areas[0],
            "as-laid embedment of the invert along the pipe (positive down)",
            (
                "distance along the pipe from the initiation anchor, KP (m)",
                "embedment (mm)",
            ),
            &[
                Labelled {
                    points: laid
                        .iter()
                        .map(|&g| (n.kp[g], n.as_laid[g] * 1e3))
                        .collect(),
                    colour: RGBColor(200, 30, 30),
                    label: "as laid (this lay)",
                },
                Labelled {
                    points: flat(s.static_embedment),
                    colour: RGBColor(20, 90, 200),
                    label: "static, with force concentration",
                },
                Labelled {
                    points: flat(s.self_weight_embedment),
                    colour: RGBColor(60, 60, 60),
                    label: "self-weight z(W')",
                },
            ],
            &[],
            Some(kp_range),
        )
        .map_err(&perr)?;
        let rec = &r.records;
        let td: Points = rec
            .time
            .iter()
            .zip(&rec.touchdown_x)
            .filter(|(_, x)| x.is_finite())
            .map(|(&t, &x)| (t, x))
            .collect();
        let vessel: Points = rec
            .time
            .iter()
            .zip(&rec.vessel_x)
            .map(|(&t, &x)| (t, x + r.positions_exit_x()))
            .collect();
        legend_panel(
            &areas[1],
            "the touchdown's track and the tower's",
            ("time (s)", "x (m)"),
            &[
                Labelled {
                    points: td,
                    colour: RGBColor(200, 30, 30),
                    label: "touchdown point",
                },
                Labelled {
                    points: vessel,
                    colour: RGBColor(20, 90, 200),
                    label: "tower's exit (mean)",
                },
            ],
            &[],
            None,
        )
        .map_err(&perr)?;
        let kn = |v: &[f64]| -> Points {
            rec.time
                .iter()
                .zip(v)
                .map(|(&t, &x)| (t, x / 1e3))
                .collect()
        };
        let mut tension = vec![Labelled {
            points: kn(&rec.top_tension),
            colour: RGBColor(200, 30, 30),
            label: "top tension",
        }];
        if let Some(target) = r.target_tension {
            tension.push(Labelled {
                points: rec.time.iter().map(|&t| (t, target / 1e3)).collect(),
                colour: RGBColor(60, 60, 60),
                label: "tensioner's target",
            });
        }
        legend_panel(
            &areas[2],
            "the top tension",
            ("time (s)", "tension (kN)"),
            &tension,
            &[],
            None,
        )
        .map_err(&perr)?;
        lines_panel(
            &areas[3],
            &format!(
                "uplift–repenetration episodes (uplift of at least 0.1 % D) per point; lay factor {:.2}",
                s.lay_factor
            ),
            ("KP (m)", "episodes"),
            &[Labelled {
                points: laid
                    .iter()
                    .map(|&g| (n.kp[g], f64::from(n.episodes[g])))
                    .collect(),
                colour: RGBColor(20, 90, 200),
                label: "",
            }],
            &[],
            Some(kp_range),
            false,
        )
        .map_err(&perr)?;
    }
    write_image(path, &rgb, size)
}
