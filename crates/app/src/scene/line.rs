//! The line of a scene: `[line]` and `[[mesh]]` into the elements' properties and segments, the
//! seabed contact and flexjoint, and the ends (`[ends]`), each checked. No physics here: a default
//! anchor height (the pipe resting at its static embedment) is found by the statics
//! ([`Ends::positions`]).

use catena_fe::beam::Section;
use catena_fe::model::{Attachment, LineModel, LineSpec, SeabedContact, Segment, Support};
use catena_fe::statics::EndPositions;

use super::checks::positive;
use super::invalid;
use super::tables::{EnvironmentTable, MeshTable, RiserFile, SupportKey};
use crate::error::SceneError;

/// The uniform line's properties: `(EA, EI, submerged weight, mass)` in N, N·m², N/m, kg/m.
pub type LineProperties = (f64, f64, f64, f64);

/// The line's ends as the scene gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ends {
    /// The top end `(x, z)`, m (z above the mudline).
    pub top: (f64, f64),
    /// The anchor's x, m.
    pub anchor_x: f64,
    /// The anchor's height above the mudline, m; `None`: the pipe rests on the seabed at its static
    /// embedment there, which the statics find.
    pub anchor_z: Option<f64>,
}

impl Ends {
    /// The end positions for the statics. A default anchor height is `D/2 − e`, `e` the static
    /// embedment of the submerged weight of the line's last element (N/m) on the Model's seabed
    /// there (0 if none is found).
    pub fn positions(&self, model: &LineModel) -> EndPositions {
        let w = model.elements.last().map_or(0.0, |e| e.weight);
        let z = self.anchor_z.unwrap_or_else(|| {
            // On the soil at the anchor (its zone's, else the default).
            let d = model.node_od[model.nodes() - 1];
            let emb = model
                .seabed_law_for(self.anchor_x, d)
                .and_then(|sb| catena_fe::statics::static_embedment_on(sb, d, w))
                .unwrap_or(0.0);
            let (zm, m) = model.mudline_at(self.anchor_x);
            zm + (0.5 * d - emb) * (1.0 + m * m).sqrt()
        });
        EndPositions {
            top: self.top,
            anchor: (self.anchor_x, z),
        }
    }

    /// The anchor height the scene's checks use: the given one, or the pipe resting on the mudline
    /// (`D/2`; its static embedment lowers it by at most a fraction of a diameter).
    pub fn anchor_z_for_checks(&self, od: f64) -> f64 {
        self.anchor_z.unwrap_or(0.5 * od)
    }
}

/// A pipe's keys as written (`[line]`'s or a `[[line_type]]`'s), with the key prefix for messages
/// and the diameter that displaces water (the outer diameter, or a line type's hydrodynamic one).
pub(super) struct PipeKeys<'a> {
    pub(super) prefix: &'a str,
    pub(super) od: f64,
    pub(super) wall: Option<f64>,
    pub(super) youngs_modulus: Option<f64>,
    pub(super) ea: Option<f64>,
    pub(super) ei: Option<f64>,
    pub(super) submerged_weight: Option<f64>,
    pub(super) mass: Option<f64>,
    pub(super) steel_density: Option<f64>,
    pub(super) contents_density: Option<f64>,
    pub(super) displaced_od: f64,
}

/// `[line]` → EA, EI, submerged weight and mass, from the stiffnesses and weights given, or from
/// the steel's modulus, the wall and the densities.
pub(super) fn line_properties(file: &str, raw: &RiserFile) -> Result<LineProperties, SceneError> {
    let l = &raw.line;
    positive(file, "line.length", l.length, "a length in m")?;
    let props = pipe_properties(
        file,
        &PipeKeys {
            prefix: "line",
            od: l.od,
            wall: l.wall,
            youngs_modulus: l.youngs_modulus,
            ea: l.ea,
            ei: l.ei,
            submerged_weight: l.submerged_weight,
            mass: l.mass,
            steel_density: l.steel_density,
            contents_density: l.contents_density,
            displaced_od: l.od,
        },
        &raw.environment,
    )?;
    positive(
        file,
        "line.submerged_weight",
        props.2,
        "a submerged weight in N/m",
    )?;
    Ok(props)
}

/// A pipe's EA, EI, submerged weight (any sign: negative is net buoyant) and mass, checked.
pub(super) fn pipe_properties(
    file: &str,
    l: &PipeKeys<'_>,
    env: &EnvironmentTable,
) -> Result<LineProperties, SceneError> {
    let key = |k: &str| format!("{}.{k}", l.prefix);
    positive(file, &key("od"), l.od, "a diameter in m")?;
    if !(0.005..=5.0).contains(&l.od) {
        return Err(invalid(
            file,
            key("od"),
            format!("an outer diameter between 0.005 and 5 m (got {} m)", l.od),
        ));
    }
    let pi = std::f64::consts::PI;
    let (a_steel, a_inner) = match l.wall {
        Some(t) => {
            if !(t > 0.0 && 2.0 * t < l.od) {
                return Err(invalid(
                    file,
                    key("wall"),
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
                    key("wall"),
                    format!(
                        "the wall thickness in m (needed with {})",
                        key("youngs_modulus")
                    ),
                )
            })?;
            positive(file, &key("youngs_modulus"), e, "a modulus in Pa")?;
            (e * a_steel, e * i)
        }
        _ => {
            return Err(invalid(
                file,
                key("youngs_modulus"),
                "either youngs_modulus (with wall) or both ea and ei",
            ))
        }
    };
    positive(file, &key("ea"), ea, "an axial stiffness in N")?;
    positive(file, &key("ei"), ei, "a bending stiffness in N·m²")?;
    let g = env.gravity;
    let a_outer = pi / 4.0 * l.displaced_od * l.displaced_od;
    let from_densities = match (l.steel_density, l.contents_density) {
        (Some(rs), Some(rc)) => {
            if l.wall.is_none() {
                return Err(invalid(
                    file,
                    key("wall"),
                    "the wall thickness (needed with the densities)",
                ));
            }
            let m = rs * a_steel + rc * a_inner;
            Some((m, (m - env.water_density * a_outer) * g))
        }
        (None, None) => None,
        // The contents' density alone, with the mass and weight given: for the wall tension only.
        (None, Some(_)) if l.mass.is_some() && l.submerged_weight.is_some() => None,
        _ => {
            return Err(invalid(
                file,
                key("contents_density"),
                "both steel_density and contents_density, or neither (contents_density alone with mass and submerged_weight)",
            ))
        }
    };
    let (mass, weight) = match (l.mass, l.submerged_weight, from_densities) {
        (Some(m), Some(w), None) => (m, w),
        (None, None, Some(mw)) => mw,
        _ => return Err(invalid(
            file,
            key("submerged_weight"),
            "either mass and submerged_weight, or steel_density and contents_density (with wall)",
        )),
    };
    if !weight.is_finite() {
        return Err(invalid(
            file,
            key("submerged_weight"),
            "a finite submerged weight in N/m",
        ));
    }
    positive(file, &key("mass"), mass, "a mass in kg/m")?;
    Ok((ea, ei, weight, mass))
}

/// `[[mesh]]` → the segments, from the top, each ending at its `to` (the last at the line's length).
pub(super) fn segments(
    file: &str,
    raw: &RiserFile,
    (ea, ei, weight, mass): LineProperties,
) -> Result<Vec<Segment>, SceneError> {
    let l = &raw.line;
    if raw.mesh.is_empty() {
        return Err(invalid(file, "mesh", "at least one [[mesh]] section"));
    }
    let lengths = mesh_lengths(file, "mesh", &raw.mesh, l.length)?;
    let segments = raw
        .mesh
        .iter()
        .zip(lengths)
        .map(|(m, length)| Segment {
            wall: l.wall,
            ..Segment::uniform(
                length,
                m.element_length,
                Section { ea, ei },
                weight,
                mass,
                l.od,
            )
        })
        .collect();
    Ok(segments)
}

/// The lengths of a line's sections as written (`[[mesh]]` or `[[section]]`, the array `table`),
/// checked: each ends (`to`, m of arc length from the top) beyond the previous one's end, has an
/// element length > 0, and the last ends at the line's `length`.
pub(super) fn mesh_lengths(
    file: &str,
    table: &str,
    rows: &[MeshTable],
    length: f64,
) -> Result<Vec<f64>, SceneError> {
    let mut out = Vec::with_capacity(rows.len());
    let mut from = 0.0;
    for (i, m) in rows.iter().enumerate() {
        if m.to.is_nan() || m.to <= from {
            return Err(invalid(
                file,
                format!("{table}[{i}].to"),
                format!(
                    "an arc length beyond the previous section's end ({from} m), got {}",
                    m.to
                ),
            ));
        }
        positive(
            file,
            &format!("{table}[{i}].element_length"),
            m.element_length,
            "an element length in m",
        )?;
        out.push(m.to - from);
        from = m.to;
    }
    if (from - length).abs() > 1e-9 * length {
        return Err(invalid(
            file,
            format!("{table}[{}].to", rows.len().saturating_sub(1)),
            format!("the line length {length} m (the last section must end there), got {from}"),
        ));
    }
    Ok(out)
}

/// The line Model: segments, supports, the seabed contact (`[seabed]`) and the flexjoint
/// (`[flexjoint]`, its neutral angle set by the statics).
pub(super) fn line_model(
    file: &str,
    raw: &RiserFile,
    segments: Vec<Segment>,
) -> Result<LineModel, SceneError> {
    let env = &raw.environment;
    // The seabed's default law is for the contact diameter at the anchor, which lies on it; a line
    // of sections gets laws for its other contact diameters too (unless `[seabed] diameter` sets
    // one for all).
    let d_anchor = segments.last().map_or(raw.line.od, |s| s.contact_od);
    let mut diameters: Vec<f64> = Vec::new();
    for s in &segments {
        if s.contact_od != d_anchor && !diameters.contains(&s.contact_od) {
            diameters.push(s.contact_od);
        }
    }
    let seabed = match &raw.seabed {
        Some(t) => Some(SeabedContact {
            seabed: t.build(file, "seabed", Some(d_anchor), Some(env.water_density))?,
            mudline_z: 0.0,
            friction: t.friction(file, "seabed")?,
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
    let zones = match &raw.seabed {
        Some(t) => t.zones(file, "seabed", Some(d_anchor), Some(env.water_density))?,
        None => Vec::new(),
    };
    let mut diameter_laws = Vec::new();
    if let Some(t) = raw.seabed.as_ref().filter(|t| t.diameter.is_none()) {
        for d in diameters {
            let rho = Some(env.water_density);
            let laws = t.zones(file, "seabed", Some(d), rho)?;
            diameter_laws.push((
                d,
                t.build(file, "seabed", Some(d), rho)?,
                laws.into_iter().map(|z| z.seabed).collect(),
            ));
        }
    }
    let profile = match &raw.seabed {
        Some(t) => t.profile(file, "seabed", env.water_depth)?,
        None => Vec::new(),
    };
    Ok(model
        .with_attachments(&attachments(file, raw)?)
        .with_seabed_zones(zones)
        .with_diameter_laws(diameter_laws)
        .with_mudline_profile(profile))
}

/// `[[attachment]]`, checked: an arc length on the line, a mass ≥ 0 kg, a finite submerged weight
/// (N, negative: buoyant), a drag area ≥ 0 m² and an added mass ≥ 0 kg (these two only with
/// `[hydrodynamics]`). Each is carried by the node nearest to its arc length.
fn attachments(file: &str, raw: &RiserFile) -> Result<Vec<(f64, Attachment)>, SceneError> {
    let length = raw.line.length;
    let mut out = Vec::new();
    for (i, a) in raw.attachment.iter().enumerate() {
        let key = |k: &str| format!("attachment[{i}].{k}");
        if !(0.0..=length).contains(&a.arc) {
            return Err(invalid(
                file,
                key("arc"),
                format!(
                    "an arc length from the top within [0, {length}] m (got {})",
                    a.arc
                ),
            ));
        }
        for (k, v, what) in [
            ("mass", a.mass, "a mass >= 0 kg"),
            ("drag_area", a.drag_area, "a drag area Cd·A >= 0 m²"),
            ("added_mass", a.added_mass, "an added mass >= 0 kg"),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(invalid(file, key(k), format!("{what} (got {v})")));
            }
        }
        if !a.submerged_weight.is_finite() {
            return Err(invalid(
                file,
                key("submerged_weight"),
                "a finite submerged weight in N (negative: buoyant)",
            ));
        }
        if raw.hydrodynamics.is_none() && (a.drag_area > 0.0 || a.added_mass > 0.0) {
            let k = if a.drag_area > 0.0 {
                "drag_area"
            } else {
                "added_mass"
            };
            return Err(invalid(
                file,
                key(k),
                "a [hydrodynamics] table as well (the water's density and the drag act through it)",
            ));
        }
        out.push((
            a.arc,
            Attachment {
                node: 0,
                mass: a.mass,
                weight: a.submerged_weight,
                drag_area: a.drag_area,
                added_mass: a.added_mass,
            },
        ));
    }
    Ok(out)
}

/// `[ends]`, checked: finite coordinates, the top above the mudline, within the water and on the
/// vessel side of the anchor, the anchor below the surface and above the top's height, the line
/// longer than the chord between them. Without `anchor_z` the line must have a seabed.
pub(super) fn ends(file: &str, raw: &RiserFile) -> Result<Ends, SceneError> {
    let (e, l, env) = (&raw.ends, &raw.line, &raw.environment);
    for (k, v) in [
        ("ends.top_x", e.top_x),
        ("ends.top_z", e.top_z),
        ("ends.anchor_x", e.anchor_x),
    ] {
        if !v.is_finite() {
            return Err(invalid(file, k, "a finite coordinate in m"));
        }
    }
    if e.anchor_z.is_none() && raw.seabed.is_none() {
        return Err(invalid(
            file,
            "ends.anchor_z",
            "the anchor height in m (required without a [seabed])",
        ));
    }
    let ends = Ends {
        top: (e.top_x, e.top_z),
        anchor_x: e.anchor_x,
        anchor_z: e.anchor_z,
    };
    let anchor_z = ends.anchor_z_for_checks(l.od);
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
    Ok(ends)
}
