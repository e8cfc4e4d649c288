//! What several front ends and emitters share about notations, in one
//! place that each of them may import while none imports another (as
//! naga's `common`): what each notation's symbols do to the turtle
//! ([`vocabulary`]), the keywords of the `.gft` notation ([`gft_words`]),
//! the names STL keeps from its rules ([`stl_words`]) and Fractint's
//! palette ([`palettes`]).
//!
//! This module stands on the IR ([`crate::ir`]) and on nothing else: the
//! IR itself says nothing about any notation, so a table that names one
//! lives here, not there.

pub mod gft_words;
pub mod palettes;
pub mod stl_words;
pub mod vocabulary;
