//! Diagnostic codes of translation (`graftal translate`): `E06xx` for what
//! the target notation cannot express, and `W06xx`, with the same number,
//! for the same construct approximated under `--lossy`.

use super::Code;

codes! { TRANSLATE;
    TR_CONTEXT = "E0601", "context cannot be expressed in the target",
"LinF and STL rewrite every symbol without looking at its neighbours: a
production with a left or right context (pfg `a < b > c --> d`) has no
equivalent there.

Example:
    graftal translate std:hogeweg-hesper-a --to linf

With `--lossy` the contexts are dropped (W0601): the first production for
each predecessor then applies everywhere, and the picture changes.";

    TR_STOCHASTIC = "E0602", "stochastic choice cannot be expressed in the target",
"A production with several weighted successors (pfg `F --> F[+F]F : 1`
and `F --> F[-F]F : 1`) chooses one at random at each occurrence. LinF's
`p?s` is a different construct (expand or keep), and STL has no chance at
all.

Example:
    graftal translate std:stochastic-bush --to stl

With `--lossy` the most likely successor is always used (W0602).";

    TR_GUARD = "E0603", "per-occurrence probability cannot be expressed in the target",
"LinF's `p?s` expands an occurrence of `s` with probability p at each step
and otherwise keeps it. pfg and STL have no such construct.

Example:
    rules
      i = [.5?j]        <- no pfg or STL equivalent

With `--lossy` the occurrence is always expanded (W0603).";

    TR_INTERVAL = "E0604", "interval angle cannot be expressed in the target",
"A LinF angle `[lo hi]` is drawn at random each time it is applied. pfg
and STL turn by fixed multiples of one angle.

Example:
    angles (0, [0 2*pi])

With `--lossy` the middle of the interval is used (W0604).";

    TR_3D = "E0605", "3D rotation cannot be expressed in the target",
"STL draws in the plane: it turns left and right, nothing else. pfg's
`& ^ \\ /` and LinF torsions rotate out of the plane.

Example:
    angles t = (pi/3, 0)     <- a torsion: 3D

With `--lossy` the rotation is dropped (W0605).";

    TR_ANGLE = "E0606", "angles are not multiples of one increment",
"pfg and STL turn by whole multiples of one angle (360/n degrees for pfg's
`angle factor: n`, `ANGLE` for STL). A translation looks for the largest
such angle that divides every angle of the source exactly; there is none
when, for example, one angle is pi/3 and another 1 radian.

With `--lossy` each angle is rounded to the nearest multiple of a fine
increment (W0606).";

    TR_LENGTH = "E0607", "length factor cannot be expressed in the target",
"pfg and STL draw every step with the same length: LinF's `x@` (multiply
the length by x), a step length other than 1, and STL's per-level stem
lengths do not exist there (STL's `L` is per level, not per symbol).

Example:
    rules
      p = f [+a .55@p]       <- .55@ has no pfg equivalent

With `--lossy` the factor is dropped (W0607): the picture changes.";

    TR_ATTRIBUTE = "E0608", "colour, width or polygon cannot be expressed in the target",
"Each notation draws with its own attributes: pfg has `'` (next colour of
a fixed palette), `!` (thinner lines) and polygons `{ }`; LinF has a
colour list stepped by `{` and `}` and no widths; STL has stem
broadness per level and no colours on stems.

Example:
    graftal translate std:fibonacci-bush --to stl

With `--lossy` the attribute is dropped (W0608): the segments are the
same, drawn with other colours or widths.";

    TR_SWAP = "E0609", "swapping turns cannot be expressed in the target",
"LinF's `!` exchanges the meaning of `+` and `-` for the rest of the
branch. pfg and STL have no such state.

With `--lossy` it is dropped (W0609): the turns after it go the other
way.";

    TR_LAYOUT = "E0610", "an STL layout cannot be expressed in the target",
"An STL outline description draws its layout shapes under the grown tree.
pfg and LinF have no shapes. The grown tree itself is translated exactly.

With `--lossy` the shapes are dropped (W0610).";

    TR_RULE = "E0611", "production has no equivalent rule in the target",
"LinF rules rewrite one declared name (`f = f+f`), and STL rules are
macros of drawing components. A production whose predecessor is several
symbols (pfg `AB --> C`), or that rewrites a turn, a bracket or another
turtle symbol, has no equivalent.

With `--lossy` the production is dropped (W0611).";

    TR_MOVE = "E0612", "moving without drawing cannot be expressed in STL",
"Every STL stem is drawn: there is no component that moves the turtle
without a line (pfg `f`, a LinF blank).

With `--lossy` the move is drawn as a stem (W0612).";

    TR_TOO_LARGE = "E0613", "the translation would be too large for the target",
"Some targets need what the source computes in a derivation written out:
STL has no derivation steps, so a pfg or LinF system becomes STL rules
whose expansion is the derived word. When that word is longer than the
STL reader expands (8 000 000 components), or when the source uses more
symbols than pfg has characters, the translation is not written.

Translate with fewer steps (`-n`).";

    TR_TEXTURES_DROPPED = "W0615", "textures not translated",
"The source maps images on its surfaces (cpfg `texture:` lines and
`@Tx`). Only `.gft` writes textures (its `texture` lines, naming the image
file): pfg, LinF, STL and the other targets draw the same shapes in their
own colours, untextured. `.gft` says this only of an image whose file name
holds a double quote or a line break, which it cannot quote.";

    TR_PICTURE_DIFFERS = "W0614", "the approximated translation draws another picture",
"After a `--lossy` translation, graftal draws the source and the
translation (with the same steps, within small limits) and compares the
number of segments and the proportions of their bounds. When they differ
much, the approximations together changed the picture, not just its
details: the warning gives both sets of figures.

Example:
    graftal translate std:hogeweg-hesper-a --to linf --lossy

Fig. 3.11a draws 2501 segments at 30 steps; without its contexts, LinF
draws 3. A source too large to draw quickly is not compared (a note
says so).";

    TR_PARAMETRIC = "E0615", "a parametric cpfg L-system cannot be translated",
"Translation rewrites a system into another notation's productions.
A cpfg L-system whose modules carry parameters computes with them at
each step (expressions, conditions, variables), which no other notation
graftal writes can express: the translation is not written. pfg, LinF,
STL and Fractint systems, and cpfg ones without parameters, translate.";

    TR_GRAPH = "E0616", "an object-instancing graph cannot be translated",
"An object-instancing graph (a `.gft` `graph { … }` block: symbols placed
by affine transforms, Bekaert & Willems' IFS codes with restrictions) is
never expanded into a word, and no notation graftal writes but its own
says what a graph says: the translation is not written, even with
`--lossy`, rather than written without the graph. `--to gft` writes it.

Example:
    graftal translate std:bekaert/fern --to linf     <- write `--to gft`";

    TR_CONTEXT_APPROX = "W0601", "context dropped",
"`--lossy` dropped the context of a production that the target cannot
express (see E0601): the production applies wherever its predecessor
occurs.";

    TR_STOCHASTIC_APPROX = "W0602", "stochastic choice made deterministic",
"`--lossy` replaced a random choice between successors by its most likely
successor (see E0602); of equal weights, the first.";

    TR_GUARD_APPROX = "W0603", "per-occurrence probability dropped",
"`--lossy` replaced `p?s` by `s`, always expanded (see E0603): a LinF
`i = [.5?j]` becomes `i = [j]`, so every branch grows.";

    TR_INTERVAL_APPROX = "W0604", "interval angle fixed",
"`--lossy` replaced an interval angle `[lo hi]` by its middle (see
E0604): `(0, [0 2*pi])` turns by pi every time.";

    TR_3D_APPROX = "W0605", "3D rotation dropped",
"`--lossy` dropped a rotation out of the plane (see E0605); the drawing
is flattened.";

    TR_ANGLE_APPROX = "W0606", "angle rounded",
"`--lossy` rounded an angle to a multiple of the increment the target
can express (see E0606).";

    TR_LENGTH_APPROX = "W0607", "length factor dropped",
"`--lossy` dropped a length factor or a step length the target cannot
express (see E0607): the picture has the same shape where the factor is
uniform, scaled or distorted elsewhere.";

    TR_ATTRIBUTE_APPROX = "W0608", "colour, width or polygon dropped",
"`--lossy` dropped a drawing attribute the target cannot express (see
E0608): the segments are the same, their colours or widths differ.";

    TR_SWAP_APPROX = "W0609", "swapping turns dropped",
"`--lossy` dropped LinF's `!` (see E0609): turns after it are not
exchanged, so a mirrored branch is drawn unmirrored.";

    TR_LAYOUT_APPROX = "W0610", "layout dropped",
"`--lossy` dropped an STL layout's shapes (see E0610); the grown tree is
translated exactly.";

    TR_RULE_APPROX = "W0611", "production dropped",
"`--lossy` dropped a production the target cannot express (see E0611):
the symbols it rewrote are copied unchanged.";

    TR_MOVE_APPROX = "W0612", "move drawn",
"`--lossy` drew a move without a line as a stem (see E0612): the
positions are the same, the gaps are filled.";
}
