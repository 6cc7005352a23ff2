//! An animated GIF of the touchdown zone: what `catena animate RESULTS.h5 --out tdz.gif` and
//! `catena.animate` draw from a run's records.
//!
//! Each frame has three panels, one above the other:
//! - **the whole line** (x right, z up, m), the static line faint, the touchdown-zone
//!   window outlined;
//! - **the touchdown zone**, larger, heights in true metres (exaggerated, the factor printed): the pipe
//!   as a band of its outer diameter `D`, its nodes coloured by penetration (m, positive down) or
//!   seabed force (N/m), the soil below the mudline, and the **trench as it forms**;
//! - **the bending moment** along the arc of the touchdown zone (N·m, negative in a sag bend): the
//!   frame's, and the least and greatest so far.
//!
//! The caption gives the time and the top's motion from its static position.
//!
//! **Geometry.** Node `i`'s invert is `z_i − D/2`; its penetration `p_i` is measured below the
//! mudline, so the mudline under it is `z_mud,i = z_i − D/2 + p_i` (taken from the first record,
//! where every node is at its static place). The trench under node `i` at record `k` is the deepest
//! penetration it has reached over **every** record up to `k` (not only the drawn frames),
//! `max(0, max_{j≤k} p_i(j))`: the soil the pipe has pushed aside does not come back in the
//! seabed law (the Randolph–Quiggin trench is plastic).
//!
//! **Frames.** At most `frames` frames, chosen evenly from the records (the first and the last
//! always). The window of the touchdown zone spans the touchdown points' travel over the whole
//! run, with half that travel (at least 30 `D` and 8 m) on the seabed's side and 10 `D` (at
//! least 3 m) on the other, at least 20 m in all, fixed for the whole animation. A lay's
//! (`Records::follow_touchdown`: its records are `/lay/frames`, every material point of the pipe a
//! node) follows the touchdown instead: `max(60 D, 15 m)` behind it and `max(20 D, 5 m)` ahead,
//! moving with it from frame to frame. Its heights are
//! true metres, exaggerated so that the deepest trench and a pipe fill the lower fifth of the
//! panel (the factor is printed on it).
//!
//! **Encoding.** A fixed palette (a 6×7×6 colour cube and four greys), so no per-frame colour
//! quantisation; each frame after the first stores only the rectangle of pixels that changed,
//! the unchanged ones transparent (GIF disposal "keep"). With the defaults the heave benchmark's
//! animation is a few hundred kilobytes.

use std::path::Path;

use catena::AppError;
use plotters::prelude::*;

use crate::plot::{init_fonts, padded};

mod frame;

use frame::{draw_frame, envelope_limits};

/// What the nodes are coloured by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Colour {
    /// The invert's penetration below the mudline, m (positive down).
    Penetration,
    /// The seabed's force on the pipe, N/m (positive up).
    SeabedForce,
}

impl Colour {
    /// `penetration` or `seabed_force` (also `seabed-force`).
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "penetration" => Some(Self::Penetration),
            "seabed_force" | "seabed-force" => Some(Self::SeabedForce),
            _ => None,
        }
    }
}

/// A run's records, row-major (`records × nodes` for the fields).
#[derive(Debug, Clone, Default)]
pub struct Records {
    /// Arc length of each node from the top, m.
    pub arc: Vec<f64>,
    /// Time of each record, s.
    pub time: Vec<f64>,
    /// Node positions, m (records × nodes).
    pub x: Vec<f64>,
    /// Node elevations, m (records × nodes).
    pub z: Vec<f64>,
    /// Penetration of the invert, m, positive down (records × nodes).
    pub penetration: Vec<f64>,
    /// Seabed force, N/m, positive up (records × nodes).
    pub seabed_force: Vec<f64>,
    /// Bending moment, N·m, negative in a sag bend (records × nodes).
    pub bending_moment: Vec<f64>,
    /// The top's position, m (records).
    pub top_x: Vec<f64>,
    /// The top's elevation, m (records).
    pub top_z: Vec<f64>,
    /// Outer diameter of each node's pipe, m.
    pub od: Vec<f64>,
    /// The touchdown zone's window follows the touchdown from frame to frame (a lay, whose
    /// touchdown travels the whole route) instead of spanning its travel over the run.
    pub follow_touchdown: bool,
}

/// How to animate.
#[derive(Debug, Clone, Copy)]
pub struct Options {
    /// The most frames.
    pub frames: usize,
    /// Frames a second.
    pub fps: f64,
    /// What the nodes are coloured by.
    pub colour: Colour,
    /// Image size, pixels.
    pub size: (u32, u32),
}

impl Default for Options {
    fn default() -> Self {
        Self {
            frames: 120,
            fps: 12.0,
            colour: Colour::Penetration,
            size: (800, 760),
        }
    }
}

/// What was written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Report {
    /// Frames drawn.
    pub frames: usize,
    /// The file's size, bytes.
    pub bytes: u64,
    /// Seconds of the run the animation covers.
    pub seconds: f64,
    /// The touchdown-zone panel's x range in the first frame and in the last, m (the same unless
    /// the window follows the touchdown: a lay).
    pub windows: [(f64, f64); 2],
}

impl Records {
    /// Records from a source of named arrays (the names of `results.h5`'s `/dynamic`: `arc`,
    /// `time`, `x`, `z`, `penetration`, `seabed_force`, `bending_moment`, `top_x`, `top_z`), with
    /// each node's diameter from `od` (given the arc lengths).
    pub fn from_named<E>(
        get: impl Fn(&str) -> Result<Vec<f64>, E>,
        od: impl FnOnce(&[f64]) -> Result<Vec<f64>, E>,
    ) -> Result<Self, E> {
        let arc = get("arc")?;
        Ok(Self {
            od: od(&arc)?,
            time: get("time")?,
            x: get("x")?,
            z: get("z")?,
            penetration: get("penetration")?,
            seabed_force: get("seabed_force")?,
            bending_moment: get("bending_moment")?,
            top_x: get("top_x")?,
            top_z: get("top_z")?,
            arc,
            follow_touchdown: false,
        })
    }

    fn n(&self) -> usize {
        self.arc.len()
    }

    fn records(&self) -> usize {
        self.time.len()
    }

    /// Checks the shapes (`what` names the source in errors).
    pub fn check(&self, what: &str) -> Result<(), AppError> {
        let (r, n) = (self.records(), self.n());
        let bad = |m: String| AppError::Run {
            file: what.to_string(),
            message: m,
        };
        if r == 0 || n < 2 {
            return Err(bad(format!(
                "nothing to animate: {r} records of {n} nodes (a dynamic run's records are needed)"
            )));
        }
        for (name, v, len) in [
            ("x", &self.x, r * n),
            ("z", &self.z, r * n),
            ("penetration", &self.penetration, r * n),
            ("seabed_force", &self.seabed_force, r * n),
            ("bending_moment", &self.bending_moment, r * n),
            ("top_x", &self.top_x, r),
            ("top_z", &self.top_z, r),
            ("outer diameter", &self.od, n),
        ] {
            if v.len() != len {
                return Err(bad(format!(
                    "{name} has {} values, expected {len} ({r} records × {n} nodes)",
                    v.len()
                )));
            }
        }
        Ok(())
    }

    fn row<'a>(&self, v: &'a [f64], k: usize) -> &'a [f64] {
        &v[k * self.n()..(k + 1) * self.n()]
    }
}

/// Each node's outer diameter, m, from a scene's text (as `results.h5` carries it in its `scene`
/// attribute) and the case file's path (its `case` attribute; its folder resolves the files the
/// scene names): the model's diameters, as the run used them. If the scene no longer reads there
/// (a table file moved), `line.od` for every node (`nodes` of them); `None` if neither is found.
/// For a `results.h5` that has `/line/contact_od` (every file written since `/line` exists),
/// `h5::read_animation` reads the diameters there instead, whatever became of the files.
pub fn diameters(text: &str, case: &str, nodes: usize) -> Option<Vec<f64>> {
    let files = catena::scene::DirResolver::beside(Path::new(case));
    match catena::scene::riser::RiserScene::parse(case, text, &files) {
        Ok(scene) if scene.model.node_od.len() == nodes => Some(scene.model.node_od),
        _ => text
            .parse::<toml::Table>()
            .ok()
            .and_then(|t| t.get("line")?.get("od")?.as_float())
            .map(|od| vec![od; nodes]),
    }
}

/// The records drawn: at most `budget`, evenly spaced, the first and the last always.
pub fn frame_records(records: usize, budget: usize) -> Vec<usize> {
    let budget = budget.max(2);
    if records <= budget {
        return (0..records).collect();
    }
    let mut v: Vec<usize> = (0..budget)
        .map(|k| ((k as f64) * (records - 1) as f64 / (budget - 1) as f64).round() as usize)
        .collect();
    v.dedup();
    v
}

/// The 256-colour palette: a 6×7×6 cube (252) and four greys.
fn palette() -> Vec<u8> {
    let mut p = Vec::with_capacity(768);
    for r in 0..6u32 {
        for g in 0..7u32 {
            for b in 0..6u32 {
                p.extend([(r * 51) as u8, (g * 255 / 6) as u8, (b * 51) as u8]);
            }
        }
    }
    for v in [64u8, 128, 192, 224] {
        p.extend([v, v, v]);
    }
    p
}

/// The palette index of an RGB colour (nearest in each channel of the cube; greys to the grey
/// ramp when nearer).
fn index_of(r: u8, g: u8, b: u8) -> u8 {
    let q = |v: u8, levels: u32| ((v as u32 * (levels - 1) + 127) / 255) as u8;
    let (ri, gi, bi) = (q(r, 6), q(g, 7), q(b, 6));
    let cube = ri * 42 + gi * 6 + bi;
    let (mx, mn) = (r.max(g).max(b), r.min(g).min(b));
    if mx - mn < 12 {
        // A grey: the cube's greys are coarse, the ramp adds four between them.
        let m = ((r as u32 + g as u32 + b as u32) / 3) as i32;
        let cube_grey = ri as i32 * 51;
        let mut best = (cube, (m - cube_grey).abs());
        for (k, v) in [64, 128, 192, 224].into_iter().enumerate() {
            let d = (m - v).abs();
            if d < best.1 {
                best = (252 + k as u8, d);
            }
        }
        return best.0;
    }
    cube
}

/// A colour ramp (dark blue, teal, green, yellow) at `f` in [0, 1].
fn ramp(f: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 4] = [
        (40.0, 30.0, 120.0),
        (30.0, 130.0, 140.0),
        (90.0, 190.0, 70.0),
        (250.0, 220.0, 30.0),
    ];
    let f = f.clamp(0.0, 1.0) * 3.0;
    let i = (f.floor() as usize).min(2);
    let t = f - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let c = |x: f64, y: f64| (x + (y - x) * t).round() as u8;
    RGBColor(c(a.0, b.0), c(a.1, b.1), c(a.2, b.2))
}

/// Writes the animation of `rec` to `path` (a `.gif`).
pub fn animate(path: &Path, rec: &Records, opts: &Options) -> Result<Report, AppError> {
    rec.check(&path.display().to_string())?;
    init_fonts();
    let err = |e: String| AppError::Plot {
        path: path.to_path_buf(),
        message: e,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| AppError::io(dir, e))?;
    }
    let (w, h) = opts.size;
    let n = rec.n();
    let nr = rec.records();
    let picks = frame_records(nr, opts.frames);
    let mut geo = Geometry::new(rec);
    if rec.follow_touchdown {
        geo.follow(rec, 0);
    }
    // The touchdown-zone panel's plotting area (the layout of `draw_frame`), for the exaggeration.
    let (pw, ph) = (w as f64 - 68.0, (h as f64 - 30.0) * 0.7 * 0.36 - 56.0);
    geo.exaggeration =
        ((geo.window.1 - geo.window.0) / pw) / ((geo.z_window.1 - geo.z_window.0) / ph.max(10.0));

    let file = std::fs::File::create(path).map_err(|e| AppError::io(path, e))?;
    let mut enc = gif::Encoder::new(
        std::io::BufWriter::new(file),
        w as u16,
        h as u16,
        &palette(),
    )
    .map_err(|e| err(e.to_string()))?;
    enc.set_repeat(gif::Repeat::Infinite)
        .map_err(|e| err(e.to_string()))?;
    let delay = (100.0 / opts.fps.max(0.1)).round().clamp(2.0, 6000.0) as u16;

    let mut rgb = vec![0u8; (w * h * 3) as usize];
    let mut prev: Option<Vec<u8>> = None;
    let mut trench = vec![0.0f64; n];
    let (mut m_lo, mut m_hi) = (vec![f64::INFINITY; n], vec![f64::NEG_INFINITY; n]);
    let mut next_record = 0;
    let mut windows = [geo.window; 2];
    for (f, &k) in picks.iter().enumerate() {
        // The trench and the moment's envelope over every record up to this one.
        while next_record <= k {
            let p = rec.row(&rec.penetration, next_record);
            let m = rec.row(&rec.bending_moment, next_record);
            for i in 0..n {
                trench[i] = trench[i].max(p[i]);
                m_lo[i] = m_lo[i].min(m[i]);
                m_hi[i] = m_hi[i].max(m[i]);
            }
            next_record += 1;
        }
        if rec.follow_touchdown {
            geo.follow(rec, k);
        }
        if f == 0 {
            windows[0] = geo.window;
        }
        windows[1] = geo.window;
        draw_frame(
            &mut rgb,
            (w, h),
            rec,
            &geo,
            opts,
            k,
            &trench,
            (&m_lo, &m_hi),
        )
        .map_err(err)?;
        let idx: Vec<u8> = rgb
            .chunks_exact(3)
            .map(|c| index_of(c[0], c[1], c[2]))
            .collect();
        let frame = match &prev {
            None => gif::Frame {
                width: w as u16,
                height: h as u16,
                buffer: std::borrow::Cow::Borrowed(&idx),
                delay,
                dispose: gif::DisposalMethod::Keep,
                ..gif::Frame::default()
            },
            Some(p) => changed_rect(p, &idx, w as usize, h as usize, delay),
        };
        enc.write_frame(&frame).map_err(|e| err(e.to_string()))?;
        prev = Some(idx);
    }
    drop(enc);
    let bytes = std::fs::metadata(path)
        .map_err(|e| AppError::io(path, e))?
        .len();
    Ok(Report {
        windows,
        frames: picks.len(),
        bytes,
        seconds: rec.time[nr - 1] - rec.time[0],
    })
}

/// The index of the transparent colour in frames after the first.
const TRANSPARENT: u8 = 255;

/// A frame holding only the rectangle where `now` differs from `prev`, unchanged pixels
/// transparent.
fn changed_rect(prev: &[u8], now: &[u8], w: usize, h: usize, delay: u16) -> gif::Frame<'static> {
    let (mut x0, mut x1, mut y0, mut y1) = (w, 0, h, 0);
    for y in 0..h {
        for x in 0..w {
            if prev[y * w + x] != now[y * w + x] {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    if x0 > x1 {
        // Nothing changed: one transparent pixel.
        (x0, x1, y0, y1) = (0, 0, 0, 0);
    }
    let (fw, fh) = (x1 - x0 + 1, y1 - y0 + 1);
    let mut buf = Vec::with_capacity(fw * fh);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let (a, b) = (prev[y * w + x], now[y * w + x]);
            buf.push(if a == b { TRANSPARENT } else { b });
        }
    }
    gif::Frame {
        left: x0 as u16,
        top: y0 as u16,
        width: fw as u16,
        height: fh as u16,
        buffer: std::borrow::Cow::Owned(buf),
        delay,
        dispose: gif::DisposalMethod::Keep,
        transparent: Some(TRANSPARENT),
        ..gif::Frame::default()
    }
}

/// What every frame shares: the mudline, the windows, the colour scale.
struct Geometry {
    /// The mudline under each node, m (from the first record).
    mud: Vec<f64>,
    /// The touchdown zone's window in x, m.
    window: (f64, f64),
    /// Its vertical extent, m.
    z_window: (f64, f64),
    /// How much the touchdown zone's heights are exaggerated (set in [`animate`] from the panel's
    /// size).
    exaggeration: f64,
    /// The nodes inside the window at the first record (the moment panel's arc range).
    arc_window: (f64, f64),
    /// The whole line's extent.
    whole: ((f64, f64), (f64, f64)),
    /// The colour scale's range, by [`Colour`] (penetration, seabed force).
    colour_range: [(f64, f64); 2],
    /// The moment axis over the whole run, kN·m.
    moment_range: (f64, f64),
}

impl Geometry {
    fn new(rec: &Records) -> Self {
        let n = rec.n();
        let nr = rec.records();
        let (x0, z0, p0) = (
            rec.row(&rec.x, 0),
            rec.row(&rec.z, 0),
            rec.row(&rec.penetration, 0),
        );
        let mud: Vec<f64> = (0..n).map(|i| z0[i] - 0.5 * rec.od[i] + p0[i]).collect();
        // The touchdown points' travel: the first node in contact at each record.
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..nr {
            let p = rec.row(&rec.penetration, k);
            let x = rec.row(&rec.x, k);
            if let Some(i) = (0..n).find(|&i| p[i] > 0.0) {
                lo = lo.min(x[i]);
                hi = hi.max(x[i]);
            }
        }
        // The pipe's diameter where it touches down (not a buoyancy section's elsewhere).
        let d = (0..n)
            .find(|&i| p0[i] > 0.0)
            .map_or_else(|| rec.od[n - 1], |i| rec.od[i])
            .max(1e-3);
        if !lo.is_finite() {
            // Nothing touches down: the window around the lowest node.
            let i = (0..n)
                .min_by(|&a, &b| z0[a].total_cmp(&z0[b]))
                .unwrap_or(n - 1);
            (lo, hi) = (x0[i], x0[i]);
        }
        // More room on the seabed's side (the trench), less above the suspended line.
        let travel = hi - lo;
        let (mut a, mut b) = (
            lo - (0.5 * travel).max(30.0 * d).max(8.0),
            hi + (10.0 * d).max(3.0),
        );
        if b - a < 20.0 {
            let c = 0.5 * (a + b);
            (a, b) = (c - 10.0, c + 10.0);
        }
        let inside: Vec<usize> = (0..n).filter(|&i| x0[i] >= a && x0[i] <= b).collect();
        let arc_window = match (inside.first(), inside.last()) {
            (Some(&i), Some(&j)) if j > i => (rec.arc[i], rec.arc[j]),
            _ => (rec.arc[0], rec.arc[n - 1]),
        };
        let mud_mean = if inside.is_empty() {
            mud[n - 1]
        } else {
            inside.iter().map(|&i| mud[i]).sum::<f64>() / inside.len() as f64
        };
        let (xs, zs) = (rec.x.iter(), rec.z.iter());
        let whole = (
            padded(
                xs.clone().copied().fold(f64::INFINITY, f64::min),
                xs.copied().fold(f64::NEG_INFINITY, f64::max),
            ),
            padded(
                zs.clone()
                    .copied()
                    .fold(f64::INFINITY, f64::min)
                    .min(mud_mean),
                zs.copied().fold(f64::NEG_INFINITY, f64::max),
            ),
        );
        let g = Self {
            mud,
            window: (a, b),
            // The deepest trench and a pipe below the mudline, four times that above.
            z_window: {
                let deepest = (0..nr)
                    .flat_map(|k| inside.iter().map(move |&i| rec.penetration[k * n + i]))
                    .fold(0.0f64, f64::max);
                let h = deepest + d;
                (mud_mean - 1.5 * h, mud_mean + 4.0 * h)
            },
            exaggeration: 1.0,
            arc_window,
            whole,
            colour_range: [(0.0, 1.0); 2],
            moment_range: (-1.0, 1.0),
        };
        let mut g = g;
        g.colour_range = [
            colour_limits(rec, g.window, Colour::Penetration),
            colour_limits(rec, g.window, Colour::SeabedForce),
        ];
        g.moment_range = envelope_limits(rec, g.arc_window).unwrap_or((-1.0, 1.0));
        g
    }

    /// The touchdown zone's window at record `k` when it follows the touchdown (a lay): the same
    /// width at every frame, `max(60 D, 15 m)` on the seabed's side of the touchdown point (the
    /// trench forming) and `max(20 D, 5 m)` above it; the arc window of the nodes inside it.
    fn follow(&mut self, rec: &Records, k: usize) {
        let (x, p) = (rec.row(&rec.x, k), rec.row(&rec.penetration, k));
        let n = rec.n();
        let Some(td) = (0..n).find(|&i| p[i] > 0.0) else {
            return;
        };
        let d = rec.od[td].max(1e-3);
        let (a, b) = (x[td] - (60.0 * d).max(15.0), x[td] + (20.0 * d).max(5.0));
        self.window = (a, b);
        let inside: Vec<usize> = (0..n).filter(|&i| x[i] >= a && x[i] <= b).collect();
        if let (Some(&i), Some(&j)) = (inside.first(), inside.last()) {
            if j > i {
                self.arc_window = (rec.arc[i], rec.arc[j]);
            }
        }
    }

    fn colour(&self, c: Colour) -> (f64, f64) {
        self.colour_range[match c {
            Colour::Penetration => 0,
            Colour::SeabedForce => 1,
        }]
    }
}

fn colour_limits(rec: &Records, (a, b): (f64, f64), c: Colour) -> (f64, f64) {
    let n = rec.n();
    let v = match c {
        Colour::Penetration => &rec.penetration,
        Colour::SeabedForce => &rec.seabed_force,
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..rec.records() {
        for i in 0..n {
            let x = rec.x[k * n + i];
            if x >= a && x <= b {
                lo = lo.min(v[k * n + i]);
                hi = hi.max(v[k * n + i]);
            }
        }
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let lo = match c {
        Colour::Penetration => 0.0,
        Colour::SeabedForce => lo.min(0.0),
    };
    (lo, hi.max(lo + 1e-9))
}
