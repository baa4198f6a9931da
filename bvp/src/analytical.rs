//! Closed-form solutions used by tests, examples and benchmarks; each cites its source.

pub mod elastica {
    //! The clamped–clamped inextensible Euler elastica under unknown end loads, and its
    //! exact first (symmetric) buckling mode in Jacobi elliptic functions.
    //!
    //! # The problem (EI = 1, length 1, arclength s ∈ [0, 1])
    //!
    //! State y = (x, y, θ, m): position, tangent angle, bending moment m = EI θ'.
    //! Parameters p = (P, Q): the force applied to the end s = 1 is F = (−P, Q), so P > 0
    //! is an **axial compressive** load and Q the **transverse** load (+y).
    //!
    //! Derivation of the signs: with n(s) the force the part (s, 1] exerts on [0, s] and
    //! m(s) the moment, balance of a rod element without distributed loads gives n' = 0 and
    //! m' + r' × n = 0 (Antman, *Nonlinear Problems of Elasticity*, 2nd ed., §4.2). Hence
    //! n ≡ n(1) = (−P, Q), r' = (cos θ, sin θ) and r' × n = P sin θ + Q cos θ, so
    //!
    //! ```text
    //!     x' = cos θ,   y' = sin θ,   θ' = m,   m' = −P sin θ − Q cos θ.
    //! ```
    //!
    //! Linearised (Q = 0): θ'' + P θ = 0, the Euler column; the clamped–clamped critical load
    //! is P = 4π² with mode θ = sin 2πs. Boundary conditions (6 = 4 states + 2 parameters):
    //! x(0) = y(0) = θ(0) = 0, x(1) = a, y(1) = 0, θ(1) = 0, with end position a < 1.
    //!
    //! # Exact first mode (Love, *Mathematical Theory of Elasticity*, §263; Timoshenko &
    //! Gere, *Theory of Elastic Stability*, §2.7)
    //!
    //! With Q = 0 the angle obeys the pendulum equation θ'' = −P sin θ. Its solution with
    //! θ(0) = 0, θ'(0) > 0 is sin(θ/2) = k sn(√P s, k), k = sin(θ_max/2); θ returns to zero
    //! with the same slope after one full period √P = 4K(k). Writing u = 4K s:
    //!
    //! ```text
    //!     θ = 2 arcsin(k sn u),          m = 8 k K cn u,
    //!     x = (2 ε(u) − u) / (4K),       y = k (1 − cn u) / (2K),
    //!     P = 16 K²,  Q = 0,             a = x(1) = 2E/K − 1,
    //! ```
    //!
    //! using sin θ = 2k sn dn, cos θ = 2 dn² − 1, ∫ dn² = ε (Jacobi's epsilon) and
    //! ∫ sn dn = −cn. The shape rises to y_max = k/K at s = ½ and is symmetric about it.

    use crate::elliptic::{complete_ke, jacobi, jacobi_epsilon};
    use crate::error::BvpError;
    use crate::problem::{Problem, Scalar};
    use crate::solution::Solution;

    /// The clamped–clamped elastica BVP with end position `a` (see the module documentation).
    /// One segment, 4 components (x, y, θ, m), 2 parameters (P, Q).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct ClampedElastica {
        /// Prescribed x(1); 0 < a < 1 for a buckled state.
        pub a: f64,
    }

    impl Problem for ClampedElastica {
        fn n_segments(&self) -> usize {
            1
        }
        fn dim(&self, _k: usize) -> usize {
            4
        }
        fn n_params(&self) -> usize {
            2
        }
        fn rhs<D: Scalar>(&self, _k: usize, _s: f64, y: &[D], p: &[D], _eta: D, f: &mut [D]) {
            let (sin, cos) = (y[2].sin(), y[2].cos());
            f[0] = cos;
            f[1] = sin;
            f[2] = y[3];
            f[3] = -(p[0] * sin) - p[1] * cos;
        }
        fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], _p: &[D], _eta: D, r: &mut [D]) {
            r[0] = ya[0][0];
            r[1] = ya[0][1];
            r[2] = ya[0][2];
            r[3] = yb[0][0] - self.a;
            r[4] = yb[0][1];
            r[5] = yb[0][2];
        }
        fn component_names(&self, _k: usize) -> Vec<String> {
            ["x", "y", "theta", "m"].iter().map(|s| s.to_string()).collect()
        }
        fn param_names(&self) -> Vec<String> {
            vec!["P".into(), "Q".into()]
        }
    }

    /// The exact first mode for modulus k = sin(θ_max / 2).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Exact {
        /// Elliptic modulus k = sin(θ_max / 2), 0 < k < 1.
        pub k: f64,
        /// K(k).
        pub big_k: f64,
        /// E(k).
        pub big_e: f64,
    }

    impl Exact {
        /// The mode with modulus `k` ∈ (0, 1); [`BvpError::InvalidInput`] otherwise.
        pub fn new(k: f64) -> Result<Self, BvpError> {
            if !(k > 0.0 && k < 1.0) {
                return Err(BvpError::InvalidInput(format!("elastica modulus k = {k} outside (0, 1)")));
            }
            let (big_k, big_e) = complete_ke(k);
            Ok(Self { k, big_k, big_e })
        }

        /// The mode whose largest tangent angle is `theta_max` ∈ (0, π) radians.
        pub fn from_max_angle(theta_max: f64) -> Result<Self, BvpError> {
            Self::new((0.5 * theta_max).sin()).and_then(|e| {
                if theta_max > 0.0 && theta_max < std::f64::consts::PI {
                    Ok(e)
                } else {
                    Err(BvpError::InvalidInput(format!("theta_max = {theta_max} outside (0, π)")))
                }
            })
        }

        /// End position a = 2E/K − 1 (the BVP's x(1)).
        pub fn end_position(&self) -> f64 {
            2.0 * self.big_e / self.big_k - 1.0
        }

        /// The BVP this mode solves.
        pub fn problem(&self) -> ClampedElastica {
            ClampedElastica { a: self.end_position() }
        }

        /// Parameters (P, Q) = (16 K², 0).
        pub fn params(&self) -> [f64; 2] {
            [16.0 * self.big_k * self.big_k, 0.0]
        }

        /// Largest tangent angle θ_max = 2 arcsin k (at s = ¼).
        pub fn max_angle(&self) -> f64 {
            2.0 * self.k.asin()
        }

        /// State (x, y, θ, m) at arclength s ∈ [0, 1].
        pub fn state(&self, s: f64) -> [f64; 4] {
            let u = 4.0 * self.big_k * s;
            let j = jacobi(u, self.k);
            [
                (2.0 * jacobi_epsilon(u, self.k) - u) / (4.0 * self.big_k),
                self.k * (1.0 - j.cn) / (2.0 * self.big_k),
                2.0 * (self.k * j.sn).asin(),
                8.0 * self.k * self.big_k * j.cn,
            ]
        }

        /// Error of a computed solution against this mode:
        /// max over components i of max_s |y_i(s) − y_i^exact(s)| / max(1, max_s |y_i^exact|),
        /// the max over s taken on `samples` + 1 equally spaced points of the dense output
        /// (so interpolation error between nodes counts), and the load errors
        /// |P − P_exact| / P_exact and |Q − 0| / P_exact (loads relative to the exact load)
        /// are included in the max.
        pub fn max_error(&self, solution: &Solution, samples: usize) -> f64 {
            let samples = samples.max(1);
            let exact: Vec<[f64; 4]> = (0..=samples).map(|i| self.state(i as f64 / samples as f64)).collect();
            let mut err: f64 = 0.0;
            for c in 0..4 {
                let scale = exact.iter().map(|e| e[c].abs()).fold(1.0, f64::max);
                for (i, e) in exact.iter().enumerate() {
                    let y = solution.eval(0, i as f64 / samples as f64);
                    err = err.max((y[c] - e[c]).abs() / scale);
                }
            }
            let [p, _] = self.params();
            if solution.params.len() == 2 {
                err = err.max((solution.params[0] - p).abs() / p).max(solution.params[1].abs() / p);
            } else {
                err = f64::NAN;
            }
            err
        }
    }

    /// A starting guess of the form the linear buckling mode suggests: θ = ε sin 2πs,
    /// m = 2πε cos 2πs, (x, y) = ∫ (cos θ, sin θ) by the trapezoidal rule on `nodes`
    /// equally spaced nodes (an exactly consistent curve, not a solution: x(1) = J_0(ε) ≠ a
    /// in general), (P, Q) = (4π², 0). Piecewise-linear dense output, η = 0.
    pub fn guess(eps: f64, nodes: usize) -> Solution {
        let nodes = nodes.max(2);
        let two_pi = 2.0 * std::f64::consts::PI;
        let theta = |s: f64| eps * (two_pi * s).sin();
        // Positions on the node grid by the trapezoidal rule with 32 sub-steps per interval.
        let sub = 32;
        let mut xy = vec![[0.0_f64; 2]; nodes];
        let h = 1.0 / ((nodes - 1) * sub) as f64;
        let (mut x, mut y) = (0.0, 0.0);
        for (i, node) in xy.iter_mut().enumerate().skip(1) {
            for q in 0..sub {
                let s0 = ((i - 1) * sub + q) as f64 * h;
                let (t0, t1) = (theta(s0), theta(s0 + h));
                x += 0.5 * h * (t0.cos() + t1.cos());
                y += 0.5 * h * (t0.sin() + t1.sin());
            }
            *node = [x, y];
        }
        Solution::from_fn(1, nodes, vec![two_pi * two_pi, 0.0], 0.0, |_k, s| {
            let i = (s * (nodes - 1) as f64).round() as usize;
            let [x, y] = xy[i.min(nodes - 1)];
            vec![x, y, theta(s), two_pi * eps * (two_pi * s).cos()]
        })
    }
}

pub mod bratu {
    //! The Bratu (Liouville–Bratu–Gelfand) problem and its exact solutions.
    //!
    //! ```text
    //!     y'' + λ e^y = 0,   y(0) = y(1) = 0,
    //! ```
    //!
    //! as the first-order system y₀' = y₁, y₁' = −λ e^{y₀} with λ = η, the continuation
    //! parameter. Exact solutions (Bratu 1914; see J. P. Boyd, "Chebyshev polynomial
    //! expansions for simultaneous approximation of two branches of a function with
    //! application to the one-dimensional Bratu equation", Appl. Math. Comput. 143,
    //! 2003, eqs. (2)–(4); Ascher, Mattheij & Russell, "Numerical Solution of Boundary
    //! Value Problems for ODEs", SIAM 1995, Example 9.2):
    //!
    //! ```text
    //!     y(x)  = −2 ln[ cosh((x − ½) θ/2) / cosh(θ/4) ],
    //!     y'(x) = −θ tanh((x − ½) θ/2),
    //!     θ     = √(2λ) cosh(θ/4)     ⇔   λ = θ² / (2 cosh²(θ/4)).
    //! ```
    //!
    //! For 0 < λ < λ_c the θ equation has two roots (lower and upper branch); they meet
    //! at the fold θ_c, the root of (θ/4) tanh(θ/4) = 1, where λ_c = 3.513830719125162.

    use crate::error::BvpError;
    use crate::problem::{Problem, Scalar};
    use crate::solution::Solution;

    /// The fold (critical) value λ_c = θ_c² / (2 cosh²(θ_c/4)).
    pub const CRITICAL_LAMBDA: f64 = 3.513830719125162;
    /// θ at the fold: the root of (θ/4) tanh(θ/4) = 1.
    pub const CRITICAL_THETA: f64 = 4.798714561030935;

    /// The Bratu BVP with λ = η: one segment, 2 components (y, y'), no parameters.
    #[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
    pub struct Bratu;

    impl Problem for Bratu {
        fn n_segments(&self) -> usize {
            1
        }
        fn dim(&self, _k: usize) -> usize {
            2
        }
        fn n_params(&self) -> usize {
            0
        }
        fn rhs<D: Scalar>(&self, _k: usize, _x: f64, y: &[D], _p: &[D], eta: D, f: &mut [D]) {
            f[0] = y[1];
            f[1] = -(eta * y[0].exp());
        }
        fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], _p: &[D], _eta: D, r: &mut [D]) {
            r[0] = ya[0][0];
            r[1] = yb[0][0];
        }
        fn component_names(&self, _k: usize) -> Vec<String> {
            vec!["y".into(), "dy/dx".into()]
        }
    }

    /// Which of the two solutions for 0 < λ < λ_c.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum BratuBranch {
        /// θ < θ_c: the stable solution, y → 0 as λ → 0.
        Lower,
        /// θ > θ_c: the unstable solution, y(½) → ∞ as λ → 0.
        Upper,
    }

    /// λ(θ) = θ² / (2 cosh²(θ/4)).
    pub fn lambda_of_theta(theta: f64) -> f64 {
        let c = (theta / 4.0).cosh();
        theta * theta / (2.0 * c * c)
    }

    /// The root θ of θ = √(2λ) cosh(θ/4) on `branch`, by Brent's method (argmin) to
    /// 1e-14. Errors: λ outside (0, λ_c] → [`BvpError::InvalidInput`].
    pub fn theta(lambda: f64, branch: BratuBranch) -> Result<f64, BvpError> {
        if !(lambda > 0.0 && lambda <= CRITICAL_LAMBDA) {
            return Err(BvpError::InvalidInput(format!(
                "Bratu: lambda = {lambda} outside (0, {CRITICAL_LAMBDA}]"
            )));
        }
        let g = |t: f64| Ok(t - (2.0 * lambda).sqrt() * (t / 4.0).cosh());
        // g(θ_c) ≥ 0 for λ ≤ λ_c (up to rounding at λ = λ_c itself).
        if g(CRITICAL_THETA)? <= 0.0 {
            return Ok(CRITICAL_THETA);
        }
        match branch {
            BratuBranch::Lower => crate::continuation::brent_root(g, 0.0, CRITICAL_THETA, 1e-14),
            BratuBranch::Upper => {
                let mut hi = 2.0 * CRITICAL_THETA;
                while g(hi)? > 0.0 {
                    hi *= 2.0;
                }
                crate::continuation::brent_root(g, CRITICAL_THETA, hi, 1e-14)
            }
        }
    }

    /// One exact solution.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Exact {
        /// λ.
        pub lambda: f64,
        /// θ of the closed form.
        pub theta: f64,
    }

    impl Exact {
        /// The solution on `branch` at `lambda` ∈ (0, λ_c].
        pub fn new(lambda: f64, branch: BratuBranch) -> Result<Self, BvpError> {
            Ok(Self { lambda, theta: theta(lambda, branch)? })
        }

        /// The solution with a given θ ≥ 0 (λ follows).
        pub fn from_theta(theta: f64) -> Self {
            Self { lambda: lambda_of_theta(theta), theta }
        }

        /// (y(x), y'(x)).
        pub fn state(&self, x: f64) -> [f64; 2] {
            let a = (x - 0.5) * self.theta / 2.0;
            [-2.0 * (a.cosh() / (self.theta / 4.0).cosh()).ln(), -self.theta * a.tanh()]
        }

        /// y(½) = 2 ln cosh(θ/4), the usual branch diagram coordinate.
        pub fn midpoint(&self) -> f64 {
            2.0 * (self.theta / 4.0).cosh().ln()
        }

        /// max over mesh nodes and components of |y_num − y_exact|.
        pub fn max_node_error(&self, solution: &Solution) -> f64 {
            let seg = &solution.segments[0];
            seg.mesh
                .iter()
                .zip(&seg.nodes)
                .flat_map(|(&x, y)| {
                    let e = self.state(x);
                    [(y[0] - e[0]).abs(), (y[1] - e[1]).abs()]
                })
                .fold(0.0, f64::max)
        }

        /// max over `samples` equally spaced points (≥ 2) of the dense-output error.
        pub fn max_dense_error(&self, solution: &Solution, samples: usize) -> f64 {
            let samples = samples.max(2);
            (0..samples)
                .map(|i| {
                    let x = i as f64 / (samples - 1) as f64;
                    let (u, e) = (solution.eval(0, x), self.state(x));
                    (u[0] - e[0]).abs().max((u[1] - e[1]).abs())
                })
                .fold(0.0, f64::max)
        }

        /// The exact solution sampled on `nodes` equally spaced nodes (piecewise-linear
        /// dense output), at η = λ: a guess that lies on the chosen branch.
        pub fn guess(&self, nodes: usize) -> Solution {
            Solution::from_fn(1, nodes, vec![], self.lambda, |_, x| self.state(x).to_vec())
        }
    }
}
