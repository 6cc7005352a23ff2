//! Short-term extremes as an observer of a run (`[extremes]`): every step from its start, the value
//! of each chosen channel is kept (8 bytes a step and channel: 1.7 MB for a 3-hour storm at
//! 0.05 s), and at the end each record is analysed ([`crate::checks::extremes::analyse`]: the sample's
//! extreme, the Rayleigh, Weibull-of-peaks and Gumbel-of-block-maxima estimates of the target
//! duration's most probable extreme and a quantile).
//!
//! Channels: `top_tension` (the top's effective tension, its greatest), `least_tension` (the least
//! effective tension anywhere on the line, its least), `sag_moment` (the most negative moment
//! anywhere, its least), `utilisation` (the largest design-check utilisation anywhere, its greatest;
//! needs `[design_check]`), `gauge:NAME` (the moment at a gauge, its least; `gauge:NAME:max` for
//! its greatest).

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::checks::design::Evaluator;
use crate::checks::extremes::{analyse, Extremes, ExtremesSpec, Source};
use crate::error::AppError;
use crate::run::observe::{at_arc, Control, Observer, RunContext, StepView, Stop};

/// The extremes observer.
#[derive(Debug, Clone)]
pub struct ExtremesObserver {
    /// The specification.
    pub spec: ExtremesSpec,
    /// Each channel's record, one value a step from the start.
    pub records: Vec<Vec<f64>>,
    /// The time step, s.
    pub dt: f64,
    /// The analyses (after the run).
    pub results: Vec<Extremes>,
    evaluator: Option<Evaluator>,
    gauge_arcs: Vec<f64>,
    scratch: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
struct Saved {
    records: Vec<Vec<f64>>,
}

impl ExtremesObserver {
    /// The observer for a run of time step `dt`.
    pub fn new(spec: ExtremesSpec, dt: f64) -> Self {
        let n = spec.channels.len();
        Self {
            spec,
            records: vec![Vec::new(); n],
            dt,
            results: Vec::new(),
            evaluator: None,
            gauge_arcs: Vec::new(),
            scratch: Vec::new(),
        }
    }

    fn take(&mut self, s: &StepView<'_>, arc: &[f64]) {
        if s.t < self.spec.start - 1e-9 {
            return;
        }
        let r = s.results;
        for (c, rec) in self.spec.channels.iter().zip(&mut self.records) {
            let v = match c.source {
                Source::TopTension => r.tension[0],
                Source::LeastTension => r.tension.iter().copied().fold(f64::INFINITY, f64::min),
                Source::SagMoment => r.moment.iter().copied().fold(f64::INFINITY, f64::min),
                Source::Utilisation => match &self.evaluator {
                    Some(ev) => {
                        self.scratch.resize(r.tension.len(), 0.0);
                        ev.along(r, &mut self.scratch);
                        self.scratch.iter().copied().fold(0.0, f64::max)
                    }
                    None => f64::NAN,
                },
                Source::GaugeMoment(g) => at_arc(arc, &r.moment, self.gauge_arcs[g]),
            };
            rec.push(v);
        }
    }
}

impl Observer for ExtremesObserver {
    fn name(&self) -> &'static str {
        "extremes"
    }
    fn start(
        &mut self,
        ctx: &RunContext<'_>,
        first: &StepView<'_>,
        restarted: bool,
    ) -> Result<(), AppError> {
        self.evaluator = crate::run::observers::design::evaluator_of(ctx);
        self.gauge_arcs = ctx.spec.gauges.iter().map(|g| g.arc).collect();
        if !restarted {
            self.take(first, &ctx.model.line.arc);
        }
        Ok(())
    }
    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        self.take(s, &ctx.model.line.arc);
        Ok(Control::Continue)
    }
    fn finish(&mut self, _: &RunContext<'_>, _: Option<&Stop>) -> Result<(), AppError> {
        self.results = self
            .spec
            .channels
            .iter()
            .zip(&self.records)
            .filter_map(|(c, x)| analyse(&c.name, c.tail, x, self.dt, &self.spec.settings))
            .collect();
        Ok(())
    }
    fn save(&mut self) -> Result<Value, AppError> {
        Ok(serde_json::to_value(Saved {
            records: self.records.clone(),
        })
        .unwrap_or(Value::Null))
    }
    fn restore(&mut self, v: &Value) -> Result<(), String> {
        let s: Saved = serde_json::from_value(v.clone()).map_err(|e| format!("extremes: {e}"))?;
        if s.records.len() != self.records.len() {
            return Err("extremes: the saved records do not fit the scene's channels".into());
        }
        self.records = s.records;
        Ok(())
    }
}
