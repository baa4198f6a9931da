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

pub mod belt_creep {
    //! Belt-creep theory of the gravity-free steady friction drive, exact for the
    //! extensible string (docs/string-drive.md, "The gravity-free closed form"; the
    //! reference's §6.1 and §8.2 (Paper B); Johnson, *Contact Mechanics*, §8.6, for the
    //! classical creep picture).
    //!
    //! Without gravity the spans are the straight outer tangents, each contact arc is π,
    //! each pulley has a stick zone at the incoming effective tension followed by a slip
    //! zone over which the effective tension T̃ = T − ρc²λ changes by e^{±μ φ_slip}. The
    //! one scalar unknown T̃_s (slack effective tension) is fixed by the **exact** total
    //! unstretched length, solved by Brent's method (argmin); the approximation
    //! T₁ + T₂ = 2T₀ is not used.

    use std::f64::consts::PI;

    use thiserror::Error;

    use crate::continuation::brent_root;

    /// Data of a gravity-free drive (SI units).
    #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
    pub struct CreepData {
        /// Pulley radius R to the belt centreline (m).
        pub radius: f64,
        /// Centre distance H (m).
        pub centre_distance: f64,
        /// Unstretched loop length L (m).
        pub length: f64,
        /// Axial stiffness EA (N).
        pub axial_stiffness: f64,
        /// Mass per unstretched length ρ (kg/m).
        pub mass_per_length: f64,
        /// Persistent transport inertia (the ρc² terms) on or off.
        pub inertia: bool,
        /// Coulomb coefficient μ ≥ 0.
        pub friction: f64,
        /// Driver speed ω₁ (rad/s, clockwise positive).
        pub driver_speed: f64,
        /// Load torque M₂ of the driven pulley (N·m, the clockwise torque the belt must
        /// exert on it; resisting a clockwise drive when positive).
        pub driven_torque: f64,
        /// Viscous damping d₂ ≥ 0 of the driven pulley (N·m·s): resisting torque M₂ + d₂ω₂.
        pub driven_damping: f64,
    }

    /// Why a gravity-free drive has no steady creep solution.
    #[derive(Debug, Clone, PartialEq, Error)]
    pub enum CreepError {
        /// A datum is non-finite or out of range.
        #[error("invalid input: {name} = {} ({reason})", numerics::Sig(*value))]
        InvalidInput { name: &'static str, value: f64, reason: &'static str },
        /// The belt is not stretched on: no pretension, no torque, no unique shape.
        #[error("no steady solution: without gravity a belt of length L = {} m not shorter than the contour L_geom = {} m has no pretension; add gravity or shorten the belt", numerics::Sig(*length), numerics::Sig(*geometric_length))]
        WeightlessSlack { length: f64, geometric_length: f64 },
        /// The driver speed reaches the critical speed (effective tension ≤ 0).
        #[error("no steady solution: driver speed ω₁ = {driver_speed} rad/s is at or above the critical speed {critical_speed:.6} rad/s, where the effective tension T − ρc²λ of the unloaded belt vanishes")]
        SpeedAtOrAboveCritical { driver_speed: f64, critical_speed: f64 },
        /// The resisting torque exceeds what friction can transmit (slip arc > contact arc).
        #[error("no steady solution: driven torque {torque:.6} N·m (M₂ + d₂ω₂) exceeds the friction capacity {capacity:.6} N·m (slip zone over the whole contact arc)")]
        FrictionCapacityExceeded { torque: f64, capacity: f64 },
        /// The scalar root did not converge (should not happen for valid data).
        #[error("belt-creep root: {0}")]
        Root(String),
    }

    /// The exact steady state of belt-creep theory.
    #[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
    pub struct CreepSolution {
        /// Effective tension T̃ in the driver's stick zone (of the span running onto the
        /// driver: the tight span when the driver puts power in, the slack one when the
        /// driven pulley does), N.
        pub effective_tight: f64,
        /// Effective tension T̃ in the driven pulley's stick zone, N.
        pub effective_slack: f64,
        /// Axial force in the driver's stick zone (the summary's `tension_tight`), N.
        pub tension_tight: f64,
        /// Axial force in the driven pulley's stick zone (`tension_slack`), N.
        pub tension_slack: f64,
        /// Transport rate c (m/s of unstretched length).
        pub transport_rate: f64,
        /// Driven speed ω₂ = ω₁ λ_s/λ_t (rad/s).
        pub driven_speed: f64,
        /// Slip arc on each pulley, ln(T̃_t/T̃_s)/μ (rad, T̃_t ≥ T̃_s the larger and the
        /// smaller span tension); the stick arc is π − this.
        pub slip_arc: f64,
        /// Torque of the belt on the driven pulley, R(T̃_lower − T̃_upper) = M₂ + d₂ω₂
        /// (N·m, clockwise positive).
        pub driven_torque: f64,
        /// Torque of the belt on the driver, −R(T̃_lower − T̃_upper) (N·m, clockwise
        /// positive).
        pub driver_torque: f64,
        /// Stretch in the driver's stick zone: c λ = ω₁R.
        pub stretch_tight: f64,
        /// Stretch in the driven pulley's stick zone: c λ = ω₂R.
        pub stretch_slack: f64,
    }

    /// The state for a given slack effective tension (everything but the length): T̃_s ≤
    /// T̃_t the span tensions; the driver's stick zone carries T̃_t when the driver puts
    /// power in, T̃_s when the driven pulley does (`reversed`).
    #[derive(Debug, Clone, Copy)]
    struct State {
        ts: f64,
        tt: f64,
        reversed: bool,
        c: f64,
        k: f64,
        phi: f64,
    }

    impl CreepData {
        /// L_geom = 2H + 2πR.
        pub fn geometric_length(&self) -> f64 {
            2.0 * self.centre_distance + 2.0 * PI * self.radius
        }

        fn validate(&self) -> Result<(), CreepError> {
            let positive = [
                ("pulley_radius", self.radius),
                ("centre_distance", self.centre_distance),
                ("length", self.length),
                ("axial_stiffness", self.axial_stiffness),
                ("mass_per_length", self.mass_per_length),
            ];
            for (name, value) in positive {
                if !(value.is_finite() && value > 0.0) {
                    return Err(CreepError::InvalidInput { name, value, reason: "must be finite and > 0" });
                }
            }
            let non_negative = [("coulomb", self.friction), ("driven_damping", self.driven_damping)];
            for (name, value) in non_negative {
                if !(value.is_finite() && value >= 0.0) {
                    return Err(CreepError::InvalidInput { name, value, reason: "must be finite and ≥ 0" });
                }
            }
            for (name, value) in [("driver_speed", self.driver_speed), ("driven_torque", self.driven_torque)] {
                if !value.is_finite() {
                    return Err(CreepError::InvalidInput { name, value, reason: "must be finite" });
                }
            }
            Ok(())
        }

        /// ρc² if inertia is on, else 0.
        fn inertia_force(&self, c: f64) -> f64 {
            if self.inertia { self.mass_per_length * c * c } else { 0.0 }
        }

        /// c from (D5) at the tight effective tension: c λ_t = ω₁R with
        /// λ = (EA + T̃)/(EA − ρc²) (D2); a quadratic in c with inertia.
        fn rate(&self, tt: f64) -> f64 {
            let (ea, w) = (self.axial_stiffness, self.driver_speed * self.radius);
            let b = ea + tt;
            if self.inertia {
                let a = self.mass_per_length * w;
                2.0 * w * ea / (b + (b * b + 4.0 * a * w * ea).sqrt())
            } else {
                w * ea / b
            }
        }

        /// The state at slack effective tension `ts` > 0 (torque balance and kinematics),
        /// ω₁ ≥ 0.
        fn state(&self, ts: f64) -> State {
            let (ea, r) = (self.axial_stiffness, self.radius);
            let a = ea + ts;
            let m = self.driven_torque;
            let net = m + self.driven_damping * self.driver_speed;
            let reversed = net < 0.0;
            let d = if reversed {
                // the driven pulley drives: the upper span is tight, ω₂ = ω₁ (A + D)/A,
                // −R D = M₂ + d₂ω₂, linear in D: D = −A (M₂ + d₂ω₁)/(RA + d₂ω₁)
                -a * net / (r * a + self.driven_damping * self.driver_speed)
            } else {
                // R D² + (RA − M₂) D − A (M₂ + d₂ω₁) = 0, positive root (stable form).
                let q = a * net;
                let b = r * a - m;
                if q == 0.0 { 0.0 } else { 2.0 * q / (b + (b * b + 4.0 * r * q).sqrt()) }
            };
            let tt = ts + d;
            let c = self.rate(if reversed { ts } else { tt });
            let k = ea - self.inertia_force(c);
            let phi = if d == 0.0 { 0.0 } else { (tt / ts).ln() / self.friction };
            State { ts, tt, reversed, c, k, phi }
        }

        /// (driver's, driven pulley's) stick-zone effective tensions of a state.
        fn stick_tensions(s: &State) -> (f64, f64) {
            if s.reversed { (s.ts, s.tt) } else { (s.tt, s.ts) }
        }

        /// ω₂ = ω₁ λ_driven/λ_driver of a state (D5).
        fn driven_speed_of(&self, s: &State) -> f64 {
            let ea = self.axial_stiffness;
            let (t1, t2) = Self::stick_tensions(s);
            self.driver_speed * (ea + t2) / (ea + t1)
        }

        /// The exact unstretched length ∫ ds of the state (docs: spans, stick zones with
        /// the arcs π − φ_slip, slip zones in closed form).
        fn length_of(&self, s: &State) -> f64 {
            let (ea, r, h, mu) = (self.axial_stiffness, self.radius, self.centre_distance, self.friction);
            let inv = |t: f64| s.k / (ea + t);
            let spans = h * (inv(s.ts) + inv(s.tt));
            let sticks = r * (PI - s.phi) * (inv(s.ts) + inv(s.tt));
            let slip_one = if s.phi == 0.0 { 0.0 } else { r * s.k * (s.phi - ((ea + s.tt) / (ea + s.ts)).ln() / mu) / ea };
            spans + sticks + 2.0 * slip_one
        }

        /// Critical driver speed of the unloaded belt (inertia on, belt stretched on):
        /// T̃ = 0 with L = L_geom (EA − ρc²)/EA and c λ(0) = ω R; `None` without inertia
        /// or without pretension.
        pub fn critical_speed(&self) -> Option<f64> {
            let lg = self.geometric_length();
            if !self.inertia || self.length >= lg {
                return None;
            }
            let c = (self.axial_stiffness * (1.0 - self.length / lg) / self.mass_per_length).sqrt();
            Some(c * lg / (self.length * self.radius))
        }

        /// Solve the steady creep state (docs/string-drive.md, all four quadrants of
        /// "Both rotation senses and both power flows"). Errors: the variants of
        /// [`CreepError`], raised before any iteration where the data decide them.
        pub fn solve(&self) -> Result<CreepSolution, CreepError> {
            self.validate()?;
            if self.driver_speed < 0.0 {
                // without gravity the counter-clockwise drive is the mirror image y → −y of
                // the clockwise one with the load torque negated
                let mirrored = CreepData { driver_speed: -self.driver_speed, driven_torque: -self.driven_torque, ..*self };
                return mirrored.solve().map(CreepSolution::mirrored).map_err(|e| match e {
                    CreepError::SpeedAtOrAboveCritical { driver_speed, critical_speed } => {
                        CreepError::SpeedAtOrAboveCritical { driver_speed: -driver_speed, critical_speed }
                    }
                    CreepError::FrictionCapacityExceeded { torque, capacity } => {
                        CreepError::FrictionCapacityExceeded { torque: -torque, capacity }
                    }
                    other => other,
                });
            }
            let lg = self.geometric_length();
            if self.length >= lg {
                return Err(CreepError::WeightlessSlack { length: self.length, geometric_length: lg });
            }
            if let Some(critical_speed) = self.critical_speed() {
                if self.driver_speed >= critical_speed {
                    return Err(CreepError::SpeedAtOrAboveCritical { driver_speed: self.driver_speed, critical_speed });
                }
            }
            let root = |e: crate::error::BvpError| CreepError::Root(e.to_string());
            let loaded = self.driven_torque + self.driven_damping * self.driver_speed != 0.0;
            let ea = self.axial_stiffness;
            // Smallest admissible T̃_s: zero unloaded; φ_slip = π loaded.
            let ts_min = if !loaded {
                0.0
            } else {
                if self.friction == 0.0 {
                    return Err(CreepError::FrictionCapacityExceeded {
                        torque: self.driven_torque + self.driven_damping * self.driver_speed,
                        capacity: 0.0,
                    });
                }
                let mut hi = 1e-9 * ea;
                while self.state(hi).phi > PI {
                    hi *= 2.0;
                }
                let mut lo = hi / 2.0;
                while self.state(lo).phi <= PI && lo > 1e-300 {
                    lo /= 2.0;
                }
                brent_root(|x| Ok(self.state(x).phi - PI), lo, hi, 1e-15 * hi).map_err(root)?
            };
            let excess = |x: f64| self.length_of(&self.state(x)) - self.length;
            let at_min = if ts_min == 0.0 { self.length_of(&self.state(1e-300)) - self.length } else { excess(ts_min) };
            if at_min <= 0.0 {
                // The belt is too long for the torque: the slack side would need T̃ below
                // the φ_slip = π limit. Capacity = R(T̃_t − T̃_s) with φ = π at this length.
                let e = self.friction * PI;
                let reversed = self.driven_torque + self.driven_damping * self.driver_speed < 0.0;
                let len_pi = |ts: f64| {
                    let tt = ts * e.exp();
                    let c = self.rate(if reversed { ts } else { tt });
                    let k = ea - self.inertia_force(c);
                    let s = State { ts, tt, reversed, c, k, phi: PI };
                    self.length_of(&s) - self.length
                };
                let mut hi = 1e-9 * ea;
                while len_pi(hi) > 0.0 {
                    hi *= 2.0;
                }
                let ts = brent_root(|x| Ok(len_pi(x)), 0.0, hi, 1e-15 * hi).map_err(root)?;
                let capacity = self.radius * ts * (e.exp() - 1.0);
                let st = self.state(ts_min.max(1e-300));
                let omega2 = self.driven_speed_of(&st);
                return Err(CreepError::FrictionCapacityExceeded {
                    torque: self.driven_torque + self.driven_damping * omega2,
                    capacity,
                });
            }
            let mut hi = (2.0 * ts_min).max(1e-6 * ea);
            while excess(hi) > 0.0 {
                hi *= 2.0;
            }
            let ts = brent_root(|x| Ok(excess(x)), ts_min, hi, 1e-15 * hi).map_err(root)?;
            let s = self.state(ts);
            let rc2 = self.inertia_force(s.c);
            let tension = |t: f64| ea * (t + rc2) / (ea - rc2);
            // the driver's and the driven pulley's stick zones
            let (t1, t2) = Self::stick_tensions(&s);
            let (lt, ls) = ((ea + t1) / s.k, (ea + t2) / s.k);
            // R (T̃_lower − T̃_upper): the lower span runs onto the driver
            let torque = self.radius * (t1 - t2);
            Ok(CreepSolution {
                effective_tight: t1,
                effective_slack: t2,
                tension_tight: tension(t1),
                tension_slack: tension(t2),
                transport_rate: s.c,
                driven_speed: self.driver_speed * ls / lt,
                slip_arc: s.phi,
                driven_torque: torque,
                driver_torque: -torque,
                stretch_tight: lt,
                stretch_slack: ls,
            })
        }
    }

    impl CreepSolution {
        /// The mirror image y → −y (without gravity): the same tensions, arcs and
        /// stretches; the speeds, the transport rate and the torques change sign.
        pub fn mirrored(self) -> Self {
            Self {
                transport_rate: -self.transport_rate,
                driven_speed: -self.driven_speed,
                driven_torque: -self.driven_torque,
                driver_torque: -self.driver_torque,
                ..self
            }
        }
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        fn data() -> CreepData {
            CreepData {
                radius: 0.1,
                centre_distance: 0.5,
                length: 1.25,
                axial_stiffness: 1.0e4,
                mass_per_length: 0.5,
                inertia: true,
                friction: 0.4,
                driver_speed: 20.0,
                driven_torque: 10.0,
                driven_damping: 0.1,
            }
        }

        /// The closed form satisfies its own defining equations in all four quadrants
        /// (ω₁ ≷ 0, power from the driver or from the driven pulley): torque balance with
        /// damping, the Euler–Eytelwein ratio, (D5) and the exact length, each to
        /// rounding (1e-12 relative: a few operations on O(1) ratios).
        #[test]
        fn defining_equations_hold() {
            for (omega1, torque, reversed) in [(20.0, 10.0, false), (20.0, -10.0, true), (-20.0, -10.0, false), (-20.0, 10.0, true)] {
                let d = CreepData { driver_speed: omega1, driven_torque: torque, ..data() };
                let s = d.solve().unwrap();
                defining_equations_hold_for(&d, &s);
                // the driver's stick zone is the tight span's when it puts power in
                assert_eq!(s.tension_tight < s.tension_slack, reversed, "ω₁ {omega1}, M₂ {torque}");
                assert_eq!(s.driven_speed.abs() > omega1.abs(), reversed);
                assert_eq!(s.transport_rate.signum(), omega1.signum());
            }
        }

        fn defining_equations_hold_for(d: &CreepData, s: &CreepSolution) {
            let m = d.driven_torque + d.driven_damping * s.driven_speed;
            assert!((s.driven_torque - m).abs() < 1e-12 * m.abs(), "{} vs {m}", s.driven_torque);
            assert!(((s.effective_tight / s.effective_slack).ln().abs() - d.friction * s.slip_arc).abs() < 1e-12);
            assert!((s.transport_rate * s.stretch_tight - d.driver_speed * d.radius).abs() < 1e-12);
            assert!((s.transport_rate * s.stretch_slack - s.driven_speed * d.radius).abs() < 1e-12);
            let rc2 = d.mass_per_length * s.transport_rate.powi(2);
            assert!((s.tension_tight - rc2 * s.stretch_tight - s.effective_tight).abs() < 1e-9 * s.tension_tight);
            assert!((s.tension_tight - d.axial_stiffness * (s.stretch_tight - 1.0)).abs() < 1e-9 * s.tension_tight);
            // Length by brute-force quadrature of the slip zone (composite Simpson, 2000
            // panels: error ~1e-14 relative for this smooth integrand).
            let n = 2000;
            let h = s.slip_arc / n as f64;
            let smaller = s.effective_slack.min(s.effective_tight);
            let inv = |psi: f64| 1.0 / ((d.axial_stiffness + smaller * (d.friction * psi).exp()) / (d.axial_stiffness - rc2));
            let mut slip = inv(0.0) + inv(s.slip_arc);
            for i in 1..n {
                slip += if i % 2 == 1 { 4.0 } else { 2.0 } * inv(i as f64 * h);
            }
            slip *= h / 3.0 * d.radius;
            let stick = d.radius * (PI - s.slip_arc) * (1.0 / s.stretch_tight + 1.0 / s.stretch_slack);
            let spans = d.centre_distance * (1.0 / s.stretch_tight + 1.0 / s.stretch_slack);
            let total = spans + stick + 2.0 * slip;
            assert!((total - d.length).abs() < 1e-12 * d.length, "length {total} vs {}", d.length);
        }

        /// Without gravity the counter-clockwise drive is the mirror image of the
        /// clockwise one with the load negated: bit for bit (the solve mirrors).
        #[test]
        fn counter_clockwise_is_the_mirror_image() {
            for torque in [10.0, -10.0] {
                let cw = CreepData { driven_torque: torque, ..data() }.solve().unwrap();
                let ccw = CreepData { driver_speed: -20.0, driven_torque: -torque, ..data() }.solve().unwrap();
                assert_eq!(ccw, cw.mirrored());
            }
        }

        /// The named no-solution cases, decided before any iteration.
        #[test]
        fn no_solution_cases() {
            let mut d = data();
            d.driven_torque = 1e4;
            assert!(matches!(d.solve(), Err(CreepError::FrictionCapacityExceeded { .. })), "{:?}", d.solve());
            let mut d = data();
            d.driver_speed = 1.01 * d.critical_speed().unwrap();
            assert!(matches!(d.solve(), Err(CreepError::SpeedAtOrAboveCritical { .. })));
            let mut d = data();
            d.length = 1.7;
            assert!(matches!(d.solve(), Err(CreepError::WeightlessSlack { .. })));
            let mut d = data();
            d.friction = 0.0;
            assert!(matches!(d.solve(), Err(CreepError::FrictionCapacityExceeded { capacity, .. }) if capacity == 0.0));
        }

        /// The capacity is where φ_slip reaches π: just below it the solution exists with
        /// φ_slip close to π, just above it the error names a capacity between the two.
        #[test]
        fn capacity_is_sharp() {
            let mut d = data();
            d.driven_damping = 0.0;
            d.driven_torque = 1e4;
            let Err(CreepError::FrictionCapacityExceeded { capacity, .. }) = d.solve() else { panic!("expected capacity error") };
            d.driven_torque = capacity * (1.0 - 1e-6);
            let s = d.solve().unwrap();
            assert!(s.slip_arc < PI && s.slip_arc > PI - 1e-4, "slip arc {}", s.slip_arc);
            d.driven_torque = capacity * (1.0 + 1e-6);
            assert!(d.solve().is_err());
        }
    }
}
