//! The report's force figure of a shear-deformable (Cosserat) rod: its contact pressure
//! p(σ) with the finite edge peaks and its shear strain Γ₂(σ) (issue 13, "Outputs":
//! "Reports plot the pressure with its edge peaks and the shear strain").
//!
//! Source: the Cosserat rod replaces the Kirchhoff rod's concentrated edge forces by a
//! finite pressure peak of width √(a/b₂) at each contact edge (§3, §6.3 of the reference;
//! spec cosserat-and-shell.md §1–§2). What is proved here:
//! - the harness samples a Cosserat view on a σ grid refined at the contact edges
//!   (`verification::run::EdgeDetail`): finite p and Γ₂, the sampled maximum of p at an
//!   edge and equal there to the BVP's summary edge pressure, far above mid-arc;
//! - the force figure of `cosserat-hanging` (static) and `cosserat-pulley` (one pulley,
//!   open contour) has the pressure, edge close-up and shear-strain panels;
//! - the figures of the string and Kirchhoff scenes keep their panel count (no empty
//!   pressure or shear-strain panel).
//!
//! Run in release mode (`cargo test --release --test report_cosserat`): the studies solve
//! BVPs (and one FE mesh of the Cosserat loop, whose view gives Γ₂ as well).

use std::path::Path;

use drive::scene::Scene;
use drive::view::ContactState;
use verification::plot;
use verification::run::EdgeDetail;
use verification::study::{Study, StudyPlan};

fn catalogue_scene(name: &str) -> Scene {
    Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes").join(format!("{name}.json"))).unwrap()
}

/// A quick study of a catalogue scene: the BVP at 1e-6 and the FE formulations `fe` at
/// `meshes` elements, against the usual gauss6 reference.
fn study(scene: &Scene, fe: &[&str], meshes: &[usize]) -> Study {
    let names: Vec<String> = fe.iter().map(|s| s.to_string()).collect();
    let plan = StudyPlan::convergence(scene).with_tolerances(&[1e-6]).with_formulations(&names).with_meshes(meshes);
    Study::run(scene, &plan, &mut |_| {}).unwrap()
}

/// Panels of a force figure: each is 420 px high (`plot::force_svg`).
fn panel_count(svg: &str) -> u32 {
    let head = &svg[..svg.find('>').unwrap()];
    let h = head.split("height=\"").nth(1).unwrap();
    let h: u32 = h[..h.find('"').unwrap()].parse().unwrap();
    assert_eq!(h % 420, 0, "{head}");
    h / 420
}

/// The pressure at the middle of the contact zone that starts at the edge `edge`: the
/// refined sample nearest to σ_edge + w/2, w the zone's length along σ.
fn mid_zone_pressure(d: &EdgeDetail, edge: f64, next: f64) -> f64 {
    let mid = 0.5 * (edge + next);
    let k = d.sigma.partition_point(|&s| s < mid);
    d.pressure[k]
}

/// The static Cosserat loop: p and Γ₂ sampled finite on the refined grid, the peak of p at
/// a contact edge, at least 5× the mid-arc pressure (measured: 620 N/m against 25 N/m, a
/// factor 25; the tolerance 5 leaves room for any b₂ of the catalogue's order), equal
/// there to the summary's edge pressure (per unit unstretched length; the view gives it
/// per unit contour length, p/λ with λ − 1 = N/b₁ ≈ 1e-4: hence 1e-3); the figure has
/// the pressure, close-up and shear-strain panels, FE overlaid.
#[test]
fn cosserat_hanging_figure_shows_the_edge_peaks_and_the_shear_strain() {
    let scene = catalogue_scene("cosserat-hanging");
    let study = study(&scene, &["cosserat-gauss"], &[128]);
    let reference = study.reference.data().expect("reference solved");
    let s = &reference.samples;
    assert_eq!(s.len(), 2048, "the uniform grid is unchanged");
    let d = s.edges.as_ref().expect("a Cosserat view has the refined edge samples");
    assert_eq!(d.edges.len(), 4, "two contact edges per pulley: {:?}", d.edges);
    assert!(d.sigma.len() > s.len() + 4 * 100, "{} refined samples", d.sigma.len());
    assert!(d.sigma.windows(2).all(|w| w[0] < w[1]), "σ increasing");
    assert!(d.pressure.iter().chain(&d.shear_strain).all(|v| v.is_finite()));
    assert!(d.pressure.iter().all(|&p| p >= 0.0));
    // The shear layer √(a/b₂) = 2.24 mm; the finest refined sample sits within 1e-9 m of
    // an edge.
    let layer = (scene.belt.bending_stiffness.unwrap() / scene.belt.shear_stiffness.unwrap()).sqrt();
    for &e in &d.edges {
        let nearest = d.sigma.iter().filter(|&&x| x != e).map(|&x| (x - e).abs()).fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-9, "edge {e}: nearest other sample {nearest:e} m away");
    }
    // Peak at an edge.
    let (kmax, pmax) = d.pressure.iter().copied().enumerate().fold((0, 0.0), |m, (k, p)| if p > m.1 { (k, p) } else { m });
    let at = d.sigma[kmax];
    let from_edge = d.edges.iter().map(|&e| (e - at).abs()).fold(f64::INFINITY, f64::min);
    assert!(from_edge < 0.1 * layer, "max p = {pmax} at σ = {at}, {from_edge:e} m from the nearest edge");
    // Mid-arc pressures: the driven zone runs from edges[0] to edges[1], the driver's from
    // edges[2] to edges[3].
    for (a, b) in [(d.edges[0], d.edges[1]), (d.edges[2], d.edges[3])] {
        assert_eq!(d.state[d.sigma.partition_point(|&x| x < 0.5 * (a + b))], ContactState::Contact);
        let mid = mid_zone_pressure(d, a, b);
        assert!(mid > 0.0 && pmax >= 5.0 * mid, "max p {pmax} vs mid-arc {mid}");
    }
    // The summary's edge pressures are the values at the edges.
    let summary = &reference.summary;
    let mut expected: Vec<f64> = [&summary.driver, &summary.driven]
        .iter()
        .flat_map(|p| {
            let p = p.as_ref().unwrap();
            [p.edge_pressure_start.unwrap(), p.edge_pressure_end.unwrap()]
        })
        .collect();
    let mut at_edges: Vec<f64> = d.edges.iter().map(|&e| d.pressure[d.sigma.partition_point(|&x| x < e)]).collect();
    expected.sort_by(f64::total_cmp);
    at_edges.sort_by(f64::total_cmp);
    for (p, q) in at_edges.iter().zip(&expected) {
        assert!((p - q).abs() <= 1e-3 * q, "edge pressure {p} vs summary {q}");
    }
    assert!((pmax - expected[3]).abs() <= 1e-3 * expected[3], "max {pmax} vs the largest summary edge pressure {}", expected[3]);
    // Γ₂ = Q/b₂: of the order of the edge shear (Q ~ p·√(a/b₂) ≈ 1.4 N → Γ₂ ~ 1e-3).
    let gmax = d.shear_strain.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    assert!(gmax > 1e-4 && gmax < 1e-2, "max |Γ₂| = {gmax}");

    let svg = plot::force_svg(&scene, &study).unwrap();
    // N, M, p, the edge close-ups, Γ₂, |N − N_ref|
    assert_eq!(panel_count(&svg), 6);
    for needle in ["contact pressure along σ: finite edge peaks", "p(σ) at each contact edge", "shear strain Γ₂", "fem cosserat-gauss (128 el.)"] {
        assert!(svg.contains(needle), "force.svg lacks {needle:?}");
    }
    // The FE Cosserat view has Γ₂ too: its run is refined at its own contact edges, with
    // finite p and Γ₂; its largest |Γ₂| (at the edges) within 20 % of the BVP's at 128
    // elements (measured 1.388e-3 against 1.330e-3, 4.4 %: the edge layer spans a few
    // graded elements there; 20 % leaves room for the penalty layer's shift of the edge).
    let fe = study.series.iter().find(|x| x.method == "fem cosserat-gauss").unwrap();
    let fd = fe.rows.last().unwrap().run.data().expect("FE at 128 elements solved");
    let fe_d = fd.samples.edges.as_ref().expect("the FE view has a shear strain");
    assert_eq!(fe_d.edges.len(), 4, "{:?}", fe_d.edges);
    assert!(fe_d.pressure.iter().chain(&fe_d.shear_strain).all(|v| v.is_finite()));
    let fe_gmax = fe_d.shear_strain.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    assert!((fe_gmax - gmax).abs() <= 0.2 * gmax, "FE max |Γ₂| {fe_gmax} vs BVP {gmax}");
}

/// The one-pulley Cosserat belt (open contour 2D + πR = 1.314 m): the refined samples span
/// the whole contour, the peak of p sits at a contact edge, and the figure has the
/// pressure, close-up, shear-strain and friction panels.
#[test]
fn cosserat_pulley_figure_shows_the_edge_peaks_on_the_open_contour() {
    let scene = catalogue_scene("cosserat-pulley");
    let study = study(&scene, &[], &[]);
    let s = &study.reference.data().expect("reference solved").samples;
    let d = s.edges.as_ref().expect("refined edge samples");
    let l = scene.path().length();
    assert!((d.sigma[d.sigma.len() - 1] - l).abs() < 1e-12 && d.sigma[0] == 0.0, "σ from 0 to {l}");
    // free → stick → slip → free
    assert_eq!(d.edges.len(), 3, "{:?}", d.edges);
    let (kmax, pmax) = d.pressure.iter().copied().enumerate().fold((0, 0.0), |m, (k, p)| if p > m.1 { (k, p) } else { m });
    let from_edge = d.edges.iter().map(|&e| (e - d.sigma[kmax]).abs()).fold(f64::INFINITY, f64::min);
    assert!(from_edge < 1e-6, "max p {pmax} is {from_edge:e} m from an edge");
    let mid = mid_zone_pressure(d, d.edges[0], d.edges[2]);
    assert!(pmax >= 5.0 * mid, "max p {pmax} vs mid-contact {mid}");
    let svg = plot::force_svg(&scene, &study).unwrap();
    // N, M, p, close-ups, Γ₂, f_t, |N − N_ref|
    assert_eq!(panel_count(&svg), 7);
    assert!(svg.contains("shear strain Γ₂") && svg.contains("p(σ) at each contact edge"));
}

/// The other models keep their figures: no refined samples, no pressure panel for a
/// static string or Kirchhoff rod (the rod's edge forces are concentrated), pressure and
/// friction for the string drive — 2, 3 and 4 panels as before.
#[test]
fn string_and_rod_figures_keep_their_panels() {
    for (name, panels) in [("string-hanging-steel", 2), ("rod-hanging", 3), ("string-drive", 4)] {
        let scene = catalogue_scene(name);
        let study = study(&scene, &[], &[]);
        let s = &study.reference.data().expect("reference solved").samples;
        assert!(s.edges.is_none(), "{name}: no shear strain, no refined samples");
        let svg = plot::force_svg(&scene, &study).unwrap();
        assert_eq!(panel_count(&svg), panels, "{name}");
        assert!(!svg.contains("shear strain"), "{name}");
        assert_eq!(svg.contains("contact pressure"), name == "string-drive", "{name}");
    }
}
