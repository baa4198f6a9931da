//! SVG plots of a study (plotters, SVG backend only: no system libraries).
//!
//! - [`shape_svg`]: the belt to scale with the pulleys, contact zones marked, and the
//!   deflection ν(σ) magnified below;
//! - [`force_svg`]: axial force (and moment) along σ, BVP reference and the finest run
//!   of each FE formulation overlaid, with |N − N_ref| of every method's finest run;
//!   for a shear-deformable rod also its contact pressure with close-ups of the edge
//!   peaks and its shear strain, on a σ grid refined at the contact edges;
//! - [`convergence_svg`]: FE error vs elements with reference slopes, BVP error vs
//!   requested tolerance with the line error = tolerance;
//! - [`work_precision_svg`]: error vs wall time, every method of the scene on one axis.
//!
//! Canvases are large (1200 px wide) because SVG coordinates are whole pixels.

use plotters::coord::Shift;
use plotters::chart::MeshStyle;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::CoordTranslate;
use plotters::prelude::*;

use drive::result::Refinement;
use drive::scene::Scene;
use drive::view::ContactState;

use crate::run::{fmt_tolerance, Discretisation, EdgeDetail, Family, Samples};
use crate::study::{Series, SeriesStatus, Study};

/// Canvas width, px.
pub const WIDTH: u32 = 1200;

pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Why a plot could not be drawn (a plotters error, as text).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("plot {plot}: {message}")]
pub struct PlotError {
    /// Which plot.
    pub plot: &'static str,
    /// plotters' message.
    pub message: String,
}

pub(crate) fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

const REFERENCE: RGBColor = RGBColor(0, 0, 0);
/// FE formulations, in registry order (none of them the contact orange or a BVP colour).
const FE_COLORS: [RGBColor; 5] = [RGBColor(214, 39, 40), RGBColor(0, 150, 136), RGBColor(140, 86, 75), RGBColor(227, 80, 180), RGBColor(128, 128, 0)];
const FREE: RGBColor = RGBColor(31, 119, 180);
const CONTACT: RGBColor = RGBColor(230, 115, 0);
const STICK: RGBColor = RGBColor(44, 160, 44);
const SLIP: RGBColor = RGBColor(214, 39, 40);
const PULLEY: RGBColor = RGBColor(200, 200, 200);
const GRID: RGBColor = RGBColor(225, 225, 225);

/// The colour of a series: fixed per BVP variant, FE formulations in registry order.
pub fn series_color(study: &Study, index: usize) -> RGBColor {
    let s = &study.series[index];
    match s.family {
        Family::ClosedForm => RGBColor(0, 0, 0),
        Family::Bvp => {
            if s.method.contains("gauss4") {
                RGBColor(31, 119, 180)
            } else if s.method.contains("gauss6") {
                RGBColor(44, 160, 44)
            } else if s.method.contains("gauss8") {
                RGBColor(23, 190, 207)
            } else {
                RGBColor(148, 103, 189)
            }
        }
        Family::Fem => {
            let k = study.series[..index].iter().filter(|s| s.family == Family::Fem).count();
            FE_COLORS[k % FE_COLORS.len()]
        }
    }
}

fn state_color(s: ContactState) -> RGBColor {
    match s {
        ContactState::Free => FREE,
        ContactState::Contact => CONTACT,
        ContactState::Stick => STICK,
        ContactState::Slip => SLIP,
    }
}

fn state_name(s: ContactState) -> &'static str {
    match s {
        ContactState::Free => "free span",
        ContactState::Contact => "contact",
        ContactState::Stick => "stick",
        ContactState::Slip => "slip",
    }
}

/// Renders `draw` into an SVG string of `WIDTH × height`.
pub(crate) fn render(plot: &'static str, height: u32, draw: impl FnOnce(&Area) -> Result<(), String>) -> Result<String, PlotError> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (WIDTH, height)).into_drawing_area();
        let run = || -> Result<(), String> {
            root.fill(&WHITE).map_err(err)?;
            draw(&root)?;
            root.present().map_err(err)
        };
        run().map_err(|message| PlotError { plot, message })?;
    }
    Ok(buf)
}

/// The finest successful FE run of each studied FE series: (series index, samples, label).
fn finest_fe(study: &Study) -> Vec<(usize, &Samples, String)> {
    study
        .series
        .iter()
        .enumerate()
        .filter(|(_, s)| s.family == Family::Fem && s.status == SeriesStatus::Studied)
        .filter_map(|(i, s)| {
            let row = s.rows.iter().rev().find(|r| r.run.data().is_some())?;
            let d = row.run.data()?;
            Some((i, &d.samples, format!("{} ({})", s.method, row.run.discretisation)))
        })
        .collect()
}

/// Contiguous runs of equal contact state: (state, first index, last index inclusive).
fn state_runs(states: &[ContactState]) -> Vec<(ContactState, usize, usize)> {
    let mut out: Vec<(ContactState, usize, usize)> = Vec::new();
    for (i, &s) in states.iter().enumerate() {
        match out.last_mut() {
            Some(last) if last.0 == s => last.2 = i,
            _ => out.push((s, i, i)),
        }
    }
    out
}

pub(crate) fn range_of<'a>(vals: impl IntoIterator<Item = &'a f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in vals {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 * (1.0 + hi.abs()) {
        let d = 0.5 * (1e-3 + hi.abs() * 1e-3);
        return (lo - d, hi + d);
    }
    (lo, hi)
}

/// Linear range with 6 % padding.
pub(crate) fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let d = 0.06 * (hi - lo);
    (lo - d, hi + d)
}

/// Decade bounds around positive values.
fn log_bounds(vals: &[f64]) -> (f64, f64) {
    let pos: Vec<f64> = vals.iter().copied().filter(|v| v.is_finite() && *v > 0.0).collect();
    if pos.is_empty() {
        return (1e-16, 1.0);
    }
    let lo = pos.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = pos.iter().copied().fold(0.0, f64::max);
    let mut a = 10f64.powf(lo.log10().floor());
    let mut b = 10f64.powf(hi.log10().ceil());
    if b <= a * 1.0001 {
        a /= 10.0;
        b *= 10.0;
    }
    // Slightly outside the decades: plotters places its first key point at
    // ceil(log10(start)), which rounding can push one decade up.
    (a * 0.999, b * 1.001)
}

fn log_label(v: &f64) -> String {
    let e = v.log10();
    if (e - e.round()).abs() < 1e-6 {
        format!("1e{}", e.round() as i64)
    } else {
        format!("{v:.0e}")
    }
}

/// The σ bounds of the regions of the scene's path (four round the loop, three along
/// the open contour) with short names.
fn regions(scene: &Scene) -> Vec<(f64, f64, &'static str)> {
    scene.path().regions()
}

// ---------------------------------------------------------------------------
// Belt shape

/// The belt of the reference to scale — pulleys (radius R to the belt centreline),
/// free spans and contact zones in their colours, contact boundaries as dots, the
/// finest run of each FE formulation dashed — and below it the deflection ν(σ)
/// magnified, with the contact zones shaded.
pub fn shape_svg(scene: &Scene, study: &Study) -> Result<String, PlotError> {
    let Some(reference) = study.reference.data() else {
        return message_svg("shape", "belt shape", "the reference could not be computed: no shape to draw");
    };
    let s = &reference.samples;
    let path = scene.path();
    let r = path.radius();
    let centres = path.pulley_centres();
    let fe = finest_fe(study);
    // Equal aspect ratio: choose the shape panel's height from its data ranges.
    let xs = s.x.iter().chain(fe.iter().flat_map(|f| f.1.x.iter()));
    let ys = s.y.iter().chain(fe.iter().flat_map(|f| f.1.y.iter()));
    let extent: Vec<f64> = centres.iter().flat_map(|c| [c[0] - r, c[0] + r]).collect();
    let (mut x0, mut x1) = range_of(xs.chain(extent.iter()));
    let (mut y0, mut y1) = range_of(ys.chain([-r, r].iter()));
    let pad = 0.08 * (x1 - x0).max(y1 - y0);
    x0 -= pad;
    x1 += pad;
    y0 -= pad;
    y1 += pad;
    let (left, right, top, bottom) = (90u32, 30u32, 60u32, 60u32);
    let pw = (WIDTH - left - right) as f64;
    // Headroom above the belt for the legend (entries × 22 px), in metres at 1:1.
    let entries = 4 + fe.len() + usize::from(s.state.iter().any(|&st| st != ContactState::Free && st != ContactState::Contact));
    y1 += (22.0 * entries as f64 + 16.0) * (x1 - x0) / pw;
    let mut ph = pw * (y1 - y0) / (x1 - x0);
    if ph > 900.0 {
        // Very tall: widen x instead so the aspect stays 1:1.
        let xr = (y1 - y0) * pw / 900.0;
        let xc = 0.5 * (x0 + x1);
        x0 = xc - xr / 2.0;
        x1 = xc + xr / 2.0;
        ph = 900.0;
    }
    if ph < 260.0 {
        let yr = (x1 - x0) * 260.0 / pw;
        let yc = 0.5 * (y0 + y1);
        y0 = yc - yr / 2.0;
        y1 = yc + yr / 2.0;
        ph = 260.0;
    }
    let shape_h = ph.round() as u32 + top + bottom;
    let nu_h = 360u32;
    render("shape", shape_h + nu_h, |root| {
        let (upper, lower) = root.split_vertically(shape_h);
        let mut chart = ChartBuilder::on(&upper)
            .caption(format!("{} — belt shape to scale (reference: {})", scene.name, study.reference.method), ("sans-serif", 24))
            .margin_left(10)
            .margin_right(right as i32)
            .margin_top(10)
            .x_label_area_size(bottom as i32 - 10)
            .y_label_area_size(left as i32 - 10)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        grid_style(&mut chart.configure_mesh(), 16)
            .x_desc("x [m]")
            .y_desc("y [m]")
            .x_label_formatter(&axis_label)
            .y_label_formatter(&axis_label)
            .draw()
            .map_err(err)?;
        // Pulleys: discs of radius R (to the belt centreline) and their centres.
        for &centre in &centres {
            let circle: Vec<(f64, f64)> = (0..=180)
                .map(|k| {
                    let a = k as f64 / 180.0 * std::f64::consts::TAU;
                    (centre[0] + r * a.cos(), centre[1] + r * a.sin())
                })
                .collect();
            chart.draw_series(std::iter::once(Polygon::new(circle.clone(), PULLEY.mix(0.5).filled()))).map_err(err)?;
            chart.draw_series(LineSeries::new(circle, PULLEY.stroke_width(2))).map_err(err)?;
            chart.draw_series(PointSeries::of_element([(centre[0], centre[1])], 6, BLACK, &|p, sz, st| Cross::new(p, sz, st))).map_err(err)?;
        }
        chart
            .draw_series(std::iter::once(PathElement::new(Vec::<(f64, f64)>::new(), PULLEY.stroke_width(8))))
            .map_err(err)?
            .label(format!("pulleys, R = {} m to the belt centreline", r))
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 24, y + 6)], PULLEY.filled()));
        // The reference belt, coloured by contact state (closed loop).
        let n = s.len();
        let mut labelled = Vec::new();
        for (state, a, b) in state_runs(&s.state) {
            let end = (b + 1).min(n.saturating_sub(1));
            let mut pts: Vec<(f64, f64)> = (a..=end).map(|i| (s.x[i], s.y[i])).collect();
            if b + 1 == n && n > 0 {
                pts.push((s.x[0], s.y[0]));
            }
            let width = if state == ContactState::Free { 3 } else { 7 };
            let series = chart.draw_series(LineSeries::new(pts, state_color(state).stroke_width(width))).map_err(err)?;
            if !labelled.contains(&state) {
                labelled.push(state);
                let col = state_color(state);
                series.label(format!("reference: {}", state_name(state))).legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], col.stroke_width(width)));
            }
        }
        // Contact boundaries.
        let runs = state_runs(&s.state);
        let bounds: Vec<(f64, f64)> = runs.iter().skip(1).map(|&(_, a, _)| (s.x[a], s.y[a])).collect();
        if !bounds.is_empty() {
            chart
                .draw_series(PointSeries::of_element(bounds, 6, BLACK.filled(), &|p, sz, st| Circle::new(p, sz, st)))
                .map_err(err)?
                .label("contact boundary")
                .legend(|(x, y)| Circle::new((x + 12, y), 5, BLACK.filled()));
        }
        for (i, fs, label) in &fe {
            let col = series_color(study, *i);
            let mut pts: Vec<(f64, f64)> = fs.x.iter().zip(&fs.y).map(|(&x, &y)| (x, y)).collect();
            if let Some(&p) = pts.first() {
                pts.push(p);
            }
            labelled_line(&mut chart, pts, col, 2, true, label.clone())?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        nu_panel(scene, study, &lower, &fe)
    })
}

/// ν(σ) of the reference and the FE runs, magnified, contact zones shaded.
fn nu_panel(scene: &Scene, study: &Study, area: &Area, fe: &[(usize, &Samples, String)]) -> Result<(), String> {
    let Some(reference) = study.reference.data() else { return Ok(()) };
    let s = &reference.samples;
    let l = scene.path().length();
    let (y0, y1) = padded_range(s.deflection.iter().chain(fe.iter().flat_map(|f| f.1.deflection.iter())));
    let caption = "deflection ν(σ) from the contour (positive away from the pulleys); shaded: contact".to_string();
    let axes = SigmaAxes { caption, caption_font: 20, l, y: (y0, y1), y_area: 80, ydesc: "ν [m]", y_format: Some(&axis_label), shade: Some(s) };
    let mut chart = sigma_chart(area, axes)?;
    region_labels(&mut chart, scene)?;
    labelled_line(&mut chart, s.sigma.iter().zip(&s.deflection).map(|(&a, &b)| (a, b)).collect(), REFERENCE, 2, false, "reference".to_string())?;
    for (i, fs, label) in fe {
        labelled_line(&mut chart, fs.sigma.iter().zip(&fs.deflection).map(|(&a, &b)| (a, b)).collect(), series_color(study, *i), 2, true, label.clone())?;
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// Linear range of the data with room for the region labels below and the legend above.
fn padded_range<'a>(vals: impl IntoIterator<Item = &'a f64>) -> (f64, f64) {
    let (a, b) = range_of(vals);
    let (a, b) = padded(a, b);
    let d = b - a;
    (a - 0.10 * d, b + 0.40 * d)
}

/// A linear axis label without "-0.0".
fn axis_label(v: &f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" || s.is_empty() {
        "0".to_string()
    } else {
        s
    }
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>>;

/// Light bands where the reference is in contact.
fn shade_contact<'a, 'b: 'a>(chart: &mut Chart<'a, 'b>, s: &Samples, l: f64, y0: f64, y1: f64) -> Result<(), String> {
    let n = s.len();
    for (state, a, b) in state_runs(&s.state) {
        if state == ContactState::Free {
            continue;
        }
        let x0 = s.sigma[a];
        let x1 = if b + 1 < n { s.sigma[b + 1] } else { l };
        chart
            .draw_series(std::iter::once(Rectangle::new([(x0, y0), (x1, y1)], state_color(state).mix(0.12).filled())))
            .map_err(err)?;
    }
    Ok(())
}

/// Region names along the top and dotted region boundaries.
fn region_labels<'a, 'b: 'a>(chart: &mut Chart<'a, 'b>, scene: &Scene) -> Result<(), String> {
    let (ya, yb) = (chart.y_range().start, chart.y_range().end);
    let y_text = ya + 0.01 * (yb - ya);
    for (a, b, name) in regions(scene) {
        if a > 0.0 {
            chart.draw_series(DashedLineSeries::new([(a, ya), (a, yb)], 4, 4, BLACK.mix(0.35).stroke_width(1))).map_err(err)?;
        }
        let grey = BLACK.mix(0.6);
        let style = TextStyle::from(("sans-serif", 15).into_font()).color(&grey).pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Center,
            plotters::style::text_anchor::VPos::Bottom,
        ));
        chart.draw_series(std::iter::once(Text::new(name.to_string(), (0.5 * (a + b), y_text), style))).map_err(err)?;
    }
    Ok(())
}

/// The legend box every chart uses, at `pos`, labels in `font` px.
pub(crate) fn legend_box<'a, 'b: 'a, CT: CoordTranslate>(chart: &mut ChartContext<'a, SVGBackend<'b>, CT>, pos: SeriesLabelPosition, font: u32) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(pos)
        .label_font(("sans-serif", font))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw()
        .map_err(err)
}

fn legend<'a, 'b: 'a>(chart: &mut Chart<'a, 'b>, pos: SeriesLabelPosition) -> Result<(), String> {
    legend_box(chart, pos, 16)
}

/// The grid and label style of every chart: bold grid lines only, tick labels in
/// `font` px, axis descriptions 2 px larger.
pub(crate) fn grid_style<'m, 'a, 'b, X, Y, DB>(mesh: &'m mut MeshStyle<'a, 'b, X, Y, DB>, font: u32) -> &'m mut MeshStyle<'a, 'b, X, Y, DB>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    DB: DrawingBackend,
{
    mesh.light_line_style(GRID.mix(0.0)).bold_line_style(GRID).label_style(("sans-serif", font)).axis_desc_style(("sans-serif", font + 2))
}

/// One labelled curve: solid or dashed (10/6 px) in `col` of `width` px, with a short
/// line of the same style as its legend entry.
pub(crate) fn labelled_line<'a, 'b: 'a, CT: CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, CT>,
    pts: Vec<(f64, f64)>,
    col: RGBColor,
    width: u32,
    dashed: bool,
    label: String,
) -> Result<(), String> {
    let entry = move |(x, y): (i32, i32)| PathElement::new(vec![(x, y), (x + 24, y)], col.stroke_width(width));
    if dashed {
        chart.draw_series(DashedLineSeries::new(pts, 10, 6, col.stroke_width(width))).map_err(err)?.label(label).legend(entry);
    } else {
        chart.draw_series(LineSeries::new(pts, col.stroke_width(width))).map_err(err)?.label(label).legend(entry);
    }
    Ok(())
}

/// A chart over σ ∈ [0, l] (linear axes) with the common grid style: used by every
/// panel that plots a field along the contour.
/// The reference's contact zones are shaded under the grid when `shade` is given.
struct SigmaAxes<'s> {
    caption: String,
    caption_font: u32,
    /// Contour length: the σ axis is [0, l].
    l: f64,
    y: (f64, f64),
    y_area: u32,
    ydesc: &'s str,
    y_format: Option<&'s dyn Fn(&f64) -> String>,
    shade: Option<&'s Samples>,
}

fn sigma_chart<'a, 'b>(area: &'a Area<'b>, axes: SigmaAxes<'_>) -> Result<Chart<'a, 'b>, String> {
    let SigmaAxes { caption, caption_font, l, y, y_area, ydesc, y_format, shade } = axes;
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", caption_font))
        .margin_left(10)
        .margin_right(30)
        .x_label_area_size(50)
        .y_label_area_size(y_area)
        .build_cartesian_2d(0.0..l, y.0..y.1)
        .map_err(err)?;
    if let Some(samples) = shade {
        shade_contact(&mut chart, samples, l, y.0, y.1)?;
    }
    let mut mesh = chart.configure_mesh();
    grid_style(&mut mesh, 16).x_desc("σ [m]").y_desc(ydesc);
    if let Some(f) = y_format {
        mesh.y_label_formatter(f);
    }
    mesh.draw().map_err(err)?;
    Ok(chart)
}

// ---------------------------------------------------------------------------
// Axial force (and moment) along σ

/// N(σ) of the reference with the finest run of each FE formulation overlaid (and
/// M(σ) if the belt has a moment), then |N − N_ref| of the finest run of every method.
/// A shear-deformable rod (samples with [`crate::run::EdgeDetail`]) adds its contact
/// pressure p(σ) — static scenes too — on the σ grid refined at the contact edges, a
/// row of close-ups of p over ±[`EDGE_WINDOW`] shear-layer widths at each contact edge,
/// and its shear strain Γ₂(σ).
pub fn force_svg(scene: &Scene, study: &Study) -> Result<String, PlotError> {
    let Some(reference) = study.reference.data() else {
        return message_svg("force", "axial force", "the reference could not be computed");
    };
    let s = &reference.samples;
    let fe = finest_fe(study);
    let with_moment = s.moment.is_some();
    let detail = s.edges.as_ref();
    // The contact traction along σ for a friction drive: where the stick and slip zones
    // (shaded) carry the normal load. (Static Kirchhoff rods carry concentrated edge
    // forces, which a sampled curve cannot show: not plotted for them; the Cosserat rod's
    // edge peaks are finite, and plotted from its refined samples.)
    let with_pressure = s.pressure.is_some() && (scene.analysis != drive::scene::Analysis::Static || detail.is_some());
    let with_friction = s.friction.is_some();
    let edge_windows = detail.map(contact_edges).unwrap_or_default();
    let with_zoom = !edge_windows.is_empty();
    let panels = 2 + usize::from(with_moment) + usize::from(with_pressure) + usize::from(with_friction) + 2 * usize::from(detail.is_some());
    let panel = 420u32;
    let height = panel * panels as u32;
    render("force", height, |root| {
        let areas = root.split_evenly((panels, 1));
        field_panel(scene, study, &areas[0], "tension", "axial force N(σ) [N]", &format!("{} — axial force along σ", scene.name), &fe)?;
        let mut next = 1;
        if with_moment {
            field_panel(scene, study, &areas[next], "moment", "bending moment M(σ) [N·m]", "bending moment along σ", &fe)?;
            next += 1;
        }
        if with_pressure {
            if let Some(d) = detail {
                let title = format!("contact pressure along σ: finite edge peaks of width √(a/b₂); {} uniform σ + {} clustered at each of the {} state changes", s.len(), 2 * EdgeDetail::CLUSTER + 2, d.edges.len());
                detail_panel(scene, study, &areas[next], DetailField::Pressure, &title, &fe)?;
            } else {
                field_panel(scene, study, &areas[next], "pressure", "contact pressure p(σ) [N/m]", "contact pressure (normal traction) along σ, stick and slip zones shaded", &fe)?;
            }
            next += 1;
        }
        if with_zoom {
            edge_zoom_row(scene, study, &areas[next], &edge_windows, &fe)?;
            next += 1;
        } else if detail.is_some() {
            area_message(&areas[next], "contact pressure at the contact edges", "no contact edge in the reference")?;
            next += 1;
        }
        if detail.is_some() {
            detail_panel(scene, study, &areas[next], DetailField::ShearStrain, "shear strain Γ₂ = Q/b₂ along σ (same refined σ grid)", &fe)?;
            next += 1;
        }
        if with_friction {
            field_panel(scene, study, &areas[next], "friction", "friction traction τ(σ) [N/m]", "friction traction on the belt along σ (+ along σ; |τ| = μp in the slip zones)", &fe)?;
        }
        difference_panel(scene, study, areas.last().unwrap_or(root))
    })
}

/// Half-width of an edge close-up, in shear-layer widths √(a/(b₂ − ρc²)).
pub const EDGE_WINDOW: f64 = 8.0;

/// The σ of the reference's contact edges (free ↔ contact, stick or slip; not the
/// stick ↔ slip changes) with the side the contact is on (+1: contact at larger σ).
fn contact_edges(d: &EdgeDetail) -> Vec<(f64, f64)> {
    let state_near = |s: f64, side: f64| {
        let k = d.sigma.partition_point(|&x| x < s);
        let i = if side > 0.0 { (k + 1).min(d.sigma.len() - 1) } else { k.saturating_sub(1) };
        d.state[i]
    };
    d.edges
        .iter()
        .filter_map(|&e| {
            let (before, after) = (state_near(e, -1.0), state_near(e, 1.0));
            match (before == ContactState::Free, after == ContactState::Free) {
                (true, false) => Some((e, 1.0)),
                (false, true) => Some((e, -1.0)),
                _ => None,
            }
        })
        .collect()
}

/// A field of [`EdgeDetail`].
#[derive(Clone, Copy)]
enum DetailField {
    Pressure,
    ShearStrain,
}

impl DetailField {
    fn of(self, d: &EdgeDetail) -> &[f64] {
        match self {
            DetailField::Pressure => &d.pressure,
            DetailField::ShearStrain => &d.shear_strain,
        }
    }

    fn ydesc(self) -> &'static str {
        match self {
            DetailField::Pressure => "contact pressure p(σ) [N/m]",
            DetailField::ShearStrain => "shear strain Γ₂(σ) [–]",
        }
    }

    /// A run's curve: its refined samples, else (pressure only) its uniform ones.
    fn curve(self, s: &Samples) -> Option<Vec<(f64, f64)>> {
        if let Some(d) = &s.edges {
            return Some(d.sigma.iter().zip(self.of(d)).map(|(&a, &b)| (a, b)).collect());
        }
        match self {
            DetailField::Pressure => s.pressure.as_ref().map(|p| s.sigma.iter().zip(p).map(|(&a, &b)| (a, b)).collect()),
            DetailField::ShearStrain => None,
        }
    }
}

/// A field of a shear-deformable rod along σ from the refined samples: the reference
/// solid, each FE formulation's finest run dashed (its uniform pressure where it has no
/// shear strain).
fn detail_panel(scene: &Scene, study: &Study, area: &Area, field: DetailField, title: &str, fe: &[(usize, &Samples, String)]) -> Result<(), String> {
    let Some(reference) = study.reference.data() else { return Ok(()) };
    let s = &reference.samples;
    let Some(pts) = field.curve(s) else { return Ok(()) };
    let l = scene.path().length();
    let (y0, y1) = padded_range(pts.iter().map(|p| &p.1));
    let axes = SigmaAxes { caption: title.to_string(), caption_font: 20, l, y: (y0, y1), y_area: 90, ydesc: field.ydesc(), y_format: None, shade: Some(s) };
    let mut chart = sigma_chart(area, axes)?;
    region_labels(&mut chart, scene)?;
    let reference_label = format!("reference: {} {}", study.reference.method, study.reference.discretisation);
    labelled_line(&mut chart, pts, REFERENCE, 2, false, reference_label)?;
    for (i, fs, label) in fe {
        if let Some(c) = field.curve(fs) {
            let c = c.into_iter().map(|(a, b)| (a, b.clamp(y0, y1))).collect();
            labelled_line(&mut chart, c, series_color(study, *i), 2, true, label.clone())?;
        }
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// One close-up of p(σ) per contact edge of the reference, σ within ±EDGE_WINDOW shear
/// layers √(a/(b₂ − ρc²)) of the edge (c the transport rate of the reference's summary,
/// 0 at rest), the refined samples marked.
fn edge_zoom_row(scene: &Scene, study: &Study, area: &Area, edges: &[(f64, f64)], fe: &[(usize, &Samples, String)]) -> Result<(), String> {
    let Some(reference) = study.reference.data() else { return Ok(()) };
    let Some(d) = reference.samples.edges.as_ref() else { return Ok(()) };
    let a = scene.belt.bending_stiffness.unwrap_or(f64::NAN);
    let b2 = scene.belt.shear_stiffness.unwrap_or(f64::NAN);
    let c = reference.summary.transport_rate.unwrap_or(0.0);
    let layer = (a / (b2 - scene.belt.mass_per_length * c * c)).sqrt();
    let half = if layer.is_finite() && layer > 0.0 { EDGE_WINDOW * layer } else { 0.01 * scene.path().length() };
    let (title_area, row) = area.split_vertically(34);
    title_area
        .draw(&Text::new(
            format!("p(σ) at each contact edge: σ within ±{EDGE_WINDOW}·√(a/(b₂ − ρc²)) = ±{:.2} mm of the edge, refined samples as dots, edge pressure labelled", 1e3 * half),
            (20, 8),
            ("sans-serif", 20).into_font(),
        ))
        .map_err(err)?;
    let cells = row.split_evenly((1, edges.len()));
    let path = scene.path();
    let l = path.length();
    for (cell, &(edge, side)) in cells.iter().zip(edges) {
        // σ − σ_edge, mm, across σ = 0 on the loop; the points within the window, in order
        let near = |pts: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
            let mut v: Vec<(f64, f64)> = pts
                .into_iter()
                .map(|(s, p)| (if path.is_open() { s - edge } else { (s - edge + 0.5 * l).rem_euclid(l) - 0.5 * l }, p))
                .filter(|(x, _)| x.abs() <= half)
                .map(|(x, p)| (1e3 * x, p))
                .collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let inside = near(d.sigma.iter().copied().zip(d.pressure.iter().copied()).collect());
        let (_, top) = range_of(inside.iter().map(|p| &p.1));
        let (y0, y1) = (-0.05 * top.max(1e-12), 1.25 * top.max(1e-12));
        let mut chart = ChartBuilder::on(cell)
            .caption(format!("σ = {edge:.4} m"), ("sans-serif", 16))
            .margin(6)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(-1e3 * half..1e3 * half, y0..y1)
            .map_err(err)?;
        grid_style(&mut chart.configure_mesh(), 13).x_desc("σ − σ_edge [mm]").x_labels(5).y_labels(6).x_label_formatter(&axis_label).draw().map_err(err)?;
        chart.draw_series(LineSeries::new(inside.clone(), REFERENCE.stroke_width(2))).map_err(err)?;
        chart.draw_series(PointSeries::of_element(inside.clone(), 2, REFERENCE.filled(), &|p, sz, st| Circle::new(p, sz, st))).map_err(err)?;
        for (i, fs, _) in fe {
            let Some(cv) = DetailField::Pressure.curve(fs) else { continue };
            let cv: Vec<(f64, f64)> = near(cv).into_iter().map(|(x, p)| (x, p.clamp(y0, y1))).collect();
            chart.draw_series(DashedLineSeries::new(cv, 6, 4, series_color(study, *i).stroke_width(2))).map_err(err)?;
        }
        // The edge pressure: the sample at the edge (its contact-side end, a sample).
        let k = d.sigma.partition_point(|&x| x < edge).min(d.sigma.len() - 1);
        {
            let label = format!("  p = {:.1} N/m  ", d.pressure[k]);
            let pos = (0.0, d.pressure[k].min(y1));
            let style = TextStyle::from(("sans-serif", 13).into_font()).color(&BLACK).pos(plotters::style::text_anchor::Pos::new(
                if side > 0.0 { plotters::style::text_anchor::HPos::Left } else { plotters::style::text_anchor::HPos::Right },
                plotters::style::text_anchor::VPos::Bottom,
            ));
            chart.draw_series(std::iter::once(Text::new(label, pos, style))).map_err(err)?;
        }
    }
    Ok(())
}

fn field_panel(scene: &Scene, study: &Study, area: &Area, field: &str, ydesc: &str, title: &str, fe: &[(usize, &Samples, String)]) -> Result<(), String> {
    let Some(reference) = study.reference.data() else { return Ok(()) };
    let s = &reference.samples;
    let Some(f) = s.field(field) else { return Ok(()) };
    let l = scene.path().length();
    let others: Vec<&[f64]> = fe.iter().filter_map(|x| x.1.field(field)).collect();
    // The range follows the reference (widened to at least ±25 % of its span around
    // it); FE curves that leave it are clipped, and the caption says so.
    let (r0, r1) = range_of(f.iter());
    let span = (r1 - r0).max(1e-3 * r1.abs().max(r0.abs()));
    let (o0, o1) = range_of(others.iter().flat_map(|o| o.iter()));
    let (lo, hi) = if others.is_empty() { (r0, r1) } else { (o0.max(r0 - 0.25 * span).min(r0), o1.min(r1 + 0.25 * span).max(r1)) };
    let clipped = !others.is_empty() && (o0 < lo || o1 > hi);
    let (y0, y1) = padded_range([lo, hi].iter());
    let title = if clipped { format!("{title} (FE curves clipped to the plotted range)") } else { title.to_string() };
    let axes = SigmaAxes { caption: title, caption_font: 22, l, y: (y0, y1), y_area: 90, ydesc, y_format: None, shade: Some(s) };
    let mut chart = sigma_chart(area, axes)?;
    region_labels(&mut chart, scene)?;
    let reference_label = format!("reference: {} {}", study.reference.method, study.reference.discretisation);
    labelled_line(&mut chart, s.sigma.iter().zip(f).map(|(&a, &b)| (a, b)).collect(), REFERENCE, 2, false, reference_label)?;
    for (i, fs, label) in fe {
        let Some(g) = fs.field(field) else { continue };
        labelled_line(&mut chart, fs.sigma.iter().zip(g).map(|(&a, &b)| (a, b)).collect(), series_color(study, *i), 2, true, label.clone())?;
    }
    if fe.is_empty() {
        chart
            .draw_series(std::iter::once(PathElement::new(Vec::<(f64, f64)>::new(), WHITE)))
            .map_err(err)?
            .label("no FE run to overlay (no FE formulation studied)")
            .legend(|(x, y)| PathElement::new(vec![(x, y)], WHITE));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// |N − N_ref|(σ) of the finest successful run of every series, log scale.
fn difference_panel(scene: &Scene, study: &Study, area: &Area) -> Result<(), String> {
    let Some(reference) = study.reference.data() else { return Ok(()) };
    let s = &reference.samples;
    let l = scene.path().length();
    let scale = s.tension.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    let floor = 1e-15 * scale;
    let mut curves = Vec::new();
    for (i, series) in study.series.iter().enumerate() {
        let Some(row) = series.rows.iter().rev().find(|r| r.run.data().is_some()) else { continue };
        let Some(d) = row.run.data() else { continue };
        if d.samples.len() != s.len() {
            continue;
        }
        let pts: Vec<(f64, f64)> = s.sigma.iter().zip(d.samples.tension.iter().zip(&s.tension)).map(|(&x, (a, b))| (x, (a - b).abs().max(floor))).collect();
        curves.push((i, format!("{} ({})", series.method, row.run.discretisation), pts));
    }
    let all: Vec<f64> = curves.iter().flat_map(|c| c.2.iter().map(|p| p.1)).collect();
    let (y0, y1) = log_bounds(&all);
    // Headroom for the legend: about 6 % of the height per entry.
    let y1 = y1 * 10f64.powf((y1 / y0).log10() * (0.10 + 0.07 * curves.len() as f64));
    let mut chart = ChartBuilder::on(area)
        .caption("|N − N_ref|(σ) of the finest run of each method (floored at 1e-15·max|N_ref|)", ("sans-serif", 20))
        .margin_left(10)
        .margin_right(30)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..l, (y0..y1).log_scale())
        .map_err(err)?;
    grid_style(&mut chart.configure_mesh(), 16).x_desc("σ [m]").y_desc("|N − N_ref| [N]").y_label_formatter(&log_label).draw().map_err(err)?;
    for (a, _, _) in regions(scene) {
        if a > 0.0 {
            chart.draw_series(DashedLineSeries::new([(a, y0), (a, y1)], 4, 4, BLACK.mix(0.35).stroke_width(1))).map_err(err)?;
        }
    }
    for (i, label, pts) in curves {
        labelled_line(&mut chart, pts, series_color(study, i), 1, false, label)?;
    }
    legend_box(&mut chart, SeriesLabelPosition::UpperRight, 15)
}

// ---------------------------------------------------------------------------
// Convergence and work–precision

/// The two headline measures of the log–log plots: (quantity index or None for the
/// scalar aggregate, label).
fn headline(study: &Study) -> Vec<(Option<usize>, String)> {
    let mut h = vec![(None, "summary scalars (max rel. error)".to_string())];
    if let Some(k) = study.quantity_index("tension_l2") {
        h.push((Some(k), "axial force N (L2 rel. error)".to_string()));
    }
    h
}

fn row_error(series: &Series, row: usize, which: Option<usize>) -> Option<f64> {
    let r = &series.rows[row];
    match which {
        None => r.scalar_error,
        Some(k) => r.errors[k],
    }
    .filter(|e| *e > 0.0 && e.is_finite())
}

/// (x, error) of every row of a series whose discretisation `x` maps to an abscissa.
fn error_points(series: &Series, which: Option<usize>, x: impl Fn(Discretisation) -> Option<f64>) -> Vec<(f64, f64)> {
    (0..series.rows.len()).filter_map(|r| Some((x(series.rows[r].run.discretisation)?, row_error(series, r, which)?))).collect()
}

type LogChart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::combinators::LogCoord<f64>, plotters::coord::combinators::LogCoord<f64>>,
>;

fn loglog<'a, 'b>(area: &'a Area<'b>, title: &str, x: (f64, f64), y: (f64, f64), xdesc: &str, ydesc: &str) -> Result<LogChart<'a, 'b>, String> {
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d((x.0..x.1).log_scale(), (y.0..y.1).log_scale())
        .map_err(err)?;
    grid_style(&mut chart.configure_mesh(), 15)
        .x_desc(xdesc)
        .y_desc(ydesc)
        .x_labels(8)
        .y_labels(14)
        .x_label_formatter(&log_label)
        .y_label_formatter(&log_label)
        .draw()
        .map_err(err)?;
    Ok(chart)
}

fn log_legend<'a, 'b: 'a>(chart: &mut LogChart<'a, 'b>, pos: SeriesLabelPosition) -> Result<(), String> {
    legend_box(chart, pos, 15)
}

/// Draws a message in the middle of an area.
pub(crate) fn area_message(area: &Area, title: &str, text: &str) -> Result<(), String> {
    let (w, h) = area.dim_in_pixel();
    area.draw(&Text::new(title.to_string(), (20, 12), ("sans-serif", 20).into_font())).map_err(err)?;
    let grey = BLACK.mix(0.6);
    let style = TextStyle::from(("sans-serif", 18).into_font()).color(&grey).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Center,
        plotters::style::text_anchor::VPos::Center,
    ));
    for (k, line) in text.lines().enumerate() {
        area.draw(&Text::new(line.to_string(), (w as i32 / 2, h as i32 / 2 + 26 * k as i32), style.clone())).map_err(err)?;
    }
    Ok(())
}

/// Left: FE error vs elements (log–log) per formulation for the headline measures, with
/// reference slopes h¹, h², h⁴ below the first point (against the step's refinement
/// Δt₀/Δt for a shell study that refines only Δt, against n_ζ for one that refines only
/// the width). Right: BVP error vs the
/// requested tolerance per variant, with the line error = tolerance.
pub fn convergence_svg(scene: &Scene, study: &Study) -> Result<String, PlotError> {
    let measures = headline(study);
    // the abscissa: the element count, or for a shell study that refines only the time
    // step on one mesh the step's refinement Δt₀/Δt (Δt₀ the coarsest level's)
    let first_step = study.plan.shell_levels().and_then(|l| l.first().copied());
    let (x_of, x_name): (Box<dyn Fn(Discretisation) -> Option<usize>>, &str) = match (study.plan.shell_refinement(), first_step) {
        (Some(Refinement::Step), Some(Discretisation::Mesh2d { time_step: t0, .. })) => (
            Box::new(move |d| if let Discretisation::Mesh2d { time_step, .. } = d { Some((t0 / time_step).round() as usize) } else { None }),
            "time-step refinement Δt₀/Δt",
        ),
        (Some(Refinement::Width), _) => (Box::new(|d: Discretisation| if let Discretisation::Mesh2d { zeta, .. } = d { Some(zeta) } else { None }), "elements across the width n_ζ"),
        _ => (Box::new(|d: Discretisation| d.elements_along()), "elements"),
    };
    render("convergence", 620, |root| {
        let (left, right) = root.split_horizontally(WIDTH / 2);
        // FE panel.
        let fe: Vec<usize> = (0..study.series.len()).filter(|&i| study.series[i].family == Family::Fem && study.series[i].status == SeriesStatus::Studied).collect();
        let mut pts_all = Vec::new();
        let mut xs = Vec::new();
        for &i in &fe {
            for (r, row) in study.series[i].rows.iter().enumerate() {
                if let Some(n) = x_of(row.run.discretisation) {
                    xs.push(n as f64);
                    for (m, _) in &measures {
                        if let Some(e) = row_error(&study.series[i], r, *m) {
                            pts_all.push(e);
                        }
                    }
                }
            }
        }
        if fe.is_empty() || pts_all.is_empty() {
            let why = if study.registered_formulations.is_empty() {
                "no FE formulation registered:\nno mesh convergence to plot"
            } else {
                "no FE run produced errors\nagainst the reference"
            };
            area_message(&left, &format!("{} — FE: error vs {x_name}", scene.name), why)?;
        } else {
            // x: log₂ of the element count on a linear axis, labelled with the counts.
            let (n0, n1) = range_of(xs.iter());
            let (x0, x1) = (n0.log2() - 0.3, n1.log2() + 0.3);
            // Reference slopes h¹, h², h⁴ start half a decade below the first error of
            // the first formulation and run over the mesh range.
            let first = fe.iter().find_map(|&i| {
                let s = &study.series[i];
                (0..s.rows.len()).find_map(|r| x_of(s.rows[r].run.discretisation).and_then(|n| row_error(s, r, None).map(|e| (n as f64, e))))
            });
            let slopes: Vec<(f64, Vec<(f64, f64)>)> = first
                .map(|(na, ea)| {
                    [1.0, 2.0, 4.0].iter().map(|&p| (p, [na, n1].iter().map(|&n| (n.log2(), 0.3 * ea * (na / n).powf(p))).collect())).collect()
                })
                .unwrap_or_default();
            let mut ys = pts_all.clone();
            ys.extend(slopes.iter().flat_map(|(_, l)| l.iter().map(|p| p.1)));
            let (y0, y1) = log_bounds(&ys);
            // Room below the data for the legend (entries × ~5 % of the height).
            let entries = 2 * fe.len() + slopes.len();
            let y0 = y0 / 10f64.powf((y1 / y0).log10() * (0.05 * entries as f64).min(0.6));
            let mut chart = ChartBuilder::on(&left)
                .caption(format!("{} — FE: error vs {x_name}", scene.name), ("sans-serif", 20))
                .margin(12)
                .x_label_area_size(50)
                .y_label_area_size(80)
                .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                .map_err(err)?;
            let count_label = |v: &f64| if (v - v.round()).abs() < 1e-9 { format!("{}", 2f64.powf(v.round()) as u64) } else { String::new() };
            grid_style(&mut chart.configure_mesh(), 15)
                .x_desc(format!("{x_name} (log scale)"))
                .y_desc("relative error")
                .x_labels(((x1 - x0).ceil() as usize + 1) * 2)
                .x_label_formatter(&count_label)
                .y_labels(14)
                .y_label_formatter(&log_label)
                .draw()
                .map_err(err)?;
            for (p, line) in slopes {
                let shade = 0.2 + 0.12 * p;
                chart
                    .draw_series(DashedLineSeries::new(line, 6, 6, BLACK.mix(shade).stroke_width(1)))
                    .map_err(err)?
                    .label(if x_name.starts_with("time-step") { format!("slope Δt^{p}") } else { format!("slope h^{p}") })
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.mix(shade).stroke_width(1)));
            }
            for &i in &fe {
                let col = series_color(study, i);
                let s = &study.series[i];
                for (mi, (m, mlabel)) in measures.iter().enumerate() {
                    let pts = error_points(s, *m, |d| x_of(d).map(|n| (n as f64).log2()));
                    if !pts.is_empty() {
                        let (marker, dashed) = Marker::of_measure(mi);
                        marked_line(&mut chart, &pts, col, marker, dashed, format!("{} — {mlabel}", s.method))?;
                    }
                }
            }
            legend_box(&mut chart, SeriesLabelPosition::LowerLeft, 15)?;
        }
        // BVP panel.
        let bvp: Vec<usize> = (0..study.series.len()).filter(|&i| study.series[i].family == Family::Bvp && study.series[i].status == SeriesStatus::Studied).collect();
        let mut tols = Vec::new();
        let mut errs = Vec::new();
        for &i in &bvp {
            for (r, row) in study.series[i].rows.iter().enumerate() {
                if let Discretisation::Tolerance(t) = row.run.discretisation {
                    tols.push(t);
                    for (m, _) in &measures {
                        if let Some(e) = row_error(&study.series[i], r, *m) {
                            errs.push(e);
                        }
                    }
                }
            }
        }
        if errs.is_empty() {
            return area_message(&right, "BVP: error vs requested tolerance", "no BVP run produced errors\nagainst the reference");
        }
        let (x0, x1) = log_bounds(&tols);
        let (y0, y1) = log_bounds(&errs.iter().chain(tols.iter()).copied().collect::<Vec<_>>());
        let title = format!("BVP: error vs tolerance (reference {} {})", study.reference.method.trim_start_matches("BVP run bvp-collocation "), study.reference.discretisation);
        let mut chart = loglog(&right, &title, (x0, x1), (y0, y1), "requested tolerance", "relative error")?;
        chart
            .draw_series(DashedLineSeries::new([(x0, x0), (x1, x1)], 6, 6, BLACK.mix(0.5).stroke_width(1)))
            .map_err(err)?
            .label("error = tolerance")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], BLACK.mix(0.5).stroke_width(1)));
        for &i in &bvp {
            let col = series_color(study, i);
            let s = &study.series[i];
            for (mi, (m, mlabel)) in measures.iter().enumerate() {
                let pts = error_points(s, *m, |d| match d {
                    Discretisation::Tolerance(t) => Some(t),
                    _ => None,
                });
                if !pts.is_empty() {
                    let short = if mi == 0 { "scalars" } else { "N L2" };
                    let _ = mlabel;
                    let (marker, dashed) = Marker::of_measure(mi);
                    marked_line(&mut chart, &pts, col, marker, dashed, format!("{} — {short}", s.method.trim_start_matches("bvp-")))?;
                }
            }
        }
        log_legend(&mut chart, SeriesLabelPosition::LowerRight)
    })
}

/// The point marker of a curve.
#[derive(Clone, Copy)]
enum Marker {
    Circle,
    Triangle,
}

impl Marker {
    /// The style of one measure of a method: measure 0 solid with circles, measure 1
    /// dashed with triangles — (marker, dashed).
    fn of_measure(measure: usize) -> (Marker, bool) {
        if measure == 0 {
            (Marker::Circle, false)
        } else {
            (Marker::Triangle, true)
        }
    }
}

/// A curve with a marker at every point, labelled with a line and the marker:
/// solid or dashed (8/5 px), 2 px wide.
fn marked_line<'a, 'b: 'a, CT: CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'a, SVGBackend<'b>, CT>,
    pts: &[(f64, f64)],
    col: RGBColor,
    marker: Marker,
    dashed: bool,
    label: String,
) -> Result<(), String> {
    if dashed {
        chart.draw_series(DashedLineSeries::new(pts.to_vec(), 8, 5, col.stroke_width(2))).map_err(err)?;
    } else {
        chart.draw_series(LineSeries::new(pts.to_vec(), col.stroke_width(2))).map_err(err)?;
    }
    let line = move |(x, y): (i32, i32)| EmptyElement::at((x, y)) + PathElement::new(vec![(0, 0), (24, 0)], col.stroke_width(2));
    // The markers of shape `$shape` at the points (size `$size` px) and in the legend
    // (`$legend` px): the element types differ, the drawing does not.
    macro_rules! marked {
        ($shape:ident, $size:expr, $legend:expr) => {
            chart
                .draw_series(PointSeries::of_element(pts.to_vec(), $size, col.filled(), &|p, sz, st| $shape::new(p, sz, st)))
                .map_err(err)?
                .label(label)
                .legend(move |p| line(p) + $shape::new((12, 0), $legend, col.filled()))
        };
    }
    match marker {
        Marker::Circle => marked!(Circle, 5, 4),
        Marker::Triangle => marked!(TriangleMarker, 6, 5),
    };
    Ok(())
}

/// Error vs wall time (log–log), every studied method of the scene on one axis; one
/// panel per headline measure. Each point is a run; BVP lines run through the
/// tolerance sweep, FE lines through the mesh sequence.
pub fn work_precision_svg(scene: &Scene, study: &Study) -> Result<String, PlotError> {
    let measures = headline(study);
    render("work-precision", 640, |root| {
        let panels = root.split_evenly((1, measures.len()));
        for (mi, (m, mlabel)) in measures.iter().enumerate() {
            let mut ts = Vec::new();
            let mut es = Vec::new();
            let mut curves = Vec::new();
            for (i, s) in study.series.iter().enumerate() {
                if s.status != SeriesStatus::Studied {
                    continue;
                }
                let pts: Vec<(f64, f64)> = (0..s.rows.len()).filter_map(|r| Some((s.rows[r].run.wall_seconds()?.max(1e-6), row_error(s, r, *m)?))).collect();
                ts.extend(pts.iter().map(|p| p.0));
                es.extend(pts.iter().map(|p| p.1));
                if !pts.is_empty() {
                    curves.push((i, pts));
                }
            }
            let title = format!("work–precision: {mlabel}");
            let _ = scene;
            if curves.is_empty() {
                area_message(&panels[mi], &title, "no run produced errors against the reference")?;
                continue;
            }
            let (x0, x1) = log_bounds(&ts);
            let (y0, y1) = log_bounds(&es);
            let y1 = y1 * 10f64.powf((y1 / y0).log10() * (0.08 + 0.06 * curves.len() as f64));
            let mut chart = loglog(&panels[mi], &title, (x0, x1), (y0, y1), "wall time [s]", "relative error")?;
            for (i, pts) in curves {
                let col = series_color(study, i);
                let s = &study.series[i];
                let marker = if s.family == Family::Fem { Marker::Triangle } else { Marker::Circle };
                marked_line(&mut chart, &pts, col, marker, false, s.method.clone())?;
                // Label the loosest and tightest discretisation of each line.
                for &r in [0, s.rows.len().saturating_sub(1)].iter() {
                    let Some(row) = s.rows.get(r) else { continue };
                    let (Some(t), Some(e)) = (row.run.wall_seconds(), row_error(s, r, *m)) else { continue };
                    let text = match row.run.discretisation {
                        Discretisation::Tolerance(tol) => fmt_tolerance(tol),
                        d => format!("{} el.", d.cell()),
                    };
                    chart
                        .draw_series(std::iter::once(Text::new(format!("  {text}"), (t.max(1e-6), e), TextStyle::from(("sans-serif", 13).into_font()).color(&col))))
                        .map_err(err)?;
                }
            }
            log_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        }
        Ok(())
    })
}

/// A placeholder SVG carrying a message.
fn message_svg(plot: &'static str, title: &str, text: &str) -> Result<String, PlotError> {
    render(plot, 300, |root| area_message(root, title, text))
}
