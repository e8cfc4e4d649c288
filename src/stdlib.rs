//! The standard library: the classic systems of the seeds, addressable as
//! `std:NAME`. The files live in `stdlib/` and are compiled into the binary.

/// One stdlib entry: its name, the file name it is shown under, its text.
pub struct Entry {
    pub name: &'static str,
    pub file: &'static str,
    pub text: &'static str,
}

macro_rules! entry {
    ($name:literal) => {
        Entry {
            name: $name,
            file: concat!("std:", $name, ".l"),
            text: include_str!(concat!("../stdlib/pfg/", $name, ".l")),
        }
    };
}

/// Every entry, sorted by name.
pub static ENTRIES: &[Entry] = &[
    entry!("algae"),
    entry!("anabaena"),
    entry!("dragon"),
    entry!("fern-schema"),
    entry!("fibonacci"),
    entry!("fibonacci-bush"),
    entry!("filled-polygon"),
    entry!("gosper-hexagonal"),
    entry!("gosper-quadratic"),
    entry!("hilbert"),
    entry!("hogeweg-hesper-a"),
    entry!("hogeweg-hesper-b"),
    entry!("hogeweg-hesper-c"),
    entry!("hogeweg-hesper-d"),
    entry!("hogeweg-hesper-e"),
    entry!("hormone-diffusion"),
    entry!("islands-lakes"),
    entry!("koch-curves-a"),
    entry!("koch-curves-b"),
    entry!("koch-curves-c"),
    entry!("koch-curves-d"),
    entry!("koch-curves-e"),
    entry!("koch-curves-f"),
    entry!("koch-island"),
    entry!("koch-island-quadratic"),
    entry!("kolam-anklets"),
    entry!("kolam-bag-of-candies"),
    entry!("kolam-mango-leaves"),
    entry!("kolam-snake"),
    entry!("leaf-cordate"),
    entry!("lychnis"),
    entry!("paper-tape"),
    entry!("peano"),
    entry!("plant"),
    entry!("plant-a"),
    entry!("plant-b"),
    entry!("plant-c"),
    entry!("plant-d"),
    entry!("plant-e"),
    entry!("plant-f"),
    entry!("raceme"),
    entry!("sierpinski-arrowhead"),
    entry!("sierpinski-square"),
    entry!("signal-acropetal"),
    entry!("signal-basipetal"),
    entry!("snowflake-quadratic"),
    entry!("stochastic-bush"),
];

/// The entry called `name` (with or without the `.l` extension).
pub fn get(name: &str) -> Option<&'static Entry> {
    let name = name.strip_suffix(".l").unwrap_or(name);
    ENTRIES.iter().find(|e| e.name == name)
}

/// Names of all entries.
pub fn names() -> impl Iterator<Item = &'static str> {
    ENTRIES.iter().map(|e| e.name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_in_stdlib_is_an_entry() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/stdlib/pfg");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter_map(|f| f.strip_suffix(".l").map(str::to_string))
            .collect();
        files.sort();
        let listed: Vec<String> = names().map(str::to_string).collect();
        assert_eq!(files, listed);
        assert!(get("koch-island.l").is_some() && get("nope").is_none());
    }
}
