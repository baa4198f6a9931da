//! Result JSON contract (DESIGN.md "Result format"): keys and nesting exactly as
//! documented, absent quantities absent, round trip, no NaN written.

use drive::{Cost, CostPhases, Fields, Frame, History, PulleySummary, ResultError, RunResult, Summary, SurfaceFields, TimeSeries, SCALAR_NAMES};
use serde_json::{json, Value};

fn full_summary() -> Summary {
    let mut s = Summary::default();
    for (i, name) in SCALAR_NAMES.iter().enumerate() {
        s.set(name, Some(0.5 + i as f64)).unwrap();
    }
    s
}

fn result(summary: Summary, fields: Option<Fields>) -> RunResult {
    RunResult {
        scene: "string-hanging".into(),
        method: "bvp-collocation".into(),
        converged: true,
        summary,
        cost: Cost {
            wall_seconds: 0.25,
            newton_iterations: 12,
            unknowns: 3400,
            mesh_nodes: None,
            phases: None,
        },
        fields,
        options: None,
        surface: None,
        history: None,
        discretisation: None,
        warnings: Vec::new(),
        measured: None,
    }
}

/// A breakdown of the 0.25 s of [`result`]: every phase non-zero, so that a field the
/// round trip dropped or renamed would show.
fn phases() -> CostPhases {
    CostPhases {
        assembly: 0.08,
        symbolic_factorisation: 0.01,
        numeric_factorisation: 0.03,
        linear_solves: 0.02,
        residuals: 0.04,
        integration: 0.005,
        mesh_adaptation: 0.015,
        fitting: 0.01,
        other: 0.04,
        fitting_total: 0.12,
        continuation_steps: 7,
        mesh_refinements: 3,
        fitting_passes: 4,
    }
}

fn keys(v: &Value) -> Vec<String> {
    v.as_object().unwrap().keys().cloned().collect::<Vec<_>>()
}

fn sorted(mut k: Vec<&str>) -> Vec<String> {
    k.sort();
    k.into_iter().map(String::from).collect()
}

/// The key sets of DESIGN.md's example, level by level (with the one-pulley and
/// Cosserat names its definitions add: `pulley.*`, `pulley_speed`, `tension_in`,
/// `tension_out`, `y_in`, `y_out`, `edge_pressure_*`, and the shell's `runoff_velocity`,
/// `drift_per_revolution`, `edge_stress_max` of spec §4.15 and `settled_runoff_velocity`,
/// its run-off after the lateral transient).
#[test]
fn keys_and_nesting_exactly_as_design() {
    let fields = Fields {
        sigma: vec![0.0, 0.5],
        x: vec![-0.2, 0.1],
        y: vec![0.08, 0.07],
        tension: vec![10.0, 10.5],
        moment: Some(vec![0.0, 0.01]),
        ..Fields::default()
    };
    let v: Value = serde_json::from_str(
        &result(full_summary(), Some(fields))
            .to_json_pretty()
            .unwrap(),
    )
    .unwrap();
    assert_eq!(
        keys(&v),
        sorted(vec![
            "scene",
            "method",
            "converged",
            "summary",
            "cost",
            "fields"
        ])
    );
    assert_eq!(
        keys(&v["summary"]),
        sorted(vec![
            "y_upper_mid",
            "y_lower_mid",
            "tension_upper_mid",
            "tension_lower_mid",
            "moment_upper_mid",
            "moment_lower_mid",
            "tension_tight",
            "tension_slack",
            "driven_speed",
            "transport_rate",
            "pulley_speed",
            "tension_in",
            "tension_out",
            "y_in",
            "y_out",
            "runoff_velocity",
            "settled_runoff_velocity",
            "drift_per_revolution",
            "edge_stress_max",
            "driver",
            "driven",
            "pulley",
        ])
    );
    let pulley = sorted(vec![
        "contact_arc",
        "contact_start",
        "contact_end",
        "stick_arc",
        "slip_arc",
        "torque",
        "edge_force_start",
        "edge_force_end",
        "edge_pressure_start",
        "edge_pressure_end",
        "pressure_min",
        "stick_slip_angle",
        "shear_strain_max",
        "moment_start",
        "moment_end",
        "stretch_stick",
        "dissipation",
    ]);
    assert_eq!(keys(&v["summary"]["driver"]), pulley);
    assert_eq!(keys(&v["summary"]["driven"]), pulley);
    assert_eq!(keys(&v["summary"]["pulley"]), pulley);
    assert_eq!(
        keys(&v["cost"]),
        sorted(vec!["wall_seconds", "newton_iterations", "unknowns"])
    );
    assert_eq!(
        keys(&v["fields"]),
        sorted(vec!["sigma", "x", "y", "tension", "moment"])
    );
    assert_eq!(v["scene"], json!("string-hanging"));
    assert_eq!(v["converged"], json!(true));
    assert_eq!(v["cost"]["newton_iterations"], json!(12));
    // driver.contact_arc is the 20th name (after the 19 globals).
    assert_eq!(v["summary"]["driver"]["contact_arc"], json!(19.5));
}

#[test]
fn design_example_result_parses() {
    let text = r#"{
      "scene": "string-hanging", "method": "bvp-collocation", "converged": true,
      "summary": {"y_upper_mid": 0.0, "tension_upper_mid": 0.0,
                  "driver": {"contact_arc": 0.0, "torque": 0.0}},
      "cost": {"wall_seconds": 0.0, "newton_iterations": 0, "unknowns": 0},
      "fields": {"sigma": [], "x": [], "y": [], "tension": [], "moment": []}
    }"#;
    let r = RunResult::from_json_str(text).unwrap();
    assert_eq!(r.summary.get("driver.contact_arc"), Some(0.0));
    assert_eq!(r.summary.get("driven.contact_arc"), None);
    assert_eq!(r.fields.as_ref().unwrap().moment, Some(vec![]));
}

#[test]
fn absent_quantities_are_absent_not_zero_or_null() {
    let summary = Summary {
        y_upper_mid: Some(-0.02),
        tension_upper_mid: Some(12.0),
        driver: Some(PulleySummary {
            contact_arc: Some(3.3),
            ..Default::default()
        }),
        ..Default::default()
    };
    let fields = Fields {
        sigma: vec![0.0],
        x: vec![0.0],
        y: vec![0.0],
        tension: vec![1.0],
        moment: None,
        ..Fields::default()
    };
    let text = result(summary, Some(fields)).to_json_pretty().unwrap();
    assert!(!text.contains("null"), "{text}");
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(
        keys(&v["summary"]),
        sorted(vec!["y_upper_mid", "tension_upper_mid", "driver"])
    );
    assert_eq!(
        keys(&v["summary"]["driver"]),
        vec!["contact_arc".to_string()]
    );
    assert!(v["fields"].get("moment").is_none());
    assert!(v["cost"].get("mesh_nodes").is_none());
    assert!(v["cost"].get("phases").is_none());
    assert!(v.get("options").is_none());
    // flattened names for the harness
    let flat = result(
        Summary {
            driver: Some(PulleySummary {
                torque: Some(1.0),
                ..Default::default()
            }),
            ..Default::default()
        },
        None,
    )
    .summary
    .scalars();
    assert_eq!(flat, vec![("driver.torque".to_string(), 1.0)]);
}

#[test]
fn round_trip() {
    let mut r = result(full_summary(), None);
    r.cost.mesh_nodes = Some(801);
    r.cost.phases = Some(phases());
    r.options = Some(json!({"tolerance": 1e-8, "scheme": "gauss6"}));
    let text = r.to_json_pretty().unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["cost"]["phases"]["numeric_factorisation"], json!(0.03));
    assert_eq!(v["cost"]["phases"]["fitting_passes"], json!(4));
    let back = RunResult::from_json_str(&text).unwrap();
    assert_eq!(back, r);
    let flat = back.summary.scalars();
    assert_eq!(
        flat.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
        SCALAR_NAMES.to_vec()
    );
    let rebuilt = Summary::from_scalars(flat.iter().map(|(n, v)| (n.as_str(), *v))).unwrap();
    assert_eq!(rebuilt, r.summary);
}

#[test]
fn nan_is_never_written() {
    let mut s = full_summary();
    s.set("tension_slack", Some(f64::NAN)).unwrap();
    let e = result(s, None).to_json_pretty().unwrap_err();
    assert!(
        matches!(&e, ResultError::NotFinite { quantity, value } if quantity == "tension_slack" && value.is_nan()),
        "{e}"
    );
    assert!(e.to_string().contains("`tension_slack`"));

    // Two samples at σ = 0, 1 with y = 0 and the given x and tension: the error of writing them.
    let written = |x: Vec<f64>, tension: Vec<f64>| {
        let fields = Fields { sigma: vec![0.0, 1.0], x, y: vec![0.0, 0.0], tension, moment: None, ..Fields::default() };
        result(Summary::default(), Some(fields)).to_json_pretty().unwrap_err()
    };
    let e = written(vec![0.0, 0.0], vec![1.0, f64::INFINITY]);
    assert_eq!(
        e.to_string(),
        "result quantity `fields.tension[1]` is not finite (inf)"
    );

    let e = written(vec![0.0], vec![1.0, 1.0]);
    assert!(
        matches!(
            e,
            ResultError::FieldLength {
                len: 1,
                expected: 2,
                ..
            }
        ),
        "{e}"
    );

    let mut r = result(Summary::default(), None);
    r.cost.phases = Some(CostPhases { linear_solves: f64::INFINITY, ..phases() });
    assert_eq!(r.to_json_pretty().unwrap_err().to_string(), "result quantity `cost.phases.linear_solves` is not finite (inf)");

    let mut r = result(Summary::default(), None);
    r.cost.wall_seconds = f64::NAN;
    assert!(r
        .to_json_pretty()
        .unwrap_err()
        .to_string()
        .contains("cost.wall_seconds"));
}

/// Fields along σ, over (σ, ζ) and in time (issue 11 item 4): each written and read back
/// equal, in the documented JSON shape.
#[test]
fn surface_and_time_fields_round_trip() {
    let surface = SurfaceFields {
        sigma: vec![0.0, 0.5, 1.0],
        zeta: vec![-0.1, 0.1],
        values: [
            ("z".to_string(), vec![vec![0.0, 1e-3], vec![2e-3, 3e-3], vec![4e-3, 5e-3]]),
            ("contact_pressure".to_string(), vec![vec![1e4, 2e4], vec![0.0, 0.0], vec![3e4, 1e4]]),
        ]
        .into(),
    };
    let along = Fields { sigma: vec![0.0, 1.0], x: vec![-0.2, 0.2], y: vec![0.08, 0.07], tension: vec![12.0, 11.5], moment: None, ..Fields::default() };
    let mut history = TimeSeries::default();
    history.push(0.1, &[("runoff_velocity", 1e-4), ("lateral_position", 0.0)]);
    history.push(0.2, &[("runoff_velocity", 2e-4), ("lateral_position", 1e-5)]);
    history.frames = vec![
        Frame { time: 0.1, fields: Some(along.clone()), surface: None },
        Frame { time: 0.2, fields: None, surface: Some(surface.clone()) },
    ];
    let mut r = result(full_summary(), Some(along));
    r.surface = Some(surface);
    r.history = Some(history);
    let text = r.to_json_pretty().unwrap();
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["surface"]["z"][1], json!([2e-3, 3e-3]), "surface.<name>[i][j] at (σ_i, ζ_j)");
    assert_eq!(v["surface"]["zeta"], json!([-0.1, 0.1]));
    assert_eq!(v["history"]["runoff_velocity"], json!([1e-4, 2e-4]), "channels sit beside `time`");
    assert_eq!(v["history"]["frames"][1]["time"], json!(0.2));
    assert_eq!(RunResult::from_json_str(&text).unwrap(), r);
}

/// The friction drive's `History` becomes a `TimeSeries` with the same JSON, and a result
/// written before (its `history` object) reads as one.
#[test]
fn drive_history_is_a_time_series() {
    let h = History {
        time: vec![0.01, 0.02],
        driven_speed: vec![19.0, 19.5],
        transport_rate: vec![1.5, 1.6],
        tension_upper_mid: vec![3.0, 3.1],
        tension_lower_mid: vec![9.0, 9.1],
        driver_stick_arc: vec![1.0, 1.1],
        driver_slip_arc: vec![2.0, 1.9],
        driver_torque: vec![0.3, 0.31],
        driven_stick_arc: vec![1.2, 1.3],
        driven_slip_arc: vec![1.8, 1.7],
        driven_torque: vec![-0.1, -0.1],
        change_rate: vec![1e-2, 1e-3],
    };
    let old_json = serde_json::to_value(&h).unwrap();
    let series = TimeSeries::from(h.clone());
    assert_eq!(series.len(), 2);
    assert_eq!(series.channel("driver_torque"), Some(&[0.3, 0.31][..]));
    assert_eq!(serde_json::to_value(&series).unwrap(), old_json, "the same history JSON");
    let read: TimeSeries = serde_json::from_value(old_json).unwrap();
    assert_eq!(read, series);
}

#[test]
fn ragged_or_unknown_surface_and_time_fields_are_refused() {
    let mut s = SurfaceFields { sigma: vec![0.0, 1.0], zeta: vec![0.0], values: [("z".to_string(), vec![vec![0.0], vec![0.0, 1.0]])].into() };
    assert_eq!(s.check(), Err(ResultError::FieldLength { field: "surface.z[1]".into(), len: 2, expected: 1 }));
    s.values = [("zz".to_string(), vec![vec![0.0], vec![0.0]])].into();
    let e = s.check().unwrap_err();
    assert!(e.to_string().contains("did you mean `z`"), "{e}");
    s.values = [("y".to_string(), vec![vec![0.0], vec![f64::NAN]])].into();
    assert!(matches!(s.check(), Err(ResultError::NotFinite { quantity, .. }) if quantity == "surface.y[1][0]"));

    let mut t = TimeSeries::default();
    t.push(0.0, &[("a", 1.0)]);
    t.series.insert("b".into(), vec![]);
    assert_eq!(t.check(), Err(ResultError::FieldLength { field: "history.b".into(), len: 0, expected: 1 }));
    let mut t = TimeSeries::default();
    t.push(0.0, &[("Bad Name", 1.0)]);
    assert!(matches!(t.check(), Err(ResultError::UnknownField { .. })));
    let mut t = TimeSeries::default();
    t.push(0.0, &[("a", 1.0)]);
    t.frames = vec![Frame { time: 0.0, fields: Some(Fields { sigma: vec![0.0], x: vec![f64::INFINITY], y: vec![0.0], tension: vec![0.0], moment: None, ..Fields::default() }), surface: None }];
    assert!(matches!(t.check(), Err(ResultError::NotFinite { quantity, .. }) if quantity == "history.frames[0].fields.x[0]"));
}
