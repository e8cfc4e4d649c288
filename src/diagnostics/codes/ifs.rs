//! Diagnostic codes of Fractint's IFS libraries (`.ifs`, `E11xx`,
//! `W11xx`).

use super::Code;

codes! { IFS;
    IFS_UNCLOSED_ENTRY = "E1101", "IFS entry not closed with `}`",
"An IFS entry runs from `Name {` to a `}`. Without the `}` Fractint reads
on into the next entry as if its name and numbers were maps of this one,
and rejects the whole (\"invalid IFS definition\"). graftal ends the entry
where the next one starts (or at the end of the file) and reports it, so
the other entries still work.

Example:
    fern {
       0   0    0  .16 0  0 .01
      .85 .04 -.04 .85 0 1.6 .85
                          <- `}` missing
    tree {";

    IFS_OUTSIDE_ENTRY = "E1102", "numbers outside an entry",
"A line of numbers stands outside every entry. Fractint finds an entry by
a line `Name {` and skips every other line outside entries, so these maps
belong to nothing: the `{` after the entry's name is most likely missing
(or a `}` closed the entry too early).

Example:
    fern               <- write `fern {`
      0 0 0 .16 0 0 .01
    }";

    IFS_NOT_A_NUMBER = "E1103", "not a number",
"Every word of a map's line is a number: a decimal such as `0.5`, `.5`,
`-0.04` or `1e-3`. Fractint reads the numbers one after the other with
C's `%f`; words are separated by spaces and tabs, and `;` starts a
comment. A comma, a letter or a number too large for floating point is
not read.

Example:
    .5, 0, 0, .5, 0, 0, .33     <- write `.5 0 0 .5 0 0 .33`";

    IFS_NUMBER_COUNT = "E1104", "wrong count of numbers in a map",
"A map of a 2D entry is one line of 7 numbers `a b c d e f p`:
    x' = a x + b y + e
    y' = c x + d y + f
and p is its probability in the chaos game. An entry marked `(3D)` after
its name has 13 numbers a line, `a b c d e f g h i j k l p`:
    x' = a x + b y + c z + j
    y' = d x + e y + f z + k
    z' = g x + h y + i z + l
A line of 13 numbers in an entry without `(3D)` means the mark is
missing; a line of 7 in a `(3D)` entry, that it is a 2D map.

Example:
    fern {
      .85 .04 -.04 .85 0 1.6      <- the probability is missing: 6 numbers
    }";

    IFS_EMPTY_ENTRY = "E1105", "IFS entry without maps",
"An IFS entry needs at least one map (one line of numbers): Fractint
rejects an empty one (\"Empty IFS definition\"), and an IFS of no maps has
no attractor to draw.

Example:
    fern { }";

    IFS_NOT_CONTRACTIVE = "E1106", "map not contractive",
"Every map of an IFS must shrink: bring any two points closer together.
The attractor is the one figure made of its images under the maps, and it
exists because each map shrinks; a map that stretches some direction by 1
or more (its largest singular value) sends the chaos game's points off or
round in circles, and the IFS has no attractor. graftal reports it as an
error and draws nothing: a picture would show points that belong to no
attractor. The label says how much the map stretches.

Example:
    1.2 0 0 1.2 0 0 .5     <- stretches by 1.2: write .6 0 0 .6 0 0 .5";

    IFS_TOO_MANY_MAPS = "E1107", "more maps than Fractint reads",
"Fractint 19.6 reads at most 64 maps in an entry (\"IFS definition has
too many lines\"); graftal keeps the same limit. An IFS needs few maps:
each map is a shrunken copy of the whole, and 64 copies already make a
detailed figure.";

    IFS_NO_ENTRIES = "E1108", "IFS file without entries",
"An IFS library is a file of entries `Name { … }`, each a list of maps,
one line of numbers each. The file holds no line `Name {`, so there is
nothing to read.

Example:
    fern { 0 0 0 .16 0 0 .01 }   <- one entry on one line";

    IFS_PROBABILITIES = "W1101", "probabilities do not sum to 1",
"The last number of each map is its probability in Fractint's chaos game:
how often the game applies that map. The probabilities of an entry are
not negative and add up to 1 (within 1%). Fractint picks maps by adding
them up, so with a sum below 1 the last map takes what is left, with a
sum above 1 the last maps are picked less often or never, and a map of
probability 0 is never applied (nor any map after it). graftal draws
every map of the IFS whatever its probability (the attractor does not
depend on them), so its picture is the same; Fractint's may not be.

Example:
    .5 0 0 .5 0 0 .5
    .5 0 0 .5 1 0 .3     <- .5 + .3 = .8: write .5 for each";

    IFS_DUPLICATE_ENTRY = "W1102", "two IFS entries with one name",
"Two entries of the file have the same name (case does not matter).
Fractint finds the first one; so does graftal's `FILE:NAME` and
`--entry NAME`: the second is never chosen. Rename one of them.";
}
