//! What is written after the run: `/ranges`, the design check and the fatigue damage.

use super::*;

/// Writes the design check's per-node results into `/design_check` (beside the per-record
/// `utilisation` the recorder wrote): `utilisation_max`, `time_of_max`, `term_of_max` (an index
/// into the attribute `terms`), `least_effective_tension`, `time_of_least` and `euler_load`, with
/// units and the code's name and conventions as attributes. Nothing without a check.
pub fn write_design_check(path: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    let Some(d) = r.output::<catena::run::observers::design::DesignCheck>() else {
        return Ok(());
    };
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    let g = if file.link_exists("design_check") {
        file.group("design_check").map_err(&err)?
    } else {
        file.create_group("design_check").map_err(&err)?
    };
    for name in [
        "utilisation_max",
        "time_of_max",
        "term_of_max",
        "least_effective_tension",
        "time_of_least",
        "euler_load",
    ] {
        if g.link_exists(name) {
            g.unlink(name).map_err(&err)?;
        }
    }
    // A restart into the same directory rewrites them.
    for name in g.attr_names().map_err(&err)? {
        g.delete_attr(&name).map_err(&err)?;
    }
    attr(&g, "code", d.spec.code.name()).map_err(&err)?;
    num_attr(&g, "start", d.spec.start).map_err(&err)?;
    attr(
        &g,
        "convention",
        "utilisation: the code's criterion (DNV-ST-F201 combined loading with functional = the static state, environmental = the increment over it; API STD 2RD von Mises over C*SMYS); above 1 fails",
    )
    .map_err(&err)?;
    vector(&g, "utilisation_max", &d.max, "1").map_err(&err)?;
    vector(&g, "time_of_max", &d.time_of_max, "s").map_err(&err)?;
    let terms: Vec<u8> = d.term_of_max.iter().map(|t| t.index()).collect();
    let ds = g
        .new_dataset_builder()
        .with_data(&terms)
        .create("term_of_max")
        .map_err(&err)?;
    let names: Vec<String> = catena::checks::design::Term::ALL
        .iter()
        .enumerate()
        .map(|(i, t)| format!("{i} {}", t.name()))
        .collect();
    attr(&ds, "terms", &names.join(", ")).map_err(&err)?;
    let least: Vec<f64> = d
        .least_tension
        .iter()
        .map(|t| if *t == f64::MAX { f64::NAN } else { *t })
        .collect();
    vector(&g, "least_effective_tension", &least, "N").map_err(&err)?;
    vector(&g, "time_of_least", &d.time_of_least, "s").map_err(&err)?;
    vector(
        &g,
        "euler_load",
        &d.euler,
        "N (pi^2 EI / L^2, the smaller of the adjacent elements')",
    )
    .map_err(&err)?;
    let dims: Vec<(String, Vec<Option<&str>>)> = [
        "utilisation_max",
        "time_of_max",
        "term_of_max",
        "least_effective_tension",
        "time_of_least",
        "euler_load",
    ]
    .iter()
    .map(|n| (format!("design_check/{n}"), vec![Some("dynamic/arc")]))
    .collect();
    dimension_scales(&file, &dims).map_err(&err)?;
    file.flush().map_err(&err)?;
    Ok(())
}

/// Writes `/fatigue/damage_<fibre>` (one value per node, the larger of top and bottom; attributes
/// `sn_curve`, `scf`, `counted_seconds`) into a results file after the run.
pub fn write_fatigue(path: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    let Some(f) = &r.fatigue else {
        return Ok(());
    };
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    if file.link_exists("fatigue") {
        file.unlink("fatigue").map_err(&err)?;
    }
    let g = file.create_group("fatigue").map_err(&err)?;
    attr(&g, "sn_curve", &f.spec.curve_name).map_err(&err)?;
    num_attr(&g, "scf", f.spec.scf).map_err(&err)?;
    num_attr(&g, "counted_seconds", f.counted_seconds()).map_err(&err)?;
    for fib in &f.spec.fibres {
        if let Some(d) = f.damage_of(*fib) {
            vector(
                &g,
                &format!("damage_{}", fib.name()),
                &d,
                "1 (Miner damage of the counted record)",
            )
            .map_err(&err)?;
            dimension_scales(
                &file,
                &[(
                    format!("fatigue/damage_{}", fib.name()),
                    vec![Some("dynamic/arc")],
                )],
            )
            .map_err(&err)?;
        }
    }
    link_scales(&file, "fatigue", "dynamic", &["arc"]).map_err(&err)?;
    file.flush().map_err(&err)?;
    Ok(())
}

/// Writes `/ranges/<quantity>/min`, `max` and `mean` (one value per node, node order as in
/// `/dynamic/arc`; every quantity of [`catena::run::observe::RANGE_QUANTITIES`] the run has) into a
/// results file after the run. The group's attributes `start` (s) and `steps` say what they were
/// taken over (every step from the envelope start, not only the recorded ones); each quantity's
/// group has `units` and `description`.
pub fn write_ranges(path: &Path, r: &catena::run::DynamicRun) -> Result<(), AppError> {
    let err = h5err(path);
    let file = hdf5::File::open_rw(path).map_err(&err)?;
    if file.link_exists("ranges") {
        file.unlink("ranges").map_err(&err)?;
    }
    let g = file.create_group("ranges").map_err(&err)?;
    let e = &r.envelopes;
    num_attr(&g, "start", r.spec.envelope_start).map_err(&err)?;
    num_attr(&g, "steps", e.samples as f64).map_err(&err)?;
    attr(
        &g,
        "description",
        "least, greatest and mean of each quantity at each node over every step from `start`",
    )
    .map_err(&err)?;
    let mut dims: Vec<(String, Vec<Option<&str>>)> = Vec::new();
    for (name, range) in e.ranges() {
        let (units, what) = catena::run::observe::RANGE_QUANTITIES
            .iter()
            .find(|q| q.0 == name)
            .map_or(("", ""), |q| (q.1, q.2));
        let q = g.create_group(name).map_err(&err)?;
        attr(&q, "units", units).map_err(&err)?;
        attr(&q, "description", what).map_err(&err)?;
        vector(&q, "min", &range.min, units).map_err(&err)?;
        vector(&q, "max", &range.max, units).map_err(&err)?;
        vector(&q, "mean", &range.mean(e.samples), units).map_err(&err)?;
        dims.extend(
            ["min", "max", "mean"]
                .iter()
                .map(|w| (format!("ranges/{name}/{w}"), vec![Some("dynamic/arc")])),
        );
    }
    // Attached in one pass: `/dynamic/arc`'s list of uses rewritten once, not once per quantity.
    dimension_scales(&file, &dims).map_err(&err)?;
    // `/ranges` opens on its own too: its scale and each quantity's arrays as `<quantity>_min`,
    // `_max`, `_mean` (hard links to the same datasets); each quantity's group holds the scale.
    link_scales(&file, "ranges", "dynamic", &["arc"]).map_err(&err)?;
    for (name, _) in e.ranges() {
        link_scales(&file, &format!("ranges/{name}"), "dynamic", &["arc"]).map_err(&err)?;
        for w in ["min", "max", "mean"] {
            g.link_hard(&format!("{name}/{w}"), &format!("{name}_{w}"))
                .map_err(&err)?;
        }
    }
    file.flush().map_err(&err)?;
    Ok(())
}
