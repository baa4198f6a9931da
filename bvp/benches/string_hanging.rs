//! Criterion benchmarks: the `string-hanging` BVP solve (homotopy included) at tolerances
//! 1e-6 and 1e-10, by collocation (orders 6 and 8) and by shooting; order 4 only at 1e-6:
//! at 1e-10 its residual (O(h²)) needs more than the 20 000-node cap, which it reports.

mod common;

use bvp::belt::BvpMethod;
use bvp::collocation::Scheme;
use bvp::string_hanging::{solve, StringHanging};
use criterion::{criterion_group, criterion_main, Criterion};

fn scene() -> StringHanging {
    StringHanging { radius: 0.08, centre_distance: 0.45, length: 1.41, axial_stiffness: 2.0e4, mass_per_length: 0.12, gravity: 9.81 }
}

fn bench(c: &mut Criterion) {
    let mut g = common::group(c, "string_hanging");
    let runs = [
        ("gauss4", BvpMethod::Collocation, Scheme::Gauss4, &[1e-6][..]),
        ("gauss6", BvpMethod::Collocation, Scheme::Gauss6, &[1e-6, 1e-10][..]),
        ("gauss8", BvpMethod::Collocation, Scheme::Gauss8, &[1e-6, 1e-10][..]),
        ("shooting", BvpMethod::Shooting, Scheme::default(), &[1e-6, 1e-10][..]),
    ];
    for (name, method, scheme, tols) in runs {
        common::bench_methods(&mut g, "", &scene(), &[(name, method, scheme)], tols, solve);
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
