//! Property tests over random valid geometries and materials (docs/model.md §2):
//! no NaN, no panic, af within [0, D/2], af non-increasing, af' <= 0,
//! af' consistent with af, and equilibrium by an independent quadrature.
//! 256 cases by default; more with `PROPTEST_CASES`.

mod support;

use proptest::prelude::*;
use rocking::{Interface, Shape};
use support::base::{law, resultants};

fn shape_strategy() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (0.1f64..100.0, 0.1f64..100.0).prop_map(|(b, l)| Shape::SolidRectangle { b, l }),
        (0.1f64..100.0, 0.1f64..100.0, 0.01f64..0.49).prop_map(|(b, l, f)| {
            Shape::HollowRectangle {
                b,
                l,
                t: f * b.min(l),
            }
        }),
        (0.05f64..50.0).prop_map(|ro| Shape::SolidCircle { ro }),
        (0.05f64..50.0, 0.01f64..0.99).prop_map(|(ro, f)| Shape::HollowCircle { ro, ri: f * ro }),
    ]
}

proptest! {
    #[test]
    fn af_stays_within_the_base_decreases_and_carries_the_weight(
        shape in shape_strategy(),
        stress in 1e3f64..1e7,       // W/A, Pa
        kn_exp in 6.0f64..15.0,      // kn = 10^kn_exp Pa/m
        fm_ratio in prop_oneof![Just(f64::INFINITY), 1.01f64..50.0], // fm / (W/A)
        theta_exp in -9.0f64..0.0,
    ) {
        let w = stress * shape.area();
        let kn = 10f64.powf(kn_exp);
        let fm = fm_ratio * stress;
        let it = Interface::new(shape, law(kn, fm), w);
        let d = shape.depth();
        prop_assert!(it.theta_jo() > 0.0 && it.theta_jo().is_finite());
        prop_assert!(it.theta_c() > 0.0);
        let th = 10f64.powf(theta_exp);
        let c = it.contact(th);
        let c2 = it.contact(th * 1.01);
        for v in [c.af, c.daf, c.a, c.contact_length, c2.af] {
            prop_assert!(!v.is_nan());
        }
        prop_assert!(c.af >= 0.0 && c.af <= d / 2.0 * (1.0 + 1e-15), "af {} D {}", c.af, d);
        prop_assert!(c.daf <= 0.0);
        prop_assert!(c2.af <= c.af * (1.0 + 1e-13), "af grows: {} -> {}", c.af, c2.af);
        // af' against the secant over [th, 1.01 th]: af is C1 and its
        // derivative is monotone within a regime, so the secant lies between
        // the end derivatives (with rounding slack).
        let sec = (c2.af - c.af) / (0.01 * th);
        let lo = c.daf.min(c2.daf);
        let hi = c.daf.max(c2.daf);
        let slack = 1e-9 * lo.abs() + 1e-12 * c.af / (0.01 * th);
        if c.regime == c2.regime {
            prop_assert!(sec >= lo - slack && sec <= hi + slack, "secant {sec} not in [{lo}, {hi}]");
        }
        // equilibrium by quadrature between the kinks of the stress and the
        // width (a midpoint sum across the jumps of a thin hollow
        // rectangle's width errs by up to 1.2e-4): the bound is the contact
        // solve's, as in tests/interface.rs; measured at most 1.7e-13 over
        // 20 000 cases (median 2.2e-16)
        let [n, _] = resultants(&shape, kn, fm, th, c.a);
        prop_assert!((n - w).abs() < 1e-12 * w, "N = {n} vs W = {w}");
    }
}

proptest! {
    /// The contact under a bed resultant `n` other than the weight (docs/model.md
    /// §6.1), solved from a warm start anywhere (the regime of the warm start is
    /// tried first and kept only where the solve converges inside it): its `a`
    /// carries `n` and its `af` is the stress's moment over `n`, by an independent
    /// quadrature, as the unwarmed solve's does.
    #[test]
    fn the_loaded_contact_carries_n_from_any_warm_start(
        shape in shape_strategy(),
        stress in 1e3f64..1e7,
        kn_exp in 6.0f64..15.0,
        fm_ratio in prop_oneof![Just(f64::INFINITY), 1.01f64..50.0],
        theta_exp in -9.0f64..0.0,
        n_ratio in 0.05f64..1.9,      // n / W, below fm A / W
        hint_ratio in prop_oneof![Just(f64::NAN), 1e-3f64..1e3], // warm start / D
    ) {
        let w = stress * shape.area();
        let kn = 10f64.powf(kn_exp);
        let fm = fm_ratio * stress;
        prop_assume!(n_ratio * w < fm * shape.area());
        let it = Interface::new(shape, law(kn, fm), w);
        let (th, n) = (10f64.powf(theta_exp), n_ratio * w);
        let (c, _) = it.contact_loaded(th, n, hint_ratio * shape.depth());
        let (cold, _) = it.contact_loaded(th, n, f64::NAN);
        let [nq, mq] = resultants(&shape, kn, fm, th, c.a);
        prop_assert!((nq - n).abs() < 1e-12 * n, "N = {nq} vs {n}");
        prop_assert!((c.af - mq / nq).abs() <= 1e-11 * c.af.abs().max(1e-12 * shape.depth()),
            "af {} vs {}", c.af, mq / nq);
        prop_assert!((c.af - cold.af).abs() <= 1e-12 * cold.af.abs().max(1e-12 * shape.depth()),
            "af {} warm vs {} cold", c.af, cold.af);
    }
}
