//! Results of outside codes (`beltcheck check`): result files written by another
//! program — in C++, Fortran, Julia, Python, an Abaqus user element — read, checked and
//! turned into runs of the harness, so that an outside code is one more method of a
//! study, held against the scene's reference by the same errors, orders, Richardson
//! extrapolation, mutual convergence and cost columns as a built-in formulation, and
//! gated by the scene's `gate` limits (docs/check-your-code.md).
//!
//! A result file is the result JSON of DESIGN.md with its `discretisation` object
//! (`{"elements": 64}`), or a CSV file of the fields along σ (columns `sigma`, `x`, `y`,
//! `tension`, optionally `moment`) whose leading `#` lines hold the same JSON without
//! `fields`. Every problem with a file is an [`OutsideError`] naming the file, the
//! field and what was expected; a file that is well formed but cannot be compared (for
//! another scene, not converged, no quantity the reference has) is a [`Skip`] with its
//! reason, listed in the check's output — never silently dropped.
//!
//! The fields of a run enter the harness through the contour: each sample's point
//! (x, y) is mapped to (σ, ν) by [`drive::Contour::sigma_nu`] (the σ the file gives
//! must agree with it), and ν(σ), N(σ), M(σ) are interpolated linearly and periodically
//! onto the harness's uniform σ grid — a code that writes its fields at its own nodes
//! (or finer) is compared by its own piecewise-linear solution.

use std::path::{Path, PathBuf};

use drive::result::{Discretisation, Fields, RunResult};
use drive::contour::Path as Path2;
use drive::scene::Scene;
use drive::view::ContactState;
use serde::Serialize;
use serde_json::Value;

use crate::measure::Quantity;
use crate::run::{Family, Run, RunCost, RunData, Samples};

/// Relative disagreement (of L_geom) allowed between a sample's σ and the σ of its point
/// (x, y) on the contour: far above round-off of a map computed in double precision,
/// far below any mesh spacing.
pub const SIGMA_TOLERANCE: f64 = 1e-6;

/// Largest gap between successive field samples round the loop, as a fraction of
/// L_geom: fields with a larger hole do not describe the loop (a mesh of the minimum
/// four elements has gaps of L_geom/4).
pub const MAX_GAP: f64 = 0.25;

/// Fewest samples a field must have (one per region of the contour).
pub const MIN_FIELD_SAMPLES: usize = 4;

/// Why an outside result file cannot be read (`beltcheck check` exits with status 2).
#[derive(Debug, thiserror::Error)]
pub enum OutsideError {
    /// The file or directory cannot be read.
    #[error("{}: cannot read: {error}", .file.display())]
    Read {
        /// The path.
        file: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
    /// A directory without result files.
    #[error("{}: no result file (*.json, *.csv) in this directory", .dir.display())]
    EmptyDirectory {
        /// The directory.
        dir: PathBuf,
    },
    /// No result file given at all.
    #[error("no result file given: name result files (*.json, *.csv) or directories of them")]
    NoFiles,
    /// Not JSON (or a CSV line that is not a row of numbers).
    #[error("{}: line {line}, column {column}: {message}", .file.display())]
    Syntax {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What the parser expected.
        message: String,
    },
    /// A number that is NaN or infinite (`NaN`, `Infinity` — not JSON, but written by
    /// some libraries — or a CSV cell).
    #[error("{}: `{field}` is {value}: expected a finite number", .file.display())]
    NotFinite {
        /// The file.
        file: PathBuf,
        /// Field path, e.g. `summary.y_upper_mid`, `fields.tension[12]`.
        field: String,
        /// The literal as written.
        value: String,
    },
    /// A field of the wrong type, a missing required field, an unknown name.
    #[error("{}: `{field}`: {message}", .file.display())]
    Field {
        /// The file.
        file: PathBuf,
        /// Field path (`.` = the whole document).
        field: String,
        /// What was expected.
        message: String,
    },
    /// The result's own consistency (field lengths, a discretisation out of range).
    #[error("{}: {error}", .file.display())]
    Result {
        /// The file.
        file: PathBuf,
        /// The offending entry.
        error: drive::error::ResultError,
    },
    /// A result without `discretisation`: its run cannot be placed in a sequence.
    #[error("{}: `discretisation` is missing: expected e.g. {{\"elements\": 64}} (or {{\"tolerance\": 1e-8}}, {{\"mesh2d\": {{…}}}})", .file.display())]
    MissingDiscretisation {
        /// The file.
        file: PathBuf,
    },
    /// A sample whose σ is not the σ of its point (x, y) on the contour.
    #[error("{}: `fields.sigma[{index}]` = {given} but the point (x, y) = ({x}, {y}) lies on the contour normal at σ = {mapped:.9}: expected σ of the contour of DESIGN.md ({convention}), |Δσ| ≤ {tol:.1e} m", .file.display())]
    SigmaMismatch {
        /// The file.
        file: PathBuf,
        /// Sample index.
        index: usize,
        /// σ in the file.
        given: f64,
        /// x of the sample.
        x: f64,
        /// y of the sample.
        y: f64,
        /// σ of (x, y).
        mapped: f64,
        /// Tolerance, m.
        tol: f64,
        /// Where σ starts and which way it runs on this layout.
        convention: &'static str,
    },
    /// Fields that do not cover the contour.
    #[error("{}: `fields` leave a gap of {gap:.4} m between σ = {from:.4} and σ = {to:.4} m (at most {max:.4} m = {MAX_GAP}·L_geom allowed, {n} samples given, at least {MIN_FIELD_SAMPLES}): expected samples over the whole contour (round the loop; from end to end on the one-pulley layout)", .file.display())]
    FieldCoverage {
        /// The file.
        file: PathBuf,
        /// Number of samples.
        n: usize,
        /// Largest gap, m.
        gap: f64,
        /// Start of the gap, m.
        from: f64,
        /// End of the gap, m.
        to: f64,
        /// Largest allowed, m.
        max: f64,
    },
    /// Two files of one method at the same discretisation.
    #[error("{} and {}: both are runs of `{method}` at {disc}: expected each discretisation once per method", .first.display(), .second.display())]
    Duplicate {
        /// The method.
        method: String,
        /// The discretisation.
        disc: Discretisation,
        /// The first file.
        first: PathBuf,
        /// The second file.
        second: PathBuf,
    },
    /// Runs of one method at discretisations of different kinds.
    #[error("{}: a run of `{method}` at {}, but {} is at {}: expected one kind of discretisation per method", .file.display(), .discs.0, .other_file.display(), .discs.1)]
    MixedKinds {
        /// The method.
        method: String,
        /// This file.
        file: PathBuf,
        /// Another run's file.
        other_file: PathBuf,
        /// This file's discretisation and the other run's.
        discs: Box<(Discretisation, Discretisation)>,
    },
}

impl OutsideError {
    fn field(file: &Path, field: impl Into<String>, message: impl Into<String>) -> OutsideError {
        OutsideError::Field { file: file.to_path_buf(), field: field.into(), message: message.into() }
    }
}

/// Why a well-formed result file is not compared.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SkipReason {
    /// The result is of another scene.
    OtherScene {
        /// Its `scene`.
        scene: String,
    },
    /// The result says `"converged": false`.
    NotConverged,
    /// Neither a summary scalar nor a field the reference has.
    NothingComparable,
}

impl std::fmt::Display for SkipReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SkipReason::OtherScene { scene } => write!(f, "a result of scene `{scene}`, not of the scene checked"),
            SkipReason::NotConverged => f.write_str("the result says \"converged\": false — its numbers are no answer to compare"),
            SkipReason::NothingComparable => f.write_str("no summary quantity and no field the reference has: nothing to compare"),
        }
    }
}

/// A file set aside, with why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Skip {
    /// The file.
    pub file: PathBuf,
    /// Its method, if it was read.
    pub method: String,
    /// Its discretisation.
    pub discretisation: Option<Discretisation>,
    /// Why.
    pub reason: SkipReason,
}

/// One result file, read and checked.
#[derive(Debug, Clone, PartialEq)]
pub struct OutsideRun {
    /// Where it came from.
    pub file: PathBuf,
    /// The result.
    pub result: RunResult,
    /// Its discretisation (the result's, required).
    pub discretisation: Discretisation,
}

/// The files of the arguments: files as given, directories expanded to their `*.json`
/// and `*.csv` files (sorted).
///
/// # Errors
/// [`OutsideError::NoFiles`], [`OutsideError::Read`], [`OutsideError::EmptyDirectory`].
pub fn result_files(inputs: &[PathBuf], exclude: &[PathBuf]) -> Result<Vec<PathBuf>, OutsideError> {
    // beltcheck's own output of an earlier run (`check --json` into the results
    // directory) is not a result file: a directory listing passes it over
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if inputs.is_empty() {
        return Err(OutsideError::NoFiles);
    }
    let mut files = Vec::new();
    for p in inputs {
        if p.is_dir() {
            let entries = std::fs::read_dir(p).map_err(|error| OutsideError::Read { file: p.clone(), error })?;
            let mut found: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.is_file() && f.extension().is_some_and(|x| x == "json" || x == "csv"))
                .filter(|f| !exclude.iter().any(|x| same(f, x)))
                .collect();
            found.sort();
            if found.is_empty() {
                return Err(OutsideError::EmptyDirectory { dir: p.clone() });
            }
            files.extend(found);
        } else {
            files.push(p.clone());
        }
    }
    Ok(files)
}

/// Reads one result file (JSON, or CSV with a `#` JSON header by its `.csv` extension)
/// and checks it against the scene's contour.
///
/// # Errors
/// The first problem, naming the file and the field.
pub fn read_result(file: &Path, scene: &Scene) -> Result<OutsideRun, OutsideError> {
    let text = std::fs::read_to_string(file).map_err(|error| OutsideError::Read { file: file.to_path_buf(), error })?;
    let is_csv = file.extension().is_some_and(|x| x.eq_ignore_ascii_case("csv"));
    let (header, csv_fields) = if is_csv {
        let (header, first_line) = csv_header(&text);
        let fields = csv_fields(file, &text, first_line)?;
        (header, Some(fields))
    } else {
        (text, None)
    };
    let value = parse_json(file, &header)?;
    if let Some(root) = value.as_object() {
        if is_csv && root.contains_key("fields") {
            return Err(OutsideError::field(file, "fields", "a CSV file's fields are its rows: expected no `fields` in its # header"));
        }
        if let Some(summary) = root.get("summary") {
            check_summary_names(file, summary)?;
        }
    }
    let mut result: RunResult = serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        OutsideError::field(file, path, e.into_inner().to_string())
    })?;
    if let Some(f) = csv_fields {
        result.fields = Some(f);
    }
    result.check().map_err(|error| OutsideError::Result { file: file.to_path_buf(), error })?;
    let Some(discretisation) = result.discretisation else {
        return Err(OutsideError::MissingDiscretisation { file: file.to_path_buf() });
    };
    if let Some(fields) = &result.fields {
        check_fields(file, fields, scene)?;
    }
    Ok(OutsideRun { file: file.to_path_buf(), result, discretisation })
}

/// Marks a non-finite literal replaced before parsing (a JSON string no writer emits).
const NON_FINITE_MARK: &str = "\u{0}non-finite:";

/// Parses JSON, turning the non-JSON literals `NaN`, `Infinity`, `-Infinity` (outside
/// strings) into a named [`OutsideError::NotFinite`] instead of a syntax error.
fn parse_json(file: &Path, text: &str) -> Result<Value, OutsideError> {
    let mut out = String::with_capacity(text.len());
    let mut in_string = false;
    let mut escaped = false;
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if in_string {
            in_string = c != '"' || escaped;
            escaped = c == '\\' && !escaped;
            out.push(c);
            rest = &rest[c.len_utf8()..];
            continue;
        }
        let literal = ["-Infinity", "Infinity", "NaN", "-NaN", "+Infinity"].into_iter().find(|l| rest.starts_with(l));
        if let Some(l) = literal {
            out.push('"');
            out.push_str("\\u0000non-finite:"); // NON_FINITE_MARK, escaped in the JSON text
            out.push_str(l);
            out.push('"');
            rest = &rest[l.len()..];
            continue;
        }
        in_string = c == '"';
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    let value: Value = serde_json::from_str(&out).map_err(|e| OutsideError::Syntax { file: file.to_path_buf(), line: e.line(), column: e.column(), message: e.to_string() })?;
    if let Some((field, literal)) = find_mark(&value, "") {
        return Err(OutsideError::NotFinite { file: file.to_path_buf(), field, value: literal });
    }
    Ok(value)
}

/// The path and literal of the first replaced non-finite literal.
fn find_mark(v: &Value, path: &str) -> Option<(String, String)> {
    match v {
        Value::String(s) => s.strip_prefix(NON_FINITE_MARK).map(|l| (path.to_string(), l.to_string())),
        Value::Array(a) => a.iter().enumerate().find_map(|(i, x)| find_mark(x, &format!("{path}[{i}]"))),
        Value::Object(m) => m.iter().find_map(|(k, x)| find_mark(x, &if path.is_empty() { k.clone() } else { format!("{path}.{k}") })),
        _ => None,
    }
}

/// Every summary name must be a quantity of the result format (a misspelt name would
/// otherwise vanish and its quantity read as absent).
fn check_summary_names(file: &Path, summary: &Value) -> Result<(), OutsideError> {
    let Some(map) = summary.as_object() else { return Ok(()) };
    for (k, v) in map {
        let names: Vec<String> = match v.as_object() {
            Some(inner) => inner.keys().map(|q| format!("{k}.{q}")).collect(),
            None => vec![k.clone()],
        };
        for name in names {
            if let Err(e) = drive::summary::Quantity::parse(&name) {
                return Err(OutsideError::field(file, format!("summary.{name}"), e.to_string()));
            }
        }
    }
    Ok(())
}

/// The JSON header of a CSV file (its leading `#` lines, `#` removed) and the index of
/// its first line after the header.
fn csv_header(text: &str) -> (String, usize) {
    let mut header = String::new();
    let mut first = 0;
    for (i, line) in text.lines().enumerate() {
        match line.trim_start().strip_prefix('#') {
            Some(h) => {
                header.push_str(h);
                header.push('\n');
                first = i + 1;
            }
            None => break,
        }
    }
    (header, first)
}

/// The CSV column names.
const CSV_COLUMNS: [&str; 5] = ["sigma", "x", "y", "tension", "moment"];

/// The fields of a CSV file: a row of column names, then one row of numbers per sample.
fn csv_fields(file: &Path, text: &str, first_line: usize) -> Result<Fields, OutsideError> {
    let mut lines = text.lines().enumerate().skip(first_line).filter(|(_, l)| !l.trim().is_empty());
    let Some((_, names)) = lines.next() else {
        return Err(OutsideError::field(file, "fields", "a CSV file needs a row of column names after its # header: sigma,x,y,tension[,moment]"));
    };
    let names: Vec<&str> = names.split(',').map(str::trim).collect();
    for n in &names {
        if !CSV_COLUMNS.contains(n) {
            return Err(OutsideError::field(file, format!("fields.{n}"), "not a column of the result format: expected sigma, x, y, tension, moment"));
        }
        if names.iter().filter(|m| *m == n).count() > 1 {
            return Err(OutsideError::field(file, format!("fields.{n}"), "the column appears twice"));
        }
    }
    for required in &CSV_COLUMNS[..4] {
        if !names.contains(required) {
            return Err(OutsideError::field(file, format!("fields.{required}"), "missing column: expected sigma, x, y, tension (moment for rods)"));
        }
    }
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for (row, (i, line)) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(OutsideError::Syntax { file: file.to_path_buf(), line: i + 1, column: 1, message: format!("{} cells, expected {} ({})", cells.len(), names.len(), names.join(",")) });
        }
        for (k, cell) in cells.iter().enumerate() {
            let field = format!("fields.{}[{row}]", names[k]);
            let v: f64 = cell.parse().map_err(|_| OutsideError::field(file, field.clone(), format!("`{cell}` (line {}) is not a number", i + 1)))?;
            if !v.is_finite() {
                return Err(OutsideError::NotFinite { file: file.to_path_buf(), field, value: (*cell).to_string() });
            }
            columns[k].push(v);
        }
    }
    let mut take = |name: &str| names.iter().position(|n| *n == name).map(|k| std::mem::take(&mut columns[k]));
    Ok(Fields {
        sigma: take("sigma").unwrap_or_default(),
        x: take("x").unwrap_or_default(),
        y: take("y").unwrap_or_default(),
        tension: take("tension").unwrap_or_default(),
        moment: take("moment"),
        ..Fields::default()
    })
}

/// Where σ starts and which way it runs on the scene's layout (DESIGN.md).
fn sigma_convention(path: &Path2) -> &'static str {
    if path.is_open() {
        "one-pulley layout: from the inflow end at x = −end_distance, along the upper span, round the pulley clockwise, to the outflow end"
    } else {
        "from the top of the driver, clockwise"
    }
}

/// σ consistent with the points, and samples over the whole contour: round the loop, or
/// from end to end of the open one-pulley contour.
fn check_fields(file: &Path, f: &Fields, scene: &Scene) -> Result<(), OutsideError> {
    let path = scene.path();
    let l = path.length();
    let tol = SIGMA_TOLERANCE * l;
    for i in 0..f.len() {
        let (mapped, _) = path.sigma_nu([f.x[i], f.y[i]]);
        let d = (path.wrap(f.sigma[i]) - mapped).abs();
        let d = if path.is_open() { d } else { d.min(l - d) };
        if d > tol {
            return Err(OutsideError::SigmaMismatch { file: file.to_path_buf(), index: i, given: f.sigma[i], x: f.x[i], y: f.y[i], mapped, tol, convention: sigma_convention(&path) });
        }
    }
    let mut s: Vec<f64> = f.sigma.iter().map(|&x| path.wrap(x)).collect();
    s.sort_by(f64::total_cmp);
    let max = MAX_GAP * l;
    // the loop closes over the seam σ = 0; the open contour has its two ends instead
    let ends: Vec<(f64, f64, f64)> = match (s.first(), s.last()) {
        (Some(&a), Some(&b)) if path.is_open() => vec![(a, 0.0, a), (l - b, b, l)],
        (Some(&a), Some(&b)) => vec![(a + l - b, b, a)],
        _ => Vec::new(),
    };
    let gaps = s.windows(2).map(|w| (w[1] - w[0], w[0], w[1])).chain(ends);
    let worst = gaps.fold((0.0, 0.0, 0.0), |m, g| if g.0 > m.0 { g } else { m });
    if s.len() < MIN_FIELD_SAMPLES || worst.0 > max {
        let (gap, from, to) = if s.len() < 2 { (l, 0.0, l) } else { worst };
        return Err(OutsideError::FieldCoverage { file: file.to_path_buf(), n: s.len(), gap, from, to, max });
    }
    Ok(())
}

/// The runs of one outside method, coarsest first.
#[derive(Debug, Clone, PartialEq)]
pub struct OutsideMethod {
    /// The `method` of its files.
    pub method: String,
    /// Its runs, coarsest first.
    pub runs: Vec<OutsideRun>,
}

impl OutsideMethod {
    /// The label of the method in tables and reports: `<method> (outside)`.
    pub fn label(&self) -> String {
        format!("{} (outside)", self.method)
    }

    /// FE for meshes, BVP for tolerances (the kind of all its runs).
    pub fn family(&self) -> Family {
        match self.runs.first().map(|r| r.discretisation) {
            Some(Discretisation::Tolerance(_)) => Family::Bvp,
            _ => Family::Fem,
        }
    }

    /// Its runs as runs of the harness, fields on `samples` uniform σ points.
    pub fn harness_runs(&self, scene: &Scene, samples: usize) -> Vec<Run> {
        self.runs.iter().map(|r| harness_run(&self.label(), self.family(), r, scene, samples)).collect()
    }
}

/// The fine-to-coarse order of a discretisation kind: elements along σ, or the inverse
/// tolerance.
fn fineness(d: Discretisation) -> f64 {
    match d {
        Discretisation::Tolerance(t) => 1.0 / t,
        Discretisation::Elements(n) => n as f64,
        Discretisation::Mesh2d { sigma, zeta, time_step } => (sigma * zeta) as f64 / time_step,
    }
}

fn same_kind(a: Discretisation, b: Discretisation) -> bool {
    std::mem::discriminant(&a) == std::mem::discriminant(&b)
}

/// The runs grouped by method (in order of first appearance), each sorted coarsest
/// first, and the files set aside (another scene, not converged).
///
/// # Errors
/// [`OutsideError::Duplicate`] for a discretisation used twice by one method,
/// [`OutsideError::MixedKinds`] for a method with meshes and tolerances.
pub fn group(scene: &Scene, runs: Vec<OutsideRun>) -> Result<(Vec<OutsideMethod>, Vec<Skip>), OutsideError> {
    let mut methods: Vec<OutsideMethod> = Vec::new();
    let mut skipped = Vec::new();
    for run in runs {
        let skip = |reason| Skip { file: run.file.clone(), method: run.result.method.clone(), discretisation: Some(run.discretisation), reason };
        if run.result.scene != scene.name {
            skipped.push(skip(SkipReason::OtherScene { scene: run.result.scene.clone() }));
            continue;
        }
        if !run.result.converged {
            skipped.push(skip(SkipReason::NotConverged));
            continue;
        }
        let k = match methods.iter().position(|m| m.method == run.result.method) {
            Some(k) => k,
            None => {
                methods.push(OutsideMethod { method: run.result.method.clone(), runs: Vec::new() });
                methods.len() - 1
            }
        };
        let m = &mut methods[k];
        if let Some(other) = m.runs.iter().find(|o| !same_kind(o.discretisation, run.discretisation)) {
            return Err(OutsideError::MixedKinds { method: m.method.clone(), file: run.file.clone(), other_file: other.file.clone(), discs: Box::new((run.discretisation, other.discretisation)) });
        }
        if let Some(other) = m.runs.iter().find(|o| o.discretisation == run.discretisation) {
            return Err(OutsideError::Duplicate { method: m.method.clone(), disc: run.discretisation, first: other.file.clone(), second: run.file.clone() });
        }
        m.runs.push(run);
    }
    for m in &mut methods {
        m.runs.sort_by(|a, b| fineness(a.discretisation).total_cmp(&fineness(b.discretisation)));
    }
    Ok((methods, skipped))
}

/// Sets aside the runs with no quantity among `quantities` (the reference's): no
/// summary scalar it has, and no fields where it has field norms. Methods left without
/// runs are dropped (their files are in the skips).
pub fn drop_incomparable(methods: Vec<OutsideMethod>, quantities: &[Quantity], skipped: &mut Vec<Skip>) -> Vec<OutsideMethod> {
    let has_field_norms = quantities.iter().any(|q| !q.is_scalar());
    let mut kept = Vec::new();
    for mut m in methods {
        let (keep, drop): (Vec<OutsideRun>, Vec<OutsideRun>) = m.runs.into_iter().partition(|r| {
            let scalar = quantities.iter().any(|q| q.is_scalar() && r.result.summary.get(&q.name).is_some());
            scalar || (has_field_norms && r.result.fields.as_ref().is_some_and(|f| !f.is_empty()))
        });
        for r in drop {
            skipped.push(Skip { file: r.file, method: m.method.clone(), discretisation: Some(r.discretisation), reason: SkipReason::NothingComparable });
        }
        m.runs = keep;
        if !m.runs.is_empty() {
            kept.push(m);
        }
    }
    kept
}

/// One outside run as a run of the harness: its summary, its cost (the wall time it
/// reports), its fields interpolated onto `n` uniform σ samples.
fn harness_run(label: &str, family: Family, r: &OutsideRun, scene: &Scene, n: usize) -> Run {
    let c = &r.result.cost;
    let cost = RunCost { mesh_nodes: c.mesh_nodes, elements: r.discretisation.elements_along(), ..RunCost::counted(c.wall_seconds, c.newton_iterations, c.unknowns) };
    let samples = r.result.fields.as_ref().map_or_else(Samples::default, |f| interpolate(f, scene, n));
    let data = RunData {
        summary: r.result.summary.clone(),
        cost,
        options: r.result.options.clone().unwrap_or(Value::Null),
        terms: Vec::new(),
        notes: vec![format!("read from {}", r.file.display())],
        warnings: r.result.warnings.clone(),
        samples,
        history: r.result.history.clone(),
    };
    Run { method: label.to_string(), family, discretisation: r.discretisation, wall_seconds: c.wall_seconds, outcome: Ok(data) }
}

/// Linear interpolation of the fields (at their σ, with ν from (x, y)) onto the
/// harness's grid σ_i = i·L_geom/n: periodic round the loop; on the open one-pulley
/// contour between its samples, held at the end values beyond the first and last (which
/// [`check_fields`] has kept within [`MAX_GAP`] of the ends). The contact state is
/// inferred: in contact where the point lies on a pulley arc with ν ≤ 0 (the files carry
/// no state).
fn interpolate(f: &Fields, scene: &Scene, n: usize) -> Samples {
    let path = scene.path();
    let l = path.length();
    let mut pts: Vec<(f64, f64, f64, Option<f64>)> = (0..f.len())
        .map(|i| {
            let (s, nu) = path.sigma_nu([f.x[i], f.y[i]]);
            (s, nu, f.tension[i], f.moment.as_ref().map(|m| m[i]))
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let m = pts.len();
    let mut out = Samples::default();
    let mut moment = f.moment.is_some().then(Vec::new);
    let mut j = 0; // pts[j].0 ≤ σ < pts[j+1].0 (periodically on the loop)
    for i in 0..n {
        let sigma = l * i as f64 / n as f64;
        while j + 1 < m && pts[j + 1].0 <= sigma {
            j += 1;
        }
        // the bracketing pair: across the seam σ = 0 on the loop, the end sample itself
        // beyond an end of the open contour
        let (a, b, sa, sb) = if sigma < pts[0].0 {
            if path.is_open() {
                (0, 0, pts[0].0, pts[0].0)
            } else {
                (m - 1, 0, pts[m - 1].0 - l, pts[0].0)
            }
        } else if j + 1 < m {
            (j, j + 1, pts[j].0, pts[j + 1].0)
        } else if path.is_open() {
            (m - 1, m - 1, pts[m - 1].0, pts[m - 1].0)
        } else {
            (m - 1, 0, pts[m - 1].0, pts[0].0 + l)
        };
        let t = if sb > sa { (sigma - sa) / (sb - sa) } else { 0.0 };
        let lerp = |u: f64, v: f64| u + t * (v - u);
        let nu = lerp(pts[a].1, pts[b].1);
        let p = path.position(sigma, nu);
        out.sigma.push(sigma);
        out.x.push(p[0]);
        out.y.push(p[1]);
        out.deflection.push(nu);
        out.tension.push(lerp(pts[a].2, pts[b].2));
        if let (Some(mv), Some(ma), Some(mb)) = (moment.as_mut(), pts[a].3, pts[b].3) {
            mv.push(lerp(ma, mb));
        }
        let on_arc = path.is_polar(sigma);
        out.state.push(if on_arc && nu <= 0.0 { ContactState::Contact } else { ContactState::Free });
    }
    out.moment = moment;
    out
}

/// The CSV form of a result (the reader's format, [`read_result`]): one `#` line with
/// the result JSON without `fields`, a row of column names (`sigma,x,y,tension` and
/// `moment` for rods), one row per sample. Numbers are written to round-trip exactly.
///
/// # Errors
/// A non-finite number ([`RunResult::check`]).
pub fn to_csv(result: &RunResult) -> Result<String, drive::error::ResultError> {
    use std::fmt::Write;
    result.check()?;
    let mut header = result.clone();
    let fields = header.fields.take().unwrap_or_default();
    let mut out = format!("# {}\n", serde_json::to_string(&header).unwrap_or_default());
    let _ = writeln!(out, "sigma,x,y,tension{}", if fields.moment.is_some() { ",moment" } else { "" });
    for i in 0..fields.len() {
        let _ = write!(out, "{},{},{},{}", fields.sigma[i], fields.x[i], fields.y[i], fields.tension[i]);
        if let Some(m) = &fields.moment {
            let _ = write!(out, ",{}", m[i]);
        }
        out.push('\n');
    }
    Ok(out)
}
