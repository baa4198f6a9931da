//! Solve a scene file by MEL finite elements and print the summary and the work.
//!
//! `cargo run --release -p fem --example solve -- scenes/string-hanging.json [elements] [formulation] [penalty]`
//!
//! Solver settings for experiments, from the environment: `FEM_FITS=n` (0: no contact
//! fitting, else at most n passes), `FEM_KAPPA=κ` (default penalty factor),
//! `FEM_TOL=t` (Newton update tolerance), `FEM_NOFIT=1` (no contact fitting).

use std::path::Path;


fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map(String::as_str).unwrap_or("scenes/string-hanging.json");
    let scene = match drive::Scene::from_path(Path::new(path)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let mut opts = fem::FemOptions::from_scene(&scene, fem::default_formulation());
    if let Some(n) = args.get(2).and_then(|a| a.parse().ok()) {
        opts.elements = n;
    }
    if let Some(f) = args.get(3) {
        opts.formulation = f.clone();
    }
    if let Some(p) = args.get(4).and_then(|a| a.parse().ok()) {
        opts.penalty = Some(p);
    }
    let mut settings = fem::SolverSettings::default();
    if let Ok(v) = std::env::var("FEM_FITS") {
        let m: usize = v.parse().unwrap_or(0);
        settings.contact_fitting = m > 0;
        settings.max_fits = m.max(1);
    }
    if let Ok(v) = std::env::var("FEM_TOL") {
        settings.update_tolerance = v.parse().unwrap_or(1e-10);
    }
    if let Ok(v) = std::env::var("FEM_NOFIT") {
        settings.contact_fitting = v != "1";
    }
    if let Ok(v) = std::env::var("FEM_KAPPA") {
        settings.penalty_factor = v.parse().unwrap_or(1e4);
    }
    match fem::solve_scene_with(&scene, &opts, &settings) {
        Ok(run) => {
            for (name, v) in run.summary.scalars() {
                let shown = if name.contains("contact") { v.to_degrees() } else { v };
                println!("{name:<24} {shown:>18.10}");
            }
            for t in &run.terms {
                println!("term: {t}");
            }
            let s = &run.stats;
            println!(
                "{} elements, {} unknowns, {} homotopy steps, {} Newton iterations, {:.3} s",
                s.elements, s.unknowns, s.homotopy_steps, s.newton_iterations, s.wall_seconds
            );
            println!("options: {}", run.options);
            let _ = run.view.path();
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
