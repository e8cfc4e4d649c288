// The unsaved text, kept in localStorage so a reload or a crash loses
// nothing. One draft per file (or "scratch" when serving no file); it goes
// away when the text is saved or is the same as the file again.

const PREFIX = "graftal:draft:";

function storage() {
  try {
    return window.localStorage;
  } catch {
    return null; // storage disabled: drafts are simply not kept
  }
}

export class Draft {
  constructor(file) {
    this.key = PREFIX + (file ?? "scratch");
  }

  read() {
    return storage()?.getItem(this.key) ?? null;
  }

  /** Keeps `text` unless it is what the file already holds. */
  keep(text, fileText) {
    const s = storage();
    if (!s) return;
    try {
      if (text === fileText) s.removeItem(this.key);
      else s.setItem(this.key, text);
    } catch {
      // Quota exceeded: a draft is a convenience, not worth an error.
    }
  }

  clear() {
    storage()?.removeItem(this.key);
  }
}
