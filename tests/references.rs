//! The references of the harness (issue 11 item 6): a BVP run, a closed form, or
//! Richardson extrapolation of the finest FE runs — each held against the others on the
//! catalogue's `string-hanging` (scenes/string-hanging.json), and each named in the tables.
//!
//! - The elastic catenary loop (verification::closed_form, docs/string-hanging.md (S3),
//!   (S6)) and the BVP (collocation gauss6 at 1e-11) are independent computations of the
//!   same ten summary scalars: they agree to 1e-10 relative, the BVP's own accuracy at that
//!   tolerance (its gauss6 runs agree with each other to 1e-11).
//! - Richardson extrapolation of `string-simpson` over 64, 128, 256 elements (order ≈ 2)
//!   agrees with the BVP reference within its stated error estimate |q_R − q₃| for every
//!   scalar it extrapolates; a scalar whose levels oscillate is refused, not guessed.
//!
//! Run in release mode (`cargo test --release --test references`).

use drive::result::Refinement;
use drive::scene::Scene;
use verification::reference::Reference;
use verification::run::{BvpVariant, Discretisation, Scheme};

mod common;
use common::{beltcheck, stderr, stdout};

fn scene() -> Scene {
    Scene::from_path(std::path::Path::new("scenes/string-hanging.json")).unwrap()
}

fn bvp() -> Reference {
    Reference::Bvp { variant: BvpVariant::Collocation(Scheme::Gauss6), tolerance: 1e-11 }
}

#[test]
fn closed_form_and_bvp_references_agree() {
    let scene = scene();
    let exact = Reference::ClosedForm.compute(&scene, 64, None);
    let reference = bvp().compute(&scene, 64, Some(100_000));
    let (e, b) = (exact.run.data().expect("the catenary loop solves"), reference.run.data().expect("the BVP solves"));
    let (diffs, only) = verification::compare_summaries(&e.summary, &b.summary);
    assert!(only.is_empty(), "produced by one only: {only:?}");
    assert_eq!(diffs.len(), 10, "mid-span heights and forces, three angles per pulley");
    for d in &diffs {
        assert!(d.relative < 1e-10, "{}: closed form {} vs BVP {} (relative {:.2e})", d.name, d.a, d.b, d.relative);
    }
    assert!(exact.run.method.contains("closed form"));
    assert!(e.samples.is_empty(), "a closed form without fields has no samples");
}

#[test]
fn richardson_reference_agrees_with_the_bvp_within_its_estimate() {
    let scene = scene();
    let levels = [64, 128, 256].map(Discretisation::Elements).to_vec();
    let rich = Reference::Richardson { formulation: "string-simpson".into(), levels }.compute(&scene, 512, None);
    let reference = bvp().compute(&scene, 512, Some(100_000));
    let (r, b) = (rich.run.data().expect("the FE levels solve"), reference.run.data().unwrap());
    // work counter: most scalars are in the asymptotic range at these meshes; those that
    // are not are named in the notes and absent from the reference
    assert!(rich.estimates.len() >= 8, "{} extrapolated; notes: {:?}", rich.estimates.len(), rich.notes);
    assert_eq!(rich.estimates.len(), r.summary.scalars().len());
    assert_eq!(rich.notes.iter().filter(|n| n.starts_with("refused")).count(), 10 - rich.estimates.len(), "{:?}", rich.notes);
    for e in &rich.estimates {
        let q = b.summary.get(&e.quantity).unwrap();
        let p = e.order.expect("not converged to round-off at 256 elements");
        assert!((1.0..4.0).contains(&p), "{}: order {p}", e.quantity);
        assert!(e.error_estimate > 0.0 && e.error_estimate < 1e-5 * q.abs().max(1.0), "{}: estimate {:.2e}", e.quantity, e.error_estimate);
        assert!((e.value - q).abs() <= e.error_estimate, "{}: Richardson {} vs BVP {q}: |Δ| = {:.2e} above the estimate {:.2e}", e.quantity, e.value, (e.value - q).abs(), e.error_estimate);
    }
    assert_eq!(r.samples.len(), 512, "the fields are extrapolated too");
}

#[test]
fn two_d_discretisation_prints_and_serialises() {
    let d = Discretisation::Mesh2d { sigma: 64, zeta: 4, time_step: 0.01 };
    assert_eq!(d.to_string(), "64×4 el., Δt 0.01 s");
    assert_eq!(verification::table::fmt_disc(d), "64×4 Δt 1e-2");
    let json = serde_json::to_value(d).unwrap();
    assert_eq!(json, serde_json::json!({"mesh2d": {"sigma": 64, "zeta": 4, "time_step": 0.01}}));
    assert_eq!(serde_json::from_value::<Discretisation>(json).unwrap(), d);
    let fine = Discretisation::Mesh2d { sigma: 128, zeta: 8, time_step: 0.005 };
    assert_eq!(d.refinement_ratio(fine), Some(2.0));
    assert_eq!(d.refinement(fine), Some((Refinement::Together, 2.0)));
    // refined in space only (to the limit in space at that step) or time only (to the
    // time-continuous limit on that mesh)
    assert_eq!(d.refinement(Discretisation::Mesh2d { sigma: 128, zeta: 8, time_step: 0.01 }), Some((Refinement::Mesh, 2.0)));
    assert_eq!(d.refinement(Discretisation::Mesh2d { sigma: 128, zeta: 4, time_step: 0.01 }), Some((Refinement::Mesh, 2.0)));
    assert_eq!(d.refinement(Discretisation::Mesh2d { sigma: 64, zeta: 4, time_step: 0.0025 }), Some((Refinement::Step, 4.0)));
    // n_ζ alone on one σ-mesh at one Δt: the limit across the width (its ratio n_ζ's)
    assert_eq!(d.refinement(Discretisation::Mesh2d { sigma: 64, zeta: 8, time_step: 0.01 }), Some((Refinement::Width, 2.0)));
    assert_eq!(d.refinement(Discretisation::Mesh2d { sigma: 64, zeta: 6, time_step: 0.01 }), Some((Refinement::Width, 1.5)));
    assert_eq!(d.refinement_ratio(Discretisation::Mesh2d { sigma: 64, zeta: 2, time_step: 0.01 }), None);
    let across = |zeta: usize| Discretisation::Mesh2d { sigma: 128, zeta, time_step: 0.01 };
    assert_eq!(verification::study::shell_refinement(&[across(4), across(8), across(16)]), Some(Refinement::Width));
    assert!(verification::study::StudyPlan::shell(vec![across(4), across(8), across(16)]).validate().is_ok());
    assert!(verification::study::shell_level_notes(&[across(4), across(8), across(16)]).iter().any(|n| n.contains("the width alone is refined")));
    // σ and Δt by different ratios, or a step refined while ζ alone changes: none
    assert_eq!(d.refinement_ratio(Discretisation::Mesh2d { sigma: 128, zeta: 4, time_step: 0.0025 }), None);
    assert_eq!(d.refinement_ratio(Discretisation::Mesh2d { sigma: 64, zeta: 8, time_step: 0.005 }), None);
    assert_eq!(d.refinement_ratio(d), None);
    // a study's levels refine in one way throughout
    let at = |sigma: usize, time_step: f64| Discretisation::Mesh2d { sigma, zeta: 4, time_step };
    assert_eq!(verification::study::shell_refinement(&[at(64, 0.01), at(64, 0.005), at(64, 0.0025)]), Some(Refinement::Step));
    assert_eq!(verification::study::shell_refinement(&[at(64, 0.01), at(128, 0.01), at(256, 0.01)]), Some(Refinement::Mesh));
    assert_eq!(verification::study::shell_refinement(&[at(64, 0.01), at(128, 0.005), at(256, 0.0025)]), Some(Refinement::Together));
    let mixed = [at(64, 0.01), at(128, 0.01), at(128, 0.005)];
    assert_eq!(verification::study::shell_refinement(&mixed), None);
    assert!(matches!(verification::study::StudyPlan::shell(mixed.to_vec()).validate(), Err(verification::study::PlanError::ShellLevels(_))));
    assert!(verification::study::StudyPlan::shell(vec![at(64, 0.01), at(64, 0.005), at(64, 0.0025)]).validate().is_ok());
    // σ and Δt refined together at one n_ζ: a sequence of that n_ζ (the study says so)
    assert_eq!(d.refinement_ratio(Discretisation::Mesh2d { sigma: 128, zeta: 4, time_step: 0.005 }), Some(2.0));
    // ζ refined by another ratio than σ and Δt: none
    assert_eq!(d.refinement_ratio(Discretisation::Mesh2d { sigma: 128, zeta: 6, time_step: 0.005 }), None);
    assert_eq!(Discretisation::Elements(64).refinement_ratio(Discretisation::Elements(128)), Some(2.0));
    assert_eq!(Discretisation::Elements(64).refinement_ratio(d), None);
}

#[test]
fn converge_names_the_reference_it_used() {
    let args = ["converge", "scenes/string-hanging.json", "--elements", "64,128,256", "--tolerances", "1e-6", "--formulation", "string-simpson", "--samples", "256"];
    for (kind, shown) in [("bvp", "reference: BVP run bvp-collocation gauss6 at tol 1e-11"), ("closed-form", "reference: closed form (elastic catenary loop)"), ("richardson", "reference: Richardson extrapolation of fem string-simpson (levels 64, 128, 256), finest at 256 el.")] {
        let mut a = args.to_vec();
        a.extend(["--reference", kind]);
        let o = beltcheck(&a);
        assert!(o.status.success(), "{kind}: {}", stderr(&o));
        assert!(stdout(&o).contains(shown), "{kind}: {}", stdout(&o));
    }
    // levels out of the asymptotic range are refused, not extrapolated: at 16, 32, 64
    // elements every scalar's finer difference is the larger one
    let o = beltcheck(&["converge", "scenes/string-hanging.json", "--elements", "16,32,64", "--tolerances", "1e-6", "--formulation", "string-simpson", "--reference", "richardson"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("no summary scalar is in the asymptotic range"), "{}", stderr(&o));
    // a closed form the scene has none of is a failed reference: exit 2
    let o = beltcheck(&["converge", "scenes/rod-hanging.json", "--elements", "16,32", "--tolerances", "1e-6", "--reference", "closed-form"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("elastic catenary"), "{}", stderr(&o));
}
