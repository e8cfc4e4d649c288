// graftal serve's page: the text on the left, its picture on the right, and
// the server's answers tying them together. This file wires the pieces; each
// piece (editor, diagnostics, picture, growth, draft) lives in its module.

import { ApiError, getJson, postForFile, postJson } from "./api.js";
import { Draft } from "./draft.js";
import { listPlain, showDiagnostics } from "./diagnostics.js";
import { createEditor, replaceText, setNotation, showDrew } from "./editor.js";
import { Growth } from "./growth.js";
import { markdownToHtml } from "./markdown.js";
import { Picture, litRange } from "./picture.js";
import { Tracker } from "./tracker.js";

const $ = (id) => document.getElementById(id);

const UPDATE_DELAY_MS = 300; // wait for a pause in typing before deriving
const DRAG_INTERVAL_MS = 200; // at most one redraw this often while dragging
const DEGREES_PER_PIXEL = 0.5;

// One id per page load: the server keeps one derivation per page and drops
// the older one when a newer seq arrives.
const pageId = `${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 10)}`;

const page = {
  start: null, // /api/start's answer
  view: null, // the EditorView
  draft: null,
  fileText: "", // the text as saved on disk, to know what a draft is
  notation: "pfg",
  seq: 0, // the newest update sent
  applied: 0, // the newest update shown
  checked: null, // the mark of the text the shown diagnostics speak of
  drawn: null, // {seq, mark, productions, axiom} of the answer that drew the picture
  is3d: false,
  view3d: { azimuth: null, elevation: null }, // asked for; null: the server's default
  shownView: null, // the view the server says it drew, when it says
  dragFrom: null, // the view when a drag started
  lastDragSend: 0,
  timer: null,
  translations: 0, // counts translate requests, to drop stale answers
};

const tracker = new Tracker();
let picture;
let growth;

// ---- status line ----

function setStatus(text, kind = "ready") {
  const status = $("status");
  status.textContent = text;
  status.dataset.kind = kind;
}

function showError(err) {
  setStatus(err instanceof ApiError ? err.message : String(err), "error");
  if (!(err instanceof ApiError)) console.error(err);
}

// ---- the request every derivation sends ----

function numberOr(input, fallback) {
  const n = Number.parseInt(input.value, 10);
  return Number.isFinite(n) ? n : fallback;
}

function derivationBody() {
  return {
    page: pageId,
    seq: page.seq,
    text: page.view.state.doc.toString(),
    notation: page.notation,
    steps: $("steps").value.trim() === "" ? null : Math.max(0, numberOr($("steps"), 0)),
    seed: numberOr($("seed"), 0),
    azimuth: page.view3d.azimuth,
    elevation: page.view3d.elevation,
    width: numberOr($("width"), 600),
    height: numberOr($("height"), 600),
  };
}

function schedule(delay = UPDATE_DELAY_MS) {
  clearTimeout(page.timer);
  page.timer = setTimeout(update, delay);
  document.body.dataset.settled = "false";
}

/** Tells a test (or anyone watching) that the newest text has its answer. */
function settleIfNewest(seq) {
  if (seq === page.seq && page.timer === null) document.body.dataset.settled = "true";
}

async function update() {
  clearTimeout(page.timer);
  page.timer = null;
  document.body.dataset.settled = "false";
  page.seq += 1;
  const body = derivationBody();
  const mark = tracker.follow(page.view.state.doc);
  setStatus("updating", "busy");
  try {
    const answer = await postJson("/api/update", body);
    if (answer.superseded || answer.seq < page.applied) {
      tracker.drop(mark);
      settleIfNewest(body.seq);
      return;
    }
    apply(answer, body, mark);
  } catch (err) {
    tracker.drop(mark);
    if (body.seq === page.seq) showError(err);
    settleIfNewest(body.seq);
  }
}

/** A mark no longer needed by what is shown stops following the edits. */
function retire(mark) {
  if (mark && mark !== page.checked && mark !== page.drawn?.mark) tracker.drop(mark);
}

function apply(answer, body, mark) {
  page.applied = answer.seq;
  const oldChecked = page.checked;
  page.checked = mark;
  const diagnostics = answer.diagnostics || [];
  showDiagnostics(page.view, $("diagnostics"), diagnostics, mark);

  if (answer.picture !== null && answer.picture !== undefined) {
    const oldDrawn = page.drawn?.mark;
    page.drawn = { seq: answer.seq, mark, productions: answer.productions || [], axiom: answer.axiom ?? null };
    retire(oldDrawn);
    picture.show(answer.picture);
    picture.setStale(false);
    relight();
    setThreeD(answer);
    $("steps").placeholder = String(answer.steps ?? "");
    if (answer.seq === page.seq) setStatus("ready");
    // While dragging, every step's picture from each new view is wasted work.
    if (!page.dragFrom) loadFrames(body);
  } else {
    picture.setStale(true);
    const first = diagnostics.find((d) => d.severity === "error") || diagnostics[0];
    setStatus(first ? `not drawn: ${first.message}` : "not drawn", "limit");
  }
  retire(oldChecked);
  document.body.dataset.seq = String(answer.seq);
  settleIfNewest(answer.seq);
  translate();
}

async function loadFrames(body) {
  growth.clear();
  document.body.dataset.frames = "0";
  try {
    const answer = await postJson("/api/frames", body);
    // Only the frames of the picture on screen: a newer text may have won.
    if (answer.seq !== page.drawn?.seq || answer.seq !== page.applied) return;
    growth.load(answer.frames, answer.stopped);
    document.body.dataset.frames = String(answer.frames.length);
    document.body.dataset.framesSeq = String(answer.seq);
  } catch (err) {
    if (body.seq === page.applied) $("growth-note").textContent = err.message;
  }
}

// ---- picture ↔ text ----

function relight() {
  picture.light(litRange(page.view.state, page.drawn));
}

function hoverPicture(src) {
  if (!src || !page.drawn) return showDrew(page.view, null);
  showDrew(page.view, page.drawn.mark.range(src));
}

function setThreeD(answer) {
  page.is3d = Boolean(answer.is3d);
  picture.setRotatable(page.is3d);
  // The server may say which view it drew; drags start from there.
  if (typeof answer.azimuth === "number") page.shownView = { azimuth: answer.azimuth, elevation: answer.elevation };
  $("view-row").hidden = !page.is3d;
  const v = page.view3d;
  $("view-label").textContent =
    v.azimuth === null ? "the file's view" : `azimuth ${Math.round(v.azimuth)}°, elevation ${Math.round(v.elevation)}°`;
}

const clamp = (x, lo, hi) => Math.min(hi, Math.max(lo, x));
const wrap = (deg) => ((((deg + 180) % 360) + 360) % 360) - 180;

function drag(dx, dy, done) {
  if (!page.dragFrom) {
    const shown = page.shownView || {};
    page.dragFrom = {
      azimuth: page.view3d.azimuth ?? shown.azimuth ?? 0,
      elevation: page.view3d.elevation ?? shown.elevation ?? 0,
    };
  }
  page.view3d = {
    azimuth: wrap(page.dragFrom.azimuth + dx * DEGREES_PER_PIXEL),
    elevation: clamp(page.dragFrom.elevation + dy * DEGREES_PER_PIXEL, -90, 90),
  };
  const now = performance.now();
  if (done) {
    page.dragFrom = null;
    update();
  } else if (now - page.lastDragSend > DRAG_INTERVAL_MS) {
    page.lastDragSend = now;
    update();
  }
}

// ---- hover tooltips ----

async function hover(view, pos) {
  const doc = view.state.doc;
  let answer;
  try {
    answer = await postJson("/api/hover", { text: doc.toString(), notation: page.notation, offset: pos });
  } catch {
    return null; // a hover that fails shows nothing; the status line is for edits
  }
  if (!answer || view.state.doc !== doc) return null;
  const dom = document.createElement("div");
  dom.className = "hover-doc";
  dom.innerHTML = markdownToHtml(answer.markdown);
  return { dom, from: answer.from ?? pos, to: answer.to ?? pos };
}

// ---- translation ----

async function translate() {
  const to = $("translate-to").value;
  const out = $("translation");
  const list = $("translation-diagnostics");
  const ticket = ++page.translations;
  if (!to) {
    out.textContent = "";
    list.replaceChildren();
    return;
  }
  const body = { text: page.view.state.doc.toString(), notation: page.notation, to };
  try {
    const answer = await postJson("/api/translate", body);
    if (ticket !== page.translations) return;
    out.textContent = answer.text ?? "";
    out.classList.toggle("none", answer.text === null);
    listPlain(list, answer.diagnostics || []);
  } catch (err) {
    if (ticket !== page.translations) return;
    out.textContent = "";
    listPlain(list, [{ code: "error", severity: "error", line: null, message: err.message }]);
  }
}

// ---- saving, exporting, the standard library ----

async function save() {
  if (!page.start.can_save) {
    setStatus("not saved: the server was started without a file", "error");
    return;
  }
  const text = page.view.state.doc.toString();
  try {
    const answer = await postJson("/api/save", { text });
    page.fileText = text;
    page.draft.clear();
    $("draft-note").hidden = true;
    setStatus(`saved ${answer.saved}`);
  } catch (err) {
    showError(err);
  }
}

function baseName() {
  const file = page.start.file || "scratch";
  return file.replace(/^.*[\\/]/, "").replace(/\.[^.]*$/, "") || "graftal";
}

async function download(format) {
  try {
    const body = { ...derivationBody(), format };
    const { blob, name } = await postForFile("/api/export", body, `${baseName()}.${format}`);
    const link = document.createElement("a");
    link.href = URL.createObjectURL(blob);
    link.download = name;
    document.body.append(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 10_000);
  } catch (err) {
    showError(err);
  }
}

async function openStd(name) {
  try {
    const answer = await postJson("/api/std", { name });
    changeNotation(answer.notation, false);
    replaceText(page.view, answer.text);
    schedule(0);
  } catch (err) {
    showError(err);
  }
}

function changeNotation(notation, recheck = true) {
  page.notation = notation;
  $("notation").value = notation;
  setNotation(page.view, notation);
  if (recheck) schedule(0);
}

// ---- start ----

function fillSelect(select, items) {
  for (const [value, label] of items) select.append(new Option(label, value));
}

function restoreDraft(start) {
  const draft = page.draft.read();
  if (draft === null || draft === start.text) return start.text;
  $("draft-note").hidden = false;
  $("draft-discard").addEventListener("click", () => {
    page.draft.clear();
    replaceText(page.view, start.text);
    $("draft-note").hidden = true;
  });
  return draft;
}

function wireControls() {
  $("notation").addEventListener("change", (e) => changeNotation(e.target.value));
  $("std").addEventListener("change", (e) => {
    if (e.target.value) openStd(e.target.value);
    e.target.value = "";
  });
  for (const id of ["steps", "seed", "width", "height"]) $(id).addEventListener("input", () => schedule());
  $("save").addEventListener("click", save);
  for (const button of document.querySelectorAll("button[data-format]")) {
    button.addEventListener("click", () => download(button.dataset.format));
  }
  $("translate-to").addEventListener("change", translate);
  $("view-reset").addEventListener("click", () => {
    page.view3d = { azimuth: null, elevation: null };
    update();
  });
}

async function boot() {
  const start = await getJson("/api/start");
  page.start = start;
  page.fileText = start.text;
  page.notation = start.notation;
  page.draft = new Draft(start.file);
  document.title = `${start.file ?? "scratch"} · graftal`;
  $("file-name").textContent = start.file ?? "(no file)";

  fillSelect($("notation"), start.notations.map((n) => [n.id, n.name]));
  $("notation").value = start.notation;
  fillSelect($("translate-to"), start.notations.map((n) => [n.id, n.name]));
  fillSelect($("std"), start.entries.map((e) => [e, e]));
  $("save").disabled = !start.can_save;
  if (!start.can_save) $("save").title = "the server was started without a file to save to";
  if (start.steps !== null && start.steps !== undefined) $("steps").placeholder = String(start.steps);

  page.view = createEditor($("editor"), {
    doc: restoreDraft(start),
    notation: start.notation,
    hooks: {
      onDocChange(u) {
        tracker.record(u.changes);
        page.draft.keep(u.state.doc.toString(), page.fileText);
        schedule();
      },
      onSelection: () => relight(),
      hover,
      save,
    },
  });
  window.graftalEditor = page.view;

  picture = new Picture($("picture"), $("stale-badge"), { hover: hoverPicture, drag });
  growth = new Growth(
    { slider: $("slider"), play: $("play"), label: $("growth-label"), note: $("growth-note") },
    (svg) => picture.show(svg),
  );
  wireControls();
  update();
}

boot().catch(showError);
