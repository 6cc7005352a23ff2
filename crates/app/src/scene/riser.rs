//! Riser and pipeline scenes: the line, its mesh, its ends and the optional effects.
//! Every key, its unit and its default are listed in `docs/scene.md`.

use catena_fe::beam::Section;
use catena_fe::dynamics::{DynamicSettings, Scheme};
use catena_fe::environment::{Environment, Hydro};
use catena_fe::model::{LineModel, LineSpec, SeabedContact, Segment, Support};
use catena_fe::motion::TopMotion;

use crate::fatigue::sn::SnCurve;
use crate::fatigue::stress::{Fibre, PipeSection};
use crate::fatigue::FatigueSpec;
use catena_fe::statics::EndPositions;
use catena_fe::vessel::{RaoTable, Vessel};
use catena_fe::waves::{Direction, Waves};
use serde::Deserialize;

use super::edit::{self, Edit};
use super::seabed::SeabedTable;
use super::{from_doc, invalid, parse, required, Resolver};
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

/// The integration scheme as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SchemeKey {
    /// HHT-α.
    Hht,
    /// Newmark (β, γ).
    Newmark,
}

/// `[dynamic]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct DynamicTable {
    pub duration: f64,
    pub time_step: f64,
    pub output_interval: Option<f64>,
    #[serde(default = "hht")]
    pub scheme: SchemeKey,
    pub alpha: Option<f64>,
    pub beta: Option<f64>,
    pub gamma: Option<f64>,
    #[serde(default = "default_dyn_tol")]
    pub tolerance: f64,
    #[serde(default = "default_dyn_iter")]
    pub max_iterations: usize,
    #[serde(default = "default_cuts")]
    pub max_step_cuts: u32,
    #[serde(default)]
    pub envelope_start: f64,
}

fn hht() -> SchemeKey {
    SchemeKey::Hht
}
fn default_dyn_tol() -> f64 {
    1e-8
}
fn default_dyn_iter() -> usize {
    20
}
fn default_cuts() -> u32 {
    6
}

/// `[hydrodynamics]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct HydroTable {
    pub cd_normal: f64,
    #[serde(default)]
    pub cd_axial: f64,
    pub ca_normal: f64,
}

/// `[current]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct CurrentTable {
    pub profile: Vec<[f64; 2]>,
}

/// A stage of `[motion.staged]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StageTable {
    pub duration: f64,
    #[serde(default)]
    pub vx: f64,
    #[serde(default)]
    pub vz: f64,
}

/// `[motion]`: exactly one of its sub-tables.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct MotionTable {
    pub staged: Option<StagedTable>,
    pub harmonic: Option<HarmonicTable>,
    pub series: Option<SeriesTable>,
}

/// `[motion.staged]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StagedTable {
    pub stages: Vec<StageTable>,
}

/// `[motion.harmonic]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct HarmonicTable {
    #[serde(default)]
    pub heave: f64,
    #[serde(default)]
    pub surge: f64,
    pub period: f64,
    #[serde(default)]
    pub phase_deg: f64,
    #[serde(default)]
    pub ramp: f64,
}

/// `[motion.series]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SeriesTable {
    pub file: String,
}

/// The kind of `[waves]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WaveKind {
    /// Irregular, JONSWAP.
    Jonswap,
    /// Regular (Airy).
    Airy,
}

/// `[waves]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct WavesTable {
    pub kind: WaveKind,
    pub hs: Option<f64>,
    pub tp: Option<f64>,
    pub gamma: Option<f64>,
    pub seed: Option<u64>,
    pub components: Option<usize>,
    pub height: Option<f64>,
    pub period: Option<f64>,
    pub phase_deg: Option<f64>,
    #[serde(default = "plus_x")]
    pub direction: String,
    pub ramp: Option<f64>,
    pub kinematics_interval: Option<f64>,
}

fn plus_x() -> String {
    "+x".into()
}

/// A user S-N curve in `[fatigue]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SnTable {
    pub m1: f64,
    pub log_a1: f64,
    pub m2: Option<f64>,
    pub log_a2: Option<f64>,
    pub knee_cycles: Option<f64>,
    #[serde(default)]
    pub thickness_exponent: f64,
}

/// `sn_curve`: a name or a table.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
#[allow(missing_docs)]
pub enum SnKey {
    Name(String),
    Table(SnTable),
}

/// `[fatigue]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct FatigueTable {
    pub sn_curve: SnKey,
    #[serde(default = "one")]
    pub scf: f64,
    #[serde(default = "outer")]
    pub fibres: Vec<String>,
    pub design_factor: Option<f64>,
    pub start: Option<f64>,
    pub contents_density: Option<f64>,
    #[serde(default)]
    pub internal_pressure: f64,
}

fn one() -> f64 {
    1.0
}
fn outer() -> Vec<String> {
    vec!["outer".into()]
}

/// `[structural_damping]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct StructuralDampingTable {
    pub critical_percent: f64,
    pub period: f64,
}

/// `[vessel]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct VesselTable {
    pub rao: String,
    pub hangoff_offset: [f64; 2],
}

/// `[[gauge]]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct GaugeTable {
    pub name: String,
    pub arc: Option<f64>,
    pub midway_touchdown_lift: Option<f64>,
}

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
    /// The pipe's section for wall tension and stress range graphs: `[fatigue]`'s, or from
    /// `line.wall` and `line.contents_density` (no internal pressure) when both are given.
    pub section: Option<PipeSection>,
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
    pub dynamic: Option<DynamicTable>,
    pub hydrodynamics: Option<HydroTable>,
    pub current: Option<CurrentTable>,
    pub motion: Option<MotionTable>,
    pub waves: Option<WavesTable>,
    pub vessel: Option<VesselTable>,
    pub structural_damping: Option<StructuralDampingTable>,
    pub fatigue: Option<FatigueTable>,
    #[serde(default)]
    pub gauge: Vec<GaugeTable>,
    pub limits: Option<LimitsTable>,
}

/// `[limits]`: the largest run a scene may ask for. A run is sized before anything is built (elements
/// from the mesh, steps from the duration and time step, records and their bytes from the output
/// interval) and refused beyond these, so that a slip (`element_length = 1e-5`, `duration = 1e9`)
/// gets an error instead of hours of work or gigabytes of memory. Raise them here for a genuinely
/// large run.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LimitsTable {
    /// Elements (default 50 000).
    #[serde(default = "default_max_elements")]
    pub max_elements: f64,
    /// Time steps of `dynamic.time_step` (default 10 000 000: 139 hours at 0.05 s).
    #[serde(default = "default_max_steps")]
    pub max_steps: f64,
    /// Bytes of `results.h5` records (default 20 GB).
    #[serde(default = "default_max_output_bytes")]
    pub max_output_bytes: f64,
}

impl Default for LimitsTable {
    fn default() -> Self {
        Self {
            max_elements: default_max_elements(),
            max_steps: default_max_steps(),
            max_output_bytes: default_max_output_bytes(),
        }
    }
}

fn default_max_elements() -> f64 {
    50_000.0
}
fn default_max_steps() -> f64 {
    1e7
}
fn default_max_output_bytes() -> f64 {
    20e9
}

/// Bytes recorded per node per record in `/dynamic` (x, z, rotation, effective and wall tension,
/// moment, curvature, penetration, seabed force as f64 and the seabed mode).
pub const RECORD_BYTES_PER_NODE: f64 = 9.0 * 8.0 + 1.0;

/// What a scene would run: its size, estimated before anything is built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSize {
    /// Elements of the mesh.
    pub elements: usize,
    /// Time steps of the dynamics (0 for a static scene).
    pub steps: u64,
    /// Records written to `results.h5`.
    pub records: u64,
    /// Bytes of those records (uncompressed).
    pub output_bytes: f64,
}

/// A scene's size from its tables alone, checked against `[limits]` (the error names the key to
/// change and the limit to raise).
pub fn run_size(file: &str, raw: &RiserFile) -> Result<RunSize, SceneError> {
    let lim = raw.limits.unwrap_or_default();
    let mut elements = 0.0f64;
    let mut from = 0.0;
    for m in &raw.mesh {
        if m.element_length > 0.0 && m.to > from {
            elements += ((m.to - from) / m.element_length).ceil();
            from = m.to;
        }
    }
    if elements > lim.max_elements {
        return Err(invalid(
            file,
            "mesh",
            format!(
                "at most {:e} elements (this mesh has {elements:e}); check each mesh[i].element_length, or raise limits.max_elements",
                lim.max_elements
            ),
        ));
    }
    let (mut steps, mut records) = (0.0f64, 0.0f64);
    if let Some(d) = &raw.dynamic {
        if d.time_step > 0.0 && d.duration > 0.0 {
            steps = (d.duration / d.time_step).ceil();
            if steps > lim.max_steps {
                return Err(invalid(
                    file,
                    "dynamic.duration",
                    format!(
                        "at most {:e} time steps (duration / time_step = {steps:e}); check dynamic.duration and dynamic.time_step, or raise limits.max_steps",
                        lim.max_steps
                    ),
                ));
            }
            let out = d
                .output_interval
                .unwrap_or(d.time_step * (steps / DEFAULT_MAX_RECORDS).ceil().max(1.0));
            if out > 0.0 {
                records = (d.duration / out.max(d.time_step)).floor() + 1.0;
            }
        }
    }
    let output_bytes = records * (elements + 1.0) * RECORD_BYTES_PER_NODE;
    if output_bytes > lim.max_output_bytes {
        return Err(invalid(
            file,
            "dynamic.output_interval",
            format!(
                "records of at most {:.1} GB ({records:e} records of {} nodes would be {:.1} GB); lengthen dynamic.output_interval, or raise limits.max_output_bytes",
                lim.max_output_bytes / 1e9,
                elements + 1.0,
                output_bytes / 1e9
            ),
        ));
    }
    Ok(RunSize {
        elements: elements as usize,
        steps: steps as u64,
        records: records as u64,
        output_bytes,
    })
}

/// A riser scene, read and checked.
#[derive(Debug, Clone)]
pub struct RiserScene {
    /// The case file.
    pub file: String,
    /// The file's text (stored with the results); for an edited scene, its document written out.
    pub text: String,
    /// The parsed TOML document (edited by key path, see [`RiserScene::edited`]).
    pub doc: toml::Table,
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
    /// The sea water's hydrodynamics (`[hydrodynamics]`, `[current]`), if any: a current acts in the
    /// statics too.
    pub hydro: Option<Hydro>,
    /// The dynamic analysis, if the scene has a `[dynamic]` table.
    pub dynamic: Option<DynamicSpec>,
    /// The run's size, estimated from the tables (checked against `[limits]`).
    pub size: RunSize,
}

/// What the dynamic tables need to know of the site.
#[derive(Debug, Clone, Copy)]
struct Site {
    length: f64,
    water_depth: f64,
    water_density: f64,
    gravity: f64,
    top_x: f64,
}

/// A Newton tolerance: relative, in (0, 10⁻³] (a looser one would accept unconverged answers).
fn tolerance_in_range(file: &str, key: &str, v: f64) -> Result<(), SceneError> {
    if v > 0.0 && v <= 1e-3 {
        Ok(())
    } else {
        Err(invalid(
            file,
            key,
            format!("a relative tolerance in (0, 1e-3] (got {v:e})"),
        ))
    }
}

fn iterations_at_least_one(file: &str, key: &str, v: usize) -> Result<(), SceneError> {
    if v >= 1 {
        Ok(())
    } else {
        Err(invalid(file, key, "at least 1 iteration (got 0)"))
    }
}

fn positive(file: &str, key: &str, v: f64, what: &str) -> Result<f64, SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(invalid(file, key, format!("{what} > 0 (got {v})")))
    }
}

impl RiserScene {
    /// Parses and checks scene text (`file` names it in messages); files the scene names are read
    /// through `files`.
    pub fn parse(file: &str, text: &str, files: &dyn Resolver) -> Result<Self, SceneError> {
        let raw: RiserFile = parse(file, text)?;
        let doc: toml::Table = text
            .parse()
            .map_err(|e: toml::de::Error| SceneError::Parse {
                file: file.to_string(),
                message: e.to_string().trim_end().to_string(),
            })?;
        Self::build(file, text.to_string(), doc, &raw, files)
    }

    /// The scene with `edits` applied to its document (key paths, see [`edit`]), checked anew. Its
    /// text is the edited document written out.
    pub fn edited(&self, edits: &[Edit], files: &dyn Resolver) -> Result<Self, SceneError> {
        let mut doc = self.doc.clone();
        edit::apply(&self.file, &mut doc, edits)?;
        let raw: RiserFile = from_doc(&self.file, &doc)?;
        let text = toml::to_string(&doc)
            .map_err(|e| invalid(&self.file, "", format!("a document TOML can write ({e})")))?;
        Self::build(&self.file, text, doc, &raw, files)
    }

    fn build(
        file: &str,
        text: String,
        doc: toml::Table,
        raw: &RiserFile,
        files: &dyn Resolver,
    ) -> Result<Self, SceneError> {
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
        if !(0.005..=5.0).contains(&l.od) {
            return Err(invalid(
                file,
                "line.od",
                format!("an outer diameter between 0.005 and 5 m (got {} m)", l.od),
            ));
        }
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
        let size = run_size(file, raw)?;
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
        if e.top_z <= 0.5 * l.od {
            return Err(invalid(
                file,
                "ends.top_z",
                format!(
                    "a top end above the mudline: height in m above it, > od/2 = {} m (got {})",
                    0.5 * l.od,
                    e.top_z
                ),
            ));
        }
        if anchor_z > env.water_depth {
            return Err(invalid(
                file,
                "ends.anchor_z",
                format!(
                    "an anchor below the sea surface (height above the mudline at most the water depth {} m, got {anchor_z})",
                    env.water_depth
                ),
            ));
        }
        // A given anchor height: at most 5 diameters below the mudline (catena models no buried
        // line). The default, at the static embedment, may be deeper on a very soft seabed (0.6 m
        // for the SCR on su0 = 0, a gradient of 650 Pa/m).
        if e.anchor_z.is_some() && anchor_z < -5.0 * l.od {
            return Err(invalid(
                file,
                "ends.anchor_z",
                format!(
                    "an anchor at most 5 diameters ({:.3} m) below the mudline (got {anchor_z:.3} m): catena models no buried line",
                    5.0 * l.od
                ),
            ));
        }
        if e.top_z <= anchor_z {
            return Err(invalid(
                file,
                "ends.top_z",
                format!("a top end above the anchor (anchor_z = {anchor_z} m)"),
            ));
        }
        if let Some(st) = &raw.statics {
            tolerance_in_range(file, "static.tolerance", st.tolerance)?;
            iterations_at_least_one(file, "static.max_iterations", st.max_iterations)?;
        }
        if let Some(d) = &raw.dynamic {
            tolerance_in_range(file, "dynamic.tolerance", d.tolerance)?;
            iterations_at_least_one(file, "dynamic.max_iterations", d.max_iterations)?;
            if d.max_step_cuts > 20 {
                return Err(invalid(
                    file,
                    "dynamic.max_step_cuts",
                    format!("at most 20 halvings (Δt/10⁶), got {}", d.max_step_cuts),
                ));
            }
        }
        // `[f64; 2]` would read the first two numbers of a longer entry and drop the rest.
        if let Some(toml::Value::Array(rows)) = doc
            .get("current")
            .and_then(|c| c.as_table())
            .and_then(|c| c.get("profile"))
        {
            for (i, r) in rows.iter().enumerate() {
                if r.as_array().map(Vec::len) != Some(2) {
                    return Err(invalid(
                        file,
                        format!("current.profile[{i}]"),
                        "a pair [height above the mudline in m, speed in m/s]",
                    ));
                }
            }
        }
        let _ = required::<f64>;
        let hydro = hydro_of(file, raw, env.water_density)?;
        let dynamic = match &raw.dynamic {
            Some(d) => Some(dynamic_spec(
                file,
                raw,
                d,
                hydro.clone(),
                Site {
                    length: l.length,
                    water_depth: env.water_depth,
                    water_density: env.water_density,
                    gravity: env.gravity,
                    top_x: e.top_x,
                },
                files,
            )?),
            None => {
                for (present, key) in [
                    (raw.motion.is_some(), "motion"),
                    (raw.waves.is_some(), "waves"),
                    (raw.vessel.is_some(), "vessel"),
                    (raw.structural_damping.is_some(), "structural_damping"),
                    (raw.fatigue.is_some(), "fatigue"),
                    (!raw.gauge.is_empty(), "gauge"),
                ] {
                    if present {
                        return Err(invalid(
                            file,
                            key,
                            "a [dynamic] table as well (this table only acts in a dynamic run)",
                        ));
                    }
                }
                None
            }
        };
        if let Some(m) = dynamic.as_ref().and_then(|d| d.motion.as_ref()) {
            // The prescribed top motion's extreme offsets (a harmonic moves along the segment between
            // ±(surge, heave); staged and series motions are piecewise linear between their points).
            let corners: Vec<(f64, f64)> = match m {
                TopMotion::Harmonic { surge, heave, .. } => {
                    vec![(*surge, *heave), (-surge, -heave)]
                }
                TopMotion::Staged(st) => {
                    let (mut x, mut z) = (0.0, 0.0);
                    st.iter()
                        .map(|(d, vx, vz)| {
                            x += d * vx;
                            z += d * vz;
                            (x, z)
                        })
                        .collect()
                }
                TopMotion::Series(pts) => pts.iter().map(|p| (p.1, p.2)).collect(),
            };
            for (dx, dz) in corners {
                let (x, z) = (e.top_x + dx, e.top_z + dz);
                let reach = ((x - e.anchor_x).powi(2) + (z - anchor_z).powi(2)).sqrt();
                if reach >= l.length || z <= 0.5 * l.od {
                    return Err(invalid(
                        file,
                        "motion",
                        format!(
                            "a top motion that keeps the top above the mudline and within the line's reach: at its extreme offset ({dx:.3}, {dz:.3}) m the top is at ({x:.3}, {z:.3}) m, {reach:.3} m from the anchor, with a line of {} m",
                            l.length
                        ),
                    ));
                }
            }
        }
        Ok(Self {
            file: file.to_string(),
            text,
            doc,
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
            hydro,
            dynamic,
            size,
        })
    }
}

/// `[hydrodynamics]` and `[current]`: the sea water's hydrodynamics, if the scene has them.
fn hydro_of(file: &str, raw: &RiserFile, water_density: f64) -> Result<Option<Hydro>, SceneError> {
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

fn dynamic_spec(
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
    let scheme = match d.scheme {
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
    };
    positive(
        file,
        "dynamic.tolerance",
        d.tolerance,
        "a relative tolerance",
    )?;
    let motion = match &raw.motion {
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
    };
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
    let structural_damping = match &raw.structural_damping {
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
    };
    let fatigue = match &raw.fatigue {
        Some(t) => Some(fatigue_of(file, raw, t, d, site)?),
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
        section,
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

/// The default kinematics samples per peak (or regular) period: `h = T/40`.
pub const KINEMATICS_PER_PERIOD: f64 = 40.0;

/// `[waves]` → the wave train (see `docs/scene.md`).
fn waves_of(file: &str, w: &WavesTable, site: Site, time_step: f64) -> Result<Waves, SceneError> {
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
fn vessel_of(
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

/// `[fatigue]` → what the fatigue observer counts (see `docs/scene.md`).
fn fatigue_of(
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
    let (curve, curve_name) = match &t.sn_curve {
        SnKey::Name(n) => (
            SnCurve::dnv(n).ok_or_else(|| {
                invalid(
                    file,
                    "fatigue.sn_curve",
                    format!(
                        "one of {} or a table {{ m1, log_a1, m2, log_a2, knee_cycles }}, got \"{n}\"",
                        crate::fatigue::sn::NAMES.join(", ")
                    ),
                )
            })?,
            n.clone(),
        ),
        SnKey::Table(c) => {
            for (k, v) in [("m1", c.m1), ("log_a1", c.log_a1)] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(invalid(file, format!("fatigue.sn_curve.{k}"), "a number > 0"));
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
                        "fatigue.sn_curve",
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
    };
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
    })
}
