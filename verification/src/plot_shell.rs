//! SVG plots of a shell study (issue 15; plotters, SVG backend): the run-off in time of
//! every level, and heat maps over (σ, ζ) of the contact pressure and the interlayer
//! shear of the finest level's last frame.

use plotters::prelude::*;

use drive::result::{SurfaceFields, TimeSeries};

use crate::plot::{area_message, err, grid_style, labelled_line, legend_box, padded, range_of, render, Area, PlotError, WIDTH};
use crate::study::{SeriesStatus, Study};

/// The history of every successful level of the study's shell series, coarsest first:
/// (label, start of the rotation t₀ in s, history). The levels' ramps at rest last
/// `ramp_steps` of their own Δt, so their rotations start at different t; the plots are
/// over t − t₀.
fn level_histories(study: &Study) -> Vec<(String, f64, &TimeSeries)> {
    studied_rows(study)
        .filter_map(|r| {
            let d = r.run.data()?;
            let t0 = d.options.pointer("/shell/rotation_start").and_then(serde_json::Value::as_f64).unwrap_or(0.0);
            d.history.as_ref().map(|h| (crate::table::fmt_disc(r.run.discretisation), t0, h))
        })
        .collect()
}

/// The rows of the studied series (the shell study's one series: its levels, coarsest
/// first).
fn studied_rows(study: &Study) -> impl DoubleEndedIterator<Item = &crate::study::Row> {
    study.series.iter().filter(|s| s.status == SeriesStatus::Studied).flat_map(|s| s.rows.iter())
}

/// Level k of n in light to dark red (the finest darkest).
fn level_color(k: usize, n: usize) -> RGBColor {
    let f = if n <= 1 { 1.0 } else { k as f64 / (n - 1) as f64 };
    let mix = |a: f64, b: f64| (a + (b - a) * f) as u8;
    RGBColor(mix(250.0, 150.0), mix(160.0, 0.0), mix(140.0, 20.0))
}

/// One channel of every level over t, in one panel.
fn channel_panel(area: &Area, histories: &[(String, f64, &TimeSeries)], channel: &str, title: &str, ydesc: &str) -> Result<(), String> {
    let curves: Vec<(&String, Vec<(f64, f64)>)> = histories
        .iter()
        .filter_map(|(label, t0, h)| h.channel(channel).map(|c| (label, h.time.iter().map(|t| t - t0).zip(c.iter().copied()).collect())))
        .collect();
    if curves.is_empty() {
        return area_message(area, title, &format!("no `{channel}` channel in the runs"));
    }
    let (t0, t1) = range_of(curves.iter().flat_map(|(_, p)| p.iter().map(|q| &q.0)));
    let (t0, t1) = padded(t0, t1);
    let (y0, y1) = range_of(curves.iter().flat_map(|(_, p)| p.iter().map(|q| &q.1)));
    let (y0, y1) = padded(y0, y1);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 20))
        .margin_left(10)
        .margin_right(30)
        .x_label_area_size(50)
        .y_label_area_size(110)
        .build_cartesian_2d(t0..t1, y0..y1)
        .map_err(err)?;
    let mut mesh = chart.configure_mesh();
    // a tick at round-off from 0 reads 0, not −1.7e-21
    let tiny = 1e-9 * (y1 - y0).abs();
    let label = move |v: &f64| if v.abs() <= tiny { "0".to_string() } else { format!("{v:.2e}") };
    grid_style(&mut mesh, 16).x_desc("t − t₀ [s] (t₀: the start of the rotation)").y_desc(ydesc).y_label_formatter(&label);
    mesh.draw().map_err(err)?;
    let n = curves.len();
    for (k, (label, pts)) in curves.into_iter().enumerate() {
        labelled_line(&mut chart, pts, level_color(k, n), 2, false, label.clone())?;
    }
    legend_box(&mut chart, SeriesLabelPosition::UpperLeft, 16)
}

/// The run-off in time: the belt's lateral offset z̄(t) (the width-averaged lateral
/// position, docs/fem-shell.md §9.3) and its rate, every level of the study overlaid.
///
/// # Errors
/// A plot plotters cannot draw.
pub fn runoff_svg(study: &Study) -> Result<String, PlotError> {
    let histories = level_histories(study);
    render("runoff", 900, |root| {
        let panels = root.split_evenly((2, 1));
        channel_panel(&panels[0], &histories, "lateral_offset", "run-off: lateral offset z̄(t) of the belt, every level", "z̄ [m]")?;
        channel_panel(&panels[1], &histories, "lateral_velocity", "run-off velocity dz̄/dt", "dz̄/dt [m/s]")
    })
}

/// A perceptually ordered colour scale (dark blue → teal → yellow) at f ∈ [0, 1].
pub fn heat_color(f: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [(0.0, [68.0, 1.0, 84.0]), (0.25, [59.0, 82.0, 139.0]), (0.5, [33.0, 145.0, 140.0]), (0.75, [94.0, 201.0, 98.0]), (1.0, [253.0, 231.0, 37.0])];
    let f = if f.is_finite() { f.clamp(0.0, 1.0) } else { 0.0 };
    let k = STOPS.iter().position(|s| s.0 >= f).unwrap_or(STOPS.len() - 1).max(1);
    let ((a, ca), (b, cb)) = (STOPS[k - 1], STOPS[k]);
    let w = if b > a { (f - a) / (b - a) } else { 0.0 };
    let c = |i: usize| (ca[i] + (cb[i] - ca[i]) * w).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// One field of a frame as a heat map over (σ, ζ): each cell of the node grid coloured
/// by the mean of its four corner values on a linear scale from 0 (or the smallest value,
/// if negative) to the largest, with a colour bar.
fn heat_panel(area: &Area, frame: &SurfaceFields, field: &str, factor: f64, title: &str, unit: &str) -> Result<(), String> {
    let Some(values) = frame.values.get(field) else {
        return area_message(area, title, &format!("no `{field}` in the frame"));
    };
    let values: Vec<Vec<f64>> = values.iter().map(|row| row.iter().map(|v| factor * v).collect()).collect();
    let (ns, nz) = (frame.sigma.len(), frame.zeta.len());
    if ns < 2 || nz < 2 {
        return area_message(area, title, "the frame's grid has fewer than 2 × 2 nodes");
    }
    let (lo, hi) = values.iter().flatten().fold((0.0f64, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let scale = if hi > lo { hi - lo } else { 1.0 };
    let (map, bar) = area.split_horizontally(WIDTH - 170);
    let s_end = frame.sigma[ns - 1];
    let (z0, z1) = (frame.zeta[0], frame.zeta[nz - 1]);
    let mut chart = ChartBuilder::on(&map)
        .caption(title, ("sans-serif", 20))
        .margin_left(10)
        .margin_right(10)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(frame.sigma[0]..s_end, z0..z1)
        .map_err(err)?;
    chart.configure_mesh().disable_mesh().x_desc("σ [m]").y_desc("ζ [m]").label_style(("sans-serif", 16)).axis_desc_style(("sans-serif", 18)).draw().map_err(err)?;
    let mut cells = Vec::with_capacity((ns - 1) * (nz - 1));
    for i in 0..ns - 1 {
        for j in 0..nz - 1 {
            let mean = 0.25 * (values[i][j] + values[i + 1][j] + values[i][j + 1] + values[i + 1][j + 1]);
            let col = heat_color((mean - lo) / scale);
            cells.push(Rectangle::new([(frame.sigma[i], frame.zeta[j]), (frame.sigma[i + 1], frame.zeta[j + 1])], col.filled()));
        }
    }
    chart.draw_series(cells).map_err(err)?;
    // the colour bar
    let mut cb = ChartBuilder::on(&bar)
        .caption(unit, ("sans-serif", 16))
        .margin_top(40)
        .margin_right(10)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..1.0, lo..lo + scale)
        .map_err(err)?;
    cb.configure_mesh().disable_mesh().disable_x_axis().y_label_formatter(&|v| format!("{v:.2e}")).label_style(("sans-serif", 14)).draw().map_err(err)?;
    let steps = 64;
    cb.draw_series((0..steps).map(|k| {
        let (a, b) = (lo + scale * k as f64 / steps as f64, lo + scale * (k + 1) as f64 / steps as f64);
        Rectangle::new([(0.0, a), (1.0, b)], heat_color((k as f64 + 0.5) / steps as f64).filled())
    }))
    .map_err(err)?;
    Ok(())
}

/// The last frame of the finest level with surface fields: (label, time, fields, the
/// interlayer's tangential stiffness P_⊥ of the run's options if it states it).
fn last_frame(study: &Study) -> Option<(String, f64, &SurfaceFields, Option<f64>)> {
    studied_rows(study).rev().find_map(|r| {
        let d = r.run.data()?;
        let h = d.history.as_ref()?;
        let f = h.frames.iter().rev().find(|f| f.surface.is_some())?;
        let p_t = d.options.pointer("/shell/interlayer/tangential_stiffness").and_then(serde_json::Value::as_f64);
        Some((crate::table::fmt_disc(r.run.discretisation), f.time, f.surface.as_ref()?, p_t))
    })
}

/// Heat maps over (σ, ζ) of the contact pressure Pγ and the interlayer shear stress
/// P_⊥|u| (the frame's `interlayer_shear` is |u|, scaled by the run's P_⊥; |u| itself
/// where the options do not state P_⊥) of the finest level at its last frame (the fields
/// of docs/fem-shell.md §14).
///
/// # Errors
/// A plot plotters cannot draw.
pub fn contact_maps_svg(study: &Study) -> Result<String, PlotError> {
    let frame = last_frame(study);
    render("contact-maps", 760, |root| {
        let panels = root.split_evenly((2, 1));
        let Some((label, t, f, p_t)) = frame else {
            return area_message(root, "contact maps", "no level of the study wrote a frame of surface fields");
        };
        heat_panel(&panels[0], f, "contact_pressure", 1.0, &format!("contact pressure Pγ over (σ, ζ), {label}, t = {t:.3} s"), "Pγ [N/m²]")?;
        match p_t {
            Some(p) => heat_panel(&panels[1], f, "interlayer_shear", p, &format!("interlayer shear stress P_⊥|u| over (σ, ζ), {label}, t = {t:.3} s"), "P_⊥|u| [N/m²]"),
            None => heat_panel(&panels[1], f, "interlayer_shear", 1.0, &format!("interlayer displacement |u| over (σ, ζ), {label}, t = {t:.3} s"), "|u| [m]"),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_scale_runs_from_its_first_to_its_last_stop_and_is_monotone_in_lightness() {
        assert_eq!(heat_color(0.0), RGBColor(68, 1, 84));
        assert_eq!(heat_color(1.0), RGBColor(253, 231, 37));
        assert_eq!(heat_color(-3.0), heat_color(0.0));
        assert_eq!(heat_color(f64::NAN), heat_color(0.0));
        let light = |c: RGBColor| 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
        let mut last = -1.0;
        for k in 0..=100 {
            let l = light(heat_color(k as f64 / 100.0));
            assert!(l >= last - 1e-9, "lightness falls at {k}: {l} < {last}");
            last = l;
        }
    }

    /// The runs of a synthetic shell study at `levels` (three; no solve): q = 1 + 1/n²
    /// for the mid-span heights with n = 32, 64, 128 by level, an oscillating tension, a
    /// lateral offset z̄ = v (t − t₀) per level and one frame of surface fields on the
    /// finest.
    fn synthetic_runs(levels: &[crate::run::Discretisation]) -> Vec<crate::run::Run> {
        use crate::run::{Family, Run, RunCost, RunData, Samples};
        levels
            .iter()
            .enumerate()
            .map(|(k, &d)| {
                let n = [32.0, 64.0, 128.0][k];
                let mut summary = drive::summary::Summary::default();
                summary.set("y_upper_mid", Some(1.0 + 1.0 / (n * n))).unwrap();
                summary.set("tension_upper_mid", Some([40.0, 50.0, 45.0][k])).unwrap();
                let t0 = 1.0 + 0.1 * k as f64;
                let mut history = TimeSeries::default();
                for i in 0..=4 {
                    let t = t0 + 0.05 * i as f64;
                    history.push(t, &[("lateral_offset", 1e-6 * (t - t0)), ("lateral_velocity", 1e-6)]);
                }
                if k == 2 {
                    let sigma = vec![0.0, 1.0, 2.0];
                    let zeta = vec![-0.1, 0.0, 0.1];
                    let field = vec![vec![0.0, 1.0, 0.0], vec![2.0, 3.0, 2.0], vec![0.0, 1.0, 0.0]];
                    let surface = SurfaceFields { sigma, zeta, values: [("contact_pressure".to_string(), field.clone()), ("interlayer_shear".to_string(), field)].into() };
                    history.frames.push(drive::result::Frame { time: t0 + 0.2, fields: None, surface: Some(surface) });
                }
                let data = RunData {
                    summary,
                    cost: RunCost::counted(1.0 + k as f64, 10, 100),
                    options: serde_json::json!({"shell": {"rotation_start": t0, "interlayer": {"tangential_stiffness": 1e8}}}),
                    terms: Vec::new(),
                    notes: Vec::new(),
                    warnings: Vec::new(),
                    samples: Samples::default(),
                    history: Some(history),
                };
                Run { method: crate::run::SHELL_FE.into(), family: Family::Fem, discretisation: d, wall_seconds: 1.0, outcome: Ok(data) }
            })
            .collect()
    }

    /// A shell study that refines only the time step on one mesh (`--refine step`):
    /// its convergence plot is over the step's refinement Δt₀/Δt (not the element
    /// count, which is one), the study notes the limit it converges to, and the report's
    /// command reproduces it.
    #[test]
    fn a_study_of_the_time_step_alone_plots_over_the_step_and_says_what_it_converges_to() {
        use crate::run::Discretisation;
        use crate::study::{Study, StudyPlan};
        let scene = drive::Scene::from_json_str(include_str!("../../scenes/shell-runoff.json")).unwrap();
        let levels: Vec<Discretisation> = (0..3).map(|k| Discretisation::Mesh2d { sigma: 32, zeta: 2, time_step: 0.1 / f64::from(1u32 << k) }).collect();
        let plan = StudyPlan::shell(levels.clone()).with_compensation();
        plan.validate().unwrap();
        assert_eq!(plan.shell_refinement(), Some(drive::result::Refinement::Step));
        let notes = crate::study::shell_level_notes(&levels);
        assert!(notes.len() == 1 && notes[0].starts_with("the time step alone is refined, on the mesh 32×2: the sequence converges to the time-continuous limit on that mesh"), "{notes:?}");
        let computed = plan.reference.richardson(&synthetic_runs(&levels));
        let y = computed.estimates.iter().find(|e| e.quantity == "y_upper_mid").expect("y extrapolated");
        assert!((y.value - 1.0).abs() < 1e-12 && (y.order.unwrap() - 2.0).abs() < 1e-9, "{y:?}");
        let study = Study::of_runs(&scene, &plan, computed, vec![(crate::run::SHELL_FE.into(), crate::run::Family::Fem, synthetic_runs(&levels))]);
        let svg = crate::plot::convergence_svg(&scene, &study).unwrap();
        assert!(svg.contains("error vs time-step refinement Δt₀/Δt") && svg.contains("slope Δt^2"), "the step's axis");
        let texts: Vec<&str> = svg.split("</text>").filter_map(|t| t.rsplit_once('>').map(|(_, x)| x.trim())).collect();
        for tick in ["1", "2", "4"] {
            assert!(texts.contains(&tick), "tick {tick} of Δt₀/Δt in {texts:?}");
        }
        let dir = std::env::temp_dir().join(format!("beltcheck-report-shell-step-{}", std::process::id()));
        crate::report::write_scene_report(&scene, std::path::Path::new("scenes/shell-runoff.json"), &study, &dir).unwrap();
        let md = std::fs::read_to_string(dir.join("shell-runoff").join("report.md")).unwrap();
        // a plan that searches the swivel reproduces without --no-compensation
        assert!(md.contains("beltcheck converge scenes/shell-runoff.json --refine step --levels 32x2`"), "{md}");
        assert!(md.contains("against the step's refinement Δt₀/Δt"), "the caption names the step's axis");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A shell study that refines only the width on one σ-mesh (`--refine width`): its
    /// convergence plot is over n_ζ (not the σ count, which is one), the study notes the
    /// limit it converges to and what it leaves out, and the report's command reproduces
    /// it, with `--no-compensation` for a plan that did not search the swivel.
    #[test]
    fn a_study_of_the_width_alone_plots_over_n_zeta_and_says_what_it_converges_to() {
        use crate::run::Discretisation;
        use crate::study::{Study, StudyPlan};
        let scene = drive::Scene::from_json_str(include_str!("../../scenes/shell-runoff.json")).unwrap();
        let levels: Vec<Discretisation> = (0..3).map(|k| Discretisation::Mesh2d { sigma: 32, zeta: 2 << k, time_step: 0.1 }).collect();
        let plan = StudyPlan::shell(levels.clone());
        plan.validate().unwrap();
        assert_eq!(plan.shell_refinement(), Some(drive::result::Refinement::Width));
        let notes = crate::study::shell_level_notes(&levels);
        assert!(notes.len() == 1 && notes[0].starts_with("the width alone is refined, n_ζ on the σ-mesh of 32 elements at Δt = 0.1 s"), "{notes:?}");
        let computed = plan.reference.richardson(&synthetic_runs(&levels));
        let y = computed.estimates.iter().find(|e| e.quantity == "y_upper_mid").expect("y extrapolated");
        assert!((y.value - 1.0).abs() < 1e-12 && (y.order.unwrap() - 2.0).abs() < 1e-9, "{y:?}");
        let study = Study::of_runs(&scene, &plan, computed, vec![(crate::run::SHELL_FE.into(), crate::run::Family::Fem, synthetic_runs(&levels))]);
        let svg = crate::plot::convergence_svg(&scene, &study).unwrap();
        assert!(svg.contains("elements across the width n_ζ") && svg.contains("slope h^2") && !svg.contains("slope Δt"), "the width's axis and slopes");
        let texts: Vec<&str> = svg.split("</text>").filter_map(|t| t.rsplit_once('>').map(|(_, x)| x.trim())).collect();
        assert!(!texts.contains(&"32"), "no σ count on the axis: {texts:?}");
        let dir = std::env::temp_dir().join(format!("beltcheck-report-shell-width-{}", std::process::id()));
        crate::report::write_scene_report(&scene, std::path::Path::new("scenes/shell-runoff.json"), &study, &dir).unwrap();
        let md = std::fs::read_to_string(dir.join("shell-runoff").join("report.md")).unwrap();
        assert!(md.contains("beltcheck converge scenes/shell-runoff.json --refine width --levels 32x2,32x4,32x8 --no-compensation`"), "{md}");
        assert!(md.contains("against the elements across the width n_ζ"), "the caption names the width's axis");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A shell study made of three synthetic levels (no solve): q(n) = 1 + 1/n² for the
    /// mid-span heights, an oscillating tension, a lateral offset z̄ = v (t − t₀) per
    /// level and one frame of surface fields on the finest. `report` writes the run-off
    /// and contact-map plots in place of shape and force, the reference's estimates
    /// (the exact limit), and no mutual-convergence table.
    #[test]
    fn a_shell_study_reports_its_run_off_its_contact_maps_and_its_estimates() {
        use crate::run::{Discretisation, Family};
        use crate::study::{Study, StudyPlan};
        let scene = drive::Scene::from_json_str(include_str!("../../scenes/shell-runoff.json")).unwrap();
        let levels: Vec<Discretisation> = [32usize, 64, 128].iter().map(|&n| crate::run::ShellFe::level(&scene, n, 2)).collect();
        let plan = StudyPlan::shell(levels.clone());
        let runs = synthetic_runs(&levels);
        let computed = plan.reference.richardson(&runs);
        let mut study = Study::of_runs(&scene, &plan, computed, vec![(crate::run::SHELL_FE.into(), Family::Fem, runs)]);
        study.compensation = Some(fem::shell::compensation::Compensation {
            drum: drive::scene::SteeringDrum::Driven,
            measure: fem::shell::compensation::RunoffMeasure::LastRevolution,
            swivel: -1.25e-6,
            runoff_without: 3.0e-8,
            probe: [5e-4, -1.2e-5],
            linear_estimate: -1.24e-6,
            runoff_left: 1.0e-12,
            tolerance: 1.2e-10,
            solves: 5,
        });
        let y = study.reference_estimates.iter().find(|e| e.quantity == "y_upper_mid").expect("y extrapolated");
        assert!((y.value - 1.0).abs() < 1e-12 && (y.order.unwrap() - 2.0).abs() < 1e-9, "{y:?}");
        assert!(study.reference_estimates.iter().all(|e| e.quantity != "tension_upper_mid"), "the oscillating tension is refused");
        let dir = std::env::temp_dir().join(format!("beltcheck-report-shell-{}", std::process::id()));
        let entry = crate::report::write_scene_report(&scene, std::path::Path::new("scenes/shell-runoff.json"), &study, &dir).unwrap();
        let sdir = dir.join("shell-runoff");
        for f in ["runoff.svg", "contact-maps.svg", "convergence.svg", "work-precision.svg", "study.json", "report.md"] {
            assert!(sdir.join(f).is_file(), "{f} missing");
        }
        assert!(!sdir.join("shape.svg").exists() && !sdir.join("force.svg").exists());
        assert_eq!(entry.files.len(), 5);
        let md = std::fs::read_to_string(sdir.join("report.md")).unwrap();
        for part in ["![run-off](runoff.svg)", "![contact maps](contact-maps.svg)", "### The reference's values", "| y_upper_mid |", "no BVP exists for the shell", "--levels 32x2,64x2,128x2", "refused (left out of the reference): tension_upper_mid"] {
            assert!(md.contains(part), "report.md lacks {part:?}:\n{md}");
        }
        assert!(!md.contains("Mutual convergence FE ↔ BVP"), "{md}");
        assert!(md.contains("### The compensating swivel") && md.contains("β_y* = -1.250000e-6 rad"), "{md}");
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(sdir.join("study.json")).unwrap()).unwrap();
        assert_eq!(json["compensation"]["swivel"], -1.25e-6);
        assert_eq!(json["compensation"]["drum"], "driven");
        assert_eq!(json["compensation"]["measure"], "last_revolution");
        assert!(md.contains("the slope over the last revolution"), "{md}");
        // the run-off panel: one curve per level over t − t₀ (all start at 0)
        let svg = std::fs::read_to_string(sdir.join("runoff.svg")).unwrap();
        for label in ["32×2", "64×2", "128×2"] {
            assert!(svg.contains(label), "{label} not in the run-off legend");
        }
        assert!(svg.contains("t − t₀ [s]"));
        // the contact maps: the finest level's frame; each of its four cells has the corner
        // mean 1.5 on the scale 0 … 3, so the middle colour, twice (two fields)
        let maps = std::fs::read_to_string(sdir.join("contact-maps.svg")).unwrap();
        let hex = |c: RGBColor| format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
        assert!(maps.matches(&hex(heat_color(0.5))).count() >= 8, "the four cells of both maps at the corner mean");
        assert_eq!(maps.matches(&hex(heat_color(0.0))).count(), 0, "no cell at the bottom of the scale");
        assert!(maps.contains("128×2"), "labelled with its level");
        // |u| of the frame scaled by P_⊥ = 1e8 of the options: the bar tops at 3e8
        assert!(maps.contains("interlayer shear stress P_⊥|u|") && maps.contains("3.00e8"), "the shear map in N/m²");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A frame whose pressure is σ·ζ-free except one hot cell: the SVG carries the
    /// hot colour once per hot cell and the colour bar, and a frame-less study says so.
    #[test]
    fn heat_map_colours_cells_by_their_corner_mean() {
        let sigma = vec![0.0, 1.0, 2.0, 3.0];
        let zeta = vec![-0.1, 0.0, 0.1];
        let mut p = vec![vec![0.0; 3]; 4];
        for row in p.iter_mut().skip(1).take(2) {
            row[1] = 4.0; // the cells (1, 0) and (1, 1) touch two hot corners each; (0, *) and (2, *) one
        }
        let frame = SurfaceFields { sigma, zeta, values: [("contact_pressure".to_string(), p.clone()), ("interlayer_shear".to_string(), p)].into() };
        let svg = render("test", 760, |root| heat_panel(root, &frame, "contact_pressure", 1.0, "t", "Pγ")).unwrap();
        // corner means: 1.0 (four cells), 2.0 (two cells): scale 0 … 4
        let half = heat_color(0.5);
        let quarter = heat_color(0.25);
        let hex = |c: RGBColor| format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
        let count = |c: RGBColor| svg.matches(&hex(c)).count();
        assert!(count(half) >= 2, "two cells at half the scale: {}", count(half));
        assert!(count(quarter) >= 4, "four cells at a quarter: {}", count(quarter));
    }
}
