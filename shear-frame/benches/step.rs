//! Cost of the exact step: building the map for one step size (the matrix
//! exponential of the augmented system, once per size) and applying it, by
//! number of storeys. Prints a table; no timing is asserted.

use std::hint::black_box;
use std::time::Instant;

use shear_frame::{Damping, Frame, Load, State};

fn per_call(repeats: usize, mut f: impl FnMut()) -> f64 {
    f();
    let start = Instant::now();
    for _ in 0..repeats {
        f();
    }
    start.elapsed().as_secs_f64() / repeats as f64
}

fn main() {
    println!("| storeys | build the step map (us) | one step (us) |");
    println!("|---:|---:|---:|");
    for n in [1usize, 3, 5, 10, 20] {
        let m = vec![2.0e5; n];
        let k = vec![3.0e8; n];
        let frame = Frame::new(&m, &k, Damping::Modal { zeta: 0.05 }).unwrap();
        let build = per_call(50, || {
            black_box(frame.propagator(black_box(0.01)));
        });
        let p = frame.propagator(0.01);
        let mut s = State::at_rest(0.0);
        let load = Load {
            ag: 1.0,
            ..Load::ZERO
        };
        let step = per_call(20_000, || {
            p.step(&mut s, black_box(&load), &Load::ZERO);
        });
        println!("| {n} | {:.1} | {:.3} |", build * 1e6, step * 1e6);
    }
}
