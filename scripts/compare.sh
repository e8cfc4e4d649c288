#!/usr/bin/env bash
# compare.sh: show that two builds of graftal print the same output over the
# whole standard library and the Fractint and cpfg corpora, e.g. before and
# after a big refactoring.
#
# Usage:
#   scripts/compare.sh BASE_REV [NEW_REV]
#       Builds BASE_REV (and NEW_REV; default: this checkout's working tree
#       as it is, uncommitted changes included) in release mode and compares.
#       A revision is built from a temporary `git worktree` with its own
#       CARGO_TARGET_DIR, $CACHE/<commit>, and reused on the next run.
#   BASE_BIN=/path/graftal NEW_BIN=/path/graftal scripts/compare.sh
#       Compares two prebuilt binaries (either one may be given alone, the
#       other then comes from BASE_REV / NEW_REV).
#
# Environment:
#   CORPUS   corpus root holding fractint/ and cpfg/ (default: tests/corpus
#            of this checkout, else ../shared/corpus beside it)
#   CACHE    builds and run results (default: ${TMPDIR:-/tmp}/graftal-compare)
#   JOBS     commands run at a time (default 2)
#   TIMEOUT  seconds per command (default 20)
#   ONLY     a bash pattern: compare only the cases matching it, e.g.
#            ONLY='std:*' or ONLY='*penrose*' (to look again at a difference)
#   STATS_ADDED  members of `stats --format json` that the newer build adds
#            on purpose, left out of the comparison (default: derivation;
#            empty to compare them too)
#
# What is compared, for each case (std:NAME from `graftal list`, each entry
# FILE:NAME of each Fractint library as `graftal check FILE` lists it, the
# main .l file of each cpfg object folder) and each binary:
#   derive CASE | stats CASE --format json (the timing object "time" removed)
#   | render CASE -o OUT.svg (the SVG file) | render CASE --size 256x256
#   -o OUT.png (the PNG file) | render CASE -o OUT.obj (the OBJ file)
#   | translate CASE --to pfg|linf|stl, each also with --lossy.
# plus `list` and `check FILE` of each Fractint library, which enumerate the
# cases. Each run gives one manifest line per binary: case, command, exit
# status (or `timeout`), sha256 of stdout, of stderr, of the output file.
# Defaults (seed 0, steps, size) are used, with the same arguments for both.
# Commands run in the corpus root with case paths relative to it, so both
# binaries' diagnostics name the same files. Two runs that both time out
# count as identical.
#
# Prints the number of cases per source, of runs compared, identical and
# different, and each difference; the outputs of a differing run are kept
# under $CACHE/runs/<run>/diffs/. Exit status 0 when everything is identical,
# 1 when something differs, 2 on a usage or build problem.
#
# Needs bash, coreutils, xargs, git and python3 (and cargo to build).

set -euo pipefail

# The header comment above is the help text.
usage() {
    local line
    while IFS= read -r line && [[ $line == '#'* ]]; do
        if [[ $line != '#!'* ]]; then echo "${line#'#'}" | cut -c 2-; fi
    done <"$0" >&2
    exit 2
}

start_time=$(date +%s)
SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(git -C "$SCRIPT_DIR" rev-parse --show-toplevel)
CACHE=${CACHE:-${TMPDIR:-/tmp}/graftal-compare}
JOBS=${JOBS:-2}
TIMEOUT=${TIMEOUT:-20}
mkdir -p "$CACHE"
CACHE=$(cd "$CACHE" && pwd)

case "${1:-}" in -h | --help) usage ;; esac
[[ $# -le 2 ]] || usage
BASE_REV=${1:-}
NEW_REV=${2:-}
if [[ -z ${BASE_BIN:-} && -z $BASE_REV ]]; then
    echo "compare.sh: give BASE_REV, or BASE_BIN and NEW_BIN" >&2
    usage
fi

# --- Building ---------------------------------------------------------------

# A temporary worktree to remove if the script stops half-way.
TMP_WORKTREE=
RUN_DIR=
cleanup() {
    if [[ -n $TMP_WORKTREE ]]; then
        git -C "$REPO" worktree remove --force "$TMP_WORKTREE" 2>/dev/null || true
        git -C "$REPO" worktree prune 2>/dev/null || true
    fi
    # Scratch files of the runs; manifests and kept diffs stay.
    if [[ -n $RUN_DIR ]]; then rm -rf "$RUN_DIR/scratch"; fi
}
trap cleanup EXIT

# build_rev REV: sets BUILT_BIN to a release binary of commit REV. Built in
# a detached worktree so that this checkout is not touched, into
# $CACHE/<commit> so that a second run (or the other side naming the same
# commit) reuses it. The `.built` stamp is written only after a successful
# build, so an interrupted build is redone (incrementally) next time.
# (Called directly, not in $(...), so that the EXIT trap sees TMP_WORKTREE.)
BUILT_BIN=
build_rev() {
    local commit target
    commit=$(git -C "$REPO" rev-parse --verify --quiet "$1^{commit}") || {
        echo "compare.sh: \`$1\` is not a commit" >&2
        exit 2
    }
    target=$CACHE/$commit
    if [[ -f $target/.built && -x $target/release/graftal ]]; then
        echo "reusing the build of $1 ($commit)" >&2
    else
        echo "building $1 ($commit) in release mode into $target" >&2
        TMP_WORKTREE=$CACHE/src-$commit-$$
        git -C "$REPO" worktree add --detach --quiet "$TMP_WORKTREE" "$commit" >&2
        (cd "$TMP_WORKTREE" && CARGO_TARGET_DIR=$target cargo build --release --quiet >&2) || {
            echo "compare.sh: building $1 failed" >&2
            exit 2
        }
        touch "$target/.built"
        git -C "$REPO" worktree remove --force "$TMP_WORKTREE"
        TMP_WORKTREE=
    fi
    BUILT_BIN=$target/release/graftal
}

# build_worktree: the working tree of this checkout, as it is. Its own target
# dir (named after the checkout's path) keeps the cargo build of the
# checkout itself untouched; cargo decides what is fresh.
build_worktree() {
    local target
    target=$CACHE/worktree-$(printf '%s' "$REPO" | sha256sum | cut -c1-12)
    echo "building the working tree of $REPO in release mode into $target" >&2
    (cd "$REPO" && CARGO_TARGET_DIR=$target cargo build --release --quiet >&2) || {
        echo "compare.sh: building the working tree failed" >&2
        exit 2
    }
    BUILT_BIN=$target/release/graftal
}

# One build at a time: the machine's cores are shared.
if [[ -z ${BASE_BIN:-} ]]; then
    build_rev "$BASE_REV"
    BASE_BIN=$BUILT_BIN
fi
if [[ -z ${NEW_BIN:-} ]]; then
    if [[ -n $NEW_REV ]]; then build_rev "$NEW_REV"; else build_worktree; fi
    NEW_BIN=$BUILT_BIN
fi
for b in "$BASE_BIN" "$NEW_BIN"; do
    [[ -x $b ]] || { echo "compare.sh: no executable $b" >&2; exit 2; }
done
# Absolute paths: the runs happen in the corpus directory.
BASE_BIN=$(cd "$(dirname "$BASE_BIN")" && pwd)/$(basename "$BASE_BIN")
NEW_BIN=$(cd "$(dirname "$NEW_BIN")" && pwd)/$(basename "$NEW_BIN")

# --- The corpus and the cases --------------------------------------------------

# tests/corpus is being filled in; until it exists the shared copy is used.
if [[ -n ${CORPUS:-} ]]; then
    :
elif [[ -d $REPO/tests/corpus ]]; then
    CORPUS=$REPO/tests/corpus
else
    CORPUS=$REPO/../shared/corpus
fi
[[ -d $CORPUS ]] || { echo "compare.sh: no corpus at $CORPUS" >&2; exit 2; }
CORPUS=$(cd "$CORPUS" && pwd)
for d in fractint cpfg; do
    [[ -d $CORPUS/$d ]] || echo "compare.sh: warning: no $CORPUS/$d, its cases are skipped" >&2
done

RUN_DIR=$CACHE/runs/$(date +%Y%m%d-%H%M%S)-$$
mkdir -p "$RUN_DIR/scratch"
echo "base: $BASE_BIN" >&2
echo "new:  $NEW_BIN" >&2
echo "corpus: $CORPUS" >&2
echo "results: $RUN_DIR" >&2

# Every command runs in the corpus root with case paths relative to it, so
# both binaries see the same file names (and diagnostics name files the same
# way wherever the corpus lives). Standard input is empty so nothing waits.
cd "$CORPUS"

# The cases of each source, enumerated with both binaries (union, first
# seen order): a case only one of them lists still gets compared, and the
# listings themselves are compared as the `list` and `check` runs.
stdlib_cases() {
    local line
    while IFS= read -r line; do
        # `list` prints the name, then the figure and whether it draws.
        if [[ $line == std:* ]]; then echo "${line%%[[:space:]]*}"; fi
    done < <("$1" list </dev/null || true)
}

# The Fractint libraries: the .l files and the older releases in history/
# (fractint.l.v15.0 ...), which tests/it/fractint.rs also reads as Fractint.
shopt -s nullglob
fractint_files() {
    local f
    for f in fractint/*.l fractint/history/*.l.v*; do
        if [[ -f $f ]]; then echo "$f"; fi
    done | LC_ALL=C sort
}

# `check FILE` prints "FILE: dialect: Fractint, N entries (...)", then each
# entry as "  NAME<padding>  line N  STATE". The count in the header is
# checked so that a change of this format cannot silently drop cases.
fractint_cases() {
    local bin=$1 f line expected found
    fractint_files | while IFS= read -r f; do
        expected=0 found=0
        while IFS= read -r line; do
            if [[ $line =~ dialect:\ Fractint,\ ([0-9]+)\ entr ]]; then
                expected=${BASH_REMATCH[1]}
            elif [[ $line =~ ^\ \ (.*[^ ])\ +line\ [0-9]+\  ]]; then
                printf '%s:%s\n' "$f" "${BASH_REMATCH[1]}"
                found=$((found + 1))
            fi
        done < <("$bin" check "$f" </dev/null 2>/dev/null || true)
        if [[ $found != "$expected" || $found == 0 ]]; then
            echo "compare.sh: warning: $bin check $f: listed $found entries, header says $expected" >&2
        fi
    done
}

# The L-system of a cpfg object, as tests/it/cpfg.rs `main_l` picks it: the
# first .l word on a line of `specifications` starting with `cpfg`, else the
# first .l file by name. (\r counts as white space, as in Rust's
# split_whitespace.)
cpfg_main_l() {
    local dir=$1 w
    local -a words
    if [[ -f $dir/specifications ]]; then
        while IFS=$' \t\r' read -r -a words; do
            [[ ${words[0]:-} == cpfg ]] || continue
            for w in "${words[@]:1}"; do
                if [[ $w == *.l ]]; then
                    echo "$dir/$w"
                    return
                fi
            done
        done <"$dir/specifications"
    fi
    local ls=("$dir"/*.l)
    if [[ ${#ls[@]} -gt 0 ]]; then printf '%s\n' "${ls[@]}" | LC_ALL=C sort | head -n 1; fi
}

cpfg_cases() {
    local dir l
    for dir in cpfg/*/; do echo "${dir%/}"; done | LC_ALL=C sort | while IFS= read -r dir; do
        l=$(cpfg_main_l "$dir")
        if [[ -n $l ]]; then echo "$l"; else echo "compare.sh: warning: no .l file in $dir" >&2; fi
    done
}

# Lines without repeats, in first-seen order (numbered, unique, renumbered).
union() { cat -n | LC_ALL=C sort -t $'\t' -k 2 -u | sort -n | cut -f 2-; }

{ stdlib_cases "$BASE_BIN"; stdlib_cases "$NEW_BIN"; } | union >"$RUN_DIR/cases-stdlib"
{ fractint_cases "$BASE_BIN"; fractint_cases "$NEW_BIN"; } | union >"$RUN_DIR/cases-fractint"
cpfg_cases >"$RUN_DIR/cases-cpfg"

# The commands run on every case.
COMMANDS=(derive stats-json render-svg render-png render-obj
    translate-pfg translate-pfg-lossy translate-linf translate-linf-lossy
    translate-stl translate-stl-lossy)

# ONLY narrows the cases, to look again at a few quickly.
if [[ -n ${ONLY:-} ]]; then
    for src in stdlib fractint cpfg; do
        while IFS= read -r c; do
            if [[ $c == $ONLY ]]; then echo "$c"; fi
        done <"$RUN_DIR/cases-$src" >"$RUN_DIR/cases-$src.only"
        mv "$RUN_DIR/cases-$src.only" "$RUN_DIR/cases-$src"
    done
fi

# The job list, one "CASE<TAB>COMMAND" a line; the listing runs first.
{
    printf 'std:*\tlist\n'
    fractint_files | while IFS= read -r f; do printf '%s\tcheck\n' "$f"; done
    cat "$RUN_DIR/cases-stdlib" "$RUN_DIR/cases-fractint" "$RUN_DIR/cases-cpfg" |
        while IFS= read -r c; do
            for cmd in "${COMMANDS[@]}"; do printf '%s\t%s\n' "$c" "$cmd"; done
        done
} >"$RUN_DIR/jobs"

# --- Running ---------------------------------------------------------------------

# run_one BIN CASE COMMAND SCRATCH [KEEP]: runs one command of one binary and
# prints "STATUS<TAB>SHA(stdout)<TAB>SHA(stderr)<TAB>SHA(output file)".
# stdout is hashed as it streams (derived words can be huge) unless KEEP, a
# path prefix, asks to save the outputs. A missing output file hashes as "-".
run_one() {
    local bin=$1 case=$2 cmd=$3 scr=$4 keep=${5:-}
    local out=$scr/out.svg filter=cat target
    local -a args
    case $cmd in
        list) args=(list) ;;
        check) args=(check "$case") ;;
        derive) args=(derive "$case") ;;
        stats-json) args=(stats "$case" --format json) filter=strip_time ;;
        render-svg) args=(render "$case" -o "$out") ;;
        render-png) out=$scr/out.png && args=(render "$case" --size 256x256 -o "$out") ;;
        render-obj) out=$scr/out.obj && args=(render "$case" -o "$out") ;;
        translate-*-lossy) target=${cmd#translate-} && args=(translate "$case" --to "${target%-lossy}" --lossy) ;;
        translate-*) args=(translate "$case" --to "${cmd#translate-}") ;;
        *) echo "compare.sh: unknown command $cmd" >&2; return 1 ;;
    esac
    rm -f "$out"
    local ps
    set +e
    if [[ -n $keep ]]; then
        timeout -k 5 "$TIMEOUT" "$bin" "${args[@]}" </dev/null 2>"$scr/err" | $filter >"$keep.stdout"
        ps=("${PIPESTATUS[@]}")
        sha256sum <"$keep.stdout" >"$scr/out.sha"
    else
        timeout -k 5 "$TIMEOUT" "$bin" "${args[@]}" </dev/null 2>"$scr/err" | $filter | sha256sum >"$scr/out.sha"
        ps=("${PIPESTATUS[@]}")
    fi
    set -e
    local status=${ps[0]}
    # 124: timeout stopped the command (graftal does not catch SIGTERM).
    if [[ $status == 124 ]]; then status=timeout; fi
    if [[ ${ps[1]} != 0 || ${ps[2]:-0} != 0 ]]; then
        echo "compare.sh: hashing the output of $cmd $case failed" >&2
        return 1
    fi
    # The output path is the same for both binaries, but naming it <OUT>
    # keeps manifests comparable across runs.
    if [[ -s $scr/err && $(<"$scr/err") == *"$scr"* ]]; then
        python3 -c 'import sys; p = sys.argv[1]; d = open(sys.argv[2], "rb").read()
sys.stdout.buffer.write(d.replace(p.encode(), b"<OUT>"))' "$scr" "$scr/err" >"$scr/err.n"
        mv "$scr/err.n" "$scr/err"
    fi
    local h_out h_err h_file=-
    h_out=$(cut -d' ' -f1 "$scr/out.sha")
    h_err=$(sha256sum <"$scr/err" | cut -d' ' -f1)
    if [[ -f $out ]]; then h_file=$(sha256sum <"$out" | cut -d' ' -f1); fi
    if [[ -n $keep ]]; then
        cp "$scr/err" "$keep.stderr"
        if [[ -f $out ]]; then cp "$out" "$keep.out.${out##*.}"; fi
        echo "$status" >"$keep.status"
    fi
    rm -f "$out" "$scr/out.mtl" "$scr/err" "$scr/out.sha"
    printf '%s\t%s\t%s\t%s\n' "$status" "$h_out" "$h_err" "$h_file"
}

# `stats --format json` prints one JSON object whose "time" object holds
# wall-clock timings, different on every run: remove exactly that member
# from the text and keep every other byte as printed (re-serialising would
# hide formatting changes). Anything else (an error, no JSON) passes as is.
# Members a change adds on purpose are removed too when STATS_ADDED names
# them (default "derivation", the evaluation method added by the redesign;
# its value is checked by the tests, not here).
strip_time() {
    python3 -c '
import json, os, re, sys
data = sys.stdin.buffer.read()
try:
    text = data.decode()
    doc = json.loads(text)
    out = text
    members = [("time", r"\{[^{}]*\}")]
    members += [(k, r"\"[^\"]*\"") for k in os.environ.get("STATS_ADDED", "").split()]
    for key, value in members:
        if key not in doc:
            continue
        member = "\"" + key + "\":" + value
        new = re.sub("," + member, "", out, count=1)
        if new == out:
            new = re.sub(member + ",?", "", out, count=1)
        out = new
        doc.pop(key)
    if json.loads(out) != doc:
        raise ValueError
    sys.stdout.buffer.write(out.encode())
except Exception:
    sys.stdout.buffer.write(data)
'
}

# run_job "CASE<TAB>COMMAND": both binaries, one after the other, with the
# same scratch path so that paths in their output are equal. Prints the two
# manifest lines, "base|new<TAB>CASE<TAB>COMMAND<TAB>STATUS<TAB>...", in one
# write so that parallel jobs' lines do not interleave.
run_job() {
    set -euo pipefail
    local case=${1%%$'\t'*} cmd=${1#*$'\t'} scr b n
    scr=$(mktemp -d "$RUN_DIR/scratch/job.XXXXXX")
    b=$(run_one "$BASE_BIN" "$case" "$cmd" "$scr")
    n=$(run_one "$NEW_BIN" "$case" "$cmd" "$scr")
    # A run may leave side files (a mesh's material, its textures).
    rm -rf "$scr"
    printf 'base\t%s\t%s\t%s\nnew\t%s\t%s\t%s\n' "$case" "$cmd" "$b" "$case" "$cmd" "$n"
}

STATS_ADDED=${STATS_ADDED-derivation}
export BASE_BIN NEW_BIN RUN_DIR TIMEOUT STATS_ADDED
export -f run_one run_job strip_time

total_jobs=$(wc -l <"$RUN_DIR/jobs")
echo "running $total_jobs commands on each binary, $JOBS at a time, ${TIMEOUT}s each at most" >&2
xargs -P "$JOBS" -d '\n' -n 1 bash -c 'run_job "$1"' _ <"$RUN_DIR/jobs" >"$RUN_DIR/manifest"

# --- Comparing ---------------------------------------------------------------------

# Splits the manifest into base.tsv and new.tsv (sorted, one line a run),
# writes the differing runs ("CASE<TAB>COMMAND<TAB>WHAT") to diffs.tsv and
# prints the counts.
python3 - "$RUN_DIR" <<'EOF'
import sys
run = sys.argv[1]

sides = {"base": {}, "new": {}}
for line in open(f"{run}/manifest", encoding="utf-8"):
    side, case, cmd, *fields = line.rstrip("\n").split("\t")
    sides[side][(case, cmd)] = fields
for side, rows in sides.items():
    with open(f"{run}/{side}.tsv", "w", encoding="utf-8") as f:
        for key in sorted(rows):
            f.write("\t".join([*key, *rows[key]]) + "\n")

def lines(name):
    return [l.rstrip("\n") for l in open(f"{run}/{name}", encoding="utf-8") if l.strip()]

base, new = sides["base"], sides["new"]
jobs = [tuple(l.split("\t")) for l in lines("jobs")]
what = ["status", "stdout", "stderr", "output"]
diffs = []
timeouts = 0
for key in jobs:
    b, n = base.get(key), new.get(key)
    if b is None or n is None:
        diffs.append((key, ["missing " + ("base" if b is None else "new")]))
        continue
    # Two runs that both time out are equal whatever they printed first.
    if b[0] == n[0] == "timeout":
        timeouts += 1
        continue
    differ = [w for w, x, y in zip(what, b, n) if x != y]
    if differ:
        diffs.append((key, differ))

counts = {s: len(lines(f"cases-{s}")) for s in ("stdlib", "fractint", "cpfg")}
print(f"cases: stdlib {counts['stdlib']}, fractint {counts['fractint']}, cpfg {counts['cpfg']}"
      f" ({sum(counts.values())} in all; plus {sum(1 for j in jobs if j[1] in ('list', 'check'))} listing runs)")
print(f"runs compared: {len(jobs)} (each on both binaries)")
print(f"identical: {len(jobs) - len(diffs)}" + (f" ({timeouts} of them timed out in both)" if timeouts else ""))
print(f"different: {len(diffs)}")
with open(f"{run}/diffs.tsv", "w", encoding="utf-8") as f:
    for (case, cmd), differ in diffs:
        f.write(f"{case}\t{cmd}\t{', '.join(differ)}\n")
EOF

# Each difference, with both runs' outputs saved for inspection: the command
# is run again on each binary, keeping its stdout, stderr, SVG and status.
status=0
if [[ -s $RUN_DIR/diffs.tsv ]]; then
    status=1
    echo "differences (outputs kept in $RUN_DIR/diffs/):"
    mkdir -p "$RUN_DIR/diffs"
    while IFS=$'\t' read -r case cmd differ; do
        # A file name for the case: its path with / and : made plain.
        dir=$RUN_DIR/diffs/$(printf '%s' "$case" | tr '/: ' '___')/$cmd
        mkdir -p "$dir"
        scr=$(mktemp -d "$RUN_DIR/scratch/keep.XXXXXX")
        b=$(run_one "$BASE_BIN" "$case" "$cmd" "$scr" "$dir/base")
        n=$(run_one "$NEW_BIN" "$case" "$cmd" "$scr" "$dir/new")
        rmdir "$scr"
        note=
        # Said when a second run no longer differs: the output is not
        # deterministic, which matters as much as a change.
        if [[ $b == "$n" || ($b == timeout* && $n == timeout*) ]]; then note=" (identical when run again: not deterministic?)"; fi
        printf '  %s  %s: %s differ%s\n' "$case" "$cmd" "$differ" "$note"
    done <"$RUN_DIR/diffs.tsv"
fi

echo "wall time: $(($(date +%s) - start_time)) s"
exit "$status"
