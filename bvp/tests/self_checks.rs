//! Every balance a BVP run reports is also a check (issue 12, item 6;
//! `bvp/src/belt/balance.rs`): a run whose own closure defect or power imbalance exceeds
//! 1e-4 of the scene's scale fails with `BeltError::BalanceFailed`, carrying the numbers.
//!
//! Reproducers of the issue (the catalogue scenes with one number pushed beyond what
//! double precision resolves), each of which used to print its failed balance and exit 0:
//! - `string-hanging` with centre_distance = 1e50 m: closure defect 1.1e23 N against a
//!   belt weight of 1.7 N (both methods);
//! - `string-drive` with axial_stiffness = 1e17 N (shooting: imbalance 0.79 W of 780 W),
//!   1e50 N (collocation: 1.6e17 W; shooting: 774 W), centre_distance = 1e50 m
//!   (collocation: 5.5e38 W).
//!
//! And the other side: the catalogue scenes pass with balances many orders below the
//! tolerance (closure ≤ 1e-10 of the weight, power ≤ 1e-7 of P_ref at tolerance 1e-8), so
//! the checks cannot fire on a converged solve.

use std::path::Path;

use bvp::belt::balance::{CLOSURE_TOLERANCE, POWER_TOLERANCE};
use bvp::belt::BeltError;
use bvp::scene::{solve_scene, BvpMethod, BvpRunOptions, SceneSolveError};
use drive::scene::Scene;

fn catalogue(name: &str) -> Scene {
    Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("scenes").join(name)).expect("catalogue scene")
}

fn options(scene: &Scene, method: BvpMethod) -> BvpRunOptions {
    BvpRunOptions { method, ..BvpRunOptions::from_scene(scene).expect("options") }
}

/// Solve and expect the named balance failure; returns (value, scale, tolerance).
fn expect_balance_failure(scene: &Scene, method: BvpMethod, which: &str) -> (f64, f64, f64) {
    match solve_scene(scene, &options(scene, method)) {
        Err(SceneSolveError::Belt(BeltError::BalanceFailed(b))) => {
            let (value, scale, tolerance) = (b.value, b.scale, b.tolerance);
            assert_eq!(b.name, which, "{}", method.name());
            assert!(value.abs() > tolerance * scale, "{}: {value} within {tolerance} × {scale}", method.name());
            (value, scale, tolerance)
        }
        Err(e) => panic!("{}: expected a failed {which}, got {e}", method.name()),
        Ok(run) => panic!("{}: expected a failed {which}, got a result with notes {:?}", method.name(), run.notes),
    }
}

#[test]
fn hanging_string_at_centre_distance_1e50_fails_its_closure() {
    let mut s = catalogue("string-hanging.json");
    s.drive.centre_distance = 1e50;
    s.validate().expect("valid scene");
    let weight = s.belt.mass_per_length * s.effects.gravity.unwrap() * s.belt.length;
    for method in [BvpMethod::Collocation, BvpMethod::Shooting] {
        let (value, scale, tolerance) = expect_balance_failure(&s, method, "closure defect");
        assert_eq!(scale, weight, "measured against the belt weight ρgL");
        assert_eq!(tolerance, CLOSURE_TOLERANCE);
        // The defect is of order 1e23 N: twenty orders above the weight.
        assert!(value.abs() > 1e20 * weight, "{value}");
    }
}

#[test]
fn drive_with_unresolvable_numbers_fails_its_power_balance() {
    let base = catalogue("string-drive.json");
    let resisting = (base.drive.driven_torque + base.drive.driven_damping * base.drive.driver_speed) * base.drive.driver_speed;
    let cases: [(&str, f64, BvpMethod); 4] = [
        ("axial_stiffness", 1e17, BvpMethod::Shooting),
        ("axial_stiffness", 1e50, BvpMethod::Collocation),
        ("axial_stiffness", 1e50, BvpMethod::Shooting),
        ("centre_distance", 1e50, BvpMethod::Collocation),
    ];
    for (field, value, method) in cases {
        let mut s = base.clone();
        match field {
            "axial_stiffness" => s.belt.axial_stiffness = value,
            _ => s.drive.centre_distance = value,
        }
        s.validate().expect("valid scene");
        let (imbalance, scale, tolerance) = expect_balance_failure(&s, method, "power imbalance");
        assert_eq!(scale, resisting, "{field} = {value}: P_ref is the scene's resisting power (M₂ + d₂ω₁)ω₁");
        assert_eq!(tolerance, POWER_TOLERANCE);
        assert!(imbalance.abs() > 1e-3 * resisting, "{field} = {value}, {}: {imbalance}", method.name());
    }
}

/// The catalogue passes both checks with a wide margin, by both methods.
#[test]
fn catalogue_balances_are_far_inside_the_tolerance() {
    let hanging = catalogue("string-hanging.json");
    let data = bvp::scene::string_hanging_data(&hanging);
    let weight = data.mass_per_length * data.gravity * data.length;
    let drive_scene = catalogue("string-drive.json");
    let drive::scene::Contact::Coulomb(mu) = drive_scene.effects.contact else { panic!("a friction drive") };
    let drive = bvp::scene::string_drive_data(&drive_scene, mu);
    for method in [BvpMethod::Collocation, BvpMethod::Shooting] {
        let sol = bvp::string_hanging::solve(&data, &options(&hanging, method)).expect("string-hanging solves");
        let f = sol.closure_defect().expect("a frictionless loop has a closure defect");
        assert!(f.abs() <= 1e-10 * weight, "{}: closure defect {f:e} N vs weight {weight} N", method.name());
        let sol = bvp::string_drive::solve(&drive, &options(&drive_scene, method)).expect("string-drive solves");
        let (input, output, dissipation) = sol.power_balance();
        let imbalance = input - output - dissipation;
        assert!(imbalance.abs() <= 1e-7 * sol.power_scale(), "{}: imbalance {imbalance:e} W vs {} W", method.name(), sol.power_scale());
    }
}
