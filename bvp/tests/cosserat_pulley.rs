//! `cosserat-pulley` (Paper C, docs/cosserat-pulley.md): the BVP of the Cosserat belt in
//! steady motion over one pulley, held against the exact identities, approximations,
//! limits and hard cases of spec §2.7–§2.8 (`shared/spec/cosserat-and-shell.md`).
//!
//! Expected values quoted from the spec were computed there by an independent scipy
//! integration (spec §0.2); they are not outputs of this code.

use bvp::belt::{BeltError, BeltOptions, BeltPoint};
use bvp::collocation::Scheme;
use bvp::cosserat_pulley::{self, CosseratPulley, CosseratPulleySolution, Mode};
use drive::scene::End;
use drive::view::ContactState;

/// The catalogue scene `cosserat-pulley` (issue 13).
fn catalogue() -> CosseratPulley {
    CosseratPulley {
        radius: 0.1,
        end_distance: 0.5,
        transport_rate: 2.0,
        tension_in: 15.0,
        tension_out: 10.0,
        axial_stiffness: 1e4,
        bending_stiffness: 0.01,
        shear_stiffness: 1e3,
        mass_per_length: 0.1,
        friction: 0.3,
        inertia: true,
        mode: Mode::Tensions,
    }
}

fn solve(d: &CosseratPulley) -> CosseratPulleySolution {
    cosserat_pulley::solve(d, &BeltOptions::default()).unwrap_or_else(|e| panic!("{d:?}: {e}"))
}

/// Dense samples per mesh interval of the quadratures: with 8 the trapezoidal rule over
/// the edge-pressure layers leaves 5e-5 of the contact resultant; 32 closes it below 1e-6.
const SAMPLES: usize = 32;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Trapezoidal ∫ g ds over the dense samples of segment `k` ([`SAMPLES`] per mesh interval).
fn integral(s: &CosseratPulleySolution, k: usize, g: impl Fn(&BeltPoint) -> f64) -> f64 {
    let pts: Vec<BeltPoint> = s.samples(SAMPLES).into_iter().filter(|(j, _, _)| *j == k).map(|(_, _, p)| p).collect();
    pts.windows(2).map(|q| 0.5 * (g(&q[0]) + g(&q[1])) * (q[1].material - q[0].material)).sum()
}

/// Spec C-5, C-6, C-7, C-8 on the catalogue scene: the stick kinematics exactly, the
/// torque, far-field offsets and edge pressures to the spec's stated accuracy of their
/// asymptotic estimates, and the driving sense (N_in > N_out: the pulley drives, torque
/// of the belt on the pulley negative, slip with λ < λ_B).
#[test]
fn catalogue_scene_meets_the_spec_estimates() {
    let d = catalogue();
    let s = solve(&d);
    let (t_in, t_out) = (d.effective(d.tension_in), d.effective(d.tension_out));
    // C-5: ω = cλ_B/R and the slip zone starts at λ_B; the stick λ_B is the stretch of the
    // inflow section to first order (λ(N_in) = 1 + N_in/b₁ = 1.0015, shear correction small)
    let lam_b = s.stick_stretch();
    assert_eq!(s.pulley_speed(), d.transport_rate * lam_b / d.radius);
    assert!((s.point(2, 0.0).stretch - lam_b).abs() < 1e-12);
    assert!((lam_b - 1.0015).abs() < 1e-4, "λ_B = {lam_b}");
    for (k, _, p) in s.samples(2) {
        if k == 1 {
            assert!((p.stretch - lam_b).abs() < 1e-12, "stick stretch {} vs λ_B {lam_b}", p.stretch);
        }
        if k == 2 {
            assert!(p.stretch <= lam_b + 1e-12, "driving pulley: the belt is slower in slip");
        }
    }
    // C-6: torque ≈ R(F̃_in − F̃_out), spec: ≈ 5e-5 relative on this scene
    let torque = s.torque();
    assert!(torque < 0.0, "the pulley drives: torque of the belt on it {torque} < 0");
    let estimate = -d.radius * (t_in - t_out);
    assert!(rel(torque, estimate) < 2e-4, "torque {torque} vs {estimate}");
    // C-7: far-field offsets a/(2RT̃): spec values 3.4248e-3, 5.2086e-3 m, ≤ 1 %
    let sum = s.summary();
    let (y_in, y_out) = (sum.y_in.unwrap(), sum.y_out.unwrap());
    assert!(rel(y_in - d.radius, 3.4248e-3) < 0.01, "y_in {y_in}");
    assert!(rel(-(y_out + d.radius), 5.2086e-3) < 0.01, "y_out {y_out}");
    // C-8: edge pressures √(T̃(b₂ − χ))/R: spec 1208.0, 979.6 N/m, ≤ 2 %
    let pulley = sum.pulley.unwrap();
    let (pa, pc) = (pulley.edge_pressure_start.unwrap(), pulley.edge_pressure_end.unwrap());
    assert!(rel(pa, 1208.0) < 0.02 && rel(pc, 979.6) < 0.02, "edge pressures {pa} {pc}");
    // the edge pressure is the maximum, far above the interior level (T̃ − a/(2R²))λ/R =
    // 141 N/m (spec §1.8's T̃λ/R less the bending energy a/(2R²) = 0.5 N that (C5) takes
    // from the tension on the curved arc; measured 142.7, within 2 %)
    let p_mid = s.point(1, 0.5).pressure.unwrap();
    let interior = (t_in - d.bending_stiffness / (2.0 * d.radius * d.radius)) * lam_b / d.radius;
    assert!(p_mid < 0.2 * pa && rel(p_mid, interior) < 0.02, "interior pressure {p_mid} vs {interior}");
    // the end conditions hold as given: N_in, N_out; the contact arc shorter than π by the
    // two bending layers
    assert!(rel(sum.tension_in.unwrap(), d.tension_in) < 1e-9 && rel(sum.tension_out.unwrap(), d.tension_out) < 1e-9);
    let arc = pulley.contact_arc.unwrap();
    assert!(arc < std::f64::consts::PI && arc > 2.5, "contact arc {arc}");
    assert!(pulley.edge_force_start.is_none() && sum.driver.is_none() && sum.tension_upper_mid.is_none());
}

/// Spec §1.7 / C-1…C-4, exact identities: E of (C5) constant on each span; across the
/// contact ΔE = −∫f_tλ ds; the moment about the centre (C-2); the resultant of the
/// contact load (C-3); the power balance (C-4) with D ≥ 0. The tolerances are the
/// trapezoidal quadrature over 32 dense points per mesh interval (the exact balances hold
/// to the solve tolerance: C-2 uses the torque state and closes to 1e-9).
#[test]
fn global_balances_of_the_open_domain() {
    let d = catalogue();
    let s = solve(&d);
    let fr = d.tension_in;
    // C-1 on the spans
    for k in [0, 3] {
        let e: Vec<f64> = s.samples(4).into_iter().filter(|(j, _, _)| *j == k).map(|(_, _, p)| s.invariant(&p)).collect();
        let drift = e.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - e.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!(drift < 1e-8 * fr, "span {k}: E drifts by {drift:.3e} N");
    }
    let (inflow, outflow) = (s.point(0, 0.0), s.point(3, 1.0));
    let (e_in, e_out) = (s.invariant(&inflow), s.invariant(&outflow));
    let work = integral(&s, 1, |p| p.friction.unwrap() * p.stretch) + integral(&s, 2, |p| p.friction.unwrap() * p.stretch);
    assert!((e_out - e_in + work).abs() < 1e-6 * fr, "ΔE {:.9} vs −∫f_tλ ds {:.9}", e_out - e_in, -work);
    // C-2: the torque state against the end moments and forces
    let imbalance = cosserat_pulley::moment_imbalance(&d, |k, xi| s.point(k, xi));
    assert!(imbalance.abs() < 1e-9 * fr * d.radius, "moment imbalance {imbalance:.3e} N·m");
    // ∫f_t ds by quadrature agrees with the torque state τ = −R∫f_t ds
    let friction = integral(&s, 1, |p| p.friction.unwrap()) + integral(&s, 2, |p| p.friction.unwrap());
    assert!(rel(-d.radius * friction, s.torque()) < 1e-6, "∫f_t ds {friction} vs torque {}", s.torque());
    // C-3: ∫(p n + f_t t) ds = F̃(in) − F̃(out)
    let load = |c: usize| {
        let g = |p: &BeltPoint| {
            let phi = p.angle.unwrap();
            let (n, t) = ([phi.cos(), phi.sin()], [phi.sin(), -phi.cos()]);
            p.pressure.unwrap() * n[c] + p.friction.unwrap() * t[c]
        };
        integral(&s, 1, g) + integral(&s, 2, g)
    };
    let (f_in, f_out) = (cosserat_pulley::effective_force(&d, &inflow), cosserat_pulley::effective_force(&d, &outflow));
    for c in 0..2 {
        assert!((load(c) - (f_in[c] - f_out[c])).abs() < 1e-5 * fr, "component {c}: {} vs {}", load(c), f_in[c] - f_out[c]);
    }
    // C-4: c(E_in − E_out) = ωR∫f_t ds − D, D ≥ 0
    let dissipation = s.dissipation();
    assert!(dissipation > 0.0);
    let power = d.transport_rate * (e_in - e_out);
    let balance = s.pulley_speed() * d.radius * friction - dissipation;
    assert!((power - balance).abs() < 1e-6 * fr * d.transport_rate, "power {power} vs {balance}");
}

/// The two BVP methods agree, and collocation converges in its tolerance: outputs at
/// 1e-6 and 1e-8 differ from those at 1e-10 by less than 10 × the tolerance.
#[test]
fn both_methods_agree_and_collocation_converges_in_tolerance() {
    let d = catalogue();
    let quantities = |s: &CosseratPulleySolution| {
        let [a, b, c] = s.contact_angles();
        let p = s.summary().pulley.unwrap();
        [a, b, c, s.pulley_speed(), s.torque(), p.edge_pressure_start.unwrap(), p.edge_pressure_end.unwrap()]
    };
    let fine = quantities(&cosserat_pulley::solve(&d, &BeltOptions::collocation(Scheme::default(), 1e-10)).unwrap());
    for tol in [1e-6, 1e-8] {
        let q = quantities(&cosserat_pulley::solve(&d, &BeltOptions::collocation(Scheme::default(), tol)).unwrap());
        for (a, b) in q.iter().zip(&fine) {
            assert!(rel(*a, *b) < 10.0 * tol, "tolerance {tol}: {a} vs {b}");
        }
    }
    let shooting = cosserat_pulley::solve(&d, &BeltOptions::shooting(1e-8)).unwrap();
    for (a, b) in quantities(&shooting).iter().zip(&fine) {
        assert!(rel(*a, *b) < 1e-6, "shooting {a} vs collocation {b}");
    }
}

/// N_in < N_out: the belt drives the pulley (braking, σ = −1): torque positive, the belt
/// faster than the surface in slip (λ ≥ λ_B). The mirrored scene (tensions swapped) has
/// the same torque magnitude and swapped edge pressures and offsets within the
/// small asymmetry of the transport term (χ/T̃ ≈ 3 %): equal to 1e-3 relative.
#[test]
fn braking_pulley_reverses_the_slip() {
    let d = catalogue();
    let braking = CosseratPulley { tension_in: d.tension_out, tension_out: d.tension_in, ..d };
    let (s, b) = (solve(&d), solve(&braking));
    assert!(b.torque() > 0.0, "torque {}", b.torque());
    assert!(rel(b.torque(), -s.torque()) < 1e-3);
    let lam_b = b.stick_stretch();
    assert!(b.samples(2).iter().filter(|(k, _, _)| *k == 2).all(|(_, _, p)| p.stretch >= lam_b - 1e-12));
    assert!(b.point(2, 1.0).stretch > lam_b + 1e-4);
    let (ps, pb) = (s.summary(), b.summary());
    let (qs, qb) = (ps.pulley.unwrap(), pb.pulley.unwrap());
    assert!(rel(qb.edge_pressure_start.unwrap(), qs.edge_pressure_end.unwrap()) < 1e-3);
    assert!(rel(pb.y_in.unwrap(), -ps.y_out.unwrap()) < 1e-3);
    // the slip arc is ln(T̃_out/T̃_in)/μ to leading order in both senses
    assert!(rel(qb.slip_arc.unwrap(), qs.slip_arc.unwrap()) < 0.05);
    // σ = −1 slows the pulley: ω from the slower inflow stretch
    assert!(b.pulley_speed() < s.pulley_speed());
}

/// Spec C-9, the string limit a → 0: the spec's independent values of the slip and
/// contact arcs at a = 3e-3 and 1e-3 (to 2e-5 rad: the spec prints six digits), and the
/// approach to the string creep values (slip arc 1.397530 rad, contact arc π,
/// λ_B → 1 + N_in/b₁) with an error that shrinks like √a.
#[test]
fn string_limit_as_bending_vanishes() {
    let d = catalogue();
    let mut errors = Vec::new();
    for (a, slip_spec, contact_spec) in [(3e-3, 1.26855, 2.85387), (1e-3, 1.31565, 2.97561)] {
        let s = solve(&CosseratPulley { bending_stiffness: a, ..d });
        let p = s.summary().pulley.unwrap();
        let (slip, contact) = (p.slip_arc.unwrap(), p.contact_arc.unwrap());
        assert!((slip - slip_spec).abs() < 2e-5 && (contact - contact_spec).abs() < 2e-5, "a = {a}: {slip} {contact}");
        errors.push(((d.string_slip_arc() - slip) / a.sqrt(), (std::f64::consts::PI - contact) / a.sqrt()));
        assert!((s.stick_stretch() - (1.0 + d.tension_in / d.axial_stiffness)).abs() < 1e-4);
    }
    assert!((d.string_slip_arc() - 1.397530).abs() < 1e-6);
    // O(√a): the scaled errors agree to 25 % between the two bending stiffnesses
    for (e3, e1) in [(errors[0].0, errors[1].0), (errors[0].1, errors[1].1)] {
        assert!(e3 > 0.0 && rel(e1, e3) < 0.25, "scaled errors {e3} {e1}");
    }
}

/// Spec C-12, the Kirchhoff limit b₂ → ∞ (b₂ = 1e3, 1e4, 1e5 N): the contact angles
/// converge with differences shrinking like √(a/b₂) (ratio √10 ≈ 3.2 per decade; measured
/// 4.1 between the decades 1e3–1e4 and 1e4–1e5, still pre-asymptotic: asserted within
/// (2, 6), which excludes both O(1/b₂) (ratio 10) and no convergence (ratio 1)),
/// and p(A⁺)·ℓ_s converges (successive changes shrink by > 5×) to within 1 % of the
/// asymptotic Kirchhoff edge force √(aT̃)/R of spec §1.8 (measured 0.60 %, 0.64 %,
/// 0.65 %: the estimate itself assumes ℓ_b = √(a/T̃) ≪ R, here ℓ_b/R = 0.26).
#[test]
fn kirchhoff_limit_as_shear_stiffens() {
    let d = catalogue();
    let runs: Vec<_> = [1e3, 1e4, 1e5]
        .iter()
        .map(|&b2| {
            let c = CosseratPulley { shear_stiffness: b2, ..d };
            let s = solve(&c);
            let p = s.summary().pulley.unwrap();
            let kirchhoff = (c.bending_stiffness * c.effective(c.tension_in)).sqrt() / c.radius;
            (s.contact_angles(), p.edge_pressure_start.unwrap() * c.shear_layer() / kirchhoff - 1.0)
        })
        .collect();
    let step = |i: usize, j: usize| (0..3).map(|c| (runs[i].0[c] - runs[j].0[c]).abs()).fold(0.0, f64::max);
    let ratio = step(0, 1) / step(1, 2);
    assert!(ratio > 2.0 && ratio < 6.0, "angle steps shrink by {ratio}");
    let edge: Vec<f64> = runs.iter().map(|r| r.1).collect();
    let converging = (edge[2] - edge[1]).abs() < 0.2 * (edge[1] - edge[0]).abs();
    assert!(converging && edge.iter().all(|e| e.abs() < 0.01), "p·ℓ_s/P − 1: {edge:?}");
}

/// Spec §2.8, b₂ = 1e6 N: a shear layer √(a/(b₂ − ρc²)) = 0.1 mm on a 100 mm pulley.
/// Between the layers the fast shear mode (h|μ| ≈ 50 on the mesh the residual asks for)
/// is not damped by the Gauss collocation (A- but not L-stable), so the residual of
/// gauss6 chattered around tol 1e-8 for 43 passes and failed at the pass limit; the
/// adaptation now halves a segment whose residual stops falling (`FLOOR_PASSES`) and
/// solves. gauss6 and gauss8 at tol 1e-8 agree to their tolerances (ω, torque 1e-6
/// relative, angles 1e-6 rad; measured: ω identical — the stick zone's stretch at the
/// inflow tension sets it —, torque 2e-13, angles 2e-10 rad). The answer continues the Kirchhoff-limit trend
/// of `kirchhoff_limit_as_shear_stiffens`: the angles move less from 1e5 to 1e6 than from
/// 1e4 to 1e5.
#[test]
fn very_stiff_shear_solves() {
    let d = CosseratPulley { shear_stiffness: 1e6, ..catalogue() };
    let opts = |scheme| BeltOptions { tolerance: 1e-8, scheme, ..BeltOptions::default() };
    let g6 = cosserat_pulley::solve(&d, &opts(Scheme::Gauss6)).unwrap_or_else(|e| panic!("gauss6: {e}"));
    let g8 = cosserat_pulley::solve(&d, &opts(Scheme::Gauss8)).unwrap_or_else(|e| panic!("gauss8: {e}"));
    let da = (0..3).map(|c| (g6.contact_angles()[c] - g8.contact_angles()[c]).abs()).fold(0.0, f64::max);
    let (dw, dt) = (rel(g6.pulley_speed(), g8.pulley_speed()), rel(g6.torque(), g8.torque()));
    eprintln!("b₂ = 1e6: gauss6 vs gauss8 at 1e-8: ω {dw:.2e}, torque {dt:.2e}, angles {da:.2e} rad");
    assert!(dw < 1e-6 && dt < 1e-6 && da < 1e-6, "ω {dw:.2e}, torque {dt:.2e}, angles {da:.2e}");
    let angles = |b2: f64| solve(&CosseratPulley { shear_stiffness: b2, ..catalogue() }).contact_angles();
    let (a4, a5, a6) = (angles(1e4), angles(1e5), g8.contact_angles());
    let step = |a: [f64; 3], b: [f64; 3]| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max);
    assert!(step(a5, a6) < step(a4, a5), "1e5 → 1e6 moves {} rad, 1e4 → 1e5 {}", step(a5, a6), step(a4, a5));
}

/// Large μ (spec §2.8: μ ≥ 1): the slip arc shrinks faster than the string's capstan
/// ln(T̃_in/T̃_out)/μ, because μ times the edge-pressure peak at the last contact (its
/// excess ≈ the Kirchhoff edge force √(aT̃)/R ≈ 3 N against ΔT̃ = 5 N) carries a growing
/// share of the tension drop: measured 0.19 rad (capstan 0.42) at μ = 1, 0.023 rad
/// (capstan 0.14) at μ = 3; the inflow side (stick) does not see μ, the torque hardly
/// (1e-5), and the solves stay admissible. N_in = N_out: pure stick — the slip arc is 0
/// (not a failure), the torque vanishes and the summary has no `stick_slip_angle`.
#[test]
fn large_friction_and_equal_tensions() {
    let d = catalogue();
    let base = solve(&d);
    let mut slip = base.summary().pulley.unwrap().slip_arc.unwrap();
    for mu in [1.0, 3.0] {
        let s = solve(&CosseratPulley { friction: mu, ..d });
        let arc = s.summary().pulley.unwrap().slip_arc.unwrap();
        let creep = CosseratPulley { friction: mu, ..d }.string_slip_arc();
        assert!(arc > 0.0 && arc < 0.5 * creep && arc < 0.2 * slip, "μ = {mu}: slip arc {arc} (capstan {creep}, previous {slip})");
        slip = arc;
        assert_eq!(s.contact_angles()[0], base.contact_angles()[0], "μ = {mu}: the inflow side does not see μ");
        assert!(rel(s.torque(), base.torque()) < 1e-5);
    }
    let equal = solve(&CosseratPulley { tension_in: 12.0, tension_out: 12.0, ..d });
    let p = equal.summary().pulley.unwrap();
    assert!(p.slip_arc.unwrap().abs() < 1e-12, "slip arc {:?}", p.slip_arc);
    assert!(equal.torque().abs() < 1e-12, "torque {}", equal.torque());
    // no stick → slip point without a slip zone (the FE writes none either); the
    // catalogue scene's is there
    assert_eq!(p.stick_slip_angle, None, "pure stick has no transition");
    assert!(base.summary().pulley.unwrap().stick_slip_angle.is_some());
}

/// Spec C-13: doubling the end distance changes the outputs by O(exp(−D√(T̃_out/a))),
/// ≈ 1e-7 relative or less.
#[test]
fn end_distance_does_not_matter() {
    let d = catalogue();
    let (s, l) = (solve(&d), solve(&CosseratPulley { end_distance: 2.0 * d.end_distance, ..d }));
    for (a, b) in s.contact_angles().iter().zip(l.contact_angles()) {
        assert!((a - b).abs() < 1e-7, "{a} {b}");
    }
    assert!(rel(s.pulley_speed(), l.pulley_speed()) < 1e-7 && rel(s.torque(), l.torque()) < 1e-7);
}

/// Mode `tensions` beyond the string's capstan (docs/cosserat-pulley.md, "Beyond the
/// string's capstan"): tension ratios whose string creep slip arc ln(T̃_high/T̃_low)/μ
/// exceeds the string contact arc π − (√(a/T̃_in) + √(a/T̃_out))/R, but which the rod
/// carries (μ times its edge pressure peaks adds friction the string has not; the FE
/// solves them too). Before, the BVP refused them by the string estimate. Each solves,
/// driving and braking, with a stick arc > 0, the torque of the tension difference
/// (C-6, 1e-3: the estimate R(F̃_in − F̃_out) holds to 5e-5 on the catalogue scene), and
/// round-trips through mode `transition` (C-11: φ_B and the larger tension given, the
/// smaller returned to 1e-8 relative at collocation tolerance 1e-10, as
/// `prescription_modes_round_trip`). Measured stick arcs: 2.348° (15 → 6.8 N), 0.485°
/// (15 → 6.5 N), 4.695° (7 → 15 N); the FE at 256 elements 2.25°, 0.454°, 5.04°.
#[test]
fn tension_ratios_beyond_the_string_capstan_solve() {
    let opts = BeltOptions::collocation(Scheme::default(), 1e-10);
    for (n_in, n_out) in [(15.0, 6.8), (15.0, 6.5), (7.0, 15.0)] {
        let d = CosseratPulley { tension_in: n_in, tension_out: n_out, ..catalogue() };
        let layers = ((d.bending_stiffness / d.effective(n_in)).sqrt() + (d.bending_stiffness / d.effective(n_out)).sqrt()) / d.radius;
        assert!(d.string_slip_arc() > std::f64::consts::PI - layers, "({n_in}, {n_out}) is not beyond the string's capstan");
        let s = cosserat_pulley::solve(&d, &opts).unwrap_or_else(|e| panic!("({n_in}, {n_out}): {e}"));
        let [a, b, c] = s.contact_angles();
        assert!(a > b && b > c, "({n_in}, {n_out}): φ = {a}, {b}, {c}");
        let torque = d.radius * (d.effective(n_in) - d.effective(n_out));
        assert!(rel(s.torque(), -torque) < 1e-3, "({n_in}, {n_out}): torque {} vs {}", s.torque(), -torque);
        let driving = n_in > n_out;
        let (given, mode_data) = if driving {
            (End::In, CosseratPulley { tension_out: f64::NAN, ..d })
        } else {
            (End::Out, CosseratPulley { tension_in: f64::NAN, ..d })
        };
        let back = cosserat_pulley::solve(&mode_data.with_mode(Mode::Transition { stick_slip_angle: b, given, driving }).unwrap(), &opts).unwrap_or_else(|e| panic!("({n_in}, {n_out}) round trip: {e}"));
        let (free, want) = if driving { (back.data.tension_out, n_out) } else { (back.data.tension_in, n_in) };
        eprintln!("({n_in}, {n_out}): stick arc {:.6}°, round trip {free}", (a - b).to_degrees());
        assert!(rel(free, want) < 1e-8, "({n_in}, {n_out}): round trip returns {free}");
    }
    // beyond the rod's capacity too: named with the tension the wrap holds at a vanished
    // stick arc (μ = 0.1: down to 11.18 N against the 10 N given; the string's capstan over
    // its contact arc 2.557 rad reaches only 11.71 N — the rod's edge peaks carry more)
    let e = cosserat_pulley::solve(&CosseratPulley { friction: 0.1, ..catalogue() }, &BeltOptions::default()).unwrap_err();
    match e {
        BeltError::CapstanLimitExceeded { reached, target, stick_arc, .. } => {
            assert!(reached > target + 1.0 && reached < 12.0 && stick_arc < 1e-8, "{reached} {target} {stick_arc}");
        }
        e => panic!("{e}"),
    }
}

/// Named errors before any solve (spec §2.2, §2.8): b₂ at the transport term ρc²
/// (shear-critical speed), T̃ ≤ 0 at an end, a tension ratio beyond the friction
/// capacity of the wrap; b₂ − χ small with a shear layer longer than R fails by name, as
/// does shooting across a shear layer far thinner than its intervals.
#[test]
fn hard_cases_fail_by_name() {
    let d = catalogue();
    let chi = d.mass_per_length * d.transport_rate * d.transport_rate;
    let e = cosserat_pulley::solve(&CosseratPulley { shear_stiffness: chi, ..d }, &BeltOptions::default()).unwrap_err();
    assert!(matches!(e, BeltError::SpeedAtOrAboveCritical { stiffness, .. } if stiffness.contains("shear")), "{e}");
    let e = cosserat_pulley::solve(&CosseratPulley { transport_rate: 11.0, ..d }, &BeltOptions::default()).unwrap_err();
    assert!(matches!(e, BeltError::EffectiveTensionNotPositive { end: "outflow", effective, .. } if effective < 0.0), "{e}");
    let e = cosserat_pulley::solve(&CosseratPulley { friction: 0.1, ..d }, &BeltOptions::default()).unwrap_err();
    assert!(matches!(e, BeltError::CapstanLimitExceeded { reached, target, .. } if reached > target), "{e}");
    // b₂ − χ ≤ T̃ (1 N; a scene file is refused before, drive's validation) and just above
    // it (16 N): the first solve from the string's creep state at the scene's a fails —
    // said so, not as a homotopy "stalled at η = 0" from a₀ = a (the message before)
    for b2 in [1.0, 16.0] {
        let e = cosserat_pulley::solve(&CosseratPulley { shear_stiffness: b2, ..d }, &BeltOptions::default()).unwrap_err();
        let text = e.to_string();
        assert!(matches!(e, BeltError::StartFailed { .. }) && text.contains("no continuation in a needed") && text.contains("shear layer") && !text.contains("stalled"), "b₂ = {b2}: {text}");
    }
    // b₂ = 1e6 N by shooting: its 8 intervals per segment span ≈ 390 shear layers of
    // 0.1 mm, the flows overflow; named with the layer and the interval, while
    // collocation solves it (very_stiff_shear_solves)
    let shooting = BeltOptions { method: bvp::belt::BvpMethod::Shooting, ..BeltOptions::default() };
    let e = cosserat_pulley::solve(&CosseratPulley { shear_stiffness: 1e6, ..d }, &shooting).unwrap_err();
    assert!(matches!(e, BeltError::ShootingAcrossLayer { layer, intervals: 8, .. } if (layer - 1e-4).abs() < 1e-9), "{e}");
}

/// The catalogue scene file (`scenes/cosserat-pulley.json`, exactly the format
/// plus its gate block) solves from the file alone through `solve_scene` to the catalogue
/// data's answer, and its common view runs along the open contour: σ from the inflow end
/// (x = −D, upper side) to the outflow end (x = −D, lower side), free → stick → slip →
/// free in that order, the summary's end offsets and tensions at the ends of σ, pressure
/// and friction zero on the spans. `pulley_speed` with `tension_in` is refused by name.
#[test]
fn scene_file_solves_from_the_file_alone() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cosserat-pulley.json");
    let scene = drive::scene::Scene::from_path(&path).expect("the issue's scene parses");
    let opts = bvp::scene::BvpRunOptions::from_scene(&scene).unwrap();
    let data = bvp::scene::cosserat_pulley_data(&scene).unwrap();
    let d = catalogue();
    assert_eq!(format!("{data:?}"), format!("{d:?}"));
    let run = bvp::scene::solve_scene(&scene, &opts).expect("solve_scene runs the one-pulley layout");
    let v = &*run.view;
    assert!(rel(run.summary.pulley_speed.unwrap(), 20.02931) < 1e-6 && run.summary.pulley.as_ref().unwrap().slip_arc.is_some());
    assert!(run.summary.driver.is_none() && run.summary.y_upper_mid.is_none(), "no two-pulley quantities");
    let path = v.path();
    assert!(path.is_open() && v.contour().is_none());
    let l = path.length();
    assert!((l - (2.0 * d.end_distance + std::f64::consts::PI * d.radius)).abs() < 1e-14);
    let (p0, p1) = (v.position(0.0), v.position(l));
    assert!((p0[0] + d.end_distance).abs() < 1e-12 && (p1[0] + d.end_distance).abs() < 1e-12, "{p0:?} {p1:?}");
    assert!((p0[1] - run.summary.y_in.unwrap()).abs() < 1e-12 && (p1[1] - run.summary.y_out.unwrap()).abs() < 1e-12);
    assert!((v.axial_force(0.0) - 15.0).abs() < 1e-9 && (v.axial_force(l) - 10.0).abs() < 1e-9);
    assert!((v.rotation(0.0).unwrap()).abs() < 1e-12 && (v.rotation(l).unwrap() + std::f64::consts::PI).abs() < 1e-12);
    let mut states = vec![];
    for i in 0..=400 {
        let sigma = l * i as f64 / 400.0;
        let st = v.contact_state(sigma);
        if states.last() != Some(&st) {
            states.push(st);
        }
        if st == ContactState::Free {
            assert_eq!((v.contact_pressure(sigma), v.friction_traction(sigma)), (Some(0.0), Some(0.0)));
        } else {
            assert!(v.contact_pressure(sigma).unwrap() > 0.0);
        }
        // the belt point at σ lies on the contour normal at σ
        let q = v.position(sigma);
        assert!((path.sigma_nu(q).0 - sigma).abs() < 1e-9, "σ = {sigma}");
    }
    assert_eq!(states, [ContactState::Free, ContactState::Stick, ContactState::Slip, ContactState::Free]);
    let fields = drive::view::sample_fields(v, 64);
    fields.check().unwrap();
    assert!(fields.rotation.is_some() && fields.shear_strain.is_some() && fields.pressure.is_some() && fields.state.is_some());
    let mut speed = scene.clone();
    (speed.drive.tension_out, speed.drive.pulley_speed) = (None, Some(20.0));
    let e = bvp::scene::cosserat_pulley_data(&speed).unwrap_err();
    assert!(matches!(e, bvp::scene::SceneSolveError::IllPosedPrescription { given: "pulley_speed + tension_in", .. }), "{e}");
}

/// The braking sense from a scene file: φ_B of the braking `tensions` solve (N_in = 10,
/// N_out = 15 N) with N_out given and `belt_drives_pulley: true` returns N_in = 10 N (to
/// 1e-8, the collocation tolerance 1e-10 as in the round trip below) and a positive
/// torque; the same φ_B without the field is the driving solution, N_in > N_out, with the
/// same slip arc to the capstan's accuracy (a different state: φ_B fixes the arc, not its
/// sense).
#[test]
fn scene_chooses_the_sense_of_a_prescribed_transition() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cosserat-pulley.json");
    let base = drive::scene::Scene::from_path(&path).unwrap();
    let mut tensions = base.clone();
    (tensions.drive.tension_in, tensions.drive.tension_out) = (Some(10.0), Some(15.0));
    let mut opts = bvp::scene::BvpRunOptions::from_scene(&tensions).unwrap();
    opts.tolerance = 1e-10;
    let reference = bvp::scene::solve_scene(&tensions, &opts).unwrap().summary;
    let p = reference.pulley.as_ref().unwrap();
    let phi_b = p.contact_end.unwrap() + p.slip_arc.unwrap();
    let mut braking = base.clone();
    (braking.drive.tension_in, braking.drive.stick_slip_angle, braking.drive.belt_drives_pulley) = (None, Some(phi_b), Some(true));
    braking.drive.tension_out = Some(15.0);
    braking.validate().unwrap();
    let s = bvp::scene::solve_scene(&braking, &opts).unwrap().summary;
    assert!((s.tension_in.unwrap() - 10.0).abs() < 1e-8, "N_in = {:?}", s.tension_in);
    assert!(s.pulley.as_ref().unwrap().torque.unwrap() > 0.49, "the belt drives the pulley");
    braking.drive.belt_drives_pulley = None;
    let s = bvp::scene::solve_scene(&braking, &opts).unwrap().summary;
    let q = s.pulley.as_ref().unwrap();
    assert!(s.tension_in.unwrap() > 20.0 && q.torque.unwrap() < -0.5, "driving: N_in = {:?}, torque {:?}", s.tension_in, q.torque);
    assert!((q.slip_arc.unwrap() - p.slip_arc.unwrap()).abs() < 1e-3, "slip arcs {:?} / {:?}", q.slip_arc, p.slip_arc);
}

/// Spec C-11, the round trip of the prescription modes: given the `tensions` solution's
/// ω (mode `pulley_speed`, with N_out) or φ_B (mode `transition`, with either tension),
/// each mode returns the other tension and every output of that solution. Driving
/// (N_in > N_out) and braking (N_in < N_out). Tolerance: the three solves meet the same
/// collocation tolerance 1e-10 on the same problem, so their outputs agree to a few
/// times it (1e-8 relative; measured ≤ 1e-9).
#[test]
fn prescription_modes_round_trip() {
    let opts = BeltOptions::collocation(Scheme::default(), 1e-10);
    for base in [catalogue(), CosseratPulley { tension_in: 10.0, tension_out: 15.0, ..catalogue() }] {
        let reference = cosserat_pulley::solve(&base, &opts).unwrap();
        let (omega, phi_b) = (reference.pulley_speed(), reference.contact_angles()[1]);
        let driving = base.tension_in > base.tension_out;
        let modes = [
            (Mode::PulleySpeed { pulley_speed: omega }, CosseratPulley { tension_in: f64::NAN, ..base }),
            (Mode::Transition { stick_slip_angle: phi_b, given: End::Out, driving }, CosseratPulley { tension_in: f64::NAN, ..base }),
            (Mode::Transition { stick_slip_angle: phi_b, given: End::In, driving }, CosseratPulley { tension_out: f64::NAN, ..base }),
        ];
        for (mode, data) in modes {
            let d = data.with_mode(mode).unwrap();
            assert!(d.tension_in.is_finite() && d.tension_out.is_finite(), "{mode:?}: the start estimate fills the free tension");
            let s = cosserat_pulley::solve(&d, &opts).unwrap_or_else(|e| panic!("{mode:?}: {e}"));
            let (a, b) = (s.summary(), reference.summary());
            for ((name, x), (_, y)) in a.scalars().iter().zip(b.scalars().iter()) {
                assert!((x - y).abs() <= 1e-8 * y.abs().max(1.0), "{mode:?} ({} → {}): {name} {x} vs {y}", base.tension_in, base.tension_out);
            }
            assert_eq!(a.scalars().len(), b.scalars().len());
            assert!((s.data.tension_in - base.tension_in).abs() < 1e-8 * base.tension_in, "{mode:?}: N_in {}", s.data.tension_in);
        }
    }
    // a transition angle below the contact end has no slip arc: named before the solve
    let e = catalogue().with_mode(Mode::Transition { stick_slip_angle: -1.6, given: End::Out, driving: true }).unwrap_err();
    assert!(matches!(e, BeltError::InvalidInput { name: "stick_slip_angle", .. }), "{e}");
}
