//! Lines of sections (`[[line_type]]`, `[[section]]`): a uniform line written three ways gives the
//! same bits, a tapered stress joint bends as its closed form says, and a steel lazy wave's statics
//! match the catenary of its sections.

use std::path::{Path, PathBuf};

use catena::run::{self, RunOptions};
use catena::scene::riser::RiserScene;
use catena::scene::NoFiles;
use catena::statics;
use catena_fe::assembly::Placement;
use catena_fe::beam::Section;
use catena_fe::model::{LineModel, LineSpec, Segment, Support};
use catena_fe::statics::{solve, StaticOptions, StaticWorkspace};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The heave benchmark with its `[line]` and `[[mesh]]` replaced by `line`.
fn heave_with(line: &str) -> RiserScene {
    let text =
        std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("test data");
    let a = text.find("[line]").expect("test data");
    let b = text.find("[ends]").expect("test data");
    let text = format!("{}{line}\n{}", &text[..a], &text[b..])
        .replace("duration = 100.0", "duration = 20.0")
        .replace("envelope_start = 50.0", "envelope_start = 10.0");
    RiserScene::parse("heave.toml", &text, &NoFiles).expect("scene")
}

const PIPE: &str = r#"
[[line_type]]
name = "pipe"
od = 0.2286
ea = 3.356e9
ei = 17.59e6
submerged_weight = 1010.0
mass = 145.06
"#;

/// The heave benchmark's uniform line written in the short form (`[line]` and one `[[mesh]]`), as
/// one section and as three sections of the same type: the same statics and the same 20 s of
/// heave, every range graph to the bit.
#[test]
fn a_uniform_line_as_one_or_three_sections_is_the_short_form_to_the_bit() {
    let short = heave_with(
        "[line]\nlength = 1600.0\nod = 0.2286\nea = 3.356e9\nei = 17.59e6\nsubmerged_weight = 1010.0\nmass = 145.06\n[[mesh]]\nto = 1600.0\nelement_length = 4.0\n",
    );
    let one = heave_with(&format!(
        "[line]\nlength = 1600.0\n{PIPE}[[section]]\ntype = \"pipe\"\nto = 1600.0\nelement_length = 4.0\n"
    ));
    let three = heave_with(&format!(
        "[line]\nlength = 1600.0\n{PIPE}[[section]]\ntype = \"pipe\"\nto = 500.0\nelement_length = 4.0\n[[section]]\ntype = \"pipe\"\nto = 1100.0\nelement_length = 4.0\n[[section]]\ntype = \"pipe\"\nto = 1600.0\nelement_length = 4.0\n"
    ));
    let runs: Vec<_> = [short, one, three]
        .into_iter()
        .map(|s| {
            let st = statics::solve(s).expect("statics");
            run::run(st, &mut [], RunOptions::default()).expect("run")
        })
        .collect();
    let bits = |r: &run::DynamicRun| -> Vec<u64> {
        let mut v: Vec<u64> = r
            .statics
            .results
            .tension
            .iter()
            .map(|x| x.to_bits())
            .collect();
        v.extend(r.statics.results.moment.iter().map(|x| x.to_bits()));
        for (_, range) in r.envelopes.ranges() {
            for s in [&range.min, &range.max, &range.sum] {
                v.extend(s.iter().map(|x| x.to_bits()));
            }
        }
        v
    };
    let want = bits(&runs[0]);
    assert!(want.len() > 3000);
    for (k, r) in runs.iter().enumerate().skip(1) {
        assert!(
            bits(r) == want,
            "form {k} differs from the short form (top tension {} vs {})",
            r.statics.summary.top_tension,
            runs[0].statics.summary.top_tension
        );
    }
}

/// A tapered stress joint (od 0.40 → 0.2286 m, wall 0.045 → 0.0254 m over 12 m, E 207 GPa) as the
/// scene meshes it (24 elements, each with the taper's properties at its middle), clamped at its
/// wide end with a small load P = 1 kN at its tip: the tip deflection is the closed form
/// `δ = P ∫₀ᴸ (L − x)²/EI(x) dx` (EI(x) from the linear od and wall, the integral by Simpson's rule
/// on 20 000 intervals) within 0.2 % (0.08 % measured); with the taper's top properties everywhere
/// it would be 43 % less.
#[test]
fn a_tapered_stress_joint_bends_as_its_closed_form() {
    let (od0, od1, t0, t1, len, e) = (0.40, 0.2286, 0.045, 0.0254, 12.0, 207e9);
    let text = format!(
        r#"
title = "stress joint"
[environment]
water_depth = 1000.0
[line]
length = 1600.0
[[line_type]]
name = "taper"
od = {od0}
wall = {t0}
od_end = {od1}
wall_end = {t1}
youngs_modulus = {e}
steel_density = 7850.0
contents_density = 726.0
[[line_type]]
name = "pipe"
od = {od1}
wall = {t1}
youngs_modulus = {e}
steel_density = 7850.0
contents_density = 726.0
[[section]]
type = "taper"
to = {len}
element_length = 0.5
[[section]]
type = "pipe"
to = 1600.0
element_length = 5.0
[ends]
top_x = 920.0
top_z = 1000.0
anchor_x = 0.0
anchor_z = 0.1
"#
    );
    let scene = RiserScene::parse("joint.toml", &text, &NoFiles).expect("scene");
    let taper: Vec<_> = scene
        .model
        .elements
        .iter()
        .take_while(|el| el.kind == 0)
        .copied()
        .collect();
    assert_eq!(taper.len(), 24);
    let segments: Vec<Segment> = taper
        .iter()
        .map(|el| {
            Segment::uniform(
                el.l0,
                el.l0,
                Section {
                    ea: el.section.ea,
                    ei: el.section.ei,
                },
                0.0,
                0.0,
                el.od,
            )
        })
        .collect();
    let mut m = LineModel::build(&LineSpec {
        segments,
        top: Support::Fixed,
        anchor: Support::Free,
        seabed: None,
        flexjoint: None,
    })
    .expect("model");
    let p = 1e3;
    let n = m.nodes();
    m.dead_load[3 * (n - 1) + 1] -= p;
    let q: Vec<f64> = (0..n).flat_map(|i| [m.arc[i], 0.0, 0.0]).collect();
    let pl = Placement::new(&q);
    let mut u = vec![0.0; q.len()];
    let mut ws = StaticWorkspace::new(&m).expect("workspace");
    solve(&m, &pl, &mut u, &mut ws, &StaticOptions::default()).expect("converges");
    let tip = -u[3 * (n - 1) + 1];
    let ei = |x: f64| {
        let (d, t) = (od0 + (od1 - od0) * x / len, t0 + (t1 - t0) * x / len);
        e * std::f64::consts::PI / 64.0 * (d.powi(4) - (d - 2.0 * t).powi(4))
    };
    let k = 20_000;
    let h = len / k as f64;
    let f = |x: f64| (len - x).powi(2) / ei(x);
    let simpson: f64 = (0..=k)
        .map(|i| {
            let w = if i == 0 || i == k {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    let want = p * simpson;
    let uniform = p * len.powi(3) / (3.0 * ei(0.0));
    println!(
        "taper tip deflection {:.6} mm, closed form {:.6} mm (top section everywhere {:.6} mm)",
        tip * 1e3,
        want * 1e3,
        uniform * 1e3
    );
    assert!((tip / want - 1.0).abs() < 2e-3, "{tip} vs {want}");
    assert!(uniform < 0.6 * want);
}

/// The steel lazy wave of `cases/lazy-wave/static.toml` converges from its seed (the catenary of
/// its sections) and agrees with that catenary where bending matters little: top tension within
/// 0.2 % (0.04 % measured), the horizontal tension within 1 % (0.4 %), the sag and hog bends'
/// heights within 0.5 m (0.2 m; the catenary has no bending stiffness and no seabed penetration),
/// the hog bend more than 50 m above the sag bend.
#[test]
fn a_lazy_wave_matches_the_catenary_of_its_sections() {
    let scene = statics::read_scene(&root().join("cases/lazy-wave/static.toml")).expect("scene");
    let st = statics::solve(scene).expect("statics");
    let m = &st.model;
    let r = &st.results;
    let n = m.nodes();
    // The catenary of the sections between the same ends.
    let zc = r.z[n - 1];
    let top = (r.x[0], r.z[0]);
    let (q, h, _) =
        catena_fe::sectioned::seed(m, top, (r.x[n - 1], zc)).expect("sectioned catenary");
    let bend = |z: &dyn Fn(usize) -> f64| {
        // The lowest node above the buoyancy (sag) and the highest in it (hog).
        let b = m.section_boundaries();
        let (b0, b1) = (b[0], b[1]);
        let idx = |lo: f64, hi: f64| (0..n).filter(move |&i| m.arc[i] >= lo && m.arc[i] <= hi);
        let sag = idx(b0 - 300.0, b1).fold(f64::MAX, |a, i| a.min(z(i)));
        let hog = idx(b0, b1 + 300.0).fold(f64::MIN, |a, i| a.max(z(i)));
        (sag, hog)
    };
    let (sag, hog) = bend(&|i| r.z[i]);
    let (sag_c, hog_c) = bend(&|i| q[3 * i + 1]);
    let t_top_c = {
        // The catenary's top tension: H / cos of its top angle.
        let th = q[2] + std::f64::consts::PI;
        h / th.cos()
    };
    let s = &st.summary;
    println!(
        "lazy wave: top tension {:.2} kN (catenary {:.2}), H {:.2} kN ({:.2}), sag bend {sag:.2} m ({sag_c:.2}), hog bend {hog:.2} m ({hog_c:.2})",
        s.top_tension / 1e3,
        t_top_c / 1e3,
        s.horizontal_tension / 1e3,
        h / 1e3
    );
    assert!((s.top_tension / t_top_c - 1.0).abs() < 2e-3);
    assert!((s.horizontal_tension / h - 1.0).abs() < 1e-2);
    assert!((sag - sag_c).abs() < 0.5 && (hog - hog_c).abs() < 0.5);
    assert!(hog > sag + 50.0, "a wave: sag {sag} hog {hog}");
}

/// A line type no section uses is read, and said: the scene's warnings name it.
#[test]
fn an_unused_line_type_is_a_warning() {
    let path = root().join("cases/lazy-wave/static.toml");
    let text = std::fs::read_to_string(&path).expect("case");
    let text = text.replacen(
        "[[section]]",
        "[[line_type]]\nname = \"spare\"\nod = 0.3\nea = 1e9\nei = 1e6\nmass = 100.0\nsubmerged_weight = 500.0\n\n[[section]]",
        1,
    );
    let scene = RiserScene::parse("lw.toml", &text, &NoFiles).expect("scene");
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(scene.warnings[0].contains("\"spare\""));
    let plain = RiserScene::parse(
        "lw.toml",
        &std::fs::read_to_string(&path).expect("case"),
        &NoFiles,
    )
    .expect("scene");
    assert!(plain.warnings.is_empty());
}

/// The steel lazy wave as CableDyn 0.3.0 runs it too (`cases/lazy-wave/cabledyn-heave.toml`,
/// `validation/cabledyn/lazy-wave.dat`: a linear seabed and a pinned top): CableDyn's statics give
/// top tension 1023.91 kN, anchor tension 169.36 kN, touchdown 1745.78 m of (stretched) arc, the hog
/// bend 241.15 m and the sag bend 133.85 m above the mudline. catena agrees within 0.1 %, and the
/// bends' heights within 0.2 m (measured: 0.00 %, 0.03 %, 0.02 %, 0.06 m and 0.08 m;
/// `validation/lazy-wave.md` has the heave's ranges too).
#[test]
fn a_lazy_wave_matches_cabledyn() {
    let scene =
        statics::read_scene(&root().join("cases/lazy-wave/cabledyn-heave.toml")).expect("scene");
    let st = statics::solve(scene).expect("statics");
    let (s, r, m) = (&st.summary, &st.results, &st.model);
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let n = m.nodes();
    let between = |lo: f64, hi: f64| (0..n).filter(move |&i| m.arc[i] >= lo && m.arc[i] <= hi);
    let sag = between(900.0, 1400.0).fold(f64::MAX, |a, i| a.min(r.z[i]));
    let hog = between(1150.0, 1700.0).fold(f64::MIN, |a, i| a.max(r.z[i]));
    let td = s.touchdown_arc.expect("touchdown");
    println!(
        "lazy wave vs CableDyn: top {:.2} kN, anchor {:.2} kN, touchdown {td:.2} m, sag {sag:.2} m, hog {hog:.2} m",
        r.tension[0] / 1e3,
        r.tension[n - 1] / 1e3
    );
    assert!(rel(r.tension[0], 1023.91e3) < 1e-3);
    assert!(rel(r.tension[n - 1], 169.36e3) < 1e-3);
    assert!(rel(td, 1745.78) < 1e-3);
    assert!((hog - 241.15).abs() < 0.2 && (sag - 133.85).abs() < 0.2);
}

/// The same lazy wave in the heave benchmark's motion (2 m, 10 s) against CableDyn 0.3.0
/// (`validation/lazy-wave.md`, from t = 50 s): top tension 911.12 to 1136.52 kN, the moment's range
/// 5.25 kN·m at the sag bend and 10.50 kN·m at the hog bend. catena agrees within 0.1 % on the
/// tension (measured 0.03 %) and 2 % on the moment ranges (measured 0.74 % and 1.00 %). The
/// buoyancy section's drag and added mass act on its hydrodynamic diameter (0.763 m, not the steel
/// 0.2731 m): on the steel diameter the bends' ranges move by several per cent (the safety net's
/// `section-drag-on-steel-diameter`).
#[test]
fn a_lazy_wave_heaves_as_cabledyn_has_it() {
    let scene =
        statics::read_scene(&root().join("cases/lazy-wave/cabledyn-heave.toml")).expect("scene");
    let st = statics::solve(scene).expect("statics");
    let r = catena::run::run(st, &mut [], catena::run::RunOptions::default()).expect("run");
    assert!(r.stop.is_none(), "{:?}", r.stop);
    let (res, m) = (&r.statics.results, &r.model.line);
    let n = m.nodes();
    let between = |lo: f64, hi: f64| (0..n).filter(move |&i| m.arc[i] >= lo && m.arc[i] <= hi);
    let i_sag = between(900.0, 1400.0)
        .min_by(|&a, &b| res.z[a].total_cmp(&res.z[b]))
        .expect("sag bend");
    let i_hog = between(m.arc[i_sag], 1700.0)
        .max_by(|&a, &b| res.z[a].total_cmp(&res.z[b]))
        .expect("hog bend");
    let range = |i: usize| (r.envelopes.moment.max[i] - r.envelopes.moment.min[i]) / 1e3;
    let (lo, hi) = (
        r.top.tension_extremes.0.expect("least"),
        r.top.tension_extremes.1.expect("greatest"),
    );
    println!(
        "lazy wave heave vs CableDyn: top tension {:.2} to {:.2} kN, moment range sag {:.3} hog {:.3} kN·m",
        lo / 1e3,
        hi / 1e3,
        range(i_sag),
        range(i_hog)
    );
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    assert!(rel(lo, 911.12e3) < 1e-3 && rel(hi, 1136.52e3) < 1e-3);
    assert!(rel(range(i_sag), 5.25) < 0.02, "sag bend: {}", range(i_sag));
    assert!(
        rel(range(i_hog), 10.50) < 0.02,
        "hog bend: {}",
        range(i_hog)
    );
}

/// The seabed holds a section by its contact diameter, not its steel's: the touchdown-joint case
/// on a linear seabed (`P = k·D·z`, k = 100 kN/m/m²) with the last 250 m of pipe given a contact
/// diameter of 0.456 m (a coated pipe; the steel's is 0.228 m). Resting on the flat, far beyond the
/// touchdown, its penetration is `W'/(k·D_contact)` = 1010 N/m / (100 kN/m/m² × 0.456 m) =
/// 22.1 mm (on the steel's diameter it would be twice that), within 1 %; the joint before it, on
/// its steel's diameter, rests at `W'_joint/(k·0.228 m)`.
#[test]
fn the_seabed_holds_a_section_by_its_contact_diameter() {
    let text = std::fs::read_to_string(root().join("cases/scr1000/static-rq-touchdown-joint.toml"))
        .expect("case");
    let seabed = text.find("[seabed]").expect("seabed");
    let text = format!(
        "{}[seabed]\nmodel = \"linear\"\nstiffness = 100.0e3\n",
        &text[..seabed]
    )
    .replacen(
        "[[section]]\ntype = \"pipe\"\nto = 1600.0",
        "[[section]]\ntype = \"coated\"\nto = 1600.0",
        1,
    ) + "\n[[line_type]]\nname = \"coated\"\nod = 0.228\nwall = 0.0254\nyoungs_modulus = 210.0e9\nsteel_density = 7850.0\ncontents_density = 726.0\ncontact_od = 0.456\n";
    let scene = RiserScene::parse("coated.toml", &text, &NoFiles).expect("scene");
    let st = statics::solve(scene).expect("statics");
    let (r, m) = (&st.results, &st.model);
    let n = m.nodes();
    let w = m.elements[m.elements.len() - 1].weight;
    let at = |s: f64| (0..n).min_by(|&a, &b| (m.arc[a] - s).abs().total_cmp(&(m.arc[b] - s).abs()));
    let (coated, joint) = (at(1500.0).expect("node"), at(1300.0).expect("node"));
    let w_joint = m.elements[(0..m.elements.len())
        .find(|&e| m.arc[e] >= 1300.0)
        .expect("joint element")]
    .weight;
    println!(
        "resting on the flat: coated {:.5} m (W' {w:.1} N/m), joint {:.5} m (W' {w_joint:.1} N/m)",
        r.penetration[coated], r.penetration[joint]
    );
    let expected = w / (100.0e3 * 0.456);
    assert!(
        (r.penetration[coated] / expected - 1.0).abs() < 0.01,
        "{}",
        r.penetration[coated]
    );
    let on_steel = w_joint / (100.0e3 * 0.228);
    assert!(
        (r.penetration[joint] / on_steel - 1.0).abs() < 0.01,
        "{}",
        r.penetration[joint]
    );
}
