// The picture: the server's SVG put into #picture, dimmed while the text has
// errors, linked to the text through the `data-src="FROM-TO"` attributes of
// its drawn elements, and turned by dragging when the model is 3D.

/** The {from, to} of an element's data-src, or null. */
function sourceOf(element) {
  const m = /^(\d+)-(\d+)$/.exec(element.getAttribute("data-src") || "");
  return m ? { from: Number(m[1]), to: Number(m[2]) } : null;
}

const within = (inner, outer) => inner.from >= outer.from && inner.to <= outer.to;

/**
 * What the cursor lights up: the production it is in, or the axiom when it
 * is on the axiom's line. `drawn` is the answer that made the picture (its
 * ranges are offsets into the text it was sent; `drawn.mark` carries them to
 * the editor's current text). Returns a range in the sent text, or null.
 */
export function litRange(state, drawn) {
  if (!drawn) return null;
  const head = state.selection.main.head;
  for (const p of drawn.productions) {
    const r = drawn.mark.range(p);
    if (r.from <= head && head <= r.to) return p;
  }
  if (drawn.axiom) {
    const line = state.doc.lineAt(drawn.mark.pos(drawn.axiom.from, 1));
    if (line.from <= head && head <= line.to) return drawn.axiom;
  }
  return null;
}

export class Picture {
  /** hooks: hover(range | null) with the hovered element's data-src; drag(dx, dy, done). */
  constructor(container, badge, hooks) {
    this.container = container;
    this.badge = badge;
    this.hooks = hooks;
    this.hot = null;
    this.lit = null;
    this.rotatable = false;
    this.listen();
  }

  show(svg) {
    this.hot = null;
    this.container.innerHTML = svg;
    this.applyLit();
  }

  setStale(stale) {
    this.container.classList.toggle("stale", stale);
    this.badge.hidden = !stale;
  }

  setRotatable(rotatable) {
    this.rotatable = rotatable;
    this.container.classList.toggle("rotatable", rotatable);
  }

  /** Lights every element drawn by text inside `range` (null: none). */
  light(range) {
    const same = range === this.lit || (range && this.lit && range.from === this.lit.from && range.to === this.lit.to);
    if (same) return;
    this.lit = range;
    this.applyLit();
  }

  applyLit() {
    const range = this.lit;
    for (const element of this.container.querySelectorAll("[data-src]")) {
      const src = range && sourceOf(element);
      element.classList.toggle("lit", Boolean(src && within(src, range)));
    }
  }

  setHot(element) {
    if (element === this.hot) return;
    this.hot?.classList.remove("hot");
    this.hot = element;
    element?.classList.add("hot");
    this.hooks.hover(element ? sourceOf(element) : null);
  }

  listen() {
    const c = this.container;
    c.addEventListener("mouseover", (e) => {
      if (this.dragging) return;
      const element = e.target.closest?.("[data-src]");
      this.setHot(element && c.contains(element) ? element : null);
    });
    c.addEventListener("mouseleave", () => this.setHot(null));
    c.addEventListener("pointerdown", (e) => this.startDrag(e));
  }

  // A drag reports its movement in pixels since it started; the page turns
  // that into azimuth and elevation.
  startDrag(down) {
    if (!this.rotatable || down.button !== 0) return;
    down.preventDefault();
    const c = this.container;
    c.setPointerCapture(down.pointerId);
    this.dragging = true;
    this.setHot(null);
    c.classList.add("dragging");
    const delta = (e) => [e.clientX - down.clientX, e.clientY - down.clientY];
    const move = (e) => this.hooks.drag(...delta(e), false);
    const end = (e) => {
      c.removeEventListener("pointermove", move);
      c.removeEventListener("pointerup", end);
      c.removeEventListener("pointercancel", end);
      c.classList.remove("dragging");
      this.dragging = false;
      this.hooks.drag(...delta(e), true);
    };
    c.addEventListener("pointermove", move);
    c.addEventListener("pointerup", end);
    c.addEventListener("pointercancel", end);
  }
}
