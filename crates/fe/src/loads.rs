//! The loads on the line besides its elements, submerged weight and flexjoint (those are the
//! structure, [`crate::assembly::Assembler::assemble_structure`]): **one list for the statics and
//! the dynamics**. Each load adds its part of the residual `F` ("internal minus external") and, when
//! the tangent is wanted, its part of `k·(K + c_v·C)` (stiffness `K = ∂F/∂u`, damping
//! `C = ∂F/∂v`): the dynamics pass `k = 1 + α` and `c_v = γ/(βΔt)`, the statics `k = 1`, `c_v = 0`.
//! [`assemble`] adds every load the Model has, in the order of the list:
//!
//! 1. **Structural damping** (dynamics; `β` s, stiffness-proportional):
//!    `F_e = β·Bᵀ K_l B·v` per element ([`crate::beam::structural_damping`]).
//! 2. **Seabed contact.** The penetration of node `i`'s invert, positive down,
//!    `z_pen = z_mudline − (z_i − D_i/2)`, its rate `ż_pen = −v_z`; the force per length `P`
//!    acts over the tributary length `L_i`: `F_z −= L_i·P`, with `∂(−L·P)/∂z = L·P'` and
//!    `∂(−L·P)/∂v_z = L·c`. In the statics `P` is the law's backbone (initial penetration, no
//!    history, nothing above the mudline: [`SeabedPass::Backbone`]); in the dynamics it is each
//!    node's trial from its committed history ([`SeabedPass::Trial`], pure: the caller commits).
//! 3. **Axial seabed friction** (dynamics, when the seabed has it), elastic–slip along the flat
//!    mudline (x): at node `i` pressed on the seabed by `N = L_i·P > 0` (P its seabed force per
//!    length at the iterate), with `s = x_i − a_i` its distance from its committed anchor `a_i`,
//!    the force on the node is `F = −μN·s/δ` for `|s| ≤ δ` (stick: a spring `μN/δ`) and
//!    `F = −μN·sign(s)` beyond (slip); `∂R/∂x = μN/δ` in stick, 0 in slip. The coupling through `N`
//!    (`∂F/∂z = −μ·∂N/∂z·s/δ`) would make the tangent unsymmetric and is left out of it (the
//!    residual has it: the converged answer is exact; Newton converges a little slower in contact
//!    changes). Out of contact (`N ≤ 0`) there is no friction. The anchors are history, committed
//!    once per converged step ([`commit_friction`]): a node that slid past `δ` drags its anchor to
//!    `x − δ·sign(s)`, a node out of contact takes its anchor with it. The statics are
//!    frictionless; friction acts from the start of the dynamics, each anchor where the statics
//!    left its node. **On a sloping mudline** (a profile) it acts along the local mudline's tangent
//!    `t = (1, m)/√(1 + m²)` (`m` its slope under the node): the anchor is a point `a_i`, the
//!    distance `s = t·(r_i − a_i)`, the force `F·t` and its tangent `(∂R/∂s)·t tᵀ`; a sliding node
//!    drags its anchor to `r − δ·sign(s)·t`. Motion normal to the mudline (penetration) moves no
//!    anchor, and crossing a kink of the profile changes `s` by at most `δ·(1 − cos Δα)`. The
//!    tangent's change along the profile (zero between kinks) is left out of the tangent.
//! 4. **Hydrodynamics** (Morison, per unit unstretched length, lumped at nodes): drag on the
//!    velocity relative to the current `U(z)` and the waves, split along the node's tangent `t`,
//!    `f = ½ρ Cd_n D |v_n| v_n + ½ρ Cd_a πD |v_t| v_t t`, its velocity derivative in `C` (its
//!    dependence on the orientation is left out of the tangent); and the wave inertia
//!    `ρA(1 + Ca)·a_n + ρA·a_t` ([`crate::environment::Hydro::wave_inertia`]). In the statics only
//!    a steady current acts, on the line at rest.
//!
//! 5. **Attached bodies' drag** (with hydrodynamics): isotropic, `½ρ·CdA·|u|·u` on the water's
//!    velocity relative to the node (current and waves); their weight is a dead load and their
//!    mass and added mass are lumped at their node (`crate::dynamics`).
//!
//! **A new load** is a function here, called from [`assemble`] when its `Option` in [`LoadModel`]
//! is `Some` (an effect absent from the scene is not built and costs nothing), with its
//! finite-difference tangent test and a mutation in `scripts/mutations.toml`.

use catena_seabed::law::{Law, SeabedHistory, TrialMemo};

use std::ops::Range;

use crate::assembly::{Assembler, Part, Placement};
use crate::environment::Hydro;
use crate::model::{Attachment, AxialFriction, LineModel};
use crate::waves::Kinematics;

mod linear_contact;
mod morison;
pub use linear_contact::ContactScratch;
pub use morison::MorisonScratch;

/// What the loads need of the Model: the line, its placement and the optional effects.
#[derive(Debug, Clone, Copy)]
pub struct LoadModel<'a> {
    /// The line (its seabed contact is `line.seabed`).
    pub line: &'a LineModel,
    /// The base configuration.
    pub placement: &'a Placement,
    /// The water's hydrodynamics, if they act (the statics: only with a current).
    pub hydro: Option<&'a Hydro>,
    /// Stiffness-proportional structural damping `β` (s), if any (dynamics only).
    pub structural_damping: Option<f64>,
}

/// The iterate the loads are evaluated at: displacements from the base, velocities (zeros in the
/// statics) and the water's kinematics at each node (empty without waves).
#[derive(Debug, Clone, Copy)]
pub struct Iterate<'a> {
    /// Displacements, 3 per node.
    pub u: &'a [f64],
    /// Velocities, 3 per node.
    pub v: &'a [f64],
    /// Wave kinematics per node (`None` above the surface); empty without waves.
    pub wave_kin: &'a [Option<Kinematics>],
}

/// How the seabed law is evaluated.
#[derive(Debug)]
pub enum SeabedPass<'a> {
    /// The statics: the backbone (initial penetration), no history; nodes above the mudline carry
    /// nothing.
    Backbone,
    /// The dynamics: each node's trial from its committed history over a step `dt`, with its memo;
    /// `keep` receives each node's trial history (the pass expected to converge).
    Trial {
        /// The committed histories, one per node.
        committed: &'a [SeabedHistory],
        /// The committed friction anchors, one per node (empty without friction).
        anchors: &'a [f64],
        /// The step the law sees, s.
        dt: f64,
        /// Each node's trial memo (empty for a law that keeps nothing).
        memo: &'a mut [TrialMemo],
        /// Where each node's trial history goes, when kept.
        keep: Option<&'a mut [SeabedHistory]>,
    },
}

/// What the tangent is wanted for: `scale·(K + c_v·C)` when `with_k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentScale {
    /// Assemble the tangent (else the residual alone).
    pub with_k: bool,
    /// `k`: the factor on every load's tangent (`1 + α` in the dynamics, 1 in the statics).
    pub k: f64,
    /// `c_v`: the factor on the damping within it (`γ/(βΔt)`; 0 in the statics).
    pub c_v: f64,
}

/// Per-node scratch the loads fill: each node's unit tangent `[cos θ, sin θ]` (hydrodynamics) and
/// its seabed force per length (N/m; resistance, buoyancy and damping).
#[derive(Debug, Clone)]
pub struct LoadScratch {
    /// Each node's unit tangent at the iterate, `[cos, sin]`.
    pub node_tangent: [Vec<f64>; 2],
    /// Seabed force per length at the iterate, N/m.
    pub seabed_force: Vec<f64>,
    /// The Morison passes' arrays ([`morison`]).
    pub morison: MorisonScratch,
    /// The linear seabed's contact passes' arrays ([`linear_contact`]).
    pub contact: ContactScratch,
}

impl LoadScratch {
    /// Sized for `n` nodes.
    pub fn new(n: usize) -> Self {
        Self {
            node_tangent: [vec![1.0; n], vec![0.0; n]],
            seabed_force: vec![0.0; n],
            morison: MorisonScratch::new(n),
            contact: ContactScratch::new(n),
        }
    }
}

/// The penetration of node `i`'s invert and its rate (positive down), if the line has a seabed.
#[inline]
pub fn penetration(
    line: &LineModel,
    pl: &Placement,
    u: &[f64],
    v: &[f64],
    i: usize,
) -> Option<(f64, f64)> {
    line.seabed.as_ref()?;
    let (z, rate, _) = if line.mudline_profile.is_empty() {
        penetration_of::<false>(line, pl, u, v, i)
    } else {
        penetration_of::<true>(line, pl, u, v, i)
    };
    Some((z, rate))
}

/// Adds the seabed's force `L·P` (`lp`, N) along the mudline's normal `n` at node `i` (residual
/// `−L·P·n`) and, with `kk`, its tangent `kk·n nᵀ` (`kk = k·(L·P' + c_v·L·c)`); on a flat seabed
/// (`normal` `None`) the vertical dof alone, the same operations as before a profile existed.
#[inline(always)]
fn add_contact(
    asm: &mut Assembler,
    model: &LineModel,
    i: usize,
    lp: f64,
    kk: Option<f64>,
    normal: Option<(f64, f64)>,
) {
    match normal {
        None => {
            asm.residual[3 * i + 1] -= lp;
            if let Some(kk) = kk {
                asm.add_dof_tangent(model, 3 * i + 1, kk);
            }
        }
        Some((nx, nz)) => {
            asm.residual[3 * i] -= lp * nx;
            asm.residual[3 * i + 1] -= lp * nz;
            if let Some(kk) = kk {
                asm.add_node_block(i, kk * nx * nx, kk * nx * nz, kk * nz * nz);
            }
        }
    }
}

/// Adds every load of the list (see the module docs) at the iterate `at` to the assembler's residual
/// and, with `scale.with_k`, its tangent (after the structure). Allocates nothing.
pub fn assemble(
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    seabed: SeabedPass<'_>,
    scale: TangentScale,
    asm: &mut Assembler,
    scratch: &mut LoadScratch,
) {
    assemble_part(m, at, seabed, scale, (asm, scratch), &Part::whole(m.line));
}

/// [`assemble`] over a part of the line (issue 48): the loads of its elements (structural damping)
/// and of its nodes (the rest), so that the part's own nodes get the whole line's sums to the bit
/// ([`Part`]); a trial seabed history is evaluated (and kept) at the part's nodes only.
pub fn assemble_part(
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    seabed: SeabedPass<'_>,
    scale: TangentScale,
    (asm, scratch): (&mut Assembler, &mut LoadScratch),
    part: &Part,
) {
    if let Some(beta) = m.structural_damping {
        asm.add_structural_damping(
            m.line,
            m.placement,
            at.u,
            at.v,
            beta,
            (scale.k * scale.c_v, scale.with_k),
            part.elements.clone(),
        );
    }
    let nodes = part.nodes.clone();
    if let Some(sb) = &m.line.seabed {
        let anchors = match &seabed {
            SeabedPass::Trial { anchors, .. } => Some(*anchors),
            SeabedPass::Backbone => None,
        };
        add_seabed(
            m,
            at,
            seabed,
            scale,
            asm,
            (&mut scratch.seabed_force, &mut scratch.contact, &nodes),
        );
        if let (Some(f), Some(anchors)) = (&sb.friction, anchors) {
            add_friction(
                f,
                m,
                at,
                anchors,
                scale,
                asm,
                (&scratch.seabed_force, &nodes),
            );
        }
    }
    if let Some(h) = m.hydro {
        // Each node's tangent first, in a pass of its own: a node's sine and cosine and its drag
        // are two long dependency chains, and in one loop too few nodes fit in the processor's
        // window to overlap them.
        let dofs = 3 * nodes.start..3 * nodes.end;
        let [cos, sin] = &mut scratch.node_tangent;
        node_tangents(
            &m.placement.base[dofs.clone()],
            &at.u[dofs],
            [&mut cos[nodes.clone()], &mut sin[nodes.clone()]],
        );
        let tangents = [&cos[..], &sin[..]];
        if m.line.node_coefficients.is_empty() {
            // The sea's coefficients everywhere: a run of nodes at a time.
            let with_c = scale.with_k && scale.c_v != 0.0;
            morison::add_morison(
                h,
                (m.line, m.placement),
                (at.u, at.v, at.wave_kin),
                (with_c, scale.k * scale.c_v),
                asm,
                tangents,
                &mut scratch.morison,
                &nodes,
            );
        } else {
            add_hydrodynamics(h, m, at, scale, asm, (tangents, &nodes));
        }
        if !m.line.attachments.is_empty() {
            add_attachment_drag(h, m, at, scale, (asm, &nodes));
        }
    }
}

/// The drag on attached bodies (isotropic): `f = ½ρ·CdA·|u|·u` on the water's velocity relative to
/// the node, `u = (U(z) + w_x − v_x, w_z − v_z)`; its damping block `½ρ·CdA·(|u|·I + u uᵀ/|u|)`.
#[inline(never)]
fn add_attachment_drag(
    h: &Hydro,
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    scale: TangentScale,
    (asm, nodes): (&mut Assembler, &Range<usize>),
) {
    let (model, pl) = (m.line, m.placement);
    let with_c = scale.with_k && scale.c_v != 0.0;
    let drag = |a: &&Attachment| a.drag_area > 0.0 && nodes.contains(&a.node);
    for a in model.attachments.iter().filter(drag) {
        let i = a.node;
        let z = pl.base[3 * i + 1] + at.u[3 * i + 1];
        let w = at
            .wave_kin
            .get(i)
            .copied()
            .flatten()
            .map_or([0.0; 2], |k| k.velocity);
        let (ux, uz) = (h.current_at(z) + w[0] - at.v[3 * i], w[1] - at.v[3 * i + 1]);
        let c = 0.5 * h.water_density * a.drag_area;
        let speed = (ux * ux + uz * uz).sqrt();
        asm.residual[3 * i] -= c * speed * ux;
        asm.residual[3 * i + 1] -= c * speed * uz;
        if with_c && speed > 0.0 {
            let f = scale.k * scale.c_v * c;
            let (cxx, cxz, czz) = (
                speed + ux * ux / speed,
                ux * uz / speed,
                speed + uz * uz / speed,
            );
            asm.add_node_block(i, f * cxx, f * cxz, f * czz);
        }
    }
}

/// Seabed contact at every node (see the module docs): on a flat seabed or a profile, each loop
/// compiled for its own case ([`seabed_loops`]).
#[inline]
fn add_seabed(
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    mut pass: SeabedPass<'_>,
    scale: TangentScale,
    asm: &mut Assembler,
    (seabed_force, contact, nodes): (&mut [f64], &mut ContactScratch, &Range<usize>),
) {
    let part = (seabed_force, nodes);
    if m.line.mudline_profile.is_empty() {
        // The commonest seabed in the dynamics, a run of nodes at a time ([`linear_contact`]).
        if let (
            Some(sb),
            SeabedPass::Trial {
                committed,
                dt,
                keep,
                ..
            },
        ) = (&m.line.seabed, &mut pass)
        {
            if let (Law::Linear(law), None, true) = (
                &sb.seabed.law,
                &sb.seabed.buoyancy,
                m.line.node_seabed.is_empty(),
            ) {
                let keep = keep.as_deref_mut();
                return linear_contact::add_linear_contact(
                    (&sb.seabed, law, *dt),
                    (m.line, m.placement, sb.mudline_z),
                    (at.u, at.v),
                    scale,
                    asm,
                    (committed, keep),
                    (contact, part.0),
                    nodes,
                );
            }
        }
        seabed_loops::<false>(m, at, pass, scale, asm, part);
    } else {
        seabed_loops::<true>(m, at, pass, scale, asm, part);
    }
}

/// The penetration, its rate and the mudline's unit normal `(−sin α, cos α)` (out of the seabed)
/// at node `i` of a line with a seabed, on a flat seabed (normal `(0, 1)`) or (`SLOPED`) normal to
/// the profile ([`penetration`]; the loops choose `SLOPED` once).
#[inline(always)]
fn penetration_of<const SLOPED: bool>(
    line: &LineModel,
    pl: &Placement,
    u: &[f64],
    v: &[f64],
    i: usize,
) -> (f64, f64, (f64, f64)) {
    let (x, z) = (pl.base[3 * i] + u[3 * i], pl.base[3 * i + 1] + u[3 * i + 1]);
    if !SLOPED {
        let mudline_z = line.seabed.as_ref().map_or(0.0, |s| s.mudline_z);
        return (
            mudline_z - (z - 0.5 * line.node_od[i]),
            -v[3 * i + 1],
            (0.0, 1.0),
        );
    }
    // Normal to the local mudline: `n = (−sin α, cos α)`, `z_pen = D/2 − (z − z_m(x))·cos α`,
    // `ż_pen = −n·v`.
    let (zm, m) = line.mudline_at(x);
    let c = 1.0 / (1.0 + m * m).sqrt();
    let sn = m * c;
    (
        0.5 * line.node_od[i] - (z - zm) * c,
        sn * v[3 * i] - c * v[3 * i + 1],
        (-sn, c),
    )
}

/// [`add_seabed`]'s loops, on a flat seabed or (`SLOPED`) a profile.
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn seabed_loops<const SLOPED: bool>(
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    pass: SeabedPass<'_>,
    scale: TangentScale,
    asm: &mut Assembler,
    (seabed_force, nodes): (&mut [f64], &Range<usize>),
) {
    let (model, pl) = (m.line, m.placement);
    let Some(sb) = &model.seabed else { return };
    let (u, v) = (at.u, at.v);
    match pass {
        SeabedPass::Backbone => {
            for i in nodes.clone() {
                let (z_pen, _, n) = penetration_of::<SLOPED>(model, pl, u, u, i);
                if z_pen <= 0.0 {
                    seabed_force[i] = 0.0;
                    continue;
                }
                let law = model.node_seabed.get(i).unwrap_or(&sb.seabed);
                let t = law.backbone(z_pen);
                let l = model.tributary[i];
                seabed_force[i] = t.total();
                // d(−L·F(z_pen))/dz = L·F'(z_pen), since dz_pen/dz = −1 (on a slope: −n).
                let kk = scale.with_k.then_some(l * t.tangent);
                add_contact(asm, model, i, l * t.total(), kk, SLOPED.then_some(n));
            }
        }
        SeabedPass::Trial {
            committed,
            dt,
            memo,
            mut keep,
            ..
        } => {
            let mut spare = TrialMemo::default();
            for i in nodes.clone() {
                let (z, zdot, n) = penetration_of::<SLOPED>(model, pl, u, v, i);
                // The trial history is kept only in the pass expected to converge; the others need
                // the force alone. Only a law that keeps something has memos (the linear law's
                // trials take `spare`).
                let memo = memo.get_mut(i).unwrap_or(&mut spare);
                // The node's zone's law, or the default (no zones: always the default).
                let law = model.node_seabed.get(i).unwrap_or(&sb.seabed);
                let t = match keep.as_deref_mut() {
                    Some(next) => {
                        law.response_and_next(&committed[i], z, zdot, dt, (memo, &mut next[i]))
                    }
                    None => law.response(&committed[i], z, zdot, dt, memo),
                };
                let l = model.tributary[i];
                let up = t.total;
                let mut k = t.tangent;
                let mut c = t.damping_coefficient;
                seabed_force[i] = up;
                // z_pen = const − z, ż_pen = −v_z: d(−L·F)/dz = L·F', d(−L·F)/dv_z = L·c (on a
                // slope, along the normal n: ∇z_pen = −n).
                let kk = (scale.with_k && (k != 0.0 || c != 0.0)).then(|| {
                    k *= l;
                    c *= l;
                    scale.k * (k + scale.c_v * c)
                });
                add_contact(asm, model, i, l * up, kk, SLOPED.then_some(n));
            }
        }
    }
}

/// Axial friction at every node in contact (see the module docs): the force from each node's
/// committed anchor and its normal force at the iterate (`seabed_force`, per length).
#[inline]
fn add_friction(
    f: &AxialFriction,
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    anchors: &[f64],
    scale: TangentScale,
    asm: &mut Assembler,
    (seabed_force, nodes): (&[f64], &Range<usize>),
) {
    let (model, pl) = (m.line, m.placement);
    if !model.mudline_profile.is_empty() {
        return add_friction_on_profile(f, m, at, anchors, scale, asm, (seabed_force, nodes));
    }
    let pairs = seabed_force.iter().zip(anchors).enumerate();
    for (i, (&p, &a)) in pairs.take(nodes.end).skip(nodes.start) {
        let n = model.tributary[i] * p;
        if n <= 0.0 {
            continue;
        }
        let s = pl.base[3 * i] + at.u[3 * i] - a;
        let (r, k) = friction_response(f, n, s);
        asm.residual[3 * i] += r;
        if scale.with_k && k != 0.0 {
            asm.add_dof_tangent(model, 3 * i, scale.k * k);
        }
    }
}

/// [`add_friction`] on a profile: along each node's local mudline tangent, from its anchor point
/// (`anchors` holds `x, z` per node).
#[inline(never)]
fn add_friction_on_profile(
    f: &AxialFriction,
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    anchors: &[f64],
    scale: TangentScale,
    asm: &mut Assembler,
    (seabed_force, nodes): (&[f64], &Range<usize>),
) {
    let (model, pl) = (m.line, m.placement);
    let pairs = seabed_force.iter().zip(anchors.chunks_exact(2)).enumerate();
    for (i, (&p, a)) in pairs.take(nodes.end).skip(nodes.start) {
        let n = model.tributary[i] * p;
        if n <= 0.0 {
            continue;
        }
        let (x, z) = (
            pl.base[3 * i] + at.u[3 * i],
            pl.base[3 * i + 1] + at.u[3 * i + 1],
        );
        let (tx, tz) = model.mudline_tangent(x);
        let s = tx * (x - a[0]) + tz * (z - a[1]);
        let (r, k) = friction_response(f, n, s);
        asm.residual[3 * i] += r * tx;
        asm.residual[3 * i + 1] += r * tz;
        if scale.with_k && k != 0.0 {
            let k = scale.k * k;
            asm.add_node_block(i, k * tx * tx, k * tx * tz, k * tz * tz);
        }
    }
}

/// The friction's part of the residual at a node (`−F`, N) and its derivative in x (N/m), for a
/// normal force `n > 0` (N) and the distance `s` (m) from the anchor: a spring `μn/δ` up to `μn`.
#[inline(always)]
pub fn friction_response(f: &AxialFriction, n: f64, s: f64) -> (f64, f64) {
    let cap = f.mu * n;
    if s.abs() <= f.mobilisation {
        let k = cap / f.mobilisation;
        (k * s, k)
    } else {
        (cap.copysign(s), 0.0)
    }
}

/// Commits each node's friction anchor at a converged state (`u`, the seabed force per length
/// `seabed_force` there): a node that slid further than `δ` from its anchor drags it to
/// `x − δ·sign(s)`; a node out of contact takes it along (`a = x`); otherwise it stays. On a
/// profile the same along the local mudline (`anchors` holds `x, z` per node, see the module docs).
pub fn commit_friction(
    f: &AxialFriction,
    model: &LineModel,
    pl: &Placement,
    u: &[f64],
    seabed_force: &[f64],
    anchors: &mut [f64],
) {
    if !model.mudline_profile.is_empty() {
        for (i, (a, &p)) in anchors.chunks_exact_mut(2).zip(seabed_force).enumerate() {
            let (x, z) = (pl.base[3 * i] + u[3 * i], pl.base[3 * i + 1] + u[3 * i + 1]);
            let (tx, tz) = model.mudline_tangent(x);
            let s = tx * (x - a[0]) + tz * (z - a[1]);
            if p <= 0.0 {
                (a[0], a[1]) = (x, z);
            } else if s.abs() > f.mobilisation {
                let d = f.mobilisation.copysign(s);
                (a[0], a[1]) = (x - d * tx, z - d * tz);
            }
        }
        return;
    }
    for (i, (a, &p)) in anchors.iter_mut().zip(seabed_force).enumerate() {
        let x = pl.base[3 * i] + u[3 * i];
        let s = x - *a;
        if p <= 0.0 {
            *a = x;
        } else if s.abs() > f.mobilisation {
            *a = x - f.mobilisation.copysign(s);
        }
    }
}

/// Drag and wave inertia at every node (see the module docs) of a line whose nodes have their own
/// coefficients (`LineModel::node_coefficients`; with the sea's everywhere, [`morison`]), node by
/// node, with each node's unit tangent `[cos, sin]`. The damping block enters the tangent when
/// `c_v ≠ 0` (the dynamics).
#[inline]
fn add_hydrodynamics(
    h: &Hydro,
    m: &LoadModel<'_>,
    at: &Iterate<'_>,
    scale: TangentScale,
    asm: &mut Assembler,
    (node_tangent, nodes): ([&[f64]; 2], &Range<usize>),
) {
    let (model, pl) = (m.line, m.placement);
    let (u, v) = (at.u, at.v);
    let with_c = scale.with_k && scale.c_v != 0.0;
    for i in nodes.clone() {
        let c = &model.node_coefficients[i];
        let (tx, ty) = (node_tangent[0][i], node_tangent[1][i]);
        let z = pl.base[3 * i + 1] + u[3 * i + 1];
        let kin = at.wave_kin.get(i).copied().flatten();
        let d = h.drag(
            c,
            model.node_hydro_od[i],
            model.tributary[i],
            (tx, ty),
            z,
            (v[3 * i], v[3 * i + 1]),
            kin.map(|k| k.velocity),
            with_c,
        );
        asm.residual[3 * i] -= d.force[0];
        asm.residual[3 * i + 1] -= d.force[1];
        if let Some(k) = kin {
            let f = h.wave_inertia(
                c,
                model.node_hydro_od[i],
                model.tributary[i],
                (tx, ty),
                k.acceleration,
            );
            asm.residual[3 * i] -= f[0];
            asm.residual[3 * i + 1] -= f[1];
        }
        if with_c {
            let f = scale.k * scale.c_v;
            let [cxx, cxz, czz] = d.damping;
            asm.add_node_block(i, f * cxx, f * cxz, f * czz);
        }
    }
}

/// Each node's unit tangent `(cos θ, sin θ)`, `θ = base + u` (rotation dofs), into `[cos, sin]`:
/// compiled also for AVX2 and AVX-512 and chosen at run time, where the branch-free sine and
/// cosine of [`crate::fastmath::sin_cos`] run four or eight nodes at a time (the same operations:
/// the same values to the bit).
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
pub fn node_tangents(base: &[f64], u: &[f64], [cos, sin]: [&mut [f64]; 2]) {
    let th = base
        .chunks_exact(3)
        .zip(u.chunks_exact(3))
        .map(|(b, u)| b[2] + u[2]);
    for ((c, s), th) in cos.iter_mut().zip(sin.iter_mut()).zip(th) {
        (*s, *c) = crate::fastmath::sin_cos(th);
    }
}

#[cfg(test)]
mod contact_tests;
#[cfg(test)]
mod tests;
