//! The report's fuzzy part: the motivations as bars, the terms they weigh, how F is computed
//! with the membership functions (the shared labels and each motivation's own), and the best
//! robot's F per room with its firing rules. It follows the run's N motivations; the paper's
//! four keep the paper's wording.

use std::fmt::Write as _;

use fuzzymotiv::experiment::Combination;
use fuzzymotiv::params::joined_list;
use fuzzymotiv_records::records::RoomFuzzy;
use fuzzymotiv_records::records::context::{OwnLabels, RenderContext};

use super::{Page, Section, figure, xs};
use crate::figure::{colour, esc};
use crate::svg::{MEMBERSHIP_TITLE, membership_svg_of};
use crate::terms::{html, mission_term_definition, terms};

/// The paper's motivations: name, symbol and bar colour.
const PAPER_BARS: [(&str, &str, &str); 4] = [
    ("curiosity", "C", "#2ca02c"),
    ("homing", "H", "#9467bd"),
    ("orientation", "O", "#8c564b"),
    ("energy", "E", "#ff7f0e"),
];

/// The terms the paper's four motivations weigh, in the order of [`PAPER_BARS`].
const PAPER_TERMS: [&str; 4] = ["a", "g", "l", "b"];

/// The palette colours the paper's bars leave free, for the other motivations.
const OTHER_COLOURS: [usize; 6] = [0, 3, 6, 8, 9, 7];

/// Whether the run's motivations are the paper's four on the shared labels.
fn is_paper(ctx: &RenderContext) -> bool {
    ctx.motivations.table.is_empty() && ctx.fuzzy.own_labels.is_empty()
}

/// One bar per motivation: its label, weight and colour.
fn bars(ctx: &RenderContext) -> Vec<(String, f64, String)> {
    let m = &ctx.motivations;
    if m.table.is_empty() {
        let weights = [m.curiosity, m.homing, m.orientation, m.energy];
        return (PAPER_BARS.iter().zip(weights))
            .map(|((name, symbol, c), w)| (format!("{name} {symbol}"), w, c.to_string()))
            .collect();
    }
    let mut others = 0;
    (m.table.iter())
        .map(|e| match PAPER_BARS.iter().find(|(n, ..)| *n == e.name) {
            Some((name, symbol, c)) => (format!("{name} {symbol}"), e.weight, c.to_string()),
            None => {
                others += 1;
                let name = if e.name == e.term {
                    e.name.clone()
                } else {
                    format!("{} ({})", e.name, e.term)
                };
                let c = OTHER_COLOURS[(others - 1) % OTHER_COLOURS.len()];
                (name, e.weight, colour(c).to_string())
            }
        })
        .collect()
}

/// The motivations as bars, the terms and how F is computed, the membership functions.
fn fuzzy_intro(page: &mut Page, ctx: &RenderContext) {
    let paper = ctx.motivations.table.is_empty();
    page.push(if paper {
        "<p>The robot's <b>motivations</b> X weight the four fitness terms Y it is measured on:</p>\n<div class=\"bars\">\n"
    } else {
        "<p>The robot's <b>motivations</b> X each weight the fitness term Y it names (in brackets for a motivation not named after its term):</p>\n<div class=\"bars\">\n"
    });
    for (name, v, colour) in bars(ctx) {
        let _ = writeln!(
            page.body,
            "<span>{}</span><div class=\"bar\"><span style=\"width:{:.1}%;background:{colour}\"></span></div><span>{v}</span>",
            esc(&name),
            100.0 * v
        );
    }
    // The terms as this run's homing, motion and energy modes define them (docs/model.md §7).
    page.push("</div>\n<dl class=\"terms\">");
    for t in terms(ctx.homing, ctx.motion, ctx.energy) {
        let _ = write!(
            page.body,
            "<dt>{}</dt><dd><b>{}</b>: {}</dd>",
            t.symbol,
            esc(t.title),
            html(&t.definition.join(" "))
        );
    }
    for (name, _) in &ctx.extra_terms {
        let definition = mission_term_definition(name)
            .unwrap_or("a term of your own, computed from each trial by the function registered under this name.");
        // A name longer than the paper's one-letter symbols: its column is as wide as it.
        let _ = write!(
            page.body,
            "<dt style=\"width:auto;margin-right:0.5em\">{}</dt><dd>{}</dd>",
            esc(name),
            html(definition)
        );
    }
    page.push("</dl>");
    if is_paper(ctx) {
        paper_rule_text(page, ctx);
    } else {
        rule_text(page, ctx);
    }
    baseline_text(page, ctx);
    let fuzzy = &ctx.fuzzy;
    figure(
        page,
        &membership_svg_of(
            &fuzzy.peaks,
            &fuzzy.label_names,
            MEMBERSHIP_TITLE,
            &format!(
                "fitness value y ({})",
                joined_list(&shared_terms(ctx), "or")
            ),
        ),
        "Triangular membership functions: each value belongs to at most two neighbouring labels, and its memberships add up to 1.",
    );
    for own in &fuzzy.own_labels {
        own_membership(page, own);
    }
}

/// How F is computed, in the paper's words (four inputs on shared labels).
fn paper_rule_text(page: &mut Page, ctx: &RenderContext) {
    let fuzzy = &ctx.fuzzy;
    let labels = fuzzy.label_names.len();
    let _ = writeln!(
        page.body,
        "<p><b>How F is computed.</b> Each term y is described by fuzzy labels, very low (V.L.) to very high (V.H.) by default, with the membership functions below. A rule takes one label per term, e.g. \"if a is H and g is L and l is V.L. and b is H\"; with {labels} labels there are {labels}⁴ = {rules} rules. A rule fires with strength w = the smallest membership of its four labels, and proposes f = C·a·c(label of a) + H·g·c(label of g) + O·l·c(label of l) + E·b·c(label of b), where c = {:?} rises with the label. The fitness is the weighted mean <b>F = Σ w·f / Σ w</b>; since every value lies between two label peaks, at most 16 rules fire at once.</p>",
        fuzzy.coefficients,
        rules = fuzzy.rule_count,
    );
}

/// How F is computed over the run's N inputs, each on the shared labels or its own.
fn rule_text(page: &mut Page, ctx: &RenderContext) {
    let fuzzy = &ctx.fuzzy;
    let n = input_count(ctx);
    let shared = fuzzy.label_names.len();
    let counts: Vec<String> = (0..n)
        .map(|i| {
            own_of(ctx, i)
                .map_or(shared, |o| o.label_names.len())
                .to_string()
        })
        .collect();
    let own = if fuzzy.own_labels.is_empty() {
        String::new()
    } else {
        let names: Vec<String> = (fuzzy.own_labels.iter())
            .map(|o| esc(&o.motivation))
            .collect();
        format!(
            " ({} has labels of its own, drawn after them, each with its own c)",
            names.join(", ")
        )
    };
    let _ = writeln!(
        page.body,
        "<p><b>How F is computed.</b> Each motivation's input y (the term it weighs) is described by fuzzy labels, very low (V.L.) to very high (V.H.) by default, with the membership functions below{own}. A rule takes one label per input; with M₁ × … × M_N = {} = {rules} rules. A rule fires with strength w = the smallest membership of its {n} labels, and proposes f = Σ Xᵢ·yᵢ·c(label of yᵢ), where c = {:?} rises with the label. The fitness is the weighted mean <b>F = Σ w·f / Σ w</b>; since every value lies between two label peaks, at most 2^{n} = {} rules fire at once.</p>",
        counts.join(" × "),
        fuzzy.coefficients,
        1u64 << n.min(63),
        rules = fuzzy.rule_count,
    );
}

/// For a run whose F is a baseline combination, not the TSK: what F is instead.
fn baseline_text(page: &mut Page, ctx: &RenderContext) {
    let (what, key) = match ctx.combine {
        Combination::Tsk => return,
        Combination::WeightedSum => ("a weighted sum, F = Σ Xᵢ·Yᵢ", "weighted-sum"),
        Combination::WeightedSquares => (
            "a weighted sum of squares, F = Σ Xᵢ·Yᵢ² (the TSK's value on its peaks)",
            "weighted-squares",
        ),
    };
    let _ = writeln!(
        page.body,
        "<p><b>This run's F is not the TSK's.</b> It combines the motivations by {what} (<code>fitness.combine = \"{key}\"</code>, a baseline); the evolution, the column F below and every fitness of this report are that. The rule base is described, and each room's rules are listed, to show what the TSK would give for the same terms.</p>"
    );
}

/// The number of motivations (inputs) of the run: its table's, or the paper's four.
fn input_count(ctx: &RenderContext) -> usize {
    match ctx.motivations.table.len() {
        0 => PAPER_BARS.len(),
        n => n,
    }
}

/// The terms of the inputs on the shared labels, in input order (all of them if every
/// motivation has labels of its own): the paper's a, g, l and b, or the run's own.
fn shared_terms(ctx: &RenderContext) -> Vec<&str> {
    let inputs: Vec<(&str, &str)> = if ctx.motivations.table.is_empty() {
        PAPER_BARS
            .iter()
            .map(|(name, ..)| *name)
            .zip(PAPER_TERMS)
            .collect()
    } else {
        (ctx.motivations.table.iter())
            .map(|e| (e.name.as_str(), e.term.as_str()))
            .collect()
    };
    let own = |name: &str| ctx.fuzzy.own_labels.iter().any(|o| o.motivation == name);
    let shared: Vec<&str> = (inputs.iter())
        .filter(|(name, _)| !own(name))
        .map(|(_, term)| *term)
        .collect();
    if shared.is_empty() {
        inputs.iter().map(|(_, term)| *term).collect()
    } else {
        shared
    }
}

/// The own labels of input `i`, if its motivation has some.
fn own_of(ctx: &RenderContext, i: usize) -> Option<&OwnLabels> {
    let name = match ctx.motivations.table.get(i) {
        Some(e) => e.name.as_str(),
        None => PAPER_BARS.get(i)?.0,
    };
    (ctx.fuzzy.own_labels.iter()).find(|o| o.motivation == name)
}

/// A motivation's own membership functions, with its coefficients.
fn own_membership(page: &mut Page, own: &OwnLabels) {
    let title = format!(
        "Membership of {}'s input ({}) in its own labels",
        own.motivation, own.term
    );
    figure(
        page,
        &membership_svg_of(
            &own.peaks,
            &own.label_names,
            &title,
            &format!("value of {}", own.term),
        ),
        &format!(
            "{}'s own labels (peaks {:?}, coefficients c = {:?}): the other inputs use the shared labels above.",
            own.motivation, own.peaks, own.coefficients
        ),
    );
}

pub(super) fn fuzzy_part(page: &mut Page, s: &Section<'_>) {
    fuzzy_intro(page, s.ctx);
    page.push(
        "<p>The best robot of the last generation, as the GA evaluated it (one trial per room, \
         with noise). F is its fitness in that room; the robot's overall fitness is the mean F over \
         its rooms. Open a row's rules to see how F came about.</p>\n",
    );
    let extra = &s.ctx.extra_terms;
    page.push("<table><tr><th>room</th><th>a</th><th>g</th><th>l</th><th>b</th>");
    for (name, _) in extra {
        let _ = write!(page.body, "<th>{}</th>", esc(name));
    }
    page.push("<th>F</th><th class=\"left\">firing rules</th></tr>\n");
    for room in &s.done.fuzzy {
        let t = room.terms;
        let mut cells = format!(
            "<td>{:.3}</td><td>{:.3}</td><td>{:.3}</td><td>{:.3}</td>",
            t.a, t.g, t.l, t.b
        );
        for (_, id) in extra {
            let _ = write!(cells, "<td>{:.3}</td>", t.get(*id));
        }
        let rules = rules_html(s.ctx, room);
        let _ = writeln!(
            page.body,
            "<tr><td>{}</td>{cells}<td><b>{:.4}</b></td><td class=\"left\"><details><summary>{} rules</summary>{rules}</details></td></tr>",
            esc(&room.room),
            room.f,
            room.explanation.rules.len()
        );
    }
    page.push("</table>\n");
    for evo in &s.done.outcome.evolutions {
        let e = &evo.evaluations[evo.best];
        let _ = writeln!(
            page.body,
            "<p class=\"note\">Best robot of run “{}”: individual {} of generation {}, fitness (mean F over its rooms) = {:.4}.</p>",
            esc(&evo.run.label),
            evo.best,
            evo.history.len().saturating_sub(1),
            e.fitness
        );
    }
}

/// One room's firing rules as an HTML table, with the sums that give F.
fn rules_html(ctx: &RenderContext, room: &RoomFuzzy) -> String {
    let (ex, y) = (&room.explanation, &room.inputs);
    let mut rules = String::from(
        "<table><tr><th>rule</th><th class=\"left\">if …</th><th>w</th><th>f</th><th>w·f</th></tr>",
    );
    let mut sum_wf = 0.0;
    for rule in &ex.rules {
        let cond = ex
            .inputs
            .iter()
            .zip(&rule.label_names)
            .map(|(i, n)| format!("{i} is {n}"))
            .collect::<Vec<_>>()
            .join(" and ");
        sum_wf += rule.weight * rule.output;
        let _ = write!(
            rules,
            "<tr><td>{}</td><td class=\"rule-if\">{}</td><td>{:.4}</td><td>{:.4}</td><td>{:.4}</td></tr>",
            rule.number,
            esc(&cond),
            rule.weight,
            rule.output,
            rule.weight * rule.output
        );
    }
    let inputs: Vec<String> = y.iter().map(|v| format!("{v:.3}")).collect();
    let _ = write!(
        rules,
        "<tr><th colspan=\"2\" class=\"left\">Σ</th><th>{:.4}</th><th></th><th>{sum_wf:.4}</th></tr></table><p class=\"note\">{tsk}F = Σ w·f / Σ w = {sum_wf:.4} / {:.4} = {:.4}; inputs Y = ({}), motivations X = {}.</p>",
        ex.weight_sum,
        ex.weight_sum,
        ex.fitness,
        inputs.join(", "),
        xs(ctx),
        tsk = if ctx.combine == Combination::Tsk {
            ""
        } else {
            "The TSK would give "
        },
    );
    rules
}
