//! Criterion benchmarks: the `rod-hanging` BVP solve (string start and log-EI homotopy
//! included) at tolerances 1e-6 and 1e-10, by collocation (orders 6 and 8) and by
//! shooting — the data of `scenes/rod-hanging.json` (EI = 1e-3 N·m², boundary layer
//! √(EI/T) ≈ 0.027 m) and the thin steel belt of Paper A (EI = 1.75 N·m², EA = 2e7 N).

mod common;

use bvp::belt::BvpMethod;
use bvp::collocation::Scheme;
use bvp::rod_hanging::{solve, RodHanging};
use criterion::{criterion_group, criterion_main, Criterion};

fn catalogue() -> RodHanging {
    RodHanging {
        radius: 0.08,
        centre_distance: 0.45,
        length: 1.41,
        axial_stiffness: 2.0e4,
        bending_stiffness: 1e-3,
        mass_per_length: 0.12,
        gravity: 9.81,
    }
}

/// Paper A's steel belt: L = L_geom (1 + 1e-4).
fn steel() -> RodHanging {
    let (r, h) = (0.25, 2.0);
    RodHanging {
        radius: r,
        centre_distance: h,
        length: (2.0 * h + 2.0 * std::f64::consts::PI * r) * (1.0 + 1e-4),
        axial_stiffness: 2.0e7,
        bending_stiffness: 1.75,
        mass_per_length: 0.748,
        gravity: 9.81,
    }
}

fn bench(c: &mut Criterion) {
    let mut g = common::group(c, "rod_hanging");
    let methods = [
        ("gauss6", BvpMethod::Collocation, Scheme::Gauss6),
        ("gauss8", BvpMethod::Collocation, Scheme::Gauss8),
        ("shooting", BvpMethod::Shooting, Scheme::default()),
    ];
    for (scene_name, data) in [("catalogue", catalogue()), ("steel", steel())] {
        common::bench_methods(&mut g, &format!("{scene_name}/"), &data, &methods, &[1e-6, 1e-10], solve);
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
