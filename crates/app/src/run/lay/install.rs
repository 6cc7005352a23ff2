//! The installation check of a lay (`[design_check] code = "dnv-st-f101"`): DNV-ST-F101's
//! load-controlled combined loading at every node and step of the free span (from the tower's exit
//! to the touchdown), and the sag bend's strain against the displacement-controlled limit
//! (`crate::checks::design`, whose module docs give the criteria and where F101 differs from F201).
//!
//! **Functional and environmental.** A point of the pipe passes through the whole span, so its
//! functional load effects are those of the calm steady lay at the same place in the span: the
//! statics of the lay's start (the steady lay in calm water is that statics, `validation/lay.md`)
//! at the same unstretched arc length from the exit, interpolated; the environmental load effects
//! are the difference. The design strain is the outer fibre's `|M|·D/(2EI) + T/EA`.

use crate::checks::design::{DesignSpec, Resistance};
use crate::checks::fatigue::stress::PipeSection;
use catena_fe::assembly::LineResults;

/// The check and what it found.
#[derive(Debug, Clone)]
pub struct InstallationCheck {
    /// The check's parameters.
    pub spec: DesignSpec,
    section: PipeSection,
    resistance: Resistance,
    /// The statics: arc length from the exit, moment, effective tension.
    functional: (Vec<f64>, Vec<f64>, Vec<f64>),
    /// `EI` and `EA` of the pipe.
    stiffness: (f64, f64),
    /// Each material node's largest LCC utilisation in the free span (NaN: never in it).
    pub lcc_of_node: Vec<f64>,
    /// The largest LCC utilisation: value, time, KP, arc length from the exit.
    pub lcc_max: (f64, f64, f64, f64),
    /// The largest DCC utilisation: value, design strain, time, KP.
    pub dcc_max: (f64, f64, f64, f64),
    /// The design strain resistance `ε_c/γ_ε` at the sag bend's node of the largest DCC.
    pub strain_resistance: f64,
}

impl InstallationCheck {
    /// The check of a pipe of `section` (corrosion off its wall), its `(EI, EA)`, with the statics'
    /// arc lengths, moments and tensions; `nodes` material nodes.
    pub fn new(
        spec: DesignSpec,
        section: PipeSection,
        stiffness: (f64, f64),
        statics: (&[f64], &[f64], &[f64]),
        nodes: usize,
    ) -> Self {
        let section = PipeSection {
            wall: section.wall - spec.corrosion_allowance,
            internal_pressure: spec.internal_pressure,
            ..section
        };
        Self {
            resistance: Resistance::new(&spec, section.od, section.wall),
            spec,
            section,
            functional: (statics.0.to_vec(), statics.1.to_vec(), statics.2.to_vec()),
            stiffness,
            lcc_of_node: vec![f64::NAN; nodes],
            lcc_max: (0.0, f64::NAN, f64::NAN, f64::NAN),
            dcc_max: (0.0, f64::NAN, f64::NAN, f64::NAN),
            strain_resistance: f64::NAN,
        }
    }

    /// The statics' moment and tension at `s` m from the exit (linear between nodes, the ends'
    /// beyond them).
    fn functional_at(&self, s: f64) -> (f64, f64) {
        let (arc, m, t) = &self.functional;
        let k = arc.partition_point(|&a| a <= s).clamp(1, arc.len() - 1);
        let f = ((s - arc[k - 1]) / (arc[k] - arc[k - 1])).clamp(0.0, 1.0);
        (
            m[k - 1] + f * (m[k] - m[k - 1]),
            t[k - 1] + f * (t[k] - t[k - 1]),
        )
    }

    /// Checks the free span of a converged step: window nodes `1..span` (`span` the touchdown's
    /// node), material node `first + i` at arc length `s_i` from the exit, at time `t`, with the
    /// KP of each node from `kp`.
    pub fn observe(
        &mut self,
        (t, first, span): (f64, usize, usize),
        res: &LineResults,
        arc_from_exit: impl Fn(usize) -> f64,
        kp: &[f64],
    ) {
        let sec = &self.section;
        let (ei, ea) = self.stiffness;
        let (gf, ge) = (self.spec.gamma_f * self.spec.gamma_c, self.spec.gamma_e);
        for i in 1..span.min(res.moment.len() - 1) {
            let s = arc_from_exit(i);
            if s < 0.0 {
                continue;
            }
            let head = (sec.water_depth - res.z[i]).max(0.0);
            let p_ld = sec.internal_pressure + sec.contents_density * sec.gravity * head;
            let p_e = sec.water_density * sec.gravity * head;
            let (mf, tf) = self.functional_at(s);
            let (m, te) = (res.moment[i], res.tension[i]);
            let md = gf * mf + ge * (m - mf);
            let ted = gf * tf + ge * (te - tf);
            let u = self.resistance.f101(p_ld, p_e, md, ted).value;
            let g = first + i;
            // NaN (never in the span before) or smaller: this one.
            if self.lcc_of_node[g].is_nan() || self.lcc_of_node[g] < u {
                self.lcc_of_node[g] = u;
            }
            if u > self.lcc_max.0 {
                self.lcc_max = (u, t, kp[g], s);
            }
            let strain = m.abs() * 0.5 * sec.od / ei + te / ea;
            let d = self.resistance.f101_strain(strain, p_ld, p_e);
            if d > self.dcc_max.0 {
                self.dcc_max = (d, strain, t, kp[g]);
                self.strain_resistance = self.resistance.f101_strain_resistance(p_ld, p_e);
            }
        }
    }
}
