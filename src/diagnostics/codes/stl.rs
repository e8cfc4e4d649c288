//! Diagnostic codes of the STL front end (`E05xx`, `W05xx`).

#[allow(unused_imports)]
use super::Code;

codes! { STL;
}
