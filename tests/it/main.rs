//! graftal's integration tests, as one test binary: each module is the
//! suite that used to be its own binary (`tests/NAME.rs`), `common` what
//! they share. One binary links the library once instead of fifty times.
//!
//! `cargo test` runs the quick suites; the slow ones (fuzzing, Neovim,
//! mesh validators, wall-clock bounds) run too when `GRAFTAL_SLOW=1`
//! ([`common::slow`]), as `.ci/run` sets it.

// Counts allocations for the peak-memory figures of `scale` and `lychnis`:
// those tests run in a process of their own ([`common::alone`]), where no
// other test allocates beside them and where counting starts; the other
// processes allocate uncounted, at full speed.
#[path = "../../benches/common/alloc.rs"]
mod alloc;

#[global_allocator]
static ALLOC: alloc::CountingWhenStarted = alloc::CountingWhenStarted;

mod common;

mod animate;
mod architecture;
mod book;
mod check_derives;
mod cli;
mod cpfg;
mod cpfg_environment;
mod cpfg_files;
mod cpfg_frame;
mod cpfg_gencyl;
mod cpfg_icons;
mod cpfg_objects;
mod cpfg_random;
mod cpfg_shapes;
mod cpfg_sub_lsystems;
mod depth;
mod diagnostics;
mod evaluation;
mod fmt;
mod fractint;
mod front_speed;
mod fuzz;
mod gallery;
mod gft;
mod gft_emitter;
mod gft_graph;
mod gft_hub;
mod gft_models;
mod gft_roundtrip;
mod grammar;
mod ifs;
mod json_records;
mod library_derivations;
mod linf;
mod linf_stdlib;
mod lsp;
mod lychnis;
mod mesh;
mod nearly_nothing;
mod notation_guess;
mod output_limits;
mod picture;
mod raster;
mod raytrace;
mod readme;
mod render_style;
mod robustness;
mod scale;
mod serve;
mod smith;
mod smith_figures;
mod snapshots;
mod stale_words;
mod stdlib_entries;
mod stl;
mod stl_cli;
mod stl_robustness;
mod streamed;
mod svg_detail;
mod textures;
mod threads;
mod translate;
