//! Collocation engine tests: convergence orders on fixed meshes, node removal, the
//! mesh cap, and a two-segment problem with an unknown length parameter.
//!
//! Sources:
//! - Orders: Gauss–Legendre collocation with s stages is superconvergent of order 2s at
//!   the mesh nodes, its collocation polynomial is accurate to O(h^{s+1}) between nodes
//!   and its residual is O(h^s) (Hairer, Nørsett & Wanner, "Solving ODEs I", §II.7;
//!   de Boor & Swartz, SIAM J. Numer. Anal. 10, 1973). Test problem: Bratu at λ = 1,
//!   lower branch (closed form in `bvp::analytical::bratu`, θ = 1.5171645990503775), a
//!   smooth solution on which the asymptotic regime starts at a few intervals.
//! - Length parameter: y'' = −y, y(0) = 0, y'(0) = 1, y(L) = 0 with L unknown has the
//!   first solution L = π, y = sin x (standard form by Ascher & Russell, SIAM Rev. 23,
//!   1981: x = L ξ, ξ ∈ [0, 1]).

use bvp::analytical::bratu::{Bratu, BratuBranch, Exact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::{BvpError, Problem, Scalar, Solution};

/// Bratu at λ = 1 on a uniform mesh of `intervals`, no adaptation; returns
/// (node error, dense-output error, max residual ρ).
fn uniform(scheme: Scheme, intervals: usize) -> (f64, f64, f64) {
    let exact = Exact::new(1.0, BratuBranch::Lower).unwrap();
    let guess = Solution::from_fn(1, intervals + 1, vec![], 1.0, |_, _| vec![0.0, 0.0]);
    let opts = CollocationOptions { scheme, adapt_mesh: false, tolerance: 1e-10, ..Default::default() };
    let sol = collocation::solve(&Bratu, &guess, &opts).unwrap();
    assert_eq!(sol.stats.mesh_nodes, intervals + 1, "no adaptation");
    (exact.max_node_error(&sol), exact.max_dense_error(&sol, 4001), sol.stats.max_residual)
}

fn rate(coarse: f64, fine: f64) -> f64 {
    (coarse / fine).log2()
}

/// Observed orders on meshes h, h/2: node values 2s, dense output s + 1, residual s.
/// The meshes are chosen so that the node errors stay above 1e-13 (round-off in the
/// node values is ~1e-15). Accepted band ±0.35 around the theoretical order: the
/// next term of the error expansion is one power of h smaller, i.e. a relative
/// perturbation ~h ≤ 1/8 of the rate on these meshes.
#[test]
fn observed_orders_on_uniform_meshes() {
    for (scheme, meshes) in [(Scheme::Gauss4, [8, 16, 32]), (Scheme::Gauss6, [4, 8, 16]), (Scheme::Gauss8, [2, 4, 8])] {
        let s = scheme.stages() as f64;
        let results: Vec<(f64, f64, f64)> = meshes.iter().map(|&n| uniform(scheme, n)).collect();
        let mut node_rates_checked = 0;
        for (j, w) in results.windows(2).enumerate() {
            let (node, dense, res) = (rate(w[0].0, w[1].0), rate(w[0].1, w[1].1), rate(w[0].2, w[1].2));
            eprintln!(
                "{scheme}: node rate {node:.3}, dense rate {dense:.3}, residual rate {res:.3}; errors {:?}",
                w[1]
            );
            if w[1].0 > 1e-13 {
                assert!((node - 2.0 * s).abs() < 0.35, "{scheme}: node order {node}");
                node_rates_checked += 1;
            }
            // The lower-order quantities are checked on the finest pair only (their
            // pre-asymptotic correction is relatively larger on the coarsest meshes).
            if j + 2 == results.len() {
                assert!((dense - (s + 1.0)).abs() < 0.35, "{scheme}: dense-output order {dense}");
                assert!((res - s).abs() < 0.35, "{scheme}: residual order {res}");
            }
        }
        assert!(node_rates_checked >= 1, "{scheme}: no node rate above round-off");
    }
}

/// Starting from an over-fine uniform mesh (2001 nodes) with a loose tolerance, nodes
/// are removed; the result still meets the tolerance. With removal off the mesh stays.
#[test]
fn node_removal_happens() {
    let exact = Exact::new(1.0, BratuBranch::Lower).unwrap();
    let guess = exact.guess(2001);
    for scheme in [Scheme::Gauss4, Scheme::Gauss6] {
        let opts = CollocationOptions { scheme, tolerance: 1e-5, ..Default::default() };
        let sol = collocation::solve(&Bratu, &guess, &opts).unwrap();
        eprintln!(
            "{scheme}: {} nodes after {} passes, residual {:.2e}",
            sol.stats.mesh_nodes, sol.stats.refinements, sol.stats.max_residual
        );
        assert!(sol.stats.mesh_nodes < 300, "{scheme}: {} nodes left", sol.stats.mesh_nodes);
        assert!(sol.stats.refinements >= 3, "several halving passes from 2000 intervals");
        assert!(sol.stats.max_residual < 1e-5);
        // A tolerance-1e-5 solution is accurate to better than 1e-6 at the nodes here.
        assert!(exact.max_node_error(&sol) < 1e-6);
        let keep = CollocationOptions { remove_nodes: false, ..opts };
        let sol = collocation::solve(&Bratu, &guess, &keep).unwrap();
        assert_eq!(sol.stats.mesh_nodes, 2001);
        assert_eq!(sol.stats.refinements, 0);
    }
}

/// A guess on a fine mesh started on a coarse, non-uniform one: the guess is carried
/// over by its dense output and the result meets the tolerance.
#[test]
fn guess_on_a_different_mesh() {
    let exact = Exact::new(1.0, BratuBranch::Lower).unwrap();
    let guess = exact.guess(501);
    let meshes = vec![vec![0.0, 0.1, 0.45, 0.8, 1.0]];
    let opts = CollocationOptions { tolerance: 1e-8, ..Default::default() };
    let sol = collocation::solve_on_meshes(&Bratu, &guess, meshes, &opts).unwrap();
    assert!(sol.stats.max_residual < 1e-8);
    assert!(sol.stats.mesh_nodes < 501);
    assert!(exact.max_node_error(&sol) < 1e-8);
    let bad = vec![vec![0.0, 0.6, 0.5, 1.0]];
    assert!(matches!(collocation::solve_on_meshes(&Bratu, &guess, bad, &opts), Err(BvpError::InvalidInput(_))));
}

/// A cap far below what the tolerance needs gives MeshCapReached with the numbers.
#[test]
fn mesh_cap_is_an_error() {
    let guess = Solution::from_fn(1, 11, vec![], 1.0, |_, _| vec![0.0, 0.0]);
    let opts = CollocationOptions { scheme: Scheme::Gauss4, tolerance: 1e-9, max_nodes: 30, ..Default::default() };
    match collocation::solve(&Bratu, &guess, &opts) {
        Err(BvpError::MeshCapReached { max_nodes, residual, tolerance }) => {
            assert_eq!(max_nodes, 30);
            assert_eq!(tolerance, 1e-9);
            assert!(residual > tolerance && residual.is_finite());
        }
        other => panic!("expected MeshCapReached, got {other:?}"),
    }
    // A guess with more nodes than the cap is rejected up front.
    let big = Solution::from_fn(1, 31, vec![], 1.0, |_, _| vec![0.0, 0.0]);
    assert!(matches!(collocation::solve(&Bratu, &big, &opts), Err(BvpError::InvalidInput(_))));
}

/// y'' = −y on [0, L] in two segments [0, L/2], [L/2, L], L unknown: tests parameters,
/// interface conditions and both Jacobian modes.
struct HalfWaves;

impl Problem for HalfWaves {
    fn n_segments(&self) -> usize {
        2
    }
    fn dim(&self, _k: usize) -> usize {
        2
    }
    fn n_params(&self) -> usize {
        1
    }
    fn rhs<D: Scalar>(&self, _k: usize, _x: f64, y: &[D], p: &[D], _eta: D, f: &mut [D]) {
        let half = p[0] * 0.5;
        f[0] = half * y[1];
        f[1] = -(half * y[0]);
    }
    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], _p: &[D], _eta: D, r: &mut [D]) {
        r[0] = ya[0][0];
        r[1] = ya[0][1] - 1.0;
        r[2] = ya[1][0] - yb[0][0];
        r[3] = ya[1][1] - yb[0][1];
        r[4] = yb[1][0];
    }
}

/// L = π to 1e-10: the parameter is a node-level quantity (order 2s), far more
/// accurate than the residual tolerance 1e-8; y = sin(L x) to 1e-8 in the dense output
/// (error ≈ residual for this well-conditioned linear-in-y problem).
#[test]
fn unknown_length_two_segments() {
    for mode in [bvp::JacobianMode::Ad, bvp::JacobianMode::FiniteDifference] {
        for scheme in [Scheme::Gauss4, Scheme::Gauss6] {
            let guess = Solution::from_fn(2, 5, vec![2.5], 0.0, |k, x| {
                let t = 0.5 * (k as f64 + x) * 2.5;
                vec![t.sin(), t.cos()]
            });
            let opts = CollocationOptions { scheme, tolerance: 1e-8, jacobian: mode, ..Default::default() };
            let sol = collocation::solve(&HalfWaves, &guess, &opts).unwrap();
            let l = sol.params[0];
            assert!((l - std::f64::consts::PI).abs() < 1e-10, "{scheme} {mode:?}: L = {l}");
            let mut err: f64 = 0.0;
            for k in 0..2 {
                for i in 0..=100 {
                    let x = i as f64 / 100.0;
                    let t = 0.5 * (k as f64 + x) * l;
                    let y = sol.eval(k, x);
                    err = err.max((y[0] - t.sin()).abs()).max((y[1] - t.cos()).abs());
                }
            }
            assert!(err < 1e-8, "{scheme} {mode:?}: dense error {err:e}");
        }
    }
}
