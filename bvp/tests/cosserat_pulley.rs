//! `cosserat-pulley` (Paper C, docs/cosserat-pulley.md): checks of spec §2.7–§2.8.

use bvp::belt::BeltOptions;
use bvp::cosserat_pulley::{self, CosseratPulley};

fn scene() -> CosseratPulley {
    CosseratPulley {
        radius: 0.1,
        end_distance: 0.5,
        transport_rate: 2.0,
        tension_in: 15.0,
        tension_out: 10.0,
        axial_stiffness: 1e4,
        bending_stiffness: 0.01,
        shear_stiffness: 1e3,
        mass_per_length: 0.1,
        friction: 0.3,
        inertia: true,
    }
}

#[test]
fn probe() {
    let t = std::time::Instant::now();
    let s = cosserat_pulley::solve(&scene(), &BeltOptions::default());
    match s {
        Ok(s) => {
            println!("{:?}", s.solution.params);
            println!("{:#?}", s.summary());
            println!("steps {} stats {:?} {:?}", s.homotopy_steps, s.stats, t.elapsed());
        }
        Err(e) => println!("ERR {e}"),
    }
}
