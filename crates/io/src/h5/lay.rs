//! A lay's `results.h5`: the statics of its start (`/static`) and `/lay`: the records on the
//! dimension `time` and each material node on the dimension `kp` (the distance along the pipe
//! from the initiation anchor), with units.

use super::*;

/// Writes `results.h5` of a lay (created anew).
pub fn write_lay(path: &Path, r: &catena::run::lay::LayRun) -> Result<(), AppError> {
    let err = h5err(path);
    let f = hdf5::File::create(path).map_err(&err)?;
    write_static_into(path, &f, &r.statics)?;
    let g = f.create_group("lay").map_err(&err)?;
    attr(
        &g,
        "convention",
        "records on `time`; nodes on `kp` (unstretched distance along the pipe from the initiation \
         anchor; `arc` from the pipe's last end); embedment of the invert positive down; NaN: not \
         laid (or not measured)",
    )
    .map_err(&err)?;
    num_attr(&g, "tower_angle", r.tower_angle).map_err(&err)?;
    let rec = &r.records;
    let series: [(&str, &[f64], &str); 9] = [
        ("time", &rec.time, "s"),
        ("paid_out", &rec.paid_out, "m"),
        (
            "vessel_x",
            &rec.vessel_x,
            "m (travel along +x from the start)",
        ),
        ("top_tension", &rec.top_tension, "N"),
        ("payout_rate", &rec.payout_rate, "m/s"),
        ("touchdown_x", &rec.touchdown_x, "m"),
        (
            "touchdown_arc",
            &rec.touchdown_arc,
            "m (unstretched, from the tower's exit)",
        ),
        ("window_nodes", &rec.window_nodes, "1 (nodes in the solve)"),
        (
            "sag_moment",
            &rec.sag_moment,
            "N·m (the most negative in the free span)",
        ),
    ];
    for (name, data, units) in series {
        vector(&g, name, data, units).map_err(&err)?;
    }
    let n = &r.nodes;
    let pos: Vec<f64> = r.positions.iter().map(|p| p[0]).collect();
    let posz: Vec<f64> = r.positions.iter().map(|p| p[1]).collect();
    let episodes: Vec<f64> = n.episodes.iter().map(|&e| f64::from(e)).collect();
    let landed: Vec<f64> = n.landed.iter().map(|&b| f64::from(u8::from(b))).collect();
    let per_node: [(&str, &[f64], &str); 10] = [
        ("kp", &n.kp, "m"),
        ("arc", &n.arc, "m"),
        ("as_laid_embedment", &n.as_laid, "m (positive down)"),
        ("laid_x", &n.laid_x, "m"),
        ("max_contact_force", &n.max_contact, "N/m"),
        ("episodes", &episodes, "1 (uplift-repenetration episodes)"),
        (
            "strength_factor",
            &n.strength,
            "1 (NaN without degradation)",
        ),
        (
            "landed_during_lay",
            &landed,
            "1 (1: off the seabed at the start; the steady part)",
        ),
        ("x", &pos, "m (at the end)"),
        ("z", &posz, "m (at the end)"),
    ];
    for (name, data, units) in per_node {
        vector(&g, name, data, units).map_err(&err)?;
    }
    let mut extra: Vec<&str> = Vec::new();
    if let Some(c) = &r.installation {
        vector(
            &g,
            "lcc_utilisation",
            &c.lcc_of_node,
            "1 (DNV-ST-F101 load-controlled combined loading, the largest in the free span; NaN: never in it)",
        )
        .map_err(&err)?;
        attr(&g, "installation_check", c.spec.code.name()).map_err(&err)?;
        extra.push("lcc_utilisation");
    }
    let framed = write_frames(&g, r).map_err(&err)?;
    let mut dims: Vec<(String, Vec<Option<&str>>)> = series[1..]
        .iter()
        .map(|(name, ..)| (format!("/lay/{name}"), vec![Some("/lay/time")]))
        .collect();
    dims.extend(
        per_node[1..]
            .iter()
            .map(|(name, ..)| (format!("/lay/{name}"), vec![Some("/lay/kp")])),
    );
    dims.extend(
        extra
            .iter()
            .map(|name| (format!("/lay/{name}"), vec![Some("/lay/kp")])),
    );
    for (name, two) in framed {
        let scales = if name == "contact_od" {
            vec![Some("/lay/kp")]
        } else if two {
            vec![Some("/lay/frames/time"), Some("/lay/kp")]
        } else {
            vec![Some("/lay/frames/time")]
        };
        dims.push((format!("/lay/frames/{name}"), scales));
    }
    dimension_scales(&f, &dims).map_err(&err)
}

/// `/lay/frames`, the animation's frames (`catena animate`): the whole pipe at every `every`-th
/// record (frames × kp, single precision, shuffled and deflated), the exit's track and each node's
/// contact diameter. The datasets written but `time`, and whether each is frames × kp.
fn write_frames(
    g: &hdf5::Group,
    r: &catena::run::lay::LayRun,
) -> hdf5::Result<Vec<(&'static str, bool)>> {
    let fr = &r.frames;
    if fr.is_empty() {
        return Ok(Vec::new());
    }
    let fg = g.create_group("frames")?;
    attr(
        &fg,
        "convention",
        "the whole pipe at every `every`-th record: frames x kp; penetration of the invert positive \
         down, negative above the mudline; seabed force and moment 0 off the solved window",
    )?;
    num_attr(&fg, "every", fr.every as f64)?;
    vector(&fg, "time", &fr.time, "s")?;
    let top_x: Vec<f64> = fr.exit.iter().map(|p| p[0]).collect();
    let top_z: Vec<f64> = fr.exit.iter().map(|p| p[1]).collect();
    vector(&fg, "top_x", &top_x, "m (the tower's exit)")?;
    vector(&fg, "top_z", &top_z, "m (the tower's exit)")?;
    let od: Vec<f64> = (0..r.full.nodes())
        .map(|k| catena::run::lay::frames::contact_od(&r.full, k))
        .collect();
    vector(&fg, "contact_od", &od, "m")?;
    let (nf, n) = (fr.len(), r.full.nodes());
    let deflate = hdf5::filters::deflate_available();
    for (name, data, units) in [
        ("x", &fr.x, "m"),
        ("z", &fr.z, "m"),
        ("penetration", &fr.penetration, "m (positive down)"),
        ("seabed_force", &fr.seabed_force, "N/m"),
        ("bending_moment", &fr.moment, "N·m (negative in a sag bend)"),
    ] {
        let b = fg
            .new_dataset::<f32>()
            .shape((nf, n))
            .chunk((nf.min(16), n));
        let b = if deflate { b.shuffle().deflate(4) } else { b };
        let ds = b.create(name)?;
        ds.write_raw(data)?;
        attr(&ds, "units", units)?;
    }
    Ok(vec![
        ("top_x", false),
        ("top_z", false),
        ("contact_od", false),
        ("x", true),
        ("z", true),
        ("penetration", true),
        ("seabed_force", true),
        ("bending_moment", true),
    ])
}
