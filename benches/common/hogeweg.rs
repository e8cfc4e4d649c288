//! The plain string-rewriting baseline for Fig. 3.11a (hogeweg-hesper-a),
//! shared by the benchmarks: each step rewrites the string into a second
//! buffer, finding each symbol's contexts by scanning the string as the
//! pfg listing's `lcondiff`/`rcondiff` do (no bracket table, no interning).

/// `ignore: +-F` of hogeweg-hesper-a.
fn hh_ignored(c: u8) -> bool {
    matches!(c, b'+' | b'-' | b'F')
}

/// The listing's `lcondiff`: left over ignored symbols and `[` (into the
/// parent), over whole branches `[...]` that end there.
fn hh_left(w: &[u8], i: usize) -> Option<u8> {
    let mut j = i;
    while j > 0 {
        let c = w[j - 1];
        if c == b'[' || hh_ignored(c) {
            j -= 1;
        } else if c == b']' {
            let mut depth = 0usize;
            let mut k = j - 1;
            loop {
                match w[k] {
                    b']' => depth += 1,
                    b'[' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                if k == 0 {
                    return None;
                }
                k -= 1;
            }
            j = k;
        } else {
            return Some(c);
        }
    }
    None
}

/// The listing's `rcondiff`: right over ignored symbols and whole
/// branches; the end of the branch has none.
fn hh_right(w: &[u8], i: usize) -> Option<u8> {
    let mut j = i + 1;
    while j < w.len() {
        match w[j] {
            b'[' => {
                let mut depth = 0usize;
                loop {
                    match w.get(j)? {
                        b'[' => depth += 1,
                        b']' => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                    j += 1;
                }
                j += 1;
            }
            b']' => return None,
            c if hh_ignored(c) => j += 1,
            c => return Some(c),
        }
    }
    None
}

fn hh_rule(l: u8, p: u8, r: u8) -> &'static [u8] {
    match (l, p, r) {
        (b'0', b'0', b'1') => b"1[+F1F1]",
        (b'1', b'0', b'1') => b"1F1",
        (b'1', b'1', b'0') | (b'1', b'1', b'1') => b"0",
        (_, b'0', _) => b"0",
        _ => b"1",
    }
}

pub fn plain_hogeweg(n: u64) -> Vec<u8> {
    let mut cur = b"F1F1F1".to_vec();
    let mut next = Vec::new();
    for _ in 0..n {
        next.clear();
        for (i, &c) in cur.iter().enumerate() {
            match c {
                b'0' | b'1' => match (hh_left(&cur, i), hh_right(&cur, i)) {
                    (Some(l), Some(r)) => next.extend_from_slice(hh_rule(l, c, r)),
                    _ => next.push(c),
                },
                b'+' => next.push(b'-'),
                b'-' => next.push(b'+'),
                _ => next.push(c),
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    cur
}
