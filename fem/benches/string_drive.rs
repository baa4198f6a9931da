//! Criterion benchmarks of the friction drive by MEL finite elements
//! (docs/fem-drive.md §10): wall time of a whole `string_drive::solve` — static start,
//! quasistatic transient with the augmented Lagrangian, to the steady state — against
//! the number of elements and the time step, on the weightless creep scene
//! (`fem/tests/scenes/drive-creep.json`) and on the Exudyn parameter set
//! (`fem/tests/scenes/drive-exudyn.json`, gravity and inertia).
//!
//! - `to_steady/creep/N`: N = 32, 64, 128 elements, default Δt (one arc element of
//!   driver rotation per step, so the step count grows like N);
//! - `to_steady/creep_dt/k`: 64 elements with Δt = k × default, k = ½, 1, 2;
//! - `to_steady/exudyn/N`: N = 64 (128 elements take ≈ 24 s, measured once by
//!   `--example drive`, docs/fem-drive.md §10).
//!
//! The direct steady solve (docs/fem-drive.md §12), `direct_steady/…`: static start,
//! load continuation, fitting passes — the whole `steady::solve`:
//! - `direct_steady/creep/N`: N = 64 … 512;
//! - `direct_steady/string-drive/N`: the catalogue scene (gravity, inertia), N = 32 … 256;
//! - `direct_steady/slack/N`: the very slack belt with gravity, N = 128, 256.
//!
//! The catalogue scenes of the performance targets (issues 13, 14, 17;
//! docs/performance.md "Direct steady FE"), `steady_targets/…`, through
//! [`fem::solve_problem`] as the CLI runs them:
//! - `steady_targets/cosserat-pulley/N`: the open one-pulley layout, N = 128, 512;
//! - `steady_targets/cosserat-drive/N`: semismooth scheme, N = 128, 256;
//! - `steady_targets/cosserat-drive-paper-d/128`: Paper D's scheme;
//! - `steady_targets/string-drive-exudyn/N`: N = 128, 512;
//! - `steady_targets/exudyn-iteration/N` and `steady_targets/exudyn-lu/N`, N = 128, 512:
//!   one Newton iteration of the steady equations with the Exudyn scene's parameters —
//!   the Jacobian pass (F and the generalised Jacobian), the bordered LU solve and one
//!   residual-only pass at the new iterate (a full step's trial) — against one bordered
//!   LU solve of the same matrix alone (the numeric sparse LU of the inner block, its
//!   three triangular solves and the 2 × 2 Schur complement): the ratio of issue 17
//!   (target ≤ 3). The state is the static start with c, ω₂ guessed and zero
//!   tractions, as in `--example steady_cost`; the cost of a pass does not depend on it.
//!
//! Run: `cargo bench -p fem --bench string_drive`. Sample size 10.

use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use drive::Scene;
use fem::string_drive::{self, DriveSettings};
use fem::assembly::Assembler;
use fem::kinematics::TermParams;
use fem::linear::BorderedLu;
use fem::mesh::Mesh;
use fem::problem::{BeltSection, Geometry};
use fem::string_drive::steady::{friction_points, Ends, SteadyParams, SteadyProblem};
use fem::{FemOptions, SolverSettings, StringHanging};

fn scene(name: &str) -> Scene {
    Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes").join(name)).unwrap()
}

fn solve(scene: &Scene, elements: usize, ds: &DriveSettings) -> f64 {
    let opts = FemOptions { elements, formulation: fem::default_formulation().into(), penalty: None };
    let kernel = fem::formulation::find(&opts.formulation).unwrap();
    let run = string_drive::solve(&fem::FemProblem::from_scene(scene), &opts, &SolverSettings::default(), ds, kernel).expect("steady state");
    run.summary.driven_speed.unwrap()
}

fn to_steady(c: &mut Criterion) {
    let mut group = c.benchmark_group("to_steady");
    group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(3));
    let creep = scene("drive-creep.json");
    let ds = DriveSettings::from_scene(&creep);
    for n in [32, 64, 128] {
        group.bench_with_input(BenchmarkId::new("creep", n), &n, |b, &n| b.iter(|| solve(&creep, n, &ds)));
    }
    // default Δt at 64 elements: one arc element (π/11) of driver rotation over ω₁
    let dt0 = std::f64::consts::PI / 11.0 / creep.drive.driver_speed;
    for k in [0.5, 1.0, 2.0] {
        let ds = DriveSettings { time_step: Some(k * dt0), ..ds.clone() };
        group.bench_with_input(BenchmarkId::new("creep_dt", k), &k, |b, _| b.iter(|| solve(&creep, 64, &ds)));
    }
    let exudyn = scene("drive-exudyn.json");
    let ds = DriveSettings::from_scene(&exudyn);
    group.bench_with_input(BenchmarkId::new("exudyn", 64), &64, |b, &n| b.iter(|| solve(&exudyn, n, &ds)));
    group.finish();
}

fn solve_direct(scene: &Scene, elements: usize) -> f64 {
    let opts = FemOptions { elements, formulation: fem::default_formulation().into(), penalty: None };
    let kernel = fem::formulation::find(&opts.formulation).unwrap();
    let run = string_drive::steady::solve(&fem::FemProblem::from_scene(scene), &opts, &SolverSettings::default(), &DriveSettings::from_scene(scene), kernel).expect("steady state");
    run.summary.driven_speed.unwrap()
}

fn direct_steady(c: &mut Criterion) {
    let mut group = c.benchmark_group("direct_steady");
    group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(3));
    let creep = scene("drive-creep.json");
    for n in [64, 128, 256, 512] {
        group.bench_with_input(BenchmarkId::new("creep", n), &n, |b, &n| b.iter(|| solve_direct(&creep, n)));
    }
    let catalogue = Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/string-drive.json")).unwrap();
    for n in [32, 64, 128, 256] {
        group.bench_with_input(BenchmarkId::new("string-drive", n), &n, |b, &n| b.iter(|| solve_direct(&catalogue, n)));
    }
    let slack = scene("drive-slack.json");
    for n in [128, 256] {
        group.bench_with_input(BenchmarkId::new("slack", n), &n, |b, &n| b.iter(|| solve_direct(&slack, n)));
    }
    group.finish();
}

/// A catalogue scene's FE solve as the CLI runs it (its formulation, settings and
/// scheme) on `elements`; returns ω of its last pulley to keep the solve.
fn solve_catalogue(scene: &Scene, elements: usize, ds: &DriveSettings) -> f64 {
    let formulation = scene.fem_settings().formulations.first().cloned().unwrap_or_else(|| fem::formulations_for(scene.belt.theory)[0].to_string());
    let opts = FemOptions { elements, ..FemOptions::from_scene(scene, &formulation) };
    let run = fem::solve_problem(&fem::FemProblem::from_scene(scene), &opts, &SolverSettings::default(), ds).expect("steady state");
    run.summary.driven_speed.or(run.summary.pulley_speed).unwrap()
}

fn steady_targets(c: &mut Criterion) {
    let mut group = c.benchmark_group("steady_targets");
    group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(5));
    let catalogue = |name: &str| Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(name)).unwrap();
    for (name, sizes) in [("cosserat-pulley", [128, 512]), ("cosserat-drive", [128, 256]), ("string-drive-exudyn", [128, 512])] {
        let scene = catalogue(&format!("{name}.json"));
        let ds = DriveSettings::from_scene(&scene);
        for n in sizes {
            group.bench_with_input(BenchmarkId::new(name, n), &n, |b, &n| b.iter(|| solve_catalogue(&scene, n, &ds)));
        }
    }
    let drive = catalogue("cosserat-drive.json");
    let ds = DriveSettings { steady_scheme: string_drive::steady::SteadyScheme::PaperD, ..DriveSettings::from_scene(&drive) };
    group.bench_with_input(BenchmarkId::new("cosserat-drive-paper-d", 128), &128, |b, &n| b.iter(|| solve_catalogue(&drive, n, &ds)));
    iteration_vs_lu(&mut group, &catalogue("string-drive-exudyn.json"));
    group.finish();
}

/// `exudyn-iteration/N` against `exudyn-lu/N` (module docs): the steady equations of the
/// scene's string drive on N elements at its static start.
fn iteration_vs_lu(group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>, scene: &Scene) {
    let settings = SolverSettings::default();
    let kernel = fem::formulation::find(fem::default_formulation()).unwrap();
    let (d, b) = (&scene.drive, &scene.belt);
    let (r, ea, rho, g) = (d.pulley_radius, b.axial_stiffness, b.mass_per_length, scene.effects.gravity.unwrap_or(0.0));
    let penalty = settings.penalty_factor * ea / (r * r);
    let geometry = Geometry { radius: r, centre_distance: d.centre_distance };
    let belt = BeltSection { theory: b.theory, length: b.length, axial_stiffness: ea, mass_per_length: rho, bending_stiffness: None, shear_stiffness: None };
    let data = StringHanging { geometry, belt, gravity: Some(g), penalty: Some(penalty) };
    for n in [128, 512] {
        let (start, _, _) = data.solve(Mesh::new(data.contour().unwrap(), n, 1.0).unwrap(), kernel.clone(), &settings).unwrap();
        let asm = Assembler::new(start.mesh().clone(), kernel.clone());
        let points = friction_points(&asm, &[], drive::contour::Direction::Clockwise);
        let params = TermParams { axial_stiffness: ea, weight: Some(g * rho), penalty: Some(penalty), bending_stiffness: None };
        let sp = SteadyParams { mu: 0.5, penalty, kappa: 1e6, radius: r, omega1: d.driver_speed, torque: d.driven_torque, damping: d.driven_damping, inertia: Some(rho), ends: Ends::Loop };
        let prob: SteadyProblem = SteadyProblem { asm: &asm, params, length: b.length, points: &points, sp, strain_rule: kernel.rules().strain };
        let mut x = fem::static_homotopy::transfer(&start, &asm);
        x.extend([0.95 * r * d.driver_speed, d.driver_speed]);
        x.extend(std::iter::repeat_n(0.0, points.len()));
        let (rows, cols) = prob.pattern();
        let mut lu = BorderedLu::banded(&rows, &cols, x.len(), [asm.len(), asm.len() + 1]).unwrap();
        let values = prob.evaluate(&x, true).unwrap().values;
        let mut rhs = vec![1.0; x.len()];
        group.bench_with_input(BenchmarkId::new("exudyn-lu", n), &n, |bch, _| {
            bch.iter(|| {
                rhs.fill(1.0);
                lu.solve(&values, &[], &mut rhs).unwrap();
                rhs[0]
            })
        });
        group.bench_with_input(BenchmarkId::new("exudyn-iteration", n), &n, |bch, _| {
            bch.iter(|| {
                let ev = prob.evaluate(&x, true).unwrap();
                let mut dx: Vec<f64> = ev.residual.iter().map(|v| -v).collect();
                lu.solve(&ev.values, &[], &mut dx).unwrap();
                // the trial at a small fraction of the step keeps it admissible
                let trial: Vec<f64> = x.iter().zip(&dx).map(|(a, b)| a + 1e-6 * b).collect();
                prob.evaluate(&trial, false).map_or(0.0, |t| t.residual[0])
            })
        });
    }
}

criterion_group!(benches, to_steady, direct_steady, steady_targets);
criterion_main!(benches);
