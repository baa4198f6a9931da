//! Criterion benchmarks of issue 13's BVP target (≤ 0.2 s at tolerance 1e-8 from the scene
//! file): the catalogue scenes `cosserat-hanging` (static loop, string/Kirchhoff start and
//! continuation in a and b₂, docs/cosserat-hanging.md) and `cosserat-pulley` (open
//! one-pulley layout with stick and slip, docs/cosserat-pulley.md) through
//! `bvp::scene::solve_scene` — exactly what `beltcheck solve SCENE` runs, start and
//! homotopy included — by collocation (the scene's scheme, gauss8) and by shooting, at the
//! scenes' tolerance 1e-8; and the one-pulley scene beyond the string's capstan
//! (N_out = 7 N: the φ_B search in mode `transition` before the `tensions` solve,
//! docs/cosserat-pulley.md "Beyond the string's capstan").

mod common;

use bvp::belt::BvpMethod;
use bvp::scene::{solve_scene, BvpRunOptions};
use drive::scene::Scene;
use std::hint::black_box;
use std::path::Path;

fn catalogue(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(name);
    Scene::from_path(&path).expect("catalogue scene reads")
}

fn bench(c: &mut criterion::Criterion) {
    let mut g = common::group(c, "cosserat");
    let mut beyond: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cosserat-pulley.json")).unwrap()).unwrap();
    beyond["drive"]["tension_out"] = 7.0.into();
    let beyond = Scene::from_json_str(&beyond.to_string()).expect("the scene with N_out = 7 N");
    let scenes = [("hanging", catalogue("cosserat-hanging.json")), ("pulley", catalogue("cosserat-pulley.json")), ("pulley-beyond-capstan", beyond)];
    for (name, scene) in &scenes {
        for (method_name, method) in [("collocation", BvpMethod::Collocation), ("shooting", BvpMethod::Shooting)] {
            let opts = BvpRunOptions { method, tolerance: 1e-8, ..BvpRunOptions::from_scene(scene).expect("the scene's bvp block") };
            g.bench_function(format!("{name}/{method_name}/tol=1e-8"), |b| b.iter(|| solve_scene(black_box(scene), &opts).expect("solves")));
        }
    }
    g.finish();
}

criterion::criterion_group!(benches, bench);
criterion::criterion_main!(benches);
