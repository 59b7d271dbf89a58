mod common;
use common::Fixture;
use mingen::template::{best_template, TemplateOptions};
use mingen::quotient::analyse;
use std::time::Instant;

#[test]
fn explore() {
    for f in [Fixture::Gs5pt, Fixture::Grsrp10, Fixture::Grsrp] {
        let t0 = Instant::now();
        let a = analyse(&f, 1).unwrap();
        let t1 = Instant::now();
        println!("{f:?}: count {} basis {:?} gb {:.3}s", a.count, a.basis, (t1-t0).as_secs_f64());
        let (best, all) = best_template(&a.equations, &a.basis, &TemplateOptions::default()).unwrap();
        for (v, r) in &all {
            match r {
                Ok(b) => println!("  action {v}: {:?} distinct {} hist {:?}", b.template.size(), b.distinct_eigenvalues, b.history),
                Err(e) => println!("  action {v}: {e}"),
            }
        }
        println!("  best {:?} {:.3}s", best.template.size(), t1.elapsed().as_secs_f64());
    }
}
