//! Observers that talk to the user: a progress bar, and a watcher that ends the run at the next
//! step after SIGINT or SIGTERM.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use catena::run::observe::{Control, Observer, RunContext, StepView, Stop};
use catena::AppError;

/// A progress bar on the terminal (steps, simulated time, estimated time left).
pub struct ProgressBar {
    bar: Option<indicatif::ProgressBar>,
}

impl ProgressBar {
    /// A bar (drawn only on a terminal).
    pub fn new() -> Self {
        Self { bar: None }
    }
}

impl Default for ProgressBar {
    fn default() -> Self {
        Self::new()
    }
}

impl Observer for ProgressBar {
    fn name(&self) -> &'static str {
        "progress"
    }
    fn start(
        &mut self,
        ctx: &RunContext<'_>,
        first: &StepView<'_>,
        _: bool,
    ) -> Result<(), AppError> {
        let n = (ctx.spec.duration / ctx.spec.dt).round() as u64;
        let b = indicatif::ProgressBar::new(n);
        b.set_style(
            indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} steps, t = {msg} s, eta {eta}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b.set_position(first.step);
        self.bar = Some(b);
        Ok(())
    }
    fn step(&mut self, _: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        if let Some(b) = &self.bar {
            if s.step % 20 == 0 {
                b.set_position(s.step);
                b.set_message(format!("{:.2}", s.t));
            }
        }
        Ok(Control::Continue)
    }
    fn finish(&mut self, _: &RunContext<'_>, _: Option<&Stop>) -> Result<(), AppError> {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
        Ok(())
    }
}

/// Ends the run at the next converged step once `flag` is set (by the SIGINT/SIGTERM handler).
pub struct SignalStop {
    flag: Arc<AtomicBool>,
}

impl SignalStop {
    /// A watcher of `flag`.
    pub fn new(flag: Arc<AtomicBool>) -> Self {
        Self { flag }
    }
}

impl Observer for SignalStop {
    fn name(&self) -> &'static str {
        "signals"
    }
    fn step(&mut self, _: &RunContext<'_>, _: &StepView<'_>) -> Result<Control, AppError> {
        if self.flag.load(Ordering::SeqCst) {
            Ok(Control::Stop("SIGINT or SIGTERM received".into()))
        } else {
            Ok(Control::Continue)
        }
    }
}
