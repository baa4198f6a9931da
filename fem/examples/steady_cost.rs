//! Cost of one Newton iteration of the direct steady solve (docs/fem-drive.md §12)
//! against the number of elements: assembly of F and its Jacobian alone, the sparse LU
//! of the whole Jacobian (dense c- and ω₂-rows: it fills in), and one whole iteration of
//! `steady::newton` (bordered solve: LU of the banded inner block + 2 × 2 Schur
//! complement, and the line search).
//!
//! `cargo run --release -p fem --example steady_cost`

use std::time::Instant;

use fem::assembly::Assembler;
use fem::kinematics::TermParams;
use fem::linear::SparseLu;
use fem::mesh::Mesh;
use fem::string_drive::steady::{friction_points, newton, Ends, SteadyParams, SteadyProblem};
use drive::scene::Theory;
use fem::problem::{BeltSection, Geometry};
use fem::{SolverSettings, StringHanging};

fn main() {
    let settings = SolverSettings::default();
    let kernel = fem::formulation::find(fem::default_formulation()).unwrap();
    let (r, ea) = (0.08, 2.0e4);
    let penalty = settings.penalty_factor * ea / (r * r);
    let geometry = Geometry { radius: r, centre_distance: 0.45 };
    let belt = BeltSection { theory: Theory::String, length: 1.3956749, axial_stiffness: ea, mass_per_length: 0.12, bending_stiffness: None, shear_stiffness: None };
    let data = StringHanging { geometry, belt, gravity: Some(9.81), penalty: Some(penalty) };
    println!("{:>8} {:>9} {:>13} {:>14} {:>20} {:>16}", "elements", "unknowns", "assemble [ms]", "full LU [ms]", "Newton iteration [ms]", "per element [µs]");
    for n in [128, 256, 512, 1024, 2048] {
        let mesh = Mesh::new(data.contour().unwrap(), n, 1.0).unwrap();
        let (start, _, _) = data.solve(mesh, kernel.clone(), &settings).unwrap();
        let asm = Assembler::new(start.mesh().clone(), kernel.clone());
        let points = friction_points(&asm, &[], drive::contour::Direction::Clockwise);
        let params = TermParams { axial_stiffness: ea, weight: Some(9.81 * 0.12), penalty: Some(penalty), bending_stiffness: None };
        let sp = SteadyParams { mu: 0.3, penalty, kappa: 1e6, radius: r, omega1: 10.0, torque: 2.0, damping: 0.0, inertia: Some(0.12), ends: Ends::Loop };
        let prob: SteadyProblem = SteadyProblem { asm: &asm, params, length: 1.3956749, points: &points, sp, strain_rule: kernel.rules().strain };
        let mut x = fem::static_homotopy::transfer(&start, &asm);
        x.extend([0.79, 10.0]);
        x.extend(std::iter::repeat_n(0.0, points.len()));
        let (rows, cols) = prob.pattern();
        let mut lu = SparseLu::new();
        lu.set_pattern(x.len(), &rows, &cols).unwrap();
        let reps = 5;
        let t = Instant::now();
        let mut ev = None;
        for _ in 0..reps {
            ev = prob.evaluate(&x, true);
        }
        let ta = t.elapsed().as_secs_f64() / reps as f64;
        let ev = ev.unwrap();
        let t = Instant::now();
        for _ in 0..reps {
            lu.factorize(&ev.values).unwrap();
        }
        let tl = t.elapsed().as_secs_f64() / reps as f64;
        let w = vec![1.0; x.len()];
        let scales = vec![1.0; x.len()];
        let t = Instant::now();
        for _ in 0..reps {
            let mut xi = x.clone();
            let _ = newton(&prob, &mut xi, &w, &scales, 1e-10, 1);
        }
        let tn = t.elapsed().as_secs_f64() / reps as f64;
        println!("{n:>8} {:>9} {:>13.3} {:>14.3} {:>20.3} {:>16.2}", x.len(), 1e3 * ta, 1e3 * tl, 1e3 * tn, 1e6 * tn / n as f64);
    }
}
