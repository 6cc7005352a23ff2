//! The riser scene's tables as written: one serde struct per TOML table, unknown keys denied. No
//! checks and no derivations here: [`super::checks`] holds the range checks, [`super::riser`] builds
//! the Model from the checked tables. Every key, its unit and its default are in `docs/scene.md`.

use serde::Deserialize;

use super::seabed::SeabedTable;

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
    /// Absent with `[[section]]` (NaN: not given).
    #[serde(default = "not_given")]
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

fn not_given() -> f64 {
    f64::NAN
}

/// One `[[line_type]]`: a pipe's properties, referred to by name from `[[section]]`. The keys of
/// `[line]`'s short form, and a taper's end, other diameters, Morison coefficients and fatigue data.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct LineTypeTable {
    pub name: String,
    pub od: f64,
    pub wall: Option<f64>,
    pub od_end: Option<f64>,
    pub wall_end: Option<f64>,
    pub youngs_modulus: Option<f64>,
    pub ea: Option<f64>,
    pub ei: Option<f64>,
    pub submerged_weight: Option<f64>,
    pub mass: Option<f64>,
    pub steel_density: Option<f64>,
    pub contents_density: Option<f64>,
    pub hydrodynamic_od: Option<f64>,
    pub contact_od: Option<f64>,
    pub cd_normal: Option<f64>,
    pub cd_axial: Option<f64>,
    pub ca_normal: Option<f64>,
    pub sn_curve: Option<SnKey>,
    pub scf: Option<f64>,
}

/// One `[[section]]`: a length of one line type, from the previous section's end (the top for the
/// first) to `to`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct SectionTable {
    #[serde(rename = "type")]
    pub kind: String,
    pub to: f64,
    pub element_length: f64,
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

pub(super) fn default_tol() -> f64 {
    1e-9
}
pub(super) fn default_max_iter() -> usize {
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

/// `[design_check]`: the strength check along the line (see `crate::checks::design`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct DesignCheckTable {
    pub code: String,
    pub smys: f64,
    pub smts: f64,
    #[serde(default)]
    pub internal_pressure: f64,
    pub safety_class: Option<String>,
    #[serde(default)]
    pub corrosion_allowance: f64,
    pub start: Option<f64>,
    pub load_factors: Option<LoadFactorsTable>,
    pub design_factor: Option<f64>,
    pub material_strength_factor: Option<f64>,
    pub fabrication_factor: Option<f64>,
    pub ovality: Option<f64>,
    pub youngs_modulus: Option<f64>,
    pub condition_factor: Option<f64>,
    pub strain_factor: Option<f64>,
    pub yield_to_tensile_max: Option<f64>,
}

/// `[design_check] load_factors`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct LoadFactorsTable {
    #[serde(default = "gamma_f")]
    pub functional: f64,
    #[serde(default = "gamma_e")]
    pub environmental: f64,
}

fn gamma_f() -> f64 {
    1.1
}
fn gamma_e() -> f64 {
    1.3
}

/// `[extremes]`: short-term extreme statistics of chosen channels (see `crate::checks::extremes`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct ExtremesTable {
    pub channels: Option<Vec<String>>,
    pub start: Option<f64>,
    pub target_duration: Option<f64>,
    pub quantile: Option<f64>,
    pub block: Option<f64>,
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

/// `[[attachment]]`: a body at an arc length (a clump weight, a buoyancy module).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct AttachmentTable {
    pub name: Option<String>,
    pub arc: f64,
    #[serde(default)]
    pub mass: f64,
    #[serde(default)]
    pub submerged_weight: f64,
    #[serde(default)]
    pub drag_area: f64,
    #[serde(default)]
    pub added_mass: f64,
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

/// How the J-lay tower holds the pipe, as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TowerKey {
    /// Position and angle held.
    #[default]
    Clamped,
    /// Position held; the angle on a rotational spring (`tower_stiffness`).
    Hinged,
}

/// How the pipe is paid out, as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PayoutKey {
    /// At the vessel's speed.
    #[default]
    Position,
    /// By a tensioner holding a target top tension.
    Tension,
}

/// `[lay]`: the pipe's installation (`crate::run::lay`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct LayTable {
    pub speed: f64,
    pub length: Option<f64>,
    pub pipe_length: Option<f64>,
    pub tower_angle_deg: Option<f64>,
    #[serde(default)]
    pub tower: TowerKey,
    pub tower_stiffness: Option<f64>,
    #[serde(default)]
    pub payout: PayoutKey,
    pub target_tension: Option<f64>,
    pub gain: Option<f64>,
    pub max_payout_rate: Option<f64>,
    pub time_constant: Option<f64>,
    pub element_length: Option<f64>,
    pub freeze_tolerance: Option<f64>,
    pub freeze_behind: Option<f64>,
    pub ramp: Option<f64>,
    #[serde(default)]
    pub lay_down: bool,
    pub wire: Option<WireTable>,
}

/// `[lay.wire]`: the abandonment and recovery wire a lay-down lowers the pipe's end on.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct WireTable {
    pub length: f64,
    /// A `[[line_type]]`'s name: the wire's properties are that type's (else the keys below).
    #[serde(rename = "type")]
    pub line_type: Option<String>,
    pub od: Option<f64>,
    pub ea: Option<f64>,
    pub ei: Option<f64>,
    pub submerged_weight: Option<f64>,
    pub mass: Option<f64>,
    pub element_length: Option<f64>,
    #[serde(default)]
    pub station: bool,
    pub station_height: Option<f64>,
}

/// A riser scene file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct RiserFile {
    pub title: Option<String>,
    pub environment: EnvironmentTable,
    pub line: LineTable,
    #[serde(default)]
    pub mesh: Vec<MeshTable>,
    #[serde(default)]
    pub line_type: Vec<LineTypeTable>,
    #[serde(default)]
    pub section: Vec<SectionTable>,
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
    pub design_check: Option<DesignCheckTable>,
    pub extremes: Option<ExtremesTable>,
    #[serde(default)]
    pub gauge: Vec<GaugeTable>,
    #[serde(default)]
    pub attachment: Vec<AttachmentTable>,
    pub limits: Option<LimitsTable>,
    pub lay: Option<LayTable>,
    pub as_laid: Option<AsLaidTable>,
}

/// `[as_laid]`: start the dynamics on the seabed a lay left (`laid-seabed.json` of a lay run).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct AsLaidTable {
    pub file: String,
    pub x_shift: Option<f64>,
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
