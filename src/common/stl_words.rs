//! The names the STL notation keeps for itself, in one list that both its
//! front end (which refuses them as rule names) and its emitter (which must
//! rename a rule spelt like one) import: neither may import the other, and
//! the IR, which names no notation, does not hold them.

/// Names that cannot be rule names: the drawing components, the stem
/// parameters, `I` of `[I n X]` and the keywords of the STL notation,
/// which writes rules by name.
pub const RESERVED: [&str; 13] = [
    "F",
    "L",
    "R",
    "B",
    "I",
    "ANGLE",
    "GROWTH",
    "LEVELS",
    "SEED",
    "ENDSEED",
    "LAYOUT",
    "ENDLAYOUT",
    "BFS",
];
