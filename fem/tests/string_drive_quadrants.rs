//! The direct steady FE drive (docs/fem-drive.md §12, "Both rotation senses and both
//! power flows") in all four quadrants: a counter-clockwise driver (the belt runs
//! against σ: upwind elements, the order stick → slip and the fitted transitions follow
//! it) and a load that drives (the slip frictions swap by the semismooth law itself).
//!
//! Scene: `fem/tests/scenes/drive-creep.json` (no gravity: R = 0.08 m, H = 0.45 m,
//! EA = 2·10⁴ N, T₀ = 100 N, μ = 0.3, ω₁ = 10 rad/s, M₂ = 2 N·m), 64 elements.

use std::path::PathBuf;

use drive::Scene;
use fem::string_drive::{self, DriveSettings};
use fem::{FemError, FemOptions, FemRun, SolverSettings};

fn creep_scene() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/drive-creep.json");
    Scene::from_path(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// `solver` (the direct steady solve or the transient) on `scene` with the default
/// formulation and settings.
fn run_with<S>(solver: S, scene: &Scene, elements: usize) -> Result<FemRun, FemError>
where
    S: Fn(&fem::FemProblem, &FemOptions, &SolverSettings, &DriveSettings, std::sync::Arc<dyn fem::formulation::Kernel>) -> Result<FemRun, FemError>,
{
    let opts = FemOptions { elements, formulation: fem::default_formulation().into(), penalty: None };
    let kernel = fem::formulation::find(&opts.formulation).unwrap();
    solver(&fem::FemProblem::from_scene(scene), &opts, &SolverSettings::default(), &DriveSettings::from_scene(scene), kernel)
}

fn steady(scene: &Scene, elements: usize) -> Result<FemRun, FemError> {
    run_with(string_drive::steady::solve, scene, elements)
}

/// The creep scene with the load M₂ = `torque` and its reversal (−ω₁, −M₂).
fn reversed_pair(torque: f64) -> (Scene, Scene) {
    let mut cw = creep_scene();
    cw.drive.driven_torque = torque;
    let mut ccw = cw.clone();
    ccw.drive.driver_speed = -cw.drive.driver_speed;
    ccw.drive.driven_torque = -torque;
    (cw, ccw)
}

/// Every summary scalar of `ccw` is that of `cw` mirrored (`Summary::mirror_y`) to `tol`
/// relative (absolute below 1e-3, where a quantity is zero).
fn assert_mirror_image(cw: &drive::summary::Summary, ccw: &drive::summary::Summary, tol: f64, label: &str) {
    let (want, got) = (cw.mirror_y().scalars(), ccw.scalars());
    assert_eq!(want.len(), got.len());
    for ((name, w), (other, g)) in want.iter().zip(&got) {
        assert_eq!(name, other);
        assert!((g - w).abs() <= tol * w.abs().max(1e-3), "{label}: {name}: {g} vs mirrored {w}");
    }
}

fn drive_option(run: &FemRun, key: &str) -> f64 {
    run.options["drive"][key].as_f64().unwrap_or_else(|| panic!("options.drive.{key}"))
}

/// (a) Without gravity the counter-clockwise drive (−ω₁, −M₂) is the mirror image y → −y
/// of the clockwise one, and (−ω₁, +M₂) that of (ω₁, −M₂): every summary scalar through
/// `Summary::mirror_y`. The mirrored meshes and fits are the same up to round-off, so
/// the two solves agree to their Newton tolerance (measured ≤ 9e-12 relative): 1e-9.
#[test]
fn counter_clockwise_is_the_mirror_image_without_gravity() {
    for torque in [2.0, -2.0] {
        let (cw, ccw) = reversed_pair(torque);
        let a = steady(&cw, 64).unwrap_or_else(|e| panic!("cw {e}")).summary;
        let b = steady(&ccw, 64).unwrap_or_else(|e| panic!("ccw {e}")).summary;
        assert_mirror_image(&a, &b, 1e-9, &format!("M₂ {torque}"));
    }
}

/// (c) The load drives (M₂ = −2 N·m, d₂ = 0, ω₁ > 0): the semismooth law finds the
/// swapped slip frictions by itself. Belt-creep theory with the roles swapped: the
/// driver's stick zone carries the slack force, ω₂/ω₁ = λ_driven/λ_driver > 1 (1e-6,
/// as the clockwise test), each slip arc ln(T_slack/T_tight)/μ within a tenth of an
/// arc element (measured 0.4°, element 16°); the driven torque balance to 1e-9, and the
/// exact discrete power balance P_in = P_out + D with P_in < 0 (the driver brakes).
#[test]
fn the_load_drives() {
    let mut scene = creep_scene();
    scene.drive.driven_torque = -2.0;
    let r = steady(&scene, 64).unwrap_or_else(|e| panic!("{e}"));
    let s = &r.summary;
    let ea = scene.belt.axial_stiffness;
    let (tt, ts) = (s.tension_tight.unwrap(), s.tension_slack.unwrap());
    assert!(tt < ts, "driver's stick zone {tt} N, driven's {ts} N");
    let ratio = s.driven_speed.unwrap() / scene.drive.driver_speed;
    let creep = (1.0 + ts / ea) / (1.0 + tt / ea);
    assert!(ratio > 1.0 && (ratio - creep).abs() < 1e-6 * creep, "ω₂/ω₁ {ratio} vs {creep}");
    let theta = (ts / tt).ln() / 0.3;
    let arc_element = std::f64::consts::PI / 11.0;
    for p in [s.driver.as_ref().unwrap(), s.driven.as_ref().unwrap()] {
        assert!((p.slip_arc.unwrap() - theta).abs() < 0.1 * arc_element, "slip {} vs {theta}", p.slip_arc.unwrap());
    }
    assert!((s.driven.as_ref().unwrap().torque.unwrap() + 2.0).abs() < 1e-9);
    let (pin, pout, d) = (drive_option(&r, "power_in"), drive_option(&r, "power_out"), drive_option(&r, "dissipation"));
    assert!(pin < 0.0 && d > 0.0, "P_in {pin}, D {d}");
    assert!((pin - pout - d).abs() < 1e-9 * pout.abs(), "P_in {pin} P_out {pout} D {d}");
}

fn transient(scene: &Scene, elements: usize) -> Result<FemRun, FemError> {
    run_with(string_drive::solve, scene, elements)
}

/// (d) The quasistatic transient (docs/fem-drive.md §3–§7, §13) turned counter-clockwise:
/// without gravity (−ω₁, −M₂) is the mirror image of (ω₁, M₂) and (−ω₁, +M₂) — the load
/// drives — that of (ω₁, −M₂), in every summary scalar through `Summary::mirror_y`, in
/// the powers and in the number of steps to the steady state. The mirrored meshes and
/// point rules are the same up to round-off and every step solves the mirrored system, so
/// the two runs agree to the Newton tolerance (10⁻¹⁰ scaled update) carried through the
/// steps: measured ≤ 1.8e-9 relative (both power flows); 1e-8.
#[test]
fn transient_counter_clockwise_is_the_mirror_image_without_gravity() {
    for torque in [2.0, -2.0] {
        let (cw, ccw) = reversed_pair(torque);
        let (ra, rb) = (transient(&cw, 32).unwrap_or_else(|e| panic!("cw {e}")), transient(&ccw, 32).unwrap_or_else(|e| panic!("ccw {e}")));
        assert_eq!(ra.history.as_ref().unwrap().len(), rb.history.as_ref().unwrap().len(), "M₂ {torque}: steps to the steady state");
        assert_mirror_image(&ra.summary, &rb.summary, 1e-8, &format!("M₂ {torque}"));
        for key in ["power_in", "power_out", "dissipation"] {
            let (w, g) = (drive_option(&ra, key), drive_option(&rb, key));
            assert!((g - w).abs() <= 1e-8 * w.abs(), "M₂ {torque}: {key}: {g} vs {w}");
        }
    }
}
