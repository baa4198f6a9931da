//! Criterion benchmarks: the steady `string-drive` BVP (homotopy from the tight loop at
//! rest included) for the catalogue scene (scenes/string-drive.json) and the Exudyn peer
//! (scenes/string-drive-exudyn.json), by collocation (order 6) and shooting at 1e-6 and
//! 1e-10; and the gravity-free closed form (belt-creep theory, one Brent root).

use bvp::collocation::Scheme;
use bvp::belt::{BeltOptions, BvpMethod};
use bvp::string_hanging::StringHanging;
use bvp::string_drive::{solve, StringDrive};
use criterion::{criterion_group, criterion_main, Criterion};
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Duration;

fn catalogue() -> StringDrive {
    StringDrive {
        belt: StringHanging {
            radius: 0.1,
            centre_distance: 0.5,
            length: 1.6,
            axial_stiffness: 1.0e4,
            mass_per_length: 0.5,
            gravity: 9.81,
        },
        inertia: true,
        friction: 0.4,
        driver_speed: 60.0,
        driven_torque: 10.0,
        driven_damping: 0.05,
    }
}

fn exudyn() -> StringDrive {
    StringDrive {
        belt: StringHanging {
            radius: 0.1,
            centre_distance: 0.1 * PI,
            length: 0.38 * PI,
            axial_stiffness: 7600.0,
            mass_per_length: 0.8288 / 0.95,
            gravity: 9.81,
        },
        inertia: true,
        friction: 0.5,
        driver_speed: 12.0,
        driven_torque: 25.0,
        driven_damping: 2.0,
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("string_drive");
    g.sample_size(10).measurement_time(Duration::from_secs(4)).warm_up_time(Duration::from_millis(500));
    for (scene, data) in [("catalogue", catalogue()), ("exudyn", exudyn())] {
        for (name, method, scheme) in [("gauss6", BvpMethod::Collocation, Scheme::Gauss6), ("shooting", BvpMethod::Shooting, Scheme::default())] {
            for tol in [1e-6, 1e-10] {
                let opts = BeltOptions { method, scheme, tolerance: tol, ..Default::default() };
                g.bench_function(format!("{scene}/{name}/tol={tol:.0e}"), |b| b.iter(|| solve(black_box(&data), &opts).expect("solves")));
            }
        }
    }
    let creep = StringDrive { belt: StringHanging { gravity: 0.0, ..catalogue().belt }, ..catalogue() }.creep_data();
    g.bench_function("closed_form/belt_creep", |b| b.iter(|| black_box(&creep).solve().expect("solves")));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
