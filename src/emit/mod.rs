//! Emitters, one per notation: IR -> source text of that notation.
//! `stl` writes a Branch-Expansion Description; the pfg and LinF emitters
//! come with the other translation directions.

pub mod stl;
