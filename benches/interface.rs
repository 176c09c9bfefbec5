//! Cost of the interface solve: `af` and `af'` together, per shape and law.
//! Prints a table (ns per evaluation, Newton iterations per solve) for a
//! sweep of rotations from the heel opening to the overturning range, cold
//! (`contact`, no hint), started from the previous `a` (`contact_near`, the
//! path the integrator takes: `eom.rs` keeps the last `a` as the hint), and
//! extrapolated from the previous contact along `da/dphi` (`contact_after`).
//! Run: `cargo bench --bench interface`.

use std::hint::black_box;
use std::time::Instant;

use rocking::{Interface, Law, Shape};

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
            let reps = 40;
            let mut iters_cold = 0u64;
            let t0 = Instant::now();
            for _ in 0..reps {
                for &th in &thetas {
                    let c = it.contact(black_box(th));
                    iters_cold += c.iterations as u64;
                    black_box((c.af, c.daf));
                }
            }
            let cold = t0.elapsed().as_nanos() as f64 / (reps * n) as f64;
            let mut iters_near = 0u64;
            let t0 = Instant::now();
            for _ in 0..reps {
                let mut a = f64::NAN;
                for &th in &thetas {
                    let c = it.contact_near(black_box(th), a);
                    if c.a.is_finite() {
                        a = c.a;
                    }
                    iters_near += c.iterations as u64;
                    black_box((c.af, c.daf));
                }
            }
            let near = t0.elapsed().as_nanos() as f64 / (reps * n) as f64;
            let mut iters_warm = 0u64;
            let t0 = Instant::now();
            for _ in 0..reps {
                let mut prev = it.contact(thetas[0]);
                for &th in &thetas {
                    let c = it.contact_after(black_box(th), &prev);
                    prev = c;
                    iters_warm += c.iterations as u64;
                    black_box((c.af, c.daf));
                }
            }
            let warm = t0.elapsed().as_nanos() as f64 / (reps * n) as f64;
            let per = (reps * n) as f64;
            println!(
                "| {name} | {lname} | {cold:.0} | {near:.0} | {warm:.0} | {:.2}, {:.2}, {:.2} |",
                iters_cold as f64 / per,
                iters_near as f64 / per,
                iters_warm as f64 / per
            );
        }
    }
}
