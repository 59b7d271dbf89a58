//! Explores basis selection and shrinking on one problem, printing template sizes instead of
//! choosing one (`mingen::__internal::template::explore`):
//!
//! ```text
//! cargo run --release -p mingen --example explore_basis -- FILE MODE [OPTIONS]
//! ```
//!
//! Modes:
//! - `permutations`: a basis selected under grevlex for every permutation of the variables
//!   (n! column orders);
//! - `rotations`: the column orders the generator's basis selection tries;
//! - `random-shrink`: the basis selected with `--order`, shrunk under `--tries` random row
//!   removal orders.
//!
//! Options: `--action NAME` (repeatable; default every unknown in the first two modes, the
//! first unknown in `random-shrink`), `--degree D` (candidate degree, default 4),
//! `--order a,b,c` (grevlex with a > b > c; `degree-then:a,b` orders by total degree, then
//! by the degree in a, b, larger first; default: grevlex in variable order), `--tries N`
//! (default 40), `--seed S` (instance seed, default 2024).
//!
//! For instance `explore_basis templates/grsrp.mp permutations --action t1 --degree 4`.

use mingen::__internal::algebra::P1;
use mingen::__internal::quotient::{analyse, InstanceSource};
use mingen::__internal::system::ProblemSource;
use mingen::__internal::template::explore::{explore, explore_random_shrink};
use mingen::__internal::template::select::{basis_orders, BasisOrder};
use mingen::Problem;

type Error = Box<dyn std::error::Error>;

/// The command line, parsed.
struct Args {
    file: String,
    mode: String,
    actions: Vec<String>,
    degree: u32,
    order: Option<String>,
    tries: u64,
    seed: u64,
}

fn parse_args() -> Result<Args, Error> {
    let mut it = std::env::args().skip(1);
    let usage = "usage: explore_basis FILE permutations|rotations|random-shrink \
                 [--action NAME]... [--degree D] [--order ORDER] [--tries N] [--seed S]";
    let (Some(file), Some(mode)) = (it.next(), it.next()) else {
        return Err(usage.into());
    };
    let mut args = Args {
        file,
        mode,
        actions: Vec::new(),
        degree: 4,
        order: None,
        tries: 40,
        seed: 2024,
    };
    while let Some(flag) = it.next() {
        let value = it
            .next()
            .ok_or_else(|| format!("{flag} needs a value; {usage}"))?;
        match flag.as_str() {
            "--action" => args.actions.push(value),
            "--degree" => args.degree = value.parse()?,
            "--order" => args.order = Some(value),
            "--tries" => args.tries = value.parse()?,
            "--seed" => args.seed = value.parse()?,
            _ => return Err(format!("unknown option {flag}; {usage}").into()),
        }
    }
    Ok(args)
}

/// The index of each variable name of `list` (comma-separated) among `names`.
fn variables(list: &str, names: &[String]) -> Result<Vec<usize>, Error> {
    list.split(',')
        .map(|n| {
            names
                .iter()
                .position(|m| m == n.trim())
                .ok_or_else(|| format!("'{n}' is not an unknown ({})", names.join(", ")).into())
        })
        .collect()
}

fn parse_order(spec: &str, names: &[String]) -> Result<BasisOrder, Error> {
    if let Some(set) = spec.strip_prefix("degree-then:") {
        let mask = variables(set, names)?.iter().fold(0u64, |m, &v| m | 1 << v);
        return Ok(BasisOrder::DegreeThenSet(mask, true));
    }
    let perm = variables(spec, names)?;
    if perm.len() != names.len() {
        return Err(format!("--order must name all {} unknowns", names.len()).into());
    }
    Ok(BasisOrder::Grevlex(perm))
}

/// Every permutation of `0..n` as a grevlex order (Heap's algorithm).
fn permutations(n: usize) -> Vec<BasisOrder> {
    fn heap(k: usize, a: &mut Vec<usize>, out: &mut Vec<BasisOrder>) {
        if k <= 1 {
            out.push(BasisOrder::Grevlex(a.clone()));
            return;
        }
        for i in 0..k {
            heap(k - 1, a, out);
            if k % 2 == 0 {
                a.swap(i, k - 1)
            } else {
                a.swap(0, k - 1)
            }
        }
    }
    let mut out = Vec::new();
    heap(n, &mut (0..n).collect(), &mut out);
    out
}

fn main() -> Result<(), Error> {
    let args = parse_args()?;
    let problem = Problem::from_file(std::path::Path::new(&args.file))?;
    let source = ProblemSource::new(&problem);
    let names = source.var_names();
    let a = analyse(&source, args.seed)?;
    let visible = a.nvars - source.hidden_vars();
    let actions: Vec<usize> = if args.actions.is_empty() {
        (0..visible).collect()
    } else {
        variables(&args.actions.join(","), &names)?
    };
    let d = args.degree;
    let orders = match args.mode.as_str() {
        "permutations" => permutations(a.nvars),
        "rotations" => basis_orders(a.nvars),
        "random-shrink" => {
            let order = match &args.order {
                Some(spec) => parse_order(spec, &names)?,
                None => BasisOrder::Grevlex((0..a.nvars).collect()),
            };
            let (&action, n) = (actions.first().ok_or("no action")?, a.count);
            explore_random_shrink::<P1>(&a.equations, a.nvars, n, action, &order, d, args.tries);
            return Ok(());
        }
        other => return Err(format!("unknown mode '{other}'").into()),
    };
    explore::<P1>(&a.equations, a.nvars, a.count, &actions, &orders, d);
    Ok(())
}
