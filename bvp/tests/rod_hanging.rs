//! `rod-hanging` as a BVP (docs/rod-hanging.md): AD vs FD Jacobians, invariant (R7),
//! the string limit EI → 0, edge forces (R6) and pressure (R5) at moderate EI, mirror
//! symmetry, shooting vs collocation, and the hard cases of the issue: the thin steel
//! belt of Paper A, EI = 1e-8 N·m² and a very slack loop (L/L_geom = 1.15). Scene data:
//! the catalogue's string-hanging (R = 0.08, H = 0.45, L = 1.41, EA = 2e4, ρ = 0.12,
//! g = 9.81) plus a bending stiffness, except the steel belt. The whole file runs in
//! ≈ 13 s (release, 2 test threads, ≈ 15 s CPU; ≈ 20 s when another build shares the
//! cores); the EI = 1e-3, tol 1e-10 solve is shared by four tests.

use bvp::jacobian::ad_fd_mismatch_sampled;
use bvp::belt::topology::ContactModel;
use bvp::belt::{BeltOptions, BeltProblem, BeltSolution, BvpMethod, Pulley, SectionLaw, Topology};
use bvp::rod_hanging::{solve, RodHanging, RodHangingSolution, ScaledRodHanging};
use bvp::Problem;

/// Segments of the frictionless two-pulley topology (pinned by its unit tests): the
/// upper span half ending at mid-span, the driven arc, the lower span half ending at
/// mid-span, the driver arc.
const UPPER_LEFT: usize = 0;
const DRIVEN_ARC: usize = 2;
const LOWER_RIGHT: usize = 3;
const DRIVER_ARC: usize = 5;

/// Contact angles (first, last contact) of the driver (`true`) or driven pulley.
fn angles<L: SectionLaw>(s: &BeltSolution<L>, driver: bool) -> (f64, f64) {
    let a = s.contact_angles(if driver { Pulley::Driver } else { Pulley::Driven });
    (a[0], a[1])
}

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

fn opts(tol: f64) -> BeltOptions {
    BeltOptions { tolerance: tol, ..Default::default() }
}

/// The collocation solution at EI = 1e-3 N·m², tol 1e-10, solved once (≈ 5 s) and
/// shared by tests (b), (d), (e) and (f).
fn moderate_1e10() -> &'static RodHangingSolution {
    static S: std::sync::OnceLock<RodHangingSolution> = std::sync::OnceLock::new();
    S.get_or_init(|| solve(&scene(1e-3), &opts(1e-10)).expect("EI = 1e-3 solves at tol 1e-10"))
}

fn report(tag: &str, s: &RodHangingSolution) {
    let e = s.edge_forces().expect("the rod has edge forces");
    let (up, lo) = s.mid_span();
    eprintln!(
        "{tag}: EI = {:.3e} (EI0 = {:.3e}), steps {}, nodes {}, edge forces driven {:.6e} / {:.6e}, driver {:.6e} / {:.6e} N; \
         mid upper y {:.8} m N {:.8} N M {:.6e} N·m; mid lower y {:.8} m N {:.8} N M {:.6e}; defect {:.2e} N; angles driven {:?} driver {:?}",
        s.data.bending_stiffness,
        s.bending_start(),
        s.homotopy_steps,
        s.stats.mesh_nodes,
        e.driven_start,
        e.driven_end,
        e.driver_start,
        e.driver_end,
        up.y,
        up.tension,
        up.moment.unwrap(),
        lo.y,
        lo.tension,
        lo.moment.unwrap(),
        s.closure_defect().unwrap(),
        angles(s, false),
        angles(s, true),
    );
}

/// (a) AD Jacobians of rhs (R2)/(R4) and of the 41 conditions agree with central
/// differences at an arbitrary state and parameter vector. Why 1e-6 relative: central
/// differences with h ~ ε^{1/3} have error O(ε^{2/3}) ≈ 4e-11 times the second
/// derivative scale; 1e-6 leaves a wide margin while catching any wrong AD entry (O(1)).
#[test]
fn ad_jacobians_match_finite_differences() {
    let law = ScaledRodHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length: 3.2, bending_start: 3e-3, bending: 2e-5 };
    let pb = BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), law);
    assert_eq!(pb.n_bc(), 41);
    let p = [0.4, 0.6, 0.5, 0.45, 1.7, -1.4, -1.8, -4.6, 0.01];
    let worst = ad_fd_mismatch_sampled(&pb, &p, 0.8);
    assert!(worst <= 1e-6, "AD vs central differences: {worst:e}");
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
    let s = moderate_1e10();
    let (drift, nmax) = s.invariant_drift(6).expect("a frictionless loop has its invariant");
    eprintln!("invariant drift {drift:.3e} (N_max {nmax:.6} N), closure defect {:.3e} N", s.closure_defect().unwrap());
    assert!(drift < 1e-7, "drift {drift:.3e}");
    assert!(s.closure_defect().unwrap().abs() < 1e-7 * nmax);
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
        let st = &s.start;
        let (up, lo) = s.mid_span();
        let sup = st.point(UPPER_LEFT, 1.0);
        let slo = st.point(LOWER_RIGHT, 1.0);
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
        eprintln!("mid-span M upper {:.6e} (EI ρg/N {mu:.6e}), lower {:.6e} ({ml:.6e}) N·m", up.moment.unwrap(), lo.moment.unwrap());
        assert!((up.moment.unwrap() - mu).abs() < 1e-3 * mu.abs() && (lo.moment.unwrap() - ml).abs() < 1e-3 * ml.abs());
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
/// 1e-9 of the force scale for round-off). Uses the shared tol 1e-10 solution.
#[test]
fn moderate_bending_stiffness_pushes() {
    let s = moderate_1e10();
    report("EI=1e-3", s);
    let e = s.edge_forces().expect("the rod has edge forces");
    for v in [e.driven_start, e.driven_end, e.driver_start, e.driver_end] {
        assert!(v >= 0.0, "edge force {v}");
    }
    let pmin = s.samples(4).iter().filter_map(|(_, _, p)| p.pressure).fold(f64::INFINITY, f64::min);
    let (up, lo) = s.mid_span();
    eprintln!("p_min {pmin:.6e} N/m, mid-span M upper {:.6e} lower {:.6e} N·m", up.moment.unwrap(), lo.moment.unwrap());
    assert!(pmin >= -1e-9 * s.scales.force);
}

/// (e) Mirror symmetry about x = 0: the geometry and gravity are symmetric, so the
/// driver's contact angles mirror the driven's (φ₁ₐ = −π − φ₂_b, φ₁_b = −π − φ₂ₐ), the
/// arcs carry the same axial-force range, and the four edge forces pair up. Nothing in
/// the discretisation enforces this; 1e-7 (relative to π and to the force scale) is
/// ~10× the error of a tol 1e-8 solve (the shared solution is at tol 1e-10, so the
/// margin is larger still).
#[test]
fn left_right_symmetry() {
    let s = moderate_1e10();
    let (a2, b2) = angles(s, false);
    let (a1, b1) = angles(s, true);
    eprintln!("angles driven ({a2:.10}, {b2:.10}) driver ({a1:.10}, {b1:.10})");
    assert!((a1 + std::f64::consts::PI + b2).abs() < 1e-7, "{a1} vs {b2}");
    assert!((b1 + std::f64::consts::PI + a2).abs() < 1e-7, "{b1} vs {a2}");
    let e = s.edge_forces().expect("the rod has edge forces");
    let f = s.scales.force;
    assert!((e.driven_start - e.driver_end).abs() < 1e-7 * f, "{e:?}");
    assert!((e.driven_end - e.driver_start).abs() < 1e-7 * f, "{e:?}");
    let n = |k: usize, xi: f64| s.point(k, xi).tension;
    assert!((n(DRIVEN_ARC, 0.0) - n(DRIVER_ARC, 1.0)).abs() < 1e-7 * f);
    assert!((n(DRIVEN_ARC, 1.0) - n(DRIVER_ARC, 0.0)).abs() < 1e-7 * f);
}

/// Maximum relative difference between two solutions in the reported quantities:
/// mid-span heights (relative to H), tensions and moments (relative to the mid-span
/// tension and tension·H), contact angles (absolute, rad) and the four edge forces
/// (relative to the mid-span tension).
fn max_difference(a: &RodHangingSolution, b: &RodHangingSolution) -> f64 {
    let h = a.data.centre_distance;
    let (ua, la) = a.mid_span();
    let (ub, lb) = b.mid_span();
    let t = ua.tension;
    let mut d: Vec<f64> = vec![
        (ua.y - ub.y).abs() / h,
        (la.y - lb.y).abs() / h,
        (ua.tension - ub.tension).abs() / t,
        (la.tension - lb.tension).abs() / t,
        (ua.moment.unwrap() - ub.moment.unwrap()).abs() / (t * h),
        (la.moment.unwrap() - lb.moment.unwrap()).abs() / (t * h),
    ];
    for driver in [false, true] {
        let (p, q) = (angles(a, driver), angles(b, driver));
        d.push((p.0 - q.0).abs());
        d.push((p.1 - q.1).abs());
    }
    let (ea, eb) = (a.edge_forces().expect("the rod has edge forces"), b.edge_forces().expect("the rod has edge forces"));
    for (u, v) in [
        (ea.driven_start, eb.driven_start),
        (ea.driven_end, eb.driven_end),
        (ea.driver_start, eb.driver_start),
        (ea.driver_end, eb.driver_end),
    ] {
        d.push((u - v).abs() / t);
    }
    d.into_iter().fold(0.0, f64::max)
}

/// A scene whose bending layer √(EI/T) is at least the start layer (5 % of H: EI₀ =
/// 6.75e-4 N·m² here) starts at its own EI — no path in EI (`starts_at_scene`, one
/// homotopy "step") — and lands on the solution the path reaches: with a start layer of
/// 8 % (EI₀ ≈ 1.7e-3 N·m² > EI) the same scene continues from EI₀ down to EI. Both final
/// solves run at tol 1e-10, so they differ by two discretisation errors of that order,
/// amplified by the edge forces' conditioning as in (f): 1e-8.
#[test]
fn a_scene_above_the_start_layer_starts_at_its_own_bending_stiffness() {
    let direct = moderate_1e10();
    assert!(direct.problem.law.starts_at_scene(), "EI₀ = {:.3e} N·m²", direct.bending_start());
    assert_eq!(direct.homotopy_steps, 1);
    assert!((direct.bending_start() - 1e-3).abs() < 1e-15);
    let path = solve(&scene(1e-3), &BeltOptions { start_layer: 0.08, ..opts(1e-10) }).expect("the path from 8 % solves");
    assert!(!path.problem.law.starts_at_scene());
    assert!(path.bending_start() > 1.5e-3, "EI₀ = {:.3e} N·m²", path.bending_start());
    let d = max_difference(direct, &path);
    assert!(d < 1e-8, "direct start vs path: {d:.3e}");
}

/// (f) Shooting as the final method (`BvpMethod::Shooting`) agrees with collocation at
/// EI = 1e-3 N·m² in mid-span heights, tensions, moments, contact angles and edge forces.
/// Both final solves run at tol 1e-10 from the same homotopy end point; the two methods
/// discretise differently (adaptive RK integration vs order-6 collocation), so their
/// difference is the sum of two discretisation errors of order 1e-10 each, amplified by
/// the conditioning of the edge forces (a jump of V, i.e. of a derivative of M): 1e-8
/// relative leaves a factor ~50 over that.
#[test]
fn shooting_agrees_with_collocation() {
    let c = moderate_1e10();
    let s = solve(
        &scene(1e-3),
        &BeltOptions { method: BvpMethod::Shooting, tolerance: 1e-10, ..Default::default() },
    )
    .expect("shooting solves");
    report("collocation", c);
    report("shooting", &s);
    let d = max_difference(c, &s);
    eprintln!("max relative difference shooting vs collocation {d:.3e}; shooting {:?}", s.stats);
    assert!(d < 1e-8, "difference {d:e}");
}

/// The thin steel belt of Paper A from its data alone.
fn steel_belt() -> RodHanging {
    let (r, h) = (0.25, 2.0);
    let l_geom = 2.0 * h + 2.0 * std::f64::consts::PI * r;
    RodHanging {
        radius: r,
        centre_distance: h,
        length: l_geom * (1.0 + 1e-4),
        axial_stiffness: 2.0e7,
        bending_stiffness: 1.75,
        mass_per_length: 0.748,
        gravity: 9.81,
    }
}

/// (g) The thin steel belt of Paper A (EA = 2e7 N, EI = 1.75 N·m², R = 0.25 m, H = 2 m,
/// L = L_geom (1 + 1e-4), ρ = 0.748 kg/m) from the data alone. Here EI/(T H²) is large:
/// the bending layer √(EI/T) is comparable with or longer than H, so the homotopy must
/// start from a stiff-enough EI₀ and walk in log EI in whichever direction is needed.
/// Checks: the solve's own contact checks (p ≥ 0, edge forces ≥ 0, topology), mirror
/// symmetry of the contact angles (1e-7 rad: 10× the tol 1e-8 final error), the
/// invariant (R7) to 1e-6 of N_max (the M²/(2EI) term is large here; the dense output
/// error at tol 1e-8 is ≤ 1e-7), the upper span above the lower at mid-span, and
/// agreement with shooting (tol 1e-8 both) to 1e-6 relative in the quantities of test
/// (f): two independent tol 1e-8 discretisations, measured 4e-8, margin 25.
/// Measured: EI/(T H²) ≈ 6e-4 at the rod's own tension (ℓ_b ≈ 5 cm ≈ 0.025 H), but
/// ℓ_b is three times the string's sag, and bending triples the tension (string 242 N,
/// rod 697 N). The default start EI₀ (ℓ_b = 0.05 H at the string's tension) is 2.4 N·m²,
/// above the scene's 1.75, so the log-EI path runs downwards and is short.
#[test]
fn steel_belt_of_paper_a() {
    let s = solve(&steel_belt(), &opts(1e-8)).expect("steel belt solves");
    report("steel belt", &s);
    let (up, lo) = s.mid_span();
    let e = s.edge_forces().expect("the rod has edge forces");
    let (a2, b2) = angles(&s, false);
    let (a1, b1) = angles(&s, true);
    let (sup, slo) = (s.start.point(UPPER_LEFT, 1.0), s.start.point(LOWER_RIGHT, 1.0));
    eprintln!(
        "steel belt string: mid upper y {:.8} m T {:.6} N, lower y {:.8} m T {:.6} N",
        sup.y, sup.tension, slo.y, slo.tension
    );
    eprintln!(
        "steel belt: sag below the pulley tangent upper {:.6e} m lower {:.6e} m; contact arcs driven {:.4}°, driver {:.4}°; ℓ_b/H = {:.3e}",
        s.data.radius - up.y,
        -s.data.radius - lo.y,
        (a2 - b2).to_degrees(),
        (a1 - b1).to_degrees(),
        (s.data.bending_stiffness / up.tension).sqrt() / s.data.centre_distance
    );
    for v in [e.driven_start, e.driven_end, e.driver_start, e.driver_end] {
        assert!(v >= 0.0, "edge force {v}");
    }
    assert!(up.y > lo.y);
    assert!((a1 + std::f64::consts::PI + b2).abs() < 1e-7 && (b1 + std::f64::consts::PI + a2).abs() < 1e-7);
    let pts = s.samples(4);
    let inv: Vec<f64> = pts.iter().map(|(_, _, p)| s.invariant(p).unwrap()).collect();
    let nmax = pts.iter().map(|(_, _, p)| p.tension).fold(0.0, f64::max);
    let (mn, mx) = inv.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    eprintln!("steel belt invariant drift {:.3e} of N_max {nmax:.6e} N", (mx - mn) / nmax);
    assert!((mx - mn) / nmax < 1e-6);
    // Independent discretisation: shooting from the same homotopy end point.
    let sh = solve(&steel_belt(), &BeltOptions { method: BvpMethod::Shooting, ..opts(1e-8) })
        .expect("steel belt solves by shooting");
    let d = max_difference(&s, &sh);
    eprintln!("steel belt: shooting vs collocation max relative difference {d:.3e}");
    assert!(d < 1e-6, "difference {d:e}");
}

/// (h) Small EI = 1e-8 N·m² on the default data: the boundary layer √(EI/T) ≈ 9e-5 m
/// ≈ 2e-4 H is far below the span; the collocation mesh must resolve it. The solution
/// approaches the string: heights within ℓ_b and tensions within ℓ_b/H relative (the
/// first-order bound of test (c); the measured difference is O(EI), far smaller).
#[test]
fn very_small_bending_stiffness() {
    let ei = 1e-8;
    let s = solve(&scene(ei), &opts(1e-8)).expect("EI = 1e-8 solves");
    report("EI=1e-8", &s);
    let st = &s.start;
    let (up, lo) = s.mid_span();
    let sup = st.point(UPPER_LEFT, 1.0);
    let slo = st.point(LOWER_RIGHT, 1.0);
    let lb = (ei / sup.tension).sqrt();
    let h = s.data.centre_distance;
    let dy = (up.y - sup.y).abs().max((lo.y - slo.y).abs());
    let dt = ((up.tension - sup.tension) / sup.tension).abs().max(((lo.tension - slo.tension) / slo.tension).abs());
    eprintln!("EI 1e-8: ℓ_b = {lb:.3e} m, max |dy| {dy:.3e} m, max |dT|/T {dt:.3e}, stats {:?}", s.stats);
    assert!(dy < lb && dt < lb / h);
    // Test (c) measured the approach as O(EI): at EI = 1e-6, |dy| ≈ 5.9e-6 m and
    // |dT|/T ≈ 4.6e-5; scaled by 1e-2 that is 5.9e-8 m and 4.6e-7. Asserted with a
    // factor ~17 and ~20 of margin (the O(ℓ_b³) remainder and the tol 1e-8 final error).
    assert!(dy < 1e-6 && dt < 1e-5, "not O(EI): dy {dy:e} m, dT/T {dt:e}");
}

/// (i) Very slack: L = 1.613 m (L/L_geom ≈ 1.15) with EI = 1e-3 N·m². Physical checks:
/// the upper span above the lower at mid-span, wraps < 180° on both pulleys, all four
/// edge forces ≥ 0 and p ≥ 0 on the arcs (floor 1e-9 of the force scale for
/// round-off), in addition to the solver's own contact checks.
#[test]
fn very_slack_loop() {
    let d = RodHanging { length: 1.613, ..scene(1e-3) };
    let lg = 2.0 * d.centre_distance + 2.0 * std::f64::consts::PI * d.radius;
    let s = solve(&d, &opts(1e-8)).expect("very slack solves");
    report("very slack", &s);
    let (up, lo) = s.mid_span();
    let (a2, b2) = angles(&s, false);
    let (a1, b1) = angles(&s, true);
    let (w2, w1) = ((a2 - b2).to_degrees(), (a1 - b1).to_degrees());
    eprintln!("very slack L/L_geom {:.4}: wraps driven {w2:.3}° driver {w1:.3}°", d.length / lg);
    assert!(up.y > lo.y);
    assert!(w2 > 0.0 && w2 < 180.0 && w1 > 0.0 && w1 < 180.0);
    let e = s.edge_forces().expect("the rod has edge forces");
    for v in [e.driven_start, e.driven_end, e.driver_start, e.driver_end] {
        assert!(v >= 0.0, "edge force {v}");
    }
    let pmin = s.samples(4).iter().filter_map(|(_, _, p)| p.pressure).fold(f64::INFINITY, f64::min);
    eprintln!("very slack p_min {pmin:.6e} N/m");
    assert!(pmin >= -1e-9 * s.scales.force);
}

/// A stalled homotopy names the scene quantity it was switching on and the number that
/// made it hard: a rod of EI = 1e-3 N·m² on pulleys of R = 0.01 m (bending length
/// √(EI/T) ≈ 0.045 m, 4.5 R) cannot even leave the string (the string's wrap on the
/// driven pulley would turn negative), and the error says so with EI, EI₀, √(EI/T) and R.
/// Its layer is above the start layer, so the solve first tries the scene's EI directly;
/// that fails, and the retry along the path from the start layer names the stall.
#[test]
fn a_stalled_homotopy_names_the_scene_quantity() {
    let h = 0.45;
    let r = 0.01;
    let d = RodHanging { radius: r, length: 1.05 * (2.0 * h + 2.0 * std::f64::consts::PI * r), ..scene(1e-3) };
    let e = solve(&d, &opts(1e-8)).expect_err("the rod homotopy stalls");
    let bvp::belt::BeltError::HomotopyStalled { eta, ref at, ref hard, .. } = e else { panic!("{e}") };
    assert!((0.0..1.0).contains(&eta), "{eta}");
    assert!(at.contains("EI =") && at.contains("EI₀") && at.contains("0.001 N·m²"), "{at}");
    assert!(hard.contains("bending length √(EI/T)") && hard.contains("R = 0.01 m"), "{hard}");
    // the bending length in the message is the scene's √(EI/T) with the T it prints
    let t: f64 = hard.split("T = ").nth(1).and_then(|s| s.split(' ').next()).and_then(|s| s.parse().ok()).expect("T printed");
    let layer: f64 = hard.split("= ").nth(1).and_then(|s| s.split(' ').next()).and_then(|s| s.parse().ok()).expect("length printed");
    assert!((layer - (1e-3 / t).sqrt()).abs() < 1e-5 * layer, "{layer} vs √(EI/T) with T = {t}");
    let text = e.to_string();
    assert!(text.starts_with("the homotopy in log EI from the string stalled at η = "), "{text}");
}
