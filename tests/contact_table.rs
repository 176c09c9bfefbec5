//! `ContactTable` (src/interface/table.rs) against brute force: the
//! equilibrium solve at every rotation of dense grids (log-spaced and
//! uniform, 40 000 rotations from the first iterative regime to 0.2 rad), for
//! the four shapes and the three laws, crushing starting in partial contact
//! and in full contact, and a stiff interface (the rotations span decades).

use rocking::{ContactTable, Interface, Law, Shape};

const PHI_MAX: f64 = 0.2;

/// (name, shape, weight N, kn Pa/m, fm Pa for crushing in partial contact, fm for crushing in full contact)
fn bodies() -> Vec<(&'static str, Shape, f64, f64, f64, f64)> {
    vec![
        (
            "solid rectangle",
            Shape::SolidRectangle { b: 1.0, l: 1.0 },
            1e5,
            1e8,
            5e5,
            1.5e5,
        ),
        (
            "hollow rectangle",
            Shape::HollowRectangle {
                b: 1.0,
                l: 1.0,
                t: 0.15,
            },
            5e4,
            1e8,
            3e5,
            1.2e5,
        ),
        (
            "solid circle",
            Shape::SolidCircle { ro: 0.5 },
            1e5,
            1e8,
            4e5,
            1.6e5,
        ),
        (
            "hollow circle",
            Shape::HollowCircle { ro: 3.99, ri: 2.12 },
            2.4e7,
            1.7e8,
            5e6,
            1e6,
        ),
        (
            "hollow circle, stiff",
            Shape::HollowCircle { ro: 3.99, ri: 2.12 },
            2.4e7,
            1.5e10,
            2e6,
            1e6,
        ),
    ]
}

/// Every body of [`bodies`] on its three flexible laws (elastic, crushing in
/// partial and in full contact), with its table up to `PHI_MAX`.
fn tables() -> Vec<(&'static str, Law, Interface, ContactTable)> {
    let mut out = Vec::new();
    for (name, shape, w, kn, fm_partial, fm_full) in bodies() {
        for law in [
            Law::Elastic { kn },
            Law::ElastoPlastic { kn, fm: fm_partial },
            Law::ElastoPlastic { kn, fm: fm_full },
        ] {
            let it = Interface::new(shape, law, w);
            let table = ContactTable::new(&it, PHI_MAX).expect("a table");
            out.push((name, law, it, table));
        }
    }
    out
}

fn grid(lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    let n = 20_000;
    let log = (0..=n).map(move |i| lo * (hi / lo).powf(i as f64 / n as f64));
    let uniform = (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64);
    log.chain(uniform)
}

/// Largest relative differences (af, af', a, a') of the table from the
/// solver; a' relative to the largest |a'| within a factor 1.01 of the
/// rotation (it passes through 0 when crushing starts in full contact).
fn worst(it: &Interface, table: &ContactTable) -> [f64; 4] {
    let (lo, hi) = table.range();
    let mut err = [0.0f64; 4];
    let mut served = 0;
    for phi in grid(lo, hi) {
        let Some(t) = table.contact(it, phi) else {
            continue;
        };
        served += 1;
        let c = it.contact(phi);
        assert_eq!(t.regime, c.regime, "regime at {phi}");
        let da_scale = [phi / 1.01, phi, phi * 1.01]
            .iter()
            .map(|&p| it.contact(p).da.abs())
            .fold(0.0, f64::max);
        for (e, (x, y, scale)) in err.iter_mut().zip([
            (t.af, c.af, c.af.abs()),
            (t.daf, c.daf, c.daf.abs()),
            (t.a, c.a, c.a.abs()),
            (t.da, c.da, da_scale),
        ]) {
            *e = e.max((x - y).abs() / scale);
        }
    }
    assert!(
        served > 36_000,
        "the table answered only {served} of 40 002 rotations"
    );
    err
}

#[test]
fn table_agrees_with_the_solve_on_dense_grids() {
    for (name, shape, w, ..) in bodies() {
        let rigid = Interface::new(shape, Law::Rigid, w);
        assert!(
            ContactTable::new(&rigid, PHI_MAX).is_none(),
            "{name}: rigid"
        );
    }
    for (name, law, it, table) in tables() {
        let (lo, hi) = table.range();
        // whole octaves from the first iterative regime, the last one
        // reaching PHI_MAX
        let phi0 = it.theta_jo().min(it.theta_c());
        let octaves = (hi / lo).log2();
        assert!(
            lo == phi0 && (PHI_MAX..2.0 * PHI_MAX).contains(&hi) && octaves == octaves.round(),
            "{name} {law:?}: range {lo}..{hi}"
        );
        let (pieces, open) = table.pieces();
        let err = worst(&it, &table);
        println!("{name:22} {law:?}: {pieces} pieces ({open} left to the solver), max rel. error af {:.1e}, af' {:.1e}, a {:.1e}, a' {:.1e}", err[0], err[1], err[2], err[3]);
        assert!(
            err[0] <= 1e-12 && err[2] <= 1e-12,
            "{name} {law:?}: af, a: {err:?}"
        );
        // the solver's own af' is good to 1e-10 (1e-9 beside an inner edge,
        // docs/interface.md), its a' to about 3e-8
        assert!(
            err[1] <= 2e-9 && err[3] <= 3e-7,
            "{name} {law:?}: af', a': {err:?}"
        );
    }
}

/// The Dharahara tower (docs/model.md §4) on an interface of stiffness `kn`
/// crushing at `fm`.
fn dharahara(kn: f64, fm: f64) -> rocking::Model {
    use rocking::model::{LawKind, MassKind, ShapeKind};
    let (w, hg, g, ro, ri) = (24_003.94e3, 30.2, 9.81, 3.99, 2.12);
    let m = w / g;
    rocking::Params {
        shape: ShapeKind::HollowCircle,
        ro,
        ri,
        mass_model: MassKind::Lumped,
        w,
        hg,
        ic: m * ((2.0 * hg) * (2.0 * hg) / 12.0 + (ro * ro + ri * ri) / 4.0),
        interface: if fm.is_finite() {
            LawKind::ElastoPlastic
        } else {
            LawKind::Elastic
        },
        kn,
        fm,
        g,
        ..rocking::Params::default()
    }
    .build()
    .expect("valid")
}

/// A two-cycle sine pulse of `amp` m/s² and period 1.5 s, as a master
/// passes it in steps of 0.01 s: `(t_end, ag, dag)`.
fn pulse(amp: f64) -> impl Iterator<Item = (f64, GroundInput)> {
    let ag = move |t: f64| {
        if t < 3.0 {
            amp * (2.0 * std::f64::consts::PI * t / 1.5).sin()
        } else {
            0.0
        }
    };
    (0..800).map(move |k| {
        let (t0, t1) = (0.01 * k as f64, 0.01 * (k + 1) as f64);
        let (a0, a1) = (ag(t0), ag(t1));
        (
            t1,
            GroundInput {
                ag: a0,
                dag: (a1 - a0) / 0.01,
            },
        )
    })
}

use rocking::dynamics::{GroundInput, Simulator, State};

fn run(sim: &Simulator, amp: f64) -> Vec<State> {
    let mut st = sim.initial_state(0.0, 0.0);
    let mut states = vec![st];
    for (t_end, input) in pulse(amp) {
        sim.advance(&mut st, t_end, input);
        states.push(st);
        if st.overturned {
            break;
        }
    }
    states
}

/// `reaction_bounded`'s bound on `a` (what the equation of motion under a
/// vertical input reads to show that a crushing bed has not crushed
/// without the contact's `a`) is at least the solver's `a`, and its `af`,
/// `af'` are the table's contact's, over every fourth rotation of the grids.
#[test]
fn the_table_bounds_a_from_above() {
    for (name, law, it, table) in tables() {
        let (lo, hi) = table.range();
        let (mut tightest, mut served) = (f64::INFINITY, 0);
        for phi in grid(lo, hi).step_by(4) {
            let Some((r, bound)) = table.reaction_bounded(&it, phi) else {
                continue;
            };
            let t = table.contact(&it, phi).expect("the same piece");
            assert!(r.af == t.af && r.daf == t.daf, "{name} {law:?} at {phi}");
            let a = it.contact(phi).a;
            assert!(
                bound >= a * (1.0 - 1e-12),
                "{name} {law:?} at {phi}: bound {bound} < a {a}"
            );
            tightest = tightest.min(bound / a - 1.0);
            served += 1;
        }
        println!("{name:22} {law:?}: {served} rotations, bound/a - 1 >= {tightest:.1e}");
        assert!(served > 9_000, "{name} {law:?}: {served} rotations");
    }
}

#[test]
fn the_integrator_takes_its_contacts_from_the_table_within_1e12_of_the_solve() {
    for (kn, fm) in [(85e6, 2e6), (15e9, f64::INFINITY), (15e9, 2e6)] {
        let model = dharahara(kn, fm);
        let sim = Simulator::new(model, 1e-9);
        let table = sim.contact_table().expect("a flexible law has a table");
        let (lo, _) = table.range();
        let mut served = 0;
        for st in run(&sim, 2.5) {
            let phi = st.theta.abs();
            let (c, solved) = (sim.contact(phi, f64::NAN), model.interface.contact(phi));
            if phi > lo && c.iterations == 0 && solved.iterations > 0 {
                served += 1;
            }
            let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE);
            // (at theta = 0 both have a = infinity: the closure is 0)
            let a_ok = (c.a == solved.a) || rel(c.a, solved.a) <= 1e-12;
            assert!(
                rel(c.af, solved.af) <= 1e-12 && a_ok,
                "kn {kn:e} fm {fm:e} at theta {}: af {} vs {}",
                st.theta,
                c.af,
                solved.af
            );
        }
        assert!(
            served > 50,
            "kn {kn:e} fm {fm:e}: table used {served} times"
        );
    }
}

#[test]
fn the_table_leaves_the_integrator_as_accurate_as_the_solve() {
    // The same pulse at rtol 1e-9 with contacts from the table and all
    // solved, each against a run at rtol 1e-12 (solved). A change of 1e-13
    // in af changes the steps the controller picks, so the two runs differ
    // at the level of the integrator's own error; the table must not make
    // that error larger (a table off by 1e-8 in af would, by orders).
    let max_diff = |a: &[State], b: &[State]| {
        assert_eq!(a.len(), b.len(), "overturning differs");
        let d = a.iter().zip(b).map(|(x, y)| (x.theta - y.theta).abs());
        d.fold(0.0, f64::max)
    };
    for (kn, fm) in [(85e6, 2e6), (15e9, f64::INFINITY), (15e9, 2e6)] {
        let model = dharahara(kn, fm);
        let tabled = Simulator::new(model, 1e-9);
        let mut solved = tabled.clone();
        solved.set_contact_table(false);
        assert!(solved.contact_table().is_none());
        let mut reference = Simulator::new(model, 1e-12);
        reference.set_contact_table(false);
        let (a, b, r) = (run(&tabled, 2.5), run(&solved, 2.5), run(&reference, 2.5));
        let (with_table, without) = (max_diff(&a, &r), max_diff(&b, &r));
        let ov = model.theta_ov;
        println!(
            "kn {kn:e} fm {fm:e}: error at rtol 1e-9 with the table {:.1e} thetaOv, without {:.1e}, between them {:.1e}",
            with_table / ov,
            without / ov,
            max_diff(&a, &b) / ov
        );
        assert!(
            with_table <= 3.0 * without,
            "kn {kn:e} fm {fm:e}: {with_table:e} rad vs {without:e}"
        );
        assert_eq!(a.last().unwrap().impacts, b.last().unwrap().impacts);
    }
}

#[test]
fn simulators_of_one_body_share_one_table() {
    let model = dharahara(85e6, 2e6);
    let (a, b) = (Simulator::new(model, 1e-9), Simulator::new(model, 1e-6));
    let other = Simulator::new(dharahara(86e6, 2e6), 1e-9);
    let ptr = |s: &Simulator| s.contact_table().map(|t| t as *const ContactTable);
    assert_eq!(ptr(&a), ptr(&b));
    assert_ne!(ptr(&a), ptr(&other));
}
