//! `rod-hanging` (Paper A, §8.1 of the reference; docs/fem-rod.md) by the MEL Kirchhoff
//! rod elements, from the catalogue scene: the quantities of the summary, the common
//! view (moment, transverse force, pressure), the rod's closed-form properties and work
//! counters. Against the BVP: `tests/fem_vs_bvp.rs` and `tests/fem_rod_hard_cases.rs`
//! in the workspace root.
//!
//! Parameters: R = 0.08 m, H = 0.45 m, L = 1.41 m, EA = 2e4 N, EI = 1e-3 N·m²,
//! ρ = 0.12 kg/m, g = 9.81 m/s²; 128 elements (h = 11 mm on the spans).

mod common;

use common::{run, scene};
use drive::contour::Region;

/// Both rod formulations at 128 elements: every quantity a rod scene produces is present
/// and finite, the four edge forces push (> 0), left–right mirror symmetry of the edge
/// forces and contact angles (1e-4 relative / 1e-4 rad: the edge recovery scans in the
/// direction of σ on a grid that is not mirror-symmetric; measured ≈ 1e-5), the terms assembled
/// include the bending energy, and the Newton work stays bounded (measured 155–175
/// iterations; limit 2× the larger).
#[test]
fn rod_hanging_from_its_scene() {
    let scene = scene("rod-hanging");
    for f in fem::formulations_for(drive::scene::Theory::Kirchhoff) {
        let r = run(&scene, 128, f);
        let s = &r.summary;
        println!("{f}: {} Newton iterations, {} unknowns, terms {:?}", r.stats.newton_iterations, r.stats.unknowns, r.terms);
        assert_eq!(r.stats.unknowns, 4 * 128 - 1, "one shared slope pair per transition");
        assert!(r.terms.iter().any(|t| t.starts_with("bending energy")));
        for q in ["moment_upper_mid", "moment_lower_mid", "driver.edge_force_start", "driver.edge_force_end", "driven.edge_force_start", "driven.edge_force_end"] {
            let v = s.get(q).unwrap_or_else(|| panic!("{f}: {q} missing"));
            assert!(v.is_finite());
        }
        for q in ["driver.edge_force_start", "driver.edge_force_end", "driven.edge_force_start", "driven.edge_force_end"] {
            assert!(s.get(q).unwrap() > 0.0, "{f}: {q} = {}", s.get(q).unwrap());
        }
        let pair = |a: &str, b: &str| (s.get(a).unwrap(), s.get(b).unwrap());
        let (a, b) = pair("driven.edge_force_start", "driver.edge_force_end");
        assert!((a - b).abs() < 1e-4 * a, "{f}: {a} vs {b}");
        let (a, b) = pair("driven.contact_start", "driver.contact_end");
        assert!((std::f64::consts::PI - a - b).abs() < 1e-4, "{f}: mirror angles {a} + {b} ≠ π");
        assert!(r.stats.newton_iterations < 350, "{f}: {} Newton iterations", r.stats.newton_iterations);
        assert!(s.get("moment_upper_mid").unwrap() > 0.0 && s.get("moment_lower_mid").unwrap() < 0.0);
    }
}

/// The rod's closed-form relations on the converged FE solution (`rod-simpson`, 128):
/// (a) on the middle half of each arc M = −EIλ/R (R3): relative deviation ≤ 1e-4
///     (measured 1.4e-5: on a polar element ν ≈ −δ is nearly constant, so the moment is
///     the circle's up to the O(h²) error of ∂²σν);
/// (b) the invariant (R7) E = M²/(2EI) + N + N²/(2EA) − ρ g y is constant on the middle
///     of each free span (|x| ≤ 0.15 m): drift ≤ 3e-5 N, 2e-5 of N (measured 7.3e-6 and
///     9.4e-6 N: the O(h²) error of the recovered axial force);
/// (c) V = 0 at the mid-spans by the left–right symmetry: |V| ≤ 1e-9 N (measured 1e-14);
/// (d) the contact pressure is ≥ 0 everywhere and 0 on the free mid-spans.
#[test]
fn closed_form_relations_of_the_rod() {
    let scene = scene("rod-hanging");
    let r = run(&scene, 128, "rod-simpson");
    let v = r.view.as_ref();
    let c = v.contour().expect("a two-pulley loop");
    let (ea, ei) = (scene.belt.axial_stiffness, scene.belt.bending_stiffness.unwrap());
    let w = scene.belt.mass_per_length * scene.effects.gravity.unwrap();
    let mut worst_m: f64 = 0.0;
    for region in [Region::DrivenArc, Region::DriverArc] {
        let (a, b) = c.region_bounds(region);
        for k in 0..=50 {
            let s = a + (b - a) * (0.25 + 0.5 * k as f64 / 50.0);
            let n = v.axial_force(s);
            let m = v.bending_moment(s).unwrap();
            let expect = -ei * (1.0 + n / ea) / c.radius();
            worst_m = worst_m.max(((m - expect) / expect).abs());
        }
    }
    println!("arc moment: largest relative deviation from −EIλ/R {worst_m:.3e}");
    assert!(worst_m < 1e-4);
    let h = c.centre_distance();
    for (start, label) in [(0.0, "upper"), (h + std::f64::consts::PI * c.radius(), "lower")] {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..=60 {
            let s = start + h * (0.5 - 0.15 / h + 0.3 / h * k as f64 / 60.0);
            let n = v.axial_force(s);
            let m = v.bending_moment(s).unwrap();
            let e = m * m / (2.0 * ei) + n + n * n / (2.0 * ea) - w * v.position(s)[1];
            lo = lo.min(e);
            hi = hi.max(e);
            assert_eq!(v.contact_pressure(s), Some(0.0));
        }
        let shear = v.transverse_force(start + 0.5 * h).unwrap();
        println!("{label} span: invariant drift {:.3e} N, V(mid) = {shear:.3e} N", hi - lo);
        assert!(hi - lo < 3e-5);
        assert!(shear.abs() < 1e-9);
    }
    for k in 0..2000 {
        let s = c.length() * k as f64 / 2000.0;
        assert!(v.contact_pressure(s).unwrap() >= 0.0);
    }
}

/// The two edge-force measures of docs/fem-rod.md §5 agree as the mesh is refined: the
/// statics of the free span (K10, the summary's value) and the penalty pressure
/// integrated over a window of 3 elements on each side of the fitted edge node with the
/// distributed part subtracted (K11, the definition). Measured largest
/// difference over the four edges (`rod-simpson`): 4.4e-2, 1.2e-2, 1.1e-4 N at 128, 256,
/// 512 elements
/// (the window covers 6 elements, a quarter of the arc at 64 elements, and the
/// distributed pressure is extrapolated over it). Asserted: decreasing, and below
/// 1e-3 N (0.2 % of the force) at 512.
#[test]
fn penalty_window_and_span_statics_give_the_same_edge_forces() {
    let scene = scene("rod-hanging");
    let settings = fem::SolverSettings::default();
    let mut last = f64::INFINITY;
    for n in [128, 256, 512] {
        let opts = fem::FemOptions { elements: n, ..fem::FemOptions::from_scene(&scene, "rod-simpson") };
        let data = fem::string_hanging_data(&scene, &opts, &settings).unwrap();
        let mesh = fem::mesh::Mesh::new(data.contour().unwrap(), n, settings.arc_weight).unwrap();
        let (sol, _, _) = data.solve(mesh, fem::formulation::find("rod-simpson").unwrap(), &settings).unwrap();
        let mut worst: f64 = 0.0;
        for pulley in [drive::contour::Pulley::Driven, drive::contour::Pulley::Driver] {
            let z = sol.zone(pulley).unwrap();
            let w_start = sol.window_edge_force(z.sigma_start, 1.0).unwrap();
            let w_end = sol.window_edge_force(z.sigma_end, -1.0).unwrap();
            worst = worst.max((w_start - z.edge_force_start.unwrap()).abs()).max((w_end - z.edge_force_end.unwrap()).abs());
        }
        println!("{n} elements: largest |window − statics| = {worst:.3e} N");
        assert!(worst < last, "{n}: {worst:e} not below {last:e}");
        last = worst;
    }
    assert!(last < 1e-3, "{last:e}");
}
