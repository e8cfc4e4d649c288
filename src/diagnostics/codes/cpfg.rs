//! Diagnostic codes of the cpfg dialect of `.l` (`E08xx`, `W08xx`).
//!
//! `E0801`–`E0829` and `W0801`–`W0819` belong to the files around the
//! L-system: the C preprocessor pass ([`crate::front::cpfg::preprocess`]), view
//! files, function files and surface files. `E0830` and up, `W0820` and up
//! are the cpfg language's own.

use super::Code;

codes! { CPFG;
    CPFG_UNTERMINATED_COMMENT = "E0801", "unterminated comment",
"cpfg runs the C preprocessor over the L-system file first, and a comment
opened with /* must be closed with */ before the end of the file; otherwise
everything after it is swallowed by the comment.

Example:
    /* internode growth rate
    #define RATE 1.02

Close the comment:
    /* internode growth rate */";

    CPFG_UNTERMINATED_IF = "E0802", "`#if` without `#endif`",
"Every conditional block of the preprocessor (`#if`, `#ifdef`, `#ifndef`)
must be closed by an `#endif`. Without it the preprocessor cannot tell where
the conditional text ends.

Example:
    #if LEAVES==1
    L(a) --> ~l(a)
    endlsystem

Add the missing line:
    #endif";

    CPFG_STRAY_CONDITIONAL = "E0803", "`#else`, `#elif` or `#endif` without `#if`",
"`#else`, `#elif` and `#endif` continue or close a conditional block
opened by `#if`, `#ifdef` or `#ifndef`. This one has no open block: an
`#endif` too many, or an `#else` after the block's own `#else`.

Example:
    #if LEAVES==1
    ...
    #endif
    #endif          <- nothing left to close";

    CPFG_MACRO_ARGUMENTS = "E0804", "wrong number of macro arguments",
"A function-like macro (`#define F(a,b) ...`) must be called with as many
arguments as it has parameters, separated by commas outside parentheses.
The call is left unexpanded.

Example:
    #define MAX(a,b) (((a)>(b))?(a):(b))
    A(x) --> A(MAX(x))

Write:
    A(x) --> A(MAX(x,1))";

    CPFG_UNKNOWN_DIRECTIVE = "E0805", "unknown preprocessor directive",
"A line whose first character (after spaces) is `#` is a preprocessor
directive: #define, #undef, #include, #if, #ifdef, #ifndef, #elif, #else,
#endif, #error, #pragma, #line. A `#` followed by a name that is none of
these is an error. (A `#` followed by something else, like the width module
`#(0.06)` on a continuation line of a production, is kept as text, as
vlab's cpfg does; a strict C preprocessor would reject that too.)

Example:
    #defin RATE 1.02
    #w(d) --> #(d*1.06)     <- `#w` read as a directive

Write:
    #define RATE 1.02
    * < #w(d) --> #(d*1.06)  (something before the `#`)";

    CPFG_MISSING_INCLUDE = "E0806", "included file not found",
"`#include \"file\"` inserts the named file, which is looked for beside the
L-system file. The file could not be read.

Example:
    #include \"female.l\"     <- no female.l in the object's folder

Check the name (case matters on most systems) and that the file is part of
the object.";

    CPFG_RECURSIVE_INCLUDE = "E0807", "recursive or too deep `#include`",
"A file includes itself, directly or through other files, or includes are
nested more than 16 deep. The preprocessor would never finish, so the
include is skipped.

Example (a.l):
    #include \"b.l\"
and b.l:
    #include \"a.l\"";

    CPFG_UNTERMINATED_CALL = "E0808", "unterminated macro call",
"A function-like macro name followed by `(` starts a macro call, and the
call's closing `)` was not found before the end of the text (or before the
next preprocessor directive). The name is left unexpanded.

Example:
    #define LEAF(a) ~l(a)
    A --> F LEAF(2

Write:
    A --> F LEAF(2)";

    CPFG_BAD_DIRECTIVE = "E0809", "malformed preprocessor directive",
"A preprocessor directive is missing a part or has one it cannot use:
#define needs a macro name, #include a file name in quotes, #if an integer
constant expression (after macro expansion; names that are not macros count
as 0, and `defined(NAME)` tests whether NAME is a macro).

Example:
    #define
    #include female.l
    #if LEAVES ==

Write:
    #define LEAVES 1
    #include \"female.l\"
    #if LEAVES == 1";

    CPFG_EXPANSION_LIMIT = "E0810", "preprocessor output too large",
"Macro expansion produced more than graftal allows (8 MiB of text, 64
nested macro calls in arguments, or 20 million expansion steps). Macros
that expand into several copies of other macros grow exponentially; the
expansion is cut off here.

Example:
    #define A B B
    #define B C C
    #define C D D
    ...";

    CPFG_ERROR_DIRECTIVE = "E0811", "`#error`",
"The file contains an `#error` directive in text the preprocessor keeps:
the author made this configuration an error on purpose. The message is
the directive's text.

Example:
    #if LEAVES > 2
    #error only 0, 1 or 2 leaves are modelled
    #endif";

    CPFG_VIEW_BLANK = "E0812", "view-file value left as `?`",
"A view-file command's value is `?`: the object is an exercise (the vlab
course objects leave `?` where the student writes a value), and its
picture depends on the blank. Fill it in.

Example:
    angle increment: ?

Write:
    angle increment: 18

(A value of the wrong kind, rather than a blank, is warning W0808: the
line is ignored and its default kept.)";

    CPFG_FUNCTION_FILE = "E0813", "malformed function file",
"A function file (`.func`, written by vlab's funcedit) or function set
(`.fset`, written by the gallery) does not have the expected layout:

    fver 1 1
    name: internode
    samples: 10
    flip: off
    points: 4
    0.000000 0.000000 1
    ...

(or the older `range: 0.0 1.0` / `points: n` layout). cpfg needs at least 4
control points, each `x y` with an optional multiplicity.";

    CPFG_SURFACE_FILE = "E0814", "malformed surface file",
"A surface file (`.s`, written by vlab's bezieredit) does not have the
expected layout: a bounding-box line, CONTACT POINT, END POINT, HEADING,
UP and SIZE lines, then patches, each a name, a TOP COLOR line, three
neighbour lines (AL: A: AR: / L: R: / BL: B: BR:) and 4 rows of 4 control
points `x y z`.

Example of a patch:
    patch
    TOP COLOR: 0 DIFFUSE: 0.00 BOTTOM COLOR: 0 DIFFUSE: 0.00
    AL: ~ A: ~ AR: ~
    L: ~ R: ~
    BL: ~ B: ~ BR: ~
    -0.60 1.21 0.10  0.47 2.02 -0.61  -0.36 2.03 -0.61  0.75 1.23 0.16
    ... (three more rows)";

    CPFG_CONTOUR_FILE = "E0816", "malformed contour file",
"A contour file (`.con`, written by vlab's cuspy or the curve gallery) does
not have the expected layout. cpfg reads three:

    cver 1 3
    name: leaf.con
    points: 4 8
    type: or
    samples: 8
    -1.0 -2.0 0.0 3
    ...

(`points: n total`, then n lines `x y z multiplicity`; `type:` is `or`,
`cr`, `oe` or `ce`, open or closed), the gallery's `version: 1.4` with
`key: value` lines and `type: bspline`, and the oldest `n dim closed|open`
followed by the points. An open curve needs at least 4 control points, a
closed one 3, multiplicities counted.";

    CPFG_OUTSIDE_FOLDER = "E0815", "side file outside the object's folder",
"A cpfg object is a folder: the `.l` file and the files it names (the view
file's `function:`, `function set:`, `surface:` and `contours:` files, and
`#include`s) are read from that folder only. A name that leaves it (an
absolute path, `..`, or a link that points elsewhere) is not read, so that
opening an object never reads files it does not hold.

Example:
    function: ../../shared/leaf.func     <- outside the object's folder

Copy the file into the object's folder and name it there.";

    CPFG_MACRO_REDEFINED = "W0801", "macro redefined",
"A macro is defined again with a different body (or different parameters)
without an `#undef` first. The C preprocessor warns and uses the later
definition; so does graftal.

Example:
    #define in(x,y) (WIDTH*x*x+(y-R)*(y-R) <= R*R)
    #define in(x,y) (y<0 || y>R+R || x<-R || x > R)

Write `#undef in` before the second definition if this is intended.";

    CPFG_STRAY_BACKSLASH = "W0802", "backslash before a line continuation",
"A directive line ends with two backslashes `\\\\`. The last one joins the
next line to this one; the first one would stay in the macro's text, where
cpfg would read it as the roll module `\\`. graftal drops it, which is what
the author meant in every file that has it.

Example:
    #define int_length(x) \\\\
        (INT_LENGTH_SCALE * func(INT_LENGTH,x))

Write a single backslash:
    #define int_length(x) \\";

    CPFG_EXTRA_TOKENS = "W0803", "extra text after a directive",
"`#include`, `#else`, `#endif`, `#ifdef`, `#ifndef` and `#undef` take at
most one name; the text after it is ignored, as the C preprocessor does.
A second file name in an `#include` is not included: write one `#include`
per file.

Example:
    #include \"female.l\" \"male.l\"

Write:
    #include \"female.l\"
    #include \"male.l\"";

    CPFG_UNKNOWN_VIEW_COMMAND = "W0804", "unknown view-file command",
"The view file (`.v`) has a line whose command cpfg does not know (or
that is not `command: value`). cpfg ignores such lines; so does graftal.
Misspellings get a suggestion.

Example:
    angel factor: 16

Write:
    angle factor: 16";

    CPFG_DEPRECATED_VIEW_SPELLING = "W0805", "misspelt view command accepted",
"Some view files of the vlab distribution write `tappered lines:`, which
old cpfg versions accepted for `tapered lines:`. graftal reads it as
`tapered lines:` and says so.

Example:
    tappered lines: on

Write:
    tapered lines: on";

    CPFG_COLOUR_FILE = "W0806", "colour map or material file not used",
"The object's `specifications` runs cpfg with a colour map (`-m file.map`:
256 RGB byte triples, 768 bytes) or a material file (`-M file.mat`: records
of 15 bytes: index, transparency, ambient, diffuse, emission and specular
RGB, shininess). This file is missing from the object's folder or does not
have that shape, so it is not used: the picture is drawn with cpfg's
default colours instead.

Put the file in the object's folder, or save it again with vlab's palette
(colour maps) or medit (materials) editor.";

    CPFG_VIEW_NOT_DRAWN = "W0807", "view command not drawn",
"The view file asks for something that changes cpfg's picture and that
graftal does not draw yet: a background scene, textures or rayshade
surfaces (`tsurface:`). (Shadows are drawn: `render mode: shadows` is ray
traced, with no need of a `shadow map:`.) The rest of the picture is drawn; this
part is left out.

Example:
    background scene: scene.dat

To draw the scene's objects, model them in the L-system itself.";

    CPFG_VIEW_VALUE = "W0808", "malformed view-file value ignored",
"A view-file command's value is not of the kind it takes: numbers for
`angle factor:`, `initial line width:`, `scale factor:`, three numbers
separated by commas for `viewpoint:`, `on`/`off` for flags, a name and a
number for `surface:`. The line is ignored and the command's default kept,
as cpfg does, so this is a warning: the picture may differ from the one
intended.

Example:
    angle factor: sixteen
    viewpoint: 0 0 1

Write:
    angle factor: 16
    viewpoint: 0,0,1";

    CPFG_NAME_CASE = "W0809", "side file found in another case",
"A view file, `specifications` or `#include` names a file of the object's
folder in another case than the file on disk has. L-studio and vlab ran on
file systems that do not tell cases apart (Windows, macOS), so such objects
worked there; graftal finds the file the same way and says which it read,
since a case-sensitive system (Linux) would not.

Example (the view file):
    contour: SEPAL.con
and the folder holds `sepal.con`.

Write:
    contour: sepal.con";

    CPFG_NO_VIEW = "W0810", "no view file",
"cpfg draws an L-system with the view file named on its command line (in
vlab, on the `cpfg` line of the object's `specifications`): the angle
increment, line widths, colours, camera, surfaces and functions. Here
there is none: the object's `specifications` names a view file that is not
in the folder, or nothing names one and the folder holds no `.v` file (or
several, none named like the `.l`). The picture is drawn with cpfg's
defaults, which the note lists, and may look nothing like the object.

Put the view file beside the `.l`, named like it (`plant.l`, `plant.v`).";

    CPFG_FOLDER_COLOURS = "W0811", "colour files taken from the folder",
"The object's folder has no `specifications` file, the layout L-studio
(vlab's Windows successor) uses: the `.l`, `.v`, colour map (`.map`) or
materials (`.mat`) and side files side by side. As L-studio does, graftal
draws with the colour map and the materials named like the `.l`, else the
folder's only ones, and says which it took, since a folder of several
would be drawn with others.

To choose the files, write a `specifications` file with the `cpfg` line
vlab runs, e.g.
    cpfg plant.l plant.v -m plant.map -M plant.mat";

    CPFG_SLASHES_COMMENT = "W0812", "`//` read as a comment in a word",
"cpfg runs the C preprocessor over the `.l` file, and `//` starts a
comment that runs to the end of the line. In an axiom or a successor, two
rolls written together (`//`) therefore cut the word short: everything
after them is not read, and cpfg (and graftal) draw what is left. Write
the rolls with a space between them.

Example:
    Axiom: E///T(0)FFFA(0)     <- read as `Axiom: E`

Write:
    Axiom: E/ / /T(0)FFFA(0)";

    CPFG_MISSING_SURFACE = "W0813", "surface file missing: its module draws nothing",
"A `surface:` (or `line:`) line of the view file names a `.s` file the
object's folder does not have. cpfg reads a surface only when its file
exists and says nothing otherwise; the module that would draw it then
draws nothing and leaves the turtle where it is. graftal does the same and
says so at the view file's line.

Example (female.v):
    surface: b bract.s 1.5 3 3     <- no bract.s in the folder

Put the file in the object's folder, or take the line out (and `~b` out of
the L-system).";

    CPFG_ENVIRONMENT_LINE = "W0816", "environment or specification line not read",
"A line of the `.e` file or of the environment program's specification
file (`density.spec`, `light.spec`, `enviro.spec`) that the program does
not read: its keyword (the text before the first `:`) is none of the
program's, matched exactly as vlab's programs match it (`3D case` is not
`3d case`), or its value has no number. The program skips such a line and
keeps its default, and so does graftal, which runs the program's
computation itself.

Example (density.spec, read by honda81):
    3D case: on     <- honda81 reads `3d case`: the model stays in the plane

Write the keyword as the program spells it (the help lists them), or take
the line out if the default is what is meant.";

    CPFG_TEXTURE_IMAGE = "W0814", "texture image missing or unreadable: drawn untextured",
"A `texture:` line of the view file (or the texture file at the end of a
`surface:` line) names an image the object's folder does not have, or one
that is not a PNG or SGI (`.rgb`) image graftal can decode. cpfg then says
it cannot load the texture and draws without it; graftal draws what the
texture would cover in its own colours too, and keeps the texture's
number, so that `@Tx(n)` still picks the texture the line after means.

Example (plant.v):
    texture: F: maple.png H:n L:n E:m S:     <- no maple.png in the folder

Put the image in the object's folder (cpfg reads PNG and SGI images;
convert others), or take the line out.";
}
