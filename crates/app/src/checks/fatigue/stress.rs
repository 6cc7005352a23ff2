//! Stress recovery for fatigue: wall tension from effective tension, and the axial stress at the top
//! and bottom fibres of the pipe wall.
//!
//! **Wall tension** (the force the steel carries; OrcaFlex and SIMA define it the same way):
//!
//! ```text
//! T_w = T_e + p_i A_i − p_o A_o
//! p_o = ρ_w g (d − z)                     the sea's hydrostatic pressure at the node
//! p_i = p_op + ρ_c g (d − z)              the contents column, taken to the still water level [A],
//!                                          plus an operating pressure
//! ```
//!
//! with `z` the node's height above the mudline, `d` the water depth, `A_o = πD²/4`, `A_i = πD_i²/4`.
//! For the paper's riser (contents 726 kg/m³, no operating pressure) `T_w − T_e ≈ −235 kN` at the
//! seabed.
//!
//! **Fibre stress** (2D: in-plane bending makes the top and bottom of the section the extremes), at
//! radius `r` (`D/2` outer, `D_i/2` inner, the girth weld's root):
//!
//! ```text
//! σ_top = T_w/A − M·r/I,     σ_bottom = T_w/A + M·r/I
//! ```
//!
//! ("top" is the fibre on the upper side of the pipe: a sag bend, M < 0, stretches it). Stresses are
//! taken **at the nodes**, from the nodal tension and moment (the means of the adjacent elements'
//! end values): the envelopes and results are nodal, the moment is continuous there, and the
//! touchdown-zone mesh is fine enough (0.5 m against a boundary layer of ~9 m) that the element
//! mid-points would add nothing. The SCF and the S-N curve's thickness correction multiply the stress
//! ranges (`sn::miner`), not the stresses.

use serde::{Deserialize, Serialize};

/// A fibre of the section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Fibre {
    /// At the outer radius.
    Outer,
    /// At the inner radius (the girth weld's root).
    Inner,
}

impl Fibre {
    /// The name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Fibre::Outer => "outer",
            Fibre::Inner => "inner",
        }
    }
}

/// The pipe's section and contents, what stress recovery needs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PipeSection {
    /// Outer diameter, m.
    pub od: f64,
    /// Wall thickness, m.
    pub wall: f64,
    /// Contents density, kg/m³ (0 for an empty pipe).
    pub contents_density: f64,
    /// Operating (internal) pressure at the still water level, Pa.
    pub internal_pressure: f64,
    /// Sea water density, kg/m³.
    pub water_density: f64,
    /// Gravity, m/s².
    pub gravity: f64,
    /// Water depth, m.
    pub water_depth: f64,
}

impl PipeSection {
    /// Steel area `π(D² − D_i²)/4`, m².
    pub fn area(&self) -> f64 {
        let id = self.od - 2.0 * self.wall;
        std::f64::consts::PI / 4.0 * (self.od * self.od - id * id)
    }

    /// Second moment of area `π(D⁴ − D_i⁴)/64`, m⁴.
    pub fn inertia(&self) -> f64 {
        let id = self.od - 2.0 * self.wall;
        std::f64::consts::PI / 64.0 * (self.od.powi(4) - id.powi(4))
    }

    /// The radius of a fibre, m.
    pub fn radius(&self, f: Fibre) -> f64 {
        match f {
            Fibre::Outer => 0.5 * self.od,
            Fibre::Inner => 0.5 * self.od - self.wall,
        }
    }

    /// `T_w − T_e = p_i A_i − p_o A_o` at height `z` above the mudline, N.
    pub fn wall_minus_effective(&self, z: f64) -> f64 {
        let pi = std::f64::consts::PI;
        let id = self.od - 2.0 * self.wall;
        let head = (self.water_depth - z).max(0.0);
        let p_o = self.water_density * self.gravity * head;
        let p_i = self.internal_pressure + self.contents_density * self.gravity * head;
        p_i * pi / 4.0 * id * id - p_o * pi / 4.0 * self.od * self.od
    }

    /// The axial stresses `(top, bottom)` at a fibre, Pa, from the effective tension `te` (N), the
    /// bending moment `m` (N·m, negative = sag) and the height `z` (m).
    pub fn fibre_stresses(&self, f: Fibre, te: f64, m: f64, z: f64) -> (f64, f64) {
        let axial = (te + self.wall_minus_effective(z)) / self.area();
        let bending = m * self.radius(f) / self.inertia();
        (axial - bending, axial + bending)
    }
}
