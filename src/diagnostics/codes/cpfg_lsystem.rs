//! Diagnostic codes of the cpfg L-system language (`E083x`, `W082x`): the
//! parts of a cpfg `.l` file after preprocessing. The preprocessor and the
//! side files (view, functions, surfaces) have their own codes in
//! `codes/cpfg.rs`.

use super::Code;

codes! { CPFG_LSYSTEM;
    CPFG_UNSUPPORTED = "E0830", "object productions are not supported",
"graftal reads the cpfg dialect of `.l`, but not object productions
(`A -o> …`): cpfg builds them as instanced objects, which graftal does
not have. Missing curves (E0840) have a code of their own. The rest of the file is still checked.

Example:
    A -o> F[+F]F     <- write `A --> F[+F]F`";

    CPFG_SUB_LSYSTEM = "E0839", "a sub-L-system call names no L-system",
"A sub-L-system call `?(n, s)` hands the modules after it, up to the
matching `$`, to the L-system labelled n (`lsystem: n`): its productions
rewrite them and its homomorphism draws them, at s times the size. No
L-system of this file (its own `#include`s counted) has the label the
call names.

Example:
    lsystem: 1
    A --> ?(2, 0.5)B$      <- needs an `lsystem: 2` block with B's productions
    endlsystem";

    CPFG_NO_CURVE = "E0840", "curve not loaded",
"`curveX`, `curveY`, `curveZ` and `curveGAL` read a curve that the view
file loads with a `curve:` line (`curve: profile.con`). Here the view file
loads no curve, or fewer than the one asked for: cpfg has nothing to
read. Name the curve's file on a `curve:` line of the view file.";

    CPFG_NOT_FORMAL = "E0831", "a predecessor parameter must be a name",
"The parameters of a predecessor and of its contexts are formal: names that
take the values of the matched module's parameters. An expression there has
nothing to match.

Example:
    A(x+1) --> B(x)     <- write A(y) : … and compute with y";

    CPFG_UNKNOWN_FUNCTION = "E0832", "unknown function",
"Only cpfg's predefined functions can be called in expressions (manual §5):
sin cos tan asin acos atan atan2 exp log sqrt fabs floor ceil trunc sign
srand ran nran bran biran func curveX curveY curveZ curveGAL printf fprintf
fopen fclose fflush fscanf stop vvXmin … vvZmax SetDerivationLength
GetDerivationLength.";

    CPFG_ARITY = "E0833", "wrong number of arguments",
"A predefined function was called with a number of arguments it does not
take, e.g. `nran(1)` (it takes a mean and a deviation).";

    CPFG_NO_AXIOM = "E0834", "no axiom",
"A cpfg L-system needs an `axiom:` line with at least one module, after
`lsystem:` and before the productions.";

    CPFG_NOT_ARRAY = "E0835", "not an array",
"A name was used with subscripts `[i]` but is not declared as an array in
`define: { array name[size]; }`, or an array was used without subscripts,
or with a different number of them than it was declared with.";

    CPFG_MISPLACED = "E0836", "item out of place",
"cpfg reads an L-system in a fixed order: `lsystem:`, the declarations
(`seed:`, `derivation length:`, `ignore:`/`consider:`, `define:`, the
Start/End blocks), `axiom:`, the productions, then `decomposition` and
`homomorphism` (each with an optional `maximum depth:`), then `endlsystem`.
This item stands where cpfg does not read it.";

    CPFG_NO_LSYSTEM = "E0837", "no `lsystem:`",
"A cpfg file holds its L-system between `lsystem: label` and `endlsystem`.
This file has none, so there is nothing to derive.";

    CPFG_BAD_VALUE = "E0838", "value out of range",
"This value cannot be used where it stands: a derivation length, a maximum
depth or an array size must be a number from 0 up to a limit graftal
states, and an array subscript must lie inside the array.";

    CPFG_UNDEFINED_NAME = "W0820", "name not defined",
"The name is neither a parameter of the production, nor a variable assigned
before it in the production, nor a global variable assigned in a Start,
StartEach, EndEach or End block. cpfg warns and uses 0, and so does graftal.
A misspelt name or a missing `#define` is the usual cause.";

    CPFG_NO_ENVIRONMENT = "W0821", "no environment answers `?E`",
"`?E(…)` modules exchange values with an environment program, named in
the object's `.e` file, that cpfg starts with `-e`. graftal runs the
computations of vlab's honda81, chiba, clover, ecosystem and obcheck
itself; for any other program, or without a `.e` file naming one, nothing
answers: the module keeps the parameters the L-system gave it, and the
model grows as if the environment never answered. The note names the
program the `.e` file gives.";

    CPFG_IO_IGNORED = "W0822", "file and console output not performed",
"`printf`, `fprintf`, `fopen`, `fclose`, `fflush` and `fscanf` read or
write files and the console in cpfg. graftal does not let a model write
files or print into its output: the calls do nothing and return 0.";

    CPFG_NOT_DRAWN = "W0823", "turtle command not drawn",
"graftal understands this turtle command but does not draw it: labels
(`@L`) and L-system-defined surfaces (`@PS`, `@PC`,
`@PD`); or the command has nothing to act on: elasticity modules (`@Ts`,
`@Ti`, `@Td`, `@Tp`, `@Tf`) when the view file sets no tropism, tropisms
past cpfg's ten. The rest of the picture is drawn as cpfg draws it.";

    CPFG_PROBABILITY_IGNORED = "W0824", "probability in a deterministic L-system",
"The production gives a probability (`--> succ : p`) but the L-system has no
`seed:` statement, so it is deterministic and cpfg ignores the probability.
Add `seed: n` after `lsystem:` to make it stochastic.";

    CPFG_STRAY_RETURN = "W0825", "`$` returns from no sub-L-system",
"In cpfg, `$` ends a sub-L-system call `?(n, s)`: the modules after it
belong to the calling L-system again. This file has a single L-system, so
the `$` returns from nothing and cpfg ignores it. A `$` is more often
pfg's and LinF's roll to horizontal, which cpfg writes `@v`.

Example:
    A --> F$F      <- cpfg's roll to horizontal is `@v`: A --> F@vF";

    CPFG_NO_USER_FUNCTION = "W0828", "user function not given",
"`func(id, x)` reads user function `id` (counted from 1) among the
`function:` files the view file names. Here the view file names no
function file, or fewer than `id`: cpfg has no curve to read, and graftal
evaluates the call to 0, which usually draws a different plant. Name the
function's file in the view file (`function: name.func`), beside the `.l`.";

    CPFG_SUBSCRIPT_RANGE = "W0829", "array subscript out of range",
"An array element is read or written with a subscript outside the array:
below 0, or at its size or past it (an array of size 3 has elements 0, 1
and 2). graftal reads such an element as 0 and writes nothing; cpfg reads
or overwrites memory that is not the array's. Subscripts computed at run
time are not checked when the file is read.";

    CPFG_REST_OF_BRANCH = "W0826", "`=` in a right context must be followed by `]`",
"In a right context cpfg's `=` skips the rest of the current branch, up to
the `]` that closes it: `F > [+D=]` matches `F[+DX…]`, whatever follows
`D` in the branch. The module after `=` is matched at that `]`, so
anything but `]` never matches, and cpfg reads past the pattern when `=`
ends it. graftal matches `=]` as cpfg does and reads this context as
never matching. Write `=]` to skip the rest of a branch.";

    CPFG_PARAMETER_COUNT = "W0827", "no production takes this many parameters",
"cpfg rewrites a module only with a production whose predecessor has the
same letter and the same number of parameters. This module's letter has
productions, but none with as many parameters as it is written with here,
so it is never rewritten (nor decomposed, nor drawn by a homomorphism
production) and the plant does not grow from it. cpfg says nothing; it is
usually a parameter left out or added by mistake.

Example:
    axiom: A(1,2)
    A(l) --> F(l) A(l+1)     <- takes one parameter

Write:
    axiom: A(1)";
}
