//! A solved (or guessed) multi-segment BVP: node values, dense output, statistics.

use serde::Serialize;

/// The solution on one segment, on the normalised interval [0, 1].
#[derive(Debug, Clone, Serialize)]
pub struct SegmentSolution {
    /// Mesh nodes 0 = x_0 < x_1 < … < x_N = 1.
    pub mesh: Vec<f64>,
    /// `nodes[i]` = y(x_i), n_k components.
    pub nodes: Vec<Vec<f64>>,
    /// Dense output: `poly[i][j]` are the power-basis coefficients c_l of component j on
    /// interval i, u_j(x_i + t (x_{i+1} − x_i)) = Σ_l c_l t^l for t ∈ [0, 1].
    pub poly: Vec<Vec<Vec<f64>>>,
}

impl SegmentSolution {
    /// A segment whose dense output is the piecewise-linear interpolant of `nodes`.
    pub fn piecewise_linear(mesh: Vec<f64>, nodes: Vec<Vec<f64>>) -> Self {
        assert_eq!(mesh.len(), nodes.len(), "one node value per mesh node");
        let poly = (0..mesh.len() - 1)
            .map(|i| {
                (0..nodes[i].len())
                    .map(|j| vec![nodes[i][j], nodes[i + 1][j] - nodes[i][j]])
                    .collect()
            })
            .collect();
        Self { mesh, nodes, poly }
    }

    /// Number of ODE components.
    pub fn dim(&self) -> usize {
        self.nodes.first().map_or(0, Vec::len)
    }

    /// Index i of the interval [x_i, x_{i+1}] holding `x` (clamped to [0, 1]).
    pub fn interval(&self, x: f64) -> usize {
        let n = self.mesh.len() - 1;
        match self.mesh.partition_point(|&m| m <= x) {
            0 => 0,
            i if i > n => n - 1,
            i => (i - 1).min(n - 1),
        }
    }

    /// The interval of x ([`Self::interval`]) as (its polynomial coefficients, its
    /// length h, the local coordinate t = (x − x_i)/h).
    fn local(&self, x: f64) -> (&[Vec<f64>], f64, f64) {
        let i = self.interval(x);
        let h = self.mesh[i + 1] - self.mesh[i];
        (&self.poly[i], h, (x - self.mesh[i]) / h)
    }

    /// Dense output y(x), x ∈ [0, 1].
    pub fn eval(&self, x: f64) -> Vec<f64> {
        let mut y = vec![0.0; self.dim()];
        self.eval_into(x, &mut y);
        y
    }

    /// Dense output y(x) into `y` (length n), without allocating.
    pub fn eval_into(&self, x: f64, y: &mut [f64]) {
        let (poly, _, t) = self.local(x);
        for (ya, c) in y.iter_mut().zip(poly) {
            *ya = c.iter().rev().fold(0.0, |acc, &cl| acc * t + cl);
        }
    }

    /// Dense output of the derivative y'(x), x ∈ [0, 1].
    pub fn eval_derivative(&self, x: f64) -> Vec<f64> {
        let (poly, h, t) = self.local(x);
        poly.iter()
            .map(|c| {
                c.iter()
                    .enumerate()
                    .skip(1)
                    .rev()
                    .fold(0.0, |acc, (l, &cl)| acc * t + l as f64 * cl)
                    / h
            })
            .collect()
    }

    /// y(0).
    pub fn start(&self) -> &[f64] {
        &self.nodes[0]
    }

    /// y(1).
    pub fn end(&self) -> &[f64] {
        self.nodes.last().expect("a segment has at least two nodes")
    }

    /// y(ξ): the exact node values at ξ ≤ 0 and ξ ≥ 1, the dense output inside.
    pub fn state_at(&self, xi: f64) -> Vec<f64> {
        if xi <= 0.0 {
            self.start().to_vec()
        } else if xi >= 1.0 {
            self.end().to_vec()
        } else {
            self.eval(xi)
        }
    }
}

/// Work counters and outcome data of a solve. Exact counts, so that a change in
/// convergence shows up in tests and review.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Stats {
    /// Newton iterations summed over all mesh refinements (and continuation steps).
    pub newton_iterations: usize,
    /// Jacobian assemblies (each one numeric LU factorisation).
    pub jacobian_evaluations: usize,
    /// Right-hand-side evaluations f_k(x, y, p, η) with f64 arguments.
    pub rhs_evaluations: usize,
    /// Mesh adaptation passes (collocation) or integrations (shooting).
    pub refinements: usize,
    /// Size of the final nonlinear system.
    pub unknowns: usize,
    /// Final number of mesh nodes over all segments.
    pub mesh_nodes: usize,
    /// Largest scaled residual of the final solution (collocation: the relative
    /// residual norm of [`crate::collocation`]; shooting: the matching defect).
    pub max_residual: f64,
    /// Wall time in seconds.
    pub wall_seconds: f64,
}

impl Stats {
    /// Add the iteration counters of one step (Newton iterations, Jacobians, mesh passes);
    /// right-hand-side evaluations are counted by the caller's discretisation.
    pub fn add_iterations(&mut self, step: &Stats) {
        self.newton_iterations += step.newton_iterations;
        self.jacobian_evaluations += step.jacobian_evaluations;
        self.refinements += step.refinements;
    }

    /// Add the work counters of one stage of a run (homotopy, final solve): iterations
    /// and right-hand-side evaluations.
    pub fn add_work(&mut self, stage: &Stats) {
        self.add_iterations(stage);
        self.rhs_evaluations += stage.rhs_evaluations;
    }

    /// Close a run's total with its last stage: that stage's work, its size and residual,
    /// and the run's wall time since `clock`.
    pub fn close_with(&mut self, last: &Stats, clock: std::time::Instant) {
        self.add_work(last);
        self.unknowns = last.unknowns;
        self.mesh_nodes = last.mesh_nodes;
        self.max_residual = last.max_residual;
        self.wall_seconds = clock.elapsed().as_secs_f64();
    }
}

/// A multi-segment BVP solution; also used as an initial guess.
#[derive(Debug, Clone, Serialize)]
pub struct Solution {
    /// One entry per segment.
    pub segments: Vec<SegmentSolution>,
    /// The unknown parameters p.
    pub params: Vec<f64>,
    /// The continuation parameter η the solution belongs to.
    pub eta: f64,
    /// Work counters.
    pub stats: Stats,
}

impl Solution {
    /// A guess from a function `guess(k, x) -> y_k(x)` sampled on `nodes` equally spaced
    /// nodes per segment (piecewise-linear dense output).
    pub fn from_fn(
        n_segments: usize,
        nodes: usize,
        params: Vec<f64>,
        eta: f64,
        guess: impl Fn(usize, f64) -> Vec<f64>,
    ) -> Self {
        let nodes = nodes.max(2);
        let segments = (0..n_segments)
            .map(|k| {
                let mesh: Vec<f64> = (0..nodes).map(|i| i as f64 / (nodes - 1) as f64).collect();
                let values = mesh.iter().map(|&x| guess(k, x)).collect();
                SegmentSolution::piecewise_linear(mesh, values)
            })
            .collect();
        Self { segments, params, eta, stats: Stats::default() }
    }

    /// Dense output y_k(x).
    pub fn eval(&self, k: usize, x: f64) -> Vec<f64> {
        self.segments[k].eval(x)
    }

    /// Sample points (segment k, ξ) along all segments in order: every mesh node and
    /// `per_interval` − 1 equally spaced points inside each mesh interval, then ξ = 1.
    pub fn sample_points(&self, per_interval: usize) -> Vec<(usize, f64)> {
        let n = per_interval.max(1);
        let mut out = Vec::new();
        for (k, seg) in self.segments.iter().enumerate() {
            for w in seg.mesh.windows(2) {
                for j in 0..n {
                    out.push((k, w[0] + (w[1] - w[0]) * j as f64 / n as f64));
                }
            }
            out.push((k, 1.0));
        }
        out
    }
}
