//! Criterion benchmarks: the `cosserat-drive` BVP of the catalogue scene
//! (scenes/cosserat-drive.json, issue 14's target ≤ 0.5 s at 1e-8) from its file data —
//! string-drive start, Cosserat guess, path and final solve — by collocation (gauss6) and
//! shooting at the scene's tolerance 1e-8, and its first stage alone (the string drive
//! of the same scene, the homotopy start).

mod common;

use bvp::belt::{BeltOptions, BvpMethod};
use bvp::collocation::Scheme;
use bvp::cosserat_drive::{self, solve, CosseratDrive};
use criterion::{criterion_group, criterion_main, Criterion};
use drive::scene::Scene;
use std::hint::black_box;
use std::path::Path;

fn bench(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cosserat-drive.json");
    let scene = Scene::from_path(&path).expect("catalogue scene reads");
    let data = CosseratDrive::from_scene(&scene).expect("a Cosserat drive scene");
    let mut g = common::group(c, "cosserat_drive");
    let methods = [("gauss6", BvpMethod::Collocation, Scheme::Gauss6), ("shooting", BvpMethod::Shooting, Scheme::default())];
    common::bench_methods(&mut g, "catalogue/", &data, &methods, &[1e-8], solve);
    let opts = BeltOptions::default();
    g.bench_function("catalogue/string_start", |b| {
        b.iter(|| cosserat_drive::string_start(black_box(&data), &opts).expect("solves"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
