//! The fields of the common solution view of both BVP methods on slack belts over small
//! pulleys, whose upper span sags below the pulley centres (y_upper_mid < 0).
//!
//! Source: issue 12, item 1 — the summary was right but every upper-span field sample
//! sat at one point, because the σ map read a span point below the centre line as a
//! point of the lower span. The checks follow the definition of "the belt point at σ"
//! (MEL description, eq. 27; `bvp/src/sigma_map.rs`):
//! - on the upper straight σ ∈ [0, H] the belt point lies on the contour normal at σ,
//!   i.e. x = σ − H/2 exactly (to the bisection's 1e-15 in ξ: 1e-9 H is generous);
//!   on the lower straight x = H/2 − (σ − H − πR);
//! - at the mid-points σ = H/2 and σ = H + πR + H/2 the fields give the summary's
//!   y_upper_mid, y_lower_mid, tension_upper_mid, tension_lower_mid (same point, same
//!   dense output: 1e-9 relative);
//! - collocation and shooting, each at tolerance 1e-8 on its own scaled residual, give
//!   the same fields: positions within 1e-6 H, tensions within 1e-6 of the largest
//!   tension (100× the tolerance, the margin the catalogue's method comparison uses).

use std::f64::consts::PI;
use std::path::Path;

use bvp::scene::{solve_scene, BvpMethod, BvpRun, BvpRunOptions};
use drive::scene::Scene;

fn catalogue(name: &str) -> Scene {
    Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("scenes").join(name)).expect("catalogue scene")
}

/// `string-hanging` with pulley radius `radius` and L = `ratio` · L_geom.
fn slack_small_pulley(radius: f64, ratio: Option<f64>) -> Scene {
    let mut s = catalogue("string-hanging.json");
    s.drive.pulley_radius = radius;
    if let Some(r) = ratio {
        s.belt.length = r * s.geometric_length();
    }
    s.validate().expect("valid scene");
    s
}

fn run(scene: &Scene, method: BvpMethod) -> BvpRun {
    let opts = BvpRunOptions { method, ..BvpRunOptions::from_scene(scene).expect("options") };
    solve_scene(scene, &opts).unwrap_or_else(|e| panic!("{}: {e}", method.name()))
}

/// Largest |x(σ) − x_expected(σ)| over n points of each straight (m).
fn straight_defect(run: &BvpRun, h: f64, r: f64, n: usize) -> f64 {
    let mut worst: f64 = 0.0;
    for i in 0..=n {
        let t = i as f64 / n as f64;
        let upper = t * h;
        worst = worst.max((run.view.position(upper)[0] - (upper - 0.5 * h)).abs());
        let lower = h + PI * r + t * h;
        worst = worst.max((run.view.position(lower)[0] - (0.5 * h - t * h)).abs());
    }
    worst
}

fn check_scene(scene: &Scene) {
    let (h, r) = (scene.drive.centre_distance, scene.drive.pulley_radius);
    let runs = [run(scene, BvpMethod::Collocation), run(scene, BvpMethod::Shooting)];
    for run in &runs {
        let s = &run.summary;
        let y_upper = s.y_upper_mid.expect("y_upper_mid");
        assert!(y_upper < 0.0, "{}: the case must sag below the centres (y_upper_mid = {y_upper})", run.method);
        let defect = straight_defect(run, h, r, 200);
        assert!(defect <= 1e-9 * h, "{}: a straight's belt point is off its contour normal by {defect:.3e} m", run.method);
        let upper_mid = 0.5 * h;
        let lower_mid = h + PI * r + 0.5 * h;
        let t_max = s.tension_upper_mid.unwrap().max(s.tension_lower_mid.unwrap());
        let pairs = [
            ("y_upper_mid", run.view.position(upper_mid)[1], y_upper, h),
            ("y_lower_mid", run.view.position(lower_mid)[1], s.y_lower_mid.unwrap(), h),
            ("tension_upper_mid", run.view.axial_force(upper_mid), s.tension_upper_mid.unwrap(), t_max),
            ("tension_lower_mid", run.view.axial_force(lower_mid), s.tension_lower_mid.unwrap(), t_max),
        ];
        for (name, field, summary, scale) in pairs {
            assert!((field - summary).abs() <= 1e-9 * scale, "{}: field {name} {field} ≠ summary {summary}", run.method);
        }
    }
    // The two methods against each other along the whole loop.
    let contour_length = 2.0 * h + 2.0 * PI * r;
    let n = 400;
    let t_max = runs[0].summary.tension_upper_mid.unwrap().max(runs[0].summary.tension_lower_mid.unwrap());
    for i in 0..n {
        let sigma = contour_length * i as f64 / n as f64;
        let (a, b) = (runs[0].view.position(sigma), runs[1].view.position(sigma));
        let dp = (a[0] - b[0]).hypot(a[1] - b[1]);
        assert!(dp <= 1e-6 * h, "σ = {sigma}: positions differ by {dp:.3e} m between the methods");
        let dt = (runs[0].view.axial_force(sigma) - runs[1].view.axial_force(sigma)).abs();
        assert!(dt <= 1e-6 * t_max, "σ = {sigma}: tensions differ by {dt:.3e} N between the methods");
    }
}

/// The reproducer of the issue: R = 0.01 m, the catalogue's length.
#[test]
fn upper_span_below_the_centres_small_pulley() {
    check_scene(&slack_small_pulley(0.01, None));
}

/// The second reproducer: R = 0.005 m, L/L_geom = 1.05 (inside the documented slack range).
#[test]
fn upper_span_below_the_centres_very_slack() {
    check_scene(&slack_small_pulley(0.005, Some(1.05)));
}
