//! One mistake repeated through an item is reported a few times, then
//! counted.
//!
//! A generated or damaged file can repeat one mistake a million times on
//! one line (`SEED F(1)F(1)…`, `rules f = f@f@…`). Reporting each costs a
//! diagnostic built and kept (hundreds of megabytes) for a reader who needs
//! the first. Like rustc and typst with cascades, a front end reports the
//! first [`SHOWN_PER_ITEM`] diagnostics of each code in an item (a line, a
//! string), counts the rest without building them, and says on the last
//! one reported how many more there were. Once the list is full
//! ([`Diagnostics::is_full`]) nothing is built either: the list only
//! counts.

use crate::diagnostics::{Code, Diagnostic, Diagnostics, Severity};

/// How many diagnostics of one code an item gets; the rest are counted.
pub const SHOWN_PER_ITEM: usize = 3;

/// The diagnostics of one code in the current item.
#[derive(Debug)]
struct Seen {
    code: Code,
    reported: usize,
    /// Where the last one reported is in the list, when it was kept.
    last: Option<usize>,
    /// How many were found after the last one reported.
    more: usize,
}

/// What an item reported so far, code by code (see the module). Items
/// may nest ([`Repeats::begin_item`]): a rule read while reading another
/// counts its own mistakes.
#[derive(Debug, Default)]
pub struct Repeats {
    seen: Vec<Seen>,
    /// Where each item begun inside another starts in `seen`.
    starts: Vec<usize>,
}

impl Repeats {
    /// Pushes to `diags` what `build` makes, a diagnostic of `code` found
    /// in the current item, unless [`SHOWN_PER_ITEM`] of that code were
    /// reported in it already or the list is full: then it is only counted
    /// and `build` is not called.
    pub fn report(
        &mut self,
        diags: &mut Diagnostics,
        code: Code,
        build: impl FnOnce() -> Diagnostic,
    ) {
        if self.admit(diags, code) {
            self.push(diags, build());
        }
    }

    /// Whether a diagnostic of `code` found now is to be built and given
    /// to [`Repeats::push`]; when not, it has been counted. For a caller
    /// whose `build` needs what [`Repeats::report`] would borrow.
    pub fn admit(&mut self, diags: &mut Diagnostics, code: Code) -> bool {
        if count_without_building(diags, code) {
            return false;
        }
        let seen = self.seen(code);
        if seen.reported < SHOWN_PER_ITEM {
            return true;
        }
        seen.more += 1;
        false
    }

    /// Pushes `d`, which [`Repeats::admit`] let through.
    pub fn push(&mut self, diags: &mut Diagnostics, d: Diagnostic) {
        let kept = !diags.is_full();
        let at = diags.len();
        let seen = self.seen(d.code);
        seen.reported += 1;
        seen.last = kept.then_some(at);
        diags.push(d);
    }

    /// Begins an item inside the current one, ended by the next
    /// [`Repeats::end_item`]. Without it, each item ends where the next
    /// begins.
    pub fn begin_item(&mut self) {
        self.starts.push(self.seen.len());
    }

    /// Ends the item: the last diagnostic of each code reported in it says
    /// how many more followed `place` (`on this line`, `in this string`).
    pub fn end_item(&mut self, diags: &mut Diagnostics, place: &str) {
        let start = self.starts.pop().unwrap_or(0);
        for seen in self.seen.drain(start..) {
            if seen.more == 0 {
                continue;
            }
            if let Some(d) = seen.last.and_then(|i| diags.0.get_mut(i)) {
                let (n, s) = (seen.more, if seen.more == 1 { "" } else { "s" });
                d.notes.push(format!(
                    "{n} more {} diagnostic{s} {place} are not shown one by one",
                    seen.code
                ));
            }
        }
    }

    fn seen(&mut self, code: Code) -> &mut Seen {
        let start = self.starts.last().copied().unwrap_or(0);
        let i = match self.seen[start..].iter().position(|s| s.code == code) {
            Some(i) => start + i,
            None => {
                self.seen.push(Seen {
                    code,
                    reported: 0,
                    last: None,
                    more: 0,
                });
                self.seen.len() - 1
            }
        };
        &mut self.seen[i]
    }
}

/// Pushes to `diags` what `build` makes, a diagnostic of `code`, unless
/// the list is full: then it is counted without being built (see
/// [`count_without_building`]). For a mistake a file may repeat on every
/// line, where what the diagnostic says costs more than finding it (a
/// suggestion's edit distances, a formatted list).
pub fn push_lazily(diags: &mut Diagnostics, code: Code, build: impl FnOnce() -> Diagnostic) {
    if !count_without_building(diags, code) {
        diags.push(build());
    }
}

/// When `diags` is full, counts a diagnostic of `code` without building
/// it and returns true; false when it has to be built. The list counts
/// what it does not keep on its last diagnostic, except that an error
/// takes the place of a warning kept last: that error is kept, so it is
/// built (once: after it, the last one is an error).
pub fn count_without_building(diags: &mut Diagnostics, code: Code) -> bool {
    if !diags.is_full() {
        return false;
    }
    let last_is_error = diags.0.last().is_none_or(Diagnostic::is_error);
    if code.severity() == Severity::Error && !last_is_error {
        return false;
    }
    diags.push(Diagnostic::global(code, String::new()));
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::{codes, MAX_KEPT};

    fn syntax(at: usize) -> Diagnostic {
        Diagnostic::at(codes::SYNTAX, at..at + 1, "unexpected `(`")
    }

    #[test]
    fn an_item_reports_a_few_of_a_code_then_counts() {
        let mut diags = Diagnostics::default();
        let mut r = Repeats::default();
        let mut built = 0;
        for at in 0..1000 {
            r.report(&mut diags, codes::SYNTAX, || {
                built += 1;
                syntax(at)
            });
        }
        r.report(&mut diags, codes::UNEXPECTED_EOF, || {
            Diagnostic::at(codes::UNEXPECTED_EOF, 1000..1000, "unexpected end of file")
        });
        r.end_item(&mut diags, "on this line");
        assert_eq!(built, SHOWN_PER_ITEM);
        assert_eq!(diags.len(), SHOWN_PER_ITEM + 1);
        let last = &diags.0[SHOWN_PER_ITEM - 1];
        assert_eq!(
            last.notes,
            ["997 more E0003 diagnostics on this line are not shown one by one"]
        );
        assert!(diags.0[SHOWN_PER_ITEM].notes.is_empty());
        // The next item starts again.
        r.report(&mut diags, codes::SYNTAX, || syntax(2000));
        r.end_item(&mut diags, "on this line");
        assert_eq!(diags.len(), SHOWN_PER_ITEM + 2);
        assert!(diags.0[SHOWN_PER_ITEM + 1].notes.is_empty());
    }

    #[test]
    fn a_nested_item_counts_its_own() {
        let mut diags = Diagnostics::default();
        let mut r = Repeats::default();
        let report = |r: &mut Repeats, diags: &mut Diagnostics, n: usize| {
            for at in 0..n {
                r.report(diags, codes::SYNTAX, || syntax(at));
            }
        };
        r.begin_item();
        report(&mut r, &mut diags, 2);
        r.begin_item();
        report(&mut r, &mut diags, 5);
        r.end_item(&mut diags, "in this rule");
        // The outer item had two: one more is reported, then counted.
        report(&mut r, &mut diags, 4);
        r.end_item(&mut diags, "in this rule");
        assert_eq!(diags.len(), 2 + 3 + 1);
        let notes: Vec<usize> = diags.iter().map(|d| d.notes.len()).collect();
        assert_eq!(notes, [0, 0, 0, 0, 1, 1]);
        assert!(diags.0[4].notes[0].starts_with("2 more E0003"));
        assert!(diags.0[5].notes[0].starts_with("3 more E0003"));
    }

    #[test]
    fn a_full_list_counts_without_building() {
        let mut diags = Diagnostics::default();
        let warning = || Diagnostic::at(codes::FR_LONG_LINE, 0..1, "a warning");
        for _ in 0..MAX_KEPT {
            diags.push(warning());
        }
        let mut built = 0;
        for at in 0..10 {
            let mut r = Repeats::default();
            r.report(&mut diags, codes::SYNTAX, || {
                built += 1;
                syntax(at)
            });
            r.report(&mut diags, codes::FR_LONG_LINE, || {
                built += 1;
                warning()
            });
            r.end_item(&mut diags, "on this line");
        }
        // The first error is built to take the last warning's place; the
        // rest are counted.
        assert_eq!(built, 1);
        assert_eq!(diags.len(), MAX_KEPT);
        let last = diags.0.last().unwrap();
        assert_eq!(last.message, "unexpected `(`");
        let not_kept = last.not_kept.unwrap();
        assert_eq!((not_kept.errors, not_kept.warnings), (9, 11));
        // The last kept is an error now: nothing more is built.
        push_lazily(&mut diags, codes::SYNTAX, || unreachable!("built"));
        push_lazily(&mut diags, codes::FR_LONG_LINE, || unreachable!("built"));
        let not_kept = diags.0.last().unwrap().not_kept.unwrap();
        assert_eq!((not_kept.errors, not_kept.warnings), (10, 12));
    }
}
