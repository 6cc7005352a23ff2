//! The dynamic part of a scene: `[dynamic]`, the top motion, gauges, structural damping and
//! fatigue, checked and turned into a [`DynamicSpec`].

use catena_fe::dynamics::{DynamicSettings, Scheme};
use catena_fe::environment::{Environment, Hydro};
use catena_fe::motion::TopMotion;
use catena_fe::vessel::Vessel;

use super::checks::{positive, Site};
use super::sea::{vessel_of, waves_of};
use super::tables::*;
use super::{invalid, Resolver};
use crate::checks::design::DesignSpec;
use crate::checks::extremes::ExtremesSpec;
use crate::checks::fatigue::stress::PipeSection;
use crate::checks::fatigue::FatigueSpec;
use crate::error::SceneError;

use super::outputs::Gauge;
use super::outputs::{design_check_of, extremes_of, fatigue_of, gauges_of};

/// Records a run keeps at most when its scene gives no `dynamic.output_interval`.
pub const DEFAULT_MAX_RECORDS: f64 = 10_000.0;

/// The dynamic part of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicSpec {
    /// Solver settings.
    pub settings: DynamicSettings,
    /// The environment (hydrodynamics and current), each part only if the scene has it.
    pub environment: Environment,
    /// The top end's prescribed motion, if any.
    pub motion: Option<TopMotion>,
    /// The vessel carrying the top end (`[vessel]`), if any.
    pub vessel: Option<Vessel>,
    /// Stiffness-proportional structural damping `β = ζ·T/π` (s), if `[structural_damping]`.
    pub structural_damping: Option<f64>,
    /// Fatigue counting (`[fatigue]`), if any.
    pub fatigue: Option<FatigueSpec>,
    /// The strength check (`[design_check]`), if any.
    pub design_check: Option<DesignSpec>,
    /// Short-term extremes (`[extremes]`), if any.
    pub extremes: Option<ExtremesSpec>,
    /// The pipe's section for wall tension and stress range graphs: `[fatigue]`'s, or from
    /// `line.wall` and `line.contents_density` (no internal pressure) when both are given.
    pub section: Option<PipeSection>,
    /// A line of sections: each node's pipe section (see `scene::sections::node_sections`); empty:
    /// `section` at every node.
    pub node_sections: Vec<PipeSection>,
    /// Duration, s.
    pub duration: f64,
    /// Time step, s.
    pub dt: f64,
    /// Output every this many steps.
    pub output_every: usize,
    /// Envelopes are taken from this time on, s.
    pub envelope_start: f64,
    /// Gauges.
    pub gauges: Vec<Gauge>,
}

pub(super) fn dynamic_spec(
    file: &str,
    raw: &RiserFile,
    d: &DynamicTable,
    hydro: Option<Hydro>,
    site: Site,
    files: &dyn Resolver,
) -> Result<DynamicSpec, SceneError> {
    let length = site.length;
    positive(file, "dynamic.duration", d.duration, "a duration in s")?;
    positive(file, "dynamic.time_step", d.time_step, "a time step in s")?;
    if d.time_step > d.duration {
        return Err(invalid(
            file,
            "dynamic.time_step",
            "a time step no longer than the duration",
        ));
    }
    // Default: every step, up to DEFAULT_MAX_RECORDS records; beyond that the smallest whole
    // multiple of the time step that keeps the run within it (a 3-hour storm at 0.05 s would
    // otherwise write every one of its 216 000 steps: gigabytes).
    let out = d.output_interval.unwrap_or_else(|| {
        let steps = (d.duration / d.time_step).ceil();
        d.time_step * (steps / DEFAULT_MAX_RECORDS).ceil().max(1.0)
    });
    positive(file, "dynamic.output_interval", out, "an interval in s")?;
    let every = (out / d.time_step).round();
    if every < 1.0 || ((every * d.time_step) - out).abs() > 1e-9 * out {
        return Err(invalid(
            file,
            "dynamic.output_interval",
            "a whole multiple of dynamic.time_step",
        ));
    }
    let scheme = scheme_of(file, d)?;
    positive(
        file,
        "dynamic.tolerance",
        d.tolerance,
        "a relative tolerance",
    )?;
    let motion = motion_of(file, raw, files)?;
    let gauges = gauges_of(file, raw, length)?;
    if !(d.envelope_start >= 0.0 && d.envelope_start < d.duration) {
        return Err(invalid(
            file,
            "dynamic.envelope_start",
            "a time in [0, duration) s",
        ));
    }
    let waves = match &raw.waves {
        Some(w) => Some(waves_of(file, w, site, d.time_step)?),
        None => None,
    };
    let vessel = match (&raw.vessel, &waves) {
        (Some(v), Some(w)) => Some(vessel_of(file, v, w, site, files)?),
        (Some(_), None) => {
            return Err(invalid(
                file,
                "vessel",
                "a [waves] table as well (the vessel moves with the waves)",
            ))
        }
        (None, _) => None,
    };
    let structural_damping = structural_damping_of(file, raw)?;
    let fatigue = match &raw.fatigue {
        Some(t) => Some(fatigue_of(file, raw, t, d, site)?),
        None => None,
    };
    let design_check = match &raw.design_check {
        Some(t) => Some(design_check_of(file, raw, t, d)?),
        None => None,
    };
    let extremes = match &raw.extremes {
        Some(t) => Some(extremes_of(file, raw, t, d, &gauges)?),
        None => None,
    };
    let l = &raw.line;
    let section = fatigue
        .as_ref()
        .map(|f| f.section)
        .or(match (l.wall, l.contents_density) {
            (Some(wall), Some(contents_density)) => Some(PipeSection {
                od: l.od,
                wall,
                contents_density,
                internal_pressure: 0.0,
                water_density: site.water_density,
                gravity: site.gravity,
                water_depth: site.water_depth,
            }),
            _ => None,
        });
    Ok(DynamicSpec {
        fatigue,
        design_check,
        extremes,
        section,
        node_sections: Vec::new(),
        structural_damping,
        environment: Environment {
            hydro,
            waves,
            water_level: site.water_depth,
        },
        motion,
        vessel,
        settings: DynamicSettings {
            scheme,
            tol: d.tolerance,
            max_iter: d.max_iterations,
            max_cuts: d.max_step_cuts,
        },
        duration: d.duration,
        dt: d.time_step,
        output_every: every as usize,
        envelope_start: d.envelope_start,
        gauges,
    })
}

/// `dynamic.scheme` with its α, or β and γ.
fn scheme_of(file: &str, d: &DynamicTable) -> Result<Scheme, SceneError> {
    Ok(match d.scheme {
        SchemeKey::Hht => {
            if d.beta.is_some() || d.gamma.is_some() {
                return Err(invalid(
                    file,
                    "dynamic.beta",
                    "no beta or gamma with scheme = \"hht\" (they follow from alpha)",
                ));
            }
            let alpha = d.alpha.unwrap_or(-0.1);
            if !(-1.0 / 3.0..=0.0).contains(&alpha) {
                return Err(invalid(
                    file,
                    "dynamic.alpha",
                    format!("-1/3 <= alpha <= 0 (Hilber's convention), got {alpha}"),
                ));
            }
            Scheme::Hht { alpha }
        }
        SchemeKey::Newmark => {
            if d.alpha.is_some() {
                return Err(invalid(
                    file,
                    "dynamic.alpha",
                    "no alpha with scheme = \"newmark\"",
                ));
            }
            let beta = d.beta.unwrap_or(0.25);
            let gamma = d.gamma.unwrap_or(0.5);
            if !(beta > 0.0 && beta <= 0.5) {
                return Err(invalid(
                    file,
                    "dynamic.beta",
                    format!("0 < beta <= 0.5, got {beta}"),
                ));
            }
            if !(0.5..=1.0).contains(&gamma) {
                return Err(invalid(
                    file,
                    "dynamic.gamma",
                    format!("0.5 <= gamma <= 1, got {gamma}"),
                ));
            }
            Scheme::Newmark { beta, gamma }
        }
    })
}

/// `[motion]`: exactly one of staged velocities, a harmonic motion or a series read through the
/// resolver.
fn motion_of(
    file: &str,
    raw: &RiserFile,
    files: &dyn Resolver,
) -> Result<Option<TopMotion>, SceneError> {
    Ok(match &raw.motion {
        None => None,
        Some(m) => {
            let count = [m.staged.is_some(), m.harmonic.is_some(), m.series.is_some()]
                .iter()
                .filter(|b| **b)
                .count();
            if count != 1 {
                return Err(invalid(
                    file,
                    "motion",
                    "exactly one of [motion.staged], [motion.harmonic], [motion.series]",
                ));
            }
            if let Some(st) = &m.staged {
                if st.stages.is_empty() {
                    return Err(invalid(file, "motion.staged.stages", "at least one stage"));
                }
                for (i, s) in st.stages.iter().enumerate() {
                    if !(s.duration >= 0.0
                        && s.duration.is_finite()
                        && s.vx.is_finite()
                        && s.vz.is_finite())
                    {
                        return Err(invalid(
                            file,
                            format!("motion.staged.stages[{i}]"),
                            "a duration >= 0 s and finite velocities in m/s",
                        ));
                    }
                }
                Some(TopMotion::Staged(
                    st.stages.iter().map(|s| (s.duration, s.vx, s.vz)).collect(),
                ))
            } else if let Some(h) = &m.harmonic {
                positive(file, "motion.harmonic.period", h.period, "a period in s")?;
                if h.ramp.is_nan() || h.ramp < 0.0 {
                    return Err(invalid(
                        file,
                        "motion.harmonic.ramp",
                        "a ramp duration >= 0 s",
                    ));
                }
                Some(TopMotion::Harmonic {
                    surge: h.surge,
                    heave: h.heave,
                    period: h.period,
                    phase: h.phase_deg.to_radians(),
                    ramp: h.ramp,
                })
            } else if let Some(se) = &m.series {
                let text = files.read(&se.file).map_err(|e| {
                    invalid(
                        file,
                        "motion.series.file",
                        format!("a readable CSV file ({e})"),
                    )
                })?;
                let path = &se.file;
                let mut pts = Vec::new();
                for (ln, line) in text.lines().enumerate().skip(1) {
                    if line.trim().is_empty() {
                        continue;
                    }
                    let mut v = Vec::with_capacity(3);
                    for (c, cell) in line.split(',').enumerate() {
                        match cell.trim().parse::<f64>() {
                            Ok(x) if x.is_finite() && x.abs() <= super::MAX_MAGNITUDE => v.push(x),
                            _ => {
                                return Err(invalid(
                                    file,
                                    "motion.series.file",
                                    format!(
                                        "{path}: line {}, column {}: a finite number (got \"{}\")",
                                        ln + 1,
                                        c + 1,
                                        cell.trim()
                                    ),
                                ))
                            }
                        }
                    }
                    if v.len() != 3 || pts.last().is_some_and(|p: &(f64, f64, f64)| v[0] <= p.0) {
                        return Err(invalid(
                            file,
                            "motion.series.file",
                            format!(
                                "{}: line {}: three numbers t, dx, dz with t increasing",
                                path,
                                ln + 1
                            ),
                        ));
                    }
                    pts.push((v[0], v[1], v[2]));
                }
                if pts.is_empty() {
                    return Err(invalid(
                        file,
                        "motion.series.file",
                        format!("{}: a header line and at least one row t, dx, dz", path),
                    ));
                }
                Some(TopMotion::Series(pts))
            } else {
                None
            }
        }
    })
}

/// `[structural_damping]` → `β = ζ·T/π` (s), if the scene has it.
fn structural_damping_of(file: &str, raw: &RiserFile) -> Result<Option<f64>, SceneError> {
    Ok(match &raw.structural_damping {
        Some(t) => {
            if !(t.critical_percent.is_finite()
                && t.critical_percent > 0.0
                && t.critical_percent <= 100.0)
            {
                return Err(invalid(
                    file,
                    "structural_damping.critical_percent",
                    format!(
                        "a percentage of critical damping in (0, 100], got {}",
                        t.critical_percent
                    ),
                ));
            }
            positive(file, "structural_damping.period", t.period, "a period in s")?;
            Some(t.critical_percent / 100.0 * t.period / std::f64::consts::PI)
        }
        None => None,
    })
}
