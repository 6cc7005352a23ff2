//! The start of a dynamic run on the seabed a lay left (`[as_laid]`, [`crate::scene::as_laid`]):
//! each node over the laid pipe's span takes the seabed history and friction anchors of the laid
//! point nearest to it, and the line is brought to its static equilibrium on that seabed (each
//! node's reaction its law's trial from the laid history: the pipe rests in the lay's trench, not
//! at the initial penetration of the scene's statics); the run starts at rest there.

use catena_fe::dynamics::{self, DynState, DynWorkspace, DynamicModel};

use catena_fe::statics::{self, StaticOptions, StaticWorkspace};

use crate::error::AppError;
use crate::scene::as_laid::AsLaid;
use crate::scene::riser::RiserScene;

/// The State a run starts from on the laid seabed `al`, from the static displacements `u`; the
/// number of nodes that took a laid history.
pub fn start_state(
    dm: &DynamicModel,
    u: &[f64],
    (scene, al): (&RiserScene, &AsLaid),
    ws: &mut DynWorkspace,
) -> Result<(DynState, usize), AppError> {
    let file = &scene.file;
    let fail = |message: String| AppError::Run {
        file: file.clone(),
        message: format!("key `as_laid.file` ({}): {message}", al.file),
    };
    let mut carry = dynamics::initial_state(dm, u, ws).carry();
    let line = &dm.line;
    let n = line.nodes();
    let stride = carry.friction_anchor.len() / n;
    let base = &dm.placement.base;
    let mut mapped = 0;
    for i in 0..n {
        let x = base[3 * i] + carry.u[3 * i];
        let Some(p) = al.seabed.nearest(x - al.x_shift) else {
            continue;
        };
        let od = line.elements[i.min(n - 2)].contact_od;
        if (od / al.seabed.contact_od - 1.0).abs() > 1e-9 {
            return Err(fail(format!(
                "the laid pipe's contact diameter is {} m, this line's {od} m at node {i}",
                al.seabed.contact_od
            )));
        }
        if std::mem::discriminant(&p.history) != std::mem::discriminant(&carry.history[i]) {
            return Err(fail(format!(
                "the laid seabed is of another law than this scene's [seabed] (node {i})"
            )));
        }
        if p.friction.len() != stride {
            return Err(fail(format!(
                "the laid seabed has {} friction anchors a node, this scene {stride} (axial \
                 friction on in one and not the other)",
                p.friction.len()
            )));
        }
        carry.history[i] = p.history;
        // The anchors' x in this scene's frame; a second entry (z) is unchanged.
        for (k, a) in p.friction.iter().enumerate() {
            carry.friction_anchor[stride * i + k] = if k == 0 { a + al.x_shift } else { *a };
        }
        mapped += 1;
    }
    if mapped == 0 {
        let (a, b) = (
            al.seabed.points[0].x + al.x_shift,
            al.seabed.points[al.seabed.points.len() - 1].x + al.x_shift,
        );
        return Err(fail(format!(
            "no node of this line lies over the laid pipe ({a:.1} to {b:.1} m in this scene's x, \
             with x_shift {})",
            al.x_shift
        )));
    }
    let mut sws = StaticWorkspace::new(line).map_err(|source| AppError::Solver {
        file: file.clone(),
        source,
    })?;
    sws.on_histories(carry.history.clone(), carry.friction_anchor.clone());
    let opts = StaticOptions {
        tol: scene.statics.tolerance,
        max_iter: scene.statics.max_iterations,
        ..StaticOptions::default()
    };
    statics::solve_in(
        line,
        scene.hydro.as_ref(),
        &dm.placement,
        &mut carry.u,
        &mut sws,
        &opts,
    )
    .map_err(|e| fail(format!("the statics on the laid seabed: {e}")))?;
    let state = dynamics::carried_state(dm, &carry, ws).map_err(fail)?;
    Ok((state, mapped))
}
