//! The `[seabed]` table, shared by every kind of case.
//!
//! | key | unit | default | meaning |
//! |---|---|---|---|
//! | `model` | — | required | `"linear"` or `"randolph-quiggin"` |
//! | `diameter` | m | required in soil tests; the riser's outer diameter in riser scenes | contact diameter `D` |
//! | `stiffness` | N/m/m² | required (linear) | stiffness per unit contact area, `P = k·D·z` |
//! | `damping` | N·s/m/m² | 0 (linear) | damping per unit contact area |
//! | `su0` | Pa | required (R–Q) | undrained shear strength at the mudline |
//! | `su_gradient` | Pa/m | required (R–Q) | strength gradient |
//! | `a`, `b` | — | required (R–Q) | bearing factor `Nc = a·(z/D)^b` |
//! | `k_max` | — | required (R–Q) | normalised maximum stiffness |
//! | `f_suc` | — | required (R–Q) | suction ratio, in [0, 1] |
//! | `lambda_suc` | — | required (R–Q) | suction decay distance |
//! | `lambda_rep` | — | required (R–Q) | repenetration offset |
//! | `liftoff_smoothing` | — | false (R–Q) | cap uplift `P` by `P_IP` |
//! | `f_b`, `soil_density`, `water_density` | —, kg/m³, kg/m³ | none | soil buoyancy (eq. 15): all three or none |
//! | `profile` | [[m, m], …] | flat at z = 0 | the mudline's height `[x, z]` along the route, piecewise linear, constant beyond the ends (riser scenes) |
//! | `[[seabed.zone]]` `from_x`, `to_x` and any law key | m, m, … | none | a stretch of the route `[from_x, to_x)` (riser scenes) whose law keys override the table's; zones may not overlap |
//! | `[seabed.degradation]` `sensitivity`, `ductility`, `regain_t50`, `regain_exponent` | —, D, s, — | none | cyclic strength degradation (R–Q): sensitivity S_t ≥ 1, ductility ξ95 > 0 in pipe diameters of accumulated plastic displacement; regain at rest (both or neither): t50 > 0, m > 0 |
//! | `[seabed.rate_suction]` `drained_ratio`, `cv`, `v50`, `exponent` | —, m²/s, —, — | none | a suction ratio that depends on the uplift velocity (R–Q): `f(V) = f_dr + (f_suc − f_dr)/(1 + (V50/V)^c)`, `V = v·D/cv` |
//! | `[seabed.friction]` `axial`, `mobilisation` | —, m | none | axial friction (riser scenes, dynamics only): Coulomb μ on the normal seabed force, and the displacement δ > 0 that mobilises it |

use catena_seabed::law::{Law, Seabed};
use catena_seabed::{
    Degradation, LinearSeabed, ParamError, RandolphQuiggin, RateSuction, Regain, RqParams,
    SoilBuoyancy,
};
use serde::Deserialize;

use super::{invalid, required};
use crate::error::SceneError;

/// The seabed model a scene chose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SeabedModel {
    /// Linear elastic, tensionless.
    Linear,
    /// Randolph & Quiggin (2009).
    RandolphQuiggin,
}

/// The `[seabed]` table as written.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SeabedTable {
    pub model: Option<SeabedModel>,
    pub diameter: Option<f64>,
    pub stiffness: Option<f64>,
    pub damping: Option<f64>,
    pub su0: Option<f64>,
    pub su_gradient: Option<f64>,
    pub a: Option<f64>,
    pub b: Option<f64>,
    pub k_max: Option<f64>,
    pub f_suc: Option<f64>,
    pub lambda_suc: Option<f64>,
    pub lambda_rep: Option<f64>,
    pub liftoff_smoothing: Option<bool>,
    pub f_b: Option<f64>,
    pub soil_density: Option<f64>,
    pub water_density: Option<f64>,
    pub friction: Option<FrictionTable>,
    pub degradation: Option<DegradationTable>,
    pub rate_suction: Option<RateSuctionTable>,
    #[serde(default)]
    pub zone: Vec<ZoneTable>,
    pub profile: Option<Vec<Vec<f64>>>,
}

/// `[[seabed.zone]]` as written: a stretch of the route `[from_x, to_x)` whose law keys override the
/// `[seabed]` table's (the law itself, its diameter and buoyancy stay the default's).
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct ZoneTable {
    pub from_x: f64,
    pub to_x: f64,
    pub stiffness: Option<f64>,
    pub damping: Option<f64>,
    pub su0: Option<f64>,
    pub su_gradient: Option<f64>,
    pub a: Option<f64>,
    pub b: Option<f64>,
    pub k_max: Option<f64>,
    pub f_suc: Option<f64>,
    pub lambda_suc: Option<f64>,
    pub lambda_rep: Option<f64>,
}

/// `[seabed.degradation]` as written (Randolph–Quiggin only).
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct DegradationTable {
    pub sensitivity: Option<f64>,
    pub ductility: Option<f64>,
    pub regain_t50: Option<f64>,
    pub regain_exponent: Option<f64>,
}

impl DegradationTable {
    /// Checked: `sensitivity` and `ductility` required; `regain_t50` and `regain_exponent` both or
    /// neither.
    fn build(&self, file: &str, table: &str) -> Result<Degradation, SceneError> {
        let key = |k: &str| format!("{table}.degradation.{k}");
        let sensitivity = required(
            file,
            &key("sensitivity"),
            self.sensitivity,
            "the sensitivity S_t >= 1 (intact over remoulded strength)",
        )?;
        let ductility = required(
            file,
            &key("ductility"),
            self.ductility,
            "the ductility xi95 > 0 (pipe diameters of accumulated plastic displacement)",
        )?;
        let regain = match (self.regain_t50, self.regain_exponent) {
            (None, None) => None,
            (Some(t50), Some(exponent)) => Some(Regain { t50, exponent }),
            (Some(_), None) => {
                return Err(invalid(
                    file,
                    key("regain_exponent"),
                    "the regain exponent m > 0 (regain needs regain_t50 and regain_exponent)",
                ))
            }
            (None, Some(_)) => {
                return Err(invalid(
                    file,
                    key("regain_t50"),
                    "the regain time t50 > 0 s (regain needs regain_t50 and regain_exponent)",
                ))
            }
        };
        Ok(Degradation {
            sensitivity,
            ductility,
            regain,
        })
    }
}

/// `[seabed.rate_suction]` as written (Randolph–Quiggin only): every key required.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct RateSuctionTable {
    pub drained_ratio: Option<f64>,
    pub cv: Option<f64>,
    pub v50: Option<f64>,
    pub exponent: Option<f64>,
}

impl RateSuctionTable {
    fn build(&self, file: &str, table: &str) -> Result<RateSuction, SceneError> {
        let key = |k: &str| format!("{table}.rate_suction.{k}");
        Ok(RateSuction {
            drained_ratio: required(
                file,
                &key("drained_ratio"),
                self.drained_ratio,
                "the drained suction ratio in [0, f_suc]",
            )?,
            cv: required(
                file,
                &key("cv"),
                self.cv,
                "the coefficient of consolidation cv in m²/s",
            )?,
            v50: required(
                file,
                &key("v50"),
                self.v50,
                "the normalised velocity V50 = v·D/cv at half-way",
            )?,
            exponent: required(
                file,
                &key("exponent"),
                self.exponent,
                "the backbone's exponent c > 0",
            )?,
        })
    }
}

/// `[seabed.friction]` as written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct FrictionTable {
    pub axial: Option<f64>,
    pub mobilisation: Option<f64>,
}

fn param_error(file: &str, table: &str, e: ParamError) -> SceneError {
    invalid(
        file,
        format!("{table}.{}", e.key),
        format!("{} (got {})", e.expected, e.value),
    )
}

impl SeabedTable {
    /// `[seabed.friction]`, checked: `axial` = μ ≥ 0 and `mobilisation` = δ > 0 (m), both required.
    pub fn friction(
        &self,
        file: &str,
        table: &str,
    ) -> Result<Option<catena_fe::model::AxialFriction>, SceneError> {
        let Some(f) = &self.friction else {
            return Ok(None);
        };
        let key = |k: &str| format!("{table}.friction.{k}");
        let mu = required(
            file,
            &key("axial"),
            f.axial,
            "the axial friction coefficient μ >= 0",
        )?;
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(invalid(
                file,
                key("axial"),
                format!("a friction coefficient μ >= 0 (got {mu})"),
            ));
        }
        let delta = required(
            file,
            &key("mobilisation"),
            f.mobilisation,
            "the displacement that mobilises full friction, in m (> 0)",
        )?;
        if !(delta.is_finite() && delta > 0.0) {
            return Err(invalid(
                file,
                key("mobilisation"),
                format!("a mobilisation displacement > 0 m (got {delta})"),
            ));
        }
        Ok(Some(catena_fe::model::AxialFriction {
            mu,
            mobilisation: delta,
        }))
    }

    /// `profile = [[x, z], …]`, checked: at least two points, each a pair of finite numbers, x
    /// strictly increasing, the mudline below the sea surface (`z < water_depth`). Empty without it.
    pub fn profile(
        &self,
        file: &str,
        table: &str,
        water_depth: f64,
    ) -> Result<Vec<(f64, f64)>, SceneError> {
        let Some(rows) = &self.profile else {
            return Ok(Vec::new());
        };
        let key = format!("{table}.profile");
        if rows.len() < 2 {
            return Err(invalid(file, &key, "at least two points [x, z] (m)"));
        }
        let mut out: Vec<(f64, f64)> = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            let k = format!("{key}[{i}]");
            let &[x, z] = r.as_slice() else {
                return Err(invalid(file, k, "a pair [x, z] in m"));
            };
            if !(x.is_finite() && z.is_finite()) {
                return Err(invalid(file, k, "finite numbers [x, z] in m"));
            }
            if let Some(&(px, _)) = out.last() {
                if x <= px {
                    return Err(invalid(
                        file,
                        k,
                        format!("an x beyond the previous point's ({px} m), got {x} m"),
                    ));
                }
            }
            if z >= water_depth {
                return Err(invalid(
                    file,
                    k,
                    format!("a mudline below the sea surface (z < the water depth {water_depth} m), got {z} m"),
                ));
            }
            out.push((x, z));
        }
        Ok(out)
    }

    /// `[[seabed.zone]]`, checked and built: each zone's law is the default table with the zone's
    /// keys overriding it (errors name `seabed.zone[i].key`); `from_x < to_x`, and zones may not
    /// overlap.
    pub fn zones(
        &self,
        file: &str,
        table: &str,
        default_diameter: Option<f64>,
        default_water_density: Option<f64>,
    ) -> Result<Vec<catena_fe::model::SeabedZone>, SceneError> {
        let mut out: Vec<catena_fe::model::SeabedZone> = Vec::new();
        for (i, z) in self.zone.iter().enumerate() {
            let name = format!("{table}.zone[{i}]");
            if !(z.from_x.is_finite() && z.to_x.is_finite() && z.from_x < z.to_x) {
                return Err(invalid(
                    file,
                    format!("{name}.to_x"),
                    format!(
                        "an end beyond the zone's start (from_x = {} m), got {} m",
                        z.from_x, z.to_x
                    ),
                ));
            }
            if let Some((j, o)) = out
                .iter()
                .enumerate()
                .find(|(_, o)| z.from_x < o.to_x && o.from_x < z.to_x)
            {
                return Err(invalid(
                    file,
                    format!("{name}.from_x"),
                    format!(
                        "a zone that does not overlap another ({table}.zone[{j}] covers [{}, {}) m)",
                        o.from_x, o.to_x
                    ),
                ));
            }
            let merged = SeabedTable {
                stiffness: z.stiffness.or(self.stiffness),
                damping: z.damping.or(self.damping),
                su0: z.su0.or(self.su0),
                su_gradient: z.su_gradient.or(self.su_gradient),
                a: z.a.or(self.a),
                b: z.b.or(self.b),
                k_max: z.k_max.or(self.k_max),
                f_suc: z.f_suc.or(self.f_suc),
                lambda_suc: z.lambda_suc.or(self.lambda_suc),
                lambda_rep: z.lambda_rep.or(self.lambda_rep),
                friction: None,
                zone: Vec::new(),
                profile: None,
                ..self.clone()
            };
            let seabed = merged.build(file, &name, default_diameter, default_water_density)?;
            out.push(catena_fe::model::SeabedZone {
                from_x: z.from_x,
                to_x: z.to_x,
                seabed,
            });
        }
        Ok(out)
    }

    /// Builds the seabed. `table` is the table's name in the file (for messages); `default_diameter`
    /// and `default_water_density` fill keys a riser scene knows from elsewhere.
    pub fn build(
        &self,
        file: &str,
        table: &str,
        default_diameter: Option<f64>,
        default_water_density: Option<f64>,
    ) -> Result<Seabed, SceneError> {
        let key = |k: &str| format!("{table}.{k}");
        let model = required(
            file,
            &key("model"),
            self.model,
            "\"linear\" or \"randolph-quiggin\"",
        )?;
        let diameter = required(
            file,
            &key("diameter"),
            self.diameter.or(default_diameter),
            "the contact diameter in m",
        )?;
        let linear_keys = [("stiffness", self.stiffness), ("damping", self.damping)];
        let rq_keys = [
            ("su0", self.su0),
            ("su_gradient", self.su_gradient),
            ("a", self.a),
            ("b", self.b),
            ("k_max", self.k_max),
            ("f_suc", self.f_suc),
            ("lambda_suc", self.lambda_suc),
            ("lambda_rep", self.lambda_rep),
        ];
        let law = match model {
            SeabedModel::Linear => {
                let stray = rq_keys.iter().map(|(k, v)| (*k, v.is_some())).chain([
                    ("liftoff_smoothing", self.liftoff_smoothing.is_some()),
                    ("degradation", self.degradation.is_some()),
                ]);
                reject_stray(file, table, "linear", stray)?;
                let stiffness = required(
                    file,
                    &key("stiffness"),
                    self.stiffness,
                    "the stiffness per unit contact area in N/m/m²",
                )?;
                Law::Linear(
                    LinearSeabed::new(diameter, stiffness, self.damping.unwrap_or(0.0))
                        .map_err(|e| param_error(file, table, e))?,
                )
            }
            SeabedModel::RandolphQuiggin => {
                reject_stray(
                    file,
                    table,
                    "randolph-quiggin",
                    linear_keys.iter().map(|(k, v)| (*k, v.is_some())),
                )?;
                let get = |k: &str, v: Option<f64>, what: &str| required(file, &key(k), v, what);
                let p = RqParams {
                    diameter,
                    su0: get("su0", self.su0, "the mudline strength in Pa")?,
                    su_gradient: get(
                        "su_gradient",
                        self.su_gradient,
                        "the strength gradient in Pa/m",
                    )?,
                    a: get("a", self.a, "the bearing-factor coefficient a")?,
                    b: get("b", self.b, "the bearing-factor exponent b")?,
                    k_max: get("k_max", self.k_max, "the normalised maximum stiffness")?,
                    f_suc: get("f_suc", self.f_suc, "the suction ratio in [0, 1]")?,
                    lambda_suc: get("lambda_suc", self.lambda_suc, "the suction decay distance")?,
                    lambda_rep: get("lambda_rep", self.lambda_rep, "the repenetration offset")?,
                    liftoff_smoothing: self.liftoff_smoothing.unwrap_or(false),
                    degradation: self.degradation.map(|d| d.build(file, table)).transpose()?,
                    rate_suction: self
                        .rate_suction
                        .map(|r| r.build(file, table))
                        .transpose()?,
                };
                Law::RandolphQuiggin(
                    RandolphQuiggin::new(p).map_err(|e| param_error(file, table, e))?,
                )
            }
        };
        let water = self.water_density.or(default_water_density);
        let buoyancy = match (self.f_b, self.soil_density) {
            (None, None) => {
                if self.water_density.is_some() {
                    return Err(invalid(
                        file,
                        key("water_density"),
                        "f_b and soil_density as well (soil buoyancy needs all three), or none",
                    ));
                }
                None
            }
            (Some(f_b), Some(soil)) => {
                let water = required(
                    file,
                    &key("water_density"),
                    water,
                    "the water density in kg/m³ (soil buoyancy needs f_b, soil_density and water_density)",
                )?;
                Some(
                    SoilBuoyancy::new(diameter, f_b, soil, water)
                        .map_err(|e| param_error(file, table, e))?,
                )
            }
            (Some(_), None) => {
                return Err(invalid(
                    file,
                    key("soil_density"),
                    "the saturated soil density in kg/m³ (soil buoyancy needs f_b, soil_density and water_density)",
                ))
            }
            (None, Some(_)) => {
                return Err(invalid(
                    file,
                    key("f_b"),
                    "the soil buoyancy factor (soil buoyancy needs f_b, soil_density and water_density)",
                ))
            }
        };
        Ok(Seabed { law, buoyancy })
    }
}

fn reject_stray(
    file: &str,
    table: &str,
    model: &str,
    keys: impl Iterator<Item = (&'static str, bool)>,
) -> Result<(), SceneError> {
    for (k, present) in keys {
        if present {
            return Err(invalid(
                file,
                format!("{table}.{k}"),
                format!("no such key for model = \"{model}\" (remove it, or change the model)"),
            ));
        }
    }
    Ok(())
}
