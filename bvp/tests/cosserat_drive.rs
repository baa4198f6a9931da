//! The Cosserat two-pulley drive in steady motion (docs/cosserat-drive.md; issue 14, BVP).

use std::path::Path;

use bvp::belt::BeltOptions;
use bvp::cosserat_drive::{self, CosseratDrive};
use drive::scene::Scene;
use drive::view::SolutionView;

fn scene_data() -> (Scene, CosseratDrive) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cosserat-drive.json");
    let scene = Scene::from_path(&path).expect("the scene parses and validates");
    let data = CosseratDrive::from_scene(&scene).expect("a Cosserat drive scene");
    (scene, data)
}

#[test]
fn scene_solves_from_its_file() {
    let (scene, data) = scene_data();
    let opts = BeltOptions::from_scene(&scene).expect("options");
    let t = std::time::Instant::now();
    let sol = cosserat_drive::solve(&data, &opts).expect("solves");
    eprintln!("time {:?} steps {} nodes {:?}", t.elapsed(), sol.homotopy_steps, sol.solution.segments.iter().map(|s| s.mesh.len()).collect::<Vec<_>>());
    eprintln!("{:#?}", sol.summary());
    eprintln!("params {:?}", sol.solution.params);
    eprintln!("power {:?}", sol.power_balance());
}
