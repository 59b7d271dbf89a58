//! Generates the crate's solvers from problem files at build time.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    mingen::build::Config::new()
        .problems(&[
            "../../templates/gs5pt.mp",
            "../../templates/classic/relpose_6pt_focal.mp",
        ])
        .compile()?;
    Ok(())
}
