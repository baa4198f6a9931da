//! Criterion benchmarks: the `string-hanging` BVP solve (homotopy included) at tolerances
//! 1e-6 and 1e-10, by collocation (orders 6 and 8) and by shooting; order 4 only at 1e-6:
//! at 1e-10 its residual (O(h²)) needs more than the 20 000-node cap, which it reports.

use bvp::collocation::Scheme;
use bvp::belt::{BeltOptions, BvpMethod};
use bvp::string_hanging::{solve, StringHanging};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;

fn scene() -> StringHanging {
    StringHanging { radius: 0.08, centre_distance: 0.45, length: 1.41, axial_stiffness: 2.0e4, mass_per_length: 0.12, gravity: 9.81 }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("string_hanging");
    g.sample_size(10).measurement_time(Duration::from_secs(4)).warm_up_time(Duration::from_millis(500));
    let runs = [
        ("gauss4", BvpMethod::Collocation, Scheme::Gauss4, &[1e-6][..]),
        ("gauss6", BvpMethod::Collocation, Scheme::Gauss6, &[1e-6, 1e-10][..]),
        ("gauss8", BvpMethod::Collocation, Scheme::Gauss8, &[1e-6, 1e-10][..]),
        ("shooting", BvpMethod::Shooting, Scheme::default(), &[1e-6, 1e-10][..]),
    ];
    for (name, method, scheme, tols) in runs {
        for &tol in tols {
            let opts = BeltOptions { method, scheme, tolerance: tol, ..Default::default() };
            g.bench_function(format!("{name}/tol={tol:.0e}"), |b| b.iter(|| solve(black_box(&scene()), &opts).expect("solves")));
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
