//! Hard cases of the MEL Kirchhoff rod (issue 5, DESIGN.md "Numerical stability"; Paper
//! A, §8.1 of the reference; docs/fem-rod.md §9): each solved by `rod-simpson` from the
//! scene alone (the homotopy of docs/fem-rod.md §5) and checked against the rod BVP
//! (collocation, gauss6, tolerance 1e-8 — far below the FE errors checked here).
//!
//! - **small EI** (1e-6 N·m² on the `rod-hanging` geometry): boundary layer
//!   √(EI/T) = 0.9 mm below the 5.5 mm span elements at 256 elements. Heights, tensions
//!   and contact angles converge to the BVP's (which is within O(EI) of the string); the
//!   edge forces (0.012–0.016 N, 30× smaller than at EI = 1e-3) are not resolved by such a
//!   mesh — only asserted finite and small against the weight scale.
//! - **steel belt** of Paper A (EA = 2e7 N, EI = 1.75 N·m², R = 0.25 m, H = 2 m,
//!   L = L_geom(1 + 1e-4), ρ = 0.748 kg/m): EA/(ρ g H) = 1.4e6, tension 697 N set by
//!   the path length with sensitivity EA/L.
//! - **very slack** loop (L = 1.613 m, L/L_geom = 1.15, EI = 1e-3 N·m²).
//!
//! Bounds (relative to the BVP value, or absolute where stated) are ≈ 3× the errors
//! measured at the mesh used (printed), so that a regression of the discretisation,
//! the homotopy or the edge recovery fails while mesh-level noise does not.

use bvp::scene::{BvpMethod, BvpRunOptions};
use drive::summary::Summary;
use drive::Scene;

fn scene(name: &str, r: f64, h: f64, length: f64, ea: f64, ei: f64, rho: f64) -> Scene {
    Scene::from_json_str(&format!(
        r#"{{"name": "{name}", "drive": {{"pulley_radius": {r}, "centre_distance": {h}, "driver_speed": 0.0, "driven_torque": 0.0}},
            "belt": {{"theory": "kirchhoff", "length": {length}, "axial_stiffness": {ea}, "bending_stiffness": {ei}, "mass_per_length": {rho}}},
            "effects": {{"gravity": 9.81, "contact": "frictionless"}}, "analysis": "static"}}"#
    ))
    .unwrap()
}

/// The FE and BVP summaries, and the FE run's stated warnings (docs/fem-rod.md §10).
fn both(scene: &Scene, elements: usize) -> (Summary, Summary, Vec<String>) {
    let mut opts = BvpRunOptions::from_scene(scene).unwrap();
    opts.method = BvpMethod::Collocation;
    opts.tolerance = 1e-8;
    let bvp = bvp::scene::solve_scene(scene, &opts).unwrap_or_else(|e| panic!("{}: BVP {e}", scene.name)).summary;
    let fo = fem::FemOptions { elements, ..fem::FemOptions::from_scene(scene, "rod-simpson") };
    let run = fem::solve_scene(scene, &fo).unwrap_or_else(|e| panic!("{}: FE {e}", scene.name));
    println!("{}: {} Newton iterations, {:.2} s", scene.name, run.stats.newton_iterations, run.stats.wall_seconds);
    (run.summary, bvp, run.notes)
}

/// Asserts |fe − bvp| ≤ bound (relative to |bvp| if `relative`) for each quantity.
const HEIGHTS: &[&str] = &["y_upper_mid", "y_lower_mid"];
const FORCES: &[&str] = &["tension_upper_mid", "tension_lower_mid", "moment_upper_mid", "moment_lower_mid"];
const DRIVEN_EDGES: &[&str] = &["driven.contact_start", "driven.contact_end"];
const DRIVEN_EDGE_FORCES: &[&str] = &["driven.edge_force_start", "driven.edge_force_end"];

/// `limits`: (quantities, bound, relative?) — each quantity's FE−BVP difference, relative
/// to the BVP value or absolute, within the bound.
fn check(name: &str, fe: &Summary, bvp: &Summary, limits: &[(&[&str], f64, bool)]) {
    for (q, bound, relative) in limits.iter().flat_map(|&(qs, b, r)| qs.iter().map(move |&q| (q, b, r))) {
        let (a, b) = (fe.get(q).unwrap(), bvp.get(q).unwrap());
        let e = if relative { (a - b).abs() / b.abs() } else { (a - b).abs() };
        println!("{name} {q:<26} FE {a:+.9e} BVP {b:+.9e} error {e:.3e} (bound {bound:.1e}{})", if relative { " rel." } else { "" });
        assert!(e.is_finite() && e <= bound, "{name} {q}: FE {a} BVP {b}, error {e:.3e} > {bound:.1e}");
    }
    for v in fe.scalars() {
        assert!(v.1.is_finite(), "{name}: {} = {}", v.0, v.1);
    }
}

/// Measured at 256 elements: heights 2.4e-6 / 2.7e-6 m, tensions 6.3e-5 / 8.1e-5
/// relative, contact angles ≤ 1.1e-2 rad (the edge, located by the moment condition, is
/// found only to a fraction of an element when the layer is 6× thinner than the element:
/// one span element spans 0.07 rad of the pulley); edge forces 0.014–0.025 N against
/// the BVP's 0.012–0.016 N (unresolved layer).
#[test]
fn small_bending_stiffness_below_the_element_size() {
    let s = scene("rod-small-ei", 0.08, 0.45, 1.41, 2e4, 1e-6, 0.12);
    let (fe, bvp, notes) = both(&s, 256);
    // h/ℓ_b ≈ 6 at the edges: a stated warning, never a clean result (docs/fem-rod.md §10);
    // the edges the fit cannot place within such a layer (it moves them by 3e-5 m after its
    // 20 passes, measured) are stated too, since the fit's non-convergence is
    assert!(notes.iter().any(|n| n.contains("unresolved bending layer")), "{notes:?}");
    assert!(notes.iter().all(|n| n.contains("unresolved bending layer") || n.contains("contact fitting did not converge")), "{notes:?}");
    let angles: &[&str] = &["driver.contact_start", "driver.contact_end", "driven.contact_start", "driven.contact_end"];
    check("small EI", &fe, &bvp, &[(&["y_upper_mid", "y_lower_mid"], 1e-5, false), (&["tension_upper_mid", "tension_lower_mid"], 2e-4, true), (angles, 3e-2, false)]);
    // unresolved edge forces: finite and below 5 % of the weight ρ g H of a span
    for q in ["driver.edge_force_start", "driver.edge_force_end", "driven.edge_force_start", "driven.edge_force_end"] {
        let f = fe.get(q).unwrap();
        assert!(f.is_finite() && f.abs() < 0.05 * 0.12 * 9.81 * 0.45 * 10.0, "{q} = {f}");
    }
}

/// Measured at 256 elements: tensions 8.8e-4 relative (0.62 N of 697 N: path length
/// sensitivity EA/L), heights 2.7e-6 / 6.3e-6 m, moments 8.9e-4 relative, edge forces
/// 1.3–1.5 %, angles ≤ 2.8e-3 rad.
#[test]
fn steel_belt_of_paper_a() {
    let (r, h) = (0.25, 2.0);
    let lg = 2.0 * h + 2.0 * std::f64::consts::PI * r;
    let s = scene("rod-steel", r, h, lg * (1.0 + 1e-4), 2e7, 1.75, 0.748);
    let (fe, bvp, notes) = both(&s, 256);
    assert!(notes.is_empty(), "{notes:?}");
    check("steel", &fe, &bvp, &[(HEIGHTS, 1e-5, false), (FORCES, 3e-3, true), (DRIVEN_EDGES, 1e-2, false), (DRIVEN_EDGE_FORCES, 5e-2, true)]);
}

/// Measured at 128 elements: heights ≤ 1.6e-6 m, tensions ≤ 9.4e-5 relative, moments
/// 1.2e-4 relative, edge forces 0.3–1.0 %, angles ≤ 5.3e-3 rad.
#[test]
fn very_slack_loop() {
    let s = scene("rod-very-slack", 0.08, 0.45, 1.613, 2e4, 1e-3, 0.12);
    let (fe, bvp, notes) = both(&s, 128);
    assert!(notes.is_empty(), "{notes:?}");
    check("very slack", &fe, &bvp, &[(HEIGHTS, 1e-5, false), (FORCES, 5e-4, true), (DRIVEN_EDGES, 1.5e-2, false), (DRIVEN_EDGE_FORCES, 3e-2, true)]);
    assert!(fe.get("y_upper_mid").unwrap() > fe.get("y_lower_mid").unwrap());
}

/// The CLI's side of docs/fem-rod.md §10: the issue's coarse reproducer (7 elements)
/// exits 2 naming the compressive edge force and the elements needed; an admissible but
/// unresolved mesh (32 elements, h/ℓ_b = 2.4) exits 0 with a printed warning.
#[test]
fn cli_refuses_inadmissible_and_warns_on_unresolved_rod_meshes() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/rod-hanging.json");
    let run = |elements: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_beltcheck"))
            .args(["solve", scene, "--method", "fem", "--formulation", "rod-simpson", "--elements", elements])
            .output()
            .unwrap()
    };
    let coarse = run("7");
    let err = String::from_utf8_lossy(&coarse.stderr);
    assert_eq!(coarse.status.code(), Some(2), "{err}");
    assert!(err.contains("inadmissible contact") && err.contains("edge force") && err.contains("use at least"), "{err}");
    let unresolved = run("32");
    let out = String::from_utf8_lossy(&unresolved.stdout);
    assert_eq!(unresolved.status.code(), Some(0), "{}", String::from_utf8_lossy(&unresolved.stderr));
    assert!(out.contains("warning: unresolved bending layer"), "{out}");
}
