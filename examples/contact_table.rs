//! What the tabulated contact solve (`ContactTable`, src/interface/table.rs)
//! costs against the warm-started solve the dynamics uses
//! (`Interface::contact_near` with the previous `a`), on the Dharahara base
//! (docs/model.md §4) for four of the case study's laws, rotations up to
//! 1.1 alpha: pieces, the largest relative difference of `af` from the
//! solver over 200 001 rotations, and ns per evaluation (both timed in the
//! same run over the same rocking-like sweep of rotations).
//! docs/performance.md, "Contact solve", shows a run.
//!
//! ```sh
//! cargo run --release --example contact_table
//! ```

use std::hint::black_box;
use std::time::Instant;

use rocking::{ContactTable, Interface, Law, Shape};

const W: f64 = 24_003.94e3;
const ALPHA: f64 = 0.13135;

fn main() {
    let shape = Shape::HollowCircle { ro: 3.99, ri: 2.12 };
    println!("| case | pieces | build | max rel. error af | table ns/eval | warm solve ns/eval |");
    println!("|---|---|---|---|---|---|");
    for (name, law) in [
        ("F170_fm5", Law::ElastoPlastic { kn: 170e6, fm: 5e6 }),
        ("F85_fm2", Law::ElastoPlastic { kn: 85e6, fm: 2e6 }),
        ("I15_elastic", Law::Elastic { kn: 15e9 }),
        ("I15_fm2", Law::ElastoPlastic { kn: 15e9, fm: 2e6 }),
    ] {
        let it = Interface::new(shape, law, W);
        let t0 = Instant::now();
        let table = ContactTable::new(&it, 1.1 * ALPHA).expect("a flexible law");
        let build = t0.elapsed().as_secs_f64();
        let (lo, hi) = table.range();
        let mut err = 0.0f64;
        for i in 0..=200_000 {
            let phi = lo + (hi - lo) * i as f64 / 200_000.0;
            if let Some(t) = table.contact(&it, phi) {
                let c = it.contact(phi);
                err = err.max(((t.af - c.af) / c.af).abs());
            }
        }
        let rots: Vec<f64> = (1..1_000_000)
            .map(|i| lo + (hi - lo) * 0.5 * (1.0 - (i as f64 * 1e-4).cos()))
            .filter(|&phi| phi > lo)
            .collect();
        let t0 = Instant::now();
        let mut acc = 0.0;
        for &phi in &rots {
            acc += table
                .contact(&it, black_box(phi))
                .map_or(0.0, |c| c.af + c.daf);
        }
        let table_ns = 1e9 * t0.elapsed().as_secs_f64() / rots.len() as f64;
        let t0 = Instant::now();
        let mut hint = f64::NAN;
        for &phi in &rots {
            let c = it.contact_near(black_box(phi), hint);
            hint = c.a;
            acc += c.af + c.daf;
        }
        let solve_ns = 1e9 * t0.elapsed().as_secs_f64() / rots.len() as f64;
        black_box(acc);
        let (pieces, open) = table.pieces();
        println!(
            "| {name} | {pieces} ({open} to the solver) | {:.1} ms | {err:.1e} | {table_ns:.0} | {solve_ns:.0} |",
            1e3 * build
        );
    }
}
