// Positions in a server answer are offsets into the text as it was sent; by
// the time the answer arrives the user may have typed more. A Tracker keeps,
// for each outstanding or displayed answer, the changes made since its text
// was sent, so those offsets can be carried over to the current document.

import { ChangeSet } from "@codemirror/state";

export class Tracker {
  constructor() {
    this.live = new Set();
  }

  /** Starts following `doc` (the document as it is sent). */
  follow(doc) {
    const mark = new Mark(doc.length);
    this.live.add(mark);
    return mark;
  }

  drop(mark) {
    if (mark) this.live.delete(mark);
  }

  /** Called with every document change (an update's ChangeSet). */
  record(changes) {
    for (const mark of this.live) mark.changes = mark.changes.compose(changes);
  }
}

class Mark {
  constructor(length) {
    this.changes = ChangeSet.empty(length);
  }

  pos(offset, assoc = -1) {
    const clamped = Math.max(0, Math.min(offset, this.changes.length));
    return this.changes.mapPos(clamped, assoc);
  }

  /** A range, kept from turning inside out when its text was deleted. */
  range({ from, to }) {
    const a = this.pos(from, 1);
    const b = this.pos(to, -1);
    return b < a ? { from: a, to: a } : { from: a, to: b };
  }
}
