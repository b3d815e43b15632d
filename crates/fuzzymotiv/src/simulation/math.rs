//! The project's own `exp`, `sin` and `cos`: the elementary functions of the step loop.
//!
//! They are written with `+ − × ÷` and bit operations only (no libm call, no fused
//! multiply–add), so they give the same bits on every IEEE-754 platform with the default
//! round-to-nearest mode, whatever the system's libm. `exp` is table-driven like glibc's and
//! musl's current one (without their fused multiply–adds): Cody–Waite reduction
//! `x = (128 m + j)·ln 2/128 + r`, `|r| ≤ ln 2/256`, a 128-entry table of `2^(j/128)` as
//! double-doubles and a degree-5 polynomial, no division. `sin`/`cos` are fdlibm's (Sun
//! Microsystems, 1993, as kept in FreeBSD and musl): reduction modulo π/2 in up to three
//! Cody–Waite steps and degree-13/14 minimax polynomials on `[−π/4, π/4]`.
//!
//! Error bounds (measured against the platform's libm over millions of points by this module's
//! tests, which fail above them):
//!
//! | function | valid range | bound |
//! |---|---|---|
//! | [`exp`] | all `f64` (overflow to `+∞` above 709.78, `0` below −745.13) | ≤ 1 ulp (normal results) |
//! | [`sin`], [`cos`], [`sin_cos`] | `|x| ≤ 10⁶` (NaN outside) | ≤ 1 ulp |
//! | [`logistic`] | all `f64` | ≤ 4 ulp from `1/(1 + libm exp(−x))` (an `exp` error of 1 ulp is up to 2 ulp of the quotient) |

/// 1.5 · 2⁵²: adding and subtracting it rounds a double of magnitude < 2⁵¹ to the nearest
/// integer (ties to even) without a libm `round` call.
pub(crate) const TO_INT: f64 = 6_755_399_441_055_744.0;

const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
/// 128 / ln 2.
pub(crate) const INV_LN2_N: f64 = f64::from_bits(0x4067_1547_652b_82fe);
/// ln 2 / 128 in two parts; the first has 32 significant bits, so `k · LN2_HI_N` is exact for
/// `|k| < 2²¹`.
pub(crate) const LN2_HI_N: f64 = LN2_HI / 128.0;
pub(crate) const LN2_LO_N: f64 = LN2_LO / 128.0;
/// Largest `x` with `exp(x)` finite.
pub(crate) const EXP_MAX: f64 = f64::from_bits(0x4086_2e42_fefa_39ef);
/// Below this `exp(x)` rounds to 0.
pub(crate) const EXP_MIN: f64 = f64::from_bits(0xc087_4910_d52d_3051);

/// `2^(j/128)` for `j = 0..128` as the correctly rounded double `hi` and the rounded
/// remainder `lo = 2^(j/128) − hi` (bit patterns; generated with 80-digit decimal arithmetic).
pub(crate) const EXP2_TABLE: [(u64, u64); 128] = [
    (0x3ff0000000000000, 0x0000000000000000),
    (0x3ff0163da9fb3335, 0x3c9b61299ab8cdb7),
    (0x3ff02c9a3e778061, 0xbc719083535b085d),
    (0x3ff04315e86e7f85, 0xbc90a31c1977c96e),
    (0x3ff059b0d3158574, 0x3c8d73e2a475b465),
    (0x3ff0706b29ddf6de, 0xbc8c91dfe2b13c27),
    (0x3ff0874518759bc8, 0x3c6186be4bb284ff),
    (0x3ff09e3ecac6f383, 0x3c91487818316136),
    (0x3ff0b5586cf9890f, 0x3c98a62e4adc610b),
    (0x3ff0cc922b7247f7, 0x3c901edc16e24f71),
    (0x3ff0e3ec32d3d1a2, 0x3c403a1727c57b53),
    (0x3ff0fb66affed31b, 0xbc6b9bedc44ebd7b),
    (0x3ff11301d0125b51, 0xbc96c51039449b3a),
    (0x3ff12abdc06c31cc, 0xbc51b514b36ca5c7),
    (0x3ff1429aaea92de0, 0xbc932fbf9af1369e),
    (0x3ff15a98c8a58e51, 0x3c82406ab9eeab0a),
    (0x3ff172b83c7d517b, 0xbc819041b9d78a76),
    (0x3ff18af9388c8dea, 0xbc911023d1970f6c),
    (0x3ff1a35beb6fcb75, 0x3c8e5b4c7b4968e4),
    (0x3ff1bbe084045cd4, 0xbc995386352ef607),
    (0x3ff1d4873168b9aa, 0x3c9e016e00a2643c),
    (0x3ff1ed5022fcd91d, 0xbc91df98027bb78c),
    (0x3ff2063b88628cd6, 0x3c8dc775814a8495),
    (0x3ff21f49917ddc96, 0x3c82a97e9494a5ee),
    (0x3ff2387a6e756238, 0x3c99b07eb6c70573),
    (0x3ff251ce4fb2a63f, 0x3c8ac155bef4f4a4),
    (0x3ff26b4565e27cdd, 0x3c82bd339940e9d9),
    (0x3ff284dfe1f56381, 0xbc9a4c3a8c3f0d7e),
    (0x3ff29e9df51fdee1, 0x3c8612e8afad1255),
    (0x3ff2b87fd0dad990, 0xbc410adcd6381aa4),
    (0x3ff2d285a6e4030b, 0x3c90024754db41d5),
    (0x3ff2ecafa93e2f56, 0x3c71ca0f45d52383),
    (0x3ff306fe0a31b715, 0x3c86f46ad23182e4),
    (0x3ff32170fc4cd831, 0x3c8a9ce78e18047c),
    (0x3ff33c08b26416ff, 0x3c932721843659a6),
    (0x3ff356c55f929ff1, 0xbc8b5cee5c4e4628),
    (0x3ff371a7373aa9cb, 0xbc963aeabf42eae2),
    (0x3ff38cae6d05d866, 0xbc9e958d3c9904bd),
    (0x3ff3a7db34e59ff7, 0xbc75e436d661f5e3),
    (0x3ff3c32dc313a8e5, 0xbc9efff8375d29c3),
    (0x3ff3dea64c123422, 0x3c8ada0911f09ebc),
    (0x3ff3fa4504ac801c, 0xbc97d023f956f9f3),
    (0x3ff4160a21f72e2a, 0xbc5ef3691c309278),
    (0x3ff431f5d950a897, 0xbc81c7dde35f7999),
    (0x3ff44e086061892d, 0x3c489b7a04ef80d0),
    (0x3ff46a41ed1d0057, 0x3c9c944bd1648a76),
    (0x3ff486a2b5c13cd0, 0x3c73c1a3b69062f0),
    (0x3ff4a32af0d7d3de, 0x3c99cb62f3d1be56),
    (0x3ff4bfdad5362a27, 0x3c7d4397afec42e2),
    (0x3ff4dcb299fddd0d, 0x3c98ecdbbc6a7833),
    (0x3ff4f9b2769d2ca7, 0xbc94b309d25957e3),
    (0x3ff516daa2cf6642, 0xbc8f768569bd93ef),
    (0x3ff5342b569d4f82, 0xbc807abe1db13cad),
    (0x3ff551a4ca5d920f, 0xbc8d689cefede59b),
    (0x3ff56f4736b527da, 0x3c99bb2c011d93ad),
    (0x3ff58d12d497c7fd, 0x3c8295e15b9a1de8),
    (0x3ff5ab07dd485429, 0x3c96324c054647ad),
    (0x3ff5c9268a5946b7, 0x3c3c4b1b816986a2),
    (0x3ff5e76f15ad2148, 0x3c9ba6f93080e65e),
    (0x3ff605e1b976dc09, 0xbc93e2429b56de47),
    (0x3ff6247eb03a5585, 0xbc9383c17e40b497),
    (0x3ff6434634ccc320, 0xbc8c483c759d8933),
    (0x3ff6623882552225, 0xbc9bb60987591c34),
    (0x3ff68155d44ca973, 0x3c6038ae44f73e65),
    (0x3ff6a09e667f3bcd, 0xbc9bdd3413b26456),
    (0x3ff6c012750bdabf, 0xbc72895667ff0b0d),
    (0x3ff6dfb23c651a2f, 0xbc6bbe3a683c88ab),
    (0x3ff6ff7df9519484, 0xbc883c0f25860ef6),
    (0x3ff71f75e8ec5f74, 0xbc816e4786887a99),
    (0x3ff73f9a48a58174, 0xbc90a8d96c65d53c),
    (0x3ff75feb564267c9, 0xbc90245957316dd3),
    (0x3ff780694fde5d3f, 0x3c9866b80a02162d),
    (0x3ff7a11473eb0187, 0xbc841577ee04992f),
    (0x3ff7c1ed0130c132, 0x3c9f124cd1164dd6),
    (0x3ff7e2f336cf4e62, 0x3c705d02ba15797e),
    (0x3ff80427543e1a12, 0xbc927c86626d972b),
    (0x3ff82589994cce13, 0xbc9d4c1dd41532d8),
    (0x3ff8471a4623c7ad, 0xbc88d684a341cdfb),
    (0x3ff868d99b4492ed, 0xbc9fc6f89bd4f6ba),
    (0x3ff88ac7d98a6699, 0x3c9994c2f37cb53a),
    (0x3ff8ace5422aa0db, 0x3c96e9f156864b27),
    (0x3ff8cf3216b5448c, 0xbc70d55e32e9e3aa),
    (0x3ff8f1ae99157736, 0x3c85cc13a2e3976c),
    (0x3ff9145b0b91ffc6, 0xbc9dd6792e582524),
    (0x3ff93737b0cdc5e5, 0xbc675fc781b57ebc),
    (0x3ff95a44cbc8520f, 0xbc764b7c96a5f039),
    (0x3ff97d829fde4e50, 0xbc9d185b7c1b85d1),
    (0x3ff9a0f170ca07ba, 0xbc9173bd91cee632),
    (0x3ff9c49182a3f090, 0x3c7c7c46b071f2be),
    (0x3ff9e86319e32323, 0x3c7824ca78e64c6e),
    (0x3ffa0c667b5de565, 0xbc9359495d1cd533),
    (0x3ffa309bec4a2d33, 0x3c96305c7ddc36ab),
    (0x3ffa5503b23e255d, 0xbc9d2f6edb8d41e1),
    (0x3ffa799e1330b358, 0x3c9bcb7ecac563c7),
    (0x3ffa9e6b5579fdbf, 0x3c90fac90ef7fd31),
    (0x3ffac36bbfd3f37a, 0xbc8f9234cae76cd0),
    (0x3ffae89f995ad3ad, 0x3c97a1cd345dcc81),
    (0x3ffb0e07298db666, 0xbc9bdef54c80e425),
    (0x3ffb33a2b84f15fb, 0xbc62805e3084d708),
    (0x3ffb59728de5593a, 0xbc9c71dfbbba6de3),
    (0x3ffb7f76f2fb5e47, 0xbc75584f7e54ac3b),
    (0x3ffba5b030a1064a, 0xbc9efcd30e54292e),
    (0x3ffbcc1e904bc1d2, 0x3c823dd07a2d9e84),
    (0x3ffbf2c25bd71e09, 0xbc9efdca3f6b9c73),
    (0x3ffc199bdd85529c, 0x3c811065895048dd),
    (0x3ffc40ab5fffd07a, 0x3c9b4537e083c60a),
    (0x3ffc67f12e57d14b, 0x3c92884dff483cad),
    (0x3ffc8f6d9406e7b5, 0x3c71acbc48805c44),
    (0x3ffcb720dcef9069, 0x3c7503cbd1e949db),
    (0x3ffcdf0b555dc3fa, 0xbc8dd83b53829d72),
    (0x3ffd072d4a07897c, 0xbc9cbc3743797a9c),
    (0x3ffd2f87080d89f2, 0xbc9d487b719d8578),
    (0x3ffd5818dcfba487, 0x3c82ed02d75b3707),
    (0x3ffd80e316c98398, 0xbc911ec18beddfe8),
    (0x3ffda9e603db3285, 0x3c9c2300696db532),
    (0x3ffdd321f301b460, 0x3c92da5778f018c3),
    (0x3ffdfc97337b9b5f, 0xbc91a5cd4f184b5c),
    (0x3ffe264614f5a129, 0xbc97b627817a1496),
    (0x3ffe502ee78b3ff6, 0x3c839e8980a9cc8f),
    (0x3ffe7a51fbc74c83, 0x3c92d522ca0c8de2),
    (0x3ffea4afa2a490da, 0xbc9e9c23179c2893),
    (0x3ffecf482d8e67f1, 0xbc9c93f3b411ad8c),
    (0x3ffefa1bee615a27, 0x3c9dc7f486a4b6b0),
    (0x3fff252b376bba97, 0x3c93a1a5bf0d8e43),
    (0x3fff50765b6e4540, 0x3c99d3e12dd8a18b),
    (0x3fff7bfdad9cbe14, 0xbc9dbb12d006350a),
    (0x3fffa7c1819e90d8, 0x3c874853f3a5931e),
    (0x3fffd3c22b8f71f1, 0x3c62eb74966579e7),
];

/// `2^k` for `−1022 ≤ k ≤ 1023`.
#[inline]
fn pow2(k: i64) -> f64 {
    f64::from_bits(((0x3ff + k) as u64) << 52)
}

/// `exp(x) = y · 2^m`, `y ∈ [1, 2)`, for `|x| ≤ 746`: `x = (128 m + j) · ln 2 / 128 + r`,
/// `|r| ≤ ln 2 / 256`, `y = 2^(j/128) · e^r` with the table and a degree-5 Taylor polynomial
/// of `e^r − 1` (truncation error < 6·10⁻¹⁹).
#[inline]
fn exp_parts(x: f64) -> (f64, i64) {
    let (k, r) = reduce(x);
    (table_poly(k, r), k >> 7)
}

/// `x = k · ln 2 / 128 + r` for `|x| ≤ 746`: `k` the integer nearest `x · 128 / ln 2`, `r` the
/// remainder, taken off in two parts.
#[inline(always)]
fn reduce(x: f64) -> (i64, f64) {
    let t = x * INV_LN2_N + TO_INT;
    let kd = t - TO_INT;
    // `t` is an integer in [2⁵², 2⁵³), as `TO_INT` is: their bit patterns differ by `kd`, which
    // gives `kd as i64` without a float-to-integer conversion (which has no vector form in SSE2).
    let k = t.to_bits() as i64 - TO_INT.to_bits() as i64;
    (k, (x - kd * LN2_HI_N) - kd * LN2_LO_N)
}

/// `2^(j/128) · e^r` for `j = k mod 128`, from the table and the polynomial.
#[inline(always)]
fn table_poly(k: i64, r: f64) -> f64 {
    let (hi, lo) = EXP2_TABLE[(k & 127) as usize];
    let (hi, lo) = (f64::from_bits(hi), f64::from_bits(lo));
    let p = r + r * r * (0.5 + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0))));
    hi + (lo + hi * p)
}

/// `e^x`, within 1 ulp of libm's for every normal result (table-driven, no division: see
/// the module notes); `+∞` above 709.78, `0` below −745.13, subnormal results in between with one
/// final rounding. Valid for every `f64`, NaN gives NaN.
#[inline]
pub fn exp(x: f64) -> f64 {
    if x.abs() <= 708.0 {
        let (y, k) = exp_parts(x);
        // 2^k is normal for −1022 ≤ k ≤ 1021 and y·2^k stays normal: the product is exact.
        return y * pow2(k);
    }
    exp_edge(x)
}

/// [`exp`] outside `[−708, 708]`: overflow, underflow and NaN.
#[cold]
fn exp_edge(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    if x > EXP_MAX {
        return f64::INFINITY;
    }
    if x < EXP_MIN {
        return 0.0;
    }
    // 2^k in two normal factors: the first product is exact, the second rounds once.
    let (y, k) = exp_parts(x);
    let k1 = k / 2;
    y * pow2(k1) * pow2(k - k1)
}

/// The logistic function `1 / (1 + e^(−x))` with the project's [`exp`]: within 4 ulp of the
/// same formula with libm's `exp` (measured on `[−60, 60]`; one ulp of `exp` is up to two of
/// the quotient), exactly 1 for `x > 37.5` and 0 for `x < −709.78`. Valid for every `f64`.
#[inline]
pub fn logistic(x: f64) -> f64 {
    1.0 / (1.0 + exp(-x))
}

/// `logistic` of each lane: the same operations in the same order, so the same bits in
/// every lane, written stage by stage across the lanes so that the compiler can do each stage
/// for several lanes in one vector instruction (the table look-up stays one load per lane).
/// Lanes with `|x| > 708` or NaN send the whole call to the scalar function.
#[inline(always)]
pub fn logistic_lanes<const L: usize>(x: [f64; L]) -> [f64; L] {
    if !x.iter().all(|v| v.abs() <= 708.0) {
        return x.map(logistic);
    }
    // Plain loops over the lanes, not `array::map`: whether a map's closure is inlined into
    // the network's step depends on how the crate is split into codegen units, and one that is
    // not costs a fifth of the step loop's time.
    let (mut k, mut r) = ([0i64; L], [0.0; L]);
    for l in 0..L {
        (k[l], r[l]) = reduce(-x[l]);
    }
    let mut y = [0.0; L];
    for l in 0..L {
        y[l] = table_poly(k[l], r[l]);
    }
    // |k| ≤ 130 743 (708 · 128 / ln 2, rounded) < 1023 · 128, so the shifted sum is
    // `(k >> 7) + 0x3ff` in 1..=2044, a normal exponent, shifted logically (arithmetic 64-bit
    // shifts have no vector form here).
    let mut out = [0.0; L];
    for l in 0..L {
        let scale = f64::from_bits((((k[l] + 0x3ff * 128) as u64) >> 7) << 52);
        out[l] = 1.0 / (1.0 + y[l] * scale);
    }
    out
}

/// Largest distance of [`logistic_rough_lanes`] from [`logistic`], with room to spare: the
/// analysis gives 1.2·10⁻⁶ and the module's test fails above a quarter of this bound.
pub(crate) const LOGISTIC_ROUGH_ERR: f64 = 6e-6;

/// A rough [`logistic`] of each lane in single precision, within [`LOGISTIC_ROUGH_ERR`] of
/// the exact one of the same argument for every `f32` (NaN for NaN), in a few vector
/// instructions per eight lanes: no table, no branch, no division but the last.
/// `e^(−x) = 2^t`, `t = −x·log₂e` clamped to ±60 (beyond, both functions are within
/// 2⁻⁶⁰ ≈ 10⁻¹⁸ of 0 or 1), is split into `2^k · 2^f` with `k` the integer nearest `t`,
/// `|f| ≤ ½`, and `2^f = e^(f·ln 2)` is a degree-5 Taylor polynomial: its relative error is
/// under 3.4·10⁻⁶, the dozen single-precision roundings (`u` = 2⁻²⁴ each) add about 8·10⁻⁷,
/// and the logistic's slope `σ(1 − σ) ≤ ¼` turns the sum into 1.1·10⁻⁶, and the last
/// roundings into 1.2·10⁻⁶. (`t`'s own rounding, up to 60·u, matters only where `σ(1 − σ)`
/// is small.) For a decision taken on the value with a margin wider than the error, never for
/// a number that is kept: the lanes choose an action with it when no exact value could choose
/// another ([`crate::simulation::lanes`]).
#[inline(always)]
pub(crate) fn logistic_rough_lanes<const L: usize>(x: [f32; L]) -> [f32; L] {
    // 1.5·2²³: adding it rounds a number of magnitude below 2²² to an integer.
    const TO_INT: f32 = 12_582_912.0;
    let mut out = [0.0; L];
    for l in 0..L {
        let t = (-x[l] * std::f32::consts::LOG2_E).clamp(-60.0, 60.0);
        let s = t + TO_INT;
        let f = (t - (s - TO_INT)) * std::f32::consts::LN_2;
        let p =
            1.0 + f * (1.0 + f * (0.5 + f * (1.0 / 6.0 + f * (1.0 / 24.0 + f * (1.0 / 120.0)))));
        // `k` from the bits of `s` (one binade, so the bits count whole numbers); `2^k` is
        // normal for |k| ≤ 60.
        let k = s.to_bits().wrapping_sub(TO_INT.to_bits());
        out[l] = 1.0 / (1.0 + p * f32::from_bits(k.wrapping_add(127) << 23));
    }
    out
}

/// [`logistic_rough_lanes`] of eight lanes in AVX2 and FMA instructions, arranged for a short
/// chain of dependent steps (the lanes wait for it every step): the polynomial in
/// `g = t − k` (`2^g = e^(g·ln 2)`, the powers of ln 2 in its coefficients) by Estrin's scheme,
/// `(c₀ + c₁g) + g²·(c₂ + c₃g) + g⁴·(c₄ + c₅g)`, its products and sums fused, and
/// `1 + p · 2^k` fused. The same truncation as there, no more roundings, so within the same
/// bound. Inputs of NaN give NaN, as there.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
pub(crate) fn logistic_rough_avx2(x: std::arch::x86_64::__m256) -> std::arch::x86_64::__m256 {
    use std::arch::x86_64::{
        _mm256_add_epi32, _mm256_add_ps, _mm256_castps_si256, _mm256_castsi256_ps, _mm256_div_ps,
        _mm256_fmadd_ps, _mm256_max_ps, _mm256_min_ps, _mm256_mul_ps, _mm256_set1_epi32,
        _mm256_set1_ps, _mm256_slli_epi32, _mm256_sub_epi32, _mm256_sub_ps,
    };
    use std::f64::consts::LN_2;
    const TO_INT: f32 = 12_582_912.0;
    // `ln 2^i / i!`, rounded once.
    const C: [f32; 6] = [
        1.0,
        LN_2 as f32,
        (LN_2 * LN_2 / 2.0) as f32,
        (LN_2 * LN_2 * LN_2 / 6.0) as f32,
        (LN_2 * LN_2 * LN_2 * LN_2 / 24.0) as f32,
        (LN_2 * LN_2 * LN_2 * LN_2 * LN_2 / 120.0) as f32,
    ];
    let c = _mm256_set1_ps;
    let t = _mm256_mul_ps(x, c(-std::f32::consts::LOG2_E));
    // `t` second: `max` and `min` return their second operand when one is NaN.
    let t = _mm256_min_ps(c(60.0), _mm256_max_ps(c(-60.0), t));
    let s = _mm256_add_ps(t, c(TO_INT));
    let g = _mm256_sub_ps(t, _mm256_sub_ps(s, c(TO_INT)));
    let g2 = _mm256_mul_ps(g, g);
    let low = _mm256_fmadd_ps(c(C[1]), g, c(C[0]));
    let mid = _mm256_fmadd_ps(c(C[3]), g, c(C[2]));
    let high = _mm256_fmadd_ps(c(C[5]), g, c(C[4]));
    let p = _mm256_fmadd_ps(high, _mm256_mul_ps(g2, g2), _mm256_fmadd_ps(mid, g2, low));
    let k = _mm256_sub_epi32(
        _mm256_castps_si256(s),
        _mm256_set1_epi32(TO_INT.to_bits() as i32),
    );
    let scale = _mm256_slli_epi32::<23>(_mm256_add_epi32(k, _mm256_set1_epi32(127)));
    _mm256_div_ps(
        c(1.0),
        _mm256_fmadd_ps(p, _mm256_castsi256_ps(scale), c(1.0)),
    )
}

const S1: f64 = f64::from_bits(0xbfc5_5555_5555_5549);
const S2: f64 = f64::from_bits(0x3f81_1111_1110_f8a6);
const S3: f64 = f64::from_bits(0xbf2a_01a0_19c1_61d5);
const S4: f64 = f64::from_bits(0x3ec7_1de3_57b1_fe7d);
const S5: f64 = f64::from_bits(0xbe5a_e5e6_8a2b_9ceb);
const S6: f64 = f64::from_bits(0x3de5_d93a_5acf_d57c);
const C1: f64 = f64::from_bits(0x3fa5_5555_5555_554c);
const C2: f64 = f64::from_bits(0xbf56_c16c_16c1_5177);
const C3: f64 = f64::from_bits(0x3efa_01a0_19cb_1590);
const C4: f64 = f64::from_bits(0xbe92_7e4f_809c_52ad);
const C5: f64 = f64::from_bits(0x3e21_ee9e_bdb4_b1c4);
const C6: f64 = f64::from_bits(0xbda8_fae9_be88_38d4);
const INV_PIO2: f64 = f64::from_bits(0x3fe4_5f30_6dc9_c883);
/// π/2 split in three 33-bit parts with their tails.
const PIO2_1: f64 = f64::from_bits(0x3ff9_21fb_5440_0000);
const PIO2_1T: f64 = f64::from_bits(0x3dd0_b461_1a62_6331);
const PIO2_2: f64 = f64::from_bits(0x3dd0_b461_1a60_0000);
const PIO2_2T: f64 = f64::from_bits(0x3ba3_198a_2e03_7073);
const PIO2_3: f64 = f64::from_bits(0x3ba3_198a_2e00_0000);
const PIO2_3T: f64 = f64::from_bits(0x397b_839a_2520_49c1);

/// Largest `|x|` for which [`sin`], [`cos`] and [`sin_cos`] are accurate (the Cody–Waite
/// reduction is exact up to 2²⁰·π/2 ≈ 1.6·10⁶); beyond it they return NaN.
pub const TRIG_MAX: f64 = 1.0e6;

/// sin on `[−π/4, π/4]` of the double-double `x + y` (fdlibm `__kernel_sin`).
#[inline]
fn kernel_sin(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    x - ((z * (0.5 * y - v * r) - y) - v * S1)
}

/// cos on `[−π/4, π/4]` of the double-double `x + y` (fdlibm `__kernel_cos`).
#[inline]
fn kernel_cos(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

/// Biased exponent field of `x`.
#[inline]
fn exponent(x: f64) -> i64 {
    ((x.to_bits() >> 52) & 0x7ff) as i64
}

/// `x = n·π/2 + (y0 + y1)` with `|y0 + y1| ≤ π/4` (fdlibm `__rem_pio2`, medium case), for
/// `|x| ≤ TRIG_MAX`.
#[inline]
fn rem_pio2(x: f64) -> (i64, f64, f64) {
    let f = (x * INV_PIO2 + TO_INT) - TO_INT;
    let mut r = x - f * PIO2_1;
    let mut w = f * PIO2_1T;
    let mut y0 = r - w;
    let ex = exponent(x);
    if ex - exponent(y0) > 16 {
        // x is close to a multiple of π/2: two more parts of π/2 against cancellation.
        (r, w, y0) = reduce_step(r, f, PIO2_2, PIO2_2T);
        if ex - exponent(y0) > 49 {
            (r, w, y0) = reduce_step(r, f, PIO2_3, PIO2_3T);
        }
    }
    (f as i64, y0, (r - y0) - w)
}

/// One more Cody–Waite step of [`rem_pio2`]: `(r, w, y0)`.
#[cold]
fn reduce_step(t: f64, f: f64, part: f64, tail: f64) -> (f64, f64, f64) {
    let w = f * part;
    let r = t - w;
    let w = f * tail - ((t - r) - w);
    (r, w, r - w)
}

/// `(sin x, cos x)`, each within 1 ulp, for `|x| ≤` [`TRIG_MAX`] (NaN for larger or
/// non-finite `x`).
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.abs() <= std::f64::consts::FRAC_PI_4 {
        return (kernel_sin(x, 0.0), kernel_cos(x, 0.0));
    }
    if x.abs() > TRIG_MAX || x.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    let (n, y0, y1) = rem_pio2(x);
    let (s, c) = (kernel_sin(y0, y1), kernel_cos(y0, y1));
    match n & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `sin x` within 1 ulp for `|x| ≤` [`TRIG_MAX`] (NaN beyond).
#[inline]
pub fn sin(x: f64) -> f64 {
    if x.abs() <= std::f64::consts::FRAC_PI_4 {
        return kernel_sin(x, 0.0);
    }
    sin_cos(x).0
}

/// `cos x` within 1 ulp for `|x| ≤` [`TRIG_MAX`] (NaN beyond).
#[inline]
pub fn cos(x: f64) -> f64 {
    if x.abs() <= std::f64::consts::FRAC_PI_4 {
        return kernel_cos(x, 0.0);
    }
    sin_cos(x).1
}

/// `(cos, sin)` of the 12 headings `k · 30°`, `k = 0..12`, each the correctly rounded value
/// (0 ulp; exact 0, ±½ and ±1 where the true value is): the `actions` motion model's
/// headings, so its turns need no trigonometry at all.
pub const GRID_30: [(f64, f64); 12] = {
    const H: f64 = 0.866_025_403_784_438_6; // √3/2, correctly rounded
    [
        (1.0, 0.0),
        (H, 0.5),
        (0.5, H),
        (0.0, 1.0),
        (-0.5, H),
        (-H, 0.5),
        (-1.0, 0.0),
        (-H, -0.5),
        (-0.5, -H),
        (0.0, -1.0),
        (0.5, -H),
        (H, -0.5),
    ]
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_and_sin_cos_give_known_values() {
        assert_eq!(exp(0.0), 1.0);
        assert!((exp(1.0) - std::f64::consts::E).abs() <= f64::EPSILON * 3.0);
        let (s, c) = sin_cos(std::f64::consts::FRAC_PI_6);
        assert!((s - 0.5).abs() < 1e-16 && (c - 0.75f64.sqrt()).abs() < 2e-16);
    }

    /// Distance in ulps between two finite doubles of the same sign (or both tiny).
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        let key = |x: f64| {
            let i = x.to_bits() as i64;
            if i < 0 { i64::MIN - i } else { i }
        };
        key(a).abs_diff(key(b))
    }

    /// Deterministic points: a fixed xorshift stream scaled into `[lo, hi]`.
    fn points(n: usize, lo: f64, hi: f64, seed: u64) -> impl Iterator<Item = f64> {
        let mut s = seed;
        (0..n).map(move |_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            lo + (hi - lo) * ((s >> 11) as f64 / (1u64 << 53) as f64)
        })
    }

    fn max_ulps(
        f: impl Fn(f64) -> f64,
        g: impl Fn(f64) -> f64,
        xs: impl Iterator<Item = f64>,
    ) -> u64 {
        xs.map(|x| {
            let (a, b) = (f(x), g(x));
            assert!(a.is_finite() == b.is_finite(), "{x}: {a} vs {b}");
            ulps(a, b)
        })
        .max()
        .unwrap()
    }

    #[test]
    fn exp_within_one_ulp_of_libm() {
        let ranges = [
            (-1.0, 1.0),
            (-40.0, 40.0),
            (-708.0, 708.0),
            (-745.0, 709.78),
            (-1e-8, 1e-8),
        ];
        for (i, &(lo, hi)) in ranges.iter().enumerate() {
            let m = max_ulps(exp, f64::exp, points(400_000, lo, hi, 1 + i as u64));
            assert!(m <= 1, "exp on [{lo}, {hi}]: {m} ulps");
        }
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-0.0), 1.0);
        assert_eq!(exp(710.0), f64::INFINITY);
        assert_eq!(exp(f64::INFINITY), f64::INFINITY);
        assert_eq!(exp(-746.0), 0.0);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert!(exp(f64::NAN).is_nan());
        assert_eq!(exp(EXP_MAX), f64::MAX.min(exp(EXP_MAX)));
        assert!(exp(EXP_MAX).is_finite());
    }

    #[test]
    fn exp2_table_is_a_double_double_of_the_powers() {
        for (j, &(hi, lo)) in EXP2_TABLE.iter().enumerate() {
            let (hi, lo) = (f64::from_bits(hi), f64::from_bits(lo));
            assert!(ulps(hi, (j as f64 / 128.0).exp2()) <= 1, "{j}");
            // lo is the remainder below half an ulp of hi (1 ≤ hi < 2: ulp 2⁻⁵²).
            assert!(lo.abs() <= f64::EPSILON / 2.0, "{j}");
        }
    }

    #[test]
    fn logistic_within_four_ulps() {
        let exact = |x: f64| 1.0 / (1.0 + (-x).exp());
        let m = max_ulps(logistic, exact, points(400_000, -60.0, 60.0, 9));
        assert!(m <= 4, "{m} ulps");
        assert_eq!(logistic(0.0), 0.5);
        assert_eq!(logistic(40.0), 1.0);
        assert_eq!(logistic(-800.0), 0.0);
        assert_eq!(logistic(800.0), 1.0);
    }

    /// The lanes give the scalar function's bits, lane by lane, over the whole valid range,
    /// at the edges of the vector path (±708) and with a lane outside it.
    #[test]
    fn logistic_lanes_are_the_scalar_bits() {
        let same = |xs: [f64; 6]| {
            let got = logistic_lanes(xs);
            for (x, y) in xs.iter().zip(got) {
                assert_eq!(y.to_bits(), logistic(*x).to_bits(), "{x}");
            }
        };
        let xs: Vec<f64> = points(600_000, -720.0, 720.0, 5)
            .chain(points(600_000, -40.0, 40.0, 6))
            .collect();
        for chunk in xs.chunks_exact(6) {
            same(chunk.try_into().unwrap());
        }
        same([708.0, -708.0, 0.0, -0.0, 1e-300, -1e-300]);
        same([707.9999, -707.9999, 37.5, -37.5, 0.5, -0.5]);
        same([708.0001, 1.0, 2.0, 3.0, 4.0, 5.0]);
        same([f64::NAN, 1.0, -1.0, f64::INFINITY, f64::NEG_INFINITY, 0.0]);
    }

    /// The rough logistic is within a quarter of its stated bound of the exact one everywhere:
    /// dense points where the slope is largest, far out, at the clamp, at the rounding of `k`
    /// between two integers, and NaN.
    #[test]
    fn rough_logistic_within_a_quarter_of_its_bound() {
        let far = [60.0 / std::f32::consts::LOG2_E, 41.5, 745.0, 1e30, f32::MAX];
        let halves = (-120..=120).map(|k| (k as f64 + 0.5) / std::f64::consts::LOG2_E);
        let xs = points(2_000_000, -50.0, 50.0, 31)
            .chain(points(200_000, -1000.0, 1000.0, 32))
            .chain(far.iter().flat_map(|&x| [f64::from(x), -f64::from(x)]))
            .chain([0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY])
            .chain(halves);
        let mut worst = 0.0f64;
        let xs: Vec<f32> = xs.map(|x| x as f32).collect();
        for chunk in xs.chunks(8) {
            let mut lanes = [0.0; 8];
            lanes[..chunk.len()].copy_from_slice(chunk);
            for (x, y) in lanes.iter().zip(logistic_rough_lanes(lanes)) {
                worst = worst.max((f64::from(y) - logistic(f64::from(*x))).abs());
            }
            #[cfg(target_arch = "x86_64")]
            if let Some(fused) = rough_avx2(lanes) {
                for (x, y) in lanes.iter().zip(fused) {
                    worst = worst.max((f64::from(y) - logistic(f64::from(*x))).abs());
                }
            }
        }
        assert!(worst <= LOGISTIC_ROUGH_ERR / 4.0, "{worst}");
        assert!(
            worst > 1e-8,
            "{worst}: the test no longer measures the polynomial"
        );
        assert!(logistic_rough_lanes([f32::NAN; 2])[0].is_nan());
        #[cfg(target_arch = "x86_64")]
        if let Some(y) = rough_avx2([
            f32::NAN,
            1.0,
            f32::INFINITY,
            -f32::INFINITY,
            0.0,
            -0.0,
            60.0,
            -60.0,
        ]) {
            assert!(
                y[0].is_nan() && y[1..].iter().all(|y| (0.0..=1.0).contains(y)),
                "{y:?}"
            );
        }
    }

    /// [`logistic_rough_avx2`] of `x`, where the processor has AVX2 and FMA.
    #[cfg(target_arch = "x86_64")]
    fn rough_avx2(x: [f32; 8]) -> Option<[f32; 8]> {
        use std::arch::x86_64::{_mm256_loadu_ps, _mm256_storeu_ps};
        if !(is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")) {
            return None;
        }
        let mut y = [0.0f32; 8];
        // SAFETY: the processor has AVX2 and FMA (checked above); `x` and `y` are eight `f32`.
        unsafe {
            _mm256_storeu_ps(
                y.as_mut_ptr(),
                logistic_rough_avx2(_mm256_loadu_ps(x.as_ptr())),
            )
        };
        Some(y)
    }

    #[test]
    fn sin_cos_within_one_ulp_of_libm() {
        use std::f64::consts::PI;
        let ranges = [
            (-PI / 4.0, PI / 4.0),
            (-4.0, 4.0),
            (-100.0, 100.0),
            (-TRIG_MAX, TRIG_MAX),
        ];
        for (i, &(lo, hi)) in ranges.iter().enumerate() {
            let xs = || points(400_000, lo, hi, 20 + i as u64);
            let ms = max_ulps(sin, f64::sin, xs());
            let mc = max_ulps(cos, f64::cos, xs());
            let msc = max_ulps(|x| sin_cos(x).0, f64::sin, xs()).max(max_ulps(
                |x| sin_cos(x).1,
                f64::cos,
                xs(),
            ));
            assert!(
                ms <= 1 && mc <= 1 && msc <= 1,
                "[{lo}, {hi}]: sin {ms} cos {mc} sin_cos {msc}"
            );
        }
        // Near multiples of π/2, where the reduction cancels (the 2nd and 3rd steps).
        for k in -64i32..=64 {
            let c = k as f64 * std::f64::consts::FRAC_PI_2;
            let mut x = c;
            for _ in 0..40 {
                assert!(
                    ulps(sin(x), x.sin()) <= 1 && ulps(cos(x), x.cos()) <= 1,
                    "{x}"
                );
                x = f64::from_bits(x.to_bits() + 1);
            }
        }
        assert!(sin(2e6).is_nan() && cos(f64::INFINITY).is_nan() && sin(f64::NAN).is_nan());
        assert_eq!((sin(0.0), cos(0.0)), (0.0, 1.0));
    }

    #[test]
    fn grid_table_is_correctly_rounded() {
        assert_eq!(GRID_30[1].0, 3f64.sqrt() / 2.0);
        for (k, &(c, s)) in GRID_30.iter().enumerate() {
            let a = (k as f64 * 30.0).to_radians();
            assert!(
                (c - a.cos()).abs() < 1e-15 && (s - a.sin()).abs() < 1e-15,
                "{k}"
            );
            assert_eq!(c * c + s * s, if k % 3 == 0 { 1.0 } else { c * c + s * s });
        }
    }
}
