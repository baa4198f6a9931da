//! `beltcheck`: the command line. Parses arguments, calls the crates, prints.
//!
//! `beltcheck` with no arguments solves the embedded default scene
//! (`scenes/string-hanging.json`) by collocation and by shooting and prints both with
//! their difference; `beltcheck solve SCENE` solves one scene; `converge`, `report` and
//! `gate` run the verification harness (crate `verification`, docs/verification.md).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand, ValueEnum};

use bvp::collocation::Scheme;
use drive::result::{Cost, RunResult};
use drive::scene::Scene;
use drive::summary::Summary;
use drive::view::sample_fields;
use verification::run::{BvpSolver, BvpVariant, Discretisation, FemFormulation, Method, Solved};

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
    /// Convergence study of one scene: BVP tolerance sweeps and FE mesh sequences held
    /// against the tightest BVP run, with observed orders, Richardson extrapolation and
    /// the cost of every run.
    Converge(ConvergeArgs),
    /// Write Markdown + SVG + JSON reports of scenes (files or directories) and an index.
    Report(ReportArgs),
    /// CI gate: CI-sized studies checked against each scene's `gate` block; exit status 1
    /// with a table of what drifted, 0 if everything holds.
    Gate(GateArgs),
}

/// What a study runs (shared by `converge` and `report`).
#[derive(clap::Args, Clone)]
struct StudyArgs {
    /// FE formulation to study (repeatable); default: the scene's `fem.formulations`,
    /// else every registered formulation.
    #[arg(long = "formulation", value_name = "NAME")]
    formulations: Vec<String>,
    /// FE element counts, e.g. 8,16,32; default: the scene's `fem` mesh sequence.
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    elements: Vec<usize>,
    /// BVP tolerances for every variant, e.g. 1e-4,1e-6,1e-8; default: 1e-4 … 1e-10
    /// (gauss4 to 1e-8).
    #[arg(long, value_delimiter = ',', value_name = "TOL,TOL,…")]
    tolerances: Vec<f64>,
    /// σ samples of the field norms.
    #[arg(long, default_value_t = verification::study::DEFAULT_SAMPLES)]
    samples: usize,
}

#[derive(clap::Args)]
struct ConvergeArgs {
    /// Scene JSON file.
    scene: PathBuf,
    #[command(flatten)]
    study: StudyArgs,
    /// Also write the study (every number) as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
}

#[derive(clap::Args)]
struct ReportArgs {
    /// Scene files or directories of scenes (default: scenes/).
    inputs: Vec<PathBuf>,
    /// Output directory (created if needed).
    #[arg(short = 'o', long = "out", value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    study: StudyArgs,
}

#[derive(clap::Args)]
struct GateArgs {
    /// Scene files or directories of scenes (default: scenes/).
    scenes: Vec<PathBuf>,
    /// Tolerance of the gated BVP runs (gauss4, shooting).
    #[arg(long, default_value_t = verification::gate::GATE_BVP_TOLERANCE)]
    tolerance: f64,
    /// FE element counts, e.g. 16,32,64; default: each scene's `fem` mesh sequence.
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    elements: Vec<usize>,
    /// Gate only this FE formulation (repeatable); default: the scene's
    /// `fem.formulations`, else every registered formulation.
    #[arg(long = "formulation", value_name = "NAME", conflicts_with = "bvp_only")]
    formulations: Vec<String>,
    /// Gate the BVP methods only (no FE runs).
    #[arg(long)]
    bvp_only: bool,
    /// Also write every check as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
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
    /// Tolerance of the final BVP solve; default: the scene's `bvp.tolerance`, else 1e-8.
    #[arg(long)]
    tolerance: Option<f64>,
    /// Collocation scheme (gauss4, gauss6, gauss8); default: the scene's `bvp.scheme`, else gauss6.
    #[arg(long)]
    scheme: Option<String>,
    /// FE: number of elements round the loop; default: the scene's `fem.elements`, else 256.
    #[arg(long)]
    elements: Option<usize>,
    /// FE: element formulation (an unknown name lists the registered ones); default: the scene's first
    /// `fem.formulations`, else the first registered one.
    #[arg(long)]
    formulation: Option<String>,
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
        Some(Command::Converge(args)) => run_converge(&args),
        Some(Command::Report(args)) => run_report(&args),
        Some(Command::Gate(args)) => match run_gate(&args) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
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

/// The method and discretisation a `solve` asks for (scene defaults, then flags).
fn chosen_method(
    scene: &Scene,
    method: Option<MethodArg>,
    tolerance: Option<f64>,
    scheme: Option<&str>,
    elements: Option<usize>,
    formulation: Option<&str>,
) -> Result<(Box<dyn Method>, Discretisation, String)> {
    let bvp = scene.bvp_settings();
    let method = method.unwrap_or(match bvp.method {
        drive::scene::BvpMethod::Collocation => MethodArg::BvpCollocation,
        drive::scene::BvpMethod::Shooting => MethodArg::BvpShooting,
    });
    match method {
        MethodArg::BvpCollocation | MethodArg::BvpShooting => {
            let variant = if matches!(method, MethodArg::BvpShooting) {
                BvpVariant::Shooting
            } else {
                let name = scheme.unwrap_or(&bvp.scheme);
                BvpVariant::Collocation(name.parse::<Scheme>().map_err(|e| anyhow::anyhow!("scheme `{name}`: {e}"))?)
            };
            let name = if matches!(variant, BvpVariant::Shooting) { "bvp-shooting" } else { "bvp-collocation" };
            Ok((Box::new(BvpSolver::new(variant)), Discretisation::Tolerance(tolerance.unwrap_or(bvp.tolerance)), name.to_string()))
        }
        MethodArg::Fem => {
            let fem = scene.fem_settings();
            let registered = fem::available_formulations();
            let name = match formulation.map(str::to_string).or_else(|| fem.formulations.first().cloned()) {
                Some(n) => n,
                None => registered
                    .first()
                    .map(|n| n.to_string())
                    .ok_or_else(|| anyhow::anyhow!("method fem: no MEL finite element formulation is registered"))?,
            };
            if !registered.contains(&name.as_str()) {
                anyhow::bail!("unknown FE formulation `{name}`; registered: {}", registered.join(", "));
            }
            let elements = elements.unwrap_or(fem.elements);
            Ok((Box::new(FemFormulation { name, penalty: fem.penalty }), Discretisation::Elements(elements), "fem".to_string()))
        }
    }
}

/// Solve and time one run (the harness's clock, around the whole solve).
fn solve_once(scene: &Scene, method: &dyn Method, disc: Discretisation) -> Result<Solved> {
    let start = std::time::Instant::now();
    let mut solved = method.solve(scene, disc).map_err(|e| anyhow::anyhow!("{}: {e}", method.label()))?;
    solved.cost.wall_seconds = start.elapsed().as_secs_f64();
    Ok(solved)
}

fn run_solve(args: &SolveArgs) -> Result<()> {
    let scene = load_scene(&args.scene)?;
    let (method, disc, name) = chosen_method(
        &scene,
        args.method,
        args.tolerance,
        args.scheme.as_deref(),
        args.elements,
        args.formulation.as_deref(),
    )?;
    let run = solve_once(&scene, method.as_ref(), disc)?;
    let label = format!("{} ({disc})", method.label());
    print_run(&scene, &label, &run);
    if let Some(path) = &args.json {
        let result = result_json(&scene, &name, &run, args.fields)?;
        write_atomically(path, &result)?;
        println!("result written to {}", path.display());
    }
    Ok(())
}

fn run_default() -> Result<()> {
    let scene = Scene::from_json_str(DEFAULT_SCENE).context("embedded default scene")?;
    println!("beltcheck: no command given; solving the embedded default scene `{}` by both BVP methods.", scene.name);
    println!("(`beltcheck --help` lists the commands; `beltcheck solve scenes/<scene>.json` solves a scene file.)\n");
    let mut runs = Vec::new();
    for m in [MethodArg::BvpCollocation, MethodArg::BvpShooting] {
        let (method, disc, _) = chosen_method(&scene, Some(m), None, None, None, None)?;
        let run = solve_once(&scene, method.as_ref(), disc)?;
        print_run(&scene, &format!("{} ({disc})", method.label()), &run);
        println!();
        runs.push(run);
    }
    print_agreement(&runs[0].summary, &runs[1].summary);
    Ok(())
}

/// The result JSON of DESIGN.md, checked finite before anything is written.
fn result_json(scene: &Scene, method: &str, run: &Solved, fields: usize) -> Result<String> {
    run.summary.check_finite()?;
    let fields = (fields > 0).then(|| sample_fields(run.view.as_ref(), fields));
    let result = RunResult {
        scene: scene.name.clone(),
        method: method.to_string(),
        converged: true,
        summary: run.summary.clone(),
        cost: Cost {
            wall_seconds: run.cost.wall_seconds,
            newton_iterations: run.cost.newton_iterations,
            unknowns: run.cost.unknowns,
            mesh_nodes: run.cost.mesh_nodes.or(run.cost.elements.map(|e| e + 1)),
        },
        fields,
        options: Some(run.options.clone()),
        history: run.history.clone(),
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

fn print_run(scene: &Scene, label: &str, run: &Solved) {
    let s = &run.summary;
    println!("scene   {} — {}", scene.name, scene.description);
    println!("method  {label}");
    let r = scene.drive.pulley_radius;
    if let (Some(yu), Some(yl)) = (s.y_upper_mid, s.y_lower_mid) {
        println!("                               upper span     lower span");
        println!("  y at x = 0           [m]  {:>13.8} {:>14.8}", yu, yl);
        println!("  sag below the contour [m]  {:>13.8} {:>14.8}", r - yu, -r - yl);
    }
    if let (Some(tu), Some(tl)) = (s.tension_upper_mid, s.tension_lower_mid) {
        println!("  tension at x = 0      [N]  {:>13.8} {:>14.8}", tu, tl);
    }
    if let (Some(mu), Some(ml)) = (s.moment_upper_mid, s.moment_lower_mid) {
        println!("  moment at x = 0     [N·m]  {:>13.6e} {:>14.6e}", mu, ml);
    }
    if let (Some(tt), Some(ts)) = (s.tension_tight, s.tension_slack) {
        println!("  tension tight / slack [N]  {:>13.8} {:>14.8}", tt, ts);
    }
    if let Some(w2) = s.driven_speed {
        println!("  driven speed ω₂  [rad/s]  {:>13.8}   (driver ω₁ = {} rad/s)", w2, scene.drive.driver_speed);
    }
    if let Some(c) = s.transport_rate {
        println!("  transport rate c   [m/s]  {:>13.8}", c);
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
        row("stick arc         [deg]", d1.stick_arc, d2.stick_arc);
        row("slip arc          [deg]", d1.slip_arc, d2.slip_arc);
        let value = |label: &str, a: Option<f64>, b: Option<f64>| {
            if let (Some(a), Some(b)) = (a, b) {
                println!("  {label:<25}  {:>13.8} {:>14.8}", a, b);
            }
        };
        value("torque on pulley     [N·m]", d1.torque, d2.torque);
        let force = |label: &str, a: Option<f64>, b: Option<f64>| {
            if let (Some(a), Some(b)) = (a, b) {
                println!("  {label:<25}  {:>13.6e} {:>14.6e}", a, b);
            }
        };
        force("edge force, first   [N]", d1.edge_force_start, d2.edge_force_start);
        force("edge force, last    [N]", d1.edge_force_end, d2.edge_force_end);
    }
    for note in &run.notes {
        println!("  {note}");
    }
    if !run.terms.is_empty() {
        println!("  terms assembled: {}", run.terms.join(", "));
    }
    let c = &run.cost;
    let size = match (c.mesh_nodes, c.elements) {
        (Some(n), _) => format!("{n} mesh nodes"),
        (None, Some(e)) => format!("{e} elements"),
        (None, None) => String::new(),
    };
    println!("cost    {:.4} s wall, {} Newton iterations, {} unknowns, {size}", c.wall_seconds, c.newton_iterations, c.unknowns);
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

// ---------------------------------------------------------------------------
// Verification harness: converge, report, gate

/// A progress bar on stderr, hidden when stderr is not a terminal.
fn progress_bar() -> indicatif::ProgressBar {
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(0);
    let style = indicatif::ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} runs, {elapsed} — {msg}")
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
        .progress_chars("=> ");
    bar.set_style(style);
    bar
}

/// Runs a study with a progress bar labelled `prefix`.
fn study_with_progress(scene: &Scene, plan: &verification::study::StudyPlan, bar: &indicatif::ProgressBar) -> Result<verification::study::Study> {
    bar.set_prefix(scene.name.clone());
    let mut update = |p: &verification::study::Progress| {
        bar.set_length(p.total as u64);
        bar.set_position(p.done as u64);
        bar.set_message(p.label.clone());
    };
    Ok(verification::study::Study::run(scene, plan, &mut update)?)
}

fn study_plan(scene: &Scene, args: &StudyArgs) -> verification::study::StudyPlan {
    let mut plan = verification::study::StudyPlan::convergence(scene);
    if !args.tolerances.is_empty() {
        plan = plan.with_tolerances(&args.tolerances);
    }
    if !args.elements.is_empty() {
        plan = plan.with_meshes(&args.elements);
    }
    if !args.formulations.is_empty() {
        plan = plan.with_formulations(&args.formulations);
    }
    plan.samples = args.samples.max(16);
    plan
}

fn run_converge(args: &ConvergeArgs) -> Result<()> {
    let scene = load_scene(&args.scene)?;
    let plan = study_plan(&scene, &args.study);
    plan.validate()?;
    let bar = progress_bar();
    let study = study_with_progress(&scene, &plan, &bar)?;
    bar.finish_and_clear();
    print!("{}", verification::table::study_text(&study));
    println!("\nstudy: {} runs in {:.1} s", plan.run_count(), study.wall_seconds);
    if let Some(path) = &args.json {
        let text = verification::report::study_json(&scene, &study)?;
        write_atomically(path, &text)?;
        println!("study written to {}", path.display());
    }
    if let Err(e) = &study.reference.outcome {
        anyhow::bail!("the reference could not be computed: {e}");
    }
    Ok(())
}

/// Scene files of the arguments: files as given, directories expanded to their `*.json`
/// (sorted); no arguments = scenes/.
fn scene_files(inputs: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let default = [PathBuf::from("scenes")];
    let inputs = if inputs.is_empty() { &default[..] } else { inputs };
    let mut files = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(p)
                .with_context(|| format!("reading directory {}", p.display()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.extension().is_some_and(|x| x == "json"))
                .collect();
            found.sort();
            if found.is_empty() {
                anyhow::bail!("no scene (*.json) in {}", p.display());
            }
            files.extend(found);
        } else {
            files.push(p.clone());
        }
    }
    Ok(files)
}

fn run_report(args: &ReportArgs) -> Result<()> {
    let files = scene_files(&args.inputs)?;
    let scenes: Vec<(PathBuf, Scene)> = files.iter().map(|f| Ok((f.clone(), load_scene(f)?))).collect::<Result<_>>()?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let bar = progress_bar();
    let mut entries = Vec::new();
    for (file, scene) in &scenes {
        let plan = study_plan(scene, &args.study);
        plan.validate().with_context(|| format!("scene {}", file.display()))?;
        let study = study_with_progress(scene, &plan, &bar)?;
        let entry = verification::report::write_scene_report(scene, file, &study, &args.out)
            .with_context(|| format!("writing the report of {}", scene.name))?;
        bar.println(format!("{}: {} ({:.1} s)", scene.name, entry.markdown.display(), study.wall_seconds));
        entries.push(entry);
    }
    bar.finish_and_clear();
    let index = verification::report::write_index(&entries, &args.out)?;
    for e in &entries {
        println!("{}", e.markdown.display());
        for f in &e.files {
            println!("  {}", f.display());
        }
    }
    println!("index: {}", index.display());
    Ok(())
}

/// Returns Ok(true) if every scene passed.
fn run_gate(args: &GateArgs) -> Result<bool> {
    use verification::gate;
    let files = scene_files(&args.scenes)?;
    let start = std::time::Instant::now();
    let bar = progress_bar();
    let meshes = (!args.elements.is_empty()).then_some(args.elements.as_slice());
    let mut outcomes = Vec::new();
    for file in &files {
        let name = file.display().to_string();
        let outcome = match load_scene(file) {
            Err(e) => gate::failed_outcome(&name, format!("{e:#}")),
            Ok(scene) => {
                let formulations = if args.bvp_only {
                    Some(verification::study::Formulations::Named(Vec::new()))
                } else if !args.formulations.is_empty() {
                    Some(verification::study::Formulations::Named(args.formulations.clone()))
                } else {
                    None
                };
                let plan = gate::gate_plan_with(&scene, args.tolerance, meshes, formulations);
                match study_with_progress(&scene, &plan, &bar) {
                    Ok(study) => gate::evaluate(&scene.gate_settings(), &study),
                    Err(e) => gate::failed_outcome(&scene.name, format!("{e:#}")),
                }
            }
        };
        outcomes.push(outcome);
    }
    bar.finish_and_clear();
    let passed = outcomes.iter().all(gate::GateOutcome::passed);
    println!("beltcheck gate: {} scene(s), {:.1} s", outcomes.len(), start.elapsed().as_secs_f64());
    print!("{}", gate::summary_table(&outcomes).to_text("  "));
    for o in &outcomes {
        for n in &o.notes {
            println!("  note ({}): {n}", o.scene);
        }
    }
    if !passed {
        let failures = gate::failure_table(&outcomes);
        println!("\nFAILED: {} check(s) out of their limits", failures.rows.len());
        print!("{}", failures.to_text("  "));
    } else {
        println!("\npassed: every gated quantity within its limit");
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&outcomes)?;
        write_atomically(path, &text)?;
        println!("checks written to {}", path.display());
    }
    Ok(passed)
}
