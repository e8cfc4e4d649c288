//! The `graftal` binary: see [`graftal::cli`].

fn main() {
    std::process::exit(graftal::cli::main());
}
