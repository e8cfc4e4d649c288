//! Where a command writes, and the picture format it writes there: what
//! the command line says, checked before anything is read.

use crate::driver::picture::Target;
use crate::driver::Format;

/// The formats `render` writes, for its help and its errors: each with its
/// extension, an animation's with `--animate`. Made from [`Target::all`],
/// so that a format added there is named here.
pub fn formats_written() -> String {
    let named = |t: Target| match t {
        Target::Animation(_) => format!("{} (.{}, with --animate)", t.name(), t.extension()),
        Target::Still(_) | Target::Mesh(_) => format!("{} (.{})", t.name(), t.extension()),
    };
    Target::all().map(named).collect::<Vec<_>>().join(", ")
}

/// Where a command writes its result: `-o -`, like no `-o`, is standard
/// output; anything else is a file's path (a file named `-` is `-o ./-`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Output {
    Stdout,
    File(String),
}

impl Output {
    /// The output `-o` names; `None` (no `-o`) is standard output.
    pub fn from_arg(arg: Option<&str>) -> Output {
        match arg {
            None | Some("-") => Output::Stdout,
            Some(path) => Output::File(path.to_string()),
        }
    }

    /// The file's path, `None` for standard output.
    pub fn path(&self) -> Option<&str> {
        match self {
            Output::Stdout => None,
            Output::File(p) => Some(p),
        }
    }
}

/// A command line that cannot be carried out (exit status 2): what is
/// wrong, and how to say it instead.
#[derive(Debug, PartialEq, Eq)]
pub struct UsageError {
    pub message: String,
    pub help: String,
}

/// The picture format `render` writes to `output`: `to` (`--to`) when
/// given, else the file's extension. Standard output has no extension, so
/// there `to` is needed; a `to` that contradicts the extension is refused
/// rather than writing SVG text into `plant.png`. A binary PNG is refused
/// when standard output is a terminal (`stdout_terminal`): it would fill
/// the screen with noise and can leave the terminal in a strange state.
pub fn picture_format(
    output: &Output,
    to: Option<Format>,
    stdout_terminal: bool,
) -> Result<Format, UsageError> {
    let format = match (output, to) {
        (Output::Stdout, None) => {
            return Err(UsageError {
                message: "`-o -` writes the picture to standard output, but in which format?"
                    .into(),
                help: "add `--to png` or `--to svg`".into(),
            })
        }
        (Output::Stdout, Some(f)) => f,
        (Output::File(path), to) => match (Format::from_path(path), to) {
            (None, None) => {
                return Err(UsageError {
                    message: format!(
                        "cannot tell the format of `{path}`: graftal writes {}",
                        formats_written()
                    ),
                    help: "end the file name in one of these extensions, or add `--to png` or \
                           `--to svg`"
                        .into(),
                })
            }
            (Some(by_name), Some(f)) if by_name != f => {
                return Err(UsageError {
                    message: format!(
                        "`--to {}` but `{path}` names a {} file",
                        f.name(),
                        by_name.name()
                    ),
                    help: format!("drop `--to`, or name the file `….{}`", f.name()),
                })
            }
            (_, Some(f)) | (Some(f), None) => f,
        },
    };
    if format == Format::Png && *output == Output::Stdout && stdout_terminal {
        return Err(UsageError {
            message: "refusing to write a binary PNG to the terminal".into(),
            help: "redirect standard output (`… -o - --to png > plant.png`), or use `--to svg`"
                .into(),
        });
    }
    Ok(format)
}
