// Colouring for each notation graftal reads: one small stream tokenizer,
// configured per notation with its keywords and comment syntax. It is a
// light heuristic (the server's diagnostics are the real parser); it only
// has to make headers, arrows, symbols and comments easy to tell apart.

import { HighlightStyle, StreamLanguage, syntaxHighlighting } from "@codemirror/language";
import { tags } from "@lezer/highlight";

// keywords: the words that start an item; `atLineStart`: only there (in
// most notations a keyword elsewhere is a run of symbols, e.g. pfg's `axiom`
// is just five letters inside a production). `lineComment`: a string that
// starts a comment to the end of the line; `blockComment`: /* */.
// `digitSymbols`: digits are symbols (pfg's 0 and 1 cells, Smith's 0 and
// 1), numbers only as a header's whole value.
const notations = {
  pfg: {
    keywords: ["derivation length:", "angle factor:", "scale factor:", "axiom:", "ignore:"],
    anyHeader: true,
    atLineStart: true,
    blockComment: true,
    digitSymbols: true,
  },
  cpfg: {
    keywords: [
      "lsystem:", "seed:", "derivation length:", "maximum depth:", "consider:", "ignore:",
      "axiom:", "define:", "ring lsystem", "start:", "end:", "starteach:", "endeach:",
      "homomorphism", "decomposition", "no warnings", "warnings", "endlsystem",
    ],
    caseInsensitive: true,
    anyHeader: true,
    atLineStart: true,
    blockComment: true,
    preprocessor: true,
  },
  fractint: {
    keywords: ["axiom", "angle"],
    caseInsensitive: true,
    atLineStart: true,
    lineComment: ";",
    entryNames: true,
  },
  ifs: { keywords: [], lineComment: ";", entryNames: true },
  linf: {
    keywords: ["lines", "blanks", "angles", "axiom", "rules", "colors"],
    lineComment: "#",
    directive: "#:",
  },
  stl: {
    keywords: ["ANGLE", "B", "L", "GROWTH", "LEVELS", "SEED", "ENDSEED", "LAYOUT", "ENDLAYOUT"],
    atLineStart: true,
    lineComment: "#",
  },
  smith: {
    keywords: [
      "rules:", "axiom:", "generations:", "angle:", "alternate:", "angles:", "roll:",
      "length:", "width:", "leaf:", "leaf-size:", "flower-size:",
    ],
    anyHeader: true,
    atLineStart: true,
    lineComment: "#",
    digitSymbols: true,
  },
  gft: {
    keywords: [
      "turtle", "symbol", "silent", "steps", "angle", "length", "scale", "width-factor",
      "width-step", "widths", "width", "cpfg-polygons", "colour-step", "colours", "colour",
      "view", "seed", "random", "choose", "ignore", "consider", "ring", "cut", "axiom",
      "rotation", "globals", "array", "decomposition", "homomorphism", "label",
      "sub-lsystem", "start-each", "end-each", "start", "end", "function", "tropism", "rule",
      "stems", "outline", "growth", "background", "camera", "lighting", "light", "material",
      "texture", "surface", "backdrop", "contour", "graph",
    ],
    atLineStart: true,
    blockComment: true,
  },
};

function escapeRegExp(text) {
  return text.replace(/[.*+?^${}()|[\]\\]/g, "\\$&");
}

/** One regexp for all of a notation's keywords, longest first. */
function keywordPattern(spec) {
  if (!spec.keywords.length) return null;
  const words = [...spec.keywords].sort((a, b) => b.length - a.length);
  // A keyword that ends in a letter must end a word: `angle` in `angles`.
  const alternatives = words.map((w) => escapeRegExp(w) + (/\w$/.test(w) ? "(?![\\w-])" : ""));
  return new RegExp(`^(?:${alternatives.join("|")})`, spec.caseInsensitive ? "i" : "");
}

function tokenizer(spec) {
  const keyword = keywordPattern(spec);
  return function token(stream, state) {
    if (state.inComment) return blockCommentRest(stream, state);
    if (stream.sol()) {
      state.lineStart = true;
      state.valueNext = false;
    }
    if (stream.eatSpace()) return null;
    const atStart = state.lineStart;
    const atValue = state.valueNext; // the first token after a header
    state.lineStart = false;
    state.valueNext = false;

    if (spec.blockComment && stream.match("/*")) {
      state.inComment = true;
      return blockCommentRest(stream, state);
    }
    if (spec.directive && stream.match(spec.directive)) {
      stream.skipToEnd();
      return "meta";
    }
    if (spec.lineComment && stream.match(spec.lineComment)) {
      stream.skipToEnd();
      return "comment";
    }
    if (spec.preprocessor && atStart && stream.match(/^#\s*\w+/)) return "meta";
    // An unknown header (`angle:` in a pfg file) still reads as a header;
    // the diagnostics say it is wrong.
    const header =
      (keyword && (atStart || !spec.atLineStart) && stream.match(keyword)) ||
      (spec.anyHeader && atStart && stream.match(/^[A-Za-z][A-Za-z ]*[A-Za-z]:/));
    if (header) {
      state.valueNext = true;
      return "keyword";
    }
    if (spec.entryNames && atStart && stream.match(/^[^\s{;]+(?=\s*\{)/)) return "className";
    // Where digits are symbols, a number is a header's whole value
    // (`derivation length: 30`, not the cells of `axiom: F1F1F1`).
    if (spec.digitSymbols) {
      const value = atValue && stream.match(/^\d+(?:\.\d*)?(?=\s*(?:\/\*|#|$))/);
      return value ? "number" : symbolToken(stream, false);
    }
    return symbolToken(stream, true);
  };
}

function blockCommentRest(stream, state) {
  if (stream.skipTo("*/")) {
    stream.pos += 2;
    state.inComment = false;
  } else {
    stream.skipToEnd();
  }
  return "comment";
}

function symbolToken(stream, numbers) {
  if (stream.match(/^(?:-->|->|=>|→)/)) return "definitionOperator";
  if (stream.match(/^"(?:[^"\\]|\\.)*"?/)) return "string";
  if (numbers && (stream.match(/^\d+(?:\.\d*)?(?:[eE][-+]?\d+)?/) || stream.match(/^\.\d+/))) return "number";
  const c = stream.next();
  if (/[[\](){}]/.test(c)) return "bracket";
  if (/[A-Za-z0-9]/.test(c)) return "variableName";
  if (/[-+&^\\/|!~?:<>*=%$@,]/.test(c)) return "operator";
  return null;
}

const cache = new Map();

/** The StreamLanguage for a notation id from /api/start (unknown ids: gft's). */
export function languageFor(id) {
  const key = notations[id] ? id : "gft";
  if (!cache.has(key)) {
    const spec = notations[key];
    cache.set(
      key,
      StreamLanguage.define({
        name: key,
        startState: () => ({ inComment: false, lineStart: true, valueNext: false }),
        copyState: (s) => ({ ...s }),
        token: tokenizer(spec),
        languageData: {
          commentTokens: spec.lineComment
            ? { line: spec.lineComment }
            : { block: { open: "/*", close: "*/" } },
        },
      }),
    );
  }
  return cache.get(key);
}

export const notationHighlighting = syntaxHighlighting(
  HighlightStyle.define([
    { tag: tags.keyword, color: "#7a3e9d", fontWeight: "600" },
    { tag: tags.comment, color: "#7a7a7a", fontStyle: "italic" },
    { tag: tags.meta, color: "#8a6d00" },
    { tag: tags.definitionOperator, color: "#b3261e", fontWeight: "600" },
    { tag: tags.operator, color: "#1f6fb2" },
    { tag: tags.number, color: "#0b7a5a" },
    { tag: tags.string, color: "#0b7a5a" },
    { tag: tags.bracket, color: "#8a6d00" },
    { tag: tags.className, color: "#b3261e", fontWeight: "600" },
    { tag: tags.variableName, color: "#1b1b1b" },
  ]),
);
