//! Finding the files of a cpfg object's folder as the tools that wrote it
//! did: vlab names them on the `cpfg` line of `specifications`; L-studio
//! (vlab's Windows successor) keeps no `specifications` and takes the
//! files of the folder by their extension; and both ran on file systems
//! where a name's case may differ from the one written (L-studio on
//! Windows, where `SEPAL.con` opens `sepal.con`).

use std::path::{Component, Path, PathBuf};

/// The most entries of a folder looked at when searching it: a folder of
/// many holds no single answer, and reading it must stay quick.
const MAX_ENTRIES: usize = 256;

/// The names of the files of `dir` whose extension is `ext` (without the
/// dot, compared ignoring case), sorted; `None` when the folder cannot be
/// read or holds too many entries to look through.
pub fn with_extension(dir: &Path, ext: &str) -> Option<Vec<String>> {
    let mut names = Vec::new();
    for (k, entry) in std::fs::read_dir(dir).ok()?.enumerate() {
        if k == MAX_ENTRIES {
            return None;
        }
        let Ok(entry) = entry else { continue };
        let name = entry.file_name().to_string_lossy().into_owned();
        let matches = Path::new(&name)
            .extension()
            .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case(ext));
        if matches && entry.path().is_file() {
            names.push(name);
        }
    }
    names.sort();
    Some(names)
}

/// The file of `dir` with extension `ext` that belongs to the object whose
/// `.l` has the stem `stem`: the one named like the `.l` (any case), else
/// the folder's only one.
pub fn named_like_or_only(dir: &Path, stem: &str, ext: &str) -> Option<String> {
    let names = with_extension(dir, ext)?;
    let own = names.iter().find(|n| {
        Path::new(n)
            .file_stem()
            .is_some_and(|s| s.to_string_lossy().eq_ignore_ascii_case(stem))
    });
    match own {
        Some(n) => Some(n.clone()),
        None if names.len() == 1 => names.into_iter().next(),
        None => None,
    }
}

/// The path of the side file `name` (relative, as a view file or
/// `specifications` writes it) in `dir`: as written when it exists, else
/// the one entry whose name differs only in case, component by component.
/// `None` when there is neither (the caller reports the name as written).
pub fn find_any_case(dir: &Path, name: &str) -> Option<PathBuf> {
    let written = dir.join(name);
    if written.exists() {
        return Some(written);
    }
    let mut path = dir.to_path_buf();
    for part in Path::new(name).components() {
        match part {
            Component::Normal(part) => {
                let want = part.to_string_lossy();
                path = entry_any_case(&path, &want)?;
            }
            Component::CurDir => {}
            _ => return None,
        }
    }
    Some(path)
}

/// The entry of `dir` named `want`, ignoring case; the first in sorted
/// order when several are (a case-sensitive folder may hold `a.v` and
/// `A.v`, and the picture must not depend on the order the system lists
/// them in).
fn entry_any_case(dir: &Path, want: &str) -> Option<PathBuf> {
    let mut found: Vec<String> = std::fs::read_dir(dir)
        .ok()?
        .take(MAX_ENTRIES)
        .filter_map(Result::ok)
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.eq_ignore_ascii_case(want))
        .collect();
    found.sort();
    found.first().map(|n| dir.join(n))
}

/// The name a path found by [`find_any_case`] has inside `dir`, to say
/// which file was really read.
pub fn name_in(dir: &Path, path: &Path) -> String {
    path.strip_prefix(dir)
        .unwrap_or(path)
        .to_string_lossy()
        .into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder holding `files`, one per test (`name`).
    fn folder(name: &str, files: &[&str]) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("graftal-folder-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for f in files {
            std::fs::write(dir.join(f), b"x").unwrap();
        }
        dir
    }

    #[test]
    fn a_name_written_in_another_case_finds_the_file() {
        let dir = folder("case", &["sepal.con", "plant.l"]);
        let found = find_any_case(dir.as_path(), "SEPAL.con").unwrap();
        assert_eq!(name_in(dir.as_path(), &found), "sepal.con");
        assert_eq!(find_any_case(dir.as_path(), "petal.con"), None);
        assert_eq!(find_any_case(dir.as_path(), "../sepal.con"), None);
    }

    #[test]
    fn the_file_named_like_the_l_is_taken_else_the_only_one() {
        let dir = folder("like", &["Plant.MAP", "other.map", "leaf.mat"]);
        let own = named_like_or_only(dir.as_path(), "plant", "map");
        assert_eq!(own.as_deref(), Some("Plant.MAP"));
        assert_eq!(
            named_like_or_only(dir.as_path(), "plant", "mat").as_deref(),
            Some("leaf.mat")
        );
        let two = folder("two", &["a.map", "b.map"]);
        assert_eq!(named_like_or_only(two.as_path(), "plant", "map"), None);
    }
}
