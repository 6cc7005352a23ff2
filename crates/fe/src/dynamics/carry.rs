//! What a run leaves for the next when the line is at rest (a storm sequence's calm), and
//! the State at rest from it.

use crate::newton::Pass;
use catena_seabed::law::SeabedHistory;
use serde::{Deserialize, Serialize};

use super::*;

/// What a run leaves for the next one when the line has been brought to rest (a storm sequence's
/// calm interval): positions, every node's committed seabed history (its trench, its degradation)
/// and friction anchors. Velocities and accelerations are not carried: the next run starts at rest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Carry {
    /// Displacements from the placement's base, 3 per node.
    pub u: Vec<f64>,
    /// Each node's committed seabed history.
    pub history: Vec<SeabedHistory>,
    /// Each node's friction anchor ([`DynState::friction_anchor`]).
    pub friction_anchor: Vec<f64>,
}

impl DynState {
    /// What this State leaves for a run that continues from rest ([`Carry`]).
    pub fn carry(&self) -> Carry {
        Carry {
            u: self.u.clone(),
            history: self.history.clone(),
            friction_anchor: self.friction_anchor.clone(),
        }
    }
}

/// The dynamic State at rest from a carried one ([`Carry`]): `t = 0`, zero velocities, the
/// histories and anchors as carried, and the lumped `a0 = −M⁻¹F(u, 0)` (zero at an equilibrium).
/// The carry is checked to fit the Model (the error says which field is wrong).
pub fn carried_state(
    dm: &DynamicModel,
    carry: &Carry,
    ws: &mut DynWorkspace,
) -> Result<DynState, String> {
    let n = dm.line.nodes();
    let probe = DynState {
        t: 0.0,
        step: 0,
        u: carry.u.clone(),
        v: vec![0.0; 3 * n],
        a: vec![0.0; 3 * n],
        f_prev: vec![0.0; 3 * n],
        history: carry.history.clone(),
        wave_grid: None,
        friction_anchor: carry.friction_anchor.clone(),
    };
    probe.check_fits(dm)?;
    Ok(at_rest(dm, carry.clone(), ws))
}

/// The State at rest at `carry`, its forces evaluated and its acceleration `−M⁻¹F` on the free dofs.
pub(super) fn at_rest(dm: &DynamicModel, carry: Carry, ws: &mut DynWorkspace) -> DynState {
    let model = &dm.line;
    let n = model.nodes();
    let v = vec![0.0; 3 * n];
    let Carry {
        u,
        history,
        friction_anchor,
    } = carry;
    ws.factored_dt = None;
    let mut state = DynState {
        t: 0.0,
        step: 0,
        u,
        v: v.clone(),
        a: v,
        f_prev: vec![0.0; 3 * n],
        history,
        wave_grid: None,
        friction_anchor,
    };
    ws.u.copy_from_slice(&state.u);
    ws.v.copy_from_slice(&state.v);
    forces_at_iterate(dm, &state, ws, Pass::Forces, 0.0, 0.0, 0.0);
    state.f_prev.copy_from_slice(&ws.f);
    lump_mass(dm, &state.u, ws);
    for i in 0..n {
        let m = ws.mass[i];
        let (fx, fz, fr) = (ws.f[3 * i], ws.f[3 * i + 1], ws.f[3 * i + 2]);
        let det = m[0] * m[2] - m[1] * m[1];
        if det > 0.0 {
            let ax = -(m[2] * fx - m[1] * fz) / det;
            let az = -(m[0] * fz - m[1] * fx) / det;
            if model.equation[3 * i].is_some() {
                state.a[3 * i] = ax;
            }
            if model.equation[3 * i + 1].is_some() {
                state.a[3 * i + 1] = az;
            }
        }
        if m[3] > 0.0 && model.equation[3 * i + 2].is_some() {
            state.a[3 * i + 2] = -fr / m[3];
        }
    }
    state
}
