// The server's diagnostics, shown twice: as lint underlines in the editor
// (with their fixes as lint actions) and as the list under the editor, where
// a click goes to the place and a button applies a fix.

import { setDiagnostics } from "@codemirror/lint";
import { goTo } from "./editor.js";

// Our severities → @codemirror/lint's.
const lintSeverity = { error: "error", warning: "warning", note: "info", help: "hint" };

/** The fix's edits, carried through what was typed since, as one transaction. */
export function applyFix(view, fix, mark) {
  const changes = fix.edits.map((e) => {
    const r = mark.range(e);
    return { from: r.from, to: r.to, insert: e.insert };
  });
  view.dispatch({ changes, userEvent: "input.fix", scrollIntoView: true });
  view.focus();
}

function explanation(d) {
  const dom = document.createElement("div");
  dom.className = "lint-message";
  const lines = [
    [`${d.code}: ${d.message}`, "msg"],
    ...(d.help || []).map((h) => [`help: ${h}`, "help"]),
    ...(d.notes || []).map((n) => [`note: ${n}`, "note"]),
  ];
  for (const [text, kind] of lines) {
    const line = document.createElement("div");
    line.className = kind;
    line.textContent = text;
    dom.append(line);
  }
  return dom;
}

// A diagnostic about the whole file (no entries at all, say) may come
// without a place; it is shown at the start.
const placeOf = (d) => ({ from: d.from ?? 0, to: d.to ?? d.from ?? 0 });

function toLint(view, d, mark) {
  const length = view.state.doc.length;
  const r = mark.range(placeOf(d));
  return {
    from: Math.min(r.from, length),
    to: Math.min(r.to, length),
    severity: lintSeverity[d.severity] || "info",
    source: d.code,
    message: `${d.code}: ${d.message}`,
    renderMessage: () => explanation(d),
    actions: (d.fixes || []).map((fix) => ({
      name: fix.title,
      apply: (v) => applyFix(v, fix, mark),
    })),
  };
}

function listItem(view, d, mark) {
  const li = document.createElement("li");
  li.className = `diag ${d.severity}`;
  li.dataset.code = d.code;
  if (d.line != null) li.dataset.line = String(d.line);
  li.tabIndex = 0;

  const head = document.createElement("div");
  head.className = "head";
  const code = document.createElement("span");
  code.className = "code";
  code.textContent = d.code;
  const where = document.createElement("span");
  where.className = "where";
  where.textContent = d.line != null ? `line ${d.line}` : "";
  const message = document.createElement("span");
  message.className = "message";
  message.textContent = d.message;
  head.append(code, where, message);
  li.append(head);

  for (const [prefix, texts] of [["help", d.help], ["note", d.notes]]) {
    for (const text of texts || []) {
      const line = document.createElement("div");
      line.className = prefix;
      line.textContent = `${prefix}: ${text}`;
      li.append(line);
    }
  }
  for (const fix of d.fixes || []) {
    const button = document.createElement("button");
    button.className = "fix";
    button.type = "button";
    button.textContent = fix.title;
    button.addEventListener("click", (event) => {
      event.stopPropagation();
      applyFix(view, fix, mark);
    });
    li.append(button);
  }
  const go = () => goTo(view, Math.min(mark.range(placeOf(d)).from, view.state.doc.length));
  li.addEventListener("click", go);
  li.addEventListener("keydown", (e) => e.key === "Enter" && e.target === li && go());
  return li;
}

/** Shows `diagnostics` (positions in the text `mark` follows) in the editor and in `list`. */
export function showDiagnostics(view, list, diagnostics, mark) {
  view.dispatch(setDiagnostics(view.state, diagnostics.map((d) => toLint(view, d, mark))));
  list.replaceChildren(...diagnostics.map((d) => listItem(view, d, mark)));
  list.classList.toggle("empty", diagnostics.length === 0);
}

/** A plain list (the translation's diagnostics): nothing to click there. */
export function listPlain(list, diagnostics) {
  list.replaceChildren(
    ...diagnostics.map((d) => {
      const li = document.createElement("li");
      li.className = `diag ${d.severity}`;
      li.dataset.code = d.code;
      if (d.line != null) li.dataset.line = String(d.line);
      li.textContent = d.line != null ? `${d.code} line ${d.line}: ${d.message}` : `${d.code}: ${d.message}`;
      return li;
    }),
  );
}
