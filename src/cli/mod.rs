//! The `graftal` command line (clap). Thin: every command is a few
//! [`crate::driver`] calls and printing. `run` takes its output streams as
//! arguments so tests can drive it.
//!
//! Exit status: 0 success (warnings allowed), 1 the input has errors, 2 a
//! usage or I/O problem.

mod bars;
mod output;
mod records;

use crate::diagnostics::{self, render_all, render_json, Diagnostic};
use crate::driver::picture;
use crate::driver::DEFAULT_MAX_SYMBOLS;
use crate::driver::{self, Compiled, Format, RunOptions};
use crate::render::View;
use bars::{stage_bar, step_bar, Bars};
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand, ValueEnum};
use output::{picture_format, Output, UsageError};
use std::io::{IsTerminal, Write};

#[derive(Parser, Debug)]
#[command(
    name = "graftal",
    version,
    about = "Read, check, derive, draw, translate and explain L-systems",
    after_help = "FILE is a path or std:NAME (`graftal list`). The notation comes from the \
extension, and for `.l` (pfg, cpfg, Fractint) from the content; `--notation` overrides it."
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
enum OutputFormat {
    /// For people: ariadne's snippets, in colour on a terminal.
    #[default]
    Human,
    /// One JSON object per line.
    Json,
}

/// Notations graftal reads: the front ends' names.
fn notations() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(crate::front::FRONTS.iter().map(|f| f.name()))
}

/// Notations `translate` writes: the emitters' names.
fn targets() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(crate::back::BACKS.iter().map(|b| b.name()))
}

/// How a file is read: which entry of a library, in which notation.
#[derive(clap::Args, Debug, Clone)]
struct Reading {
    /// The entry of a Fractint library (case-insensitive, as in Fractint).
    #[arg(long)]
    entry: Option<String>,
    /// Read the file in this notation, whatever its extension or content
    /// [default: by the extension, and by content for `.l`].
    #[arg(long, value_parser = notations())]
    notation: Option<String>,
}

#[derive(clap::Args, Debug, Clone)]
struct DeriveArgs {
    /// A path, or std:NAME for a standard-library system; FILE:NAME
    /// chooses an entry of a Fractint library.
    file: String,
    #[command(flatten)]
    reading: Reading,
    /// Derivation steps (default: the file's derivation length, else 0;
    /// Fractint's order 2 for Fractint entries).
    #[arg(short = 'n', long = "steps")]
    steps: Option<u64>,
    /// Seed for stochastic productions and random angles.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Stop with an error when the word would grow past this many symbols.
    #[arg(long, default_value_t = DEFAULT_MAX_SYMBOLS)]
    max_symbols: usize,
    /// How diagnostics are printed.
    #[arg(long, value_enum, default_value_t)]
    format: OutputFormat,
}

#[derive(clap::Args, Debug, Clone)]
struct TranslateArgs {
    /// A path, or std:NAME for a standard-library system; FILE:NAME
    /// chooses an entry of a Fractint library.
    file: String,
    #[command(flatten)]
    reading: Reading,
    /// The target notation.
    #[arg(long, value_parser = targets())]
    to: String,
    /// Output file; `-` (the default) is standard output.
    #[arg(short = 'o', long = "output")]
    output: Option<String>,
    /// Approximate or drop what the target cannot express, with a warning each.
    #[arg(long)]
    lossy: bool,
    /// Derivation steps: the target's derivation length, or, for STL, the
    /// steps written into its rules (default: the file's derivation length).
    #[arg(short = 'n', long = "steps")]
    steps: Option<u64>,
    /// `json` prints the mapping (each construct, exact or approximated,
    /// with its span) on stdout, and diagnostics as JSON.
    #[arg(long, value_enum, default_value_t)]
    format: OutputFormat,
}

#[derive(clap::Args, Debug, Clone)]
struct DeriveCmd {
    #[command(flatten)]
    args: DeriveArgs,
    /// Output file; `-` (the default) is standard output.
    #[arg(short = 'o', long = "output")]
    output: Option<String>,
    /// Threads that derive [default: every core; also GRAFTAL_THREADS].
    /// The word is the same for every count.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
}

#[derive(clap::Args, Debug, Clone)]
struct RenderArgs {
    #[command(flatten)]
    args: DeriveArgs,
    // The help lists the formats from the code that writes them.
    #[arg(short = 'o', long = "output", help = output_help())]
    output: String,
    /// Picture format: png or svg [default: by the output's extension].
    /// Needed with `-o -`; `--format` is the diagnostics' format.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(Format::NAMES))]
    to: Option<String>,
    /// Picture size in pixels.
    #[arg(long, default_value = "1024x1024", value_parser = parse_size)]
    size: (u32, u32),
    /// View direction for 3D systems: AZIMUTH,ELEVATION in degrees
    /// [default: the file's own view, else 0,0].
    #[arg(long, value_parser = parse_view, allow_hyphen_values = true)]
    view: Option<(f64, f64)>,
    /// Draw each branch as a B-spline through the turtle's positions
    /// (as the book draws kolams and Fig. 2.11).
    #[arg(long)]
    spline: bool,
    /// An SVG whose drawn parts name the bytes of the source that drew
    /// them (`data-src="FROM-TO"`), as the live page links them.
    #[arg(long)]
    linked: bool,
    /// Do not draw an STL file's layout shapes under the tree.
    #[arg(long)]
    no_layout: bool,
    /// Background: a name (white), #rrggbb, #rrggbbaa, or none/transparent
    /// [default: the file's own, else white].
    #[arg(long, value_parser = crate::ir::colours::parse)]
    background: Option<crate::ir::colours::Rgba>,
    /// Pixels of a line of the system's initial width; other widths scale
    /// with it.
    #[arg(long, value_parser = parse_stroke_width)]
    stroke_width: Option<f64>,
    /// Blank border on every side: pixels (50), or a share (5%, 0.05)
    /// [default: 5%].
    #[arg(long, value_parser = crate::render::Margin::parse)]
    margin: Option<crate::render::Margin>,
    /// Degrees to turn the picture (counterclockwise) before fitting it.
    #[arg(long, default_value_t = 0.0, value_parser = parse_degrees, allow_hyphen_values = true)]
    rotate: f64,
    /// Line colours instead of the system's: mono (black), depth (by
    /// branch depth), rainbow (along the turtle's path). Lines, splines and
    /// a lit look's cylinders and ribbons take them (shaded by its light);
    /// polygons, surfaces and spheres keep the system's colours.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::render::Palette::NAMES))]
    palette: Option<String>,
    /// SVG detail: merged (lines that add nothing visible at the picture's
    /// size left out, points within half a pixel of a straight line
    /// merged, coordinates to a tenth of a pixel) or full (every segment).
    #[arg(long, default_value = "merged", value_parser = clap::builder::PossibleValuesParser::new(crate::render::Detail::NAMES))]
    detail: String,
    /// Draw steps 0..N as the frames of an animation, from the first step
    /// that draws anything, all framed as the last: `-o OUT.gif`, or
    /// `-o OUT.png` for an animated PNG.
    #[arg(long)]
    animate: bool,
    /// Ray trace the picture: lit, with shadows, the turtle's lines as
    /// round cylinders [default: for 3D instancing graphs and looks that
    /// cast shadows].
    #[arg(long)]
    raytrace: bool,
    /// Samples per pixel of a ray-traced picture: 1, 4, 9 or 16.
    #[arg(long, default_value_t = 4, value_parser = parse_samples)]
    samples: u32,
    /// Threads that draw [default: every core; also GRAFTAL_THREADS]. The
    /// picture is the same for every count.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// Frames per second of `--animate` [default: 10].
    // No default here: `--fps` without `--animate` is refused, so whether it
    // was given must show.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100))]
    fps: Option<u32>,
}

/// The help of `render -o`: every format graftal writes, by extension.
fn output_help() -> String {
    format!(
        "Output file, in the format its extension names: {}; `-` is standard output (with `--to`)",
        output::formats_written()
    )
}

fn parse_stroke_width(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|w| w.is_finite() && *w >= 0.0 && *w <= f64::from(MAX_SIDE))
        .ok_or_else(|| format!("`{s}` is not a width in pixels (0..={MAX_SIDE})"))
}

fn parse_samples(s: &str) -> Result<u32, String> {
    match s.trim().parse::<u32>() {
        Ok(n @ (1 | 4 | 9 | 16)) => Ok(n),
        _ => Err(format!("`{s}` is not 1, 4, 9 or 16 samples per pixel")),
    }
}

/// Threads asked for: `--threads`, else `GRAFTAL_THREADS`, else 0 (every
/// core).
fn threads_asked(flag: Option<u32>) -> usize {
    flag.map(|n| n as usize)
        .or_else(|| {
            let env = std::env::var("GRAFTAL_THREADS").ok()?;
            env.trim()
                .parse::<usize>()
                .ok()
                .filter(|n| (1..=1024).contains(n))
        })
        .unwrap_or(0)
}

fn parse_degrees(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|d| d.is_finite())
        .ok_or_else(|| format!("`{s}` is not an angle in degrees"))
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse and validate files; diagnostics on stderr. A Fractint library's
    /// entries are all checked and listed on stdout (FILE:NAME or --entry
    /// checks one).
    Check {
        /// Files to check: paths, or std:NAME; FILE:NAME checks one entry
        /// of a Fractint library.
        #[arg(required = true)]
        files: Vec<String>,
        #[command(flatten)]
        reading: Reading,
        /// How diagnostics are printed.
        #[arg(long, value_enum, default_value_t)]
        format: OutputFormat,
        /// Threads that read the files [default: every core; also
        /// GRAFTAL_THREADS]. The report is the same for every count.
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        threads: Option<u32>,
    },
    /// Print the derived word after N steps (to stdout, or to `-o FILE`).
    Derive(DeriveCmd),
    /// Draw the system to a picture, a mesh or an animation (by the output's
    /// extension or `--to`); `-o - --to svg` writes to standard output.
    Render(RenderArgs),
    /// Translate a file to another notation (pfg, LinF, STL or gft); what the
    /// target cannot express is an error, or a warning with --lossy.
    Translate(TranslateArgs),
    /// Count symbols, segments, polygons; bounding box and branch depth.
    Stats(DeriveArgs),
    /// Explain a diagnostic code, e.g. `graftal explain E0004`; without a
    /// code, list every code with its title.
    Explain {
        /// The code, e.g. E0004 or W0001.
        code: Option<String>,
    },
    /// Serve the Language Server Protocol on stdin and stdout (LSP 3.17):
    /// an editor's diagnostics, hover, definitions, outline and completion.
    Lsp,
    /// Serve a page on 127.0.0.1 where a model is edited and its picture
    /// and diagnostics follow as it is typed; Save writes FILE.
    Serve {
        /// A file (created when saved), or `std:NAME`; none: an empty model.
        file: Option<String>,
        /// The port; 0 takes any free one.
        #[arg(long, default_value_t = 7878)]
        port: u16,
        /// Listen on this address instead of 127.0.0.1 (loopback): the
        /// page can then be reached, and FILE written, from the network.
        #[arg(long, default_value = "127.0.0.1")]
        host: std::net::IpAddr,
    },
    /// List the standard library (`std:NAME`): each entry's figure and
    /// whether it draws at its defaults or is a schema (a string example).
    List {
        /// `human` (a line per entry) or `json` (one document).
        #[arg(long, value_enum, default_value_t)]
        format: OutputFormat,
    },
    /// Rewrite `.gft` files in the canonical layout (the one `translate
    /// --to gft` writes), keeping their comments. Each file is rewritten in
    /// place; `-` reads standard input and writes standard output. A file
    /// with errors is left as it is (exit status 1).
    Fmt {
        /// `.gft` files, or `-` for standard input.
        #[arg(required = true)]
        files: Vec<String>,
        /// Write nothing: list the files that would change, exit status 1
        /// if any would.
        #[arg(long)]
        check: bool,
    },
    /// Draw every standard-library entry (PNG and SVG) into OUT_DIR with
    /// an index (index.html, README.md) naming each entry's figure.
    Gallery {
        /// The folder to write, e.g. docs/gallery.
        out_dir: String,
        /// Threads that draw [default: every core; also GRAFTAL_THREADS].
        /// The files are the same for every count.
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        threads: Option<u32>,
    },
    /// Print a standard-library entry's source text, e.g. `graftal show std:algae`.
    Show {
        /// The entry, `std:NAME` or `NAME`.
        name: String,
    },
}

/// The largest picture side: 8192² pixels take 256 MB.
const MAX_SIDE: u32 = 8192;

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT"))?;
    let w: u32 = w.trim().parse().map_err(|_| format!("bad width `{w}`"))?;
    let h: u32 = h.trim().parse().map_err(|_| format!("bad height `{h}`"))?;
    if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(format!("width and height must be 1..={MAX_SIDE}"));
    }
    Ok((w, h))
}

fn parse_view(s: &str) -> Result<(f64, f64), String> {
    let (a, e) = s
        .split_once(',')
        .ok_or_else(|| format!("`{s}` is not AZIMUTH,ELEVATION"))?;
    let a: f64 = a.trim().parse().map_err(|_| format!("bad azimuth `{a}`"))?;
    let e: f64 = e
        .trim()
        .parse()
        .map_err(|_| format!("bad elevation `{e}`"))?;
    if !a.is_finite() || !e.is_finite() {
        return Err("angles must be finite".into());
    }
    Ok((a, e))
}

/// Where output goes, whether stderr is a terminal (colour, progress), and
/// whether stdout is one (no binary pictures there).
pub struct Io<'a> {
    pub stdout: &'a mut dyn Write,
    pub stderr: &'a mut dyn Write,
    pub terminal: bool,
    pub stdout_terminal: bool,
}

/// The one-line description, naming the notations the registry reads.
fn about() -> String {
    format!(
        "Read, check, derive, draw, translate and explain L-systems ({})",
        driver::notations()
    )
}

/// Runs the command line `args` (with the program name first); returns the
/// exit status.
pub fn run<I, T>(args: I, io: &mut Io<'_>) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let parsed = Cli::command()
        .about(about())
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m));
    let cli = match parsed {
        Ok(c) => c,
        Err(e) => return usage(io, &e),
    };
    match cli.command {
        Command::Check {
            files,
            reading,
            format,
            threads,
        } => check(io, &files, &reading, format, threads_asked(threads)),
        Command::Derive(a) => derive(io, &a),
        Command::Stats(a) => stats(io, &a),
        Command::Render(a) => render(io, &a),
        Command::Translate(a) => translate(io, &a),
        Command::Explain { code: Some(code) } => explain(io, &code),
        Command::Explain { code: None } => explain_all(io),
        Command::List { format } => list(io, format),
        Command::Show { name } => show(io, &name),
        Command::Gallery { out_dir, threads } => gallery(io, &out_dir, threads_asked(threads)),
        Command::Lsp => lsp(io),
        Command::Serve { file, port, host } => {
            serve(io, file, std::net::SocketAddr::new(host, port))
        }
        Command::Fmt { files, check } => files.iter().map(|f| fmt(io, f, check)).max().unwrap_or(0),
    }
}

/// Prints clap's message for a command line it did not accept, or for
/// `--help` and `--version`; the exit status.
fn usage(io: &mut Io<'_>, e: &clap::Error) -> i32 {
    let code = if e.use_stderr() { 2 } else { 0 };
    let text = if io.terminal {
        e.render().ansi().to_string()
    } else {
        e.render().to_string()
    };
    let out: &mut dyn Write = if e.use_stderr() { io.stderr } else { io.stdout };
    let _ = write!(out, "{text}");
    code
}

/// `graftal check`: each file's diagnostics, and its listing.
fn check(
    io: &mut Io<'_>,
    files: &[String],
    reading: &Reading,
    format: OutputFormat,
    threads: usize,
) -> i32 {
    let notation = reading.notation.as_deref().and_then(crate::front::by_name);
    // Read and checked on every thread, reported in the order given.
    let checked = crate::parallel::map_in_order(
        files.len(),
        threads,
        |k| {
            let (path, named) = driver::split_entry(&files[k]);
            driver::load(&path).map(|file| {
                let entry = reading.entry.as_deref().or(named.as_deref());
                let c = driver::compile_as(file, entry, notation);
                // What `derive` would add: the derivation's limits.
                let limits = driver::derivation_diagnostics(&c);
                (c, limits)
            })
        },
        |_| {},
    );
    let mut status = 0;
    let mut listings = Vec::new();
    for done in checked {
        match done {
            Ok((c, limits)) => {
                report(io, &c, &c.diagnostics.0, format);
                report(io, &c, &limits, format);
                match format {
                    OutputFormat::Human => list_entries(io, &c),
                    OutputFormat::Json => listings.push(listing_json(&c)),
                }
                if c.diagnostics.has_errors() || (c.system.is_none() && !c.needs_entry()) {
                    status = status.max(1);
                }
            }
            Err(e) => {
                fail(io, format, &e.to_string(), None);
                status = 2;
            }
        }
    }
    if format == OutputFormat::Json {
        let listing = serde_json::json!({ "files": listings });
        let _ = write!(io.stdout, "{}", records::line(records::FILES, listing));
    }
    status
}

/// `graftal derive`: the derived word on stdout, or in `-o FILE`.
fn derive(io: &mut Io<'_>, a: &DeriveCmd) -> i32 {
    let path = match Output::from_arg(a.output.as_deref()) {
        Output::Stdout => None,
        Output::File(p) => Some(p),
    };
    // Created up front: a path that cannot be written is found before
    // deriving, and is a usage problem (status 2).
    let mut file = match path.as_deref().map(std::fs::File::create).transpose() {
        Ok(f) => f,
        Err(e) => {
            let path = path.as_deref().unwrap_or_default();
            let message = format!("cannot write `{path}`: {e}");
            fail(io, a.args.format, &message, None);
            return 2;
        }
    };
    let status = with_system(io, &a.args, |io, c, sys, opts, _| {
        let bar = step_bar(io, sys, opts);
        let out: &mut dyn Write = match &mut file {
            Some(f) => f,
            None => io.stdout,
        };
        let opts = &RunOptions {
            threads: threads_asked(a.threads),
            ..opts.clone()
        };
        let r = driver::write_derived(c.front, sys, opts, out, |step, len| {
            if let Some(bar) = &bar {
                bar.set_position(step);
                bar.set_message(format!("{len} symbols"));
            }
        });
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        r.map_err(|d| vec![d])?;
        Ok(0)
    });
    if status != 0 {
        // No half-written or empty word is left behind.
        if let Some(p) = &path {
            let _ = std::fs::remove_file(p);
        }
    }
    status
}

/// `graftal stats`: counts, box, depth, method and times, as text or JSON.
fn stats(io: &mut Io<'_>, a: &DeriveArgs) -> i32 {
    with_system(io, a, |io, c, sys, opts, parse| {
        let mut s = driver::stats(sys, opts).map_err(|d| vec![d])?;
        s.time.parse = parse;
        report(io, c, &s.warnings, a.format);
        match a.format {
            OutputFormat::Json => {
                let _ = write!(io.stdout, "{}", records::line(records::STATS, &s));
            }
            OutputFormat::Human => {
                let bbox = match s.bbox.map(|b| b.map(crate::number::readable)) {
                    Some(b) => format!(
                        "[{}, {}, {}] .. [{}, {}, {}]",
                        b[0], b[1], b[2], b[3], b[4], b[5]
                    ),
                    None => format!(
                        "beyond floating point ({})",
                        diagnostics::codes::BOX_TOO_LARGE
                    ),
                };
                let _ = writeln!(
                    io.stdout,
                    "steps      {}\nsymbols    {}\nsegments   {}\npolygons   {}\nbbox       {bbox}\nmax depth  {}\nmethod     {}\ntime       parse {:.6}s, derive {:.6}s, interpret {:.6}s",
                    s.steps, s.symbols, s.segments, s.polygons, s.max_depth, s.method, s.time.parse, s.time.derive, s.time.interpret
                );
                if let Some(n) = s.instances {
                    let side = crate::driver::GRAPH_STATS_PIXELS;
                    let _ = writeln!(
                        io.stdout,
                        "instances  {n} (primitives placed, down to the pixels of a {side}x{side} picture)"
                    );
                }
            }
        }
        Ok(0)
    })
}

/// `graftal render`: the picture, a mesh or an animation, as the output's
/// name and `--to` say, drawn by [`picture::draw`].
fn render(io: &mut Io<'_>, a: &RenderArgs) -> i32 {
    let (target, output) = match render_target(io, a) {
        Ok(t) => t,
        Err(e) => return usage_error(io, &e, a.args.format),
    };
    with_system(io, &a.args, |io, c, _sys, opts, _| {
        let req = picture::Request {
            run: opts.clone(),
            target,
            width: a.size.0,
            height: a.size.1,
            // `--view` is in degrees.
            view: a.view.map(|(az, el)| View::degrees(az, el)),
            style: crate::render::Style {
                background: a.background,
                stroke_width: a.stroke_width,
                margin: a.margin,
                rotate: a.rotate,
                palette: a
                    .palette
                    .as_deref()
                    .and_then(crate::render::Palette::from_name),
            },
            detail: crate::render::Detail::from_name(&a.detail).unwrap_or_default(),
            spline: a.spline,
            layout: !a.no_layout,
            fps: a.fps.unwrap_or(picture::DEFAULT_FPS),
            material_library: material_library(&a.output),
            tracing: picture::Tracing {
                raytrace: a.raytrace.then_some(true),
                samples: a.samples,
                threads: threads_asked(a.threads),
            },
            linked: a.linked,
        };
        let mut bars = Bars::new(io);
        let drawn = picture::draw(c, &req, &mut bars);
        bars.clear();
        let p = match drawn {
            Ok(p) => p,
            Err(picture::DrawError::Stopped(d)) => return Err(vec![*d]),
            Err(e) => {
                fail(io, a.args.format, &e.to_string(), None);
                return Ok(2);
            }
        };
        report(io, c, &p.warnings, a.args.format);
        Ok(write_picture(io, a, &output, &p))
    })
}

/// What `render` makes and where it writes it: a mesh by the output's
/// extension (`.obj`, `.ply`, `.glb`), an animation with `--animate`, else
/// a still picture in the format `--to` or the extension names.
fn render_target(io: &Io<'_>, a: &RenderArgs) -> Result<(picture::Target, Output), UsageError> {
    if let (Some(fps), false) = (a.fps, a.animate) {
        return Err(UsageError {
            message: format!(
                "`--fps {fps}` is the frame rate of an animation, but there is no `--animate`"
            ),
            help: "add `--animate` to draw the steps as the frames of a GIF or an animated PNG, \
                   or drop `--fps`"
                .into(),
        });
    }
    if let Some(mesh) = crate::mesh::MeshFormat::from_path(&a.output).filter(|_| a.to.is_none()) {
        if a.animate {
            let ext = picture::Target::Mesh(mesh).extension();
            return Err(UsageError {
                message: format!(
                    "`--animate` writes a GIF or an animated PNG, but `{}` names a mesh (.{ext})",
                    a.output
                ),
                help: "name the output `….gif` or `….png`, or drop `--animate` for the mesh of \
                       the last step"
                    .into(),
            });
        }
        return Ok((picture::Target::Mesh(mesh), Output::File(a.output.clone())));
    }
    let output = Output::from_arg(Some(&a.output));
    if a.animate {
        use crate::render::animate::Container;
        let Some(container) = Container::choose(output.path(), a.to.as_deref()) else {
            return Err(UsageError {
                message: "`--animate` writes a GIF or an animated PNG".into(),
                help: "name the output `….gif` or `….png` (`--to png` with `-o -`)".into(),
            });
        };
        if container == Container::Apng && output == Output::Stdout && io.stdout_terminal {
            picture_format(&output, Some(Format::Png), true)?;
        }
        return Ok((picture::Target::Animation(container), output));
    }
    let to = a.to.as_deref().and_then(Format::from_name);
    let format = picture_format(&output, to, io.stdout_terminal)?;
    Ok((picture::Target::Still(format), output))
}

/// The file name an OBJ gives its material library: the output's, ending
/// in `.mtl`.
fn material_library(output: &str) -> String {
    let mtl = std::path::Path::new(output).with_extension("mtl");
    mtl.file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("graftal.mtl")
        .to_string()
}

/// Writes a picture, its side files beside it, and for a mesh what it
/// holds on stdout; the exit status.
fn write_picture(io: &mut Io<'_>, a: &RenderArgs, output: &Output, p: &picture::Picture) -> i32 {
    let folder = std::path::Path::new(&a.output)
        .parent()
        .unwrap_or(std::path::Path::new(""));
    for side in &p.side_files {
        let path = folder.join(&side.name).display().to_string();
        let status = write_output(io, &Output::File(path), &side.bytes, a.args.format);
        if status != 0 {
            return status;
        }
    }
    let status = write_output(io, output, &p.bytes, a.args.format);
    if let (0, Some(s)) = (status, &p.mesh) {
        let _ = match a.args.format {
            OutputFormat::Json => write!(io.stdout, "{}", records::line(records::MESH, s)),
            OutputFormat::Human => writeln!(
                io.stdout,
                "{} vertices, {} triangles, {} materials, {} meshes placed {} times",
                s.vertices, s.triangles, s.materials, s.meshes, s.nodes
            ),
        };
    }
    status
}

/// `graftal gallery`: every stdlib entry's pictures and the index.
fn gallery(io: &mut Io<'_>, dir: &str, threads: usize) -> i32 {
    let bar = stage_bar(io, "gallery", "entries");
    let mut progress = |k: u64, n: u64| {
        if let Some(bar) = &bar {
            bar.set_length(n);
            bar.set_position(k);
        }
    };
    let done = crate::gallery::write(std::path::Path::new(dir), threads, &mut progress);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    match done {
        Ok(items) => {
            let drawn = items.iter().filter(|i| i.png.is_some()).count();
            let _ = writeln!(
                io.stdout,
                "{drawn} of {} entries drawn into {dir}",
                items.len()
            );
            0
        }
        Err(e) => {
            let _ = writeln!(io.stderr, "error: {e}");
            2
        }
    }
}

/// `graftal lsp`: serves the protocol until the client says `exit`.
fn lsp(io: &mut Io<'_>) -> i32 {
    match crate::lsp::run_stdio(io.stdout) {
        Ok(()) => 0,
        Err(e) => {
            let _ = writeln!(io.stderr, "error: graftal lsp: {e}");
            1
        }
    }
}

/// `graftal serve`: the live page, until the process is stopped.
fn serve(io: &mut Io<'_>, file: Option<String>, addr: std::net::SocketAddr) -> i32 {
    match crate::serve::run(&crate::serve::Options { file, addr }, io.stdout) {
        Ok(()) => 0,
        Err(e) => {
            let _ = writeln!(io.stderr, "error: graftal serve: {e}");
            1
        }
    }
}

/// `graftal explain`: a diagnostic code's title and explanation.
fn explain(io: &mut Io<'_>, code: &str) -> i32 {
    let Some(info) = diagnostics::codes::lookup(code) else {
        let _ = writeln!(
            io.stderr,
            "error: no diagnostic code `{code}` (codes look like E0004 or W0001)"
        );
        return 2;
    };
    let _ = writeln!(io.stdout, "{}", diagnostics::codes::explain_text(info));
    0
}

/// `graftal explain` without a code: every code and its title, a line each,
/// sorted so that a code is found where its number says: the errors, then
/// the warnings, each by number (the registry keeps them by front end).
fn explain_all(io: &mut Io<'_>) -> i32 {
    let mut infos: Vec<_> = diagnostics::codes::all().collect();
    // `E` sorts before `W`, and every number has four digits.
    infos.sort_by_key(|info| info.code);
    for info in infos {
        let _ = writeln!(io.stdout, "{}  {}", info.code, info.title);
    }
    let _ = writeln!(
        io.stdout,
        "\n`graftal explain CODE` explains one (E: errors, W: warnings)."
    );
    0
}

/// `graftal list`: the standard library's names, figures and kinds.
fn list(io: &mut Io<'_>, format: OutputFormat) -> i32 {
    let text = match format {
        OutputFormat::Human => crate::stdlib::listing(),
        OutputFormat::Json => records::line(records::STDLIB, crate::stdlib::listing_json()),
    };
    let _ = write!(io.stdout, "{text}");
    0
}

/// `graftal show`: a stdlib entry's source text.
fn show(io: &mut Io<'_>, name: &str) -> i32 {
    let name = name.strip_prefix("std:").unwrap_or(name);
    match crate::stdlib::get(name) {
        Some(e) => {
            let _ = write!(io.stdout, "{}", e.text);
            0
        }
        None => {
            let _ = writeln!(io.stderr, "error: {}", crate::stdlib::unknown(name));
            2
        }
    }
}

/// `graftal fmt` of one file (`-`: standard input to standard output).
fn fmt(io: &mut Io<'_>, spec: &str, check: bool) -> i32 {
    let file = if spec == "-" {
        match std::io::read_to_string(std::io::stdin()) {
            Ok(text) => crate::source::SourceFile::new("<stdin>", text),
            Err(e) => {
                let _ = writeln!(io.stderr, "error: cannot read standard input: {e}");
                return 2;
            }
        }
    } else {
        match crate::source::SourceFile::read(std::path::Path::new(spec)) {
            Ok(f) => f,
            Err(e) => {
                let _ = writeln!(io.stderr, "error: cannot read `{spec}`: {e}");
                return 2;
            }
        }
    };
    let f = crate::format::format(file);
    let text = match f.outcome {
        crate::format::Outcome::Formatted(text) => text,
        crate::format::Outcome::HasErrors => {
            report(
                io,
                &f.compiled,
                &f.compiled.diagnostics.0,
                OutputFormat::Human,
            );
            return 1;
        }
        crate::format::Outcome::NotSame(why) => {
            let _ = writeln!(io.stderr, "error: `{spec}` not formatted: {why}");
            return 1;
        }
    };
    let changed = text != f.compiled.file.text;
    if check {
        if changed {
            let _ = writeln!(io.stdout, "{spec} would be reformatted");
        }
        return i32::from(changed);
    }
    if spec == "-" {
        return write_output(io, &Output::Stdout, text.as_bytes(), OutputFormat::Human);
    }
    if !changed {
        return 0;
    }
    let output = Output::File(spec.to_string());
    write_output(io, &output, text.as_bytes(), OutputFormat::Human)
}

/// `graftal translate`: source -> IR -> the target's emitter. Errors (what
/// the target cannot express, without `--lossy`) mean exit status 1 and
/// nothing written.
fn translate(io: &mut Io<'_>, a: &TranslateArgs) -> i32 {
    let Some(c) = load_and_compile(io, &a.file, &a.reading, a.format) else {
        return 2;
    };
    let Some(sys) = &c.system else {
        return 1;
    };
    let Some(target) = crate::back::by_name(&a.to) else {
        return 2;
    };
    let req = crate::back::Request {
        target,
        lossy: a.lossy,
        steps: a.steps,
    };
    let t = driver::translate(&c, sys, &req);
    let output = Output::from_arg(a.output.as_deref());
    report(io, &c, &t.diagnostics.0, a.format);
    if a.format == OutputFormat::Json {
        let span = |s: &Option<crate::ir::Span>| {
            s.as_ref().map(|s| {
                let (line, column) = c.file.line_col(s.start);
                serde_json::json!({"start": s.start, "end": s.end, "line": line, "column": column})
            })
        };
        let constructs: Vec<serde_json::Value> = t
            .mapping
            .iter()
            .map(|m| {
                serde_json::json!({
                    "construct": m.construct,
                    "status": m.status,
                    "span": span(&m.span),
                    "target": m.target,
                    "note": m.note,
                })
            })
            .collect();
        let names: Vec<serde_json::Value> = t
            .names
            .iter()
            .map(|(f, to)| serde_json::json!({"source": f, "target": to}))
            .collect();
        let mut doc = serde_json::json!({
            "file": c.file.name,
            "from": c.front.name(),
            "to": target.name(),
            "exact": t.is_exact(),
            "written": t.text.is_some(),
            "output": output.path(),
            "names": names,
            "constructs": constructs,
        });
        if output == Output::Stdout {
            doc["text"] = serde_json::json!(t.text);
        }
        let _ = write!(io.stdout, "{}", records::line(records::TRANSLATION, doc));
    }
    let Some(text) = t.text else {
        return 1;
    };
    // With `--format json` the text is in the JSON document on stdout.
    if output == Output::Stdout && a.format == OutputFormat::Json {
        return 0;
    }
    write_output(io, &output, text.as_bytes(), a.format)
}

/// Loads and compiles `a.file`, prints its diagnostics, and runs `f` on the
/// system when there are no errors. `f`'s diagnostics (evaluation errors)
/// are printed too, and mean exit status 1.
fn with_system(
    io: &mut Io<'_>,
    a: &DeriveArgs,
    f: impl FnOnce(
        &mut Io<'_>,
        &Compiled,
        &crate::ir::System,
        &RunOptions,
        f64,
    ) -> Result<i32, Vec<Diagnostic>>,
) -> i32 {
    let t = std::time::Instant::now();
    let Some(c) = load_and_compile(io, &a.file, &a.reading, a.format) else {
        return 2;
    };
    let parse_seconds = t.elapsed().as_secs_f64();
    let Some(sys) = &c.system else {
        return 1;
    };
    let opts = RunOptions {
        steps: a.steps,
        seed: a.seed,
        max_symbols: a.max_symbols,
        threads: threads_asked(None),
        ..RunOptions::default()
    };
    match f(io, &c, sys, &opts, parse_seconds) {
        Ok(code) => code,
        Err(ds) => {
            report(io, &c, &ds, a.format);
            1
        }
    }
}

/// Loads `spec` (`FILE:NAME` or `--entry` choosing a Fractint entry) and
/// compiles it, printing its diagnostics, and the error asking for an
/// entry when a library's entry is not chosen. `None` when the file cannot
/// be read.
fn load_and_compile(
    io: &mut Io<'_>,
    spec: &str,
    reading: &Reading,
    format: OutputFormat,
) -> Option<Compiled> {
    let (path, named) = driver::split_entry(spec);
    let file = match driver::load(&path) {
        Ok(f) => f,
        Err(e) => {
            fail(io, format, &e.to_string(), None);
            return None;
        }
    };
    let notation = reading.notation.as_deref().and_then(crate::front::by_name);
    let entry = reading.entry.as_deref().or(named.as_deref());
    let c = driver::compile_as(file, entry, notation);
    report(io, &c, &c.diagnostics.0, format);
    if c.needs_entry() {
        report(io, &c, &[driver::choose_entry(&c)], format);
    }
    Some(c)
}

/// The widest entry name `check` lists; a longer one is shortened.
const LISTED_NAME: usize = 40;

/// The most entries `check` lists.
use driver::LISTED_ENTRIES;

/// `check`'s listing: which notation a file shared by several was read
/// as (`FILE: dialect: …`), then a library's entries with their lines and
/// what was found: the first [`LISTED_ENTRIES`], and the chosen one if it
/// comes later, then how many more there are. Names come from the file:
/// shown escaped and shortened.
fn list_entries(io: &mut Io<'_>, c: &Compiled) {
    let summary = match &c.library {
        Some(lib) => Some(lib.summary.clone()),
        None => c.front.describe(c.system.as_ref()),
    };
    let file_name = diagnostics::escaped(&c.file.name);
    if let Some(summary) = summary {
        let _ = writeln!(
            io.stdout,
            "{file_name}: dialect: {}",
            diagnostics::shortened(&summary, 4 * LISTED_NAME)
        );
    }
    let Some(lib) = &c.library else { return };
    let listed = listed_entries(lib);
    let names: Vec<_> = listed
        .iter()
        .map(|&i| diagnostics::shortened(&lib.entries[i].name, LISTED_NAME))
        .collect();
    let width = names.iter().map(|n| n.chars().count()).max().unwrap_or(0);
    for (&i, name) in listed.iter().zip(&names) {
        let e = &lib.entries[i];
        let (line, _) = c.file.line_col(e.span.start);
        let state = match (e.errors, e.warnings) {
            (0, 0) => "ok".to_string(),
            (0, w) => format!("ok, {w} warning{}", if w == 1 { "" } else { "s" }),
            (n, _) => format!("{n} error{}", if n == 1 { "" } else { "s" }),
        };
        let chosen = if lib.chosen == Some(i) && lib.entries.len() > 1 {
            "  (chosen)"
        } else {
            ""
        };
        let _ = writeln!(io.stdout, "  {name:width$}  line {line:<4} {state}{chosen}");
    }
    let more = lib.entries.len() - listed.len();
    if more > 0 {
        let _ = writeln!(
            io.stdout,
            "  … and {more} more; `graftal check {file_name}:NAME` checks one"
        );
    }
}

/// The entries `check` lists: the first [`LISTED_ENTRIES`], and the
/// chosen one if it comes later.
fn listed_entries(lib: &crate::front::Library) -> Vec<usize> {
    (0..lib.entries.len().min(LISTED_ENTRIES))
        .chain(lib.chosen.filter(|&i| i >= LISTED_ENTRIES))
        .collect()
}

/// `check --format json`'s listing of one file, an object of the one
/// document on stdout: `file`, `notation`, `dialect` (what the human
/// listing prints after `dialect:`, or null), and for a library `entries`
/// (name, line, errors, warnings, chosen; as many as the human listing)
/// and `total`; `entries` is null for a file of one system.
fn listing_json(c: &Compiled) -> serde_json::Value {
    let dialect = match &c.library {
        Some(lib) => Some(lib.summary.clone()),
        None => c.front.describe(c.system.as_ref()),
    };
    let entries = c.library.as_ref().map(|lib| {
        let listed: Vec<serde_json::Value> = listed_entries(lib)
            .into_iter()
            .map(|i| {
                let e = &lib.entries[i];
                serde_json::json!({
                    "name": e.name,
                    "line": c.file.line_col(e.span.start).0,
                    "errors": e.errors,
                    "warnings": e.warnings,
                    "chosen": lib.chosen == Some(i),
                })
            })
            .collect();
        listed
    });
    serde_json::json!({
        "file": c.file.name,
        "notation": c.front.name(),
        "dialect": dialect,
        "entries": entries,
        "total": c.library.as_ref().map(|l| l.entries.len()),
    })
}

/// Writes `bytes` to a file or to stdout; the exit status. A closed pipe
/// (`| head`) is not an error, as for `derive`. A file that cannot be
/// written is said in `format`.
fn write_output(io: &mut Io<'_>, output: &Output, bytes: &[u8], format: OutputFormat) -> i32 {
    match output {
        Output::Stdout => {
            let _ = io.stdout.write_all(bytes).and_then(|()| io.stdout.flush());
        }
        Output::File(path) => {
            if let Err(e) = std::fs::write(path, bytes) {
                fail(io, format, &format!("cannot write `{path}`: {e}"), None);
                return 2;
            }
        }
    }
    0
}

/// Prints a command line that cannot be carried out, with its help line;
/// the exit status (2).
fn usage_error(io: &mut Io<'_>, e: &UsageError, format: OutputFormat) -> i32 {
    fail(io, format, &e.message, Some(&e.help));
    2
}

/// Prints a problem that is not a diagnostic (a file that cannot be read
/// or written): `error: MESSAGE` and its help line, or in JSON its
/// [`records::ERROR`] record, so that every line of `--format json` is one.
fn fail(io: &mut Io<'_>, format: OutputFormat, message: &str, help: Option<&str>) {
    let text = match (format, help) {
        (OutputFormat::Json, _) => records::error(message, help),
        (OutputFormat::Human, Some(help)) => format!("error: {message}\n  help: {help}\n"),
        (OutputFormat::Human, None) => format!("error: {message}\n"),
    };
    let _ = write!(io.stderr, "{text}");
}

fn report(io: &mut Io<'_>, c: &Compiled, ds: &[Diagnostic], format: OutputFormat) {
    let text = match format {
        OutputFormat::Json => render_json(ds, &c.file),
        OutputFormat::Human => render_all(ds, &c.file, io.terminal),
    };
    let _ = write!(io.stderr, "{text}");
}

/// The binary's entry point.
pub fn main() -> i32 {
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    let terminal = stderr.is_terminal();
    let stdout_terminal = stdout.is_terminal();
    let mut out = stdout.lock();
    let mut err = stderr.lock();
    let mut io = Io {
        stdout: &mut out,
        stderr: &mut err,
        terminal,
        stdout_terminal,
    };
    run(std::env::args_os(), &mut io)
}
