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

/// The issue's scene by the direct steady solve at 128, 256 and 512 elements (meshes
/// graded over the shear layer √(a/b₂) = 2.2 mm towards the contact edges and the
/// transitions) against the BVP (`bvp::cosserat_drive`, collocation at the scene's
/// tolerance 1e-8), docs/fem-cosserat.md §11. Measured relative errors (128 / 256 / 512):
/// c 2.5e-6 / 1.1e-6 / 4.2e-7, ω₂ 8.9e-8 / 8.3e-8 / 1.3e-8, mid-span tensions ≤ 4.8e-4 /
/// 2.8e-4 / 1.2e-4, heights ≤ 3.8e-5 / 2.0e-5 / 8.5e-6, mid-span moments ≤ 5.0e-4 /
/// 2.8e-4 / 1.2e-4, contact arcs 1.1e-3 / 9.7e-5 / 4.3e-5, slip arcs (driver, driven)
/// 1.16, 3.0 / 0.49, 1.08 / 0.19, 0.35 (the slip zones, 15 and 8 mm, lie inside the exit
/// bending layer √(a/T̃) ≈ 24 mm), the driver torque 4.3e-7 / 1.5e-7 / 2.9e-8. Bounds
/// 2× the measured per mesh; the slip arcs must fall by ≥ 2 per doubling (measured
/// 2.4–3.1), tensions, moments, heights, contact arcs and c by ≥ 1.4 (measured 1.7–12;
/// ω₂ and the torques sit near the BVP's tolerance: bounds only).
/// T_tight/T_slack are not compared: the BVP writes the axial force at the stick arc's
/// entry, inside the entry layer, the FE midway along the stick zone (fem-drive.md §12).
/// Power P_in − P_out − D to 1e-9 P_in and the driven torque M₂ at every mesh.
#[test]
fn issue_scene_converges_to_the_bvp() {
    let sc = issue_scene();
    let data = bvp::cosserat_drive::CosseratDrive::from_scene(&sc).unwrap();
    let bvp_opts = bvp::belt::BeltOptions::from_scene(&sc).unwrap();
    let reference = drive::view::SolutionView::summary(&bvp::cosserat_drive::solve(&data, &bvp_opts).unwrap());
    // (quantity, bounds at 128, 256, 512, least error ratio per doubling or 0: bound only)
    let table: [(&str, [f64; 3], f64); 14] = [
        ("transport_rate", [5e-6, 2.2e-6, 9e-7], 1.4),
        ("driven_speed", [1.8e-7, 1.7e-7, 3e-8], 0.0),
        ("tension_upper_mid", [1e-3, 6e-4, 2.5e-4], 1.4),
        ("tension_lower_mid", [9e-4, 5e-4, 2.2e-4], 1.4),
        ("y_upper_mid", [1.5e-5, 4e-6, 1.4e-6], 1.4),
        ("y_lower_mid", [8e-5, 4e-5, 1.7e-5], 1.4),
        ("moment_upper_mid", [1e-3, 6e-4, 2.5e-4], 1.4),
        ("moment_lower_mid", [9e-4, 5.5e-4, 2.3e-4], 1.4),
        ("driver.contact_arc", [2.3e-3, 2e-4, 9e-5], 1.4),
        ("driven.contact_arc", [2.3e-3, 2e-4, 9e-5], 1.4),
        ("driver.slip_arc", [2.4, 1.0, 0.4], 2.0),
        ("driven.slip_arc", [6.0, 2.2, 0.7], 2.0),
        ("driver.torque", [9e-7, 3e-7, 6e-8], 0.0),
        ("driven.torque", [1e-9, 1e-9, 1e-9], 0.0),
    ];
    let mut errors = vec![[0.0; 3]; table.len()];
    for (m, n) in [128, 256, 512].into_iter().enumerate() {
        let r = solve(&sc, n, &SolverSettings::default());
        let (pin, pout, d) = (drive_option(&r, "power_in"), drive_option(&r, "power_out"), drive_option(&r, "dissipation"));
        assert!((pin - pout - d).abs() < 1e-9 * pin && d > 0.0, "{n}: P_in {pin} − P_out {pout} − D {d}");
        let w2 = r.summary.driven_speed.unwrap();
        assert!(w2 > 0.0 && w2 < sc.drive.driver_speed, "{n}: creep, ω₂ = {w2}");
        // a slip arc more than 10 % off is never a clean result: the run states that
        // its slip zone is unresolved (fem::string_drive::steady::SLIP_ELEMENTS; it is
        // at every mesh here: the zones span 2.9–6.5 arc elements), and at 128 also
        // that the fitting stopped at its pass limit (30 passes, 0.44 mm = 4 % of an
        // arc element from a node)
        for pulley in ["driver", "driven"] {
            let error = relative_error(&r.summary, &reference, &format!("{pulley}.slip_arc"));
            let warned = r.notes.iter().any(|w| w.starts_with(&format!("unresolved slip zone on the {pulley} pulley")));
            assert!(warned || error <= 0.1, "{n} elements, {pulley}: slip arc {error:.2} off and no warning in {:?}", r.notes);
        }
        assert_eq!(r.notes.iter().any(|w| w.contains("pass limit")), n == 128, "{n}: {:?}", r.notes);
        for (k, (q, bounds, _)) in table.iter().enumerate() {
            errors[k][m] = relative_error(&r.summary, &reference, q);
            println!("{n} {q}: FE {:?} BVP {:?} relative error {:.2e}", r.summary.get(q), reference.get(q), errors[k][m]);
            assert!(errors[k][m] <= bounds[m], "{n} elements, {q}: relative error {:e} above {:e}", errors[k][m], bounds[m]);
        }
    }
    for (k, (q, _, ratio)) in table.iter().enumerate() {
        for m in 0..2 {
            assert!(errors[k][m] >= ratio * errors[k][m + 1], "{q}: errors {:?} do not fall by {ratio} per doubling", errors[k]);
        }
    }
}

/// The issue's scene counter-clockwise (ω₁ = −20 rad/s, M₂ = −0.1 N·m: with gravity the
/// upper span is the tight one, a different problem from the mirror image) at 128
/// elements against the BVP's counter-clockwise solution (collocation, tolerance 1e-8).
/// Measured relative errors: c 2.6e-6, ω₂ 4.5e-7, mid-span tensions 5.4e-4 / 6.2e-4,
/// heights 6.1e-6 / 5.2e-5, moments 5.5e-4 / 6.5e-4, contact arcs 9.7e-4 / 9.5e-4,
/// T_tight / T_slack (both read midway along the stick arc) 5.1e-3 / 4.9e-3, driver
/// torque 1.6e-6, slip arcs 0.72 / 1.46 (longer than the BVP's, as clockwise at 128:
/// 1.16 / 3.0). Bounds 2× the measured; the slip arcs only within 3× the BVP's.
#[test]
fn issue_scene_counter_clockwise_against_the_bvp() {
    let mut v: Value = serde_json::from_str(include_str!("../../scenes/cosserat-drive.json")).unwrap();
    v["name"] = json!("cosserat-drive-ccw");
    v["drive"]["driver_speed"] = json!(-20.0);
    v["drive"]["driven_torque"] = json!(-0.1);
    let sc = Scene::from_json_str(&v.to_string()).unwrap();
    let data = bvp::cosserat_drive::CosseratDrive::from_scene(&sc).unwrap();
    let bvp_opts = bvp::belt::BeltOptions::from_scene(&sc).unwrap();
    let reference = drive::view::SolutionView::summary(&bvp::cosserat_drive::solve(&data, &bvp_opts).unwrap());
    let r = solve(&sc, 128, &SolverSettings::default());
    let (pin, pout, d) = (drive_option(&r, "power_in"), drive_option(&r, "power_out"), drive_option(&r, "dissipation"));
    assert!((pin - pout - d).abs() < 1e-9 * pin.abs() && d > 0.0, "P_in {pin} − P_out {pout} − D {d}");
    let w2 = r.summary.driven_speed.unwrap();
    assert!(w2 < 0.0 && w2 > sc.drive.driver_speed, "counter-clockwise creep, ω₂ = {w2}");
    assert!(
        r.summary.tension_upper_mid.unwrap() > r.summary.tension_lower_mid.unwrap(),
        "counter-clockwise the upper span is the tight one"
    );
    for (q, bound) in [
        ("transport_rate", 5.2e-6),
        ("driven_speed", 9e-7),
        ("tension_upper_mid", 1.1e-3),
        ("tension_lower_mid", 1.3e-3),
        ("y_upper_mid", 1.3e-5),
        ("y_lower_mid", 1.1e-4),
        ("moment_upper_mid", 1.1e-3),
        ("moment_lower_mid", 1.3e-3),
        ("driver.contact_arc", 2e-3),
        ("driven.contact_arc", 2e-3),
        ("tension_tight", 1.1e-2),
        ("tension_slack", 1e-2),
        ("driver.torque", 3.3e-6),
    ] {
        let e = relative_error(&r.summary, &reference, q);
        println!("ccw 128 {q}: FE {:?} BVP {:?} relative error {e:.2e}", r.summary.get(q), reference.get(q));
        assert!(e <= bound, "counter-clockwise, {q}: relative error {e:e} above {bound:e}");
    }
    for q in ["driver.slip_arc", "driven.slip_arc"] {
        let (f, b) = (r.summary.get(q).unwrap(), reference.get(q).unwrap());
        assert!(f > 0.0 && b > 0.0 && f < 3.0 * b, "counter-clockwise {q}: FE {f} against BVP {b}");
    }
}
