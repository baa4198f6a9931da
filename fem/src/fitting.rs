//! Mesh fitting: move a node onto every point a solution locates (contact boundaries,
//! stick→slip transitions) and re-solve, until the located points sit on nodes
//! (docs/fem-string.md §5, docs/fem-drive.md §12).
//!
//! The analysis-specific parts stay with the caller behind [`Fitted`]: what the points
//! are (`locate`), how a solution moves to a new mesh and is solved there (`refit`),
//! and how the best solution is kept. What is shared is the loop every fitting repeats
//! — locate → measure → propose → refit → accept — with its rules as data
//! ([`FitRules`]):
//!
//! - **measure** ([`Measure`]): the largest distance of a located point from the
//!   position it was fitted to, or from the nearest node; converged at ≤ `tolerance`;
//! - **propose** ([`Secant`]): per point a secant step on F(x) = g(x) − x, with x the
//!   position fitted to and g the located point, from the pass before (it converges
//!   also where g' ≈ −1, a period-2 oscillation of plain substitution x ← g(x), or
//!   g' ≈ 1); a step beyond `bound`·|F| is clamped or replaced by the plain step F;
//!   without a usable secant (first pass, |ΔF| ≤ `degenerate`, Δx = 0) the plain step
//!   x + F or the located point g itself;
//! - **limit** ([`MoveLimit`]): an absolute cap on the step from x, or a cap relative
//!   to the local element measured from the node nearest g, which doubles after an
//!   accepted pass and shrinks after a rejected one (a failed refit retried with a
//!   smaller move; a rejection restarts the secant from the located points);
//! - **stall** ([`Stall`]): stop when the measure has not improved by a factor in some
//!   passes and is already small;
//! - **keep best**: a fitting that does not converge returns the solution with the
//!   smallest measure instead of the last one;
//! - at most `max_passes` refit attempts.

use drive::contour::Contour;
use numerics::phases::{self, timed, Phase};

use crate::mesh::{Grading, Mesh};

/// A solution whose mesh is fitted to points it locates on itself.
pub trait Fitted {
    /// Why a refit failed (its solve did not converge).
    type Failure;
    /// A kept copy of the accepted solution ([`FitRules::keep_best`]).
    type Snapshot;
    /// The mesh of the accepted solution.
    fn mesh(&self) -> &Mesh;
    /// The points (σ on the contour, m) the mesh should have a node at, located on the
    /// accepted solution; the same point keeps its index from pass to pass.
    fn locate(&mut self) -> Vec<f64>;
    /// Solve on `mesh`, fitted to `points` (the order of [`Fitted::locate`]), from the
    /// accepted solution. On `Ok` the new solution is the accepted one; on `Err` the
    /// old one stays.
    ///
    /// # Errors
    /// The failed solve.
    fn refit(&mut self, mesh: Mesh, points: &[f64]) -> Result<(), Self::Failure>;
    /// A copy of the accepted solution.
    fn snapshot(&self) -> Self::Snapshot;
    /// Make a copy the accepted solution again.
    fn restore(&mut self, snapshot: Self::Snapshot);
    /// The grading of the fitted meshes towards the points ([`Mesh::regraded`]); `None`
    /// (the default): uniform pieces between them.
    fn grading(&self) -> Option<Grading> {
        None
    }
}

/// What the fitting measures after each pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// max |g − x| over the points, x the position the mesh was fitted to (∞ before the
    /// first pass or when the number of points changed).
    FittedTo,
    /// max over the points of the distance to the nearest node.
    NearestNode,
}

/// A secant step larger than the bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// Clamped to ±bound·|F|.
    Clamp,
    /// Replaced by the plain step F.
    Plain,
}

/// The proposal without a usable secant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fallback {
    /// x + F (subject to the step cap).
    Step,
    /// The located point g.
    Located,
}

/// The secant proposal per point (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Secant {
    /// Largest trusted secant step, as a multiple of |F|.
    pub bound: f64,
    /// What a larger step becomes.
    pub beyond: Beyond,
    /// |F − F_prev| at or below this (m) makes the secant degenerate.
    pub degenerate: f64,
    /// The proposal without a usable secant.
    pub fallback: Fallback,
}

/// The limit on one pass's move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MoveLimit {
    /// |step from x| ≤ this, m; a failed refit ends the fitting.
    Step(f64),
    /// |proposal − node nearest g| ≤ f·h, h the length of the element containing g; f
    /// starts at `max`, becomes min(`grow`·f, `max`) after an accepted pass and
    /// `shrink`·f after a rejected one; a rejection with f ≤ `min` ends the fitting.
    Element { max: f64, grow: f64, shrink: f64, min: f64 },
}

/// The stall rule: stop when the measure has not fallen below `gain` times the best
/// one for `patience` passes and is below `below` (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stall {
    /// Factor an improvement must beat.
    pub gain: f64,
    /// Passes without improvement.
    pub patience: usize,
    /// The measure must be below this, m.
    pub below: f64,
}

/// The rules of a fitting (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitRules {
    /// Converged when the measure is ≤ this, m.
    pub tolerance: f64,
    /// Largest number of refit attempts (accepted and rejected).
    pub max_passes: usize,
    /// What is measured.
    pub measure: Measure,
    /// The proposal.
    pub secant: Secant,
    /// The move limit.
    pub limit: MoveLimit,
    /// The stall rule, if any.
    pub stall: Option<Stall>,
    /// A fitting that does not converge returns the solution of the smallest measure
    /// (among those measured against their fitted positions).
    pub keep_best: bool,
    /// The fitted meshes' tie tolerance of their element distribution, in elements
    /// ([`Mesh::regraded`]).
    pub tie: f64,
    /// Bisection of a located point that jumps across its node, m (`None`: none). When
    /// the stall rule's patience runs out above its `below`, each point whose residual
    /// F = g − x changed sign between two accepted passes is fitted to the middle of the
    /// narrowest such bracket instead; the fitting ends [`FitEnd::Bracketed`] once
    /// every point is either below the stall's `below` or bracketed within this width.
    /// A locator that is discontinuous in x (a node that flips from stick to slip as it
    /// crosses the discrete transition, docs/fem-drive.md §12) has no fixed point; the
    /// jump is where the mesh puts its node.
    pub bracket: Option<f64>,
}

/// How a fitting ended.
#[derive(Debug)]
pub enum FitEnd<F> {
    /// Every point within the tolerance.
    Converged,
    /// `max_passes` refits attempted.
    PassLimit,
    /// The stall rule stopped it.
    Stalled,
    /// Every point either below the stall's `below` or, bisected, fitted to a jump of
    /// its locator: `width` (m) the widest remaining bracket, `jump` (m) the largest
    /// |g − x| of a bracketed point — the located positions carry up to that much.
    Bracketed {
        /// The widest remaining bracket, m.
        width: f64,
        /// The largest |g − x| of a bracketed point, m.
        jump: f64,
    },
    /// A refit failed (and the move limit allows no retry).
    Refit(F),
}

/// What a fitting did.
#[derive(Debug)]
pub struct FitOutcome<F> {
    /// How it ended.
    pub end: FitEnd<F>,
    /// Accepted refits.
    pub passes: usize,
    /// Rejected refits (retried with a smaller move).
    pub rejected: usize,
    /// The measure of the returned solution, m (`None`: not measured, or ∞).
    pub last_move: Option<f64>,
}

impl<F> FitOutcome<F> {
    /// True if every point is within the tolerance.
    pub fn converged(&self) -> bool {
        matches!(self.end, FitEnd::Converged | FitEnd::Bracketed { .. })
    }
}

/// What a contact fitting did, as a run reports it (flattened into the static
/// [`crate::HomotopyReport`] and the steady drive's report: the field names are the
/// report's keys).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct FitReport {
    /// Fitting passes done (each a Newton solve on a refitted mesh).
    pub fits: usize,
    /// True if the fitting converged ([`FitRules::tolerance`] met by its measure).
    pub fit_converged: bool,
    /// The measure of the returned solution after the last pass ([`FitOutcome::last_move`]),
    /// m: the largest boundary move (static), the largest distance of a located point
    /// from its node (steady).
    pub fit_last_move: Option<f64>,
    /// Why a fitting pass failed (the solution is then the last converged one).
    pub fit_failure: Option<String>,
}

impl FitReport {
    /// Adds the passes of `out` and takes its end (a failure is kept from an earlier
    /// fitting unless this one fails too).
    pub fn record<F: std::fmt::Display>(&mut self, out: &FitOutcome<F>) {
        self.fits += out.passes;
        self.fit_converged = out.converged();
        self.fit_last_move = out.last_move;
        match &out.end {
            FitEnd::Refit(e) => self.fit_failure = Some(e.to_string()),
            FitEnd::Converged | FitEnd::PassLimit | FitEnd::Stalled | FitEnd::Bracketed { .. } => {}
        }
    }

    /// The fitting as a run states it when it did not converge: `None` if it met its
    /// `tolerance` (m) or never ran (no passes and no failure).
    pub fn unfitted(&self, tolerance: f64) -> Option<Unfitted> {
        let ran = self.fits > 0 || self.fit_failure.is_some();
        (ran && !self.fit_converged).then(|| Unfitted { passes: self.fits, last_move: self.fit_last_move, tolerance, failure: self.fit_failure.clone() })
    }
}

/// A contact fitting that ended without meeting its tolerance: the result is the best
/// fitted solution, with its contact boundaries up to `last_move` off their nodes — not
/// a converged answer (stated as a warning; `"converged": false` in the result, a failed
/// run in a study, docs/fem-string.md §5).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Unfitted {
    /// Fitting passes done.
    pub passes: usize,
    /// The largest boundary move of the returned solution, m (`None`: never measured).
    pub last_move: Option<f64>,
    /// The tolerance it did not meet, m.
    pub tolerance: f64,
    /// Why a fitting pass failed, if one did.
    pub failure: Option<String>,
}

impl Unfitted {
    /// True if the fitting stopped without a failed pass (its pass limit): the result is
    /// then no converged answer. After a failed pass the result is the last converged
    /// solve, stated only (the documented coarse-mesh case, `string-hanging-very-slack`
    /// with `string-gauss` at 128 elements, which the gate keeps as a run).
    pub fn not_converged(&self) -> bool {
        self.failure.is_none()
    }
}

impl std::fmt::Display for Unfitted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "the contact fitting did not converge: after {} pass(es) ", self.passes)?;
        match self.last_move {
            Some(m) => write!(f, "a contact boundary still moved {} m, above the tolerance {} m", numerics::Sig(m), numerics::Sig(self.tolerance))?,
            None => write!(f, "no boundary was measured against its node (tolerance {} m)", numerics::Sig(self.tolerance))?,
        }
        if let Some(e) = &self.failure {
            write!(f, "; a pass failed: {e}")?;
        }
        write!(f, "; the result is the best fitted solution, its contact boundaries up to that far from their nodes")
    }
}

/// a − b on a periodic contour of length `period`, in (−period/2, period/2].
pub fn periodic_diff(a: f64, b: f64, period: f64) -> f64 {
    let d = (a - b).rem_euclid(period);
    if d > 0.5 * period {
        d - period
    } else {
        d
    }
}

/// Fit the mesh of `problem` by `rules` (module documentation). The accepted solution
/// at the end is the fitted one (or the best, [`FitRules::keep_best`]).
/// Timed as [`Phase::Fitting`] (its Newton solves in their own phases), its accepted
/// passes counted.
pub fn fit<P: Fitted>(problem: &mut P, rules: &FitRules) -> FitOutcome<P::Failure> {
    timed(Phase::Fitting, || {
        let out = fit_passes(problem, rules);
        phases::count(phases::Step::FittingPass, out.passes);
        out
    })
}

fn fit_passes<P: Fitted>(problem: &mut P, rules: &FitRules) -> FitOutcome<P::Failure> {
    let contour = *problem.mesh().contour();
    let period = contour.length();
    // the positions the accepted mesh was fitted to (none at the start and after a
    // rejected refit) and (x, F) of the pass before, for the secant
    let mut fitted_to: Vec<f64> = Vec::new();
    let mut previous: Option<(Vec<f64>, Vec<f64>)> = None;
    let mut best: Option<(f64, P::Snapshot)> = None;
    let (mut best_move, mut best_attempt) = (f64::INFINITY, 0usize);
    let mut factor = match rules.limit {
        MoveLimit::Element { max, .. } => max,
        MoveLimit::Step(_) => 0.0,
    };
    let mut out = FitOutcome { end: FitEnd::PassLimit, passes: 0, rejected: 0, last_move: None };
    let mut attempts = 0;
    // (x, F) of every accepted pass, per point, while the point count holds; and
    // whether the stall rule has turned to bisection (`rules.bracket`)
    let mut history: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut bisecting = false;
    loop {
        // locate and measure
        let located = problem.locate();
        let residual: Option<Vec<f64>> =
            (fitted_to.len() == located.len()).then(|| located.iter().zip(&fitted_to).map(|(g, x)| periodic_diff(*g, *x, period)).collect());
        let moved = match rules.measure {
            Measure::FittedTo => residual.as_ref().map_or(f64::INFINITY, |f| f.iter().fold(0.0f64, |m, f| m.max(f.abs()))),
            Measure::NearestNode => {
                let nodes = problem.mesh().node_sigmas();
                located.iter().map(|&g| nodes.iter().map(|&n| periodic_diff(n, g, period).abs()).fold(f64::INFINITY, f64::min)).fold(0.0f64, f64::max)
            }
        };
        out.last_move = moved.is_finite().then_some(moved);
        match &residual {
            Some(f) => {
                if history.len() != f.len() {
                    history = vec![Vec::new(); f.len()];
                }
                for (h, (x, f)) in history.iter_mut().zip(fitted_to.iter().zip(f)) {
                    h.push((*x, *f));
                }
            }
            None => history.clear(),
        }
        if rules.keep_best && residual.is_some() && best.as_ref().is_none_or(|(m, _)| moved < *m) {
            best = Some((moved, problem.snapshot()));
        }
        if moved <= rules.tolerance {
            out.end = FitEnd::Converged;
            break;
        }
        if let Some(stall) = rules.stall {
            if moved < stall.gain * best_move {
                best_move = moved;
                best_attempt = attempts;
            } else if attempts >= best_attempt + stall.patience && moved < stall.below {
                out.end = FitEnd::Stalled;
                break;
            } else if attempts >= best_attempt + stall.patience && rules.bracket.is_some() && residual.is_some() {
                bisecting = true;
            }
        }
        // the brackets of the bisected points (`None` for the others)
        let brackets: Vec<Option<(f64, f64)>> = match (&residual, bisecting) {
            (Some(_), true) => fitted_to.iter().zip(&history).map(|(x, h)| bracket(h, *x, period)).collect(),
            _ => Vec::new(),
        };
        if let (Some(f), Some(width), Some(stall)) = (&residual, rules.bracket, rules.stall.filter(|_| !brackets.is_empty())) {
            let bracketed = |i: usize| brackets[i].filter(|(lo, hi)| hi - lo <= width);
            if (0..f.len()).all(|i| f[i].abs() < stall.below || bracketed(i).is_some()) && (0..f.len()).any(|i| bracketed(i).is_some()) {
                let bracketed: Vec<usize> = (0..f.len()).filter(|&i| bracketed(i).is_some()).collect();
                let width = bracketed.iter().filter_map(|&i| brackets[i]).map(|(lo, hi)| hi - lo).fold(0.0, f64::max);
                let jump = bracketed.iter().map(|&i| f[i].abs()).fold(0.0, f64::max);
                out.end = FitEnd::Bracketed { width, jump };
                break;
            }
        }
        if attempts >= rules.max_passes {
            out.end = FitEnd::PassLimit;
            break;
        }
        attempts += 1;

        // propose
        let mut next = propose(problem.mesh(), &contour, rules, factor, &located, &fitted_to, residual.as_deref(), previous.as_ref());
        for (n, b) in next.iter_mut().zip(&brackets) {
            if let Some((lo, hi)) = b {
                *n = contour.wrap(0.5 * (lo + hi));
            }
        }
        previous = residual.map(|f| (std::mem::take(&mut fitted_to), f));

        // refit and accept, on the accepted mesh's topology (a loop's or an open mesh's
        // regions and elements per region: the same unknowns and sparsity pattern)
        let (mesh, _) = problem.mesh().regraded(&next, problem.grading(), rules.tie);
        match (problem.refit(mesh, &next), rules.limit) {
            (Ok(()), limit) => {
                out.passes += 1;
                fitted_to = next;
                if let MoveLimit::Element { max, grow, .. } = limit {
                    factor = (grow * factor).min(max);
                }
            }
            (Err(_), MoveLimit::Element { shrink, min, .. }) if factor > min => {
                factor *= shrink;
                out.rejected += 1;
            }
            (Err(f), _) => {
                out.end = FitEnd::Refit(f);
                break;
            }
        }
    }
    if let Some((m, snapshot)) = best.filter(|_| !out.converged()) {
        problem.restore(snapshot);
        out.last_move = Some(m);
    }
    out
}

/// The narrowest bracket of a sign change of F among the (x, F) of `history`, as
/// (lo, hi) with lo < hi unwrapped next to `x` (period `period`); `None` without one.
fn bracket(history: &[(f64, f64)], x: f64, period: f64) -> Option<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = history.iter().map(|(xj, f)| (x + periodic_diff(*xj, x, period), *f)).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.windows(2).filter(|w| w[0].1 * w[1].1 < 0.0 && w[1].0 > w[0].0).map(|w| (w[0].0, w[1].0)).min_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)))
}

/// The next positions: per located point `g`, the secant proposal from the position
/// fitted to (when the point count is unchanged), then the move limit.
#[allow(clippy::too_many_arguments)]
fn propose(
    mesh: &Mesh,
    contour: &Contour,
    rules: &FitRules,
    factor: f64,
    located: &[f64],
    fitted_to: &[f64],
    residual: Option<&[f64]>,
    previous: Option<&(Vec<f64>, Vec<f64>)>,
) -> Vec<f64> {
    let period = contour.length();
    let s = &rules.secant;
    let previous = previous.filter(|(xp, _)| xp.len() == fitted_to.len());
    (0..located.len())
        .map(|i| {
            let g = located[i];
            let proposed = match residual {
                Some(f) => {
                    let (x, f) = (fitted_to[i], f[i]);
                    let secant = previous.and_then(|(xp, fp)| {
                        let dx = periodic_diff(x, xp[i], period);
                        let df = f - fp[i];
                        (df.abs() > s.degenerate && dx != 0.0).then(|| -f * dx / df)
                    });
                    let bound = s.bound * f.abs();
                    let step = match secant {
                        Some(step) if step.abs() <= bound => Some(step),
                        Some(step) if step.is_finite() && s.beyond == Beyond::Clamp => Some(step.max(-bound).min(bound)),
                        Some(_) => Some(f),
                        None if s.fallback == Fallback::Step => Some(f),
                        None => None,
                    };
                    match (step, rules.limit) {
                        (Some(step), MoveLimit::Step(cap)) => contour.wrap(x + step.max(-cap).min(cap)),
                        (Some(step), _) => contour.wrap(x + step),
                        (None, _) => g,
                    }
                }
                None => g,
            };
            match rules.limit {
                MoveLimit::Element { .. } => {
                    // measured from the node nearest g, in the element containing g
                    let near = mesh
                        .node_sigmas()
                        .iter()
                        .copied()
                        .min_by(|a, b| periodic_diff(*a, g, period).abs().total_cmp(&periodic_diff(*b, g, period).abs()))
                        .unwrap_or(g);
                    let (e, _) = mesh.locate(g);
                    let limit = factor * mesh.elements()[e].h;
                    let d = periodic_diff(proposed, near, period);
                    if d.abs() > limit {
                        contour.wrap(near + limit * d.signum())
                    } else {
                        proposed
                    }
                }
                MoveLimit::Step(_) => proposed,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    //! The driver on a synthetic fitting whose fixed points are known: each located
    //! point is g(x) = a + k (x − a) of the position x the solution was fitted to, so
    //! F(x) = (k − 1)(x − a) is linear and the secant lands on a in one step.
    use super::*;
    use drive::contour::Region;

    const ELEMENTS: usize = 32;

    /// Located points g = a + k (x − a) (plus `drift` per refit); refit number
    /// `fail_at` fails. `moves`: per refit attempt, the largest distance of a proposed
    /// point from the node nearest its located point, in element lengths.
    struct Linear {
        mesh: Mesh,
        x: Vec<f64>,
        a: Vec<f64>,
        k: Vec<f64>,
        drift: f64,
        fail_at: Option<usize>,
        refits: usize,
        moves: Vec<f64>,
    }

    impl Linear {
        fn new(a: Vec<f64>, k: Vec<f64>, x: Vec<f64>) -> Linear {
            let mesh = Mesh::new(contour(), ELEMENTS, 1.0).unwrap();
            Linear { mesh, x, a, k, drift: 0.0, fail_at: None, refits: 0, moves: Vec::new() }
        }
    }

    impl Fitted for Linear {
        type Failure = f64;
        type Snapshot = (Mesh, Vec<f64>);
        fn mesh(&self) -> &Mesh {
            &self.mesh
        }
        fn locate(&mut self) -> Vec<f64> {
            (0..self.a.len()).map(|i| self.a[i] + self.k[i] * (self.x[i] - self.a[i]) + self.drift * self.refits as f64).collect()
        }
        fn refit(&mut self, mesh: Mesh, points: &[f64]) -> Result<(), f64> {
            self.refits += 1;
            let period = self.mesh.contour().length();
            let located = self.locate();
            let mut largest = 0.0f64;
            for (p, g) in points.iter().zip(&located) {
                let node = self.mesh.node_sigmas().iter().copied().min_by(|m, n| periodic_diff(*m, *g, period).abs().total_cmp(&periodic_diff(*n, *g, period).abs())).unwrap();
                let h = self.mesh.elements()[self.mesh.locate(*g).0].h;
                largest = largest.max(periodic_diff(*p, node, period).abs() / h);
            }
            self.moves.push(largest);
            if self.fail_at == Some(self.refits) {
                return Err(largest);
            }
            self.mesh = mesh;
            self.x = points.to_vec();
            Ok(())
        }
        fn snapshot(&self) -> (Mesh, Vec<f64>) {
            (self.mesh.clone(), self.x.clone())
        }
        fn restore(&mut self, (mesh, x): (Mesh, Vec<f64>)) {
            self.mesh = mesh;
            self.x = x;
        }
    }

    fn contour() -> Contour {
        Contour::new(0.1, 0.5).unwrap()
    }

    /// Mid-span of the upper span and mid-arc of the driven arc.
    fn fixed_points() -> Vec<f64> {
        let c = contour();
        [Region::UpperSpan, Region::DrivenArc].iter().map(|r| c.region_bounds(*r)).map(|(a, b)| 0.5 * (a + b) + 0.013).collect()
    }

    /// The static fit's rules (fem-string.md §5).
    fn static_rules() -> FitRules {
        FitRules {
            tolerance: 1e-12,
            max_passes: 10,
            measure: Measure::FittedTo,
            secant: Secant { bound: 50.0, beyond: Beyond::Clamp, degenerate: 0.0, fallback: Fallback::Step },
            limit: MoveLimit::Step(0.01),
            stall: None,
            keep_best: true,
            tie: 1e-3,
            bracket: None,
        }
    }

    /// The steady fit's rules (fem-drive.md §12).
    fn steady_rules() -> FitRules {
        FitRules {
            measure: Measure::NearestNode,
            secant: Secant { bound: 2.0, beyond: Beyond::Plain, degenerate: 1e-12 * contour().length(), fallback: Fallback::Located },
            limit: MoveLimit::Element { max: 0.3, grow: 2.0, shrink: 0.25, min: 0.02 },
            stall: Some(Stall { gain: 0.9, patience: 4, below: 1e-3 }),
            keep_best: false,
            max_passes: 30,
            tie: 0.0,
            ..static_rules()
        }
    }

    #[test]
    fn the_secant_lands_on_the_fixed_points_in_three_passes() {
        // k = −0.9: plain substitution x ← g(x) would oscillate and shrink by 0.9 per
        // pass (≈ 250 passes to 1e-12); k = 0.95 creeps. Pass 1 fits to g(x₀), pass 2
        // takes the plain step x + F, pass 3 the secant, exact for a linear F up to
        // round-off of σ ≈ 1 m (1e-15 m); the fourth measure converges.
        let a = fixed_points();
        let x0 = vec![a[0] + 0.004, a[1] - 0.003];
        let mut p = Linear::new(a.clone(), vec![-0.9, 0.95], x0);
        let out = fit(&mut p, &static_rules());
        assert!(out.converged(), "{:?}", out.end);
        assert_eq!((out.passes, out.rejected), (3, 0));
        for (x, a) in p.x.iter().zip(&a) {
            assert!((x - a).abs() < 1e-13, "fitted {x}, fixed point {a}");
        }
        assert!(out.last_move.is_some_and(|m| m <= 1e-12));
        // the nodes sit on the fixed points
        for a in &a {
            assert!(p.mesh.node_sigmas().iter().any(|n| (n - a).abs() < 1e-13));
        }
    }

    #[test]
    fn the_step_cap_slows_the_secant() {
        // the same problem with the step from x capped at 1 mm: the 4 mm and 3 mm
        // offsets need more passes, and every pass moves a point by ≤ 1 mm
        let a = fixed_points();
        let mut p = Linear::new(a.clone(), vec![-0.9, 0.95], vec![a[0] + 0.004, a[1] - 0.003]);
        let capped = FitRules { limit: MoveLimit::Step(1e-3), ..static_rules() };
        let out = fit(&mut p, &capped);
        assert!(out.converged(), "{:?}", out.end);
        assert!(out.passes > 3 && out.passes <= capped.max_passes, "{} passes", out.passes);
        for (x, a) in p.x.iter().zip(&a) {
            assert!((x - a).abs() < 1e-12, "fitted {x}, fixed point {a}");
        }
    }

    #[test]
    fn a_failed_refit_keeps_the_best_solution() {
        // the second refit fails: the fitting ends with that failure and returns the
        // solution of pass 1, the only one measured against its fitted positions
        let a = fixed_points();
        let mut p = Linear::new(a.clone(), vec![-0.9, 0.95], vec![a[0] + 0.004, a[1] - 0.003]);
        p.fail_at = Some(2);
        let x1: Vec<f64> = p.locate();
        let f1 = (0..2).map(|i| (a[i] + p.k[i] * (x1[i] - a[i]) - x1[i]).abs()).fold(0.0, f64::max);
        let out = fit(&mut p, &static_rules());
        assert!(matches!(out.end, FitEnd::Refit(_)), "{:?}", out.end);
        assert_eq!((out.passes, out.rejected), (1, 0));
        assert_eq!(p.x, x1);
        let m = out.last_move.unwrap();
        assert!((m - f1).abs() <= 1e-15, "{m} against {f1}");
    }

    #[test]
    fn the_move_limit_retries_smaller_moves_and_converges() {
        // started 6 elements off with k = ±0.5; the first refit fails. Each pass moves a
        // point at most f element lengths from the node nearest its located point, f
        // starting at 0.3, ×¼ on the rejection (0.075), then ×2 per accepted pass up
        // to 0.3 again; the secant restarts after the rejection and still reaches the
        // fixed points
        let a = fixed_points();
        let mesh = Mesh::new(contour(), ELEMENTS, 1.0).unwrap();
        let h = mesh.elements()[mesh.locate(a[0]).0].h;
        let mut p = Linear::new(a.clone(), vec![-0.5, 0.5], vec![a[0] + 6.0 * h, a[1] - 6.0 * h]);
        p.fail_at = Some(1);
        let rules = steady_rules();
        let out = fit(&mut p, &rules);
        assert!(out.converged(), "{:?}", out.end);
        assert_eq!(out.rejected, 1);
        assert!(out.passes >= 3 && out.passes + out.rejected <= rules.max_passes, "{} passes", out.passes);
        let schedule = [0.3, 0.075, 0.15, 0.3];
        for (k, m) in p.moves.iter().enumerate() {
            let f = schedule[k.min(3)];
            assert!(*m <= f + 1e-9, "refit {}: a move of {m} elements above the limit {f}", k + 1);
        }
        // the limit was active: the first moves were cut to it
        assert!((p.moves[1] - 0.075).abs() < 1e-9, "{:?}", p.moves);
        for (x, a) in p.x.iter().zip(&a) {
            assert!((x - a).abs() < 1e-12, "fitted {x}, fixed point {a}");
        }
    }

    #[test]
    fn a_drifting_point_stalls_after_the_patience() {
        // every refit moves the located points by 10 µm: the nearest-node measure stays
        // at 10 µm, never 10 % better than the first, so the fitting stops after 4
        // passes (the patience) with the measure 10 µm
        let a = fixed_points();
        let mut p = Linear::new(a.clone(), vec![0.0, 0.0], a.clone());
        p.drift = 1e-5;
        // start on nodes so the first measure is the drift too
        let nodes: Vec<f64> = a.iter().map(|&s| p.mesh.node_sigmas().iter().copied().min_by(|m, n| (m - s).abs().total_cmp(&(n - s).abs())).unwrap()).collect();
        p.a = nodes.clone();
        p.x = nodes;
        p.refits = 1;
        let out = fit(&mut p, &steady_rules());
        assert!(matches!(out.end, FitEnd::Stalled), "{:?}", out.end);
        assert_eq!((out.passes, out.rejected), (4, 0));
        let m = out.last_move.unwrap();
        assert!((m - 1e-5).abs() < 1e-12, "{m}");
    }

    #[test]
    fn periodic_differences_wrap() {
        let l = 2.0;
        // the short way round, of either sign; half the period counts as +
        assert!((periodic_diff(0.1, 1.9, l) - 0.2).abs() < 1e-15);
        assert!((periodic_diff(1.9, 0.1, l) + 0.2).abs() < 1e-15);
        assert_eq!(periodic_diff(1.0, 0.0, l), 1.0);
        assert_eq!(periodic_diff(0.0, 1.0, l), 1.0);
    }

    /// A located point that jumps across its node: g(x) = a + J/2 for x < a, a − J/2
    /// for x ≥ a (a node that sticks on one side of the discrete transition and slips
    /// on the other), so F = g − x has no zero. The second point is linear and
    /// converges.
    struct Jump {
        lin: Linear,
        jump: f64,
    }

    impl Fitted for Jump {
        type Failure = f64;
        type Snapshot = (Mesh, Vec<f64>);
        fn mesh(&self) -> &Mesh {
            self.lin.mesh()
        }
        fn locate(&mut self) -> Vec<f64> {
            let mut g = self.lin.locate();
            let (x, a) = (self.lin.x[0], self.lin.a[0]);
            g[0] = if x < a { a + 0.5 * self.jump } else { a - 0.5 * self.jump };
            g
        }
        fn refit(&mut self, mesh: Mesh, points: &[f64]) -> Result<(), f64> {
            self.lin.refit(mesh, points)
        }
        fn snapshot(&self) -> (Mesh, Vec<f64>) {
            self.lin.snapshot()
        }
        fn restore(&mut self, s: (Mesh, Vec<f64>)) {
            self.lin.restore(s)
        }
    }

    #[test]
    fn a_point_that_jumps_across_its_node_is_bisected_onto_the_jump() {
        // J = 8 mm (16 % of an element) above the stall's 1 mm: without the bracket
        // rule the secant and the plain steps cycle across a until the pass limit
        let a = fixed_points();
        let jump = 8e-3;
        let width = 1e-4;
        let start = || Jump { lin: Linear::new(a.clone(), vec![-0.9, 0.5], vec![a[0] + 0.01, a[1] - 0.003]), jump };
        let mut p = start();
        let out = fit(&mut p, &steady_rules());
        assert!(matches!(out.end, FitEnd::PassLimit), "{:?}", out.end);
        assert!(!out.converged());
        // with it: bisected onto the jump to within the bracket width, the linear
        // point converged to below the stall's 1 mm, and the jump reported
        let rules = FitRules { bracket: Some(width), ..steady_rules() };
        let mut p = start();
        let out = fit(&mut p, &rules);
        let FitEnd::Bracketed { width: w, jump: j } = out.end else { panic!("{:?}", out.end) };
        assert!(out.converged());
        assert!(w <= width && w > 0.0, "bracket {w}");
        assert!((p.lin.x[0] - a[0]).abs() <= width, "fitted {} against the jump at {}", p.lin.x[0], a[0]);
        // |g − x| at the end is the half jump plus at most the bracket
        assert!(j >= 0.5 * jump - width && j <= 0.5 * jump + width, "jump {j}");
        assert!((p.lin.x[1] - a[1]).abs() < 1e-3, "linear point at {} against {}", p.lin.x[1], a[1]);
        assert!(out.passes + out.rejected <= rules.max_passes);
    }
}
