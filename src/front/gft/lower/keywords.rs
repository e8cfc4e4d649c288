//! The keywords that set the system: settings given once, arrays and
//! globals, the view, colours, phases and the axiom.

use super::structure;
use super::{err, groups, Cx, Locals};
use crate::diagnostics::codes;
use crate::front::gft::ast::{Arg, Block, Keyword};
use crate::ir::program::ArrayDecl;
use crate::ir::{ContextFilter, Rgb, RulePolicy, SubLsystem};

impl Cx<'_> {
    /// Whether `k` is the first item under `key` (else reported, E0905).
    fn once_as(&mut self, k: &Keyword, key: &str) -> bool {
        if let Some(first) = self.settings.get(key) {
            let d = err(
                codes::GFT_DUPLICATE,
                &k.span,
                format!("`{}` given twice", k.name),
                "given again here",
                "remove one of them",
            )
            .with_secondary(first.clone(), "first given here");
            self.diags.push(d);
            return false;
        }
        self.settings.insert(key.to_string(), k.span.clone());
        true
    }

    /// The constant value of a keyword (`angle 360/7`).
    pub(super) fn value(&mut self, k: &Keyword) -> Option<f64> {
        // A name is not a value here: it gives E0903, not E0906.
        let v = k.value.as_ref().and_then(|e| {
            let saved = std::mem::take(self.diags);
            let v = self.expr(e, &mut Locals(Vec::new())).constant();
            let named = !std::mem::replace(self.diags, saved).is_empty();
            v.filter(|_| !named)
        });
        if v.is_none() {
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                format!("`{}` takes a number", k.name),
                "no number here",
                &format!("write e.g. `{} 2`", k.name),
            ));
        }
        v
    }

    fn whole(&mut self, k: &Keyword) -> Option<u64> {
        let v = self.value(k)?;
        if v >= 0.0 && v.fract() == 0.0 && v < u64::MAX as f64 {
            return Some(v as u64);
        }
        self.diags.push(err(
            codes::GFT_BAD_VALUE,
            &k.line,
            format!("`{}` takes a whole number", k.name),
            "not a whole number",
            "write e.g. `4`",
        ));
        None
    }

    pub(super) fn keyword(&mut self, k: &Keyword) {
        let settings = &mut self.sys.settings;
        let _ = settings;
        let repeated = [
            "symbol", "silent", "rotation", "array", "globals", "rule", "light", "material",
            "texture", "surface", "contour", "function", "tropism", "backdrop",
        ];
        if structure::is_structure_seed(k) {
            // Read with the structure; given once like the settings.
            self.once_as(k, "structure seed");
            return;
        }
        if !repeated.contains(&k.name.as_str()) && !self.once_as(k, &once_key(k))
            || self.look_item(k)
        {
            return;
        }
        match k.name.as_str() {
            "steps" => self.sys.settings.steps = self.whole(k),
            "seed" => self.sys.settings.seed = self.whole(k),
            "colour" => {
                if let Some(v) = self.whole(k) {
                    self.sys.settings.colour = v as usize;
                }
            }
            "angle" => {
                let rad = k.args.last().is_some_and(|a| a.text() == "rad");
                if let Some(v) = self.value(k) {
                    self.sys.settings.delta = if rad { v } else { v.to_radians() };
                }
            }
            "length" | "scale" | "width" | "width-factor" | "width-step" | "colour-step" => {
                if let Some(v) = self.value(k) {
                    let s = &mut self.sys.settings;
                    *match k.name.as_str() {
                        "length" => &mut s.step,
                        "scale" => &mut s.scale,
                        "width" => &mut s.width,
                        "width-factor" => &mut s.width_factor,
                        "width-step" => &mut s.width_step,
                        _ => &mut s.colour_step,
                    } = v;
                }
            }
            "random" => {
                self.sys.settings.randomness = match k.args.first().map(Arg::text) {
                    Some("cpfg") => crate::ir::Randomness::Cpfg,
                    _ => crate::ir::Randomness::Graftal,
                }
            }
            "cpfg-polygons" => self.sys.settings.cpfg_polygons = true,
            "widths" => {
                self.sys.settings.world_widths = k.args.first().is_some_and(|a| a.text() == "world")
            }
            "view" => self.view(k),
            "choose" => {
                self.sys.policy = match k.args.first().map(Arg::text) {
                    Some("weighted") => RulePolicy::Weighted,
                    _ => RulePolicy::FirstMatch,
                }
            }
            "ring" => self.sys.ring = true,
            "axiom" => self.axiom(k),
            "ignore" | "consider" => {
                let w = k
                    .word
                    .as_ref()
                    .map(|w| self.word(w, &mut Locals(Vec::new())).0);
                let ids = w.map(|w| w.symbols().to_vec()).unwrap_or_default();
                self.sys.context = if k.name == "ignore" {
                    ContextFilter::Ignore(ids)
                } else {
                    ContextFilter::Consider(ids)
                };
            }
            "cut" => {
                let w = k
                    .word
                    .as_ref()
                    .map(|w| self.word(w, &mut Locals(Vec::new())).0);
                self.sys.cut = w.and_then(|w| w.symbols().first().copied());
            }
            "colours" => self.colours(k),
            "graph" => self.graph(k),
            "decomposition" | "homomorphism" => self.phase(k),
            "label" => {
                if let Some(v) = self.whole(k) {
                    self.sys.label = v.min(u64::from(u32::MAX)) as u32;
                }
            }
            "sub-lsystem" => self.sub_lsystem(k),
            "environment" => self.environment(k),
            "start" | "start-each" | "end-each" | "end" => {
                let Some(Block::Statements(s)) = &k.block else {
                    return;
                };
                let s = self.stmts(s, &mut Locals(Vec::new()));
                let p = &mut self.sys.program;
                *match k.name.as_str() {
                    "start" => &mut p.start,
                    "start-each" => &mut p.start_each,
                    "end-each" => &mut p.end_each,
                    _ => &mut p.end,
                } = s;
            }
            _ => {}
        }
    }

    /// `array NAME[D1][D2]… [= V, V, …]` (cpfg's arrays; values row-major).
    pub(super) fn array(&mut self, k: &Keyword) {
        let g = groups(&k.args);
        let name = k
            .args
            .first()
            .map(|a| a.text().to_string())
            .unwrap_or_default();
        let eq = g.iter().position(|a| a.0 == "=").unwrap_or(g.len());
        let head: String = g[..eq].iter().map(|a| a.0.as_str()).collect();
        let dims: Option<Vec<usize>> = head
            .strip_prefix(name.as_str())
            .map(|d| d.trim_start_matches('[').trim_end_matches(']'))
            .map(|d| d.split("][").map(|n| n.parse().ok()).collect())
            .unwrap_or_default();
        let init: Option<Vec<f64>> = g[(eq + 1).min(g.len())..]
            .iter()
            .map(|a| a.0.trim_end_matches(','))
            .filter(|a| !a.is_empty())
            .map(|a| a.parse().ok())
            .collect();
        let size = dims
            .as_ref()
            .map(|d| d.iter().try_fold(1usize, |n, &x| n.checked_mul(x)));
        match (dims, init, size) {
            (Some(dims), Some(init), Some(Some(n)))
                if !dims.is_empty() && n <= 1 << 20 && init.len() <= n && !name.is_empty() =>
            {
                let id = self.sys.program.arrays.len() as u16;
                self.arrays.insert(name.clone(), (id, dims.len()));
                self.sys.program.arrays.push(ArrayDecl { name, dims, init });
            }
            _ => self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "malformed array",
                "not `array NAME[N]… = VALUES`",
                "write e.g. `array lengths[3] = 1, 2, 3` (at most 1048576 elements)",
            )),
        }
    }

    pub(super) fn global(&mut self, name: &str) -> u16 {
        if let Some(&g) = self.globals.get(name) {
            return g;
        }
        let g = self.sys.program.globals.len() as u16;
        self.sys.program.globals.push(name.to_string());
        self.globals.insert(name.to_string(), g);
        g
    }

    fn view(&mut self, k: &Keyword) {
        // A sign is its own token: read the groups (`-0.1`) as numbers.
        let nums: Vec<f64> = groups(&k.args)
            .iter()
            .filter_map(|g| g.0.parse().ok())
            .collect();
        let rad = k.args.last().is_some_and(|a| a.text() == "rad");
        match nums.as_slice() {
            [az, el] if rad => self.sys.settings.view = Some((*az, *el)),
            [az, el] => self.sys.settings.view = Some((az.to_radians(), el.to_radians())),
            _ => self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "`view` takes two angles",
                "not `view AZIMUTH ELEVATION`",
                "write e.g. `view 30 20`",
            )),
        }
    }

    fn colours(&mut self, k: &Keyword) {
        if let [Arg::Word(w, _)] = k.args.as_slice() {
            if w == "fractint" {
                self.sys.colours = crate::common::palettes::fractint_palette();
                return;
            }
        }
        for a in &k.args {
            let rgb = match a {
                Arg::Colour(c, _) => {
                    let h = |i: usize| u8::from_str_radix(&c[i..i + 2], 16).unwrap_or(0);
                    Some(Rgb(h(1), h(3), h(5)))
                }
                _ => None,
            };
            match rgb {
                Some(c) => self.sys.colours.push(c),
                None => self.diags.push(err(
                    codes::GFT_BAD_VALUE,
                    a.span(),
                    format!("`{}` is not a colour", a.text()),
                    "not `#rrggbb`",
                    "write colours as `#rrggbb`, e.g. `#00a000`",
                )),
            }
        }
    }

    fn phase(&mut self, k: &Keyword) {
        let g = groups(&k.args);
        let mut depth = 0;
        let mut seed = None;
        let mut lsystem = None;
        for pair in g.windows(2) {
            match (pair[0].0.as_str(), pair[1].0.parse::<u64>()) {
                ("depth", Ok(v)) => depth = v.min(u32::MAX as u64) as u32,
                ("seed", Ok(v)) => seed = Some(v),
                ("lsystem", Ok(v)) => lsystem = Some(v.min(u64::from(u32::MAX)) as u32),
                _ => {}
            }
        }
        let mut ps = Vec::new();
        if let Some(Block::Productions(list)) = &k.block {
            for p in list {
                ps.extend(self.production(p));
            }
        }
        let decomposition = k.name == "decomposition";
        let phase = match lsystem {
            Some(label) => {
                let sub = self.sub_named(label);
                if decomposition {
                    &mut sub.decomposition
                } else {
                    &mut sub.homomorphism
                }
            }
            None if decomposition => &mut self.sys.decomposition,
            None => &mut self.sys.homomorphism,
        };
        phase.productions = ps;
        phase.depth = depth;
        phase.seed = seed;
    }

    /// The sub-L-system labelled `label`, added when it is new (its
    /// phases may come before its block).
    fn sub_named(&mut self, label: u32) -> &mut SubLsystem {
        let subs = &mut self.sys.sub_lsystems;
        let at = match subs.iter().position(|s| s.label == label) {
            Some(at) => at,
            None => {
                subs.push(SubLsystem {
                    label,
                    ..SubLsystem::default()
                });
                subs.len() - 1
            }
        };
        &mut subs[at]
    }

    /// `sub-lsystem N { … }`: its productions and context filter.
    fn sub_lsystem(&mut self, k: &Keyword) {
        let Some(label) = k.args.first().and_then(|a| a.text().parse::<u32>().ok()) else {
            self.diags.push(err(
                codes::GFT_BAD_VALUE,
                &k.line,
                "`sub-lsystem` takes the L-system's number".to_string(),
                "expected a whole number before `{`",
                "write e.g. `sub-lsystem 2 { … }`",
            ));
            return;
        };
        let Some(Block::Lsystem {
            productions,
            context,
        }) = &k.block
        else {
            return;
        };
        let ps: Vec<_> = productions
            .iter()
            .filter_map(|p| self.production(p))
            .collect();
        let filter = context.as_ref().map(|(key, w)| {
            let ids = self.word(w, &mut Locals(Vec::new())).0.symbols().to_vec();
            if key == "ignore" {
                ContextFilter::Ignore(ids)
            } else {
                ContextFilter::Consider(ids)
            }
        });
        let sub = self.sub_named(label);
        sub.productions = ps;
        sub.context = filter.unwrap_or_default();
    }

    pub(super) fn axiom(&mut self, k: &Keyword) {
        let Some(w) = &k.word else { return };
        let (word, args, spans) = self.word(w, &mut Locals(Vec::new()));
        self.sys.axiom = word;
        self.sys.axiom_args = args;
        self.spans.axiom = spans;
    }
}

/// The key a keyword may be given once under: a phase or block of a
/// sub-L-system is once per L-system.
fn once_key(k: &Keyword) -> String {
    let label = match k.name.as_str() {
        "sub-lsystem" => k.args.first().map(|a| a.text().to_string()),
        "decomposition" | "homomorphism" => k
            .args
            .windows(2)
            .find(|w| w[0].text() == "lsystem")
            .map(|w| w[1].text().to_string()),
        _ => None,
    };
    match label {
        Some(n) => format!("{} lsystem {n}", k.name),
        None => k.name.clone(),
    }
}
