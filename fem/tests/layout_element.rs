//! An element of the Cosserat layout {s, ν, θ} (12 unknowns) registered by name from
//! outside `fem` and run through the static analysis with homotopy (`static_homotopy`)
//! on the `rod-hanging` scene, and through the quasistatic transient of the friction
//! drive (`string_drive::solve_layout`) on `string-drive` — the registry face and the
//! analyses generic over the element layout (issue 11, "one MEL element core").
//!
//! The test element `ThetaRod` is a string-layout formulation (the Kirchhoff rod
//! `rod-simpson`, or the string `string-simpson` for the drive) on the (s, ν) part of
//! its unknowns plus a decoupled θ energy ½ k ∫ (θ − θ*(σ))² dσ with the known target
//! θ*(σ) = a sin(2πσ/L_c) (periodic on the closed loop): the (s, ν) equilibrium is the
//! base formulation's, and θ is the C¹ cubic least-squares fit of θ*. It is not the Cosserat rod of
//! the spec — it checks the plumbing: numbering with a third field, the homotopy, the
//! contact fitting and penalty continuation, the refits' transfer of every field, and the
//! solution view reading S and ν through the layout.

mod common;

use std::f64::consts::PI;
use std::sync::Arc;

use common::scene;
use drive::contour::Contour;
use drive::scene::{Analysis, Theory};
use fem::assembly::ElementKernel;
use fem::element::{ElementLayout, Field, COSSERAT, STRING};
use fem::formulation::layout::LayoutElement;
use fem::formulation::{self, ElementContext, ElementDerivatives, Kernel, RegisteredElement, TermParams, TermRules, NDOF, NDOF_COSSERAT};
use fem::mesh::Mesh;
use fem::{FemError, FemOptions, SolverSettings};

const NAME: &str = "rod-theta-test";
const NC: usize = NDOF_COSSERAT;

/// A string-layout formulation on (s, ν) plus ½ k ∫ (θ − a sin(2πσ/L_c))² dσ by
/// 3-point Gauss.
struct ThetaRod {
    name: &'static str,
    rod: Arc<dyn Kernel>,
    /// k, N (any positive value: the θ problem is decoupled).
    stiffness: f64,
    /// a, rad.
    amplitude: f64,
}

impl ThetaRod {
    /// On `rod-simpson`, registered as [`NAME`].
    fn new() -> ThetaRod {
        ThetaRod::on("rod-simpson", NAME)
    }

    /// On the built-in formulation `base`, named `name`.
    fn on(base: &str, name: &'static str) -> ThetaRod {
        ThetaRod { name, rod: formulation::find(base).expect("built in"), stiffness: 10.0, amplitude: 0.3 }
    }

    fn target(&self, contour: &Contour, sigma: f64) -> f64 {
        self.amplitude * (2.0 * PI * sigma / contour.length()).sin()
    }

    /// The (s, ν) unknowns in the string layout's order.
    fn rod_part(q: &[f64; NC]) -> [f64; NDOF] {
        let mut out = [0.0; NDOF];
        for (i, j) in pairs() {
            out[i] = q[j];
        }
        out
    }

    /// θ energy, gradient and Hessian over the four θ unknowns (a, a′, b, b′).
    fn theta(&self, el: &ElementContext, q: &[f64; NC]) -> (f64, [f64; 4], [[f64; 4]; 4]) {
        let idx = COSSERAT.hermite_indices(2);
        let (mut e, mut g, mut h) = (0.0, [0.0; 4], [[0.0; 4]; 4]);
        for &(xi, wt) in formulation::Rule::Gauss(3).points() {
            let (wv, _) = fem::hermite::weights(xi, el.geometry.h);
            let theta: f64 = (0..4).map(|k| wv[k] * q[idx[k]]).sum();
            let r = theta - self.target(&el.contour, el.sigma(xi));
            let w = wt * el.jacobian() * self.stiffness;
            e += 0.5 * w * r * r;
            for k in 0..4 {
                g[k] += w * r * wv[k];
                for l in 0..4 {
                    h[k][l] += w * wv[k] * wv[l];
                }
            }
        }
        (e, g, h)
    }
}

/// (string-layout index, Cosserat-layout index) of the s and ν unknowns.
fn pairs() -> impl Iterator<Item = (usize, usize)> {
    (0..2).flat_map(|node| (0..2).flat_map(move |f| (0..2).map(move |d| (STRING.index(node, f, d), COSSERAT.index(node, f, d)))))
}

fn rod8(k: &Arc<dyn Kernel>) -> &(dyn Kernel + 'static) {
    k.as_ref()
}

impl ElementKernel<NC> for ThetaRod {
    fn layout(&self) -> ElementLayout {
        COSSERAT
    }
    fn separate_transition_slopes(&self) -> bool {
        ElementKernel::<NDOF>::separate_transition_slopes(rod8(&self.rod))
    }
    fn admissible(&self, el: &ElementContext, q: &[f64; NC]) -> bool {
        ElementKernel::<NDOF>::admissible(rod8(&self.rod), el, &Self::rod_part(q))
    }
    fn energy(&self, el: &ElementContext, q: &[f64; NC]) -> f64 {
        Kernel::energy(rod8(&self.rod), el, &Self::rod_part(q)) + self.theta(el, q).0
    }
    fn gradient(&self, el: &ElementContext, q: &[f64; NC]) -> (f64, [f64; NC]) {
        let d = self.derivatives(el, q);
        (d.energy, d.gradient)
    }
    fn derivatives(&self, el: &ElementContext, q: &[f64; NC]) -> ElementDerivatives<NC> {
        let r = Kernel::derivatives(rod8(&self.rod), el, &Self::rod_part(q));
        let (e, g, h) = self.theta(el, q);
        let mut out = ElementDerivatives { energy: r.energy + e, gradient: [0.0; NC], hessian: [[0.0; NC]; NC] };
        for (i, j) in pairs() {
            out.gradient[j] = r.gradient[i];
            for (k, l) in pairs() {
                out.hessian[j][l] = r.hessian[i][k];
            }
        }
        let idx = COSSERAT.hermite_indices(2);
        for a in 0..4 {
            out.gradient[idx[a]] = g[a];
            for b in 0..4 {
                out.hessian[idx[a]][idx[b]] = h[a][b];
            }
        }
        out
    }
}

impl LayoutElement<NC> for ThetaRod {
    fn name(&self) -> &'static str {
        self.name
    }
    fn description(&self) -> &'static str {
        "test: a string-layout formulation on (s, ν) and a decoupled least-squares θ on the Cosserat layout"
    }
    fn theory(&self) -> Theory {
        Kernel::theory(rod8(&self.rod))
    }
    fn rules(&self) -> TermRules {
        Kernel::rules(rod8(&self.rod))
    }
    fn term_labels(&self, params: &TermParams) -> Vec<String> {
        let mut l = Kernel::term_labels(rod8(&self.rod), params);
        l.push(format!("θ least squares (gauss3, k = {:e} N)", self.stiffness));
        l
    }
    fn axial_force_at(&self, el: &ElementContext, q: &[f64; NC], xi: f64) -> f64 {
        LayoutElement::<NDOF>::axial_force_at(rod8(&self.rod), el, &Self::rod_part(q), xi)
    }
    fn effective(&self, el: &ElementContext, q: &[f64; NC]) -> [f64; NC] {
        let m = LayoutElement::<NDOF>::effective(rod8(&self.rod), el, &Self::rod_part(q));
        let mut out = *q;
        for (i, j) in pairs() {
            out[j] = m[i];
        }
        out
    }
}

fn opts(scene: &drive::Scene, name: &str) -> FemOptions {
    FemOptions::from_scene(scene, name)
}

/// Registered by name (once per process; the tests of this file share it).
fn registered() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| formulation::register_element(RegisteredElement::Cosserat(Arc::new(ThetaRod::new()))).expect("registers"));
}

/// The registry lists the element with its layout and theory; the string-layout face
/// (`find`, `registry`) does not, and a second registration of the name is refused.
/// The summaries `a` (of element `a_name`) and `b` have the same scalars, each within
/// 1e-9 relative to max(|a|, 1e-3) (values below 1e-3 compared absolutely)
/// — the layout element computes the same discrete problem as the element it wraps, so
/// only rounding may differ. Returns (the number of scalars, the largest difference).
fn same_scalars(a: &drive::Summary, a_name: &str, b: &drive::Summary, b_name: &str) -> (usize, f64) {
    let (a, b) = (a.scalars(), b.scalars());
    assert_eq!(a.iter().map(|x| &x.0).collect::<Vec<_>>(), b.iter().map(|x| &x.0).collect::<Vec<_>>());
    let mut worst: f64 = 0.0;
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        let rel = (x - y).abs() / x.abs().max(1e-3);
        worst = worst.max(rel);
        assert!(rel <= 1e-9, "{name}: {a_name} {x} vs {b_name} {y} ({rel:e})");
    }
    (a.len(), worst)
}

#[test]
fn a_cosserat_layout_element_is_registered_by_name() {
    registered();
    assert!(fem::available_formulations().contains(&NAME));
    assert!(fem::formulations_for(Theory::Kirchhoff).contains(&NAME));
    let e = formulation::find_element(NAME).expect("found");
    assert_eq!((e.layout(), e.theory()), (COSSERAT, Theory::Kirchhoff));
    assert!(e.string_kernel().is_none());
    assert!(formulation::find(NAME).is_none());
    assert!(formulation::registry().iter().all(|k| k.name() != NAME));
    assert!(matches!(
        formulation::register_element(RegisteredElement::Cosserat(Arc::new(ThetaRod::new()))),
        Err(formulation::RegistryError::Duplicate { .. })
    ));
    assert_eq!(formulation::find_element("rod-simpson").unwrap().layout(), STRING);
}

/// `solve_scene` on `rod-hanging` with the 12-unknown element by name: every summary
/// scalar equals `rod-simpson`'s. Tolerance 1e-9 relative (of max(|v|, 1e-3) for the
/// angles in rad and moments in N·m): the (s, ν) problem is the same, but the Newton
/// iterates may differ at the level of the update tolerance because the θ unknowns enter
/// the update norm, the Armijo test and the Levenberg–Marquardt shifts of the first
/// iterations (measured 7e-13).
/// The run adds θ and one shared ∂σθ per node: 2 unknowns per element more.
#[test]
fn the_static_analysis_runs_a_cosserat_layout_element_by_name() {
    registered();
    let scene = scene("rod-hanging");
    let rod = fem::solve_scene(&scene, &opts(&scene, "rod-simpson")).expect("rod-simpson");
    let run = fem::solve_scene(&scene, &opts(&scene, NAME)).expect("the Cosserat-layout element");
    let elements = opts(&scene, NAME).elements;
    assert_eq!(run.stats.unknowns, rod.stats.unknowns + 2 * elements);
    assert!(run.terms.iter().any(|t| t.starts_with("θ least squares")));
    assert!(run.terms.iter().any(|t| t.starts_with("bending energy")));
    let (count, worst) = same_scalars(&rod.summary, "rod-simpson", &run.summary, NAME);
    assert!(count >= 14, "{count} scalars");
    println!("largest relative difference of {count} summary scalars: {worst:e}");
    // the fields along σ through the common view
    for k in 0..50 {
        let sigma = scene.drive.centre_distance * 4.0 * k as f64 / 50.0;
        let (p, q) = (rod.view.position(sigma), run.view.position(sigma));
        assert!((p[0] - q[0]).abs().max((p[1] - q[1]).abs()) <= 1e-9, "position at σ = {sigma}");
        let (m, n) = (rod.view.bending_moment(sigma).unwrap(), run.view.bending_moment(sigma).unwrap());
        assert!((m - n).abs() <= 1e-6 * 1e-3, "moment at σ = {sigma}: {m} vs {n}");
    }
}

/// The typed solution of the static analysis (`StringHanging::solve` with the element
/// itself, N = 12 monomorphised): the θ field through the layout is the least-squares
/// C¹ cubic fit of θ*, whose error is at most a small multiple of the cubic Hermite
/// interpolation bound h⁴/384·max|θ*''''| = h⁴/384·a(2π/L_c)⁴ (h the largest element);
/// tolerance 4× that bound plus 1e-9 rad for the Newton tolerance (measured 1.5e-10 against
/// 2.3e-9). ∂σθ against 2·h³/24·max|θ*''''| (h³/24 is about 5× the Hermite interpolant's
/// derivative bound √3/216·h³·max|f''''|; ×2 for the least-squares fit; measured 1.6e-7
/// against 1.8e-6). S and ν equal the rod's typed solution; a string-layout solution has
/// no θ.
#[test]
fn the_theta_field_is_read_through_the_layout() {
    let scene = scene("rod-hanging");
    let settings = SolverSettings::default();
    let o = opts(&scene, "rod-simpson");
    let data = fem::string_hanging_data(&scene, &o, &settings).unwrap();
    let contour = data.contour().unwrap();
    let mesh = || Mesh::new(contour, o.elements, settings.arc_weight).unwrap();
    let element = Arc::new(ThetaRod::new());
    let (sol, report, _) = data.solve(mesh(), element.clone(), &settings).expect("solves");
    let (rod, _, _) = data.solve(mesh(), formulation::find("rod-simpson").unwrap(), &settings).unwrap();
    assert_eq!(sol.layout(), COSSERAT);
    assert!(report.fit.fits > 0 && report.penalty_steps > 0, "fitting and penalty continuation ran: {report:?}");
    assert!(rod.field(Field::Theta, 0.1).is_none());
    let h = sol.mesh().elements().iter().fold(0.0f64, |m, e| m.max(e.h));
    let k = 2.0 * PI / contour.length();
    let bound = 4.0 * h.powi(4) / 384.0 * element.amplitude * k.powi(4) + 1e-9;
    let slope_bound = 2.0 * h.powi(3) / 24.0 * element.amplitude * k.powi(4) + 1e-9;
    let (mut worst, mut worst_slope) = (0.0f64, 0.0f64);
    for i in 0..997 {
        let sigma = contour.length() * i as f64 / 997.0;
        let [theta, dtheta, _] = sol.field(Field::Theta, sigma).expect("θ is a field of the layout");
        worst = worst.max((theta - element.target(&contour, sigma)).abs());
        worst_slope = worst_slope.max((dtheta - element.amplitude * k * (k * sigma).cos()).abs());
        let (a, b) = (sol.fields(sigma), rod.fields(sigma));
        assert!((a.nu - b.nu).abs() <= 1e-9 && (a.s - b.s).abs() <= 1e-9, "S, ν at σ = {sigma}");
        assert_eq!(sol.field(Field::Nu, sigma).unwrap()[0], a.nu);
    }
    println!("θ error {worst:e} (bound {bound:e}), ∂σθ error {worst_slope:e} (bound {slope_bound:e})");
    assert!(worst <= bound, "θ − θ* = {worst:e} > {bound:e}");
    assert!(worst_slope <= slope_bound, "∂σθ − θ*′ = {worst_slope:e} > {slope_bound:e}");
}

/// The drive analyses run on the string layout only: a Cosserat-layout element is
/// answered `Unsupported`, naming the layout.
#[test]
fn the_drive_analyses_refuse_another_layout() {
    registered();
    let scene = scene("string-drive");
    match fem::solve_scene(&scene, &opts(&scene, NAME)) {
        Err(FemError::Unsupported(m)) => assert!(m.contains("string layout"), "{m}"),
        Err(e) => panic!("expected Unsupported, got {e}"),
        Ok(_) => panic!("a drive ran with a Cosserat-layout element"),
    }
}

/// The quasistatic transient of the friction drive generic over the element
/// (`string_drive::solve_layout`, N = 12, X = N + 2 = 14 extended unknowns per element):
/// the test element on `string-simpson` runs `string-drive` (analysis `transient`, 32
/// elements, to its steady state) with the contact, friction and transport-inertia terms
/// on the element's centreline. Every summary scalar equals the string transient's
/// (`string_drive::solve`, N = 8): the (s, ν) problem is the same and θ is decoupled;
/// tolerance 1e-9 relative (of max(|v|, 1e-3)), as for the static analysis above — the
/// θ unknowns enter the update norm and the Levenberg–Marquardt shifts only. The run adds
/// θ and one ∂σθ per node, and a second ∂σθ at each of the four region transitions (the
/// string's separate transition slopes), and takes as many time steps.
#[test]
fn the_transient_runs_a_cosserat_layout_element() {
    let scene = scene("string-drive");
    let mut problem = fem::FemProblem::from_scene(&scene);
    problem.analysis = Analysis::Transient;
    let o = FemOptions { elements: 32, ..opts(&scene, "string-simpson") };
    let settings = SolverSettings::default();
    let ds = fem::string_drive::DriveSettings::from_scene(&scene);
    let string = fem::string_drive::solve(&problem, &o, &settings, &ds, formulation::find("string-simpson").unwrap()).expect("string transient");
    let element = Arc::new(ThetaRod::on("string-simpson", "string-theta-test"));
    let run = fem::string_drive::solve_layout::<NC, { NC + 2 }, ThetaRod>(&problem, &o, &settings, &ds, element).expect("the Cosserat-layout transient");
    let (hs, hr) = (string.history.as_ref().unwrap(), run.history.as_ref().unwrap());
    assert_eq!(hs.len(), hr.len(), "time steps");
    assert!(hs.len() > 10, "{} steps", hs.len());
    assert_eq!(run.stats.unknowns, string.stats.unknowns + 2 * o.elements + 4);
    assert!(run.terms.iter().any(|t| t.starts_with("θ least squares")));
    assert!(run.terms.iter().any(|t| t.starts_with("Coulomb contact")));
    let (count, worst) = same_scalars(&string.summary, "string-simpson", &run.summary, "the Cosserat layout");
    assert!(count >= 16, "{count} scalars");
    println!("{} steps; largest relative difference of {count} summary scalars: {worst:e}", hs.len());
}
