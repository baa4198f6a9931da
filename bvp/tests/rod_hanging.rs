//! `rod-hanging` as a BVP (docs/rod-hanging.md): AD vs FD Jacobians, invariant (R7),
//! the string limit EI → 0, edge forces (R6) and pressure (R5) at moderate EI, mirror
//! symmetry. Scene data: the catalogue's string-hanging (R = 0.08, H = 0.45, L = 1.41,
//! EA = 2e4, ρ = 0.12, g = 9.81) plus a bending stiffness. The whole file runs in ≈ 6 s
//! (release).

use bvp::jacobian::{bc_jacobian, rhs_jacobian};
use bvp::rod_hanging::problem::{DRIVER_ARC, DRIVEN_ARC, UPPER_LEFT};
use bvp::rod_hanging::{solve, RodHanging, RodHangingOptions, RodHangingSolution, ScaledRodHanging};
use bvp::{JacobianMode, Problem};

/// The catalogue's `string-hanging` data with bending stiffness `ei` (N·m²).
fn scene(ei: f64) -> RodHanging {
    RodHanging {
        radius: 0.08,
        centre_distance: 0.45,
        length: 1.41,
        axial_stiffness: 2.0e4,
        bending_stiffness: ei,
        mass_per_length: 0.12,
        gravity: 9.81,
    }
}

fn opts(tol: f64) -> RodHangingOptions {
    RodHangingOptions { tolerance: tol, ..Default::default() }
}

fn report(tag: &str, s: &RodHangingSolution) {
    let e = s.edge_forces();
    let (up, lo) = s.mid_span();
    eprintln!(
        "{tag}: EI = {:.3e} (EI0 = {:.3e}), steps {}, nodes {}, edge forces driven {:.6e} / {:.6e}, driver {:.6e} / {:.6e} N; \
         mid upper y {:.8} m N {:.8} N M {:.6e} N·m; mid lower y {:.8} m N {:.8} N M {:.6e}; defect {:.2e} N; angles driven {:?} driver {:?}",
        s.data.bending_stiffness,
        s.bending_start,
        s.homotopy_steps,
        s.stats.mesh_nodes,
        e.driven_start,
        e.driven_end,
        e.driver_start,
        e.driver_end,
        up.y,
        up.tension,
        up.moment,
        lo.y,
        lo.tension,
        lo.moment,
        s.closure_defect(),
        s.contact_angles(false),
        s.contact_angles(true),
    );
}

/// (a) AD Jacobians of rhs (R2)/(R4) and of the 41 conditions agree with central
/// differences at an arbitrary state and parameter vector. Why 1e-6 relative: central
/// differences with h ~ ε^{1/3} have error O(ε^{2/3}) ≈ 4e-11 times the second
/// derivative scale; 1e-6 leaves a wide margin while catching any wrong AD entry (O(1)).
#[test]
fn ad_jacobians_match_finite_differences() {
    let pb = ScaledRodHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length: 3.2, bending_start: 3e-3, bending: 2e-5 };
    let p = [0.4, 0.6, 0.5, 0.45, 1.7, -1.4, -1.8, -4.6, 0.01];
    for k in 0..6 {
        let y: Vec<f64> = (0..pb.dim(k)).map(|i| 0.3 + 0.17 * i as f64 - 0.05 * k as f64).collect();
        let a = rhs_jacobian(&pb, JacobianMode::Ad, k, 0.37, &y, &p, 0.8);
        let f = rhs_jacobian(&pb, JacobianMode::FiniteDifference, k, 0.37, &y, &p, 0.8);
        for (u, v) in a.1.iter().chain(&a.2).chain(&a.3).zip(f.1.iter().chain(&f.2).chain(&f.3)) {
            assert!((u - v).abs() <= 1e-6 * (1.0 + u.abs()), "segment {k}: {u} vs {v}");
        }
    }
    let ys: Vec<Vec<f64>> = (0..12).map(|j| (0..pb.dim(j / 2)).map(|i| 0.2 + 0.1 * (i + j) as f64).collect()).collect();
    let ya: Vec<&[f64]> = (0..6).map(|k| ys[2 * k].as_slice()).collect();
    let yb: Vec<&[f64]> = (0..6).map(|k| ys[2 * k + 1].as_slice()).collect();
    let (ga, da) = bc_jacobian(&pb, JacobianMode::Ad, &ya, &yb, &p, 0.8);
    let (gf, df) = bc_jacobian(&pb, JacobianMode::FiniteDifference, &ya, &yb, &p, 0.8);
    assert_eq!(ga, gf);
    assert_eq!(pb.n_bc(), 41);
    for (u, v) in da.iter().zip(&df) {
        assert!((u - v).abs() <= 1e-6 * (1.0 + u.abs()), "{u} vs {v}");
    }
}

/// (b) The invariant (R7) E = M²/(2EI) + N + N²/(2EA) − ρ g y is constant along the
/// whole loop (spans and arcs, dense output between nodes). It is not imposed anywhere
/// (one tension continuity is replaced by the closure defect f), so its drift measures
/// the discretisation error. Why 1e-7 relative to max N: at tol 1e-10 the collocation
/// residual is 1e-10 per unit length relative, the dense output carries the O(h^q)
/// interpolation error well below 1e-8; 1e-7 leaves a margin of ~10 for the thin
/// boundary layer terms M²/(2EI).
#[test]
fn invariant_r7_is_constant() {
    let s = solve(&scene(1e-3), &opts(1e-10)).expect("solves");
    let pts = s.samples(6);
    let e: Vec<f64> = pts.iter().map(|(_, _, p)| s.invariant(p)).collect();
    let nmax = pts.iter().map(|(_, _, p)| p.tension).fold(0.0, f64::max);
    let (lo, hi) = e.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let drift = (hi - lo) / nmax;
    eprintln!("invariant drift {drift:.3e} (N_max {nmax:.6} N), closure defect {:.3e} N", s.closure_defect());
    assert!(drift < 1e-7, "drift {drift:.3e}");
    assert!(s.closure_defect().abs() < 1e-7 * nmax);
}

/// (c) EI → 0: at EI = 1e-6 N·m² the mid-span heights and tensions approach the
/// string's. The rod differs from the string by the boundary layers of length
/// ℓ_b = √(EI/T) at the four contact boundaries; outside them it is a string whose
/// contact points are displaced by O(ℓ_b) along the pulley, so the first-order bound on
/// the change of sag and tension is O(ℓ_b) and O(ℓ_b/H) relative. With T ≈ 1.3 N,
/// ℓ_b ≈ 8.7e-4 m ≈ 1.9e-3 H the test asserts heights within ℓ_b (m) and tensions within
/// ℓ_b/H relative, and that the difference shrinks when EI is divided by 4 (ℓ_b halved).
/// Run time: two solves, ≈ 1 s each.
/// The mid-span moment is the string's curvature times EI: at the vertex of the
/// catenary κ = ρ g / N, so M = ±EI ρ g / N (upper span sags with θ increasing: M > 0;
/// lower span travels leftwards: M < 0), to O(N/EA) + O(ℓ_b/H); asserted to 1e-3.
#[test]
fn small_bending_stiffness_approaches_the_string() {
    let h = scene(1.0).centre_distance;
    let mut diffs = Vec::new();
    for ei in [4e-6, 1e-6] {
        let s = solve(&scene(ei), &opts(1e-8)).expect("solves");
        report(&format!("EI={ei:e}"), &s);
        let st = &s.string;
        let (up, lo) = s.mid_span();
        let sup = st.point(UPPER_LEFT, 1.0);
        let slo = st.point(bvp::rod_hanging::problem::LOWER_RIGHT, 1.0);
        let lb = (ei / sup.tension).sqrt();
        let dy = (up.y - sup.y).abs().max((lo.y - slo.y).abs());
        let dt = ((up.tension - sup.tension) / sup.tension).abs().max(((lo.tension - slo.tension) / slo.tension).abs());
        eprintln!(
            "EI {ei:e}: string upper y {:.8} T {:.8}, lower y {:.8} T {:.8}; ℓ_b = {lb:.3e} m; max |dy| {dy:.3e} m, max |dT|/T {dt:.3e}",
            sup.y, sup.tension, slo.y, slo.tension
        );
        assert!(dy < lb, "heights differ by {dy:e} m > ℓ_b = {lb:e} m");
        assert!(dt < lb / h, "tensions differ by {dt:e} > ℓ_b/H = {:e}", lb / h);
        let w = s.data.mass_per_length * s.data.gravity;
        let (mu, ml) = (ei * w / up.tension, -ei * w / lo.tension);
        eprintln!("mid-span M upper {:.6e} (EI ρg/N {mu:.6e}), lower {:.6e} ({ml:.6e}) N·m", up.moment, lo.moment);
        assert!((up.moment - mu).abs() < 1e-3 * mu.abs() && (lo.moment - ml).abs() < 1e-3 * ml.abs());
        diffs.push((dy, dt));
    }
    // Measured: the differences fall by ≈ 4 when EI falls by 4 (O(EI) = O(ℓ_b²), the
    // leading O(ℓ_b) shift cancels at mid-span); asserted > 3, i.e. clearly faster than
    // the first-order bound's factor 2.
    let (ry, rt) = (diffs[0].0 / diffs[1].0, diffs[0].1 / diffs[1].1);
    eprintln!("reduction factors for EI / 4: heights {ry:.3}, tensions {rt:.3}");
    assert!(ry > 3.0 && rt > 3.0, "no O(EI) approach to the string: {diffs:?}");
}

/// (d) Moderate EI = 1e-3 N·m² (ℓ_b ≈ 3 cm ≈ 0.07 H): the solve succeeds and the
/// contact reactions push: all four edge forces (R6) ≥ 0 and p (R5) ≥ 0 on both arcs
/// (the solver's own check repeats these; asserted here explicitly with a floor of
/// 1e-9 of the force scale for round-off).
#[test]
fn moderate_bending_stiffness_pushes() {
    let s = solve(&scene(1e-3), &opts(1e-8)).expect("solves");
    report("EI=1e-3", &s);
    let e = s.edge_forces();
    for v in [e.driven_start, e.driven_end, e.driver_start, e.driver_end] {
        assert!(v >= 0.0, "edge force {v}");
    }
    let pmin = s.samples(4).iter().filter_map(|(_, _, p)| p.pressure).fold(f64::INFINITY, f64::min);
    let (up, lo) = s.mid_span();
    eprintln!("p_min {pmin:.6e} N/m, mid-span M upper {:.6e} lower {:.6e} N·m", up.moment, lo.moment);
    assert!(pmin >= -1e-9 * s.scales.force);
}

/// (e) Mirror symmetry about x = 0: the geometry and gravity are symmetric, so the
/// driver's contact angles mirror the driven's (φ₁ₐ = −π − φ₂_b, φ₁_b = −π − φ₂ₐ), the
/// arcs carry the same axial-force range, and the four edge forces pair up. Nothing in
/// the discretisation enforces this; 1e-7 (relative to π and to the force scale) is
/// ~10× the tol 1e-8 error of the final solve.
#[test]
fn left_right_symmetry() {
    let s = solve(&scene(1e-3), &opts(1e-8)).expect("solves");
    let (a2, b2) = s.contact_angles(false);
    let (a1, b1) = s.contact_angles(true);
    eprintln!("angles driven ({a2:.10}, {b2:.10}) driver ({a1:.10}, {b1:.10})");
    assert!((a1 + std::f64::consts::PI + b2).abs() < 1e-7, "{a1} vs {b2}");
    assert!((b1 + std::f64::consts::PI + a2).abs() < 1e-7, "{b1} vs {a2}");
    let e = s.edge_forces();
    let f = s.scales.force;
    assert!((e.driven_start - e.driver_end).abs() < 1e-7 * f, "{e:?}");
    assert!((e.driven_end - e.driver_start).abs() < 1e-7 * f, "{e:?}");
    let n = |k: usize, xi: f64| s.point(k, xi).tension;
    assert!((n(DRIVEN_ARC, 0.0) - n(DRIVER_ARC, 1.0)).abs() < 1e-7 * f);
    assert!((n(DRIVEN_ARC, 1.0) - n(DRIVER_ARC, 0.0)).abs() < 1e-7 * f);
}
