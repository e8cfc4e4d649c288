//! The `graftal` binary: see [`graftal::cli`].

/// The stack of the thread graftal runs on. Every recursion over input is
/// bounded by `ir::MAX_NESTING`, and at that depth the parsers need under
/// 1 MiB in optimised builds but up to about 9 MiB in an unoptimised
/// debug build: 64 MiB of address space (only what is touched is memory)
/// leaves every build a wide margin, as rustc does for its own parser.
const STACK_BYTES: usize = 64 << 20;

fn main() {
    let status = std::thread::Builder::new()
        .name("graftal".into())
        .stack_size(STACK_BYTES)
        .spawn(graftal::cli::main)
        .map_or_else(|_| graftal::cli::main(), |t| t.join().unwrap_or(101));
    std::process::exit(status);
}
