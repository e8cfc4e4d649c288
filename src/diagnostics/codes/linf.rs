//! Diagnostic codes of the LinF front end (`E04xx`, `W04xx`).

use super::Code;

codes! { LINF;
    LINF_OUTSIDE_BLOCK = "E0401", "text before the first block",
"A LinF file is a sequence of blocks, each starting with its keyword:
lines, blanks, angles, axiom, rules, colors. Text before the first keyword
belongs to no block.

Example:
    line f          <- `line` is not a keyword: did you mean `lines`?
    axiom f";

    LINF_UNDECLARED = "E0402", "name not declared",
"Every name in a string must be declared: as a line (`lines f`), a blank
(`blanks b`), an angle (`angles t = (0, pi/2)`, used as `+t`) or a rule
head (`i = …`). In a string without spaces, names are split by the longest
declared name, so `fg` is `f g` when both are declared.

Example:
    lines f
    axiom f+g       <- `g` is not declared";

    LINF_UNKNOWN_ANGLE = "E0403", "unknown angle after signs",
"A run of `+` or `-` signs rotates by the angle named right after it (or by
the default rotation when no name follows). The name right after these signs
is not a declared angle, nor any other declared name.

Example:
    angles t = (0, pi/3)
    rules f = f+q   <- `q` is not an angle (did you mean `t`?)";

    LINF_NO_DEFAULT_ROTATION = "E0404", "sign without an angle and no default rotation",
"`+` or `-` not followed by an angle name rotates by the default rotation:
the unnamed pair of the angles block. This file declares none.

Example:
    angles t = (0, pi/3)
    rules f = f+f   <- write `+t`, or declare `angles (0, pi/3)`";

    LINF_BARE_ANGLE = "E0405", "angle used without a sign",
"An angle name means something only right after a run of signs: `+t`
rotates by t, `-t` by the negated pair. Alone in a string it would be a
symbol with no meaning. The name must follow the signs with no space.

Example:
    rules f = f+ t f   <- write `f+tf`";

    LINF_MISSING_NUMBER = "E0406", "`?` or `@` without a number",
"`@` multiplies the current length by the number right before it (`0.7@`);
`?` gives the probability with which the next symbol is expanded
(`0.5?j`). Both need that number.

Example:
    rules f = f[@f]     <- write `0.7@`";

    LINF_STRAY_NUMBER = "E0407", "number not followed by `?` or `@`",
"Numbers appear in strings only as length factors `x@` or probabilities
`p?s`. A number followed by anything else has no meaning.

Example:
    rules f = f 0.5 f   <- `0.5@` or `0.5?f`?";

    LINF_PROBABILITY = "E0408", "probability outside (0, 1)",
"In `p?s`, p is the probability that this occurrence of s is expanded at a
step; the paper requires 0 < p < 1. p = 1 is `s` alone; p = 0 would never
expand it.

Example:
    rules i = [1.5?j]   <- write e.g. `0.5?j`";

    LINF_GUARD_TARGET = "E0409", "`?` not followed by a symbol",
"`p?s` makes the expansion of the symbol s right after `?` happen with
probability p. Here `?` is followed by no symbol (or by a sign, a bracket,
the end of the string).

Example:
    rules i = [0.5?]    <- write `0.5?j`";

    LINF_EMPTY_INTERVAL = "E0410", "interval whose low end exceeds its high end",
"An interval `[lo hi]` in a rotation draws a value uniformly between lo and
hi each time the rotation is applied. Its low end must not exceed its high
end.

Example:
    angles w = (0, [pi 0])   <- write `[0 pi]`";

    LINF_NOT_A_PAIR = "E0411", "rotation that is not a pair",
"A rotation is a pair (torsion, curvature), in radians. A turn in the plane
is a curvature alone: `(0, angle)`.

Example:
    angles t = (pi/3)        <- write `(0, pi/3)`";

    LINF_BAD_EXPRESSION = "E0412", "expression without a value",
"Rotation components and colour components are arithmetic expressions over
numbers and `pi` with `+ - * /` and parentheses. This one has no finite
value: it divides by zero, or names something other than `pi`.

Example:
    angles t = (0, pi/0)     <- division by zero
    angles u = (0, 2*tau)    <- unknown name `tau`";

    LINF_COLOUR_RANGE = "E0413", "colour component outside 0..255",
"Colours are (red, green, blue) triples of whole numbers from 0 to 255.

Example:
    colors (0, 0, 0) (300, 40, 40)   <- 300 is too large";

    LINF_COLOUR_ARITY = "E0414", "colour that is not a triple",
"A colour in the colors block is written (r, g, b): exactly three
components.

Example:
    colors (40, 40)          <- write `(40, 40, 40)`";

    LINF_UNBALANCED = "E0415", "unbalanced `[` `]`",
"`[` saves the turtle state and `]` restores it; in each string (the axiom
and every rule) they must pair up, as the branches of a plant do.

Example:
    rules f = f[+f          <- the branch is never closed";

    LINF_RESERVED_RULE = "E0416", "rule for a reserved symbol",
"The reserved symbols `[ ] @ ? + - { } !` have fixed meanings and cannot be
rewritten. A rule's left side is a name.

Example:
    rules + = -             <- `+` is reserved";

    LINF_NAME_CONFLICT = "E0417", "name declared with two meanings",
"A name is a line, a blank, an angle or a rule head. It cannot be both a
line and a blank, nor an angle and anything else (a line may have a rule).

Example:
    lines f
    blanks f                <- `f` is already a line";

    LINF_RULE_IN_AXIOM = "E0418", "rule in the axiom block",
"The axiom block holds one string. A `name = …` after it is a rule, and
rules belong in the rules block; the keyword `rules` is probably missing.

Example:
    axiom f
    f = f+f                 <- write `rules` before this line";

    LINF_MISSPELT_KEYWORD = "E0419", "misspelt block keyword",
"A line starts with a name close to a block keyword and goes on with `(`,
as an `angles` or `colors` block does. graftal reads the block as the
keyword's, so that its contents are checked and the rest of the file is
not reported as undeclared names; the file is still an error until the
keyword is spelt right.

Example:
    angels (0, pi/2)        <- write `angles`";

    LINF_DUPLICATE_BLOCK = "W0401", "block given twice",
"Each of the six blocks may appear once. When a block keyword appears
twice, the later block is used and the earlier one is ignored.

Example:
    axiom f
    axiom g                 <- this axiom is used";

    LINF_REDEFINED = "W0402", "defined twice",
"A name, a rotation or a rule is defined twice. The later definition is
used and the earlier one ignored.

Example:
    rules f = ff
          f = f+f           <- this rule is used";

    LINF_COLOUR_BALANCE = "W0403", "unbalanced `{` `}`",
"`{` moves to the next colour of the list and `}` back to the previous one.
A `{` left open at the top level of a string changes the colour of
everything drawn after it, more at every step; a `}` with no `{` before it
in its string goes back to a colour chosen elsewhere. Branches `[…]`
restore the colour, so `{` inside a branch needs no `}`.

Example:
    rules f = {f            <- the colour drifts with every step";

    LINF_COLOUR_LABEL = "W0404", "colour label out of order",
"Colours may be labelled with their position, as the paper's Fig. 7 does
(`0: (0,0,0) 1: (40,40,40)`). The label does not match the position: the
colours are used in list order whatever the labels say.

Example:
    colors 0: (0,0,0) 2: (40,40,40)   <- this is colour 1";

    LINF_DIRECTIVE = "W0405", "directive not understood",
"A comment starting with `#:` is a graftal directive (cFLC reads it as a
comment). graftal understands `#: steps N` (the default number of
derivation steps) and `#: view AZIMUTH,ELEVATION` (the default view, in
degrees). Others are ignored.

Example:
    #: stpes 4                <- did you mean `#: steps 4`?";

    LINF_NO_AXIOM = "W0406", "no axiom",
"The file has no axiom block, so the axiom is empty and nothing is drawn.

Example:
    lines f
    rules f = f+f             <- add `axiom f`";

    LINF_GUARD_NO_RULE = "W0407", "guard on a symbol without a rule",
"`p?s` makes the expansion of s happen with probability p. When s has no
rule there is nothing to expand, and the guard changes nothing.

Example:
    lines f
    rules i = [0.5?f]        <- `f` has no rule";
}
