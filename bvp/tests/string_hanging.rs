//! `string-hanging` as a BVP (docs/string-hanging.md): the closed-form and balance checks
//! of the issue, on the catalogue's parameter sets.
//!
//! Source of each check: (S3) elastic catenary, (S6) frictionless invariant (DESIGN.md),
//! mirror symmetry of the geometry about x = 0, the length condition, and agreement of
//! the two independent BVP methods.

use bvp::collocation::Scheme;
use bvp::belt::Pulley;

/// Segments of the frictionless two-pulley topology (pinned by its unit tests), in loop
/// order from the driver: upper span to x = 0, upper span to the driven pulley, driven
/// arc, lower span to x = 0, lower span to the driver, driver arc.
const UPPER_LEFT: usize = 0;
const UPPER_RIGHT: usize = 1;
const DRIVEN_ARC: usize = 2;
const LOWER_RIGHT: usize = 3;
const LOWER_LEFT: usize = 4;
const DRIVER_ARC: usize = 5;

/// Contact angles (first, last contact) of the driver (`true`) or driven pulley.
fn angles(s: &StringHangingSolution, driver: bool) -> (f64, f64) {
    let a = s.contact_angles(if driver { Pulley::Driver } else { Pulley::Driven });
    (a[0], a[1])
}
use bvp::belt::{BeltError, BeltOptions, BvpMethod};
use bvp::string_hanging::{solve, StringHanging, StringHangingSolution};

/// The catalogue's `string-hanging` (scenes/string-hanging.json).
fn base() -> StringHanging {
    StringHanging { radius: 0.08, centre_distance: 0.45, length: 1.41, axial_stiffness: 2.0e4, mass_per_length: 0.12, gravity: 9.81 }
}

fn with_length(length: f64) -> StringHanging {
    StringHanging { length, ..base() }
}

/// scenes/string-hanging-steel.json: steel band, EA/(ρ g H) = 6.1e6, L − L_geom = 1.4e-4 m.
fn steel() -> StringHanging {
    StringHanging { axial_stiffness: 2.0e7, mass_per_length: 0.748, length: 1.4027951, ..base() }
}

fn colloc(tol: f64) -> BeltOptions {
    BeltOptions::collocation(Scheme::default(), tol)
}

fn shoot(tol: f64) -> BeltOptions {
    BeltOptions::shooting(tol)
}

/// Largest deviation of E = T + T²/(2EA) − ρ g y from its mean over dense samples,
/// relative to the largest tension.
fn invariant_drift(sol: &StringHangingSolution) -> f64 {
    let pts = sol.samples(6);
    let e: Vec<f64> = pts.iter().map(|(_, _, p)| sol.invariant(p).unwrap()).collect();
    let tmax = pts.iter().map(|(_, _, p)| p.tension).fold(0.0, f64::max);
    let (lo, hi) = e.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    (hi - lo) / tmax
}

/// Largest distance (m) of the span points from the elastic catenary (S3) through the
/// same vertex, relative to H.
fn catenary_error(sol: &StringHangingSolution) -> f64 {
    let d = &sol.data;
    let w = d.mass_per_length * d.gravity;
    let ea = d.axial_stiffness;
    let shape = |h: f64, st: f64| -> (f64, f64) {
        (h * st / ea + (h / w) * (w * st / h).asinh(), w * st * st / (2.0 * ea) + (h / w) * ((1.0 + (w * st / h).powi(2)).sqrt() - 1.0))
    };
    let mut worst: f64 = 0.0;
    for k in [UPPER_LEFT, UPPER_RIGHT, LOWER_RIGHT, LOWER_LEFT] {
        let raw = |xi: f64| -> Vec<f64> { sol.solution.segments[k].eval(xi) };
        let (lh, fr) = (sol.scales.length, sol.scales.force);
        let y0 = sol.solution.segments[k].start().to_vec();
        // Horizontal force magnitude and the vertex: F_y = w s̃ in the direction of travel.
        let h = y0[2].abs() * fr;
        let dir = y0[2].signum();
        let st0 = y0[3] * fr / w;
        let (cx0, cy0) = shape(h, st0);
        let (xv, yv) = (y0[0] * lh - dir * cx0, y0[1] * lh - cy0);
        for i in 0..=200 {
            let y = raw(i as f64 / 200.0);
            let st = y[3] * fr / w;
            let (cx, cy) = shape(h, st);
            let err = (y[0] * lh - (xv + dir * cx)).hypot(y[1] * lh - (yv + cy));
            worst = worst.max(err / d.centre_distance);
        }
    }
    worst
}

/// (S6) along the whole loop and (S3) on every span, default scene, collocation 1e-10.
/// The invariant is not imposed; collocation conserves it only to its truncation error,
/// which the residual tolerance bounds: 1e-8 relative is two decades above what the
/// 1e-10 tolerance leaves in the dense output.
#[test]
fn invariant_and_catenary_hold() {
    let sol = solve(&base(), &colloc(1e-10)).expect("solves");
    let drift = invariant_drift(&sol);
    assert!(drift < 1e-8, "invariant drift {drift:.3e}");
    let cat = catenary_error(&sol);
    assert!(cat < 1e-8, "catenary deviation {cat:.3e} H");
    assert!(sol.closure_defect().unwrap().abs() < 1e-8 * sol.point(UPPER_LEFT, 1.0).tension, "closure defect {}", sol.closure_defect().unwrap());
}

/// Mirror symmetry about x = 0 of a geometry and load that are symmetric: the upper span's
/// halves have equal length, the contact angles mirror (φ → π − φ), the mid-span force is
/// horizontal.
#[test]
fn left_right_symmetry() {
    let sol = solve(&base(), &colloc(1e-10)).expect("solves");
    let p = &sol.solution.params;
    assert!((p[0] - p[1]).abs() < 1e-9, "upper halves {} vs {}", p[0], p[1]);
    assert!((p[2] - p[3]).abs() < 1e-9, "lower halves {} vs {}", p[2], p[3]);
    let (d_a, d_b) = angles(&sol, true);
    let (r_a, r_b) = angles(&sol, false);
    // driven first contact φ₂ₐ mirrors the driver's last contact φ₁_b (mod 2π).
    let mirror = |phi: f64| std::f64::consts::PI - phi;
    let wrap = |a: f64| a.rem_euclid(2.0 * std::f64::consts::PI);
    assert!((wrap(r_a) - wrap(mirror(d_b))).abs() < 1e-9, "{r_a} vs mirror of {d_b}");
    assert!((wrap(r_b) - wrap(mirror(d_a))).abs() < 1e-9, "{r_b} vs mirror of {d_a}");
    let mid = sol.solution.segments[UPPER_LEFT].end().to_vec();
    assert!(mid[3].abs() < 1e-9 * mid[2].abs(), "vertical force at mid-span {}", mid[3]);
}

/// The unstretched length of all segments adds up to L (the closing condition, checked
/// from the segment data independently of s).
#[test]
fn total_length_is_l() {
    let d = base();
    let sol = solve(&d, &colloc(1e-10)).expect("solves");
    let mut total = 0.0;
    for k in 0..6 {
        let seg = &sol.solution.segments[k];
        let s = if sol.topology().is_span(k) { 4 } else { 1 };
        total += seg.end()[s] - seg.start()[s];
    }
    total *= sol.scales.length;
    assert!((total - d.length).abs() < 1e-12 * d.length, "total {total} vs {}", d.length);
    // The pieces: spans by parameter, arcs by the integral of R/λ dφ.
    let lh = sol.scales.length;
    let spans: f64 = sol.solution.params[..4].iter().sum::<f64>() * lh;
    let arcs: f64 = [DRIVEN_ARC, DRIVER_ARC].iter().map(|&k| (sol.solution.segments[k].end()[1] - sol.solution.segments[k].start()[1]) * lh).sum();
    assert!((spans + arcs - d.length).abs() < 1e-10 * d.length);
}

/// Collocation (order 6, 1e-10) and shooting (1e-10) agree to 1e-8 in every summary
/// quantity (relative to its size, tensions in N, positions relative to H).
#[test]
fn collocation_and_shooting_agree() {
    for d in [base(), with_length(1.45)] {
        let a = solve(&d, &colloc(1e-10)).expect("collocation");
        let b = solve(&d, &shoot(1e-10)).expect("shooting");
        for k in [UPPER_LEFT, LOWER_RIGHT] {
            let (pa, pb) = (a.point(k, 1.0), b.point(k, 1.0));
            assert!((pa.y - pb.y).abs() < 1e-8 * d.centre_distance, "y: {} vs {}", pa.y, pb.y);
            assert!((pa.tension - pb.tension).abs() < 1e-8 * pa.tension, "T: {} vs {}", pa.tension, pb.tension);
        }
        for i in 4..8 {
            let (u, v) = (a.solution.params[i], b.solution.params[i]);
            assert!((u - v).abs() < 1e-8, "angle {i}: {u} vs {v}");
        }
    }
}

/// Tightening the tolerance converges: the mid-span sag changes by less from 1e-8 to 1e-10
/// than from 1e-4 to 1e-6, and the differences stay below the tolerances they compare.
#[test]
fn converges_as_tolerance_tightens() {
    let d = with_length(1.45);
    let ys: Vec<f64> = [1e-4, 1e-6, 1e-8, 1e-10]
        .iter()
        .map(|&t| solve(&d, &colloc(t)).expect("solves").point(UPPER_LEFT, 1.0).y)
        .collect();
    let d1 = (ys[0] - ys[3]).abs();
    let d3 = (ys[2] - ys[3]).abs();
    assert!(d3 <= d1, "not converging: {ys:?}");
    assert!(d1 < 1e-4 * d.centre_distance * 10.0, "1e-4 solution off by {d1}");
    assert!(d3 < 1e-8 * d.centre_distance * 10.0, "1e-8 solution off by {d3}");
}

/// Hard cases from the scene data alone: very slack (L/L_geom = 1.15), steel (EA/(ρgH) =
/// 6e6, L − L_geom = 1.4e-4 m), stretched on without gravity (closed form), by both methods.
#[test]
fn hard_cases_solve_from_the_data_alone() {
    let very_slack = with_length(1.613053);
    let s = solve(&very_slack, &colloc(1e-8)).expect("very slack");
    assert!(invariant_drift(&s) < 1e-6);
    // Physical shape: the upper span hangs between the pulleys' top and bottom, the lower
    // span below, and each pulley keeps less than a half turn of wrap (the upper span
    // adds wrap, the more slack lower span removes more). A belt wound once more round a
    // pulley also satisfies the discrete equations; this caught it once.
    let (yu, yl) = (s.point(UPPER_LEFT, 1.0).y, s.point(LOWER_RIGHT, 1.0).y);
    assert!(yu < 0.08 && yu > -0.08 && yl < -0.08, "mid-span heights {yu}, {yl}");
    for driver in [true, false] {
        let (a, b) = angles(&s, driver);
        assert!(a - b > 0.5 * std::f64::consts::PI && a - b < std::f64::consts::PI, "wrap {}°", (a - b).to_degrees());
    }
    solve(&very_slack, &shoot(1e-8)).expect("very slack by shooting");

    let st = solve(&steel(), &colloc(1e-8)).expect("steel");
    assert!(invariant_drift(&st) < 1e-6);
    let sag = 0.08 - st.point(UPPER_LEFT, 1.0).y;
    assert!(sag > 0.0 && sag < 0.02, "steel sag {sag}");
    solve(&steel(), &shoot(1e-8)).expect("steel by shooting");

    // No gravity, 0.1 % shorter than the contour: T = EA (L_geom/L − 1) exactly, no sag.
    let d = StringHanging { gravity: 0.0, length: base().geometric_length() / 1.001, ..base() };
    let s = solve(&d, &colloc(1e-10)).expect("weightless stretched on");
    let t = s.point(UPPER_LEFT, 1.0).tension;
    assert!((t - d.tight_tension()).abs() < 1e-9 * t, "{t} vs {}", d.tight_tension());
    assert!((s.point(UPPER_LEFT, 1.0).y - d.radius).abs() < 1e-12);
}

/// No solution → named error, never a panic: weightless slack belt; overlapping pulleys;
/// non-finite stiffness.
#[test]
fn impossible_scenes_are_named_errors() {
    let e = solve(&StringHanging { gravity: 0.0, ..base() }, &colloc(1e-8)).unwrap_err();
    assert!(matches!(e, BeltError::WeightlessSlack { .. }), "{e}");
    assert!(e.to_string().contains("1.41"), "{e}");
    let e = solve(&StringHanging { centre_distance: 0.1, ..base() }, &colloc(1e-8)).unwrap_err();
    assert!(e.to_string().contains("centre_distance"), "{e}");
    let e = solve(&StringHanging { axial_stiffness: f64::NAN, ..base() }, &colloc(1e-8)).unwrap_err();
    assert!(e.to_string().contains("axial_stiffness"), "{e}");
}

/// The post-solve contact checks catch what they are for: a negative arc tension (the
/// belt would lift off inside the arc) and a span point inside a pulley are errors.
#[test]
fn contact_checks_catch_violations() {
    let sol = solve(&base(), &colloc(1e-6)).expect("solves");
    sol.check_contact().expect("the real solution passes");

    let mut lifted = sol.clone();
    for y in lifted.solution.segments[DRIVER_ARC].nodes.iter_mut() {
        y[0] = -y[0];
    }
    for c in lifted.solution.segments[DRIVER_ARC].poly.iter_mut().flatten().take(1) {
        c[0] = -c[0].abs();
    }
    let e = lifted.check_contact().unwrap_err();
    assert!(matches!(e, BeltError::ContactViolated(_)), "{e}");

    let mut inside = sol.clone();
    // Pull the first node after the driver's departure point into the driver pulley.
    let seg = &mut inside.solution.segments[UPPER_LEFT];
    let r = sol.problem.law.radius;
    seg.nodes[1][0] = -0.5 + 0.5 * r;
    seg.nodes[1][1] = 0.0;
    for c in seg.poly[1].iter_mut().take(2).zip([-0.5 + 0.5 * r, 0.0]) {
        c.0.iter_mut().for_each(|v| *v = 0.0);
        c.0[0] = c.1;
    }
    let e = inside.check_contact().unwrap_err();
    assert!(e.to_string().contains("driver pulley"), "{e}");
}

/// The mesh cap is reported, never a silent failure: order 4 at 1e-10 needs far more
/// than 2000 nodes (its residual falls like h²), so the final solve names the cap.
#[test]
fn mesh_cap_is_reported() {
    let o = BeltOptions {
        method: BvpMethod::Collocation,
        scheme: Scheme::Gauss4,
        tolerance: 1e-10,
        max_nodes: 2000,
        ..Default::default()
    };
    match solve(&base(), &o) {
        Err(BeltError::Solver { stage, cause: bvp::BvpError::MeshCapReached { max_nodes, residual, tolerance } }) => {
            assert_eq!(stage, "final solve");
            assert_eq!(max_nodes, 2000);
            assert!(residual > tolerance && tolerance == 1e-10);
        }
        other => panic!("expected the mesh cap, got {:?}", other.map(|s| s.stats.mesh_nodes)),
    }
}

/// Extremes found by a parameter sweep (L/L_geom ∈ [0.99, 1.18], EA ∈ [1e2, 1e9] N):
/// a very slack, very stiff belt once landed on an unphysical solution (wound once more
/// round a pulley at T ≈ 1e7 N), and a stretched-on belt with EA = 1e9 N failed Newton
/// from bad force scaling. Both now solve to the physical answer: the very slack stiff
/// belt has the same mid-span tension as the default-stiffness one to O(T/EA), and the
/// stretched-on belt carries T = EA (L_geom/L − 1) up to its weight's small effect.
#[test]
fn stiff_extremes_stay_physical() {
    let soft = solve(&StringHanging { length: 1.613, ..base() }, &colloc(1e-8)).expect("very slack");
    let stiff = solve(&StringHanging { length: 1.613, axial_stiffness: 2.0e7, ..base() }, &colloc(1e-8)).expect("very slack, stiff");
    let (ts, tk) = (soft.point(UPPER_LEFT, 1.0).tension, stiff.point(UPPER_LEFT, 1.0).tension);
    assert!((ts - tk).abs() < 1e-2 * ts, "{ts} vs {tk}");
    let (a, b) = angles(&stiff, true);
    assert!(a - b > 0.0 && a - b < std::f64::consts::PI, "very slack wrap {}°", (a - b).to_degrees());

    let d = StringHanging { length: 1.39, axial_stiffness: 1.0e9, ..base() };
    let s = solve(&d, &colloc(1e-8)).expect("stretched on, EA = 1e9 N");
    let t = s.point(UPPER_LEFT, 1.0).tension;
    assert!((t - d.tight_tension()).abs() < 1e-6 * t, "{t} vs {}", d.tight_tension());
}
