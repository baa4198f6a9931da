//! The FE's own contact boundaries (zero crossings of the gap, `FemSolution::contact_zone`)
//! beside the recovered ones of the summary (docs/fem-string.md §10), per mesh.
//!
//! `cargo run --release -p fem --example raw_contact -- scenes/string-hanging.json`

use std::path::Path;

use drive::contour::Pulley;
use fem::mesh::Mesh;
use fem::{FemOptions, SolverSettings};

fn main() {
    let path = std::env::args().nth(1).unwrap_or_else(|| "scenes/string-hanging.json".into());
    let scene = match drive::Scene::from_path(Path::new(&path)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let settings = SolverSettings::default();
    println!("{:>6} {:>10}  {:>14} {:>14}  {:>14} {:>14}  (driven pulley, degrees)", "N", "fitted", "raw start", "raw end", "start", "end");
    for n in [64usize, 128, 256, 512] {
        for fitting in [false, true] {
            let s = SolverSettings { contact_fitting: fitting, ..settings.clone() };
            let opts = FemOptions { elements: n, ..FemOptions::from_scene(&scene, fem::default_formulation()) };
            let data = fem::string_hanging_data(&scene, &opts, &s).expect("a string scene");
            let mesh = Mesh::new(data.contour().expect("contour"), n, s.arc_weight).expect("mesh");
            let kernel = fem::formulation::find(&opts.formulation).expect("registered");
            match data.solve(mesh, kernel, &s) {
                Ok((sol, _, _)) => {
                    let raw = sol.contact_zone(Pulley::Driven).expect("contact");
                    let rec = sol.zone(Pulley::Driven).expect("contact");
                    println!(
                        "{n:>6} {fitting:>10}  {:>14.8} {:>14.8}  {:>14.8} {:>14.8}",
                        raw.angle_start.to_degrees(),
                        raw.angle_end.to_degrees(),
                        rec.angle_start.to_degrees(),
                        rec.angle_end.to_degrees()
                    );
                }
                Err(e) => println!("{n:>6} {fitting:>10}  error: {e}"),
            }
        }
    }
}
