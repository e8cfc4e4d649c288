//! Diagnostic codes of the `.gft` front end (`E09xx`, `W09xx`; `E092x`
//! for its `graph` blocks).

use super::Code;

codes! { GFT;
    GFT_UNKNOWN_KEYWORD = "E0900", "unknown keyword",
"A line of a `.gft` file that has no `->` starts with a keyword (`axiom`,
`angle`, `steps`, `turtle`, …) or is `NAME = OPERATION`. Keywords are
lowercase, words joined by `-` (docs/gft.md lists them).

Example:
    axoim F         <- did you mean `axiom`?";

    GFT_UNKNOWN_LINE = "E0901", "not an item",
"A line is a keyword line, `NAME = OPERATION` or a production with `->`.

Example:
    F F+F           <- write `F -> F+F`";

    GFT_UNKNOWN_OPERATION = "E0902", "unknown turtle operation or set",
"`NAME = OPERATION` gives a symbol one of the operations of docs/gft.md §3
(`forward`, `move`, `turn A`, `push`, `nothing`, …); `turtle SET` names one
of the sets `pfg`, `linf`, `stl`, `cpfg`, `fractint`, `none`.

Example:
    X = forwrd      <- did you mean `forward`?
    turtle lsys     <- a set graftal knows: `pfg`, `cpfg`, …";

    GFT_BAD_VALUE = "E0903", "bad value",
"The value of a setting or an operation is not what it takes: a number
where a number is needed (a whole one for `steps`, `seed` and `colour`), an
angle as `30deg`, `0.5rad`, `delta` or `2*delta`, a colour as `#rrggbb`.

Example:
    steps ten       <- write `steps 10`
    angle           <- write `angle 90`";

    GFT_UNBALANCED = "E0904", "unbalanced braces",
"A block item (`decomposition`, `start`, …) takes its `{ … }`, and an STL
seed's term closes its entries with `}`.

Example:
    start n = 0;    <- write `start { n = 0; }`";

    GFT_DUPLICATE = "E0905", "setting given twice",
"Each setting appears at most once in a file: which one would hold is
not obvious to a reader.

Example:
    angle 90
    angle 60        <- remove one";

    GFT_UNKNOWN_NAME = "E0906", "unknown name",
"An array in an expression is declared with `array`, a call is one of
cpfg's built-in functions, `frenet NAME` names a `rotation`, and a seed's
or `unit`'s rule is declared with `rule` (a plain name never assigned is a
local worth 0, W0902).

Example:
    A(x) -> F(v[0])    <- declare `array v[1]`";

    GFT_PARAMETER_COUNT = "E0907", "wrong number of parameters",
"A built-in function takes the number of arguments cpfg gives it, and a
predecessor's module binds names, not values.

Example:
    A(x) -> F(sin(x, 2))   <- `sin` takes one argument
    A(1) -> F              <- write a name: `A(x) : x == 1 -> F`";

    GFT_LONG_ARROW = "E0908", "`-->` in a `.gft` file",
"`.gft` writes the production arrow `->`. pfg and cpfg write `-->`, and in
`.gft` that reads as the symbol `-` then `->`: a production for `F-`, not
for `F`. A `-` touching the arrow is therefore refused; a production that
really rewrites a `-` writes a space before the arrow.

Example:
    F --> F[+F]F[-F]F

Write:
    F -> F[+F]F[-F]F";

    GFT_UNCLOSED = "E0909", "parenthesis not closed",
"A module's parameters are written in parentheses, `F(x*0.7, 2)`, and the
`(` must be closed on the item. A `(` never closed would take the rest of
the file as parameters; graftal stops at the end of the file and refuses
the item instead of guessing where the parameters end.

Example:
    X -> Y(

Write:
    X -> Y(1)";

    GRAPH_BAD_LINE = "E0920", "malformed graph line",
"A line of a `graph { … }` block is one of
    transform NAME = STEPS
    axiom COUPLES
    symbol NAMES
    geometry SYMBOL = SHAPE
    alternative SYMBOL [below PIXELS] = SHAPE
    SYMBOL -> COUPLES
(docs/gft.md §13). A rule rewrites one symbol; a transform's name is not
one of the transform words (`translate`, `scale`, `rotate`, `shear`,
`matrix`); nothing comes before the block's `{`.

Example:
    graph {
      axoim A                   <- did you mean `axiom`?
      A B -> h(A)               <- a rule rewrites one symbol
    }";

    GRAPH_UNKNOWN_TRANSFORM = "E0921", "unknown transform",
"A transform written in steps (after `transform NAME =`, or between `[`
and `]` before a couple's symbol) is composed of `translate P`, `scale S`
or `scale (x, y, z)`, `rotate x|y|z ANGLE` or `rotate (ax, ay, az) ANGLE`,
`shear x y F`, `matrix (…)`, and the names of transforms declared above.

Example:
    A -> [scal 0.5](A)          <- did you mean `scale`?";

    GRAPH_BAD_VALUE = "E0922", "malformed number or point",
"The values of a `graph` block are numbers (`0.5`, `-2`, `1/3`), points
`(x, y, z)` (`(x, y)` is z = 0), angles in degrees (`30`, `30deg`) or
radians (`0.52rad`), and matrices of three rows of four numbers, rows
separated by commas: `matrix (0.5 0 0 1, 0 0.5 0 0, 0 0 0.5 0)`. `scale`
takes one number or three; a rotation's axis is not zero; a shear moves
one axis along another; `below` takes a number of pixels above zero.

Example:
    transform t = translate (1, 0, 0, 2)   <- a point has three coordinates";

    GRAPH_BAD_SHAPE = "E0923", "malformed shape",
"A `geometry` or `alternative` line gives one shape:
    sphere CENTRE RADIUS
    box MIN MAX
    cylinder BASE TOP RADIUS
    cone BASE TOP RADIUS [TOP-RADIUS]
    disc CENTRE NORMAL RADIUS
    triangle P Q R
    polygon P Q R …
then an optional colour `#rrggbb` and finish words `ambient X`,
`diffuse X`, `specular X`, `shininess X`, each at most once.

Example:
    geometry B = sphere (0, 0, 0)          <- a sphere takes a radius";

    GRAPH_UNKNOWN_SYMBOL = "E0924", "unknown symbol",
"Each symbol of a `graph` block is introduced by a line of its own: a
rule `A -> …`, a `geometry` or `alternative` line, or `symbol A`. A symbol
that an axiom or a rule places but no line introduces is most often a
misspelt one. (In a graph that has geometries, such a symbol is a
terminal without a geometry: E1002 says so.)

Example:
    graph {
      axiom A
      A -> h(A) h(a)            <- did you mean `A`?
    }";

    GRAPH_DEFINED_TWICE = "E0925", "given twice in a graph",
"In a `graph` block, a symbol has at most one rule, a transform name is
declared once, the block has one `axiom`, and a symbol's `alternative`
lines all give the same `below`: which one would hold is not obvious to a
reader.

Example:
    A -> h(A)
    A -> t(A)                   <- merge them: `A -> h(A) t(A)`";

    GRAPH_UNKNOWN_NAME = "E0926", "unknown transform name",
"A couple `NAME(B)` places `B` by the transform declared with `transform
NAME = …`. The name is declared in the same `graph` block; a transform's
definition may use only the transforms declared above it.

Example:
    transform h = scale 0.5
    A -> g(A)                   <- did you mean `h`?";

    GFT_NO_AXIOM = "W0900", "no axiom",
"A file without `axiom` (and without a `graph` block or a structure's
`seed`, which give what is drawn) derives the empty word: nothing is
drawn. A `graph` block without its `axiom` places nothing either.

Example:
    F -> F+F        <- add `axiom F`";

    GFT_UNBALANCED_BRACKETS = "W0901", "unbalanced brackets",
"A `[` of a word is not closed by a `]` in the same word, or a `]` closes
no `[`. cpfg and Fractint words may be so (a production may open a branch
that another closes), and the word is read as written; check that the
branches close where you mean them to.

Example:
    F -> F[+F       <- add `]` unless another production closes it";

    GFT_UNASSIGNED = "W0902", "a name never assigned",
"A name in an expression that is no parameter, local, global or array is,
as in cpfg, a local whose value is 0. It is often a misspelt name.

Example:
    A(x) -> F(y)    <- `y` is 0: did you mean `x`?";

    GFT_UNDECLARED_NAME = "W0903", "letters near a declared name",
"A run of letters that no declared name matches is read one letter a
module, as the books read `FF`. When the run is near a name the file
declares (with `symbol` or `NAME = OPERATION`), it is often that name
misspelt.

Example:
    symbol apex
    axiom apx       <- did you mean `apex`? (read as `a p x`)";

    GFT_TEXTURE_IMAGE = "W0904", "texture image missing or unreadable: drawn untextured",
"A `texture` line names an image file (relative to the `.gft` file's
folder) that is not there, or that is not a PNG or SGI (`.rgb`) image
graftal can decode. What the texture would cover is drawn in its own
colours, as cpfg draws it when a view file's image is missing (W0814);
the texture keeps its number, so that `set-texture` still picks the
texture the line after means.

Example (plant.gft, written in another folder than the object's):
    texture \"maple.png\" filter nearest mode modulate ratio 1  <- no maple.png here

Put the image beside the `.gft` file, or name it relative to the file's
folder (`\"../maple/maple.png\"`).";
}
