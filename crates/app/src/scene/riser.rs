//! Riser and pipeline scenes: the line, its mesh, its ends and the optional effects.
//! Every key, its unit and its default are listed in `docs/scene.md`.

use catena_fe::beam::Section;
use catena_fe::model::{LineModel, LineSpec, SeabedContact, Segment, Support};
use catena_fe::statics::EndPositions;
use serde::Deserialize;

use super::seabed::SeabedTable;
use super::{invalid, parse, required};
use crate::error::SceneError;

/// `[environment]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct EnvironmentTable {
    pub water_depth: f64,
    #[serde(default = "default_water_density")]
    pub water_density: f64,
    #[serde(default = "default_gravity")]
    pub gravity: f64,
}

fn default_water_density() -> f64 {
    1025.0
}
fn default_gravity() -> f64 {
    catena_seabed::G
}

/// `[line]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct LineTable {
    pub length: f64,
    pub od: f64,
    pub wall: Option<f64>,
    pub youngs_modulus: Option<f64>,
    pub ea: Option<f64>,
    pub ei: Option<f64>,
    pub submerged_weight: Option<f64>,
    pub mass: Option<f64>,
    pub steel_density: Option<f64>,
    pub contents_density: Option<f64>,
}

/// One `[[mesh]]` section.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct MeshTable {
    pub to: f64,
    pub element_length: f64,
}

/// How an end is held, as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SupportKey {
    /// Position prescribed, rotation free.
    Pinned,
    /// Position and rotation prescribed.
    Fixed,
}

/// `[ends]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct EndsTable {
    pub top_x: f64,
    pub top_z: f64,
    #[serde(default)]
    pub anchor_x: f64,
    pub anchor_z: Option<f64>,
    #[serde(default = "pinned")]
    pub top: SupportKey,
    #[serde(default = "pinned")]
    pub anchor: SupportKey,
}

fn pinned() -> SupportKey {
    SupportKey::Pinned
}

/// `[flexjoint]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct FlexJointTable {
    pub stiffness: f64,
    pub neutral_angle_deg: Option<f64>,
}

/// `[static]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StaticTable {
    #[serde(default = "default_tol")]
    pub tolerance: f64,
    #[serde(default = "default_max_iter")]
    pub max_iterations: usize,
}

fn default_tol() -> f64 {
    1e-9
}
fn default_max_iter() -> usize {
    40
}

/// A riser scene file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct RiserFile {
    pub title: Option<String>,
    pub environment: EnvironmentTable,
    pub line: LineTable,
    pub mesh: Vec<MeshTable>,
    pub ends: EndsTable,
    pub seabed: Option<SeabedTable>,
    pub flexjoint: Option<FlexJointTable>,
    #[serde(rename = "static")]
    pub statics: Option<StaticTable>,
}

/// A riser scene, read and checked.
#[derive(Debug, Clone)]
pub struct RiserScene {
    /// The case file.
    pub file: String,
    /// The file's text (stored with the results).
    pub text: String,
    /// Its title.
    pub title: String,
    /// The Model.
    pub model: LineModel,
    /// The end positions.
    pub ends: EndPositions,
    /// The flexjoint neutral angle from the vertical, rad, if given (else the static angle).
    pub flexjoint_neutral_from_vertical: Option<f64>,
    /// Static solve tolerance and iteration limit.
    pub statics: StaticTable,
    /// Water depth, m.
    pub water_depth: f64,
    /// Line summary: (EA, EI, submerged weight, mass).
    pub line: (f64, f64, f64, f64),
}

fn positive(file: &str, key: &str, v: f64, what: &str) -> Result<f64, SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(file, key, format!("{what} > 0 (got {v})")))
    }
}

impl RiserScene {
    /// Parses and checks scene text (`file` names it in messages).
    pub fn parse(file: &str, text: &str) -> Result<Self, SceneError> {
        let raw: RiserFile = parse(file, text)?;
        let env = &raw.environment;
        positive(
            file,
            "environment.water_depth",
            env.water_depth,
            "a depth in m",
        )?;
        positive(
            file,
            "environment.water_density",
            env.water_density,
            "a density in kg/m³",
        )?;
        positive(
            file,
            "environment.gravity",
            env.gravity,
            "an acceleration in m/s²",
        )?;
        let l = &raw.line;
        positive(file, "line.length", l.length, "a length in m")?;
        positive(file, "line.od", l.od, "a diameter in m")?;
        let pi = std::f64::consts::PI;
        let (a_steel, a_inner) = match l.wall {
            Some(t) => {
                if !(t > 0.0 && 2.0 * t < l.od) {
                    return Err(invalid(
                        file,
                        "line.wall",
                        format!("0 < wall < od/2 (got {t})"),
                    ));
                }
                let id = l.od - 2.0 * t;
                (pi / 4.0 * (l.od * l.od - id * id), pi / 4.0 * id * id)
            }
            None => (f64::NAN, f64::NAN),
        };
        let i_steel = l.wall.map(|t| {
            let id = l.od - 2.0 * t;
            pi / 64.0 * (l.od.powi(4) - id.powi(4))
        });
        let (ea, ei) = match (l.ea, l.ei, l.youngs_modulus) {
            (Some(ea), Some(ei), None) => (ea, ei),
            (None, None, Some(e)) => {
                let i = i_steel.ok_or_else(|| {
                    invalid(
                        file,
                        "line.wall",
                        "the wall thickness in m (needed with line.youngs_modulus)",
                    )
                })?;
                positive(file, "line.youngs_modulus", e, "a modulus in Pa")?;
                (e * a_steel, e * i)
            }
            _ => {
                return Err(invalid(
                    file,
                    "line.youngs_modulus",
                    "either youngs_modulus (with wall) or both ea and ei",
                ))
            }
        };
        positive(file, "line.ea", ea, "an axial stiffness in N")?;
        positive(file, "line.ei", ei, "a bending stiffness in N·m²")?;
        let g = env.gravity;
        let a_outer = pi / 4.0 * l.od * l.od;
        let from_densities = match (l.steel_density, l.contents_density) {
            (Some(rs), Some(rc)) => {
                if l.wall.is_none() {
                    return Err(invalid(
                        file,
                        "line.wall",
                        "the wall thickness (needed with the densities)",
                    ));
                }
                let m = rs * a_steel + rc * a_inner;
                Some((m, (m - env.water_density * a_outer) * g))
            }
            (None, None) => None,
            _ => {
                return Err(invalid(
                    file,
                    "line.contents_density",
                    "both steel_density and contents_density, or neither",
                ))
            }
        };
        let (mass, weight) = match (l.mass, l.submerged_weight, from_densities) {
            (Some(m), Some(w), None) => (m, w),
            (None, None, Some(mw)) => mw,
            _ => {
                return Err(invalid(
                    file,
                    "line.submerged_weight",
                    "either mass and submerged_weight, or steel_density and contents_density (with wall)",
                ))
            }
        };
        positive(
            file,
            "line.submerged_weight",
            weight,
            "a submerged weight in N/m",
        )?;
        positive(file, "line.mass", mass, "a mass in kg/m")?;
        if raw.mesh.is_empty() {
            return Err(invalid(file, "mesh", "at least one [[mesh]] section"));
        }
        let mut segments = Vec::new();
        let mut from = 0.0;
        for (i, m) in raw.mesh.iter().enumerate() {
            if m.to.is_nan() || m.to <= from {
                return Err(invalid(
                    file,
                    format!("mesh[{i}].to"),
                    format!(
                        "an arc length beyond the previous section's end ({from} m), got {}",
                        m.to
                    ),
                ));
            }
            positive(
                file,
                &format!("mesh[{i}].element_length"),
                m.element_length,
                "an element length in m",
            )?;
            segments.push(Segment {
                length: m.to - from,
                element_length: m.element_length,
                section: Section { ea, ei },
                weight,
                mass,
                od: l.od,
            });
            from = m.to;
        }
        if (from - l.length).abs() > 1e-9 * l.length {
            return Err(invalid(
                file,
                format!("mesh[{}].to", raw.mesh.len() - 1),
                format!(
                    "the line length {} m (the last section must end there), got {from}",
                    l.length
                ),
            ));
        }
        let seabed = match &raw.seabed {
            Some(t) => Some(SeabedContact {
                seabed: t.build(file, "seabed", Some(l.od), Some(env.water_density))?,
                mudline_z: 0.0,
            }),
            None => None,
        };
        let flexjoint = match &raw.flexjoint {
            Some(f) => {
                positive(
                    file,
                    "flexjoint.stiffness",
                    f.stiffness,
                    "a rotational stiffness in N·m/rad",
                )?;
                Some((f.stiffness, 0.0))
            }
            None => None,
        };
        let support = |s: SupportKey| match s {
            SupportKey::Pinned => Support::Pinned,
            SupportKey::Fixed => Support::Fixed,
        };
        let spec = LineSpec {
            segments,
            top: support(raw.ends.top),
            anchor: support(raw.ends.anchor),
            seabed,
            flexjoint,
        };
        let model = LineModel::build(&spec).map_err(|e| invalid(file, "mesh", e.to_string()))?;
        let e = &raw.ends;
        for (k, v) in [
            ("ends.top_x", e.top_x),
            ("ends.top_z", e.top_z),
            ("ends.anchor_x", e.anchor_x),
        ] {
            if !v.is_finite() {
                return Err(invalid(file, k, "a finite coordinate in m"));
            }
        }
        let anchor_z = match e.anchor_z {
            Some(z) => z,
            None => {
                let emb = catena_fe::statics::static_embedment(&model, weight).unwrap_or(0.0);
                if model.seabed.is_some() {
                    0.5 * l.od - emb
                } else {
                    return Err(invalid(
                        file,
                        "ends.anchor_z",
                        "the anchor height in m (required without a [seabed])",
                    ));
                }
            }
        };
        let chord = ((e.top_x - e.anchor_x).powi(2) + (e.top_z - anchor_z).powi(2)).sqrt();
        if l.length <= chord {
            return Err(invalid(
                file,
                "line.length",
                format!(
                    "a length longer than the distance between the ends ({chord:.3} m), got {} m",
                    l.length
                ),
            ));
        }
        if e.top_x <= e.anchor_x {
            return Err(invalid(
                file,
                "ends.top_x",
                "a top end on the vessel side of the anchor (top_x > anchor_x)",
            ));
        }
        if e.top_z > env.water_depth {
            return Err(invalid(
                file,
                "ends.top_z",
                format!("a height within the water depth {} m", env.water_depth),
            ));
        }
        let _ = required::<f64>;
        Ok(Self {
            file: file.to_string(),
            text: text.to_string(),
            title: raw.title.clone().unwrap_or_else(|| file.to_string()),
            model,
            ends: EndPositions {
                top: (e.top_x, e.top_z),
                anchor: (e.anchor_x, anchor_z),
            },
            flexjoint_neutral_from_vertical: raw
                .flexjoint
                .as_ref()
                .and_then(|f| f.neutral_angle_deg.map(f64::to_radians)),
            statics: raw.statics.clone().unwrap_or(StaticTable {
                tolerance: default_tol(),
                max_iterations: default_max_iter(),
            }),
            water_depth: env.water_depth,
            line: (ea, ei, weight, mass),
        })
    }
}
