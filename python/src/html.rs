//! The command line's coloured text (its terminal colour codes) as HTML:
//! the same characters in a `<pre>`, each coloured run a `<span>`, so that
//! a notebook shows a diagnostic as a terminal does, its place marked.

/// `text`, with its SGR colour codes (`ESC [ … m`), as a `<pre>` of HTML.
pub fn of_terminal(text: &str) -> String {
    let mut out = String::from(
        "<pre class=\"graftal-diagnostics\" style=\"line-height:1.25;white-space:pre;overflow-x:auto\">",
    );
    let mut open = false;
    let mut rest = text;
    while let Some(at) = rest.find("\x1b[") {
        escape_into(&mut out, &rest[..at]);
        let after = &rest[at + 2..];
        let Some(end) = after.find(|c: char| !(c.is_ascii_digit() || c == ';')) else {
            rest = "";
            break;
        };
        if after[end..].starts_with('m') {
            let style = style_of(&after[..end]);
            if open {
                out.push_str("</span>");
            }
            open = !style.is_empty();
            if open {
                out.push_str(&format!("<span style=\"{style}\">"));
            }
        }
        rest = &after[end + 1..];
    }
    escape_into(&mut out, rest);
    if open {
        out.push_str("</span>");
    }
    out.push_str("</pre>");
    out
}

/// The CSS of one SGR sequence's parameters (`31`, `1;34`, `38;5;246`);
/// empty for a reset.
fn style_of(params: &str) -> String {
    let codes: Vec<u32> = params.split(';').filter_map(|p| p.parse().ok()).collect();
    let mut css = Vec::new();
    let mut k = 0;
    while k < codes.len() {
        match codes[k] {
            1 => css.push("font-weight:bold".to_string()),
            c @ (30..=37 | 90..=97) => css.push(format!("color:{}", BASIC[basic_index(c)])),
            38 if codes.get(k + 1) == Some(&5) => {
                if let Some(&n) = codes.get(k + 2) {
                    css.push(format!("color:{}", xterm(n)));
                }
                k += 2;
            }
            _ => {}
        }
        k += 1;
    }
    css.join(";")
}

/// The sixteen terminal colours, as xterm draws them, but white and bright
/// white drawn grey: a notebook's page is white.
const BASIC: [&str; 16] = [
    "#000000", "#cd0000", "#00a000", "#b8a000", "#2050e0", "#cd00cd", "#00a0a0", "#808080",
    "#7f7f7f", "#ff0000", "#00c000", "#c0a000", "#5c5cff", "#ff00ff", "#00c0c0", "#404040",
];

fn basic_index(code: u32) -> usize {
    match code {
        30..=37 => (code - 30) as usize,
        _ => (code - 90 + 8) as usize,
    }
}

/// Colour `n` of xterm's 256: the sixteen, a 6x6x6 cube, 24 greys.
fn xterm(n: u32) -> String {
    match n {
        0..=15 => BASIC[n as usize].to_string(),
        16..=231 => {
            let level = |v: u32| if v == 0 { 0 } else { 55 + 40 * v };
            let v = n - 16;
            format!(
                "#{:02x}{:02x}{:02x}",
                level(v / 36),
                level(v / 6 % 6),
                level(v % 6)
            )
        }
        _ => {
            let g = 8 + 10 * (n.min(255) - 232);
            format!("#{g:02x}{g:02x}{g:02x}")
        }
    }
}

fn escape_into(out: &mut String, s: &str) {
    for c in s.chars() {
        match c {
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
}
