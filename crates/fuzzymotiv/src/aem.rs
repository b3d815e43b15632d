//! Action-based environment modelling (AEM): per-step action labels and environment vectors.
//!
//! Each control step is one of four [`Action`]s (with `actions` motion the robot executes it;
//! with `wheels` motion it labels the motor outputs); a run of `T` actions is then encoded as a
//! `T`-dimensional environment vector (docs/model.md). The default
//! [`Encoder::ChainCode`] is the paper's unwrapped 12-direction chain code divided by 12.

/// The action taken in one control step, derived from the two motor outputs.
///
/// Its chain-code step ([`Action::chain_step`]) is the heading change in units of 30°.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Action {
    /// Both wheels forward at about the same speed; heading change 0.
    Straight,
    /// Right wheel faster than the left by more than the tolerance; heading change +30°.
    Left30,
    /// Left wheel faster than the right by more than the tolerance; heading change −30°.
    Right30,
    /// Both wheels backwards; heading change 180°.
    Turn180,
}

impl Action {
    /// Classifies one control step from the motor outputs `m_left`, `m_right` ∈ [0, 1].
    ///
    /// With signed speeds `sL = 2·m_left − 1` and `sR = 2·m_right − 1`: both `< 0` → `Turn180`;
    /// else `sR − sL > tolerance` → `Left30`; else `sL − sR > tolerance` → `Right30`; else
    /// `Straight`. Comparisons are strict, so a difference exactly equal to `tolerance` is
    /// `Straight`. `tolerance` is in signed-speed units (range [−1, 1]); the project default is
    /// 0.25 (config key `aem.action_tolerance`). NaN inputs fail every comparison and give
    /// `Straight`.
    pub fn from_motors(m_left: f64, m_right: f64, tolerance: f64) -> Action {
        Action::from_speeds(2.0 * m_left - 1.0, 2.0 * m_right - 1.0, tolerance)
    }

    /// Classifies wheel speeds given as fractions of `v_max`, `s_left`, `s_right` (nominally in
    /// [−1, 1]; noise may take them a little beyond): both `< 0` → `Turn180`; else
    /// `sR − sL > tolerance` → `Left30`; else `sL − sR > tolerance` → `Right30`; else
    /// `Straight` (see [`Action::from_motors`]).
    ///
    /// ```
    /// use fuzzymotiv::aem::Action;
    /// assert_eq!(Action::from_speeds(-0.1, -0.9, 0.25), Action::Turn180);
    /// assert_eq!(Action::from_speeds(0.2, 0.6, 0.25), Action::Left30);
    /// assert_eq!(Action::from_speeds(0.9, 0.8, 0.25), Action::Straight);
    /// ```
    #[inline]
    pub fn from_speeds(s_left: f64, s_right: f64, tolerance: f64) -> Action {
        if s_left < 0.0 && s_right < 0.0 {
            Action::Turn180
        } else if s_right - s_left > tolerance {
            Action::Left30
        } else if s_left - s_right > tolerance {
            Action::Right30
        } else {
            Action::Straight
        }
    }

    /// A short lowercase name: `"straight"`, `"left30"`, `"right30"` or `"turn180"`.
    pub fn label(self) -> &'static str {
        match self {
            Action::Straight => "straight",
            Action::Left30 => "left30",
            Action::Right30 => "right30",
            Action::Turn180 => "turn180",
        }
    }

    /// The change of the chain code in 30° units: Straight 0, Left30 +1, Right30 −1, Turn180 +6.
    pub fn chain_step(self) -> i32 {
        match self {
            Action::Straight => 0,
            Action::Left30 => 1,
            Action::Right30 => -1,
            Action::Turn180 => 6,
        }
    }

    /// The raw symbol value used by [`Encoder::Symbols`]: Straight 0, Left30 1/3,
    /// Right30 2/3, Turn180 1.
    pub fn symbol_value(self) -> f64 {
        match self {
            Action::Straight => 0.0,
            Action::Left30 => 1.0 / 3.0,
            Action::Right30 => 2.0 / 3.0,
            Action::Turn180 => 1.0,
        }
    }
}

/// How a sequence of actions becomes an environment vector (one element per action).
///
/// Config spelling is kebab-case: `"chain-code"` (default), `"heading"`, `"symbols"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Encoder {
    /// The paper's encoding (default): the cumulative chain code after each step, starting
    /// from code 0 and kept unwrapped (no mod 12), divided by 12 — i.e. the total heading
    /// change in full turns.
    #[default]
    ChainCode,
    /// The cumulative chain code wrapped into 0..12 (`rem_euclid(12)`), divided by 12 — the
    /// current heading as a fraction of a full turn, in [0, 1).
    Heading,
    /// The raw action symbol of each step, not accumulated: Straight 0, Left30 1/3,
    /// Right30 2/3, Turn180 1 (see [`Action::symbol_value`]).
    Symbols,
}

/// The environment vector of an action sequence: element `t` (0-based) encodes the state after
/// action `t`, so `T` actions give a `T`-dimensional vector (empty input → empty vector).
pub fn environment_vector(actions: &[Action], encoder: Encoder) -> Vec<f64> {
    let mut out = Vec::with_capacity(actions.len());
    environment_vector_into(actions, encoder, &mut out);
    out
}

/// As [`environment_vector`], but writes into `out` (cleared first), reusing its allocation.
pub fn environment_vector_into(actions: &[Action], encoder: Encoder, out: &mut Vec<f64>) {
    out.clear();
    out.reserve(actions.len());
    match encoder {
        Encoder::ChainCode | Encoder::Heading => {
            let mut code: i64 = 0;
            for &a in actions {
                code += i64::from(a.chain_step());
                let c = if encoder == Encoder::Heading {
                    code.rem_euclid(12)
                } else {
                    code
                };
                out.push(c as f64 / 12.0);
            }
        }
        Encoder::Symbols => out.extend(actions.iter().map(|a| a.symbol_value())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Action::*;

    fn scaled(codes: &[i64]) -> Vec<f64> {
        codes.iter().map(|&c| c as f64 / 12.0).collect()
    }

    #[test]
    fn chain_code_hand_made() {
        let seq = [Straight, Left30, Left30, Right30, Turn180];
        assert_eq!(
            environment_vector(&seq, Encoder::ChainCode),
            scaled(&[0, 1, 2, 1, 7])
        );
        assert_eq!(
            environment_vector(&[], Encoder::ChainCode),
            Vec::<f64>::new()
        );
        let rights = [Right30; 3];
        assert_eq!(
            environment_vector(&rights, Encoder::ChainCode),
            scaled(&[-1, -2, -3])
        );
    }

    #[test]
    fn chain_code_is_unwrapped_heading_wraps() {
        let seq = [Left30; 13];
        let v = environment_vector(&seq, Encoder::ChainCode);
        assert_eq!(v.len(), 13);
        assert_eq!(*v.last().unwrap(), 13.0 / 12.0);
        let h = environment_vector(&seq, Encoder::Heading);
        assert_eq!(*h.last().unwrap(), 1.0 / 12.0);
        assert_eq!(h[11], 0.0);
        // Negative codes wrap into [0, 1).
        let h = environment_vector(&[Right30, Turn180, Turn180], Encoder::Heading);
        assert_eq!(h, scaled(&[11, 5, 11]));
    }

    #[test]
    fn symbols_values() {
        let seq = [Straight, Left30, Right30, Turn180];
        assert_eq!(
            environment_vector(&seq, Encoder::Symbols),
            vec![0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0]
        );
    }

    #[test]
    fn into_reuses_buffer() {
        let mut buf = vec![9.0; 50];
        environment_vector_into(&[Left30, Left30], Encoder::ChainCode, &mut buf);
        assert_eq!(buf, scaled(&[1, 2]));
    }

    #[test]
    fn from_motors_thresholds() {
        let tol = 0.25;
        assert_eq!(Action::from_motors(0.2, 0.3, tol), Turn180);
        assert_eq!(Action::from_motors(0.5, 0.7, tol), Left30);
        assert_eq!(Action::from_motors(0.7, 0.5, tol), Right30);
        assert_eq!(Action::from_motors(0.6, 0.65, tol), Straight);
        // Exactly representable boundary: sR − sL = 0.25 exactly → Straight (strict >).
        assert_eq!(Action::from_motors(0.5, 0.625, tol), Straight);
        assert_eq!(Action::from_motors(0.625, 0.5, tol), Straight);
        // One wheel backwards, other forward: a turn, not Turn180.
        assert_eq!(Action::from_motors(0.4, 0.9, tol), Left30);
        assert_eq!(Action::from_motors(f64::NAN, 0.5, tol), Straight);
    }

    #[test]
    fn labels_and_steps() {
        let all = [Straight, Left30, Right30, Turn180];
        let labels: Vec<_> = all.iter().map(|a| a.label()).collect();
        assert_eq!(labels, ["straight", "left30", "right30", "turn180"]);
        let steps: Vec<_> = all.iter().map(|a| a.chain_step()).collect();
        assert_eq!(steps, [0, 1, -1, 6]);
    }
}
