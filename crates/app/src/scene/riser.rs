//! Riser and pipeline scenes: the line, its mesh, its ends and the optional effects.
//! Every key, its unit and its default are listed in `docs/scene.md`.

use catena_fe::environment::Hydro;
use catena_fe::model::LineModel;
use catena_fe::motion::TopMotion;

use super::checks::{iterations_at_least_one, positive, tolerance_in_range, Site};
use super::dynamic::dynamic_spec;
use super::edit::{self, Edit};
use super::line;
use super::sea::hydro_of;
use super::sections;
use super::{from_doc, invalid, parse, required, Resolver};
use crate::error::SceneError;

pub use super::dynamic::{DynamicSpec, DEFAULT_MAX_RECORDS};
pub use super::line::{Ends, LineProperties};
pub use super::outputs::Gauge;
pub use super::sea::KINEMATICS_PER_PERIOD;
pub use super::size::{run_size, RunSize, RECORD_BYTES_PER_NODE};
pub use super::tables::*;
use super::tables::{default_max_iter, default_tol};

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
    /// The ends as given (a default anchor height is found by the statics).
    pub ends: Ends,
    /// The flexjoint neutral angle from the vertical, rad, if given (else the static angle).
    pub flexjoint_neutral_from_vertical: Option<f64>,
    /// Static solve tolerance and iteration limit.
    pub statics: StaticTable,
    /// Water depth, m.
    pub water_depth: f64,
    /// Line summary: (EA, EI, submerged weight, mass); a line of sections': its top type's.
    pub line: LineProperties,
    /// The line types of a line of sections, indexed by the elements' `kind` (empty: the short
    /// form, one type).
    pub line_types: Vec<sections::LineType>,
    /// What the scene does that may not be meant (an unused line type), to be shown to the user.
    pub warnings: Vec<String>,
    /// The sea water's hydrodynamics (`[hydrodynamics]`, `[current]`), if any: a current acts in the
    /// statics too.
    pub hydro: Option<Hydro>,
    /// The dynamic analysis, if the scene has a `[dynamic]` table.
    pub dynamic: Option<DynamicSpec>,
    /// The run's size, estimated from the tables (checked against `[limits]`).
    pub size: RunSize,
    /// The pipe's installation (`[lay]`), if the scene is a lay.
    pub lay: Option<super::lay::LaySpec>,
    /// The seabed a lay left, to start the dynamics on (`[as_laid]`).
    pub as_laid: Option<super::as_laid::AsLaid>,
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
        // A line of sections is read as the short form of its top type (the checks on the ends
        // and the top's motion see that), with its own segments.
        let sectioned = sections::layout(file, raw)?;
        let normalised;
        let (raw, props, segments, line_types, warnings) = match sectioned {
            Some((layout, warnings)) => {
                normalised = sections::as_short_form(raw, &layout);
                let top = layout.types[layout.segments[0].kind].properties;
                (&normalised, top, layout.segments, layout.types, warnings)
            }
            None => {
                let props = line::line_properties(file, raw)?;
                if raw.mesh.is_empty() {
                    return Err(invalid(file, "mesh", "at least one [[mesh]] section"));
                }
                let segments = line::segments(file, raw, props)?;
                (raw, props, segments, Vec::new(), Vec::new())
            }
        };
        let size = run_size(file, raw)?;
        let lay = super::lay::lay_spec(file, raw)?;
        let as_laid = super::as_laid::as_laid(file, raw, files)?;
        let model = line::line_model(file, raw, segments)?;
        let ends = line::ends(file, raw)?;
        check_solvers(file, raw)?;
        check_current_profile(file, &doc)?;
        let _ = required::<f64>;
        let hydro = hydro_of(file, raw, env.water_density)?;
        let model = match &hydro {
            Some(h) => model.with_sea_coefficients(h.coefficients()),
            None => model,
        };
        let mut dynamic = match &raw.dynamic {
            Some(d) => Some(dynamic_spec(
                file,
                raw,
                d,
                hydro.clone(),
                Site {
                    length: raw.line.length,
                    water_depth: env.water_depth,
                    water_density: env.water_density,
                    gravity: env.gravity,
                    top_x: raw.ends.top_x,
                },
                files,
            )?),
            None => {
                check_no_dynamic_tables(file, raw)?;
                None
            }
        };
        if let (Some(d), false) = (&mut dynamic, line_types.is_empty()) {
            sections::attach(file, raw, &model, &line_types, d)?;
        }
        if let Some(d) = &dynamic {
            check_design_sections(file, d)?;
        }
        if let Some(m) = dynamic.as_ref().and_then(|d| d.motion.as_ref()) {
            check_motion_reach(file, raw, &ends, m)?;
        }
        Ok(Self {
            file: file.to_string(),
            text,
            doc,
            title: raw.title.clone().unwrap_or_else(|| file.to_string()),
            model,
            ends,
            flexjoint_neutral_from_vertical: raw
                .flexjoint
                .as_ref()
                .and_then(|f| f.neutral_angle_deg.map(f64::to_radians)),
            statics: raw.statics.clone().unwrap_or(StaticTable {
                tolerance: default_tol(),
                max_iterations: default_max_iter(),
            }),
            water_depth: env.water_depth,
            line: props,
            line_types,
            warnings,
            hydro,
            dynamic,
            size,
            lay,
            as_laid,
        })
    }
}

impl RiserScene {
    /// The names of the line types, indexed by the elements' `kind` (`["line"]` for the short
    /// form).
    pub fn line_type_names(&self) -> Vec<String> {
        if self.line_types.is_empty() {
            vec!["line".to_string()]
        } else {
            self.line_types.iter().map(|t| t.name.clone()).collect()
        }
    }

    /// The sections as `(type name, from, to)`, m of arc length from the top (one for the short
    /// form).
    pub fn sections(&self) -> Vec<(String, f64, f64)> {
        let names = self.line_type_names();
        let m = &self.model;
        let mut out: Vec<(String, f64, f64)> = Vec::new();
        for (e, el) in m.elements.iter().enumerate() {
            match out.last_mut() {
                Some(last) if e > 0 && m.elements[e - 1].kind == el.kind => last.2 = m.arc[e + 1],
                _ => out.push((names[el.kind].clone(), m.arc[e], m.arc[e + 1])),
            }
        }
        out
    }
}

/// `[static]` and `[dynamic]`'s Newton settings.
fn check_solvers(file: &str, raw: &RiserFile) -> Result<(), SceneError> {
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
    Ok(())
}

/// `current.profile`'s rows are pairs (`[f64; 2]` would read the first two numbers of a longer
/// entry and drop the rest).
fn check_current_profile(file: &str, doc: &toml::Table) -> Result<(), SceneError> {
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
    Ok(())
}

/// A `[design_check]` needs every node's section (a wall and a contents density), and its
/// corrosion allowance must leave some wall.
fn check_design_sections(file: &str, d: &DynamicSpec) -> Result<(), SceneError> {
    let Some(c) = &d.design_check else {
        return Ok(());
    };
    let least_wall = if d.node_sections.is_empty() {
        d.section.map(|s| s.wall)
    } else {
        d.node_sections.iter().map(|s| s.wall).reduce(f64::min)
    };
    let Some(wall) = least_wall else {
        return Err(invalid(
            file,
            "line.wall",
            "the wall thickness in m and the contents density (in [line] or [fatigue], or every line type's wall): the design check needs the section",
        ));
    };
    if c.corrosion_allowance >= wall {
        return Err(invalid(
            file,
            "design_check.corrosion_allowance",
            format!(
                "less than the thinnest wall ({wall} m), got {} m",
                c.corrosion_allowance
            ),
        ));
    }
    Ok(())
}

/// Without `[dynamic]`, no table that only acts in a dynamic run.
fn check_no_dynamic_tables(file: &str, raw: &RiserFile) -> Result<(), SceneError> {
    for (present, key) in [
        (raw.motion.is_some(), "motion"),
        (raw.waves.is_some(), "waves"),
        (raw.vessel.is_some(), "vessel"),
        (raw.structural_damping.is_some(), "structural_damping"),
        (raw.fatigue.is_some(), "fatigue"),
        (raw.design_check.is_some(), "design_check"),
        (raw.extremes.is_some(), "extremes"),
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
    Ok(())
}

/// The prescribed top motion keeps the top above the mudline and within the line's reach at its
/// extreme offsets (a harmonic moves along the segment between ±(surge, heave); staged and series
/// motions are piecewise linear between their points). A default anchor height is taken at
/// `D/2` ([`Ends::anchor_z_for_checks`]).
fn check_motion_reach(
    file: &str,
    raw: &RiserFile,
    ends: &Ends,
    m: &TopMotion,
) -> Result<(), SceneError> {
    let l = &raw.line;
    let ((top_x, top_z), anchor_x) = (ends.top, ends.anchor_x);
    let anchor_z = ends.anchor_z_for_checks(l.od);
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
        let (x, z) = (top_x + dx, top_z + dz);
        let reach = ((x - anchor_x).powi(2) + (z - anchor_z).powi(2)).sqrt();
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
    Ok(())
}
