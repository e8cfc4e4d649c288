//! Diagnostic codes of the LinF front end (`E04xx`, `W04xx`).

#[allow(unused_imports)]
use super::Code;

codes! { LINF;
}
