//! Criterion benchmarks of the MEL elements, for the string (docs/fem-string.md §12,
//! "Cost") and the Kirchhoff rod (docs/fem-rod.md §9, "Cost"). Per case, N = 64 … 4096
//! elements, throughput in elements (criterion reports element evaluations per second):
//!
//! - `assembly/N`, `rod_assembly/N`: energy, gradient and sparse Hessian of the whole
//!   loop (element derivatives in parallel + scatter; for the rod by AD through the
//!   augmented map);
//! - `newton_step/N`, `rod_newton_step/N`: one Newton iteration — assembly, numeric
//!   sparse LU (symbolic LU reused), solve;
//! - `newton_solve/N`, `rod_newton_solve/N`: one full Newton solve, symbolic LU
//!   included. String: the first homotopy step from the tight weightless loop (F11) to a
//!   quarter of the weight of `string-hanging` (η = 1/8); its iteration count grows with
//!   N (10, 9, 10, 29 at 64 … 4096): the penalty contact boundaries move by ~3 mm in this
//!   step, and each Newton iteration moves the active set by a few elements. Rod
//!   (`rod-hanging`, `rod-simpson`): the start of the homotopy (η = 0), from the tight
//!   loop, where the arcs' moment −EIλ/R meets straight spans, to the rod's tight
//!   equilibrium with its four transition boundary layers; the iteration count per N is
//!   printed to stderr.
//!
//! Run: `cargo bench -p fem --bench fem`. Sample size 10 to keep the run short.

use std::path::Path;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, Throughput};
use fem::linear::SparseLu;
use fem::mesh::Mesh;
use fem::{FemOptions, SolverSettings};

const SIZES: [usize; 4] = [64, 256, 1024, 4096];

/// One benchmarked model: group-name prefix, scene, formulation, homotopy fraction η of
/// the benchmarked start problem.
struct Case {
    prefix: &'static str,
    scene: &'static str,
    formulation: &'static str,
    eta: f64,
}

const CASES: [Case; 2] = [
    Case { prefix: "", scene: "string-hanging", formulation: "string-simpson", eta: 0.125 },
    Case { prefix: "rod_", scene: "rod-hanging", formulation: "rod-simpson", eta: 0.0 },
];

fn problem(case: &Case, elements: usize) -> fem::static_homotopy::StartProblem {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../scenes/{}.json", case.scene));
    let scene = drive::Scene::from_path(&path).unwrap();
    let settings = SolverSettings::default();
    let opts = FemOptions { elements, ..FemOptions::from_scene(&scene, case.formulation) };
    let data = fem::string_hanging_data(&scene, &opts, &settings).unwrap();
    let mesh = Mesh::new(data.contour().unwrap(), elements, settings.arc_weight).unwrap();
    let kernel = fem::formulation::find(case.formulation).unwrap();
    data.start_problem(mesh, kernel, &settings, case.eta).unwrap()
}

/// One group `{prefix}{name}` per case (10 samples, 0.3 s warm-up, `measurement`), in it
/// `bench(group, case, N)` for every mesh size N with throughput N elements.
fn per_case_and_size(c: &mut Criterion, name: &str, measurement: Duration, mut bench: impl FnMut(&mut BenchmarkGroup<'_, WallTime>, &Case, usize)) {
    for case in &CASES {
        let mut group = c.benchmark_group(format!("{}{name}", case.prefix));
        group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(measurement);
        for n in SIZES {
            group.throughput(Throughput::Elements(n as u64));
            bench(&mut group, case, n);
        }
        group.finish();
    }
}

fn assembly(c: &mut Criterion) {
    per_case_and_size(c, "assembly", Duration::from_secs(1), |group, case, n| {
        let p = problem(case, n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &p, |b, p| {
            b.iter(|| p.assembler.assemble(&p.z, &p.params, p.length).expect("admissible"))
        });
    });
}

fn newton_step(c: &mut Criterion) {
    per_case_and_size(c, "newton_step", Duration::from_secs(1), |group, case, n| {
        let p = problem(case, n);
        let mut lu = SparseLu::new();
        let (rows, cols) = p.assembler.pattern();
        lu.set_pattern(p.assembler.len(), rows, cols).unwrap();
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                let a = p.assembler.assemble(&p.z, &p.params, p.length).expect("admissible");
                lu.factorize(&a.values).unwrap();
                let mut step: Vec<f64> = a.gradient.iter().map(|g| -g).collect();
                lu.solve_in_place(&mut step).unwrap();
                step
            })
        });
    });
}

fn newton_solve(c: &mut Criterion) {
    let settings = SolverSettings::default();
    per_case_and_size(c, "newton_solve", Duration::from_secs(3), |group, case, n| {
        let iterations = problem(case, n).newton(&settings).expect("converges").iterations;
        eprintln!("{}newton_solve/{n}: {iterations} Newton iterations", case.prefix);
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter_batched(|| problem(case, n), |mut p| p.newton(&settings).expect("converges"), criterion::BatchSize::LargeInput)
        });
    });
}

criterion_group!(benches, assembly, newton_step, newton_solve);
criterion_main!(benches);
