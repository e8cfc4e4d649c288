// The CodeMirror editor: a deliberately small setup (no basicSetup bundle),
// the notation's colouring in a compartment so it can be swapped, lint
// diagnostics pushed from the server's answers, hover tooltips fetched from
// /api/hover, and the `cm-drew` mark that shows which text drew the part of
// the picture under the mouse.

import { defaultKeymap, history, historyKeymap, indentWithTab } from "@codemirror/commands";
import { bracketMatching } from "@codemirror/language";
import { lintGutter, lintKeymap } from "@codemirror/lint";
import { highlightSelectionMatches, searchKeymap } from "@codemirror/search";
import { Compartment, EditorState, StateEffect, StateField } from "@codemirror/state";
import {
  Decoration,
  EditorView,
  drawSelection,
  highlightActiveLine,
  highlightActiveLineGutter,
  hoverTooltip,
  keymap,
  lineNumbers,
} from "@codemirror/view";
import { languageFor, notationHighlighting } from "./languages.js";

const language = new Compartment();

/** Sets (a {from, to} range) or clears (null) the `cm-drew` mark. */
const setDrew = StateEffect.define();
const drewMark = Decoration.mark({ class: "cm-drew" });

const drewField = StateField.define({
  create: () => Decoration.none,
  update(marks, tr) {
    marks = marks.map(tr.changes);
    for (const effect of tr.effects) {
      if (!effect.is(setDrew)) continue;
      const r = effect.value;
      marks = r && r.from < r.to ? Decoration.set([drewMark.range(r.from, r.to)]) : Decoration.none;
    }
    return marks;
  },
  provide: (field) => EditorView.decorations.from(field),
});

/**
 * hooks: onDocChange(update), onSelection(state), hover(view, pos) → a
 * Promise of {dom, from, to} or null, save() for Mod-s.
 */
export function createEditor(parent, { doc, notation, hooks }) {
  const listener = EditorView.updateListener.of((update) => {
    if (update.docChanged) hooks.onDocChange(update);
    if (update.selectionSet || update.docChanged) hooks.onSelection(update.state);
  });
  const hover = hoverTooltip(
    async (view, pos) => {
      const found = await hooks.hover(view, pos);
      if (!found) return null;
      return { pos: found.from, end: found.to, above: true, create: () => ({ dom: found.dom }) };
    },
    { hoverTime: 350 },
  );
  const saveKey = { key: "Mod-s", preventDefault: true, run: () => (hooks.save(), true) };

  return new EditorView({
    parent,
    state: EditorState.create({
      doc,
      extensions: [
        lineNumbers(),
        highlightActiveLineGutter(),
        lintGutter(),
        history(),
        drawSelection(),
        bracketMatching(),
        highlightActiveLine(),
        highlightSelectionMatches(),
        language.of(languageFor(notation)),
        notationHighlighting,
        drewField,
        hover,
        listener,
        keymap.of([saveKey, ...defaultKeymap, ...historyKeymap, ...searchKeymap, ...lintKeymap, indentWithTab]),
        EditorView.theme({ "&": { height: "100%" }, ".cm-scroller": { overflow: "auto" } }),
      ],
    }),
  });
}

export function setNotation(view, notation) {
  view.dispatch({ effects: language.reconfigure(languageFor(notation)) });
}

/** Replaces the whole text as one undoable change. */
export function replaceText(view, text) {
  view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: text } });
}

/** Marks `range` (or nothing, for null) as the text that drew the hovered part. */
export function showDrew(view, range) {
  const effects = [setDrew.of(range)];
  if (range) effects.push(EditorView.scrollIntoView(range.from, { y: "nearest" }));
  view.dispatch({ effects });
}

/** Puts the cursor at `pos`, scrolls there and focuses the editor. */
export function goTo(view, pos) {
  view.dispatch({ selection: { anchor: pos }, scrollIntoView: true });
  view.focus();
}
