//! The water kinematics of a step: sampled on the wave grid from the committed State when a
//! step first needs them, interpolated at the step's end (generic over the wave theory).

use std::ops::Range;

use crate::assembly::Placement;
use crate::wave_sampling::{fill_interval, grid_index, interpolate, KinematicsGrid};
use crate::waves::{Kinematics, WaveKinematics};

use super::*;

/// The water kinematics at each node at `t` into `ws.wave_kin` (nothing without waves, or without
/// hydrodynamics to load the line with them): see [`water_kinematics`].
pub(super) fn wave_kinematics(dm: &DynamicModel, state: &DynState, t: f64, ws: &mut DynWorkspace) {
    let env = &dm.environment;
    let (Some(waves), Some(_)) = (&env.waves, &env.hydro) else {
        return;
    };
    let out = WaterOut {
        nodes: ws.scope.part.nodes.clone(),
        kin: &mut ws.wave_kin,
        scratch: &mut ws.wave_scratch,
        grid: &mut ws.grid_trial,
        grid_new: &mut ws.grid_new,
        lane: ws.lane.as_mut(),
    };
    water_kinematics(waves, &dm.placement, env.water_level, state, t, &ws.u, out);
}

/// Where [`water_kinematics`] writes: at the nodes `nodes` (this thread's own: the loads it
/// assembles read the kinematics at those only), their kinematics, the theory's scratch, and the
/// new samples of the step (and whether it took any); on two threads, where this thread meets
/// the other, to hand over the lent samples ([`Lane::lend_samples`]).
pub(super) struct WaterOut<'a, S> {
    nodes: Range<usize>,
    kin: &'a mut [Option<Kinematics>],
    scratch: &'a mut S,
    grid: &'a mut KinematicsGrid,
    grid_new: &'a mut bool,
    lane: Option<&'a mut super::cut::Lane>,
}

/// The water kinematics of any wave theory ([`WaveKinematics`]) at each node at `t`: evaluated at
/// the positions of the iterate `u` (the predictor), or, when the waves are sampled on a time grid
/// (`kinematics_interval` h > 0), interpolated between the samples at the grid times around `t`
/// ([`crate::wave_sampling`]), new samples being taken from the committed `state` when the step
/// first needs them.
pub(super) fn water_kinematics<W: WaveKinematics>(
    waves: &W,
    pl: &Placement,
    level: f64,
    state: &DynState,
    t: f64,
    u: &[f64],
    out: WaterOut<'_, W::Scratch>,
) {
    let h = waves.sampling_interval();
    *out.grid_new = false;
    // Node `i` at the iterate (the predictor).
    let predicted = |i: usize| {
        (
            pl.base[3 * i] + u[3 * i],
            pl.base[3 * i + 1] + u[3 * i + 1] - level,
        )
    };
    let nodes = out.nodes;
    if h <= 0.0 {
        for i in nodes {
            let (x, z) = predicted(i);
            out.kin[i] = waves.water_at(x, z, t, out.scratch);
        }
        return;
    }
    let m = grid_index(t, h);
    let reuse = state.wave_grid.as_ref().filter(|g| g.index == m);
    if reuse.is_none() {
        let mut lane = out.lane;
        if let Some(l) = lane.as_deref_mut() {
            l.lend_state(state);
        }
        // Node `i` at grid time `tm`, extrapolated from the committed State (on the second
        // thread, a lent node's from the first's, [`super::cut::Lane::lent_state`]).
        let lent_state = lane.as_deref().filter(|l| l.side == 1);
        let (u, v, a) = (&state.u, &state.v, &state.a);
        let at = |tm: f64, i: usize| {
            let tau = tm - state.t;
            let p = |j: usize| {
                let (u, v, a) = lent_state
                    .and_then(|l| l.lent_state(j))
                    .unwrap_or((u[j], v[j], a[j]));
                pl.base[j] + u + tau * v + 0.5 * tau * tau * a
            };
            (p(3 * i), p(3 * i + 1) - level)
        };
        let n = out.kin.len();
        for s in &mut out.grid.samples {
            s.resize(n, None); // sized once
        }
        let prev = state.wave_grid.as_ref();
        // On two threads the second also samples the first part's lent nodes, and the first
        // does not (its own nodes on either side of them: none above, its last node below).
        let lent = lane.as_ref().map_or(0..0, |l| l.lent.clone());
        let ranges = match lane.as_ref().map(|l| l.side) {
            Some(1) => [nodes.clone(), lent],
            _ => [
                nodes.start..lent.start.max(nodes.start),
                lent.end.max(nodes.start)..nodes.end,
            ],
        };
        for r in ranges.into_iter().filter(|r| !r.is_empty()) {
            fill_interval(waves, (h, m), prev, at, (&mut *out.grid, r), out.scratch);
        }
        out.grid.index = m;
        if let Some(l) = lane {
            l.lend_samples(out.grid);
        }
        *out.grid_new = true;
    }
    let grid = reuse.unwrap_or(out.grid);
    let s = (t - (m - 1) as f64 * h) / h;
    for (i, k) in out.kin[nodes.clone()].iter_mut().enumerate() {
        let i = nodes.start + i;
        // Each arm writes its own answer: a `match` that returned one built the interpolated
        // value on the stack and copied it over with loads straddling its stores, a stall per
        // node (1.7 % of the 3-hour storm's samples).
        match (&grid.samples[0][i], &grid.samples[1][i]) {
            (Some(k0), Some(k1)) => *k = Some(interpolate(k0, k1, s, h)),
            // Out of the water at a sample: the exact kinematics at the predicted position.
            _ => {
                let (x, z) = predicted(i);
                *k = waves.water_at(x, z, t, out.scratch);
            }
        }
    }
}
