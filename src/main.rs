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

use drive::error::num;
use drive::result::{Cost, RunResult};
use drive::scene::Scene;
use drive::summary::Summary;
use drive::view::sample_fields;
use verification::run::{BvpSolver, BvpVariant, Discretisation, FemFormulation, Method, Scheme, Solved};

use verification::study::{MAX_ELEMENTS, MIN_ELEMENTS, SAMPLES_RANGE};

/// Why the command line refuses to run or to write (exit status 2).
#[derive(Debug, thiserror::Error)]
enum CliError {
    /// A flag that only a shell scene uses.
    #[error("--{flag} is for shell scenes (theory `shell`, a run-off transient); this scene's belt is theory `{theory}`")]
    FlagNotForScene { flag: &'static str, theory: String },
    /// `gate` flags of the 1-D studies with a shell scene among the scenes.
    #[error("--elements, --tolerance and --formulation set the 1-D studies; {} is a shell scene, gated at its `gate.levels` (give the other scenes without it)", .file.display())]
    ShellGateFlags { file: PathBuf },
    /// A flag that only works with another.
    #[error("--{flag} needs --{needs}")]
    FlagNeeds { flag: &'static str, needs: &'static str },
    /// A flag that the chosen method does not use.
    #[error("--{flag} is not used by method {method}: {hint}")]
    FlagNotForMethod { flag: &'static str, method: &'static str, hint: &'static str },
    /// A flag value outside its documented range.
    #[error("--{flag} = {value} is out of range: {range}")]
    OutOfRange { flag: &'static str, value: String, range: String },
    /// A result file that was not written (nothing of it is left behind).
    #[error(transparent)]
    File(#[from] verification::files::WriteError),
    /// Two scenes of one `report` run with the same name (their reports would overwrite
    /// each other).
    #[error("scene name `{name}` appears twice ({} and {}; names that differ only in letter case count as one, as on a case-insensitive file system): each scene's report is written to a directory of its name; rename one", .first.display(), .second.display())]
    DuplicateSceneName { name: String, first: PathBuf, second: PathBuf },
    /// Scenes of a `report` run without a usable study (reports are written, exit 2).
    #[error("{} scene(s) without a usable study: {}", .0.len(), .0.join("; "))]
    Unsolved(Vec<String>),
}

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
    ///
    /// `beltcheck quantities` says what each summary name means: e.g. `tension_tight` /
    /// `tension_slack` are the axial forces at the middle of the driver's / the driven
    /// pulley's stick arcs, by both methods — the tight / slack sides while the driver drives (either
    /// sense of rotation: a negative `driver_speed` turns it counter-clockwise and makes
    /// the upper span the tight one), swapped when the load drives (a `driven_torque`
    /// of the sign opposite to `driver_speed`, larger than the damping's d₂|ω₁|).
    Solve(SolveArgs),
    /// Convergence study of one scene: BVP tolerance sweeps and FE mesh sequences held
    /// against the tightest BVP run, with observed orders, Richardson extrapolation and
    /// the cost of every run.
    Converge(ConvergeArgs),
    /// Write Markdown + SVG + JSON reports of scenes (files or directories) and an index;
    /// exit status 2 if a scene name repeats (nothing run) or a scene's study is not
    /// usable (as `converge`; the reports are still written).
    Report(ReportArgs),
    /// CI gate: CI-sized studies checked against each scene's `gate` block; exit status 1
    /// with a table of what drifted, 0 if everything holds, 2 for a usage or input error
    /// (missing or invalid scene, bad tolerance, unknown formulation).
    Gate(GateArgs),
    /// Check the results of an outside FE code (result files, or directories of them)
    /// against the scene's reference with the scene's `gate` limits: the same errors,
    /// orders, Richardson values and cost as `converge`; exit status 1 with the table of
    /// what drifted, 0 if everything holds, 2 for a bad file or argument (each named).
    /// docs/check-your-code.md.
    Check(CheckArgs),
    /// The scene's reference solution (the gate's BVP run) sampled where an outside code
    /// wants it: at the σ of a file, or at N equally spaced σ; as a result JSON or CSV.
    Reference(ReferenceArgs),
    /// Parameter study: every summary output against numeric scene fields, by BVP
    /// natural-parameter continuation (warm starts, step halving, fold detection) with
    /// FE spot checks and the asymptotes; Markdown + SVG + JSON to -o DIR. Exit status 2
    /// for a bad --param (nothing run or written), or when a point has no solution (the
    /// report is still written and names it). docs/sweep.md.
    Sweep(SweepArgs),
    /// Print the JSON Schema of the scene or the result format (shipped in schemas/).
    Schema {
        /// Which format.
        #[arg(value_enum)]
        format: SchemaArg,
    },
    /// List every summary quantity of the result format: its JSON name, unit and
    /// meaning (a scene produces only those its layout and effects call for).
    Quantities,
}

/// What a study runs (shared by `converge` and `report`).
#[derive(clap::Args, Clone)]
struct StudyArgs {
    /// FE formulation to study (repeatable); default: the scene's `fem.formulations`,
    /// else every registered formulation.
    #[arg(long = "formulation", value_name = "NAME")]
    formulations: Vec<String>,
    /// FE element counts (4 … 16384, increasing), e.g. 8,16,32; default: the scene's
    /// `fem` mesh sequence.
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    elements: Vec<usize>,
    /// BVP tolerances for every variant, e.g. 1e-4,1e-6,1e-8; default: 1e-4 … 1e-10
    /// (gauss4 to 1e-8).
    #[arg(long, value_delimiter = ',', value_name = "TOL,TOL,…")]
    tolerances: Vec<f64>,
    /// σ samples of the field norms (16 … 100000).
    #[arg(long, default_value_t = verification::study::DEFAULT_SAMPLES)]
    samples: usize,
    /// What the runs are held against: a BVP run (collocation gauss6 at 1e-11), the
    /// closed form of the scene's model (the elastic catenary loop of a static string),
    /// or Richardson extrapolation of the first studied FE formulation over the study's
    /// meshes (three or more, one refinement ratio; for models with no BVP).
    #[arg(long, value_enum, default_value_t = ReferenceArg::Bvp)]
    reference: ReferenceArg,
    /// Shell scenes only: the levels n_σ×n_ζ, coarsest first (e.g. 64x8,128x8,256x8 or
    /// 64x2,128x4,256x8), each with Δt scaled like the σ spacing (see `--refine`); the reference is the
    /// Richardson extrapolation of the three finest. Default: the scene's mesh, then
    /// twice and four times its n_σ at its n_ζ (with `--refine width`, its n_ζ).
    #[arg(long, value_delimiter = ',', value_name = "NσxNζ,…")]
    levels: Vec<String>,
    /// Shell scenes only: what the levels refine. `both`: σ and Δt together (the limit
    /// in space and time); `mesh`: the levels' meshes at the scene's Δt (the limit in
    /// space at that step); `step`: the scene's Δt, then a half and a quarter of it, on
    /// one mesh — the one `--levels` entry, else the scene's (the time-continuous limit
    /// on that mesh); `width`: n_ζ alone, the levels at one n_σ and the scene's Δt (the
    /// limit across the width on that σ-mesh).
    #[arg(long, value_enum, default_value_t = RefineArg::Both)]
    refine: RefineArg,
    /// Shell scenes only: skip the cambered belt's compensating swivel (a root over
    /// whole solves, six to eight at the coarsest level: on a long run they cost more than
    /// the study); the study then names it as not searched.
    #[arg(long)]
    no_compensation: bool,
}

/// What a shell study's levels refine (`--refine`).
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum RefineArg {
    /// σ and Δt together, Δt scaled like the σ spacing.
    Both,
    /// The mesh at the scene's time step.
    Mesh,
    /// The time step on one mesh.
    Step,
    /// The elements across the width on one σ-mesh at the scene's time step.
    Width,
}

#[derive(Clone, Copy, ValueEnum)]
enum ReferenceArg {
    /// A BVP run at a tight tolerance.
    Bvp,
    /// The closed form of the scene's model.
    ClosedForm,
    /// Richardson extrapolation of the finest FE runs.
    Richardson,
}

#[derive(clap::Args)]
struct ConvergeArgs {
    /// Scene JSON file.
    scene: PathBuf,
    #[command(flatten)]
    study: StudyArgs,
    /// Also write the study (every number) as JSON to this file — only if the study
    /// is usable (its reference solved, every method it asked for with at least one
    /// successful run); otherwise exit status 2 and nothing is written. An existing
    /// symlink, FIFO, device or directory there is refused, never replaced.
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
    /// Tolerance of the gated BVP runs (gauss4, shooting), 0 < tolerance < 1; default:
    /// each scene's `gate.bvp_tolerance`, else 1e-8.
    #[arg(long)]
    tolerance: Option<f64>,
    /// FE element counts (4 … 16384, increasing), e.g. 16,32,64; default: each
    /// scene's `fem` mesh sequence.
    #[arg(long, value_delimiter = ',', value_name = "N,N,…")]
    elements: Vec<usize>,
    /// Gate only this FE formulation (repeatable); default: the scene's
    /// `fem.formulations`, else every registered formulation.
    #[arg(long = "formulation", value_name = "NAME", conflicts_with = "bvp_only")]
    formulations: Vec<String>,
    /// Gate the BVP methods only (no FE runs).
    #[arg(long)]
    bvp_only: bool,
    /// Also write every check as JSON to this file (a symlink, FIFO, device or
    /// directory there is refused, never replaced).
    #[arg(long)]
    json: Option<PathBuf>,
}

#[derive(clap::Args)]
struct CheckArgs {
    /// Scene JSON file (the scene the results were computed for).
    scene: PathBuf,
    /// Result files (*.json, or *.csv with a # JSON header) or directories of them.
    #[arg(required = true)]
    results: Vec<PathBuf>,
    /// What the results are held against: the gate's BVP run (`auto` falls back to
    /// Richardson extrapolation of the supplied runs where no BVP solves the scene),
    /// the closed form of the scene's model, or the supplied runs' extrapolation.
    #[arg(long, value_enum, default_value_t = CheckReferenceArg::Auto)]
    reference: CheckReferenceArg,
    /// σ samples of the field norms (16 … 100000).
    #[arg(long, default_value_t = verification::study::DEFAULT_SAMPLES)]
    samples: usize,
    /// Also write the Markdown + SVG + JSON report of the check to this directory (the
    /// outside code is a method of the study, as in `report`).
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// Also write every check as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
}

#[derive(Clone, Copy, ValueEnum)]
enum CheckReferenceArg {
    /// The BVP run; Richardson of the supplied runs where no BVP solves the scene.
    Auto,
    /// The BVP run (an error for a scene no BVP solves).
    Bvp,
    /// The closed form of the scene's model.
    ClosedForm,
    /// Richardson extrapolation of the supplied runs.
    Supplied,
}

#[derive(clap::Args)]
struct ReferenceArgs {
    /// Scene JSON file.
    scene: PathBuf,
    /// File of σ values, m (numbers separated by commas, blanks or newlines; `#` starts
    /// a comment).
    #[arg(long, value_name = "FILE", conflicts_with = "samples")]
    sigma: Option<PathBuf>,
    /// N equally spaced σ_i = i·L/N, L the contour length (2H + 2πR on the loop, 2D + πR on the one-pulley layout), 1 … 100000; default 200.
    #[arg(long, value_name = "N")]
    samples: Option<usize>,
    /// Output format: the result JSON, or CSV with a # JSON header.
    #[arg(long, value_enum, default_value_t = FormatArg::Json)]
    format: FormatArg,
    /// Relative tolerance of the BVP run, 0 < tolerance < 1.
    #[arg(long, default_value_t = verification::gate::GATE_REFERENCE_TOLERANCE)]
    tolerance: f64,
    /// Write to this file instead of standard output.
    #[arg(short = 'o', long = "out", value_name = "FILE")]
    out: Option<PathBuf>,
}

#[derive(clap::Args)]
struct SweepArgs {
    /// Scene JSON file.
    scene: PathBuf,
    /// A swept field: NAME=FROM:TO[:log]:N, NAME the dotted path of a numeric scene field
    /// (e.g. belt.shear_stiffness=1e2:1e6:log:40); N ≥ 2 values, equally spaced in the
    /// value or its logarithm (log: both bounds > 0). Repeat for a grid: the first runs
    /// along the continuation lines, the others make one line per combination.
    #[arg(long = "param", value_name = "NAME=FROM:TO[:log]:N", required = true)]
    params: Vec<String>,
    /// FE spot checks per line, evenly spaced over its points (0 = none).
    #[arg(long, default_value_t = 2, value_name = "K")]
    fe_points: usize,
    /// Elements of the FE spot checks (4 … 16384); default: the scene's `fem.elements`.
    #[arg(long, value_name = "N")]
    fe_elements: Option<usize>,
    /// BVP tolerance of every point, 0 < tolerance < 1; default: the scene's
    /// `bvp.tolerance`, else 1e-8.
    #[arg(long)]
    tolerance: Option<f64>,
    /// Leave out the asymptotes (string limit, Kirchhoff limit, belt-creep closed form).
    #[arg(long)]
    no_asymptotes: bool,
    /// Output directory (created if needed): sweep.md, sweep.svg, sweep.json.
    #[arg(short = 'o', long = "out", value_name = "DIR")]
    out: PathBuf,
}

#[derive(Clone, Copy, ValueEnum)]
enum SchemaArg {
    /// The scene format (DESIGN.md "Scene format").
    Scene,
    /// The result format (DESIGN.md "Result format", with `discretisation`).
    Result,
}

#[derive(Clone, Copy, ValueEnum)]
enum FormatArg {
    /// Result JSON (DESIGN.md "Result format").
    Json,
    /// CSV: a # line with the result JSON without fields, then sigma,x,y,tension[,moment].
    Csv,
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    /// Collocation with residual control (scheme from --scheme or the scene, default gauss8).
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
    /// BVP methods only: tolerance of the final BVP solve, 0 < tolerance < 1; default:
    /// the scene's `bvp.tolerance`, else 1e-8.
    #[arg(long)]
    tolerance: Option<f64>,
    /// bvp-collocation only: scheme (gauss4, gauss6, gauss8); default: the scene's
    /// `bvp.scheme`, else gauss8.
    #[arg(long)]
    scheme: Option<String>,
    /// fem only: number of elements round the loop, 4 … 16384; default: the scene's
    /// `fem.elements`, else 256.
    #[arg(long)]
    elements: Option<usize>,
    /// fem only: element formulation of the scene's belt theory (an unknown name lists
    /// the registered ones; one of another theory is refused); default: the scene's
    /// first `fem.formulations`, else the first registered one of its belt theory.
    #[arg(long)]
    formulation: Option<String>,
    /// Write the result JSON (DESIGN.md "Result format") to this file. Written via a
    /// temporary file in the same directory and renamed; an existing symlink, FIFO,
    /// device or directory there is refused, never replaced; on any error nothing is
    /// left behind.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Number of equally spaced σ samples in the JSON `fields` (0 = no fields, else
    /// at most 100000).
    #[arg(long, default_value_t = 200)]
    fields: usize,
    /// Also print where the wall time went: seconds and share per phase (assembly,
    /// symbolic and numeric LU, solves, residuals, integration, mesh adaptation,
    /// fitting, other) and the step counts — the result's `cost.phases`.
    #[arg(long, short)]
    verbose: bool,
    /// Shell scenes only: a measurement to hold the run against — a CSV of (time, lateral
    /// position) lines, time in s from the start of the drums' rotation, lateral
    /// position in m (+z along the drum axes); `#` comments and one header line allowed.
    /// Printed beside the model with the difference, and written to the JSON's `measured`.
    /// A malformed file is refused (line named) before anything is solved.
    #[arg(long, value_name = "FILE.csv")]
    measured: Option<PathBuf>,
    /// Shell scenes only, with --measured: the history channel compared (default
    /// `lateral_offset`, the belt's mean lateral offset; also `lateral_upper_mid`,
    /// `lateral_lower_mid`, `lateral_driver_apex`, `lateral_driven_apex`,
    /// `edge_minus_upper_mid`, `edge_plus_upper_mid`).
    #[arg(long, value_name = "CHANNEL")]
    measured_channel: Option<String>,
    /// Shell scenes only: write the belt surface over time as VTK files into DIR (created
    /// if absent): one `<scene>_NNNN.vtu` per frame (the start and the end of the
    /// rotation, and every `fem.frame_every` steps) with the displacement from the
    /// undeformed placement, the membrane force, the bending moment and the contact
    /// pressure, and a `<scene>.pvd` series for ParaView.
    #[arg(long, value_name = "DIR")]
    vtk: Option<PathBuf>,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        None => run_default(),
        Some(Command::Solve(args)) => run_solve(&args),
        Some(Command::Converge(args)) => run_converge(&args),
        Some(Command::Report(args)) => run_report(&args),
        Some(Command::Quantities) => {
            print_quantities();
            Ok(())
        }
        Some(Command::Reference(args)) => run_reference(&args),
        Some(Command::Sweep(args)) => run_sweep(&args),
        Some(Command::Schema { format }) => {
            let schema = match format {
                SchemaArg::Scene => drive::schemas::scene_schema(),
                SchemaArg::Result => drive::schemas::result_schema(),
            };
            print!("{}", drive::schemas::to_text(&schema));
            Ok(())
        }
        Some(Command::Check(args)) => match run_check(&args) {
            Ok(true) => Ok(()),
            Ok(false) => return ExitCode::from(1),
            Err(e) => Err(e),
        },
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

/// The flags of a `solve` that choose the method and its discretisation.
#[derive(Clone, Copy, Default)]
struct MethodFlags<'a> {
    method: Option<MethodArg>,
    tolerance: Option<f64>,
    scheme: Option<&'a str>,
    elements: Option<usize>,
    formulation: Option<&'a str>,
}

/// Refuses a flag the method does not use.
fn unused(given: bool, flag: &'static str, method: &'static str, hint: &'static str) -> Result<(), CliError> {
    if given {
        return Err(CliError::FlagNotForMethod { flag, method, hint });
    }
    Ok(())
}

/// `n` FE elements within [`MIN_ELEMENTS`, `MAX_ELEMENTS`].
fn check_elements(flag: &'static str, n: usize) -> Result<(), CliError> {
    if !(MIN_ELEMENTS..=MAX_ELEMENTS).contains(&n) {
        return Err(CliError::OutOfRange {
            flag,
            value: n.to_string(),
            range: format!("{MIN_ELEMENTS} … {MAX_ELEMENTS} elements (at least one per region of the contour; the cost grows with the square of the count)"),
        });
    }
    Ok(())
}

/// A relative tolerance in (0, 1).
fn check_tolerance(flag: &'static str, t: f64) -> Result<(), CliError> {
    if !(t > 0.0 && t < 1.0) {
        return Err(CliError::OutOfRange { flag, value: num(&t), range: "a relative tolerance, 0 < tolerance < 1".into() });
    }
    Ok(())
}

/// The method and discretisation a `solve` asks for (scene defaults, then flags); a flag
/// the chosen method does not use is an error, not ignored.
fn chosen_method(scene: &Scene, flags: MethodFlags<'_>) -> Result<(Box<dyn Method>, Discretisation, String)> {
    // the shell: its FE by default (no BVP exists for it: a BVP method is refused by the
    // solver with that reason); its mesh and time step are the scene's `fem` block
    if scene.belt.theory == drive::scene::Theory::Shell && matches!(flags.method, None | Some(MethodArg::Fem)) {
        let name = "fem";
        let hint = "the shell's mesh and time step are the scene's `fem.elements_sigma`, `fem.elements_zeta` and `fem.time_step`";
        unused(flags.elements.is_some(), "elements", name, hint)?;
        unused(flags.formulation.is_some(), "formulation", name, "the shell has one element (Bogner–Fox–Schmit, docs/fem-shell.md)")?;
        unused(flags.scheme.is_some(), "scheme", name, "it sets the BVP solve")?;
        unused(flags.tolerance.is_some(), "tolerance", name, "it sets the BVP solve")?;
        return Ok((Box::new(verification::run::ShellFe), verification::run::ShellFe::discretisation(scene), name.to_string()));
    }
    let bvp = scene.bvp_settings();
    let method = flags.method.unwrap_or(match bvp.method {
        drive::scene::BvpMethod::Collocation => MethodArg::BvpCollocation,
        drive::scene::BvpMethod::Shooting => MethodArg::BvpShooting,
    });
    match method {
        MethodArg::BvpCollocation | MethodArg::BvpShooting => {
            let name = if matches!(method, MethodArg::BvpShooting) { "bvp-shooting" } else { "bvp-collocation" };
            let fem_only = "it sets the FE discretisation; use --method fem";
            unused(flags.elements.is_some(), "elements", name, fem_only)?;
            unused(flags.formulation.is_some(), "formulation", name, fem_only)?;
            let variant = if matches!(method, MethodArg::BvpShooting) {
                unused(flags.scheme.is_some(), "scheme", name, "it chooses the collocation scheme; use --method bvp-collocation")?;
                BvpVariant::Shooting
            } else {
                let scheme = flags.scheme.unwrap_or(&bvp.scheme);
                BvpVariant::Collocation(scheme.parse::<Scheme>().map_err(|e| anyhow::anyhow!("scheme `{}`: {e}", drive::error::clip(scheme)))?)
            };
            let tolerance = flags.tolerance.unwrap_or(bvp.tolerance);
            check_tolerance("tolerance", tolerance)?;
            Ok((Box::new(BvpSolver::new(variant)), Discretisation::Tolerance(tolerance), name.to_string()))
        }
        MethodArg::Fem => {
            let bvp_only = "it sets the BVP solve; the FE is refined by --elements";
            unused(flags.scheme.is_some(), "scheme", "fem", bvp_only)?;
            unused(flags.tolerance.is_some(), "tolerance", "fem", bvp_only)?;
            let registered = verification::run::registered_formulations();
            let name = match flags.formulation {
                Some(n) => n.to_string(),
                None => verification::run::default_formulation(scene)?,
            };
            if !registered.contains(&name.as_str()) {
                anyhow::bail!("unknown FE formulation `{}`; registered: {}", drive::error::clip(&name), registered.join(", "));
            }
            let elements = flags.elements.unwrap_or(scene.fem_settings().elements);
            check_elements("elements", elements)?;
            Ok((Box::new(FemFormulation { name, penalty: scene.fem_settings().penalty }), Discretisation::Elements(elements), "fem".to_string()))
        }
    }
}

/// Solve and time one run (the harness's clock, around the whole solve).
fn solve_once(scene: &Scene, method: &dyn Method, disc: Discretisation) -> Result<Solved> {
    // the method's typed error stays the source (`{:#}` prints its chain)
    verification::run::solve_timed(method, scene, disc).map_err(|e| anyhow::Error::new(e).context(method.label()))
}

/// The glossary of the summary: one line a quantity, from the typed ids of
/// `drive::summary` (one source for the names, units and meanings).
fn print_quantities() {
    use drive::summary::{PulleyId, PulleyQuantity, Quantity};
    println!("{:<28} {:<6} meaning", "name", "unit");
    for q in Quantity::ALL {
        // The pulley quantities mean the same for every pulley: list them once, as
        // `<pulley>.name` with the pulleys named below.
        if let Quantity::Pulley(p, _) = q {
            if p != PulleyId::Driver {
                continue;
            }
        }
        let name = match q {
            Quantity::Pulley(_, pq) => format!("<pulley>.{}", pq.name()),
            Quantity::Global(_) => q.name().to_string(),
        };
        println!("{:<28} {:<6} {}", name, q.unit(), q.meaning());
    }
    let pulleys: Vec<&str> = PulleyId::ALL.iter().map(|p| p.name()).collect();
    println!(
        "\n<pulley> is one of {} (driver/driven: the two-pulley loop; pulley: a one-pulley scene); {} quantities a pulley.",
        pulleys.join(", "),
        PulleyQuantity::ALL.len()
    );
    println!("A quantity a scene does not produce is absent from its result (never 0, never null).");
}

fn run_solve(args: &SolveArgs) -> Result<()> {
    if args.fields > *SAMPLES_RANGE.end() {
        return Err(CliError::OutOfRange { flag: "fields", value: args.fields.to_string(), range: format!("0 (no fields) … {} samples", SAMPLES_RANGE.end()) }.into());
    }
    let scene = load_scene(&args.scene)?;
    let shell = scene.belt.theory == drive::scene::Theory::Shell;
    for (flag, given) in [("measured", args.measured.is_some()), ("measured-channel", args.measured_channel.is_some()), ("vtk", args.vtk.is_some())] {
        if given && !shell {
            return Err(CliError::FlagNotForScene { flag, theory: scene.belt.theory.to_string() }.into());
        }
    }
    if args.measured_channel.is_some() && args.measured.is_none() {
        return Err(CliError::FlagNeeds { flag: "measured-channel", needs: "measured" }.into());
    }
    // read before solving: a bad file costs nothing
    let measured = args.measured.as_deref().map(verification::measured::Measured::read).transpose()?;
    if let Some(dir) = &args.vtk {
        verification::vtk::check_directory(dir)?;
    }
    let flags = MethodFlags {
        method: args.method,
        tolerance: args.tolerance,
        scheme: args.scheme.as_deref(),
        elements: args.elements,
        formulation: args.formulation.as_deref(),
    };
    let (method, disc, name) = chosen_method(&scene, flags)?;
    let run = solve_once(&scene, method.as_ref(), disc)?;
    let label = format!("{} ({disc})", method.label());
    print_run(&scene, &label, &run);
    if args.verbose {
        print_phases(&run.cost);
    }
    if let Some(n) = &run.not_steady {
        eprintln!("warning: {n}");
    }
    if let Some(u) = &run.unfitted {
        eprintln!("warning: {u}");
    }
    if shell {
        print_shell_history(&run);
    }
    let comparison = match (&measured, &run.history) {
        (Some(m), Some(h)) => {
            let channel = args.measured_channel.as_deref().unwrap_or("lateral_offset");
            let start = run.options.pointer("/shell/rotation_start").and_then(serde_json::Value::as_f64).unwrap_or(0.0);
            let c = m.compare(h, channel, start)?;
            print_measured(&c);
            Some(c)
        }
        _ => None,
    };
    if let (Some(dir), Some(h)) = (&args.vtk, &run.history) {
        let written = verification::vtk::write_series(dir, &scene.name, &scene.contour(), h)?;
        println!("VTK: {} frame(s) written to {} (series {})", written.frames.len(), dir.display(), written.series.display());
    }
    if let Some(path) = &args.json {
        let result = result_json(&scene, &name, disc, &run, args.fields, comparison)?;
        write_output(path, &result)?;
        println!("result written to {}", path.display());
    }
    Ok(())
}

/// The shell run's history in short: the lateral channels at the start and the end of
/// the rotation.
fn print_shell_history(run: &Solved) {
    let Some(h) = &run.history else { return };
    let stage = h.channel("stage").unwrap_or(&[]);
    let Some(first) = stage.iter().position(|&s| s >= 2.0).map(|k| k.saturating_sub(1)) else { return };
    let last = h.len() - 1;
    println!("history (lateral positions, m; +z along the drum axes)   t = {:.4} s      t = {:.4} s", h.time[first], h.time[last]);
    for name in ["lateral_offset", "lateral_upper_mid", "lateral_lower_mid", "lateral_driver_apex", "lateral_driven_apex", "edge_minus_upper_mid", "edge_plus_upper_mid"] {
        if let Some(c) = h.channel(name) {
            println!("  {name:<24} {:>32.6e} {:>16.6e}", c[first], c[last]);
        }
    }
    println!("lateral force of each drum on the belt, N (+z); mid-span tensions, N");
    for name in ["lateral_force_driver", "lateral_force_driven", "tension_upper_mid", "tension_lower_mid"] {
        if let Some(c) = h.channel(name) {
            println!("  {name:<24} {:>32.6e} {:>16.6e}", c[first], c[last]);
        }
    }
}

/// The measurement beside the model, with the difference.
fn print_measured(c: &drive::result::MeasuredComparison) {
    println!("measured ({}) against the model's `{}` (t from the start of the rotation):", c.file, c.channel);
    println!("  {:>10} {:>14} {:>14} {:>14}", "t [s]", "measured", "model", "difference");
    let n = c.time.len();
    let shown: Vec<usize> = if n <= 12 { (0..n).collect() } else { (0..12).map(|k| k * (n - 1) / 11).collect() };
    for k in shown {
        println!("  {:>10.4} {:>14.6e} {:>14.6e} {:>14.6e}", c.time[k], c.measured[k], c.model[k], c.difference[k]);
    }
    println!("  {n} sample(s) compared, {} outside the simulated rotation; difference rms {:.4e}, largest {:.4e}", c.outside, c.rms_difference, c.max_difference);
}

fn run_default() -> Result<()> {
    let scene = Scene::from_json_str(DEFAULT_SCENE).context("embedded default scene")?;
    println!("beltcheck: no command given; solving the embedded default scene `{}` by both BVP methods.", scene.name);
    println!("(`beltcheck --help` lists the commands; `beltcheck solve scenes/<scene>.json` solves a scene file.)\n");
    let mut runs = Vec::new();
    for m in [MethodArg::BvpCollocation, MethodArg::BvpShooting] {
        let (method, disc, _) = chosen_method(&scene, MethodFlags { method: Some(m), ..MethodFlags::default() })?;
        let run = solve_once(&scene, method.as_ref(), disc)?;
        print_run(&scene, &format!("{} ({disc})", method.label()), &run);
        println!();
        runs.push(run);
    }
    print_agreement(&runs[0].summary, &runs[1].summary);
    Ok(())
}

/// The result JSON of DESIGN.md, checked finite before anything is written.
fn result_json(scene: &Scene, method: &str, disc: Discretisation, run: &Solved, fields: usize, measured: Option<drive::result::MeasuredComparison>) -> Result<String> {
    run.summary.check_finite()?;
    let fields = (fields > 0).then(|| sample_fields(run.view.as_ref(), fields));
    let mut result = run_result(scene, method, disc, run, fields);
    result.measured = measured;
    result.check()?;
    Ok(serde_json::to_string_pretty(&result)?)
}

/// The result of a run in the result format, with these fields.
fn run_result(scene: &Scene, method: &str, disc: Discretisation, run: &Solved, fields: Option<drive::result::Fields>) -> RunResult {
    RunResult {
        scene: scene.name.clone(),
        method: method.to_string(),
        converged: run.not_steady.is_none() && !run.unfitted.as_ref().is_some_and(|u| u.not_converged()),
        summary: run.summary.clone(),
        cost: Cost {
            wall_seconds: run.cost.wall_seconds,
            newton_iterations: run.cost.newton_iterations,
            unknowns: run.cost.unknowns,
            mesh_nodes: run.cost.mesh_nodes.or(run.cost.elements.map(|e| e + 1)),
            phases: run.cost.cost_phases(),
        },
        fields,
        options: Some(run.options.clone()),
        surface: None,
        history: run.history.clone(),
        discretisation: Some(disc),
        warnings: run.warnings.clone(),
        measured: None,
    }
}

/// Writes `text` to `path` by [`verification::files::write_file`]: nothing half-written
/// on an error, and never over a link, a directory or a device.
fn write_output(path: &Path, text: &str) -> Result<(), CliError> {
    Ok(verification::files::write_file(path, text)?)
}

fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// The quantities of a one-pulley scene (open ends, the single `pulley`), those present.
fn print_one_pulley(s: &drive::Summary) {
    let line = |label: &str, v: Option<f64>| {
        if let Some(v) = v {
            println!("  {label:<25}  {v:>13.8}");
        }
    };
    line("pulley speed ω  [rad/s]", s.pulley_speed);
    line("tension in / out    [N]", s.tension_in);
    line("                    [N]", s.tension_out);
    line("y at the inflow end [m]", s.y_in);
    line("y at the outflow end [m]", s.y_out);
    if let Some(p) = &s.pulley {
        line("contact arc       [deg]", p.contact_arc.map(deg));
        line("first contact     [deg]", p.contact_start.map(deg));
        line("last contact      [deg]", p.contact_end.map(deg));
        line("stick arc         [deg]", p.stick_arc.map(deg));
        line("slip arc          [deg]", p.slip_arc.map(deg));
        line("torque on pulley  [N·m]", p.torque);
        line("stick → slip point [deg]", p.stick_slip_angle.map(deg));
        line("edge pressure, first [N/m]", p.edge_pressure_start);
        line("edge pressure, last [N/m]", p.edge_pressure_end);
        line("pressure, smallest [N/m]", p.pressure_min);
        line("shear strain, largest", p.shear_strain_max);
        line("moment, first contact [N·m]", p.moment_start);
        line("moment, last contact [N·m]", p.moment_end);
        line("stretch of the stick zone", p.stretch_stick);
        line("slip dissipation    [W]", p.dissipation);
    }
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
        println!("  driven speed ω₂  [rad/s]  {:>13.8}   (driver ω₁ = {} rad/s)", w2, num(&scene.drive.driver_speed));
    }
    if let Some(c) = s.transport_rate {
        println!("  transport rate c   [m/s]  {:>13.8}", c);
    }
    if let Some(v) = s.runoff_velocity {
        println!("  run-off velocity   [m/s]  {:>13.6e}   (+z along the drum axes; the last revolution's slope)", v);
    }
    if let Some(v) = s.settled_runoff_velocity {
        println!("  settled run-off    [m/s]  {:>13.6e}   (after the lateral transient)", v);
    }
    if let Some(d) = s.drift_per_revolution {
        println!("  drift per revolution [m]  {:>13.6e}", d);
    }
    if let Some(e) = s.edge_stress_max {
        println!("  edge stress, largest [Pa] {:>13.6e}", e);
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
        row("stick → slip point [deg]", d1.stick_slip_angle, d2.stick_slip_angle);
        value("stretch of the stick zone", d1.stretch_stick, d2.stretch_stick);
        force("slip dissipation    [W]", d1.dissipation, d2.dissipation);
        force("edge pressure, first [N/m]", d1.edge_pressure_start, d2.edge_pressure_start);
        force("edge pressure, last [N/m]", d1.edge_pressure_end, d2.edge_pressure_end);
        force("pressure, smallest [N/m]", d1.pressure_min, d2.pressure_min);
        force("shear strain, largest", d1.shear_strain_max, d2.shear_strain_max);
        force("moment, first contact [N·m]", d1.moment_start, d2.moment_start);
        force("moment, last contact [N·m]", d1.moment_end, d2.moment_end);
    }
    print_one_pulley(s);
    for note in &run.notes {
        println!("  {note}");
    }
    for w in &run.warnings {
        println!("  warning: {w}");
    }
    if let Some(n) = &run.not_steady {
        println!("  NOT CONVERGED: {n}; the numbers above are the last state of the transient");
    }
    if run.unfitted.as_ref().is_some_and(|u| u.not_converged()) {
        println!("  NOT CONVERGED: the contact fitting (see the warning above); the numbers above are the best fitted solution's");
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

/// The `--verbose` table of where the wall time went (`cost.phases`): the phases that
/// took any time, seconds and share of the wall, then the step counts.
fn print_phases(cost: &verification::run::RunCost) {
    let Some(p) = cost.cost_phases() else { return };
    let wall = cost.wall_seconds;
    println!("time    phase                      seconds   share");
    for (name, seconds) in p.named().into_iter().filter(|(_, s)| *s > 0.0) {
        println!("        {:<24} {seconds:>9.4} {:>6.1}%", name.replace('_', " "), 100.0 * seconds / wall.max(f64::MIN_POSITIVE));
    }
    if p.fitting_passes > 0 {
        println!("        {:<24} {:>9.4} {:>6.1}%   (its Newton solves included)", "fitting, inclusive", p.fitting_total, 100.0 * p.fitting_total / wall.max(f64::MIN_POSITIVE));
    }
    println!(
        "steps   {} Newton iterations, {} continuation steps, {} mesh refinements, {} fitting passes",
        cost.newton_iterations, p.continuation_steps, p.mesh_refinements, p.fitting_passes
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

/// A note on `study` when `--no-compensation` skipped a cambered, turning shell's
/// compensating swivel (one the study would have searched), so that its absence from
/// the study is stated, not silent.
fn note_skipped_compensation(scene: &Scene, args: &StudyArgs, study: &mut verification::study::Study) {
    if args.no_compensation && verification::study::has_compensating_swivel(scene) {
        study.notes.push("the compensating swivel (spec E-5) was not searched (--no-compensation)".to_string());
    }
}

fn study_plan(scene: &Scene, args: &StudyArgs) -> Result<verification::study::StudyPlan> {
    if !SAMPLES_RANGE.contains(&args.samples) {
        return Err(CliError::OutOfRange { flag: "samples", value: args.samples.to_string(), range: format!("{} … {} σ samples", SAMPLES_RANGE.start(), SAMPLES_RANGE.end()) }.into());
    }
    for &n in &args.elements {
        check_elements("elements", n)?;
    }
    for &t in &args.tolerances {
        check_tolerance("tolerances", t)?;
        // the BVP runs of the sweep would each fail: refused before anything runs
        if !bvp::belt::options::tolerance_in_range(t) {
            let (lo, hi) = bvp::belt::options::TOLERANCE_RANGE;
            return Err(CliError::OutOfRange { flag: "tolerances", value: num(&t), range: format!("a BVP tolerance, {} < tolerance ≤ {}", num(&lo), num(&hi)) }.into());
        }
    }
    if scene.belt.theory == drive::scene::Theory::Shell {
        return shell_study_plan(scene, args);
    }
    if !args.levels.is_empty() {
        return Err(CliError::FlagNotForScene { flag: "levels", theory: scene.belt.theory.to_string() }.into());
    }
    if args.refine != RefineArg::Both {
        return Err(CliError::FlagNotForScene { flag: "refine", theory: scene.belt.theory.to_string() }.into());
    }
    if args.no_compensation {
        return Err(CliError::FlagNotForScene { flag: "no-compensation", theory: scene.belt.theory.to_string() }.into());
    }
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
    plan.samples = args.samples;
    match args.reference {
        ReferenceArg::Bvp => {}
        ReferenceArg::ClosedForm => plan.reference = verification::reference::Reference::ClosedForm,
        ReferenceArg::Richardson => {
            let formulation = match args.formulations.first() {
                Some(f) => f.clone(),
                None => verification::run::default_formulation(scene)?,
            };
            let levels = plan.meshes.iter().map(|&n| Discretisation::Elements(n)).collect();
            plan.reference = verification::reference::Reference::Richardson { formulation, levels };
        }
    }
    plan.validate_for(scene)?;
    Ok(plan)
}

/// The study of a shell scene (`StudyPlan::shell`): its levels from `--levels` or the
/// default (the scene's mesh, then 2× and 4× its n_σ at its n_ζ, or for `--refine width`
/// its n_ζ at its n_σ), refined as `--refine` says (σ with Δt, σ alone at the scene's Δt,
/// the scene's Δt halved twice on one mesh, or n_ζ alone at the scene's n_σ and Δt:
/// docs/verification.md "The shell's study"); the flags of the 1-D
/// studies are refused by name. `converge` and `report` find a cambered belt's
/// compensating swivel too (`StudyPlan::with_compensation`; the gate does not).
fn shell_study_plan(scene: &Scene, args: &StudyArgs) -> Result<verification::study::StudyPlan> {
    const SHELL: &str = "fem shell-bfs (the shell's study)";
    const HINT: &str = "a shell study refines n_σ × n_ζ with Δt: give them with --levels (e.g. 64x8,128x8,256x8); its reference is always the Richardson extrapolation of the three finest levels";
    unused(!args.elements.is_empty(), "elements", SHELL, HINT)?;
    unused(!args.tolerances.is_empty(), "tolerances", SHELL, HINT)?;
    unused(!args.formulations.is_empty(), "formulation", SHELL, "the shell has one element (Bogner–Fox–Schmit, docs/fem-shell.md)")?;
    unused(matches!(args.reference, ReferenceArg::ClosedForm), "reference closed-form", SHELL, "the shell has no closed form; its reference is the Richardson extrapolation of its three finest levels")?;
    // the run a solve makes (n_ζ defaulted by the edge layer)
    let own = verification::run::ShellFe::run_of(scene);
    let sizes: Vec<(usize, usize)> = args.levels.iter().map(|l| parse_level(l)).collect::<Result<_, _>>()?;
    let levels: Vec<Discretisation> = match args.refine {
        RefineArg::Step => {
            let (sigma, zeta) = match sizes.as_slice() {
                [] => (own.elements_sigma, own.elements_zeta),
                [one] => *one,
                _ => return Err(CliError::OutOfRange { flag: "levels", value: args.levels.join(","), range: "with --refine step one mesh n_σxn_ζ (the study halves the scene's time step on it twice)".to_string() }.into()),
            };
            (0..3).map(|k| Discretisation::Mesh2d { sigma, zeta, time_step: own.time_step / f64::from(1u32 << k) }).collect()
        }
        RefineArg::Both | RefineArg::Mesh | RefineArg::Width => {
            let sizes = match (sizes.is_empty(), args.refine) {
                (false, _) => sizes,
                (true, RefineArg::Width) => (0..3).map(|k| (own.elements_sigma, own.elements_zeta << k)).collect(),
                (true, _) => (0..3).map(|k| (own.elements_sigma << k, own.elements_zeta)).collect(),
            };
            sizes
                .into_iter()
                .map(|(ns, nz)| match args.refine {
                    RefineArg::Mesh | RefineArg::Width => Discretisation::Mesh2d { sigma: ns, zeta: nz, time_step: own.time_step },
                    _ => verification::run::ShellFe::level(scene, ns, nz),
                })
                .collect()
        }
    };
    // levels that refine in another way than `--refine` asked (e.g. one n_σ under
    // `--refine mesh`): refused, not studied as another kind of limit
    use drive::result::Refinement;
    let what = |kind: Refinement| match kind {
        Refinement::Together => "σ and Δt together",
        Refinement::Mesh => "σ alone at one Δt",
        Refinement::Step => "Δt alone on one mesh",
        Refinement::Width => "n_ζ alone on one σ-mesh at one Δt",
    };
    let (asked, flag) = match args.refine {
        RefineArg::Both => (Refinement::Together, "both"),
        RefineArg::Mesh => (Refinement::Mesh, "mesh"),
        RefineArg::Step => (Refinement::Step, "step"),
        RefineArg::Width => (Refinement::Width, "width"),
    };
    if let Some(kind) = verification::study::shell_refinement(&levels).filter(|&k| k != asked) {
        return Err(CliError::OutOfRange { flag: "levels", value: args.levels.join(","), range: format!("with --refine {flag} levels that refine {}; these refine {}", what(asked), what(kind)) }.into());
    }
    // each level is a valid scene (n_ζ even, the step count within range): refused
    // before anything runs, not as a failed run minutes later
    for &level in &levels {
        if let Discretisation::Mesh2d { sigma, zeta, time_step } = level {
            let which = if args.levels.is_empty() { "the default levels" } else { "--levels" };
            verification::run::ShellFe::scene_at(scene, sigma, zeta, time_step).with_context(|| format!("{which}: the level {level}"))?;
        }
    }
    let mut plan = verification::study::StudyPlan::shell(levels);
    if !args.no_compensation {
        plan = plan.with_compensation();
    }
    plan.samples = args.samples;
    plan.validate_for(scene)?;
    Ok(plan)
}

/// One `--levels` entry `NσxNζ` (`x` or `×`), each count within the scene format's range.
fn parse_level(text: &str) -> Result<(usize, usize), CliError> {
    let bad = || CliError::OutOfRange { flag: "levels", value: text.to_string(), range: "a level n_σxn_ζ such as 64x2: n_σ and n_ζ whole numbers (n_ζ even, docs/fem-shell.md §9.1)".to_string() };
    let (a, b) = text.trim().split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let ns: usize = a.trim().parse().map_err(|_| bad())?;
    let nz: usize = b.trim().parse().map_err(|_| bad())?;
    if ns == 0 || nz == 0 {
        return Err(bad());
    }
    Ok((ns, nz))
}


fn run_converge(args: &ConvergeArgs) -> Result<()> {
    let scene = load_scene(&args.scene)?;
    let plan = study_plan(&scene, &args.study)?;
    let bar = progress_bar();
    let mut study = study_with_progress(&scene, &plan, &bar)?;
    note_skipped_compensation(&scene, &args.study, &mut study);
    bar.finish_and_clear();
    print!("{}", verification::table::study_text(&study));
    println!("\nstudy: {} runs in {:.1} s", plan.run_count(), study.wall_seconds);
    // an unusable study is an error, and nothing is written for it
    study.usable()?;
    if let Some(path) = &args.json {
        let text = verification::report::study_json(&scene, &study)?;
        write_output(path, &text)?;
        println!("study written to {}", path.display());
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

/// Drops the shell scenes from a `report` or `gate` run, saying so on stdout.
fn without_shells(command: &str, scenes: Vec<(PathBuf, Scene)>, why: &str) -> Vec<(PathBuf, Scene)> {
    let (shells, others): (Vec<_>, Vec<_>) = scenes.into_iter().partition(|(_, s)| s.belt.theory == drive::scene::Theory::Shell);
    for (file, scene) in &shells {
        println!("{command}: skipped scene `{}` ({}): {why}", scene.name, file.display());
    }
    others
}

fn run_report(args: &ReportArgs) -> Result<()> {
    let files = scene_files(&args.inputs)?;
    let scenes: Vec<(PathBuf, Scene)> = files.iter().map(|f| Ok((f.clone(), load_scene(f)?))).collect::<Result<_>>()?;
    for (i, (file, scene)) in scenes.iter().enumerate() {
        if let Some((first, _)) = scenes[..i].iter().find(|(_, s)| s.name.eq_ignore_ascii_case(&scene.name)) {
            return Err(CliError::DuplicateSceneName { name: scene.name.clone(), first: first.clone(), second: file.clone() }.into());
        }
    }
    let plans: Vec<verification::study::StudyPlan> =
        scenes.iter().map(|(file, scene)| study_plan(scene, &args.study).with_context(|| format!("scene {}", file.display()))).collect::<Result<_>>()?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let bar = progress_bar();
    let mut entries = Vec::new();
    let mut unsolved = Vec::new();
    for ((file, scene), plan) in scenes.iter().zip(&plans) {
        let mut study = study_with_progress(scene, plan, &bar)?;
        note_skipped_compensation(scene, &args.study, &mut study);
        if let Err(e) = study.usable() {
            unsolved.push(format!("{}: {:#}", scene.name, anyhow::Error::from(e)));
        }
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
    if !unsolved.is_empty() {
        return Err(CliError::Unsolved(unsolved).into());
    }
    Ok(())
}

/// Returns Ok(true) if every scene passed, Ok(false) on drift; usage and input errors
/// (a missing or invalid scene, a bad tolerance or element count, an unknown
/// formulation) are errors before anything runs.
fn run_gate(args: &GateArgs) -> Result<bool> {
    use verification::gate;
    if let Some(t) = args.tolerance {
        check_tolerance("tolerance", t)?;
    }
    for &n in &args.elements {
        check_elements("elements", n)?;
    }
    let files = scene_files(&args.scenes)?;
    let loaded: Vec<(PathBuf, Scene)> = files.iter().map(|f| Ok((f.clone(), load_scene(f)?))).collect::<Result<_>>()?;
    // --bvp-only: a shell has no BVP, so nothing of it would be gated
    let loaded = if args.bvp_only { without_shells("gate --bvp-only", loaded, "no BVP exists for the shell") } else { loaded };
    let (files, scenes): (Vec<PathBuf>, Vec<Scene>) = loaded.into_iter().unzip();
    let shells: Vec<&PathBuf> = files.iter().zip(&scenes).filter(|(_, s)| s.belt.theory == drive::scene::Theory::Shell).map(|(f, _)| f).collect();
    // the 1-D study's flags have no meaning for a shell's levels: refused, not ignored
    if let (Some(file), true) = (shells.first(), !args.elements.is_empty() || args.tolerance.is_some() || !args.formulations.is_empty()) {
        return Err(CliError::ShellGateFlags { file: (*file).clone() }.into());
    }
    // a shell scene is gated as its `gate.steps` part of the rotation
    let scenes: Vec<Scene> = scenes.iter().map(gate::gate_scene).collect();
    let meshes = (!args.elements.is_empty()).then_some(args.elements.as_slice());
    let formulations = if args.bvp_only {
        Some(verification::study::Formulations::Named(Vec::new()))
    } else if !args.formulations.is_empty() {
        Some(verification::study::Formulations::Named(args.formulations.clone()))
    } else {
        None
    };
    let plans: Vec<verification::study::StudyPlan> = scenes
        .iter()
        .zip(&files)
        .map(|(scene, file)| {
            let plan = gate::gate_plan_with(scene, args.tolerance, meshes, formulations.clone());
            plan.validate_for(scene).with_context(|| format!("scene {}", file.display()))?;
            Ok(plan)
        })
        .collect::<Result<_>>()?;
    let start = std::time::Instant::now();
    let bar = progress_bar();
    let mut outcomes = Vec::new();
    for (scene, plan) in scenes.iter().zip(&plans) {
        let study = study_with_progress(scene, plan, &bar)?;
        outcomes.push(gate::evaluate(&scene.gate_settings(), &study));
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
        write_output(path, &text)?;
        println!("checks written to {}", path.display());
    }
    Ok(passed)
}

// ---------------------------------------------------------------------------
// Outside codes: check, reference

/// `beltcheck check`: Ok(true) if every check passed, Ok(false) on drift; a bad file or
/// argument is an error before anything is written.
fn run_check(args: &CheckArgs) -> Result<bool> {
    use verification::check::{self, ReferenceChoice};
    if !SAMPLES_RANGE.contains(&args.samples) {
        return Err(CliError::OutOfRange { flag: "samples", value: args.samples.to_string(), range: format!("{} … {} σ samples", SAMPLES_RANGE.start(), SAMPLES_RANGE.end()) }.into());
    }
    let scene = load_scene(&args.scene)?;
    let choice = match args.reference {
        CheckReferenceArg::Auto => ReferenceChoice::Auto,
        CheckReferenceArg::Bvp => ReferenceChoice::Bvp,
        CheckReferenceArg::ClosedForm => ReferenceChoice::ClosedForm,
        CheckReferenceArg::Supplied => ReferenceChoice::Supplied,
    };
    let checked = check::check(&scene, &args.results, args.json.as_slice(), choice, args.samples)?;
    let passed = checked.passed();
    println!("beltcheck check: {} — {} outside method(s)", scene.name, checked.study.series.len());
    print!("{}", verification::table::study_text(&checked.study));
    if !checked.skipped.is_empty() {
        println!("
skipped {} file(s):", checked.skipped.len());
        print!("{}", check::skip_table(&checked.skipped).to_text("  "));
    }
    let outcomes = [checked.gate.clone()];
    println!();
    print!("{}", verification::gate::summary_table(&outcomes).to_text("  "));
    for n in &checked.gate.notes {
        println!("  note: {n}");
    }
    if passed {
        println!("\npassed: every gated quantity within its limit");
    } else {
        let failures = verification::gate::failure_table(&outcomes);
        println!("\nFAILED: {} check(s) out of their limits", failures.rows.len());
        print!("{}", failures.to_text("  "));
    }
    if let Some(dir) = &args.report {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        // the report shows the scene's own FE formulations at the same meshes beside the
        // outside code (not gated: the verdict above is the outside code's)
        let study = checked.study.clone().with_built_in_fem(&scene);
        let entry = verification::report::write_scene_report(&scene, &args.scene, &study, dir)
            .with_context(|| format!("writing the report of {}", scene.name))?;
        println!("report: {}", entry.markdown.display());
    }
    if let Some(path) = &args.json {
        let text = serde_json::to_string_pretty(&serde_json::json!({"gate": &checked.gate, "skipped": &checked.skipped}))?;
        write_output(path, &text)?;
        println!("checks written to {}", path.display());
    }
    Ok(passed)
}

/// Why `reference --sigma FILE` refuses the file.
#[derive(Debug, thiserror::Error)]
enum SigmaFileError {
    #[error("{}: cannot read: {error}", .file.display())]
    Read { file: PathBuf, error: std::io::Error },
    #[error("{}: line {line}: `{token}` is not a finite number (σ in m)", .file.display())]
    NotANumber { file: PathBuf, line: usize, token: String },
    #[error("{}: no σ value in the file", .file.display())]
    Empty { file: PathBuf },
}

/// σ values of a file: numbers separated by commas, blanks or newlines; `#` comments.
fn read_sigma_file(file: &Path) -> Result<Vec<f64>, SigmaFileError> {
    let text = std::fs::read_to_string(file).map_err(|error| SigmaFileError::Read { file: file.to_path_buf(), error })?;
    let mut sigma = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        for token in line.split(|c: char| c == ',' || c.is_whitespace()).filter(|t| !t.is_empty()) {
            match token.parse::<f64>() {
                Ok(v) if v.is_finite() => sigma.push(v),
                _ => return Err(SigmaFileError::NotANumber { file: file.to_path_buf(), line: i + 1, token: drive::error::clip(token) }),
            }
        }
    }
    if sigma.is_empty() {
        return Err(SigmaFileError::Empty { file: file.to_path_buf() });
    }
    Ok(sigma)
}

/// `beltcheck reference`: the reference sampled at the σ asked for, as result JSON or
/// CSV; nothing is written on an error.
fn run_reference(args: &ReferenceArgs) -> Result<()> {
    check_tolerance("tolerance", args.tolerance)?;
    if let Some(n) = args.samples {
        if !(1..=*SAMPLES_RANGE.end()).contains(&n) {
            return Err(CliError::OutOfRange { flag: "samples", value: n.to_string(), range: format!("1 … {} σ samples", SAMPLES_RANGE.end()) }.into());
        }
    }
    let sigma_file = args.sigma.as_deref().map(read_sigma_file).transpose()?;
    let scene = load_scene(&args.scene)?;
    let (label, solved) = verification::check::reference_solution(&scene, args.tolerance).map_err(|e| anyhow::Error::new(e).context("the reference (BVP run)"))?;
    let sigma = sigma_file.unwrap_or_else(|| {
        let n = args.samples.unwrap_or(200);
        let l = scene.path().length();
        (0..n).map(|i| l * i as f64 / n as f64).collect()
    });
    let fields = drive::view::fields_at(solved.view.as_ref(), sigma);
    let result = run_result(&scene, &label, Discretisation::Tolerance(args.tolerance), &solved, Some(fields));
    let text = match args.format {
        FormatArg::Json => result.to_json_pretty()? + "\n",
        FormatArg::Csv => verification::outside::to_csv(&result)?,
    };
    match &args.out {
        Some(path) => {
            write_output(path, &text)?;
            eprintln!("reference written to {}", path.display());
        }
        None => print!("{text}"),
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Parameter studies: sweep

/// `beltcheck sweep` (docs/sweep.md): every argument checked before anything runs; the
/// report is written even when points have no solution, and those make exit status 2.
fn run_sweep(args: &SweepArgs) -> Result<()> {
    use verification::sweep::{ParamRange, Sweep, SweepPlan};
    let params: Vec<ParamRange> = args.params.iter().map(|p| p.parse()).collect::<Result<_, _>>()?;
    if let Some(t) = args.tolerance {
        check_tolerance("tolerance", t)?;
    }
    if let Some(n) = args.fe_elements {
        check_elements("fe-elements", n)?;
    }
    let scene = load_scene(&args.scene)?;
    let mut plan = SweepPlan::new(&scene, params, args.fe_points)?;
    if let Some(t) = args.tolerance {
        plan.tolerance = t;
    }
    if let Some(n) = args.fe_elements {
        plan.fe_elements = n;
    }
    plan.asymptotes = !args.no_asymptotes;
    let bar = progress_bar();
    bar.set_prefix(scene.name.clone());
    let update = |p: verification::sweep::Progress| {
        bar.set_length(p.total as u64);
        bar.set_position(p.done as u64);
        bar.set_message(p.label);
    };
    let sweep = Sweep::run(&scene, &plan, &update);
    bar.finish_and_clear();
    // the command as given, for the report
    let command = std::iter::once("beltcheck".to_string()).chain(std::env::args().skip(1)).collect::<Vec<_>>().join(" ");
    let files = verification::sweep::write_sweep(&sweep, &command, &args.out)?;
    println!(
        "beltcheck sweep: {} — {} of {} BVP points solved in {:.1} s ({} thread(s)), {} FE spot check(s)",
        scene.name,
        sweep.solved(),
        plan.point_count(),
        sweep.wall_seconds,
        sweep.threads,
        sweep.fe_checks.len()
    );
    for f in &files {
        println!("  {}", f.display());
    }
    let failures = sweep.failures();
    if !failures.is_empty() {
        anyhow::bail!("{} point(s) or check(s) without a solution:\n  {}", failures.len(), failures.join("\n  "));
    }
    Ok(())
}
