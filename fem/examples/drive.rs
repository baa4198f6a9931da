//! Run a friction-drive scene by MEL finite elements and print the summary, the
//! history (every k-th step) and the work (docs/fem-drive.md).
//!
//! `cargo run --release -p fem --example drive -- fem/tests/scenes/drive-creep.json [elements] [penalty|al|steady] [time_step] [kappa_t]`
//! (`steady`: the direct steady solve of docs/fem-drive.md §12)

use std::path::Path;

use fem::string_drive::{DriveSettings, FrictionMethod};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map(String::as_str).unwrap_or("fem/tests/scenes/drive-creep.json");
    let scene = drive::Scene::from_path(Path::new(path)).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(2)
    });
    let mut opts = fem::FemOptions::from_scene(&scene, fem::default_formulation());
    if let Some(n) = args.get(2).and_then(|a| a.parse().ok()) {
        opts.elements = n;
    }
    let mut ds = DriveSettings::from_scene(&scene);
    if args.get(3).map(String::as_str) == Some("penalty") {
        ds.friction = FrictionMethod::Penalty;
    }
    if let Some(dt) = args.get(4).and_then(|a| a.parse().ok()) {
        ds.time_step = Some(dt);
    }
    if let Some(k) = args.get(5).and_then(|a| a.parse().ok()) {
        ds.tangential_penalty_factor = k;
    }
    let kernel = fem::formulation::find(&opts.formulation).expect("formulation");
    let steady = args.get(3).map(String::as_str) == Some("steady");
    let t0 = std::time::Instant::now();
    let result = if steady {
        fem::string_drive::steady::solve(&fem::FemProblem::from_scene(&scene), &opts, &fem::SolverSettings::default(), &ds, kernel)
    } else {
        fem::string_drive::solve(&fem::FemProblem::from_scene(&scene), &opts, &fem::SolverSettings::default(), &ds, kernel)
    };
    println!("wall {:.3} s", t0.elapsed().as_secs_f64());
    match result {
        Ok(run) => {
            for (name, v) in run.summary.scalars() {
                let shown = if name.contains("arc") || name.contains("contact_") { v.to_degrees() } else { v };
                println!("{name:<24} {shown:>18.10}");
            }
            if let Some(h) = &run.history {
                let every = (h.len() / 20).max(1);
                println!("{:>6} {:>9} {:>10} {:>10} {:>10} {:>8} {:>8} {:>8} {:>8} {:>9} {:>9}", "step", "t", "omega2", "T_upper", "T_lower", "stick1", "slip1", "stick2", "slip2", "M1", "rate");
                for i in (0..h.len()).filter(|i| i % every == 0 || *i + 1 == h.len()) {
                    println!(
                        "{:>6} {:>9.5} {:>10.6} {:>10.4} {:>10.4} {:>8.2} {:>8.2} {:>8.2} {:>8.2} {:>9.5} {:>9.2e}",
                        i + 1,
                        h.time[i],
                        h.driven_speed[i],
                        h.tension_upper_mid[i],
                        h.tension_lower_mid[i],
                        h.driver_stick_arc[i].to_degrees(),
                        h.driver_slip_arc[i].to_degrees(),
                        h.driven_stick_arc[i].to_degrees(),
                        h.driven_slip_arc[i].to_degrees(),
                        h.driver_torque[i],
                        h.change_rate[i]
                    );
                }
            }
            let s = &run.stats;
            println!("{} elements, {} unknowns, {} Newton iterations, {:.3} s", s.elements, s.unknowns, s.newton_iterations, s.wall_seconds);
            println!("drive: {}", run.options["drive"]);
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
