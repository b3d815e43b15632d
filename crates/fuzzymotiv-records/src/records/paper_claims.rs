//! The paper's claims as data: each has an id ([`ClaimId`]), a measure ([`Measure`]), its arms
//! (high against low curiosity, or each setting on its own) and a direction ([`Direction`]);
//! its sentence is rendered from them ([`ClaimId::sentence`]). Records keep the sentence
//! (`claims.csv`, `claims.md`, `summary.json` are as they always were): a claim is written as its
//! sentence and read back as the claim whose sentence it is, so no code decides what a claim is
//! from its words.

use std::fmt;

use fuzzymotiv::statistics::Expect;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::records::TableRow;

/// The paper's claims, in the order a study lists them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ClaimId {
    /// High curiosity explores more than low curiosity.
    Explores,
    /// High curiosity uses more battery.
    Battery,
    /// High curiosity recognises rooms better.
    Recognition,
    /// High curiosity returns home less.
    Homing,
    /// Fig. 6: the first generation's mean F is about 0.1, in each setting.
    FirstGenerationF,
    /// Fig. 6: the mean F rises over the generations, in each setting.
    FitnessRises,
}

/// What a claim measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// % optimal exploration (a column of the tables).
    Exploration,
    /// % battery usage.
    Battery,
    /// % recognition.
    Recognition,
    /// % homing.
    Homing,
    /// The first generation's mean F.
    FirstGenerationF,
    /// The last generation's mean F against the first's.
    FitnessRise,
}

/// Which settings a claim is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Arms {
    /// One setting against another, paired by seed (in a study's order: `settings[0]` against
    /// `settings[1]`), each named in words.
    Paired(&'static str, &'static str),
    /// Every setting on its own.
    EachSetting,
}

/// Which way a claim goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Direction {
    /// The first arm's measure is higher (or the measure rises).
    Higher,
    /// The first arm's measure is lower.
    Lower,
    /// The measure lies between the two bounds.
    Within(f64, f64),
}

impl Direction {
    /// The direction a paired test expects; none for a band.
    pub fn expect(self) -> Option<Expect> {
        match self {
            Direction::Higher => Some(Expect::Higher),
            Direction::Lower => Some(Expect::Lower),
            Direction::Within(..) => None,
        }
    }
}

/// The band Fig. 6 puts the first generation's mean F in ("about 0.1").
pub const FIRST_F_BAND: (f64, f64) = (0.05, 0.15);

/// The paper's two settings in words, as its comparisons name them.
const CURIOSITY: Arms = Arms::Paired("high curiosity", "low curiosity");

impl ClaimId {
    /// Every claim, in the order a study lists them.
    pub const ALL: [ClaimId; 6] = [
        ClaimId::Explores,
        ClaimId::Battery,
        ClaimId::Recognition,
        ClaimId::Homing,
        ClaimId::FirstGenerationF,
        ClaimId::FitnessRises,
    ];

    /// The comparisons of high against low curiosity, paired by seed.
    pub const COMPARISONS: [ClaimId; 4] = [
        ClaimId::Explores,
        ClaimId::Battery,
        ClaimId::Recognition,
        ClaimId::Homing,
    ];

    /// What the claim measures.
    pub fn measure(self) -> Measure {
        match self {
            ClaimId::Explores => Measure::Exploration,
            ClaimId::Battery => Measure::Battery,
            ClaimId::Recognition => Measure::Recognition,
            ClaimId::Homing => Measure::Homing,
            ClaimId::FirstGenerationF => Measure::FirstGenerationF,
            ClaimId::FitnessRises => Measure::FitnessRise,
        }
    }

    /// Which settings it is about.
    pub fn arms(self) -> Arms {
        match self {
            ClaimId::FirstGenerationF | ClaimId::FitnessRises => Arms::EachSetting,
            _ => CURIOSITY,
        }
    }

    /// Which way it goes.
    pub fn direction(self) -> Direction {
        match self {
            ClaimId::Homing => Direction::Lower,
            ClaimId::FirstGenerationF => Direction::Within(FIRST_F_BAND.0, FIRST_F_BAND.1),
            _ => Direction::Higher,
        }
    }

    /// What the first arm does, without naming the arms: "explores more", "returns home less".
    pub fn short(self) -> String {
        let (measure, direction) = (self.measure(), self.direction());
        match (measure, direction) {
            (Measure::Exploration, Direction::Higher) => "explores more".into(),
            (Measure::Exploration, _) => "explores less".into(),
            (Measure::Battery, Direction::Higher) => "uses more battery".into(),
            (Measure::Battery, _) => "uses less battery".into(),
            (Measure::Recognition, Direction::Higher) => "recognises rooms better".into(),
            (Measure::Recognition, _) => "recognises rooms worse".into(),
            (Measure::Homing, Direction::Lower) => "returns home less".into(),
            (Measure::Homing, _) => "returns home more".into(),
            (Measure::FirstGenerationF, Direction::Within(lo, hi)) => {
                format!("first-generation mean F about 0.1 (between {lo} and {hi})")
            }
            (Measure::FirstGenerationF, _) => "first-generation mean F".into(),
            (Measure::FitnessRise, _) => "mean F rises over the generations".into(),
        }
    }

    /// The claim in words, as the records have always written it.
    pub fn sentence(self) -> String {
        match self.arms() {
            Arms::EachSetting => self.short(),
            Arms::Paired(a, b) => {
                // Exploration says whom it is compared with; homing, which way its column goes.
                let tail = match (self.measure(), self.direction()) {
                    (Measure::Exploration, _) => format!(" than {b}"),
                    (Measure::Homing, Direction::Lower) => " (lower % homing)".into(),
                    (Measure::Homing, _) => " (higher % homing)".into(),
                    _ => String::new(),
                };
                format!("{a} {}{tail}", self.short())
            }
        }
    }

    /// The claim whose [`sentence`](Self::sentence) `text` is, as a record holds it.
    pub fn of_sentence(text: &str) -> Option<ClaimId> {
        ClaimId::ALL.into_iter().find(|id| id.sentence() == text)
    }
}

impl Measure {
    /// The measure's value in a row of a seed's table; none for a measure of the fitness
    /// curves or a value the row lacks.
    pub fn of_row(self, row: &TableRow) -> Option<f64> {
        match self {
            Measure::Exploration => row.exploration_pct,
            Measure::Battery => row.battery_pct,
            Measure::Recognition => row.recognition_pct,
            Measure::Homing => row.homing_pct,
            Measure::FirstGenerationF | Measure::FitnessRise => None,
        }
    }
}

impl fmt::Display for ClaimId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.sentence())
    }
}

impl Serialize for ClaimId {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.sentence())
    }
}

impl<'de> Deserialize<'de> for ClaimId {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        ClaimId::of_sentence(&text).ok_or_else(|| {
            let known: Vec<String> = ClaimId::ALL.iter().map(|c| c.sentence()).collect();
            serde::de::Error::custom(format!(
                "`{text}` is not one of the paper's claims ({})",
                known.join("; ")
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sentences rendered from the typed claims are the records' words, byte for byte
    /// (claims.csv, claims.md and summary.json of every committed study hold these).
    #[test]
    fn each_claims_sentence_is_rendered_from_its_parts_as_the_records_have_it() {
        let sentences: Vec<String> = ClaimId::ALL.iter().map(|c| c.sentence()).collect();
        assert_eq!(
            sentences,
            [
                "high curiosity explores more than low curiosity",
                "high curiosity uses more battery",
                "high curiosity recognises rooms better",
                "high curiosity returns home less (lower % homing)",
                "first-generation mean F about 0.1 (between 0.05 and 0.15)",
                "mean F rises over the generations",
            ]
        );
        let short: Vec<String> = ClaimId::COMPARISONS.iter().map(|c| c.short()).collect();
        assert_eq!(
            short,
            [
                "explores more",
                "uses more battery",
                "recognises rooms better",
                "returns home less"
            ]
        );
    }

    /// A claim is written as its sentence and read back as the same claim; a sentence that is
    /// not one of the paper's claims (or merely contains one's words) is refused, naming it.
    #[test]
    fn a_claim_reads_back_from_its_sentence_and_nothing_else() {
        for id in ClaimId::ALL {
            let json = serde_json::to_string(&id).unwrap();
            assert_eq!(json, format!("\"{}\"", id.sentence()));
            assert_eq!(serde_json::from_str::<ClaimId>(&json).unwrap(), id);
        }
        let e = serde_json::from_str::<ClaimId>("\"uses more battery\"").unwrap_err();
        assert!(
            e.to_string()
                .contains("`uses more battery` is not one of the paper's claims"),
            "{e}"
        );
    }

    /// Each comparison takes its measure's column of the table, not the column its words
    /// suggest; the curve claims take none.
    #[test]
    fn a_comparison_measures_its_own_column() {
        let row = TableRow {
            room: "H".into(),
            average_fitness: Some(0.5),
            battery_pct: Some(2.0),
            exploration_pct: Some(1.0),
            homing_pct: Some(4.0),
            recognition_pct: Some(3.0),
        };
        let of = |c: ClaimId| c.measure().of_row(&row);
        assert_eq!(of(ClaimId::Explores), Some(1.0));
        assert_eq!(of(ClaimId::Battery), Some(2.0));
        assert_eq!(of(ClaimId::Recognition), Some(3.0));
        assert_eq!(of(ClaimId::Homing), Some(4.0));
        assert_eq!(of(ClaimId::FitnessRises), None);
        assert_eq!(ClaimId::Homing.direction().expect(), Some(Expect::Lower));
        assert_eq!(ClaimId::FirstGenerationF.direction().expect(), None);
    }
}
