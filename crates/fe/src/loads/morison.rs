//! The Morison loads at the nodes ([`crate::loads`], item 4) for a line whose nodes all take the
//! sea's coefficients, a run of nodes at a time, in three passes:
//!
//! 1. **gather** (scalar): each node's velocity relative to the water,
//!    `r = (U(z) + w_x − v_x, w_z − v_z)` (`w` the waves' velocity, `0` and no sum where a node has
//!    no wave kinematics), and the water's acceleration, into arrays;
//! 2. **the loads** ([`morison_dispatch`]): per node, with the unit tangent `t`, `s = r·t`, the
//!    normal part `r_n = r − s·t`, `|r_n|`, the drag `½ρ Cd_n D L |r_n| r_n + ½ρ Cd_a πD L |s| s t`,
//!    its velocity derivative `½ρ Cd_a πD L·2|s|·t tᵀ + ½ρ Cd_n D L (|r_n| (I − t tᵀ) + r_n r_nᵀ/|r_n|)`
//!    (the second term where `|r_n| > 0`), and the wave inertia `ρA(1 + Ca)·a_n + ρA·a_t` (`A = πD²/4`,
//!    per tributary length `L`): array in, array out, no branch, compiled also for AVX2 and AVX-512
//!    and chosen at run time, so that four or eight nodes' square roots and divisions run at once;
//! 3. **scatter** (scalar): each node's drag, then its wave inertia, taken from the residual and its
//!    damping block added to the tangent.
//!
//! The same operations in the same order as [`crate::environment::Hydro::drag`] and
//! [`crate::environment::Hydro::wave_inertia`] (no fused multiply-adds: Rust never contracts them),
//! so the same values to the bit (`morison_lanes_are_the_node_loop_to_the_bit`). Measured in
//! `benches/README.md`.

use std::ops::Range;

use crate::assembly::{Assembler, Placement};
use crate::environment::Hydro;
use crate::model::LineModel;
use crate::waves::Kinematics;

/// The arrays of the Morison passes, one entry per node (allocated once, with the Workspace).
#[derive(Debug, Clone)]
pub struct MorisonScratch {
    /// The velocity relative to the water `(r_x, r_z)`, m/s.
    rel: [Vec<f64>; 2],
    /// The water's acceleration `(a_x, a_z)`, m/s² (zero where none).
    acc: [Vec<f64>; 2],
    /// Whether the node has wave kinematics (its wave inertia is added).
    waves: Vec<bool>,
    /// The drag `(f_x, f_z)`, N.
    drag: [Vec<f64>; 2],
    /// The wave inertia `(f_x, f_z)`, N.
    inertia: [Vec<f64>; 2],
    /// The drag's velocity derivative `[c_xx, c_xz, c_zz]`, N·s/m.
    damping: [Vec<f64>; 3],
}

impl MorisonScratch {
    /// Sized for `n` nodes.
    pub fn new(n: usize) -> Self {
        let v = || vec![0.0; n];
        Self {
            rel: [v(), v()],
            acc: [v(), v()],
            waves: vec![false; n],
            drag: [v(), v()],
            inertia: [v(), v()],
            damping: [v(), v(), v()],
        }
    }
}

/// The sea's constants of the loads: `½ρ Cd_n`, `½ρ Cd_a π`, `ρπ` and `1 + Ca`, each formed as
/// [`Hydro::drag`] and [`Hydro::wave_inertia`] form them.
#[derive(Debug, Clone, Copy)]
struct Constants {
    kn0: f64,
    ka0: f64,
    rho_pi: f64,
    one_ca: f64,
}

/// One run of nodes' inputs to [`morison_dispatch`] (each slice the run's length).
struct Inputs<'a> {
    cos: &'a [f64],
    sin: &'a [f64],
    rel: [&'a [f64]; 2],
    acc: [&'a [f64]; 2],
    od: &'a [f64],
    len: &'a [f64],
}

/// One run of nodes' outputs of [`morison_dispatch`].
struct Outputs<'a> {
    drag: [&'a mut [f64]; 2],
    inertia: [&'a mut [f64]; 2],
    damping: [&'a mut [f64]; 3],
}

/// Adds the Morison loads of the nodes `nodes` (every node with the sea's coefficients; see the
/// module docs): their drag and wave inertia to the residual and, `with_c`, `f·C` (the drag's
/// velocity derivative times `f`) to the tangent.
#[allow(clippy::too_many_arguments)]
pub(super) fn add_morison(
    h: &Hydro,
    (model, pl): (&LineModel, &Placement),
    (u, v, wave_kin): (&[f64], &[f64], &[Option<Kinematics>]),
    (with_c, f): (bool, f64),
    asm: &mut Assembler,
    [cos, sin]: [&[f64]; 2],
    sc: &mut MorisonScratch,
    nodes: &Range<usize>,
) {
    let c = h.coefficients();
    let (kn0, ka0) = h.drag_factors(&c);
    let k = Constants {
        kn0,
        ka0,
        rho_pi: h.water_density * std::f64::consts::PI,
        one_ca: 1.0 + c.ca_normal,
    };
    // 1. Gather, zipped rather than indexed (the indexed loop checked every bound). A list of
    // wave kinematics shorter than the nodes (the statics': empty) has none for the nodes beyond
    // it, as the node loop reads it.
    let (r, dofs) = (nodes.clone(), 3 * nodes.start..3 * nodes.end);
    let kins = wave_kin.get(r.clone());
    let pts = pl.base[dofs.clone()].chunks_exact(3);
    let pts = pts.zip(u[dofs.clone()].chunks_exact(3).zip(v[dofs].chunks_exact(3)));
    let [rx, rz] = &mut sc.rel;
    let [ax, az] = &mut sc.acc;
    let outs = rx[r.clone()].iter_mut().zip(&mut rz[r.clone()]);
    let outs = outs.zip(ax[r.clone()].iter_mut().zip(&mut az[r.clone()]));
    let outs = outs.zip(&mut sc.waves[r]);
    for (j, ((((rx, rz), (ax, az)), waves), (b, (u, v)))) in outs.zip(pts).enumerate() {
        let z = b[1] + u[1];
        let kin = match kins {
            Some(k) => k[j],
            None => wave_kin.get(nodes.start + j).copied().flatten(),
        };
        let current = h.current_at(z);
        *waves = kin.is_some();
        (*rx, *rz, *ax, *az) = match kin {
            None => (current - v[0], -v[1], 0.0, 0.0),
            Some(k) => {
                let [wx, wz] = k.velocity;
                let [gx, gz] = k.acceleration;
                (current + wx - v[0], wz - v[1], gx, gz)
            }
        };
    }
    // 2. The loads.
    let r = nodes.clone();
    let inputs = Inputs {
        cos: &cos[r.clone()],
        sin: &sin[r.clone()],
        rel: [&sc.rel[0][r.clone()], &sc.rel[1][r.clone()]],
        acc: [&sc.acc[0][r.clone()], &sc.acc[1][r.clone()]],
        od: &model.node_hydro_od[r.clone()],
        len: &model.tributary[r.clone()],
    };
    let [dx, dz] = &mut sc.drag;
    let [ix, iz] = &mut sc.inertia;
    let [cxx, cxz, czz] = &mut sc.damping;
    let outputs = Outputs {
        drag: [&mut dx[r.clone()], &mut dz[r.clone()]],
        inertia: [&mut ix[r.clone()], &mut iz[r.clone()]],
        damping: [
            &mut cxx[r.clone()],
            &mut cxz[r.clone()],
            &mut czz[r.clone()],
        ],
    };
    morison_dispatch(k, &inputs, outputs, with_c);
    // 3. Scatter, in the node loop's order: the drag, the wave inertia, the damping block.
    let [dx, dz] = &sc.drag;
    let [ix, iz] = &sc.inertia;
    for i in nodes.clone() {
        asm.residual[3 * i] -= dx[i];
        asm.residual[3 * i + 1] -= dz[i];
        if sc.waves[i] {
            asm.residual[3 * i] -= ix[i];
            asm.residual[3 * i + 1] -= iz[i];
        }
        if with_c {
            let [cxx, cxz, czz] = &sc.damping;
            asm.add_node_block(i, f * cxx[i], f * cxz[i], f * czz[i]);
        }
    }
}

/// [`morison_lanes`] with and without the damping, compiled for the baseline processor and again
/// for AVX2 and AVX-512, chosen at run time.
#[multiversion::multiversion(targets("x86_64+avx512f", "x86_64+avx2"))]
fn morison_dispatch<'a>(k: Constants, inp: &Inputs<'a>, out: Outputs<'a>, with_c: bool) {
    if with_c {
        morison_lanes::<true>(k, inp, out);
    } else {
        morison_lanes::<false>(k, inp, out);
    }
}

/// The loads of a run of nodes (the module docs, pass 2), each node's as [`Hydro::drag`] and
/// [`Hydro::wave_inertia`] compute them; `WITH_C`: also the drag's velocity derivative.
#[inline(always)]
fn morison_lanes<const WITH_C: bool>(k: Constants, inp: &Inputs<'_>, out: Outputs<'_>) {
    let n = inp.cos.len();
    let Outputs {
        drag: [dx, dz],
        inertia: [ix, iz],
        damping: [cxx, cxz, czz],
    } = out;
    let (dx, dz, ix, iz) = (&mut dx[..n], &mut dz[..n], &mut ix[..n], &mut iz[..n]);
    let (cxx, cxz, czz) = (&mut cxx[..n], &mut cxz[..n], &mut czz[..n]);
    let (sin, [rx, rz], [ax, az]) = (&inp.sin[..n], inp.rel, inp.acc);
    let (rx, rz, ax, az) = (&rx[..n], &rz[..n], &ax[..n], &az[..n]);
    let (od, len) = (&inp.od[..n], &inp.len[..n]);
    for j in 0..n {
        let (tx, tz) = (inp.cos[j], sin[j]);
        let (d, l) = (od[j], len[j]);
        // Hydro::drag.
        let s = rx[j] * tx + rz[j] * tz;
        let (nx, nz) = (rx[j] - s * tx, rz[j] - s * tz);
        let vn = (nx * nx + nz * nz).sqrt();
        let kn = k.kn0 * d * l;
        let ka = k.ka0 * d * l;
        dx[j] = kn * vn * nx + ka * s.abs() * s * tx;
        dz[j] = kn * vn * nz + ka * s.abs() * s * tz;
        if WITH_C {
            let xx = 2.0 * ka * s.abs() * tx * tx;
            let xz = 2.0 * ka * s.abs() * tx * tz;
            let zz = 2.0 * ka * s.abs() * tz * tz;
            // Both sums formed, one kept (a select, not a branch: the lanes stay together).
            let moving = vn > 0.0;
            let xx_n = xx + kn * (vn * (1.0 - tx * tx) + nx * nx / vn);
            let xz_n = xz + kn * (-vn * tx * tz + nx * nz / vn);
            let zz_n = zz + kn * (vn * (1.0 - tz * tz) + nz * nz / vn);
            cxx[j] = if moving { xx_n } else { xx };
            cxz[j] = if moving { xz_n } else { xz };
            czz[j] = if moving { zz_n } else { zz };
        }
        // Hydro::wave_inertia.
        let fk = k.rho_pi * d * d / 4.0 * l;
        let c = fk * k.one_ca;
        let s = ax[j] * tx + az[j] * tz;
        ix[j] = c * (ax[j] - s * tx) + fk * s * tx;
        iz[j] = c * (az[j] - s * tz) + fk * s * tz;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::Coefficients;
    use crate::test_rng::uniform;

    /// The lanes give each node's drag, damping block and wave inertia to the bit of
    /// [`Hydro::drag`] and [`Hydro::wave_inertia`] node by node, over 1000 random nodes (a current
    /// profile, some nodes with waves and some without, some with no normal velocity: the
    /// select's other side).
    #[test]
    fn morison_lanes_are_the_node_loop_to_the_bit() {
        let h = Hydro {
            water_density: 1025.0,
            cd_normal: 1.2,
            cd_axial: 0.008,
            ca_normal: 1.0,
            current: vec![(-1000.0, 0.1), (0.0, 0.8)],
        };
        let mut st = 0x9E37_79B9_7F4A_7C15_u64;
        let n = 1000;
        let mut r = || uniform(&mut st);
        let th: Vec<f64> = (0..n).map(|_| 6.3 * r()).collect();
        let (cos, sin): (Vec<f64>, Vec<f64>) = th.iter().map(|t| (t.cos(), t.sin())).unzip();
        let z: Vec<f64> = (0..n).map(|_| -1000.0 * r()).collect();
        let mut vel: Vec<[f64; 2]> = (0..n).map(|_| [r() - 0.5, r() - 0.5]).collect();
        // Nodes moving with the current, no waves (no velocity relative to the water): the
        // select's other side.
        for i in (0..n).step_by(7) {
            vel[i] = [h.current_at(z[i]), 0.0];
        }
        let kin: Vec<Option<Kinematics>> = (0..n)
            .map(|i| {
                (i % 3 != 0 && i % 7 != 0).then(|| Kinematics {
                    velocity: [r() - 0.5, r() - 0.5],
                    acceleration: [r() - 0.5, r() - 0.5],
                })
            })
            .collect();
        let od: Vec<f64> = (0..n).map(|_| 0.2 + 0.3 * r()).collect();
        let len: Vec<f64> = (0..n).map(|_| 0.5 + 4.5 * r()).collect();
        let (kn0, ka0) = h.drag_factors(&h.coefficients());
        let k = Constants {
            kn0,
            ka0,
            rho_pi: h.water_density * std::f64::consts::PI,
            one_ca: 1.0 + h.ca_normal,
        };
        let mut rel = [vec![0.0; n], vec![0.0; n]];
        let mut acc = [vec![0.0; n], vec![0.0; n]];
        for i in 0..n {
            let c = h.current_at(z[i]);
            let w = kin[i].map(|k| (k.velocity, k.acceleration));
            (rel[0][i], rel[1][i]) = match w {
                None => (c - vel[i][0], -vel[i][1]),
                Some(([wx, wz], _)) => (c + wx - vel[i][0], wz - vel[i][1]),
            };
            [acc[0][i], acc[1][i]] = w.map_or([0.0; 2], |w| w.1);
        }
        let inp = Inputs {
            cos: &cos,
            sin: &sin,
            rel: [&rel[0], &rel[1]],
            acc: [&acc[0], &acc[1]],
            od: &od,
            len: &len,
        };
        let mut o = MorisonScratch::new(n);
        let [dx, dz] = &mut o.drag;
        let [ix, iz] = &mut o.inertia;
        let [cxx, cxz, czz] = &mut o.damping;
        let out = Outputs {
            drag: [dx, dz],
            inertia: [ix, iz],
            damping: [cxx, cxz, czz],
        };
        morison_dispatch(k, &inp, out, true);
        let c: Coefficients = h.coefficients();
        let bits = |x: f64| x.to_bits();
        let mut still = 0;
        for i in 0..n {
            let t = (cos[i], sin[i]);
            let w = kin[i].map(|k| k.velocity);
            let d = h.drag(&c, od[i], len[i], t, z[i], (vel[i][0], vel[i][1]), w, true);
            assert_eq!(bits(o.drag[0][i]), bits(d.force[0]), "node {i} drag x");
            assert_eq!(bits(o.drag[1][i]), bits(d.force[1]), "node {i} drag z");
            for (a, b) in [&o.damping[0], &o.damping[1], &o.damping[2]]
                .iter()
                .zip(d.damping)
            {
                assert_eq!(bits(a[i]), bits(b), "node {i} damping");
            }
            if let Some(kk) = kin[i] {
                let f = h.wave_inertia(&c, od[i], len[i], t, kk.acceleration);
                assert_eq!(bits(o.inertia[0][i]), bits(f[0]), "node {i} inertia x");
                assert_eq!(bits(o.inertia[1][i]), bits(f[1]), "node {i} inertia z");
            }
            let n_speed = {
                let (rx, rz) = (rel[0][i], rel[1][i]);
                let s = rx * t.0 + rz * t.1;
                (rx - s * t.0).hypot(rz - s * t.1)
            };
            still += usize::from(n_speed == 0.0);
        }
        assert!(
            still > 0,
            "no node without normal velocity: the select's other side untested"
        );
    }
}
