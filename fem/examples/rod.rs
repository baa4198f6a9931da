//! Solve a rod scene by MEL FE and print the summary and the work, per element count:
//! `cargo run --release -p fem --example rod -- scenes/rod-hanging.json rod-simpson 64 128 256`
//! (optional `ROD_PENALTY=<P in N/m²>` in the environment).
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("scenes/rod-hanging.json", |s| s.as_str());
    let formulation = args.get(2).map_or("rod-simpson", |s| s.as_str());
    let scene = drive::Scene::from_path(std::path::Path::new(path)).expect("scene");
    let meshes: Vec<usize> = if args.len() > 3 { args[3..].iter().map(|s| s.parse().expect("element count")).collect() } else { vec![64, 128, 256] };
    for n in meshes {
        // optional penalty factor P (N/m²) from the environment, e.g. ROD_PENALTY=3.125e10
        let penalty = std::env::var("ROD_PENALTY").ok().and_then(|v| v.parse().ok());
        let opts = fem::FemOptions { elements: n, penalty, ..fem::FemOptions::from_scene(&scene, formulation) };
        match fem::solve_scene(&scene, &opts) {
            Ok(run) => {
                println!("{formulation} N = {n}: {} Newton iterations, {:.3} s", run.stats.newton_iterations, run.stats.wall_seconds);
                let h = &run.options["homotopy"];
                println!("  fitting: {} passes, converged {}, last move {} m", h["fits"], h["fit_converged"], h["fit_last_move"]);
                if let Some(sol) = fem_solution(&scene, &opts) {
                    for pulley in [drive::contour::Pulley::Driven, drive::contour::Pulley::Driver] {
                        if let Some(z) = sol.zone(pulley) {
                            let a = sol.window_edge_force(z.sigma_start, 1.0);
                            let b = sol.window_edge_force(z.sigma_end, -1.0);
                            println!("  {pulley:?} penalty-window edge forces {a:?} {b:?}");
                        }
                    }
                }
                for (k, v) in run.summary.scalars() {
                    println!("  {k:<28} {v:+.12e}");
                }
            }
            Err(e) => println!("{formulation} N = {n}: {e}"),
        }
    }
}

/// The FE solution itself (for the diagnostics only the crate's types carry).
fn fem_solution(scene: &drive::Scene, opts: &fem::FemOptions) -> Option<fem::FemSolution> {
    let settings = fem::SolverSettings::default();
    let data = fem::string_hanging_data(scene, opts, &settings).ok()?;
    let kernel = fem::formulation::find(&opts.formulation)?;
    let mesh = fem::mesh::Mesh::new(data.contour().ok()?, opts.elements, settings.arc_weight).ok()?;
    data.solve(mesh, kernel, &settings).ok().map(|x| x.0)
}
