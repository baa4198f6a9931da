//! The Bratu problem y'' + λ e^y = 0, y(0) = y(1) = 0: both solution branches near the
//! fold, the fold itself, and natural-parameter continuation.
//!
//! Source: the closed form y = −2 ln[cosh((x − ½)θ/2) / cosh(θ/4)],
//! θ = √(2λ) cosh(θ/4), fold λ_c = 3.513830719125162 at θ_c = 4.798714561030935
//! (J. P. Boyd, Appl. Math. Comput. 143, 2003, eqs. (2)–(4); Ascher, Mattheij &
//! Russell, "Numerical Solution of BVPs for ODEs", SIAM 1995, Example 9.2), in
//! `bvp::analytical::bratu`.
//!
//! Parameters: λ = 3.51 (0.1 % below λ_c), where the two branches are only 0.11 apart
//! at x = ½ (y(½) = 1.1326 and 1.2427) and the linearised problem is nearly singular —
//! the hardest place for a solver that must stay on the branch it started on.
//! Every solve runs with both Jacobian modes (AD and central differences).

use bvp::analytical::bratu::{lambda_of_theta, Bratu, BratuBranch, Exact, CRITICAL_LAMBDA, CRITICAL_THETA};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::continuation::{self, ContinuationOptions, Termination};
use bvp::{BvpError, JacobianMode, Solution};

const LAMBDA: f64 = 3.51;

/// θ recovered from a numerical solution's midpoint value y(½) = 2 ln cosh(θ/4).
fn theta_of(sol: &Solution) -> f64 {
    4.0 * (sol.eval(0, 0.5)[0] / 2.0).exp().acosh()
}

#[test]
fn closed_form_constants_are_consistent() {
    // λ_c = λ(θ_c) and (θ_c/4) tanh(θ_c/4) = 1 to rounding.
    assert!((lambda_of_theta(CRITICAL_THETA) - CRITICAL_LAMBDA).abs() < 1e-14);
    assert!((CRITICAL_THETA / 4.0 * (CRITICAL_THETA / 4.0).tanh() - 1.0).abs() < 1e-15);
    let lower = Exact::new(LAMBDA, BratuBranch::Lower).unwrap();
    let upper = Exact::new(LAMBDA, BratuBranch::Upper).unwrap();
    assert!(lower.theta < CRITICAL_THETA && upper.theta > CRITICAL_THETA);
    for e in [lower, upper] {
        assert!((lambda_of_theta(e.theta) - LAMBDA).abs() < 1e-13);
        // The closed form satisfies the ODE: y'' = −λ e^y by central differences
        // (step 1e-4: truncation ~1e-8 · |y''''|, round-off ~1e-16/1e-8).
        for x in [0.1, 0.37, 0.5, 0.9] {
            let h = 1e-4;
            let d2 = (e.state(x + h)[0] - 2.0 * e.state(x)[0] + e.state(x - h)[0]) / (h * h);
            assert!((d2 + LAMBDA * e.state(x)[0].exp()).abs() < 1e-6);
        }
    }
    assert!(Exact::new(3.6, BratuBranch::Lower).is_err());
}

/// Both branches at λ = 3.51, both schemes, both Jacobian modes, tolerance 1e-6.
///
/// Tolerances: the node values are superconvergent (O(h^{2s}) against the O(h^s)
/// residual): they must be below the residual tolerance 1e-6. The dense output error
/// is bounded by κ · residual with κ the stability constant of the linearised BVP,
/// which grows like (λ_c − λ)^{-1/2} ≈ 16 here: allow 20 · tol = 2e-5. Either bound
/// is 5000× smaller than the distance 0.11 between the branches, so a solve that
/// jumped to the other branch fails. Work bounds are ~1.5× the measured counts.
#[test]
fn both_branches_near_the_fold() {
    let tol = 1e-6;
    for branch in [BratuBranch::Lower, BratuBranch::Upper] {
        let exact = Exact::new(LAMBDA, branch).unwrap();
        // Guess: the closed-form shape 0.5 away in θ, on the far side from the fold
        // (it solves a different λ), on 11 nodes.
        let offset = if branch == BratuBranch::Lower { -0.5 } else { 0.5 };
        let mut guess = Exact::from_theta(exact.theta + offset).guess(11);
        guess.eta = LAMBDA;
        for scheme in [Scheme::Gauss4, Scheme::Gauss6] {
            let mut rhs_counts = Vec::new();
            for mode in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
                let opts = CollocationOptions { scheme, tolerance: tol, jacobian: mode, ..Default::default() };
                let sol = collocation::solve(&Bratu, &guess, &opts).unwrap();
                rhs_counts.push(sol.stats.rhs_evaluations);
                let (node, dense) = (exact.max_node_error(&sol), exact.max_dense_error(&sol, 2001));
                eprintln!(
                    "{branch:?} {scheme} {mode:?}: nodes {}, node err {node:.2e}, dense err {dense:.2e}, newton {}, theta {:.10}",
                    sol.stats.mesh_nodes,
                    sol.stats.newton_iterations,
                    theta_of(&sol)
                );
                assert!(sol.stats.max_residual < tol);
                assert!(node < tol, "{branch:?} {scheme} {mode:?}: node error {node:e}");
                assert!(dense < 20.0 * tol, "{branch:?} {scheme} {mode:?}: dense error {dense:e}");
                assert!(sol.stats.newton_iterations <= 20, "{:?}", sol.stats);
                let cap = if scheme == Scheme::Gauss4 { 1100 } else { 120 };
                assert!(sol.stats.mesh_nodes <= cap, "{:?}", sol.stats);
                assert_eq!(sol.eta, LAMBDA);
            }
            // The finite-difference mode really differences: 2 (n + n_p + 1) = 6 extra
            // f64 right-hand-side calls per stage and Jacobian (measured: 18 510 vs
            // 32 310 for gauss4), so its count must exceed the AD count by > 30 %.
            assert!(10 * rhs_counts[1] > 13 * rhs_counts[0], "{scheme}: rhs evaluations {rhs_counts:?}");
        }
    }
}

/// Pseudo-arclength from λ = 1 (lower branch) around the fold and down the upper
/// branch; the fold must be found and located to 1e-9.
///
/// Tolerance: the discrete fold differs from λ_c by the node-level discretisation
/// error (O(h^{2s}); ≲ 1e-11 at these tolerances, see the example's table) plus the
/// Newton tolerance (1e-10 · scale) and the Brent tolerance δs = 1e-10 in the state
/// coordinate, which enters λ only as O(δs²) because λ is stationary at the fold.
/// Every branch point is also checked against the closed form: θ from y(½) must give
/// back the point's λ to 1e-7 (node-level error amplified by dλ/dθ ≤ 1).
#[test]
fn fold_located_by_pseudo_arclength() {
    for (scheme, tol) in [(Scheme::Gauss4, 1e-6), (Scheme::Gauss6, 1e-8)] {
        for mode in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
            let opts = CollocationOptions { scheme, tolerance: tol, jacobian: mode, ..Default::default() };
            let copts = ContinuationOptions { initial_step: 0.2, max_step: 1.0, ..Default::default() };
            let start = Exact::new(1.0, BratuBranch::Lower).unwrap().guess(11);
            let branch = continuation::pseudo_arclength(&Bratu, &start, 1.0, 0.5, 4.0, &copts, &opts).unwrap();
            assert_eq!(branch.termination, Termination::LeftInterval);
            assert_eq!(branch.folds.len(), 1, "exactly one fold on [0.5, 4]");
            let fold = &branch.folds[0];
            let err = (fold.eta - CRITICAL_LAMBDA).abs();
            eprintln!(
                "{scheme} {mode:?}: fold λ = {:.15} (error {err:.2e}), {} points, {} Newton iterations, fold evaluations {}",
                fold.eta,
                branch.points.len(),
                branch.stats.newton_iterations,
                fold.evaluations
            );
            assert!(err < 1e-9, "{scheme} {mode:?}: fold error {err:e}");
            // The fold solution is the closed form at θ_c.
            let theta = theta_of(&fold.solution);
            assert!((theta - CRITICAL_THETA).abs() < 1e-4, "θ at the fold {theta}");
            // Fold bracketed by its neighbours, which straddle θ_c.
            let (a, b) = (&branch.points[fold.after_point], &branch.points[fold.after_point + 1]);
            assert!(theta_of(&a.solution) < CRITICAL_THETA && theta_of(&b.solution) > CRITICAL_THETA);
            assert!(a.eta < fold.eta && b.eta < fold.eta);
            // All points on the exact branch; the last one on the upper branch below 0.5.
            for p in &branch.points {
                let lam = lambda_of_theta(theta_of(&p.solution));
                assert!((lam - p.eta).abs() < 1e-7, "point at λ = {}: closed form gives {lam}", p.eta);
            }
            let last = branch.points.last().unwrap();
            assert!(last.eta < 0.5 && theta_of(&last.solution) > CRITICAL_THETA);
            // Work per step: a regression in the corrector shows here.
            let per_step = branch.points.iter().skip(1).map(|p| p.solution.stats.newton_iterations).max().unwrap();
            assert!(per_step <= 12, "max Newton iterations per step {per_step}");
            assert!(branch.points.len() <= 30, "{} points", branch.points.len());
        }
    }
}

/// Natural continuation from y = 0 at λ = 0.1 up to λ = 3.5 on the lower branch; the
/// last point is at λ = 3.5 exactly and matches the closed form (node tolerance as in
/// `both_branches_near_the_fold`). Beyond the fold there is no solution: asking for
/// λ = 3.6 must stall with an error, not return a wrong answer.
#[test]
fn natural_continuation_homotopy() {
    let opts = CollocationOptions { scheme: Scheme::Gauss6, tolerance: 1e-8, ..Default::default() };
    let copts = ContinuationOptions::default();
    let guess = Solution::from_fn(1, 11, vec![], 0.0, |_, _| vec![0.0, 0.0]);
    let branch = continuation::natural(&Bratu, &guess, 0.1, 3.5, &copts, &opts).unwrap();
    let last = branch.last().unwrap();
    assert_eq!(last.eta, 3.5);
    assert_eq!(branch.termination, Termination::Reached);
    let exact = Exact::new(3.5, BratuBranch::Lower).unwrap();
    let err = exact.max_node_error(last);
    eprintln!(
        "natural: {} points, node error {err:.2e}, {} Newton iterations",
        branch.points.len(),
        branch.stats.newton_iterations
    );
    assert!(err < 1e-8, "node error {err:e}");
    assert!(branch.points.windows(2).all(|w| w[1].eta > w[0].eta));
    assert!(branch.points.len() <= 20, "{} points", branch.points.len());

    let quick = ContinuationOptions { min_step: 1e-4, ..copts };
    match continuation::natural(&Bratu, &guess, 0.1, 3.6, &quick, &opts) {
        Err(BvpError::ContinuationStalled { eta, step, min_step, .. }) => {
            eprintln!("stalled at λ = {eta}, step {step:e}");
            assert!(eta < CRITICAL_LAMBDA && eta > 3.3, "stalled at {eta}");
            assert!(step < min_step);
        }
        other => panic!("expected ContinuationStalled, got {:?}", other.map(|b| b.points.len())),
    }
}

/// `natural_checked`: a step whose converged solution the acceptance test rejects is
/// halved like a failed one. Rejecting max y > 0.5 on the lower branch (max y = 0.5 is
/// reached at λ ≈ 2.68 by the closed form) stops the homotopy below that λ with the
/// rejection reason as the cause, and every accepted point satisfies the test.
#[test]
fn natural_checked_rejects_unacceptable_steps() {
    let opts = CollocationOptions { scheme: Scheme::Gauss6, tolerance: 1e-8, ..Default::default() };
    let copts = ContinuationOptions { min_step: 1e-4, ..Default::default() };
    let guess = Solution::from_fn(1, 11, vec![], 0.0, |_, _| vec![0.0, 0.0]);
    let max_y = |s: &Solution| s.segments[0].nodes.iter().map(|y| y[0]).fold(f64::MIN, f64::max);
    let accept = |s: &Solution| if max_y(s) <= 0.5 { Ok(()) } else { Err(format!("max y = {:.3} > 0.5", max_y(s))) };
    match continuation::natural_checked(&Bratu, &guess, 0.1, 3.0, &copts, &opts, accept) {
        Err(BvpError::ContinuationStalled { eta, cause, .. }) => {
            assert!(cause.contains("max y"), "{cause}");
            let exact = Exact::new(eta, BratuBranch::Lower).unwrap();
            assert!(exact.midpoint() <= 0.5 + 1e-9 && eta > 1.0, "stalled at λ = {eta}");
        }
        other => panic!("expected ContinuationStalled, got {:?}", other.map(|b| b.points.len())),
    }
    // Without the test the same homotopy reaches λ = 3.
    assert!(continuation::natural(&Bratu, &guess, 0.1, 3.0, &copts, &opts).is_ok());
}

/// The accuracy-matched solve of the speed comparison with scipy's `solve_bvp`
/// (`docs/bvp-engine.md`, "Speed"; `bvp/examples/speed.rs`): the lower branch at
/// λ = 3.51 by gauss8 (the default scheme) at tol 1e-8, started from the closed form at
/// θ = 4 with 11 nodes, must be at least as accurate as scipy at tol 1e-8 (max error of
/// y 3.5e-10 with 379 nodes); here the error of y and y′ together is bounded, which is
/// stricter. Measured 1.5e-10 on 63 nodes; the node bound (190, half of scipy's)
/// catches an adaptation change that buys the accuracy with many more nodes.
#[test]
fn gauss8_at_tol_1e_8_is_as_accurate_as_scipy_with_half_its_nodes() {
    let exact = Exact::new(LAMBDA, BratuBranch::Lower).unwrap();
    let mut guess = Exact::from_theta(4.0).guess(11);
    guess.eta = LAMBDA;
    for jacobian in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
        let opts = CollocationOptions { scheme: Scheme::Gauss8, tolerance: 1e-8, jacobian, ..Default::default() };
        let sol = collocation::solve(&Bratu, &guess, &opts).expect("Bratu by gauss8");
        let err = exact.max_dense_error(&sol, 2001);
        eprintln!("gauss8 {jacobian:?}: error {err:.2e}, nodes {}, newton {}", sol.stats.mesh_nodes, sol.stats.newton_iterations);
        assert!(err <= 3.5e-10, "{jacobian:?}: error {err:e}");
        assert!(sol.stats.mesh_nodes <= 190, "{jacobian:?}: {:?}", sol.stats);
    }
}
