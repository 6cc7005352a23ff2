//! The linear seabed's contact in the dynamics ([`crate::loads`], item 2), a run of nodes at a
//! time, for the commonest seabed: the linear law on a flat mudline, one law for every node (no soil
//! zones) and no soil buoyancy. Per node `i`, with the invert's penetration
//! `z_pen = z_mudline − (z_i − D_i/2)` and its rate `ż_pen = −v_z`:
//!
//! ```text
//! P = k·D·z_pen,  P' = k·D          for z_pen > 0, else 0
//! F_d = c·D·ż_pen, c_d = c·D        for z_pen > 0 and c > 0, else 0
//! F = P + 0 + F_d                   (N/m; the law's sum, the soil buoyancy's 0 included)
//! F_z −= L_i·F;  K_zz += s_k·(L_i·P' + c_v·L_i·c_d)   when the tangent is asked and P' or c_d ≠ 0
//! ```
//!
//! (`D` the law's contact diameter, `D_i` the node's, `L_i` its tributary length, `s_k` and `c_v`
//! the dynamics' factors). Two passes: the forces and tangents of all the nodes, array in, array
//! out, with selects and no branch ([`contact_dispatch`], compiled also for AVX2 and AVX-512 and
//! chosen at run time: four or eight nodes at once); then, node by node, the residual and the
//! tangent, and in the pass that keeps them, each node's next history
//! ([`catena_seabed::linear::LinearHistory::next`]). The same operations in the same order as
//! [`catena_seabed::law::Seabed::response`] and the node loop of `seabed_loops`, so the same
//! values to the bit (`linear_contact_lanes_are_the_node_loop_to_the_bit`).

use std::ops::Range;

use catena_seabed::law::{Seabed, SeabedHistory, TrialMemo};
use catena_seabed::linear::LinearSeabed;

use crate::assembly::{Assembler, Placement};
use crate::model::LineModel;

use super::TangentScale;

/// The arrays of the contact passes, one entry per node (allocated once, with the Workspace).
#[derive(Debug, Clone)]
pub struct ContactScratch {
    /// The penetration `z_pen`, m.
    pen: Vec<f64>,
    /// `L_i·F`, N.
    load: Vec<f64>,
    /// The tangent's diagonal term (where `flag` says so), N/m.
    tangent: Vec<f64>,
    /// Whether the node adds `tangent` (`P'` or `c_d` not zero, the tangent asked for).
    flag: Vec<bool>,
}

impl ContactScratch {
    /// Sized for `n` nodes.
    pub fn new(n: usize) -> Self {
        Self {
            pen: vec![0.0; n],
            load: vec![0.0; n],
            tangent: vec![0.0; n],
            flag: vec![false; n],
        }
    }
}

/// The law's and the line's constants of [`contact_lanes`].
#[derive(Debug, Clone, Copy)]
struct Constants {
    /// `k·D`, N/m².
    kd: f64,
    /// `c·D` (N·s/m²) where the law has damping (`c > 0`).
    cd: Option<f64>,
    mudline_z: f64,
    scale: TangentScale,
}

/// One run of nodes' inputs and outputs of [`contact_dispatch`].
struct Run<'a> {
    /// The nodes' base coordinates, displacements and velocities (three dofs a node).
    base: &'a [f64],
    u: &'a [f64],
    v: &'a [f64],
    od: &'a [f64],
    len: &'a [f64],
    /// The force per length `F` (the seabed force the friction and the results read), N/m.
    force: &'a mut [f64],
    pen: &'a mut [f64],
    load: &'a mut [f64],
    tangent: &'a mut [f64],
    flag: &'a mut [bool],
}

/// The linear seabed's contact at the nodes `nodes` (see the module docs): `F` into
/// `seabed_force`, `L·F` taken from the residual, the tangent where asked, and with `keep` each
/// node's next history from `committed`.
#[allow(clippy::too_many_arguments)]
pub(super) fn add_linear_contact(
    (seabed, law, dt): (&Seabed, &LinearSeabed, f64),
    (model, pl, mudline_z): (&LineModel, &Placement, f64),
    (u, v): (&[f64], &[f64]),
    scale: TangentScale,
    asm: &mut Assembler,
    (committed, keep): (&[SeabedHistory], Option<&mut [SeabedHistory]>),
    (sc, seabed_force): (&mut ContactScratch, &mut [f64]),
    nodes: &Range<usize>,
) {
    let k = Constants {
        kd: law.stiffness * law.diameter,
        cd: (law.damping > 0.0).then_some(law.damping * law.diameter),
        mudline_z,
        scale,
    };
    let (r, dofs) = (nodes.clone(), 3 * nodes.start..3 * nodes.end);
    let run = Run {
        base: &pl.base[dofs.clone()],
        u: &u[dofs.clone()],
        v: &v[dofs],
        od: &model.node_od[r.clone()],
        len: &model.tributary[r.clone()],
        force: &mut seabed_force[r.clone()],
        pen: &mut sc.pen[r.clone()],
        load: &mut sc.load[r.clone()],
        tangent: &mut sc.tangent[r.clone()],
        flag: &mut sc.flag[r],
    };
    contact_dispatch(k, run);
    for i in nodes.clone() {
        asm.residual[3 * i + 1] -= sc.load[i];
        if sc.flag[i] {
            asm.add_dof_tangent(model, 3 * i + 1, sc.tangent[i]);
        }
    }
    if let Some(next) = keep {
        for i in nodes.clone() {
            match &committed[i] {
                SeabedHistory::Linear(h) => next[i] = SeabedHistory::Linear(h.next(sc.pen[i])),
                // A history of another law (which a checked scene never gives): the law's own
                // reading of it (its force does not depend on it).
                other => {
                    let (z, zdot, memo) = (sc.pen[i], -v[3 * i + 1], &mut TrialMemo::default());
                    seabed.response_and_next(other, z, zdot, dt, (memo, &mut next[i]));
                }
            }
        }
    }
}

/// [`contact_lanes`] compiled for the baseline processor and again for AVX2 and AVX-512, chosen at
/// run time.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn contact_dispatch<'a>(k: Constants, run: Run<'a>) {
    match (k.cd, k.scale.with_k) {
        (None, false) => contact_lanes::<false, false>(k, run),
        (None, true) => contact_lanes::<false, true>(k, run),
        (Some(_), false) => contact_lanes::<true, false>(k, run),
        (Some(_), true) => contact_lanes::<true, true>(k, run),
    }
}

/// The nodes' contact forces and tangents (the module docs' first pass); `DAMPED`: the law has
/// damping; `WITH_K`: the tangent is asked for.
#[inline(always)]
fn contact_lanes<const DAMPED: bool, const WITH_K: bool>(k: Constants, run: Run<'_>) {
    let n = run.force.len();
    let (od, len) = (&run.od[..n], &run.len[..n]);
    let (pen, load, tangent, flag) = (
        &mut run.pen[..n],
        &mut run.load[..n],
        &mut run.tangent[..n],
        &mut run.flag[..n],
    );
    let cd = k.cd.unwrap_or(0.0);
    let nodes = run.base.chunks_exact(3).zip(run.u.chunks_exact(3));
    let nodes = nodes.zip(run.v.chunks_exact(3)).zip(run.force.iter_mut());
    for (j, (((b, u), v), force)) in nodes.enumerate() {
        // loads::penetration_of (flat).
        let z = k.mudline_z - ((b[1] + u[1]) - 0.5 * od[j]);
        let zdot = -v[1];
        // LinearSeabed::force and ::damping_force, then Seabed::response's sum.
        let touching = z > 0.0;
        let (p, dp) = if touching {
            (k.kd * z, k.kd)
        } else {
            (0.0, 0.0)
        };
        let (fd, dfd) = if DAMPED && touching {
            (cd * zdot, cd)
        } else {
            (0.0, 0.0)
        };
        let total = p + 0.0 + fd;
        let kt = dp + 0.0;
        *force = total;
        pen[j] = z;
        let l = len[j];
        load[j] = l * total;
        if WITH_K {
            flag[j] = kt != 0.0 || dfd != 0.0;
            tangent[j] = k.scale.k * (kt * l + k.scale.c_v * (dfd * l));
        } else {
            flag[j] = false;
        }
    }
}
