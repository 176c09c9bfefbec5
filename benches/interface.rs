//! Cost of the interface solve: `af` and `af'` together, per shape and law.
//! Prints a table (ns per evaluation, Newton iterations per solve) for a
//! sweep of rotations from the heel opening to the overturning range, cold
//! (`contact`, no hint), started from the previous `a` (`contact_near`, the
//! path the integrator takes: `eom.rs` keeps the last `a` as the hint), and
//! extrapolated from the previous contact along `da/dphi` (`contact_after`).
//! Run: `cargo bench --bench interface`.

use std::hint::black_box;
use std::time::Instant;

use rocking::{Contact, Interface, Law, Shape};

fn main() {
    let shapes = [
        ("solid rectangle", Shape::SolidRectangle { b: 0.5, l: 1.0 }),
        (
            "hollow rectangle",
            Shape::HollowRectangle {
                b: 3.0,
                l: 2.0,
                t: 0.35,
            },
        ),
        ("solid circle", Shape::SolidCircle { ro: 0.5 }),
        ("hollow circle", Shape::HollowCircle { ro: 3.99, ri: 2.12 }),
    ];
    println!("| shape | law | cold ns/eval | contact_near (integrator) ns/eval | contact_after ns/eval | iterations/solve: cold, near, after |");
    println!("|---|---|---|---|---|---|");
    for (name, shape) in shapes {
        let w = 0.3e6 * shape.area();
        for (lname, law) in [
            ("elastic", Law::Elastic { kn: 5e9 }),
            ("elastoPlastic", Law::ElastoPlastic { kn: 5e9, fm: 2e6 }),
        ] {
            let it = Interface::new(shape, law, w);
            // rotations from thetaJo to 0.3 rad, where the contact is partial
            let n = 4096;
            let lo = it.theta_jo();
            let thetas: Vec<f64> = (0..n)
                .map(|i| lo * (0.3 / lo).powf(i as f64 / (n - 1) as f64))
                .collect();
            let cold = time_sweeps(&thetas, || (), |_, th| it.contact(th));
            let near = time_sweeps(
                &thetas,
                || f64::NAN,
                |a, th| {
                    let c = it.contact_near(th, *a);
                    if c.a.is_finite() {
                        *a = c.a;
                    }
                    c
                },
            );
            let after = time_sweeps(
                &thetas,
                || it.contact(thetas[0]),
                |prev, th| {
                    *prev = it.contact_after(th, prev);
                    *prev
                },
            );
            println!(
                "| {name} | {lname} | {:.0} | {:.0} | {:.0} | {:.2}, {:.2}, {:.2} |",
                cold.0, near.0, after.0, cold.1, near.1, after.1
            );
        }
    }
}

/// `(ns, Newton iterations)` per solve of 40 sweeps of `solve` over
/// `thetas`, each sweep from the state `start` gives it (the previous
/// contact, its `a`, or nothing).
fn time_sweeps<S>(
    thetas: &[f64],
    start: impl Fn() -> S,
    solve: impl Fn(&mut S, f64) -> Contact,
) -> (f64, f64) {
    let reps = 40;
    let mut iterations = 0u64;
    let t0 = Instant::now();
    for _ in 0..reps {
        let mut state = start();
        for &th in thetas {
            let c = solve(&mut state, black_box(th));
            iterations += c.iterations as u64;
            black_box((c.af, c.daf));
        }
    }
    let solves = (reps * thetas.len()) as f64;
    (
        t0.elapsed().as_nanos() as f64 / solves,
        iterations as f64 / solves,
    )
}
