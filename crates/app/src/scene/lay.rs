//! `[lay]`: the pipe's installation by J-lay (the run in `crate::run::lay`), checked.
//!
//! The scene's line is the pipe in the water at the start: from the tower's exit (`[ends]` top) to
//! the initiation anchor (`[ends]` anchor), its static configuration the lay's start. The rest of
//! the pipe (`pipe_length` less the line's length) waits on the vessel along the tower. The vessel
//! moves along +x (away from the anchor) at `speed`; the pipe is paid out at the vessel's speed
//! (`payout = "position"`) or by a tensioner that holds `target_tension` at the top
//! (`payout = "tension"`: the payout rate follows `V + gain·(T − T_target)` with the time constant
//! `time_constant`, limited to ±`max_payout_rate`).
//! With `lay_down = true`, the pipe's end is lowered to the seabed on the A&R wire of `[lay.wire]`
//! (a section of the `[[line_type]]` its `type` names, or its own keys) once it has left the tower,
//! the vessel keeping the lay's speed (or, with `station = true`, holding station for the last of
//! the lowering). Every key is SI: m, s, N, N·m/rad; the tower angle
//! in degrees from the vertical.

use super::checks::positive;
use super::invalid;
use super::sections;
use super::tables::{LayTable, PayoutKey, RiserFile, TowerKey, WireTable};
use crate::error::SceneError;
use catena_fe::beam::Section;
use catena_fe::model::Segment;

/// How the tower holds the pipe at its exit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tower {
    /// Position and angle held.
    Clamped,
    /// Position held, the angle on a rotational spring of this stiffness, N·m/rad.
    Hinged(f64),
}

/// How the pipe is paid out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Payout {
    /// At the vessel's speed.
    Position,
    /// By a tensioner: the rate follows `V + gain·(T − target)` with a time constant, within
    /// ±`max_rate`.
    Tension {
        /// The top tension it holds, N (`None`: the static top tension).
        target: Option<f64>,
        /// m/s per N.
        gain: f64,
        /// The largest payout (or pay-in) rate, m/s.
        max_rate: f64,
        /// The time constant with which the rate follows the demand, s (a tensioner's response).
        time_constant: f64,
    },
}

/// A checked `[lay]` table.
#[derive(Debug, Clone, PartialEq)]
pub struct LaySpec {
    /// The vessel's speed along +x, m/s.
    pub speed: f64,
    /// The lay ends when this much pipe has been paid out, m (`None`: at `[dynamic] duration`).
    pub length: Option<f64>,
    /// The whole pipe, m: the line in the water at the start and the pipe on the vessel.
    pub pipe_length: f64,
    /// The tower's angle from the vertical, rad (`None`: the static departure angle).
    pub tower_angle: Option<f64>,
    /// How the tower holds the pipe.
    pub tower: Tower,
    /// How the pipe is paid out.
    pub payout: Payout,
    /// The length of the elements of the pipe on the vessel, m (`None`: the line's top element's).
    pub element_length: Option<f64>,
    /// A node may be frozen when it moved less than this over the last payout of one element, m.
    pub freeze_tolerance: f64,
    /// ... and lies at least this far behind the touchdown point (in x), m.
    pub freeze_behind: f64,
    /// The vessel's speed rises from 0 to `speed` over this time (quintic), s.
    pub ramp: f64,
    /// The lay-down at the end, if the scene asks for one: the wire the pipe's end is lowered on.
    pub lay_down: Option<Wire>,
}

/// The abandonment and recovery wire of a lay-down (`[lay.wire]`), SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wire {
    /// Its length, element length and properties: one section of its `[[line_type]]`, or of its
    /// own keys (`Segment::uniform`: the three diameters its `od`, `[hydrodynamics]`' coefficients).
    pub segment: Segment,
    /// Whether the vessel comes to rest and holds station for the last of the lowering (else it
    /// keeps the lay's speed until the pipe's end rests, as lay-downs are done: the sag bend keeps
    /// its tension).
    pub station: bool,
    /// With `station`: the pipe end's height above the mudline, m, below which the vessel holds
    /// station; it slows from twice this height (`None`: a quarter of the pipe's bending length
    /// `λ = (EI/W')^(1/3)`, set by the run).
    pub station_height: Option<f64>,
}

/// Default `time_constant` of a tensioner, s.
pub const TIME_CONSTANT: f64 = 5.0;

/// Default `ramp`, s.
pub const RAMP: f64 = 20.0;

/// Default `freeze_tolerance`, m.
pub const FREEZE_TOLERANCE: f64 = 1e-3;

/// The tables a lay run does not take (yet): each would need the line of a fixed length.
const NOT_WITH_LAY: [&str; 7] = [
    "motion",
    "flexjoint",
    "fatigue",
    "extremes",
    "gauge",
    "attachment",
    "section",
];

/// `[lay]`, checked against the rest of the scene.
pub(super) fn lay_spec(file: &str, raw: &RiserFile) -> Result<Option<LaySpec>, SceneError> {
    let Some(l) = &raw.lay else { return Ok(None) };
    let Some(d) = &raw.dynamic else {
        return Err(invalid(
            file,
            "lay",
            "a [dynamic] table as well (the lay is a dynamic run: its time step and duration)",
        ));
    };
    for (present, key) in [
        (raw.motion.is_some(), NOT_WITH_LAY[0]),
        (raw.flexjoint.is_some(), NOT_WITH_LAY[1]),
        (raw.fatigue.is_some(), NOT_WITH_LAY[2]),
        (raw.extremes.is_some(), NOT_WITH_LAY[3]),
        (!raw.gauge.is_empty(), NOT_WITH_LAY[4]),
        (!raw.attachment.is_empty(), NOT_WITH_LAY[5]),
        (!raw.section.is_empty(), NOT_WITH_LAY[6]),
    ] {
        if present {
            return Err(invalid(
                file,
                key,
                "no such table in a scene with [lay] (the lay moves the top itself and holds the \
                 angle with `lay.tower`; fatigue, extremes, gauges, bodies and sections of a line \
                 of fixed length are not taken by a lay run)",
            ));
        }
    }
    if let Some(c) = raw
        .design_check
        .as_ref()
        .filter(|c| c.code != "dnv-st-f101")
    {
        return Err(invalid(
            file,
            "design_check.code",
            format!(
                "\"dnv-st-f101\" in a scene with [lay] (the installation check), got \"{}\"",
                c.code
            ),
        ));
    }
    if raw.seabed.as_ref().is_some_and(|s| !s.zone.is_empty()) {
        return Err(invalid(
            file,
            "seabed.zone",
            "no soil zones in a scene with [lay] (a lay run has one soil along the route)",
        ));
    }
    if !(l.speed.is_finite() && l.speed > 0.0) {
        return Err(invalid(
            file,
            "lay.speed",
            format!(
                "the vessel's speed along the route, m/s > 0 (got {})",
                l.speed
            ),
        ));
    }
    let in_water = raw.line.length;
    let lay_down = lay_down(file, raw, l)?;
    if lay_down.is_some() && l.pipe_length.is_none_or(|v| v <= in_water) {
        return Err(invalid(
            file,
            "lay.pipe_length",
            format!(
                "the whole pipe's length for a lay-down, longer than the line in the water \
                 ({in_water} m): its end is what is lowered"
            ),
        ));
    }
    let pipe_length = pipe_length(file, l, (in_water, d.duration), lay_down.is_some())?;
    let tower_angle = match l.tower_angle_deg {
        Some(a) if (0.0..90.0).contains(&a) => Some(a.to_radians()),
        Some(a) => {
            return Err(invalid(
                file,
                "lay.tower_angle_deg",
                format!("an angle from the vertical in [0, 90) degrees (got {a})"),
            ))
        }
        None => None,
    };
    let tower = match (l.tower, l.tower_stiffness) {
        (TowerKey::Clamped, None) => Tower::Clamped,
        (TowerKey::Clamped, Some(_)) => {
            return Err(invalid(
                file,
                "lay.tower_stiffness",
                "no stiffness with a clamped tower (set `tower = \"hinged\"` for a spring)",
            ))
        }
        (TowerKey::Hinged, Some(k)) => Tower::Hinged(positive(
            file,
            "lay.tower_stiffness",
            k,
            "a rotational stiffness in N·m/rad",
        )?),
        (TowerKey::Hinged, None) => {
            return Err(invalid(
                file,
                "lay.tower_stiffness",
                "a rotational stiffness in N·m/rad for a hinged tower",
            ))
        }
    };
    let payout = payout(file, l)?;
    let element_length = l
        .element_length
        .map(|h| positive(file, "lay.element_length", h, "an element length in m"))
        .transpose()?;
    let freeze_tolerance = positive(
        file,
        "lay.freeze_tolerance",
        l.freeze_tolerance.unwrap_or(FREEZE_TOLERANCE),
        "a distance in m",
    )?;
    let freeze_behind = l
        .freeze_behind
        .unwrap_or(0.25 * raw.environment.water_depth);
    if !(freeze_behind.is_finite() && freeze_behind >= 0.0) {
        return Err(invalid(
            file,
            "lay.freeze_behind",
            format!("a distance behind the touchdown in m >= 0 (got {freeze_behind})"),
        ));
    }
    let ramp = l.ramp.unwrap_or(RAMP);
    if !(ramp.is_finite() && ramp >= 0.0) {
        return Err(invalid(
            file,
            "lay.ramp",
            format!("a ramp time in s >= 0 (got {ramp})"),
        ));
    }
    Ok(Some(LaySpec {
        speed: l.speed,
        length: l.length,
        pipe_length,
        tower_angle,
        tower,
        payout,
        element_length,
        freeze_tolerance,
        freeze_behind,
        ramp,
        lay_down,
    }))
}

/// `pipe_length`, checked: at least the line in the water and the lay (not for a lay-down, which
/// lays the whole pipe), or by default the line, 1.5 × the lay and 20 m.
fn pipe_length(
    file: &str,
    l: &LayTable,
    (in_water, duration): (f64, f64),
    lay_down: bool,
) -> Result<f64, SceneError> {
    let laid = match l.length {
        Some(v) => positive(file, "lay.length", v, "a length of pipe to lay in m")?,
        None => l.speed * duration,
    };
    Ok(match l.pipe_length {
        Some(v) => {
            positive(file, "lay.pipe_length", v, "the whole pipe's length in m")?;
            if v < in_water + laid && !lay_down {
                return Err(invalid(
                    file,
                    "lay.pipe_length",
                    format!(
                        "a pipe at least as long as the line in the water ({in_water} m) plus the \
                         lay ({laid:.1} m{}), got {v} m",
                        if l.length.is_some() {
                            ", lay.length"
                        } else {
                            ": lay.speed × dynamic.duration"
                        }
                    ),
                ));
            }
            v
        }
        // Room for a tensioner that pays out faster than the vessel moves.
        None => in_water + 1.5 * laid + 20.0,
    })
}

/// `lay_down` and `[lay.wire]`, checked: the wire's properties from its keys or from the
/// `[[line_type]]` its `type` names (a lay scene's only use of `[[line_type]]`).
fn lay_down(file: &str, raw: &RiserFile, l: &LayTable) -> Result<Option<Wire>, SceneError> {
    let wire_type = l.wire.as_ref().and_then(|w| w.line_type.as_deref());
    // (A `type` that names no line type is reported as such below.)
    let named = wire_type.is_none_or(|n| raw.line_type.iter().any(|t| t.name == n));
    let other = raw
        .line_type
        .iter()
        .enumerate()
        .find(|(_, t)| Some(t.name.as_str()) != wire_type || !l.lay_down);
    if let (true, Some((i, t))) = (named, other) {
        return Err(invalid(
            file,
            format!("line_type[{i}]"),
            format!(
                "in a scene with [lay], a [[line_type]] only for the lay-down's A&R wire \
                 (`[lay.wire] type = \"{}\"`; the pipe is [line]'s)",
                t.name
            ),
        ));
    }
    let w = match (l.lay_down, &l.wire) {
        (false, None) => return Ok(None),
        (false, Some(_)) => {
            return Err(invalid(
                file,
                "lay.lay_down",
                "`lay_down = true` with a [lay.wire] (the wire is for the lay-down)",
            ))
        }
        (true, None) => {
            return Err(invalid(
                file,
                "lay.wire",
                "a [lay.wire] table for the lay-down: the wire the pipe's end is lowered on \
                 (length, and a [[line_type]]'s name as `type` or od, ea, submerged_weight, mass)",
            ))
        }
        (true, Some(w)) => w,
    };
    let p = |key: &str, v: f64, what: &str| positive(file, &format!("lay.wire.{key}"), v, what);
    let length = p("length", w.length, "a length in m")?;
    let element_length = p(
        "element_length",
        w.element_length.unwrap_or(1.0),
        "an element length in m",
    )?;
    let segment = match &w.line_type {
        Some(name) => wire_segment(file, raw, w, name, length, element_length)?,
        None => {
            let need = |key: &str, v: Option<f64>, what: &str| match v {
                Some(v) => p(key, v, what),
                None => Err(invalid(
                    file,
                    format!("lay.wire.{key}"),
                    format!("{what} (or `type`: a [[line_type]]'s name for the wire)"),
                )),
            };
            let od = need("od", w.od, "a diameter in m")?;
            let ea = need("ea", w.ea, "an axial stiffness in N")?;
            let ei = p(
                "ei",
                w.ei.unwrap_or(1e-6 * ea),
                "a bending stiffness in N·m²",
            )?;
            let weight = need("submerged_weight", w.submerged_weight, "a weight in N/m")?;
            let mass = need("mass", w.mass, "a mass in kg/m")?;
            Segment::uniform(length, element_length, Section { ea, ei }, weight, mass, od)
        }
    };
    Ok(Some(Wire {
        segment,
        station: w.station,
        station_height: match (w.station_height, w.station) {
            (None, _) => None,
            (Some(h), true) => Some(p("station_height", h, "a height above the mudline in m")?),
            (Some(_), false) => return Err(invalid(
                file,
                "lay.wire.station_height",
                "`station = true` with a station height (the vessel keeps its speed without it)",
            )),
        },
    }))
}

/// The wire as one section of the `[[line_type]]` named `name` (checked as any line type; no
/// property key of its own beside `type`, and no taper).
fn wire_segment(
    file: &str,
    raw: &RiserFile,
    w: &WireTable,
    name: &str,
    length: f64,
    element_length: f64,
) -> Result<Segment, SceneError> {
    let own = [
        ("od", w.od.is_some()),
        ("ea", w.ea.is_some()),
        ("ei", w.ei.is_some()),
        ("submerged_weight", w.submerged_weight.is_some()),
        ("mass", w.mass.is_some()),
    ];
    if let Some((k, _)) = own.iter().find(|(_, given)| *given) {
        return Err(invalid(
            file,
            format!("lay.wire.{k}"),
            format!(
                "no property key beside `type` (the wire's properties are line type \"{name}\"'s)"
            ),
        ));
    }
    let Some(k) = raw.line_type.iter().position(|t| t.name == name) else {
        return Err(invalid(
            file,
            "lay.wire.type",
            format!("the name of a [[line_type]] (got \"{name}\", and none has it)"),
        ));
    };
    let t = &raw.line_type[k];
    sections::line_type(file, raw, k, t)?;
    if t.od_end.is_some() || t.wall_end.is_some() {
        return Err(invalid(
            file,
            format!("line_type[{k}].od_end"),
            "no taper for the A&R wire (one section of constant properties)",
        ));
    }
    let mut segs = sections::section_segments(file, raw, k, t, length, element_length)?;
    Ok(segs.remove(0))
}

fn payout(file: &str, l: &LayTable) -> Result<Payout, SceneError> {
    let keys = [
        ("lay.target_tension", l.target_tension),
        ("lay.gain", l.gain),
        ("lay.max_payout_rate", l.max_payout_rate),
        ("lay.time_constant", l.time_constant),
    ];
    match l.payout {
        PayoutKey::Position => {
            if let Some((key, _)) = keys.iter().find(|(_, v)| v.is_some()) {
                return Err(invalid(
                    file,
                    *key,
                    "no tensioner key with `payout = \"position\"` (set `payout = \"tension\"`)",
                ));
            }
            Ok(Payout::Position)
        }
        PayoutKey::Tension => {
            let need = |key: &str, v: Option<f64>, what: &str| {
                let v = v.ok_or_else(|| {
                    invalid(file, key, format!("{what} for `payout = \"tension\"`"))
                })?;
                positive(file, key, v, what)
            };
            let target = l
                .target_tension
                .map(|t| positive(file, "lay.target_tension", t, "a top tension in N"))
                .transpose()?;
            Ok(Payout::Tension {
                target,
                gain: need("lay.gain", l.gain, "a gain in (m/s)/N")?,
                max_rate: need(
                    "lay.max_payout_rate",
                    l.max_payout_rate,
                    "a payout rate limit in m/s",
                )?,
                time_constant: positive(
                    file,
                    "lay.time_constant",
                    l.time_constant.unwrap_or(TIME_CONSTANT),
                    "a time constant in s",
                )?,
            })
        }
    }
}
