//! Every cpfg object of the corpus that carries cpfg's own thumbnail
//! (`icon.png`, vlab's `icon`: cpfg's picture of the object at its
//! defaults) is drawn by graftal at the thumbnail's size and held against
//! it:
//!
//! - **background**: the most common colour of the border pixels of each
//!   picture, compared by RGB distance;
//! - **silhouette**: the pixels that differ from the background, cropped
//!   to their bounding box, fitted (aspect kept) into a `GRID`×`GRID` grid
//!   and dilated by one cell (so a line one pixel off still meets), then
//!   compared by intersection over union;
//! - **colour**: the mean colour of the foreground pixels most unlike the
//!   background, compared by RGB distance.
//!
//! A thumbnail that is a crop of cpfg's window (its foreground runs off
//! its sides: zoomed by hand, or a window smaller than the object) is held
//! against the window of graftal's picture that fits it best
//! ([`fitted_crop`]): the silhouettes are then compared cell for cell,
//! positions kept. A thumbnail that is a later frame of the object's
//! animation is drawn at that frame's steps ([`FRAMES`], with the evidence).
//!
//! The thresholds are below. `GRAFTAL_ICONS=1 cargo test --test it cpfg_icons
//! -- --nocapture` prints every object's figures and writes graftal's
//! pictures beside the thumbnails in `target/icons/`.

use graftal::driver::{self, Format, RunOptions};
use graftal::render::RenderOptions;
use graftal::source::SourceFile;
use std::path::{Path, PathBuf};

/// Cells across the fitted silhouette grid.
const GRID: usize = 40;
/// RGB distance beyond which a pixel is foreground.
const FOREGROUND: f64 = 40.0;

/// Foreground pixels on one side of a thumbnail that make it a crop.
const CROPPED: usize = 20;

/// What every object must reach.
const MIN_OVERLAP: f64 = 0.5;
const MAX_COLOUR_DISTANCE: f64 = 90.0;
const MAX_BACKGROUND_DISTANCE: f64 = 40.0;

/// An RGB picture.
struct Picture {
    width: usize,
    height: usize,
    pixels: Vec<[u8; 3]>,
}

impl Picture {
    fn decode(bytes: &[u8]) -> Picture {
        let pm = tiny_skia::Pixmap::decode_png(bytes).expect("a PNG");
        let pixels = pm
            .pixels()
            .iter()
            .map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue()]
            })
            .collect();
        Picture {
            width: pm.width() as usize,
            height: pm.height() as usize,
            pixels,
        }
    }

    fn at(&self, x: usize, y: usize) -> [u8; 3] {
        self.pixels[y * self.width + x]
    }

    /// The part of the picture in `w`, resampled to `width`×`height` (the
    /// mean of four samples a pixel).
    fn window(&self, w: Window, width: usize, height: usize) -> Picture {
        let sample = |fx: f64, fy: f64| {
            let x = ((w.x0 + fx * w.side) * self.width as f64) as usize;
            let y = ((w.y0 + fy * w.side) * self.height as f64) as usize;
            self.at(x.min(self.width - 1), y.min(self.height - 1))
        };
        let mut pixels = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let mut sum = [0u32; 3];
                for (dx, dy) in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)] {
                    let c = sample(
                        (x as f64 + dx) / width as f64,
                        (y as f64 + dy) / height as f64,
                    );
                    for k in 0..3 {
                        sum[k] += u32::from(c[k]);
                    }
                }
                pixels.push(sum.map(|v| ((v + 2) / 4) as u8));
            }
        }
        Picture {
            width,
            height,
            pixels,
        }
    }

    /// The picture as a PNG.
    fn encode(&self) -> Vec<u8> {
        let size = tiny_skia::IntSize::from_wh(self.width as u32, self.height as u32).unwrap();
        let rgba = self
            .pixels
            .iter()
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        tiny_skia::Pixmap::from_vec(rgba, size)
            .unwrap()
            .encode_png()
            .unwrap()
    }

    /// The most common colour of the border.
    fn background(&self) -> [u8; 3] {
        let mut counts = std::collections::BTreeMap::new();
        for x in 0..self.width {
            for y in [0, self.height - 1] {
                *counts.entry(self.at(x, y)).or_insert(0) += 1;
            }
        }
        for y in 0..self.height {
            for x in [0, self.width - 1] {
                *counts.entry(self.at(x, y)).or_insert(0) += 1;
            }
        }
        counts
            .into_iter()
            .max_by_key(|&(c, n)| (n, c))
            .map(|(c, _)| c)
            .unwrap()
    }

    /// Whether the thumbnail is a crop of cpfg's window (zoomed by hand,
    /// or a window too small for the object): its foreground runs off two
    /// sides, or off one side over `CROPPED` pixels. A plant standing on
    /// the bottom edge (vlab trims its icons) is not a crop. A crop's
    /// silhouette cannot be fitted against a whole picture.
    fn cropped(&self, fg: &[bool]) -> bool {
        let (w, h) = (self.width, self.height);
        let count = |pixels: &mut dyn Iterator<Item = usize>| pixels.filter(|&i| fg[i]).count();
        let sides = [
            count(&mut (0..w)),
            count(&mut (0..w).map(|x| (h - 1) * w + x)),
            count(&mut (0..h).map(|y| y * w)),
            count(&mut (0..h).map(|y| y * w + w - 1)),
        ];
        sides.iter().filter(|&&n| n >= 3).count() >= 2 || sides.iter().any(|&n| n >= CROPPED)
    }

    /// Whether each pixel differs from `bg`.
    fn foreground(&self, bg: [u8; 3]) -> Vec<bool> {
        self.pixels
            .iter()
            .map(|&p| distance(p, bg) > FOREGROUND)
            .collect()
    }
}

fn distance(a: [u8; 3], b: [u8; 3]) -> f64 {
    (0..3)
        .map(|k| (a[k] as f64 - b[k] as f64).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn mean_distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The foreground cropped to its bounding box and fitted, aspect kept and
/// centred, into the grid; then dilated by one cell. Empty when nothing is
/// in the foreground.
fn silhouette(p: &Picture, fg: &[bool]) -> Vec<bool> {
    let mut grid = vec![false; GRID * GRID];
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for y in 0..p.height {
        for x in 0..p.width {
            if fg[y * p.width + x] {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
    }
    if x0 == usize::MAX {
        return grid;
    }
    let side = (x1 - x0 + 1).max(y1 - y0 + 1) as f64;
    let (ox, oy) = (
        (side - (x1 - x0 + 1) as f64) / 2.0,
        (side - (y1 - y0 + 1) as f64) / 2.0,
    );
    for y in y0..=y1 {
        for x in x0..=x1 {
            if fg[y * p.width + x] {
                let gx = (((x - x0) as f64 + ox + 0.5) / side * GRID as f64) as usize;
                let gy = (((y - y0) as f64 + oy + 0.5) / side * GRID as f64) as usize;
                grid[gy.min(GRID - 1) * GRID + gx.min(GRID - 1)] = true;
            }
        }
    }
    dilate(&grid)
}

/// `grid` with every cell's four neighbours added (so that a line one
/// pixel off still meets).
fn dilate(grid: &[bool]) -> Vec<bool> {
    let mut dilated = grid.to_vec();
    for y in 0..GRID {
        for x in 0..GRID {
            if grid[y * GRID + x] {
                for (dx, dy) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    if (0..GRID as i64).contains(&nx) && (0..GRID as i64).contains(&ny) {
                        dilated[ny as usize * GRID + nx as usize] = true;
                    }
                }
            }
        }
    }
    dilated
}

fn overlap(a: &[bool], b: &[bool]) -> f64 {
    let both = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    if either == 0 {
        0.0
    } else {
        both as f64 / either as f64
    }
}

/// The colour of the foreground: the mean of its half most unlike the
/// background, so that the edges of thin lines, half background after
/// anti-aliasing or a thumbnail's downscaling, do not pull it towards the
/// background.
fn mean_colour(p: &Picture, fg: &[bool], bg: [u8; 3]) -> [f64; 3] {
    let mut strong: Vec<(f64, [u8; 3])> = p
        .pixels
        .iter()
        .zip(fg)
        .filter(|(_, f)| **f)
        .map(|(&px, _)| (distance(px, bg), px))
        .collect();
    strong.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    strong.truncate(strong.len().div_ceil(2));
    let n = strong.len().max(1) as f64;
    let mut sum = [0.0; 3];
    for (_, px) in &strong {
        for k in 0..3 {
            sum[k] += px[k] as f64;
        }
    }
    sum.map(|s| s / n)
}

/// The `.l` file cpfg draws for an object: the one on the `cpfg` command
/// line of its `specifications`, else its only `.l` with an L-system.
fn l_file(dir: &Path) -> PathBuf {
    if let Ok(spec) = std::fs::read_to_string(dir.join("specifications")) {
        for line in spec.lines() {
            let words: Vec<&str> = line.split_whitespace().collect();
            if words.first() == Some(&"cpfg") {
                if let Some(l) = words.iter().find(|w| w.ends_with(".l")) {
                    return dir.join(l);
                }
            }
        }
    }
    let mut ls: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "l"))
        .filter(|p| {
            std::fs::read_to_string(p)
                .unwrap_or_default()
                .to_ascii_lowercase()
                .contains("lsystem:")
        })
        .collect();
    ls.sort();
    ls.remove(0)
}

/// graftal's PNG of the object in `dir` at `width`×`height`.
fn draw(dir: &Path, width: u32, height: u32, steps: Option<u64>) -> Result<Vec<u8>, String> {
    let file = SourceFile::read(&l_file(dir)).map_err(|e| e.to_string())?;
    let c = driver::compile(file);
    let sys = c.system.ok_or_else(|| {
        let first = c
            .diagnostics
            .iter()
            .find(|d| d.code.severity() == graftal::diagnostics::Severity::Error);
        format!("{REFUSED}: {:?}", first.map(|d| (d.code.0, &d.message)))
    })?;
    let opts = RunOptions {
        steps,
        ..RunOptions::default()
    };
    let (_, g) = driver::geometry(&sys, &opts).map_err(|d| d.message)?;
    let ropts = RenderOptions {
        width,
        height,
        ..RenderOptions::default()
    };
    driver::render_bytes(&sys, &g, Format::Png, ropts).map_err(|e| format!("{e:?}"))
}

/// One object's figures against its thumbnail.
struct Figures {
    name: String,
    overlap: f64,
    /// Whether the thumbnail is a crop, held against the window of
    /// graftal's picture that fits it best ([`fitted_crop`]).
    cropped: bool,
    colour: f64,
    background: f64,
}

impl Figures {
    fn passes(&self) -> bool {
        self.overlap >= MIN_OVERLAP
            && self.colour <= MAX_COLOUR_DISTANCE
            && self.background <= MAX_BACKGROUND_DISTANCE
    }
}

impl std::fmt::Display for Figures {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let how = if self.cropped { "crop" } else { "" };
        write!(
            f,
            "{:<44} overlap {:4.2}{how:>5} (min {MIN_OVERLAP}) colour {:5.1} (max {MAX_COLOUR_DISTANCE}) \
             background {:5.1} (max {MAX_BACKGROUND_DISTANCE})",
            self.name, self.overlap, self.colour, self.background
        )
    }
}

fn compare(dir: &Path, report: bool) -> Result<Figures, String> {
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    let frame = FRAMES.iter().find(|(n, ..)| *n == name).map(|(_, k, _)| *k);
    compare_at(dir, report, frame)
}

/// The figures of the object in `dir` drawn at `steps` (the file's own
/// when `None`).
fn compare_at(dir: &Path, report: bool, steps: Option<u64>) -> Result<Figures, String> {
    let icon = Picture::decode(&std::fs::read(dir.join("icon.png")).unwrap());
    let bg_icon = icon.background();
    let fg_icon = icon.foreground(bg_icon);
    let cropped = icon.cropped(&fg_icon);
    let (ours, overlap) = if cropped {
        fitted_crop(dir, &icon, &fg_icon, steps)?
    } else {
        let ours = Picture::decode(&draw(dir, icon.width as u32, icon.height as u32, steps)?);
        let fg_ours = ours.foreground(ours.background());
        let o = overlap(&silhouette(&icon, &fg_icon), &silhouette(&ours, &fg_ours));
        (ours, o)
    };
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    if report {
        let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/icons");
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(out.join(format!("{name}.png")), ours.encode()).unwrap();
        std::fs::copy(dir.join("icon.png"), out.join(format!("{name}.icon.png"))).unwrap();
    }
    let bg_ours = ours.background();
    let fg_ours = ours.foreground(bg_ours);
    Ok(Figures {
        name,
        overlap,
        cropped,
        colour: mean_distance(
            mean_colour(&icon, &fg_icon, bg_icon),
            mean_colour(&ours, &fg_ours, bg_ours),
        ),
        background: distance(bg_icon, bg_ours),
    })
}

/// How many times the thumbnail's size graftal's picture is drawn to look
/// for the window a cropped thumbnail shows.
const SEARCH: usize = 3;
/// The zooms tried (the window's side is the picture's over the zoom) and,
/// for each, the positions across and down.
const ZOOMS: [f64; 8] = [1.0, 1.2, 1.4, 1.65, 1.95, 2.3, 2.65, 3.0];
const POSITIONS: usize = 9;

/// A square-cornered window of a picture: its corner and side as shares of
/// the picture's width and height.
#[derive(Clone, Copy)]
struct Window {
    x0: f64,
    y0: f64,
    side: f64,
}

/// A thumbnail that is a crop of cpfg's window (zoomed by hand, or a
/// window smaller than the object) shows a window of the picture the files
/// give, which no file says. Registration finds it: graftal's picture is
/// drawn `SEARCH` times larger, and of the windows of `ZOOMS` and
/// `POSITIONS` the one whose foreground, cell for cell (positions kept,
/// unlike [`silhouette`]'s fit), overlaps the thumbnail's most is drawn
/// again at its own scale (lines keep their widths in pixels, as in a
/// zoomed cpfg window). That picture and its overlap are returned; the
/// overlap must still reach `MIN_OVERLAP`.
fn fitted_crop(
    dir: &Path,
    icon: &Picture,
    fg_icon: &[bool],
    steps: Option<u64>,
) -> Result<(Picture, f64), String> {
    let (w, h) = (icon.width, icon.height);
    let big = Picture::decode(&draw(dir, (w * SEARCH) as u32, (h * SEARCH) as u32, steps)?);
    let target = cells(icon, fg_icon);
    let (_, window) = best_window(&big, &target, w, h);
    let scale = 1.0 / window.side;
    let (bw, bh) = (
        (w as f64 * scale).round() as u32,
        (h as f64 * scale).round() as u32,
    );
    let zoomed = Picture::decode(&draw(dir, bw, bh, steps)?);
    let ours = zoomed.window(
        Window {
            x0: window.x0,
            y0: window.y0,
            side: w as f64 / f64::from(bw),
        },
        w,
        h,
    );
    let o = overlap(&target, &cells(&ours, &ours.foreground(ours.background())));
    Ok((ours, o))
}

/// Of the windows of `ZOOMS` and `POSITIONS` in `big`, seen at
/// `width`×`height`, the one whose foreground cells overlap `target` most,
/// with that overlap.
fn best_window(big: &Picture, target: &[bool], width: usize, height: usize) -> (f64, Window) {
    let mut best = (
        f64::NEG_INFINITY,
        Window {
            x0: 0.0,
            y0: 0.0,
            side: 1.0,
        },
    );
    for zoom in ZOOMS {
        let side = 1.0 / zoom;
        let steps = if zoom == 1.0 { 1 } else { POSITIONS };
        for i in 0..steps {
            for j in 0..steps {
                let at = |k: usize| (1.0 - side) * k as f64 / (steps - 1).max(1) as f64;
                let window = Window {
                    x0: at(i),
                    y0: at(j),
                    side,
                };
                let seen = big.window(window, width, height);
                let o = overlap(target, &cells(&seen, &seen.foreground(seen.background())));
                if o > best.0 {
                    best = (o, window);
                }
            }
        }
    }
    best
}

/// The foreground in a `GRID`×`GRID` grid of the whole picture (a cell is
/// foreground when any of its pixels is), dilated.
fn cells(p: &Picture, fg: &[bool]) -> Vec<bool> {
    let mut grid = vec![false; GRID * GRID];
    for y in 0..p.height {
        for x in 0..p.width {
            if fg[y * p.width + x] {
                grid[y * GRID / p.height * GRID + x * GRID / p.width] = true;
            }
        }
    }
    dilate(&grid)
}

/// Thumbnails that are a frame of the object's animation other than the
/// file's derivation length: the steps graftal draws, and the evidence.
const FRAMES: &[(&str, u64, &str)] = &[
    (
        "07-Open-01-ulam-collide",
        16,
        "fractal.a animates frames 1 to 16 where the file says `derivation length: 1` (a red \
         cross): the thumbnail's pattern of crosses is the last frame's",
    ),
    (
        "04-Signaling-06-florigen+auxin",
        40,
        "the thumbnail shows auxin half way down the stem, about step 40 of the 50 the \
         animation runs",
    ),
    (
        "04-Signaling-08-basipetal-2-signals",
        44,
        "the thumbnail is step 44 of the 50 the animation runs",
    ),
    ("07-Open-13-clover", 200, CLOVER_FRAME),
    ("20-EnviroPgms-CPFG-Clover", 200, CLOVER_FRAME),
];

/// Why the clover objects are drawn at 200 steps.
const CLOVER_FRAME: &str =
    "plant.a animates frames 0 to 200 where the file derives one step (`derivation \
     length: STEPS`, one year): the thumbnail's ramets and leaves spread over the ground are a \
     late frame's";

/// Thumbnails that show what the object's files do not say, each with the
/// reason and its evidence. They are still drawn (an error fails the
/// test), and each must still miss the thresholds: one that starts to pass
/// leaves this list. Every other object must pass.
const NOT_COMPARABLE: &[(&str, &str)] = &[
    (
        "07-Open-03-sierpinski-collide",
        "the thumbnail is cpfg's window zoomed on the apex, the sides leaving it at about a \
         third of the triangle's height; the registration of crops finds the whole triangle \
         instead (overlap 0.74: thin lines on black fit at many zooms), whose green lower \
         branches the thumbnail leaves out (colour 106). The apex, its colours (red, orange, \
         yellow down the sides) and the grey zigzags where honda81 blocked tips are the \
         thumbnail's; at 14 to 18 steps, before the green, every measure passes",
    ),
    (
        "04-Signaling-08-basipetal-2-signals",
        "the thumbnail is step 44 of the animation (drawn so, FRAMES) zoomed on the top: the \
         stem runs off its bottom edge alone, so the silhouette is fitted as a whole picture's \
         against graftal's whole plant",
    ),
    (
        "11-CPFG-Tropisms",
        "the thumbnail's axis bends, and the file sets every tropism's strength to 0 \
         (`#define` values that `specifications` takes from panel.l, which the object lacks): \
         with the file's values nothing bends, in cpfg as in graftal, and the fitted crop of \
         graftal's straight axis overlaps the bent one 0.41",
    ),
    (
        "11-CPFG-Snowflake",
        "the thumbnail shows edits made with the mouse (X inserted)",
    ),
    (
        "04-Signaling-21-insect-schematic",
        "the thumbnail is a frame of the animation, the insect (two balls) on its way",
    ),
    (
        "10-GettingStarted-01-Lychnis",
        "the thumbnail is zoomed by hand on three flowers",
    ),
    (
        "11-CPFG-DragonCurve",
        "the thumbnail is the left-right mirror of what the file's rules draw under cpfg's frame \
         (IoU 0.76 mirrored, 0.31 as is, at the file's 8 steps): cpfg's source starts the turtle \
         with H = +y, L = -x and turns H towards L on `+` (interpret.c, InitializeTurtle and \
         change_dir), and its default view puts +x right and +y up (control.c, SetView), which \
         is what graftal draws; quadratic-Koch's thumbnail, as asymmetric, agrees with graftal \
         as is (IoU 0.79, 0.26 mirrored). The rules were changed after the thumbnail \
         (description: updated 2020-11-08)",
    ),
    (
        "11-CPFG-Sedge",
        "the thumbnail is framed by hand on the top of the plant: the rules branch at two nodes \
         (`A(a,t)` with t == 10, at a = 10 and 21), each with a leaf and a female spike, and the \
         thumbnail shows one leaf and one spike rising from its bottom edge, which cuts the stem \
         below them; its male spike is brown from `sedge.map2`, which `specifications` names \
         and the object lacks (W0806)",
    ),
    (
        "06-Enviro-sensitive-query-position",
        "the thumbnail was drawn with other `#define` values, which `specifications` sets through \
         `panel panel.l | awkped plant.l` and the object lacks panel.l: its side branches droop \
         (about 37°, 21°, 4°, then below horizontal), which the file's `TROPISM 0` cannot do \
         (`@Ts(1,0)`), its ellipse is 1.72:1 where a = 5, b = 10 give 2:1, and its stem has 16 \
         internodes where the file gives 20; its spheres and rings keep the file's ratio (9.0 : \
         3.3 px = 2.7, `@O(0.8)` : `@c(0.3)` = 2.67). With a 3, b 5, l 0.7, TROPISM -0.3 graftal's \
         picture reaches overlap 0.96 and colour 52",
    ),
    (
        "06-Enviro-sensitive-ellipse",
        "the thumbnail is a smooth downscale of a larger grab of cpfg's window (vlab's snapicon \
         scales with Qt's SmoothTransformation): it has 1793 colours where 1:1 grabs of pixel \
         lines have a handful, and the file's 3-pixel lines cover 0.69 to 0.72 pixel across, a \
         scale of about 0.24; no file of the object gives the window's size",
    ),
    (
        "05-Quantitative-info-flow-03-Borcher-Honda",
        "the thumbnail is a smooth downscale of cpfg's window: its labels (`@L` in colour 5, \
         255,255,0 in tree.map, in the view's 10-pixel font) are 4 to 5 pixels tall and half \
         as bright (117 to 137, 117 to 137, 0), among 403 colours; cpfg writes labels in \
         pixels, unscaled, as graftal does (8-pixel glyphs in the full colour), and at the \
         thumbnail's size those cover the plant; no file of the object gives the window's size",
    ),
];

/// What `draw` says of an object graftal refuses.
const REFUSED: &str = "not read";

#[test]
fn every_object_looks_like_cpfgs_thumbnail() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cpfg");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&corpus)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|d| d.join("icon.png").exists())
        .collect();
    dirs.sort();
    assert_eq!(dirs.len(), 48, "the corpus has 48 thumbnails");
    let report = std::env::var_os("GRAFTAL_ICONS").is_some();
    let mut failures = Vec::new();
    let mut passed = 0;
    // Open L-systems (a `.e` file names their environment program): how
    // many there are, and how many pass.
    let (mut open, mut open_passed) = (0, 0);
    for dir in &dirs {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let exempt = NOT_COMPARABLE.iter().find(|(n, _)| *n == name);
        let f = match (compare(dir, report), exempt) {
            (Ok(f), _) => f,
            // Refused with its error: a gap that must be listed.
            (Err(e), Some((_, why))) if e.contains(REFUSED) => {
                if report {
                    println!("{name:<44} {e}: {why}");
                }
                continue;
            }
            (Err(e), _) => {
                failures.push(format!("{}: {e}", dir.display()));
                continue;
            }
        };
        if report {
            let mark = match (f.passes(), exempt) {
                (true, _) => "",
                (false, None) => "FAIL",
                (false, Some((_, why))) => why,
            };
            println!("{f} {mark}");
        }
        passed += usize::from(f.passes());
        if has_environment(dir) {
            open += 1;
            open_passed += usize::from(f.passes());
        }
        match (f.passes(), exempt) {
            (false, None) => failures.push(f.to_string()),
            (true, Some((_, why))) => failures.push(format!(
                "{f}: passes now; take it out of NOT_COMPARABLE (it was: {why})"
            )),
            _ => {}
        }
    }
    let comparable = dirs.len() - NOT_COMPARABLE.len();
    if report {
        println!(
            "{passed} of {} pass; {passed} of the {comparable} comparable ({:.0}%); \
             {open_passed} of the {open} open L-systems",
            dirs.len(),
            100.0 * passed as f64 / comparable as f64
        );
    }
    if report {
        pairs_sheet(&Path::new(env!("CARGO_MANIFEST_DIR")).join("target/icons"));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The goal of issue 34: at least 85% of the comparable objects alike.
    assert!(passed * 100 >= comparable * 85, "{passed} of {comparable}");
    // Issue 36's: at least 80% of the open L-systems alike, their
    // environment programs answering.
    assert_eq!(open, 8, "the corpus has 8 open L-systems with thumbnails");
    assert!(open_passed * 100 >= open * 80, "{open_passed} of {open}");
}

/// Whether the object in `dir` is an open L-system (it has a `.e` file).
fn has_environment(dir: &Path) -> bool {
    std::fs::read_dir(dir)
        .unwrap()
        .any(|e| e.unwrap().path().extension().is_some_and(|x| x == "e"))
}

/// The objects of the README's side-by-side sheet (docs/cpfg-pairs.png).
const SHEET: &[&str] = &[
    "02-Mod-vis-3D-05-monopodial",
    "11-CPFG-Horneophyton",
    "15-VlabTools-LeafPosition",
    "11-CPFG-Ridley",
    "15-VlabTools-LilyLeaf",
    "07-Open-13-clover",
    "04-Signaling-10-mycelis-realistic",
    "11-CPFG-BackgroundScene",
    "07-Open-05-phyllotaxis-Vogel",
];

/// With `GRAFTAL_ICONS`, the README's sheet: for each object of [`SHEET`]
/// its name, cpfg's thumbnail (left) and graftal's picture side by side, three
/// objects a row, written to `dir/pairs.png` (copied to docs/ on purpose).
fn pairs_sheet(dir: &Path) {
    use graftal::render::text::{self, Placed};
    const CELL: u32 = 140;
    const GAP: u32 = 10;
    const TITLE: u32 = 14;
    let (cols, rows) = (3u32, SHEET.len().div_ceil(3) as u32);
    let col_w = 2 * CELL + GAP;
    let (w, h) = (
        cols * col_w + (cols - 1) * 2 * GAP,
        rows * (TITLE + CELL + GAP),
    );
    let mut rgba = vec![255u8; (w * h * 4) as usize];
    for (k, name) in SHEET.iter().enumerate() {
        let (x0, y0) = (
            (k as u32 % cols) * (col_w + 2 * GAP),
            (k as u32 / cols) * (TITLE + CELL + GAP),
        );
        let title = Placed {
            at: [f64::from(x0), f64::from(y0 + TITLE - 4)],
            text: name.to_string(),
            colour: graftal::ir::Rgb(0, 0, 0),
        };
        text::write(&mut rgba, w, 0, &title);
        for (j, file) in [format!("{name}.icon.png"), format!("{name}.png")]
            .iter()
            .enumerate()
        {
            let Ok(bytes) = std::fs::read(dir.join(file)) else {
                continue;
            };
            let pic = Picture::decode(&bytes);
            let left = x0 + j as u32 * (CELL + GAP);
            for y in 0..pic.height.min(CELL as usize) {
                for x in 0..pic.width.min(CELL as usize) {
                    let at = (((y0 + TITLE) as usize + y) * w as usize + left as usize + x) * 4;
                    let [r, g, b] = pic.at(x, y);
                    rgba[at..at + 4].copy_from_slice(&[r, g, b, 255]);
                }
            }
        }
    }
    let size = tiny_skia::IntSize::from_wh(w, h).unwrap();
    let pixmap = tiny_skia::Pixmap::from_vec(rgba, size).unwrap();
    pixmap.save_png(dir.join("pairs.png")).unwrap();
}

/// The measures themselves: a picture matches itself, and a picture
/// against a different shape on another background does not.
#[test]
fn the_measures_tell_pictures_apart() {
    let square = |bg: [u8; 3], fg: [u8; 3], x0: usize, x1: usize| Picture {
        width: 20,
        height: 20,
        pixels: (0..400)
            .map(|i| {
                let (x, y) = (i % 20, i / 20);
                if (x0..x1).contains(&x) && (5..15).contains(&y) {
                    fg
                } else {
                    bg
                }
            })
            .collect(),
    };
    let a = square([0, 0, 0], [255, 255, 0], 5, 15);
    let b = square([255, 255, 255], [0, 0, 255], 2, 4);
    let (fa, fb) = (a.foreground(a.background()), b.foreground(b.background()));
    assert_eq!(overlap(&silhouette(&a, &fa), &silhouette(&a, &fa)), 1.0);
    assert!(overlap(&silhouette(&a, &fa), &silhouette(&b, &fb)) < MIN_OVERLAP);
    let (ca, cb) = (
        mean_colour(&a, &fa, a.background()),
        mean_colour(&b, &fb, b.background()),
    );
    assert_eq!(ca, [255.0, 255.0, 0.0]);
    assert!(mean_distance(ca, cb) > MAX_COLOUR_DISTANCE);
    assert!(distance(a.background(), b.background()) > MAX_BACKGROUND_DISTANCE);
}

/// Registration finds the window a crop shows, and finds none in a
/// picture that does not hold it.
#[test]
fn a_crop_is_found_where_it_is_and_nowhere_else() {
    // A black picture with a yellow ring and a red bar.
    let big = Picture {
        width: 120,
        height: 120,
        pixels: (0..120 * 120)
            .map(|i| {
                let (x, y) = ((i % 120) as f64, (i / 120) as f64);
                let r = ((x - 40.0).powi(2) + (y - 40.0).powi(2)).sqrt();
                match () {
                    _ if (14.0..20.0).contains(&r) => [255, 255, 0],
                    _ if (80.0..86.0).contains(&x) && (60.0..110.0).contains(&y) => [255, 0, 0],
                    _ => [0, 0, 0],
                }
            })
            .collect(),
    };
    // The thumbnail: a window around the ring, zoomed 2.3 times (one of
    // the windows tried: registration is as fine as ZOOMS and POSITIONS).
    let side = 1.0 / 2.3;
    let corner = (1.0 - side) * 2.0 / (POSITIONS - 1) as f64;
    let shown = Window {
        x0: corner,
        y0: corner,
        side,
    };
    let crop = big.window(shown, 40, 40);
    let target = cells(&crop, &crop.foreground(crop.background()));
    let (o, found) = best_window(&big, &target, 40, 40);
    assert_eq!(o, 1.0);
    assert_eq!(
        (found.x0, found.y0, found.side),
        (shown.x0, shown.y0, shown.side)
    );
    // A picture of the bar alone holds no such window.
    let bar_only = Picture {
        pixels: big
            .pixels
            .iter()
            .map(|&p| if p == [255, 255, 0] { [0, 0, 0] } else { p })
            .collect(),
        ..big
    };
    let (o, _) = best_window(&bar_only, &target, 40, 40);
    assert!(o < MIN_OVERLAP, "{o}");
}
