//! What the commands read back from a results file: the extremes' channels and the animation's
//! records.

use super::*;

/// A channel's name, design end and record.
pub type Channel = (String, catena::checks::extremes::Tail, Vec<f64>);

/// The channels of `catena extremes` from a results file's records: `/dynamic/time` and, for each
/// name, its record: `top_tension`, `least_tension` (the least of each record's effective
/// tensions), `sag_moment` (the least moment), `utilisation` (the largest of
/// `/design_check/utilisation`'s row), `utilisation_at_critical` and `moment_at_critical` (at the
/// node of the largest utilisation over the run; the moment's least where the static moment is a
/// sag, else its greatest), `gauge:NAME[:max|:min]` (the gauge's moment). Each with its
/// design end; no names: the first three and, with a design check, `utilisation`. A name the file
/// cannot give is an error naming the file and the channel.
pub fn read_extreme_channels(
    path: &Path,
    names: &[String],
) -> Result<(Vec<f64>, Vec<Channel>), AppError> {
    use catena::checks::extremes::Tail;
    let err = h5err(path);
    let file = hdf5::File::open(path).map_err(&err)?;
    let read = |name: &str| -> Result<Vec<f64>, AppError> {
        file.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .map_err(&err)
    };
    let time = read("dynamic/time")?;
    let nt = time.len();
    let mut defaults: Vec<String> = ["top_tension", "least_tension", "sag_moment"]
        .map(String::from)
        .to_vec();
    if file.link_exists("design_check") {
        defaults.push("utilisation".into());
    }
    let names = if names.is_empty() {
        &defaults[..]
    } else {
        names
    };
    let rows = |name: &str, pick: fn(&[f64]) -> f64| -> Result<Vec<f64>, AppError> {
        let v = read(name)?;
        let n = v.len() / nt.max(1);
        Ok(v.chunks_exact(n.max(1)).map(pick).collect())
    };
    let least = |r: &[f64]| r.iter().copied().fold(f64::INFINITY, f64::min);
    let most = |r: &[f64]| r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let mut out = Vec::new();
    for name in names {
        let missing = |what: &str| AppError::Run {
            file: path.display().to_string(),
            message: format!("--channel {name}: {what}"),
        };
        let (tail, v) = match name.as_str() {
            "top_tension" => (Tail::Max, read("dynamic/top_tension")?),
            "least_tension" => (Tail::Min, rows("dynamic/effective_tension", least)?),
            "sag_moment" => (Tail::Min, rows("dynamic/bending_moment", least)?),
            "utilisation" => {
                if !file.link_exists("design_check") {
                    return Err(missing(
                        "the file has no /design_check (the run had no [design_check])",
                    ));
                }
                (Tail::Max, rows("design_check/utilisation", most)?)
            }
            "utilisation_at_critical" | "moment_at_critical" => {
                // The critical node: the largest utilisation over the run (every step).
                if !file.link_exists("design_check/utilisation_max") {
                    return Err(missing(
                        "the file has no /design_check/utilisation_max (the run had no [design_check])",
                    ));
                }
                let umax = read("design_check/utilisation_max")?;
                let i = umax
                    .iter()
                    .enumerate()
                    .fold(0, |b, (i, v)| if *v > umax[b] { i } else { b });
                let column = |name: &str| -> Result<Vec<f64>, AppError> {
                    let v = read(name)?;
                    let n = v.len() / nt.max(1);
                    Ok(v.chunks_exact(n.max(1)).map(|r| r[i]).collect())
                };
                if name == "utilisation_at_critical" {
                    (Tail::Max, column("design_check/utilisation")?)
                } else {
                    // A sag (negative static moment) is a least extreme, a hog a greatest.
                    let m0 = read("static/bending_moment")?;
                    let tail = if m0.get(i).is_some_and(|m| *m < 0.0) {
                        Tail::Min
                    } else {
                        Tail::Max
                    };
                    (tail, column("dynamic/bending_moment")?)
                }
            }
            other => {
                let g = other.strip_prefix("gauge:").ok_or_else(|| {
                    missing("not a channel: top_tension, least_tension, sag_moment, utilisation, utilisation_at_critical, moment_at_critical or gauge:NAME[:max]")
                })?;
                let (g, tail) = match g.strip_suffix(":max") {
                    Some(g) => (g, Tail::Max),
                    None => (g.strip_suffix(":min").unwrap_or(g), Tail::Min),
                };
                let ds = format!("dynamic/gauges/{g}/bending_moment");
                if !file.link_exists(&format!("dynamic/gauges/{g}")) {
                    return Err(missing(&format!("the file has no gauge `{g}`")));
                }
                (tail, read(&ds)?)
            }
        };
        if v.len() != nt {
            return Err(missing("its record is not as long as /dynamic/time"));
        }
        out.push((name.clone(), tail, v));
    }
    Ok((time, out))
}

/// A run's records for the animation ([`crate::animate`]): `/dynamic`'s fields and each node's
/// outer diameter, `/line/contact_od` (in a file written before `/line` existed: from the scene
/// the file carries, [`crate::animate::diameters`]).
pub fn read_animation(path: &Path) -> Result<crate::animate::Records, AppError> {
    let err = h5err(path);
    let file = hdf5::File::open(path).map_err(&err)?;
    let bad = |m: String| AppError::Run {
        file: path.display().to_string(),
        message: m,
    };
    let read = |name: &str| -> Result<Vec<f64>, AppError> {
        file.dataset(name)
            .and_then(|d| d.read_raw::<f64>())
            .map_err(&err)
    };
    if file.link_exists("lay") {
        // A lay: its frames (the whole pipe, every material point a node), the window following
        // the touchdown.
        if !file.link_exists("lay/frames") {
            return Err(bad(
                "a lay's results without /lay/frames (written by a build before the lay's \
                 animation): lay.png and /lay have its touchdown's track"
                    .into(),
            ));
        }
        let mut rec = crate::animate::Records::from_named(
            |name| match name {
                "arc" => read("lay/arc"),
                "bending_moment" => read("lay/frames/bending_moment"),
                _ => read(&format!("lay/frames/{name}")),
            },
            |_| read("lay/frames/contact_od"),
        )?;
        rec.follow_touchdown = true;
        return Ok(rec);
    }
    if !file.link_exists("dynamic") {
        return Err(bad(
            "no /dynamic group: a dynamic run's results.h5 is needed (`catena run` with a \
             [dynamic] table)"
                .into(),
        ));
    }
    let scene: VarLenUnicode = file
        .attr("scene")
        .and_then(|a| a.read_scalar())
        .map_err(&err)?;
    let case: VarLenUnicode = file
        .attr("case")
        .and_then(|a| a.read_scalar())
        .map_err(&err)?;
    crate::animate::Records::from_named(
        |name| read(&format!("dynamic/{name}")),
        |arc| {
            // Each node's diameter as the run used it (`/line/contact_od`); a file written before
            // `/line` existed: from the scene it carries.
            if file.link_exists("line/contact_od") {
                let od = read("line/contact_od")?;
                if od.len() == arc.len() {
                    return Ok(od);
                }
            }
            crate::animate::diameters(scene.as_str(), case.as_str(), arc.len()).ok_or_else(|| {
                bad(
                    "the scene in the `scene` attribute gives no pipe diameter (line.od or line \
                     types)"
                        .into(),
                )
            })
        },
    )
}
