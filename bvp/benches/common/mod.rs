//! What the belt benchmarks share: one group setting (10 samples, 4 s measurement,
//! 0.5 s warm-up) and the loop that solves one scene by each method at each tolerance.

use bvp::belt::{BeltOptions, BvpMethod};
use bvp::collocation::Scheme;
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion};
use std::fmt::Debug;
use std::hint::black_box;
use std::time::Duration;

/// The benchmark group `name` with the setting all belt benchmarks use.
pub fn group<'a>(c: &'a mut Criterion, name: &str) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.sample_size(10).measurement_time(Duration::from_secs(4)).warm_up_time(Duration::from_millis(500));
    g
}

/// (Not every benchmark uses it: `cosserat` solves whole scene files.)
#[allow(dead_code)]
/// Benchmarks `solve(data, opts)` for every `(name, method, scheme)` of `methods` at every
/// tolerance of `tols`, as `{prefix}{name}/tol={tol:.0e}`.
pub fn bench_methods<D, S, E: Debug>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    prefix: &str,
    data: &D,
    methods: &[(&str, BvpMethod, Scheme)],
    tols: &[f64],
    solve: impl Fn(&D, &BeltOptions) -> Result<S, E>,
) {
    for &(name, method, scheme) in methods {
        for &tol in tols {
            let opts = BeltOptions { method, scheme, tolerance: tol, ..Default::default() };
            g.bench_function(format!("{prefix}{name}/tol={tol:.0e}"), |b| {
                b.iter(|| solve(black_box(data), &opts).expect("solves"))
            });
        }
    }
}
