//! `beltcheck`: the command line. Parses arguments, calls the crates, prints.
//!
//! `beltcheck` with no arguments solves the embedded default scene
//! (`scenes/string-hanging.json`) by collocation and by shooting and prints both with
//! their difference; `beltcheck solve SCENE` solves one scene.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand, ValueEnum};

use bvp::scene::{solve_scene, BvpMethod, BvpRun, BvpRunOptions};
use drive::result::{Cost, RunResult};
use drive::scene::Scene;
use drive::summary::Summary;
use drive::view::sample_fields;

/// The embedded default scene (the catalogue's `string-hanging`).
const DEFAULT_SCENE: &str = include_str!("../scenes/string-hanging.json");

#[derive(Parser)]
#[command(name = "beltcheck", version, about = "Slack belt drive mechanics, computed two independent ways and held against each other")]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Solve one scene and print its summary (optionally write the result JSON).
    Solve(SolveArgs),
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    /// Collocation with residual control (scheme from --scheme or the scene, default gauss6).
    BvpCollocation,
    /// Multiple shooting on an adaptive Runge–Kutta integrator (diffsol).
    BvpShooting,
    /// MEL finite elements.
    Fem,
}

#[derive(clap::Args)]
struct SolveArgs {
    /// Scene JSON file (format: DESIGN.md "Scene format").
    scene: PathBuf,
    /// Method; default: the scene's `bvp.method`, else bvp-collocation.
    #[arg(long, value_enum)]
    method: Option<MethodArg>,
    /// Tolerance of the final solve; default: the scene's `bvp.tolerance`, else 1e-8.
    #[arg(long)]
    tolerance: Option<f64>,
    /// Collocation scheme (gauss4, gauss6); default: the scene's `bvp.scheme`, else gauss6.
    #[arg(long)]
    scheme: Option<String>,
    /// Write the result JSON (DESIGN.md "Result format") to this file.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Number of equally spaced σ samples in the JSON `fields` (0 = no fields).
    #[arg(long, default_value_t = 200)]
    fields: usize,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        None => run_default(),
        Some(Command::Solve(args)) => run_solve(&args),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn load_scene(path: &Path) -> Result<Scene> {
    Scene::from_path(path).with_context(|| format!("scene {}", path.display()))
}

fn run_options(scene: &Scene, method: Option<MethodArg>, tolerance: Option<f64>, scheme: Option<&str>) -> Result<BvpRunOptions> {
    let mut opts = BvpRunOptions::from_scene(scene)?;
    match method {
        Some(MethodArg::BvpCollocation) => opts.method = BvpMethod::Collocation,
        Some(MethodArg::BvpShooting) => opts.method = BvpMethod::Shooting,
        Some(MethodArg::Fem) => {
            anyhow::bail!(
                "method fem: no MEL finite element formulation is available yet (registered formulations: {:?}); use --method bvp-collocation or bvp-shooting",
                fem::available_formulations()
            )
        }
        None => {}
    }
    if let Some(t) = tolerance {
        opts.tolerance = t;
    }
    if let Some(s) = scheme {
        opts.scheme = s.parse().map_err(|e| anyhow::anyhow!("--scheme {s}: {e}"))?;
    }
    Ok(opts)
}

fn run_solve(args: &SolveArgs) -> Result<()> {
    let scene = load_scene(&args.scene)?;
    let opts = run_options(&scene, args.method, args.tolerance, args.scheme.as_deref())?;
    let run = solve_scene(&scene, &opts)?;
    print_run(&scene, &run);
    if let Some(path) = &args.json {
        let result = result_json(&scene, &run, args.fields)?;
        write_atomically(path, &result)?;
        println!("result written to {}", path.display());
    }
    Ok(())
}

fn run_default() -> Result<()> {
    let scene = Scene::from_json_str(DEFAULT_SCENE).context("embedded default scene")?;
    println!("beltcheck: no command given; solving the embedded default scene `{}` by both BVP methods.", scene.name);
    println!("(`beltcheck --help` lists the commands; `beltcheck solve scenes/<scene>.json` solves a scene file.)\n");
    let coll = solve_scene(&scene, &run_options(&scene, Some(MethodArg::BvpCollocation), None, None)?)?;
    print_run(&scene, &coll);
    println!();
    let shoot = solve_scene(&scene, &run_options(&scene, Some(MethodArg::BvpShooting), None, None)?)?;
    print_run(&scene, &shoot);
    println!();
    print_agreement(&coll.summary, &shoot.summary);
    Ok(())
}

/// The result JSON of DESIGN.md, checked finite before anything is written.
fn result_json(scene: &Scene, run: &BvpRun, fields: usize) -> Result<String> {
    run.summary.check_finite()?;
    let fields = (fields > 0).then(|| sample_fields(run.view.as_ref(), fields));
    let result = RunResult {
        scene: scene.name.clone(),
        method: run.method.clone(),
        converged: true,
        summary: run.summary.clone(),
        cost: Cost {
            wall_seconds: run.stats.wall_seconds,
            newton_iterations: run.stats.newton_iterations,
            unknowns: run.stats.unknowns,
            mesh_nodes: Some(run.stats.mesh_nodes),
        },
        fields,
        options: Some(run.options.clone()),
    };
    result.check()?;
    Ok(serde_json::to_string_pretty(&result)?)
}

/// Write via a temporary file and rename, so a failure leaves nothing half-written.
fn write_atomically(path: &Path, text: &str) -> Result<()> {
    let tmp = path.with_extension("json.partial");
    std::fs::write(&tmp, text).with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, path).with_context(|| format!("renaming to {}", path.display()))?;
    Ok(())
}

fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

fn print_run(scene: &Scene, run: &BvpRun) {
    let s = &run.summary;
    println!("scene   {} — {}", scene.name, scene.description);
    println!("method  {} ({})", run.method, run.method_detail);
    let r = scene.drive.pulley_radius;
    if let (Some(yu), Some(yl)) = (s.y_upper_mid, s.y_lower_mid) {
        println!("                               upper span     lower span");
        println!("  y at x = 0           [m]  {:>13.8} {:>14.8}", yu, yl);
        println!("  sag below the contour [m]  {:>13.8} {:>14.8}", r - yu, -r - yl);
    }
    if let (Some(tu), Some(tl)) = (s.tension_upper_mid, s.tension_lower_mid) {
        println!("  tension at x = 0      [N]  {:>13.8} {:>14.8}", tu, tl);
    }
    if let (Some(d1), Some(d2)) = (&s.driver, &s.driven) {
        println!("                                  driver         driven");
        let row = |label: &str, a: Option<f64>, b: Option<f64>| {
            if let (Some(a), Some(b)) = (a, b) {
                println!("  {label:<25}  {:>13.8} {:>14.8}", deg(a), deg(b));
            }
        };
        row("contact arc       [deg]", d1.contact_arc, d2.contact_arc);
        row("first contact     [deg]", d1.contact_start, d2.contact_start);
        row("last contact      [deg]", d1.contact_end, d2.contact_end);
    }
    for note in &run.notes {
        println!("  {note}");
    }
    let st = &run.stats;
    println!(
        "cost    {:.4} s wall, {} Newton iterations, {} unknowns, {} mesh nodes",
        st.wall_seconds, st.newton_iterations, st.unknowns, st.mesh_nodes
    );
}

fn print_agreement(a: &Summary, b: &Summary) {
    let (diffs, only) = verification::compare_summaries(a, b);
    println!("collocation vs shooting: largest differences");
    let mut diffs = diffs;
    diffs.sort_by(|x, y| y.absolute.total_cmp(&x.absolute));
    for d in diffs.iter().take(6) {
        println!("  {:<28} |Δ| = {:.2e}  (relative {:.2e})", d.name, d.absolute, d.relative);
    }
    if !only.is_empty() {
        println!("  produced by one method only: {}", only.join(", "));
    }
}
