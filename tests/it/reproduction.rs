//! The reproduction registry: every claim obtains its expected status (a regression, or an
//! unexplained change, fails here), ids are unique, printed numbers parse.

use adhesion::reproduction::{Status, claims, evaluate_all, printed_value};

#[test]
fn every_claim_has_its_expected_status() {
    let outcomes = evaluate_all();
    let bad: Vec<String> = outcomes
        .iter()
        .filter(|o| !o.as_expected)
        .map(|o| {
            format!(
                "{} ({}): printed {}, computed {}, {:?}: {}",
                o.id, o.source, o.printed_text, o.computed, o.status, o.reason
            )
        })
        .collect();
    assert!(bad.is_empty(), "claims changed status:\n{}", bad.join("\n"));
    assert!(outcomes.iter().all(|o| o.status != Status::Failed));
}

#[test]
fn claim_ids_are_unique_and_printed_numbers_parse() {
    let all = claims();
    let mut ids: Vec<&str> = all.iter().map(|c| c.id).collect();
    ids.sort_unstable();
    let n = ids.len();
    ids.dedup();
    assert_eq!(n, ids.len(), "duplicate claim ids");
    for c in &all {
        let (v, tol) = printed_value(c.printed);
        assert!(v.is_finite() && tol > 0.0, "{}", c.id);
        assert!(c.id.starts_with("ch") || c.id.starts_with("app"), "{}", c.id);
    }
}
