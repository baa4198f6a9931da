//! Convergence table of the penalty FE of the linearised rod on a rigid stamp
//! (docs/rod-stamp.md; §6.3, Fig. 5a of the reference) against its closed form:
//! contact half width, edge force, interior pressure, support balance, Newton iterations
//! and wall time, for two penalty factors.
//!
//! `cargo run --release -p fem --example stamp`

use fem::stamp::{closed_form, solve_fe, Stamp, StampFeOptions};
use std::time::Instant;

fn main() {
    let s = Stamp {
        half_span: 1.0,
        bending_stiffness: 1.0,
        axial_force: 100.0,
        stamp_radius: 1.0,
        indentation: 0.2,
    };
    let cf = closed_form(&s).expect("closed form");
    println!(
        "closed form: a = {:.10} m, p = F/ρ = {} N/m, P = {:.10} N, support = {:.10} N",
        cf.half_width, cf.pressure, cf.edge_force, cf.support_reaction
    );
    println!(
        "{:>10} {:>6} {:>12} {:>12} {:>12} {:>12} {:>5} {:>9}",
        "P_γ", "n", "a_h − a", "P_h − P", "p(0) − F/ρ", "balance", "iter", "time ms"
    );
    for penalty in [1e6, 1e8, 1e10] {
        for n in [16, 32, 64, 128, 256, 512, 1024, 2048, 4096] {
            let opts = StampFeOptions {
                elements: n,
                penalty,
                ..Default::default()
            };
            let t = Instant::now();
            let fe = solve_fe(&s, &opts).expect("FE solves");
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let p = fe.edge_force(cf.half_width, 0.5 * cf.half_width);
            let mid = fe
                .pressure_points()
                .iter()
                .min_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
                .map(|q| q.2)
                .unwrap();
            let balance = fe.support_reactions[0] + fe.support_reactions[1] - fe.stamp_force;
            println!(
                "{penalty:>10.0e} {n:>6} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e} {:>5} {ms:>9.2}",
                fe.half_width() - cf.half_width,
                p - cf.edge_force,
                mid - cf.pressure,
                balance,
                fe.iterations
            );
        }
    }
}
