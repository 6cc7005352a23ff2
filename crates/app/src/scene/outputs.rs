//! What a run measures and checks: the `[[gauge]]` tables, and the tables of the checks a run
//! applies — `[fatigue]`, `[design_check]`, `[extremes]` — checked and turned into the gauges and
//! the specs of [`crate::checks`] that [`super::dynamic`] puts in the `DynamicSpec`.

use super::checks::{positive, Site};
use super::invalid;
use super::tables::*;
use crate::checks::design::{safety_class_factor, strain_resistance_factor, Code, DesignSpec};
use crate::checks::extremes::{Channel, ExtremesSpec, Settings, Source, Tail};
use crate::checks::fatigue::sn::SnCurve;
use crate::checks::fatigue::stress::{Fibre, PipeSection};
use crate::checks::fatigue::FatigueSpec;
use crate::error::SceneError;

/// A gauge: bending moment and tension recorded at an arc length (interpolated between nodes).
#[derive(Debug, Clone, PartialEq)]
pub struct Gauge {
    /// Its name.
    pub name: String,
    /// Arc length from the top, m (for a `midway_touchdown_lift` gauge, set after the statics).
    pub arc: f64,
    /// If given: the gauge lies midway (in arc length) between the static touchdown point and the one
    /// with the top raised by this much, m.
    pub midway_touchdown_lift: Option<f64>,
}

/// `[[gauge]]`: distinct names, each at an arc length or midway between touchdown points.
pub(super) fn gauges_of(
    file: &str,
    raw: &RiserFile,
    length: f64,
) -> Result<Vec<Gauge>, SceneError> {
    let mut gauges = Vec::new();
    for (i, g) in raw.gauge.iter().enumerate() {
        if g.name.is_empty() || g.name.contains('/') {
            return Err(invalid(
                file,
                format!("gauge[{i}].name"),
                "a non-empty name without '/'",
            ));
        }
        if let Some(j) = raw.gauge[..i].iter().position(|o| o.name == g.name) {
            return Err(invalid(
                file,
                format!("gauge[{i}].name"),
                format!(
                    "a name no other gauge has (gauge[{j}] is also \"{}\")",
                    g.name
                ),
            ));
        }
        match (g.arc, g.midway_touchdown_lift) {
            (Some(arc), None) => {
                if !(0.0..=length).contains(&arc) {
                    return Err(invalid(
                        file,
                        format!("gauge[{i}].arc"),
                        format!("an arc length from the top within [0, {length}] m"),
                    ));
                }
                gauges.push(Gauge {
                    name: g.name.clone(),
                    arc,
                    midway_touchdown_lift: None,
                });
            }
            (None, Some(lift)) => {
                positive(
                    file,
                    &format!("gauge[{i}].midway_touchdown_lift"),
                    lift,
                    "a lift of the top in m",
                )?;
                gauges.push(Gauge {
                    name: g.name.clone(),
                    arc: f64::NAN,
                    midway_touchdown_lift: Some(lift),
                });
            }
            _ => {
                return Err(invalid(
                    file,
                    format!("gauge[{i}]"),
                    "exactly one of `arc` (m) or `midway_touchdown_lift` (m)",
                ))
            }
        }
    }
    Ok(gauges)
}

/// An S-N curve as written at `key` (a DNV-RP-C203 name or a table) → the curve and its name.
pub(super) fn sn_curve_of(
    file: &str,
    key: &str,
    sn: &SnKey,
) -> Result<(SnCurve, String), SceneError> {
    Ok(match sn {
        SnKey::Name(n) => (
            SnCurve::dnv(n).ok_or_else(|| {
                invalid(
                    file,
                    key,
                    format!(
                        "one of {} or a table {{ m1, log_a1, m2, log_a2, knee_cycles }}, got \"{n}\"",
                        crate::checks::fatigue::sn::NAMES.join(", ")
                    ),
                )
            })?,
            n.clone(),
        ),
        SnKey::Table(c) => {
            for (k, v) in [("m1", c.m1), ("log_a1", c.log_a1)] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(invalid(file, format!("{key}.{k}"), "a number > 0"));
                }
            }
            let lower = match (c.m2, c.log_a2, c.knee_cycles) {
                (Some(m2), Some(a2), Some(knee)) if m2 > 0.0 && a2 > 0.0 && knee > 0.0 => {
                    Some((m2, a2, knee))
                }
                (None, None, None) => None,
                _ => {
                    return Err(invalid(
                        file,
                        key,
                        "m2, log_a2 and knee_cycles all > 0, or none of them (a single slope)",
                    ))
                }
            };
            (
                SnCurve {
                    m1: c.m1,
                    log_a1: c.log_a1,
                    lower: lower.map(|(m2, a2, _)| (m2, a2)),
                    knee_cycles: lower.map(|(_, _, k)| k),
                    thickness_exponent: c.thickness_exponent,
                },
                "user".to_string(),
            )
        }
    })
}

/// `[fatigue]` → what the fatigue observer counts (see `docs/scene.md`).
pub(super) fn fatigue_of(
    file: &str,
    raw: &RiserFile,
    t: &FatigueTable,
    d: &DynamicTable,
    site: Site,
) -> Result<FatigueSpec, SceneError> {
    let l = &raw.line;
    let wall = l.wall.ok_or_else(|| {
        invalid(
            file,
            "line.wall",
            "the wall thickness in m (fatigue needs the section's stresses)",
        )
    })?;
    let (curve, curve_name) = sn_curve_of(file, "fatigue.sn_curve", &t.sn_curve)?;
    if !(t.scf.is_finite() && t.scf >= 1.0) {
        return Err(invalid(
            file,
            "fatigue.scf",
            format!("a stress concentration factor >= 1, got {}", t.scf),
        ));
    }
    let mut fibres = Vec::new();
    for (i, f) in t.fibres.iter().enumerate() {
        let fib = match f.as_str() {
            "outer" => Fibre::Outer,
            "inner" => Fibre::Inner,
            other => {
                return Err(invalid(
                    file,
                    format!("fatigue.fibres[{i}]"),
                    format!("\"outer\" or \"inner\", got \"{other}\""),
                ))
            }
        };
        if !fibres.contains(&fib) {
            fibres.push(fib);
        }
    }
    if fibres.is_empty() {
        return Err(invalid(
            file,
            "fatigue.fibres",
            "at least one of \"outer\", \"inner\"",
        ));
    }
    if let Some(f) = t.design_factor {
        positive(file, "fatigue.design_factor", f, "a design fatigue factor")?;
    }
    let start = t.start.unwrap_or(d.envelope_start);
    if !(start.is_finite() && start >= 0.0 && start < d.duration) {
        return Err(invalid(file, "fatigue.start", "a time in [0, duration) s"));
    }
    let contents_density = t.contents_density.or(l.contents_density).ok_or_else(|| {
        invalid(
            file,
            "fatigue.contents_density",
            "the contents density in kg/m³ (here or in [line]): the wall tension needs it",
        )
    })?;
    if !(contents_density.is_finite() && contents_density >= 0.0) {
        return Err(invalid(
            file,
            "fatigue.contents_density",
            "a density >= 0 kg/m³",
        ));
    }
    if !t.internal_pressure.is_finite() {
        return Err(invalid(
            file,
            "fatigue.internal_pressure",
            "a pressure in Pa",
        ));
    }
    Ok(FatigueSpec {
        curve,
        curve_name,
        scf: t.scf,
        fibres,
        design_factor: t.design_factor,
        start,
        section: PipeSection {
            od: l.od,
            wall,
            contents_density,
            internal_pressure: t.internal_pressure,
            water_density: site.water_density,
            gravity: site.gravity,
            water_depth: site.water_depth,
        },
        nodes: Vec::new(),
    })
}

/// `[design_check]` → the check's parameters (see `docs/scene.md`); its sections are checked with
/// the line's (`riser.rs`).
pub(super) fn design_check_of(
    file: &str,
    raw: &RiserFile,
    t: &DesignCheckTable,
    d: &DynamicTable,
) -> Result<DesignSpec, SceneError> {
    let code = match t.code.as_str() {
        "dnv-st-f201" => Code::DnvStF201,
        "dnv-st-f101" => Code::DnvStF101,
        "api-std-2rd" => Code::ApiStd2rd,
        other => {
            return Err(invalid(
                file,
                "design_check.code",
                format!("\"dnv-st-f201\", \"dnv-st-f101\" or \"api-std-2rd\", got \"{other}\""),
            ))
        }
    };
    positive(file, "design_check.smys", t.smys, "a yield strength in Pa")?;
    positive(
        file,
        "design_check.smts",
        t.smts,
        "a tensile strength in Pa",
    )?;
    if t.smts < t.smys {
        return Err(invalid(
            file,
            "design_check.smts",
            format!(
                "a tensile strength no less than smys ({} Pa), got {} Pa",
                t.smys, t.smts
            ),
        ));
    }
    if !(t.internal_pressure.is_finite() && t.internal_pressure >= 0.0) {
        return Err(invalid(
            file,
            "design_check.internal_pressure",
            "a pressure >= 0 Pa at the still water level",
        ));
    }
    if !(t.corrosion_allowance.is_finite() && t.corrosion_allowance >= 0.0) {
        return Err(invalid(
            file,
            "design_check.corrosion_allowance",
            "a thickness >= 0 m",
        ));
    }
    let class = t.safety_class.as_deref().unwrap_or("normal");
    let gamma_sc = safety_class_factor(class).ok_or_else(|| {
        invalid(
            file,
            "design_check.safety_class",
            format!("\"low\", \"normal\" (or \"medium\") or \"high\", got \"{class}\""),
        )
    })?;
    let lf = t.load_factors.unwrap_or(LoadFactorsTable {
        functional: 1.1,
        environmental: 1.3,
    });
    positive(
        file,
        "design_check.load_factors.functional",
        lf.functional,
        "a load factor",
    )?;
    positive(
        file,
        "design_check.load_factors.environmental",
        lf.environmental,
        "a load factor",
    )?;
    let factor = |key: &str, v: Option<f64>, default: f64, what: &str| {
        let v = v.unwrap_or(default);
        positive(file, &format!("design_check.{key}"), v, what).map(|_| v)
    };
    let design_factor = factor("design_factor", t.design_factor, 0.8, "a design factor")?;
    let alpha_u = factor(
        "material_strength_factor",
        t.material_strength_factor,
        0.96,
        "a material strength factor",
    )?;
    let alpha_fab = factor(
        "fabrication_factor",
        t.fabrication_factor,
        1.0,
        "a fabrication factor",
    )?;
    let ovality = factor("ovality", t.ovality, 0.005, "an ovality")?;
    let youngs_modulus = factor(
        "youngs_modulus",
        t.youngs_modulus.or(raw.line.youngs_modulus),
        207e9,
        "a Young's modulus in Pa",
    )?;
    let start = t.start.unwrap_or(d.envelope_start);
    if !(start.is_finite() && start >= 0.0 && start < d.duration) {
        return Err(invalid(
            file,
            "design_check.start",
            "a time in [0, duration) s",
        ));
    }
    let gamma_c = factor(
        "condition_factor",
        t.condition_factor,
        1.0,
        "a condition factor",
    )?;
    let gamma_eps = factor(
        "strain_factor",
        t.strain_factor,
        strain_resistance_factor(class).unwrap_or(2.5),
        "a strain resistance factor",
    )?;
    let alpha_h = factor(
        "yield_to_tensile_max",
        t.yield_to_tensile_max,
        0.92,
        "a yield to tensile strength ratio",
    )?;
    Ok(DesignSpec {
        code,
        gamma_c,
        gamma_eps,
        alpha_h,
        smys: t.smys,
        smts: t.smts,
        internal_pressure: t.internal_pressure,
        corrosion_allowance: t.corrosion_allowance,
        start,
        gamma_sc,
        gamma_m: 1.15,
        gamma_f: lf.functional,
        gamma_e: lf.environmental,
        alpha_u,
        alpha_fab,
        ovality,
        youngs_modulus,
        poisson: 0.3,
        design_factor,
    })
}

/// `[extremes]` → the channels and settings of the extreme-value analysis (see `docs/scene.md`).
pub(super) fn extremes_of(
    file: &str,
    raw: &RiserFile,
    t: &ExtremesTable,
    d: &DynamicTable,
    gauges: &[Gauge],
) -> Result<ExtremesSpec, SceneError> {
    let names = t.channels.clone().unwrap_or_else(|| {
        let mut v: Vec<String> = ["top_tension", "least_tension", "sag_moment"]
            .map(String::from)
            .to_vec();
        if raw.design_check.is_some() {
            v.push("utilisation".into());
        }
        v
    });
    if names.is_empty() {
        return Err(invalid(file, "extremes.channels", "at least one channel"));
    }
    let mut channels = Vec::new();
    for (i, name) in names.iter().enumerate() {
        let key = format!("extremes.channels[{i}]");
        let (source, tail) = match name.as_str() {
            "top_tension" => (Source::TopTension, Tail::Max),
            "least_tension" => (Source::LeastTension, Tail::Min),
            "sag_moment" => (Source::SagMoment, Tail::Min),
            "utilisation" => {
                if raw.design_check.is_none() {
                    return Err(invalid(
                        file,
                        key,
                        "a [design_check] table as well (the utilisation is the check's)",
                    ));
                }
                (Source::Utilisation, Tail::Max)
            }
            other => {
                let gauge = other.strip_prefix("gauge:").ok_or_else(|| {
                    invalid(
                        file,
                        &key,
                        format!("top_tension, least_tension, sag_moment, utilisation or gauge:NAME[:max], got \"{other}\""),
                    )
                })?;
                let (g, tail) = match gauge.strip_suffix(":max") {
                    Some(g) => (g, Tail::Max),
                    None => (gauge.strip_suffix(":min").unwrap_or(gauge), Tail::Min),
                };
                let k = gauges.iter().position(|x| x.name == g).ok_or_else(|| {
                    invalid(
                        file,
                        &key,
                        format!(
                            "a gauge of the scene ({}), got \"{g}\"",
                            if gauges.is_empty() {
                                "it has none".to_string()
                            } else {
                                gauges
                                    .iter()
                                    .map(|x| x.name.as_str())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            }
                        ),
                    )
                })?;
                (Source::GaugeMoment(k), tail)
            }
        };
        if channels.iter().any(|c: &Channel| c.name == *name) {
            return Err(invalid(
                file,
                key,
                format!("a channel not already listed, got \"{name}\" twice"),
            ));
        }
        channels.push(Channel {
            name: name.clone(),
            source,
            tail,
        });
    }
    let start = t.start.unwrap_or(d.envelope_start);
    if !(start.is_finite() && start >= 0.0 && start < d.duration) {
        return Err(invalid(file, "extremes.start", "a time in [0, duration) s"));
    }
    let defaults = Settings::default();
    let target = t.target_duration.unwrap_or(defaults.target);
    positive(file, "extremes.target_duration", target, "a duration in s")?;
    let quantile = t.quantile.unwrap_or(defaults.quantile);
    if !(quantile > 0.0 && quantile < 1.0) {
        return Err(invalid(
            file,
            "extremes.quantile",
            "a probability of non-exceedance in (0, 1), e.g. 0.9",
        ));
    }
    let block = t.block.unwrap_or(defaults.block);
    positive(file, "extremes.block", block, "a block length in s")?;
    if block < d.time_step {
        return Err(invalid(
            file,
            "extremes.block",
            "a block no shorter than dynamic.time_step",
        ));
    }
    Ok(ExtremesSpec {
        channels,
        start,
        settings: Settings {
            target,
            quantile,
            block,
        },
    })
}
