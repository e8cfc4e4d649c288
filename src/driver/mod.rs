//! The pipeline as library calls, one room per responsibility: load and
//! compile a file (`load.rs`), derive its word (`derive.rs`), what `check`
//! derives to find limits (`check.rs`), turn a word into geometry
//! ([`interpret`], which also answers query modules), translate it
//! (`translate.rs`), make its picture ([`picture`]: the one call every face
//! draws through), say why a picture is empty (`empty.rs`), measure it
//! (`stats.rs`) and say what a place of a file is ([`explain`]: the hover
//! and the definitions every face that shows a file's text asks for).
//!
//! The faces (the command line, the gallery, the language server, the page
//! of `graftal serve`) are thin layers over these calls: they parse their
//! input, call the library and print or send what it returns. How a
//! picture is made (from shared subtrees, streamed, lit or stored, a mesh,
//! an animation) is decided in [`picture`] alone; its strategies are
//! private to it.

mod check;
mod derive;
mod empty;
mod environment;
pub mod explain;
mod interpret;
mod load;
pub mod picture;
mod stats;
mod translate;

pub use crate::eval::parametric::Globals;
pub use crate::eval::DEFAULT_MAX_SYMBOLS;
pub use crate::source::MAX_SOURCE_BYTES;
pub use check::{
    derivation_diagnostics, CHECK_ENTRY_MAX_SYMBOLS, CHECK_MAX_SYMBOLS, LISTED_ENTRIES,
};
pub use derive::{
    derive, derive_symbols, derive_values, derive_with_progress, write_derived, RunOptions,
};
pub use empty::{nearly_nothing_drawn, nothing_drawn, why_nothing_drawn, NEARLY_NOTHING};
pub use explain::{hover, what_it_does, HoverText, Knowledge, Names};
pub use interpret::{add_fixed, add_layout, geometry, interpret, turns_in_space, MAX_MOVES};
pub use load::{
    choose_entry, compile, compile_as, compile_entry, load, notations, split_entry, Compiled,
    LoadError,
};
pub use picture::{render_bytes, Format};
pub use stats::{stats, StageTimes, Stats, GRAPH_STATS_PIXELS};
pub use translate::{translate, COMPARE_MAX_SYMBOLS};
