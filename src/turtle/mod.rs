//! Turtle interpretation: a derived word -> [`Geometry`] (segments and
//! filled polygons in 3D turtle units).
//!
//! The turtle starts at the origin with step length 1, heading H = +y, left
//! L = −x and up U = H × L = +z, so a 2D system drawn in 3D lies in the
//! xy-plane and looks, from the default view (down −z), as in the papers.
//! Rotations are the book's matrices (see [`crate::ir::TurtleOp`]).
//!
//! `|` turns by exactly 180°. The Appendix A listing, which keeps the heading
//! as an integer multiple of δ, turns by `angle factor / 2` steps instead, so
//! for an odd angle factor its `|` falls short of a half turn; graftal
//! follows the book's definition (§2.3: `R_U(180°)`), which the listing
//! meets for every even angle factor.
//!
//! One entry point, [`run`]: a [`Run`] (the system, the word, the seed and
//! what to record) interpreted into a [`Sink`], returning what the run
//! learned ([`Learned`]). The rooms: [`geometry`](self) holds what the
//! turtle draws and where it goes, `state` the turtle's frame and its
//! matrices, `interpret` what each symbol does, and `run` the entry point.

mod cost;
mod gencyl;
mod geometry;
pub mod instanced;
mod interpret;
mod label;
pub mod pieces;
mod run;
mod state;
mod tropism;

pub use cost::drawn_cost;
pub(crate) use geometry::index_of;
pub use geometry::{
    grow_box, join_boxes, Disc, Drawn, Geometry, Label, Origins, Parts, Polygon, Segment, Sink,
    Textured, TurtlePath,
};
pub use label::printf;
pub use pieces::{Letters, Pieced, Pieces};
pub use run::{run, Learned, Run, WordSymbols};
pub(crate) use state::{cross, dot};

pub type Vec3 = [f64; 3];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::pfg::read_ok;
    use crate::ir::{QueryKind, Rgb, SymbolId, TurtleOp, Word};

    fn draw(src: &str) -> Geometry {
        let sys = read_ok(src);
        Run::word(&sys, &sys.axiom, 0).geometry()
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-9)
    }

    /// Records the kinds given to it, in order.
    #[derive(Default)]
    struct Kinds(Vec<Drawn>);

    impl Sink for Kinds {
        fn segment(&mut self, _: Segment) {
            self.0.push(Drawn::Segment);
        }
        fn polygon(&mut self, _: Polygon) {
            self.0.push(Drawn::Polygon);
        }
        fn disc(&mut self, _: Disc) {
            self.0.push(Drawn::Disc);
        }
    }

    #[test]
    fn a_stored_drawing_replays_in_the_order_it_was_drawn() {
        let square = || Polygon {
            points: vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
            colour: Rgb(0, 0, 0),
            index: 0,
            surface: false,
            texture: None,
        };
        let line = || Segment {
            a: [0.0; 3],
            b: [0.0, 1.0, 0.0],
            width: 1.0,
            colour: Rgb(0, 0, 0),
            index: 0,
            depth: 0,
        };
        let mut g = Geometry::default();
        g.segment(line());
        g.polygon(square());
        g.polygon(square());
        g.segment(line());
        // Added without a note of its order: after the rest.
        g.polygons.push(square());
        let mut kinds = Kinds::default();
        g.replay(&mut kinds);
        use Drawn::{Polygon as P, Segment as S};
        assert_eq!(kinds.0, [S, P, P, S, P]);
        assert_eq!(g.order, [(S, 1), (P, 2), (S, 1)]);
    }

    #[test]
    fn starts_at_origin_facing_up_and_plus_turns_right() {
        let g = draw("angle factor: 4\naxiom: F+F-F\n");
        assert!(close(g.segments[0].a, [0.0, 0.0, 0.0]));
        assert!(close(g.segments[0].b, [0.0, 1.0, 0.0]));
        assert!(
            close(g.segments[1].b, [1.0, 1.0, 0.0]),
            "{:?}",
            g.segments[1]
        );
        assert!(close(g.segments[2].b, [1.0, 2.0, 0.0]));
    }

    #[test]
    fn three_d_symbols_follow_the_book_matrices() {
        // & pitches: H' = H cos + U sin, so with δ=90° the heading becomes +z.
        let g = draw("angle factor: 4\naxiom: &F\n");
        assert!(close(g.segments[0].b, [0.0, 0.0, 1.0]));
        // \ rolls: then + (about the new U) turns right in the rolled plane.
        let g = draw("angle factor: 4\naxiom: \\+F\n");
        // Rolling by 90° makes L = +z, so a right turn heads to −L = −z.
        assert!(
            close(g.segments[0].b, [0.0, 0.0, -1.0]),
            "{:?}",
            g.segments[0]
        );
        // | turns around.
        let g = draw("angle factor: 4\naxiom: |F\n");
        assert!(close(g.segments[0].b, [0.0, -1.0, 0.0]));
    }

    #[test]
    fn branches_restore_state_and_count_depth() {
        let g = draw("angle factor: 4\naxiom: F[+F[-F]]F\n");
        assert_eq!(g.max_depth, 2);
        assert!(close(g.segments[3].a, [0.0, 1.0, 0.0]));
        assert!(close(g.segments[3].b, [0.0, 2.0, 0.0]));
    }

    #[test]
    fn polygons_collect_vertices_instead_of_lines() {
        let g = draw("angle factor: 4\naxiom: {f+f+f+f}F\n");
        assert_eq!(g.polygons.len(), 1);
        assert_eq!(g.polygons[0].points.len(), 5);
        assert_eq!(g.segments.len(), 1);
    }

    #[test]
    fn paths_follow_every_move_per_branch() {
        let sys = read_ok("angle factor: 4\naxiom: f+f[-fF]f\n");
        let g = Run {
            paths: true,
            ..Run::word(&sys, &sys.axiom, 0)
        }
        .geometry();
        assert_eq!(g.paths.len(), 2);
        // The main axis: origin, two moves, then (after the branch) one more.
        assert_eq!(g.paths[0].points.len(), 4);
        assert!(close(g.paths[0].points[3], [2.0, 1.0, 0.0]));
        // The branch starts where it was pushed.
        assert!(close(g.paths[1].points[0], [1.0, 1.0, 0.0]));
        assert!(close(g.paths[1].points[2], [1.0, 3.0, 0.0]));
        // Without the option nothing is recorded.
        assert!(Run::word(&sys, &sys.axiom, 0).geometry().paths.is_empty());
    }

    #[test]
    fn a_run_learns_its_depth_and_what_it_was_asked_to_record() {
        let mut sys = read_ok("angle factor: 4\naxiom: F\n");
        let q = sys.intern("q");
        sys.set_interpretation(q, TurtleOp::Query(QueryKind::Position));
        let word: Vec<SymbolId> = "F[Fq]q"
            .chars()
            .map(|c| sys.symbols.get(&c.to_string()).unwrap())
            .collect();
        let word = Word::from(word);
        let everything = Run {
            paths: true,
            origins: true,
            queries: true,
            ..Run::word(&sys, &word, 0)
        };
        let learned = run(everything, &mut Geometry::default());
        assert_eq!(learned.max_depth, 1);
        assert_eq!(learned.paths.len(), 2);
        assert_eq!(learned.origins.segments, [0, 2]);
        assert_eq!(learned.answers.len(), 2);
        assert_eq!(learned.answers[0].0, 3);
        assert!(close(learned.answers[0].1, [0.0, 2.0, 0.0]));
        assert_eq!(learned.answers[1].0, 5);
        assert!(close(learned.answers[1].1, [0.0, 1.0, 0.0]));
        // Asked for nothing, it learns the depth only.
        let plain = run(Run::word(&sys, &word, 0), &mut Geometry::default());
        assert_eq!(
            plain,
            Learned {
                max_depth: 1,
                ..Learned::default()
            }
        );
    }

    #[test]
    fn branching_does_not_copy_the_colour_history() {
        // 2^16 colour changes before 2^16 branches: a push must not copy them.
        let sys = read_ok("axiom: 'X\n' --> ''\nX --> X[F]X\n");
        let word = crate::eval::derive(&sys, &crate::eval::DeriveOptions::new(16)).unwrap();
        let t = std::time::Instant::now();
        let g = Run::word(&sys, &word, 0).geometry();
        assert_eq!(g.segments.len(), (1 << 16) - 1);
        assert!(t.elapsed().as_secs_f64() < 1.0, "{:?}", t.elapsed());
    }

    #[test]
    fn previous_colour_goes_back_through_the_history_per_branch() {
        let mut sys = read_ok("axiom: F\n");
        let next = sys.intern("n");
        let prev = sys.intern("p");
        sys.set_interpretation(next, TurtleOp::NextColour);
        sys.set_interpretation(prev, TurtleOp::PreviousColour);
        sys.colours = vec![Rgb(1, 1, 1), Rgb(2, 2, 2), Rgb(3, 3, 3)];
        let word: Vec<SymbolId> = "FnFnF[pF]FpFpFpF"
            .chars()
            .map(|c| sys.symbols.get(&c.to_string()).unwrap())
            .collect();
        let g = Run::word(&sys, &Word::from(word), 0).geometry();
        let colours: Vec<u8> = g.segments.iter().map(|s| s.colour.0).collect();
        assert_eq!(colours, [1, 2, 3, 2, 3, 2, 1, 1]);
    }

    /// The frame after `n` rotations by an irrational (torsion, curvature)
    /// pair, read off three unit segments drawn along t, n and −b.
    fn frame_after_rotations(n: usize) -> [Vec3; 3] {
        let mut sys = crate::front::linf::read_ok(
            "lines f\nangles w = (0.7311, 1.1234) q = (0, pi/2) p = (pi/2, pi/2)\nrules x = +w f+q+p",
        );
        let [f, w, q, p] = ["f", "+w", "+q", "+p"].map(|s| sys.symbols.get(s).unwrap());
        sys.axiom = Word::from([vec![w; n], vec![f, q, f, p, f]].concat());
        let g = Run::word(&sys, &sys.axiom, 0).geometry();
        let d = |k: usize| {
            let s: &Segment = &g.segments[k];
            [s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]]
        };
        [d(0), d(1), d(2)]
    }

    #[test]
    fn frames_stay_orthonormal_over_millions_of_rotations() {
        let dot = |a: Vec3, b: Vec3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: Vec3, b: Vec3| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let [t, n, minus_b] = frame_after_rotations(5_000_000);
        let mut worst: f64 = 0.0;
        for v in [t, n, minus_b] {
            worst = worst.max((dot(v, v) - 1.0).abs());
        }
        for (a, b) in [(t, n), (n, minus_b), (t, minus_b)] {
            worst = worst.max(dot(a, b).abs());
        }
        // b = t × n, and the third segment runs along −b.
        let b = cross(t, n);
        for k in 0..3 {
            worst = worst.max((b[k] + minus_b[k]).abs());
        }
        assert!(worst < 1e-13, "orthonormality error {worst:e}");
    }

    #[test]
    fn width_and_colour_change() {
        let g = draw("axiom: F!'F\n");
        assert!(g.segments[1].width < g.segments[0].width);
        assert_ne!(g.segments[1].colour, g.segments[0].colour);
    }
}
