//! Which instructions the hot loops are compiled for, detected at run time.

/// Which instructions a loop (a trial's steps, the lanes, a look's rays, the SOM) is compiled
/// for. Both forms run the same IEEE-754 operations in the same order (no fused multiply-add:
/// Rust never contracts `a * b + c`, and `avx2` does not enable FMA), so every result has the
/// same bits; AVX2 only does more lanes per instruction (the network's six hidden units in two
/// vector operations instead of three) and has three-operand forms that save register copies.
/// The one use of FMA, by name, is the lanes' rough network, whose outputs only choose actions
/// that the exact outputs would choose ([`crate::simulation::lanes`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Isa {
    /// The build's baseline (x86-64: SSE2).
    Baseline,
    /// x86-64 with AVX2 and FMA, when the processor has both (checked at run time; every
    /// processor with AVX2 made so far also has FMA). Only the lanes' rough network uses FMA,
    /// for a value that chooses nothing by itself ([`crate::simulation::lanes`]).
    #[cfg(target_arch = "x86_64")]
    Avx2,
}

impl Isa {
    /// The best form this processor runs.
    #[inline]
    pub(crate) fn detected() -> Isa {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            return Isa::Avx2;
        }
        Isa::Baseline
    }
}
