//! Generates the crate's solver from its problem file at build time.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    mingen::build::Config::new()
        .problems(&["../../templates/gs5pt.mp"])
        .compile()?;
    Ok(())
}
