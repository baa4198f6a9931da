//! What the contract can describe but no solver solves yet, and which issue brings it.
//!
//! The scene format runs ahead of the solvers: `drive.layout = "one-pulley"` and the
//! theories `cosserat` and `shell` are read and validated here so that scene files and
//! other tools can use them now. A solver that meets such a scene refuses it with
//! [`NotYetSolvable`] — naming the scene, the layout or theory, and the issue that brings
//! it — before it reads anything else; it never solves something else in its place (a
//! one-pulley scene is no two-pulley loop with H = 0). Each issue deletes its rows from
//! [`not_yet_solvable`] when it lands.

use std::fmt;

use serde::Serialize;

use crate::scene::{Analysis, Layout, Scene, Theory};

/// The two independent ways to solve a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    /// The multi-segment BVP (crate `bvp`).
    Bvp,
    /// The MEL finite elements (crate `fem`).
    Fem,
}

impl fmt::Display for Solver {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Solver::Bvp => "BVP",
            Solver::Fem => "finite element solver",
        })
    }
}

/// The part of a scene a solver cannot solve yet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Unsolved {
    /// A drive layout (`drive.layout`).
    Layout(Layout),
    /// A belt theory (`belt.theory`) in an analysis.
    Theory(Theory, Analysis),
    /// A belt theory for which no BVP exists at all (the shell: a 2-D transient; only
    /// its planar limit is a rod BVP): not "not yet", never.
    NoBvp(Theory),
}

impl fmt::Display for Unsolved {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Unsolved::Layout(l) => write!(f, "layout `{l}`"),
            Unsolved::Theory(t, a) => write!(f, "theory `{t}` (analysis `{a}`)"),
            Unsolved::NoBvp(t) => write!(f, "theory `{t}`"),
        }
    }
}

/// A solver's refusal of a scene it cannot solve yet, or (the BVP for a shell) cannot
/// solve at all (the CLI exits 2 and writes nothing).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error, Serialize)]
#[error("{}", refusal(self))]
pub struct NotYetSolvable {
    /// Scene name.
    pub scene: String,
    /// Which solver refuses.
    pub solver: Solver,
    /// What it cannot solve.
    pub unsolved: Unsolved,
    /// The issue that brings it.
    pub issue: u32,
    /// The issue's subject, in short.
    pub title: &'static str,
}

fn refusal(e: &NotYetSolvable) -> String {
    let NotYetSolvable { scene, solver, unsolved, issue, title } = e;
    match unsolved {
        Unsolved::NoBvp(_) => format!(
            "scene `{scene}`: no {solver} exists for {unsolved} — the Kirchhoff–Love shell's run-off is a transient over (σ, ζ) that no multi-segment BVP describes (only its planar limit is the rod's BVP); solve it with `--method fem`, whose reference is its own finest run with Richardson extrapolation (issue {issue}, {title}) — nothing was solved"
        ),
        _ => format!("scene `{scene}`: the {solver} does not solve {unsolved} yet; it comes with issue {issue} ({title}) — nothing was solved"),
    }
}

const PAPER_C: (u32, &str) = (13, "Cosserat rod, static and on one pulley, Paper C");
const PAPER_D: (u32, &str) = (14, "Cosserat two-pulley drive in steady motion, Paper D");
const PAPER_E: (u32, &str) = (15, "Kirchhoff–Love shell, lateral run-off, Paper E");

/// Why `solver` cannot solve `scene` yet, or `None` if the scene's layout and theory are
/// ones it has (it may still refuse an analysis or effect it has no model for, with its
/// own error). The BVP solves the static Cosserat rod on the two-pulley loop
/// (`cosserat-hanging`) and so does the FE (the Cosserat elements, fem/src/formulation/cosserat.rs);
/// both solve the Cosserat belt in steady motion over one pulley (`cosserat-pulley`) and the
/// Cosserat two-pulley drive in steady motion (`cosserat-drive`); the Cosserat transient
/// is issue 14's. The FE solves the shell (transient run-off and the static hanging
/// belt; issue 15); no BVP exists for it ([`Unsolved::NoBvp`]).
pub fn not_yet_solvable(scene: &Scene, solver: Solver) -> Option<NotYetSolvable> {
    let (unsolved, (issue, title)) = match (scene.drive.layout, scene.belt.theory, scene.analysis) {
        // both solve it: the BVP (bvp::cosserat_pulley) and the FE's direct steady solve
        // on the open mesh (docs/fem-cosserat.md §12)
        (Layout::OnePulley, Theory::Cosserat, Analysis::Steady) => return None,
        (Layout::OnePulley, _, _) => (Unsolved::Layout(Layout::OnePulley), PAPER_C),
        (Layout::TwoPulley, Theory::Cosserat, Analysis::Static) => return None,
        // both solve the steady Cosserat drive: the BVP (bvp::cosserat_drive) and the FE's
        // direct steady solve (docs/fem-cosserat.md §10–§11)
        (Layout::TwoPulley, Theory::Cosserat, Analysis::Steady) => return None,
        (_, Theory::Cosserat, a) => (Unsolved::Theory(Theory::Cosserat, a), PAPER_D),
        // no BVP exists for the shell (DESIGN.md's catalogue: "— (planar limit only)")
        (_, Theory::Shell, _) if solver == Solver::Bvp => (Unsolved::NoBvp(Theory::Shell), PAPER_E),
        // the FE's stages 0–2 (fem::shell): the transient run-off and the static hanging
        // belt with the ramps at rest (docs/fem-shell.md §9); steady motion of the shell
        // is not a model of Paper E
        (_, Theory::Shell, Analysis::Transient | Analysis::Static) => return None,
        (_, Theory::Shell, a) => (Unsolved::Theory(Theory::Shell, a), PAPER_E),
        (Layout::TwoPulley, Theory::String | Theory::Kirchhoff, _) => return None,
    };
    Some(NotYetSolvable { scene: scene.name.clone(), solver, unsolved, issue, title })
}
