//! The Rust engine run directly (no FMI), for comparisons with the FMU: the
//! same parameter table as the FMU (`fmu_rocking::params`).
//!
//! ```text
//! run_direct [NAME=VALUE ...] [--tolerance RTOL] [--start T0] --steps FILE
//! run_direct [NAME=VALUE ...] [--tolerance RTOL] [--start T0] --stop T1 --step H [--ag AG]
//! ```
//!
//! `NAME` is an FMU parameter or start value (`B=0.4`, `shape=solidCircle`,
//! `theta=0.01`...). `--steps FILE` is a CSV with a header and one row
//! `t_end,ag,dag` per communication step: from the previous end (or T0) to
//! `t_end` the ground acceleration is `ag + dag (t - t_start)`. The step end is
//! computed as a master does (`t + (t_end - t)`). Prints a CSV: one row at the
//! start and one after each step (outputs with the input at the step's end,
//! `ag + dag h`), up to overturning (the last row at the overturning time).

use std::env;
use std::fs;
use std::process::exit;

use fmi2_export::model_description::Type;
use fmu_rocking::description::ROCKING_BLOCK;
use fmu_rocking::params::{self, Field};
use rocking::dynamics::{GroundInput, Simulator, State};
use rocking::Params;

fn die(msg: String) -> ! {
    eprintln!("run_direct: {msg}");
    exit(2)
}

fn number(name: &str, s: &str) -> f64 {
    match s {
        "inf" | "INF" | "Infinity" => f64::INFINITY,
        _ => s
            .parse()
            .unwrap_or_else(|_| die(format!("{name} = {s:?}: not a number"))),
    }
}

/// An enumeration value by item name or number, checked against the table.
fn item(name: &str, s: &str) -> i32 {
    let v = ROCKING_BLOCK.variable(name).expect("a field's variable");
    let Type::Enumeration { declared_type, .. } = v.ty else {
        die(format!("{name} is no enumeration"))
    };
    let t = ROCKING_BLOCK.enum_type(declared_type).expect("declared");
    t.items
        .iter()
        .find(|i| i.name == s || i.value.to_string() == s)
        .map(|i| i.value)
        .unwrap_or_else(|| die(format!("{name} = {s}: not an item of {declared_type}")))
}

/// `NAME=VALUE`: the field of the parameter or start value `name`.
fn set(p: &mut Params, name: &str, s: &str) {
    match params::field(name) {
        Some((_, Field::Real(set))) => set(p, number(name, s)),
        Some((_, Field::Integer(set))) => {
            let x = s
                .parse()
                .unwrap_or_else(|_| die(format!("{name} = {s}: not an integer")));
            set(p, x)
        }
        Some((_, Field::Enumeration(set))) => {
            set(p, item(name, s)).expect("an item of the table");
        }
        None => die(format!("unknown parameter {name}")),
    }
}

fn row(sim: &Simulator, s: &State, ag: f64) {
    let o = sim.outputs(s, ag);
    println!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{}",
        s.t,
        s.theta,
        s.omega,
        o.theta_dd,
        o.af,
        o.contact_length,
        o.mr,
        o.regime as i32,
        s.impacts,
        s.zero_crossings,
        s.overturned as i32,
        o.fx,
        o.fz
    );
}

fn main() {
    let mut p = Params::default();
    let mut rtol = ROCKING_BLOCK.default_experiment.tolerance;
    let mut start = 0.0;
    let (mut stop, mut step, mut ag0) = (None, None, 0.0);
    let mut steps_file = None;
    let mut args = env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |what: &str| {
            args.next()
                .unwrap_or_else(|| die(format!("{what} needs a value")))
        };
        match a.as_str() {
            "--tolerance" => rtol = number("--tolerance", &value("--tolerance")),
            "--start" => start = number("--start", &value("--start")),
            "--stop" => stop = Some(number("--stop", &value("--stop"))),
            "--step" => step = Some(number("--step", &value("--step"))),
            "--ag" => ag0 = number("--ag", &value("--ag")),
            "--steps" => steps_file = Some(value("--steps")),
            kv => match kv.split_once('=') {
                Some((k, v)) => set(&mut p, k, v),
                None => die(format!("unexpected argument {kv:?}")),
            },
        }
    }
    // (t_end, ag, dag) per communication step
    let steps: Vec<(f64, f64, f64)> = match (steps_file, stop, step) {
        (Some(f), _, _) => {
            let text = fs::read_to_string(&f).unwrap_or_else(|e| die(format!("{f}: {e}")));
            text.lines()
                .skip(1)
                .filter(|l| !l.trim().is_empty())
                .map(|l| {
                    let c: Vec<f64> = l.split(',').map(|x| number(&f, x.trim())).collect();
                    if c.len() != 3 {
                        die(format!("{f}: need t_end,ag,dag per row: {l}"));
                    }
                    (c[0], c[1], c[2])
                })
                .collect()
        }
        (None, Some(stop), Some(h)) => {
            let n = ((stop - start) / h).round() as usize;
            (1..=n).map(|k| (start + k as f64 * h, ag0, 0.0)).collect()
        }
        _ => die("give --steps FILE, or --stop and --step".into()),
    };
    let model = p.build().unwrap_or_else(|e| die(e.to_string()));
    let sim = Simulator::new(model, rtol);
    let mut s = sim.initial_state(p.theta0, p.omega0);
    s.t = start;
    println!(
        "time,theta,omega,angularAcceleration,af,contactLength,MR,regime,impacts,zeroCrossings,overturned,Fx,Fz"
    );
    row(&sim, &s, steps.first().map_or(ag0, |x| x.1));
    let mut time = start;
    for (next, ag, dag) in steps {
        let h = next - time;
        let ev = sim.advance(&mut s, time + h, GroundInput { ag, dag });
        if let Some(t_ov) = ev.overturned_at {
            s.t = t_ov;
            row(&sim, &s, ag + dag * (t_ov - time));
            break;
        }
        time = next;
        row(&sim, &s, ag + dag * h);
    }
}
