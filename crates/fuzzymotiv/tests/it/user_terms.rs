//! The guide's term of one's own (docs/guide/motivations.md §5), as a user writes it: through
//! the public API only.

use std::sync::Arc;

use fuzzymotiv::experiment::UserTerm;
use fuzzymotiv::fitness::{Term, TrialRecord};

/// Smoothness: 1 − the share of executed steps that turned.
#[derive(Debug)]
struct Smooth;

impl Term for Smooth {
    fn value(&self, trial: &TrialRecord<'_>) -> f64 {
        let t = trial.trajectory;
        let steps = t.idle.iter().filter(|i| !**i).count().max(1);
        let turns = t
            .poses
            .windows(2)
            .filter(|p| p[0].heading != p[1].heading)
            .count();
        1.0 - turns as f64 / steps as f64
    }
}

const CONFIG: &str = "[ga]\npopulation = 6\ngenerations = 2\n[trial]\nsteps = 120\n[aem]\nenabled = false\n[motivations]\ncuriosity = 0.7\nhoming = 0.1\norientation = 0.0\nenergy = 0.0\nsmooth = 0.2\n";

fn experiment(terms: &[UserTerm]) -> Result<fuzzymotiv::Experiment, fuzzymotiv::FieldError> {
    let raw = fuzzymotiv::RawConfig::parse(CONFIG, "mine.toml", &[])?;
    let rooms = vec![fuzzymotiv::Room::builtin("H").unwrap()];
    fuzzymotiv::Experiment::with_terms(&raw, rooms, terms, "mine.toml")
}

/// The motivation `smooth` weighs the registered term: each trial's value is the formula's,
/// computed from the same trial's trajectory, and F is the TSK of the five inputs.
#[test]
fn a_rust_term_is_weighed_by_the_motivation_that_names_it() {
    let exp = experiment(&[UserTerm::computed("smooth", Arc::new(Smooth))]).unwrap();
    assert_eq!(exp.motivations().len(), 5);
    let run = &exp.runs()[0];
    let network = exp.initial_population(run).network(2);
    let e = exp.evaluate(&network, run, 0, 2);
    let s = e.per_room[0];
    let v = s.terms.user.as_slice()[0];
    assert!((0.0..=1.0).contains(&v), "{v}");
    let mut y = exp.fuzzy_inputs(&s.terms);
    assert_eq!(y[4], v);
    assert_eq!(exp.fuzzy().evaluate(exp.motivations(), &y), s.f);
    // Another value of the term gives another F: the term is an input, not decoration.
    y[4] = 1.0 - v;
    assert_ne!(exp.fuzzy().evaluate(exp.motivations(), &y), s.f);
}

/// Without the term registered, the config is refused naming the motivation.
#[test]
fn an_unregistered_term_names_its_motivation() {
    let e = experiment(&[]).unwrap_err();
    assert_eq!(e.field, "motivations.smooth");
    assert_eq!(e.source_name, "mine.toml");
}

/// A term that returns a fixed value, to check the range.
#[derive(Debug)]
struct Fixed(f64);

impl Term for Fixed {
    fn value(&self, _: &TrialRecord<'_>) -> f64 {
        self.0
    }
}

/// An evaluation with the term `smooth` returning `value`.
fn evaluate_with_smooth(value: f64) -> f64 {
    let exp = experiment(&[UserTerm::computed("smooth", Arc::new(Fixed(value)))]).unwrap();
    let run = &exp.runs()[0];
    let network = exp.initial_population(run).network(0);
    exp.evaluate(&network, run, 0, 0).per_room[0]
        .terms
        .user
        .as_slice()[0]
}

/// The bounds are values like any other.
#[test]
fn a_term_at_its_bounds_is_taken_as_it_is() {
    assert_eq!(evaluate_with_smooth(0.0), 0.0);
    assert_eq!(evaluate_with_smooth(1.0), 1.0);
}

/// Issue #52 item 7: a value outside [0, 1], or NaN, is a bug in the term. The evaluation keeps
/// it as it came (not clamped, not counted as 0), `check_terms` names the term and the value,
/// and evolving returns that as an error (`RunError::Term`), never a panic.
#[test]
fn a_term_outside_0_1_or_nan_is_an_error_of_the_run_not_a_panic() {
    for (value, shown) in [(1.5, "1.5"), (-0.25, "-0.25"), (f64::NAN, "NaN")] {
        let kept = evaluate_with_smooth(value);
        assert!(kept.to_bits() == value.to_bits(), "{value}: kept {kept}");
        let exp = experiment(&[UserTerm::computed("smooth", Arc::new(Fixed(value)))]).unwrap();
        let run = &exp.runs()[0];
        let network = exp.initial_population(run).network(0);
        let evaluation = exp.evaluate(&network, run, 0, 0);
        let e = exp
            .check_terms(evaluation.per_room.iter().map(|s| &s.terms))
            .unwrap_err();
        assert_eq!(
            (e.term.as_str(), e.value.to_bits()),
            ("smooth", value.to_bits())
        );
        let Err(e) = exp.run(&mut |_, _| std::ops::ControlFlow::Continue(())) else {
            panic!("{value}: the run went on");
        };
        let message = e.to_string();
        assert!(matches!(e, fuzzymotiv::RunError::Term(_)), "{message}");
        assert!(
            message.contains(&format!(
                "the user-defined term \"smooth\" returned {shown}, outside [0, 1]"
            )),
            "{message}"
        );
    }
}
