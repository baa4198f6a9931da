//! Multiple shooting (`bvp::shooting`) on problems with exact solutions.
//!
//! Sources:
//! - linear BVP y'' = λ² y, y(0) = 1, y(1) = 0 with y = sinh(λ(1 − x)) / sinh λ: the
//!   standard example of growing modes in shooting (Ascher, Mattheij & Russell,
//!   *Numerical Solution of Boundary Value Problems for ODEs*, SIAM 1995, §4.1–4.3);
//! - two segments with an unknown switching point (a free boundary reformulated with the
//!   length as a parameter, Ascher & Russell, SIAM Rev. 23, 1981, §3): harmonic motion
//!   u'' = −u from u(0) = 0, u'(0) = 1 until u' = 0 (t = L = π/2), then uniform deceleration
//!   u'' = −1 until t = 2: exact L = π/2, u(2) = 1 − (2 − π/2)²/2.
//!
//! Tolerance justification: the integrator runs at 0.1 · tolerance (local error per
//! unit step, mixed absolute/relative), the global error of a stable flow over a unit
//! interval stays within a small multiple of that, and the Newton iteration stops at a
//! scaled defect ≤ tolerance. Errors are asserted ≤ 10 · tolerance; the measured ratios
//! (printed with `--nocapture`) are below 1.

use bvp::shooting::{self, flow_map, ShootingOptions};
use bvp::{BvpError, JacobianMode, Problem, Scalar, Solution};

/// y'' = λ² y as (y, y'), y(0) = 1, y(1) = 0.
struct Exponential {
    lambda: f64,
}

impl Problem for Exponential {
    fn n_segments(&self) -> usize {
        1
    }
    fn dim(&self, _k: usize) -> usize {
        2
    }
    fn n_params(&self) -> usize {
        0
    }
    fn rhs<D: Scalar>(&self, _k: usize, _x: f64, y: &[D], _p: &[D], _eta: D, f: &mut [D]) {
        f[0] = y[1];
        f[1] = y[0] * (self.lambda * self.lambda);
    }
    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], _p: &[D], _eta: D, r: &mut [D]) {
        r[0] = ya[0][0] - 1.0;
        r[1] = yb[0][0];
    }
}

fn exponential_exact(lambda: f64, x: f64) -> [f64; 2] {
    let s = lambda.sinh();
    [
        (lambda * (1.0 - x)).sinh() / s,
        -lambda * (lambda * (1.0 - x)).cosh() / s,
    ]
}

/// Two segments with the switching time L as parameter p[0] (see the file header).
struct Switching;

impl Problem for Switching {
    fn n_segments(&self) -> usize {
        2
    }
    fn dim(&self, _k: usize) -> usize {
        2
    }
    fn n_params(&self) -> usize {
        1
    }
    fn rhs<D: Scalar>(&self, k: usize, _x: f64, y: &[D], p: &[D], _eta: D, f: &mut [D]) {
        // Segment 0: t = L x, segment 1: t = L + (2 − L) x; d/dx = length · d/dt.
        let len = if k == 0 { p[0] } else { -p[0] + 2.0 };
        f[0] = len * y[1];
        f[1] = if k == 0 { -(len * y[0]) } else { -len };
    }
    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], _p: &[D], _eta: D, r: &mut [D]) {
        r[0] = ya[0][0];
        r[1] = ya[0][1] - 1.0;
        r[2] = ya[1][0] - yb[0][0];
        r[3] = ya[1][1] - yb[0][1];
        r[4] = yb[0][1];
    }
}

fn switching_exact(k: usize, x: f64) -> [f64; 2] {
    let l = std::f64::consts::FRAC_PI_2;
    if k == 0 {
        let t = l * x;
        [t.sin(), t.cos()]
    } else {
        let t = (2.0 - l) * x;
        [1.0 - 0.5 * t * t, -t]
    }
}

/// Max abs error of the dense output on 400 + 1 points per segment.
fn max_error(sol: &Solution, exact: impl Fn(usize, f64) -> [f64; 2]) -> f64 {
    let mut e: f64 = 0.0;
    for k in 0..sol.segments.len() {
        for i in 0..=400 {
            let x = i as f64 / 400.0;
            let y = sol.eval(k, x);
            let ye = exact(k, x);
            e = e
                .max((y[0] - ye[0]).abs())
                .max((y[1] - ye[1]).abs() / (1.0 + ye[1].abs()));
        }
    }
    e
}

#[test]
fn linear_exponential_bvp_matches_exact_solution() {
    let problem = Exponential { lambda: 10.0 };
    let guess = Solution::from_fn(1, 3, vec![], 0.0, |_, _| vec![0.0, 0.0]);
    for &tol in &[1e-4, 1e-6, 1e-8, 1e-10] {
        let opts = ShootingOptions {
            tolerance: tol,
            intervals_per_segment: 4,
            ..Default::default()
        };
        let sol = shooting::solve(&problem, &guess, &opts).expect("linear BVP solves");
        let err = max_error(&sol, |_, x| exponential_exact(10.0, x));
        eprintln!(
            "exponential tol {tol:.0e}: err {err:.2e} (ratio {:.2}), newton {}, nodes {}, rhs {}",
            err / tol,
            sol.stats.newton_iterations,
            sol.stats.mesh_nodes,
            sol.stats.rhs_evaluations
        );
        assert!(err <= 10.0 * tol, "tol {tol:e}: error {err:e}");
        // Linear problem: the first correction from y ≡ 0 uses sensitivities integrated on
        // the long steps chosen for the zero state (error control is on y only), so it is
        // inexact; the second, with the steps of the solution, converges.
        assert!(sol.stats.newton_iterations <= 2, "{:?}", sol.stats);
        assert!(sol.stats.max_residual <= tol);
        assert_eq!(sol.stats.unknowns, 8);
    }
}

#[test]
fn two_segments_with_unknown_switching_time() {
    let guess = Solution::from_fn(2, 5, vec![1.2], 0.0, |k, x| {
        if k == 0 {
            vec![x, 1.0 - x]
        } else {
            vec![1.0, -x]
        }
    });
    for &tol in &[1e-6, 1e-9] {
        let opts = ShootingOptions {
            tolerance: tol,
            intervals_per_segment: 2,
            ..Default::default()
        };
        let sol = shooting::solve(&Switching, &guess, &opts).expect("switching problem solves");
        let l_err = (sol.params[0] - std::f64::consts::FRAC_PI_2).abs();
        let err = max_error(&sol, switching_exact);
        eprintln!(
            "switching tol {tol:.0e}: L err {l_err:.2e}, state err {err:.2e}, newton {}, nodes {}",
            sol.stats.newton_iterations, sol.stats.mesh_nodes
        );
        assert!(l_err <= 10.0 * tol, "L = {}", sol.params[0]);
        assert!(err <= 10.0 * tol, "state error {err:e}");
        assert_eq!(sol.stats.unknowns, 2 * 2 * 2 + 1);
        assert!(sol.stats.newton_iterations <= 8, "{:?}", sol.stats);
    }
}

/// y'' = −η e^y + p₀ y' + p₁: a nonlinear right-hand side with parameters and η, for the
/// derivative checks of the flow map.
struct Nonlinear;

impl Problem for Nonlinear {
    fn n_segments(&self) -> usize {
        1
    }
    fn dim(&self, _k: usize) -> usize {
        2
    }
    fn n_params(&self) -> usize {
        2
    }
    fn rhs<D: Scalar>(&self, _k: usize, _x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        f[0] = y[1];
        f[1] = -(eta * y[0].exp()) + p[0] * y[1] + p[1];
    }
    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], _eta: D, r: &mut [D]) {
        r[0] = ya[0][0];
        r[1] = yb[0][0];
        r[2] = p[0];
        r[3] = p[1];
    }
}

#[test]
fn flow_map_sensitivities_match_central_differences() {
    // Integrator at 1e-13 (tolerance 1e-12 × 0.1); central differences with step
    // h = 1e-4 have truncation error ~h² |φ'''| ≈ 1e-8 and integrator noise ~1e-13/h =
    // 1e-9, so agreement to 1e-6 is a meaningful check of the variational equations
    // (an error in f_y, f_p or f_η would show at O(1)).
    let (y0, p, eta) = ([0.3, -0.7], [0.4, 0.25], 1.3);
    for mode in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
        let opts = ShootingOptions {
            tolerance: 1e-12,
            jacobian: mode,
            ..Default::default()
        };
        let fm = flow_map(&Nonlinear, 0, 0.1, 0.9, &y0, &p, eta, &opts).unwrap();
        let end = |y: [f64; 2], p: [f64; 2], eta: f64| {
            flow_map(&Nonlinear, 0, 0.1, 0.9, &y, &p, eta, &opts)
                .unwrap()
                .end
        };
        let h = 1e-4;
        for c in 0..5 {
            let (mut yp, mut ym, mut pp, mut pm, mut ep, mut em) = (y0, y0, p, p, eta, eta);
            match c {
                0 | 1 => {
                    yp[c] += h;
                    ym[c] -= h;
                }
                2 | 3 => {
                    pp[c - 2] += h;
                    pm[c - 2] -= h;
                }
                _ => {
                    ep += h;
                    em -= h;
                }
            }
            let (a, b) = (end(yp, pp, ep), end(ym, pm, em));
            for i in 0..2 {
                let fd = (a[i] - b[i]) / (2.0 * h);
                let an = match c {
                    0 | 1 => fm.dy0[i * 2 + c],
                    2 | 3 => fm.dp[i * 2 + c - 2],
                    _ => fm.deta[i],
                };
                assert!(
                    (fd - an).abs() <= 1e-6 * (1.0 + an.abs()),
                    "{mode:?} column {c} row {i}: fd {fd} vs {an}"
                );
            }
        }
    }
}

#[test]
fn ad_and_finite_difference_jacobians_agree() {
    // Same problem, same options, only the Jacobian mode differs: both iterations converge
    // to the same solution (within the tolerance: they stop at different iterates) with
    // the same iteration count (the FD Jacobian is accurate to ~1e-10, far below what
    // changes a Newton path).
    let guess = Solution::from_fn(2, 5, vec![1.2], 0.0, |k, x| {
        if k == 0 {
            vec![x, 1.0 - x]
        } else {
            vec![1.0, -x]
        }
    });
    let tol = 1e-8;
    let run = |mode| {
        let opts = ShootingOptions {
            tolerance: tol,
            intervals_per_segment: 3,
            jacobian: mode,
            ..Default::default()
        };
        shooting::solve(&Switching, &guess, &opts).unwrap()
    };
    let (ad, fd) = (run(JacobianMode::Ad), run(JacobianMode::FiniteDifference));
    assert_eq!(ad.stats.newton_iterations, fd.stats.newton_iterations);
    assert!((ad.params[0] - fd.params[0]).abs() <= tol);
    for k in 0..2 {
        for i in 0..=50 {
            let x = i as f64 / 50.0;
            let (a, f) = (ad.eval(k, x), fd.eval(k, x));
            assert!(
                (a[0] - f[0]).abs() <= tol && (a[1] - f[1]).abs() <= tol,
                "k {k} x {x}"
            );
        }
    }
    // FD evaluates f 1 + 2(n + n_p + 1) = 9 times per augmented call instead of once.
    assert!(fd.stats.rhs_evaluations > ad.stats.rhs_evaluations);
}

#[test]
fn dense_output_is_consistent_with_the_ode() {
    // The quartic dense output interpolates y and f at every step end, so y' of the dense
    // output equals f(x, y(x)) at nodes exactly and between them to the interpolation
    // error (≤ 1e-6 relative at tolerance 1e-9 on this smooth solution).
    let problem = Exponential { lambda: 3.0 };
    let guess = Solution::from_fn(1, 2, vec![], 0.0, |_, x| vec![1.0 - x, -1.0]);
    let opts = ShootingOptions {
        tolerance: 1e-9,
        ..Default::default()
    };
    let sol = shooting::solve(&problem, &guess, &opts).unwrap();
    let seg = &sol.segments[0];
    assert_eq!(seg.mesh.len(), seg.nodes.len());
    assert_eq!(seg.poly.len() + 1, seg.mesh.len());
    assert!(
        seg.mesh.windows(2).all(|w| w[1] > w[0])
            && seg.mesh[0] == 0.0
            && *seg.mesh.last().unwrap() == 1.0
    );
    for i in 0..=97 {
        let x = i as f64 / 97.0;
        let (y, dy) = (seg.eval(x), seg.eval_derivative(x));
        let mut f = [0.0; 2];
        problem.rhs(0, x, &y, &[], 0.0, &mut f);
        for c in 0..2 {
            assert!(
                (dy[c] - f[c]).abs() <= 1e-6 * (1.0 + f[c].abs()),
                "x {x}: {dy:?} vs {f:?}"
            );
        }
    }
}

/// y' = y², y(0) = 2 blows up at x = ½.
struct BlowUp;

impl Problem for BlowUp {
    fn n_segments(&self) -> usize {
        1
    }
    fn dim(&self, _k: usize) -> usize {
        1
    }
    fn n_params(&self) -> usize {
        0
    }
    fn rhs<D: Scalar>(&self, _k: usize, _x: f64, y: &[D], _p: &[D], _eta: D, f: &mut [D]) {
        f[0] = y[0] * y[0];
    }
    fn bc<D: Scalar>(&self, ya: &[&[D]], _yb: &[&[D]], _p: &[D], _eta: D, r: &mut [D]) {
        r[0] = ya[0][0] - 2.0;
    }
}

#[test]
fn failures_are_errors_not_panics() {
    // Integration through a blow-up from the guess.
    let guess = Solution::from_fn(1, 2, vec![], 0.0, |_, _| vec![2.0]);
    let opts = ShootingOptions {
        intervals_per_segment: 1,
        ..Default::default()
    };
    match shooting::solve(&BlowUp, &guess, &opts) {
        Err(BvpError::IntegrationFailed { segment: 0, x, .. }) => {
            assert!(x <= 0.5 + 1e-3, "x = {x}")
        }
        other => panic!("expected IntegrationFailed, got {other:?}"),
    }
    // Iteration limit.
    let problem = Exponential { lambda: 10.0 };
    let guess = Solution::from_fn(1, 3, vec![], 0.0, |_, _| vec![0.0, 0.0]);
    let opts = ShootingOptions {
        max_newton_iterations: 1,
        tolerance: 1e-10,
        ..Default::default()
    };
    match shooting::solve(&problem, &guess, &opts) {
        Err(BvpError::NewtonDiverged {
            iterations: 1,
            residual,
            tolerance,
        }) => {
            assert!(residual > tolerance && residual.is_finite())
        }
        other => panic!("expected NewtonDiverged, got {other:?}"),
    }
    // Invalid options and guesses.
    let bad = [
        ShootingOptions {
            tolerance: 0.0,
            ..Default::default()
        },
        ShootingOptions {
            tolerance: f64::NAN,
            ..Default::default()
        },
        ShootingOptions {
            intervals_per_segment: 0,
            ..Default::default()
        },
        ShootingOptions {
            max_newton_iterations: 0,
            ..Default::default()
        },
        ShootingOptions {
            integrator_tolerance_ratio: 2.0,
            ..Default::default()
        },
        ShootingOptions {
            min_damping: 0.0,
            ..Default::default()
        },
        ShootingOptions {
            max_steps_per_interval: 0,
            ..Default::default()
        },
    ];
    for o in &bad {
        assert!(
            matches!(
                shooting::solve(&problem, &guess, o),
                Err(BvpError::InvalidInput(_))
            ),
            "{o:?}"
        );
    }
    let opts = ShootingOptions::default();
    let wrong_dim = Solution::from_fn(1, 3, vec![], 0.0, |_, _| vec![0.0]);
    let wrong_params = Solution::from_fn(1, 3, vec![1.0], 0.0, |_, _| vec![0.0, 0.0]);
    let wrong_segments = Solution::from_fn(2, 3, vec![], 0.0, |_, _| vec![0.0, 0.0]);
    let nan = Solution::from_fn(1, 3, vec![], 0.0, |_, _| vec![f64::NAN, 0.0]);
    for g in [&wrong_dim, &wrong_params, &wrong_segments, &nan] {
        assert!(matches!(
            shooting::solve(&problem, g, &opts),
            Err(BvpError::InvalidInput(_))
        ));
    }
}
