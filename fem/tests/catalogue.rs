//! Every `string-hanging` scene of the catalogue solves from its file alone (issue 3,
//! DESIGN.md "hard cases": slack, very slack L/L_geom = 1.15, steel EA/(ρgH) ≈ 6e6),
//! with 128 elements, and the solution is a plausible hanging belt seen through the
//! common view. Accuracy against the BVP is `tests/fem_vs_bvp.rs`; here: structure,
//! symmetry, signs, consistency of view and summary, and work counters.

mod common;

use std::f64::consts::PI;

use common::*;
use drive::contour::Region;
use drive::view::ContactState;
use fem::FemOptions;

const SCENES: [&str; 4] = ["string-hanging", "string-hanging-slack", "string-hanging-very-slack", "string-hanging-steel"];

fn wrap_pi(a: f64) -> f64 {
    let w = (a + PI).rem_euclid(2.0 * PI) - PI;
    if w <= -PI { w + 2.0 * PI } else { w }
}

#[test]
fn every_string_hanging_scene_solves_from_its_file() {
    for name in SCENES {
        let scene = scene(name);
        let opts = FemOptions { elements: 128, ..FemOptions::from_scene(&scene, fem::default_formulation()) };
        let run = fem::solve_scene(&scene, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
        let s = &run.summary;
        s.check_finite().unwrap();
        let st = &run.stats;
        println!("{name}: {} homotopy steps, {} Newton iterations, {:.3} s; {:?}", st.homotopy_steps, st.newton_iterations, st.wall_seconds, s);
        let r = scene.drive.pulley_radius;

        // present exactly the quantities of a static frictionless string
        let names: Vec<String> = s.scalars().into_iter().map(|(n, _)| n).collect();
        assert_eq!(
            names,
            ["y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid", "driver.contact_arc", "driver.contact_start", "driver.contact_end", "driven.contact_arc", "driven.contact_start", "driven.contact_end"],
            "{name}"
        );
        // a hanging belt: both spans sag, tension positive and larger on the upper span
        // (frictionless invariant: N grows with height)
        let (tu, tl) = (s.tension_upper_mid.unwrap(), s.tension_lower_mid.unwrap());
        assert!(s.y_upper_mid.unwrap() < r && s.y_lower_mid.unwrap() < -r, "{name}");
        assert!(tl > 0.0 && tu > tl, "{name}: {tu} {tl}");
        // left–right symmetry (the mirror x → −x maps a polar angle φ to π − φ and
        // reverses the direction of travel): arcs equal, start ↔ end mirrored
        let (d, n) = (s.driver.as_ref().unwrap(), s.driven.as_ref().unwrap());
        assert!((d.contact_arc.unwrap() - n.contact_arc.unwrap()).abs() < 1e-5, "{name}");
        assert!(wrap_pi(PI - n.contact_end.unwrap() - d.contact_start.unwrap()).abs() < 1e-5, "{name}");
        assert!(wrap_pi(PI - n.contact_start.unwrap() - d.contact_end.unwrap()).abs() < 1e-5, "{name}");
        assert!(d.contact_arc.unwrap() > 0.5 * PI && d.contact_arc.unwrap() < 2.0 * PI, "{name}");
        if name == "string-hanging-very-slack" {
            // a deep lower span carries the slack (the upper span stays nearly tight),
            // not a folded configuration with crossing spans: y ≈ −0.29 m and +0.038 m
            assert!(s.y_lower_mid.unwrap() < -0.25 && s.y_upper_mid.unwrap() > 0.0, "{s:?}");
        }

        // the view agrees with the summary
        let v = run.view.as_ref();
        let c = v.contour().expect("a two-pulley loop");
        // the middle of each arc (polar angle 0 on the driven, π on the driver) is in
        // contact for every scene here
        for region in [Region::DriverArc, Region::DrivenArc] {
            let (a, b) = c.region_bounds(region);
            assert_eq!(v.contact_state(0.5 * (a + b)), ContactState::Contact, "{name} {region:?}");
            assert!(v.contact_pressure(0.5 * (a + b)).unwrap() > 0.0);
        }
        let h = c.centre_distance();
        assert_eq!(v.contact_state(0.5 * h), ContactState::Free, "{name}");
        assert_eq!(v.contact_state(1.5 * h + PI * r), ContactState::Free, "{name}");
        assert!((v.position(0.5 * h)[1] - s.y_upper_mid.unwrap()).abs() < 1e-15);
        assert!((v.axial_force(0.5 * h) - tu).abs() < 1e-12);
        assert!(v.bending_moment(0.3).is_none() && v.transverse_force(0.3).is_none());
        assert_eq!(v.contact_pressure(0.5 * h), Some(0.0));
        // the contact state switches exactly where the summary's boundaries are:
        // count the switches along the loop — two per pulley
        let nsamp = 20000;
        let l = c.length();
        let states: Vec<ContactState> = (0..nsamp).map(|k| v.contact_state(l * k as f64 / nsamp as f64)).collect();
        let switches = (0..nsamp).filter(|&k| states[k] != states[(k + 1) % nsamp]).count();
        assert_eq!(switches, 4, "{name}");
        // material coordinate: increasing with σ, L per loop, s(0) = 0
        let mut prev = v.material_coordinate(0.0);
        assert_eq!(prev, 0.0);
        for k in 1..=1000 {
            let sk = v.material_coordinate(l * k as f64 / 1000.0);
            assert!(sk > prev, "{name}: s not increasing at k = {k}");
            prev = sk;
        }
        assert!((prev - scene.belt.length).abs() < 1e-12, "{name}: s(L_c) = {prev}");

        // the terms of the scene, and nothing else
        assert_eq!(run.terms.len(), 3, "{:?}", run.terms);
        assert!(run.terms[0].starts_with("strain energy (Biot, simpson"));
        assert!(run.terms[1].starts_with("gravity potential"));
        assert!(run.terms[2].starts_with("penalty normal contact"));
        assert!(run.options.get("penalty").and_then(|p| p.as_f64()).is_some_and(|p| p > 0.0));
        // both boundaries of both pulleys recovered from the free spans (not the raw
        // zero crossing of the gap, docs/fem-string.md §10)
        for pulley in ["driver", "driven"] {
            assert_eq!(run.options["contact_boundaries"][pulley]["recovered"], serde_json::json!(true), "{name} {pulley}");
        }
        // work counters within 2× of the values measured when the test was written
        // (homotopy steps / Newton iterations: 30/251, 51/427, 194/1660, 11/102)
        assert!(st.homotopy_steps <= 400 && st.newton_iterations <= 3400, "{name}: {st:?}");
        assert_eq!(st.unknowns, 4 * 128 + 7);
    }
}
