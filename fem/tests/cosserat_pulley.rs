//! The open one-pulley layout by the FE's direct steady solve (Paper C; issue 13;
//! docs/fem-cosserat.md §12): the catalogue scene `scenes/cosserat-pulley.json` (mode
//! `tensions`: c, N_in, N_out given) through `solve_scene` with `cosserat-gauss` at 64,
//! 128 and 256 elements, held against the BVP (`bvp::cosserat_pulley`, collocation gauss6
//! at tolerance 1e-10, docs/cosserat-pulley.md), with the balances of §12.4.

use drive::Scene;
use fem::{FemOptions, FemRun, SolverSettings};

/// The BVP's summary of the catalogue scene (`beltcheck solve scenes/cosserat-pulley.json
/// --method bvp-collocation --tolerance 1e-10`): ω, y_in, y_out, contact arc, slip arc,
/// torque.
const BVP: [f64; 6] = [20.029306422508085, 0.10342985780441241, -0.1052136618467024, 2.6148197641824757, 1.205833230346616, -0.500004565897267];

fn solve(elements: usize) -> FemRun {
    let scene = Scene::from_json_str(include_str!("../../scenes/cosserat-pulley.json")).unwrap();
    let opts = FemOptions { elements, formulation: "cosserat-gauss".into(), penalty: None };
    fem::solve_scene_with(&scene, &opts, &SolverSettings::default()).unwrap_or_else(|e| panic!("{elements} elements: {e}"))
}

/// Relative errors of (ω, y_in, y_out, contact arc, slip arc, torque) against [`BVP`].
fn errors(r: &FemRun) -> [f64; 6] {
    let s = &r.summary;
    let p = s.pulley.as_ref().expect("pulley summary");
    let fe = [s.pulley_speed.unwrap(), s.y_in.unwrap(), s.y_out.unwrap(), p.contact_arc.unwrap(), p.slip_arc.unwrap(), p.torque.unwrap()];
    std::array::from_fn(|k| ((fe[k] - BVP[k]) / BVP[k]).abs())
}

/// Measured (docs/fem-cosserat.md §12.5, unfitted meshes) and bounded at 2× those: ω
/// 2.0e-5, 2.1e-5, 1.4e-5; y_in 1.7e-4, 2.8e-5, 1.4e-5; y_out 4.4e-4, 1.0e-5, 1.4e-5;
/// contact arc 8.6e-3, 8.0e-3, 1.4e-3; slip arc 4.2e-3, 3.9e-2, 2.2e-2; torque 3.2e-6,
/// 2.1e-7, 8.1e-8. The data at the ends are the natural conditions (C19): N at the end
/// sections to round-off. Power (§12.4): −torque·ω = c(𝓗_in − 𝓗_out) + D to round-off
/// by the ω-row (C21), with D > 0 (slip dissipates). C-6 of spec §2.7: the torque is
/// R(F̃_in − F̃_out) to 1e-4. The pulley drives (N_in > N_out): torque < 0, slip after
/// stick (both arcs > 0.3 rad).
#[test]
fn catalogue_scene_against_the_bvp_and_its_balances() {
    let bounds = [[4e-5, 4e-4, 9e-4, 2e-2, 1e-2, 7e-6], [5e-5, 6e-5, 3e-5, 2e-2, 8e-2, 5e-7], [3e-5, 3e-5, 3e-5, 3e-3, 5e-2, 2e-7]];
    let mut last = [f64::INFINITY; 6];
    for (k, n) in [64, 128, 256].into_iter().enumerate() {
        let r = solve(n);
        let e = errors(&r);
        eprintln!("{n} elements: errors {e:?}, {:.2} s", r.stats.wall_seconds);
        for q in 0..6 {
            assert!(e[q] <= bounds[k][q], "{n} elements, quantity {q}: error {:e} above {:e}", e[q], bounds[k][q]);
        }
        last = e;
        let s = &r.summary;
        assert!((s.tension_in.unwrap() - 15.0).abs() < 1e-9 && (s.tension_out.unwrap() - 10.0).abs() < 1e-9, "end tensions {:?} {:?}", s.tension_in, s.tension_out);
        let o = &r.options["drive"];
        let (pin, pends, d) = (o["power_in"].as_f64().unwrap(), o["power_ends"].as_f64().unwrap(), o["dissipation"].as_f64().unwrap());
        assert!((pin - pends - d).abs() < 1e-12 * pin, "power: −torque·ω {pin} vs c(𝓗_in − 𝓗_out) {pends} + D {d}");
        assert!(d > 0.0, "slip dissipates: D = {d}");
        let p = s.pulley.as_ref().unwrap();
        let (chi, b1) = (0.1 * 2.0 * 2.0, 1e4);
        let ft = |n: f64| n - chi * (1.0 + n / b1);
        let c6 = 0.1 * (ft(10.0) - ft(15.0));
        assert!((p.torque.unwrap() - c6).abs() < 1e-4 * c6.abs(), "C-6: torque {:?} vs R(F̃_in − F̃_out) = {c6}", p.torque);
        assert!(p.torque.unwrap() < 0.0 && p.stick_arc.unwrap() > 0.3 && p.slip_arc.unwrap() > 0.3, "{p:?}");
    }
    // at 256 the spans' quantities and the torque are converged to ≤ 3e-5
    assert!(last[0] < 3e-5 && last[5] < 2e-7);
}
