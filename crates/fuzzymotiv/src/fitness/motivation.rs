//! Motivations as data (docs/model.md §8, "Motivations you define"): any number N of named
//! motivations (1 ≤ N ≤ [`MAX_MOTIVATIONS`]), each a weight, the fitness term it weighs and,
//! optionally, its own labels. The paper's four — curiosity, homing, orientation, energy, bound
//! to the terms a, g, l, b — are the default.
//!
//! In a config, `[motivations]` maps a name to a weight, or to a table with the weight and the
//! motivation's term, peaks and coefficients:
//!
//! ```toml
//! [motivations]
//! curiosity = 0.6
//! homing = 0.1
//! orientation = 0.0
//! energy = 0.1
//! hurry = { weight = 0.2, term = "urgency" }
//! ```
//!
//! A table that names any motivation defines the whole set: nothing is added to it (naming
//! `curiosity` and `urgency` makes two motivations, as `fuzzymotiv fuzzy --motivations` reads
//! the same names). No table, or an empty one, means the paper's four with their defaults
//! (0.8, 0.1, 0, 0.1). Those of the paper's four that are named come first, in that order, and
//! the others follow in alphabetical order of their names (which fixes the rule numbering). A
//! motivation without `term` weighs the term of its own name (curiosity → a, homing → g,
//! orientation → l, energy → b).

use std::collections::BTreeMap;
use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::fitness::fuzzy::{
    Coefficients, FuzzyError, MOTIVATION_NORMALISE_TOLERANCE, MOTIVATION_SUM_TOLERANCE, TskFitness,
};
use crate::params::{FieldError, joined_list};

/// The most motivations a config may declare (the TSK then has up to 2^8 firing rules).
pub const MAX_MOTIVATIONS: usize = 8;

/// The paper's motivations, in the order of its X = (C, H, O, E).
pub const PAPER_MOTIVATIONS: [&str; 4] = ["curiosity", "homing", "orientation", "energy"];

/// The terms the paper's motivations weigh, in the same order: Y = (a, g, l, b).
pub const PAPER_TERMS: [&str; 4] = ["a", "g", "l", "b"];

/// One motivation: its name, its weight in X, the fitness term it weighs and its own labels
/// (peaks and coefficients), if it has any rather than the `[fuzzy]` ones.
#[derive(Debug, Clone, PartialEq)]
pub struct Motivation {
    name: String,
    weight: f64,
    term: String,
    labels: Option<TskFitness>,
}

impl Motivation {
    /// A motivation `name` of weight `weight` weighing the term `term` with the shared labels.
    pub fn new(name: impl Into<String>, weight: f64, term: impl Into<String>) -> Motivation {
        Motivation {
            name: name.into(),
            weight,
            term: term.into(),
            labels: None,
        }
    }

    /// The same motivation with its own labels.
    pub fn with_labels(mut self, labels: TskFitness) -> Motivation {
        self.labels = Some(labels);
        self
    }

    /// Its name (`curiosity`, …, or the config's).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its weight `X_i`.
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// The name of the fitness term it weighs (`a`, `g`, `l`, `b`, `goal`, …).
    pub fn term(&self) -> &str {
        &self.term
    }

    /// Its own labels, if any (else the TSK's shared ones).
    pub fn labels(&self) -> Option<&TskFitness> {
        self.labels.as_ref()
    }
}

/// Motivations `X`: N named weights in `[0, 1]` summing to 1, each bound to a fitness term.
///
/// Built only by checking: [`Motivations::new`] and [`Motivations::normalised`] (the paper's
/// four), [`Motivations::from_list`] (any), [`RawMotivations::validated`], or the paper's
/// settings ([`Motivations::high_curiosity`], [`Motivations::low_curiosity`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Motivations {
    list: Vec<Motivation>,
}

impl Motivations {
    /// The paper's high-curiosity setting `(C, H, O, E) = (0.8, 0.1, 0, 0.1)`.
    pub fn high_curiosity() -> Motivations {
        Self::paper([0.8, 0.1, 0.0, 0.1])
    }

    /// The paper's low-curiosity setting `(C, H, O, E) = (0.5, 0.3, 0, 0.2)`.
    pub fn low_curiosity() -> Motivations {
        Self::paper([0.5, 0.3, 0.0, 0.2])
    }

    /// The paper's four with these weights, unchecked.
    fn paper(x: [f64; 4]) -> Motivations {
        let list = PAPER_MOTIVATIONS
            .iter()
            .zip(PAPER_TERMS)
            .zip(x)
            .map(|((name, term), w)| Motivation::new(*name, w, term))
            .collect();
        Motivations { list }
    }

    /// Validates and builds the paper's four motivations. Each value must be a finite number
    /// in `[0, 1]` and the four must sum to 1 within [`MOTIVATION_SUM_TOLERANCE`]; nothing is
    /// renormalised.
    pub fn new(
        curiosity: f64,
        homing: f64,
        orientation: f64,
        energy: f64,
    ) -> Result<Self, FuzzyError> {
        Self::checked(Self::paper([curiosity, homing, orientation, energy]).list)
    }

    /// Like [`Motivations::new`], but a sum within [`MOTIVATION_NORMALISE_TOLERANCE`] of 1 is
    /// normalised (each value divided by the sum); then the original sum is returned as well,
    /// so the caller can say so.
    pub fn normalised(
        curiosity: f64,
        homing: f64,
        orientation: f64,
        energy: f64,
    ) -> Result<(Self, Option<f64>), FuzzyError> {
        Self::from_list(Self::paper([curiosity, homing, orientation, energy]).list)
    }

    /// Validates any list of motivations: 1 to [`MAX_MOTIVATIONS`] of them, distinct names,
    /// each weight a number in `[0, 1]`, summing to 1 — a sum within
    /// [`MOTIVATION_NORMALISE_TOLERANCE`] of 1 is normalised, and the original sum returned.
    pub fn from_list(list: Vec<Motivation>) -> Result<(Self, Option<f64>), FuzzyError> {
        check_list(&list)?;
        let sum = weight_sum(&list);
        let off = (sum - 1.0).abs();
        if off <= MOTIVATION_SUM_TOLERANCE || off > MOTIVATION_NORMALISE_TOLERANCE {
            return Self::checked(list).map(|m| (m, None));
        }
        let list = list
            .into_iter()
            .map(|m| Motivation {
                weight: m.weight / sum,
                ..m
            })
            .collect();
        Self::checked(list).map(|m| (m, Some(sum)))
    }

    /// The list if it is valid and sums to 1 within [`MOTIVATION_SUM_TOLERANCE`].
    fn checked(list: Vec<Motivation>) -> Result<Self, FuzzyError> {
        check_list(&list)?;
        let sum = weight_sum(&list);
        if (sum - 1.0).abs() > MOTIVATION_SUM_TOLERANCE {
            return Err(FuzzyError::MotivationSum {
                sum,
                parts: list.iter().map(|m| (m.name.clone(), m.weight)).collect(),
            });
        }
        Ok(Motivations { list })
    }

    /// The motivations, in input order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &Motivation> {
        self.list.iter()
    }

    /// Motivation `i` (input order).
    pub fn get(&self, i: usize) -> Option<&Motivation> {
        self.list.get(i)
    }

    /// N, the number of motivations (TSK inputs).
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Never true for checked motivations (there is at least one).
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The weights `X`, in input order.
    pub fn weights(&self) -> Vec<f64> {
        self.list.iter().map(|m| m.weight).collect()
    }

    /// The weight of the motivation named `name`, if there is one.
    pub fn weight_of(&self, name: &str) -> Option<f64> {
        self.list.iter().find(|m| m.name == name).map(|m| m.weight)
    }

    /// The total weight of the motivations bound to term `term` (0 if none is).
    pub fn weight_on(&self, term: &str) -> f64 {
        self.list
            .iter()
            .filter(|m| m.term == term)
            .map(|m| m.weight)
            .sum()
    }

    /// Curiosity `C` (0 when there is no motivation of that name).
    pub fn curiosity(&self) -> f64 {
        self.weight_of("curiosity").unwrap_or(0.0)
    }

    /// Homing `H` (0 when there is no motivation of that name).
    pub fn homing(&self) -> f64 {
        self.weight_of("homing").unwrap_or(0.0)
    }

    /// Orientation `O` (0 when there is no motivation of that name).
    pub fn orientation(&self) -> f64 {
        self.weight_of("orientation").unwrap_or(0.0)
    }

    /// Energy `E` (0 when there is no motivation of that name).
    pub fn energy(&self) -> f64 {
        self.weight_of("energy").unwrap_or(0.0)
    }

    /// The paper's `[C, H, O, E]` (each 0 when there is no motivation of that name).
    pub fn as_array(&self) -> [f64; 4] {
        PAPER_MOTIVATIONS.map(|name| self.weight_of(name).unwrap_or(0.0))
    }

    /// Whether these are the paper's four motivations, in order, bound to a, g, l, b with the
    /// shared labels (what the paper's tables, figures and simplex sweeps describe).
    pub fn is_paper(&self) -> bool {
        self.list.len() == 4
            && self.list.iter().enumerate().all(|(i, m)| {
                m.name == PAPER_MOTIVATIONS[i] && m.term == PAPER_TERMS[i] && m.labels.is_none()
            })
    }

    /// The names of the TSK's inputs, in input order: the term each motivation weighs (`a`,
    /// `g`, `l`, `b` for the paper's four), or the motivation's own name where two weigh the
    /// same term.
    pub fn input_names(&self) -> Vec<String> {
        self.list
            .iter()
            .map(|m| {
                let shared = self.list.iter().filter(|o| o.term == m.term).count() > 1;
                if shared {
                    m.name.clone()
                } else {
                    m.term.clone()
                }
            })
            .collect()
    }

    /// The names of the terms the motivations weigh, in input order.
    pub fn terms(&self) -> Vec<&str> {
        self.list.iter().map(|m| m.term.as_str()).collect()
    }
}

/// `Σ X_i`, summed left to right as the paper's `C + H + O + E`.
fn weight_sum(list: &[Motivation]) -> f64 {
    let mut it = list.iter().map(|m| m.weight);
    let first = it.next().unwrap_or(0.0);
    it.fold(first, |s, w| s + w)
}

/// 1 to [`MAX_MOTIVATIONS`] motivations with distinct names, each weight in `[0, 1]` (so not
/// NaN); the error names the first that is not.
fn check_list(list: &[Motivation]) -> Result<(), FuzzyError> {
    if list.is_empty() || list.len() > MAX_MOTIVATIONS {
        return Err(FuzzyError::MotivationCount {
            count: list.len(),
            max: MAX_MOTIVATIONS,
        });
    }
    for (i, m) in list.iter().enumerate() {
        if list[..i].iter().any(|o| o.name == m.name) {
            return Err(FuzzyError::DuplicateMotivation {
                name: m.name.clone(),
            });
        }
    }
    match list.iter().find(|m| !(0.0..=1.0).contains(&m.weight)) {
        Some(m) => Err(FuzzyError::MotivationOutOfRange {
            name: m.name.clone(),
            value: m.weight,
        }),
        None => Ok(()),
    }
}

/// One motivation as written in `[motivations]`: a weight, or a table.
#[derive(Debug, Clone, PartialEq)]
pub enum RawMotivation {
    /// `name = 0.2`: the weight, the term of the motivation's own name, the shared labels.
    Weight(f64),
    /// `name = { weight = 0.2, term = "urgency", peaks = [...], coefficients = ... }`.
    Table(RawMotivationTable),
}

/// `name = { weight, term, peaks, coefficients }` in `[motivations]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMotivationTable {
    /// The weight `X_i`, in [0, 1].
    pub weight: f64,
    /// The term it weighs; default the term of the motivation's own name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub term: Option<String>,
    /// Its own label peaks (default the `[fuzzy]` ones).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peaks: Option<Vec<f64>>,
    /// Its own coefficients (default the `[fuzzy]` ones when it has no peaks of its own, else
    /// `"linear"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coefficients: Option<Coefficients>,
}

impl RawMotivation {
    /// The weight as written.
    pub fn weight(&self) -> f64 {
        match self {
            RawMotivation::Weight(w) => *w,
            RawMotivation::Table(t) => t.weight,
        }
    }

    fn set_weight(&mut self, w: f64) {
        match self {
            RawMotivation::Weight(x) => *x = w,
            RawMotivation::Table(t) => t.weight = w,
        }
    }
}

impl Serialize for RawMotivation {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            RawMotivation::Weight(w) => s.serialize_f64(*w),
            RawMotivation::Table(t) => t.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for RawMotivation {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = RawMotivation;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a weight (a number from 0 to 1) or a table { weight = …, term = \"…\" }",
                )
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<RawMotivation, E> {
                Ok(RawMotivation::Weight(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<RawMotivation, E> {
                Ok(RawMotivation::Weight(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<RawMotivation, E> {
                Ok(RawMotivation::Weight(v as f64))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<RawMotivation, A::Error> {
                let table =
                    RawMotivationTable::deserialize(de::value::MapAccessDeserializer::new(map))?;
                Ok(RawMotivation::Table(table))
            }
        }
        d.deserialize_any(V)
    }
}

/// `[motivations]` in a config, as written (the paper's four when nothing is written), in
/// input order as the module documentation says: those of the paper's four that are named
/// first (in paper order), then the others by name.
#[derive(Debug, Clone, PartialEq)]
pub struct RawMotivations {
    /// `(name, motivation)` in input order.
    pub list: Vec<(String, RawMotivation)>,
}

impl Default for RawMotivations {
    /// The paper's high-curiosity setting.
    fn default() -> Self {
        Self::ordered(BTreeMap::new())
    }
}

impl RawMotivations {
    /// The paper's four as plain weights (`[C, H, O, E]`).
    pub fn paper(x: [f64; 4]) -> RawMotivations {
        let list = PAPER_MOTIVATIONS
            .iter()
            .zip(x)
            .map(|(n, w)| (n.to_string(), RawMotivation::Weight(w)))
            .collect();
        RawMotivations { list }
    }

    /// The motivations named in `written` (a name given twice keeps its last value; callers
    /// that must refuse that check it first), in input order: those of the paper's four that
    /// are named, in paper order, then the others by name. Nothing written is the paper's
    /// high-curiosity setting; otherwise nothing is added.
    pub fn named(written: impl IntoIterator<Item = (String, RawMotivation)>) -> RawMotivations {
        Self::ordered(written.into_iter().collect())
    }

    fn ordered(mut written: BTreeMap<String, RawMotivation>) -> RawMotivations {
        if written.is_empty() {
            let x = Motivations::high_curiosity().as_array();
            return Self::paper(x);
        }
        let mut list: Vec<(String, RawMotivation)> = PAPER_MOTIVATIONS
            .iter()
            .filter_map(|name| written.remove(*name).map(|m| (name.to_string(), m)))
            .collect();
        list.extend(written);
        RawMotivations { list }
    }

    /// The paper's motivations this set leaves out when it names some but not all four (none
    /// otherwise): what an earlier release added with their defaults, and no longer does.
    pub fn paper_left_out(&self) -> Vec<&'static str> {
        let named = |n: &str| self.list.iter().any(|(m, _)| m == n);
        let left: Vec<&'static str> = PAPER_MOTIVATIONS
            .into_iter()
            .filter(|n| !named(n))
            .collect();
        if left.len() == PAPER_MOTIVATIONS.len() {
            Vec::new()
        } else {
            left
        }
    }

    /// When this set names some of the paper's four but not all: that those left out are no
    /// motivations here (a table defines the whole set; an earlier release added them with
    /// their defaults), for the note of a config that runs and the sum error of one that does
    /// not, so that an older config's different meaning is not silent.
    pub fn left_out_said(&self) -> Option<String> {
        let left = self.paper_left_out();
        if left.is_empty() {
            return None;
        }
        let each = |f: fn(&str) -> String| {
            joined_list(&left.iter().map(|n| f(n)).collect::<Vec<_>>(), "and")
        };
        let names = each(|n| format!("`{n}`"));
        let zeros = each(|n| format!("`{n} = 0.0`"));
        let inputs: Vec<&str> = self.list.iter().map(|(n, _)| n.as_str()).collect();
        Some(format!(
            "[motivations] leaves out {names} of the paper's four, so the motivations are {} \
             alone: a table defines the whole set (write {zeros} to keep the paper's four)",
            inputs.join(", ")
        ))
    }

    /// The weight written for `name`, if any.
    pub fn weight_of(&self, name: &str) -> Option<f64> {
        self.list
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, m)| m.weight())
    }

    /// docs/model.md §8: motivations summing to within 0.001 of 1 (but not within 1e-9) are
    /// divided by their sum; returns the original sum then. Values farther off are left as
    /// they are, for validation to refuse.
    pub fn normalise(&mut self, shared: &TskFitness) -> Option<f64> {
        let (m, sum) = self.motivations(shared).ok()?;
        let sum = sum?;
        for ((_, raw), checked) in self.list.iter_mut().zip(m.iter()) {
            raw.set_weight(checked.weight());
        }
        Some(sum)
    }

    /// The validated motivations (normalised as [`Motivations::from_list`] says); an error
    /// names `motivations.NAME` (or its `peaks`/`coefficients`) or `motivations`. `shared` are
    /// the `[fuzzy]` labels, for a motivation that gives its own coefficients but no peaks.
    pub fn validated(&self, shared: &TskFitness) -> Result<Motivations, FieldError> {
        self.motivations(shared).map(|(m, _)| m)
    }

    fn motivations(&self, shared: &TskFitness) -> Result<(Motivations, Option<f64>), FieldError> {
        let mut list = Vec::with_capacity(self.list.len());
        for (name, raw) in &self.list {
            list.push(motivation_of(name, raw, shared)?);
        }
        Motivations::from_list(list).map_err(|e| {
            let field = match &e {
                FuzzyError::MotivationOutOfRange { name, .. } => self.weight_field(name),
                FuzzyError::DuplicateMotivation { name } => format!("motivations.{name}"),
                _ => "motivations".to_string(),
            };
            let left_out = (matches!(e, FuzzyError::MotivationSum { .. }))
                .then(|| self.left_out_said())
                .flatten();
            match left_out {
                Some(said) => FieldError::new(field, format!("{e}; {said}")),
                None => FieldError::new(field, e.to_string()),
            }
        })
    }

    /// Where `name`'s weight is written: `motivations.NAME` for `NAME = 0.2`,
    /// `motivations.NAME.weight` for a table.
    fn weight_field(&self, name: &str) -> String {
        let table =
            (self.list.iter()).any(|(n, m)| n == name && matches!(m, RawMotivation::Table(_)));
        if table {
            format!("motivations.{name}.weight")
        } else {
            format!("motivations.{name}")
        }
    }
}

/// The motivation `name` as written: its default term, its own labels checked.
fn motivation_of(
    name: &str,
    raw: &RawMotivation,
    shared: &TskFitness,
) -> Result<Motivation, FieldError> {
    if name.trim().is_empty() {
        return Err(FieldError::new(
            "motivations",
            format!(
                "a motivation has the empty name {name:?}; each motivation needs a name, e.g. \
                 curiosity = 0.8 or hurry = {{ weight = 0.2, term = \"urgency\" }}"
            ),
        ));
    }
    let default_term = PAPER_MOTIVATIONS
        .iter()
        .position(|n| *n == name)
        .map_or(name, |k| PAPER_TERMS[k]);
    let RawMotivation::Table(t) = raw else {
        return Ok(Motivation::new(name, raw.weight(), default_term));
    };
    let term = t.term.clone().unwrap_or_else(|| default_term.to_string());
    let m = Motivation::new(name, t.weight, term);
    let labels = match (&t.peaks, &t.coefficients) {
        (None, None) => return Ok(m),
        (None, Some(c)) => (shared.peaks().to_vec(), c.clone()),
        (Some(p), c) => (p.clone(), c.clone().unwrap_or_default()),
    };
    let of = format!("motivations.{name}.");
    Ok(m.with_labels(TskFitness::of_raw(labels.0, &labels.1, &of)?))
}

impl Serialize for RawMotivations {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.list.len()))?;
        for (name, m) in &self.list {
            map.serialize_entry(name, m)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for RawMotivations {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let written = BTreeMap::<String, RawMotivation>::deserialize(d)?;
        Ok(RawMotivations::ordered(written))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `[motivations]` as a config holds it (`text` is the table's body).
    fn read(body: &str) -> RawMotivations {
        #[derive(Deserialize)]
        struct Doc {
            #[serde(default)]
            motivations: RawMotivations,
        }
        toml::from_str::<Doc>(body).unwrap().motivations
    }

    fn names(m: &RawMotivations) -> Vec<&str> {
        m.list.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// Issue #52 item 3: naming curiosity and urgency makes those two motivations, as
    /// `fuzzy --motivations curiosity=0.7,urgency=0.3` reads them; no paper motivation is added.
    #[test]
    fn a_motivations_table_defines_the_whole_set_and_adds_none_of_the_papers_four() {
        let written = read("[motivations]\nurgency = 0.3\ncuriosity = 0.7\n");
        assert_eq!(names(&written), ["curiosity", "urgency"]);
        let m = written.validated(&TskFitness::paper()).unwrap();
        assert_eq!(m.weights(), [0.7, 0.3]);
        let by_hand = RawMotivations::named([
            ("urgency".to_string(), RawMotivation::Weight(0.3)),
            ("curiosity".to_string(), RawMotivation::Weight(0.7)),
        ]);
        assert_eq!(by_hand, written);
        assert_eq!(
            written.paper_left_out(),
            ["homing", "orientation", "energy"]
        );
    }

    /// No table, or an empty one, is the paper's high-curiosity four (the default run's).
    #[test]
    fn no_motivations_table_or_an_empty_one_is_the_papers_four() {
        for text in ["", "[motivations]\n"] {
            let m = read(text);
            assert_eq!(m, RawMotivations::paper([0.8, 0.1, 0.0, 0.1]));
            assert!(m.paper_left_out().is_empty());
        }
    }

    /// An empty name is refused naming `motivations`, before the sum is checked.
    #[test]
    fn an_empty_motivation_name_is_refused_as_such() {
        let e = read("[motivations]\n\"\" = 1.0\n")
            .validated(&TskFitness::paper())
            .unwrap_err();
        assert_eq!(e.field, "motivations");
        assert!(e.reason.contains("empty name"), "{e}");
    }
}
