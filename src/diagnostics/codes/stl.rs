//! Diagnostic codes of the STL front end (`E05xx`, `W05xx`).

use super::Code;

codes! { STL;
    STL_UNKNOWN_RULE = "E0501", "unknown rule name",
"A name in a string or a branching term is neither a drawing component
(F, L, R) nor a rule defined in the file. Names written together are split
into the longest rule names and components: `FR1` is `F` then `R1`.

Example:
    R1 = [F][+F]
    SEED
    F R2          <- no rule R2

Define the rule (`R2 = [++F][-F]`) or correct the name.";

    STL_TOO_MANY_ENTRIES = "E0502", "more branching entries than branches",
"A branching term `R{e1, …, em}` gives one entry per top-level branch of R.
An entry beyond R's last branch has no branch to extend.

Example:
    R2 = [++F][-F]          <- two branches
    SEED
    R2{R2, R2, R2}          <- three entries

Remove the extra entries, or give R2 another branch.";

    STL_NO_BRANCHES = "E0503", "branching term on a rule without branches",
"A branching term `R{…}` extends the top-level branches `[...]` of R, so R
must have at least one. A rule like `R = FF` has none.

Example:
    R = FLF
    SEED
    R{R, R}

Use the rule without braces (`R`), or write its branches in brackets.";

    STL_UNTERMINATED = "E0504", "unterminated block",
"A `SEED` block must end with `ENDSEED` and a `LAYOUT` block with
`ENDLAYOUT`. Without it the block runs to the end of the file.

Example:
    SEED
    F R1{R1, R2}
    (file ends)

Add `ENDSEED` (or `ENDLAYOUT`) after the block.";

    STL_UNKNOWN_SHAPE = "E0505", "unknown layout shape",
"Layout shapes are Rectangle, RoundRect, Ellipse and Polygon (the paper's
Table 1).

Example:
    LAYOUT
    (clGreen) Circle (0,0), 100, 100

Write `Ellipse` with equal width and height for a circle.";

    STL_UNKNOWN_COLOUR = "E0506", "unknown colour",
"A layout colour is a Delphi colour name (clBlack, clMaroon, clGreen,
clOlive, clNavy, clPurple, clTeal, clGray, clSilver, clRed, clLime,
clYellow, clBlue, clFuchsia, clAqua, clWhite, clMoneyGreen, clSkyBlue,
clCream, clMedGray, clLtGray, clDkGray) or a hexadecimal `$00BBGGRR`
(blue, green, red: `$000000FF` is red).

Example:
    (clGren) Ellipse (-150,0), 300, 400";

    STL_FEW_POINTS = "E0507", "polygon with fewer than three points",
"A Polygon encloses an area, so it needs at least three points.

Example:
    (clGreen) Polygon (0,0), (100,0)

Add the missing points: `(clGreen) Polygon (0,0), (100,0), (50,100)`.";

    STL_NEGATIVE = "E0508", "negative size or count",
"Sizes (width, height, corner, B, L), counts (`[I n X]`, LEVELS) and the
decrements of B and L cannot be negative, and counts are whole numbers.

Example:
    (clGreen) Rectangle (0,0), -200, 100
    R3 = [I -2 R1]

Write the size as a positive number; move the starting point instead.";

    STL_CYCLE = "E0509", "rule defined through itself",
"Rules are macros: using a rule means writing its body in its place. A rule
whose body uses itself, directly or through other rules, would never end.

Example:
    R1 = [F]R2
    R2 = [+F]R1      <- R1 -> R2 -> R1

Growth by a rule is written with the rule in a SEED and a LAYOUT, or with
`[I n R1]` for n rewritings.";

    STL_DUPLICATE = "E0510", "defined twice",
"A rule name, the SEED block, or a setting may be given only once.

Example:
    R1 = [F][+F]
    R1 = [F][-F]

Give the second rule another name.";

    STL_SHAPE_ARGS = "E0511", "wrong shape arguments",
"Each shape takes the parameters of the paper's Table 1: Rectangle and
Ellipse a starting point (the lower-left corner of the bounding box),
width and height; RoundRect the same and the corner's size; Polygon its
points.

Example:
    (clWhite) Rectangle (0,0), 200

Write `(clWhite) Rectangle (0,0), 200, 100`.";

    STL_UNKNOWN_KEYWORD = "E0512", "unknown statement",
"A line outside SEED and LAYOUT is a setting (ANGLE, B, L, GROWTH, LEVELS)
or a rule definition `NAME = string`. Keywords are upper case.

Example:
    ANGEL 30

Write `ANGLE 30`.";

    STL_TOO_DEEP = "E0513", "too many levels or stems",
"graftal grows at most 256 levels (LEVELS) and 1 000 000 stems. These limits
keep every input within memory and time. (Brackets, braces and rules used
through rules nested more than 256 deep are E0013, as in every notation.)

Example:
    LEVELS 100000

Use fewer levels; a tree rarely needs more than a few dozen.";

    STL_MISSING_SEED = "E0514", "missing SEED",
"An STL file draws its seed: without a `SEED … ENDSEED` block there is
nothing to draw or grow.

Example:
    R1 = [F][+F][-F]

Add:
    SEED
    F R1
    ENDSEED";

    STL_UNBALANCED = "E0516", "unbalanced brackets or braces",
"Every `[` opens a branch that a `]` closes, and every `{` of a branching
term is closed by `}`.

Example:
    R1 = [F[+F]

Write `R1 = [F[+F]]`.";

    STL_RESERVED_NAME = "E0517", "reserved name used as a rule",
"F, L, R (drawing components), B, I and the keywords cannot name a rule.

Example:
    F = F[+F]F

Name the rule R1 and use it in the seed.";

    STL_CLAMPED = "W0501", "stem broadness or length clamped",
"With its decrement per level, B or L would reach zero or less at some level
of the tree. From that level on, graftal draws it at a tenth of its first
value instead.

Example:
    B = 8 (2)       <- 8, 6, 4, 2, then 0 at level 4
    LEVELS 6";

    STL_NO_GROWTH = "W0502", "layout with nothing to grow",
"A file with a LAYOUT is an Outline Description: the rules named in its seed
grow inside the layout. A seed without a rule that has branches (written
without `{…}`) gives growth nothing to start from.

Example:
    SEED
    F
    ENDSEED
    LAYOUT
    (clWhite) Rectangle (-100,0), 200, 100
    ENDLAYOUT";
}
