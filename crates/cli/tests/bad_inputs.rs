//! Bad input, one row per input (issue 14): each mutation of a real case must be refused by
//! `catena check` (the same reading `catena run` does, before anything runs) with an error that names
//! the file and the key, never a panic and never silently accepted. Every row's mutation must apply
//! (a row whose text is absent fails).

use std::path::{Path, PathBuf};

use catena_cli::commands;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `(name, case, text to replace, replacement, the key the message must name)`.
const ROWS: &[(&str, &str, &str, &str, &str)] = &[
    (
        "sections out of order",
        "lazy-wave/static",
        "to = 1500.0",
        "to = 1100.0",
        "section[1].to",
    ),
    (
        "sections short of the length",
        "lazy-wave/static",
        "to = 2300.0",
        "to = 2200.0",
        "section[2].to",
    ),
    (
        "a section of an unknown type",
        "lazy-wave/static",
        "type = \"buoyancy\"",
        "type = \"buoyant\"",
        "section[1].type",
    ),
    (
        "both the short form and sections",
        "lazy-wave/static",
        "length = 2300.0 ",
        "length = 2300.0\nod = 0.228\n",
        "line.od",
    ),
    (
        "sections with a [[mesh]]",
        "lazy-wave/static",
        "[ends]",
        "[[mesh]]\nto = 2300.0\nelement_length = 5.0\n\n[ends]",
        "mesh",
    ),
    (
        "a taper with a negative size",
        "lazy-wave/static",
        "name = \"pipe\"",
        "name = \"pipe\"\nod_end = -0.3\nwall_end = 0.03",
        "line_type[0].od_end",
    ),
    (
        "two line types of one name",
        "lazy-wave/static",
        "name = \"buoyancy\"",
        "name = \"pipe\"",
        "line_type[1].name",
    ),
    (
        "a line type's drag coefficient negative",
        "lazy-wave/static",
        "cd_normal = 1.2 ",
        "cd_normal = -1.2 ",
        "line_type[1].cd_normal",
    ),
    (
        "line types without sections",
        "benchmarks/scr-heave",
        "[ends]",
        "[[line_type]]\nname = \"pipe\"\nod = 0.2\nea = 1e9\nei = 1e6\nmass = 100.0\nsubmerged_weight = 500.0\n\n[ends]",
        "section",
    ),
    (
        "profile with x not increasing",
        "scr1000/static-rq-slope-2deg",
        "profile = [[0.0, 0.0], [2000.0, -69.84]]",
        "profile = [[0.0, 0.0], [0.0, -69.84]]",
        "seabed.profile[1]",
    ),
    (
        "profile above the sea",
        "scr1000/static-rq-slope-2deg",
        "profile = [[0.0, 0.0], [2000.0, -69.84]]",
        "profile = [[0.0, 0.0], [2000.0, 1200.0]]",
        "seabed.profile[1]",
    ),
    (
        "profile of one point",
        "scr1000/static-rq-slope-2deg",
        "profile = [[0.0, 0.0], [2000.0, -69.84]]",
        "profile = [[0.0, 0.0]]",
        "seabed.profile",
    ),
    (
        "zone ending before it starts",
        "hard/zone-boundary",
        "to_x = 400.0 ",
        "to_x = -200.0 ",
        "seabed.zone[0].to_x",
    ),
    (
        "zones overlapping",
        "hard/zone-boundary",
        "[hydrodynamics]",
        "[[seabed.zone]]\nfrom_x = 300.0\nto_x = 500.0\nstiffness = 50e3\n\n[hydrodynamics]",
        "seabed.zone[1].from_x",
    ),
    (
        "zone with a key of another law",
        "hard/zone-boundary",
        "stiffness = 20.0e3 ",
        "su0 = 100.0 ",
        "seabed.zone[0].su0",
    ),
    (
        "attachment beyond the line",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[[attachment]]\narc = 2000.0\nmass = 1.0\n\n[dynamic]",
        "attachment[0].arc",
    ),
    (
        "attachment with a negative mass",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[[attachment]]\narc = 600.0\nmass = -1.0\n\n[dynamic]",
        "attachment[0].mass",
    ),
    (
        "attachment drag without hydrodynamics",
        "scr1000/static-rq",
        "[flexjoint]",
        "[[attachment]]\narc = 600.0\ndrag_area = 1.0\n\n[flexjoint]",
        "attachment[0].drag_area",
    ),
    (
        "negative friction",
        "hard/friction-stick-slip",
        "axial = 0.5 ",
        "axial = -0.5 ",
        "seabed.friction.axial",
    ),
    (
        "zero mobilisation",
        "hard/friction-stick-slip",
        "mobilisation = 0.001 ",
        "mobilisation = 0.0 ",
        "seabed.friction.mobilisation",
    ),
    (
        "friction without its mobilisation",
        "hard/friction-stick-slip",
        "mobilisation = 0.001 ",
        "# no mobilisation ",
        "seabed.friction.mobilisation",
    ),
    (
        "a design check of an unknown code",
        "scr1000/design-100yr-linear",
        "code = \"dnv-st-f201\"",
        "code = \"dnv-os-f999\"",
        "design_check.code",
    ),
    (
        "a tensile strength below the yield strength",
        "scr1000/design-100yr-linear",
        "smts = 531.0e6",
        "smts = 400.0e6",
        "design_check.smts",
    ),
    (
        "a corrosion allowance that leaves no wall",
        "scr1000/design-100yr-linear",
        "corrosion_allowance = 0.003",
        "corrosion_allowance = 0.0254",
        "design_check.corrosion_allowance",
    ),
    (
        "a negative design pressure",
        "scr1000/design-100yr-linear",
        "internal_pressure = 15.0e6",
        "internal_pressure = -15.0e6",
        "design_check.internal_pressure",
    ),
    (
        "an unknown safety class",
        "scr1000/design-100yr-linear",
        "safety_class = \"normal\"",
        "safety_class = \"extreme\"",
        "design_check.safety_class",
    ),
    (
        "a design check without the pipe's wall",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[design_check]\ncode = \"api-std-2rd\"\nsmys = 448e6\nsmts = 531e6\n\n[dynamic]",
        "line.wall",
    ),
    (
        "a design check without a dynamic run",
        "scr1000/static-rq",
        "[seabed]",
        "[design_check]\ncode = \"api-std-2rd\"\nsmys = 448e6\nsmts = 531e6\n\n[seabed]",
        "design_check",
    ),
    (
        "an unknown extremes channel",
        "scr1000/design-100yr-linear",
        "\"sag_moment\", \"utilisation\"]",
        "\"sag_moment\", \"hog_moment\"]",
        "extremes.channels[3]",
    ),
    (
        "an extremes gauge the scene does not have",
        "scr1000/design-100yr-linear",
        "\"sag_moment\", \"utilisation\"]",
        "\"sag_moment\", \"gauge:tdz\"]",
        "extremes.channels[3]",
    ),
    (
        "the utilisation's extremes without a design check",
        "scr1000/design-100yr-linear",
        "[design_check]\ncode = \"dnv-st-f201\"\nsmys = 448.0e6                # Pa [A] API 5L X65\nsmts = 531.0e6                # Pa [A] API 5L X65\ninternal_pressure = 15.0e6    # Pa at the still water level [A] (a 15 MPa production riser)\nsafety_class = \"normal\"       # [A]\ncorrosion_allowance = 0.003   # m [A]\nstart = 200.0                 # s: after the ramp [A]\n",
        "",
        "extremes.channels[3]",
    ),
    (
        "an extremes quantile of one or more",
        "scr1000/design-100yr-linear",
        "quantile = 0.9 ",
        "quantile = 1.5 ",
        "extremes.quantile",
    ),
    (
        "an extremes block shorter than the time step",
        "scr1000/design-100yr-linear",
        "block = 600.0 ",
        "block = 0.01 ",
        "extremes.block",
    ),
    (
        "heave nan",
        "benchmarks/scr-heave",
        "heave = 2.0",
        "heave = nan",
        "motion.harmonic.heave",
    ),
    (
        "EA 1e300",
        "benchmarks/scr-heave",
        "ea = 3.356e9",
        "ea = 1e300",
        "line.ea",
    ),
    (
        "EI 1e300",
        "benchmarks/scr-heave",
        "ei = 17.59e6",
        "ei = 1e300",
        "line.ei",
    ),
    (
        "weight 1e300",
        "benchmarks/scr-heave",
        "submerged_weight = 1010.0",
        "submerged_weight = 1e300",
        "line.submerged_weight",
    ),
    (
        "anchor_z nan",
        "benchmarks/scr-heave",
        "anchor_x = 0.0",
        "anchor_x = 0.0\nanchor_z = nan",
        "ends.anchor_z",
    ),
    (
        "top below the mudline",
        "benchmarks/scr-heave",
        "top_z = 1000.0",
        "top_z = -1.0",
        "ends.top_z",
    ),
    (
        "anchor above the sea",
        "benchmarks/scr-heave",
        "anchor_x = 0.0",
        "anchor_x = 0.0\nanchor_z = 1100.0",
        "ends.anchor_z",
    ),
    (
        "anchor 200 m below the mudline",
        "benchmarks/scr-heave",
        "anchor_x = 0.0",
        "anchor_x = 0.0\nanchor_z = -200.0",
        "ends.anchor_z",
    ),
    (
        "heave beyond the line's reach",
        "benchmarks/scr-heave",
        "heave = 2.0",
        "heave = 700.0",
        "motion",
    ),
    (
        "surge beyond the line's reach",
        "benchmarks/scr-heave",
        "heave = 2.0",
        "heave = 2.0\nsurge = 900.0",
        "motion",
    ),
    (
        "static tolerance 1",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[static]\ntolerance = 1.0\n\n[dynamic]",
        "static.tolerance",
    ),
    (
        "static tolerance nan",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[static]\ntolerance = nan\n\n[dynamic]",
        "static.tolerance",
    ),
    (
        "static tolerance -1",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[static]\ntolerance = -1.0\n\n[dynamic]",
        "static.tolerance",
    ),
    (
        "static max_iterations 0",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[static]\nmax_iterations = 0\n\n[dynamic]",
        "static.max_iterations",
    ),
    (
        "dynamic max_iterations 0",
        "benchmarks/scr-heave",
        "scheme = \"hht\"",
        "scheme = \"hht\"\nmax_iterations = 0",
        "dynamic.max_iterations",
    ),
    (
        "max_step_cuts 1000",
        "benchmarks/scr-heave",
        "scheme = \"hht\"",
        "scheme = \"hht\"\nmax_step_cuts = 1000",
        "dynamic.max_step_cuts",
    ),
    (
        "duration 1e9",
        "benchmarks/scr-heave",
        "duration = 100.0",
        "duration = 1e9",
        "dynamic.duration",
    ),
    (
        "element length 1e-5",
        "benchmarks/scr-heave",
        "element_length = 4.0",
        "element_length = 1e-5",
        "mesh",
    ),
    (
        "records of gigabytes",
        "benchmarks/scr-heave",
        "duration = 100.0",
        "duration = 100000.0\noutput_interval = 0.05",
        "dynamic.output_interval",
    ),
    (
        "current 1e300",
        "benchmarks/scr-current",
        "[[0.0, 0.5]]",
        "[[0.0, 1e300]]",
        "current.profile[0][1]",
    ),
    (
        "current entry of three numbers",
        "benchmarks/scr-current",
        "[[0.0, 0.5]]",
        "[[0.0, 0.5, 7.0]]",
        "current.profile[0]",
    ),
    (
        "k_max 1e17",
        "scr1000/static-rq",
        "k_max = 200.0",
        "k_max = 1e17",
        "seabed.k_max",
    ),
    (
        "two gauges of one name",
        "benchmarks/scr-heave",
        "[dynamic]",
        "[[gauge]]\nname = \"a\"\narc = 1000.0\n[[gauge]]\nname = \"a\"\narc = 1100.0\n\n[dynamic]",
        "gauge[1].name",
    ),
    (
        "negative time step",
        "benchmarks/scr-heave",
        "time_step = 0.05",
        "time_step = -0.05",
        "dynamic.time_step",
    ),
    (
        "soil test step 1e-300",
        "soil/figure5",
        "step = 2.0",
        "step = 1e-300",
        "test.step",
    ),
    (
        "soil test count 1e9",
        "soil/figure5",
        "count = 100\n",
        "count = 1000000000\n",
        "test.cycles[2].count",
    ),
    (
        "soil test waypoint 1e300",
        "soil/figure5",
        "waypoints = [0.0, 612.25]",
        "waypoints = [0.0, 1e300]",
        "test.waypoints[1]",
    ),
    (
        "degradation sensitivity below 1",
        "scr1000/memory/scr1000-rq-degrading",
        "sensitivity = 3.0",
        "sensitivity = 0.5",
        "seabed.degradation.sensitivity",
    ),
    (
        "degradation ductility zero",
        "scr1000/memory/scr1000-rq-degrading",
        "ductility = 25.0",
        "ductility = 0.0",
        "seabed.degradation.ductility",
    ),
    (
        "regain t50 without its exponent",
        "scr1000/memory/scr1000-rq-degrading",
        "regain_exponent = 1.0",
        "",
        "seabed.degradation.regain_exponent",
    ),
    (
        "negative regain time",
        "scr1000/memory/scr1000-rq-degrading",
        "regain_t50 = 30000.0",
        "regain_t50 = -3.0",
        "seabed.degradation.regain_t50",
    ),
    (
        "degradation on a linear seabed",
        "scr1000/storm23",
        "[hydrodynamics]",
        "[seabed.degradation]\nsensitivity = 3.0\nductility = 10.0\n\n[hydrodynamics]",
        "seabed.degradation",
    ),
    (
        "a drained suction ratio above the undrained one",
        "scr1000/memory/scr1000-rq-degrading",
        "[seabed.degradation]          # Einav",
        "[seabed.rate_suction]\ndrained_ratio = 0.5\ncv = 1e-7\nv50 = 10.0\nexponent = 1.0\n\n[seabed.degradation]          # Einav",
        "seabed.rate_suction.drained_ratio",
    ),
    (
        "a rate-dependent suction without its cv",
        "scr1000/memory/scr1000-rq-degrading",
        "[seabed.degradation]          # Einav",
        "[seabed.rate_suction]\ndrained_ratio = 0.1\nv50 = 10.0\nexponent = 1.0\n\n[seabed.degradation]          # Einav",
        "seabed.rate_suction.cv",
    ),
    (
        "negative calm interval",
        "scr1000/memory/year-rq",
        "calm = 1051920.0",
        "calm = -1.0",
        "sequence.calm",
    ),
    (
        "a negative lay speed",
        "lay/jlay-12in-steady",
        "speed = 0.05 ",
        "speed = -0.05 ",
        "lay.speed",
    ),
    (
        "a tower angle over 90 degrees",
        "lay/jlay-12in-steady",
        "[lay]",
        "[lay]\ntower_angle_deg = 95.0",
        "lay.tower_angle_deg",
    ),
    (
        "a lay longer than the pipe",
        "lay/jlay-12in-steady",
        "[lay]",
        "[lay]\npipe_length = 500.0",
        "lay.pipe_length",
    ),
    (
        "a hinged tower without its stiffness",
        "lay/jlay-12in-steady",
        "[lay]",
        "[lay]\ntower = \"hinged\"",
        "lay.tower_stiffness",
    ),
    (
        "a tensioner without its gain",
        "lay/jlay-12in-tension-surge",
        "gain = 2.0e-5 ",
        "# gain = 2.0e-5 ",
        "lay.gain",
    ),
    (
        "a tensioner's key in position control",
        "lay/jlay-12in-steady",
        "[lay]",
        "[lay]\nmax_payout_rate = 0.5",
        "lay.max_payout_rate",
    ),
    (
        "a prescribed top motion in a lay",
        "lay/jlay-12in-steady",
        "[lay]",
        "[motion.harmonic]\nheave = 1.0\nperiod = 10.0\n\n[lay]",
        "motion",
    ),
    (
        "a lay-down without its wire",
        "lay/jlay-12in-steady",
        "[lay]",
        "[lay]\nlay_down = true\npipe_length = 500.0",
        "lay.wire",
    ),
    (
        "a station height with the vessel keeping its speed",
        "lay/laydown-12in",
        "element_length = 1.0          # m [A]\n\n[dynamic]",
        "element_length = 1.0\nstation_height = 10.0\n\n[dynamic]",
        "lay.wire.station_height",
    ),
    (
        "an A&R wire of a line type there is not",
        "lay/laydown-12in",
        "type = \"ar-wire\"",
        "type = \"no-such-wire\"",
        "lay.wire.type",
    ),
    (
        "an A&R wire of a line type with a property of its own",
        "lay/laydown-12in",
        "type = \"ar-wire\"",
        "type = \"ar-wire\"\nod = 0.08",
        "lay.wire.od",
    ),
    (
        "a line type in a lay that is not the A&R wire's",
        "lay/jlay-12in-steady",
        "[lay]",
        "[[line_type]]\nname = \"pipe\"\nod = 0.3239\nea = 4e9\nei = 4.7e7\nsubmerged_weight = 660.0\nmass = 160.0\n\n[lay]",
        "line_type[0]",
    ),
    (
        "a negative station height",
        "lay/laydown-12in-station",
        "station = true ",
        "station_height = -5.0\nstation = true ",
        "lay.wire.station_height",
    ),
    (
        "a laid seabed under a lay",
        "lay/jlay-12in-steady",
        "[lay]",
        "[as_laid]\nfile = \"laid-seabed.json\"\n\n[lay]",
        "as_laid",
    ),
    (
        "a laid seabed file that is not there",
        "lay/on-the-laid-seabed",
        "file = \"../../out/lay-steady/laid-seabed.json\"",
        "file = \"no-such-laid-seabed.json\"",
        "as_laid.file",
    ),
    (
        "a laid seabed's shift that is not a number",
        "lay/on-the-laid-seabed",
        "x_shift = -250.0 ",
        "x_shift = nan ",
        "as_laid.x_shift",
    ),
    (
        "a negative lay ramp",
        "lay/jlay-12in-steady",
        "[lay]",
        "[lay]\nramp = -1.0",
        "lay.ramp",
    ),
];

#[test]
fn every_bad_input_is_refused_naming_its_file_and_key() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bad_inputs");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut failures = Vec::new();
    for (i, (name, case, from, to, key)) in ROWS.iter().enumerate() {
        let src = root().join(format!("cases/{case}.toml"));
        let text = std::fs::read_to_string(&src).expect("case");
        assert!(text.contains(from), "row {name}: `{from}` is not in {case}");
        let path = src.with_file_name(format!("bad-input-{i}.toml"));
        let path = dir.join(path.file_name().expect("name"));
        std::fs::write(&path, text.replacen(from, to, 1)).expect("write");
        // Files the case names (RAO tables) beside it, as in `cases/`.
        for f in std::fs::read_dir(src.parent().expect("dir")).expect("dir") {
            let f = f.expect("entry").path();
            if f.extension().is_some_and(|e| e == "csv") {
                std::fs::copy(&f, dir.join(f.file_name().expect("name"))).expect("copy");
            }
        }
        match commands::check(&path) {
            Ok(out) => failures.push(format!("{name}: accepted:\n{out}")),
            Err(e) => {
                let msg = e.to_string();
                let file = path.display().to_string();
                if !msg.contains(&file) || !msg.contains(&format!("`{key}`")) {
                    failures.push(format!(
                        "{name}: the message does not name {file} and `{key}`: {msg}"
                    ));
                }
                assert!(
                    msg.len() < 400,
                    "{name}: a message of {} characters: {msg}",
                    msg.len()
                );
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A motion series with a cell that is not a number is refused with the file, line and column.
#[test]
fn a_motion_series_cell_that_is_not_a_number_is_refused() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bad_series");
    std::fs::create_dir_all(&dir).expect("dir");
    std::fs::write(dir.join("m.csv"), "t,dx,dz\n0.0,0.0,0.0\n1.0,abc,0.1,0.2\n").expect("csv");
    let text =
        std::fs::read_to_string(root().join("cases/benchmarks/scr-heave.toml")).expect("case");
    let from = "[motion.harmonic]             # z = 2·r(t)·sin(2πt/10), quintic ramp over the first 10 s\nheave = 2.0                   # m\nperiod = 10.0                 # s\nramp = 10.0                   # s";
    assert!(text.contains(from), "the harmonic table moved");
    let case = dir.join("series.toml");
    std::fs::write(
        &case,
        text.replace(from, "[motion.series]\nfile = \"m.csv\""),
    )
    .expect("case");
    let e = commands::check(&case).expect_err("refused").to_string();
    assert!(
        e.contains("motion.series.file") && e.contains("line 3, column 2") && e.contains("abc"),
        "{e}"
    );
}

/// A well-formed case passes `catena check`, which says what would run.
#[test]
fn check_describes_a_good_case() {
    let out = commands::check(&root().join("cases/benchmarks/scr-heave.toml")).expect("good");
    assert!(
        out.contains("2000 steps") && out.contains("400 elements"),
        "{out}"
    );
    assert!(
        out.contains("linear seabed") && out.contains("harmonic top motion"),
        "{out}"
    );
    assert!(
        !out.contains("waves"),
        "an absent effect is not built: {out}"
    );
}

/// The range checks refuse nonsense, not soft seabeds: the 1000 m SCR on the softest seabed of the
/// Figure 11 sweep (su0 = 0, 650 Pa/m) rests 0.6 m deep, and its default anchor (at the static
/// embedment, 2.6 D below the mudline) must still be accepted.
#[test]
fn a_very_soft_seabed_is_not_refused() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("soft_seabed");
    std::fs::create_dir_all(&dir).expect("dir");
    let src = root().join("cases/scr1000/fatigue/scr1000-rq-fsuc0.2.toml");
    let text = std::fs::read_to_string(&src).expect("case");
    for from in ["su0 = 1000.0 ", "su_gradient = 1300.0 "] {
        assert!(text.contains(from), "{from}");
    }
    let text = text
        .replace("su0 = 1000.0 ", "su0 = 0.0 ")
        .replace("su_gradient = 1300.0 ", "su_gradient = 650.0 ");
    std::fs::copy(src.with_file_name("semi-rao.csv"), dir.join("semi-rao.csv")).expect("rao");
    let case = dir.join("soft.toml");
    std::fs::write(&case, text).expect("case");
    let out = commands::check(&case).expect("a soft seabed is a valid scene");
    assert!(out.contains("Randolph–Quiggin seabed"), "{out}");
}
