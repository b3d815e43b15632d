//! Motivations in the lab: the lists the page builds its sliders from (the presets, or the
//! `[motivations]` of a config the user loads), and "What would F be?" over N named inputs.

use std::collections::BTreeMap;

use fuzzymotiv::experiment::RawConfig;
use fuzzymotiv::fitness::{Motivations, RawMotivation, RawMotivations, TermId, TskFitness};
use serde_json::{Value, json};

use crate::errors::ApiError;

/// The paper's two settings and the fetch mission of `configs/fetch.toml` (the paper's four
/// and urgency, bound to the rooms' goals), as `(name, [motivations])`.
pub fn presets() -> Vec<(&'static str, RawMotivations)> {
    let fetch = [0.5, 0.1, 0.0, 0.1];
    let mut with_urgency = RawMotivations::paper(fetch);
    with_urgency
        .list
        .push(("urgency".into(), RawMotivation::Weight(0.3)));
    vec![
        (
            "high curiosity",
            RawMotivations::paper([0.8, 0.1, 0.0, 0.1]),
        ),
        ("low curiosity", RawMotivations::paper([0.5, 0.3, 0.0, 0.2])),
        ("fetch", with_urgency),
    ]
}

/// The motivations as the page draws its sliders: one `{name, weight, term, spec}` per
/// motivation, in input order (`spec` is the motivation as written, sent back with the new
/// weight). `source` names where they came from in messages.
pub fn listed(raw: &RawMotivations, source: &str) -> Result<Vec<Value>, ApiError> {
    let m = checked(raw, source)?;
    Ok(m.iter()
        .zip(&raw.list)
        .map(|(m, (_, spec))| {
            json!({ "name": m.name(), "weight": m.weight(), "term": m.term(), "spec": spec })
        })
        .collect())
}

/// The validated motivations (the shared labels of the paper); a term the library does not
/// measure is refused naming the motivation, as `fuzzymotiv run` does.
pub fn checked(raw: &RawMotivations, source: &str) -> Result<Motivations, ApiError> {
    let m = raw
        .validated(&TskFitness::paper())
        .map_err(|e| ApiError::bad(format!("{source}: field `{}`: {}", e.field, e.reason)))?;
    if let Some(bad) = m.iter().find(|m| TermId::library(m.term()).is_none()) {
        return Err(ApiError::bad(format!(
            "{source}: field `motivations.{}`: weighs the term {:?}, which the lab does not know; a motivation weighs one of the terms {} (terms of your own run from Rust or Python)",
            bad.name(),
            bad.term(),
            fuzzymotiv::fitness::LIBRARY_TERMS.join(", ")
        )));
    }
    Ok(m)
}

/// The motivations of a config file's text (its other sections are the lab's to set).
pub fn of_config(text: &str) -> Result<Vec<Value>, ApiError> {
    const SOURCE: &str = "loaded config";
    let raw = RawConfig::parse(text, SOURCE, &[]).map_err(|e| ApiError::bad(e.to_string()))?;
    listed(&raw.motivations, SOURCE)
}

/// `motivations` of an explain request: `[C, H, O, E]` (the paper's four) or named as in a
/// config's `[motivations]`.
pub fn explain_motivations(v: Value) -> Result<Motivations, ApiError> {
    const SOURCE: &str = "request body";
    let raw = match v {
        Value::Array(_) => {
            let x: [f64; 4] = serde_json::from_value(v).map_err(|e| {
                ApiError::bad(format!("{SOURCE}: field `motivations`: {e} (expected [C, H, O, E] or {{ name: weight, … }})"))
            })?;
            RawMotivations::paper(x)
        }
        v => serde_json::from_value(v)
            .map_err(|e| ApiError::bad(format!("{SOURCE}: field `motivations`: {e}")))?,
    };
    checked(&raw, SOURCE)
}

/// `fitness` of an explain request, one value per motivation in input order: `[a, g, l, b]`
/// for the paper's four, or `{ term: value, … }` naming each input (the term, or the
/// motivation's name where two weigh the same term).
pub fn explain_inputs(m: &Motivations, v: Value) -> Result<Vec<f64>, ApiError> {
    let names = m.input_names();
    let values: BTreeMap<String, f64> = match v {
        Value::Array(_) => {
            let y: Vec<f64> = serde_json::from_value(v)
                .map_err(|e| ApiError::bad(format!("request body: field `fitness`: {e}")))?;
            if y.len() != names.len() {
                return Err(ApiError::bad(format!(
                    "request body: field `fitness`: {} values for {} motivations; give one per motivation ({}), or name them {{ term: value }}",
                    y.len(),
                    names.len(),
                    names.join(", ")
                )));
            }
            names.iter().cloned().zip(y).collect()
        }
        v => serde_json::from_value(v)
            .map_err(|e| ApiError::bad(format!("request body: field `fitness`: {e}")))?,
    };
    if let Some(k) = values.keys().find(|k| !names.contains(k)) {
        return Err(ApiError::bad(format!(
            "request body: field `fitness.{k}`: no motivation weighs it; the inputs are {}",
            names.join(", ")
        )));
    }
    names
        .iter()
        .map(|n| match values.get(n) {
            Some(v) if v.is_finite() => Ok(*v),
            Some(_) => Err(ApiError::bad(format!(
                "request body: field `fitness.{n}`: must be a finite number (terms are clamped to [0, 1])"
            ))),
            None => Err(ApiError::bad(format!(
                "request body: field `fitness.{n}`: missing; give a value in [0, 1] for every input ({})",
                names.join(", ")
            ))),
        })
        .collect()
}
