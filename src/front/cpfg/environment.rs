//! The environment program an object's `.e` file names. cpfg, started
//! with `-e file.e`, runs the program of the file's `executable:` line and
//! lets it answer the `?E` modules. graftal runs none; it only names the
//! program in its warning, so that a plant drawn half (or not at all)
//! because nothing answered says what would have answered.

use std::path::Path;

use crate::diagnostics::{codes, Diagnostics};

/// Adds to the `?E` warning (W0821) in `diags`, if there is one, the
/// environment program of the `.e` file beside `l_file` in `dir`.
pub fn name_program(dir: &Path, l_file: &Path, diags: &mut Diagnostics) {
    let Some(d) = diags
        .0
        .iter_mut()
        .find(|d| d.code == codes::CPFG_NO_ENVIRONMENT)
    else {
        return;
    };
    let Some((file, program)) = program_of(dir, l_file) else {
        return;
    };
    d.notes.push(format!(
        "cpfg runs the environment program `{program}` (named in {file}) to answer them; \
         what grows or is drawn only on its answer is missing here"
    ));
}

/// The `.e` file of the object (named after the `.l`, else the folder's
/// only `.e` file) and the command of its `executable:` line.
fn program_of(dir: &Path, l_file: &Path) -> Option<(String, String)> {
    let stem = l_file.file_stem()?.to_string_lossy().into_owned();
    let file = super::folder::named_like_or_only(dir, &stem, "e")?;
    let text = super::read_lossy(&dir.join(&file))?;
    let program = executable(&text)?;
    Some((file, program))
}

/// The value of the `executable:` line of a `.e` file's `text`.
fn executable(text: &str) -> Option<String> {
    text.lines()
        .find_map(|l| l.trim().strip_prefix("executable:"))
        .map(|v| v.trim().chars().take(200).collect::<String>())
        .filter(|v| !v.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_executable_line_names_the_program() {
        let e = "executable: honda81 density.spec\ncommunication type: files\n";
        assert_eq!(executable(e).as_deref(), Some("honda81 density.spec"));
        assert_eq!(executable("communication type: files\n"), None);
        assert_eq!(executable("executable:   \n"), None);
    }
}
