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
                for (k, v) in run.summary.scalars() {
                    println!("  {k:<28} {v:+.12e}");
                }
            }
            Err(e) => println!("{formulation} N = {n}: {e}"),
        }
    }
}
