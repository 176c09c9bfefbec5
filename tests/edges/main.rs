//! The model at the edges of its parameter space, against independent
//! references:
//!
//! - the absolute time does not matter: a run that starts at `t0 = 1e9 s`
//!   is the run that starts at 0 (regression: at large `t0` the step
//!   controller hung, or missed the passage through a stiff contact zone);
//!   `advance_to_event` goes on after an uplift (regression: it stalled);
//! - kn -> infinity: elastic and crushing interfaces tend to rigid
//!   solutions (Housner; a rigid block about the plastic pivot), with
//!   measured rates;
//! - fm -> W/A: the capacity (b - af_limit, thetaOv, the peak restoring
//!   moment) vanishes linearly, against the closed form of a solid
//!   rectangle.

//!
//! One module per edge: `start_time`, `stiff_limit` (kn -> infinity) and
//! `crushing_limit` (fm -> W/A).

mod crushing_limit;
mod start_time;
mod stiff_limit;
