//! Layouts and outline growth: what a [`Structure`](crate::ir::Structure)
//! of the IR draws. The IR states a structure (named rules, a seed of
//! branching terms, layout shapes, a growth strategy); this module
//! computes with it: the shapes' outlines and the exact test that a stem
//! stays inside them ([`shapes`]), the growth of a seed inside them
//! ([`growth`]), and the seed expanded, grown where it has growth points,
//! into the axiom word ([`seed`]).
//!
//! These are computations over the IR, not the IR itself (no type here is
//! part of a [`System`](crate::ir::System)), and several places ask for
//! them: the STL and `.gft` front ends grow their seeds, the driver draws
//! the shapes behind a picture. So they stand in their own room above the
//! IR: this module imports only `ir` (and the `number` leaf), and a front
//! end that states a growth constraint walks no turtle of its own.

pub mod growth;
pub mod seed;
pub mod shapes;
