//! Cost of one Newton solve (the first homotopy step of `string-hanging`) per mesh:
//! iterations, regularised factorisations, time split assembly / LU.
//!
//! `cargo run --release -p fem --example newton_cost`

use std::path::Path;
use std::time::Instant;

use fem::linear::SparseLu;
use fem::mesh::Mesh;
use fem::{FemOptions, SolverSettings};

fn main() {
    let scene = drive::Scene::from_path(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/string-hanging.json")).expect("scene");
    let settings = SolverSettings::default();
    println!("{:>6} {:>8} {:>5} {:>5} {:>10} {:>10} {:>10} {:>10}", "N", "unknowns", "iter", "reg", "solve [s]", "assem [s]", "LU [s]", "symb [s]");
    for n in std::env::args().skip(1).map(|a| a.parse::<usize>().unwrap()) {
        let opts = FemOptions { elements: n, ..FemOptions::from_scene(&scene, fem::default_formulation()) };
        let data = fem::string_hanging_data(&scene, &opts, &settings).expect("data");
        let mesh = Mesh::new(data.contour().expect("contour"), n, settings.arc_weight).expect("mesh");
        let kernel = fem::formulation::find(fem::default_formulation()).expect("registered");
        let mut p = data.start_problem(mesh, kernel, &settings, 0.125).expect("problem");
        // the parts, timed once each at the start state
        let t = Instant::now();
        let a = p.assembler.assemble(&p.z, &p.params, p.length).expect("admissible");
        let t_assembly = t.elapsed().as_secs_f64();
        let mut lu = SparseLu::new();
        let (rows, cols) = p.assembler.pattern();
        let t = Instant::now();
        lu.set_pattern(p.assembler.len(), rows, cols).expect("pattern");
        let t_symbolic = t.elapsed().as_secs_f64();
        let t = Instant::now();
        lu.factorize(&a.values).expect("LU");
        let t_lu = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let r = p.newton(&settings).expect("converges");
        let t_solve = t.elapsed().as_secs_f64();
        println!("{n:>6} {:>8} {:>5} {:>5} {t_solve:>10.4} {t_assembly:>10.5} {t_lu:>10.5} {t_symbolic:>10.5}", p.assembler.len(), r.iterations, r.regularised);
    }
}
