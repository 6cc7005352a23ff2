//! A lay's step, and the threads its window is stepped on.
//!
//! **A step** sets the top's motion for the step (the vessel's track over the waves, the top moving
//! down the tower or held at the exit, the top element's rest length there: [`super::exit`]), steps
//! the window, and pays out.
//!
//! **Two threads** ([`super::LayOptions::threads`] from 2): a [`Pair`] steps the window, each thread
//! its part of it, to the same bits as one thread. The window's Model changes every step (the
//! vessel's track, the top's motion, the top element's rest length at the exit): it is an [`Arc`]
//! that both threads read during a step and only the lay changes between steps
//! ([`Lay::model_mut`]), so the second thread never steps a stale copy (its decisions would
//! differ: the residual's floor sums over every element). The window itself changes when it moves
//! ([`Lay::rewindow`](super::Lay)): the pair is stopped before and started again after, on the new
//! window's Model and Workspace, the wave samples shared between the threads
//! ([`catena_fe::dynamics::Samples::Shared`]: the window's upper half, where the waves reach, is
//! the first part). A checkpoint takes the pair's whole solver memory. A lay writes
//! its files at its end, so no writer keeps a thread while it steps: on two cores it steps on two.

use std::sync::Arc;

use catena_fe::dynamics::{self, Drive, DynamicModel, StepError};
use catena_fe::motion::TopMotion;

use super::{Lay, TENSION_FILTER};
use crate::error::AppError;

/// The threads a window is stepped on.
#[derive(Debug, Default)]
pub(super) struct Stepping {
    /// One thread or two for each step ([`Drive`], from [`super::LayOptions::threads`]; one
    /// before it is set), across the windows.
    pub drive: Drive,
}

impl Lay {
    /// One step of the lay: the top's motion for the step, the step, the payout.
    pub(super) fn step(&mut self, dt: f64) -> Result<(), StepError> {
        let rate = self.payout_rate(dt);
        let speed = self.vessel_speed_at(self.state.t + 0.5 * dt);
        let s = rate * (1.0 + self.eps);
        let t = self.state.t;
        // The vessel meets the waves where it is: its RAO origin moves with it over the step.
        let origin = self
            .dspec
            .vessel
            .as_ref()
            .map(|v| v.origin_x + self.vessel_x);
        if let (Some(v), Some(x)) = (&mut self.model_mut().vessel, origin) {
            v.track(x, t, speed);
        }
        let (d0, vel) = self.top_motion(speed, s, dt);
        // Linear over the step (the series' last point beyond it, so that the velocity at the
        // step's end is the step's).
        self.model_mut().motion = Some(TopMotion::Series(vec![
            (t, d0[0], d0[1]),
            (
                t + 2.0 * dt,
                d0[0] + 2.0 * dt * vel[0],
                d0[1] + 2.0 * dt * vel[1],
            ),
        ]));
        let info = self
            .stepping
            .drive
            .advance(&self.dm, &mut self.state, &mut self.ws, dt)?;
        self.iterations += info.iterations;
        self.cuts += info.cuts;
        self.vessel_x += speed * dt;
        self.paid += rate * dt;
        self.d_top -= s * dt;
        self.rate = rate;
        dynamics::results(&self.dm, &self.state, &self.ws, &mut self.res);
        self.tension = self.exit_tension();
        self.measured += (self.tension - self.measured) * (dt / TENSION_FILTER).min(1.0);
        Ok(())
    }

    /// The window's Model, to change between steps: no thread reads it then (the second lets go
    /// of it before a step is done), so it is changed in place, never copied.
    pub(super) fn model_mut(&mut self) -> &mut DynamicModel {
        Arc::make_mut(&mut self.dm)
    }

    /// Engages the window's drive ([`Drive::start`]): a second stepping thread where the lay may
    /// keep two busy and the window's band is cut in two ([`catena_fe::dynamics::Pair::start`]);
    /// a window of its own each time it moves.
    pub(super) fn pair_up(&mut self) -> Result<(), AppError> {
        self.stepping
            .drive
            .start(&self.dm, &self.state, &mut self.ws);
        Ok(())
    }

    /// Ends the window's second stepping thread, if there is one (before the window moves, and
    /// at the lay's end).
    pub(super) fn unpair(&mut self) {
        self.stepping.drive.stop(&self.dm, &mut self.ws);
    }
}
