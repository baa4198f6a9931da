//! Tables of a study — the deal.II-style convergence table with rates, the errors per
//! quantity, and the mutual convergence of FE and BVP — as plain text (terminal) and
//! Markdown (reports). A number that does not exist is "—", never NaN.

use crate::run::{Discretisation, Family, Run};
use crate::study::{Series, SeriesStatus, Study};

/// A rectangular table of strings.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    /// Column headers.
    pub header: Vec<String>,
    /// Rows of cells (each as long as `header`).
    pub rows: Vec<Vec<String>>,
    /// Left-aligned columns (the others are right-aligned).
    pub left: Vec<usize>,
}

impl Table {
    /// A table with these headers; column 0 left-aligned.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Table {
        Table { header: header.into_iter().map(Into::into).collect(), rows: Vec::new(), left: vec![0] }
    }

    /// Appends a row (padded or cut to the header's width).
    pub fn push(&mut self, mut row: Vec<String>) {
        row.resize(self.header.len(), String::new());
        self.rows.push(row);
    }

    fn widths(&self) -> Vec<usize> {
        let mut w: Vec<usize> = self.header.iter().map(|h| h.chars().count()).collect();
        for r in &self.rows {
            for (i, c) in r.iter().enumerate() {
                w[i] = w[i].max(c.chars().count());
            }
        }
        w
    }

    /// Fixed-width text, two spaces between columns, a rule under the header; every
    /// line starts with `indent`.
    pub fn to_text(&self, indent: &str) -> String {
        let w = self.widths();
        let line = |cells: &[String]| {
            let mut s = String::from(indent);
            for (i, c) in cells.iter().enumerate() {
                if i > 0 {
                    s.push_str("  ");
                }
                let pad = w[i].saturating_sub(c.chars().count());
                if self.left.contains(&i) {
                    s.push_str(c);
                    if i + 1 < cells.len() {
                        s.push_str(&" ".repeat(pad));
                    }
                } else {
                    s.push_str(&" ".repeat(pad));
                    s.push_str(c);
                }
            }
            s.push('\n');
            s
        };
        let mut out = line(&self.header);
        let rule: Vec<String> = w.iter().map(|&n| "─".repeat(n)).collect();
        out.push_str(&line(&rule));
        for r in &self.rows {
            out.push_str(&line(r));
        }
        out
    }

    /// GitHub-flavoured Markdown.
    pub fn to_markdown(&self) -> String {
        let esc = |c: &str| c.replace('|', "\\|");
        let mut out = format!("| {} |\n", self.header.iter().map(|h| esc(h)).collect::<Vec<_>>().join(" | "));
        let align: Vec<&str> = (0..self.header.len()).map(|i| if self.left.contains(&i) { ":--" } else { "--:" }).collect();
        out.push_str(&format!("|{}|\n", align.join("|")));
        for r in &self.rows {
            out.push_str(&format!("| {} |\n", r.iter().map(|c| esc(c)).collect::<Vec<_>>().join(" | ")));
        }
        out
    }
}

/// "—" for a missing number.
pub const NONE: &str = "—";

/// An error as `1.23e-7`; "—" if absent.
pub fn fmt_error(e: Option<f64>) -> String {
    match e {
        Some(0.0) => "0".to_string(),
        Some(v) if v.is_finite() => format!("{v:.2e}"),
        _ => NONE.to_string(),
    }
}

/// An order as `2.01`; "—" if absent.
pub fn fmt_order(p: Option<f64>) -> String {
    match p {
        Some(v) if v.is_finite() => format!("{v:.2}"),
        _ => NONE.to_string(),
    }
}

/// A value with 10 significant digits; "—" if absent.
pub fn fmt_value(v: Option<f64>) -> String {
    match v {
        Some(v) if v.is_finite() => {
            if v == 0.0 {
                return "0".to_string();
            }
            let mag = v.abs().log10().floor();
            if !(-4.0..6.0).contains(&mag) {
                return format!("{v:.9e}");
            }
            let decimals = (9.0 - mag).max(0.0) as usize;
            format!("{v:.decimals$}")
        }
        _ => NONE.to_string(),
    }
}

/// Wall time in seconds.
pub fn fmt_seconds(s: Option<f64>) -> String {
    match s {
        Some(v) if v.is_finite() => {
            if v < 10.0 {
                format!("{v:.3}")
            } else {
                format!("{v:.1}")
            }
        }
        _ => NONE.to_string(),
    }
}

/// The phase that took most of a run's wall time and its share, `numeric LU 43%`
/// (`cost.phases`); `—` for a run without phases.
pub fn fmt_dominant(cost: &crate::run::RunCost) -> String {
    let dominant = cost.cost_phases().and_then(|p| p.dominant());
    dominant.map_or(NONE.into(), |(name, s)| {
        let short = match name {
            "symbolic_factorisation" => "symbolic LU",
            "numeric_factorisation" => "numeric LU",
            "linear_solves" => "solves",
            "mesh_adaptation" => "adaptation",
            other => other,
        };
        format!("{short} {:.0}%", 100.0 * s / cost.wall_seconds.max(f64::MIN_POSITIVE))
    })
}

/// The discretisation cell: `1e-8`, `256` or `64×4 Δt 1e-2`.
pub fn fmt_disc(d: Discretisation) -> String {
    d.cell()
}

/// The field norms the study measured (indices into `study.quantities`).
fn norm_columns(study: &Study) -> Vec<usize> {
    study.quantities.iter().enumerate().filter(|(_, q)| !q.is_scalar()).map(|(i, _)| i).collect()
}

/// The convergence table of one series (deal.II style): discretisation, cost, then the
/// max error over the summary scalars and each field norm, each FE error followed by
/// its observed order. Failed runs are listed under the table by [`failures`].
pub fn convergence_table(study: &Study, series: &Series) -> Table {
    let fe = series.family == Family::Fem;
    let norms = norm_columns(study);
    let mut header: Vec<String> = vec![if fe { "elements" } else { "tolerance" }.into(), "unknowns".into()];
    if !fe {
        header.push("nodes".into());
    }
    header.extend(["Newton".to_string(), "wall [s]".to_string(), "most time".to_string(), "scalars".to_string()]);
    if fe {
        header.push("rate".into());
    }
    for &k in &norms {
        header.push(study.quantities[k].name.clone());
        if fe {
            header.push("rate".into());
        }
    }
    let mut t = Table::new(header);
    for row in &series.rows {
        let d = row.run.data();
        let mut cells = vec![fmt_disc(row.run.discretisation), d.map_or(NONE.into(), |d| d.cost.unknowns.to_string())];
        if !fe {
            cells.push(d.and_then(|d| d.cost.mesh_nodes).map_or(NONE.into(), |n| n.to_string()));
        }
        cells.push(d.map_or(NONE.into(), |d| d.cost.newton_iterations.to_string()));
        cells.push(fmt_seconds(row.run.wall_seconds()));
        cells.push(d.map_or(NONE.into(), |d| fmt_dominant(&d.cost)));
        cells.push(fmt_error(row.scalar_error));
        if fe {
            cells.push(fmt_order(row.scalar_order));
        }
        for &k in &norms {
            cells.push(fmt_error(row.errors[k]));
            if fe {
                cells.push(fmt_order(row.orders[k]));
            }
        }
        t.push(cells);
    }
    t
}

/// One line per failed run of a series (`tol 1e-9: failed: <reason>`) and per stated
/// warning of a solved one (`128 el.: warning: <what>`): the runs whose numbers are not clean.
pub fn failures(series: &Series) -> Vec<String> {
    series
        .rows
        .iter()
        .flat_map(|r| match &r.run.outcome {
            Err(e) => vec![format!("{}: failed: {e}", r.run.discretisation)],
            Ok(d) => d.warnings.iter().map(|w| format!("{}: warning: {w}", r.run.discretisation)).collect(),
        })
        .collect()
}

/// The short label of a series' finest run, e.g. `gauss4 1e-8`, `shooting 1e-10`,
/// `string-mel 256`.
pub fn finest_label(series: &Series) -> String {
    let short = series.method.trim_start_matches("bvp-collocation ").trim_start_matches("bvp-").trim_start_matches("fem ");
    match series.finest() {
        Some(r) => format!("{short} {}", fmt_disc(r.run.discretisation)),
        None => short.to_string(),
    }
}

/// Errors per quantity at the finest discretisation of every studied series, beside
/// the reference value.
pub fn quantity_table(study: &Study) -> Table {
    let studied: Vec<&Series> = study.series.iter().filter(|s| s.status == SeriesStatus::Studied && !s.rows.is_empty()).collect();
    let mut header = vec!["quantity".to_string(), "reference".to_string()];
    header.extend(studied.iter().map(|s| finest_label(s)));
    let mut t = Table::new(header);
    let refd = study.reference.data();
    for (k, q) in study.quantities.iter().enumerate() {
        let mut cells = vec![q.name.clone(), if q.is_scalar() { fmt_value(refd.and_then(|d| q.value(d))) } else { "(field norm)".into() }];
        for s in &studied {
            cells.push(fmt_error(s.finest().and_then(|r| r.errors[k])));
        }
        t.push(cells);
    }
    t
}

/// Mutual convergence of one FE series: per quantity the value and error at the finest
/// mesh, the observed order against the reference at the last refinement, the
/// self-convergence order, the Richardson-extrapolated value and its error against the
/// BVP reference.
pub fn mutual_table(series: &Series) -> Table {
    let mut t = Table::new(["quantity", "FE finest", "error", "p (vs ref)", "p (self)", "Richardson", "error of Richardson"]);
    let last_orders = series.finest().map(|r| r.orders.clone()).unwrap_or_default();
    for (k, e) in series.extrapolation.iter().enumerate() {
        let is_norm = drive::result::FIELD_NORM_NAMES.contains(&e.quantity.as_str());
        t.push(vec![
            e.quantity.clone(),
            if is_norm { "(field)".into() } else { fmt_value(e.finest) },
            fmt_error(e.finest_error),
            fmt_order(last_orders.get(k).copied().flatten()),
            fmt_order(e.order),
            if is_norm { "(field)".into() } else { fmt_value(e.value) },
            fmt_error(e.mutual),
        ]);
    }
    t
}

/// A one-line description of the reference run.
pub fn reference_line(study: &Study) -> String {
    describe_run("reference", &study.reference)
}

fn describe_run(what: &str, run: &Run) -> String {
    match &run.outcome {
        Ok(d) => format!(
            "{what}: {} at {} — {} s, {} unknowns{}, {} Newton iterations",
            run.method,
            run.discretisation,
            fmt_seconds(Some(d.cost.wall_seconds)),
            d.cost.unknowns,
            d.cost.mesh_nodes.map_or(String::new(), |n| format!(", {n} mesh nodes")),
            d.cost.newton_iterations
        ),
        Err(e) => format!("{what}: {} at {} — FAILED: {e}", run.method, run.discretisation),
    }
}

/// The compensating swivel of a shell study in one sentence (terminal and report).
pub fn compensation_text(c: &fem::shell::compensation::Compensation) -> String {
    format!(
        "the compensating swivel (spec E-5) of the {} drum at the coarsest level, cancelling {}: β_y* = {:.6e} rad, leaving a run-off of {:.3e} m/s against {:.3e} m/s without swivel (linear estimate {:.6e} rad from the probe β_y = {:.3e} rad, v = {:.3e} m/s; Brent to {:.1e} rad, {} solves)",
        c.drum.name(),
        match c.measure {
            fem::shell::compensation::RunoffMeasure::Settled => "the run-off after the lateral transient (settled_runoff_velocity)",
            fem::shell::compensation::RunoffMeasure::LastRevolution =>
                "the slope over the last revolution (runoff_velocity: the run without swivel did not settle — too short for the lateral transient, or its fits refused —, so this may be a phase of the transient, not the drift a controller holds)",
        },
        c.swivel,
        c.runoff_left,
        c.runoff_without,
        c.linear_estimate,
        c.probe[0],
        c.probe[1],
        c.tolerance,
        c.solves
    )
}

/// The whole study as terminal text: reference, notes, a convergence table per series,
/// the per-quantity table and the mutual convergence of each FE formulation.
pub fn study_text(study: &Study) -> String {
    let mut out = String::new();
    out.push_str(&format!("scene {}\n", study.scene));
    out.push_str(&format!("{}\n", reference_line(study)));
    out.push_str(&format!(
        "errors are relative to the reference: scalars = max over the {} summary scalars of |q − q_ref|/|q_ref|; field norms = ‖f − f_ref‖/‖f_ref‖ over σ ({} samples); rate = log(e_(k−1)/e_k)/log(r), r the refinement ratio (n_k/n_(k−1), or Δt_(k−1)/Δt_k for a shell study of the step, n_ζ,k/n_ζ,(k−1) for one of the width)\n",
        study.quantities.iter().filter(|q| q.is_scalar()).count(),
        study.plan.samples
    ));
    for n in &study.notes {
        out.push_str(&format!("note: {n}\n"));
    }
    if !study.reference_estimates.is_empty() {
        out.push_str("\nthe reference's values: Richardson extrapolation of the three finest levels, with its error estimate |q_R − q_finest|\n");
        out.push_str(&estimate_table(&study.reference_estimates).to_text("  "));
    }
    if let Some(c) = &study.compensation {
        out.push_str(&format!("\n{}\n", compensation_text(c)));
    }
    for s in &study.series {
        out.push('\n');
        match &s.status {
            SeriesStatus::NotApplicable(why) => {
                out.push_str(&format!("{} — not applicable to this scene: {why}\n", s.method));
                continue;
            }
            SeriesStatus::Studied => {
                let what = match (s.family, study.plan.shell_refinement()) {
                    (Family::Fem, Some(drive::result::Refinement::Step)) => "time-step sequence on one mesh, observed order per refinement",
                    (Family::Fem, Some(drive::result::Refinement::Width)) => "width sequence (n_ζ) on one σ-mesh and step, observed order per refinement",
                    (Family::Fem, _) => "mesh sequence, observed order per refinement",
                    _ => "tolerance sweep, error and cost (no order vs tolerance)",
                };
                out.push_str(&format!("{} — {what}\n", s.method));
            }
        }
        out.push_str(&convergence_table(study, s).to_text("  "));
        for f in failures(s) {
            out.push_str(&format!("  {f}\n"));
        }
    }
    out.push_str("\nerror per quantity at the finest discretisation of each method\n");
    out.push_str(&quantity_table(study).to_text("  "));
    let fe: Vec<&Series> = study.series.iter().filter(|s| s.family == Family::Fem && s.status == SeriesStatus::Studied).collect();
    if fe.is_empty() {
        out.push_str("\nmutual convergence FE ↔ BVP: — (no FE formulation studied)\n");
    }
    for s in fe {
        out.push_str(&format!("\nmutual convergence of {} and the reference (Richardson over the three finest meshes)\n", s.method));
        if s.extrapolation.iter().all(|e| e.order.is_none()) {
            out.push_str("  (needs three successful meshes with a constant ratio)\n");
        }
        out.push_str(&mutual_table(s).to_text("  "));
    }
    out
}

/// The extrapolated reference values with their observed orders and error estimates
/// (absolute and relative to the value).
pub fn estimate_table(estimates: &[crate::reference::Estimate]) -> Table {
    let mut t = Table::new(["quantity", "finest level", "extrapolated", "order", "error estimate", "relative"]);
    for e in estimates {
        let relative = (e.value != 0.0).then(|| e.error_estimate / e.value.abs());
        t.push(vec![e.quantity.clone(), fmt_value(Some(e.finest)), fmt_value(Some(e.value)), fmt_order(e.order), fmt_error(Some(e.error_estimate)), fmt_error(relative)]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::fmt_tolerance;

    #[test]
    fn text_and_markdown() {
        let mut t = Table::new(["a", "bb"]);
        t.push(vec!["xyz".into(), "1".into()]);
        let s = t.to_text("");
        assert_eq!(s, "a    bb\n───  ──\nxyz   1\n");
        let m = t.to_markdown();
        assert!(m.starts_with("| a | bb |\n|:--|--:|\n| xyz | 1 |"));
    }

    #[test]
    fn numbers() {
        assert_eq!(fmt_error(Some(1.234e-7)), "1.23e-7");
        assert_eq!(fmt_error(Some(f64::NAN)), "—");
        assert_eq!(fmt_error(None), "—");
        assert_eq!(fmt_order(Some(2.0)), "2.00");
        assert_eq!(fmt_value(Some(1.33397726)), "1.333977260");
        assert_eq!(fmt_value(Some(-0.0123)), "-0.01230000000");
        assert_eq!(fmt_value(Some(2.0e7)), "2.000000000e7");
        assert_eq!(fmt_tolerance(1e-8), "1e-8");
    }
}
