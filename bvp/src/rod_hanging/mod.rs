//! `rod-hanging`: an extensible, unshearable (Kirchhoff) rod loop hanging under gravity on
//! two non-rotating frictionless pulleys, as the six-segment BVP derived in
//! `docs/rod-hanging.md` (41 unknowns).
//!
//! [`solve`] first solves the string of the same data ([`crate::string_hanging::solve`]),
//! builds the rod guess from it at a bending stiffness EI₀ whose boundary layer
//! √(EI₀/T) is 5 % of H, continues in log EI to the scene's EI — downwards for thin
//! layers, upwards for stiff rods; EI(η) = EI₀^(1−η) EI^η covers both —
//! (`continuation::natural_checked`), then solves at the requested tolerance by
//! collocation or shooting ([`BvpMethod`]). The rod is a section law ([`law`]) on the
//! frictionless two-pulley topology.

pub mod law;

use std::f64::consts::PI;
use std::time::Instant;

use numerics::Sig;
use serde::Serialize;

use crate::belt::run::StageError;
use crate::belt::solution::{self, Run};
use crate::belt::topology::{ContactModel, Scaling, Side, Topology};
use crate::belt::{BeltError, BeltOptions, BeltProblem, BeltSolution, BvpMethod, SectionLaw};
use crate::collocation::Scheme;
use crate::error::BvpError;
use crate::solution::Solution;
use crate::string_hanging::{self, StringHanging, StringHangingSolution};
pub use law::ScaledRodHanging;

/// Physical data of the scene (SI units).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct RodHanging {
    /// Pulley radius R to the rod centreline (m).
    pub radius: f64,
    /// Centre distance H (m).
    pub centre_distance: f64,
    /// Unstretched loop length L (m).
    pub length: f64,
    /// Axial stiffness EA (N).
    pub axial_stiffness: f64,
    /// Bending stiffness EI (N·m²).
    pub bending_stiffness: f64,
    /// Mass per unstretched length ρ (kg/m).
    pub mass_per_length: f64,
    /// Gravitational acceleration g (m/s²).
    pub gravity: f64,
}

impl RodHanging {
    /// The string with the same data (EI dropped).
    pub fn string(&self) -> StringHanging {
        StringHanging {
            radius: self.radius,
            centre_distance: self.centre_distance,
            length: self.length,
            axial_stiffness: self.axial_stiffness,
            mass_per_length: self.mass_per_length,
            gravity: self.gravity,
        }
    }
}

/// A solved `rod-hanging` scene; its `start` is the string solution of the same data.
pub type RodHangingSolution = BeltSolution<ScaledRodHanging>;

pub(crate) fn validate(d: &RodHanging, opts: &BeltOptions) -> Result<(), BeltError> {
    if !(d.bending_stiffness.is_finite() && d.bending_stiffness > 0.0) {
        return Err(BeltError::InvalidInput {
            name: "bending_stiffness",
            value: d.bending_stiffness,
            reason: "must be finite and > 0 (EI = 0 is the string)",
        });
    }
    opts.check_tolerance()?;
    if !(opts.start_layer > 0.0 && opts.start_layer.is_finite()) {
        return Err(BeltError::InvalidInput { name: "start_layer", value: opts.start_layer, reason: "must be finite and > 0" });
    }
    Ok(())
}


/// Unwrap an angle into (centre − π, centre + π].
fn unwrap(a: f64, centre: f64) -> f64 {
    let mut a = a;
    while a > centre + PI {
        a -= 2.0 * PI;
    }
    while a <= centre - PI {
        a += 2.0 * PI;
    }
    a
}

/// The rod guess at EI₀ from the string solution (scaled) on the same topology: θ from
/// the span force direction, Q = F, M = 0 on the spans except the boundary layers at the
/// pulleys, where M = −EI₀λ/R · exp(−d/ℓ_b), ℓ_b = √(EI₀/T); N = T and s on the arcs;
/// the string's parameters.
pub fn rod_guess(string: &Solution, rod: &BeltProblem<ScaledRodHanging>, nodes: usize) -> Solution {
    let (topo, law) = (&rod.topology, &rod.law);
    let ei0 = law.bending_start;
    let params = string.params.clone();
    Solution::from_fn(topo.len(), nodes, params.clone(), 0.0, |k, xi| {
        let y = string.eval(k, xi);
        let seg = topo.segment(k);
        let Scaling::Span { param } = seg.scaling else { return y };
        let (fx, fy) = (y[2], y[3]);
        let t = fx.hypot(fy);
        let centre = if seg.side == Side::UpperSpan { 0.0 } else { -PI };
        let theta = unwrap(fy.atan2(fx), centre);
        let layer = (ei0 / t).sqrt();
        let l = params[param];
        // Distance from the pulley the span half leaves (first halves) or meets.
        let from_start = topo.junction(k) == crate::belt::topology::Junction::MidSpan;
        let d = if from_start { l * xi } else { l * (1.0 - xi) };
        let m = -ei0 * (1.0 + t / law.axial_stiffness) / law.radius * (-d / layer).exp();
        vec![y[0], y[1], theta, m, fx, fy, y[4]]
    })
}

/// Solve a `rod-hanging` scene from its data alone.
pub fn solve(data: &RodHanging, opts: &BeltOptions) -> Result<RodHangingSolution, BeltError> {
    let clock = Instant::now();
    validate(data, opts)?;
    let (string, path) = string_start(&data.string(), data.bending_stiffness, opts)?;
    let (h, fr) = (string.scales.length, string.scales.force);
    let sp = string.problem.law.clone();
    let law = |bending_start| ScaledRodHanging {
        radius: sp.radius,
        axial_stiffness: sp.axial_stiffness,
        weight: sp.weight,
        length: sp.length,
        bending_start,
        bending: data.bending_stiffness / (fr * h * h),
    };
    solve_from_string(*data, law, string, &path, |s, pb| rod_guess(s, pb, 81), opts, clock)
}

/// Solve a rod's section law on the frictionless loop from the string start of
/// [`string_start`]: `law(EI₀)` is the scaled law whose path starts at EI₀ (scaled),
/// `guess(string, problem)` its guess; the homotopy in log bending stiffness along `path`
/// (or none, when the scene's layer is at least the start layer), the final solve and
/// the checks (the Kirchhoff and the Cosserat rod share all of it). A start at the
/// scene's own EI that fails in any way — its Newton solve from the guess, or a check —
/// is retried along the path from the start layer, whose stall names the scene quantity.
pub(crate) fn solve_from_string<L: SectionLaw<Start = StringHangingSolution>>(
    data: L::Data,
    law: impl Fn(f64) -> L,
    string: StringHangingSolution,
    path: &RodPath,
    guess: impl Fn(&Solution, &BeltProblem<L>) -> Solution,
    opts: &BeltOptions,
    clock: Instant,
) -> Result<BeltSolution<L>, BeltError> {
    let attempt = |start: f64, string: StringHangingSolution| {
        let (scales, pulleys) = (string.scales, string.pulleys);
        let problem = BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), law(start));
        let guess = guess(&string.solution, &problem);
        let run = Run { data: data.clone(), problem, scales, pulleys, guess: &guess, start: string };
        solution::solve(run, opts, clock, |e, _| match e {
            StageError::Homotopy(cause) => path.failure(pulleys.radius, cause),
            StageError::Final(cause) => BeltError::Solver { stage: "final solve", cause },
        })
    };
    if path.scaled_start != path.scaled_layer {
        if let Ok(direct) = attempt(path.scaled_start, string.clone()) {
            return Ok(direct);
        }
    }
    attempt(path.scaled_layer, string)
}

/// The start of a rod's homotopy (the Kirchhoff and the Cosserat rod): the string of the
/// same data by collocation (gauss6, 1e-8, with the run's mesh cap, Jacobian mode and
/// homotopy tolerance), and the path in log bending stiffness from EI₀, whose bending
/// layer √(EI₀/T) is `opts.start_layer` H at the string's mid-span tension T, to the
/// scene's `bending_stiffness` (N·m²) — or no path (EI₀ = EI) when the scene's layer is
/// at least the start layer.
pub(crate) fn string_start(
    string: &StringHanging,
    bending_stiffness: f64,
    opts: &BeltOptions,
) -> Result<(StringHangingSolution, RodPath), BeltError> {
    let sopts = BeltOptions {
        method: BvpMethod::Collocation,
        // gauss6, not the default scheme: the start (and with it the final mesh) of every
        // catalogue rod scene stays what it was when the default was gauss6
        scheme: Scheme::Gauss6,
        tolerance: 1e-8,
        shooting_intervals: BeltOptions::default().shooting_intervals,
        ..opts.clone()
    };
    let string = string_hanging::solve(string, &sopts).map_err(|e| BeltError::StringStart(Box::new(e)))?;
    let (h, fr) = (string.scales.length, string.scales.force);
    // String mid-span tension (upper span, x = 0), scaled.
    let (upper_mid, _) = string.topology().mid_spans();
    let mid = string.solution.segments[upper_mid].end();
    let t_mid = mid[2].hypot(mid[3]);
    // A scene whose own layer is at least the start layer starts at its own EI (no path
    // in EI, as `cosserat_drive`): the path would only stiffen a rod that already
    // resolves on the start's mesh.
    let scaled_layer = opts.start_layer * opts.start_layer * t_mid;
    let scaled_start = (bending_stiffness / (fr * h * h)).max(scaled_layer);
    let path = RodPath {
        scaled_start,
        scaled_layer,
        bending_start: scaled_start * fr * h * h,
        bending: bending_stiffness,
        tension: t_mid * fr,
    };
    Ok((string, path))
}

/// A rod's homotopy in log EI from the string: its start EI₀ and end EI (N·m²) and the
/// string's mid-span tension T (N), to name a stall by the scene quantity it was
/// switching on.
pub(crate) struct RodPath {
    /// EI₀ / (F_ref H²), the scaled start: the larger of the start layer's and the
    /// scene's.
    pub scaled_start: f64,
    /// The start layer's EI / (F_ref H²): the path's start when the direct start fails.
    pub scaled_layer: f64,
    /// EI₀ (N·m²).
    pub bending_start: f64,
    /// The scene's EI (N·m²).
    pub bending: f64,
    /// The string's mid-span tension (N).
    pub tension: f64,
}

impl RodPath {
    /// A stalled homotopy named by the bending stiffness it had reached, EI(η) =
    /// EI₀^(1−η) EI^η, and the scene's bending length √(EI/T) against the radius R (m).
    pub fn failure(&self, radius: f64, cause: BvpError) -> BeltError {
        const STAGE: &str = "the homotopy in log EI from the string";
        let BvpError::ContinuationStalled { eta, .. } = cause else {
            return BeltError::Solver { stage: STAGE, cause };
        };
        let ei = self.bending_start.powf(1.0 - eta) * self.bending.powf(eta);
        let at = format!(
            "stiffening the string into the rod: EI = {} N·m² on the way from EI₀ = {} N·m² to the scene's {} N·m²",
            Sig(ei),
            Sig(self.bending_start),
            Sig(self.bending)
        );
        let hard = format!(
            "the bending length √(EI/T) = {} m against the pulley radius R = {} m (T = {} N, the string's mid-span tension) makes it hard",
            Sig((self.bending / self.tension).sqrt()),
            Sig(radius),
            Sig(self.tension)
        );
        BeltError::HomotopyStalled { stage: STAGE, eta, at, hard, cause }
    }
}

impl RodHangingSolution {
    /// EI₀ (N·m²) of the homotopy start.
    pub fn bending_start(&self) -> f64 {
        self.problem.law.bending_start * self.scales.force * self.scales.length * self.scales.length
    }
}
