//! The built-in outputs of a run, registered rather than named: each is an [`Observer`] of converged
//! steps with its own checkpointable state under its name, built for a run from the scene when the
//! scene asks for it ([`BUILTINS`]). The run hands every step to every registered output and then to
//! the caller's own observers (the HDF5 recorder, progress, checkpoints, a signal watcher), saves
//! and restores them all by name in checkpoints, and gives them back in the result
//! ([`Outputs::get`]).
//!
//! **A new built-in output** is one file (an `Observer` that keeps its own state, with `save` and
//! `restore` for checkpoints) and one [`Registration`] in [`BUILTINS`]; restarts keep working for it
//! with nothing else to change, and `DynamicRun::output::<T>()` returns it after the run.

use std::any::Any;

use catena_fe::dynamics::DynamicModel;

use crate::run::observe::{Envelopes, Gauges, Observer, TopHistory};
use crate::run::observers::design::DesignCheck;
use crate::run::observers::extremes::ExtremesObserver;
use crate::run::observers::fatigue::Fatigue;
use crate::scene::riser::DynamicSpec;

/// A built-in output: an [`Observer`] that can be handed back by type after the run (and sent to
/// another thread with it, or shared by the threads that write a run's files and plots).
pub trait Output: Observer + Any + Send + Sync {
    /// Itself, to be downcast.
    fn as_any(&self) -> &dyn Any;
    /// Itself, to be taken out by type.
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

impl<T: Observer + Any + Send + Sync> Output for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}

/// What a registration builds an output from: the dynamic specification and Model of the run.
#[derive(Clone, Copy)]
pub struct Setup<'a> {
    /// The dynamic specification (gauges placed, fatigue, section).
    pub spec: &'a DynamicSpec,
    /// The dynamic Model.
    pub model: &'a DynamicModel,
    /// The threads the run may keep busy (at least 1: [`crate::run::RunOptions::threads`]),
    /// besides the line's second stepping thread when `paired`.
    pub threads: usize,
    /// Whether two threads may step the line ([`catena_fe::dynamics::Drive::start`]): their waits
    /// for each other can take the observers' chores ([`Observer::chores`]).
    pub paired: bool,
}

/// One built-in output: its name (the key of its state in checkpoints) and how it is built for a
/// run (`None` when the scene does not ask for it: an output absent from the scene costs nothing).
pub struct Registration {
    /// The name; `build`'s observer reports the same.
    pub name: &'static str,
    /// Builds it for a run.
    pub build: fn(&Setup<'_>) -> Option<Box<dyn Output>>,
}

/// The built-in outputs, in the order they see each step.
pub const BUILTINS: &[Registration] = &[
    Registration {
        name: "envelopes",
        build: |s| {
            let ei: Vec<f64> = s.model.line.elements.iter().map(|e| e.section.ei).collect();
            let e = Envelopes::with_sections(&ei, s.spec.section, s.spec.node_sections.clone());
            // Beside a pair, taken in its waits.
            Some(Box::new(if s.paired { e.lend_to_pair() } else { e }))
        },
    },
    Registration {
        name: "gauges",
        build: |s| Some(Box::new(Gauges::new(&s.spec.gauges))),
    },
    Registration {
        name: "top",
        build: |_| Some(Box::new(TopHistory::default())),
    },
    Registration {
        name: "fatigue",
        build: |s| {
            let n = s.model.line.nodes();
            let f = s.spec.fatigue.clone()?;
            // A core to spare: a counting thread; else, beside a pair, the pair's waits.
            Some(Box::new(if s.paired && s.threads == 1 {
                Fatigue::lent(f, n)
            } else {
                Fatigue::with_thread(f, n, s.threads > 1)
            }))
        },
    },
    Registration {
        name: "design_check",
        build: |s| {
            let c = s.spec.design_check?;
            let line = &s.model.line;
            let elements: Vec<(f64, f64)> =
                line.elements.iter().map(|e| (e.l0, e.section.ei)).collect();
            Some(Box::new(DesignCheck::new(c, &elements, &line.arc)))
        },
    },
    Registration {
        name: "extremes",
        build: |s| {
            let e = s.spec.extremes.clone()?;
            Some(Box::new(ExtremesObserver::new(e, s.spec.dt)))
        },
    },
];

/// The registered outputs of one run.
#[derive(Default)]
pub struct Outputs {
    list: Vec<Box<dyn Output>>,
}

impl std::fmt::Debug for Outputs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.list.iter().map(|o| o.name()))
            .finish()
    }
}

impl Outputs {
    /// Every registered output the scene asks for.
    pub fn build(setup: &Setup<'_>) -> Self {
        Self {
            list: BUILTINS.iter().filter_map(|r| (r.build)(setup)).collect(),
        }
    }

    /// Each output, as an observer.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = &mut dyn Observer> {
        self.list.iter_mut().map(|o| &mut **o as &mut dyn Observer)
    }

    /// The output of type `T`, if the run has one.
    pub fn get<T: Any>(&self) -> Option<&T> {
        self.list
            .iter()
            .find_map(|o| o.as_any().downcast_ref::<T>())
    }

    /// Takes the output of type `T` out, if the run has one.
    pub fn take<T: Any>(&mut self) -> Option<T> {
        let i = self.list.iter().position(|o| o.as_any().is::<T>())?;
        self.list
            .remove(i)
            .into_any()
            .downcast::<T>()
            .ok()
            .map(|b| *b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every registration's observer reports the registration's name, and the names are distinct
    /// (they key the checkpoints).
    #[test]
    fn registrations_are_named_as_their_observers() {
        let names: Vec<&str> = BUILTINS.iter().map(|r| r.name).collect();
        let mut sorted = names.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), names.len(), "{names:?}");
        let mut e = Envelopes::new(&[1.0], None);
        let mut g = Gauges::new(&[]);
        let mut t = TopHistory::default();
        for (o, want) in [
            (&mut e as &mut dyn Observer, "envelopes"),
            (&mut g, "gauges"),
            (&mut t, "top"),
        ] {
            assert_eq!(o.name(), want);
            assert!(names.contains(&want));
        }
        assert!(names.contains(&"fatigue"));
    }
}
