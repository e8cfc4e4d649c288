// Growth: every step 0..N of the derivation, fetched at once from
// /api/frames, so the slider and Play swap pictures without asking again.

const FRAME_MS = 250; // about 4 frames a second

export class Growth {
  /** els: slider, play, label, note; showFrame(svg) draws one frame. */
  constructor(els, showFrame) {
    this.els = els;
    this.showFrame = showFrame;
    this.frames = [];
    this.timer = null;
    els.slider.addEventListener("input", () => {
      this.pause();
      this.go(Number(els.slider.value));
    });
    els.play.addEventListener("click", () => (this.timer ? this.pause() : this.play()));
    this.clear();
  }

  /** While new frames are on their way: nothing to slide through. */
  clear() {
    this.pause();
    this.frames = [];
    this.els.slider.disabled = true;
    this.els.play.disabled = true;
    this.els.label.textContent = "";
    this.els.note.textContent = "";
  }

  /** Frames 0..N; the picture already shows the last, so the slider starts there. */
  load(frames, stopped) {
    this.pause();
    this.frames = frames;
    const last = Math.max(frames.length - 1, 0);
    const { slider, play, note } = this.els;
    slider.max = String(last);
    slider.value = String(last);
    slider.disabled = frames.length < 2;
    play.disabled = frames.length < 2;
    note.textContent = stopped || "";
    this.label(last);
  }

  label(step) {
    this.els.label.textContent = this.frames.length ? `step ${step} of ${this.frames.length - 1}` : "";
  }

  go(step) {
    const svg = this.frames[step];
    if (svg === undefined) return;
    this.els.slider.value = String(step);
    this.label(step);
    this.showFrame(svg);
  }

  play() {
    const last = this.frames.length - 1;
    if (last < 1) return;
    let step = Number(this.els.slider.value);
    if (step >= last) step = -1; // at the end: play from the start
    const advance = () => {
      step += 1;
      this.go(step);
      if (step >= last) this.pause();
    };
    this.els.play.textContent = "Pause";
    this.timer = setInterval(advance, FRAME_MS);
    advance();
  }

  pause() {
    if (this.timer) clearInterval(this.timer);
    this.timer = null;
    this.els.play.textContent = "Play";
  }
}
