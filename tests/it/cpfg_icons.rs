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
    let mut dilated = grid.clone();
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
fn draw(dir: &Path, width: u32, height: u32) -> Result<Vec<u8>, String> {
    let file = SourceFile::read(&l_file(dir)).map_err(|e| e.to_string())?;
    let c = driver::compile(file);
    let sys = c.system.ok_or_else(|| {
        let first = c
            .diagnostics
            .iter()
            .find(|d| d.code.severity() == graftal::diagnostics::Severity::Error);
        format!("{REFUSED}: {:?}", first.map(|d| (d.code.0, &d.message)))
    })?;
    let opts = RunOptions::default();
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
    /// `None` when the thumbnail is a crop.
    overlap: Option<f64>,
    colour: f64,
    background: f64,
}

impl Figures {
    fn passes(&self) -> bool {
        self.overlap.is_none_or(|o| o >= MIN_OVERLAP)
            && self.colour <= MAX_COLOUR_DISTANCE
            && self.background <= MAX_BACKGROUND_DISTANCE
    }
}

impl std::fmt::Display for Figures {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let overlap = self
            .overlap
            .map_or("cropped".to_string(), |o| format!("{o:.2}"));
        write!(
            f,
            "{:<44} overlap {overlap:>7} (min {MIN_OVERLAP}) colour {:5.1} (max {MAX_COLOUR_DISTANCE}) \
             background {:5.1} (max {MAX_BACKGROUND_DISTANCE})",
            self.name, self.colour, self.background
        )
    }
}

fn compare(dir: &Path, report: bool) -> Result<Figures, String> {
    let icon = Picture::decode(&std::fs::read(dir.join("icon.png")).unwrap());
    let bytes = draw(dir, icon.width as u32, icon.height as u32)?;
    let ours = Picture::decode(&bytes);
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    if report {
        let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/icons");
        std::fs::create_dir_all(&out).unwrap();
        std::fs::write(out.join(format!("{name}.png")), &bytes).unwrap();
        std::fs::copy(dir.join("icon.png"), out.join(format!("{name}.icon.png"))).unwrap();
    }
    let (bg_icon, bg_ours) = (icon.background(), ours.background());
    let (fg_icon, fg_ours) = (icon.foreground(bg_icon), ours.foreground(bg_ours));
    let overlap = (!icon.cropped(&fg_icon))
        .then(|| overlap(&silhouette(&icon, &fg_icon), &silhouette(&ours, &fg_ours)));
    Ok(Figures {
        name,
        overlap,
        colour: mean_distance(
            mean_colour(&icon, &fg_icon, bg_icon),
            mean_colour(&ours, &fg_ours, bg_ours),
        ),
        background: distance(bg_icon, bg_ours),
    })
}

/// Why the two clover objects (one model, two folders) miss.
const CLOVER: &str =
    "the thumbnail's ground is light08.rgb laid as a texture on the BACKGROUND polygon \
         (`@Tx(1)` before `{ … }`): graftal lays textures on surfaces and generalized \
         cylinders but not yet on `{ }` polygons, so the ground is drawn in its colour (a gap \
         of graftal's); and the thumbnail is a late frame of the animation (plant.a: 200 \
         frames) where the file derives 0 steps. With clover built in, graftal's plant at 60 \
         steps spreads its ramets and leaves over the ground";

/// Thumbnails that show what the object's files do not say, each with the
/// reason and its evidence. They are still drawn (an error fails the
/// test), and each must still miss the thresholds: one that starts to pass
/// leaves this list. Every other object must pass.
const NOT_COMPARABLE: &[(&str, &str)] = &[
    (
        "07-Open-01-ulam-collide",
        "the thumbnail is the animation's last frame (fractal.a: 16 frames) where the file says \
         `derivation length: 1` (a red cross), and a crop of it: cpfg's window zoomed on the \
         centre, the diamond's tips outside the frame. At 16 steps, with honda81 answering, \
         graftal draws the same pattern of crosses (red centre, yellow, grey, blue arms)",
    ),
    (
        "07-Open-03-sierpinski-collide",
        "the thumbnail is a crop of cpfg's window zoomed on the top: the apex at its top \
         edge, the sides leaving it at about a third of the triangle's height. graftal's \
         picture, with honda81 answering, has the same apex and colours (red, orange, yellow, \
         green down the sides) and the same grey zigzags where tips were blocked",
    ),
    ("07-Open-13-clover", CLOVER),
    ("20-EnviroPgms-CPFG-Clover", CLOVER),
    (
        "11-CPFG-Snowflake",
        "the thumbnail shows edits made with the mouse (X inserted)",
    ),
    (
        "04-Signaling-08-basipetal-2-signals",
        "the thumbnail is step 44 of the animation (of 50), zoomed on the top",
    ),
    (
        "04-Signaling-06-florigen+auxin",
        "the thumbnail is a frame of the animation: auxin half way down (about step 40 of 50)",
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
            "{passed} of {} pass; {passed} of the {comparable} comparable ({:.0}%)",
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
}

/// The objects of the README's side-by-side sheet (docs/cpfg-pairs.png).
const SHEET: &[&str] = &[
    "02-Mod-vis-3D-05-monopodial",
    "11-CPFG-Horneophyton",
    "15-VlabTools-LeafPosition",
    "11-CPFG-Ridley",
    "15-VlabTools-LilyLeaf",
    "03-inverse-modeling-02-fern-leaf",
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
