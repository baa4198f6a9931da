//! `verification`: holds the two independent solutions of a scene — BVP references
//! (crate `bvp`) and MEL finite elements (crate `fem`) — against each other.
//!
//! Role (DESIGN.md, "The verification harness"): a *run* is scene + method +
//! discretisation → solution view + summary + cost; a *study* is a sequence of runs (FE
//! over meshes h, h/2, …; BVP over tolerances) with errors against the tightest BVP run,
//! observed orders, Richardson extrapolation and mutual convergence; reports (Markdown +
//! SVG + JSON) and the CI gate build on studies. This crate is the only place where `bvp`
//! and `fem` meet, and only through [`drive::view::SolutionView`].
//!
//! Modules, in the order of the work:
//! - [`run`]: one run (method + discretisation → sampled solution + cost); the
//!   [`run::Method`] trait and the built-in methods (BVP variants, FE formulations
//!   discovered from the `fem` registry);
//! - [`measure`]: error measures, observed orders, Richardson extrapolation;
//! - [`study`]: sequences of runs of one scene held against the reference;
//! - [`table`]: the convergence tables (terminal text and Markdown);
//! - [`plot`], [`report`]: SVG plots and the Markdown/JSON reports;
//! - [`gate`]: the CI gate over the catalogue;
//! - [`measured`]: a user's measurement (CSV) held against a shell run's history;
//! - [`vtk`]: the shell's surface over time as VTK files (`.vtu` per frame, a `.pvd`);
//! - [`outside`] and [`check`]: results of outside codes read from files, studied and
//!   gated like a built-in method (`beltcheck check`), and the reference exported
//!   for them (`beltcheck reference`).
//!
//! Definitions of every measure: docs/verification.md and [`measure`].

pub mod check;
pub mod closed_form;
pub mod files;
pub mod gate;
pub mod measure;
pub mod measured;
pub mod outside;
pub mod plot;
pub mod plot_shell;
pub mod reference;
pub mod report;
pub mod run;
pub mod study;
pub mod sweep;
pub mod table;
pub mod vtk;

use drive::summary::Summary;

/// One quantity of two summaries side by side.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Difference {
    /// Flattened name, e.g. `driver.contact_arc`.
    pub name: String,
    /// Value in the first summary.
    pub a: f64,
    /// Value in the second summary.
    pub b: f64,
    /// |a − b|.
    pub absolute: f64,
    /// |a − b| / max(|a|, |b|, floor) with `floor` = 1e-300 (relative to the larger value).
    pub relative: f64,
}

/// Differences of every quantity present in both summaries, in `a`'s order. Quantities
/// present in only one summary are returned by name in the second vector: a method that
/// produces a quantity the other does not is itself a finding.
pub fn compare_summaries(a: &Summary, b: &Summary) -> (Vec<Difference>, Vec<String>) {
    let sa = a.scalars();
    let sb = b.scalars();
    let mut diffs = Vec::new();
    let mut only = Vec::new();
    for (name, va) in &sa {
        match sb.iter().find(|(n, _)| n == name) {
            Some((_, vb)) => {
                let absolute = (va - vb).abs();
                let relative = absolute / va.abs().max(vb.abs()).max(1e-300);
                diffs.push(Difference { name: name.clone(), a: *va, b: *vb, absolute, relative });
            }
            None => only.push(name.clone()),
        }
    }
    for (name, _) in &sb {
        if !sa.iter().any(|(n, _)| n == name) {
            only.push(name.clone());
        }
    }
    (diffs, only)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn differences_are_per_quantity_and_report_missing_ones() {
        let a = Summary { y_upper_mid: Some(1.0), tension_upper_mid: Some(10.0), ..Summary::default() };
        let b = Summary { y_upper_mid: Some(1.5), y_lower_mid: Some(-1.0), ..Summary::default() };
        let (d, only) = compare_summaries(&a, &b);
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].name, "y_upper_mid");
        assert!((d[0].absolute - 0.5).abs() < 1e-15);
        assert!((d[0].relative - 0.5 / 1.5).abs() < 1e-15);
        assert_eq!(only, vec!["tension_upper_mid".to_string(), "y_lower_mid".to_string()]);
    }
}
