//! An environment that answers a model's queries about the world (cpfg's
//! `?E` modules; Měch & Prusinkiewicz's open L-systems): which program
//! answers and with what settings, what each query tells it of the turtle,
//! and when it is asked. The programs are graftal's own (`crate::enviro`),
//! run in the derivation rather than as a process beside it.

use super::texture::Image;
use serde::Serialize;

/// The environment of an open L-system.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Environment {
    pub program: Program,
    /// How the turtle's position is written to the program (a printf format
    /// such as cpfg's `P:%.4f %.4f %.0f`): the program reads back what the
    /// format printed, so its precision is the program's. `None`: the
    /// position is not sent.
    pub position: Option<String>,
    /// Whether the environment is asked after each step (and of the axiom)
    /// rather than at the start of each step, before rewriting (cpfg's
    /// `environment display: on`); the first leaves the last word answered.
    pub after_each_step: bool,
    /// Whether the queries in a branch cut by `%` are still sent (cpfg's
    /// `interpretation past %`, on by default).
    pub past_cut: bool,
}

/// Which program answers, with its settings (its specification file).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Program {
    /// Collision by vigor (vlab's `honda81`, after Honda 1981): a query is
    /// answered 0 when another of its group, at least as vigorous, lies
    /// within `radius`; else 1.
    Density(Density),
    /// Light through spherical leaf clusters in a voxel grid, from sources
    /// or a sky of samples (vlab's `chiba`).
    Light(Light),
    /// Light from an image over a plane, shaded by the leaves the queries
    /// lay on it (vlab's `clover`).
    Canopy(Canopy),
    /// Circles that dominate smaller circles they touch (vlab's
    /// `ecosystem`).
    Circles(Circles),
    /// Steps of the turtle checked against line obstacles in the plane
    /// (vlab's `obcheck`).
    Obstacles(Obstacles),
}

/// `honda81`'s `density.spec`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Density {
    pub radius: f64,
    /// Distances in 3D; else in the plane of the turtle's x and z.
    pub three_d: bool,
}

/// A light source: its direction (towards the light) and intensity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LightSource {
    pub direction: [f64; 3],
    pub intensity: f64,
}

/// `chiba`'s `light.spec`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Light {
    pub grid: [u32; 3],
    /// The light a cluster lets through (0: opaque).
    pub transmittance: f64,
    /// The sky's light from below to its light from above.
    pub lower_to_upper: f64,
    /// Samples of the sky when no source is given.
    pub samples: u32,
    /// A cluster's radius when its query gives none.
    pub radius: f64,
    pub beam_radius: f64,
    /// Sources as given (directions not yet normalized); empty: the sky.
    pub sources: Vec<LightSource>,
    /// Shadows by the area of overlapping discs rather than by chords.
    pub estimate_area: bool,
    /// The sky's samples weighted by the CIE overcast sky.
    pub cie: bool,
}

/// `clover`'s `enviro.spec` and its image.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Canopy {
    pub grid: [u32; 2],
    /// The world's lower-left corner and extent covered by the grid.
    pub position: [f64; 2],
    pub range: [f64; 2],
    /// The light one leaf lets through.
    pub transmittance: f64,
    /// The image's file, as the specification names it.
    pub image_file: Option<String>,
    /// The light (green) and ratio (red) over the plane; `None`: full
    /// light everywhere.
    #[serde(skip)]
    pub image: Option<Image>,
    /// Leaves laid in earlier steps are forgotten each step.
    pub remove_old_leaves: bool,
    /// The plane is the turtle's x and y (else x and z).
    pub z_is_up: bool,
}

/// `ecosystem`'s `density.spec`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Circles {
    pub three_d: bool,
    /// The second parameter is a vigor that decides between circles of
    /// one size (else it names the query's group).
    pub vigor: bool,
}

/// `obcheck`'s `obstacles.dat`: line segments `[xa, ya, xb, yb]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Obstacles {
    pub segments: Vec<[f64; 4]>,
}
