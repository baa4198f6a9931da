//! Multiple shooting on diffsol's adaptive explicit Runge–Kutta integrator (Tsitouras
//! 5(4), `tsit45`).
//!
//! # Method
//!
//! Each segment k (normalised x ∈ [0, 1]) is split into M = `intervals_per_segment`
//! equal shooting intervals [x_j, x_{j+1}], x_j = j/M. The unknowns are the states at
//! the shooting nodes and the parameters,
//!
//! ```text
//!     u = [s_{0,0}, …, s_{0,M−1}, s_{1,0}, …, s_{m−1,M−1}, p],     s_{k,j} ≈ y_k(x_j) ∈ R^{n_k},
//! ```
//!
//! N = M Σ n_k + n_p unknowns. With φ_{k,j}(s, p) the flow of y' = f_k(x, y, p, η) from
//! (x_j, s) to x_{j+1}, the N equations are
//!
//! ```text
//!     matching:  φ_{k,j}(s_{k,j}, p) − s_{k,j+1} = 0,                  j = 0 … M−2,
//!     boundary:  g(s_{0,0}, φ_{0,M−1}(s_{0,M−1}, p), …, p, η) = 0      (Σ n_k + n_p rows),
//! ```
//!
//! rows ordered: all matching rows of segment 0, of segment 1, …, then the rows of g.
//! Their Jacobian needs the sensitivities of the flow, obtained by integrating the
//! variational equations together with the state (one augmented ODE of dimension
//! n + n (n + n_p + 1)):
//!
//! ```text
//!     y' = f,   Φ' = f_y Φ,  Φ(x_j) = I,   Ψ' = f_y Ψ + f_p,  Ψ(x_j) = 0,
//!     χ' = f_y χ + f_η,  χ(x_j) = 0,
//! ```
//!
//! Φ = ∂φ/∂s (n × n), Ψ = ∂φ/∂p (n × n_p), χ = ∂φ/∂η (n); f_y, f_p, f_η come from
//! [`crate::jacobian::rhs_jacobian`] (AD or finite differences, [`ShootingOptions::jacobian`]).
//! The linear system is solved by a dense LU with partial pivoting (nalgebra).
//!
//! # Integrator error control
//!
//! tsit45 with rtol = atol = `integrator_tolerance_ratio · tolerance` (default
//! 0.1 · tolerance), applied to the **state components y only**: the local error estimate
//! e is accepted when √(Σ_i (e_i / (atol + rtol |y_i|))² / n) < 1 (diffsol's weighted RMS
//! norm restricted to y). The sensitivities Φ, Ψ, χ follow the steps chosen for y, so an
//! integration with and without them takes the same steps and gives the same y: the
//! damped-Newton trial points are integrated without sensitivities. The price: where the
//! state is trivial (a guess y ≡ 0) the steps are long and Φ, Ψ coarse, so the first
//! correction is inexact and Newton needs one more iteration even for a linear problem.
//!
//! # Newton iteration and convergence test
//!
//! The scaled defect is
//!
//! ```text
//!     d(u) = max( max_{k,j,i} |φ_{k,j,i} − s_{k,j+1,i}| / (1 + |s_{k,j+1,i}|),   max_i |g_i| ),
//! ```
//!
//! (matching defects relative to the state they should meet, boundary residuals
//! absolute). The iteration stops **converged when d(u) ≤ `tolerance`**. A Newton
//! correction Δ = −J⁻¹F is damped by λ ∈ {1, ½, ¼, …} using Deuflhard's natural
//! monotonicity test: λ is accepted when the simplified correction Δ̄ = −J⁻¹F(u + λΔ)
//! (old LU) satisfies ‖Δ̄‖ ≤ (1 − λ/2)‖Δ‖, or when u + λΔ already meets the tolerance,
//! where ‖v‖ = max_i |v_i| / (1 + |u_i|). A trial point whose integration fails, or whose
//! residual is not finite, is treated as rejected. λ below `min_damping` →
//! [`BvpError::NewtonDiverged`] (or the integrator's [`BvpError::IntegrationFailed`] if the
//! last, most damped, trial failed to integrate).
//!
//! # Output
//!
//! Each returned segment stores every accepted integrator step as a mesh node; on each
//! step [t_a, t_b] the dense output is the quartic through y_a, y_b, f(t_a, y_a), f(t_b, y_b)
//! and the integrator's own (4th-order) interpolant at the midpoint. At an interior
//! shooting node x_j the stored node value is s_{k,j}; the polynomial of the step that ends
//! there ends at φ_{k,j−1}, within the matching defect (≤ tolerance · (1 + |s|)).

use std::cell::Cell;
use std::time::Instant;

use diffsol::{OdeBuilder, OdeSolverMethod, OdeSolverStopReason};
use nalgebra::{DMatrix, DVector};
use numerics::newton::scaled_norm;
use numerics::phases::{self, timed, Phase};

use crate::error::{check_fraction, BvpError};
use crate::jacobian::{bc_jacobian, rhs_jacobian};
use crate::problem::{JacobianMode, Problem};
use crate::solution::{SegmentSolution, Solution, Stats};

/// Matrix type diffsol integrates with (dense nalgebra; tsit45 never factorises it).
type OdeMatrix = diffsol::NalgebraMat<f64>;

/// Options of [`solve`]. Defaults are listed per field; [`ShootingOptions::validate`]
/// states the valid ranges.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct ShootingOptions {
    /// Convergence tolerance on the scaled defect d(u) of the module documentation
    /// (default 1e-6; valid 1e-13 ≤ tolerance < 1). Also sets the integrator tolerance.
    pub tolerance: f64,
    /// Shooting intervals M per segment (default 4; valid 1 ..= 10 000). M = 1 is simple
    /// shooting; more intervals shorten the integrations and help for problems whose
    /// flow grows quickly.
    pub intervals_per_segment: usize,
    /// Maximum number of Newton corrections (default 50; ≥ 1).
    pub max_newton_iterations: usize,
    /// How f_y, f_p, f_η and ∂g are formed (default AD).
    pub jacobian: JacobianMode,
    /// The integrator's rtol = atol = `integrator_tolerance_ratio · tolerance` (default
    /// 0.1; valid (0, 1]).
    pub integrator_tolerance_ratio: f64,
    /// Smallest Newton damping factor λ before giving up (default 1/1024; valid (0, 1]).
    pub min_damping: f64,
    /// Cap on accepted integrator steps per shooting interval (default 100 000; ≥ 1);
    /// exceeding it is an [`BvpError::IntegrationFailed`].
    pub max_steps_per_interval: usize,
}

impl Default for ShootingOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-6,
            intervals_per_segment: 4,
            max_newton_iterations: 50,
            jacobian: JacobianMode::Ad,
            integrator_tolerance_ratio: 0.1,
            min_damping: 1.0 / 1024.0,
            max_steps_per_interval: 100_000,
        }
    }
}

impl ShootingOptions {
    /// Checks every field against its valid range; [`BvpError::InvalidInput`] names the
    /// first offending field.
    pub fn validate(&self) -> Result<(), BvpError> {
        let bad = |msg: String| Err(BvpError::InvalidInput(msg));
        if !(self.tolerance >= 1e-13 && self.tolerance < 1.0) {
            return bad(format!(
                "shooting tolerance {:e} outside [1e-13, 1)",
                self.tolerance
            ));
        }
        if !(1..=10_000).contains(&self.intervals_per_segment) {
            return bad(format!(
                "intervals_per_segment {} outside 1..=10000",
                self.intervals_per_segment
            ));
        }
        if self.max_newton_iterations == 0 {
            return bad("max_newton_iterations must be at least 1".into());
        }
        check_fraction("integrator_tolerance_ratio", self.integrator_tolerance_ratio)?;
        check_fraction("min_damping", self.min_damping)?;
        if self.max_steps_per_interval == 0 {
            return bad("max_steps_per_interval must be at least 1".into());
        }
        Ok(())
    }

    /// The integrator's relative and absolute tolerance.
    pub fn integrator_tolerance(&self) -> f64 {
        self.integrator_tolerance_ratio * self.tolerance
    }
}

/// The flow map of one segment over [x0, x1] and its first derivatives.
#[derive(Debug, Clone)]
pub struct FlowMap {
    /// φ(x1; x0, y0, p, η), n entries.
    pub end: Vec<f64>,
    /// Φ = ∂φ/∂y0, n × n row-major.
    pub dy0: Vec<f64>,
    /// Ψ = ∂φ/∂p, n × n_p row-major.
    pub dp: Vec<f64>,
    /// χ = ∂φ/∂η, n entries.
    pub deta: Vec<f64>,
    /// Accepted integrator steps.
    pub steps: usize,
}

/// The flow map of segment `k` from (x0, y0) to x1 with its sensitivities, by
/// integrating the variational equations of the module documentation with the
/// integrator settings of `opts` (rtol = atol = `opts.integrator_tolerance()`).
///
/// Requires 0 ≤ x0 < x1 ≤ 1 (normalised), `y0.len() = n_k`, `p.len() = n_p`.
#[allow(clippy::too_many_arguments)]
pub fn flow_map<P: Problem>(
    problem: &P,
    k: usize,
    x0: f64,
    x1: f64,
    y0: &[f64],
    p: &[f64],
    eta: f64,
    opts: &ShootingOptions,
) -> Result<FlowMap, BvpError> {
    opts.validate()?;
    if k >= problem.n_segments() || y0.len() != problem.dim(k) || p.len() != problem.n_params() {
        return Err(BvpError::InvalidInput(format!(
            "flow_map: segment {k} of {}, state length {} (dim {}), {} parameters (expected {})",
            problem.n_segments(),
            y0.len(),
            if k < problem.n_segments() {
                problem.dim(k)
            } else {
                0
            },
            p.len(),
            problem.n_params()
        )));
    }
    if !(0.0 <= x0 && x0 < x1 && x1 <= 1.0) {
        return Err(BvpError::InvalidInput(format!(
            "flow_map: need 0 <= x0 < x1 <= 1, got [{x0}, {x1}]"
        )));
    }
    let counter = Cell::new(0);
    let flow = integrate_interval(problem, opts, k, x0, x1, y0, p, eta, true, &counter)?;
    let n = y0.len();
    let np = p.len();
    let ncol = n + np + 1;
    let sens = flow.sens.expect("sensitivities were requested");
    let mut dy0 = vec![0.0; n * n];
    let mut dp = vec![0.0; n * np];
    let mut deta = vec![0.0; n];
    for i in 0..n {
        for c in 0..ncol {
            let v = sens[i * ncol + c];
            if c < n {
                dy0[i * n + c] = v;
            } else if c < n + np {
                dp[i * np + c - n] = v;
            } else {
                deta[i] = v;
            }
        }
    }
    Ok(FlowMap {
        end: flow.end,
        dy0,
        dp,
        deta,
        steps: flow.step_count,
    })
}

/// One integration over a shooting interval.
struct IntervalFlow {
    /// y(x_{j+1}).
    end: Vec<f64>,
    /// [Φ | Ψ | χ] at x_{j+1}, n × (n + n_p + 1) row-major, when requested.
    sens: Option<Vec<f64>>,
    /// Accepted step end points t_0 = x_j < t_1 < … < t_S = x_{j+1}.
    times: Vec<f64>,
    /// y at `times`.
    values: Vec<Vec<f64>>,
    /// Quartic power-basis coefficients per step and component (see module docs).
    poly: Vec<Vec<Vec<f64>>>,
    /// Number of accepted steps S.
    step_count: usize,
}

/// Integrates segment `k` from (x0, y0) to x1 with tsit45, with or without the
/// variational equations, recording the accepted steps. `rhs_count` is incremented by
/// the number of f64 evaluations of f_k.
#[allow(clippy::too_many_arguments)]
fn integrate_interval<P: Problem>(
    problem: &P,
    opts: &ShootingOptions,
    k: usize,
    x0: f64,
    x1: f64,
    y0: &[f64],
    p: &[f64],
    eta: f64,
    with_sens: bool,
    rhs_count: &Cell<usize>,
) -> Result<IntervalFlow, BvpError> {
    let n = y0.len();
    let np = p.len();
    let ncol = n + np + 1;
    let nz = if with_sens { n + n * ncol } else { n };
    let fail = |x: f64, detail: String| BvpError::IntegrationFailed {
        segment: k,
        x,
        detail,
    };
    if y0.iter().chain(p).any(|v| !v.is_finite()) || !eta.is_finite() {
        return Err(fail(x0, "non-finite initial state or parameter".into()));
    }
    // f64 evaluations of f_k per call of the augmented right-hand side.
    let evals_per_call = match (with_sens, opts.jacobian) {
        (false, _) | (true, JacobianMode::Ad) => 1,
        (true, JacobianMode::FiniteDifference) => 1 + 2 * ncol,
    };
    let mode = opts.jacobian;

    // Augmented state z = [y, S e_0, S e_1, …] with S = [Φ | Ψ | χ] stored column by column.
    let rhs = |z: &[f64], _q: &[f64], x: f64, dz: &mut [f64]| {
        rhs_count.set(rhs_count.get() + evals_per_call);
        let y = &z[..n];
        if !with_sens {
            problem.rhs(k, x, y, p, eta, dz);
            return;
        }
        let (f, fy, fp, fe) = rhs_jacobian(problem, mode, k, x, y, p, eta);
        dz[..n].copy_from_slice(&f);
        for c in 0..ncol {
            let col = &z[n + c * n..n + (c + 1) * n];
            for i in 0..n {
                let row = &fy[i * n..(i + 1) * n];
                let mut acc: f64 = row.iter().zip(col).map(|(a, b)| a * b).sum();
                if c >= n && c < n + np {
                    acc += fp[i * np + (c - n)];
                } else if c == n + np {
                    acc += fe[i];
                }
                dz[n + c * n + i] = acc;
            }
        }
    };
    let mut z0 = vec![0.0; nz];
    z0[..n].copy_from_slice(y0);
    if with_sens {
        for c in 0..n {
            z0[n + c * n + c] = 1.0;
        }
    }
    let init = |_q: &[f64], _t: f64, z: &mut [f64]| z.copy_from_slice(&z0);

    // Error control on y only: diffsol's norm is the RMS over all nz components, so the
    // y weights are multiplied by √(n/nz) and the sensitivity components get an atol so
    // large that their contribution vanishes (see the module documentation).
    let tol = opts.integrator_tolerance();
    let w = (n as f64 / nz as f64).sqrt();
    let atol: Vec<f64> = (0..nz)
        .map(|i| if i < n { tol * w } else { 1e200 })
        .collect();
    let ode = OdeBuilder::<OdeMatrix>::new()
        .t0(x0)
        .h0(x1 - x0)
        .rtol(tol * w)
        .atol(atol)
        .rhs(rhs)
        .init(init, nz)
        .build()
        .map_err(|e| fail(x0, format!("building the ODE problem: {e}")))?;
    let mut solver = ode
        .tsit45()
        .map_err(|e| fail(x0, format!("starting tsit45: {e}")))?;
    solver
        .set_stop_time(x1)
        .map_err(|e| fail(x0, format!("setting the stop time: {e}")))?;

    let f_at = |x: f64, y: &[f64]| {
        let mut f = vec![0.0; n];
        problem.rhs(k, x, y, p, eta, &mut f);
        f
    };
    let mut times = vec![x0];
    let mut values = vec![y0.to_vec()];
    let mut f_prev = f_at(x0, y0);
    let mut poly = Vec::new();
    let mut steps = 0;
    loop {
        let reason = solver
            .step()
            .map_err(|e| fail(solver.state().t, e.to_string()))?;
        steps += 1;
        let state = solver.state();
        let (t, z) = (state.t, state.y.batch_as_slice(0));
        if !t.is_finite() || z.iter().any(|v| !v.is_finite()) {
            return Err(fail(
                times[times.len() - 1],
                format!("non-finite state after step {steps} (x = {t})"),
            ));
        }
        let y = z[..n].to_vec();
        let f = f_at(t, &y);
        let ta = times[times.len() - 1];
        let h = t - ta;
        let mid = solver
            .interpolate(0.5 * (ta + t))
            .map_err(|e| fail(t, format!("dense output: {e}")))?;
        let ya = &values[values.len() - 1];
        let fa = &f_prev;
        poly.push(
            (0..n)
                .map(|i| quartic(ya[i], y[i], h * fa[i], h * f[i], mid.batch_as_slice(0)[i]))
                .collect::<Vec<_>>(),
        );
        times.push(t);
        values.push(y);
        f_prev = f;
        if reason == OdeSolverStopReason::TstopReached {
            break;
        }
        if steps >= opts.max_steps_per_interval {
            return Err(fail(
                t,
                format!(
                    "more than {} steps on [{x0}, {x1}]",
                    opts.max_steps_per_interval
                ),
            ));
        }
    }
    // Two f evaluations per step for the dense output (counted as f64 evaluations).
    rhs_count.set(rhs_count.get() + steps + 1);
    let zend = solver.state().y.batch_as_slice(0).to_vec();
    let end = zend[..n].to_vec();
    let sens = with_sens.then(|| {
        let mut s = vec![0.0; n * ncol];
        for c in 0..ncol {
            for i in 0..n {
                s[i * ncol + c] = zend[n + c * n + i];
            }
        }
        s
    });
    Ok(IntervalFlow {
        end,
        sens,
        times,
        values,
        poly,
        step_count: steps,
    })
}

/// Power-basis coefficients of the quartic q on t ∈ [0, 1] with q(0) = ya, q(1) = yb,
/// q'(0) = da, q'(1) = db (slopes already multiplied by the step h) and q(½) = ym: the
/// cubic Hermite interpolant plus d t²(1 − t)², d = 16 (ym − H(½)).
fn quartic(ya: f64, yb: f64, da: f64, db: f64, ym: f64) -> Vec<f64> {
    let h_half = 0.5 * (ya + yb) + 0.125 * (da - db);
    let d = 16.0 * (ym - h_half);
    vec![
        ya,
        da,
        3.0 * (yb - ya) - 2.0 * da - db + d,
        2.0 * (ya - yb) + da + db - 2.0 * d,
        d,
    ]
}

/// Index bookkeeping of the unknown vector u and the residual F.
struct Layout {
    /// n_k per segment.
    dims: Vec<usize>,
    /// Shooting intervals per segment M.
    m: usize,
    /// Offset of s_{k,0} in u.
    offsets: Vec<usize>,
    /// Offset of the first matching row of segment k in F.
    row_offsets: Vec<usize>,
    /// Offset of p in u.
    p_offset: usize,
    /// Offset of the boundary rows in F.
    bc_offset: usize,
    /// N.
    size: usize,
}

impl Layout {
    fn new(dims: Vec<usize>, np: usize, m: usize) -> Self {
        let mut offsets = Vec::with_capacity(dims.len());
        let mut row_offsets = Vec::with_capacity(dims.len());
        let (mut o, mut r) = (0, 0);
        for &n in &dims {
            offsets.push(o);
            row_offsets.push(r);
            o += m * n;
            r += (m - 1) * n;
        }
        Self {
            dims,
            m,
            offsets,
            row_offsets,
            p_offset: o,
            bc_offset: r,
            size: o + np,
        }
    }

    /// Range of s_{k,j} in u.
    fn node(&self, k: usize, j: usize) -> std::ops::Range<usize> {
        let a = self.offsets[k] + j * self.dims[k];
        a..a + self.dims[k]
    }

    /// Left end x_j of shooting interval j.
    fn x(&self, j: usize) -> f64 {
        j as f64 / self.m as f64
    }
}

/// Work counters accumulated over the solve.
#[derive(Default)]
struct Counters {
    sweeps: usize,
    jacobians: usize,
}

/// All interval integrations for the unknowns u: `flows[k][j]`.
type Sweep = Vec<Vec<IntervalFlow>>;

/// Integrates every shooting interval from the node states in `u`.
#[allow(clippy::too_many_arguments)]
fn sweep<P: Problem>(
    problem: &P,
    layout: &Layout,
    u: &[f64],
    eta: f64,
    opts: &ShootingOptions,
    with_sens: bool,
    rhs_count: &Cell<usize>,
    counters: &mut Counters,
) -> Result<Sweep, BvpError> {
    counters.sweeps += 1;
    let p = &u[layout.p_offset..];
    timed(Phase::Integration, || {
        (0..layout.dims.len())
            .map(|k| {
                (0..layout.m)
                    .map(|j| {
                        let s = &u[layout.node(k, j)];
                        integrate_interval(
                            problem,
                            opts,
                            k,
                            layout.x(j),
                            layout.x(j + 1),
                            s,
                            p,
                            eta,
                            with_sens,
                            rhs_count,
                        )
                    })
                    .collect()
            })
            .collect()
    })
}

/// Residual F(u) (length N) and the scaled defect d(u) of the module documentation.
fn residual<P: Problem>(
    problem: &P,
    layout: &Layout,
    u: &[f64],
    eta: f64,
    flows: &Sweep,
) -> (Vec<f64>, f64) {
    let mut f = vec![0.0; layout.size];
    let mut defect: f64 = 0.0;
    for (k, seg) in flows.iter().enumerate() {
        for j in 0..layout.m - 1 {
            let target = &u[layout.node(k, j + 1)];
            let r0 = layout.row_offsets[k] + j * layout.dims[k];
            for i in 0..layout.dims[k] {
                let r = seg[j].end[i] - target[i];
                f[r0 + i] = r;
                defect = defect.max(r.abs() / (1.0 + target[i].abs()));
            }
        }
    }
    let (ya, yb) = segment_ends(layout, u, flows);
    let p = &u[layout.p_offset..];
    problem.bc(&ya, &yb, p, eta, &mut f[layout.bc_offset..]);
    for r in &f[layout.bc_offset..] {
        defect = defect.max(r.abs());
    }
    if f.iter().any(|v| !v.is_finite()) {
        defect = f64::NAN;
    }
    (f, defect)
}

/// The segment ends (y_k(0), y_k(1)) of a sweep: the start nodes among the unknowns, the
/// ends of the last shooting intervals' flows.
fn segment_ends<'a>(layout: &Layout, u: &'a [f64], flows: &'a Sweep) -> (Vec<&'a [f64]>, Vec<&'a [f64]>) {
    let ya = (0..layout.dims.len()).map(|k| &u[layout.node(k, 0)]).collect();
    let yb = flows.iter().map(|seg| seg[layout.m - 1].end.as_slice()).collect();
    (ya, yb)
}

/// Dense Jacobian ∂F/∂u (N × N) from a sweep with sensitivities.
fn jacobian<P: Problem>(
    problem: &P,
    layout: &Layout,
    u: &[f64],
    eta: f64,
    flows: &Sweep,
    mode: JacobianMode,
) -> DMatrix<f64> {
    let nn = layout.size;
    let np = nn - layout.p_offset;
    let mut jac = DMatrix::<f64>::zeros(nn, nn);
    let sens = |k: usize, j: usize| flows[k][j].sens.as_ref().expect("sweep with sensitivities");
    for k in 0..layout.dims.len() {
        let n = layout.dims[k];
        let ncol = n + np + 1;
        for j in 0..layout.m - 1 {
            let r0 = layout.row_offsets[k] + j * n;
            let c_here = layout.node(k, j).start;
            let c_next = layout.node(k, j + 1).start;
            let s = sens(k, j);
            for i in 0..n {
                for c in 0..n {
                    jac[(r0 + i, c_here + c)] = s[i * ncol + c];
                }
                jac[(r0 + i, c_next + i)] = -1.0;
                for q in 0..np {
                    jac[(r0 + i, layout.p_offset + q)] = s[i * ncol + n + q];
                }
            }
        }
    }
    // Boundary rows: ∂g/∂ya_k, ∂g/∂yb_k · Φ_{k,M−1}, ∂g/∂p + Σ_k ∂g/∂yb_k · Ψ_{k,M−1}.
    let (ya, yb) = segment_ends(layout, u, flows);
    let p = &u[layout.p_offset..];
    let (_g, dg) = bc_jacobian(problem, mode, &ya, &yb, p, eta);
    let nbc = nn - layout.bc_offset;
    let total: usize = layout.dims.iter().sum();
    let width = 2 * total + np + 1;
    let mut col = 0; // column of y_k(0) in dg
    for k in 0..layout.dims.len() {
        let n = layout.dims[k];
        let ncol = n + np + 1;
        let first = layout.node(k, 0).start;
        let last = layout.node(k, layout.m - 1).start;
        let s = sens(k, layout.m - 1);
        for r in 0..nbc {
            let row = &dg[r * width..(r + 1) * width];
            let jr = layout.bc_offset + r;
            for c in 0..n {
                jac[(jr, first + c)] += row[col + c];
            }
            for c in 0..n {
                let v: f64 = (0..n).map(|l| row[col + n + l] * s[l * ncol + c]).sum();
                jac[(jr, last + c)] += v;
            }
            for q in 0..np {
                let v: f64 = (0..n).map(|l| row[col + n + l] * s[l * ncol + n + q]).sum();
                jac[(jr, layout.p_offset + q)] += v;
            }
        }
        col += 2 * n;
    }
    for r in 0..nbc {
        for q in 0..np {
            jac[(layout.bc_offset + r, layout.p_offset + q)] += dg[r * width + 2 * total + q];
        }
    }
    jac
}

/// Checks the guess against the problem and returns the initial unknowns u.
fn initial_unknowns<P: Problem>(
    problem: &P,
    guess: &Solution,
    layout: &Layout,
) -> Result<Vec<f64>, BvpError> {
    let m = problem.n_segments();
    if m == 0 {
        return Err(BvpError::InvalidInput("problem has no segments".into()));
    }
    if guess.segments.len() != m {
        return Err(BvpError::InvalidInput(format!(
            "guess has {} segments, problem {m}",
            guess.segments.len()
        )));
    }
    if guess.params.len() != problem.n_params() {
        return Err(BvpError::InvalidInput(format!(
            "guess has {} parameters, problem {}",
            guess.params.len(),
            problem.n_params()
        )));
    }
    if !guess.eta.is_finite() || guess.params.iter().any(|v| !v.is_finite()) {
        return Err(BvpError::InvalidInput(
            "non-finite guess parameters or eta".into(),
        ));
    }
    let mut u = vec![0.0; layout.size];
    for k in 0..m {
        let seg = &guess.segments[k];
        if problem.dim(k) == 0 || seg.dim() != problem.dim(k) {
            return Err(BvpError::InvalidInput(format!(
                "segment {k}: guess has {} components, problem {}",
                seg.dim(),
                problem.dim(k)
            )));
        }
        if seg.mesh.len() < 2 || seg.poly.len() + 1 != seg.mesh.len() {
            return Err(BvpError::InvalidInput(format!(
                "segment {k}: guess mesh needs ≥ 2 nodes and one polynomial per interval"
            )));
        }
        for j in 0..layout.m {
            let v = seg.eval(layout.x(j));
            if v.len() != problem.dim(k) || v.iter().any(|x| !x.is_finite()) {
                return Err(BvpError::InvalidInput(format!(
                    "segment {k}: guess not finite at x = {}",
                    layout.x(j)
                )));
            }
            u[layout.node(k, j)].copy_from_slice(&v);
        }
    }
    u[layout.p_offset..].copy_from_slice(&guess.params);
    Ok(u)
}

/// Solves the BVP by multiple shooting from `guess` (its dense output is sampled at the
/// shooting nodes; its `params` and `eta` are the starting parameters and the fixed η).
///
/// Returns the solution with one mesh node per accepted integrator step (see the module
/// documentation for the dense output) and [`Stats`]:
/// `newton_iterations` = accepted Newton corrections, `jacobian_evaluations` = sweeps with
/// sensitivities (= LU factorisations), `refinements` = sweeps (integrations of all
/// shooting intervals, trial points included), `rhs_evaluations` = f64 evaluations of
/// f_k (finite-difference ones included), `unknowns` = N, `mesh_nodes` = stored nodes,
/// `max_residual` = final scaled defect d(u).
///
/// # Errors
/// [`BvpError::InvalidInput`] for invalid options or a guess that does not fit the
/// problem; [`BvpError::IntegrationFailed`] when the integration from the guess fails;
/// [`BvpError::SingularJacobian`]; [`BvpError::NonFinite`] for a non-finite residual at the
/// guess; [`BvpError::NewtonDiverged`] when the iteration limit is reached or the damping
/// falls below `min_damping`.
pub fn solve<P: Problem>(
    problem: &P,
    guess: &Solution,
    opts: &ShootingOptions,
) -> Result<Solution, BvpError> {
    let started = Instant::now();
    opts.validate()?;
    let dims: Vec<usize> = (0..problem.n_segments()).map(|k| problem.dim(k)).collect();
    let np = problem.n_params();
    let layout = Layout::new(dims.clone(), np, opts.intervals_per_segment);
    let mut u = initial_unknowns(problem, guess, &layout)?;
    let eta = guess.eta;
    let rhs_count = Cell::new(0);
    let mut counters = Counters::default();

    // One integration of every shooting interval at unknowns `u`, with the
    // sensitivities when `sens`.
    let sweep_at = |u: &[f64], sens: bool, counters: &mut Counters| sweep(problem, &layout, u, eta, opts, sens, &rhs_count, counters);
    let mut flows = sweep_at(&u, true, &mut counters)?;
    let (mut f, mut defect) = timed(Phase::Residuals, || residual(problem, &layout, &u, eta, &flows));
    if !defect.is_finite() {
        return Err(BvpError::NonFinite {
            what: "shooting residual at the initial guess".into(),
        });
    }
    let mut have_sens = true;
    let mut iterations = 0;
    while defect > opts.tolerance {
        if iterations >= opts.max_newton_iterations {
            return Err(BvpError::NewtonDiverged {
                iterations,
                residual: defect,
                tolerance: opts.tolerance,
            });
        }
        if !have_sens {
            flows = sweep_at(&u, true, &mut counters)?;
        }
        let jac = timed(Phase::Assembly, || jacobian(problem, &layout, &u, eta, &flows, opts.jacobian));
        counters.jacobians += 1;
        phases::count(phases::Step::NewtonIteration, 1);
        let lu = timed(Phase::NumericFactorisation, || jac.lu());
        let diag = lu.u().diagonal();
        let (dmin, dmax) = diag.iter().fold((f64::INFINITY, 0.0_f64), |(a, b), v| {
            (a.min(v.abs()), b.max(v.abs()))
        });
        // NaN pivots count as singular.
        if dmin.is_nan() || dmin <= layout.size as f64 * f64::EPSILON * dmax {
            return Err(BvpError::SingularJacobian {
                iteration: iterations,
                detail: format!(
                    "LU pivots range over [{dmin:.3e}, {dmax:.3e}] for {} unknowns",
                    layout.size
                ),
            });
        }
        let solve_lu = |rhs: &[f64]| -> Option<Vec<f64>> {
            timed(Phase::LinearSolves, || lu.solve(&DVector::from_column_slice(rhs)))
                .map(|x| x.iter().map(|v| -v).collect())
        };
        let delta = solve_lu(&f).ok_or_else(|| BvpError::SingularJacobian {
            iteration: iterations,
            detail: "LU solve failed".into(),
        })?;
        let delta_norm = scaled_norm(&delta, &u);
        let mut lambda = 1.0;
        let mut last_failure: Option<BvpError>;
        let accepted = loop {
            let trial: Vec<f64> = u.iter().zip(&delta).map(|(a, d)| a + lambda * d).collect();
            match sweep_at(&trial, false, &mut counters) {
                Ok(trial_flows) => {
                    last_failure = None;
                    let (ft, dt) = timed(Phase::Residuals, || residual(problem, &layout, &trial, eta, &trial_flows));
                    if dt.is_finite() {
                        let simplified = solve_lu(&ft)
                            .map(|d| scaled_norm(&d, &u))
                            .unwrap_or(f64::INFINITY);
                        if dt <= opts.tolerance || simplified <= (1.0 - 0.5 * lambda) * delta_norm {
                            break Some((trial, trial_flows, ft, dt));
                        }
                    }
                }
                Err(e) => last_failure = Some(e),
            }
            lambda *= 0.5;
            if lambda < opts.min_damping {
                break None;
            }
        };
        iterations += 1;
        match accepted {
            Some((trial, trial_flows, ft, dt)) => {
                u = trial;
                flows = trial_flows;
                f = ft;
                defect = dt;
                have_sens = false;
            }
            None => {
                return Err(match last_failure {
                    // The smallest damping still failed to integrate: report the integrator.
                    Some(e) => e,
                    None => BvpError::NewtonDiverged {
                        iterations,
                        residual: defect,
                        tolerance: opts.tolerance,
                    },
                });
            }
        }
    }

    let segments: Vec<SegmentSolution> = flows
        .iter()
        .enumerate()
        .map(|(k, seg)| {
            let mut mesh = Vec::new();
            let mut nodes = Vec::new();
            let mut poly = Vec::new();
            for (j, flow) in seg.iter().enumerate() {
                let skip = usize::from(j > 0); // x_j already stored as the end of interval j−1
                if j > 0 {
                    // Stored node value at an interior shooting node: s_{k,j}.
                    let last = nodes.len() - 1;
                    nodes[last] = u[layout.node(k, j)].to_vec();
                }
                mesh.extend_from_slice(&flow.times[skip..]);
                nodes.extend(flow.values[skip..].iter().cloned());
                poly.extend(flow.poly.iter().cloned());
            }
            SegmentSolution { mesh, nodes, poly }
        })
        .collect();
    let mesh_nodes = segments.iter().map(|s| s.mesh.len()).sum();
    let stats = Stats {
        newton_iterations: iterations,
        jacobian_evaluations: counters.jacobians,
        rhs_evaluations: rhs_count.get(),
        refinements: counters.sweeps,
        unknowns: layout.size,
        mesh_nodes,
        max_residual: defect,
        wall_seconds: started.elapsed().as_secs_f64(),
    };
    Ok(Solution {
        segments,
        params: u[layout.p_offset..].to_vec(),
        eta,
        stats,
    })
}
