//! Reports: per scene a Markdown page with SVG plots, the tables, the effects that were
//! simulated (and that nothing else was), the scene and options used; a JSON with every
//! number; and an index page over all scenes.
//!
//! Layout under the output directory `DIR`:
//! ```text
//! DIR/index.md                    one row per scene, links
//! DIR/<scene>/report.md           the report
//! DIR/<scene>/shape.svg           belt to scale + deflection
//! DIR/<scene>/force.svg           axial force (and moment) along σ
//! DIR/<scene>/convergence.svg     error vs elements / tolerance
//! DIR/<scene>/work-precision.svg  error vs wall time
//! DIR/<scene>/study.json          every number of the study + the reference fields
//! ```

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use drive::result::Refinement;
use drive::scene::{Scene, Theory};
use serde::{Deserialize, Serialize};

use crate::plot;
use crate::run::{fmt_tolerance, Discretisation, Family, Run, RunData};
use crate::study::{Formulations, SeriesStatus, Study};
use crate::table::{self, fmt_error, fmt_seconds, Table};

/// Why a report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file could not be written (nothing of the scene's set is left half-written).
    #[error(transparent)]
    Write(#[from] crate::files::WriteError),
    /// A plot failed.
    #[error(transparent)]
    Plot(#[from] plot::PlotError),
    /// JSON serialisation failed (a non-finite number would be one cause).
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
}

/// What the index needs of one written report.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ReportEntry {
    /// Scene name.
    pub scene: String,
    /// Scene description.
    pub description: String,
    /// The scene file the report was made from.
    pub scene_file: PathBuf,
    /// The Markdown report.
    pub markdown: PathBuf,
    /// Every file written (SVGs and JSON, besides the Markdown).
    pub files: Vec<PathBuf>,
    /// Theory and analysis, e.g. `string, static`.
    pub model: String,
    /// Methods studied (labels).
    pub methods: Vec<String>,
    /// FE status in words.
    pub fem: String,
    /// Largest summary-scalar error at the finest successful tolerance over the BVP
    /// variants (where computable).
    pub bvp_error: Option<f64>,
    /// Largest summary-scalar error at the finest mesh over the FE formulations.
    pub fem_error: Option<f64>,
    /// Largest mutual-convergence error of a summary scalar over the FE formulations.
    pub mutual: Option<f64>,
    /// Wall time of the study, s.
    pub wall_seconds: f64,
}

/// Fields of the reference at a reporting resolution, for the JSON.
#[derive(Debug, Clone, Serialize)]
struct FieldsOut {
    sigma: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    deflection: Vec<f64>,
    tension: Vec<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    moment: Option<Vec<f64>>,
    state: Vec<drive::view::ContactState>,
    /// A shear-deformable rod's p and Γ₂ on the σ grid refined at the contact edges
    /// (what `force.svg` plots), in full.
    #[serde(skip_serializing_if = "Option::is_none")]
    refined: Option<crate::run::EdgeDetail>,
}

fn fields_out(d: &RunData, every: usize) -> FieldsOut {
    let s = &d.samples;
    let pick = |v: &Vec<f64>| v.iter().step_by(every.max(1)).copied().collect::<Vec<f64>>();
    FieldsOut {
        sigma: pick(&s.sigma),
        x: pick(&s.x),
        y: pick(&s.y),
        deflection: pick(&s.deflection),
        tension: pick(&s.tension),
        moment: s.moment.as_ref().map(pick),
        state: s.state.iter().step_by(every.max(1)).copied().collect(),
        refined: s.edges.clone(),
    }
}

/// A run as JSON: status `solved` with its data, or `not_applicable` / `failed` with the
/// reason.
#[derive(Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
enum RunOut<'a> {
    Solved { method: &'a str, discretisation: crate::run::Discretisation, summary: &'a drive::summary::Summary, cost: &'a crate::run::RunCost, options: &'a serde_json::Value, terms: &'a [String], notes: &'a [String], #[serde(skip_serializing_if = "<[String]>::is_empty")] warnings: &'a [String] },
    NotApplicable { method: &'a str, discretisation: crate::run::Discretisation, wall_seconds: f64, reason: String },
    Failed { method: &'a str, discretisation: crate::run::Discretisation, wall_seconds: f64, reason: String },
}

fn run_out(r: &Run) -> RunOut<'_> {
    match &r.outcome {
        Ok(d) => RunOut::Solved { method: &r.method, discretisation: r.discretisation, summary: &d.summary, cost: &d.cost, options: &d.options, terms: &d.terms, notes: &d.notes, warnings: &d.warnings },
        Err(crate::run::RunError::NotApplicable(m)) => RunOut::NotApplicable { method: &r.method, discretisation: r.discretisation, wall_seconds: r.wall_seconds, reason: m.clone() },
        Err(e) => RunOut::Failed { method: &r.method, discretisation: r.discretisation, wall_seconds: r.wall_seconds, reason: e.to_string() },
    }
}

/// Every number of a study as pretty JSON: the scene, the plan, the quantities, the
/// reference (with its fields at 512 points, and a shear-deformable rod's p and Γ₂ on
/// the refined grid as `reference_fields.refined`), and per series per run the summary,
/// cost, errors and orders, plus Richardson extrapolation and mutual convergence.
///
/// # Errors
/// serde_json's error (cannot happen for finite numbers; undefined numbers are `null`).
pub fn study_json(scene: &Scene, study: &Study) -> Result<String, serde_json::Error> {
    let every = (study.plan.samples / 512).max(1);
    let series: Vec<serde_json::Value> = study
        .series
        .iter()
        .map(|s| {
            let rows: Vec<serde_json::Value> = s
                .rows
                .iter()
                .map(|r| {
                    let errors: serde_json::Map<String, serde_json::Value> =
                        study.quantities.iter().zip(&r.errors).map(|(q, e)| (q.name.clone(), serde_json::json!(e))).collect();
                    let orders: serde_json::Map<String, serde_json::Value> =
                        study.quantities.iter().zip(&r.orders).map(|(q, p)| (q.name.clone(), serde_json::json!(p))).collect();
                    serde_json::json!({
                        "run": run_out(&r.run),
                        "errors": errors,
                        "orders": orders,
                        "scalar_error": r.scalar_error,
                        "scalar_order": r.scalar_order,
                    })
                })
                .collect();
            serde_json::json!({
                "method": s.method,
                "family": s.family,
                "status": s.status,
                "terms": s.terms,
                "rows": rows,
                "extrapolation": s.extrapolation,
            })
        })
        .collect();
    let v = serde_json::json!({
        "scene": scene,
        "plan": study.plan,
        "quantities": study.quantities,
        "reference": run_out(&study.reference),
        "reference_fields": study.reference.data().map(|d| fields_out(d, every)),
        "reference_estimates": study.reference_estimates,
        "series": series,
        "registered_formulations": study.registered_formulations,
        "notes": study.notes,
        "wall_seconds": study.wall_seconds,
        "compensation": study.compensation,
    });
    serde_json::to_string_pretty(&v)
}

/// Every effect a scene can call for, in the order of [`Scene::effect_names`].
const ALL_EFFECTS: [&str; 5] = ["gravity", "transport inertia", "frictionless contact", "coulomb friction", "elastic interlayer contact"];

/// The structural terms of a theory, and those it leaves out.
fn theory_terms(t: Theory) -> (&'static str, &'static str) {
    match t {
        Theory::String => ("axial stretching (EA)", "bending, shear"),
        Theory::Kirchhoff => ("axial stretching (EA), bending (EI)", "shear"),
        Theory::Cosserat => ("axial stretching (EA), bending (EI), shear (GA)", "—"),
        Theory::Shell => ("membrane stretching, bending (Kirchhoff–Love)", "transverse shear"),
    }
}

/// The worst summary-scalar error at the finest successful discretisation over the
/// studied series of a family (over the series where it is computable).
fn worst_finest(study: &Study, family: Family) -> Option<f64> {
    study
        .series
        .iter()
        .filter(|s| s.family == family && s.status == SeriesStatus::Studied)
        .filter_map(|s| s.rows.iter().rev().find(|r| r.run.data().is_some()).and_then(|r| r.scalar_error))
        .reduce(f64::max)
}

/// The worst mutual-convergence error over the summary scalars of the FE formulations
/// (over the scalars where it is computable).
fn worst_mutual(study: &Study) -> Option<f64> {
    // a shell's extrapolation is its reference: no mutual convergence to state
    if study.plan.shell_levels().is_some() {
        return None;
    }
    study
        .series
        .iter()
        .filter(|s| s.family == Family::Fem && s.status == SeriesStatus::Studied)
        .flat_map(|s| s.extrapolation.iter().zip(&study.quantities).filter(|(_, q)| q.is_scalar()).filter_map(|(e, _)| e.mutual))
        .reduce(f64::max)
}

fn fem_status(study: &Study) -> String {
    if study.registered_formulations.is_empty() {
        return "no FE formulation registered".into();
    }
    let studied: Vec<&str> = study.series.iter().filter(|s| s.family == Family::Fem && s.status == SeriesStatus::Studied).map(|s| s.method.as_str()).collect();
    if studied.is_empty() {
        "no registered FE formulation applies".into()
    } else {
        studied.join(", ")
    }
}

/// Writes the report of one scene under `dir/<scene>/` (module docs) and returns what
/// the index needs.
///
/// # Errors
/// A file that cannot be written or a plot that cannot be drawn.
pub fn write_scene_report(scene: &Scene, scene_file: &Path, study: &Study, dir: &Path) -> Result<ReportEntry, ReportError> {
    let sdir = dir.join(&scene.name);
    crate::files::create_dir(&sdir)?;
    // a shell's study is a transient over (σ, ζ): its run-off in time and its contact
    // maps in place of the belt's shape and axial force along σ
    let (first, second) = if study.plan.shell_levels().is_some() {
        (("runoff.svg", crate::plot_shell::runoff_svg(study)?), ("contact-maps.svg", crate::plot_shell::contact_maps_svg(study)?))
    } else {
        (("shape.svg", plot::shape_svg(scene, study)?), ("force.svg", plot::force_svg(scene, study)?))
    };
    let texts = [
        first,
        second,
        ("convergence.svg", plot::convergence_svg(scene, study)?),
        ("work-precision.svg", plot::work_precision_svg(scene, study)?),
        ("study.json", study_json(scene, study)?),
        ("report.md", scene_markdown(scene, scene_file, study)),
    ];
    let set: Vec<(PathBuf, &str)> = texts.iter().map(|(name, text)| (sdir.join(name), text.as_str())).collect();
    crate::files::write_all(&set)?;
    // the page itself is `markdown`; `files` are what it shows and links
    let (page, shown) = set.split_last().expect("six files");
    let files: Vec<PathBuf> = shown.iter().map(|(p, _)| p.clone()).collect();
    let mp = page.0.clone();
    Ok(ReportEntry {
        scene: scene.name.clone(),
        description: scene.description.clone(),
        scene_file: scene_file.to_path_buf(),
        markdown: mp,
        files,
        model: format!("{}, {}", scene.belt.theory, scene.analysis),
        methods: study.series.iter().filter(|s| s.status == SeriesStatus::Studied).map(|s| s.method.clone()).collect(),
        fem: fem_status(study),
        bvp_error: worst_finest(study, Family::Bvp),
        fem_error: worst_finest(study, Family::Fem),
        mutual: worst_mutual(study),
        wall_seconds: study.wall_seconds,
    })
}

/// The command that regenerates a plan's study (for the report's "reproduce" line).
fn command_of(scene_file: &Path, study: &Study) -> String {
    let mut c = format!("beltcheck converge {}", scene_file.display());
    if let Some(levels) = study.plan.shell_levels() {
        let mut sizes: Vec<String> = levels.iter().filter_map(|d| if let Discretisation::Mesh2d { sigma, zeta, .. } = d { Some(format!("{sigma}x{zeta}")) } else { None }).collect();
        match study.plan.shell_refinement() {
            // one mesh, its time step halved twice from the scene's
            Some(Refinement::Step) => {
                sizes.truncate(1);
                let _ = write!(c, " --refine step");
            }
            Some(Refinement::Mesh) => {
                let _ = write!(c, " --refine mesh");
            }
            Some(Refinement::Width) => {
                let _ = write!(c, " --refine width");
            }
            _ => {}
        }
        let _ = write!(c, " --levels {}", sizes.join(","));
        // a report's shell study asks for the compensating swivel unless told not to
        if !study.plan.compensate {
            let _ = write!(c, " --no-compensation");
        }
        return c;
    }
    if let Formulations::Named(n) = &study.plan.formulations {
        for f in n {
            let _ = write!(c, " --formulation {f}");
        }
    }
    let _ = write!(c, " --elements {}", study.plan.meshes.iter().map(|n| n.to_string()).collect::<Vec<_>>().join(","));
    c
}

/// The Markdown of one scene.
/// The scene's `peer` block beside the BVP reference: quantity, published value, ours,
/// relative difference (ours − peer)/|peer|. Documentation only (never gated).
fn peer_section(m: &mut String, peer: &drive::scene::Peer, study: &Study) {
    let _ = writeln!(m, "## Published results of another code\n");
    let _ = writeln!(m, "Peer: {}.", peer.source);
    if !peer.reference.is_empty() {
        let _ = writeln!(m, "Published in: {}.", peer.reference);
    }
    let _ = writeln!(m, "\n| quantity | peer | beltcheck reference | (ours − peer)/\\|peer\\| |\n|:--|--:|--:|--:|");
    let ours = study.reference.data().map(|d| &d.summary);
    for (name, &theirs) in &peer.values {
        let mine = ours.and_then(|s| s.get(name));
        let (mine_s, diff) = match mine {
            Some(v) => (format!("{v:.6}"), if theirs != 0.0 { format!("{:+.2} %", 100.0 * (v - theirs) / theirs.abs()) } else { "—".into() }),
            None => ("—".into(), "—".into()),
        };
        let _ = writeln!(m, "| `{name}` | {theirs} | {mine_s} | {diff} |");
    }
    if !peer.note.is_empty() {
        let _ = writeln!(m, "\n{}", peer.note);
    }
    m.push('\n');
}

pub fn scene_markdown(scene: &Scene, scene_file: &Path, study: &Study) -> String {
    let mut m = String::new();
    let _ = writeln!(m, "# {}\n", scene.name);
    if !scene.description.is_empty() {
        let _ = writeln!(m, "{}\n", scene.description);
    }
    let _ = writeln!(
        m,
        "Scene file `{}` · {} belt, {} analysis · generated by `beltcheck report` (beltcheck {}) · [all numbers as JSON](study.json) · [index](../index.md)\n",
        scene_file.display(),
        scene.belt.theory,
        scene.analysis,
        env!("CARGO_PKG_VERSION")
    );

    // Summary.
    let _ = writeln!(m, "## Summary\n");
    let _ = writeln!(m, "- {}", table::reference_line(study));
    let _ = writeln!(m, "- FE: {}", fem_status(study));
    for n in &study.notes {
        let _ = writeln!(m, "- note: {n}");
    }
    let shell = study.plan.shell_levels().is_some();
    if shell {
        let _ = writeln!(m, "- no BVP exists for the shell: every level is held against the Richardson extrapolation of the three finest, so the finest level's error is the reference's own error estimate");
        let _ = writeln!(m, "- largest relative error of an extrapolated summary scalar at the finest level: {}", fmt_error(worst_finest(study, Family::Fem)));
    } else {
        let _ = writeln!(m, "- largest relative error of a summary scalar at the finest successful tolerance, BVP variants: {}", fmt_error(worst_finest(study, Family::Bvp)));
    }
    if study.has_fem() && !shell {
        let _ = writeln!(m, "- largest relative error of a summary scalar at the finest successful mesh, FE: {}", fmt_error(worst_finest(study, Family::Fem)));
        let _ = writeln!(m, "- largest error of a Richardson-extrapolated FE scalar against the reference (mutual convergence; over the scalars where the extrapolation is defined): {}", fmt_error(worst_mutual(study)));
    }
    let _ = writeln!(m, "- study: {} runs in {} s (runs one after another, so wall times compare)\n", study.plan.run_count(), fmt_seconds(Some(study.wall_seconds)));

    if let Some(peer) = &scene.peer {
        peer_section(&mut m, peer, study);
    }

    // Effects.
    let _ = writeln!(m, "## Effects simulated\n");
    let effects = scene.effect_names();
    let absent: Vec<&str> = ALL_EFFECTS.iter().copied().filter(|e| !effects.iter().any(|x| x == e)).collect();
    let (terms, no_terms) = theory_terms(scene.belt.theory);
    let _ = writeln!(m, "- effects the scene calls for (and the only ones simulated): **{}**", effects.join(", "));
    let _ = writeln!(m, "- not simulated: {}", if absent.is_empty() { "—".to_string() } else { absent.join(", ") });
    let _ = writeln!(m, "- belt theory `{}`: {}; not modelled: {}", scene.belt.theory, terms, no_terms);
    let fe: Vec<_> = study.series.iter().filter(|s| s.family == Family::Fem).collect();
    if fe.is_empty() {
        let _ = writeln!(m, "- FE terms assembled: — (no FE formulation ran)");
    }
    for s in fe {
        match &s.status {
            SeriesStatus::NotApplicable(why) => {
                let _ = writeln!(m, "- {}: not applicable to this scene ({why})", s.method);
            }
            SeriesStatus::Studied if s.terms.is_empty() => {
                let _ = writeln!(m, "- {}: terms assembled — (not reported by the formulation)", s.method);
            }
            SeriesStatus::Studied => {
                let _ = writeln!(m, "- {}: terms assembled: {}", s.method, s.terms.join("; "));
            }
        }
    }
    if let Some(d) = study.reference.data() {
        for n in &d.notes {
            let _ = writeln!(m, "- reference: {n}");
        }
    }
    m.push('\n');

    // Plots.
    let against = match study.plan.shell_refinement() {
        Some(Refinement::Step) => "against the step's refinement Δt₀/Δt on the one mesh",
        Some(Refinement::Width) => "against the elements across the width n_ζ on the one σ-mesh",
        _ => "against elements along σ",
    };
    let convergence_caption = format!("Error of each level against the Richardson extrapolation of the three finest, {against}, with reference slopes.");
    let shell_plots = [
        ("Run-off in time", "The belt's lateral offset z̄(t) (the width-averaged lateral position of the belt, docs/fem-shell.md §9.3) and its rate, every level of the study (light to dark: coarse to fine). The reference text gives no measured run-off: `beltcheck solve SCENE --measured FILE.csv` overlays a user's (t, lateral) samples with the difference.", "run-off", "runoff.svg"),
        ("Contact maps", "Contact pressure Pγ and interlayer shear stress P_⊥|u| over (σ, ζ) at the last frame of the finest level (each cell coloured by the mean of its corner nodes; |u| is the interlayer's committed tangential displacement, extrapolated across the width from the Gauss points of each node's ζ-elements).", "contact maps", "contact-maps.svg"),
        ("Convergence", convergence_caption.as_str(), "convergence", "convergence.svg"),
        ("Work–precision", "Error against wall time, every level of this scene.", "work–precision", "work-precision.svg"),
    ];
    let plots = [
        ("Belt shape", "The reference belt to scale with the pulleys (radius to the belt centreline); contact zones thick, contact boundaries as dots; FE finest meshes dashed. Below: the deflection ν(σ) from the contour, magnified.", "belt shape", "shape.svg"),
        ("Axial force along σ", "The reference and the finest mesh of each FE formulation; bottom: |N − N_ref| of the finest run of every method.", "axial force", "force.svg"),
        ("Convergence", "Left: FE error against elements with reference slopes. Right: BVP error against the requested tolerance (the tolerance bounds a residual, not the error, so points may sit on either side of the dashed line).", "convergence", "convergence.svg"),
        ("Work–precision", "Error against wall time, every method of this scene on one axis (the reference run itself is not plotted).", "work–precision", "work-precision.svg"),
    ];
    let refined = study.reference.data().and_then(|d| d.samples.edges.as_ref());
    for (title, caption, alt, file) in if shell { shell_plots } else { plots } {
        match refined {
            Some(d) if file == "force.svg" => {
                let _ = writeln!(m, "## {title}, contact pressure and shear strain\n\n{caption} {}\n\n![{alt}]({file})\n", refined_caption(d, study.plan.samples));
            }
            _ => {
                let _ = writeln!(m, "## {title}\n\n{caption}\n\n![{alt}]({file})\n");
            }
        }
    }

    // Tables.
    let _ = writeln!(m, "## Convergence tables\n");
    if !study.reference_estimates.is_empty() {
        let _ = writeln!(m, "### The reference's values\n\nRichardson extrapolation of the three finest levels: per scalar the extrapolated value, the observed order and the error estimate |q_R − q_finest| (quantities whose levels oscillate or do not converge are left out; the notes above name them).\n");
        m.push_str(&table::estimate_table(&study.reference_estimates).to_markdown());
        m.push('\n');
    }
    if let Some(c) = &study.compensation {
        let _ = writeln!(m, "### The compensating swivel

The constant swivel of the steering drum that cancels the camber's run-off (spec E-5: two solves give a linear estimate, secant steps bracket the root and Brent's method finds it, each evaluation a whole solve at the coarsest level; docs/fem-shell.md §14): {}.
", table::compensation_text(c));
    }
    let _ = writeln!(
        m,
        "Errors are relative to the reference: *scalars* = the largest |q − q_ref|/|q_ref| over the {} summary scalars (polar angles: |q − q_ref| wrapped, over π); field norms ‖f − f_ref‖/‖f_ref‖ (max or L2 over {} uniform σ samples). FE *rate* = log(e_(k−1)/e_k)/log(r), r the refinement ratio (n_k/n_(k−1), or Δt_(k−1)/Δt_k for a shell study of the step, n_ζ,k/n_ζ,(k−1) for one of the width). BVP rows have no rate: an order against a tolerance is not meaningful. \"—\" = not computable.\n",
        study.quantities.iter().filter(|q| q.is_scalar()).count(),
        study.plan.samples
    );
    for s in &study.series {
        match &s.status {
            SeriesStatus::NotApplicable(why) => {
                let _ = writeln!(m, "### {}\n\nNot applicable to this scene: {why}\n", s.method);
            }
            SeriesStatus::Studied => {
                let _ = writeln!(m, "### {}\n", s.method);
                m.push_str(&table::convergence_table(study, s).to_markdown());
                for f in table::failures(s) {
                    let _ = writeln!(m, "\n- {f}");
                }
                m.push('\n');
            }
        }
    }
    let _ = writeln!(m, "### Error per quantity at the finest discretisation\n");
    m.push_str(&table::quantity_table(study).to_markdown());
    m.push('\n');
    // a shell's series extrapolates to the reference itself: nothing mutual to show
    let fe_studied: Vec<_> = study.series.iter().filter(|s| !shell && s.family == Family::Fem && s.status == SeriesStatus::Studied).collect();
    if shell {
        let _ = writeln!(m, "### Mutual convergence\n\n— (no BVP exists for the shell: the reference is the extrapolation of these levels, tabled above)\n");
    } else {
        let _ = writeln!(m, "### Mutual convergence FE ↔ BVP\n");
    }
    if fe_studied.is_empty() && !shell {
        let _ = writeln!(m, "— ({}: nothing to extrapolate)\n", fem_status(study));
    }
    for s in fe_studied {
        let _ = writeln!(m, "{}: Richardson extrapolation over the three finest meshes with the self-convergence order p (self), and its error against the reference.\n", s.method);
        m.push_str(&table::mutual_table(s).to_markdown());
        m.push('\n');
    }

    // Reproduce.
    let _ = writeln!(m, "## Scene and options used\n");
    let _ = writeln!(m, "Reproduce the study: `{}`\n", command_of(scene_file, study));
    let plan = &study.plan;
    let _ = writeln!(m, "- reference: {}", plan.reference.label());
    for b in &plan.bvp {
        let _ = writeln!(m, "- {}: tolerances {}", b.variant.label(), b.tolerances.iter().map(|&t| fmt_tolerance(t)).collect::<Vec<_>>().join(", "));
    }
    let _ = writeln!(
        m,
        "- FE: {} over elements {:?} (registered: {})",
        match &plan.formulations {
            Formulations::Discovered => "every registered formulation".to_string(),
            Formulations::Named(n) => n.join(", "),
        },
        plan.meshes,
        if study.registered_formulations.is_empty() { "none".to_string() } else { study.registered_formulations.join(", ") }
    );
    let _ = writeln!(m, "- field norms over {} uniform σ samples\n", plan.samples);
    let _ = writeln!(m, "Scene:\n\n```json\n{}\n```\n", serde_json::to_string_pretty(scene).unwrap_or_default());
    if let Some(d) = study.reference.data() {
        let _ = writeln!(m, "Options of the reference run:\n\n```json\n{}\n```", serde_json::to_string_pretty(&d.options).unwrap_or_default());
    }
    m
}

/// How the pressure and shear-strain panels of a shear-deformable rod are sampled, for
/// the caption of `force.svg`.
fn refined_caption(d: &crate::run::EdgeDetail, uniform: usize) -> String {
    use crate::run::EdgeDetail;
    format!(
        "The contact pressure p(σ) has finite peaks of width √(a/(b₂ − ρc²)) at the contact edges, about as wide as a few uniform samples, so p and the shear strain Γ₂ = Q/b₂ are plotted on a refined σ grid ({} points): the {uniform} uniform samples plus, at each of the {} changes of the contact state, the two ends of a bracket bisected to {:.0e}·L and {} points on each side at 2Δ·{}ʲ from it (Δ = L/{uniform}; the nearest about 3e-7·Δ away). The close-ups show p within ±{} shear layers of each contact edge with the refined samples as dots and the edge pressure labelled; the FE curves (dashed) are on their own refined grid where the FE view gives Γ₂ (the Cosserat elements), else on their uniform samples. The error norms use the uniform samples only.",
        d.sigma.len(),
        d.edges.len(),
        EdgeDetail::BRACKET,
        EdgeDetail::CLUSTER,
        EdgeDetail::RATIO,
        plot::EDGE_WINDOW
    )
}

/// Writes `dir/index.md`: one row per scene with model, methods, FE status, worst
/// errors and links, sorted by scene name — and the same entries as `dir/index.json`.
///
/// The index covers every report in `dir`, not only the ones just written: entries of
/// an earlier `index.json` whose scene is not among `entries` are kept while their
/// Markdown report still exists (so `report one-scene.json -o reports/` refreshes one
/// row instead of dropping the others). An unreadable earlier `index.json` is ignored.
///
/// # Errors
/// A file that cannot be written.
pub fn write_index(entries: &[ReportEntry], dir: &Path) -> Result<PathBuf, ReportError> {
    let json = dir.join("index.json");
    let earlier: Vec<ReportEntry> =
        std::fs::read_to_string(&json).ok().and_then(|t| serde_json::from_str(&t).ok()).unwrap_or_default();
    let mut all: Vec<ReportEntry> = earlier
        .into_iter()
        .filter(|old| !entries.iter().any(|e| e.scene == old.scene))
        .filter_map(|mut old| {
            // Where `report` puts a scene's page; re-rooted at `dir` (the earlier run may
            // have named the directory differently).
            let page = dir.join(&old.scene).join("report.md");
            page.exists().then(|| {
                old.markdown = page;
                old
            })
        })
        .chain(entries.iter().cloned())
        .collect();
    all.sort_by(|a, b| a.scene.cmp(&b.scene));
    let entries = &all[..];
    let index_json = serde_json::to_string_pretty(entries)?;
    let mut m = String::new();
    let _ = writeln!(m, "# beltcheck reports\n");
    let _ = writeln!(m, "Each scene of the catalogue computed two independent ways — BVP references and MEL finite elements — and held against each other. Regenerate with `cargo run --release -- report scenes/ -o reports/` (see docs/verification.md).\n");
    let mut t = Table::new(["scene", "model", "methods", "FE", "BVP worst scalar error (finest)", "FE worst scalar error (finest)", "FE↔BVP after Richardson (worst scalar)", "study [s]"]);
    t.left = vec![0, 1, 2, 3];
    for e in entries {
        let rel = e.markdown.strip_prefix(dir).unwrap_or(&e.markdown);
        t.push(vec![
            format!("[{}]({})", e.scene, rel.display()),
            e.model.clone(),
            e.methods.iter().map(|s| s.trim_start_matches("bvp-")).collect::<Vec<_>>().join(", "),
            e.fem.clone(),
            fmt_error(e.bvp_error),
            fmt_error(e.fem_error),
            fmt_error(e.mutual),
            fmt_seconds(Some(e.wall_seconds)),
        ]);
    }
    m.push_str(&t.to_markdown());
    m.push('\n');
    for e in entries {
        if !e.description.is_empty() {
            let _ = writeln!(m, "- **{}**: {}", e.scene, e.description);
        }
    }
    let p = dir.join("index.md");
    crate::files::write_all(&[(json, index_json.as_str()), (p.clone(), m.as_str())])?;
    Ok(p)
}
