//! The Cosserat (shearable) rod on a rigid stamp (§6.3, Fig. 5b; check C-10;
//! docs/rod-stamp.md "The Cosserat rod"): the closed form against the spec's table, and a
//! convergence table of the Timoshenko penalty FE against it — contact half width, edge
//! and centre pressure, support reaction, balance, Newton iterations and wall time.
//!
//! `cargo run --release -p fem --example stamp_cosserat`

use fem::quadrature::Rule;
use fem::stamp_cosserat::{closed_form, solve_fe, CosseratFeOptions, CosseratStamp};
use std::time::Instant;

fn main() {
    let kirchhoff =
        fem::stamp::closed_form(&fem::stamp::Stamp::FIG_5A).expect("Kirchhoff closed form");
    println!(
        "closed form (Kirchhoff a = {:.9} m, P = {:.7} N, support {:.7} N):",
        kirchhoff.half_width, kirchhoff.edge_force, kirchhoff.support_reaction
    );
    println!(
        "{:>8} {:>12} {:>12} {:>15} {:>11} {:>11} {:>12} {:>12}",
        "b₂", "a_c", "p(0)", "p(a_c)", "excess", "support", "(a−a_K)β", "E+F/ρβ−P"
    );
    for b2 in [1e3, 1e4, 1e5, 1e6, 1e8, 1e12] {
        let cf = closed_form(&CosseratStamp::fig_5b(b2)).expect("closed form");
        let beta = cf.data.beta();
        println!(
            "{b2:>8.0e} {:>12.9} {:>12.6} {:>15.6} {:>11.7} {:>11.7} {:>12.8} {:>12.4e}",
            cf.half_width,
            cf.pressure_centre,
            cf.pressure_edge,
            cf.excess,
            cf.support_reaction,
            (cf.half_width - kirchhoff.half_width) * beta,
            cf.excess + 100.0 / beta - kirchhoff.edge_force
        );
    }
    // the spec's table (check C-10): largest relative difference per row
    let table: [(f64, [f64; 5]); 4] = [
        (
            1e3,
            [0.159811758, 103.579283, 316.250312, 7.2073563, 23.1885320],
        ),
        (
            1e4,
            [0.141432015, 100.001392, 1000.000062, 9.0453410, 23.1885424],
        ),
        (
            1e5,
            [0.134999241, 100.000000, 3162.277844, 9.6886183, 23.1885424],
        ),
        (
            1e6,
            [0.132880468, 100.000000, 10000.000577, 9.9004956, 23.1885424],
        ),
    ];
    for (b2, row) in table {
        let got = closed_form(&CosseratStamp::fig_5b(b2)).expect("closed form").table_row();
        let worst = row
            .iter()
            .zip(got)
            .map(|(w, g)| ((g - w) / w).abs())
            .fold(0.0, f64::max);
        println!("b₂ = {b2:.0e}: largest relative difference to the spec table {worst:.1e}");
    }
    println!();
    println!(
        "{:>6} {:>9} {:>6} {:>6} {:>11} {:>11} {:>11} {:>11} {:>11} {:>5} {:>8}",
        "b₂",
        "P_γ",
        "shear",
        "n",
        "a_h − a",
        "p_e − p(a)",
        "p(0) err",
        "R_h − R",
        "balance",
        "iter",
        "ms"
    );
    let cases: &[(f64, Option<f64>, Rule, &[usize])] = &[
        (
            1e3,
            Some(1e13),
            Rule::Gauss(1),
            &[64, 128, 256, 512, 1024, 2048, 4096],
        ),
        (1e3, Some(1e11), Rule::Gauss(1), &[256, 1024, 4096]),
        (
            1e4,
            None,
            Rule::Gauss(1),
            &[128, 256, 512, 1024, 2048, 4096, 8192],
        ),
        (1e6, None, Rule::Gauss(1), &[32, 64, 128, 1024]),
        (1e6, None, Rule::Gauss(2), &[32, 64, 128, 1024]),
    ];
    for &(b2, penalty, shear_rule, meshes) in cases {
        let data = CosseratStamp::fig_5b(b2);
        let cf = closed_form(&data).expect("closed form");
        for &n in meshes {
            let opts = CosseratFeOptions {
                elements: n,
                penalty,
                shear_rule,
                ..Default::default()
            };
            let t = Instant::now();
            let fe = solve_fe(&data, &opts).expect("FE solves");
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let (da, dp) = fe.edges().map_or((f64::NAN, f64::NAN), |e| {
                (e.position - cf.half_width, e.pressure - cf.pressure_edge)
            });
            let supports = fe.support_reactions[0] + fe.support_reactions[1];
            println!(
                "{b2:>6.0e} {:>9.1e} {:>6} {n:>6} {da:>11.3e} {dp:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} {:>5} {ms:>8.2}",
                fe.penalty,
                shear_rule.name(),
                fe.pressure_centre() - cf.pressure_centre,
                0.5 * supports - cf.support_reaction,
                supports - fe.stamp_force,
                fe.iterations
            );
        }
    }
}
