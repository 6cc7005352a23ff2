//! The sea of a scene: `[hydrodynamics]`, `[current]`, `[waves]` and `[vessel]`, checked and turned
//! into the hydrodynamics, the wave train and the vessel.

use catena_fe::environment::Hydro;
use catena_fe::vessel::{RaoTable, Vessel};
use catena_fe::waves::{Direction, Waves};

use super::checks::Site;
use super::tables::*;
use super::{invalid, required, Resolver};
use crate::error::SceneError;

/// `[hydrodynamics]` and `[current]`: the sea water's hydrodynamics, if the scene has them.
pub(super) fn hydro_of(
    file: &str,
    raw: &RiserFile,
    water_density: f64,
) -> Result<Option<Hydro>, SceneError> {
    let hydro = match (&raw.hydrodynamics, &raw.current) {
        (Some(h), cur) => {
            for (k, v) in [
                ("hydrodynamics.cd_normal", h.cd_normal),
                ("hydrodynamics.cd_axial", h.cd_axial),
                ("hydrodynamics.ca_normal", h.ca_normal),
            ] {
                if !(v >= 0.0 && v.is_finite()) {
                    return Err(invalid(file, k, format!("a coefficient >= 0, got {v}")));
                }
            }
            let mut current: Vec<(f64, f64)> = Vec::new();
            if let Some(c) = cur {
                if c.profile.is_empty() {
                    return Err(invalid(
                        file,
                        "current.profile",
                        "at least one [z, speed] pair",
                    ));
                }
                for (i, p) in c.profile.iter().enumerate() {
                    if !(p[0].is_finite() && p[1].is_finite())
                        || current.last().is_some_and(|l| p[0] <= l.0)
                    {
                        return Err(invalid(
                            file,
                            format!("current.profile[{i}]"),
                            "[z (m, increasing), speed (m/s)] pairs",
                        ));
                    }
                    current.push((p[0], p[1]));
                }
            }
            Some(Hydro {
                water_density,
                cd_normal: h.cd_normal,
                cd_axial: h.cd_axial,
                ca_normal: h.ca_normal,
                current,
            })
        }
        (None, Some(_)) => {
            return Err(invalid(
                file,
                "current",
                "a [hydrodynamics] table as well (the current acts through drag)",
            ))
        }
        (None, None) => None,
    };
    Ok(hydro)
}

/// The default kinematics samples per peak (or regular) period: `h = T/40`.
pub const KINEMATICS_PER_PERIOD: f64 = 40.0;

/// `[waves]` → the wave train (see `docs/scene.md`).
pub(super) fn waves_of(
    file: &str,
    w: &WavesTable,
    site: Site,
    time_step: f64,
) -> Result<Waves, SceneError> {
    let direction = match w.direction.as_str() {
        "+x" => Direction::PlusX,
        "-x" => Direction::MinusX,
        other => {
            return Err(invalid(
                file,
                "waves.direction",
                format!("\"+x\" (from the anchor towards the hang-off) or \"-x\", got \"{other}\""),
            ))
        }
    };
    let stray = |keys: &[(&str, bool)], kind: &str| -> Result<(), SceneError> {
        for (k, present) in keys {
            if *present {
                return Err(invalid(
                    file,
                    format!("waves.{k}"),
                    format!("no `{k}` with kind = \"{kind}\""),
                ));
            }
        }
        Ok(())
    };
    let bad = |e: catena_fe::waves::WaveError| {
        let catena_fe::waves::WaveError::Bad { key, expected, .. } = &e;
        invalid(file, format!("waves.{key}"), format!("{expected} ({e})"))
    };
    let (waves, natural) = match w.kind {
        WaveKind::Jonswap => {
            stray(
                &[
                    ("height", w.height.is_some()),
                    ("period", w.period.is_some()),
                    ("phase_deg", w.phase_deg.is_some()),
                ],
                "jonswap",
            )?;
            let hs = required(file, "waves.hs", w.hs, "the significant wave height in m")?;
            let tp = required(file, "waves.tp", w.tp, "the peak period in s")?;
            let seed = required(
                file,
                "waves.seed",
                w.seed,
                "an integer seed (the same seed gives the same storm)",
            )?;
            let waves = Waves::jonswap(
                hs,
                tp,
                w.gamma,
                seed,
                w.components.unwrap_or(400),
                direction,
                site.water_depth,
                site.gravity,
                0.0,
            )
            .map_err(bad)?;
            (waves, tp)
        }
        WaveKind::Airy => {
            stray(
                &[
                    ("hs", w.hs.is_some()),
                    ("tp", w.tp.is_some()),
                    ("gamma", w.gamma.is_some()),
                    ("seed", w.seed.is_some()),
                    ("components", w.components.is_some()),
                ],
                "airy",
            )?;
            let height = required(file, "waves.height", w.height, "the wave height in m")?;
            let period = required(file, "waves.period", w.period, "the wave period in s")?;
            let mut waves = Waves::regular(
                height,
                period,
                direction,
                site.water_depth,
                site.gravity,
                0.0,
            )
            .map_err(bad)?;
            if let Some(p) = w.phase_deg {
                if !p.is_finite() {
                    return Err(invalid(
                        file,
                        "waves.phase_deg",
                        "a finite phase in degrees",
                    ));
                }
                waves.components[0].phase = p.to_radians();
            }
            (waves, period)
        }
    };
    let ramp = w.ramp.unwrap_or(2.0 * natural);
    if !(ramp.is_finite() && ramp >= 0.0) {
        return Err(invalid(
            file,
            "waves.ramp",
            format!("a ramp duration >= 0 s, got {ramp}"),
        ));
    }
    let mut waves = waves;
    waves.ramp = ramp;
    // The kinematics' time grid (`catena_fe::wave_sampling`): by default a fortieth of the peak
    // (or regular) period, unless that is under two steps (sampling would then save little).
    waves.kinematics_interval = match w.kinematics_interval {
        None if natural / KINEMATICS_PER_PERIOD >= 2.0 * time_step => {
            natural / KINEMATICS_PER_PERIOD
        }
        None => 0.0,
        Some(0.0) => 0.0,
        Some(h) if h.is_finite() && h >= time_step => h,
        Some(h) => {
            return Err(invalid(
                file,
                "waves.kinematics_interval",
                format!(
                    "0 (the kinematics at every step) or an interval in s >= dynamic.time_step \
                     ({time_step} s), got {h}"
                ),
            ))
        }
    };
    Ok(waves)
}

/// `[vessel]` → the vessel on the wave train: the RAO table read through the resolver, the RAO
/// origin at `top_x − Δx`.
pub(super) fn vessel_of(
    file: &str,
    v: &VesselTable,
    waves: &Waves,
    site: Site,
    files: &dyn Resolver,
) -> Result<Vessel, SceneError> {
    let text = files
        .read(&v.rao)
        .map_err(|e| invalid(file, "vessel.rao", format!("a readable RAO table ({e})")))?;
    let table = RaoTable::parse_csv(&text).map_err(|e| {
        invalid(
            file,
            "vessel.rao",
            format!(
                "an RAO table in the format of cases/scr1000/semi-rao.csv ({}: {e})",
                v.rao
            ),
        )
    })?;
    let [dx, dz] = v.hangoff_offset;
    if !(dx.is_finite() && dz.is_finite()) {
        return Err(invalid(
            file,
            "vessel.hangoff_offset",
            "[x, z] of the hang-off relative to the RAO origin, in m",
        ));
    }
    Ok(Vessel::new(table, site.top_x - dx, [dx, dz], waves))
}
