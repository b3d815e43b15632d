//! Seed derivation: one independent stream per work item, so results never depend on the
//! number of threads or the order in which work is scheduled (docs/model.md §11).

/// Purposes of derived streams (the first tag of every derivation).
pub mod purpose {
    /// Initial population.
    pub const INIT: u64 = 1;
    /// Breeding of generation `g` → `g + 1`.
    pub const BREED: u64 = 2;
    /// Evaluation of (generation, individual, room, trial).
    pub const EVAL: u64 = 3;
    /// AEM room instance runs.
    pub const AEM_INSTANCE: u64 = 4;
    /// AEM test runs.
    pub const AEM_TEST: u64 = 5;
    /// SOM training.
    pub const SOM: u64 = 6;
    /// Online-orientation extra runs.
    pub const ONLINE: u64 = 7;
    /// The seeds of a multi-seed study (`reproduce --seeds N`).
    pub const STUDY: u64 = 8;
    /// The draw of an evaluation trial's randomised robot (`[trial.randomise]`), derived from
    /// the trial's own seed.
    pub const RANDOMISE: u64 = 9;
}

/// The random streams of one experiment, all derived from its base seed: one named method per
/// stream, so the derivation tree (docs/model.md §11) is written down once. Every method returns
/// the seed of an independent stream; `run_tag` is [`crate::experiment::Run::tag`] and
/// `room_key` is [`hash_str`] of the room's name.
///
/// ```
/// use fuzzymotiv::random::Streams;
/// let s = Streams::new(1);
/// assert_ne!(s.initial_population(0), s.breeding(0, 0));
/// assert_eq!(s.study(0), 1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Streams {
    base: u64,
}

impl Streams {
    /// The streams of base seed `base`.
    pub const fn new(base: u64) -> Streams {
        Streams { base }
    }

    /// The base seed.
    pub const fn base(&self) -> u64 {
        self.base
    }

    /// The initial population of a run.
    pub fn initial_population(&self, run_tag: u64) -> u64 {
        derive(self.base, &[purpose::INIT, run_tag])
    }

    /// The evaluation trial of `individual` of `generation` in a room.
    pub fn evaluation(
        &self,
        run_tag: u64,
        generation: usize,
        individual: usize,
        room_key: u64,
    ) -> u64 {
        derive(
            self.base,
            &[
                purpose::EVAL,
                run_tag,
                generation as u64,
                individual as u64,
                room_key,
                0,
            ],
        )
    }

    /// The second (online-orientation) trial of `individual` of `generation` in a room.
    pub fn online(&self, run_tag: u64, generation: usize, individual: usize, room_key: u64) -> u64 {
        derive(
            self.base,
            &[
                purpose::ONLINE,
                run_tag,
                generation as u64,
                individual as u64,
                room_key,
                1,
            ],
        )
    }

    /// Breeding of generation `generation` → `generation + 1`.
    pub fn breeding(&self, run_tag: u64, generation: usize) -> u64 {
        derive(self.base, &[purpose::BREED, run_tag, generation as u64])
    }

    /// The AEM instance run in a room (the run whose actions become the room's instance).
    pub fn aem_instance(&self, run_tag: u64, room_key: u64) -> u64 {
        derive(self.base, &[purpose::AEM_INSTANCE, run_tag, room_key])
    }

    /// AEM test run `test` in a room.
    pub fn aem_test(&self, run_tag: u64, room_key: u64, test: usize) -> u64 {
        derive(
            self.base,
            &[purpose::AEM_TEST, run_tag, room_key, test as u64],
        )
    }

    /// SOM training of a run.
    pub fn som(&self, run_tag: u64) -> u64 {
        derive(self.base, &[purpose::SOM, run_tag])
    }

    /// Seed `k` of a multi-seed study from this base ([`study_seed`]).
    pub fn study(&self, k: usize) -> u64 {
        study_seed(self.base, k)
    }

    /// The base seed of sweep job `key` (`SETTING;rep=R`), kept below 2^53 so that it is exact
    /// in TOML and in JSON read as doubles.
    pub fn sweep_job(&self, key: &str) -> u64 {
        derive(self.base, &[hash_str(key)]) >> 11
    }
}

/// Largest integer every JSON reader keeps exactly (JavaScript and jq read numbers as doubles).
pub const JSON_EXACT: u64 = (1 << 53) - 1;

/// Seed `k` of a study of several seeds from `base`: seed 0 is `base` itself (so a one-seed
/// study is the plain run), seed k ≥ 1 is derived from `base` and `k` and kept below 2^53 so
/// that it survives any JSON reader.
///
/// ```
/// use fuzzymotiv::random::{study_seed, JSON_EXACT};
/// assert_eq!(study_seed(1, 0), 1);
/// assert_ne!(study_seed(1, 1), study_seed(1, 2));
/// assert!(study_seed(1, 1) <= JSON_EXACT);
/// ```
pub fn study_seed(base: u64, k: usize) -> u64 {
    if k == 0 {
        base
    } else {
        derive(base, &[purpose::STUDY, k as u64]) & JSON_EXACT
    }
}

/// SplitMix64's finaliser: a bijective 64-bit mixer.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A seed derived from `base` and a path of tags, e.g.
/// `derive(seed, &[purpose::EVAL, run, generation, individual, room, trial])`.
///
/// ```
/// use fuzzymotiv::random::derive;
/// assert_ne!(derive(1, &[3, 0, 1]), derive(1, &[3, 1, 0]));
/// assert_eq!(derive(1, &[3, 0, 1]), derive(1, &[3, 0, 1]));
/// ```
pub fn derive(base: u64, tags: &[u64]) -> u64 {
    let mut h = mix64(base);
    for &t in tags {
        h = mix64(h ^ mix64(t.wrapping_add(0xD6E8_FEB8_6659_FD93)));
    }
    h
}

/// A stable 64-bit hash of a string (FNV-1a, then mixed), for keys such as room names.
pub fn hash_str(s: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in s.bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    mix64(h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_stability() {
        // Pinned: a change here changes every result of the program.
        assert_eq!(mix64(0), 0xE220_A839_7B1D_CDAF);
        assert_eq!(derive(42, &[]), mix64(42));
        assert_eq!(hash_str(""), mix64(0xcbf2_9ce4_8422_2325));
    }

    // One pinned value per stream (computed once from the inline derivations these methods
    // replaced): a change here changes every result of the program.
    const S: Streams = Streams::new(42);

    #[test]
    fn stream_initial_population() {
        assert_eq!(S.initial_population(7), 0x7B28_0CDF_2B1F_1486);
    }

    #[test]
    fn stream_evaluation() {
        assert_eq!(S.evaluation(7, 3, 5, hash_str("T")), 0x8E11_7317_FE60_8E45);
    }

    #[test]
    fn stream_online() {
        assert_eq!(S.online(7, 3, 5, hash_str("T")), 0x35E1_FD26_02A7_C31A);
    }

    #[test]
    fn stream_breeding() {
        assert_eq!(S.breeding(7, 3), 0x068E_04C4_6139_D54C);
    }

    #[test]
    fn stream_aem_instance() {
        assert_eq!(S.aem_instance(7, hash_str("T")), 0xF064_FC02_76D9_F8A5);
    }

    #[test]
    fn stream_aem_test() {
        assert_eq!(S.aem_test(7, hash_str("T"), 9), 0x37BB_123F_1D3A_2021);
    }

    #[test]
    fn stream_som() {
        assert_eq!(S.som(7), 0x5D49_E98F_9DA8_2F06);
    }

    #[test]
    fn stream_study() {
        assert_eq!(S.study(0), 42);
        assert_eq!(S.study(3), 0x0009_4971_308E_F01D);
    }

    #[test]
    fn stream_sweep_job() {
        assert_eq!(S.sweep_job("base;rep=0"), 0x0013_D055_A9CD_92BC);
    }
}
