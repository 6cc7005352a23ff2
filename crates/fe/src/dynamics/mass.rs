//! The lumped mass: the line's own (with attached bodies), the added mass at the predicted
//! positions, and its share of the tangent.

use crate::assembly::Assembler;
use crate::loads::{self};
use crate::model::LineModel;
use std::ops::Range;

use super::*;

/// The line's own lumped mass per node `[xx, xz, zz, rot]`: half of each element's mass at each
/// of its nodes, and the rotary inertia of a thin ring, `m·D²/8` per length; attached bodies'
/// masses at their nodes.
pub(super) fn structural_mass(model: &LineModel) -> Vec<[f64; 4]> {
    let mut mass = vec![[0.0; 4]; model.nodes()];
    for (e, el) in model.elements.iter().enumerate() {
        let half = 0.5 * el.mass * el.l0;
        for i in [e, e + 1] {
            mass[i][0] += half;
            mass[i][2] += half;
            mass[i][3] += half * el.od * el.od / 8.0;
        }
    }
    // Attached bodies: their mass at their node, in x and z (a point mass: no rotary inertia).
    for a in &model.attachments {
        mass[a.node][0] += a.mass;
        mass[a.node][2] += a.mass;
    }
    mass
}

/// Lumped mass at the orientation `u` at the nodes of the workspace's part of the line (the whole
/// line on one thread): the line's own ([`structural_mass`]) and the added mass normal to the
/// tangent there; attached bodies' added mass in both directions.
pub(super) fn lump_mass(dm: &DynamicModel, u: &[f64], ws: &mut DynWorkspace) {
    let (model, pl) = (&dm.line, &dm.placement);
    let nodes = ws.scope.part.nodes.clone();
    let Some(h) = &dm.environment.hydro else {
        ws.mass[nodes.clone()].copy_from_slice(&ws.structural_mass[nodes]);
        return;
    };
    let dofs = 3 * nodes.start..3 * nodes.end;
    let [cos, sin] = &mut ws.loads.node_tangent;
    loads::node_tangents(
        &pl.base[dofs.clone()],
        &u[dofs],
        [&mut cos[nodes.clone()], &mut sin[nodes.clone()]],
    );
    let [cos, sin] = &ws.loads.node_tangent;
    let hc = h.coefficients();
    // The line's own mass plus the added mass, in one pass (the same sums as a copy and `+=`).
    let line = ws.structural_mass[nodes.clone()].iter();
    for ((i, m), s) in ws.mass.iter_mut().enumerate().skip(nodes.start).zip(line) {
        let c = model.node_coefficients.get(i).unwrap_or(&hc);
        let ma = h.added_mass(c, model.node_hydro_od[i], model.tributary[i]);
        let (tx, ty) = (cos[i], sin[i]);
        *m = [
            s[0] + ma * (1.0 - tx * tx),
            s[1] + -ma * tx * ty,
            s[2] + ma * (1.0 - ty * ty),
            s[3],
        ];
    }
    // Attached bodies' added mass: isotropic (a compact body).
    for a in model.attachments.iter().filter(|a| nodes.contains(&a.node)) {
        ws.mass[a.node][0] += a.added_mass;
        ws.mass[a.node][2] += a.added_mass;
    }
}

/// The lumped mass's part of the tangent, `c_m·M_i` at the nodes `i` of `nodes`.
pub(super) fn add_mass_tangent(
    asm: &mut Assembler,
    model: &LineModel,
    c_m: f64,
    (mass, nodes): (&[[f64; 4]], Range<usize>),
) {
    for (i, m) in mass.iter().enumerate().take(nodes.end).skip(nodes.start) {
        asm.add_node_block(i, c_m * m[0], c_m * m[1], c_m * m[2]);
        asm.add_dof_tangent(model, 3 * i + 2, c_m * m[3]);
    }
}
