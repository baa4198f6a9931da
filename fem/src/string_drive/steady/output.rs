//! Outputs of a converged steady state: summary, options record, terms and the common view's points (docs/fem-drive.md §8, §12).

use super::*;

/// Outputs of a converged steady state (docs/fem-drive.md §8, §12).
#[allow(clippy::too_many_arguments)]
pub(super) fn finish<const N: usize, const P: usize, const E: usize, K: LayoutElement<N> + ?Sized + 'static>(
    problem: &crate::problem::FemProblem,
    opts: &crate::options::FemOptions,
    settings: &crate::options::SolverSettings,
    drive_settings: &super::super::DriveSettings,
    kernel: Arc<K>,
    state: State<N, K>,
    params: TermParams,
    penalty: f64,
    kappa: f64,
    mu: f64,
    homotopy: crate::static_homotopy::HomotopyReport,
    report: SteadyReport,
    clock: std::time::Instant,
) -> Result<crate::FemRun, FemError> {
    let asm = &state.asm;
    let nz = asm.len();
    let mesh = asm.mesh();
    let contour = *mesh.contour();
    let r = contour.radius();
    let length = problem.belt.length;
    let (c, omega2) = (state.x[nz], state.x[nz + 1]);
    let omega1 = problem.drive.driver_speed;
    let (load_torque, damping) = (problem.drive.driven_torque, problem.drive.driven_damping);
    let base = FemSolution::new(mesh.clone(), asm.dofs(), &state.x[..nz], params, length, kernel.clone()).with_transport_inertia(rho_c2(&state));
    let mut summary = base.summary();
    // T_tight, T_slack: the axial forces of the driver's and the driven pulley's stick
    // zones (creep theory's, as the BVP's, docs/string-drive.md) — constant there (λ̄
    // pinned), taken midway between the contact entry and the transition; the larger /
    // smaller mid-span force where a pulley has no stick zone or no recovered zone
    let (tu, tl) = (summary.tension_upper_mid.unwrap_or(0.0), summary.tension_lower_mid.unwrap_or(0.0));
    let direction = Direction::of_speed(omega1);
    // the stick→slip point: located on the slip run (semismooth), or prescribed (Paper D)
    let located = |pulley: Pulley| fixed_transition(&state.results, pulley).or_else(|| transition(&state.results, &contour, pulley));
    let stick_force = |pulley: Pulley| super::super::stick_zone_force(&base, pulley, located(pulley), direction);
    summary.tension_tight = Some(stick_force(Pulley::Driver).unwrap_or(tu.max(tl)));
    summary.tension_slack = Some(stick_force(Pulley::Driven).unwrap_or(tu.min(tl)));
    summary.driven_speed = Some(omega2);
    summary.transport_rate = Some(c);
    let mut torques = [0.0; 2];
    let mut entry_slip_force: f64 = 0.0;
    let mut warnings = report.warnings.clone();
    let arc_elements = mesh.elements().iter().filter(|e| e.region == Region::DriverArc).count().max(1);
    for (k, pulley) in [Pulley::Driver, Pulley::Driven].into_iter().enumerate() {
        let mut pts: Vec<&PointResult> = state.results.iter().filter(|p| p.point.pulley == pulley).collect();
        torques[k] = r * pts.iter().map(|p| p.point.weight * p.traction).sum::<f64>();
        pts.retain(|p| p.normal > 0.0);
        pts.sort_by(|a, b| unwrapped(&contour, pulley, a.point.sigma).total_cmp(&unwrapped(&contour, pulley, b.point.sigma)));
        // in the order of travel: the belt runs onto the pulley at its first point
        let mut travel = pts.clone();
        if direction == Direction::CounterClockwise {
            travel.reverse();
        }
        if let Some(i) = travel.iter().position(|p| !p.slip) {
            entry_slip_force = entry_slip_force.max(travel[..i].iter().map(|p| p.point.weight * p.traction).sum::<f64>().abs());
        }
        let angle = |sigma: f64| contour.polar_angle(pulley, base.position(contour.wrap(sigma)));
        let zone = base.zone(pulley);
        let (arc, start_angle, end_angle) = match (zone, pts.first(), pts.last()) {
            (Some(z), _, _) => ((z.angle_start - z.angle_end).rem_euclid(2.0 * PI), z.angle_start, z.angle_end),
            (None, Some(a), Some(b)) => ((angle(a.point.sigma) - angle(b.point.sigma)).rem_euclid(2.0 * PI), angle(a.point.sigma), angle(b.point.sigma)),
            _ => (0.0, 0.0, 0.0),
        };
        // the slip zone runs from the transition to where the belt leaves: the zone's
        // end along σ clockwise, its start counter-clockwise
        let slip_from = |s: f64| match direction {
            Direction::Clockwise => (angle(s) - end_angle).rem_euclid(2.0 * PI),
            Direction::CounterClockwise => (start_angle - angle(s)).rem_euclid(2.0 * PI),
        };
        let slip = if pts.is_empty() || pts.iter().all(|p| !p.slip) {
            0.0
        } else if pts.iter().all(|p| p.slip) {
            arc
        } else {
            located(pulley).map_or(0.0, |s| slip_from(s).min(arc))
        };
        warnings.extend(slip_resolution_warning(&format!("{} pulley", pulley.name()), slip * r, PI * r / arc_elements as f64, opts.elements, params.bending_stiffness));
        let block = if k == 0 { &mut summary.driver } else { &mut summary.driven };
        let ps = block.get_or_insert_with(drive::summary::PulleySummary::default);
        ps.contact_arc = ps.contact_arc.or(Some(arc));
        ps.slip_arc = Some(slip);
        ps.stick_arc = Some((ps.contact_arc.unwrap_or(arc) - slip).max(0.0));
        ps.torque = Some(torques[k]);
        // spec §3.7: the stick → slip point (where both zones are resolved), the stick
        // zone's stretch at its middle, the pulley's share of the dissipation below
        ps.stick_slip_angle = (slip > 0.0 && slip < ps.contact_arc.unwrap_or(arc)).then(|| located(pulley).map(angle)).flatten();
        ps.stretch_stick = super::super::stick_zone_middle(&base, pulley, located(pulley), direction).map(|s| base.stretch(s));
    }
    if let Err(e) = summary.check_finite() {
        return Err(FemError::NonFinite { what: e.to_string() });
    }
    let points: Vec<FrictionPoint> = state.results.iter().map(|p| p.point).collect();
    let sp = SteadyParams { mu, penalty, kappa, radius: r, omega1, torque: load_torque, damping, inertia: None, ends: Ends::Loop };
    let prob = SteadyProblem::<N, P, E, K> { asm, params, length, points: &points, sp, strain_rule: kernel.rules().strain };
    let dissipation = prob.dissipation(&state.x);
    for (pulley, block) in [(Pulley::Driver, &mut summary.driver), (Pulley::Driven, &mut summary.driven)] {
        if let Some(ps) = block {
            ps.dissipation = Some(prob.dissipation_on(&state.x, Some(pulley))).filter(|d| d.is_finite());
        }
    }
    let power_in = -torques[0] * omega1;
    let power_out = (load_torque + damping * omega2) * omega2;
    let max_penetration = base.max_penetration();
    let per_element = view_points(&state, params, length, &kernel);
    let view = super::super::DriveSolution::new(base, &per_element, summary.clone());
    let mut terms = kernel.term_labels(&TermParams { penalty: None, ..params });
    let zones = match report.scheme {
        SteadyScheme::PaperD => "stick and slip zones by Paper D's fixed topology",
        _ => "stick and slip zones by the semismooth fit",
    };
    terms.push(format!("Coulomb contact, direct steady state (semismooth Newton, {zones}, μ = {mu}, P_γ = {penalty:.6e} N/m², friction on the nodes)"));
    terms.push(format!("driven load M₂ = {load_torque} N·m, d₂ = {damping} N·m·s"));
    if problem.effects.inertia {
        terms.push(format!("transport inertia (ρ = {} kg/m)", problem.belt.mass_per_length));
    }
    let options = opts.record(Some(penalty), settings, serde_json::json!({
        "drive": {
            "solver": "steady",
            "settings": drive_settings,
            "kappa": kappa,
            "steady": true,
            "report": report,
            "power_in": power_in,
            "power_out": power_out,
            "dissipation": dissipation,
            "max_penetration": max_penetration,
            "entry_slip_force": entry_slip_force,
        },
        "homotopy": homotopy,
    }));
    let stats = crate::FemStats {
        wall_seconds: clock.elapsed().as_secs_f64(),
        newton_iterations: homotopy.newton_iterations + report.newton_iterations,
        unknowns: state.x.len(),
        elements: opts.elements,
        homotopy_steps: homotopy.steps + report.continuation_steps,
    };
    Ok(crate::FemRun { view: Box::new(view), summary, stats, options, terms, history: None, notes: warnings, unfitted: None })
}

/// Per element the point states the common view reads (docs/fem-drive.md §8): the
/// contact rule's points with their normal traction, the two edges with the traction
/// and state of their friction point.
pub(super) fn view_points<const N: usize, K: LayoutElement<N> + ?Sized>(state: &State<N, K>, params: TermParams, length: f64, kernel: &Arc<K>) -> Vec<Vec<super::super::ViewPoint>> {
    let asm = &state.asm;
    let mesh = asm.mesh();
    let contour = mesh.contour();
    let n = mesh.len();
    let penalty = params.penalty.unwrap_or(0.0);
    let mut edge: Vec<[Option<PointResult>; 2]> = vec![[None, None]; n];
    for res in &state.results {
        // a node's point stands for both elements' edges, a half for its own side
        if res.point.part != Part::Right {
            edge[res.point.left.0][1] = Some(*res);
        }
        if res.point.part != Part::Left {
            edge[res.point.right.0][0] = Some(*res);
        }
    }
    let rule = kernel.rules().contact;
    (0..n)
        .map(|e| {
            let el = asm.context(e, &params);
            let q = centreline(kernel.layout(), &el, &asm.dofs().gather(e, &state.x[..asm.len()], length));
            super::super::contact::mixed_rule(rule)
                .into_iter()
                .map(|(xi, w, wf)| {
                    let sigma = el.sigma(xi);
                    let p = el.fields(&q, xi);
                    let pulley = reachable_pulley(contour, el.geometry.region, sigma);
                    // the traction the contact term applies: ⟨λ − Pγ⟩₊ with the kernel's
                    // multipliers (augmented Lagrangian), P⟨−γ⟩ without
                    let normal = match pulley {
                        Some(_) => kernel.contact_traction(penalty, sigma, el.gap(&p)),
                        None => 0.0,
                    };
                    let fr = if wf > 0.0 { edge[e][usize::from(xi > 0.0)] } else { None };
                    super::super::ViewPoint {
                        xi,
                        sigma,
                        pulley,
                        weight: w * el.jacobian(),
                        friction_weight: if fr.is_some() { el.jacobian() } else { 0.0 },
                        normal,
                        tangential: fr.map_or(0.0, |f| f.traction),
                        slip: fr.is_some_and(|f| f.slip),
                    }
                })
                .collect()
        })
        .collect()
}

/// Mean arc elements (πR over the arc elements of the mesh) the slip zone of a belt
/// with bending stiffness must span for its stick and slip arcs to be trusted
/// (docs/fem-cosserat.md §11.1): such a slip zone lies inside the bending layer at the
/// contact exit. Measured on the catalogue's `cosserat-drive`, both rotation senses, at
/// 64–512 elements against the BVP (the zone's span as the FE gives it, on the drive's
/// graded meshes, `DRIVE_GRADING_RATIO`): slip-arc errors 3–17 % at 0.5–1.7 such
/// elements, 2.3–3.1 % at 2.1–2.2, ≤ 1.5 % from 3.4 on; 2.5 keeps every error above 2 %
/// warned.
pub const SLIP_ELEMENTS: f64 = 2.5;

/// The stated warning for the slip zone on `pulley` (its name in the sentence: "driver
/// pulley" on the loop, "pulley" on the one-pulley layout) of length `slip` (m along the
/// arc) when a belt with bending stiffness (`bending`) has it over fewer than
/// [`SLIP_ELEMENTS`] arc elements of length `element` (m) of a mesh of `elements`
/// elements; `None` for a resolved zone, no slip zone, or a string (whose slip zone is
/// a front in a smooth exponential field: its arcs converge at 128 elements to 4e-3,
/// docs/fem-drive.md §12).
pub fn slip_resolution_warning(pulley: &str, slip: f64, element: f64, elements: usize, bending: Option<f64>) -> Option<String> {
    bending?;
    let spans = slip / element;
    (slip > 0.0 && spans < SLIP_ELEMENTS).then(|| {
        let needed = (elements as f64 * SLIP_ELEMENTS / spans).ceil();
        format!(
            "unresolved slip zone on the {}: {} m long, {:.1} arc elements of {} m (≥ {SLIP_ELEMENTS} needed): its stick and slip arcs are not resolved (measured: 3–17 % off at 0.5–1.7 elements, 2–3 % at 2.1–2.2, ≤ 1.5 % from 3.4 on) — refine the mesh beyond {needed} elements",
            pulley,
            numerics::Sig(slip),
            spans,
            numerics::Sig(element),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rule of [`slip_resolution_warning`]: a string is never warned; a bending belt
    /// whose slip zone spans fewer than [`SLIP_ELEMENTS`] arc elements is, with the
    /// pulley, the length, the count and a mesh beyond which to refine.
    #[test]
    fn slip_zone_resolution_rule() {
        let element = 0.01;
        assert_eq!(slip_resolution_warning("driver pulley", 0.02, element, 128, None), None, "a string");
        assert_eq!(slip_resolution_warning("driver pulley", 0.0, element, 128, Some(5e-3)), None, "no slip zone");
        assert_eq!(slip_resolution_warning("driven pulley", 0.025, element, 128, Some(5e-3)), None, "2.5 elements");
        let w = slip_resolution_warning("driven pulley", 0.0149, element, 128, Some(5e-3)).expect("1.5 elements");
        assert!(w.starts_with("unresolved slip zone on the driven pulley: 0.0149 m long, 1.5 arc elements"), "{w}");
        // 128 · 2.5 / 1.49 = 214.8
        assert!(w.contains("beyond 215 elements"), "{w}");
    }
}
