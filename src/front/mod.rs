//! Front ends: one folder per notation.

pub mod cpfg;
pub mod fractint;
pub mod linf;
pub mod pfg;
pub mod stl;
