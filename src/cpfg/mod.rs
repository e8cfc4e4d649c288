//! The cpfg dialect of `.l` (the Virtual Laboratory's cpfg) and the files
//! that come with a cpfg object.
//!
//! - [`preprocess`]: the C preprocessor pass cpfg runs over the `.l` file
//!   (`#define`, `#include`, `#if`, comments), with a map from the output
//!   back to the original text for diagnostics.
//! - [`view`]: the view file (`.v`): angle, line width, colours, surfaces,
//!   functions, view parameters; and the default colour map.
//! - [`func`]: user-defined functions (`.func`, `.fset`) as cpfg evaluates
//!   `func(id, x)`.
//! - [`surface`]: bicubic Bézier surfaces (`.s`) as triangle meshes.

pub mod func;
pub mod preprocess;
pub mod surface;
pub mod view;
