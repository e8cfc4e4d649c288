//! The standard library: the classic systems of the seeds, addressable as
//! `std:NAME`. The files live in `stdlib/<notation>/` and are compiled into
//! the binary. pfg entries are named by their file name (`std:koch-island`,
//! also `std:pfg/koch-island`); the other notations' entries carry their
//! folder (`std:linf/fig03-koch-snowflake`, `std:stl/fig04-plant`), and the
//! entry's file name ends in the notation's extension, which is what picks
//! the front end. A collection in a folder of its own inside a notation's
//! folder is named by the collection (`stdlib/gft/bekaert/tree.gft` is
//! `std:bekaert/tree`, Bekaert & Willems' graphs).

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
    // A collection inside a notation's folder, named by the collection
    // (`stdlib/gft/bekaert/tree.gft` is `std:bekaert/tree`).
    ($dir:literal / $sub:literal / $name:literal . $ext:literal) => {
        Entry {
            name: concat!($sub, "/", $name),
            file: concat!("std:", $sub, "/", $name, ".", $ext),
            text: include_str!(concat!(
                "../stdlib/",
                $dir,
                "/",
                $sub,
                "/",
                $name,
                ".",
                $ext
            )),
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
    entry!("smith" / "cartoon-tree" . "smith"),
    entry!("smith" / "koch-star" . "gft"),
    entry!("smith" / "senstree" . "smith"),
    entry!("smith" / "arrowhead" . "gft"),
    entry!("smith" / "table1" . "smith"),
    entry!("smith" / "three-thistle" . "smith"),
    entry!("smith" / "white-sands" . "smith"),
    entry!("smith" / "with-without" . "smith"),
    entry!("smith" / "with-without-bare" . "smith"),
    entry!("gft" / "hogeweg-hesper-a" . "gft"),
    entry!("gft" / "koch-island" . "gft"),
    entry!("gft" / "signal-plant-3d" . "gft"),
    entry!("gft" / "stochastic-tree" . "gft"),
    entry!("gft" / "light-competition" . "gft"),
    entry!("gft" / "two-heading-curve" . "gft"),
    entry!("gft" / "bekaert" / "fern" . "gft"),
    entry!("gft" / "bekaert" / "menger" . "gft"),
    entry!("gft" / "bekaert" / "temple" . "gft"),
    entry!("gft" / "bekaert" / "tetrahedron" . "gft"),
    entry!("gft" / "bekaert" / "tree" . "gft"),
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

/// The entry a loaded file came from, by the file name [`get`] gave it
/// (`std:algae.l`); `None` for files outside the stdlib.
pub fn by_file(file: &str) -> Option<&'static Entry> {
    ENTRIES.iter().find(|e| e.file == file)
}

/// Whether the stdlib file `file` is drawn as a spline by default.
pub fn draws_as_spline(file: &str) -> bool {
    by_file(file).is_some_and(|e| e.kind() == Kind::Spline)
}

/// How an entry is meant to be seen, from the `graftal:` line of its
/// header comment (`graftal: schema …`, `graftal: spline`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Draws at its defaults.
    Drawing,
    /// Draws at its defaults as a B-spline through the turtle's positions
    /// (the kolams): `render` draws it so without `--spline`.
    Spline,
    /// A string example or schema: the source prints its words, not a
    /// picture. `render` says so; `derive` is how it is read.
    Schema,
}

impl Kind {
    /// The word `graftal list` shows.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Drawing => "draws",
            Kind::Spline => "draws (spline)",
            Kind::Schema => "schema",
        }
    }
}

/// The stdlib folders' indexes, whose tables give each entry's figure.
/// gft's comes first: its rows name entries in full (`gft/koch-island`),
/// so that they never give a pfg entry of the same base name its figure.
const INDEXES: &[&str] = &[
    include_str!("../stdlib/gft/INDEX.md"),
    include_str!("../stdlib/pfg/INDEX.md"),
    include_str!("../stdlib/linf/INDEX.md"),
];

impl Entry {
    /// The text after `graftal:` in the header, the entry's metadata.
    fn meta(&self) -> Option<&'static str> {
        self.text
            .lines()
            .take_while(|l| !l.contains("*/"))
            .find_map(|l| l.trim_start_matches(['#', ' ']).strip_prefix("graftal:"))
            .map(str::trim)
    }

    /// What the entry is meant to give at its defaults.
    pub fn kind(&self) -> Kind {
        match self.meta() {
            Some(m) if m.starts_with("schema") => Kind::Schema,
            Some(m) if m.starts_with("spline") => Kind::Spline,
            _ => Kind::Drawing,
        }
    }

    /// Why a schema draws nothing: its metadata after `schema`.
    pub fn schema_reason(&self) -> Option<&'static str> {
        let m = self.meta()?.strip_prefix("schema")?;
        Some(m.trim_start_matches([' ', ':', '(']).trim_end_matches(')'))
    }

    /// The figure the entry reproduces: its row in the folder's INDEX.md,
    /// else the first `Fig. …` (or section) of its header, else empty.
    pub fn figure(&self) -> String {
        let base = self.name.rsplit('/').next().unwrap_or(self.name);
        let row = INDEXES.iter().flat_map(|t| t.lines()).find_map(|l| {
            let mut cells = l.split('|').map(str::trim).skip(1);
            let name = cells.next()?.trim_matches('`');
            (name == base || name == self.name).then(|| cells.next().map(str::to_string))?
        });
        row.or_else(|| {
            let head: String = self.text.lines().take(4).collect::<Vec<_>>().join(" ");
            let at = [
                "Fig. ", "Section ", "section ", "Plate ", "Table ", "Figure ",
            ]
            .iter()
            .find_map(|k| head.find(k))?;
            let fig: String = head[at..]
                .chars()
                .take_while(|c| !matches!(c, ':' | ',' | '"'))
                .collect();
            Some(fig.trim().to_string())
        })
        .unwrap_or_default()
    }
}

/// `graftal list`: one line per entry, `std:NAME`, its figure and its
/// [`Kind`], in columns.
pub fn listing() -> String {
    let width = ENTRIES.iter().map(|e| e.name.len()).max().unwrap_or(0) + 4;
    let rows: Vec<(String, String)> = ENTRIES
        .iter()
        .map(|e| (e.figure(), e.kind().name().into()))
        .collect();
    let fig = rows
        .iter()
        .map(|(f, _)| f.chars().count())
        .max()
        .unwrap_or(0);
    ENTRIES
        .iter()
        .zip(rows)
        .map(|(e, (f, k))| format!("{:width$}  {f:fig$}  {k}\n", format!("std:{}", e.name)))
        .collect()
}

/// `graftal list --format json`: `{"entries": [{"name", "figure", "kind",
/// "draws"}]}`, `kind` being `drawing`, `spline` or `schema`.
pub fn listing_json() -> serde_json::Value {
    let entries: Vec<serde_json::Value> = ENTRIES
        .iter()
        .map(|e| {
            let kind = match e.kind() {
                Kind::Drawing => "drawing",
                Kind::Spline => "spline",
                Kind::Schema => "schema",
            };
            serde_json::json!({
                "name": format!("std:{}", e.name),
                "figure": e.figure(),
                "kind": kind,
                "draws": e.kind() != Kind::Schema,
            })
        })
        .collect();
    serde_json::json!({ "entries": entries })
}

/// The longest unknown name compared with the entries' names.
const LONGEST_SUGGESTED: usize = 200;

/// The error for a `std:NAME` that does not exist: the nearest names (an
/// entry whose name without its folder is `name`, else the nearest by
/// spelling, else those starting with it) and where the list is.
pub fn unknown(name: &str) -> String {
    let shown = crate::diagnostics::shortened(&crate::diagnostics::escaped(name), 60).into_owned();
    // No entry name is this long: comparing would only cost time.
    if name.len() > LONGEST_SUGGESTED {
        return format!("no stdlib entry `{shown}`; `graftal list` lists them all");
    }
    let all: Vec<&str> = names().collect();
    let base = |n: &'static str| n.rsplit('/').next().unwrap_or(n);
    let mut near: Vec<&str> = all.iter().copied().filter(|&n| base(n) == name).collect();
    if near.is_empty() {
        let bases: Vec<&str> = all.iter().map(|&n| base(n)).collect();
        let by_spelling = crate::diagnostics::nearest(name, &bases);
        near = all
            .iter()
            .copied()
            .filter(|&n| by_spelling.contains(&base(n)))
            .collect();
    }
    if near.is_empty() && !name.is_empty() {
        near = all
            .iter()
            .copied()
            .filter(|&n| base(n).starts_with(name))
            .collect();
    }
    let listed: Vec<String> = near.iter().take(3).map(|n| format!("`std:{n}`")).collect();
    let hint = match (listed.len(), near.len() > listed.len()) {
        (0, _) => String::new(),
        (_, more) => format!(
            " (did you mean {}{}?)",
            listed.join(", "),
            if more { ", …" } else { "" }
        ),
    };
    format!("no stdlib entry `{shown}`{hint}; `graftal list` lists them all")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_in_stdlib_is_an_entry() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/stdlib");
        let mut files: Vec<String> = Vec::new();
        for (dir, ext) in [
            ("pfg", ".l"),
            ("linf", ".linf"),
            ("stl", ".stl"),
            ("smith", ".smith"),
            ("smith", ".gft"),
            ("gft", ".gft"),
            ("gft/bekaert", ".gft"),
        ] {
            let Ok(entries) = std::fs::read_dir(format!("{root}/{dir}")) else {
                continue;
            };
            for e in entries.filter_map(Result::ok) {
                let f = e.file_name().into_string().unwrap();
                if let Some(stem) = f.strip_suffix(ext) {
                    files.push(match dir {
                        "pfg" => stem.to_string(),
                        "gft/bekaert" => format!("bekaert/{stem}"),
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
