//! Diagnostic codes of Smith's bracketed 2L-systems (`.smith`, `E097x`,
//! `W097x`).

use super::Code;

codes! { SMITH;
    SMITH_IMAGE_COUNT = "E0970", "not exactly eight images",
"Smith writes a bracketed 2L-system over {0, 1} as the images of the eight
binary triples (left neighbour, symbol, right neighbour) 000, 001, ..., 111
in numeric order, separated by dots. A rule string has exactly seven dots.

Example:
    rules: 0.1[1].1.1.0.11.1       <- seven images

Write all eight (the paper's Table 1 system):
    rules: 0.1[1].1.1.0.11.1.0";

    SMITH_UNBALANCED = "E0971", "unbalanced brackets",
"Brackets enclose a branch, and each image (and the axiom) must close every
branch it opens: a `]` needs a `[` before it in the same image, a `[` a `]`
after it.

Example:
    rules: 0.1[1.1.1.0.11.1.0       <- `[` never closed

Close the branch:
    rules: 0.1[1].1.1.0.11.1.0";

    SMITH_BAD_SYMBOL = "E0972", "symbol other than 0, 1, [ or ]",
"Smith's systems are over the alphabet {0, 1} with the brackets [ and ];
nothing else can appear in an image or in the axiom.

Example:
    rules: 0.1[F].1.1.0.11.1.0       <- F

Use 0 and 1 only:
    rules: 0.1[1].1.1.0.11.1.0";

    SMITH_BAD_AXIOM = "E0973", "bad axiom",
"The axiom is a word over 0, 1, [ and ] with balanced brackets and at least
one 0 or 1 (usually just `1`).

Example:
    axiom:            <- empty

Give a word:
    axiom: 1";

    SMITH_EMPTY_IMAGE = "E0974", "empty image",
"The systems of Hogeweg and Hesper that Smith draws are propagating: no
symbol is erased, so every image has at least one 0 or 1.

Example:
    rules: 0..1.1.0.11.1.0.0       <- the image of 001 is empty

Write the symbol itself to leave it unchanged:
    rules: 0.0.1.1.0.11.1.0.0";

    SMITH_NO_RULES = "E0975", "no rule string",
"A Smith file needs a `rules:` line: the eight images separated by dots.

Example:
    axiom: 1       <- and nothing else

Add the rules:
    rules: 0.1[1].1.1.0.11.1.0";

    SMITH_BAD_VALUE = "E0976", "bad value",
"`generations` is a whole number; `angle`, `roll` and `length` are numbers
(degrees for the angles); `alternate` is yes or no; `leaf` is disc, flower
or none.

Example:
    angle: wide

Give a number:
    angle: 22.5";

    SMITH_UNKNOWN_KEY = "W0970", "unknown key",
"The keys of a Smith file are rules, axiom, generations, angle, alternate,
roll, length and leaf. Any other key is ignored.

Example:
    angel: 30       <- did you mean `angle`?";

    SMITH_DUPLICATE_KEY = "W0971", "key given twice",
"Each key is given once; the last value given is used.

Example:
    axiom: 1
    axiom: 0       <- this one counts";
}
