//! Gröbner bases, solution counts, elimination templates and their validation on the
//! test systems of `common` (5-point, G-RSRP, grsrp10, degenerate inputs).
mod common;

use common::Fixture;
use mingen::__internal::groebner::GroebnerError;
use mingen::__internal::pipeline::{find_template, Generated};
use mingen::__internal::quotient::{analyse, AnalysisError};
use mingen::__internal::template::{best_template, validate, TemplateOptions};
use std::time::Instant;

fn run(f: Fixture, opts: &TemplateOptions) -> Generated {
    let t = Instant::now();
    let g = find_template(&f, opts).unwrap_or_else(|e| panic!("{f:?}: {e}"));
    let (r, c) = g.built.template.size();
    println!(
        "{f:?}: {} solutions, template {r}x{c} (action {:?}), per action {:?}; \
         GB/analysis {:.3}s, templates {:.3}s, validation ({} instances) {:.3}s, total {:.3}s",
        g.count,
        g.built.template.action,
        g.per_action,
        g.seconds.0,
        g.seconds.1,
        opts.validate_instances,
        g.seconds.2,
        t.elapsed().as_secs_f64()
    );
    println!(
        "    basis: {} {:?}",
        g.built.basis_choice, g.built.template.basis
    );
    for (step, r, c) in &g.built.history {
        println!("    {step}: {r}x{c}");
    }
    g
}

fn opts100() -> TemplateOptions {
    TemplateOptions {
        validate_instances: 100,
        ..TemplateOptions::default()
    }
}

#[test]
fn gs5pt_10_solutions_10x20() {
    let g = run(Fixture::Gs5pt, &opts100());
    assert_eq!(g.count, 10);
    assert_eq!(g.built.template.size(), (10, 20));
    assert_eq!(g.built.template.n_excess + g.built.template.n_reducible, 10);
    assert_eq!(g.validation.unwrap().instances, 100);
}

#[test]
fn grsrp10_10_solutions_10x20() {
    let g = run(Fixture::Grsrp10, &opts100());
    assert_eq!(g.count, 10);
    assert_eq!(g.built.template.size(), (10, 20));
    assert_eq!(g.validation.unwrap().instances, 100);
}

#[test]
fn grsrp_20_solutions_template_below_205x225() {
    // Default: only actions with distinct eigenvalues (the t_i; the a_j have the double
    // eigenvalues of the ±t symmetry). The basis is selected by elimination (t before a),
    // not the grevlex standard monomials (whose cubics t_i*t3^2 need degree-6 multiples).
    let g = run(Fixture::Grsrp, &opts100());
    assert_eq!(g.count, 20);
    assert!(g.built.distinct_eigenvalues);
    let (r, c) = g.built.template.size();
    let t = &g.built.template;
    assert_eq!(r, t.n_excess + t.n_reducible, "square left block");
    assert!(r <= 80 && c <= 100, "{r}x{c} regressed");
    assert!(g.built.basis_choice.starts_with("selected"));
    let action_var = g.built.template.action.single();
    assert!(matches!(action_var, Some(3..=5)), "a t action");
    // Smallest over all actions, ignoring the eigenvalue requirement.
    let opts = TemplateOptions {
        require_distinct_eigenvalues: false,
        validate_instances: 100,
        ..TemplateOptions::default()
    };
    let g = run(Fixture::Grsrp, &opts);
    let (r, c) = g.built.template.size();
    assert!(r * c < 205 * 225);
    assert!(r <= 80 && c <= 100, "{r}x{c} regressed");
}

#[test]
fn grsrp_gravity_validates() {
    let g = run(Fixture::GrsrpGravity, &opts100());
    assert!(g.built.distinct_eigenvalues);
    assert_eq!(g.validation.unwrap().instances, 100);
}

#[test]
fn same_seed_same_template() {
    for f in [Fixture::Gs5pt, Fixture::Grsrp10, Fixture::Grsrp] {
        let opts = TemplateOptions {
            validate_instances: 0,
            ..TemplateOptions::default()
        };
        let a = find_template(&f, &opts).unwrap();
        let b = find_template(&f, &opts).unwrap();
        assert_eq!(a.built.template, b.built.template, "{f:?}");
        assert_eq!(a.built.history, b.built.history, "{f:?}");
        assert_eq!(a.basis, b.basis);
    }
}

#[test]
fn templates_from_another_seed_validate_too() {
    // Template built from one instance, checked on instances of another seed family.
    let a = analyse(&Fixture::Grsrp10, 99).unwrap();
    let (b, _) = best_template(&a, &TemplateOptions::default()).unwrap();
    validate(&b.template, &Fixture::Grsrp10, 20, 12345).unwrap();
}

#[test]
fn positive_dimensional_input_is_a_named_error() {
    let e = analyse(&Fixture::GrsrpMissingPoint, 1).unwrap_err();
    println!("{e}");
    match &e {
        AnalysisError::Groebner {
            source: GroebnerError::PositiveDimensional { missing },
            ..
        } => assert!(!missing.is_empty()),
        other => panic!("unexpected {other:?}"),
    }
    assert!(e.to_string().contains("positive-dimensional"));
}

#[test]
fn inconsistent_input_is_an_error() {
    let e = analyse(&Fixture::Inconsistent, 1).unwrap_err();
    println!("{e}");
    assert!(matches!(
        e,
        AnalysisError::Groebner {
            source: GroebnerError::Inconsistent,
            ..
        }
    ));
    assert!(e.to_string().contains("inconsistent"));
}
