//! mingen: minimal-solver generator.
