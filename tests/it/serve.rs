//! `graftal serve`: the HTTP API the page talks to, spoken to over TCP as
//! a browser (or an attacker) would, malformed and oversized requests
//! included; and the page itself in headless Chromium (tests/e2e/page.mjs).

use crate::common::temp;
use graftal::serve::{self, Options, MAX_BODY};
use serde_json::{json, Value};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

/// Koch's quadratic island (the book's Fig. 1.7b) at one step.
const KOCH: &str = "derivation length: 1\nangle factor: 4\naxiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\n";

/// A server on a free loopback port serving `file`; it answers until the
/// test process ends.
fn server(file: Option<String>) -> SocketAddr {
    let opts = Options {
        file,
        addr: "127.0.0.1:0".parse().unwrap(),
    };
    let (server, served) = serve::start(&opts).unwrap();
    let addr = server.server_addr().to_ip().unwrap();
    std::thread::spawn(move || serve::serve(&server, &served));
    addr
}

/// A served file holding `text`.
#[track_caller]
fn served_file(name: &str, text: &str) -> (SocketAddr, std::path::PathBuf) {
    let path = temp(name);
    std::fs::write(&path, text).unwrap();
    (server(Some(path.display().to_string())), path)
}

/// Sends `raw` and reads the whole answer: status, head, body.
fn send(addr: SocketAddr, raw: &[u8]) -> (u16, String, Vec<u8>) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    // The server may answer (and close) before reading all of a body it
    // refuses: a failed write is that, not an error.
    let _ = s.write_all(raw);
    // Nothing more comes: a request cut short is answered (or dropped)
    // at once rather than waited on.
    let _ = s.shutdown(std::net::Shutdown::Write);
    let mut answer = Vec::new();
    let _ = s.read_to_end(&mut answer);
    let split = (answer.windows(4).position(|w| w == b"\r\n\r\n")).unwrap_or(answer.len());
    let head = String::from_utf8_lossy(&answer[..split]).into_owned();
    let body = answer.get(split + 4..).unwrap_or(&[]).to_vec();
    let status = head
        .split(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    (status, head, body)
}

/// A request with this server's own Host, and `headers` besides.
fn request(addr: SocketAddr, method: &str, path: &str, headers: &str, body: &[u8]) -> Vec<u8> {
    let mut raw = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {}\r\n{headers}\r\n",
        body.len()
    )
    .into_bytes();
    raw.extend_from_slice(body);
    raw
}

/// `POST path` with JSON `body`: the status and the JSON answer.
fn post(addr: SocketAddr, path: &str, body: &Value) -> (u16, Value) {
    let raw = request(addr, "POST", path, "", body.to_string().as_bytes());
    let (status, _, body) = send(addr, &raw);
    (status, serde_json::from_slice(&body).unwrap_or(Value::Null))
}

/// Koch's island downloaded as `format`: the status, head and bytes.
fn export(addr: SocketAddr, format: &str) -> (u16, String, Vec<u8>) {
    let body = json!({ "text": KOCH, "format": format }).to_string();
    send(
        addr,
        &request(addr, "POST", "/api/export", "", body.as_bytes()),
    )
}

fn get(addr: SocketAddr, path: &str) -> (u16, String, Vec<u8>) {
    send(addr, &request(addr, "GET", path, "", b""))
}

#[test]
fn the_page_and_its_assets_are_served_from_the_binary() {
    let addr = server(Some("std:koch-island".into()));
    let (status, head, html) = get(addr, "/");
    assert_eq!(status, 200, "{head}");
    let html = String::from_utf8(html).unwrap();
    assert!(html.contains("/assets/page.js"), "{html}");
    // Nothing from elsewhere: every script and style is this server's.
    assert!(
        !html.contains("http://") && !html.contains("https://"),
        "{html}"
    );
    let (status, head, js) = get(addr, "/assets/page.js");
    assert_eq!(status, 200);
    assert!(head.contains("text/javascript"), "{head}");
    assert!(js.len() > 10_000, "{} bytes", js.len());
    let (_, start) = (200, get(addr, "/api/start").2);
    let start: Value = serde_json::from_slice(&start).unwrap();
    assert_eq!(start["file"], "std:koch-island");
    assert_eq!(start["notation"], "pfg");
    assert_eq!(start["can_save"], false);
    assert!(start["text"].as_str().unwrap().contains("-->"));
    assert!((start["entries"].as_array().unwrap()).contains(&json!("std:koch-island")));
    assert!((start["notations"].as_array().unwrap())
        .iter()
        .any(|n| n["id"] == "cpfg"));
    assert_eq!(get(addr, "/nothing/here").0, 404);
}

#[test]
fn an_update_answers_diagnostics_and_a_picture_linked_to_the_source() {
    let addr = server(None);
    let model = json!({ "page": "p", "seq": 1, "text": KOCH, "notation": "pfg" });
    let (status, v) = post(addr, "/api/update", &model);
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["seq"], 1);
    assert_eq!(v["diagnostics"], json!([]), "{v}");
    assert_eq!(v["steps"], 1);
    assert_eq!(v["is3d"], false);
    let svg = v["picture"].as_str().unwrap();
    // 4 × 8 segments, each named by the successor symbol `F` that drew it.
    let sources: Vec<&str> = svg
        .split("data-src=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    assert_eq!(sources.len(), 32, "{svg}");
    let production = &v["productions"][0];
    let (from, to) = (
        production["from"].as_u64().unwrap(),
        production["to"].as_u64().unwrap(),
    );
    for src in &sources {
        let (a, b) = src.split_once('-').unwrap();
        let (a, b): (u64, u64) = (a.parse().unwrap(), b.parse().unwrap());
        assert!(
            from <= a && b <= to,
            "{src} outside the production {from}-{to}"
        );
        assert_eq!(&KOCH[a as usize..b as usize], "F");
    }
    // The successor has eight Fs: each one named.
    let distinct: std::collections::HashSet<_> = sources.iter().collect();
    assert_eq!(distinct.len(), 8);
    // At step 0 the axiom's Fs drew.
    let at0 = json!({ "page": "p", "seq": 2, "text": KOCH, "steps": 0 });
    let v = post(addr, "/api/update", &at0).1;
    let axiom = &v["axiom"];
    assert_eq!(
        &KOCH[axiom["from"].as_u64().unwrap() as usize..axiom["to"].as_u64().unwrap() as usize],
        "F-F-F-F"
    );
    assert_eq!(
        v["picture"].as_str().unwrap().matches("data-src").count(),
        4
    );
}

#[test]
fn a_mistake_is_answered_at_its_span_with_its_fix_and_no_picture() {
    let addr = server(None);
    let text = "derivation length: 1\nangle factor: 4\naxiom: F-F-F-F\nF --> F-F+F+FF-F-F+F\nderivaton length: 2\n";
    let model = json!({ "page": "p", "seq": 1, "text": text, "notation": "pfg" });
    let v = post(addr, "/api/update", &model).1;
    let d = (v["diagnostics"].as_array().unwrap().iter())
        .find(|d| d["severity"] == "error")
        .unwrap_or_else(|| panic!("{v}"));
    assert_eq!(d["code"], "E0101", "{d}");
    assert_eq!(d["line"], 5);
    let (from, to) = (
        d["from"].as_u64().unwrap() as usize,
        d["to"].as_u64().unwrap() as usize,
    );
    assert_eq!(&text[from..to], "derivaton length");
    let fix = &d["fixes"][0]["edits"][0];
    assert_eq!(fix["insert"], "derivation length", "{d}");
    assert_eq!(v["picture"], Value::Null);
}

#[test]
fn a_model_past_the_pages_limits_says_the_limit_at_once() {
    let addr = server(None);
    // 2^40 symbols: refused before deriving.
    let text = "derivation length: 40\naxiom: F+F\nF --> FF\n";
    let t = Instant::now();
    let v = post(
        addr,
        "/api/update",
        &json!({ "page": "p", "seq": 1, "text": text }),
    )
    .1;
    assert!(t.elapsed() < Duration::from_secs(5), "{:?}", t.elapsed());
    let codes: Vec<&Value> = v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| &d["code"])
        .collect();
    assert!(
        codes
            .iter()
            .any(|c| c.as_str().is_some_and(|c| c.starts_with("E030"))),
        "{v}"
    );
    assert_eq!(v["picture"], Value::Null);
}

#[test]
fn the_frames_of_growth_come_from_one_compile() {
    let addr = server(None);
    let model = json!({ "page": "p", "seq": 1, "text": KOCH, "steps": 3 });
    let v = post(addr, "/api/frames", &model).1;
    let frames = v["frames"].as_array().unwrap_or_else(|| panic!("{v}"));
    assert_eq!(frames.len(), 4, "{v}");
    let parts: Vec<usize> = frames
        .iter()
        .map(|f| f.as_str().unwrap().matches("<path").count())
        .collect();
    assert_eq!(parts, [4, 32, 256, 2048]);
    assert_eq!(v["stopped"], Value::Null);
}

#[test]
fn an_older_request_of_a_page_is_superseded_by_a_newer_one() {
    let addr = server(None);
    post(
        addr,
        "/api/update",
        &json!({ "page": "p", "seq": 5, "text": KOCH }),
    );
    let v = post(
        addr,
        "/api/update",
        &json!({ "page": "p", "seq": 4, "text": KOCH }),
    )
    .1;
    assert_eq!(v["superseded"], true, "{v}");
    assert!(v.get("picture").is_none());
    // Another page is its own.
    let v = post(
        addr,
        "/api/update",
        &json!({ "page": "q", "seq": 1, "text": KOCH }),
    )
    .1;
    assert_eq!(v["superseded"], false);
}

#[test]
fn hover_translation_and_downloads_come_from_the_library() {
    let addr = server(None);
    let at_f = KOCH.rfind("F-F").unwrap();
    let v = post(addr, "/api/hover", &json!({ "text": KOCH, "offset": at_f })).1;
    let md = v["markdown"].as_str().unwrap_or_else(|| panic!("{v}"));
    assert!(md.contains("forward"), "{md}");
    let v = post(
        addr,
        "/api/translate",
        &json!({ "text": KOCH, "to": "gft" }),
    )
    .1;
    assert!(
        v["text"]
            .as_str()
            .unwrap_or_else(|| panic!("{v}"))
            .contains("axiom"),
        "{v}"
    );
    let (status, head, png) = export(addr, "png");
    assert_eq!(status, 200, "{head}");
    assert!(
        head.contains("image/png") && head.contains("attachment"),
        "{head}"
    );
    assert!(png.starts_with(b"\x89PNG"));
    let (_, _, obj) = export(addr, "obj");
    assert!(
        String::from_utf8_lossy(&obj).contains("\nv "),
        "an OBJ has vertices"
    );
    let v = post(addr, "/api/std", &json!({ "name": "std:koch-island" })).1;
    assert_eq!(v["notation"], "pfg");
}

#[test]
fn save_writes_the_served_file_and_nothing_else() {
    let (addr, path) = served_file("model.l", KOCH);
    let edited = KOCH.replace("F-F-F-F", "F+F+F+F");
    let v = post(addr, "/api/save", &json!({ "text": edited })).1;
    assert_eq!(v["saved"], path.display().to_string());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), edited);
    // A stdlib entry is not a file.
    let addr = server(Some("std:koch-island".into()));
    let (status, v) = post(addr, "/api/save", &json!({ "text": "x" }));
    assert_eq!(status, 403, "{v}");
}

#[test]
fn requests_for_other_names_or_from_other_pages_are_refused() {
    let addr = server(None);
    let body = json!({ "text": KOCH }).to_string();
    // DNS rebinding: the browser sends the attacker's name as Host.
    let raw = format!(
        "POST /api/update HTTP/1.1\r\nHost: evil.example:{}\r\nConnection: close\r\nContent-Length: {}\r\n\r\n{body}",
        addr.port(),
        body.len()
    );
    assert_eq!(send(addr, raw.as_bytes()).0, 403);
    // Another site's page posting here.
    let raw = request(
        addr,
        "POST",
        "/api/save",
        "Origin: http://evil.example\r\n",
        body.as_bytes(),
    );
    assert_eq!(send(addr, &raw).0, 403);
    // This server's own page.
    let own = format!("Origin: http://{addr}\r\n");
    let raw = request(addr, "POST", "/api/update", &own, body.as_bytes());
    assert_eq!(send(addr, &raw).0, 200);
}

#[test]
fn the_server_survives_malformed_and_oversized_requests() {
    let addr = server(None);
    let oversized = format!(
        "POST /api/update HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {}\r\n\r\n",
        MAX_BODY + 1
    );
    assert_eq!(send(addr, oversized.as_bytes()).0, 413);
    let bad_json = request(addr, "POST", "/api/update", "", b"{\"text\": ");
    let (status, _, body) = send(addr, &bad_json);
    assert_eq!(status, 400, "{}", String::from_utf8_lossy(&body));
    let wrong_type = request(
        addr,
        "POST",
        "/api/update",
        "",
        b"{\"text\": 5, \"seq\": \"x\"}",
    );
    assert_eq!(send(addr, &wrong_type).0, 400);
    assert_eq!(send(addr, &request(addr, "DELETE", "/", "", b"")).0, 405);
    assert_eq!(post(addr, "/api/nothing", &json!({})).0, 404);
    let unknown = json!({ "text": KOCH, "notation": "klingon" });
    assert_eq!(post(addr, "/api/update", &unknown).0, 400);
    // Garbage, a cut-off request, an unknown notation to translate to, a
    // view past the poles, a huge size: none stops the server.
    for raw in [
        &b"\x00\xff\xfe garbage\r\n\r\n"[..],
        b"GET / HTTP/1.1\r\nHost: ",
        b"POST /api/update HTTP/1.1\r\nContent-Length: 10\r\n\r\n{",
    ] {
        send(addr, raw);
    }
    let odd = json!({ "text": KOCH, "azimuth": 1e308, "elevation": -1e308, "width": 4_000_000_000u64, "seed": 18446744073709551615u64 });
    assert_eq!(post(addr, "/api/update", &odd).0, 200);
    assert_eq!(
        post(addr, "/api/translate", &json!({ "text": KOCH, "to": "x" })).0,
        400
    );
    let v = post(addr, "/api/update", &json!({ "text": KOCH })).1;
    assert!(
        v["picture"].as_str().is_some(),
        "the server still draws: {v}"
    );
}

/// Whether the browser test's tools are here: node, Chromium, and
/// playwright-core installed in web/node_modules.
fn browser() -> Option<String> {
    let chromium = std::env::var("GRAFTAL_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    let node = std::process::Command::new("node").arg("--version").output();
    let ready = node.is_ok_and(|o| o.status.success())
        && std::path::Path::new(&chromium).exists()
        && std::path::Path::new("web/node_modules/playwright-core").exists();
    ready.then_some(chromium)
}

#[test]
fn the_page_works_in_headless_chromium() {
    let needed = std::env::var("GRAFTAL_NEED_BROWSER").as_deref() == Ok("1");
    let Some(chromium) = browser() else {
        assert!(
            !needed,
            "GRAFTAL_NEED_BROWSER=1 but node, {} or web/node_modules/playwright-core is missing",
            "chromium"
        );
        eprintln!("skipped: the browser test needs node, chromium and `npm ci --prefix web`");
        return;
    };
    let (addr, _) = served_file("page.l", KOCH);
    let shot = temp("picture.png");
    let out = std::process::Command::new("node")
        .args([
            "tests/e2e/page.mjs",
            &format!("http://{addr}/"),
            shot.to_str().unwrap(),
        ])
        .env("GRAFTAL_CHROMIUM", chromium)
        .output()
        .unwrap();
    let said = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{said}");
    compare_with_reference(&std::fs::read(&shot).unwrap());
}

/// The screenshot of the picture against tests/e2e/page-picture.png: the
/// same size, and at most 2% of its pixels differing by more than a
/// little (anti-aliasing differs between Chromium builds; the picture's
/// lines do not move).
fn compare_with_reference(shot: &[u8]) {
    let reference = "tests/e2e/page-picture.png";
    if crate::common::blessing() {
        std::fs::write(reference, shot).unwrap();
    }
    let (want_size, want) = rgb_pixels(&std::fs::read(reference).unwrap());
    let (got_size, got) = rgb_pixels(shot);
    assert_eq!(got_size, want_size, "the screenshot's size");
    let differing = (got.iter().zip(&want))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 48))
        .count();
    let share = differing as f64 / got.len().max(1) as f64;
    assert!(
        share < 0.02,
        "{:.2}% of the pixels differ from {reference}",
        share * 100.0
    );
}

/// The size and RGB pixels of a PNG of any 8-bit colour type.
fn rgb_pixels(bytes: &[u8]) -> ((u32, u32), Vec<[u8; 3]>) {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let pixels = (buf[..info.buffer_size()].chunks_exact(channels))
        .map(|p| match channels {
            1 | 2 => [p[0]; 3],
            _ => [p[0], p[1], p[2]],
        })
        .collect();
    ((info.width, info.height), pixels)
}
