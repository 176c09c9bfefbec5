//! A small linear congruential generator (Knuth's MMIX constants): a random
//! sweep that is the same every run, for the stress tests
//! (`fmu-rocking/tests/stress_c_api.rs` includes this file with `#[path]`).

/// The generator; its state is the seed.
pub struct Lcg(pub u64);

impl Lcg {
    /// Uniform in [0, 1), 53 bits.
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Log-uniform in [lo, hi).
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + self.next() * (hi.ln() - lo.ln())).exp()
    }

    /// One of `xs`, each as likely.
    pub fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[((self.next() * xs.len() as f64) as usize).min(xs.len() - 1)]
    }
}
