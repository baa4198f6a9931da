//! The Cosserat two-pulley drive in steady motion (docs/cosserat-drive.md; issue 14, BVP
//! half): the catalogue scene from its file, its balances and admissibility,
//! collocation against shooting, the string limit, the named errors; the driver's
//! stick → slip angle prescribed with M₂ released (D-9).

use std::path::Path;
use std::sync::OnceLock;

use bvp::belt::topology::{ArcKind, Pulley};
use bvp::belt::{BeltError, BeltOptions, BeltPoint, BeltSolution, SectionLaw};
use bvp::cosserat_drive::{self, CosseratDrive, CosseratDriveSolution, DriveMode};
use drive::scene::Scene;
use drive::view::SolutionView;

fn scene_data() -> (Scene, CosseratDrive) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cosserat-drive.json");
    let scene = Scene::from_path(&path).expect("the scene parses and validates");
    let data = CosseratDrive::from_scene(&scene).expect("a Cosserat drive scene");
    (scene, data)
}

/// The scene solved once by collocation from its file (shared by the tests).
fn solved() -> &'static CosseratDriveSolution {
    static SOL: OnceLock<CosseratDriveSolution> = OnceLock::new();
    SOL.get_or_init(|| {
        let (scene, data) = scene_data();
        let opts = BeltOptions::from_scene(&scene).expect("options");
        cosserat_drive::solve(&data, &opts).expect("the scene solves from its file")
    })
}

/// F̃ (N) of a point: F̃·e₁ = T̃, F̃·e₂ = Q(b₂ − χ)/b₂ (spec §1.2), rotated by θ.
fn effective_force(d: &CosseratDrive, chi: f64, p: &BeltPoint) -> [f64; 2] {
    let (te, qe) = (p.effective_tension.unwrap(), p.shear.unwrap() * (d.shear_stiffness - chi) / d.shear_stiffness);
    let (c, s) = (p.theta.unwrap().cos(), p.theta.unwrap().sin());
    [te * c - qe * s, te * s + qe * c]
}

/// The scene: the stick kinematics and the creep identity (D-4), the driven torque
/// balance, the power balance (D-3) and the edge pressure against its estimate (spec
/// §1.8). The stick kinematics and the torque are conditions of the BVP (round-off);
/// the power balance is not imposed — its defect is the quadrature of the dissipation
/// on the converged mesh (tolerance 1e-8, 5-point Gauss per interval: ≤ 1e-7 P).
#[test]
fn scene_solves_with_its_balances() {
    let sol = solved();
    let d = &sol.data.drive;
    let (l1, l2) = sol.stick_stretches();
    let (c, w2) = (sol.transport_rate().unwrap(), sol.driven_speed().unwrap());
    assert!((c * l1 - d.driver_speed * d.radius).abs() <= 1e-12, "cλ₁ = {} vs ω₁R", c * l1);
    assert!((w2 / d.driver_speed - l2 / l1).abs() <= 1e-12, "creep identity: ω₂/ω₁ = {} vs λ₂/λ₁ = {}", w2 / d.driver_speed, l2 / l1);
    assert!(l1 > l2 && w2 < d.driver_speed, "the driven pulley creeps behind: λ₁ = {l1}, λ₂ = {l2}");
    assert!((sol.torque(Pulley::Driven).unwrap() - d.driven_torque).abs() <= 1e-12);
    let (input, output, dissipation) = sol.power_balance();
    assert!(dissipation > 0.0, "D = {dissipation} W");
    assert!((input - output - dissipation).abs() <= 1e-7 * input, "power: {input} = {output} + {dissipation}");
    // edge pressure ≈ √(T̃ (b₂ − χ))/R at each first contact (spec §1.8, ~1 % on the
    // one-pulley scene; here the layers √(a/T̃) ≈ 0.3 R are not ≪ R: 5 %)
    let chi = sol.data.chi(c);
    let summary = sol.summary();
    for (pulley, ps) in [(Pulley::Driver, summary.driver.unwrap()), (Pulley::Driven, summary.driven.unwrap())] {
        let k = sol.topology().first_arc(pulley);
        let te = sol.point(k, 0.0).effective_tension.unwrap();
        let estimate = (te * (sol.data.shear_stiffness - chi)).sqrt() / d.radius;
        let p = ps.edge_pressure_start.unwrap();
        assert!((p / estimate - 1.0).abs() < 0.05, "{}: edge pressure {p} vs estimate {estimate}", pulley.name());
        assert!(ps.contact_arc.unwrap() < std::f64::consts::PI && ps.slip_arc.unwrap() > 0.0 && ps.stick_arc.unwrap() > 0.0);
    }
}

/// Moment about each pulley centre (spec §1.7): the belt's clockwise torque
/// −R∫f_t ds = −[M + k·((r − C) × F̃)]_start^end + ρg∫(x − x_C) ds, from the point
/// output (the torque is the BVP's quadrature τ′ = −R f_t, the rest its states), and
/// the vertical force balance Σ F_iy = ρgL (D-2). The moment balance holds to the
/// BVP's tolerance (1e-8) and the trapezoidal ∫(x − x_C) ds over 32 points per mesh
/// interval (measured 1.4e-8 N·m against a torque of 0.1 N·m and a limit 1.3e-7 N·m
/// on the scene's gauss8 mesh of 626 nodes; the trapezoidal error is O(h²): 8 points
/// per interval gave 5e-8 N·m on gauss6's 2457 nodes, 2.2e-7 N·m on gauss8's):
/// 1e-6 F_ref R.
#[test]
fn moment_and_force_balances_hold() {
    let sol = solved();
    let (dd, d) = (&sol.data, &sol.data.drive);
    let chi = dd.chi(sol.transport_rate().unwrap());
    let w = d.mass_per_length * d.gravity;
    let topo = sol.topology();
    let samples = sol.samples(32);
    let mut vertical = 0.0;
    for pulley in [Pulley::Driver, Pulley::Driven] {
        let xc = pulley.centre_x() * d.centre_distance;
        let (first, last) = (topo.first_arc(pulley), topo.last_arc(pulley));
        let (a, b) = (sol.point(first, 0.0), sol.point(last, 1.0));
        let moment = |p: &BeltPoint| {
            let f = effective_force(dd, chi, p);
            p.moment.unwrap() + (p.x - xc) * f[1] - p.y * f[0]
        };
        let arc: Vec<&BeltPoint> = samples.iter().filter(|(k, _, _)| *k == first || *k == last).map(|(_, _, p)| p).collect();
        let lever: f64 = arc.windows(2).map(|q| 0.5 * (q[0].x + q[1].x - 2.0 * xc) * (q[1].material - q[0].material)).sum();
        let torque = b.torque.unwrap();
        let balance = torque + moment(&b) - moment(&a) - w * lever;
        assert!(balance.abs() <= 1e-6 * sol.scales.force * d.radius, "{}: torque {torque} N·m, imbalance {balance:e}", pulley.name());
        // resultant of the pulley on the belt: F̃(start) − F̃(end) + ρg ℓ_arc j
        let (fa, fb) = (effective_force(dd, chi, &a), effective_force(dd, chi, &b));
        vertical += fa[1] - fb[1] + w * (b.material - a.material);
    }
    assert!((vertical - w * d.length).abs() <= 1e-9 * w * d.length, "Σ F_y = {vertical} N vs ρgL = {} N", w * d.length);
}

/// The contact law at every sample (D-10): slip f_t = σμp (σ₁ = +1, σ₂ = −1 clockwise
/// with the driver driving) — this holds the transport and weight terms added to the
/// one-pulley arc against (C4) — and |f_t| ≤ μp, p > 0 in stick; (C5) E − ρgy constant
/// on each span (D-1; its drift is the discretisation error at tolerance 1e-8).
#[test]
fn contact_law_and_span_invariant() {
    let sol = solved();
    let (dd, d) = (&sol.data, &sol.data.drive);
    let chi = dd.chi(sol.transport_rate().unwrap());
    let topo = sol.topology();
    let fr = sol.scales.force;
    let mut spans: Vec<(usize, f64, f64)> = Vec::new();
    for (k, _, p) in sol.samples(4) {
        let seg = topo.segment(k);
        match (seg.pulley(), seg.kind) {
            (Some(pulley), bvp::belt::SegmentKind::Arc(kind)) => {
                let (pr, ft) = (p.pressure.unwrap(), p.friction.unwrap());
                assert!(pr > 0.0, "p = {pr} on the {} pulley", pulley.name());
                if kind == ArcKind::Slip {
                    let sigma = if pulley == Pulley::Driver { 1.0 } else { -1.0 };
                    assert!((ft - sigma * d.friction * pr).abs() <= 1e-9 * fr / d.radius, "slip: f_t = {ft}, σμp = {}", sigma * d.friction * pr);
                } else {
                    assert!(ft.abs() <= d.friction * pr, "stick: |f_t| = {ft} > μp = {}", d.friction * pr);
                }
            }
            _ => {
                let (m, n, q) = (p.moment.unwrap(), p.tension, p.shear.unwrap());
                let e = m * m / (2.0 * dd.bending_stiffness) + n + n * n / (2.0 * d.axial_stiffness) + q * q / (2.0 * dd.shear_stiffness)
                    - 0.5 * chi * p.stretch * p.stretch
                    - d.mass_per_length * d.gravity * p.y;
                match spans.iter_mut().find(|s| s.0 == k) {
                    Some(s) => (s.1, s.2) = (s.1.min(e), s.2.max(e)),
                    None => spans.push((k, e, e)),
                }
            }
        }
    }
    for (k, lo, hi) in spans {
        assert!(hi - lo <= 1e-8 * fr, "span {k}: E − ρgy drifts by {:e} N", hi - lo);
    }
}

/// Collocation and shooting agree on the summary to 1e-6 of the force, length and speed
/// scales (both at tolerance 1e-8).
#[test]
fn collocation_and_shooting_agree() {
    let sol = solved();
    let (_, data) = scene_data();
    let shot = cosserat_drive::solve(&data, &BeltOptions::shooting(1e-8)).expect("shooting solves");
    let (a, b) = (sol.summary(), shot.summary());
    let pairs = [
        ("tension_tight", a.tension_tight, b.tension_tight, sol.scales.force),
        ("tension_slack", a.tension_slack, b.tension_slack, sol.scales.force),
        ("tension_upper_mid", a.tension_upper_mid, b.tension_upper_mid, sol.scales.force),
        ("y_lower_mid", a.y_lower_mid, b.y_lower_mid, data.drive.radius),
        ("driven_speed", a.driven_speed, b.driven_speed, data.drive.driver_speed),
        ("transport_rate", a.transport_rate, b.transport_rate, data.drive.driver_speed * data.drive.radius),
        ("driver.slip_arc", a.driver.as_ref().unwrap().slip_arc, b.driver.as_ref().unwrap().slip_arc, 1.0),
        ("driven.slip_arc", a.driven.as_ref().unwrap().slip_arc, b.driven.as_ref().unwrap().slip_arc, 1.0),
        ("driver.contact_arc", a.driver.as_ref().unwrap().contact_arc, b.driver.as_ref().unwrap().contact_arc, 1.0),
        ("driver.torque", a.driver.as_ref().unwrap().torque, b.driver.as_ref().unwrap().torque, sol.scales.force * data.drive.radius),
        ("driven.edge_pressure_start", a.driven.as_ref().unwrap().edge_pressure_start, b.driven.as_ref().unwrap().edge_pressure_start, sol.scales.force / data.drive.radius),
    ];
    for (name, x, y, scale) in pairs {
        let (x, y) = (x.unwrap(), y.unwrap());
        assert!((x - y).abs() <= 1e-6 * scale, "{name}: collocation {x} vs shooting {y}");
    }
}

/// String limit (D-6, spec §1.9): with b₂ = 1e4 N (shear layer √(a/b₂) ≪ bending layer
/// √(a/T̃)) and
/// a → 0 the drive approaches the `string-drive` BVP of the same scene (the solution's
/// start). The difference scales like √a (the bending layers √(a/T̃) cut the contact
/// arcs by ≈ 2√(a/T̃)/R): each quartering of a must at least roughly halve the contact-arc
/// and the tight-tension differences (ratio ≤ 0.6; measured 0.50 and 0.21 from a = 5e-4
/// to 1.25e-4), and at a = 1.25e-4 they are below 0.15 rad (2√(a/T̃)/R ≈ 0.09 rad) and 1 %.
#[test]
fn string_limit_as_a_vanishes() {
    let (scene, base) = scene_data();
    // the trend is at the 1e-2 level: tolerance 1e-6 keeps the meshes of the thin layers small
    let opts = BeltOptions { tolerance: 1e-6, ..BeltOptions::from_scene(&scene).expect("options") };
    let mut diffs = Vec::new();
    for a in [2e-3, 5e-4, 1.25e-4] {
        let data = CosseratDrive { bending_stiffness: a, shear_stiffness: 1e4, ..base };
        let sol = cosserat_drive::solve(&data, &opts).unwrap_or_else(|e| panic!("a = {a}: {e}"));
        let (c, s) = (sol.summary(), sol.start.summary());
        let dt = (c.tension_tight.unwrap() - s.tension_tight.unwrap()).abs() / s.tension_tight.unwrap();
        let darc = (c.driver.as_ref().unwrap().contact_arc.unwrap() - s.driver.as_ref().unwrap().contact_arc.unwrap()).abs();
        let dslip = (c.driver.as_ref().unwrap().slip_arc.unwrap() - s.driver.as_ref().unwrap().slip_arc.unwrap()).abs();
        eprintln!("a = {a:e}: tension {dt:e}, contact arc {darc:e}, slip arc {dslip:e}");
        diffs.push((dt, darc));
    }
    for w in diffs.windows(2) {
        assert!(w[1].1 <= 0.6 * w[0].1, "contact-arc difference {:e} → {:e} does not fall like √a", w[0].1, w[1].1);
        assert!(w[1].0 <= 0.6 * w[0].0, "tension difference {:e} → {:e} does not fall like √a", w[0].0, w[1].0);
    }
    let (dt, darc) = diffs[diffs.len() - 1];
    assert!(dt < 0.01 && darc < 0.15, "a = 1.25e-4: tension {dt:e}, contact arc {darc:e}");
}

/// Named errors: a transport term at or above b₂ before any iteration; a torque above
/// the friction capacity on the homotopy path.
#[test]
fn critical_speed_and_capacity_are_named() {
    let (_, base) = scene_data();
    let opts = BeltOptions::default();
    // ρ(ω₁R)² = 0.12 · 1.6² = 0.307 N ≥ b₂ = 0.3 N
    let fast = CosseratDrive { shear_stiffness: 0.3, ..base };
    match cosserat_drive::solve(&fast, &opts) {
        Err(BeltError::SpeedAtOrAboveCritical { stiffness, chi, value, .. }) => {
            assert!(stiffness.contains("b₂") && chi >= value, "{stiffness}: χ = {chi}, b = {value}")
        }
        other => panic!("expected SpeedAtOrAboveCritical, got {other:?}"),
    }
    // capacity ≈ R T̃_t (1 − e^{−μπ}) ≈ 0.08 · 10 · 0.61 ≈ 0.5 N·m with T̃_t ≈ 10 N: 2 N·m is far above
    let overloaded = CosseratDrive { drive: bvp::string_drive::StringDrive { driven_torque: 2.0, ..base.drive }, ..base };
    match cosserat_drive::solve(&overloaded, &opts) {
        Err(BeltError::FrictionCapacityExceeded { torque, .. }) => assert_eq!(torque, 2.0),
        other => panic!("expected FrictionCapacityExceeded, got {other:?}"),
    }
}

/// The AD Jacobians of the law (spans, arcs with the transport and weight terms through
/// the unknown c, the contact rows, the loop conditions) agree with central differences
/// at generic states, the scene's parameters and three points of the a-path; 1e-6
/// relative is the accuracy of h ~ ε^{1/3} differences.
#[test]
fn ad_jacobians_match_finite_differences() {
    let sol = solved();
    for eta in [0.0, 0.5, 1.0] {
        let worst = bvp::jacobian::ad_fd_mismatch_sampled(&sol.problem, &sol.solution.params, eta);
        assert!(worst <= 1e-6, "η = {eta}: AD vs central differences {worst:e}");
    }
}

/// Both rotation senses (issue 14): a negative driver speed with the load resisting
/// (M₂ < 0) runs the belt counter-clockwise, slip then stick along σ on each pulley.
/// Without gravity (belt 1.40 m, stretched on) it is the mirror image of the clockwise
/// drive: span tensions (upper and lower swapped), stick stretches and arcs equal, c,
/// ω₂ and the torques negated, to
/// 1e-6 of their scales (both solves at 1e-8); with gravity it solves too, with the
/// upper span the tight one (its mid-span tension above the lower span's).
#[test]
fn counter_clockwise_mirrors_without_gravity() {
    let (_, base) = scene_data();
    let opts = BeltOptions::default();
    let drive = |speed: f64, torque: f64, gravity: f64, length: f64| {
        let belt = bvp::string_hanging::StringHanging { gravity, length, ..base.drive.belt };
        CosseratDrive { drive: bvp::string_drive::StringDrive { driver_speed: speed, driven_torque: torque, belt, ..base.drive }, ..base }
    };
    let cw = cosserat_drive::solve(&drive(20.0, 0.1, 0.0, 1.40), &opts).expect("clockwise, no gravity");
    let ccw = cosserat_drive::solve(&drive(-20.0, -0.1, 0.0, 1.40), &opts).expect("counter-clockwise, no gravity");
    let (a, b) = (cw.summary(), ccw.summary());
    let fr = cw.scales.force;
    let r = base.drive.radius;
    let same = [
        // the tight span is the lower one clockwise, the upper one counter-clockwise
        ("tight mid-span tension", a.tension_lower_mid.unwrap(), b.tension_upper_mid.unwrap(), fr),
        ("slack mid-span tension", a.tension_upper_mid.unwrap(), b.tension_lower_mid.unwrap(), fr),
        ("driver stick stretch", cw.stick_stretches().0, ccw.stick_stretches().0, 1.0),
        ("driven stick stretch", cw.stick_stretches().1, ccw.stick_stretches().1, 1.0),
        ("driver.slip_arc", a.driver.as_ref().unwrap().slip_arc.unwrap(), b.driver.as_ref().unwrap().slip_arc.unwrap(), 1.0),
        ("driven.stick_arc", a.driven.as_ref().unwrap().stick_arc.unwrap(), b.driven.as_ref().unwrap().stick_arc.unwrap(), 1.0),
        ("driver.contact_arc", a.driver.as_ref().unwrap().contact_arc.unwrap(), b.driver.as_ref().unwrap().contact_arc.unwrap(), 1.0),
        ("transport_rate", a.transport_rate.unwrap(), -b.transport_rate.unwrap(), 20.0 * r),
        ("driven_speed", a.driven_speed.unwrap(), -b.driven_speed.unwrap(), 20.0),
        ("driver.torque", a.driver.as_ref().unwrap().torque.unwrap(), -b.driver.as_ref().unwrap().torque.unwrap(), fr * r),
    ];
    for (name, x, y, scale) in same {
        assert!((x - y).abs() <= 1e-6 * scale, "{name}: clockwise {x} vs mirrored counter-clockwise {y}");
    }
    let heavy = cosserat_drive::solve(&drive(-20.0, -0.1, 9.81, base.drive.length), &opts).expect("counter-clockwise with gravity");
    for (sense, sol) in [("clockwise", &cw), ("counter-clockwise", &ccw), ("counter-clockwise with gravity", &heavy)] {
        stick_middle_forces(sense, sol, false);
        stick_middle_forces(&format!("{sense}, string start"), &sol.start, true);
    }
    let s = heavy.summary();
    assert!(s.tension_upper_mid.unwrap() > s.tension_lower_mid.unwrap(), "upper span tight: {s:?}");
    let (input, output, dissipation) = heavy.power_balance();
    assert!((input - output - dissipation).abs() <= 1e-7 * input && dissipation > 0.0, "power {input} = {output} + {dissipation}");
}

/// `tension_tight` / `tension_slack` are N at the middle (ξ = ½, φ linear in ξ) of the
/// driver's / driven pulley's stick arc (spec §3.7, as the FE: docs/fem-drive.md §8),
/// in either running direction — counter-clockwise the stick arc follows the slip arc
/// along σ, so its ξ = 0 end is the slip → stick end. The string's N is constant in a
/// stick zone: middle and both ends agree to 1e-9 relative (round-off and the dense
/// output on a constant state). The Cosserat belt's N varies in the bending and shear
/// layers at the contact entry (√(a/T̃) ≈ 11 mm, √(a/(b₂ − χ)) ≈ 2.2 mm against an arc of
/// ≈ 0.19 m) and, less, at the stick → slip point: the two ends differ by more than 1e-4
/// relative (measured 5.6e-3 on the driver clockwise without gravity: 39.34 N at the
/// entry, 39.55 N at the stick → slip point), while the middle fifth of the arc is flat
/// to the solve's tolerance 1e-8 (measured ≤ 1e-11) at a value neither end gives in
/// general (there 39.56 N) — creep theory's stick-zone force.
fn stick_middle_forces<L: SectionLaw>(sense: &str, sol: &BeltSolution<L>, string: bool) {
    let summary = sol.summary();
    for (pulley, reported) in [(Pulley::Driver, summary.tension_tight), (Pulley::Driven, summary.tension_slack)] {
        let k = sol.problem.topology.arc(pulley, ArcKind::Stick).expect("a stick arc");
        let [start, near_start, middle, near_end, end] = [0.0, 0.4, 0.5, 0.6, 1.0].map(|xi| sol.point(k, xi).tension);
        let what = format!("{sense}, {pulley:?}: N = {start} (ξ = 0), {near_start} (0.4), {middle} (0.5), {near_end} (0.6), {end} (1)");
        let reported = reported.expect("a drive reports its stick-zone forces");
        assert_eq!(reported, middle, "{what}: the summary reads the middle of the stick arc");
        if string {
            for e in [start, end] {
                assert!((e - middle).abs() <= 1e-9 * middle, "{what}: the string's stick-zone force is not constant");
            }
        } else {
            assert!((start - end).abs() > 1e-4 * middle, "{what}: the ends should differ (edge layers)");
            for e in [near_start, near_end] {
                assert!((e - middle).abs() <= 1e-8 * middle, "{what}: not flat in the middle of the stick arc");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// D-9: the driver's stick → slip angle φ_B1 prescribed, M₂ released (spec §3.4;
// docs/cosserat-drive.md, "Prescribed stick→slip angle: the round trip D-9").

/// The tightest tolerance the round trip is run at (collocation, the scene's gauss8).
const ROUND_TRIP_TOLERANCE: f64 = 1e-10;

/// The catalogue scene solved in the standard mode (M₂ = 0.1 N·m given) at tolerance
/// 1e-10, shared by the D-9 tests.
fn solved_tight() -> &'static CosseratDriveSolution {
    static SOL: OnceLock<CosseratDriveSolution> = OnceLock::new();
    SOL.get_or_init(|| {
        let (scene, data) = scene_data();
        let opts = BeltOptions { tolerance: ROUND_TRIP_TOLERANCE, ..BeltOptions::from_scene(&scene).expect("options") };
        cosserat_drive::solve(&data, &opts).expect("the scene solves at 1e-10")
    })
}

/// `data` with the driver's stick → slip angle `phi` given and M₂ released.
fn with_transition(data: &CosseratDrive, phi: f64) -> CosseratDrive {
    CosseratDrive { mode: DriveMode::StickSlipAngle { driver: phi }, ..*data }
}

/// Every summary scalar of `b` against `a`, relative to its own size: the worst
/// (name, relative difference).
fn worst_summary_difference(a: &CosseratDriveSolution, b: &CosseratDriveSolution) -> (String, f64) {
    let sb = b.summary();
    let mut worst = (String::new(), 0.0);
    for (name, x) in a.summary().scalars() {
        let y = sb.get(&name).unwrap_or_else(|| panic!("{name} missing"));
        let rel = (x - y).abs() / x.abs();
        if rel > worst.1 {
            worst = (name, rel);
        }
    }
    eprintln!("  worst summary difference: {} {:.1e}", worst.0, worst.1);
    worst
}

/// D-9 round trip (spec §3.4 (i), §3.8: BVP ≤ 1e-9), collocation at 1e-10: φ_B1 read from
/// the standard solution and prescribed with M₂ released returns M₂ = 0.1 N·m, φ_B2 and
/// every summary scalar to 1e-9 relative — from the standard solution itself and, so that
/// Newton has to move, from the solution at φ_B1 + 0.02 rad (M₂ ≈ 0.104 N·m). The summary
/// reports the solved M₂ as the driven torque it balances (M₂ + d₂ω₂, d₂ = 0), and both
/// stick → slip angles through the stick arcs. The released system's AD Jacobians agree
/// with central differences (1e-6, as the standard one's).
#[test]
fn d9_round_trip_returns_the_load_torque() {
    let std = solved_tight();
    let (_, data) = scene_data();
    let opts = std.options.clone();
    let (phi1, phi2) = std.stick_slip_angles();
    eprintln!("standard: φ_B1 = {phi1:.15} rad, φ_B2 = {phi2:.15} rad, {} nodes, {} Newton, {:.3} s", std.stats.mesh_nodes, std.stats.newton_iterations, std.stats.wall_seconds);
    // the summary's angles: first contact (wrapped) − stick arc, clockwise
    for (pulley, phi, ps) in [(Pulley::Driver, phi1, std.summary().driver.unwrap()), (Pulley::Driven, phi2, std.summary().driven.unwrap())] {
        let from_summary = ps.contact_start.unwrap() - ps.stick_arc.unwrap();
        let turns = ((phi - from_summary) / std::f64::consts::TAU).round();
        assert!((from_summary + turns * std::f64::consts::TAU - phi).abs() <= 1e-12, "{}: {phi} vs summary {from_summary}", pulley.name());
    }
    let released = with_transition(&data, phi1);
    let shifted = cosserat_drive::solve_from(&with_transition(&data, phi1 + 0.02), &opts, std).expect("same topology").expect("φ_B1 + 0.02 solves");
    assert!(shifted.load_torque() > 0.1 + 1e-3, "M₂ at φ_B1 + 0.02: {}", shifted.load_torque());
    for (start, from) in [("the standard solution", std), ("the solution at φ_B1 + 0.02", &shifted)] {
        let back = cosserat_drive::solve_from(&released, &opts, from).expect("same topology").unwrap_or_else(|e| panic!("from {start}: {e}"));
        let m2 = back.load_torque();
        let (b1, b2) = back.stick_slip_angles();
        eprintln!("from {start}: M₂ = {m2:.15} N·m ({:.1e}), φ_B1 {:.1e}, φ_B2 {:.1e}, {} nodes, {} Newton, {:.3} s", m2 / 0.1 - 1.0, b1 - phi1, b2 - phi2, back.stats.mesh_nodes, back.stats.newton_iterations, back.stats.wall_seconds);
        assert!((m2 / 0.1 - 1.0).abs() <= 1e-9, "from {start}: M₂ = {m2} N·m");
        assert_eq!(back.data.drive.driven_torque, m2, "the solution's data carries the solved M₂");
        assert!((b1 - phi1).abs() <= 1e-12, "φ_B1 is a condition: {b1} vs {phi1}");
        assert!((b2 / phi2 - 1.0).abs() <= 1e-9, "from {start}: φ_B2 = {b2} vs {phi2}");
        let driven = back.summary().driven.unwrap().torque.unwrap();
        assert!((driven - m2).abs() <= 1e-12 * m2, "summary driven torque {driven} vs M₂ {m2}");
        let (name, worst) = worst_summary_difference(std, &back);
        assert!(worst <= 1e-9, "from {start}: {name} differs by {worst:e}");
        let (input, output, dissipation) = back.power_balance();
        assert!((input - output - dissipation).abs() <= 1e-7 * input, "power: {input} = {output} + {dissipation}");
    }
    let law = bvp::cosserat_drive::ScaledCosseratDrive { mode: DriveMode::StickSlipAngle { driver: phi1 }, ..std.problem.law.clone() };
    let problem = bvp::belt::BeltProblem::new(std.topology().clone(), law);
    let mut p = std.solution.params.clone();
    p.push(0.1 / (std.scales.force * std.scales.length));
    let worst = bvp::jacobian::ad_fd_mismatch_sampled(&problem, &p, 1.0);
    assert!(worst <= 1e-6, "released M₂: AD vs central differences {worst:e}");
}

/// Spec §3.4 (ii): φ_B1 shifted by −0.02 / +0.02 rad gives M₂ = 0.095926 / 0.104032 N·m.
/// The spec prints six decimals: its values are known to ±5e-7 N·m (half a unit of the
/// last digit); both BVPs resolve M₂ far below that (ours at 1e-10: the round trip holds
/// M₂ to 1e-9 relative, 1e-10 N·m), so ours must lie within 6e-7 N·m of the spec's.
/// Independent of the released mode, the standard mode with the solved M₂ given must
/// put the driver's stick → slip point at the prescribed angle (1e-9 rad: two solves of
/// different systems at 1e-10), and the slope dM₂/dφ_B1 is the spec's ≈ 0.20 N·m/rad.
#[test]
fn d9_sensitivity_of_the_load_torque_to_phi_b1() {
    let std = solved_tight();
    let (_, data) = scene_data();
    let opts = std.options.clone();
    let (phi1, _) = std.stick_slip_angles();
    let mut m2 = Vec::new();
    for (delta, spec) in [(-0.02, 0.095926), (0.02, 0.104032)] {
        let sol = cosserat_drive::solve_from(&with_transition(&data, phi1 + delta), &opts, std).expect("same topology").unwrap_or_else(|e| panic!("φ_B1 {delta:+}: {e}"));
        let m = sol.load_torque();
        let (b1, b2) = sol.stick_slip_angles();
        eprintln!("φ_B1 {delta:+}: M₂ = {m:.10} N·m (spec {spec}, {:+.2e}), φ_B2 = {b2:.10} rad, {} Newton, {:.3} s", m - spec, sol.stats.newton_iterations, sol.stats.wall_seconds);
        assert!((b1 - (phi1 + delta)).abs() <= 1e-12);
        assert!((m - spec).abs() <= 6e-7, "φ_B1 {delta:+}: M₂ = {m} N·m, spec {spec} N·m");
        let given = CosseratDrive { drive: bvp::string_drive::StringDrive { driven_torque: m, ..data.drive }, ..data };
        let standard = cosserat_drive::solve_from(&given, &opts, std).expect("same topology").expect("the standard mode at the solved M₂");
        let back = standard.stick_slip_angles().0;
        eprintln!("  standard mode at M₂ = {m:.10}: φ_B1 − prescribed = {:.2e} rad", back - (phi1 + delta));
        assert!((back - (phi1 + delta)).abs() <= 1e-9, "standard mode at M₂ = {m}: φ_B1 = {back}, prescribed {}", phi1 + delta);
        m2.push(m);
    }
    let slope = (m2[1] - m2[0]) / 0.04;
    eprintln!("dM₂/dφ_B1 ≈ {slope:.6} N·m/rad");
    assert!((slope - 0.20).abs() <= 0.005, "dM₂/dφ_B1 = {slope} N·m/rad, spec ≈ 0.20");
}

/// D-9 counter-clockwise (ω₁ = −20 rad/s, M₂ = −0.1 N·m, gravity): the driver's stick →
/// slip point is the same parameter (slip then stick along σ), so the mode applies as
/// is. From the data alone ([`cosserat_drive::solve`] in the released mode, M₂'s start
/// −0.09 N·m): the standard drive at −0.09, then φ_B1 of the −0.1 solution prescribed,
/// returns M₂ = −0.1 N·m, φ_B2 and the summary to 1e-9 relative.
#[test]
fn d9_round_trip_counter_clockwise() {
    let (scene, base) = scene_data();
    let opts = BeltOptions { tolerance: ROUND_TRIP_TOLERANCE, ..BeltOptions::from_scene(&scene).expect("options") };
    let ccw = CosseratDrive { drive: bvp::string_drive::StringDrive { driver_speed: -20.0, driven_torque: -0.1, ..base.drive }, ..base };
    let std = cosserat_drive::solve(&ccw, &opts).expect("counter-clockwise at 1e-10");
    let (phi1, phi2) = std.stick_slip_angles();
    let estimate = CosseratDrive { drive: bvp::string_drive::StringDrive { driven_torque: -0.09, ..ccw.drive }, ..ccw };
    let back = cosserat_drive::solve(&with_transition(&estimate, phi1), &opts).expect("released M₂, counter-clockwise");
    let m2 = back.load_torque();
    let (b1, b2) = back.stick_slip_angles();
    eprintln!("counter-clockwise: φ_B1 = {phi1:.12}, M₂ = {m2:.15} N·m ({:.1e}), φ_B2 {:.1e}, {:.3} s", m2 / -0.1 - 1.0, b2 - phi2, back.stats.wall_seconds);
    assert!((m2 / -0.1 - 1.0).abs() <= 1e-9, "M₂ = {m2} N·m");
    assert!((b1 - phi1).abs() <= 1e-12 && (b2 / phi2 - 1.0).abs() <= 1e-9, "φ_B = ({b1}, {b2}) vs ({phi1}, {phi2})");
    let (name, worst) = worst_summary_difference(&std, &back);
    assert!(worst <= 1e-9, "{name} differs by {worst:e}");
}

/// A prescribed φ_B1 outside the driver's contact arc is refused by name before any
/// iteration: beyond either contact end, on it, the driven pulley's φ_B2 (the wrong
/// pulley) and the driver's angle wrapped to (−π, π] (as the summary's contact angles
/// are); a non-finite one is an invalid input.
#[test]
fn d9_transition_outside_the_driver_contact_is_named() {
    let std = solved();
    let (_, data) = scene_data();
    let angles = std.contact_angles(Pulley::Driver);
    let (first, last) = (angles[0], angles[angles.len() - 1]);
    let (phi1, phi2) = std.stick_slip_angles();
    for phi in [first + 0.05, last - 0.05, first, last, phi2, phi1 + std::f64::consts::TAU] {
        match cosserat_drive::solve_from(&with_transition(&data, phi), &std.options, std) {
            Some(Err(e @ BeltError::TransitionOutsideContact { .. })) => {
                let BeltError::TransitionOutsideContact { pulley, angle, first_contact, last_contact } = e else { unreachable!() };
                assert_eq!((pulley, angle, first_contact, last_contact), ("driver", phi, first, last));
            }
            other => panic!("φ_B1 = {phi} (driver contact {first} … {last}): expected TransitionOutsideContact, got {other:?}"),
        }
    }
    match cosserat_drive::solve_from(&with_transition(&data, f64::NAN), &std.options, std) {
        Some(Err(BeltError::InvalidInput { name: "stick_slip_angle", .. })) => {}
        other => panic!("NaN: expected InvalidInput, got {other:?}"),
    }
}

/// D-9 by shooting: the same round trip at 1e-9, the tightest tolerance shooting reaches
/// on this scene (at 1e-10 its final Newton stalls at residual 2.2e-10). From the
/// standard shooting solution the released system is already solved (0 Newton
/// iterations), so the round trip starts from the shooting solution at φ_B1 + 0.02 rad:
/// M₂ = 0.1 N·m, φ_B2 and the summary to 1e-9 relative. (At 1e-8 the Newton stops
/// earlier and the driven slip arc differs by 7e-9: the round trip is as exact as the
/// solves' tolerance.)
#[test]
fn d9_round_trip_by_shooting() {
    let (_, data) = scene_data();
    let opts = BeltOptions::shooting(1e-9);
    let std = cosserat_drive::solve(&data, &opts).expect("shooting at 1e-9");
    let (phi1, phi2) = std.stick_slip_angles();
    let shifted = cosserat_drive::solve_from(&with_transition(&data, phi1 + 0.02), &opts, &std).expect("same topology").expect("φ_B1 + 0.02 by shooting");
    assert!((shifted.load_torque() - 0.104032).abs() <= 6e-7, "M₂ at φ_B1 + 0.02: {}", shifted.load_torque());
    let back = cosserat_drive::solve_from(&with_transition(&data, phi1), &opts, &shifted).expect("same topology").expect("back to φ_B1 by shooting");
    let m2 = back.load_torque();
    let (_, b2) = back.stick_slip_angles();
    eprintln!("shooting: M₂ = {m2:.15} N·m ({:.1e}), φ_B2 {:.1e}, {} Newton", m2 / 0.1 - 1.0, b2 / phi2 - 1.0, back.stats.newton_iterations);
    assert!(back.stats.newton_iterations > 0);
    assert!((m2 / 0.1 - 1.0).abs() <= 1e-9 && (b2 / phi2 - 1.0).abs() <= 1e-9, "M₂ = {m2} N·m, φ_B2 = {b2} vs {phi2}");
    let (name, worst) = worst_summary_difference(&std, &back);
    assert!(worst <= 1e-9, "{name} differs by {worst:e}");
}

/// Spec §3.7's per-pulley outputs, each against what it must equal: the stick zone's
/// stretch gives the pulley's surface speed (cλ_B = ωR, D-4, a BVP condition: round-off);
/// the two dissipations add up to the power balance's D (the same quadrature:
/// round-off) and are positive; the stick → slip angle lies inside the contact arc and
/// splits it into the stick and slip arcs (round-off); the moments at the edges are the
/// points' M; the smallest pressure and the largest |Γ₂| are no worse than a dense
/// sampling of the contact zone (64 points per mesh interval: they must be at least as
/// extreme, and within 1e-6 relative of it: the sampled extremum is O(h²/64²) off).
#[test]
fn spec_3_7_outputs_match_their_definitions() {
    let sol = solved();
    let d = &sol.data.drive;
    let summary = sol.summary();
    let c = sol.transport_rate().unwrap();
    let speeds = [(Pulley::Driver, d.driver_speed), (Pulley::Driven, sol.driven_speed().unwrap())];
    let (_, _, dissipation) = sol.power_balance();
    let mut total = 0.0;
    for ((pulley, omega), ps) in speeds.into_iter().zip([summary.driver.unwrap(), summary.driven.unwrap()]) {
        let name = pulley.name();
        let lambda = ps.stretch_stick.unwrap();
        assert!((c * lambda - omega * d.radius).abs() <= 1e-12 * omega.abs() * d.radius, "{name}: cλ_B = {} vs ωR = {}", c * lambda, omega * d.radius);
        let dp = ps.dissipation.unwrap();
        assert!(dp > 0.0, "{name}: D = {dp}");
        total += dp;
        // the angles, unwrapped from the contact start clockwise
        let (start, phi_b) = (ps.contact_start.unwrap(), ps.stick_slip_angle.unwrap());
        let stick = (start - phi_b).rem_euclid(std::f64::consts::TAU);
        assert!((stick - ps.stick_arc.unwrap()).abs() <= 1e-10, "{name}: φ_A − φ_B = {stick} vs stick arc {}", ps.stick_arc.unwrap());
        let topo = sol.topology();
        let (first, last) = (topo.first_arc(pulley), topo.last_arc(pulley));
        assert_eq!(ps.moment_start, sol.point(first, 0.0).moment);
        assert_eq!(ps.moment_end, sol.point(last, 1.0).moment);
        let dense: Vec<BeltPoint> = sol.samples(64).into_iter().filter(|(k, _, _)| topo.arcs_on(pulley).contains(k)).map(|(_, _, p)| p).collect();
        let p_min = dense.iter().map(|p| p.pressure.unwrap()).fold(f64::INFINITY, f64::min);
        let g_max = dense.iter().map(|p| p.shear_strain.unwrap().abs()).fold(0.0, f64::max);
        let (pm, gm) = (ps.pressure_min.unwrap(), ps.shear_strain_max.unwrap());
        assert!(pm <= p_min * (1.0 + 1e-12) && pm >= p_min * (1.0 - 1e-6) && pm > 0.0, "{name}: p_min {pm} vs dense {p_min}");
        assert!(gm >= g_max * (1.0 - 1e-12) && gm <= g_max * (1.0 + 1e-6), "{name}: max|Γ₂| {gm} vs dense {g_max}");
        assert!(pm < ps.edge_pressure_start.unwrap().min(ps.edge_pressure_end.unwrap()), "{name}: the pressure peaks at the edges");
    }
    assert!((total - dissipation).abs() <= 1e-12 * dissipation.max(1e-300) + 1e-15, "D₁ + D₂ = {total} vs D = {dissipation}");
}
