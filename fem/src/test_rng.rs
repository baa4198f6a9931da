//! A small deterministic generator for the crate's randomised tests (xorshift64* with
//! 53-bit output in [0, 1)): the tests need spread and reproducibility, not quality.

/// xorshift64* state (any nonzero seed).
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    /// The next number in [0, 1).
    pub(crate) fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}
