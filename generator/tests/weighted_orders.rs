//! Quotient bases of weighted monomial orders (`template/search/orders.rs`, `groebner/`'s
//! weights): on the benchmark's `p4p_fr` (P4P with unknown focal length and radial
//! distortion), whose standard-basis template of Martyushev et al. comes from the weighted
//! order with weights (5, 6, 3, 4), the search reaches at most their size (52x68), where
//! grevlex under every variable order stays far above it; the template is validated mod p
//! and solves uniform random instances accurately.

use mingen::plan_file;
use mingen::TemplateOptions;
use mingen::{audit_plan, AuditOptions};
use std::path::Path;

#[test]
fn weighted_orders_reach_the_published_standard_template_of_p4p_fr() {
    let f = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark/p4p_fr.mp");
    let options = TemplateOptions {
        weighted_orders: 32,
        ..TemplateOptions::default()
    };
    let plan = plan_file(&f, &options).unwrap();
    let built = &plan.generated.built;
    let (rows, cols) = built.template.eliminated_size();
    assert_eq!(plan.generated.count, 16);
    assert!(
        built.template.elimination_area() <= 52 * 68,
        "{rows}x{cols} ({})",
        built.basis_choice
    );
    assert!(
        built.basis_choice.contains("weighted order"),
        "{}",
        built.basis_choice
    );
    assert!(!built.pool_weights.is_empty());
    assert!(plan.generated.validation.is_some(), "validated mod p");
    let audit = audit_plan(
        &plan,
        &AuditOptions {
            instances: 300,
            seed: 11,
            ..AuditOptions::default()
        },
    );
    assert!(
        audit.median_log10_residual < -9.0 && audit.failures <= 6,
        "median {} failures {}",
        audit.median_log10_residual,
        audit.failures
    );
}

/// A weight vector given by the caller (`TemplateOptions::weights`, `--weights`) is tried
/// even with no sampled orders: on `rdist9p`, the weights (4, 7, 5, 10) of Martyushev et
/// al.'s standard-basis template give at most their size (76x100), and a template no
/// larger than the search without them (grevlex under every variable order and the
/// selected bases).
#[test]
fn given_weights_are_tried_before_the_sampled_orders() {
    let f = Path::new(env!("CARGO_MANIFEST_DIR")).join("../templates/benchmark/rdist9p.mp");
    let options = |weights: Vec<Vec<u32>>| TemplateOptions {
        weighted_orders: 0,
        weights,
        ..TemplateOptions::default()
    };
    let plan = plan_file(&f, &options(vec![vec![4, 7, 5, 10]])).unwrap();
    let built = &plan.generated.built;
    let (rows, cols) = built.template.eliminated_size();
    assert!(
        built.template.elimination_area() <= 76 * 100,
        "{rows}x{cols} ({})",
        built.basis_choice
    );
    assert_eq!(built.pool_weights, vec![4, 7, 5, 10]);
    assert!(plan.generated.validation.is_some(), "validated mod p");
    let plain = plan_file(&f, &options(Vec::new())).unwrap();
    let plain_area = plain.generated.built.template.elimination_area();
    assert!(
        plain_area >= built.template.elimination_area(),
        "without the weights {plain_area}, given weights {rows}x{cols}"
    );
    assert_ne!(plain.generated.built.pool_weights, vec![4, 7, 5, 10]);
    // One weight per unknown, all positive.
    for bad in [vec![4, 7, 5], vec![4, 0, 5, 10]] {
        let Err(e) = plan_file(&f, &options(vec![bad.clone()])) else {
            panic!("weights {bad:?} accepted");
        };
        assert!(e.to_string().contains(&format!("weights {bad:?}")), "{e}");
    }
}
