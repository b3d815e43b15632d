//! Which terms an experiment measures: each motivation's term resolved to the library's or a
//! user-defined one ([`crate::fitness::Term`]), the mission it follows in each room, and the
//! fuzzy inputs `Y` of a trial's terms.

use std::sync::Arc;

use crate::experiment::Experiment;
use crate::experiment::config::{Combination, EnergyMode};
use crate::fitness::terms::{
    FitnessTerms, LIBRARY_TERMS, MAX_USER_TERMS, MissionTracker, RECORD_COLUMN_NAMES, Term, TermId,
    WaypointOrder,
};
use crate::fitness::{MAX_MOTIVATIONS, Motivations, PAPER_MOTIVATIONS, TskFitness};
use crate::params::{FieldError, joined_list};
use crate::simulation::room::{Room, Zone};

/// A term registered with an experiment under a name a motivation's `term` can use: computed by
/// the library from each trial's record ([`Term`]), or, with no `Term`, supplied by the front
/// that drives the experiment (Python's batched terms), which fills
/// [`FitnessTerms::user`] before F is computed ([`Experiment::refit`]).
#[derive(Debug, Clone)]
pub struct UserTerm {
    /// The name motivations use.
    pub name: String,
    /// How it is computed, or `None` when the front supplies its values.
    pub term: Option<Arc<dyn Term>>,
}

impl UserTerm {
    /// A term computed by the library from each trial's record.
    pub fn computed(name: impl Into<String>, term: Arc<dyn Term>) -> UserTerm {
        UserTerm {
            name: name.into(),
            term: Some(term),
        }
    }

    /// A term whose values the front supplies.
    pub fn supplied(name: impl Into<String>) -> UserTerm {
        UserTerm {
            name: name.into(),
            term: None,
        }
    }
}

/// The terms an experiment measures, resolved once.
#[derive(Debug, Clone)]
pub(crate) struct TermPlan {
    /// The term of each motivation, in input order.
    pub(crate) inputs: Vec<TermId>,
    /// The user-defined terms, in registration order.
    pub(crate) user: Vec<UserTerm>,
    /// Whether any mission term is weighed (then every trial follows its room's mission).
    pub(crate) mission: bool,
    /// How waypoints count.
    pub(crate) order: WaypointOrder,
    /// Whether a trial ends when its mission is done.
    pub(crate) end_at_mission: bool,
}

impl TermPlan {
    /// Resolves each motivation's term; checks that the rooms have the missions the terms need.
    pub(crate) fn resolve(
        motivations: &Motivations,
        user: &[UserTerm],
        rooms: &[Room],
        order: WaypointOrder,
        end_at_mission: bool,
    ) -> Result<TermPlan, FieldError> {
        check_user_terms(user)?;
        let mut inputs = Vec::with_capacity(MAX_MOTIVATIONS);
        for m in motivations.iter() {
            let id = TermId::library(m.term())
                .or_else(|| {
                    user.iter()
                        .position(|u| u.name == m.term())
                        .map(TermId::User)
                })
                .ok_or_else(|| unknown_term(m.name(), m.term(), user))?;
            check_missions(m.name(), id, rooms)?;
            inputs.push(id);
        }
        let mission = inputs.iter().any(|id| id.is_mission());
        if end_at_mission && !mission {
            return Err(FieldError::new(
                "fitness.end_at_mission",
                "is true, but no motivation weighs a mission term (goal, urgency, waypoints or safety); set it to false or bind a motivation to one",
            ));
        }
        Ok(TermPlan {
            inputs,
            user: user.to_vec(),
            mission,
            order,
            end_at_mission,
        })
    }

    /// A tracker of `room`'s mission, when the experiment measures mission terms.
    pub(crate) fn tracker(&self, room: &Room) -> Option<MissionTracker> {
        self.mission.then(|| {
            let (goal, waypoints) = mission_of(room);
            MissionTracker::new(room, goal, waypoints, self.order, self.end_at_mission)
        })
    }
}

/// The goal and waypoints of `room`'s mission.
pub(crate) fn mission_of(room: &Room) -> (Option<Zone>, Vec<Zone>) {
    (room.mission.goal, room.mission.waypoints.clone())
}

/// At most [`MAX_USER_TERMS`], named apart from each other, from the library's terms and from
/// the records' columns ([`RECORD_COLUMN_NAMES`]).
fn check_user_terms(user: &[UserTerm]) -> Result<(), FieldError> {
    if user.len() > MAX_USER_TERMS {
        return Err(FieldError::new(
            "terms",
            format!(
                "at most {MAX_USER_TERMS} user-defined terms, got {}",
                user.len()
            ),
        ));
    }
    for (i, u) in user.iter().enumerate() {
        let clash =
            TermId::library(&u.name).is_some() || user[..i].iter().any(|o| o.name == u.name);
        let plain = !u.name.is_empty()
            && u.name.len() <= 40
            && u.name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if clash || !plain {
            return Err(FieldError::new(
                format!("terms.{}", u.name),
                "a user-defined term needs its own plain name (letters, digits, '_' or '-', at most 40), not one of the library's terms (a, g, l, b, goal, urgency, waypoints, safety) nor another user term's",
            ));
        }
        if names_a_record_column(&u.name, user) {
            return Err(FieldError::new(
                format!("terms.{}", u.name),
                format!(
                    "is a name the records already give a column (test_runs.csv writes a term NAME as NAME_pct, robustness.csv as NAME, NAME_lo and NAME_hi), so a user-defined term cannot be named {}, nor any of these, a library term or another user term followed by _lo or _hi; name it otherwise, e.g. my_{}",
                    joined_list(&RECORD_COLUMN_NAMES, "or"),
                    u.name
                ),
            ));
        }
    }
    Ok(())
}

/// Whether a term `name` would write a column the records already have: `name`, or `name`
/// without a `_lo`/`_hi`, is one of [`RECORD_COLUMN_NAMES`]; or `name` without it is a library
/// term or one of the `user` terms (whose robustness column `name` would repeat).
fn names_a_record_column(name: &str, user: &[UserTerm]) -> bool {
    let stem = ["_lo", "_hi"]
        .iter()
        .find_map(|s| name.strip_suffix(s))
        .filter(|stem| !stem.is_empty());
    let reserved = |n: &str| RECORD_COLUMN_NAMES.contains(&n);
    reserved(name)
        || stem.is_some_and(|s| {
            reserved(s) || TermId::library(s).is_some() || user.iter().any(|o| o.name == s)
        })
}

fn unknown_term(motivation: &str, term: &str, user: &[UserTerm]) -> FieldError {
    let mut known: Vec<&str> = LIBRARY_TERMS.to_vec();
    known.extend(user.iter().map(|u| u.name.as_str()));
    let mut reason = format!(
        "weighs the term {term:?}, which does not exist; a motivation weighs one of the terms {} (write {motivation} = {{ weight = …, term = \"…\" }}; a motivation without `term` weighs the term of its own name)",
        known.join(", ")
    );
    reason.push_str(&case_hint(term, &known));
    FieldError::new(format!("motivations.{motivation}"), reason)
}

/// For a name that is one of the paper's motivations or of the `known` terms but for its case
/// (`Curiosity`): ". Names are case-sensitive: did you mean `curiosity`?"; otherwise nothing.
/// A config's `[motivations]` and `fuzzy --motivations` give the same hint.
pub fn case_hint(name: &str, known: &[&str]) -> String {
    let spelled = |n: &&str| *n != name && n.eq_ignore_ascii_case(name);
    (PAPER_MOTIVATIONS.iter().copied())
        .chain(known.iter().copied())
        .find(spelled)
        .map_or_else(String::new, |like| {
            format!(". Names are case-sensitive: did you mean `{like}`?")
        })
}

/// A mission term needs its mission in every room: `goal` a goal, `waypoints` waypoints,
/// `urgency` either.
fn check_missions(motivation: &str, id: TermId, rooms: &[Room]) -> Result<(), FieldError> {
    for (i, room) in rooms.iter().enumerate() {
        let (goal, waypoints) = mission_of(room);
        let missing = match id {
            TermId::Goal if goal.is_none() => "goal zone (goal = { x, y, radius })",
            TermId::Waypoints if waypoints.is_empty() => "waypoints ([[waypoints]] x, y, radius)",
            TermId::Urgency if goal.is_none() && waypoints.is_empty() => {
                "mission (neither a goal zone nor waypoints)"
            }
            _ => continue,
        };
        return Err(FieldError::new(
            format!("rooms[{i}]"),
            format!(
                "motivation {motivation} weighs a mission term, but room \"{}\" has no {missing}; give its room file one, or leave the room out",
                room.name
            ),
        ));
    }
    Ok(())
}

/// `Σ X_i · g(Y_i)`, each `Y_i` clamped to [0, 1] (NaN as 0) as the TSK clamps its inputs.
fn weighted(x: &Motivations, y: &[f64], g: impl Fn(f64) -> f64) -> f64 {
    x.iter()
        .zip(y)
        .map(|(m, &v)| m.weight() * g(if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) }))
        .sum()
}

impl Combination {
    /// F of the fuzzy inputs `y` (one per motivation of `x`) under this combination: the TSK
    /// `tsk`'s, or a baseline's (the F of a trial, and of the lab's "What would F be?").
    #[inline]
    pub fn fitness(self, tsk: &TskFitness, x: &Motivations, y: &[f64]) -> f64 {
        match self {
            Combination::Tsk => tsk.evaluate(x, y),
            Combination::WeightedSum => weighted(x, y, |v| v),
            Combination::WeightedSquares => weighted(x, y, |v| v * v),
        }
    }
}

impl Experiment {
    /// The fuzzy inputs `Y` for a trial's terms, one per motivation (with `energy =
    /// "conserve"`, the battery term is `1 − b`).
    pub fn fuzzy_inputs(&self, terms: &FitnessTerms) -> Vec<f64> {
        self.plan
            .inputs
            .iter()
            .map(|&id| match (id, self.energy) {
                (TermId::B, EnergyMode::Conserve) => 1.0 - terms.b,
                _ => terms.get(id),
            })
            .collect()
    }

    /// F for a trial's terms under this experiment's motivations.
    pub fn fuzzy_fitness(&self, terms: &FitnessTerms) -> f64 {
        let mut y = [0.0; MAX_MOTIVATIONS];
        for (slot, &id) in y.iter_mut().zip(&self.plan.inputs) {
            *slot = match (id, self.energy) {
                (TermId::B, EnergyMode::Conserve) => 1.0 - terms.b,
                _ => terms.get(id),
            };
        }
        let y = &y[..self.plan.inputs.len()];
        self.combine.fitness(&self.fuzzy, &self.motivations, y)
    }

    /// How the motivations combine the terms.
    pub fn combination(&self) -> Combination {
        self.combine
    }

    /// The term each motivation weighs, in input order.
    pub fn input_terms(&self) -> &[TermId] {
        &self.plan.inputs
    }

    /// The user-defined terms, in registration order.
    pub fn user_terms(&self) -> &[UserTerm] {
        &self.plan.user
    }

    /// Whether trials follow their room's mission (a motivation weighs a mission term).
    pub fn measures_mission(&self) -> bool {
        self.plan.mission
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::RawConfig;
    use crate::simulation::room::BUILTIN_ROOMS;

    fn build(config: &str, user: &[UserTerm]) -> Result<Experiment, FieldError> {
        let text = format!(
            "[ga]\npopulation = 6\ngenerations = 2\n[trial]\nsteps = 80\n[aem]\nepochs = 5\ntest_runs = 2\n{config}"
        );
        let raw = RawConfig::parse(&text, "c.toml", &[])?;
        let rooms = BUILTIN_ROOMS
            .iter()
            .map(|r| Room::builtin(r).unwrap())
            .collect();
        Experiment::with_terms(&raw, rooms, user, "c.toml")
    }

    /// A config without `[motivations]` has the paper's four, in paper order, bound to a, g,
    /// l, b, and writes them back as before.
    #[test]
    fn the_paper_four_are_the_default_and_write_back_as_before() {
        let exp = build("", &[]).unwrap();
        assert!(exp.motivations().is_paper());
        assert_eq!(
            exp.input_terms(),
            [TermId::A, TermId::G, TermId::L, TermId::B]
        );
        let raw = RawConfig::parse("", "c.toml", &[]).unwrap();
        let text = raw.to_toml();
        let at = text.find("[motivations]").unwrap();
        assert!(
            text[at..].starts_with(
                "[motivations]\ncuriosity = 0.8\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\n"
            ),
            "{text}"
        );
        assert!(!text.contains("waypoints"), "{text}");
    }

    /// Five motivations: the paper's four and one of one's own bound to `safety`, in input
    /// order paper-first; the table form records its term.
    #[test]
    fn a_fifth_motivation_is_an_input_after_the_paper_four() {
        let exp = build(
            "[motivations]\ncuriosity = 0.6\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\ncare = { weight = 0.2, term = \"safety\" }\n",
            &[],
        )
        .unwrap();
        let names: Vec<&str> = exp.motivations().iter().map(|m| m.name()).collect();
        assert_eq!(
            names,
            ["curiosity", "homing", "orientation", "energy", "care"]
        );
        assert_eq!(exp.input_terms()[4], TermId::Safety);
        assert!(exp.measures_mission());
        let raw = RawConfig::parse(
            "[motivations]\ncuriosity = 0.6\nhoming = 0.1\norientation = 0.0\nenergy = 0.1\ncare = { weight = 0.2, term = \"safety\" }\n",
            "c.toml",
            &[],
        )
        .unwrap();
        assert!(
            raw.to_toml().contains("term = \"safety\""),
            "{}",
            raw.to_toml()
        );
    }

    /// One motivation alone (N = 1) when none of the paper's is named.
    #[test]
    fn a_single_motivation_of_ones_own_stands_alone() {
        let exp = build("[motivations]\nsafety = 1.0\n", &[]).unwrap();
        assert_eq!(exp.motivations().len(), 1);
        assert_eq!(exp.input_terms(), [TermId::Safety]);
    }

    /// Unknown terms, too many motivations, sums off 1 and mission terms in rooms without a
    /// mission each name their field.
    #[test]
    fn bad_motivations_name_their_field() {
        let e = build("[motivations]\nfoo = 1.0\n", &[]).unwrap_err();
        assert_eq!(e.field, "motivations.foo", "{e}");
        assert!(e.reason.contains("does not exist"), "{e}");
        let nine: String = (0..9)
            .map(|k| format!("m{k} = {{ weight = 0.1, term = \"a\" }}\n"))
            .collect();
        let e = build(&format!("[motivations]\n{nine}"), &[]).unwrap_err();
        assert_eq!(e.field, "motivations", "{e}");
        assert!(e.reason.contains("from 1 to 8"), "{e}");
        let e = build("[motivations]\nsafety = 0.5\ngoal = 0.2\n", &[]).unwrap_err();
        assert!(e.reason.contains("sum to 1"), "{e}");
        let e = build("[motivations]\nsafety = 0.5\ngoal = 0.5\n", &[]).unwrap_err();
        assert_eq!(e.field, "rooms[0]", "{e}");
        assert!(
            e.reason.contains("no a goal zone") || e.reason.contains("goal zone"),
            "{e}"
        );
        let e = build(
            "[motivations]\nsafety = { weight = 1.0, peaks = [0.5, 0.2] }\n",
            &[],
        )
        .unwrap_err();
        assert_eq!(e.field, "motivations.safety.peaks", "{e}");
        let e = build("[fitness]\nend_at_mission = true\n", &[]).unwrap_err();
        assert_eq!(e.field, "fitness.end_at_mission", "{e}");
    }

    /// The baselines: a weighted sum and a weighted sum of squares of the same inputs; on the
    /// peaks of the default labels the TSK equals the weighted squares.
    #[test]
    fn the_baseline_combinations_follow_their_formulas() {
        let t = FitnessTerms {
            a: 0.9,
            g: 0.3,
            l: 0.0,
            b: 0.7,
            ..Default::default()
        };
        let f = |combine: &str| {
            build(&format!("[fitness]\ncombine = \"{combine}\"\n"), &[])
                .unwrap()
                .fuzzy_fitness(&t)
        };
        assert_eq!(f("weighted-sum"), 0.8 * 0.9 + 0.1 * 0.3 + 0.0 + 0.1 * 0.7);
        assert_eq!(
            f("weighted-squares"),
            0.8 * 0.81 + 0.1 * 0.09 + 0.0 + 0.1 * 0.49
        );
        let on_peaks = FitnessTerms {
            a: 0.75,
            g: 0.25,
            l: 0.0,
            b: 1.0,
            ..Default::default()
        };
        let exp = build("", &[]).unwrap();
        let squares = build("[fitness]\ncombine = \"weighted-squares\"\n", &[]).unwrap();
        assert!((exp.fuzzy_fitness(&on_peaks) - squares.fuzzy_fitness(&on_peaks)).abs() < 1e-15);
        assert_ne!(f("tsk"), f("weighted-sum"));
        let e = build("[fitness]\ncombine = \"product\"\n", &[]).unwrap_err();
        assert_eq!(e.field, "fitness.combine", "{e}");
    }

    /// A term of one's own, computed from each trial's record, is the input of the motivation
    /// that names it: a constant term of 0.25 with weight 1 gives F = 0.25 · C[label] blends,
    /// and equals the TSK of that value.
    #[test]
    fn a_user_term_of_known_value_sets_f_by_its_formula() {
        #[derive(Debug)]
        struct Quarter;
        impl Term for Quarter {
            fn value(&self, _: &crate::fitness::terms::TrialRecord<'_>) -> f64 {
                0.25
            }
        }
        let exp = build(
            "[motivations]\nsteady = { weight = 1.0, term = \"quarter\" }\n",
            &[UserTerm::computed("quarter", Arc::new(Quarter))],
        )
        .unwrap();
        let run = &exp.runs()[0];
        let genome = exp.initial_population(run).network(0);
        let e = exp.evaluate(&genome, run, 0, 0);
        // One input at 0.25, the peak of label L (C = 0.25): F = 1 · 0.25 · 0.25.
        for s in &e.per_room {
            assert_eq!(s.terms.user.as_slice(), [0.25]);
            assert_eq!(s.f, 0.0625);
        }
    }

    /// A user term named like a column the records write for the paper's measures or the
    /// missions (`recognition` → `recognition_pct`, `mission_done` → `mission_done_pct`, `f`,
    /// `missions_done`, or `NAME_lo`/`NAME_hi` of a column or term) is an input error naming the
    /// term, saying which names are taken and suggesting another; other names, and the
    /// library's terms as motivation terms, still work.
    #[test]
    fn a_user_term_named_like_a_record_column_is_refused() {
        let config = "[motivations]\nsafety = 0.5\nsmooth = { weight = 0.5, term = \"smooth\" }\n";
        for taken in [
            "recognition",
            "mission_done",
            "missions_done",
            "f",
            "trials",
            "homing_lo",
            "goal_hi",
            "smooth_lo",
        ] {
            let user = [UserTerm::supplied("smooth"), UserTerm::supplied(taken)];
            let e = build(config, &user).unwrap_err();
            assert_eq!(e.field, format!("terms.{taken}"), "{e}");
            assert!(
                e.reason
                    .contains("recognition, battery, homing, mission_done"),
                "{e}"
            );
            assert!(e.reason.contains(&format!("e.g. my_{taken}")), "{e}");
        }
        for free in ["my_recognition", "recognised", "lo", "_hi"] {
            let user = [UserTerm::supplied("smooth"), UserTerm::supplied(free)];
            build(config, &user).unwrap_or_else(|e| panic!("{free}: {e}"));
        }
        for library in LIBRARY_TERMS
            .iter()
            .filter(|t| !["goal", "waypoints", "urgency"].contains(t))
        {
            let config = format!("[motivations]\nm = {{ weight = 1.0, term = \"{library}\" }}\n");
            build(&config, &[UserTerm::supplied("smooth")])
                .unwrap_or_else(|e| panic!("{library}: {e}"));
        }
    }

    /// The instance run (replays, the lab's paths, figures) measures the mission terms as the
    /// evaluation does, so its F is the evaluation's formula.
    #[test]
    fn the_instance_run_measures_the_mission_terms_too() {
        let exp = build("[motivations]\nsafety = 1.0\n", &[]).unwrap();
        let run = &exp.runs()[0];
        let network = exp.initial_population(run).network(1);
        let instance = exp.instance_run(&network, run, 0);
        let safety = instance
            .terms
            .mission
            .expect("mission terms measured")
            .safety;
        assert_eq!(instance.f, exp.fuzzy_fitness(&instance.terms));
        assert!((0.0..=1.0).contains(&safety));
    }

    /// `fitness.end_at_mission = true` ends each evaluation trial the step its mission is done,
    /// in the lanes (`evaluate_population`) as in `evaluate`: a goal zone around home is
    /// reached at step 1 whatever the robot does, so every trial executes 1 step (urgency
    /// 1 − 1/80); without the option the same trials run on.
    #[test]
    fn end_at_mission_ends_each_evaluation_trial_when_its_mission_is_done() {
        let room = Room::from_toml_str(
            "name='m'\noutline=[[0,0],[800,0],[800,400],[0,400]]\nhome={x=100,y=200,heading_deg=0}\ngoal={x=100,y=200,radius=100}\n",
            "m.toml",
        )
        .unwrap();
        let build = |end: bool| {
            let text = format!(
                "[ga]\npopulation = 8\ngenerations = 2\n[trial]\nsteps = 80\n[aem]\nenabled = false\n[motivations]\ncuriosity = 0.5\nhoming = 0.0\nenergy = 0.0\nhurry = {{ weight = 0.5, term = \"urgency\" }}\n[fitness]\nend_at_mission = {end}\n"
            );
            let raw = RawConfig::parse(&text, "c.toml", &[]).unwrap();
            Experiment::with_terms(&raw, vec![room.clone()], &[], "c.toml").unwrap()
        };
        let scores = |exp: &Experiment| {
            let run = &exp.runs()[0];
            let population = exp.initial_population(run);
            let lanes = exp.evaluate_population(&population, run, 0);
            let alone: Vec<_> = (0..population.len())
                .map(|i| exp.evaluate(&population.network(i), run, 0, i))
                .collect();
            assert_eq!(format!("{lanes:?}"), format!("{alone:?}"));
            lanes
                .into_iter()
                .flat_map(|e| e.per_room)
                .collect::<Vec<_>>()
        };
        let ending = scores(&build(true));
        assert_eq!(ending.len(), 8);
        for s in &ending {
            let m = s.terms.mission.unwrap();
            assert_eq!((s.executed, m.done_at), (1, Some(1)), "{s:?}");
            assert_eq!(m.urgency, 1.0 - 1.0 / 80.0);
        }
        let going_on = scores(&build(false));
        for (on, ended) in going_on.iter().zip(&ending) {
            let m = on.terms.mission.unwrap();
            assert_eq!(m.done_at, Some(1));
            assert!(on.executed > 1, "{on:?}");
            assert!(on.terms.b >= ended.terms.b, "{on:?} vs {ended:?}");
        }
        // The instance run (replays, figures) ends there too.
        let exp = build(true);
        let run = &exp.runs()[0];
        let instance = exp.instance_run(&exp.initial_population(run).network(0), run, 0);
        assert_eq!(instance.trajectory.executed(), 1);
        assert_eq!(instance.trajectory.len(), 80);
    }

    /// The safety term is 1 − (blocked moves / executed steps) of the trial.
    #[test]
    fn safety_counts_the_blocked_moves() {
        let exp = build("[motivations]\nsafety = 1.0\n", &[]).unwrap();
        let run = &exp.runs()[0];
        let genome = exp.initial_population(run).network(1);
        let (terms, _) = exp.trial(&genome, 0, 99);
        let arena = &exp.arenas()[0];
        let mut tr = crate::simulation::trial::Trajectory::starting_at(arena.room().home, 80);
        crate::simulation::trial::simulate(
            arena,
            &mut genome.clone(),
            &mut crate::random::rng::rng_from_seed(99),
            &mut tr,
        );
        let executed = tr.idle.iter().filter(|i| !**i).count();
        let blocked = tr
            .collisions
            .iter()
            .zip(&tr.idle)
            .filter(|(c, i)| **c && !**i)
            .count();
        let safety = terms.mission.unwrap().safety;
        assert_eq!(safety, 1.0 - blocked as f64 / executed as f64);
    }
}
