//! `string-drive` in all four quadrants (docs/string-drive.md, "Both rotation senses and
//! both power flows"; issue 12): the driver turning counter-clockwise (ω₁ < 0, the belt
//! runs against σ, slip → stick along σ on each pulley) and the load driving (net load
//! M₂ + d₂ω₁ of the sense of −ω₁, the slip frictions swap). Checked against the mirror
//! image y → −y without gravity (an exact symmetry of the gravity-free scene), against
//! belt-creep theory in every quadrant, and by the power balance and the tight span with
//! gravity, which breaks the symmetry.

mod common;

use bvp::belt::{ArcKind, BeltOptions, Pulley};
use bvp::collocation::Scheme;
use bvp::string_drive::{solve, StringDrive, StringDriveSolution};
use bvp::string_hanging::StringHanging;
use drive::view::SolutionView;

/// The gravity-free drive of `bvp/tests/string_drive.rs` (inertia and damping on).
fn base() -> StringDrive {
    StringDrive {
        belt: StringHanging { radius: 0.1, centre_distance: 0.5, length: 1.60, axial_stiffness: 1.0e4, mass_per_length: 0.5, gravity: 0.0 },
        inertia: true,
        friction: 0.4,
        driver_speed: 20.0,
        driven_torque: 10.0,
        driven_damping: 0.05,
    }
}

/// The catalogue scene's gravity (scenes/string-drive.json).
fn with_gravity(d: StringDrive) -> StringDrive {
    StringDrive { belt: StringHanging { gravity: 9.81, ..d.belt }, ..d }
}

fn colloc() -> BeltOptions {
    BeltOptions::collocation(Scheme::default(), 1e-10)
}

/// Relative difference on the scale of `b` (absolute below 1e-3 of its unit, where a
/// quantity is zero, e.g. a contact angle at 0).
fn close(name: &str, a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol * b.abs().max(1e-3), "{name}: {a} vs {b}");
}

/// The power balance P_in = P_out + D to 1e-9 of the transmitted power (the BVP does not
/// impose it; 1e-9 is above the 1e-10 solve tolerance), D > 0.
fn power_balances(sol: &StringDriveSolution) -> (f64, f64, f64) {
    let (input, output, dissipation) = sol.power_balance();
    assert!(dissipation > 0.0, "dissipation {dissipation}");
    assert!((input - output - dissipation).abs() < 1e-9 * sol.power_scale(), "P_in {input} ≠ P_out {output} + D {dissipation}");
    (input, output, dissipation)
}

/// Sign of the friction on the belt in `pulley`'s slip zone along the belt's travel:
/// +1 where the pulley drags the belt forward (it puts power in), −1 where it brakes.
fn slip_drag(sol: &StringDriveSolution, pulley: Pulley) -> f64 {
    let k = sol.topology().arc(pulley, ArcKind::Slip).unwrap();
    let tau = sol.point(k, 0.5).friction.unwrap();
    (tau * sol.data.driver_speed.signum()).signum()
}

/// (a) Without gravity the counter-clockwise drive (−ω₁, −M₂) is the mirror image of the
/// clockwise one, and so is (−ω₁, +M₂) of (ω₁, −M₂): every summary scalar through
/// [`drive::summary::Summary::mirror_y`]. The two solves run through different
/// topologies (slip → stick along σ) and arithmetic, so they agree to the solve
/// tolerance: 1e-10 residual, ~1e-10 in the node values, hence 1e-8.
#[test]
fn counter_clockwise_is_the_mirror_image_without_gravity() {
    for (torque, damping) in [(10.0, 0.05), (-10.0, 0.05), (0.0, 0.3)] {
        let cw = StringDrive { driven_torque: torque, driven_damping: damping, ..base() };
        let ccw = StringDrive { driver_speed: -cw.driver_speed, driven_torque: -torque, ..cw };
        let a = solve(&cw, &colloc()).expect("clockwise").summary();
        let b = solve(&ccw, &colloc()).expect("counter-clockwise").summary();
        let mirrored = a.mirror_y().scalars();
        let got = b.scalars();
        assert_eq!(mirrored.len(), got.len());
        for ((name, want), (other, x)) in mirrored.iter().zip(&got) {
            assert_eq!(name, other);
            close(&format!("M₂ {torque}: {name}"), *x, *want, 1e-8);
        }
    }
}

/// (d) Belt-creep theory in every quadrant without gravity (the closed form solves the
/// reversed power flow with its linear torque balance and mirrors ω₁ < 0): the BVP's
/// stick-zone forces, speeds, arcs and torques to 1e-8 (solve tolerance 1e-10).
#[test]
fn matches_belt_creep_in_every_quadrant() {
    for (omega1, torque) in [(20.0, -10.0), (-20.0, -10.0), (-20.0, 10.0)] {
        let d = StringDrive { driver_speed: omega1, driven_torque: torque, ..base() };
        let sol = solve(&d, &colloc()).expect("solves");
        let e = d.creep().expect("closed form");
        for (name, got, want) in common::creep_checks(&sol.summary(), &e) {
            close(&format!("ω₁ {omega1}, M₂ {torque}: {name}"), got, want, 1e-8);
        }
        power_balances(&sol);
    }
}

/// (b) With gravity the counter-clockwise drive is solved natively and is no mirror
/// image: the belt runs onto the driver from the upper span, which is the tight one
/// (its mid-span force above the lower span's, and the driver's stick-zone force above
/// the driven pulley's); the power balances; the driver drags the belt along its travel
/// in its slip zone and the driven pulley brakes it. The sags differ from the mirrored
/// clockwise drive's by more than 1 % (gravity pulls both spans the same way).
#[test]
fn counter_clockwise_with_gravity_has_the_upper_span_tight() {
    let cw = with_gravity(base());
    let ccw = StringDrive { driver_speed: -cw.driver_speed, driven_torque: -cw.driven_torque, ..cw };
    let sol = solve(&ccw, &colloc()).expect("counter-clockwise with gravity");
    let s = sol.summary();
    assert!(s.tension_upper_mid.unwrap() > s.tension_lower_mid.unwrap(), "upper {:?} lower {:?}", s.tension_upper_mid, s.tension_lower_mid);
    assert!(s.tension_tight.unwrap() > s.tension_slack.unwrap());
    assert!(s.transport_rate.unwrap() < 0.0 && s.driven_speed.unwrap() < 0.0);
    let (input, output, _) = power_balances(&sol);
    assert!(input > output && output > 0.0, "P_in {input}, P_out {output}");
    assert_eq!((slip_drag(&sol, Pulley::Driver), slip_drag(&sol, Pulley::Driven)), (1.0, -1.0));
    let mirrored = solve(&cw, &colloc()).expect("clockwise").summary().mirror_y();
    let sag = |y: f64| y.abs() - ccw.radius;
    let (a, b) = (sag(s.y_upper_mid.unwrap()), sag(mirrored.y_upper_mid.unwrap()));
    assert!((a - b).abs() > 0.01 * b.abs(), "upper sag {a} vs mirrored {b}");
}

/// (c) The load drives (M₂ < 0, d₂ = 0, ω₁ > 0; and its counter-clockwise twin): both
/// slip frictions swap — the driven pulley drags the belt along, the driver brakes it —
/// the driver's stick-zone force is now the smaller, ω₂ runs ahead of ω₁, the driver
/// takes power out (P_in < 0) and P_in = P_out + D, with gravity.
#[test]
fn the_load_drives() {
    for omega1 in [20.0, -20.0] {
        let d = with_gravity(StringDrive { driver_speed: omega1, driven_torque: -10.0 * omega1.signum(), driven_damping: 0.0, ..base() });
        let sol = solve(&d, &colloc()).expect("load drives");
        let s = sol.summary();
        assert!(s.tension_tight.unwrap() < s.tension_slack.unwrap());
        assert!(s.driven_speed.unwrap().abs() > omega1.abs());
        assert_eq!((slip_drag(&sol, Pulley::Driver), slip_drag(&sol, Pulley::Driven)), (-1.0, 1.0), "ω₁ {omega1}");
        let (input, output, _) = power_balances(&sol);
        assert!(input < 0.0 && output < input, "P_in {input}, P_out {output}");
        close("driven torque", s.driven.unwrap().torque.unwrap(), d.driven_torque, 1e-9);
    }
}

/// A net load whose sign differs from M₂'s (M₂ < 0 but d₂ω₁ > |M₂|: the driver drives):
/// the homotopy holds the net load while the driver is at rest, so the slip signs of the
/// scene hold along the whole path; the result satisfies the closed form without
/// gravity (1e-8) and the power balance with it.
#[test]
fn damping_outweighs_a_negative_torque() {
    let d = StringDrive { driven_torque: -0.5, driven_damping: 0.1, ..base() };
    assert!(d.net_load() > 0.0);
    let sol = solve(&d, &colloc()).expect("net load resists");
    let e = d.creep().unwrap();
    close("tension_tight", sol.summary().tension_tight.unwrap(), e.tension_tight, 1e-8);
    close("driven_speed", sol.summary().driven_speed.unwrap(), e.driven_speed, 1e-8);
    let sol = solve(&with_gravity(d), &colloc()).expect("with gravity");
    power_balances(&sol);
}
