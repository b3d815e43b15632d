//! The fitness terms a, g, l, b in words: the one place that says what they mean, for every
//! page that explains them. The sentences are docs/model.md §7's own ("In short"), chosen by
//! the run's homing, motion and energy modes; a test keeps the two equal.
//!
//! A sentence may mark code with backticks, as Markdown does; [`html`] turns them into
//! `<code>`.

use fuzzymotiv::experiment::EnergyMode;
use fuzzymotiv::fitness::Homing;
use fuzzymotiv::simulation::Motion;

use crate::figure::esc;

/// One fitness term: its symbol, names and definition.
#[derive(Debug, Clone, PartialEq)]
pub struct Term {
    /// The paper's symbol: `a`, `g`, `l` or `b`.
    pub symbol: &'static str,
    /// A short name (figure legends, the introduction).
    pub name: &'static str,
    /// The name it is defined under.
    pub title: &'static str,
    /// Its definition for the run's model, sentence by sentence.
    pub definition: Vec<&'static str>,
}

/// (symbol, short name, title) of a, g, l, b, in that order.
pub const NAMES: [(&str, &str, &str); 4] = [
    ("a", "exploration", "exploration"),
    ("g", "homing", "homing"),
    ("l", "recognition", "orientation (recognition)"),
    ("b", "battery", "battery usage"),
];

/// a, whatever the model.
const EXPLORATION: &str = "a = min(1, visited / optimum): the 50 mm grid cells the robot's centre was in at the end of a step (the home cell counts from the start), divided by the optimum, the cells a robot at full speed that never revisits a cell could enter (at most every reachable cell).";

/// g, whatever the homing mode.
const HOMING: &str = "g = 1 − d_final / d_max, clamped to [0, 1]: d_final is the distance from home at the end of the trial, d_max the largest distance from home to a vertex of the room's outline.";

/// g's escape rule, by homing mode.
fn escape(homing: Homing) -> &'static str {
    match homing {
        Homing::Escape => {
            "With `fitness.homing = \"escape\"` (the default), g is as above if the robot left the home zone during the trial, else 0: a robot that never leaves home has not homed."
        }
        Homing::Distance => {
            "With `fitness.homing = \"distance\"` (the first release), g is as above whether or not the robot left the home zone."
        }
    }
}

/// l, whatever the orientation mode.
const ORIENTATION: [&str; 2] = [
    "l is 0 during evolution, as in the paper (O = 0); rooms are recognised after evolution.",
    "With `fitness.orientation = \"online\"` and O > 0, l is the share of rooms the robot recognised during evolution (a second run in every room, told apart by 1-nearest neighbour), the same in all its rooms.",
];

/// b, whatever the motion model.
const BATTERY: &str =
    "b = (sum of step energies) / T: an idle step (after the trial ended at home) uses none.";

/// A step's energy, by motion model.
fn step_energy(motion: Motion) -> &'static str {
    match motion {
        Motion::Actions => {
            "With `robot.motion = \"actions\"` (the default), every action (a move or a turn) uses one unit, so b is the number of executed steps divided by T."
        }
        Motion::Wheels => {
            "With `robot.motion = \"wheels\"`, a step uses (|sL| + |sR|) / (2·v_max) of its commanded wheel speeds (before noise), 1 at full speed."
        }
    }
}

/// b's fuzzy input, by energy mode.
fn battery_input(energy: EnergyMode) -> &'static str {
    match energy {
        EnergyMode::Use => {
            "With `fitness.energy = \"use\"` (the default), the fuzzy input is Y₄ = b: the paper calls energy the opposite of laziness."
        }
        EnergyMode::Conserve => {
            "With `fitness.energy = \"conserve\"`, the fuzzy input is Y₄ = 1 − b."
        }
    }
}

/// a, g, l, b as a run with these modes measures them (docs/model.md §7).
pub fn terms(homing: Homing, motion: Motion, energy: EnergyMode) -> [Term; 4] {
    let definitions = [
        vec![EXPLORATION],
        vec![HOMING, escape(homing)],
        ORIENTATION.to_vec(),
        vec![BATTERY, step_energy(motion), battery_input(energy)],
    ];
    let mut definitions = definitions.into_iter();
    NAMES.map(|(symbol, name, title)| Term {
        symbol,
        name,
        title,
        definition: definitions.next().expect("four definitions"),
    })
}

/// The definition of a mission term (docs/model.md §7) in one sentence, by name; `None` for
/// another name.
pub fn mission_term_definition(name: &str) -> Option<&'static str> {
    Some(match name {
        "goal" => {
            "1 once the robot's centre has been in the room's goal zone, else 1 − (closest approach to the zone) / (the room's largest distance)."
        }
        "urgency" => {
            "1 − t_done / T, with t_done the step at which the mission (waypoints, then the goal) is done; 0 if it is never done."
        }
        "waypoints" => {
            "the fraction of the room's waypoints visited (in order by default, `fitness.waypoints = \"any-order\"` otherwise)."
        }
        "safety" => "1 − the share of executed steps whose move was blocked by a wall.",
        _ => return None,
    })
}

/// A sentence as HTML: escaped, `code` in backticks as `<code>`.
pub fn html(text: &str) -> String {
    esc(text)
        .split('`')
        .enumerate()
        .map(|(k, part)| {
            if k % 2 == 1 {
                format!("<code>{part}</code>")
            } else {
                part.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/model.md §7 with its lines joined (one space between words).
    fn model_section_7() -> String {
        let doc = include_str!("../../../docs/model.md");
        let start = doc
            .find("## 7. Fitness terms")
            .expect("docs/model.md has §7");
        let end = start + doc[start..].find("\n## 8.").expect("and §8 after it");
        doc[start..end]
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// Every sentence the report can say about a term, under every homing, motion and energy
    /// mode, is docs/model.md §7's own, word for word.
    #[test]
    fn term_texts_are_docs_model_md_section_7s() {
        let doc = model_section_7();
        for homing in [Homing::Escape, Homing::Distance] {
            for motion in [Motion::Actions, Motion::Wheels] {
                for energy in [EnergyMode::Use, EnergyMode::Conserve] {
                    for term in terms(homing, motion, energy) {
                        for sentence in term.definition {
                            assert!(
                                doc.contains(sentence),
                                "docs/model.md §7 does not say, word for word: {sentence}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// Each model gets its own g and b: the escape rule only with escape homing, the wheel
    /// speeds only with wheels motion, the unit per action only with actions motion.
    #[test]
    fn each_model_gets_its_own_g_and_b() {
        let text = |h, m, e| {
            terms(h, m, e)
                .iter()
                .flat_map(|t| t.definition.clone())
                .collect::<Vec<_>>()
                .join(" ")
        };
        let default = text(Homing::Escape, Motion::Actions, EnergyMode::Use);
        assert!(default.contains("if the robot left the home zone during the trial, else 0"));
        assert!(default.contains("every action (a move or a turn) uses one unit"));
        assert!(default.contains("Y₄ = b:"));
        assert!(!default.contains("wheel"));
        let first = text(Homing::Distance, Motion::Wheels, EnergyMode::Conserve);
        assert!(first.contains("whether or not the robot left the home zone"));
        assert!(first.contains("(|sL| + |sR|) / (2·v_max)"));
        assert!(first.contains("Y₄ = 1 − b"));
        assert!(!first.contains("one unit") && !first.contains("else 0"));
    }

    #[test]
    fn html_escapes_and_marks_code() {
        assert_eq!(
            html("With `a = \"x\"` & b < c"),
            "With <code>a = &quot;x&quot;</code> &amp; b &lt; c"
        );
    }
}
