//! What a lay gives back: the run ([`LayRun`]), its lay-down ([`LayDown`]) and what the caller sees
//! after each step ([`LayProgress`]).

use catena_fe::model::LineModel;

use super::laid::{stats, LaidNodes, LayRecords, LaySummary};
use crate::run::observe::Stop;
use crate::run::statics::StaticRun;
use crate::scene::as_laid::{LaidPoint, LaidSeabed};
use crate::scene::lay::LaySpec;
use crate::scene::riser::DynamicSpec;
use catena_fe::statics::static_embedment_on;
use catena_seabed::law::{Seabed, SeabedHistory};

/// A finished (or stopped) lay.
#[derive(Debug)]
pub struct LayRun {
    /// The statics of the start.
    pub statics: StaticRun,
    /// The lay's table.
    pub spec: LaySpec,
    /// The dynamic table (time step, output interval, sea).
    pub dynamic: DynamicSpec,
    /// The whole pipe's mesh.
    pub full: LineModel,
    /// Nodes on the vessel at the start.
    pub on_vessel: usize,
    /// The tower's angle from the vertical, rad.
    pub tower_angle: f64,
    /// The tensioner's target, N (tension control).
    pub target_tension: Option<f64>,
    /// The records.
    pub records: LayRecords,
    /// Each material node.
    pub nodes: LaidNodes,
    /// The lay's numbers.
    pub summary: LaySummary,
    /// Every node's position `(x, z)` at the end (nodes still on the vessel: along the tower).
    pub positions: Vec<[f64; 2]>,
    /// The window at the end `(first, last)`.
    pub window: (usize, usize),
    /// Converged steps.
    pub steps: u64,
    /// Newton iterations.
    pub iterations: usize,
    /// Step cuts.
    pub cuts: u32,
    /// Times the window moved.
    pub windows: u64,
    /// Times a node was taken back onto the tower (paid in).
    pub taken_back: u64,
    /// The most threads that stepped a window: 2 where a [`catena_fe::dynamics::Pair`] did
    /// ([`super::LayOptions::threads`]; a window too short to cut steps on one), else 1.
    pub stepping_threads: usize,
    /// The steps two threads took ([`catena_fe::dynamics::Drive`]).
    pub steps_on_two: u64,
    /// Wall time of the dynamics, s.
    pub wall_seconds: f64,
    /// Why the lay ended early, if it did.
    pub stop: Option<Stop>,
    /// The lay-down, if the scene has one.
    pub lay_down: Option<LayDown>,
    /// The installation check, if the scene has a `[design_check]`.
    pub installation: Option<super::install::InstallationCheck>,
    /// What the user should know about this lay (a tower holding a moment at the top).
    pub warnings: Vec<String>,
    /// The frames for the animation ([`super::frames`]).
    pub frames: super::frames::LayFrames,
    /// Every node's seabed history at the end.
    pub histories: Vec<SeabedHistory>,
    /// Every node's friction anchors at the end, and how many a node has (0 without friction).
    pub friction: (Vec<f64>, usize),
}

/// What a lay-down did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayDown {
    /// When the pipe's end left the tower, s.
    pub left_tower: f64,
    /// The touchdown's KP then, m: the steady part ends there.
    pub kp_touchdown: f64,
    /// When the pipe's end came to rest on the seabed (90 % of W'), s; `None`: it did not before
    /// the run's end.
    pub rested: Option<f64>,
    /// The pipe's end's as-laid embedment, m.
    pub end_embedment: f64,
}

impl LayRun {
    /// The seabed the lay left, for a following scene (`[as_laid]`): every node of the pipe at
    /// rest, by increasing x.
    pub fn laid_seabed(&self) -> LaidSeabed {
        let (friction, stride) = (&self.friction.0, self.friction.1);
        let n = &self.nodes;
        let mut points: Vec<LaidPoint> = (0..self.full.nodes())
            .filter(|&g| n.as_laid[g].is_finite())
            .map(|g| LaidPoint {
                kp: n.kp[g],
                x: self.positions[g][0],
                z: self.positions[g][1],
                as_laid: n.as_laid[g],
                history: self.histories[g],
                friction: friction[stride * g..stride * (g + 1)].to_vec(),
            })
            .collect();
        points.sort_by(|a, b| a.x.total_cmp(&b.x));
        points.dedup_by(|b, a| b.x <= a.x);
        LaidSeabed {
            format: crate::scene::as_laid::FORMAT.into(),
            catena_version: env!("CARGO_PKG_VERSION").into(),
            scene_file: self.statics.scene.file.clone(),
            contact_od: self.full.elements[n.pipe_end].contact_od,
            points,
        }
    }

    /// x of the tower's exit at the start, m.
    pub fn positions_exit_x(&self) -> f64 {
        self.statics.placement.base[0] + self.statics.u[0]
    }
}

/// What the caller sees after each converged step (progress, interruption).
#[derive(Debug, Clone, Copy)]
pub struct LayProgress {
    /// Time, s.
    pub t: f64,
    /// The run's duration, s.
    pub duration: f64,
    /// Pipe paid out, m.
    pub paid_out: f64,
    /// Nodes in the solve.
    pub window_nodes: usize,
}

impl super::Lay {
    /// The lay's numbers (`summary.json` `lay`).
    pub(super) fn summary(&self, st: &StaticRun) -> LaySummary {
        let top = self.full.elements[self.pipe_end];
        let w = top.weight;
        let d = top.contact_od;
        let law: Option<&Seabed> = self.full.seabed_law(self.on_vessel);
        let z = |p: f64| {
            law.and_then(|s| static_embedment_on(s, d, p))
                .unwrap_or(f64::NAN)
        };
        // The steady part: laid during the lay, before a lay-down's touchdown.
        let kp_down = self.left_tower.map_or(f64::INFINITY, |(_, kp)| kp);
        let steady = |g: &usize| {
            self.nodes.landed[*g]
                && self.nodes.as_laid[*g].is_finite()
                && self.nodes.kp[*g] <= kp_down
        };
        let n = self.full.nodes();
        let (mean, lo, hi, count) = stats((0..n).filter(steady).map(|g| self.nodes.as_laid[g]));
        let lay_factor = (0..n)
            .filter(steady)
            .map(|g| self.nodes.max_contact[g])
            .fold(f64::NAN, f64::max)
            / w;
        let static_max = st.results.seabed_force.iter().copied().fold(0.0, f64::max);
        let z_w = z(w);
        let td = st.results.seabed_force.iter().position(|&p| p > 0.0);
        let t0 = td.map_or(f64::NAN, |i| st.results.tension[i]);
        let (closed_form, lambda) = touchdown_lay_factor(top.section.ei, w, t0, z);
        let r = &self.records;
        let (_, t_lo, t_hi, _) = stats(r.top_tension.iter().copied());
        let (_, m_lo, _, _) = stats(r.sag_moment.iter().copied());
        let sag_strain = -m_lo * 0.5 * top.od / top.section.ei + t_hi / top.section.ea;
        let (episodes, ..) = stats(
            (0..n)
                .filter(steady)
                .map(|g| f64::from(self.nodes.episodes[g])),
        );
        LaySummary {
            paid_out: self.paid,
            vessel_travel: self.vessel_x,
            steady_nodes: count,
            as_laid_mean: mean,
            as_laid_min: lo,
            as_laid_max: hi,
            submerged_weight: w,
            self_weight_embedment: z_w,
            static_embedment: z(static_max),
            static_lay_factor: static_max / w,
            lay_factor,
            lay_factor_closed_form: closed_form,
            lambda,
            dynamic_embedment_factor: mean / z_w,
            top_tension_min: t_lo,
            top_tension_max: t_hi,
            sag_moment_max: -m_lo,
            sag_strain_max: sag_strain,
            episodes_mean: episodes,
        }
    }
}

/// The touchdown lay factor's closed form, `k_lay = 0.6 + 0.4 λ^0.25`, `λ = EI·k/T0²` (Randolph &
/// White 2008, OTC 19128; DNV-RP-F114 §4.2.5.2, Eq. 4.13–4.14), with `k` the seabed's secant
/// stiffness at the embedment it causes, `k = k_lay·W'/z(k_lay·W')` (`z` the backbone's
/// penetration at a force per unit length): an implicit equation, solved by bisection within the
/// form's range 1 ≤ k_lay ≤ 3 (clipped to its ends). Returns `(k_lay, λ)`; NaN where `z` is.
pub(crate) fn touchdown_lay_factor(ei: f64, w: f64, t0: f64, z: impl Fn(f64) -> f64) -> (f64, f64) {
    let lambda = |f: f64| ei * (f * w / z(f * w)) / (t0 * t0);
    let g = |f: f64| 0.6 + 0.4 * lambda(f).powf(0.25) - f;
    let (mut lo, mut hi) = (1.0, 3.0);
    let (g_lo, g_hi) = (g(lo), g(hi));
    let f = if !(g_lo.is_finite() && g_hi.is_finite()) {
        f64::NAN
    } else if g_lo <= 0.0 {
        lo
    } else if g_hi >= 0.0 {
        hi
    } else {
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    (f, lambda(f))
}

#[cfg(test)]
mod tests {
    use super::touchdown_lay_factor;

    /// On a linear seabed (`z = V/k`) the secant is `k` at any force: the explicit form. On a
    /// softening one (`z = (V/c)²`) the solution satisfies the implicit equation with the secant
    /// at its own force, to 1e-12; the form's range clips both ends.
    #[test]
    fn the_lay_factor_s_closed_form_with_the_secant_at_its_own_embedment() {
        let (ei, w, t0) = (46.9e6, 660.0, 110e3);
        let k = 2.0e5;
        let (f, lambda) = touchdown_lay_factor(ei, w, t0, |v| v / k);
        let explicit = ei * k / (t0 * t0);
        assert!((lambda - explicit).abs() < 1e-12 * explicit);
        assert!((f - (0.6 + 0.4 * explicit.powf(0.25))).abs() < 1e-12);
        let c = 4000.0;
        let z = |v: f64| (v / c) * (v / c);
        let (f, lambda) = touchdown_lay_factor(ei, w, t0, z);
        let secant = f * w / z(f * w);
        assert!((lambda - ei * secant / (t0 * t0)).abs() < 1e-9 * lambda);
        assert!((f - (0.6 + 0.4 * lambda.powf(0.25))).abs() < 1e-12, "{f}");
        assert_eq!(touchdown_lay_factor(ei, w, t0, |v| v / 10.0).0, 1.0);
        assert_eq!(touchdown_lay_factor(ei, w, t0, |v| v / 1e12).0, 3.0);
    }
}
