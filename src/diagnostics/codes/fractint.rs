//! Diagnostic codes of the Fractint front end (`E07xx`, `W07xx`).

use super::Code;

codes! { FRACTINT;
    FR_UNCLOSED_ENTRY = "E0701", "entry not closed with `}`",
"A Fractint entry runs from `Name {` to a line that starts with `}`.
Without the `}` Fractint reads on into the next entries as if they were
lines of this one. graftal ends the entry where the next one starts (or at
the end of the file) and reports it, so the other entries still work.

Example:
    Koch1 {
      Angle 6
      Axiom F--F--F
      F=F+F--F+F
                    <- `}` missing
    Dragon {";

    FR_NO_AXIOM = "E0702", "no axiom",
"Every entry needs a line `Axiom STRING` (Fractint: \"Error: no axiom\").
The string is the word the derivation starts from; it cannot contain
spaces.

Example:
    Koch1 {
      Angle 6
      F=F+F--F+F      <- add `Axiom F--F--F`
    }";

    FR_BAD_ANGLE = "E0703", "missing or illegal angle",
"`Angle n` divides the full turn into n increments: `+` and `-` turn by
360/n degrees. Fractint accepts whole numbers from 3 to 50 (its sine and
cosine tables have 50 slots) and rejects an entry without an angle
(\"illegal or missing angle\").

Example:
    Angle 2         <- at least 3
    Angle 90        <- not degrees: for 90 degrees write `Angle 4`";

    FR_UNKNOWN_KEYWORD = "E0704", "unknown keyword or rule head",
"A line of an entry is `Angle n`, `Axiom STRING`, a rule `x=STRING` for one
character x, or the closing `}`. Anything else is a syntax error in
Fractint. Rule heads are single characters: a rule rewrites one command.

Example:
    Axoim F         <- did you mean `Axiom`?
    xy=F+F          <- a rule head is one character";

    FR_EXTRA_TEXT = "E0705", "extra text after a command",
"Fractint reads one string after `Axiom`, `Angle` or a rule head; the string
ends at the first space. Anything after it is an error (\"Extra text after
command\"). Strings cannot contain spaces, and a rule has no space between
`=` and its body.

Example:
    x = -FX         <- the body is `=`, then `-FX` is extra: write `x=-FX`
    Axiom F F       <- write `Axiom FF`";

    FR_UNKNOWN_ENTRY = "E0706", "no entry of that name",
"The entry chosen with `FILE:NAME` or `--entry NAME` is not in the file.
Names are compared without regard to case, as Fractint does. `graftal
check FILE` lists the entries.";

    FR_CHOOSE_ENTRY = "E0707", "choose an entry",
"A Fractint file is a library of entries, and derive, render, stats and
translate work on one of them. Choose it with `FILE:NAME` or `--entry
NAME` (the name's case does not matter). `graftal check FILE` checks every
entry and lists them.

Example:
    graftal render fractint.l:Dragon -n 10 -o dragon.png";

    FR_RESERVED_RULE = "W0701", "rule for a reserved symbol",
"`+ - / \\ @ | ! c < > [ ]` are Fractint's commands and reserved: Fractint
19 rejects a rule for one of them (\"Redefined reserved symbol\"). Fractint
16 and earlier accepted it, and old files use it (`<=` in SnowflakeColor of
version 15 and 16). graftal reads it as Fractint 16 did: the rule rewrites
every command that starts with that character (`<=` deletes every `<n`).";

    FR_UNBALANCED = "W0702", "unbalanced brackets in a string",
"Fractint draws a derived word by expanding each rule body recursively: a
`]` ends the body it is in and a `[` without its `]` reads past the end of
its body. So Fractint's picture differs from the derived word's unless
every axiom and rule body has balanced brackets. graftal derives the word
as written.

Example:
    x=f[+x          <- write x=f[+x]";

    FR_DUPLICATE_ENTRY = "W0703", "two entries with one name",
"Two entries of the file have the same name (case does not matter).
Fractint finds the first one; so does graftal's `FILE:NAME`.";

    FR_LONG_LINE = "W0704", "line too long for Fractint",
"Fractint reads lines of up to 159 characters: it cuts a longer line there
and reads the rest as the next line, which then usually makes no sense.
graftal reads the whole line. Split a long rule into several rules for the
same character: their strings are concatenated.

Example:
    F=F+F-F ... (200 characters)
Write:
    F=F+F-F ... (the first half)
    F=... (the second half)";
}
