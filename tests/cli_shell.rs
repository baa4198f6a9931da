//! End to end, issue 15: `beltcheck solve scenes/shell-runoff.json` runs the shell's
//! stages 0–2 and writes the result format (summary with `runoff_velocity`,
//! `drift_per_revolution`, `edge_stress_max` and the planar names; the history of the
//! lateral channels with frames of surface fields; the cost), overlays a measurement
//! (`--measured`) with the difference, and writes the surface over time as VTK (`--vtk`),
//! read back here with an XML reader independent of the writer (`roxmltree` + `base64`).
//! The refusals (no BVP for a shell, the 1-D study's flags and impossible levels in
//! `converge`, flags for shells only, a malformed measurement, a bad scene) exit 2 and
//! write nothing; `gate --bvp-only` skips a shell with the reason (the whole
//! catalogue's gate, tests/harness.rs, gates it; `report` of a shell study is tested on
//! a synthetic study in `verification::plot_shell`). `converge` studies
//! a shortened scene at three levels and its Richardson reference is recomputed here
//! from the levels' own summaries.
//!
//! One solve of the CI scene (~15 s release on 2 shared cores) and the study (~20 s CPU);
//! everything else is cheap.

mod common;

use std::path::{Path, PathBuf};

use base64::Engine;
use common::{beltcheck, stderr, stdout, temp};
use drive::{RunResult, Scene, SurfaceFields};

const SCENE: &str = "scenes/shell-runoff.json";

fn scene() -> Scene {
    Scene::from_path(Path::new(SCENE)).unwrap()
}

/// The values of a `<DataArray Name=name>` of a vtkio `.vtu`: base64 of a little-endian
/// UInt64 byte count, then the little-endian values (f64 or u64 by `type`).
fn array(doc: &roxmltree::Document, parent: &str, name: &str) -> Vec<f64> {
    let node = doc
        .descendants()
        .filter(|n| n.has_tag_name("DataArray"))
        .find(|n| n.parent().is_some_and(|p| p.has_tag_name(parent)) && n.attribute("Name").unwrap_or("") == name)
        .unwrap_or_else(|| panic!("no DataArray {name} in {parent}"));
    assert_eq!(node.attribute("format"), Some("binary"), "{name}");
    let text: String = node.text().unwrap_or("").split_whitespace().collect();
    let bytes = base64::engine::general_purpose::STANDARD.decode(text).unwrap();
    let count = u64::from_le_bytes(bytes[..8].try_into().unwrap()) as usize;
    let body = &bytes[8..8 + count];
    match node.attribute("type") {
        Some("Float64") => body.chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect(),
        Some("UInt64") => body.chunks(8).map(|c| u64::from_le_bytes(c.try_into().unwrap()) as f64).collect(),
        Some("UInt8") => body.iter().map(|&b| b as f64).collect(),
        other => panic!("{name}: type {other:?}"),
    }
}

/// a and b equal to a few ulp (the frame went through JSON's decimal form).
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 4e-16 * a.abs().max(b.abs())
}

/// Checks one `.vtu` against its frame: point and cell counts, positions, the
/// displacement from g(σ) + ζ e_z, the scalar fields, and the closed quad loop.
fn check_vtu(file: &Path, frame: &SurfaceFields, contour: &drive::Contour) {
    let text = std::fs::read_to_string(file).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let piece = doc.descendants().find(|n| n.has_tag_name("Piece")).unwrap();
    let (ns, nz) = (frame.sigma.len(), frame.zeta.len());
    assert_eq!(piece.attribute("NumberOfPoints"), Some((ns * nz).to_string().as_str()), "{}", file.display());
    assert_eq!(piece.attribute("NumberOfCells"), Some((ns * (nz - 1)).to_string().as_str()), "{}", file.display());
    let points = array(&doc, "Points", "Points");
    let displacement = array(&doc, "PointData", "displacement");
    let force = array(&doc, "PointData", "membrane_force");
    let pressure = array(&doc, "PointData", "contact_pressure");
    assert_eq!(points.len(), 3 * ns * nz);
    for (i, &s) in frame.sigma.iter().enumerate() {
        let g = contour.position(s, 0.0);
        for (j, &q) in frame.zeta.iter().enumerate() {
            let k = i * nz + j;
            let r = [frame.values["x"][i][j], frame.values["y"][i][j], frame.values["z"][i][j]];
            // the JSON frame (decimal) and the binary VTK carry the same f64 to its last digits
            for c in 0..3 {
                assert!(close(points[3 * k + c], r[c]), "point {k} component {c}: {} vs {}", points[3 * k + c], r[c]);
            }
            let expected = [r[0] - g[0], r[1] - g[1], r[2] - q];
            for c in 0..3 {
                assert!((displacement[3 * k + c] - expected[c]).abs() <= 1e-15, "displacement {k}.{c}: {} vs {}", displacement[3 * k + c], expected[c]);
            }
            assert!(close(force[k], frame.values["membrane_force"][i][j]), "membrane force {k}");
            assert!(close(pressure[k], frame.values["contact_pressure"][i][j]), "contact pressure {k}");
        }
    }
    // the belt rests on the drums (pressure > 0 somewhere), nowhere a negative pressure
    assert!(pressure.iter().any(|&p| p > 0.0) && pressure.iter().all(|&p| p >= 0.0));
    let shear = array(&doc, "PointData", "interlayer_shear");
    assert!(shear.iter().all(|&u| u.is_finite() && u >= 0.0));
    for (k, u) in shear.iter().enumerate() {
        let (i, j) = (k / nz, k % nz);
        assert!(close(*u, frame.values["interlayer_shear"][i][j]), "interlayer shear {k}");
    }
    // quads (type 9), four vertices each; the last column connects to the first (closed loop)
    let connectivity = array(&doc, "Cells", "connectivity");
    let types = array(&doc, "Cells", "types");
    assert!(types.iter().all(|&t| t == 9.0) && types.len() == ns * (nz - 1));
    assert_eq!(connectivity.len(), 4 * ns * (nz - 1));
    let last = 4 * (ns - 1) * (nz - 1);
    assert_eq!(&connectivity[last..last + 4], &[((ns - 1) * nz) as f64, 0.0, 1.0, ((ns - 1) * nz + 1) as f64]);
}

/// The CI scene solved once with every output; the result, the measurement and the VTK
/// files checked against each other and against their definitions.
#[test]
fn shell_runoff_solves_and_writes_result_measured_and_vtk() {
    let s = scene();
    let run = s.shell_run();
    let json = temp("cli-shell", "result.json");
    let csv = temp("cli-shell", "measured.csv");
    let vtk = temp("cli-shell", "vtk");
    let _ = std::fs::remove_dir_all(&vtk);
    // a "measurement": z = 4e-6 t (m), one sample beyond the simulated rotation
    let rotation = run.steps as f64 * run.time_step;
    let times = [0.0, 0.3, 0.9, 1.7, 2.2, rotation + 1.0];
    let mut text = String::from("# test stand, lateral position of the centre line\ntime,lateral\n");
    for t in times {
        text.push_str(&format!("{t},{}\n", 4e-6 * t));
    }
    std::fs::write(&csv, text).unwrap();
    let start = std::time::Instant::now();
    let o = beltcheck(&["solve", SCENE, "--json", json.to_str().unwrap(), "--measured", csv.to_str().unwrap(), "--vtk", vtk.to_str().unwrap()]);
    let wall = start.elapsed().as_secs_f64();
    let out = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}\n{}", stderr(&o));
    eprintln!("shell-runoff: {wall:.1} s wall");
    for part in ["run-off velocity", "drift per revolution", "edge stress", "measured (", "VTK: 5 frame(s)"] {
        assert!(out.contains(part), "`{part}` missing in\n{out}");
    }

    let r = RunResult::from_json_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    r.check().unwrap();
    // the CI scene's 48 steps are 0.24 of a revolution, far shorter than the lateral
    // transient (period ≈ 24 s): no settled run-off, and the one warning says so (its
    // 8 elements across the width on the graded ζ-mesh resolve the edge layer,
    // docs/fem-shell.md §9.5)
    assert!(r.converged && r.method == "fem", "{:?}", r.warnings);
    assert!(r.summary.settled_runoff_velocity.is_none(), "{:?}", r.summary);
    assert!(matches!(&r.warnings[..], [w] if w.starts_with("run-off velocity not settled") && w.contains("the whole rotation")), "{:?}", r.warnings);
    assert_eq!(r.discretisation, Some(drive::Discretisation::Mesh2d { sigma: 64, zeta: 8, time_step: run.time_step }));
    // 64 × 8 elements: 12 unknowns per node × 64 × 9 nodes (closed loop); the graded
    // ζ-mesh resolves the edge layer, so no warning says it does not
    assert_eq!(r.cost.unknowns, 12 * 64 * 9);
    assert!(r.cost.newton_iterations >= run.steps + run.ramp_steps, "at least one Newton iteration per step");

    // the summary: the definitions hold to round-off
    let sum = &r.summary;
    let (v, drift) = (sum.runoff_velocity.unwrap(), sum.drift_per_revolution.unwrap());
    let revolution = s.belt.length / (s.drive.driver_speed * s.drive.pulley_radius);
    assert!((drift - v * revolution).abs() <= 1e-12 * drift.abs(), "drift {drift} vs v·L/(ωR) {}", v * revolution);
    let h = r.history.as_ref().unwrap();
    assert_eq!(h.len(), 1 + run.ramp_steps + run.steps, "one sample at the end of stage (0), one per step");
    let stage = h.channel("stage").unwrap();
    let first = stage.iter().position(|&x| x == 2.0).unwrap() - 1;
    // the rotation is shorter than a revolution here: the slope over all its samples
    assert!(rotation < revolution);
    let (t, z) = (&h.time[first..], &h.channel("lateral_offset").unwrap()[first..]);
    let (tm, zm) = (t.iter().sum::<f64>() / t.len() as f64, z.iter().sum::<f64>() / z.len() as f64);
    let slope = t.iter().zip(z).map(|(a, b)| (a - tm) * (b - zm)).sum::<f64>() / t.iter().map(|a| (a - tm) * (a - tm)).sum::<f64>();
    assert!((slope - v).abs() <= 1e-9 * v.abs(), "least-squares slope {slope} vs runoff_velocity {v}");
    // camber and swivel make the belt run off: the offset during the rotation goes well
    // above the ramp's (measured 3.9e-7 → 1.25e-5 m at mid-rotation, back to 9.7e-7 at
    // the end: the lateral transient's swing; the E-3 round-off of a perfect belt is
    // 1e-16 m)
    let swing = z.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(swing > 10.0 * z[0].abs() && swing > 1e-6, "z̄ {} → largest {swing}", z[0]);
    // the planar names: the belt sags below the contour on both spans, in tension
    let radius = s.drive.pulley_radius;
    let (yu, yl) = (sum.y_upper_mid.unwrap(), sum.y_lower_mid.unwrap());
    assert!(yu < radius && yu > radius - 0.05 && yl < -radius && yl > -radius - 0.05, "y {yu}, {yl}");
    let (tu, tl) = (sum.tension_upper_mid.unwrap(), sum.tension_lower_mid.unwrap());
    assert!(tu > 0.0 && tl > 0.0);
    // the edge stress: the largest |n_σσ|/h at the edges is at least the mean stress of a
    // mid-span (the camber's stress is linear across the width, so one edge carries more)
    let plate = s.belt.plate().unwrap();
    assert!(sum.edge_stress_max.unwrap() >= tu.max(tl) / (plate.width * plate.thickness), "{:?}", sum.edge_stress_max);
    assert_eq!(sum.driven_speed, Some(s.drive.driver_speed));
    // the width-integrated belt along σ (`fields`, the common view): each point on the
    // contour's normal at its σ (DESIGN.md's fields; `check` relies on it), to round-off
    let f = r.fields.as_ref().unwrap();
    assert_eq!(f.sigma.len(), 200);
    let c = s.contour();
    for ((&sg, &x), &y) in f.sigma.iter().zip(&f.x).zip(&f.y) {
        let (back, _) = c.sigma_nu([x, y]);
        let d = (back - sg).abs().min(c.length() - (back - sg).abs());
        assert!(d <= 1e-9, "σ = {sg}: the point lies on the normal at {back}");
    }

    // frames: the start of the rotation, every 6 steps, the end
    assert_eq!(h.frames.len(), 1 + run.steps / run.frame_every);
    assert!((h.frames[0].time - h.time[first]).abs() < 1e-12 && h.frames.last().unwrap().time == *h.time.last().unwrap());

    // the peak interlayer shear per drum: P_⊥ × the largest |u| of the history points
    // nearest each drum, positive once turning. The frame's |u| on the nodes nearer that
    // drum is each neighbouring ζ-element's points extrapolated to the node (the mean of
    // one or two; the nearest point where one is out of contact): under the default
    // 2-point rule at most Σ|ℓ_b(±1)| = √3 times the largest point's, so the peak is at
    // least P_⊥ × that over √3. The extrapolation reaches the free edge, where |u| is
    // largest, so the nodes exceed the points there (measured on this scene: the driven
    // drum's nodes 420.6 against its points' 378.0 Pa, 1.11×); they stay within 2× of it
    // (the edge element is the graded mesh's narrowest, a fraction of the edge layer).
    let drive::scene::Contact::ElasticLayer(layer) = &s.effects.contact else { panic!("the CI scene has an elastic interlayer") };
    let p_t = layer.tangential_stiffness;
    let last = h.frames.last().unwrap().surface.as_ref().unwrap();
    let (driver_c, driven_c) = (c.pulley_centre(drive::contour::Pulley::Driver), c.pulley_centre(drive::contour::Pulley::Driven));
    let mut node_peak = [0.0f64; 2];
    for (i, &sg) in last.sigma.iter().enumerate() {
        let g = c.g(sg);
        let d = |p: [f64; 2]| (g[0] - p[0]).hypot(g[1] - p[1]);
        let k = usize::from(d(driven_c) < d(driver_c));
        node_peak[k] = last.values["interlayer_shear"][i].iter().fold(node_peak[k], |a, &u| a.max(u));
    }
    for (k, name) in ["peak_shear_driver", "peak_shear_driven"].iter().enumerate() {
        let peak = h.channel(name).unwrap_or_else(|| panic!("{name} missing"));
        assert_eq!(peak[0], 0.0, "{name}: no shear at the static start");
        let end = *peak.last().unwrap();
        assert!(end > 0.0 && 3f64.sqrt() * end >= p_t * node_peak[k] * (1.0 - 1e-12), "{name}: {end} against P_⊥·max|u| of the nodes {} over √3", p_t * node_peak[k]);
        assert!(end >= 0.5 * p_t * node_peak[k] && end <= 2.0 * p_t * node_peak[k], "{name}: {end} against the nodes' {}", p_t * node_peak[k]);
    }

    // the measurement: model at the measured times, the difference model − measured
    let m = r.measured.as_ref().unwrap();
    assert_eq!(m.channel, "lateral_offset");
    assert_eq!(m.time.len(), times.len() - 1);
    assert_eq!(m.outside, 1);
    let start = h.time[first];
    for (k, &tk) in m.time.iter().enumerate() {
        assert_eq!(m.measured[k], 4e-6 * tk);
        assert!((m.difference[k] - (m.model[k] - m.measured[k])).abs() <= 1e-18);
        // the model interpolated independently here
        let tt = start + tk;
        let i = h.time.partition_point(|&x| x <= tt).clamp(1, h.len() - 1);
        let zc = h.channel("lateral_offset").unwrap();
        let w = (tt - h.time[i - 1]) / (h.time[i] - h.time[i - 1]);
        let model = zc[i - 1] + w.clamp(0.0, 1.0) * (zc[i] - zc[i - 1]);
        assert!((m.model[k] - model).abs() <= 1e-15, "t = {tk}: {} vs {model}", m.model[k]);
    }
    let rms = (m.difference.iter().map(|d| d * d).sum::<f64>() / m.difference.len() as f64).sqrt();
    assert!((m.rms_difference - rms).abs() <= 1e-15 * rms.max(1e-300));

    // VTK: one .vtu per frame, read back independently, and the series
    let contour = s.contour();
    let pvd = std::fs::read_to_string(vtk.join("shell-runoff.pvd")).unwrap();
    let doc = roxmltree::Document::parse(&pvd).unwrap();
    let sets: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("DataSet")).collect();
    assert_eq!(sets.len(), h.frames.len());
    for (k, (set, frame)) in sets.iter().zip(&h.frames).enumerate() {
        let file: PathBuf = vtk.join(set.attribute("file").unwrap());
        assert_eq!(file, vtk.join(format!("shell-runoff_{k:04}.vtu")));
        let time: f64 = set.attribute("timestep").unwrap().parse().unwrap();
        assert!((time - frame.time).abs() <= 1e-15 * frame.time);
        check_vtu(&file, frame.surface.as_ref().unwrap(), &contour);
    }
    // the turning drums shear the interlayer: |u| > 0 on the drums at the end
    let last = h.frames.last().unwrap().surface.as_ref().unwrap();
    assert!(last.values["interlayer_shear"].iter().flatten().any(|&u| u > 0.0));
}

/// What a shell scene is refused for, with exit 2 and nothing written; `gate
/// --bvp-only` skips it with the reason.
#[test]
fn shell_refusals_name_the_reason_and_write_nothing() {
    let json = temp("cli-shell-refusals", "out.json");
    let _ = std::fs::remove_file(&json);
    let j = json.to_str().unwrap();
    let refused = |args: &[&str], parts: &[&str]| {
        let o = beltcheck(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        for p in parts {
            assert!(err.contains(p), "{args:?}: `{p}` missing in {err}");
        }
        assert!(!json.exists(), "{args:?}: a file was written");
    };
    refused(&["solve", SCENE, "--method", "bvp-collocation", "--json", j], &["no BVP exists for theory `shell`", "--method fem", "nothing was solved"]);
    refused(&["solve", SCENE, "--method", "bvp-shooting", "--json", j], &["no BVP exists"]);
    // `converge` on a shell: the 1-D study's flags and impossible levels, before any run
    refused(&["converge", SCENE, "--elements", "64,128,256", "--json", j], &["--elements is not used", "--levels"]);
    refused(&["converge", SCENE, "--tolerances", "1e-6", "--json", j], &["--tolerances is not used"]);
    refused(&["converge", SCENE, "--reference", "closed-form", "--json", j], &["no closed form"]);
    refused(&["converge", SCENE, "--levels", "64x2,128x2", "--json", j], &["three or more levels"]);
    refused(&["converge", SCENE, "--levels", "64x2,128x2,192x2", "--json", j], &["the same ratio over the three finest"]);
    refused(&["converge", SCENE, "--levels", "32x2,64x6,128x8", "--json", j], &["three or more levels"]);
    refused(&["converge", SCENE, "--levels", "32x1,64x1,128x1", "--json", j], &["the level 32×1", "fem.elements_zeta", "even"]);
    refused(&["converge", SCENE, "--levels", "64by2", "--json", j], &["--levels = 64by2"]);
    refused(&["converge", "scenes/rod-hanging.json", "--levels", "64x2,128x2,256x2", "--json", j], &["--levels is for shell scenes"]);
    refused(&["converge", "scenes/rod-hanging.json", "--refine", "step", "--json", j], &["--refine is for shell scenes"]);
    refused(&["converge", SCENE, "--refine", "step", "--levels", "64x2,128x2", "--json", j], &["with --refine step one mesh"]);
    // the width alone, but σ refined too at the last level: no one limit
    refused(&["converge", SCENE, "--refine", "width", "--levels", "32x2,32x4,64x8", "--json", j], &["n_ζ alone on one σ-mesh", "three or more levels"]);
    refused(&["converge", "scenes/rod-hanging.json", "--no-compensation", "--json", j], &["--no-compensation is for shell scenes"]);
    // levels that refine in another way than --refine asks: refused, not studied as that other limit
    refused(&["converge", SCENE, "--refine", "width", "--levels", "32x2,64x4,128x8", "--json", j], &["with --refine width levels that refine n_ζ alone", "these refine σ alone at one Δt"]);
    refused(&["converge", SCENE, "--refine", "mesh", "--levels", "32x2,32x4,32x8", "--json", j], &["with --refine mesh levels that refine σ alone", "these refine n_ζ alone"]);
    refused(&["converge", SCENE, "--levels", "32x2,32x4,32x8", "--json", j], &["with --refine both levels that refine σ and Δt together", "these refine n_ζ alone"]);
    refused(&["solve", SCENE, "--elements", "32", "--json", j], &["--elements is not used", "elements_sigma"]);
    refused(&["solve", "scenes/rod-hanging.json", "--vtk", temp("cli-shell-refusals", "vtk").to_str().unwrap(), "--json", j], &["--vtk is for shell scenes", "kirchhoff"]);
    refused(&["solve", "scenes/rod-hanging.json", "--measured", "x.csv", "--json", j], &["--measured is for shell scenes"]);
    refused(&["solve", SCENE, "--measured-channel", "lateral_offset", "--json", j], &["--measured-channel needs --measured"]);
    // a malformed measurement is refused before the solve (it would take ~15 s)
    let csv = temp("cli-shell-refusals", "bad.csv");
    std::fs::write(&csv, "time,lateral\n0,0\n0.5,1e-6\n0.5,2e-6\n").unwrap();
    let start = std::time::Instant::now();
    refused(&["solve", SCENE, "--measured", csv.to_str().unwrap(), "--json", j], &["line 4", "does not follow", "increase strictly"]);
    assert!(start.elapsed().as_secs_f64() < 5.0, "the file is read before the solve");
    std::fs::write(&csv, "0,0\n1\n").unwrap();
    refused(&["solve", SCENE, "--measured", csv.to_str().unwrap(), "--json", j], &["line 2", "one field, two expected"]);
    refused(&["solve", SCENE, "--measured", "/nonexistent/m.csv", "--json", j], &["cannot read"]);
    // --vtk onto a file
    let file = temp("cli-shell-refusals", "a-file");
    std::fs::write(&file, "x").unwrap();
    refused(&["solve", SCENE, "--vtk", file.to_str().unwrap(), "--json", j], &["not a directory"]);
    // impossible scene fields (exit 2 before solving, the path named)
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    v["drive"]["driven_speed"] = serde_json::json!(-2.0);
    let bad = temp("cli-shell-refusals", "bad-scene.json");
    std::fs::write(&bad, v.to_string()).unwrap();
    refused(&["solve", bad.to_str().unwrap(), "--json", j], &["drive.driven_speed", "opposite senses"]);
    // gate: the 1-D flags are refused with a shell among the scenes; --bvp-only skips
    // a shell (it has no BVP); report skips it, saying why
    refused(&["gate", SCENE, "--elements", "64,128", "--json", j], &["shell-runoff.json is a shell scene", "gate.levels"]);
    refused(&["gate", SCENE, "--tolerance", "1e-6", "--json", j], &["is a shell scene"]);
    let o = beltcheck(&["gate", "--bvp-only", SCENE, "scenes/string-hanging.json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("gate --bvp-only: skipped scene `shell-runoff`") && stdout(&o).contains("no BVP exists for the shell"), "{}", stdout(&o));
    // a shell study whose rotation is not a whole number of a level's steps
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    v["fem"]["steps"] = serde_json::json!(3);
    let odd = temp("cli-shell-refusals", "odd-steps.json");
    std::fs::write(&odd, v.to_string()).unwrap();
    refused(&["converge", odd.to_str().unwrap(), "--levels", "32x2,64x2,128x2", "--json", j], &["the level 32×2", "fem.steps", "not a whole number"]);
    // report: the shell's study takes the same levels and refuses the same flags
    let dir = temp("cli-shell-refusals", "report");
    let o = beltcheck(&["report", SCENE, "--elements", "64,128,256", "-o", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--elements is not used"), "{}", stderr(&o));
    assert!(!dir.join("shell-runoff").exists(), "no report directory for a refused scene");
}

/// `converge` on a shell scene (issue 15): the levels 32×2, 64×2, 128×2 with Δt scaled
/// like the σ spacing over the same simulated time; the reference is the Richardson
/// extrapolation of the three levels, recomputed here from the rows' summaries (order
/// p = ln(|q₂ − q₁|/|q₃ − q₂|)/ln 2, q_R = q₃ + (q₃ − q₂)/(2^p − 1)); oscillating
/// quantities are left out and named; the rows' errors are |q − q_R|/|q_R|; n_ζ held is
/// stated.
#[test]
fn shell_converge_extrapolates_its_levels_and_holds_them_against_the_extrapolation() {
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    v["fem"]["steps"] = serde_json::json!(2);
    v["fem"]["frame_every"] = serde_json::json!(0);
    let short = temp("cli-shell-converge", "short.json");
    std::fs::write(&short, v.to_string()).unwrap();
    let dt = v["fem"]["time_step"].as_f64().unwrap();
    let json = temp("cli-shell-converge", "study.json");
    let _ = std::fs::remove_file(&json);
    let o = beltcheck(&["converge", short.to_str().unwrap(), "--levels", "32x2,64x2,128x2", "--samples", "256", "--json", json.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("reference: Richardson extrapolation of fem shell-bfs (levels 32×2"), "{out}");
    assert!(out.contains("n_ζ is held at 2"), "{out}");
    assert!(out.contains("the reference's values: Richardson extrapolation"), "{out}");
    let study: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = study["series"][0]["rows"].as_array().unwrap();
    assert_eq!(study["series"][0]["method"], "fem shell-bfs");
    assert_eq!(rows.len(), 3);
    // the levels: n_σ as asked, n_ζ held, Δt scaled like the σ spacing
    for (row, (ns, f)) in rows.iter().zip([(32, 2.0), (64, 1.0), (128, 0.5)]) {
        let d = &row["run"]["discretisation"]["mesh2d"];
        assert_eq!(d["sigma"], ns);
        assert_eq!(d["zeta"], 2);
        assert!((d["time_step"].as_f64().unwrap() - f * dt).abs() <= 1e-15 * dt, "{d}");
        assert_eq!(row["run"]["status"], "solved", "{}", row["run"]);
    }
    let value = |run: &serde_json::Value, q: &str| run["summary"].pointer(&format!("/{q}")).and_then(serde_json::Value::as_f64);
    let reference = &study["reference"];
    let estimates = study["reference_estimates"].as_array().unwrap();
    let notes: Vec<&str> = study["notes"].as_array().unwrap().iter().filter_map(|n| n.as_str()).collect();
    let (mut extrapolated, mut refused) = (0, 0);
    for q in ["y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid", "moment_upper_mid", "moment_lower_mid", "runoff_velocity", "drift_per_revolution", "edge_stress_max"] {
        let [q1, q2, q3] = [0, 1, 2].map(|k| value(&rows[k]["run"], q).unwrap_or_else(|| panic!("{q} missing at level {k}")));
        let (d21, d32) = (q2 - q1, q3 - q2);
        let in_reference = value(reference, q);
        if d21 * d32 < 0.0 || d32.abs() >= d21.abs() {
            refused += 1;
            assert!(in_reference.is_none(), "{q}: not asymptotic ({q1}, {q2}, {q3}) but in the reference");
            assert!(notes.iter().any(|n| n.starts_with("refused") && n.contains(q)), "{q}: refusal not noted: {notes:?}");
            continue;
        }
        extrapolated += 1;
        let p = (d21.abs() / d32.abs()).ln() / 2f64.ln();
        let qr = q3 + d32 / (2f64.powf(p) - 1.0);
        let got = in_reference.unwrap_or_else(|| panic!("{q}: asymptotic but not in the reference"));
        assert!((got - qr).abs() <= 1e-12 * qr.abs(), "{q}: reference {got} against {qr}");
        let e = estimates.iter().find(|e| e["quantity"] == q).unwrap();
        assert!((e["order"].as_f64().unwrap() - p).abs() <= 1e-9 * p, "{q}: order {} against {p}", e["order"]);
        assert!((e["error_estimate"].as_f64().unwrap() - (qr - q3).abs()).abs() <= 1e-12 * qr.abs(), "{q}: estimate");
        let err = rows[2]["errors"][q].as_f64().unwrap();
        assert!((err - (q3 - qr).abs() / qr.abs()).abs() <= 1e-9 * err.max(1e-300), "{q}: row error {err}");
    }
    assert!(extrapolated >= 1, "no quantity extrapolated: {notes:?}");
    // the cambered belt's compensating swivel at the coarsest level (spec E-5): found, and
    // it cancels the run-off there (Brent's tolerance bounds what is left at ~1e-4 of it)
    let c = &study["compensation"];
    let (left, without) = (c["runoff_left"].as_f64().unwrap(), c["runoff_without"].as_f64().unwrap());
    assert!(without.abs() > 0.0 && left.abs() <= 1e-3 * without.abs(), "{c}");
    assert_eq!(c["drum"], "driven");
    assert!(out.contains("the compensating swivel (spec E-5) of the driven drum at the coarsest level"), "{out}");
    assert_eq!(estimates.len(), extrapolated + usize::from(value(reference, "driven_speed").is_some()), "{estimates:?}");
    eprintln!("shell study: {extrapolated} extrapolated, {refused} refused");
}

/// `--no-compensation` skips a cambered belt's compensating swivel (about six whole
/// solves at the coarsest level) and the study says so; without it the same study
/// searches it (the CI scene shortened to 2 steps, its camber kept); with a camber of
/// zero there is nothing to skip and the study says nothing of it.
#[test]
fn shell_converge_skips_the_compensating_swivel_when_told_and_says_so() {
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    v["fem"]["steps"] = serde_json::json!(2);
    v["fem"]["frame_every"] = serde_json::json!(0);
    assert!(v["belt"]["camber"].is_object(), "the CI scene is cambered");
    let short = temp("cli-shell-no-compensation", "short.json");
    std::fs::write(&short, v.to_string()).unwrap();
    // a camber of zero given explicitly: nothing to search, so nothing said to be skipped
    v["belt"]["camber"] = serde_json::json!({"edge_length_difference": 0.0});
    let straight = temp("cli-shell-no-compensation", "straight.json");
    std::fs::write(&straight, v.to_string()).unwrap();
    for (scene, skip, skipped) in [(&short, true, true), (&short, false, false), (&straight, true, false)] {
        let json = temp("cli-shell-no-compensation", &format!("{skip}-{skipped}.json"));
        let _ = std::fs::remove_file(&json);
        let mut a = vec!["converge", scene.to_str().unwrap(), "--refine", "width", "--levels", "32x2,32x4,32x8", "--samples", "64", "--json", json.to_str().unwrap()];
        if skip {
            a.push("--no-compensation");
        }
        let o = beltcheck(&a);
        assert!(o.status.success(), "{skip}: {}", stderr(&o));
        let study: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        assert_eq!(stdout(&o).contains("the compensating swivel (spec E-5) was not searched (--no-compensation)"), skipped, "{}", stdout(&o));
        assert_eq!(study["notes"].as_array().unwrap().iter().any(|n| n.as_str().unwrap().contains("not searched")), skipped, "{}", study["notes"]);
        // searched: a root or a note why none was found
        let searched = !study["compensation"].is_null() || study["notes"].as_array().unwrap().iter().any(|n| n.as_str().unwrap().contains("could not be found"));
        assert_eq!(searched, !skip, "{skip}: {}", study["notes"]);
    }
}

/// `converge --refine step`, `--refine mesh` and `--refine width` on a shell scene (issue
/// 15: the run-off "refined together and separately"): the step alone halved twice on
/// one mesh, the mesh alone at the scene's step, or n_ζ alone on one σ-mesh at that step;
/// the study says which limit the sequence converges to, and the Richardson
/// extrapolation is of that sequence.
#[test]
fn shell_converge_refines_the_step_alone_or_the_mesh_alone() {
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(SCENE).unwrap()).unwrap();
    v["fem"]["steps"] = serde_json::json!(2);
    v["fem"]["frame_every"] = serde_json::json!(0);
    // no camber: no compensating swivel to search (its own test is above)
    v["belt"].as_object_mut().unwrap().remove("camber");
    let short = temp("cli-shell-refine", "short.json");
    std::fs::write(&short, v.to_string()).unwrap();
    let dt = v["fem"]["time_step"].as_f64().unwrap();
    for (refine, levels, expected, note) in [
        ("step", "32x2", [(32, 2, dt), (32, 2, dt / 2.0), (32, 2, dt / 4.0)], "the time step alone is refined, on the mesh 32×2"),
        ("mesh", "32x2,64x2,128x2", [(32, 2, dt), (64, 2, dt), (128, 2, dt)], "the mesh alone is refined, at Δt ="),
        ("width", "32x2,32x4,32x8", [(32, 2, dt), (32, 4, dt), (32, 8, dt)], "the width alone is refined, n_ζ on the σ-mesh of 32 elements at Δt ="),
    ] {
        let json = temp("cli-shell-refine", &format!("{refine}.json"));
        let _ = std::fs::remove_file(&json);
        let mut a = vec!["converge", short.to_str().unwrap(), "--refine", refine, "--levels", levels, "--samples", "256", "--json", json.to_str().unwrap()];
        if refine == "width" {
            // nothing to skip on a belt without camber: the study says nothing of it
            a.push("--no-compensation");
        }
        let o = beltcheck(&a);
        assert!(o.status.success(), "{refine}: {}", stderr(&o));
        assert!(stdout(&o).contains(note), "{refine}: {}", stdout(&o));
        assert_eq!(stdout(&o).contains("fem shell-bfs — time-step sequence on one mesh"), refine == "step", "{}", stdout(&o));
        assert_eq!(stdout(&o).contains("fem shell-bfs — width sequence (n_ζ) on one σ-mesh and step"), refine == "width", "{}", stdout(&o));
        let study: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let rows = study["series"][0]["rows"].as_array().unwrap();
        assert_eq!(rows.len(), 3);
        for (row, (ns, nz, step)) in rows.iter().zip(expected) {
            let d = &row["run"]["discretisation"]["mesh2d"];
            assert_eq!((&d["sigma"], &d["zeta"]), (&serde_json::json!(ns), &serde_json::json!(nz)), "{refine}");
            assert!((d["time_step"].as_f64().unwrap() - step).abs() <= 1e-15 * dt, "{refine}: {d}");
            assert_eq!(row["run"]["status"], "solved", "{}", row["run"]);
        }
        // no camber: no compensating swivel searched, and none said to be skipped (with
        // --no-compensation on the width's study)
        assert!(study["compensation"].is_null() && !stdout(&o).contains("not searched"), "{refine}");
        // the extrapolation is of this sequence (ratio 2): the recomputed Richardson value
        // of the upper mid-span height, when it is in the asymptotic range
        let y = |k: usize| rows[k]["run"]["summary"]["y_upper_mid"].as_f64().unwrap();
        let (d21, d32) = (y(1) - y(0), y(2) - y(1));
        if let Some(got) = study["reference"]["summary"]["y_upper_mid"].as_f64() {
            let p = (d21.abs() / d32.abs()).ln() / 2f64.ln();
            let qr = y(2) + d32 / (2f64.powf(p) - 1.0);
            assert!((got - qr).abs() <= 1e-12 * qr.abs(), "{refine}: {got} against {qr}");
        } else {
            assert!(d21 * d32 <= 0.0 || d32.abs() >= d21.abs(), "{refine}: asymptotic ({d21:e}, {d32:e}) but not extrapolated");
        }
    }
}
