//! The two-pulley Cosserat drive in steady motion by the FE's direct steady solve
//! (docs/fem-cosserat.md §10, §11), through `solve_scene` with the Cosserat element: the
//! issue's scene against the BVP at 128, 256 and 512 elements, and the `string-drive`
//! geometry with `"theory": "cosserat"` — the power balance P_in = P_out + D and the
//! driven pulley's torque balance to round-off, creep (ω₂ < ω₁), stick and slip on both
//! pulleys.

use drive::Scene;
use fem::{FemOptions, FemRun, SolverSettings};
use serde_json::{json, Value};

/// The catalogue's `string-drive` scene as a Cosserat belt with bending stiffness `a`
/// (N·m²) and shear stiffness `b2` (N); gravity as the scene's if `gravity`.
fn scene(a: f64, b2: f64, gravity: bool) -> Scene {
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/string-drive.json")).unwrap();
    v["name"] = json!("cosserat-drive-string-geometry");
    v["belt"]["theory"] = json!("cosserat");
    v["belt"]["bending_stiffness"] = json!(a);
    v["belt"]["shear_stiffness"] = json!(b2);
    if !gravity {
        v["effects"]["gravity"] = Value::Null;
    }
    v["fem"]["formulations"] = json!(["cosserat-gauss"]);
    v.as_object_mut().unwrap().remove("gate");
    Scene::from_json_str(&v.to_string()).unwrap()
}

fn solve(scene: &Scene, elements: usize, settings: &SolverSettings) -> FemRun {
    let opts = FemOptions { elements, formulation: "cosserat-gauss".into(), penalty: None };
    fem::solve_scene_with(scene, &opts, settings).unwrap_or_else(|e| panic!("{}: {e}", scene.name))
}

fn drive_option(run: &FemRun, key: &str) -> f64 {
    run.options["drive"][key].as_f64().unwrap_or_else(|| panic!("options.drive.{key}"))
}

/// Power P_in − P_out − D to 1e-9 of P_in (it follows from the c-row (DS2), as for the
/// string), the driven torque M₂ + d₂ω₂ to 1e-9 relative (the ω₂-row (DS3)), creep
/// 0 < ω₂ < ω₁ and both pulleys with stick and slip arcs.
fn check_balances(scene: &Scene, r: &FemRun) {
    let s = &r.summary;
    let (m2, d2) = (scene.drive.driven_torque, scene.drive.driven_damping);
    let w2 = s.driven_speed.unwrap();
    let load = m2 + d2 * w2;
    let (pin, pout, d) = (drive_option(r, "power_in"), drive_option(r, "power_out"), drive_option(r, "dissipation"));
    eprintln!("{}: P_in {pin} P_out {pout} D {d}, ω₂ {w2}, M₁ {:?}, M₂ {:?}", scene.name, s.driver.as_ref().unwrap().torque, s.driven.as_ref().unwrap().torque);
    assert!((pin - pout - d).abs() < 1e-9 * pin, "P_in {pin} − P_out {pout} − D {d} = {:e}", pin - pout - d);
    assert!(d > 0.0, "slip dissipates");
    let t2 = s.driven.as_ref().unwrap().torque.unwrap();
    assert!((t2 - load).abs() < 1e-9 * load, "driven torque {t2} vs M₂ + d₂ω₂ = {load}");
    assert!(w2 > 0.0 && w2 < scene.drive.driver_speed, "creep: ω₂ = {w2}");
    for p in [&s.driver, &s.driven] {
        let p = p.as_ref().unwrap();
        assert!(p.stick_arc.unwrap() > 0.1 && p.slip_arc.unwrap() > 0.1, "stick {:?} and slip {:?} arcs", p.stick_arc, p.slip_arc);
    }
}

#[test]
fn cosserat_drive_balances_power_and_torque() {
    let sc = scene(1e-3, 1e4, true);
    // 128 elements: at 64 the graded refits end in "no Coulomb state" (docs/fem-cosserat.md §11)
    let r = solve(&sc, 128, &SolverSettings::default());
    check_balances(&sc, &r);
    assert!(r.summary.moment_upper_mid.is_some(), "the rod's bending moment is in the view");
}

/// The issue's scene (issue 14; scenes/cosserat-drive.json: R = 0.08 m,
/// H = 0.45 m, L = 1.4028 m, b₁ = 2e4 N, b₂ = 1e3 N, a = 0.005 N·m², ρ = 0.12 kg/m,
/// g = 9.81, μ = 0.3, ω₁ = 20 rad/s, M₂ = 0.1 N·m).
fn issue_scene() -> Scene {
    Scene::from_json_str(include_str!("../../scenes/cosserat-drive.json")).unwrap()
}

/// Relative error of the FE's summary quantity `q` against the BVP's.
fn relative_error(fe: &drive::Summary, reference: &drive::Summary, q: &str) -> f64 {
    let (f, b) = (fe.get(q).unwrap_or_else(|| panic!("FE {q}")), reference.get(q).unwrap_or_else(|| panic!("BVP {q}")));
    (f - b).abs() / b.abs()
}

/// The BVP's summary of `sc` (`bvp::cosserat_drive`, collocation gauss6) at tolerance
/// 1e-10: the reference of the FE errors below (≥ 100 times below the smallest FE
/// error bound but ω₂'s, which sits within 10 of it).
fn bvp_reference(sc: &Scene) -> drive::Summary {
    let data = bvp::cosserat_drive::CosseratDrive::from_scene(sc).unwrap();
    let bvp_opts = bvp::belt::BeltOptions { tolerance: 1e-10, ..bvp::belt::BeltOptions::from_scene(sc).unwrap() };
    drive::view::SolutionView::summary(&bvp::cosserat_drive::solve(&data, &bvp_opts).unwrap())
}

/// A bound table: (summary quantity, bound on its relative error per mesh, least error
/// ratio per doubling or 0 for bounds only).
type Bounds<'a, const M: usize> = [(&'a str, [f64; M], f64)];

/// Solve `sc` at each of `meshes` and hold the FE against `reference`: power
/// P_in − P_out − D to 1e-9 P_in with D > 0, creep (|ω₂| < |ω₁|, the driver's sense),
/// no fitting at its pass limit and no refit rejected, the BVP's tight span, the slip zones warned as unresolved exactly on the
/// pulleys of `warned` per mesh (and every slip arc more than 10 % off warned), each
/// quantity of `table` within its bound and falling by its ratio per doubling. Returns
/// the errors per quantity and mesh.
fn check_meshes<const M: usize>(sc: &Scene, reference: &drive::Summary, meshes: [usize; M], warned: [&[&str]; M], table: &Bounds<M>) -> Vec<[f64; M]> {
    let w1 = sc.drive.driver_speed;
    let mut errors = vec![[0.0; M]; table.len()];
    for (m, n) in meshes.into_iter().enumerate() {
        let clock = std::time::Instant::now();
        let r = solve(sc, n, &SolverSettings::default());
        let (pin, pout, d) = (drive_option(&r, "power_in"), drive_option(&r, "power_out"), drive_option(&r, "dissipation"));
        println!("{} {n}: {:.1} s, {} Newton iterations, {} fits", sc.name, clock.elapsed().as_secs_f64(), r.options["drive"]["report"]["newton_iterations"], r.options["drive"]["report"]["fits"]);
        assert!((pin - pout - d).abs() < 1e-9 * pin.abs() && d > 0.0, "{n}: P_in {pin} − P_out {pout} − D {d}");
        // the pulleys' dissipations (spec §3.7) are the parts of D
        let parts: f64 = [&r.summary.driver, &r.summary.driven].iter().map(|p| p.as_ref().unwrap().dissipation.unwrap()).sum();
        assert!((parts - d).abs() <= 1e-12 * d, "{n}: D₁ + D₂ = {parts} vs D = {d}");
        let w2 = r.summary.driven_speed.unwrap();
        assert!(w2 * w1 > 0.0 && w2.abs() < w1.abs(), "{n}: creep, ω₂ = {w2}");
        assert!(!r.notes.iter().any(|w| w.contains("pass limit")), "{n}: {:?}", r.notes);
        assert_eq!(r.options["drive"]["report"]["rejected_fits"], 0, "{n}: refits rejected");
        let tight = |s: &drive::Summary| s.tension_upper_mid.unwrap() > s.tension_lower_mid.unwrap();
        assert_eq!(tight(&r.summary), tight(reference), "{n}: the tight span is the BVP's");
        for pulley in ["driver", "driven"] {
            let error = relative_error(&r.summary, reference, &format!("{pulley}.slip_arc"));
            let is_warned = r.notes.iter().any(|w| w.starts_with(&format!("unresolved slip zone on the {pulley} pulley")));
            assert_eq!(is_warned, warned[m].contains(&pulley), "{n} elements, {pulley}: slip arc {error:.3} off, notes {:?}", r.notes);
            assert!(is_warned || error <= 0.1, "{n} elements, {pulley}: slip arc {error:.2} off and no warning in {:?}", r.notes);
        }
        for (k, (q, bounds, _)) in table.iter().enumerate() {
            errors[k][m] = relative_error(&r.summary, reference, q);
            println!("{} {n} {q}: FE {:?} BVP {:?} relative error {:.2e}", sc.name, r.summary.get(q), reference.get(q), errors[k][m]);
            assert!(errors[k][m] <= bounds[m], "{n} elements, {q}: relative error {:e} above {:e}", errors[k][m], bounds[m]);
        }
    }
    for (k, (q, _, ratio)) in table.iter().enumerate() {
        for m in 0..M - 1 {
            assert!(errors[k][m] >= ratio * errors[k][m + 1], "{q}: errors {:?} do not fall by {ratio} per doubling", errors[k]);
        }
    }
    errors
}

/// Index of quantity `q` in `table`.
fn row<const M: usize>(table: &Bounds<M>, q: &str) -> usize {
    table.iter().position(|(name, _, _)| *name == q).unwrap()
}

/// The issue's scene by the direct steady solve at 128, 256 and 512 elements (the
/// drive's meshes: twice the arcs' share of the elements, graded 65:1 over one shear
/// layer √(a/b₂) = 2.2 mm towards the contact edges and the transitions; friction points
/// with the tributary penalty pressure of the Cosserat element,
/// `LayoutElement::friction_normal`, and contact-side halves at the fitted contact
/// boundaries) against the BVP at 1e-10, docs/fem-cosserat.md §11.1. Measured relative
/// errors 128 / 256 / 512 (against the BVP at 1e-10): c 2.7e-7 / 1.7e-7 / 1.1e-7, ω₂
/// 7.6e-9 / 5.1e-9 / 2.8e-9, mid-span tensions ≤ 6.2e-4 / 9.8e-5 / 1.7e-5, T_tight,
/// T_slack ≤ 6.5e-4 / 3.9e-4 / 2.5e-4, heights ≤ 2.8e-5 / 3.5e-6 / 1.5e-6, moments ≤
/// 6.4e-4 / 9.6e-5 / 1.7e-5, contact arcs ≤ 6.4e-5 / 8.0e-6 / 1.1e-5 (at their floor
/// from 256 on), stick arcs (driver, driven) 1.2e-4, 3.3e-4 / 3.4e-4, 3.2e-4 / 3.1e-4,
/// 2.9e-4, slip arcs 0.0025, 0.0066 / 0.0043, 0.0081 / 0.0039, 0.0073 (without the
/// contact-side halves: 0.023, 0.031 / 0.011, 0.022 / 0.0066, 0.014 — the run-on node's
/// stick row pinned the free span element's stretch, a concentrated traction that put
/// the stick zones 1.2e-2 N above the spans at 128), driver torque 3.7e-8 / 3.4e-8 /
/// 2.4e-8. Bounds 2× the measured per mesh (rounded up; the heights and contact arcs 2×
/// the larger of 256 and 512 there), the slip arcs ≤ 1 % at 256 and 512 (the issue's
/// target); the smooth quantities must fall by ≥ 1.4 per doubling (measured 1.5–6.4);
/// the stick and slip arcs and the driver torque sit at a floor from 256 on (bounds
/// only); the contact arcs at 512 below 0.35 of 128 (0.17). Spec §3.7's additions
/// (driver, driven): p_min 3.1e-3, 3.4e-3 / 9.6e-4, 1.3e-3 / 4.2e-4, 4.7e-4 (falling
/// at order ≈ 1.5, the element-mean pressure's O(h²) with the penalty's floor);
/// max|Γ₂| 7.5e-3, 5.7e-3 / 4.5e-4, 5.3e-5 / 1.7e-3, 1.7e-3 (the sampled peak of a kink
/// rounded off over the penalty layer: bounds only); edge moments ≤ 1.2e-4 / 1.1e-4 /
/// 3.6e-5; φ_B and the dissipations at the slip arcs' floor (≤ 6.9e-4; ≤ 5.2e-3);
/// λ_B 2.8e-7 / 1.7e-7 / 1.1e-7. Slip zones warned
/// (`SLIP_ELEMENTS` = 2.5 mean arc elements): both at 128 (2.0, 1.1 elements), the driven
/// one at 256 (2.2), none at 512. Power P_in − P_out − D to 1e-9 P_in and the driven
/// torque M₂ at every mesh, and no refit rejected.
#[test]
fn issue_scene_converges_to_the_bvp() {
    let sc = issue_scene();
    let reference = bvp_reference(&sc);
    let table: &Bounds<3> = &[
        ("transport_rate", [5.5e-7, 3.4e-7, 2.2e-7], 1.4),
        ("driven_speed", [1.6e-8, 1.1e-8, 5.6e-9], 0.0),
        ("tension_upper_mid", [1.3e-3, 2e-4, 3.5e-5], 1.4),
        ("tension_lower_mid", [1.1e-3, 1.8e-4, 3.1e-5], 1.4),
        ("tension_tight", [1.2e-3, 7.1e-4, 4.7e-4], 1.4),
        ("tension_slack", [1.3e-3, 7.8e-4, 5.1e-4], 1.4),
        ("y_upper_mid", [1.5e-5, 3.7e-6, 5.7e-7], 0.0),
        ("y_lower_mid", [5.6e-5, 7e-6, 3e-6], 0.0),
        ("moment_upper_mid", [1.1e-3, 1.8e-4, 3.5e-5], 1.4),
        ("moment_lower_mid", [1.3e-3, 2e-4, 3.3e-5], 1.4),
        ("driver.contact_arc", [1.3e-4, 2.3e-5, 2.3e-5], 0.0),
        ("driven.contact_arc", [1.3e-4, 2.3e-5, 2.3e-5], 0.0),
        ("driver.stick_arc", [2.5e-4, 6.7e-4, 6.3e-4], 0.0),
        ("driven.stick_arc", [6.6e-4, 6.4e-4, 5.7e-4], 0.0),
        ("driver.slip_arc", [5e-3, 8.5e-3, 7.9e-3], 0.0),
        ("driven.slip_arc", [1.4e-2, 1e-2, 1e-2], 0.0),
        ("driver.torque", [7.5e-8, 6.7e-8, 4.9e-8], 0.0),
        ("driven.torque", [1e-9, 1e-9, 1e-9], 0.0),
        // spec §3.7's additions (docs/fem-cosserat.md §12.10)
        ("driver.pressure_min", [6.3e-3, 2e-3, 8.4e-4], 1.4),
        ("driven.pressure_min", [6.8e-3, 2.6e-3, 9.3e-4], 1.4),
        ("driver.shear_strain_max", [1.5e-2, 3.4e-3, 3.4e-3], 0.0),
        ("driven.shear_strain_max", [1.2e-2, 3.5e-3, 3.5e-3], 0.0),
        ("driver.moment_start", [2.5e-4, 2.5e-4, 7.5e-5], 0.0),
        ("driver.moment_end", [2.5e-4, 2.5e-4, 7.5e-5], 0.0),
        ("driven.moment_start", [2.5e-4, 2.5e-4, 7.5e-5], 0.0),
        ("driven.moment_end", [2.5e-4, 2.5e-4, 7.5e-5], 0.0),
        ("driver.stick_slip_angle", [1.4e-3, 1.4e-3, 1.4e-3], 0.0),
        ("driven.stick_slip_angle", [1.4e-3, 1.4e-3, 1.4e-3], 0.0),
        ("driver.stretch_stick", [5.7e-7, 3.4e-7, 2.2e-7], 1.4),
        ("driven.stretch_stick", [5.5e-7, 3.3e-7, 2.2e-7], 1.4),
        ("driver.dissipation", [1.1e-2, 1.1e-2, 1.1e-2], 0.0),
        ("driven.dissipation", [1.1e-2, 1.1e-2, 1.1e-2], 0.0),
    ];
    let errors = check_meshes(&sc, &reference, [128, 256, 512], [&["driver", "driven"], &["driven"], &[]], table);
    for (q, factor) in [("driver.contact_arc", 0.35), ("driven.contact_arc", 0.35)] {
        let e = errors[row(table, q)];
        assert!(e[2] < factor * e[0], "{q}: errors {e:?}, at 512 not below {factor} of 128");
    }
}

/// The issue's scene counter-clockwise (ω₁ = −20 rad/s, M₂ = −0.1 N·m: with gravity the
/// upper span is the tight one, a different problem from the mirror image) at 128, 256
/// and 512 elements against the BVP's counter-clockwise solution (collocation at 1e-10),
/// docs/fem-cosserat.md §11.1. Measured relative errors 128 / 256 / 512: c 2.7e-7 /
/// 1.7e-7 / 1.2e-7, ω₂ 3.3e-9 / 1.7e-8 / 1.5e-8, mid-span tensions ≤ 5.8e-4 / 8.2e-5 /
/// 1.6e-5, heights ≤ 3.2e-5 / 3.4e-6 / 1.6e-6, moments ≤ 6.9e-4 / 9.2e-5 / 1.7e-5,
/// contact arcs ≤ 6.2e-5 / 1.0e-5 / 1.1e-5, T_tight / T_slack ≤ 6.3e-4 / 3.6e-4 /
/// 2.4e-4, driver torque 2.1e-8 / 1.9e-8 / 2.4e-8, stick arcs ≤ 2.4e-4 / 5.4e-4 /
/// 4.2e-4, slip arcs (driver, driven) 0.0023, 0.0018 / 0.0027, 0.0064 / 0.0025, 0.0051
/// (without the contact-side halves: 0.015, 0.023 / 0.0075, 0.012 / 0.0034, 0.0066).
/// Bounds 2× the measured (the heights and contact arcs 2× the larger of 256 and 512),
/// the slip arcs ≤ 1 % at 256 and 512; the smooth quantities must fall by ≥ 1.4 per
/// doubling (measured 5.3–8.3), c and T_tight, T_slack by ≥ 1.3 (1.43–1.78); the arcs,
/// ω₂ and the driver torque bounds only (at their floor from 256 on). The driven slip
/// zone is warned at 128 (2.2 arc elements), none at 256 and 512.
#[test]
fn issue_scene_counter_clockwise_against_the_bvp() {
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/cosserat-drive.json")).unwrap();
    v["name"] = json!("cosserat-drive-ccw");
    v["drive"]["driver_speed"] = json!(-20.0);
    v["drive"]["driven_torque"] = json!(-0.1);
    let sc = Scene::from_json_str(&v.to_string()).unwrap();
    let reference = bvp_reference(&sc);
    let table: &Bounds<3> = &[
        ("transport_rate", [5.4e-7, 3.5e-7, 2.4e-7], 1.3),
        ("driven_speed", [6.6e-9, 3.4e-8, 3.1e-8], 0.0),
        ("tension_upper_mid", [1e-3, 1.4e-4, 2.7e-5], 1.4),
        ("tension_lower_mid", [1.2e-3, 1.7e-4, 3.1e-5], 1.4),
        ("tension_tight", [1.1e-3, 6.8e-4, 4.8e-4], 1.3),
        ("tension_slack", [1.3e-3, 7.2e-4, 4.9e-4], 1.3),
        ("y_upper_mid", [1.3e-5, 2.9e-6, 4.4e-7], 0.0),
        ("y_lower_mid", [6.3e-5, 6.8e-6, 3.2e-6], 0.0),
        ("moment_upper_mid", [8.9e-4, 1.4e-4, 2.7e-5], 1.4),
        ("moment_lower_mid", [1.4e-3, 1.9e-4, 3.3e-5], 1.4),
        ("driver.contact_arc", [1.3e-4, 2.2e-5, 2.2e-5], 0.0),
        ("driven.contact_arc", [1.3e-4, 2.2e-5, 2.2e-5], 0.0),
        ("driver.stick_arc", [4.9e-4, 7.5e-4, 6.9e-4], 0.0),
        ("driven.stick_arc", [4.5e-4, 1.1e-3, 8.5e-4], 0.0),
        ("driver.slip_arc", [4.7e-3, 5.5e-3, 5e-3], 0.0),
        ("driven.slip_arc", [3.7e-3, 1e-2, 1e-2], 0.0),
        ("driver.torque", [4.3e-8, 3.8e-8, 4.7e-8], 0.0),
    ];
    assert!(reference.tension_upper_mid.unwrap() > reference.tension_lower_mid.unwrap(), "counter-clockwise the upper span is the tight one");
    check_meshes(&sc, &reference, [128, 256, 512], [&["driven"], &[], &[]], table);
}

/// Paper D's own scheme (spec §3.4–§3.5, `fem.steady_scheme` = `paper-d`;
/// docs/cosserat-drive.md, "FE, second way") on the issue's scene at 256 elements:
/// against the semismooth solve of the same scene and mesh size, and both against the BVP.
///
/// Tolerances: the two schemes solve the same discrete equations (z-rows, c-row, the
/// driven torque row) and differ only in where the stick→slip node sits — the semismooth
/// fit's located zero of v, Paper D's centre of the band of Coulomb-admissible points —
/// so the global quantities agree to the Newton tolerance times that offset (measured on
/// the drive's graded meshes: ω₂ 3.6e-13, c 2.0e-11, torques ≤ 3.1e-11, tensions ≤ 4.7e-8
/// relative; before, on the uniformly weighted 9:1 meshes: ω₂ 1.7e-9, c 1.1e-8, torques
/// ≤ 1.1e-9, tensions ≤ 2.3e-5 — the bounds, 10× those, tensions 4×, kept), and the
/// transitions to the band: both are Coulomb-admissible states, so their stick→slip
/// points lie at most one band width apart (measured: 6 µm driver, 24 µm driven against
/// bands of 0.15 / 0.14 mm; before 0.15 / 0.25 mm against 0.75 / 0.63 mm). Against the
/// BVP: 2× the measured errors (docs/fem-cosserat.md §11.1: ω₂ 2.2e-8, c 3.1e-7, driver
/// torque 7.1e-8, T_tight / T_slack 6.6e-4 / 7.9e-4, mid-span tensions ≤ 5.9e-5, contact
/// arcs 1.2e-5, slip arcs 0.012 / 0.019).
#[test]
fn paper_d_scheme_agrees_with_semismooth_and_the_bvp() {
    let sc = issue_scene();
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/cosserat-drive.json")).unwrap();
    v["fem"] = json!({"steady_scheme": "paper-d"});
    let paper = Scene::from_json_str(&v.to_string()).unwrap();
    let settings = SolverSettings::default();
    let clock = std::time::Instant::now();
    let semismooth = solve(&sc, 256, &settings);
    let t_semismooth = clock.elapsed().as_secs_f64();
    let pd = solve(&paper, 256, &settings);
    let t_paper = clock.elapsed().as_secs_f64() - t_semismooth;
    let report = &pd.options["drive"]["report"]["paper_d"];
    let outer = report["outer_iterations"].as_u64().unwrap();
    let residual: Vec<f64> = report["matching_residual"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    let band: Vec<f64> = report["band_width"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    eprintln!("paper-d: {outer} outer iterations, residual {residual:?}, bands {band:?} m; {t_paper:.2} s against {t_semismooth:.2} s semismooth");
    // the matching condition holds exactly (no stick point beyond its bound) and the
    // iteration is a work counter: 18 measured
    assert_eq!(residual, vec![0.0, 0.0]);
    assert!((8..=24).contains(&outer), "outer iterations {outer}");
    assert!(band.iter().all(|&w| w > 0.0 && w < 2e-3), "bands {band:?} m");
    assert!(semismooth.options["drive"]["report"].get("paper_d").is_none());
    // the power balance and the driven torque row hold as for the semismooth solve
    // (the fixed topology keeps (DS2) and (DS3); 1e-9 as `check_balances`)
    let (pin, pout, d) = (drive_option(&pd, "power_in"), drive_option(&pd, "power_out"), drive_option(&pd, "dissipation"));
    assert!((pin - pout - d).abs() < 1e-9 * pin && d > 0.0, "P_in {pin} − P_out {pout} − D {d}");
    let t2 = pd.summary.driven.as_ref().unwrap().torque.unwrap();
    assert!((t2 - paper.drive.driven_torque).abs() < 1e-9 * paper.drive.driven_torque, "driven torque {t2}");
    let (s, p) = (&semismooth.summary, &pd.summary);
    for (q, bound) in [("driven_speed", 2e-8), ("transport_rate", 1e-7), ("driver.torque", 1e-8), ("driven.torque", 1e-8), ("tension_tight", 1e-4), ("tension_slack", 1e-4), ("tension_upper_mid", 1e-4), ("tension_lower_mid", 1e-4)] {
        let e = relative_error(p, s, q);
        assert!(e <= bound, "paper-d vs semismooth {q}: {e:.3e} > {bound:e}");
    }
    let r = sc.drive.pulley_radius;
    for (k, q) in ["driver.slip_arc", "driven.slip_arc"].into_iter().enumerate() {
        let d = (p.get(q).unwrap() - s.get(q).unwrap()).abs() * r;
        assert!(d <= band[k], "paper-d vs semismooth {q}: transitions {d:.3e} m apart, band {:.3e} m", band[k]);
    }
    let reference = bvp_reference(&sc);
    for (q, bound) in [
        ("driven_speed", 5e-8),
        ("transport_rate", 6.3e-7),
        ("driver.torque", 1.5e-7),
        ("tension_tight", 1.4e-3),
        ("tension_slack", 1.6e-3),
        ("tension_upper_mid", 1.2e-4),
        ("tension_lower_mid", 1.1e-4),
        ("driver.contact_arc", 2.5e-5),
        ("driven.contact_arc", 2.5e-5),
        ("driver.slip_arc", 0.024),
        ("driven.slip_arc", 0.038),
    ] {
        let (ep, es) = (relative_error(p, &reference, q), relative_error(s, &reference, q));
        eprintln!("{q}: paper-d {ep:.2e}, semismooth {es:.2e}");
        assert!(ep <= bound, "paper-d vs BVP {q}: {ep:.3e} > {bound:e}");
    }
}

/// The counter-clockwise issue scene (ω₁ = −20 rad/s, M₂ = −0.1 N·m) at 128 elements,
/// where the semismooth fit failed on the meshes before (`SteadyFitFailed`: a transition
/// 8 % of an arc element off its node) and Paper D's scheme, prescribing the transitions,
/// solved it: on the drive's graded meshes both solve (docs/fem-cosserat.md §11.1) and
/// agree — the global quantities to the Newton tolerance times the transitions' offset
/// (measured before the contact-side halves: ω₂ 4.9e-10, c 6.0e-10, T_tight / T_slack
/// 5.3e-7 / 9.6e-7, bounds 10× those as at 256 clockwise; with the halves in both schemes
/// T_tight 8.4e-6, its bound and T_slack's 10× that), the transitions within one band width (measured 34 µm
/// / 13 µm against bands of 0.30 / 0.32 mm). Against the BVP 2× the measured errors
/// (Paper D: ω₂ 1.3e-7, c 8.6e-7, T_tight / T_slack 1.7e-3, slip arcs 1.6 % / 2.2 %;
/// before: ω₂ 6.4e-7, c 2.5e-6, T_tight 5.0e-3, slip arcs 6.8 % / 8.9 %).
#[test]
fn paper_d_and_semismooth_solve_the_counter_clockwise_drive_at_128() {
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/cosserat-drive.json")).unwrap();
    v["drive"]["driver_speed"] = json!(-20.0);
    v["drive"]["driven_torque"] = json!(-0.1);
    let semismooth = Scene::from_json_str(&v.to_string()).unwrap();
    v["fem"] = json!({"steady_scheme": "paper-d"});
    let paper = Scene::from_json_str(&v.to_string()).unwrap();
    let s = solve(&semismooth, 128, &SolverSettings::default());
    let pd = solve(&paper, 128, &SolverSettings::default());
    let report = &pd.options["drive"]["report"]["paper_d"];
    assert_eq!(report["matching_residual"], json!([0.0, 0.0]));
    let reference = bvp_reference(&semismooth);
    for (q, bound) in [("driven_speed", 5e-9), ("transport_rate", 6e-9), ("tension_tight", 8.4e-5), ("tension_slack", 9.6e-5)] {
        let e = relative_error(&pd.summary, &s.summary, q);
        eprintln!("paper-d vs semismooth {q}: {e:.2e}");
        assert!(e <= bound, "paper-d vs semismooth {q}: {e:.3e} > {bound:e}");
    }
    let band: Vec<f64> = report["band_width"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    for (k, q) in ["driver.slip_arc", "driven.slip_arc"].into_iter().enumerate() {
        let d = (pd.summary.get(q).unwrap() - s.summary.get(q).unwrap()).abs() * semismooth.drive.pulley_radius;
        assert!(d <= band[k], "paper-d vs semismooth {q}: transitions {d:.3e} m apart, band {:.3e} m", band[k]);
    }
    for (q, bound) in [("driven_speed", 2.6e-7), ("transport_rate", 1.8e-6), ("tension_tight", 3.5e-3), ("tension_slack", 3.5e-3), ("driver.slip_arc", 0.033), ("driven.slip_arc", 0.045)] {
        let e = relative_error(&pd.summary, &reference, q);
        eprintln!("{q}: {e:.2e}");
        assert!(e <= bound, "paper-d vs BVP {q}: {e:.3e} > {bound:e}");
    }
    assert!(pd.summary.driven_speed.unwrap() < 0.0 && pd.summary.tension_upper_mid > pd.summary.tension_lower_mid, "counter-clockwise: ω₂ < 0, the upper span tight");
}
