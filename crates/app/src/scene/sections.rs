//! `[[line_type]]` and `[[section]]`: a line of sections (a touchdown joint, a tapered stress joint,
//! a buoyancy section: the steel lazy wave) into segments with each type's properties, checked.
//!
//! A line type has the pipe keys of `[line]`'s short form (`od`, `wall`, `youngs_modulus` or `ea`
//! and `ei`, the densities or `mass` and `submerged_weight`, which may be negative: net buoyant),
//! and optionally:
//! - `hydrodynamic_od` (drag, added mass and, with the densities, the displaced volume; default
//!   `od`) and `contact_od` (the seabed's contact diameter; default `hydrodynamic_od`);
//! - `cd_normal`, `cd_axial`, `ca_normal`: its own Morison coefficients (the others from
//!   `[hydrodynamics]`);
//! - `sn_curve`, `scf`: its own fatigue data (else `[fatigue]`'s);
//! - `od_end`, `wall_end`: a **taper** (a stress joint), the outer diameter and wall varying
//!   linearly from `od`, `wall` at the section's top to these at its bottom; each element has the
//!   properties at its middle (EA, EI and, with the densities, mass and weight from them).
//!
//! Sections run from the top in order, each ending at its `to` (m of arc length), the last at
//! `line.length`. With sections, `[line]` holds only the length; `[[mesh]]` belongs to the short
//! form and may not be given with them.

use catena_fe::beam::Section;
use catena_fe::environment::Coefficients;
use catena_fe::model::{LineModel, Segment};

use super::checks::positive;
use super::dynamic::DynamicSpec;
use super::invalid;
use super::line::{mesh_lengths, pipe_properties, LineProperties, PipeKeys};
use super::outputs::sn_curve_of;
use super::tables::{LineTypeTable, MeshTable, RiserFile};
use crate::checks::fatigue::sn::SnCurve;
use crate::checks::fatigue::stress::PipeSection;
use crate::error::SceneError;

/// A line type, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct LineType {
    /// Its name.
    pub name: String,
    /// Its properties at its top: EA, EI, submerged weight, mass.
    pub properties: LineProperties,
    /// Its contents density, kg/m³, if given.
    pub contents_density: Option<f64>,
    /// Its own S-N curve (with its name), if given.
    pub sn_curve: Option<(SnCurve, String)>,
    /// Its own stress concentration factor, if given.
    pub scf: Option<f64>,
}

/// A line of sections: its types and segments, and its sections' ends and element lengths as the
/// short form's `[[mesh]]` would give them (the run's size is estimated from these).
#[derive(Debug, Clone)]
pub(super) struct Layout {
    pub(super) types: Vec<LineType>,
    pub(super) segments: Vec<Segment>,
    pub(super) mesh: Vec<MeshTable>,
}

/// The line of sections with its warnings (a line type no section uses), or `None` for the short
/// form (no `[[section]]`). A section naming an unknown type is an error.
pub(super) fn layout(
    file: &str,
    raw: &RiserFile,
) -> Result<Option<(Layout, Vec<String>)>, SceneError> {
    if raw.section.is_empty() {
        // A lay's `[[line_type]]` is its A&R wire's (`scene/lay.rs` checks it).
        if let Some(t) = raw.line_type.first().filter(|_| raw.lay.is_none()) {
            return Err(invalid(
                file,
                "section",
                format!(
                    "[[section]] tables using the line types (line type \"{}\" is given, no section)",
                    t.name
                ),
            ));
        }
        return Ok(None);
    }
    let l = &raw.line;
    positive(file, "line.length", l.length, "a length in m")?;
    // Both forms at once is a mistake the user should hear about.
    let short_form = [
        ("od", !l.od.is_nan()),
        ("wall", l.wall.is_some()),
        ("youngs_modulus", l.youngs_modulus.is_some()),
        ("ea", l.ea.is_some()),
        ("ei", l.ei.is_some()),
        ("submerged_weight", l.submerged_weight.is_some()),
        ("mass", l.mass.is_some()),
        ("steel_density", l.steel_density.is_some()),
        ("contents_density", l.contents_density.is_some()),
    ];
    if let Some((k, _)) = short_form.iter().find(|(_, given)| *given) {
        return Err(invalid(
            file,
            format!("line.{k}"),
            "only the length with [[section]] (the pipe's properties go in [[line_type]])",
        ));
    }
    if !raw.mesh.is_empty() {
        return Err(invalid(
            file,
            "mesh",
            "no [[mesh]] with [[section]] (each section has its element_length)",
        ));
    }
    let mut types = Vec::new();
    for (i, t) in raw.line_type.iter().enumerate() {
        if raw.line_type[..i].iter().any(|u| u.name == t.name) {
            return Err(invalid(
                file,
                format!("line_type[{i}].name"),
                format!("a name no other line type has (\"{}\" is taken)", t.name),
            ));
        }
        types.push(line_type(file, raw, i, t)?);
    }
    let mesh: Vec<MeshTable> = raw
        .section
        .iter()
        .map(|s| MeshTable {
            to: s.to,
            element_length: s.element_length,
        })
        .collect();
    let lengths = mesh_lengths(file, "section", &mesh, l.length)?;
    let mut segments = Vec::new();
    let mut used = vec![false; types.len()];
    for (j, (s, length)) in raw.section.iter().zip(lengths).enumerate() {
        let k = raw
            .line_type
            .iter()
            .position(|t| t.name == s.kind)
            .ok_or_else(|| {
                let names: Vec<&str> = raw.line_type.iter().map(|t| t.name.as_str()).collect();
                invalid(
                    file,
                    format!("section[{j}].type"),
                    format!(
                        "the name of a [[line_type]] (one of: {}), got \"{}\"",
                        names.join(", "),
                        s.kind
                    ),
                )
            })?;
        used[k] = true;
        segments.extend(section_segments(
            file,
            raw,
            k,
            &raw.line_type[k],
            length,
            s.element_length,
        )?);
    }
    let warnings = used
        .iter()
        .zip(&types)
        .filter(|(u, _)| !**u)
        .map(|(_, t)| format!("{file}: line type \"{}\" is used by no section", t.name))
        .collect();
    Ok(Some((
        Layout {
            types,
            segments,
            mesh,
        },
        warnings,
    )))
}

/// The keys of line type `t` at the outer diameter `od` and wall `wall`.
fn keys<'a>(prefix: &'a str, t: &LineTypeTable, od: f64, wall: Option<f64>) -> PipeKeys<'a> {
    PipeKeys {
        prefix,
        od,
        wall,
        youngs_modulus: t.youngs_modulus,
        ea: t.ea,
        ei: t.ei,
        submerged_weight: t.submerged_weight,
        mass: t.mass,
        steel_density: t.steel_density,
        contents_density: t.contents_density,
        displaced_od: t.hydrodynamic_od.unwrap_or(od),
    }
}

/// Line type `i`, checked (a taper's end too).
pub(super) fn line_type(
    file: &str,
    raw: &RiserFile,
    i: usize,
    t: &LineTypeTable,
) -> Result<LineType, SceneError> {
    let prefix = format!("line_type[{i}]");
    let key = |k: &str| format!("{prefix}.{k}");
    let properties = pipe_properties(file, &keys(&prefix, t, t.od, t.wall), &raw.environment)?;
    for (k, v) in [
        ("hydrodynamic_od", t.hydrodynamic_od),
        ("contact_od", t.contact_od),
    ] {
        if let Some(d) = v {
            if !(d.is_finite() && (0.005..=10.0).contains(&d)) {
                return Err(invalid(
                    file,
                    key(k),
                    format!("a diameter between 0.005 and 10 m (got {d})"),
                ));
            }
        }
    }
    if t.od_end.is_some() || t.wall_end.is_some() {
        let (Some(od_end), Some(wall_end)) = (t.od_end, t.wall_end) else {
            return Err(invalid(
                file,
                key(if t.od_end.is_none() {
                    "od_end"
                } else {
                    "wall_end"
                }),
                "both od_end and wall_end for a taper (m, at the section's bottom)",
            ));
        };
        if t.youngs_modulus.is_none() || t.wall.is_none() {
            return Err(invalid(
                file,
                key("youngs_modulus"),
                "youngs_modulus and wall for a taper (its stiffness follows its size)",
            ));
        }
        if !(od_end > 0.0 && od_end.is_finite()) {
            return Err(invalid(
                file,
                key("od_end"),
                format!("an outer diameter > 0 m (got {od_end})"),
            ));
        }
        if !(wall_end > 0.0 && 2.0 * wall_end < od_end) {
            return Err(invalid(
                file,
                key("wall_end"),
                format!("0 < wall_end < od_end/2 (got {wall_end})"),
            ));
        }
        pipe_properties(
            file,
            &keys(&prefix, t, od_end, Some(wall_end)),
            &raw.environment,
        )?;
    }
    for (k, v) in [
        ("cd_normal", t.cd_normal),
        ("cd_axial", t.cd_axial),
        ("ca_normal", t.ca_normal),
    ] {
        if let Some(v) = v {
            if !(v.is_finite() && v >= 0.0) {
                return Err(invalid(
                    file,
                    key(k),
                    format!("a coefficient >= 0, got {v}"),
                ));
            }
            if raw.hydrodynamics.is_none() {
                return Err(invalid(
                    file,
                    key(k),
                    "a [hydrodynamics] table as well (the sea's density and the other coefficients)",
                ));
            }
        }
    }
    let sn_curve = match &t.sn_curve {
        Some(k) => Some(sn_curve_of(file, &key("sn_curve"), k)?),
        None => None,
    };
    if let Some(scf) = t.scf {
        if !(scf.is_finite() && scf >= 1.0) {
            return Err(invalid(
                file,
                key("scf"),
                format!("a stress concentration factor >= 1, got {scf}"),
            ));
        }
    }
    if let Some(c) = t.contents_density {
        if !(c.is_finite() && c >= 0.0) {
            return Err(invalid(
                file,
                key("contents_density"),
                "a density >= 0 kg/m³",
            ));
        }
    }
    Ok(LineType {
        name: t.name.clone(),
        properties,
        contents_density: t.contents_density,
        sn_curve,
        scf: t.scf,
    })
}

/// The segments of a section `length` m long of line type `k` (`t`): one, or, tapered, one per
/// element with the taper's properties at its middle.
pub(super) fn section_segments(
    file: &str,
    raw: &RiserFile,
    k: usize,
    t: &LineTypeTable,
    length: f64,
    element_length: f64,
) -> Result<Vec<Segment>, SceneError> {
    let coefficients = match (&raw.hydrodynamics, t.cd_normal, t.cd_axial, t.ca_normal) {
        (_, None, None, None) | (None, ..) => None,
        (Some(h), cd_n, cd_a, ca) => Some(Coefficients {
            cd_normal: cd_n.unwrap_or(h.cd_normal),
            cd_axial: cd_a.unwrap_or(h.cd_axial),
            ca_normal: ca.unwrap_or(h.ca_normal),
        }),
    };
    let prefix = format!("line_type[{k}]");
    let segment = |od: f64, wall: Option<f64>, length: f64, element_length: f64| {
        let (ea, ei, weight, mass) =
            pipe_properties(file, &keys(&prefix, t, od, wall), &raw.environment)?;
        let hydro_od = t.hydrodynamic_od.unwrap_or(od);
        Ok::<_, SceneError>(Segment {
            length,
            element_length,
            section: Section { ea, ei },
            weight,
            mass,
            od,
            hydro_od,
            contact_od: t.contact_od.unwrap_or(hydro_od),
            coefficients,
            kind: k,
            wall,
        })
    };
    match (t.od_end, t.wall_end, t.wall) {
        (Some(od_end), Some(wall_end), Some(wall)) => {
            let n = (length / element_length).ceil().max(1.0) as usize;
            (0..n)
                .map(|m| {
                    let f = (m as f64 + 0.5) / n as f64;
                    let od = t.od + f * (od_end - t.od);
                    let w = wall + f * (wall_end - wall);
                    segment(od, Some(w), length / n as f64, length / n as f64)
                })
                .collect()
        }
        _ => Ok(vec![segment(t.od, t.wall, length, element_length)?]),
    }
}

/// The file as the short form of the line's top type: `[line]` with the top segment's diameter and
/// wall and the top type's contents density, `[[mesh]]` the sections' ends. What reads `[line]` for
/// a single number (the ends' checks, the default section of the stress range graphs) sees the top
/// type; everything per element reads the segments.
pub(super) fn as_short_form(raw: &RiserFile, layout: &Layout) -> RiserFile {
    let mut r = raw.clone();
    let top = &layout.segments[0];
    r.line.od = top.od;
    r.line.wall = top.wall;
    r.line.contents_density = layout.types[top.kind].contents_density;
    r.mesh = layout.mesh.clone();
    r
}

/// For each node, the element whose section its stresses are recovered with: of its two, the one
/// with the smaller section modulus `I/(D/2)` (at a change of section, the larger stress), on a tie
/// the one below it; an end node's one element. Elements without a wall count as strong.
pub fn node_elements(model: &LineModel) -> Vec<usize> {
    let ne = model.elements.len();
    let modulus = |e: usize| {
        let el = &model.elements[e];
        el.wall.map_or(f64::INFINITY, |t| {
            let id = el.od - 2.0 * t;
            std::f64::consts::PI / 32.0 * (el.od.powi(4) - id.powi(4)) / el.od
        })
    };
    (0..=ne)
        .map(|i| match i {
            0 => 0,
            i if i == ne => ne - 1,
            i => {
                if modulus(i - 1) < modulus(i) {
                    i - 1
                } else {
                    i
                }
            }
        })
        .collect()
}

/// Each node's element ([`node_elements`]) and pipe section for a line of sections: `template`
/// (the contents, pressures and sea) with the element's outer diameter and wall, and the contents
/// density `contents` if given (`[fatigue]`'s), else its line type's, else the template's. `None`
/// if an element has no wall.
pub fn node_sections(
    model: &LineModel,
    types: &[LineType],
    template: &PipeSection,
    contents: Option<f64>,
) -> Option<Vec<(usize, PipeSection)>> {
    node_elements(model)
        .into_iter()
        .map(|e| {
            let el = &model.elements[e];
            let density = contents
                .or(types[el.kind].contents_density)
                .unwrap_or(template.contents_density);
            Some((
                e,
                PipeSection {
                    od: el.od,
                    wall: el.wall?,
                    contents_density: density,
                    ..*template
                },
            ))
        })
        .collect()
}

/// A line of sections' stress recovery and fatigue per node, into `spec`: each node's section for
/// the range graphs, and with `[fatigue]` each node's section, S-N curve and SCF (its line type's,
/// else the table's). With `[fatigue]` every line type needs a wall.
pub(super) fn attach(
    file: &str,
    raw: &RiserFile,
    model: &LineModel,
    types: &[LineType],
    spec: &mut DynamicSpec,
) -> Result<(), SceneError> {
    let contents = raw.fatigue.as_ref().and_then(|f| f.contents_density);
    if let Some(f) = &mut spec.fatigue {
        for (i, t) in raw.line_type.iter().enumerate() {
            if t.wall.is_none() {
                return Err(invalid(
                    file,
                    format!("line_type[{i}].wall"),
                    "the wall thickness in m (fatigue needs every section's stresses)",
                ));
            }
        }
        f.nodes = node_sections(model, types, &f.section, contents)
            .unwrap_or_default()
            .into_iter()
            .map(|(e, sec)| {
                let t = &types[model.elements[e].kind];
                let curve = t.sn_curve.as_ref().map_or(f.curve, |c| c.0);
                (sec, curve, t.scf.unwrap_or(f.scf))
            })
            .collect();
    }
    spec.node_sections = spec
        .section
        .and_then(|template| node_sections(model, types, &template, contents))
        .map(|v| v.into_iter().map(|(_, sec)| sec).collect())
        .unwrap_or_default();
    if spec.node_sections.is_empty() {
        // Some type has no wall: no stress range graphs (the top type's would be wrong elsewhere).
        spec.section = None;
    }
    Ok(())
}

/// What a line's nodes are made of, for the outputs: each node's line type (of its element, see
/// [`node_elements`]), steel outer diameter and wall (NaN if not given), and hydrodynamic and
/// contact diameters (the means of its elements', as the loads use them), m.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NodeProperties {
    /// The line type's index (into [`RiserScene::line_type_names`](super::riser::RiserScene::line_type_names)).
    pub kind: Vec<usize>,
    /// Steel outer diameter, m.
    pub od: Vec<f64>,
    /// Wall thickness, m (NaN where not given).
    pub wall: Vec<f64>,
    /// Hydrodynamic diameter, m.
    pub hydrodynamic_od: Vec<f64>,
    /// Seabed contact diameter, m.
    pub contact_od: Vec<f64>,
}

/// Each node's properties (see [`NodeProperties`]).
pub fn node_properties(model: &LineModel) -> NodeProperties {
    let els = node_elements(model);
    NodeProperties {
        kind: els.iter().map(|&e| model.elements[e].kind).collect(),
        od: els.iter().map(|&e| model.elements[e].od).collect(),
        wall: els
            .iter()
            .map(|&e| model.elements[e].wall.unwrap_or(f64::NAN))
            .collect(),
        hydrodynamic_od: model.node_hydro_od.clone(),
        contact_od: model.node_od.clone(),
    }
}
