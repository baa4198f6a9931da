//! `string-drive` as a BVP (docs/string-drive.md): the steady friction drive checked
//! against belt-creep theory (no gravity; `analytical::belt_creep`, exact length
//! constraint), between its two methods, and by the balances the BVP does not impose:
//! power (input = output + slip dissipation) and the slip direction / stick bound.
//! Sources: reference §6.1 (Coulomb, Tab. 1), §8.2 (Paper B), DESIGN.md closed forms.

use std::f64::consts::PI;

use bvp::analytical::belt_creep::CreepError;
use bvp::collocation::Scheme;
use bvp::string_drive::{solve, StringDrive, StringDriveError, StringDriveOptions, StringDriveSolution};
use bvp::string_hanging::Method;
use drive::view::{ContactState, SolutionView};

/// A rubber-like drive (scenes/string-drive.json without gravity/inertia switches).
fn base() -> StringDrive {
    StringDrive {
        radius: 0.1,
        centre_distance: 0.5,
        length: 1.60,
        axial_stiffness: 1.0e4,
        mass_per_length: 0.5,
        gravity: 0.0,
        inertia: true,
        friction: 0.4,
        driver_speed: 20.0,
        driven_torque: 10.0,
        driven_damping: 0.05,
    }
}

fn colloc(tol: f64) -> StringDriveOptions {
    StringDriveOptions { tolerance: tol, method: Method::Collocation(Scheme::default()), ..Default::default() }
}

fn shoot(tol: f64) -> StringDriveOptions {
    StringDriveOptions { tolerance: tol, method: Method::Shooting, ..Default::default() }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

/// Compare with belt-creep theory; `tol` relative on every quantity.
fn against_creep(sol: &StringDriveSolution, tol: f64) {
    let e = sol.data.creep().expect("closed form");
    let s = sol.summary();
    let d = s.driven.as_ref().unwrap();
    let r = s.driver.as_ref().unwrap();
    let checks = [
        ("tension_tight", s.tension_tight.unwrap(), e.tension_tight),
        ("tension_slack", s.tension_slack.unwrap(), e.tension_slack),
        ("driven_speed", s.driven_speed.unwrap(), e.driven_speed),
        ("transport_rate", s.transport_rate.unwrap(), e.transport_rate),
        ("driven slip arc", d.slip_arc.unwrap(), e.slip_arc),
        ("driver slip arc", r.slip_arc.unwrap(), e.slip_arc),
        ("driven stick arc", d.stick_arc.unwrap(), PI - e.slip_arc),
        ("driven contact arc", d.contact_arc.unwrap(), PI),
        ("driver contact arc", r.contact_arc.unwrap(), PI),
        ("driven torque", d.torque.unwrap(), e.driven_torque),
        ("driver torque", r.torque.unwrap(), e.driver_torque),
        ("upper mid tension", s.tension_upper_mid.unwrap(), e.tension_slack),
        ("lower mid tension", s.tension_lower_mid.unwrap(), e.tension_tight),
    ];
    for (name, got, want) in checks {
        assert!(rel(got, want) < tol, "{name}: BVP {got} vs closed form {want} (rel {:.2e})", rel(got, want));
    }
}

/// No gravity: the BVP reproduces belt-creep theory with inertia and damping. Collocation
/// at 1e-10 residual leaves ~1e-10 relative in node values; 1e-8 leaves two decades.
#[test]
fn matches_belt_creep_without_gravity() {
    let sol = solve(&base(), &colloc(1e-10)).expect("solves");
    against_creep(&sol, 1e-8);
    let sol = solve(&StringDrive { inertia: false, ..base() }, &colloc(1e-10)).expect("solves");
    against_creep(&sol, 1e-8);
}

#[test]
fn explore() {
    for d in [StringDrive { gravity: 9.81, ..base() }, StringDrive { gravity: 9.81, length: 1.70, ..base() }] {
        for o in [colloc(1e-8), shoot(1e-8)] {
            let t = std::time::Instant::now();
            match solve(&d, &o) {
                Ok(sol) => {
                    println!("{:?} {:?} steps {} t {:.3}", sol.summary(), sol.power_balance(), sol.homotopy_steps, t.elapsed().as_secs_f64());
                }
                Err(e) => println!("ERR {e}"),
            }
        }
    }
}
