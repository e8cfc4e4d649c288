//! The standard library: the classic systems of the seeds, addressable as
//! `std:NAME`. The files live in `stdlib/<notation>/` and are compiled into
//! the binary. pfg entries are named by their file name (`std:koch-island`,
//! also `std:pfg/koch-island`); the other notations' entries carry their
//! folder (`std:linf/fig03-koch-snowflake`, `std:stl/fig04-plant`), and the
//! entry's file name ends in the notation's extension, which is what picks
//! the front end.

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
    ($dir:literal / $name:literal . $ext:literal) => {
        Entry {
            name: concat!($dir, "/", $name),
            file: concat!("std:", $dir, "/", $name, ".", $ext),
            text: include_str!(concat!("../stdlib/", $dir, "/", $name, ".", $ext)),
        }
    };
}

/// Every entry: pfg's sorted by name, then each other notation's.
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
    entry!("linf" / "fig01-koch-curve" . "linf"),
    entry!("linf" / "fig03-koch-snowflake" . "linf"),
    entry!("linf" / "fig04-sierpinski-carpet" . "linf"),
    entry!("linf" / "fig05-peano-curve" . "linf"),
    entry!("linf" / "fig06-plant" . "linf"),
    entry!("linf" / "fig07-plant-3d" . "linf"),
    entry!("linf" / "fig08-tree-3d" . "linf"),
    entry!("linf" / "fig09-stochastic-plant" . "linf"),
    entry!("linf" / "fig10-brownian-motion" . "linf"),
    entry!("linf" / "fig11-feathers" . "linf"),
    entry!("linf" / "fig12-trees" . "linf"),
    entry!("stl" / "fig02-koch-curve" . "stl"),
    entry!("stl" / "fig03-koch-curve" . "stl"),
    entry!("stl" / "fig04-plant" . "stl"),
    entry!("stl" / "fig04-plant-1" . "stl"),
    entry!("stl" / "fig04-plant-2" . "stl"),
    entry!("stl" / "fig06-rm" . "stl"),
    entry!("stl" / "fig06-rn" . "stl"),
    entry!("stl" / "fig07-layout" . "stl"),
    entry!("stl" / "fig09-outline-bfs" . "stl"),
    entry!("stl" / "fig10-outline-dfs" . "stl"),
];

/// The entry called `name` (with or without its extension; pfg entries
/// also as `pfg/NAME`).
pub fn get(name: &str) -> Option<&'static Entry> {
    let name = name.strip_prefix("pfg/").unwrap_or(name);
    ENTRIES.iter().find(|e| {
        e.name == name
            || name
                .strip_prefix(e.name)
                .is_some_and(|ext| e.file.ends_with(ext) && ext.starts_with('.'))
    })
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
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/stdlib");
        let mut files: Vec<String> = Vec::new();
        for (dir, ext) in [("pfg", ".l"), ("linf", ".linf"), ("stl", ".stl")] {
            let Ok(entries) = std::fs::read_dir(format!("{root}/{dir}")) else {
                continue;
            };
            for e in entries.filter_map(Result::ok) {
                let f = e.file_name().into_string().unwrap();
                if let Some(stem) = f.strip_suffix(ext) {
                    files.push(match dir {
                        "pfg" => stem.to_string(),
                        _ => format!("{dir}/{stem}"),
                    });
                }
            }
        }
        files.sort();
        let mut listed: Vec<String> = names().map(str::to_string).collect();
        listed.sort();
        assert_eq!(files, listed);
        assert!(get("koch-island.l").is_some() && get("nope").is_none());
        assert!(get("pfg/koch-island").is_some() && get("koch-island.linf").is_none());
    }
}
