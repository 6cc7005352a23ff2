//! The lay's start: the scene's statics set up for the tower (and a warning when the tower holds a
//! moment), and the whole pipe's mesh.

use catena_fe::model::{Element, FlexJoint, LineModel};

use crate::scene::lay::{LaySpec, Tower};
use crate::scene::riser::RiserScene;

/// The scene's statics set up for the tower: at a given tower angle, a hinged tower's spring or a
/// clamped tower (a spring 100 times the top element's own bending stiffness `EI/L`), as a
/// flexjoint at the top whose neutral angle is the tower's; at the pipe's own departure angle (no
/// angle given), a pinned top.
pub fn statics_scene(mut scene: RiserScene) -> RiserScene {
    let Some(lay) = scene.lay.clone() else {
        return scene;
    };
    let top = scene.model.elements[0];
    // At the departure angle (no `tower_angle_deg`) the tower holds no moment, hinged or clamped:
    // the statics' top is pinned. (A stiff spring whose neutral angle the statics took from their
    // own first solve would hold the top near the catenary seed's angle instead.)
    let stiffness = match (lay.tower, lay.tower_angle) {
        (_, None) => None,
        (Tower::Hinged(k), Some(_)) => Some(k),
        (Tower::Clamped, Some(_)) => Some(100.0 * top.section.ei / top.l0),
    };
    if let Some(stiffness) = stiffness {
        scene.model.flexjoint = Some(FlexJoint {
            node: 0,
            stiffness,
            neutral: 0.0,
        });
        scene.flexjoint_neutral_from_vertical = lay.tower_angle;
    }
    scene
}

/// Whether the tower holds a moment at the top (a tower angle off the pipe's departure angle, or
/// a hinge's spring turned off it): more than 5 % of the sag bend's in the statics. Such a lay
/// clamps the pipe at the exit itself (`exit.rs`).
pub(super) fn tower_holds_moment(st: &crate::run::statics::StaticRun) -> bool {
    let m = &st.results.moment;
    let top = m.first().copied().unwrap_or(0.0);
    let sag = m.iter().copied().fold(0.0f64, |a, x| a.max(x.abs()));
    top.abs() > 0.05 * sag
}

/// The whole pipe's mesh: the scene's line with the pipe on the vessel above it (elements of
/// `[lay] element_length`, the line's top element's otherwise, dividing the pipe exactly) and, for a
/// lay-down, the wire above that; how many nodes are above the line, and the pipe's last end's node.
pub(super) fn material_mesh(line: &LineModel, spec: &LaySpec) -> (LineModel, usize, usize) {
    let top = line.elements[0];
    let h = spec.element_length.unwrap_or(top.l0);
    let extra = spec.pipe_length - line.length();
    let n = (extra / h).ceil().max(1.0) as usize;
    let pipe = Element {
        l0: extra / n as f64,
        ..top
    };
    let mut above = Vec::new();
    if let Some(w) = spec.lay_down {
        let s = w.segment;
        let nw = (s.length / s.element_length).ceil().max(1.0) as usize;
        let wire = Element {
            l0: s.length / nw as f64,
            section: s.section,
            weight: s.weight,
            mass: s.mass,
            od: s.od,
            hydro_od: s.hydro_od,
            contact_od: s.contact_od,
            coefficients: s.coefficients,
            kind: top.kind,
            wall: None,
        };
        above.extend(std::iter::repeat_n(wire, nw));
    }
    let pipe_end = above.len();
    above.extend(std::iter::repeat_n(pipe, n));
    (line.with_elements_above(&above), above.len(), pipe_end)
}

/// A lay-down's station height (`[lay.wire] station_height`), m: the scene's, else a quarter of the
/// pipe's bending length `λ = (EI/W')^(1/3)` at its last end (10.2 m for the 12-inch pipe; held
/// from higher up, the end swings ahead of the vessel and the standing vessel presses the
/// touchdown zone, `validation/lay.md` §7); NaN without a lay-down.
pub(super) fn station_height(full: &LineModel, pipe_end: usize, spec: &LaySpec) -> f64 {
    let Some(w) = spec.lay_down else {
        return f64::NAN;
    };
    w.station_height.unwrap_or_else(|| {
        let e = &full.elements[pipe_end];
        0.25 * (e.section.ei / e.weight).cbrt()
    })
}
