//! graftal: L-system notations read into one IR, evaluated, drawn,
//! explained and translated.
//!
//! The pipeline: [`source`] text -> a front end ([`pfg`]) -> [`ir::System`]
//! -> [`eval`] (derivation) -> [`turtle`] (geometry) -> [`render`] (PNG,
//! SVG). Every stage reports [`diagnostics`]. [`driver`] strings the stages
//! together for the CLI and for tests.

pub mod diagnostics;
pub mod eval;
pub mod ir;
pub mod pfg;
pub mod source;
