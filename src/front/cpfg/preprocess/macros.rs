//! Macros: `#define`, and expanding calls as C does (arguments first,
//! then a rescan; hide sets keep a macro from expanding inside itself).

use super::tokens::{span_of, strip_ws, union, Kind, Tok};
use super::{Pp, MAX_PENDING_TOKENS, MAX_STEPS};
use crate::diagnostics::{codes, Diagnostic};
use crate::front::depth::too_deep;
use crate::ir::MAX_NESTING;
use std::collections::VecDeque;
use std::ops::Range;
use std::rc::Rc;

#[derive(Clone, Debug)]
pub(super) struct Macro {
    pub(super) id: u32,
    pub(super) params: Option<Vec<String>>,
    pub(super) variadic: bool,
    pub(super) body: Vec<Tok>,
    /// The definition's span when it is in the main file.
    pub(super) def: Option<Range<usize>>,
}

impl Macro {
    fn same_as(&self, other: &Macro) -> bool {
        let norm = |b: &[Tok]| -> Vec<String> {
            b.iter()
                .map(|t| {
                    if t.kind == Kind::Ws {
                        " ".to_string()
                    } else {
                        t.text.to_string()
                    }
                })
                .collect()
        };
        self.params == other.params
            && self.variadic == other.variadic
            && norm(&self.body) == norm(&other.body)
    }
}

/// The index in `input` of the `)` that closes the `(` at `open`.
fn matching_paren(input: &VecDeque<Tok>, open: usize) -> Option<usize> {
    let mut level = 0usize;
    for (j, x) in input.iter().enumerate().skip(open) {
        match &*x.text {
            "(" if x.kind == Kind::Other => level += 1,
            ")" if x.kind == Kind::Other => {
                level -= 1;
                if level == 0 {
                    return Some(j);
                }
            }
            _ => {}
        }
    }
    None
}

/// The arguments between a call's parentheses, split at the commas outside
/// nested parentheses, without surrounding blanks. `f()` has no argument
/// when `f` takes none.
fn call_arguments(
    inner: &[Tok],
    n_params: usize,
    variadic: bool,
    name_origin: &Range<usize>,
) -> Vec<Vec<Tok>> {
    let mut args: Vec<Vec<Tok>> = vec![Vec::new()];
    let mut level = 0usize;
    for x in inner {
        if x.kind == Kind::Other {
            match &*x.text {
                "(" => level += 1,
                ")" => level = level.saturating_sub(1),
                "," if level == 0 => {
                    args.push(Vec::new());
                    continue;
                }
                _ => {}
            }
        }
        if let Some(a) = args.last_mut() {
            a.push(x.clone());
        }
    }
    let mut args: Vec<Vec<Tok>> = args.into_iter().map(strip_ws).collect();
    if n_params == 0 && args.len() == 1 && args[0].is_empty() {
        args.clear();
    }
    if variadic {
        fit_variadic(&mut args, n_params, name_origin);
    }
    args
}

/// Joins the arguments of a variadic macro past its named parameters into
/// the last one (with the commas between them), or gives it an empty one.
fn fit_variadic(args: &mut Vec<Vec<Tok>>, n_params: usize, name_origin: &Range<usize>) {
    if args.len() > n_params {
        let rest = args.split_off(n_params - 1);
        let mut joined = Vec::new();
        for (i, a) in rest.into_iter().enumerate() {
            if i > 0 {
                joined.push(Tok {
                    kind: Kind::Other,
                    text: Rc::from(","),
                    origin: name_origin.clone(),
                    own: false,
                    hide: Rc::new(Vec::new()),
                });
            }
            joined.extend(a);
        }
        args.push(joined);
    } else if args.len() + 1 == n_params {
        args.push(Vec::new());
    }
}

/// A function-like macro's body with each parameter replaced by its
/// expanded argument, every token made by the call at `origin`.
fn substitute(
    body: &[Tok],
    params: &[String],
    args: &[Vec<Tok>],
    origin: &Range<usize>,
    hide: &Rc<Vec<u32>>,
) -> Vec<Tok> {
    let mut repl: Vec<Tok> = Vec::new();
    for bt in body {
        let p = if bt.kind == Kind::Ident {
            params.iter().position(|p| **p == *bt.text)
        } else {
            None
        };
        match p {
            Some(p) => {
                for at in &args[p] {
                    repl.push(at.made_by(origin, Rc::new(union(&at.hide, hide))));
                }
            }
            None => repl.push(bt.made_by(origin, hide.clone())),
        }
    }
    repl
}

impl Pp<'_> {
    /// Expands a token list (Prosser's algorithm, iteratively).
    pub(super) fn expand(&mut self, mut input: VecDeque<Tok>, depth: usize) -> Vec<Tok> {
        let mut output = Vec::with_capacity(input.len());
        // What expansion adds is bounded, not the text given: a file of a
        // million plain tokens is no runaway expansion.
        let most_pending = input.len().saturating_add(MAX_PENDING_TOKENS);
        while let Some(t) = input.pop_front() {
            self.steps += 1;
            if self.steps > MAX_STEPS || input.len() > most_pending {
                self.abort(t.origin.clone(), "too many expansion steps");
            }
            if self.aborted || t.kind != Kind::Ident {
                output.push(t);
                continue;
            }
            let Some(m) = self.macros.get(&*t.text) else {
                output.push(t);
                continue;
            };
            if t.hide.contains(&m.id) {
                output.push(t);
                continue;
            }
            let m = m.clone();
            match &m.params {
                None => {
                    // The body replaces the name, to be rescanned.
                    let hide = Rc::new(union(&t.hide, &[m.id]));
                    for bt in m.body.iter().rev() {
                        input.push_front(bt.made_by(&t.origin, hide.clone()));
                    }
                }
                Some(params) => self.expand_call(t, &m, params, &mut input, &mut output, depth),
            }
        }
        output
    }

    /// Expands the call of the function-like macro `m` whose name is `t` and
    /// whose arguments follow in `input`: the replacement goes back to the
    /// front of `input`, to be rescanned. A name without `(` goes to `output`
    /// as it is, and so does a call that is unclosed, has the wrong number
    /// of arguments or is nested too deep (with a diagnostic).
    fn expand_call(
        &mut self,
        t: Tok,
        m: &Macro,
        params: &[String],
        input: &mut VecDeque<Tok>,
        output: &mut Vec<Tok>,
        depth: usize,
    ) {
        // Is the next non-space token `(`?
        let k = input
            .iter()
            .position(|x| !matches!(x.kind, Kind::Ws | Kind::Splice));
        let Some(k) = k.filter(|&k| &*input[k].text == "(") else {
            output.push(t);
            return;
        };
        let Some(close) = matching_paren(input, k) else {
            self.diags.push(
                Diagnostic::at(
                    codes::CPFG_UNTERMINATED_CALL,
                    t.origin.clone(),
                    format!("call of macro `{}` is never closed", t.text),
                )
                .with_label("this call has no closing `)`")
                .with_help("add the missing `)`; a call cannot run past the next directive"),
            );
            output.push(t);
            return;
        };
        let call: Vec<Tok> = input.drain(..=close).collect();
        let rparen_hide = call[close].hide.clone();
        let args = call_arguments(&call[k + 1..close], params.len(), m.variadic, &t.origin);
        let mut origin = t.origin.clone();
        if let Some(s) = span_of(&call) {
            origin = origin.start.min(s.start)..origin.end.max(s.end);
        }
        // Arguments are expanded by recursion, one level per call, each
        // level holding the arguments of the levels inside it: the calls
        // written nested are counted first, in one pass, rather than found
        // too deep after that much work. (Calls that expansion makes are
        // counted as they are expanded.)
        let too_deep_at = match depth {
            0 => self.first_call_too_deep(&call[k + 1..close], MAX_NESTING),
            _ => None,
        }
        .or((depth >= MAX_NESTING).then_some(&t))
        .map(|x| x.origin.clone());
        let refused = if args.len() != params.len() {
            self.wrong_argument_count(&t, m, params, args.len(), origin.clone());
            true
        } else if let Some(at) = too_deep_at {
            if !std::mem::replace(&mut self.aborted, true) {
                self.too_deep = true;
                self.diags.push(too_deep(
                    at,
                    "call fewer macros inside the arguments of macros",
                ));
            }
            true
        } else {
            false
        };
        if refused {
            // Leave the call as it is.
            output.push(t);
            output.extend(call);
            return;
        }
        let expanded_args: Vec<Vec<Tok>> = args
            .into_iter()
            .map(|a| self.expand(a.into(), depth + 1))
            .collect();
        // The tokens made hide what both the name and the closing `)` hide,
        // and the macro itself.
        let inter: Vec<u32> = t
            .hide
            .iter()
            .filter(|h| rparen_hide.contains(h))
            .copied()
            .collect();
        let hide = Rc::new(union(&inter, &[m.id]));
        let repl = substitute(&m.body, params, &expanded_args, &origin, &hide);
        for x in repl.into_iter().rev() {
            input.push_front(x);
        }
    }

    /// The first call of a function-like macro in `toks` that is the
    /// `room`th or deeper nested in the arguments of others there.
    fn first_call_too_deep<'t>(&self, toks: &'t [Tok], room: usize) -> Option<&'t Tok> {
        let mut calls = 0usize;
        // Per open parenthesis: whether it holds the arguments of a call.
        let mut open: Vec<bool> = Vec::new();
        let mut name: Option<&Tok> = None;
        for x in toks {
            match (x.kind, &*x.text) {
                (Kind::Ws | Kind::Splice, _) => continue,
                (Kind::Ident, n) if self.macros.get(n).is_some_and(|m| m.params.is_some()) => {
                    name = Some(x);
                    continue;
                }
                (Kind::Other, "(") => {
                    if name.is_some() {
                        if calls + 1 >= room {
                            return name;
                        }
                        calls += 1;
                    }
                    open.push(name.is_some());
                }
                (Kind::Other, ")") if open.pop() == Some(true) => calls -= 1,
                _ => {}
            }
            name = None;
        }
        None
    }

    fn wrong_argument_count(
        &mut self,
        t: &Tok,
        m: &Macro,
        params: &[String],
        given: usize,
        origin: Range<usize>,
    ) {
        let mut d = Diagnostic::at(
            codes::CPFG_MACRO_ARGUMENTS,
            origin,
            format!(
                "macro `{}` takes {} argument{} but is given {}",
                t.text,
                params.len(),
                if params.len() == 1 { "" } else { "s" },
                given
            ),
        )
        .with_label("this call")
        .with_help(format!("call it as `{}({})`", t.text, params.join(", ")));
        if let Some(def) = &m.def {
            d = d.with_secondary(def.clone(), "defined here");
        }
        self.diags.push(d);
    }

    pub(super) fn define(&mut self, rest: Vec<Tok>, line_span: Range<usize>, main: bool) {
        let lead = rest.iter().take_while(|t| t.kind == Kind::Ws).count();
        let Some(name) = rest.get(lead).filter(|t| t.kind == Kind::Ident) else {
            self.bad_directive(line_span, "`#define` needs a macro name".to_string());
            return;
        };
        let mut i = lead + 1;
        let mut params = None;
        let mut variadic = false;
        // A `(` right after the name makes a function-like macro.
        if rest
            .get(i)
            .is_some_and(|t| &*t.text == "(" && t.origin.start == name.origin.end)
        {
            i += 1;
            let mut ps: Vec<String> = Vec::new();
            let mut ok = false;
            let mut expect_name = true;
            while let Some(t) = rest.get(i) {
                i += 1;
                match (t.kind, &*t.text) {
                    (Kind::Ws, _) => {}
                    (Kind::Other, ")") if !expect_name || ps.is_empty() => {
                        ok = true;
                        break;
                    }
                    (Kind::Ident, p) if expect_name => {
                        ps.push(p.to_string());
                        expect_name = false;
                    }
                    (Kind::Other, ".")
                        if expect_name && rest.get(i).is_some_and(|x| &*x.text == ".") =>
                    {
                        // `...`
                        i += 2;
                        ps.push("__VA_ARGS__".to_string());
                        variadic = true;
                        expect_name = false;
                    }
                    (Kind::Other, ",") if !expect_name && !variadic => expect_name = true,
                    _ => break,
                }
            }
            if !ok {
                self.bad_directive(
                    line_span,
                    format!("malformed parameter list of macro `{}`", name.text),
                );
                return;
            }
            params = Some(ps);
        }
        let mut body: Vec<Tok> = Vec::new();
        let raw = &rest[i.min(rest.len())..];
        for (k, t) in raw.iter().enumerate() {
            // `\\` at the end of a line: the first backslash would stay.
            if &*t.text == "\\"
                && t.kind == Kind::Other
                && raw
                    .get(k + 1)
                    .is_some_and(|n| n.kind == Kind::Ws && n.text.is_empty())
            {
                self.diags.push(
                    Diagnostic::at(
                        codes::CPFG_STRAY_BACKSLASH,
                        t.origin.clone(),
                        "backslash before the line continuation is dropped",
                    )
                    .with_label("this `\\` would stay in the macro's text")
                    .with_help("end the line with a single `\\`"),
                );
                continue;
            }
            body.push(t.clone());
        }
        let body = strip_ws(body);
        let name_s = name.text.to_string();
        let id = self.intern(&name_s);
        let m = Macro {
            id,
            params,
            variadic,
            body,
            def: if main { Some(line_span.clone()) } else { None },
        };
        if let Some(old) = self.macros.get(&name_s) {
            if !old.same_as(&m) {
                let mut d = Diagnostic::at(
                    codes::CPFG_MACRO_REDEFINED,
                    line_span,
                    format!("macro `{name_s}` redefined; this definition is used from here on"),
                )
                .with_label("new definition");
                if let Some(def) = &old.def {
                    d = d.with_secondary(def.clone(), "previous definition");
                }
                self.diags.push(
                    d.with_help(format!("write `#undef {name_s}` first if this is intended")),
                );
            }
        }
        self.macros.insert(name_s, m);
    }
}
