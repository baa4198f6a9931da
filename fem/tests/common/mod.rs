//! Shared helpers of the `fem` integration tests: scenes of the catalogue, runs, and
//! the closed forms of docs/string-hanging.md.
#![allow(dead_code)]

use std::path::PathBuf;

use drive::view::{ContactState, SolutionView};
use drive::Scene;
use fem::{FemOptions, FemRun, SolverSettings};

/// A scene of the catalogue (`scenes/<name>.json`).
pub fn scene(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(format!("{name}.json"));
    Scene::from_path(&path).unwrap_or_else(|e| panic!("scene {name}: {e}"))
}

/// Solve `scene` with `elements`, `formulation` and default settings.
pub fn run(scene: &Scene, elements: usize, formulation: &str) -> FemRun {
    run_with(scene, elements, formulation, None, &SolverSettings::default())
}

/// Solve with explicit penalty and settings.
pub fn run_with(scene: &Scene, elements: usize, formulation: &str, penalty: Option<f64>, settings: &SolverSettings) -> FemRun {
    let opts = FemOptions { elements, formulation: formulation.into(), penalty };
    fem::solve_scene_with(scene, &opts, settings).unwrap_or_else(|e| panic!("{} with {elements} elements: {e}", scene.name))
}

/// Observed order p = log2(e_coarse / e_fine) for a halving of h.
pub fn order(e_coarse: f64, e_fine: f64) -> f64 {
    (e_coarse / e_fine).log2()
}

/// Max − min of the frictionless invariant E = N + N²/(2EA) − ρ g y (S6) over `n`
/// equally spaced σ, N.
pub fn invariant_drift(scene: &Scene, view: &dyn SolutionView, n: usize) -> f64 {
    let ea = scene.belt.axial_stiffness;
    let w = scene.belt.mass_per_length * scene.effects.gravity.unwrap_or(0.0);
    let l = view.path().length();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..n {
        let s = l * k as f64 / n as f64;
        let t = view.axial_force(s);
        let e = t + t * t / (2.0 * ea) - w * view.position(s)[1];
        lo = lo.min(e);
        hi = hi.max(e);
    }
    hi - lo
}

/// Largest distance of the FE upper span from the elastic catenary (S3) through the
/// FE's own vertex (x = 0, y_mid) with the FE's horizontal force h = N(σ_mid), over the
/// free points with |x| ≤ `half_width`, m. The catenary is parametrised by the FE's
/// material coordinate s̃ = s(σ) − s(σ_mid).
pub fn catenary_distance(scene: &Scene, view: &dyn SolutionView, half_width: f64, n: usize) -> f64 {
    let ea = scene.belt.axial_stiffness;
    let w = scene.belt.mass_per_length * scene.effects.gravity.unwrap_or(0.0);
    let h_dist = scene.drive.centre_distance;
    let mid = 0.5 * h_dist;
    let h = view.axial_force(mid);
    let y_mid = view.position(mid)[1];
    let s_mid = view.material_coordinate(mid);
    let mut worst: f64 = 0.0;
    for k in 0..=n {
        let sigma = mid - half_width + 2.0 * half_width * k as f64 / n as f64;
        if view.contact_state(sigma) != ContactState::Free {
            continue;
        }
        let st = view.material_coordinate(sigma) - s_mid;
        let x = h * st / ea + (h / w) * (w * st / h).asinh();
        let y = y_mid + w * st * st / (2.0 * ea) + (h / w) * ((1.0 + (w * st / h).powi(2)).sqrt() - 1.0);
        let p = view.position(sigma);
        worst = worst.max((p[0] - x).hypot(p[1] - y));
    }
    worst
}

/// Max − min of the invariant (S6) over the points of the spans with |x| ≤ `half_width`
/// (free, away from the contact edges and the coordinate transitions), N.
pub fn invariant_drift_spans(scene: &Scene, view: &dyn SolutionView, half_width: f64, n: usize) -> f64 {
    let ea = scene.belt.axial_stiffness;
    let w = scene.belt.mass_per_length * scene.effects.gravity.unwrap_or(0.0);
    let c = view.contour().expect("a two-pulley loop");
    let h = c.centre_distance();
    let lower_mid = h + std::f64::consts::PI * c.radius() + 0.5 * h;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for mid in [0.5 * h, lower_mid] {
        for k in 0..=n {
            let s = mid - half_width + 2.0 * half_width * k as f64 / n as f64;
            let t = view.axial_force(s);
            let e = t + t * t / (2.0 * ea) - w * view.position(s)[1];
            lo = lo.min(e);
            hi = hi.max(e);
        }
    }
    hi - lo
}
