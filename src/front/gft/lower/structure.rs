//! The STL structure of docs/gft.md §8: `rule`, `stems`, `seed`, `outline`
//! and `growth`. A seed without an outline is expanded into the axiom; an
//! outline's seed is the planted one, grown when read (`layout::seed`), as the
//! STL front end grows it.

use super::items::{Fields, Val};
use super::{err, Cx, Locals};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::gft::ast::{self, Arg, File, Item, Keyword, Piece};
use crate::ir::{
    BranchEntry, BranchTerm, Growth, GrowthConstraint, Rgb, SeedItem, Shape, Span, Stems,
    Structure, StructureRule, StructureRuleId, Word, MAX_NESTING,
};
use crate::layout::seed;

/// Whether `k` is an STL seed (a `seed` line that is not one whole number).
pub(super) fn is_structure_seed(k: &Keyword) -> bool {
    k.name == "seed" && !matches!(k.args.as_slice(), [Arg::Number(..)])
}

/// The keyword items of the structure.
fn structure_items(file: &File) -> impl Iterator<Item = &Keyword> {
    file.items.iter().filter_map(|i| match i {
        Item::Keyword(k)
            if matches!(k.name.as_str(), "rule" | "stems" | "outline" | "growth")
                || is_structure_seed(k) =>
        {
            Some(k)
        }
        _ => None,
    })
}

/// Symbol text as a word to split (its pieces as written).
fn word_of(args: &[Arg], span: Span) -> ast::Word {
    let pieces = (args.iter())
        .map(|a| match a {
            Arg::Quoted(q, s) => Piece::Quoted(q.clone(), s.clone()),
            a => Piece::Text(a.text().to_string(), a.span().clone()),
        })
        .collect();
    ast::Word { pieces, span }
}

impl Cx<'_> {
    /// Reads the structure items, if the file has any.
    pub(super) fn structure(&mut self, file: &File) {
        let items: Vec<&Keyword> = structure_items(file).collect();
        if items.is_empty() {
            return;
        }
        let mut st = Structure::default();
        let rules: Vec<&Keyword> = items.iter().copied().filter(|k| k.name == "rule").collect();
        for k in &rules {
            let name = k
                .args
                .first()
                .map(|a| a.text().to_string())
                .unwrap_or_default();
            st.rules.push(StructureRule {
                name,
                body: Word::default(),
                resemblance: None,
                unit: None,
            });
        }
        for (i, k) in rules.iter().enumerate() {
            self.rule(k, i, &mut st);
        }
        for k in &items {
            match k.name.as_str() {
                "stems" => self.stems(k, &mut st.stems),
                "growth" => self.growth(k, &mut st.constraint),
                "outline" => st.constraint.outline = self.outline(k),
                _ => {}
            }
        }
        let seed = items.iter().find(|k| is_structure_seed(k));
        let planted = match seed {
            Some(k) => self.seed(k, &st),
            None => Vec::new(),
        };
        if st.constraint.outline.is_empty() {
            st.seed = planted;
        } else {
            st.planted = planted;
            self.grow(&mut st, seed.map_or(&items[0].line, |k| &k.line));
        }
        match seed::word(&mut self.sys, &st, &st.seed) {
            Ok(w) => self.sys.axiom = w,
            Err(seed::TooLarge) => self.too_large(seed.map_or(&items[0].line, |k| &k.line)),
        }
        self.sys.structure = Some(st);
    }

    fn too_large(&mut self, span: &Span) {
        self.diags.push(err(
            codes::GFT_BAD_VALUE,
            span,
            format!(
                "the seed expands to more than {} symbols",
                Structure::MAX_EXPANSION
            ),
            "this seed is too large",
            "nest fewer terms, or use rules with fewer branches",
        ));
    }

    /// Grows the planted seed inside the outline.
    fn grow(&mut self, st: &mut Structure, span: &Span) {
        match seed::grow(&self.sys, st) {
            Ok(out) => {
                if out.truncated {
                    self.diags.push(err(
                        codes::GFT_BAD_VALUE,
                        span,
                        format!(
                            "growth stopped at {} stems",
                            crate::layout::growth::MAX_STEMS
                        ),
                        "grows too many stems",
                        "use fewer levels, a larger broadness or a smaller outline",
                    ));
                }
                st.seed = out.seed;
            }
            Err(seed::TooLarge) => self.too_large(span),
        }
    }

    /// `rule NAME = BODY [resemblance N] [unit RULE]`.
    fn rule(&mut self, k: &Keyword, i: usize, st: &mut Structure) {
        let eq = k.args.iter().position(|a| a.text() == "=");
        let end = (k.args.iter())
            .position(|a| matches!(a, Arg::Word(w, _) if w == "resemblance" || w == "unit"))
            .unwrap_or(k.args.len());
        let Some(eq) = eq.filter(|&e| e == 1 && e < end) else {
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "malformed `rule`",
                "not `rule NAME = BODY`",
                "write e.g. `rule R1 = [+F][-F] resemblance 3`",
            ));
            return;
        };
        let body = &k.args[eq + 1..end];
        let span = body
            .first()
            .map_or(k.line.clone(), |a| a.span().start..k.line.end);
        st.rules[i].body = self.word(&word_of(body, span), &mut Locals(Vec::new())).0;
        let mut f = Fields::new(k);
        if f.has("resemblance") {
            st.rules[i].resemblance = f.number("resemblance");
        }
        if f.has("unit") {
            let unit = f.word("unit", &[]).unwrap_or_default();
            st.rules[i].unit = self.rule_id(&unit, &k.line, st);
        }
        self.malformed(f, k, "rule R1 = [+F][-F] resemblance 3");
    }

    /// The rule named `name`, or a reported E0906.
    fn rule_id(&mut self, name: &str, span: &Span, st: &Structure) -> Option<StructureRuleId> {
        let found = st.rules.iter().position(|r| r.name == name);
        if found.is_none() {
            self.diags.push(err(
                codes::GFT_UNKNOWN_NAME,
                span,
                format!("no rule `{name}`"),
                "not declared with `rule`",
                "declare it: `rule R1 = [+F][-F]`",
            ));
        }
        found.map(|r| StructureRuleId(r as u32))
    }

    /// `stems broadness B ΔB length L ΔL`.
    fn stems(&mut self, k: &Keyword, stems: &mut Stems) {
        let mut f = Fields::new(k);
        let pair = |f: &mut Fields<'_>, label: &str| Some((f.number(label)?, f.second(label)?));
        let (b, l) = (pair(&mut f, "broadness"), pair(&mut f, "length"));
        if let (Some(b), Some(l)) = (b, l) {
            *stems = Stems {
                broadness: b,
                length: l,
            };
        }
        self.malformed(f, k, "stems broadness 8 1 length 40 4");
    }

    /// `growth breadth-first|depth-first levels N`.
    fn growth(&mut self, k: &Keyword, c: &mut GrowthConstraint) {
        let mut f = Fields::new(k);
        let strategy = f.word("", &["breadth-first", "depth-first"]);
        let levels = f.number::<u32>("levels");
        if let (Some(s), Some(levels)) = (strategy, levels) {
            c.strategy = if s == "depth-first" {
                Growth::DepthFirst
            } else {
                Growth::BreadthFirst
            };
            c.levels = levels.min(MAX_NESTING as u32);
        }
        self.malformed(f, k, "growth breadth-first levels 5");
    }

    /// `outline { SHAPE … }`, one shape a line.
    fn outline(&mut self, k: &Keyword) -> Vec<Shape> {
        let Some(ast::Block::Lines(lines)) = &k.block else {
            return Vec::new();
        };
        lines
            .iter()
            .filter_map(|l| self.shape(l, &k.line))
            .collect()
    }

    fn shape(&mut self, line: &[Arg], at: &Span) -> Option<Shape> {
        let vals = super::items::vals(line);
        let span = line.first().map_or(at.clone(), |a| a.span().start..at.end);
        let shape = shape_of(&vals);
        if shape.is_none() {
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &span,
                "malformed shape",
                "not a shape of docs/gft.md §8",
                "write e.g. `ellipse (-150, 0) 300 400 #00a000` or `polygon (0, 0) (10, 0) (5, 8) #000000`",
            ));
        }
        shape
    }
}

/// A shape from its values: `KIND (x, y) … #colour`.
fn shape_of(vals: &[Val]) -> Option<Shape> {
    let (Val::Word(kind, _), Val::Colour(colour, _)) = (vals.first()?, vals.last()?) else {
        return None;
    };
    let colour: Rgb = *colour;
    let mid = &vals[1..vals.len() - 1];
    let point = |v: &Val| match v {
        Val::Tuple(p, _) => match p.as_slice() {
            [x, y] => Some((x.trim().parse().ok()?, y.trim().parse().ok()?)),
            _ => None,
        },
        _ => None,
    };
    let n = |v: &Val| match v {
        Val::Num(t, _) => t.parse::<f64>().ok(),
        _ => None,
    };
    if kind == "polygon" {
        let points: Option<Vec<(f64, f64)>> = mid.iter().map(point).collect();
        return Some(Shape::Polygon {
            colour,
            points: points?,
        });
    }
    let ((x, y), rest) = (point(mid.first()?)?, &mid[1..]);
    let nums: Option<Vec<f64>> = rest.iter().map(n).collect();
    Some(match (kind.as_str(), nums?.as_slice()) {
        ("rectangle", [w, h]) => Shape::Rectangle {
            colour,
            x,
            y,
            w: *w,
            h: *h,
        },
        ("ellipse", [w, h]) => Shape::Ellipse {
            colour,
            x,
            y,
            w: *w,
            h: *h,
        },
        ("round-rectangle", [w, h, corner]) => Shape::RoundRect {
            colour,
            x,
            y,
            w: *w,
            h: *h,
            corner: *corner,
        },
        _ => return None,
    })
}

impl Cx<'_> {
    /// The seed's items: words, and terms `R{e, , ~}` (a rule named bare
    /// is a growth point when there is an outline and the rule branches;
    /// else a term without entries).
    fn seed(&mut self, k: &Keyword, st: &Structure) -> Vec<SeedItem> {
        let mut items = Vec::new();
        let mut run: Vec<Arg> = Vec::new();
        let args = &k.args;
        let mut i = 0;
        while i < args.len() {
            if let Some(r) = self.rule_at(args, i, st) {
                self.flush(&mut run, &mut items);
                let (t, next) = self.term(args, i, r, st, 1);
                items.push(SeedItem::Term(t));
                i = next;
            } else {
                run.push(args[i].clone());
                i += 1;
            }
        }
        self.flush(&mut run, &mut items);
        items
    }

    /// The rule whose name is the whole argument `i`.
    fn rule_at(&self, args: &[Arg], i: usize, st: &Structure) -> Option<usize> {
        let Arg::Word(w, _) = &args[i] else {
            return None;
        };
        st.rules.iter().position(|r| r.name == *w)
    }

    fn flush(&mut self, run: &mut Vec<Arg>, items: &mut Vec<SeedItem>) {
        if run.is_empty() {
            return;
        }
        let span = run[0].span().start..run[run.len() - 1].span().end;
        let w = word_of(run, span);
        let (word, _, _) = self.word_unbalanced(&w, &mut Locals(Vec::new()));
        items.push(SeedItem::Word(word));
        run.clear();
    }

    /// The term of rule `r` named at `args[i]`, and the index after it.
    fn term(
        &mut self,
        args: &[Arg],
        i: usize,
        r: usize,
        st: &Structure,
        depth: usize,
    ) -> (BranchTerm, usize) {
        let mut t = BranchTerm {
            rule: StructureRuleId(r as u32),
            entries: Vec::new(),
            grows: false,
        };
        let braced = args.get(i + 1).is_some_and(|a| a.text() == "{");
        if !braced {
            let branches = st.rules[r].body.0.contains(&crate::ir::SymbolId::OPEN);
            t.grows = !st.constraint.outline.is_empty() && branches;
            return (t, i + 1);
        }
        if depth > MAX_NESTING {
            self.diags.push(
                Diagnostic::at(
                    codes::NESTED_TOO_DEEPLY,
                    args[i].span().clone(),
                    "nested too deeply",
                )
                .with_label(format!("more than {MAX_NESTING} terms deep"))
                .with_help("graftal reads at most 256 nested terms"),
            );
            return (t, args.len());
        }
        let mut j = i + 2;
        let mut entry: Option<BranchEntry> = None;
        while j < args.len() {
            let a = &args[j];
            match a.text() {
                "}" => {
                    if entry.is_some() || !t.entries.is_empty() {
                        t.entries.push(entry.take().unwrap_or(BranchEntry::Empty));
                    }
                    return (t, j + 1);
                }
                "," => {
                    t.entries.push(entry.take().unwrap_or(BranchEntry::Empty));
                    j += 1;
                }
                "~" => {
                    entry = Some(BranchEntry::Failed);
                    j += 1;
                }
                _ => match self.rule_at(args, j, st) {
                    Some(c) => {
                        let (child, next) = self.term(args, j, c, st, depth + 1);
                        entry = Some(BranchEntry::Term(child));
                        j = next;
                    }
                    None => {
                        let name = a.text().to_string();
                        self.rule_id(&name, a.span(), st);
                        j += 1;
                    }
                },
            }
        }
        self.diags.push(err(
            codes::GFT_UNBALANCED,
            args[i].span(),
            "unclosed `{`",
            "this term's entries are not closed",
            "close them with `}`",
        ));
        (t, j)
    }
}
