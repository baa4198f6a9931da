//! Criterion benchmarks of the Kirchhoff–Love shell's transient (docs/fem-shell.md §12
//! "Cost", issue 15's "criterion benches of the element and of one step"). The shipped
//! `scenes/shell-runoff.json` (steel belt, camber, the driven drum swivelled — here the
//! steered drum's histories at their final values, reached in the ramp) on
//! n_σ × n_ζ = 32 × 2, 64 × 2, 128 × 2 and 64 × 4 elements, brought through stage (0),
//! the ramp and two steps of rotation, then:
//!
//! - `shell_assembly/n_σxn_ζ`: energy, gradient and Hessian of the whole belt at the last
//!   step's evaluation (all elements in parallel over the cores, then the scatter) —
//!   the element's cost is this over n_σ n_ζ (throughput in elements);
//! - `shell_step/n_σxn_ζ`: one more step of rotation (its Newton iterations: assembly,
//!   numeric factorisation with the symbolic one reused, line search, the history's
//!   advection and commit), each sample moving on in time; the Newton iterations per
//!   step are printed to stderr.
//!
//! Run: `cargo bench -p fem --bench shell`. Sample size 10.

use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use drive::contour::Pulley;
use drive::scene::SteeringDrum;
use fem::shell::runoff::{Runoff, RunoffRun};
use fem::shell::scene::{static_newton, stepping_newton, ShellScene};

const SIZES: [(usize, usize); 4] = [(32, 2), (64, 2), (128, 2), (64, 4)];

/// The CI scene's run at n_σ × n_ζ after the ramp and two steps of rotation.
fn run(n_sigma: usize, n_zeta: usize) -> RunoffRun {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/shell-runoff.json");
    let scene = drive::Scene::from_path(&path).unwrap();
    let data = ShellScene::from_scene(&scene).unwrap();
    // the steered drum and the final values of its histories (reached here in the ramp)
    let last = |h: &[[f64; 2]]| h.last().map_or(0.0, |p| p[1]);
    let (steering, tilt) = data.steering.as_ref().map_or((Pulley::Driven, [0.0; 2]), |s| {
        (if s.drum == SteeringDrum::Driver { Pulley::Driver } else { Pulley::Driven }, [last(&s.tilt_x), last(&s.tilt_y)])
    });
    let solved = data.belt.solve(n_sigma, n_zeta, static_newton()).unwrap();
    let runoff = Runoff {
        shear: data.shear,
        camber: data.camber,
        steering,
        tilt,
        speed: data.speed,
        driven_speed: data.driven_speed,
        ramp_steps: 1,
        step_angle: data.speed * data.run.time_step,
    };
    let mut r = solved.runoff(&runoff, stepping_newton()).unwrap();
    r.ramp().unwrap();
    r.rotate(2).unwrap();
    r
}

fn shell_assembly(c: &mut Criterion) {
    let mut group = c.benchmark_group("shell_assembly");
    group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(2));
    for (ns, nz) in SIZES {
        let r = run(ns, nz);
        group.throughput(Throughput::Elements((ns * nz) as u64));
        group.bench_function(BenchmarkId::from_parameter(format!("{ns}x{nz}")), |b| {
            b.iter(|| r.stepping.assembler().assemble(r.stepping.unknowns(), &r.stepping.step_evaluation()).expect("admissible"))
        });
    }
    group.finish();
}

fn shell_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("shell_step");
    group.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(5));
    for (ns, nz) in SIZES {
        let mut r = run(ns, nz);
        group.throughput(Throughput::Elements((ns * nz) as u64));
        let mut iterations = Vec::new();
        group.bench_function(BenchmarkId::from_parameter(format!("{ns}x{nz}")), |b| {
            b.iter(|| {
                let series = r.rotate(1).expect("the step converges");
                iterations.push(series.channel("newton_iterations").and_then(|c| c.last().copied()).unwrap_or(f64::NAN));
            })
        });
        let mean = iterations.iter().sum::<f64>() / iterations.len().max(1) as f64;
        eprintln!("shell_step/{ns}x{nz}: {} steps, {mean:.2} Newton iterations per step", iterations.len());
    }
    group.finish();
}

criterion_group!(benches, shell_assembly, shell_step);
criterion_main!(benches);
