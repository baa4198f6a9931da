//! The elastic interlayer between belt and drums (eqs. 40–41; docs/fem-shell.md §7
//! (S13), §8): normal potential V_γ = ½∬_{γ>0} P γ² J and tangential potential
//! V_⊥ = ½∬_{γ>0} P_⊥ u·u J per dσ dζ (J = ∂σS, per reference area), with the gap γ to a
//! possibly tilted drum axis and the tangential deformation u carried as per-point
//! history ([`Interlayer::slip`], [`Interlayer::advance`]).
//!
//! Everything here is in the global frame (x, y in the drawing plane, z along the
//! untilted drum axes = k). The kernel ([`super::kernel::Shell`]) forms the position r
//! of (S1) and the material offset δs of (S13) from its point values and hands them in.
//!
//! **History state per point** ([`STATE`] values): u (3), the converged position r_n as
//! (ν_n, z_n) off the contour (and a spare 0), its material derivative ∂̊_s r_n by its
//! components on the contour frame (t_g, n_g, k) (3), the periodic part S̃_n of the
//! material coordinate, and a contact flag (1: the point was in contact in the converged
//! configuration), advected like the rest, and, kept by each point, its committed gap,
//! its share of the committed contact ([`CONTACT_SHARE`]), its distance from the
//! contact's entry ([`CONTACT_ENTRY`]), the belt's position and S̃_n at that entry
//! ([`ENTRY_RECORD`]) and its own S̃_n and (ν_n, z_n). V_⊥ acts in the point's committed
//! contact, times the share: with the foot's flag alone a point kept its spring for up to
//! cΔt past the exit (the release lag, first order in Δt), and with a whole point's
//! weight on or off the contact's edges moved by whole points (first order in h;
//! docs/fem-shell.md §7 (b)). u = 0 where contact is established (the brush model
//! [T l.329]): material that entered the contact during the step carries the relative
//! motion since its entry ([`Interlayer::slip`], [`Interlayer::entered`]; §7 (g)); a
//! point outside the committed contact starts from u = 0, and the initial zeros of the
//! core are such states (the configuration is recorded by
//! [`crate::analysis::time_stepping::TimeStepping::prime_history`]).
//! The core advects the state by the belt speed c (`belt_speed`); the density then
//! reads at σ the state of σ_r = σ − cΔt, and (S13) corrects the foot by the material
//! offset δs = S_{n+1}(σ) − S_n(σ_r) (= S̃ − S̃_n in the gauge transported with the drums,
//! docs/fem-shell.md (S2′)):
//!
//!   r_n(foot) ≈ r_n(σ_r) + ∂̊_s r_n(σ_r) δs   ([`Interlayer::foot`]),
//!   u_{n+1} = [M_i ũ + r_{n+1} − r_n(foot) − (M_i r_n(foot) − r_n(foot))]_⊥,
//!
//! M_i the drum's rigid motion over the step (tilt and spin, [`Drum::motion`]), ⊥ the
//! projection on the drum's tangent plane at r_{n+1}. u is the layer's shear, a vector
//! in the drum's tangent plane that the drum carries along: M_i turns ũ with it. A belt that rolls rigidly with the
//! drum has u ≡ 0 exactly (the drum point under the material point is moved, not a
//! linearised velocity). The gradient of ũ along the foot offset is neglected
//! (second order: δs is the deviation of the material's travel from cΔt). r_n and
//! ∂̊_s r_n are interpolated by the advection as (ν, z) and frame components and rebuilt
//! with the exact contour at σ_r: interpolating the global position across a
//! line/arc transition makes an O(h³/R²) position error that would enter u directly.

use crate::quadrature::Rule;
use crate::Scalar;

use super::membrane::dot;
use super::ShellError;

/// Number of history values per interlayer point.
pub const STATE: usize = 21;
/// Offsets in the state: u, r_n, ∂̊_s r_n (three each), S̃_n, the contact flag (advected:
/// the foot's), the point's own gap, share of the contact, distance from its entry, the
/// belt's position and S̃_n at that entry, and its own S̃_n and (ν_n, z_n) (kept).
const U: usize = 0;
const POSITION: usize = 3;
const SLOPE: usize = 6;
const MATERIAL: usize = 9;
const CONTACT: usize = 10;
/// The point's committed gap γ_n to the drum nearest to it ([`Interlayer::nearest_gap`],
/// > 0 in contact): the indicator of the cut, set by the core
/// ([`crate::surface::assembly::CutHistory`]). Kept.
pub const CONTACT_GAP: usize = 11;
/// The point's share of the committed contact, set by the core after each advance
/// ([`crate::surface::assembly::CutHistory`]): in contact, the part of its cell (the
/// σ-interval its weight stands for) inside the contact, whose edges are the roots of
/// the finite element solution's gap along σ, plus that part of an outside neighbour's
/// cell, over its cell's length; 0 out of contact. Kept, not advected
/// ([`crate::surface::assembly::SurfaceKernel::fixed_history`]), so V_⊥ ends at the
/// committed exit instead of one transport step cΔt past it (the release lag), and an
/// edge cuts the cell it lies in instead of switching whole points.
pub const CONTACT_SHARE: usize = 12;
/// The point's distance along σ from the committed contact's entry (the edge the drums
/// carry the belt in through), set by the core after each advance
/// ([`crate::surface::assembly::CutHistory::entry`]); 0 out of contact. Kept. While the
/// drums turn, it decides whether the point's foot, the step's travel cΔt upstream, was
/// in the committed contact ([`Interlayer::slip`]): a distance from the gap's root,
/// continuous as the entry moves, where the advected flag's ½-crossing decided before
/// and switched a point near an entry between taking the contact edge's slip and
/// starting from u = 0 (docs/fem-shell.md §7 (b), §14).
pub const CONTACT_ENTRY: usize = 13;
/// The committed position r_n (global, 3 values) and periodic material coordinate S̃_n
/// of the belt at the entry of the point's row ([`CONTACT_ENTRY`]), set by the core
/// ([`crate::surface::assembly::CutHistory::record`]); 0 out of contact. Kept. Where the
/// material that entered the contact during a step met the drum, and how much material
/// lay between the entry and the point ([`Interlayer::entered`]).
pub const ENTRY_RECORD: std::ops::Range<usize> = 14..18;
const ENTRY_POSITION: usize = 14;
const ENTRY_MATERIAL: usize = 17;
/// The point's own committed S̃_n (the advected one, at offset 9, is the foot's). Kept.
pub const OWN_MATERIAL: usize = 18;
/// The point's own committed (ν_n, z_n) (the advected ones are the foot's). Kept.
const OWN_POSITION: usize = 19;
/// The contact flag in the state: where it is < ½ u was released (set to 0 out of
/// contact), so the advection does not interpolate u across it with the cubic
/// ([`crate::surface::assembly::SurfaceKernel::history_support`]).
pub const CONTACT_FLAG: usize = CONTACT;
/// The components of u in the state: the only value carried by its own recursion
/// (u_{n+1} = ũ_n + increment, (S13)); the others are re-recorded from the converged
/// configuration every step. The advection keeps them between the bracketing points'
/// values ([`crate::surface::assembly::SurfaceKernel::bounded_history`];
/// docs/fem-shell.md §9.3: the cubic weights on the rod's non-uniform arc mesh amplified
/// u at a contact exit by 1.6 per step).
pub const DEFORMATION: std::ops::Range<usize> = U..U + 3;

/// A piecewise-linear history β(t) (rad), constant before its first and after its last
/// point.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    points: Vec<(f64, f64)>,
}

impl Schedule {
    /// A constant value.
    pub fn constant(value: f64) -> Schedule {
        Schedule { points: vec![(0.0, value)] }
    }

    /// The history through `points` (t, β), times strictly increasing.
    ///
    /// # Errors
    /// [`ShellError::BadParameter`]: no point, a value that is not finite, times not
    /// increasing.
    pub fn new(points: Vec<(f64, f64)>) -> Result<Schedule, ShellError> {
        if points.is_empty() {
            return Err(ShellError::BadParameter { what: "points of a tilt schedule", value: 0.0 });
        }
        if let Some(&(t, v)) = points.iter().find(|(t, v)| !(t.is_finite() && v.is_finite())) {
            return Err(ShellError::BadParameter { what: "tilt schedule point (time or angle not finite)", value: if t.is_finite() { v } else { t } });
        }
        if let Some(w) = points.windows(2).find(|w| w[1].0 <= w[0].0) {
            return Err(ShellError::BadParameter { what: "tilt schedule time (not increasing)", value: w[1].0 });
        }
        Ok(Schedule { points })
    }

    /// The points (t, β).
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// β(t).
    pub fn at(&self, time: f64) -> f64 {
        let p = &self.points;
        let k = p.partition_point(|&(t, _)| t <= time);
        if k == 0 {
            return p[0].1;
        }
        if k == p.len() {
            return p[k - 1].1;
        }
        let ((t0, v0), (t1, v1)) = (p[k - 1], p[k]);
        v0 + (v1 - v0) * (time - t0) / (t1 - t0)
    }
}

/// 3 × 3 matrix, rows.
type Matrix = [[f64; 3]; 3];

fn product(a: &Matrix, b: &Matrix) -> Matrix {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &Matrix) -> Matrix {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// The rotation by `angle` about coordinate axis `axis` (0 = x, 1 = y, 2 = z).
fn rotation(axis: usize, angle: f64) -> Matrix {
    let (s, c) = angle.sin_cos();
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m = [[0.0; 3]; 3];
    m[axis][axis] = 1.0;
    m[i][i] = c;
    m[j][j] = c;
    m[j][i] = s;
    m[i][j] = -s;
    m
}

fn apply<D: Scalar>(m: &Matrix, v: &[D; 3]) -> [D; 3] {
    std::array::from_fn(|i| v[0] * m[i][0] + v[1] * m[i][1] + v[2] * m[i][2])
}

/// What (S13) reads of the step at a point besides its state: r_n(foot) and r_n(σ_r)
/// ([`Interlayer::foot`]), the point's unknown S̃_{n+1}(σ) and the gauge c₀ of
/// S = c₀(σ − d(t)) + S̃ (docs/fem-shell.md (S2′)).
#[derive(Debug, Clone, Copy)]
pub struct Foot<D> {
    /// r_n(foot) = r_n(σ_r) + ∂̊_s r_n(σ_r) δs.
    pub position: [D; 3],
    /// r_n(σ_r).
    pub upstream: [f64; 3],
    /// S̃_{n+1}(σ).
    pub material: D,
    /// c₀.
    pub gauge: f64,
    /// r_n(σ), the point's own committed position ([`Interlayer::own_position`]).
    pub own: [f64; 3],
}

impl<D: Scalar> Foot<D> {
    /// A foot at r_n(σ_r) = r_n(σ) = `position` itself, with S̃_{n+1} = 0 and c₀ = 1
    /// (states whose own and entry S̃_n are then measured against 0).
    pub fn at(position: [f64; 3]) -> Foot<D> {
        Foot { position: position.map(D::from), upstream: position, material: D::zero(), gauge: 1.0, own: position }
    }
}

/// A drum: centre in the drawing plane, angular speed (clockwise positive: the drum
/// surface moves in +σ), and the tilt of its axis (docs/fem-shell.md §8): axis
/// a(t) = Rot_x(β_x(t)) Rot_y(β_y(t)) k through the centre.
#[derive(Debug, Clone, PartialEq)]
pub struct Drum {
    /// (x, y) of the centre, m.
    pub centre: [f64; 2],
    /// ω, rad/s (clockwise > 0).
    pub speed: f64,
    /// β_x(t): rotation about the span direction x, rad.
    pub tilt_x: Schedule,
    /// β_y(t): rotation in the plane of the axes (swivel), rad.
    pub tilt_y: Schedule,
}

impl Drum {
    /// An aligned drum (no tilt).
    pub fn aligned(centre: [f64; 2], speed: f64) -> Drum {
        Drum { centre, speed, tilt_x: Schedule::constant(0.0), tilt_y: Schedule::constant(0.0) }
    }

    /// The tilt Q(t) = Rot_x(β_x) Rot_y(β_y).
    fn tilt(&self, time: f64) -> Matrix {
        product(&rotation(0, self.tilt_x.at(time)), &rotation(1, self.tilt_y.at(time)))
    }

    /// The unit axis a(t) = Q(t) k.
    pub fn axis(&self, time: f64) -> [f64; 3] {
        let q = self.tilt(time);
        [q[0][2], q[1][2], q[2][2]]
    }

    fn centre3(&self) -> [f64; 3] {
        [self.centre[0], self.centre[1], 0.0]
    }

    /// The drum point at C + v carried by a spin by `angle` about the axis at `time`
    /// (clockwise turning: angle −ωt), relative to the centre: Q Rot_z(angle) Qᵀ v — the
    /// spin of [`Self::motion`] without the change of tilt, for an angle that depends on
    /// the unknowns.
    fn spin<D: Scalar>(&self, time: f64, angle: D, v: &[D; 3]) -> [D; 3] {
        let q = self.tilt(time);
        let w = apply(&transpose(&q), v);
        let (s, c) = (angle.sin(), angle.cos());
        let turned = [c * w[0] - s * w[1], s * w[0] + c * w[1], w[2]];
        apply(&q, &turned)
    }

    /// The drum's rigid motion from t₀ to t₁ about its centre: a drum point p goes to
    /// C + M (p − C), M = Q(t₁) Rot_z(−ω(t₁ − t₀)) Q(t₀)ᵀ (spin about the body axis, then
    /// the change of tilt); without the spin (ω taken as 0) if not `turning`.
    pub fn motion(&self, from: f64, to: f64, turning: bool) -> Matrix {
        let spin = if turning { self.speed * (to - from) } else { 0.0 };
        product(&product(&self.tilt(to), &rotation(2, -spin)), &transpose(&self.tilt(from)))
    }

    /// (γ, e): the penetration γ = R − dist(r, axis) of a point at r into the cylinder of
    /// radius R about the axis at `time`, and the unit radial direction e at r.
    pub fn gap<D: Scalar>(&self, radius: f64, r: &[D; 3], time: f64) -> (D, [D; 3]) {
        let a = self.axis(time);
        let c = self.centre3();
        let d: [D; 3] = std::array::from_fn(|k| r[k] - c[k]);
        let along = d[0] * a[0] + d[1] * a[1] + d[2] * a[2];
        let radial: [D; 3] = std::array::from_fn(|k| d[k] - along * a[k]);
        let dist = dot(&radial, &radial).sqrt();
        (-dist + radius, radial.map(|c| c / dist))
    }
}

/// The interlayer: stiffnesses, the drums, the contact radius and the transport speed.
#[derive(Debug, Clone, PartialEq)]
pub struct Interlayer {
    /// P, N/m³ (normal stiffness per area).
    pub normal: f64,
    /// P_⊥, N/m³ (tangential stiffness per area; 0: no V_⊥).
    pub shear: f64,
    /// The driver and the driven drum.
    pub drums: [Drum; 2],
    /// R = R_d + h/2: the cylinder the belt's mid-surface touches, m.
    pub radius: f64,
    /// c: the σ-speed by which the core advects the history, m/s (the drums' ωR).
    pub transport: f64,
    /// The drums turn, and the history is transported, in the steps whose middle is
    /// after this time, s (stage (2) of docs/fem-shell.md §9; −∞: from the start).
    /// Before it the drums rest (their tilt may change): quasistatic, only ωΔt counts,
    /// so the rotation starts at full speed.
    pub start: f64,
    /// The σ-rule of V_γ, V_⊥ (× Gauss 2 in ζ): [`Rule::Simpson`] or
    /// [`Rule::Trapezoidal`] (the reference's [T l.420]), closed rules whose points include
    /// the element edges (docs/fem-shell.md §6: the trapezoidal rule leaves the belt
    /// unsupported between nodes, and a stiff belt's tension shows it).
    pub rule: Rule,
    /// The ζ-rule of V_γ, V_⊥ across the width: [`Rule::Gauss`] with 2 (the reference's
    /// [T l.420, 432]) to 5 points (docs/fem-shell.md §6: across the belt's edge layer 2
    /// points per element under-integrate the layer and slow the convergence across the
    /// width).
    pub width_rule: Rule,
}

impl Interlayer {
    /// Checks the numbers.
    ///
    /// # Errors
    /// [`ShellError::BadParameter`]: P not finite and positive, P_⊥ not finite and ≥ 0, R
    /// not positive, a speed or the transport speed not finite.
    pub fn validate(&self) -> Result<(), ShellError> {
        let bad = |what: &'static str, value: f64| Err(ShellError::BadParameter { what, value });
        if !(self.normal.is_finite() && self.normal > 0.0) {
            return bad("interlayer normal stiffness P", self.normal);
        }
        if !(self.shear.is_finite() && self.shear >= 0.0) {
            return bad("interlayer shear stiffness P_⊥", self.shear);
        }
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return bad("interlayer contact radius", self.radius);
        }
        if !self.transport.is_finite() {
            return bad("transport speed", self.transport);
        }
        if self.start.is_nan() || self.start == f64::INFINITY {
            return bad("start of the rotation", self.start);
        }
        if !matches!(self.width_rule, Rule::Gauss(2..=5)) {
            return Err(ShellError::BadParameter { what: "interlayer ζ-rule (Gauss with 2 to 5 points)", value: f64::NAN });
        }
        if !matches!(self.rule, Rule::Simpson | Rule::Trapezoidal) {
            return Err(ShellError::BadParameter { what: "interlayer σ-rule (Simpson or trapezoidal)", value: f64::NAN });
        }
        if let Some(d) = self.drums.iter().find(|d| !(d.speed.is_finite() && d.centre.iter().all(|c| c.is_finite()))) {
            return bad("drum speed", d.speed);
        }
        Ok(())
    }

    /// Whether the drums turn in the step whose middle is at `time`.
    pub fn turning(&self, time: f64) -> bool {
        time > self.start
    }

    /// The transport speed in the step whose middle is at `time`: c while the drums
    /// turn, else 0.
    pub fn transport_at(&self, time: f64) -> f64 {
        if self.turning(time) {
            self.transport
        } else {
            0.0
        }
    }

    /// The tangential deformation u_{n+1} against drum `drum` of a point at r (module
    /// documentation), from the (advected) state and the [`Foot`], at the end `time` of a
    /// step `dt` (`(time, dt)`); e the drum's radial direction at r.
    /// - While the drums turn, a point in the committed contact whose material entered it
    ///   at least a step ago (θ ≥ 1, [`Self::entered`]: about its distance from the
    ///   entry, [`CONTACT_ENTRY`], over the step's travel |c|Δt) had its foot in the
    ///   contact: the recursion (S13) from it.
    /// - A point with θ < 1 holds material that entered the contact during the step, θΔt
    ///   ago, where the committed belt met the
    ///   drum (r_e, [`ENTRY_RECORD`]): u = [r_{n+1} − C − Rot(−ωθΔt)(r_e − C)]_⊥, the
    ///   brush model's u = 0 at the entry [T l.329] carried on by the step's relative
    ///   motion since (docs/fem-shell.md §7 (g)).
    /// - A point outside the committed contact (distance 0): u = 0.
    /// - At rest (the foot is the point): the recursion where its advected flag is ≥ ½
    ///   and r_n(σ_r) is inside the drum at t_n, else 0.
    pub fn slip<D: Scalar>(&self, drum: &Drum, r: &[D; 3], e: &[D; 3], foot: &Foot<D>, (time, dt): (f64, f64), state: &[f64]) -> [D; 3] {
        let shift = self.transport_at(time - 0.5 * dt) * dt;
        let c = drum.centre3();
        // Turning, by the committed entry (the root of the gap), not the advected flag:
        // the flag (the foot's, interpolated by the core's cubic) crosses ½ somewhere
        // near the entry, and a point whose foot lay in the contact edge's layer took that
        // layer's slip or none of it by which side of the crossing its foot fell — jumps
        // of the rotating span tensions with Δt (docs/fem-shell.md §14). At rest, the flag
        // and the gap of r_n(σ_r) at t_n (not of r_n(foot): its tangential extrapolation
        // leaves the drum by δs²/2R).
        // Turning and inside the committed contact, the material entered θΔt ago: its
        // foot was in the contact if θ ≥ 1. At θ = 1 the foot is the entry, where u_n = 0
        // and r_n(foot) = r_e, so the recursion and the entering material's u agree: u is
        // continuous across the switch (taken by the distance d ≥ |c|Δt, without the
        // step's creep, it jumped by the creep's slip over a step)
        let theta = (shift != 0.0 && state[CONTACT_ENTRY] > 0.0).then(|| self.entered(foot, shift, state));
        let recursion = if shift == 0.0 { state[CONTACT] >= 0.5 && drum.gap(self.radius, &foot.upstream, time - dt).0 > 0.0 } else { theta.is_some_and(|t| t.re() >= 1.0) };
        let raw: [D; 3] = if recursion {
            let m = drum.motion(time - dt, time, self.turning(time - 0.5 * dt));
            let moved = apply(&m, &std::array::from_fn(|k| foot.position[k] - c[k]));
            // ũ turns with the drum: u is the layer's shear, a vector of the drum's
            // tangent plane carried by the drum, so M ũ; the plain ũ, projected on the
            // tangent plane at r, lost the factor cos(ωΔt) of its tangential part every
            // step, a first-order error in Δt over a wrap (docs/fem-shell.md §7 (f))
            let carried = apply(&m, &[state[U], state[U + 1], state[U + 2]]);
            // M ũ + r_{n+1} − r_n(foot) − (R_{n+1} − R_n), R_n = r_n(foot)
            std::array::from_fn(|k| r[k] - moved[k] - c[k] + carried[k])
        } else if let Some(theta) = theta {
            // entered θΔt ago at r_e: the drum point that was under it then is now at
            // C + Rot(−ωθΔt)(r_e − C); θ from the material coordinate, so that the step's
            // creep is in it ([`Self::entered`]). r_e at t_{n+1} − θΔt: the committed
            // r_n(σ_e) moved on by the part 1 − θ of the step's motion of the belt at a
            // fixed σ, taken at the point, r_{n+1}(σ) − r_n(σ) — with r_n(σ_e) alone the
            // belt's drift over the step before the material entered (the run-off itself,
            // vΔt, ~15 % of the layer's lateral u at the exit at π/32) counted as slip
            let at_entry: [D; 3] = std::array::from_fn(|k| (r[k] - foot.own[k]) * (-theta + 1.0) + state[ENTRY_POSITION + k] - c[k]);
            let moved = drum.spin(time, theta * (-drum.speed * dt), &at_entry);
            std::array::from_fn(|k| r[k] - c[k] - moved[k])
        } else {
            return [D::zero(); 3];
        };
        let normal = dot(&raw, e);
        std::array::from_fn(|k| raw[k] - normal * e[k])
    }

    /// θ: how long ago, as a fraction of the step, the material now at a point of the
    /// committed contact entered it (≥ 1: before the step began; docs/fem-shell.md
    /// §7 (g)). With the material flowing steadily over the step, S at the entry falls
    /// at the rate S at the point does, and the material S_{n+1}(σ) crossed the entry σ_e
    /// when it had travelled the material S_n(σ) − S_n(σ_e) short of the step's
    /// S_n(σ) − S_{n+1}(σ):
    ///
    ///   θ = (S_n(σ) − S_n(σ_e)) / (S_n(σ) − S_{n+1}(σ)),
    ///   S_n(σ) − S_n(σ_e) = c₀ (σ − σ_e) + S̃_n(σ) − S̃_n(σ_e),   σ − σ_e = ±d,
    ///   S_n(σ) − S_{n+1}(σ) = c₀ cΔt − (S̃_{n+1}(σ) − S̃_n(σ))      (S2′),
    ///
    /// d the point's distance from the entry ([`CONTACT_ENTRY`]), S̃_n(σ_e) the entry's
    /// ([`ENTRY_RECORD`]) and S̃_n(σ) the point's own ([`OWN_MATERIAL`]). The relative
    /// motion of the material over the layer is its creep, ~1e-5 of its travel: a θ from
    /// the Eulerian distance alone, d/|c|Δt, makes the tangential u of entering material
    /// zero by construction. Linear in S̃_{n+1} (the point's unknown) through the
    /// denominator.
    pub fn entered<D: Scalar>(&self, foot: &Foot<D>, shift: f64, state: &[f64]) -> D {
        let behind = foot.gauge * shift.signum() * state[CONTACT_ENTRY] + state[OWN_MATERIAL] - state[ENTRY_MATERIAL];
        let flux = -(foot.material - state[OWN_MATERIAL]) + foot.gauge * shift;
        flux.recip() * behind
    }

    /// V_γ + V_⊥ per dσ dζ at a point at r with J = ∂σS. V_γ where γ > 0 (C¹ in the
    /// unknowns); V_⊥ where the foot of the point was in contact at the last commit (as
    /// [`Interlayer::slip`] decides), times the point's share of the
    /// committed contact ([`CONTACT_SHARE`]), against the drum nearest to r, and only with
    /// a state (the static evaluation has none) and P_⊥ > 0. Taking the V_⊥ region from
    /// the committed contact keeps each step's energy continuous: with the current
    /// γ > 0 a point at the contact's edge (the tangent point of a tight belt) switches
    /// ½P_⊥u² on and off between Newton iterates and the iteration chatters.
    pub fn density<D: Scalar>(&self, r: &[D; 3], foot: &Foot<D>, jacobian: D, step: (f64, f64), state: &[f64]) -> D {
        let [driver, driven] = self.shares(r, foot, step, state);
        (driver + driven) * jacobian
    }

    /// The density of [`Self::density`] per drum, per reference area of the deformed
    /// belt (without J): ½Pγ_i² where γ_i > 0, plus ½P_⊥u·u times the point's share
    /// of the committed contact for the drum nearest to r.
    /// −∂/∂r of drum i's share is the force per area drum i exerts on the belt.
    pub fn shares<D: Scalar>(&self, r: &[D; 3], foot: &Foot<D>, (time, dt): (f64, f64), state: &[f64]) -> [D; 2] {
        let mut w = [D::zero(); 2];
        let mut nearest: Option<(f64, usize, [D; 3])> = None;
        for (i, drum) in self.drums.iter().enumerate() {
            let (gamma, e) = drum.gap(self.radius, r, time);
            if gamma.re() > 0.0 {
                w[i] += gamma * gamma * (0.5 * self.normal);
            }
            if nearest.as_ref().is_none_or(|n| gamma.re() > n.0) {
                nearest = Some((gamma.re(), i, e));
            }
        }
        if let (Some((_, i, e)), false, true) = (nearest, state.is_empty() || state[CONTACT_SHARE] <= 0.0, self.shear > 0.0) {
            let u = self.slip(&self.drums[i], r, &e, foot, (time, dt), state);
            w[i] += dot(&u, &u) * (0.5 * self.shear * state[CONTACT_SHARE]);
        }
        w
    }

    /// The state after a converged step: u of the drum in contact (0 out of contact; r
    /// the position, `foot` = r_n(foot)), the `record` (ν, z, ∂̊_s r on (t_g, n_g, k), S̃)
    /// of the converged configuration, the contact flag, and as the gap and the share
    /// the nearest gap and the contact flag (the core then sets both,
    /// [`CONTACT_GAP`], [`CONTACT_SHARE`], and the entry's distance and record), and the
    /// point's own S̃_n and (ν_n, z_n) from the record ([`OWN_MATERIAL`]).
    pub fn advance(&self, r: &[f64; 3], foot: &Foot<f64>, record: &[f64; 6], (time, dt): (f64, f64), previous: &[f64], next: &mut [f64]) {
        let (mut u, mut contact, mut nearest) = ([0.0; 3], 0.0, f64::NEG_INFINITY);
        for drum in &self.drums {
            let (gamma, e) = drum.gap(self.radius, r, time);
            nearest = nearest.max(gamma);
            if gamma > 0.0 {
                contact = 1.0;
                if self.shear > 0.0 {
                    u = self.slip(drum, r, &e, foot, (time, dt), previous);
                }
            }
        }
        next[U..U + 3].copy_from_slice(&u);
        next[POSITION..POSITION + 2].copy_from_slice(&record[..2]);
        next[POSITION + 2] = 0.0;
        next[SLOPE..SLOPE + 3].copy_from_slice(&record[2..5]);
        next[MATERIAL] = record[5];
        next[CONTACT] = contact;
        next[CONTACT_GAP] = nearest;
        next[CONTACT_SHARE] = contact;
        next[CONTACT_ENTRY] = 0.0;
        next[ENTRY_RECORD].fill(0.0);
        next[OWN_MATERIAL] = record[5];
        next[OWN_POSITION..OWN_POSITION + 2].copy_from_slice(&record[..2]);
    }

    /// r_n(σ) = g + ν_n n_g + z_n k, the point's own committed position, from its state and
    /// the contour's [g, t_g, n_g] at σ.
    pub fn own_position(state: &[f64], frame: &[[f64; 2]; 3]) -> [f64; 3] {
        let [g, _, n] = frame;
        let (nu, z) = (state[OWN_POSITION], state[OWN_POSITION + 1]);
        [g[0] + nu * n[0], g[1] + nu * n[1], z]
    }

    /// The gap γ = R − dist(r, axis) to the drum nearest to r (the larger of the two).
    pub fn nearest_gap(&self, r: &[f64; 3], time: f64) -> f64 {
        self.drums.iter().map(|d| d.gap(self.radius, r, time).0).fold(f64::NEG_INFINITY, f64::max)
    }

    /// r_n(foot) = r_n(σ_r) + ∂̊_s r_n(σ_r) δs (global) from an (advected) state, the
    /// contour's [g, t_g, n_g] at σ_r and the material offset δs.
    /// Also r_n(σ_r) itself (the second value).
    pub fn foot<D: Scalar>(state: &[f64], upstream: &[[f64; 2]; 3], offset: D) -> ([D; 3], [f64; 3]) {
        let [g, t, n] = upstream;
        let (nu, z) = (state[POSITION], state[POSITION + 1]);
        let a = &state[SLOPE..SLOPE + 3];
        let position = [g[0] + nu * n[0], g[1] + nu * n[1], z];
        let slope = [a[0] * t[0] + a[1] * n[0], a[0] * t[1] + a[1] * n[1], a[2]];
        (std::array::from_fn(|k| offset * slope[k] + position[k]), position)
    }

    /// S̃_n of an (advected) state.
    pub fn material(state: &[f64]) -> f64 {
        state[MATERIAL]
    }

    /// u of a state.
    pub fn deformation(state: &[f64]) -> [f64; 3] {
        [state[U], state[U + 1], state[U + 2]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drum_motion_is_a_rotation_about_the_tilted_axis_and_the_schedule_interpolates() {
        let tilt = Schedule::new(vec![(0.0, 0.0), (2.0, 0.02)]).unwrap();
        assert_eq!(tilt.at(-1.0), 0.0);
        assert!((tilt.at(0.5) - 0.005).abs() < 1e-15);
        assert_eq!(tilt.at(3.0), 0.02);
        assert!(Schedule::new(vec![(1.0, 0.0), (1.0, 0.1)]).is_err());
        assert!(Schedule::new(vec![]).is_err());
        let drum = Drum { centre: [0.5, 0.0], speed: 2.0, tilt_x: Schedule::constant(0.03), tilt_y: Schedule::constant(-0.02) };
        let (a, m) = (drum.axis(1.0), drum.motion(1.0, 1.1, true));
        // the axis is fixed by the motion, |a| = 1, M orthogonal, spin angle ω Δt
        let ma = apply(&m, &a);
        assert!((0..3).all(|k| (ma[k] - a[k]).abs() < 1e-15));
        assert!((dot(&a, &a) - 1.0).abs() < 1e-15);
        let mmt = product(&m, &transpose(&m));
        assert!((0..3).all(|i| (0..3).all(|j| (mmt[i][j] - f64::from(u8::from(i == j))).abs() < 1e-15)));
        let trace = m[0][0] + m[1][1] + m[2][2];
        assert!((((trace - 1.0) / 2.0).acos() - 0.2).abs() < 1e-12);
        // the top of an aligned drum moves in +x when it turns clockwise; the gap
        let aligned = Drum::aligned([0.5, 0.0], 1.0);
        let top = apply(&aligned.motion(0.0, 0.1, true), &[0.0, 0.3, 0.0]);
        assert!(top[0] > 0.0 && top[1] < 0.3);
        // at rest only the change of tilt moves the drum
        let resting = drum.motion(1.0, 1.1, false);
        assert!((0..3).all(|i| (0..3).all(|j| (resting[i][j] - f64::from(u8::from(i == j))).abs() < 1e-15)));
        let (gamma, e): (f64, _) = aligned.gap(0.3, &[0.5f64, 0.29, 0.7], 0.0);
        assert!((gamma - 0.01).abs() < 1e-15 && (e[1] - 1.0).abs() < 1e-15);
    }

    /// The layer's shear turns with the drum (docs/fem-shell.md §7 (f)): a belt that
    /// rolls rigidly with the drum over a step keeps its u as the drum carries it,
    /// u_{n+1} = M ũ_n — length and the angle to the drum's surface kept. Here ũ =
    /// (1, 0, 0.2) mm at the top of a drum turning by ωΔt = 0.1, ν = −0.1 mm (inside):
    /// the old update, ũ projected on the new tangent plane without turning it, kept
    /// cos(ωΔt) = 0.995 of the tangential part (a deficit of 5e-3, asserted 1e-14).
    #[test]
    fn the_shear_turns_with_the_drum_when_the_belt_rolls_with_it() {
        let drum = Drum { centre: [0.5, 0.0], speed: 1.0, tilt_x: Schedule::constant(0.0), tilt_y: Schedule::constant(0.0) };
        let layer = Interlayer { normal: 1e6, shear: 1e4, drums: [Drum::aligned([-0.5, 0.0], 1.0), drum.clone()], radius: 0.3, transport: 0.3, start: f64::NEG_INFINITY, rule: Rule::Simpson, width_rule: Rule::Gauss(2) };
        let (time, dt) = (1.0, 0.1);
        let foot = [0.5, 0.2999, 0.0];
        let mut state = vec![0.0; STATE];
        state[U..U + 3].copy_from_slice(&[1e-3, 0.0, 2e-4]);
        state[CONTACT] = 1.0;
        // deep in the contact: more than the step's travel cΔt = 0.03 m past the entry
        state[CONTACT_ENTRY] = 0.1;
        let m = drum.motion(time - dt, time, true);
        let c = [0.5, 0.0, 0.0];
        let rolled = apply(&m, &[foot[0] - c[0], foot[1] - c[1], foot[2]]);
        let r: [f64; 3] = std::array::from_fn(|k| rolled[k] + c[k]);
        let (gamma, e): (f64, _) = drum.gap(layer.radius, &r, time);
        assert!(gamma > 0.0);
        let u = layer.slip(&drum, &r, &e, &Foot::at(foot), (time, dt), &state);
        let turned = apply(&m, &[1e-3, 0.0, 2e-4]);
        assert!((0..3).all(|k| (u[k] - turned[k]).abs() < 1e-14 * 1e-3), "u {u:?} against M ũ {turned:?}");
        assert!((dot(&u, &u).sqrt() - (1.04e-6f64).sqrt()).abs() < 1e-17, "|u| {:e}", dot(&u, &u).sqrt());
        assert!(dot(&u, &e).abs() < 1e-18, "u leaves the tangent plane: {u:?}");
    }

    /// V_⊥ acts with the point's share of the committed contact ([`CONTACT_SHARE`],
    /// docs/fem-shell.md §7 (b)): at the top of the driven drum (γ = 1 mm) with the
    /// foot's flag set and ũ = 1 mm along the belt, the drum turned by ωΔt = 0.1, the
    /// density is ½Pγ² + χ½P_⊥|u|² for the shares χ = 1, ¼ and 0 (a point just past the
    /// exit, whose foot was still in contact, with none of its cell in contact).
    /// `advance` records the gap to the nearest drum and the contact flag as the share
    /// (the core cuts the cells after it: `surface::history`).
    #[test]
    fn the_shear_spring_acts_on_the_part_of_the_point_cell_in_contact() {
        let drums = [Drum::aligned([-0.5, 0.0], 1.0), Drum::aligned([0.5, 0.0], 1.0)];
        let layer = Interlayer { normal: 1e6, shear: 1e4, drums, radius: 0.3, transport: 0.3, start: f64::NEG_INFINITY, rule: Rule::Simpson, width_rule: Rule::Gauss(2) };
        let r = [0.5, 0.299, 0.0];
        let mut state = vec![0.0; STATE];
        state[U] = 1e-3;
        state[CONTACT] = 1.0;
        // deep in the contact: more than the step's travel cΔt = 0.03 m past the entry
        state[CONTACT_ENTRY] = 0.1;
        let step = (1.0, 0.1);
        let (gamma, e): (f64, _) = layer.drums[1].gap(layer.radius, &r, step.0);
        let u = layer.slip(&layer.drums[1], &r, &e, &Foot::at(r), step, &state);
        let spring = 0.5 * layer.shear * dot(&u, &u);
        assert!(spring > 1e-3, "the test's point carries no shear: {u:?}");
        let with = |share: f64| {
            let mut s = state.clone();
            s[CONTACT_SHARE] = share;
            layer.shares(&r, &Foot::at(r), step, &s)
        };
        let normal = 0.5 * layer.normal * gamma * gamma;
        for share in [1.0, 0.25] {
            let w = with(share);
            assert_eq!(w[0], 0.0);
            assert!((w[1] - normal - share * spring).abs() <= 1e-12 * w[1], "share {share}: {w:?} against ½Pγ² {normal} + χ½P⊥u² {}", share * spring);
        }
        assert_eq!(with(0.0), [0.0, normal]);
        let mut next = vec![0.0; STATE];
        layer.advance(&r, &Foot::at(r), &[-1e-3, 2e-3, 0.0, 0.0, 0.0, 0.25], step, &state, &mut next);
        assert_eq!((next[CONTACT], next[CONTACT_GAP], next[CONTACT_SHARE]), (1.0, gamma, 1.0));
        // the point's own S̃_n and (ν_n, z_n), kept for the entering material (§7 (g))
        let own = Interlayer::own_position(&next, &[[0.5, 0.3], [1.0, 0.0], [0.0, 1.0]]);
        assert!(next[OWN_MATERIAL] == 0.25 && own.iter().zip([0.5, 0.299, 2e-3]).all(|(a, b)| (a - b).abs() < 1e-15), "{} {own:?}", next[OWN_MATERIAL]);
        // 50 mm along the tangent at the driven drum's top: out of contact, the gap
        // −(√(R² + d²) − R) to that drum (the nearer one)
        let d = 0.05;
        layer.advance(&[0.5 + d, 0.3, 0.0], &Foot::at(r), &[0.0; 6], step, &state, &mut next);
        assert_eq!((next[CONTACT], next[CONTACT_SHARE]), (0.0, 0.0));
        assert!((next[CONTACT_GAP] + ((0.09 + d * d) as f64).sqrt() - 0.3).abs() < 1e-15, "gap {}", next[CONTACT_GAP]);
    }

    /// Whether a point's foot was in the committed contact: while the drums turn, by the
    /// point's distance d from the committed entry ([`CONTACT_ENTRY`]) against the step's
    /// travel |c|Δt = 0.03 m, whatever the advected flag says; at rest by the flag and the
    /// gap of r_n(σ_r). At the driven drum's top (R = 0.3 m, ω = 1 rad/s, Δt = 0.1 s):
    /// - d = 0.01 m with the flag set (its cubic interpolation ≥ ½ just upstream of the
    ///   entry) and r_n(σ_r) inside the drum: not the recursion — the material entered
    ///   during the step (rolling with the drum from the entry here, so u = 0;
    ///   [`Interlayer::entered`]);
    /// - d = 0.031 m (θ > 1) with the flag unset: the recursion from the foot, ũ + r − M r_n(foot)
    ///   projected on the tangent plane (here ũ = 0), to round-off;
    /// - at rest the point itself: with the flag set and r_n(σ_r) on the drum, the
    ///   recursion whatever d is; with the flag unset, 0.
    #[test]
    fn the_foot_is_in_contact_by_its_distance_from_the_entry_while_the_drums_turn() {
        let drums = [Drum::aligned([-0.5, 0.0], 1.0), Drum::aligned([0.5, 0.0], 1.0)];
        let layer = Interlayer { normal: 1e6, shear: 1e4, drums, radius: 0.3, transport: 0.3, start: f64::NEG_INFINITY, rule: Rule::Simpson, width_rule: Rule::Gauss(2) };
        let (step, radius) = ((1.0, 0.1), 0.3);
        let at = |arc: f64| [0.5 + radius * (arc / radius).sin(), radius * (arc / radius).cos(), 1e-4];
        let recursion = |layer: &Interlayer, r: &[f64; 3], foot: &[f64; 3], turning: bool| -> [f64; 3] {
            let (_, e) = layer.drums[1].gap(layer.radius, r, step.0);
            let m = layer.drums[1].motion(step.0 - step.1, step.0, turning);
            let moved = apply(&m, &[foot[0] - 0.5, foot[1], foot[2]]);
            let raw: [f64; 3] = std::array::from_fn(|k| r[k] - moved[k] - [0.5, 0.0, 0.0][k]);
            std::array::from_fn(|k| raw[k] - dot(&raw, &e) * e[k])
        };
        let slip = |layer: &Interlayer, r: &[f64; 3], foot: &[f64; 3], flag: f64, d: f64| {
            let mut state = vec![0.0; STATE];
            (state[CONTACT], state[CONTACT_ENTRY]) = (flag, d);
            // entered at the drum's top, rolling with it (S̃ unchanged)
            state[ENTRY_RECORD].copy_from_slice(&[0.5, radius, 1e-4, 0.0]);
            let (_, e) = layer.drums[1].gap(layer.radius, r, step.0);
            layer.slip(&layer.drums[1], r, &e, &Foot { own: *r, ..Foot::at(*foot) }, step, &state)
        };
        // 0.01 m past the entry, with the flag set and r_n(σ_r) inside the drum (what the
        // flag's criterion took for a foot in contact, with u = the recursion ≠ 0)
        let (r, foot) = (at(0.01), [0.5, radius - 1e-6, 0.0]);
        assert!(recursion(&layer, &r, &foot, true).iter().any(|x| x.abs() > 1e-6));
        assert!(slip(&layer, &r, &foot, 1.0, 0.01).iter().all(|x| x.abs() < 1e-16), "{:?}", slip(&layer, &r, &foot, 1.0, 0.01));
        // 0.031 m past the entry (θ > 1): the foot just past the entry, on the drum
        let (r, foot) = (at(0.031), [0.5, radius - 1e-6, 0.0]);
        let (u, expected) = (slip(&layer, &r, &foot, 0.0, 0.031), recursion(&layer, &r, &foot, true));
        assert!(expected.iter().any(|x| x.abs() > 1e-6) && u == expected, "{u:?} against {expected:?}");
        let resting = Interlayer { start: f64::INFINITY, ..layer.clone() };
        let (u, expected) = (slip(&resting, &r, &foot, 1.0, 0.0), recursion(&resting, &r, &foot, false));
        assert!(expected.iter().any(|x| x.abs() > 1e-6) && u == expected, "at rest: {u:?} against {expected:?}");
        assert_eq!(slip(&resting, &r, &foot, 0.0, 0.031), [0.0; 3]);
    }

    /// Material that entered the contact during the step ([`Interlayer::entered`],
    /// docs/fem-shell.md §7 (g)): at the driven drum (R = 0.3 m, ω = 1 rad/s, Δt = 0.1 s,
    /// c₀ = 1.02), a point d = 0.01 m past the entry at the drum's top, with the step's
    /// travel |c|Δt = 0.03 m:
    /// - rolling with the drum (S̃ unchanged at the point and the entry): θ = d/|c|Δt and
    ///   u = 0 to round-off, in both senses of rotation (the entry upstream at −σ, or at
    ///   +σ with c, ω < 0);
    /// - held back by δ = 1 µm of material over the step (S̃_{n+1} = S̃_n + δ: the flux is
    ///   c₀|c|Δt − δ): θ = c₀d/(c₀|c|Δt − δ), so the drum point under the material has
    ///   gone ahead by ωRΔt (θ − d/|c|Δt) = 3.2681e-7 m (θ − d/|c|Δt = dδ/(|c|Δt(c₀|c|Δt − δ)))
    ///   and u is that much backwards along the drum's surface (to 1e-9 of it: the chord
    ///   against the arc);
    /// - moved sideways by 2 µm since the entry on the aligned drum: u_z = 2 µm;
    /// - the whole belt drifting sideways by δz = 3 µm over the step (r_n(σ) δz beside
    ///   r_{n+1}(σ), the entry's committed position δz behind): the material slipped over
    ///   the drum only for the θ = 1/3 of the step it was on it, u_z = δz/3 (without the
    ///   entry's motion over the step, δz);
    /// - ∂u/∂S̃_{n+1} of the dual numbers against central differences (δ ± 1e-8, to 1e-6);
    /// - 0 at the entry's distance 0 (the point outside the committed contact).
    #[test]
    fn entering_material_carries_the_relative_motion_since_the_entry() {
        use num_dual::Dual64;
        let (step, radius, gauge) = ((1.0, 0.1), 0.3, 1.02);
        let forward = Interlayer { normal: 1e6, shear: 1e4, drums: [Drum::aligned([-0.5, 0.0], 1.0), Drum::aligned([0.5, 0.0], 1.0)], radius, transport: 0.3, start: f64::NEG_INFINITY, rule: Rule::Simpson, width_rule: Rule::Gauss(2) };
        let backward = Interlayer { drums: [Drum::aligned([-0.5, 0.0], -1.0), Drum::aligned([0.5, 0.0], -1.0)], transport: -0.3, ..forward.clone() };
        // the point `arc` along the driven drum's surface from its top, at lateral z
        let at = |arc: f64, z: f64| [0.5 + radius * (arc / radius).sin(), radius * (arc / radius).cos(), z];
        let state = |d: f64, own: f64, entry: f64| {
            let mut state = vec![0.0; STATE];
            state[CONTACT_ENTRY] = d;
            state[ENTRY_RECORD].copy_from_slice(&[0.5, radius, 1e-4, entry]);
            state[OWN_MATERIAL] = own;
            state
        };
        let slip = |layer: &Interlayer, r: &[f64; 3], material: f64, state: &[f64]| {
            let (_, e) = layer.drums[1].gap(layer.radius, r, step.0);
            layer.slip(&layer.drums[1], r, &e, &Foot { position: *r, upstream: *r, material, gauge, own: *r }, step, state)
        };
        let (d, own) = (0.01, 0.2);
        // rolling: S̃_n(σ) = S̃_n(σ_e), the material between them c₀d
        let rolling = state(d, own, own);
        for (layer, sense) in [(&forward, 1.0), (&backward, -1.0)] {
            let u = slip(layer, &at(sense * d, 1e-4), own, &rolling);
            assert!(u.iter().all(|x| x.abs() < 1e-17), "rolling, sense {sense}: {u:?}");
        }
        // held back by δ
        let delta = 1e-6;
        let (shift, r) = (0.03, at(d, 1e-4));
        let u = slip(&forward, &r, own + delta, &rolling);
        let ahead = radius * 1.0 * step.1 * (gauge * d / (gauge * shift - delta) - d / shift);
        let tangent = [((d / radius).cos()), -((d / radius).sin()), 0.0];
        assert!((ahead - 3.2681e-7).abs() < 1e-11, "{ahead:e}");
        assert!((dot(&u, &tangent) + ahead).abs() < 1e-9 * ahead && u[2].abs() < 1e-20, "held back: {u:?} against {:e} along the surface", -ahead);
        // sideways
        let u = slip(&forward, &at(d, 1e-4 + 2e-6), own, &rolling);
        assert!((u[2] - 2e-6).abs() < 1e-18 && dot(&u, &tangent).abs() < 1e-17, "sideways: {u:?}");
        // the whole belt drifting sideways by δz over the step: the material was on the
        // drum for θ = 1/3 of it
        let drift = 3e-6;
        let moved = at(d, 1e-4 + drift);
        let (_, e) = forward.drums[1].gap(forward.radius, &moved, step.0);
        let u = forward.slip(&forward.drums[1], &moved, &e, &Foot { position: moved, upstream: moved, material: own, gauge, own: r }, step, &state(d, own, own));
        assert!((u[2] - drift / 3.0).abs() < 1e-18 && dot(&u, &tangent).abs() < 1e-17, "drifting: {u:?}");
        // ∂u/∂S̃_{n+1} against central differences
        let (_, e) = forward.drums[1].gap(forward.radius, &r.map(Dual64::from), step.0);
        let dual = forward.slip(&forward.drums[1], &r.map(Dual64::from), &e, &Foot { position: r.map(Dual64::from), upstream: r, material: Dual64::new(own + delta, 1.0), gauge, own: r }, step, &rolling);
        let h = 1e-8;
        let (plus, minus) = (slip(&forward, &r, own + delta + h, &rolling), slip(&forward, &r, own + delta - h, &rolling));
        for k in 0..3 {
            let fd = (plus[k] - minus[k]) / (2.0 * h);
            assert!((dual[k].eps - fd).abs() <= 1e-6 * fd.abs().max(1e-3), "∂u_{k}/∂S̃: {} against {fd}", dual[k].eps);
        }
        assert!(dual[0].eps.abs() > 1e-3, "{dual:?}");
        // outside the committed contact
        assert_eq!(slip(&forward, &r, own + delta, &state(0.0, own, own)), [0.0; 3]);
    }
}
