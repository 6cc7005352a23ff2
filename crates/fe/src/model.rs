//! The Model: everything a case fixes for the run — mesh, sections, loads, supports and the optional
//! effects (seabed, flexjoint). Built once by [`LineModel::build`], then immutable.
//!
//! A line is a chain of nodes numbered from the **top** (node 0) to the anchor; element `e` joins
//! nodes `e` and `e + 1`. Each node has three degrees of freedom `(x, z, θ)`, global index
//! `3·node + k`. The reference (stress-free) configuration is straight: element `e` has unstretched
//! length `L0_e` and no natural curvature.
//!
//! Loads and contact (per unit **unstretched** length):
//! - submerged weight `w`, lumped to the two end nodes of each element (`w·L0/2` each, downward);
//! - seabed reaction at the nodes over their tributary length `(L0_left + L0_right)/2`, from the
//!   penetration of the pipe invert `z_pen = z_mudline − (z − D/2)` (positive down);
//! - flexjoint: a rotational spring `M = −k_θ (θ − θ_neutral)` at one node.
//!
//! **Sections.** Each element carries its own properties (stiffness, weight, mass, the steel outer
//! diameter, the hydrodynamic and contact diameters, optionally its own Morison coefficients, and
//! the index of its line type). A node's contact and hydrodynamic diameters and coefficients are
//! the means of its two elements' (an end node's: its one element's); its weight, mass and
//! tributary length are the sums of its elements' halves. A uniform line is one segment; a line of
//! sections is several, a tapered section one segment per element (each with the taper's
//! properties at the element's middle).

use catena_seabed::law::Seabed;

use crate::beam::Section;
use crate::environment::Coefficients;

/// A length of line with one cross-section and one element length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Unstretched length, m.
    pub length: f64,
    /// Target element length, m (the segment gets `ceil(length/element_length)` equal elements).
    pub element_length: f64,
    /// Axial and bending stiffness.
    pub section: Section,
    /// Submerged weight per unit length, N/m (positive down).
    pub weight: f64,
    /// Structural mass per unit length (steel and contents), kg/m.
    pub mass: f64,
    /// Outer diameter of the steel, m (stress, rotary inertia).
    pub od: f64,
    /// Hydrodynamic diameter, m: drag and added mass (a coating's, or buoyancy modules' smeared).
    pub hydro_od: f64,
    /// Seabed contact diameter, m.
    pub contact_od: f64,
    /// The segment's own Morison coefficients, if its line type has them (else the sea's).
    pub coefficients: Option<Coefficients>,
    /// The index of its line type (0 for a uniform line): outputs name sections by it.
    pub kind: usize,
    /// The steel wall's thickness, m, if known (stress recovery reads it; the stiffness is given).
    pub wall: Option<f64>,
}

impl Segment {
    /// A segment of one pipe whose three diameters are its outer diameter `od`, with the sea's
    /// coefficients, line type 0.
    pub fn uniform(
        length: f64,
        element_length: f64,
        section: Section,
        weight: f64,
        mass: f64,
        od: f64,
    ) -> Self {
        Self {
            length,
            element_length,
            section,
            weight,
            mass,
            od,
            hydro_od: od,
            contact_od: od,
            coefficients: None,
            kind: 0,
            wall: None,
        }
    }
}

/// How an end of the line is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Support {
    /// Position prescribed, rotation free.
    Pinned,
    /// Position and rotation prescribed.
    Fixed,
    /// Nothing prescribed (a free end, e.g. a cantilever tip).
    Free,
}

/// One element's properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    /// Unstretched length, m.
    pub l0: f64,
    /// Stiffness.
    pub section: Section,
    /// Submerged weight, N/m.
    pub weight: f64,
    /// Mass, kg/m.
    pub mass: f64,
    /// Outer diameter of the steel, m.
    pub od: f64,
    /// Hydrodynamic diameter, m.
    pub hydro_od: f64,
    /// Seabed contact diameter, m.
    pub contact_od: f64,
    /// Its own Morison coefficients, if any.
    pub coefficients: Option<Coefficients>,
    /// Its line type's index.
    pub kind: usize,
    /// Its steel wall's thickness, m, if known.
    pub wall: Option<f64>,
}

/// The seabed under the line: a flat mudline at `z = mudline_z` and the contact law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeabedContact {
    /// The law (and soil buoyancy).
    pub seabed: Seabed,
    /// Height of the mudline, m (0 in catena's cases).
    pub mudline_z: f64,
    /// Axial friction along the mudline, if the scene has it (dynamics only).
    pub friction: Option<AxialFriction>,
}

/// Axial seabed friction, elastic–slip (Coulomb): at a node pressed on the seabed by `N` (its
/// seabed force over its tributary length, N), a spring of stiffness `μN/δ` from the node's
/// anchor position up to `±μN`, beyond which the pipe slides and the anchor follows it
/// ([`crate::loads`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialFriction {
    /// The Coulomb coefficient μ on the normal seabed force.
    pub mu: f64,
    /// The axial displacement that mobilises full friction δ, m.
    pub mobilisation: f64,
}

/// A rotational spring at a node (a flexjoint).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexJoint {
    /// The node.
    pub node: usize,
    /// Rotational stiffness, N·m/rad.
    pub stiffness: f64,
    /// The absolute tangent angle at which the joint carries no moment, rad.
    pub neutral: f64,
}

/// A stretch of seabed whose soil differs from the `[seabed]` default: the law that holds for
/// nodes whose x (in the static analysis' base configuration) lies in `[from_x, to_x)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeabedZone {
    /// Where it starts, m (horizontal position).
    pub from_x: f64,
    /// Where it ends, m.
    pub to_x: f64,
    /// Its law (the same kind as the default's, other parameters).
    pub seabed: Seabed,
}

/// A body attached at a node (a clump weight, a discrete buoyancy module): its mass, its submerged
/// weight (negative: buoyant), and, in water, its drag area and added mass (both isotropic: a
/// compact body, unlike the pipe's normal-only drag and added mass).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    /// The node that carries it (the nearest to the arc length given).
    pub node: usize,
    /// Mass, kg.
    pub mass: f64,
    /// Submerged weight, N (negative: net buoyant).
    pub weight: f64,
    /// Drag area `Cd·A`, m² (drag `½ρ·CdA·|u|u` on the velocity `u` relative to the water).
    pub drag_area: f64,
    /// Added mass, kg.
    pub added_mass: f64,
}

/// What is needed to build a line.
#[derive(Debug, Clone, PartialEq)]
pub struct LineSpec {
    /// Segments from the top to the anchor.
    pub segments: Vec<Segment>,
    /// The top end's support.
    pub top: Support,
    /// The anchor end's support.
    pub anchor: Support,
    /// The seabed, if any.
    pub seabed: Option<SeabedContact>,
    /// A flexjoint at the top, if any: `(stiffness, neutral angle)` (see
    /// [`LineModel::with_flexjoint_neutral`] for a Model with another neutral angle).
    pub flexjoint: Option<(f64, f64)>,
}

/// Why a line could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// No segment.
    #[error("the line has no segment")]
    Empty,
    /// A segment with a bad number.
    #[error("segment {index}: {what}")]
    BadSegment {
        /// Segment index (from 0, top first).
        index: usize,
        /// What is wrong.
        what: &'static str,
    },
}

/// The built Model of a line.
#[derive(Debug, Clone, PartialEq)]
pub struct LineModel {
    /// Unstretched arc length from the top at each node, m.
    pub arc: Vec<f64>,
    /// Elements, top first.
    pub elements: Vec<Element>,
    /// Tributary (unstretched) length of each node, m.
    pub tributary: Vec<f64>,
    /// Contact diameter of each node (mean of the adjacent elements' contact diameters), m.
    pub node_od: Vec<f64>,
    /// Hydrodynamic diameter of each node (mean of the adjacent elements'), m.
    pub node_hydro_od: Vec<f64>,
    /// Each node's Morison coefficients, when a line type has its own
    /// ([`LineModel::with_sea_coefficients`]); empty: the sea's everywhere.
    pub node_coefficients: Vec<Coefficients>,
    /// For each global dof, its equation number, or `None` if prescribed.
    pub equation: Vec<Option<usize>>,
    /// Number of equations (free dofs).
    pub n_eq: usize,
    /// External dead loads (submerged weight), per global dof, N.
    pub dead_load: Vec<f64>,
    /// The seabed, if the case has one.
    pub seabed: Option<SeabedContact>,
    /// The flexjoint, if the case has one.
    pub flexjoint: Option<FlexJoint>,
    /// The supports (top, anchor).
    pub supports: (Support, Support),
    /// Bodies attached at nodes ([`LineModel::with_attachments`]).
    pub attachments: Vec<Attachment>,
    /// Zones of other soil along the route ([`LineModel::with_seabed_zones`]).
    pub seabed_zones: Vec<SeabedZone>,
    /// Each node's seabed law, when zones or contact diameters other than the default's were
    /// assigned to nodes ([`LineModel::zoned_at`]); empty: every node has the default law.
    pub node_seabed: Vec<Seabed>,
    /// The laws for contact diameters other than the default law's: `(D, default, zones)`, the
    /// default and each zone's law (in the order of `seabed_zones`) built for a pipe of diameter
    /// `D` ([`LineModel::with_diameter_laws`]).
    pub diameter_laws: Vec<(f64, Seabed, Vec<Seabed>)>,
    /// The mudline's height at horizontal positions, `(x, z)` with x increasing, piecewise linear
    /// and constant beyond the ends ([`LineModel::with_mudline_profile`]); empty: flat at the seabed's
    /// `mudline_z`.
    pub mudline_profile: Vec<(f64, f64)>,
}

impl LineModel {
    /// Meshes the segments and numbers the equations.
    pub fn build(spec: &LineSpec) -> Result<Self, ModelError> {
        if spec.segments.is_empty() {
            return Err(ModelError::Empty);
        }
        let mut elements = Vec::new();
        for (index, seg) in spec.segments.iter().enumerate() {
            let bad = |what| Err(ModelError::BadSegment { index, what });
            if !(seg.length > 0.0 && seg.length.is_finite()) {
                return bad("length must be > 0");
            }
            if !(seg.element_length > 0.0 && seg.element_length.is_finite()) {
                return bad("element length must be > 0");
            }
            if !(seg.section.ea > 0.0 && seg.section.ei > 0.0) {
                return bad("EA and EI must be > 0");
            }
            let ok = seg.weight.is_finite()
                && seg.mass >= 0.0
                && seg.od > 0.0
                && seg.hydro_od > 0.0
                && seg.contact_od > 0.0;
            if !ok {
                return bad("weight must be finite, mass >= 0 and the diameters > 0");
            }
            let n = (seg.length / seg.element_length).ceil().max(1.0) as usize;
            let l0 = seg.length / n as f64;
            for _ in 0..n {
                elements.push(Element {
                    l0,
                    section: seg.section,
                    weight: seg.weight,
                    mass: seg.mass,
                    od: seg.od,
                    hydro_od: seg.hydro_od,
                    contact_od: seg.contact_od,
                    coefficients: seg.coefficients,
                    kind: seg.kind,
                    wall: seg.wall,
                });
            }
        }
        Ok(Self::from_elements(
            elements,
            (spec.top, spec.anchor),
            spec.seabed,
            spec.flexjoint.map(|(stiffness, neutral)| FlexJoint {
                node: 0,
                stiffness,
                neutral,
            }),
        ))
    }

    /// A line of these elements (top first) between these supports: the nodes' arc lengths,
    /// tributary lengths, diameters and dead loads, and the equations' numbers.
    fn from_elements(
        elements: Vec<Element>,
        (top, anchor): (Support, Support),
        seabed: Option<SeabedContact>,
        flexjoint: Option<FlexJoint>,
    ) -> Self {
        let nn = elements.len() + 1;
        let mut arc = vec![0.0; nn];
        let mut tributary = vec![0.0; nn];
        let mut node_od = vec![0.0; nn];
        let mut node_hydro_od = vec![0.0; nn];
        let mut dead_load = vec![0.0; 3 * nn];
        for (e, el) in elements.iter().enumerate() {
            arc[e + 1] = arc[e] + el.l0;
            tributary[e] += 0.5 * el.l0;
            tributary[e + 1] += 0.5 * el.l0;
            node_od[e] += 0.5 * el.contact_od;
            node_od[e + 1] += 0.5 * el.contact_od;
            node_hydro_od[e] += 0.5 * el.hydro_od;
            node_hydro_od[e + 1] += 0.5 * el.hydro_od;
            dead_load[3 * e + 1] -= 0.5 * el.weight * el.l0;
            dead_load[3 * (e + 1) + 1] -= 0.5 * el.weight * el.l0;
        }
        node_od[0] = elements[0].contact_od;
        node_od[nn - 1] = elements[nn - 2].contact_od;
        node_hydro_od[0] = elements[0].hydro_od;
        node_hydro_od[nn - 1] = elements[nn - 2].hydro_od;
        let mut fixed = vec![false; 3 * nn];
        for (node, sup) in [(0, top), (nn - 1, anchor)] {
            if sup != Support::Free {
                fixed[3 * node] = true;
                fixed[3 * node + 1] = true;
            }
            if sup == Support::Fixed {
                fixed[3 * node + 2] = true;
            }
        }
        let mut equation = vec![None; 3 * nn];
        let mut n_eq = 0;
        for (g, f) in fixed.iter().enumerate() {
            if !f {
                equation[g] = Some(n_eq);
                n_eq += 1;
            }
        }
        Self {
            arc,
            elements,
            tributary,
            node_od,
            node_hydro_od,
            node_coefficients: Vec::new(),
            equation,
            n_eq,
            dead_load,
            seabed,
            flexjoint,
            supports: (top, anchor),
            attachments: Vec::new(),
            seabed_zones: Vec::new(),
            node_seabed: Vec::new(),
            diameter_laws: Vec::new(),
            mudline_profile: Vec::new(),
        }
    }

    /// The Model with each node's Morison coefficients, where a line type has its own: the mean of
    /// its two elements' (their own, else the sea's `sea`). Unchanged when no element has its own.
    pub fn with_sea_coefficients(mut self, sea: Coefficients) -> Self {
        if self.elements.iter().all(|e| e.coefficients.is_none()) {
            return self;
        }
        let nn = self.nodes();
        let of = |e: usize| self.elements[e].coefficients.unwrap_or(sea);
        let mean = |a: Coefficients, b: Coefficients| Coefficients {
            cd_normal: 0.5 * (a.cd_normal + b.cd_normal),
            cd_axial: 0.5 * (a.cd_axial + b.cd_axial),
            ca_normal: 0.5 * (a.ca_normal + b.ca_normal),
        };
        self.node_coefficients = (0..nn)
            .map(|i| match i {
                0 => of(0),
                i if i == nn - 1 => of(nn - 2),
                i => mean(of(i - 1), of(i)),
            })
            .collect();
        self
    }

    /// The Model with the seabed laws for other contact diameters (see
    /// [`LineModel::diameter_laws`]).
    pub fn with_diameter_laws(mut self, laws: Vec<(f64, Seabed, Vec<Seabed>)>) -> Self {
        self.diameter_laws = laws;
        self
    }

    /// The arc lengths from the top where the line type changes, m (empty for one type).
    pub fn section_boundaries(&self) -> Vec<f64> {
        self.elements
            .windows(2)
            .enumerate()
            .filter(|(_, w)| w[0].kind != w[1].kind)
            .map(|(e, _)| self.arc[e + 1])
            .collect()
    }

    /// The Model on a mudline of the given profile (see [`LineModel::mudline_profile`]).
    pub fn with_mudline_profile(mut self, profile: Vec<(f64, f64)>) -> Self {
        self.mudline_profile = profile;
        self
    }

    /// The mudline's height and slope `dz/dx` at the horizontal position `x`: the profile's, or the
    /// flat seabed's `(mudline_z, 0)` (0 without a seabed).
    #[inline]
    pub fn mudline_at(&self, x: f64) -> (f64, f64) {
        let p = &self.mudline_profile;
        if p.is_empty() {
            return (self.seabed.map_or(0.0, |s| s.mudline_z), 0.0);
        }
        if x <= p[0].0 {
            return (p[0].1, 0.0);
        }
        for w in p.windows(2) {
            if x < w[1].0 {
                let m = (w[1].1 - w[0].1) / (w[1].0 - w[0].0);
                return (w[0].1 + m * (x - w[0].0), m);
            }
        }
        (p[p.len() - 1].1, 0.0)
    }

    /// The mudline's unit tangent `(1, m)/√(1 + m²)` at the horizontal position `x` (towards +x;
    /// `(1, 0)` on a flat seabed), `m` its slope ([`LineModel::mudline_at`]).
    #[inline]
    pub fn mudline_tangent(&self, x: f64) -> (f64, f64) {
        let m = self.mudline_at(x).1;
        let c = 1.0 / (1.0 + m * m).sqrt();
        (c, m * c)
    }

    /// The Model with zones of other soil along the route (their nodes are assigned by
    /// [`LineModel::zoned_at`]).
    pub fn with_seabed_zones(mut self, zones: Vec<SeabedZone>) -> Self {
        self.seabed_zones = zones;
        self
    }

    /// The Model with each node's seabed law: the zone under the node's x in the configuration `q`
    /// (3 per node; the statics' base configuration), else the default. Unchanged without zones.
    ///
    /// With laws for other contact diameters ([`LineModel::diameter_laws`]), a node of such a
    /// diameter takes that diameter's law (its zone's, or its default).
    pub fn zoned_at(mut self, q: &[f64]) -> Self {
        if self.seabed_zones.is_empty() && self.diameter_laws.is_empty() {
            return self;
        }
        let Some(sb) = self.seabed else { return self };
        self.node_seabed = (0..self.nodes())
            .map(|i| {
                *self
                    .seabed_law_for(q[3 * i], self.node_od[i])
                    .unwrap_or(&sb.seabed)
            })
            .collect();
        self
    }

    /// The seabed law at the horizontal position `x` for a pipe of contact diameter `d`: its
    /// zone's (for that diameter, if the Model has laws for it), else the default.
    pub fn seabed_law_for(&self, x: f64, d: f64) -> Option<&Seabed> {
        let sb = self.seabed.as_ref()?;
        let zone = self
            .seabed_zones
            .iter()
            .position(|z| z.from_x <= x && x < z.to_x);
        match self.diameter_laws.iter().find(|(dd, _, _)| *dd == d) {
            Some((_, default, zones)) => Some(zone.map_or(default, |k| &zones[k])),
            None => Some(zone.map_or(&sb.seabed, |k| &self.seabed_zones[k].seabed)),
        }
    }

    /// Node `i`'s seabed law (`None` without a seabed).
    #[inline]
    pub fn seabed_law(&self, i: usize) -> Option<&Seabed> {
        let sb = self.seabed.as_ref()?;
        Some(self.node_seabed.get(i).unwrap_or(&sb.seabed))
    }

    /// The Model with bodies attached: each `(arc, attachment)` at the node nearest to its arc
    /// length from the top (m; the first of two equally near), its submerged weight added to the
    /// node's dead load. Its mass (and, in water, its added mass and drag) enter the dynamics.
    pub fn with_attachments(mut self, bodies: &[(f64, Attachment)]) -> Self {
        for (arc, a) in bodies {
            let node = self
                .arc
                .iter()
                .enumerate()
                .fold((0, f64::INFINITY), |(best, d), (i, s)| {
                    let di = (s - arc).abs();
                    if di < d {
                        (i, di)
                    } else {
                        (best, d)
                    }
                })
                .0;
            self.dead_load[3 * node + 1] -= a.weight;
            self.attachments.push(Attachment { node, ..*a });
        }
        self
    }

    /// The line continued above its top node by the elements `above` (top first): a lay's pipe
    /// still on the vessel, and the wire after it ([`LineModel::window`] takes the part in the
    /// water). The new nodes come first; the supports, the seabed and the flexjoint (at the new top)
    /// stay. Attachments, zones' assignments and per-node coefficients are not carried (a lay scene
    /// has none).
    pub fn with_elements_above(&self, above: &[Element]) -> Self {
        let elements: Vec<Element> = above.iter().chain(self.elements.iter()).copied().collect();
        let mut m = Self::from_elements(elements, self.supports, self.seabed, self.flexjoint);
        m.seabed_zones = self.seabed_zones.clone();
        m.diameter_laws = self.diameter_laws.clone();
        m.mudline_profile = self.mudline_profile.clone();
        m
    }

    /// Sets the top element's rest length to `l0` (m), with what follows from it: the nodes' arc
    /// lengths, the two top nodes' tributary lengths and dead loads. A lay's top element runs
    /// from the tower's exit to the first free node, its rest length growing with the payout
    /// (`catena::run::lay`); a Workspace built before is told with
    /// [`crate::dynamics::DynWorkspace::top_rest_length_changed`]. A Model built with `l0` is the
    /// same to the bit.
    pub fn set_top_rest_length(&mut self, l0: f64) {
        self.elements[0].l0 = l0;
        for (e, el) in self.elements.iter().enumerate() {
            self.arc[e + 1] = self.arc[e] + el.l0;
        }
        // As `from_elements` sums them: node 0 has element 0's half, node 1 both halves.
        self.tributary[0] = 0.5 * l0;
        self.tributary[1] = if self.elements.len() > 1 {
            0.5 * l0 + 0.5 * self.elements[1].l0
        } else {
            0.5 * l0
        };
        let half = |e: &Element| -0.5 * e.weight * e.l0;
        let top = half(&self.elements[0]);
        self.dead_load[1] = top;
        self.dead_load[4] = if self.elements.len() > 1 {
            top + half(&self.elements[1])
        } else {
            top
        };
        for a in self.attachments.iter().filter(|a| a.node < 2) {
            self.dead_load[3 * a.node + 1] -= a.weight;
        }
    }

    /// The part of the line from node `first` to node `last` (`first < last`) as a line of its
    /// own: the same elements, held at `last` (position and rotation: a node frozen where it
    /// lies), `top` at `first`, with `flexjoint` there if given. Arc lengths start at 0 at
    /// `first`. Each node's own seabed law and coefficients, and the attachments between, go
    /// with it; the end nodes' tributary lengths and dead loads are their one element's halves
    /// (they are prescribed: only their reactions read them).
    pub fn window(
        &self,
        first: usize,
        last: usize,
        top: Support,
        flexjoint: Option<FlexJoint>,
    ) -> Self {
        let mut w = Self::from_elements(
            self.elements[first..last].to_vec(),
            (top, Support::Fixed),
            self.seabed,
            flexjoint,
        );
        if !self.node_seabed.is_empty() {
            w.node_seabed = self.node_seabed[first..=last].to_vec();
        }
        if !self.node_coefficients.is_empty() {
            w.node_coefficients = self.node_coefficients[first..=last].to_vec();
        }
        w.seabed_zones = self.seabed_zones.clone();
        w.diameter_laws = self.diameter_laws.clone();
        w.mudline_profile = self.mudline_profile.clone();
        for a in self
            .attachments
            .iter()
            .filter(|a| (first..=last).contains(&a.node))
        {
            w.dead_load[3 * (a.node - first) + 1] -= a.weight;
            w.attachments.push(Attachment {
                node: a.node - first,
                ..*a
            });
        }
        w
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.arc.len()
    }

    /// Total unstretched length, m.
    pub fn length(&self) -> f64 {
        self.arc.last().copied().unwrap_or(0.0)
    }

    /// The same Model with the flexjoint's neutral angle set to `neutral` (rad; e.g. the static top
    /// angle, for zero static moment). A Model is immutable once built: this makes a new one.
    pub fn with_flexjoint_neutral(mut self, neutral: f64) -> Self {
        if let Some(fj) = &mut self.flexjoint {
            fj.neutral = neutral;
        }
        self
    }

    /// The penetration of node `i`'s invert below the mudline at `(x, z)` (positive into the seabed,
    /// normal to the local mudline), or `None` without a seabed.
    #[inline]
    pub fn penetration(&self, i: usize, x: f64, z: f64) -> Option<f64> {
        let sb = self.seabed.as_ref()?;
        if self.mudline_profile.is_empty() {
            return Some(sb.mudline_z - (z - 0.5 * self.node_od[i]));
        }
        // Normal to the local mudline: the centre's height above it times cos α, less D/2.
        let (zm, m) = self.mudline_at(x);
        let c = 1.0 / (1.0 + m * m).sqrt();
        Some(0.5 * self.node_od[i] - (z - zm) * c)
    }
    /// The mean submerged weight per unit length, N/m.
    pub fn mean_weight(&self) -> f64 {
        self.elements.iter().map(|e| e.weight * e.l0).sum::<f64>() / self.length()
    }
}
