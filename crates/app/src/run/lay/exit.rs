//! The window's top: where the pipe leaves the tower, and how a node leaves it.
//!
//! **The tower's exit** ([`Top::Exit`]: a tower that holds a moment at the top, more than 5 % of
//! the sag bend's in the statics: one off the pipe's departure angle, clamped or on a stiff hinge).
//! The window's top node
//! is prescribed at the exit itself, moving with the vessel; the top element runs from the exit to
//! the first free node, its rest length the pipe between them,
//!
//! `L_top = L_first − d_top/(1 + ε)`,
//!
//! with `d_top` the distance of the top node's own material above the exit along the tower (at the
//! top's strain `ε`): the payout lengthens the top element, step by step
//! ([`catena_fe::model::LineModel::set_top_rest_length`]). The top node stands for the exit while
//! its material is within half an element of it: when it is half an element below
//! (`d_top ≤ −L/2`), it leaves the tower, put on the top element's cubic where its material is
//! (Hermite, from the exit's position and angle to the next node's) with the next node's velocity
//! and acceleration (the material's), and the node above it becomes the exit. Paid in, when the
//! top node's material is 0.6 of an element above the exit, the node below becomes the exit. So
//! `L_top` stays between 0.4 and 1.5 elements, the clamp is at the exit whatever the element
//! length (a tower off the pipe's departure angle holds its moment there), and a node leaves the
//! tower where and as the pipe already is.
//!
//! **A moving top** ([`Top::Moving`]: a tower at the pipe's departure angle, and a lay-down's wire
//! over the sheave). Where the top holds no moment, the top node may stand up to an element above
//! the exit: it moves down the tower's (or the wire's) line at the payout rate, the top element
//! keeps its length, and a node leaves when it reaches the exit, the node above it put one element
//! up the line. Each leaving node then releases no moment, and this costs no update of the top
//! element's length; a tower that holds a moment needs the clamp at the exit instead (with a
//! moving top, 3° off the departure angle laid 137.8 mm at 1 m elements and 126.7 mm at 0.5 m,
//! `validation/lay.md`).

use super::Lay;

/// How the window's top is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Top {
    /// At the tower's exit, by the tower (clamped or on its hinge).
    Exit,
    /// Above the exit, moving down the tower's or the wire's line.
    Moving,
}

impl Top {
    /// `d_top` at which the top node leaves the tower, and above which the node below it goes back
    /// onto it; `l_top` the top node's element's length at the top's strain.
    pub(super) fn thresholds(self, l_top: f64) -> (f64, f64) {
        match self {
            Top::Exit => (-0.5 * l_top, 0.6 * l_top),
            Top::Moving => (0.0, l_top),
        }
    }
}

/// Whether the lay clamps the pipe at the exit (the tower holds a moment in the statics `st`), the
/// window's first top node and its `d_top`: the statics' top node `o` at the exit, or the node above
/// it, one element up the tower (`full` the whole pipe's mesh, `eps` the top's strain).
pub(super) fn start(
    st: &crate::run::statics::StaticRun,
    full: &catena_fe::model::LineModel,
    o: usize,
    eps: f64,
) -> (bool, usize, f64) {
    if super::mesh::tower_holds_moment(st) {
        (true, o, 0.0)
    } else {
        (false, o - 1, full.elements[o - 1].l0 * (1.0 + eps))
    }
}

impl Lay {
    /// How the window's top is held now.
    pub(super) fn top(&self) -> Top {
        if self.clamp_at_exit && self.first >= self.pipe_end {
            Top::Exit
        } else {
            Top::Moving
        }
    }

    /// The rest length of the top element of a window whose top is node `first`, m.
    pub(super) fn top_rest_length(&self, first: usize) -> f64 {
        if self.clamp_at_exit && first >= self.pipe_end {
            self.exit_rest_length(first, self.d_top)
        } else {
            self.full.elements[first].l0
        }
    }

    /// `L_top = L_first − d_top/(1 + ε)`: the top element's rest length at the exit, m.
    fn exit_rest_length(&self, first: usize, d_top: f64) -> f64 {
        self.full.elements[first].l0 - d_top / (1.0 + self.eps)
    }

    /// The top node's displacement at the step's start and its velocity over the step of `dt`, the
    /// vessel at `speed` and the pipe paid out at `s` (m/s, at the top's strain); at the exit, the
    /// top element's rest length at the step's end is set (also for the sub-steps of a step cut).
    /// Above the exit the node is on the tower's line as the vessel's pitch turns it (rigidly, by
    /// `−β`: [`Lay::tower_up`]), the velocity the chord over the step.
    pub(super) fn top_motion(&mut self, speed: f64, s: f64, dt: f64) -> ([f64; 2], [f64; 2]) {
        let b = &self.dm.placement.base;
        match self.top() {
            Top::Exit => {
                let d0 = [self.exit0[0] + self.vessel_x - b[0], self.exit0[1] - b[1]];
                let l_end = self.exit_rest_length(self.first, self.d_top - s * dt);
                self.model_mut().line.set_top_rest_length(l_end);
                self.ws.top_rest_length_changed(&self.dm.line);
                (d0, [speed, 0.0])
            }
            Top::Moving => {
                let up = self.tower_up(self.state.t);
                let d0 = [
                    self.exit0[0] + self.vessel_x + self.d_top * up[0] - b[0],
                    self.exit0[1] + self.d_top * up[1] - b[1],
                ];
                if !self.pitches() {
                    return (d0, [speed - s * up[0], -s * up[1]]);
                }
                // The chord to where the node is at the step's end, on the tower turned then.
                let up1 = self.tower_up(self.state.t + dt);
                let (d1, x1) = (self.d_top - s * dt, self.vessel_x + speed * dt);
                let end = [
                    self.exit0[0] + x1 + d1 * up1[0] - b[0],
                    self.exit0[1] + d1 * up1[1] - b[1],
                ];
                (d0, [(end[0] - d0[0]) / dt, (end[1] - d0[1]) / dt])
            }
        }
    }

    /// Whether the tower pitches with the vessel: a `[vessel]` in waves.
    fn pitches(&self) -> bool {
        self.dm.vessel.is_some() && self.dm.environment.waves.is_some()
    }

    /// The vessel's pitch at `t`, rad (positive bow down; 0 where the tower does not pitch).
    pub(super) fn pitch_at(&self, t: f64) -> f64 {
        match (&self.dm.vessel, &self.dm.environment.waves) {
            (Some(v), Some(w)) => v.motion(w, t).motions[2],
            _ => 0.0,
        }
    }

    /// The upward direction of the top's line at `t`: the tower's, turned by the vessel's pitch
    /// (counter-clockwise by `−β`) while the top is the pipe's; the wire's own over the sheave.
    fn tower_up(&self, t: f64) -> [f64; 2] {
        if self.first < self.pipe_end {
            return self.up;
        }
        turned(self.up, self.pitch_at(t))
    }

    /// The tension at the tower's exit: the top node's; with a moving top, less the submerged
    /// weight of the pipe (or wire) between the top node and the exit.
    pub(super) fn exit_tension(&self) -> f64 {
        match self.top() {
            Top::Exit => self.res.tension[0],
            Top::Moving => {
                let w = self.full.elements[self.first].weight;
                self.res.tension[0] - w * self.d_top.max(0.0) / (1.0 + self.eps) * self.up[1]
            }
        }
    }

    /// The tower's exit (or the sheave) now, m.
    pub fn exit_point(&self) -> [f64; 2] {
        let top = self.at_window(0);
        match self.top() {
            Top::Exit => top,
            Top::Moving => {
                let up = self.tower_up(self.state.t);
                [top[0] - self.d_top * up[0], top[1] - self.d_top * up[1]]
            }
        }
    }

    /// Node `k`, the window's top, leaves the tower; node `k − 1`, `l` above it along the pipe,
    /// becomes the top: at the exit (`top` = [`Top::Exit`], node `k` put on the top element's
    /// cubic) or `l` up the tower's line from node `k` (the wire's line over the sheave).
    pub(super) fn leave_tower(&mut self, k: usize, l: f64, top: Top) {
        if top == Top::Exit && k > self.pipe_end {
            self.place_at_exit(k - 1, k);
            self.release(k);
            return;
        }
        if top == Top::Exit {
            self.release(k);
        }
        let p = self.at(k);
        if k - 1 < self.pipe_end {
            // Over the sheave, the wire runs out along its own line, not the tower's.
            let below = self.at(k + 1);
            let (dx, dz) = (p[0] - below[0], p[1] - below[1]);
            let len = dx.hypot(dz);
            self.up = [dx / len, dz / len];
        }
        let (theta, up) = self.new_top(k - 1, k);
        self.place_on_line(k - 1, [p[0] + l * up[0], p[1] + l * up[1]], k, theta);
    }

    /// The angle and the line's upward direction of node `g` becoming the window's top on the
    /// line. Over the sheave (a wire node) the wire's own line, at its angle on the branch nearest
    /// node `near`'s: the tower's angle would bend the top element and kick the top node's
    /// rotation, which the pinned sheave leaves to ring (and, with the wrap of a corotational
    /// angle, to spin). On the tower, the tower's line and angle turned with the vessel's pitch
    /// ([`catena_fe::boundary`]).
    fn new_top(&self, g: usize, near: usize) -> (f64, [f64; 2]) {
        if g < self.pipe_end {
            let near = self.store.u[3 * near + 2] + self.base.base[3 * near + 2];
            return (self.line_angle(near), self.up);
        }
        let beta = self.pitch_at(self.state.t);
        (self.theta - beta, turned(self.up, beta))
    }

    /// The angle of the line down from the top (`−up`) on the branch nearest `near`, rad.
    fn line_angle(&self, near: f64) -> f64 {
        let down = (-self.up[1]).atan2(-self.up[0]);
        near + catena_fe::beam::wrap(down - near)
    }

    /// Paid in: node `k + 1` becomes the top (at the exit, or `l` down the line from node `k`) and
    /// node `k` goes back onto the tower.
    pub(super) fn back_onto_tower(&mut self, k: usize, l: f64, top: Top) {
        match top {
            Top::Exit => self.place_at_exit(k + 1, k),
            Top::Moving => {
                let p = self.at(k);
                let (theta, up) = self.new_top(k + 1, k + 1);
                let q = [p[0] - l * up[0], p[1] - l * up[1]];
                self.place_on_line(k + 1, q, k, theta);
            }
        }
    }

    /// Node `k`, the top at the exit, leaves the tower: put on the top element's cubic (Hermite,
    /// from the exit's position and angle to node `k + 1`'s) at its own material distance
    /// `ξ·L_top = −d_top/(1 + ε)` below the exit, with the velocity and acceleration of node
    /// `k + 1` (the material's: the exit's own are the vessel's, without the payout).
    fn release(&mut self, k: usize) {
        let below = -self.d_top / (1.0 + self.eps);
        let xi = below / (self.full.elements[k].l0 + below);
        let b = &self.base.base;
        let s = &mut self.store;
        let at = |g: usize| std::array::from_fn::<f64, 3, _>(|c| b[3 * g + c] + s.u[3 * g + c]);
        let (p0, p1) = (at(k), at(k + 1));
        let c = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
        let (t0, t1) = ([p0[2].cos(), p0[2].sin()], [p1[2].cos(), p1[2].sin()]);
        let (x2, x3) = (xi * xi, xi * xi * xi);
        let h = [
            2.0 * x3 - 3.0 * x2 + 1.0,
            x3 - 2.0 * x2 + xi,
            3.0 * x2 - 2.0 * x3,
            x3 - x2,
        ];
        let dh = [
            6.0 * (x2 - xi),
            3.0 * x2 - 4.0 * xi + 1.0,
            6.0 * (xi - x2),
            3.0 * x2 - 2.0 * xi,
        ];
        let cubic = |h: &[f64; 4], i: usize| {
            h[0] * p0[i] + h[1] * c * t0[i] + h[2] * p1[i] + h[3] * c * t1[i]
        };
        let r = [cubic(&h, 0), cubic(&h, 1)];
        let turn = cubic(&dh, 1).atan2(cubic(&dh, 0)) - p0[2];
        let theta = p0[2] + (turn + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        for (i, q) in [r[0], r[1], theta].into_iter().enumerate() {
            s.u[3 * k + i] = q - b[3 * k + i];
            s.v[3 * k + i] = s.v[3 * k + 3 + i];
            s.a[3 * k + i] = s.a[3 * k + 3 + i];
        }
        let st = s.stride;
        if st > 0 {
            s.friction[st * k] = r[0];
            if st == 2 {
                s.friction[st * k + 1] = r[1];
            }
        }
    }

    /// Makes node `g` the exit: where node `like` (the exit until now) is, at its angle, moving
    /// as it does.
    fn place_at_exit(&mut self, g: usize, like: usize) {
        let b = &self.base.base;
        let s = &mut self.store;
        for c in 0..3 {
            s.u[3 * g + c] = b[3 * like + c] + s.u[3 * like + c] - b[3 * g + c];
            s.v[3 * g + c] = s.v[3 * like + c];
            s.a[3 * g + c] = s.a[3 * like + c];
        }
        let st = s.stride;
        for c in 0..st {
            s.friction[st * g + c] = s.friction[st * like + c];
        }
    }

    /// Puts node `g` at `p` on the tower's (or the wire's) line, at the angle `theta` (the tower's,
    /// or the wire's line), moving with node `like`, not turning.
    fn place_on_line(&mut self, g: usize, p: [f64; 2], like: usize, theta: f64) {
        let b = &self.base.base;
        let s = &mut self.store;
        s.u[3 * g] = p[0] - b[3 * g];
        s.u[3 * g + 1] = p[1] - b[3 * g + 1];
        s.u[3 * g + 2] = theta - b[3 * g + 2];
        for c in 0..2 {
            s.v[3 * g + c] = s.v[3 * like + c];
            s.a[3 * g + c] = s.a[3 * like + c];
        }
        s.v[3 * g + 2] = 0.0;
        s.a[3 * g + 2] = 0.0;
        let st = s.stride;
        if st > 0 {
            s.friction[st * g] = p[0];
            if st == 2 {
                s.friction[st * g + 1] = p[1];
            }
        }
    }
}

/// `up` turned with a vessel pitched by `beta` (counter-clockwise by `−β`); `up` itself, to the
/// bit, at `β = 0` (no vessel).
fn turned(up: [f64; 2], beta: f64) -> [f64; 2] {
    if beta == 0.0 {
        return up;
    }
    let (sn, cs) = (-beta).sin_cos();
    [cs * up[0] - sn * up[1], sn * up[0] + cs * up[1]]
}
