//! Criterion benchmarks of the MEL Kirchhoff rod (docs/fem-rod.md §9, "Cost") on
//! `scenes/rod-hanging.json` with `rod-simpson`:
//!
//! - `rod_assembly/N`: energy, gradient and sparse Hessian of the whole loop (element
//!   derivatives by AD over the 8 primary unknowns through the augmented map, in
//!   parallel, + scatter), throughput in elements;
//! - `rod_newton_step/N`: one Newton iteration — assembly, numeric sparse LU (symbolic
//!   LU reused), solve;
//! - `rod_newton_solve/N`: one full Newton solve — the start of the homotopy (η = 0):
//!   from the tight weightless loop (F11), where the arcs' moment −EIλ/R meets straight
//!   spans, to the rod's tight equilibrium with its four transition boundary layers,
//!   symbolic LU included.
//!
//! Run: `cargo bench -p fem --bench rod_hanging`. Sample size 10 to keep the run short.

use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use fem::linear::SparseLu;
use fem::mesh::Mesh;
use fem::{FemOptions, SolverSettings};

const SIZES: [usize; 4] = [64, 256, 1024, 4096];
const FORMULATION: &str = "rod-simpson";

fn problem(elements: usize) -> fem::string_hanging::StartProblem {
    let scene = drive::Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/rod-hanging.json")).unwrap();
    let settings = SolverSettings::default();
    let opts = FemOptions { elements, ..FemOptions::from_scene(&scene, FORMULATION) };
    let data = fem::string_hanging_data(&scene, &opts, &settings).unwrap();
    let mesh = Mesh::new(data.contour().unwrap(), elements, settings.arc_weight).unwrap();
    let kernel = fem::formulation::find(FORMULATION).unwrap();
    data.start_problem(mesh, kernel, &settings, 0.0).unwrap()
}

fn assembly(c: &mut Criterion) {
    let mut group = c.benchmark_group("rod_assembly");
    group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    for n in SIZES {
        let p = problem(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &p, |b, p| {
            b.iter(|| p.assembler.assemble(&p.z, &p.params, p.length).expect("admissible"))
        });
    }
    group.finish();
}

fn newton_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("rod_newton_step");
    group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(1));
    for n in SIZES {
        let p = problem(n);
        let mut lu = SparseLu::new();
        let (rows, cols) = p.assembler.pattern();
        lu.set_pattern(p.assembler.len(), rows, cols).unwrap();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter(|| {
                let a = p.assembler.assemble(&p.z, &p.params, p.length).expect("admissible");
                lu.factorize(&a.values).unwrap();
                let mut step: Vec<f64> = a.gradient.iter().map(|g| -g).collect();
                lu.solve_in_place(&mut step).unwrap();
                step
            })
        });
    }
    group.finish();
}

fn newton_solve(c: &mut Criterion) {
    let mut group = c.benchmark_group("rod_newton_solve");
    group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(3));
    let settings = SolverSettings::default();
    for n in SIZES {
        let iterations = problem(n).newton(&settings).expect("converges").iterations;
        eprintln!("rod_newton_solve/{n}: {iterations} Newton iterations");
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
            b.iter_batched(|| problem(n), |mut p| p.newton(&settings).expect("converges"), criterion::BatchSize::LargeInput)
        });
    }
    group.finish();
}

criterion_group!(benches, assembly, newton_step, newton_solve);
criterion_main!(benches);
