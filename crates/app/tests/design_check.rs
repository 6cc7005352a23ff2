//! The strength check (`[design_check]`) through a run: its load-effect split against a run whose
//! dynamic increment is zero, and its utilisation along the line against the same criterion
//! evaluated by hand from every step's recorded moment and tension.

use std::path::{Path, PathBuf};

use catena::design::{self, Code, Wall};
use catena::design_observer::DesignCheck;
use catena::error::AppError;
use catena::observe::{Control, Observer, RunContext, StepView};
use catena::run::{self, RunOptions};
use catena::scene::riser::RiserScene;
use catena::scene::NoFiles;
use catena::statics;

mod common;
use common::Edit;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The heave benchmark's riser with its wall and contents (the paper's pipe: 25.4 mm, 726 kg/m³)
/// and a check.
fn heave_text(check: &str) -> String {
    std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml"))
        .expect("test data")
        .edit(
            "mass = 145.06 ",
            "wall = 0.0254\ncontents_density = 726.0\nmass = 145.06 ",
        )
        .edit("duration = 100.0", "duration = 30.0")
        .edit("envelope_start = 50.0", "envelope_start = 10.0")
        + check
}

const DNV: &str = "\n[design_check]\ncode = \"dnv-st-f201\"\nsmys = 448e6\nsmts = 531e6\ninternal_pressure = 15e6\nsafety_class = \"normal\"\nstart = 0.0\n";
const API: &str = "\n[design_check]\ncode = \"api-std-2rd\"\nsmys = 448e6\nsmts = 531e6\ninternal_pressure = 15e6\ndesign_factor = 0.8\ncorrosion_allowance = 0.002\nstart = 0.0\n";

fn run_text(text: &str) -> catena::run::DynamicRun {
    let scene = RiserScene::parse("check.toml", text, &NoFiles).expect("scene");
    let st = statics::solve(scene).expect("statics");
    run::run(st, &mut [], RunOptions::default()).expect("run")
}

/// The pressures at a node by hand: external `ρ_w g (d − z)`, internal `p_d + ρ_c g (d − z)`.
fn wall_at(z: f64, t: f64, p_d: f64) -> Wall {
    let head = 1000.0 - z;
    Wall {
        od: 0.2286,
        t,
        p_ld: p_d + 726.0 * 9.80665 * head,
        p_e: 1025.0 * 9.80665 * head,
    }
}

/// A run whose dynamic increment is zero (the heave benchmark without its motion): the
/// environmental part is nil, so every node's largest utilisation is the DNV criterion of the
/// static moment and tension times γ_F = 1.1 alone (to 1e-6). Taking the whole moment and tension
/// as environmental (γ_E = 1.3) instead would raise it by up to 40 %.
#[test]
fn a_still_run_is_checked_on_its_functional_load_effects() {
    let text = heave_text(DNV);
    let a = text.find("[motion.harmonic]").expect("test data");
    let b = text.find("[dynamic]").expect("test data");
    let still = format!("{}{}", &text[..a], &text[b..]);
    let r = run_text(&still);
    let d = r.output::<DesignCheck>().expect("a design check");
    let s = d.spec;
    let st = &r.statics.results;
    let mut worst = 0.0f64;
    for i in 0..st.moment.len() {
        let w = wall_at(st.z[i], 0.0254, 15e6);
        let by_hand = design::dnv(&s, &w, 1.1 * st.moment[i], 1.1 * st.tension[i]).value;
        worst = worst.max((d.max[i] / by_hand - 1.0).abs());
    }
    let (i, u) = d.worst().expect("checked");
    println!(
        "still run: largest utilisation {u:.5} at {:.1} m; worst difference from γ_F × static {worst:.2e}",
        d.arc[i]
    );
    assert!(worst < 1e-6, "{worst}");
    assert_eq!(s.code, Code::DnvStF201);
}

/// An observer that evaluates the criteria by hand at every step from the recorded moment and
/// effective tension (DNV: the split over the statics; API: the wall tension from the pressures on
/// the corroded wall), keeping each node's largest.
struct ByHand {
    code: Code,
    max: Vec<f64>,
}

impl Observer for ByHand {
    fn name(&self) -> &'static str {
        "by-hand"
    }
    fn step(&mut self, ctx: &RunContext<'_>, s: &StepView<'_>) -> Result<Control, AppError> {
        let spec = ctx.spec.design_check.expect("check");
        let st = &ctx.statics.results;
        let r = s.results;
        for i in 0..r.moment.len() {
            let u = match self.code {
                Code::DnvStF201 => {
                    let w = wall_at(r.z[i], 0.0254, 15e6);
                    let md = 1.1 * st.moment[i] + 1.3 * (r.moment[i] - st.moment[i]);
                    let ted = 1.1 * st.tension[i] + 1.3 * (r.tension[i] - st.tension[i]);
                    design::dnv(&spec, &w, md, ted).value
                }
                Code::DnvStF101 => unreachable!("this test checks F201 and 2RD"),
                Code::ApiStd2rd => {
                    let t = 0.0254 - 0.002;
                    let w = wall_at(r.z[i], t, 15e6);
                    let (d, di) = (0.2286, 0.2286 - 2.0 * t);
                    let area = |x: f64| std::f64::consts::PI / 4.0 * x * x;
                    let tw = r.tension[i] + w.p_ld * area(di) - w.p_e * area(d);
                    design::api(&spec, &w, tw, r.moment[i]).value
                }
            };
            self.max[i] = self.max[i].max(u);
        }
        Ok(Control::Continue)
    }
}

/// The heave benchmark (2 m, 10 s) checked to both codes: each node's largest utilisation over the
/// run is the largest of the criterion evaluated by hand at every step from that step's moment,
/// tension and height (to 1e-9), and the heave raises it above the still run's.
#[test]
fn the_utilisation_follows_every_steps_moment_and_tension() {
    for (code, check) in [(Code::DnvStF201, DNV), (Code::ApiStd2rd, API)] {
        let scene = RiserScene::parse("check.toml", &heave_text(check), &NoFiles).expect("scene");
        let st = statics::solve(scene).expect("statics");
        let n = st.model.nodes();
        let mut by_hand = ByHand {
            code,
            max: vec![0.0; n],
        };
        let r = run::run(st, &mut [&mut by_hand], RunOptions::default()).expect("run");
        let d = r.output::<DesignCheck>().expect("a design check");
        let mut worst = 0.0f64;
        for i in 0..n {
            worst = worst.max((d.max[i] / by_hand.max[i] - 1.0).abs());
        }
        let (i, u) = d.worst().expect("checked");
        println!(
            "{}: largest utilisation {u:.5} at {:.1} m, t {:.2} s ({}); worst difference from by hand {worst:.2e}",
            code.name(),
            d.arc[i],
            d.time_of_max[i],
            d.term_of_max[i].name()
        );
        assert!(worst < 1e-9, "{}: {worst}", code.name());
        assert!(d.compression().is_empty());
    }
}
