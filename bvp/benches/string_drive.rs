//! Criterion benchmarks: the steady `string-drive` BVP (homotopy from the tight loop at
//! rest included) for the catalogue scene (scenes/string-drive.json) and the Exudyn peer
//! (scenes/string-drive-exudyn.json), by collocation (order 6) and shooting at 1e-6 and
//! 1e-10; and the gravity-free closed form (belt-creep theory, one Brent root).

mod common;

use bvp::belt::BvpMethod;
use bvp::collocation::Scheme;
use bvp::scene::string_drive_data;
use bvp::string_drive::{solve, StringDrive};
use bvp::string_hanging::StringHanging;
use criterion::{criterion_group, criterion_main, Criterion};
use drive::scene::{Contact, Scene};
use std::hint::black_box;
use std::path::Path;

/// The steady string drive of `scenes/{name}.json`, read through the scene contract and
/// mapped as a `report` run maps it ([`string_drive_data`]).
fn from_catalogue(name: &str) -> StringDrive {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(format!("{name}.json"));
    let scene = Scene::from_path(&path).expect("catalogue scene reads");
    let Contact::Coulomb(mu) = scene.effects.contact else { panic!("{name}: a Coulomb scene") };
    string_drive_data(&scene, mu)
}

fn bench(c: &mut Criterion) {
    let mut g = common::group(c, "string_drive");
    let methods = [("gauss6", BvpMethod::Collocation, Scheme::Gauss6), ("shooting", BvpMethod::Shooting, Scheme::default())];
    let catalogue = from_catalogue("string-drive");
    for (scene, data) in [("catalogue", catalogue), ("exudyn", from_catalogue("string-drive-exudyn"))] {
        common::bench_methods(&mut g, &format!("{scene}/"), &data, &methods, &[1e-6, 1e-10], solve);
    }
    let creep = StringDrive { belt: StringHanging { gravity: 0.0, ..catalogue.belt }, ..catalogue }.creep_data();
    g.bench_function("closed_form/belt_creep", |b| b.iter(|| black_box(&creep).solve().expect("solves")));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
