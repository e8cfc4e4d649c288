//! `graftal lsp` driven as an editor drives it: the real binary, JSON-RPC
//! over its standard input and output (LSP 3.17 base protocol).

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

use crate::common::{slow, slow_timed};

/// The longest a test waits for any one message.
const WAIT: Duration = Duration::from_secs(30);

struct Client {
    child: Child,
    stdin: ChildStdin,
    /// Each message, with when its last byte arrived.
    messages: Receiver<(Instant, Value)>,
    /// When the last message taken from `messages` arrived: the time an
    /// answer took is measured to it, not to the end of parsing its JSON
    /// in this (debug) test, which is the client's cost.
    arrived: Instant,
    next_id: i64,
    /// Notifications read while waiting for a response.
    notes: Vec<(Instant, Value)>,
    /// What the server answered `initialize` with.
    initialized: Value,
}

/// Reads framed messages (`Content-Length: N`, a blank line, N bytes).
fn read_messages(out: impl Read + Send + 'static) -> Receiver<(Instant, Value)> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        let mut r = BufReader::new(out);
        loop {
            let mut len = None;
            loop {
                let mut line = String::new();
                if r.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
                let line = line.trim();
                if line.is_empty() {
                    break;
                }
                if let Some(n) = line.strip_prefix("Content-Length: ") {
                    len = n.parse::<usize>().ok();
                }
            }
            let mut body = vec![0; len.expect("a Content-Length header")];
            if r.read_exact(&mut body).is_err() {
                return;
            }
            let arrived = Instant::now();
            let v: Value = serde_json::from_slice(&body).expect("a JSON message");
            if tx.send((arrived, v)).is_err() {
                return;
            }
        }
    });
    rx
}

/// What the test client says it can take: code actions as literals, as
/// VS Code, Neovim and Helix say.
fn editor_capabilities() -> Value {
    let kinds = json!({ "codeActionKind": { "valueSet": ["quickfix"] } });
    json!({ "textDocument": { "codeAction": { "codeActionLiteralSupport": kinds } } })
}

impl Client {
    /// Starts `graftal lsp` and initializes it as an editor does.
    fn start() -> Client {
        Client::start_with(editor_capabilities())
    }

    /// Starts `graftal lsp` and initializes it, the client saying it has
    /// `capabilities`.
    fn start_with(capabilities: Value) -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_graftal"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("graftal runs");
        let stdin = child.stdin.take().unwrap();
        let messages = read_messages(child.stdout.take().unwrap());
        let mut c = Client {
            child,
            stdin,
            messages,
            arrived: Instant::now(),
            next_id: 0,
            notes: Vec::new(),
            initialized: Value::Null,
        };
        let init = c.request("initialize", json!({ "capabilities": capabilities }));
        assert!(
            init["result"]["capabilities"]["hoverProvider"] == json!(true),
            "{init}"
        );
        c.initialized = init["result"].clone();
        c.notify("initialized", json!({}));
        c
    }

    fn send(&mut self, v: Value) {
        let body = v.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.stdin.flush().unwrap();
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({ "jsonrpc": "2.0", "method": method, "params": params }));
    }

    /// Sends a request; its whole response (`result` or `error`).
    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        self.send(json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }));
        loop {
            let (arrived, msg) = self.messages.recv_timeout(WAIT).expect("a response");
            self.arrived = arrived;
            if msg["id"] == json!(id) && msg.get("method").is_none() {
                return msg;
            }
            self.notes.push((arrived, msg));
        }
    }

    /// The next diagnostics published for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Vec<Value> {
        let is_for = |m: &Value| {
            m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uri
        };
        if let Some(i) = self.notes.iter().position(|(_, m)| is_for(m)) {
            let (arrived, m) = self.notes.remove(i);
            self.arrived = arrived;
            return m["params"]["diagnostics"].as_array().unwrap().clone();
        }
        loop {
            let (arrived, msg) = self.messages.recv_timeout(WAIT).expect("diagnostics");
            self.arrived = arrived;
            if is_for(&msg) {
                return msg["params"]["diagnostics"].as_array().unwrap().clone();
            }
            self.notes.push((arrived, msg));
        }
    }

    fn open(&mut self, uri: &str, text: &str) -> Vec<Value> {
        let doc = json!({ "uri": uri, "languageId": "lsystem", "version": 1, "text": text });
        self.notify("textDocument/didOpen", json!({ "textDocument": doc }));
        self.diagnostics(uri)
    }

    fn change(&mut self, uri: &str, version: i64, text: &str) -> Vec<Value> {
        self.notify(
            "textDocument/didChange",
            json!({
                "textDocument": { "uri": uri, "version": version },
                "contentChanges": [{ "text": text }],
            }),
        );
        self.diagnostics(uri)
    }

    /// A request about position (`line`, `character`) of `uri`.
    fn at(&mut self, method: &str, uri: &str, line: u32, character: u32) -> Value {
        let mut params = json!({
            "textDocument": { "uri": uri },
            "position": { "line": line, "character": character },
        });
        if method == "textDocument/references" {
            params["context"] = json!({ "includeDeclaration": true });
        }
        self.request(method, params)
    }

    /// `shutdown` then `exit`: the server ends with status 0.
    fn stop(mut self) {
        let r = self.request("shutdown", Value::Null);
        assert_eq!(r["result"], Value::Null, "{r}");
        self.notify("exit", Value::Null);
        let deadline = Instant::now() + WAIT;
        loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                assert!(status.success(), "{status}");
                return;
            }
            assert!(Instant::now() < deadline, "the server did not exit");
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// `exit` before `shutdown` ends the server with status 1, as LSP asks.
#[test]
fn exit_without_shutdown_ends_with_status_1() {
    let mut c = Client::start();
    c.notify("exit", Value::Null);
    let deadline = Instant::now() + WAIT;
    loop {
        if let Some(status) = c.child.try_wait().unwrap() {
            assert_eq!(status.code(), Some(1), "{status}");
            return;
        }
        assert!(Instant::now() < deadline, "the server did not exit");
        std::thread::sleep(Duration::from_millis(20));
    }
}

impl Drop for Client {
    /// A failed test leaves no server behind.
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

const URI: &str = "file:///tmp/graftal-lsp-test/plant.l";

/// A pfg system whose last line has a second `-->` after a comment of
/// characters outside the BMP (two UTF-16 units each) and accents.
const BROKEN: &str = "derivation length: 2\nangle factor: 4\naxiom: F\n\
                      F --> F+F /* é𝄞 */ F --> F\n";

const FIXED: &str = "derivation length: 2\nangle factor: 4\naxiom: F\nF --> F+F /* é𝄞 */\n";

/// The UTF-16 column of byte `at` of `text`.
fn utf16_column(text: &str, at: usize) -> u64 {
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    text[line_start..at].encode_utf16().count() as u64
}

#[test]
fn diagnostics_on_open_and_change_in_utf16_columns() {
    let mut c = Client::start();
    let ds = c.open(URI, BROKEN);
    assert_eq!(ds.len(), 1, "{ds:?}");
    let d = &ds[0];
    assert_eq!(d["code"], "E0003");
    assert_eq!(d["severity"], 1);
    let second_arrow = BROKEN.rfind("-->").unwrap();
    assert_eq!(d["range"]["start"]["line"], 3);
    // Bytes (31), characters (21) and UTF-16 units (22) all differ here.
    assert_eq!(
        d["range"]["start"]["character"],
        utf16_column(BROKEN, second_arrow)
    );
    assert_eq!(utf16_column(BROKEN, second_arrow), 22);
    let message = d["message"].as_str().unwrap();
    assert!(
        message.contains("help: a production has exactly one `-->`"),
        "{message}"
    );
    assert!(message.contains("`graftal explain E0003`"), "{message}");
    // Fixed: the diagnostics are cleared.
    assert_eq!(c.change(URI, 2, FIXED), Vec::<Value>::new());
    // Half typed: diagnostics, not an error.
    let half = c.change(URI, 3, "derivation length: 2\naxiom: F\nF -");
    assert!(!half.is_empty());
    c.stop();
}

#[test]
fn secondary_labels_are_related_information() {
    let mut c = Client::start();
    let text = "derivation length: 2\nangle factor: 4\naxiom: F\nF --> F+F\nF --> F-F\n";
    let ds = c.open(URI, text);
    let d = ds.iter().find(|d| d["code"] == "W0006").expect("W0006");
    assert_eq!(d["severity"], 2);
    let related = d["relatedInformation"].as_array().unwrap();
    assert_eq!(related.len(), 1, "{related:?}");
    assert_eq!(related[0]["location"]["uri"], URI);
    assert_eq!(related[0]["location"]["range"]["start"]["line"], 3);
    assert_eq!(related[0]["message"], "this one always matches first");
    c.stop();
}

fn explain(code: &str) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(["explain", code])
        .output()
        .unwrap();
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn hover_tells_what_a_symbol_does_and_explains_codes() {
    let mut c = Client::start();
    let text = "derivation length: 2\nangle factor: 4\naxiom: F+G\nF --> F+F\nF --> F-F\n";
    c.open(URI, text);
    // `F` in the axiom.
    let h = c.at("textDocument/hover", URI, 2, 7);
    let value = h["result"]["contents"]["value"].as_str().unwrap();
    assert!(
        value.contains("`F`: moves one step forward, drawing a line"),
        "{value}"
    );
    assert!(value.contains("line 4: `F --> F+F`"), "{value}");
    // `+`: a turn by the increment; no production rewrites it.
    let h = c.at("textDocument/hover", URI, 2, 8);
    let value = h["result"]["contents"]["value"].as_str().unwrap();
    assert!(value.contains("turns about its up axis U"), "{value}");
    assert!(value.contains("No production rewrites it"), "{value}");
    // The shadowed production on line 5 carries W0006: its explanation.
    let h = c.at("textDocument/hover", URI, 4, 3);
    let value = h["result"]["contents"]["value"].as_str().unwrap();
    assert!(value.contains(explain("W0006").trim()), "{value}");
    // Nothing under a keyword.
    let h = c.at("textDocument/hover", URI, 0, 2);
    assert_eq!(h["result"], Value::Null, "{h}");
    c.stop();
}

#[test]
fn definition_and_references_of_a_symbol() {
    let mut c = Client::start();
    let text = "derivation length: 2\nangle factor: 4\naxiom: X\nX --> F[+X]F[-X]+X\nF --> FF\n";
    c.open(URI, text);
    let d = c.at("textDocument/definition", URI, 3, 9); // the first `X` of line 4's successor
    let found = d["result"].as_array().unwrap();
    assert_eq!(found.len(), 1, "{d}");
    assert_eq!(found[0]["uri"], URI);
    assert_eq!(
        found[0]["range"]["start"],
        json!({ "line": 3, "character": 0 })
    );
    assert_eq!(
        found[0]["range"]["end"],
        json!({ "line": 3, "character": 1 })
    );
    // `X`: the axiom, the predecessor and three in the successor.
    let r = c.at("textDocument/references", URI, 2, 7);
    assert_eq!(r["result"].as_array().unwrap().len(), 5, "{r}");
    // `F`: from the successor of line 4 to the production of line 5.
    let d = c.at("textDocument/definition", URI, 3, 6);
    assert_eq!(d["result"][0]["range"]["start"]["line"], 4, "{d}");
    c.stop();
}

/// Hover, definition and references of a symbol in a file with an error
/// on another line answer as they do in the file without that line: from
/// what the recovering parse read of the parts that parse, in each
/// notation with symbols.
#[test]
fn a_file_with_an_error_answers_about_its_other_parts() {
    let dir = cpfg_object("recovered", &[]);
    let cpfg = format!("file://{}", dir.join("plant.l").display());
    let gft = "file:///tmp/graftal-lsp-test/recovered.gft";
    // The file's text before the line with the error, that line, the text
    // after it, and where a symbol is written before it.
    let cases = [
        (
            URI,
            "derivation length: 2\naxiom: X\nX --> F[+X]-X\n",
            "Y --> F --> F\n",
            "",
            (1, 7),
        ),
        (
            &cpfg,
            "Lsystem: 1\nderivation length: 2\nAxiom: X\nX --> F[+X]-X\n",
            "Y --> F(\n",
            "endlsystem\n",
            (2, 7),
        ),
        (
            LINF_URI,
            "lines f g\nangles (0, pi/2)\naxiom f\nrules f = f + f\n",
            "g = (\n",
            "",
            (3, 10),
        ),
        (gft, "axiom X\nX -> F[+X]-X\n", "widht 3\n", "", (0, 6)),
    ];
    let mut c = Client::start();
    let methods = [
        "textDocument/hover",
        "textDocument/definition",
        "textDocument/references",
    ];
    for (uri, before, broken, after, (line, column)) in cases {
        let ds = c.open(uri, &format!("{before}{after}"));
        assert!(!ds.iter().any(|d| d["severity"] == 1), "{uri}: {ds:?}");
        let clean: Vec<Value> = (methods.iter())
            .map(|m| c.at(m, uri, line, column)["result"].clone())
            .collect();
        let ds = c.change(uri, 2, &format!("{before}{broken}{after}"));
        assert!(ds.iter().any(|d| d["severity"] == 1), "{uri}: {ds:?}");
        for (method, clean) in methods.iter().zip(&clean) {
            let found = c.at(method, uri, line, column)["result"].clone();
            assert!(
                found.is_object() || found.as_array().is_some_and(|a| !a.is_empty()),
                "{uri} {method}: {found}"
            );
            assert_eq!(&found, clean, "{uri} {method}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}

#[test]
fn completion_and_outline() {
    let mut c = Client::start();
    let text = "derivation length: 2\nangle factor: 4\naxiom: X\nX --> F[+X]F[-X]+X\nF --> FF\n";
    c.open(URI, text);
    let r = c.at("textDocument/completion", URI, 4, 0);
    let items = r["result"].as_array().unwrap();
    let item = |label: &str| items.iter().find(|i| i["label"] == label).cloned();
    assert_eq!(item("angle factor").unwrap()["kind"], 14, "{r}"); // keyword
    let plus = item("+").unwrap();
    assert!(plus["detail"]
        .as_str()
        .unwrap()
        .contains("turns about its up axis U"));
    assert!(item("X").is_some(), "{r}");
    let s = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": URI } }),
    );
    let names: Vec<_> = s["result"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].clone())
        .collect();
    // The settings, then the productions, in the order written.
    let expected = [
        "derivation length: 2",
        "angle factor: 4",
        "axiom: X",
        "X",
        "F",
    ];
    assert_eq!(names, expected.map(|n| json!(n)));
    c.stop();
}

#[test]
fn an_unknown_request_is_an_error_and_the_server_goes_on() {
    let mut c = Client::start();
    let r = c.request("graftal/nothing", json!({}));
    assert_eq!(r["error"]["code"], -32601, "{r}");
    let r = c.request("textDocument/hover", json!({ "bad": 1 }));
    assert_eq!(r["error"]["code"], -32602, "{r}");
    assert_eq!(c.open(URI, FIXED), Vec::<Value>::new());
    c.stop();
}

/// Every request on a 10,000-line file answers within this bound: measured
/// in a debug build (the tests' profile) on 2 shared cores.
const BOUND: Duration = Duration::from_millis(200);

#[test]
fn a_ten_thousand_line_file_answers_every_request_quickly() {
    let Some(_timed) = slow_timed("lsp: every request on a 10,000-line file within 200 ms") else {
        return;
    };
    // 10,000 productions of `F` (each after the first shadowed: a warning
    // with related information apiece), with non-ASCII comments.
    let mut text = String::from("derivation length: 2\nangle factor: 4\naxiom: F\n");
    for i in 0..10_000 {
        text.push_str(&format!("F --> F+F-F /* é {i} */\n"));
    }
    // A `.gft` file of 10,000 lines, its layout not `graftal fmt`'s, a
    // comment on each line (each put back where it was written).
    let gft_uri = "file:///tmp/graftal-lsp-test/big.gft";
    let mut gft = String::from("axiom A0\nangle 90\n");
    for i in 0..9_998 {
        gft.push_str(&format!("A{i}  ->  F+A{}  /* é {i} */\n", i + 1));
    }
    let mut c = Client::start();
    // Each figure is the median of three runs: one run slowed by other
    // work on a loaded machine says nothing of the server. Before each run
    // of a request the document changes (untimed), so that each answer is
    // the first after a compile, as after a keystroke.
    let mut times = Vec::new();
    let mut version = 10;
    let mut time = |c: &mut Client, what: &'static str, run: &dyn Fn(&mut Client, usize)| {
        let mut runs: Vec<Duration> = (0..3)
            .map(|k| {
                if what.starts_with("textDocument/") && what != "textDocument/formatting" {
                    version += 1;
                    c.change(URI, version, &text.replacen("axiom: F", "axiom: F+F", 1));
                }
                let t = Instant::now();
                run(c, k);
                c.arrived - t
            })
            .collect();
        runs.sort();
        times.push((what, runs[1]));
    };
    time(&mut c, "open", &|c, _| {
        let ds = c.open(URI, &text);
        assert_eq!(ds.len(), 1_001); // the first 1,000 and a count of the rest
    });
    time(&mut c, "change", &|c, k| {
        let axiom = format!("axiom: F{}", "+F".repeat(k + 1));
        c.change(URI, 2 + k as i64, &text.replacen("axiom: F", &axiom, 1));
    });
    for (method, line, col) in [
        ("textDocument/hover", 2, 7),
        ("textDocument/definition", 2, 7),
        ("textDocument/references", 2, 7),
        ("textDocument/completion", 9_000, 0),
    ] {
        time(&mut c, method, &|c, _| {
            let r = c.at(method, URI, line, col);
            assert!(r.get("result").is_some(), "{r}");
        });
    }
    time(&mut c, "textDocument/documentSymbol", &|c, _| {
        c.request(
            "textDocument/documentSymbol",
            json!({ "textDocument": { "uri": URI } }),
        );
    });
    time(&mut c, "textDocument/codeAction", &|c, _| {
        let whole = json!({ "start": { "line": 0, "character": 0 }, "end": { "line": 10_003, "character": 0 } });
        let r = c.request(
            "textDocument/codeAction",
            json!({ "textDocument": { "uri": URI }, "range": whole, "context": { "diagnostics": [] } }),
        );
        assert!(r["result"].is_array(), "{r}");
    });
    c.open(gft_uri, &gft);
    time(&mut c, "textDocument/formatting", &|c, _| {
        let r = c.request(
            "textDocument/formatting",
            json!({ "textDocument": { "uri": gft_uri }, "options": { "tabSize": 4, "insertSpaces": true } }),
        );
        assert_eq!(r["result"].as_array().map(Vec::len), Some(1), "{r}");
        let formatted = r["result"][0]["newText"].as_str().unwrap_or("");
        assert!(formatted.ends_with("A9997 -> F+A9998 /* é 9997 */\n"));
    });
    eprintln!("answer times (median of 3): {times:?}");
    let slowest = times.iter().map(|t| t.1).max().unwrap();
    assert!(slowest < BOUND, "an answer took {slowest:?}: {times:?}");
    c.stop();
}

/// A Neovim configuration that starts `graftal lsp` ($GRAFTAL_EXE) on the
/// file it opens and writes the diagnostics Neovim holds for it, as JSON,
/// to $GRAFTAL_NVIM_OUT once the server has published them. Written for
/// Neovim 0.7 (Debian 12's), which has `start_client` but not `start`.
const NVIM_CONFIG: &str = r#"
local done = false
vim.api.nvim_create_autocmd("VimEnter", { callback = function()
  local id = vim.lsp.start_client({
    name = "graftal",
    cmd = { vim.env.GRAFTAL_EXE, "lsp" },
    root_dir = vim.fn.getcwd(),
    handlers = {
      ["textDocument/publishDiagnostics"] = function(err, result, ctx, config)
        vim.lsp.diagnostic.on_publish_diagnostics(err, result, ctx, config)
        local seen = {}
        for _, d in ipairs(vim.diagnostic.get(vim.uri_to_bufnr(result.uri))) do
          local lsp = d.user_data and d.user_data.lsp or {}
          table.insert(seen, { lnum = d.lnum, col = d.col, severity = d.severity,
                               code = d.code or lsp.code, message = d.message })
        end
        vim.fn.writefile({ vim.fn.json_encode(seen) }, vim.env.GRAFTAL_NVIM_OUT)
        done = true
      end,
    },
  })
  vim.lsp.buf_attach_client(0, id)
  vim.wait(20000, function() return done end, 50)
  vim.cmd("qa!")
end })
"#;

/// Neovim, as an editor runs it: `nvim --headless` opens a file with a
/// mistake, starts `graftal lsp`, and holds the diagnostic at the byte
/// column of the mistake (Neovim converts the UTF-16 column itself).
#[test]
fn neovim_shows_the_diagnostics_of_a_file_it_opens() {
    if !slow("lsp: Neovim end to end") {
        return;
    }
    let found = Command::new("nvim").arg("--version").output();
    if found.is_err() {
        // A fresh machine runs `cargo test` without an editor; CI installs
        // Neovim and sets GRAFTAL_NEED_NVIM=1, so there it cannot be missed.
        assert!(
            std::env::var("GRAFTAL_NEED_NVIM").as_deref() != Ok("1"),
            "nvim is not installed and GRAFTAL_NEED_NVIM=1: install Neovim \
             (`apt-get install neovim`; .ci/run does)"
        );
        eprintln!("nvim is not installed: the Neovim end-to-end test did not run");
        return;
    }
    let dir = std::env::temp_dir().join(format!("graftal-nvim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (config, file, out) = (
        dir.join("init.lua"),
        dir.join("plant.l"),
        dir.join("seen.json"),
    );
    std::fs::write(&config, NVIM_CONFIG).unwrap();
    std::fs::write(&file, BROKEN).unwrap();
    let status = Command::new("nvim")
        .args(["--headless", "-n", "-i", "NONE", "-u"])
        .arg(&config)
        .arg(&file)
        .current_dir(&dir)
        .env("GRAFTAL_EXE", env!("CARGO_BIN_EXE_graftal"))
        .env("GRAFTAL_NVIM_OUT", &out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .status()
        .expect("nvim runs");
    let seen = std::fs::read_to_string(&out);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(status.success(), "nvim: {status}");
    let seen: Value = serde_json::from_str(&seen.expect("Neovim wrote the diagnostics")).unwrap();
    let seen = seen.as_array().unwrap();
    assert_eq!(seen.len(), 1, "{seen:?}");
    let line = BROKEN.lines().nth(3).unwrap();
    assert_eq!(seen[0]["lnum"], 3);
    assert_eq!(seen[0]["col"], line.rfind("-->").unwrap());
    assert_eq!(seen[0]["code"], "E0003");
    assert_eq!(seen[0]["severity"], 1); // vim.diagnostic.severity.ERROR
}

/// A folder with a cpfg object: its `.l` and the files beside it.
fn cpfg_object(name: &str, files: &[(&str, &str)]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("graftal-lsp-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, text) in files {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir
}

const CPFG_PLANT: &str = "Lsystem: 1\n#define LEN 2\n#define GROW(x) F(x*LEN)\nderivation length: 2\nAxiom: F(1)\nF(x) --> GROW(x)\nendlsystem\n";

/// The view and function files of a cpfg object are read from disk beside
/// the document, and their problems published on their own URIs.
#[test]
fn cpfg_side_files_are_read_from_disk_and_reported_on_them() {
    let dir = cpfg_object(
        "side",
        &[
            ("plant.v", "angel factor: 16\nfunction: br.func\n"),
            ("br.func", "fver 1 1\nname: br\nsamples: 5\npoints: x\n"),
        ],
    );
    let uri = |f: &str| format!("file://{}", dir.join(f).display());
    let mut c = Client::start();
    let own = c.open(&uri("plant.l"), CPFG_PLANT);
    let view = c.diagnostics(&uri("plant.v"));
    let func = c.diagnostics(&uri("br.func"));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(own, Vec::<Value>::new());
    assert_eq!(view.len(), 1, "{view:?}");
    assert_eq!(view[0]["code"], "W0804");
    assert_eq!(
        view[0]["range"]["start"],
        json!({ "line": 0, "character": 0 })
    );
    assert_eq!(func.len(), 1, "{func:?}");
    assert_eq!(func[0]["code"], "E0813");
    assert_eq!(func[0]["range"]["start"]["line"], 3);
    c.stop();
}

/// Problems inside an `#include`d file, whether the preprocessor's (an
/// unknown directive) or the reader's (a production cut short), are
/// published on that file's own URI, at their own line, with a note naming
/// the `#include` line; the document itself has none.
#[test]
fn problems_of_an_included_file_are_reported_on_it() {
    let dir = cpfg_object(
        "include",
        &[
            ("leaf.h", "B --> F(1\n#bogus\n"),
            ("plant.v", "angle factor: 8\n"),
        ],
    );
    let uri = |f: &str| format!("file://{}", dir.join(f).display());
    let plant =
        "Lsystem: 1\n#include \"leaf.h\"\nderivation length: 2\nAxiom: A\nA --> B\nendlsystem\n";
    let mut c = Client::start();
    let own = c.open(&uri("plant.l"), plant);
    let inc = c.diagnostics(&uri("leaf.h"));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(own, Vec::<Value>::new());
    let found: Vec<_> = (inc.iter())
        .map(|d| {
            (
                d["code"].as_str().unwrap(),
                d["range"]["start"]["line"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(found, [("E0805", 1), ("E0003", 0)], "{inc:?}");
    for d in &inc {
        let message = d["message"].as_str().unwrap();
        assert!(
            message.contains("`leaf.h` is included at line 2"),
            "{message}"
        );
    }
    c.stop();
}

/// The hover text at (`line`, `character`) of `uri`.
fn hover_text(c: &mut Client, uri: &str, line: u32, character: u32) -> String {
    let h = c.at("textDocument/hover", uri, line, character);
    h["result"]["contents"]["value"]
        .as_str()
        .unwrap_or_else(|| panic!("no hover: {h}"))
        .to_string()
}

/// The start lines of the `Location[]` `r` answered.
fn lines_of(r: &Value) -> Vec<u64> {
    let found = r["result"].as_array().unwrap_or_else(|| panic!("{r}"));
    found
        .iter()
        .map(|l| l["range"]["start"]["line"].as_u64().unwrap())
        .collect()
}

const STL_URI: &str = "file:///tmp/graftal-lsp-test/tree.stl";
const STL_TREE: &str =
    "ANGLE 30\nLEVELS 3\nR1 = [I 4 [F]] R2\nR2 = F[+R1][-R1]\nSEED\nR2\nENDSEED\n";

#[test]
fn stl_rules_hover_define_and_are_referenced() {
    let mut c = Client::start();
    c.open(STL_URI, STL_TREE);
    // `R1` in the body of R2.
    let value = hover_text(&mut c, STL_URI, 3, 8);
    assert!(value.contains("STL rule `R1` = `[I 4 [F]] R2`"), "{value}");
    assert!(value.contains("self-resemblance count 4"), "{value}");
    let d = c.at("textDocument/definition", STL_URI, 3, 8);
    assert_eq!(lines_of(&d), [2], "{d}");
    assert_eq!(d["result"][0]["range"]["end"]["character"], 2);
    // `R2`: declared on line 4, used in R1's body and the seed.
    let r = c.at("textDocument/references", STL_URI, 5, 0);
    assert_eq!(lines_of(&r), [2, 3, 5], "{r}");
    c.stop();
}

/// Where the `Location[]` `r` answered starts and ends: (line, from, to).
fn places_of(r: &Value) -> Vec<(u64, u64, u64)> {
    let found = r["result"].as_array().unwrap_or_else(|| panic!("{r}"));
    let at = |l: &Value, end: &str, k: &str| l["range"][end][k].as_u64().unwrap();
    (found.iter())
        .map(|l| {
            (
                at(l, "start", "line"),
                at(l, "start", "character"),
                at(l, "end", "character"),
            )
        })
        .collect()
}

#[test]
fn stl_rules_glued_to_other_letters_are_used_and_names_in_comments_are_not() {
    let uri = "file:///tmp/graftal-lsp-test/glued.stl";
    let text = "ANGLE 30\n# R1 draws; R1 here is no use\nR1 = [F][+F]\nR2 = FR1LFR1\nSEED\nFR2 # R2\nENDSEED\n";
    let mut c = Client::start();
    assert_eq!(c.open(uri, text), Vec::<Value>::new());
    // R1 in `FR1LFR1`: after F, and after L F.
    let r = c.at("textDocument/references", uri, 2, 0);
    assert_eq!(places_of(&r), [(2, 0, 2), (3, 6, 8), (3, 10, 12)], "{r}");
    let d = c.at("textDocument/definition", uri, 3, 11);
    assert_eq!(places_of(&d), [(2, 0, 2)], "{d}");
    let r = c.at("textDocument/references", uri, 5, 2);
    assert_eq!(places_of(&r), [(3, 0, 2), (5, 1, 3)], "{r}");
    c.stop();
}

#[test]
fn names_in_comments_are_not_references() {
    let mut c = Client::start();
    let uri = "file:///tmp/graftal-lsp-test/commented.linf";
    c.open(
        uri,
        "# t turns\nlines f\nangles t = (0, pi/3)\naxiom f\nrules f = f +t f # f again\n",
    );
    let r = c.at("textDocument/references", uri, 2, 7);
    assert_eq!(places_of(&r), [(2, 7, 8), (4, 13, 14)], "{r}");
    let uri = "file:///tmp/graftal-lsp-test/commented.l";
    let cpfg = "/* N and\n   N */\n#define N 5 // N\nLsystem: 1\nderivation length: 1\nAxiom: F(N)\nendlsystem\n";
    c.open(uri, cpfg);
    let r = c.at("textDocument/references", uri, 2, 8);
    assert_eq!(places_of(&r), [(2, 8, 9), (5, 9, 10)], "{r}");
    c.stop();
}

const LINF_URI: &str = "file:///tmp/graftal-lsp-test/curve.linf";
const LINF_CURVE: &str = "lines f\nangles t = (0, pi/3)\naxiom f\nrules f = f +t f\n";

#[test]
fn linf_rotations_and_declared_names() {
    let mut c = Client::start();
    let ds = c.open(LINF_URI, LINF_CURVE);
    assert_eq!(ds, Vec::<Value>::new());
    // `t` in the rule: its pair.
    let value = hover_text(&mut c, LINF_URI, 3, 13);
    assert!(value.contains("LinF rotation `t` = `(0, pi/3)`"), "{value}");
    let d = c.at("textDocument/definition", LINF_URI, 3, 13);
    assert_eq!(lines_of(&d), [1], "{d}");
    // `f`: declared in `lines`, rewritten on line 4; written five times.
    let d = c.at("textDocument/definition", LINF_URI, 2, 6);
    assert_eq!(lines_of(&d), [0, 3], "{d}");
    let r = c.at("textDocument/references", LINF_URI, 2, 6);
    assert_eq!(lines_of(&r), [0, 2, 3, 3, 3], "{r}");
    c.stop();
}

#[test]
fn cpfg_macros_hover_with_their_expansion() {
    let dir = cpfg_object("macros", &[]);
    let uri = format!("file://{}", dir.join("plant.l").display());
    let mut c = Client::start();
    c.open(&uri, CPFG_PLANT);
    // `GROW` in the production of line 6.
    let value = hover_text(&mut c, &uri, 5, 10);
    assert!(
        value.contains("function-like macro `GROW`: expands as `#define GROW(x) F(x*LEN)`"),
        "{value}"
    );
    let d = c.at("textDocument/definition", &uri, 5, 10);
    assert_eq!(lines_of(&d), [2], "{d}");
    // `LEN`: defined on line 2, used in GROW's expansion.
    let r = c.at("textDocument/references", &uri, 1, 9);
    assert_eq!(lines_of(&r), [1, 2], "{r}");
    let s = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": uri } }),
    );
    let names: Vec<_> = (s["result"].as_array().unwrap().iter())
        .map(|s| s["name"].as_str().unwrap().to_string())
        .collect();
    assert!(names.contains(&"LEN".to_string()), "{names:?}");
    assert!(
        names.contains(&"derivation length: 2".to_string()),
        "{names:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}

const FRACTINT_URI: &str = "file:///tmp/graftal-lsp-test/lib.l";
const FRACTINT_LIB: &str =
    "Koch {\n  Angle 6\n  Axiom F\n  F=F+F--F+F\n}\nDragon {\n  Angle 4\n  Axiom FX\n  X=X+YF+\n  Y=-FX-Y\n}\n";

#[test]
fn fractint_entries_are_outlined_and_defined() {
    let mut c = Client::start();
    c.open(FRACTINT_URI, FRACTINT_LIB);
    let s = c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": FRACTINT_URI } }),
    );
    let entries: Vec<_> = (s["result"].as_array().unwrap().iter())
        .filter(|s| s["kind"] == 2) // module
        .map(|s| (s["name"].clone(), s["range"]["start"]["line"].clone()))
        .collect();
    assert_eq!(
        entries,
        [(json!("Koch"), json!(0)), (json!("Dragon"), json!(5))]
    );
    let d = c.at("textDocument/definition", FRACTINT_URI, 5, 2);
    assert_eq!(lines_of(&d), [5], "{d}");
    let value = hover_text(&mut c, FRACTINT_URI, 5, 2);
    assert!(value.contains("Fractint entry `Dragon`"), "{value}");
    c.stop();
}

#[test]
fn a_code_written_in_a_comment_hovers_with_its_explanation() {
    let mut c = Client::start();
    let text = "/* see E0003 */\nderivation length: 2\naxiom: F\nF --> F+F\n";
    c.open(URI, text);
    let value = hover_text(&mut c, URI, 0, 9);
    assert!(value.contains(explain("E0003").trim()), "{value}");
    c.stop();
}

/// The quick fixes offered over the range of diagnostic `d` of `uri`.
fn quick_fixes(c: &mut Client, uri: &str, d: &Value) -> Vec<Value> {
    code_actions(c, uri, d["range"].clone(), &[d])
}

/// `text` with the single edit of quick fix `fix` made.
fn apply(text: &str, uri: &str, fix: &Value) -> String {
    let edits = fix["edit"]["changes"][uri].as_array().unwrap();
    assert_eq!(edits.len(), 1, "{fix}");
    let at = |p: &Value| {
        let line = p["line"].as_u64().unwrap() as usize;
        let start: usize = text.split_inclusive('\n').take(line).map(str::len).sum();
        start + p["character"].as_u64().unwrap() as usize // ASCII here
    };
    let r = &edits[0]["range"];
    let mut out = text.to_string();
    out.replace_range(
        at(&r["start"])..at(&r["end"]),
        edits[0]["newText"].as_str().unwrap(),
    );
    out
}

/// Each diagnostic that knows its fix offers it as a quick fix, and the
/// fixed text has no diagnostic left: a mistyped pfg header, a cpfg `->`,
/// an unknown STL rule, a mistyped `.gft` keyword.
#[test]
fn quick_fixes_make_the_suggested_replacement() {
    let dir = cpfg_object("fixes", &[]);
    let cpfg = format!("file://{}", dir.join("plant.l").display());
    let gft = "file:///tmp/graftal-lsp-test/fix.gft";
    let cases = [
        (
            URI,
            "derivation length: 2\nangel factor: 4\naxiom: F\nF --> F+F\n",
            "E0101",
            "angle factor",
        ),
        (
            cpfg.as_str(),
            "Lsystem: 1\nderivation length: 2\nAxiom: F\nF -> F+F\nendlsystem\n",
            "E0005",
            "-->",
        ),
        (
            STL_URI,
            "ANGLE 30\nR1 = [F]\nSEED\nR2\nENDSEED\n",
            "E0501",
            "R1",
        ),
        (gft, "axiom F\nF -> F+F\nwidht 3\n", "E0900", "width"),
    ];
    let mut c = Client::start();
    for (uri, text, code, replacement) in cases {
        let ds = c.open(uri, text);
        let d = ds
            .iter()
            .find(|d| d["code"] == code)
            .unwrap_or_else(|| panic!("{code}: {ds:?}"));
        let fixes = quick_fixes(&mut c, uri, d);
        assert_eq!(fixes.len(), 1, "{fixes:?}");
        assert_eq!(fixes[0]["kind"], "quickfix");
        let fixed = apply(text, uri, &fixes[0]);
        assert!(fixed.contains(replacement), "{fixed}");
        let left = c.change(uri, 2, &fixed);
        assert!(!left.iter().any(|d| d["code"] == code), "{code}: {left:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}

/// The code actions over `range` of `uri`, the client listing `listed`.
fn code_actions(c: &mut Client, uri: &str, range: Value, listed: &[&Value]) -> Vec<Value> {
    let r = c.request(
        "textDocument/codeAction",
        json!({
            "textDocument": { "uri": uri },
            "range": range,
            "context": { "diagnostics": listed },
        }),
    );
    r["result"]
        .as_array()
        .unwrap_or_else(|| panic!("{r}"))
        .clone()
}

/// Each diagnostic of a malformed arrow offers its fix however it is asked
/// for: over its range (VS Code), over a cursor inside it, and over the
/// cursor at its line's start with the line's diagnostics listed (Neovim);
/// in pfg (each arrow of a file of several), cpfg and LinF.
#[test]
fn every_arrow_diagnostic_offers_its_fix_wherever_it_is_asked() {
    let dir = cpfg_object("arrows", &[]);
    let cpfg = format!("file://{}", dir.join("plant.l").display());
    let cases = [
        (
            URI,
            "derivation length: 2\naxiom: F\nF -> F+F\nG => FF\nH ==> F\n",
            3,
        ),
        (
            &cpfg,
            "Lsystem: 1\nderivation length: 2\nAxiom: F\nF -> F+F\nG -> FF\nendlsystem\n",
            2,
        ),
        (LINF_URI, "lines f\naxiom f\nrules f -> f + f\n", 1),
    ];
    let mut c = Client::start();
    let arrows = |ds: &[Value]| ds.iter().filter(|d| d["code"] == "E0005").count();
    for (uri, text, n) in cases {
        let ds = c.open(uri, text);
        assert_eq!(arrows(&ds), n, "{uri}: {ds:?}");
        for (k, d) in ds.iter().filter(|d| d["code"] == "E0005").enumerate() {
            let line = &d["range"]["start"]["line"];
            let inside = &d["range"]["start"]["character"].as_u64().unwrap() + 1;
            let cursor = |column: u64| {
                let at = json!({ "line": line, "character": column });
                json!({ "start": at, "end": at })
            };
            let asked = [
                code_actions(&mut c, uri, d["range"].clone(), &[d]),
                code_actions(&mut c, uri, cursor(inside), &[]),
                code_actions(&mut c, uri, cursor(0), &[d]),
            ];
            for fixes in &asked {
                assert_eq!(fixes.len(), 1, "{uri} arrow {k}: {fixes:?}");
                assert_eq!(fixes[0]["edit"], asked[0][0]["edit"], "{uri} arrow {k}");
            }
            let left = c.change(uri, 2, &apply(text, uri, &asked[0][0]));
            assert_eq!(arrows(&left), n - 1, "{uri} arrow {k}: {left:?}");
            c.change(uri, 3, text);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}

/// A client that takes no code action literals (no
/// `codeActionLiteralSupport`) gets each quick fix as a command the server
/// advertises; running it has the server ask the client to make the fix
/// (`workspace/applyEdit`), and the server goes on after the client's
/// answer to that and after commands it cannot run.
#[test]
fn a_client_without_code_action_literals_gets_commands_that_apply_the_fix() {
    let mut c = Client::start_with(json!({}));
    let commands = &c.initialized["capabilities"]["executeCommandProvider"]["commands"];
    assert_eq!(*commands, json!(["graftal.applyFix"]), "{}", c.initialized);
    let text = "derivation length: 2\naxiom: F\nF -> F+F\nG --> FF\n";
    let ds = c.open(URI, text);
    let d = (ds.iter().find(|d| d["code"] == "E0005")).unwrap_or_else(|| panic!("{ds:?}"));
    let actions = quick_fixes(&mut c, URI, d);
    assert_eq!(actions.len(), 1, "{actions:?}");
    let command = &actions[0];
    assert_eq!(command["command"], "graftal.applyFix", "{command}");
    assert!(
        command.get("edit").is_none(),
        "not a code action: {command}"
    );
    let run = json!({ "command": command["command"], "arguments": command["arguments"] });
    let r = c.request("workspace/executeCommand", run);
    assert_eq!(r["result"], Value::Null, "{r}");
    let (_, asked) = (c.notes.iter())
        .find(|(_, m)| m["method"] == "workspace/applyEdit")
        .unwrap_or_else(|| panic!("no workspace/applyEdit: {:?}", c.notes))
        .clone();
    assert!(
        asked["id"].is_string() || asked["id"].is_number(),
        "{asked}"
    );
    let fixed = apply(text, URI, &asked["params"]);
    assert_eq!(fixed, text.replace("F -> F", "F --> F"));
    c.send(json!({ "jsonrpc": "2.0", "id": asked["id"], "result": { "applied": true } }));
    for bad in [
        json!({ "command": "graftal.nothing" }),
        json!({ "command": "graftal.applyFix", "arguments": [1, 2] }),
        json!({ "command": "graftal.applyFix", "arguments": [{ "edit": 3 }] }),
    ] {
        let r = c.request("workspace/executeCommand", bad);
        assert!(r["error"]["message"].is_string(), "{r}");
    }
    let left = c.change(URI, 2, &fixed);
    assert!(!left.iter().any(|d| d["code"] == "E0005"), "{left:?}");
    c.stop();
}

/// The suggestions that were help text only now carry their replacement:
/// cpfg's preprocessor directive, gft's turtle operation, and the cpfg
/// view file's command (a fix asked for on the view file's own URI).
#[test]
fn directive_operation_and_view_suggestions_are_quick_fixes() {
    let dir = cpfg_object("fixes2", &[("plant.v", "angel factor: 16\n")]);
    let uri = |f: &str| format!("file://{}", dir.join(f).display());
    let gft = "file:///tmp/graftal-lsp-test/op.gft";
    let plant = "Lsystem: 1\n#defien N 2\nderivation length: 2\nAxiom: F\nF --> F+F\nendlsystem\n";
    let mut c = Client::start();
    let mut cases = vec![];
    let ds = c.open(&uri("plant.l"), plant);
    cases.push((
        uri("plant.l"),
        plant.to_string(),
        ds,
        "E0805",
        "#define N 2",
    ));
    let view = c.diagnostics(&uri("plant.v"));
    cases.push((
        uri("plant.v"),
        "angel factor: 16\n".into(),
        view,
        "W0804",
        "angle factor: 16",
    ));
    let text = "axiom F\nF -> F+F\nG = forwrd\n";
    let ds = c.open(gft, text);
    cases.push((
        gft.to_string(),
        text.to_string(),
        ds,
        "E0902",
        "G = forward",
    ));
    for (uri, text, ds, code, fixed) in cases {
        let d = (ds.iter().find(|d| d["code"] == code)).unwrap_or_else(|| panic!("{code}: {ds:?}"));
        let fixes = quick_fixes(&mut c, &uri, d);
        assert_eq!(fixes.len(), 1, "{code}: {fixes:?}");
        let out = apply(&text, &uri, &fixes[0]);
        assert!(out.contains(fixed), "{code}: {out}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}

#[test]
fn formatting_a_gft_file_is_what_graftal_fmt_writes() {
    let uri = "file:///tmp/graftal-lsp-test/plant.gft";
    let messy = "axiom   F\nangle 90\n   F -> F+F-F\n";
    let fmt = Command::new(env!("CARGO_BIN_EXE_graftal"))
        .args(["fmt", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .and_then(|mut p| {
            p.stdin.take().unwrap().write_all(messy.as_bytes())?;
            p.wait_with_output()
        })
        .unwrap();
    let expected = String::from_utf8(fmt.stdout).unwrap();
    assert_ne!(expected, messy);
    let mut c = Client::start();
    c.open(uri, messy);
    let params = json!({ "textDocument": { "uri": uri }, "options": { "tabSize": 4, "insertSpaces": true } });
    let r = c.request("textDocument/formatting", params.clone());
    let edits = r["result"].as_array().unwrap_or_else(|| panic!("{r}"));
    assert_eq!(edits.len(), 1, "{r}");
    assert_eq!(edits[0]["newText"], expected.as_str());
    assert_eq!(
        edits[0]["range"]["start"],
        json!({ "line": 0, "character": 0 })
    );
    assert_eq!(
        edits[0]["range"]["end"],
        json!({ "line": 3, "character": 0 })
    );
    // Formatted already: no edit. Not readable: no edit, and no error.
    c.change(uri, 2, &expected);
    let r = c.request("textDocument/formatting", params.clone());
    assert_eq!(r["result"], json!([]), "{r}");
    c.change(uri, 3, "axiom F\nF -> F+F\nwidht 3\n");
    let r = c.request("textDocument/formatting", params);
    assert_eq!(r["result"], json!([]), "{r}");
    c.stop();
}

/// A file half typed in each notation gives diagnostics, not an error.
#[test]
fn a_half_typed_file_of_each_notation_gives_diagnostics() {
    let dir = cpfg_object("half", &[]);
    let cpfg = format!("file://{}", dir.join("plant.l").display());
    let cases = [
        (URI.to_string(), "derivation length: 2\naxiom: F\nF -"),
        (cpfg, "Lsystem: 1\nAxiom: F(1\nF(x) --> F(x"),
        (
            FRACTINT_URI.to_string(),
            "Koch {\n  Angle 6\n  Axiom F\n  F=F+F--F+F\n\nDragon {\n  Ang",
        ),
        (
            LINF_URI.to_string(),
            "lines f\nangles t = (0, pi/\naxiom f\nrules f = f +",
        ),
        (STL_URI.to_string(), "ANGLE 30\nR1 = [I 4 [F\nSEED\nR"),
        (
            "file:///tmp/graftal-lsp-test/half.gft".to_string(),
            "axiom F\nF -> F+(\nangle",
        ),
        (
            "file:///tmp/graftal-lsp-test/half.smith".to_string(),
            "angle: 3\naxiom: F\nrules:\n F ->",
        ),
    ];
    let mut c = Client::start();
    for (uri, text) in &cases {
        let ds = c.open(uri, text);
        assert!(!ds.is_empty(), "{uri}: no diagnostics");
        for method in [
            "textDocument/hover",
            "textDocument/completion",
            "textDocument/definition",
        ] {
            let r = c.at(method, uri, 1, 3);
            assert!(r.get("result").is_some(), "{uri} {method}: {r}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}

/// The README's block fenced as ```LANG that holds `marker`.
fn readme_block(lang: &str, marker: &str) -> String {
    let readme = include_str!("../../README.md");
    let fence = format!("```{lang}\n");
    (readme.split(fence.as_str()).skip(1))
        .filter_map(|b| b.split("```").next())
        .find(|b| b.contains(marker))
        .unwrap_or_else(|| panic!("no ```{lang} block with `{marker}` in the README"))
        .to_string()
}

/// The notations' extensions an editor must hand to `graftal lsp`.
const EXTENSIONS: [&str; 4] = ["l", "linf", "stl", "gft"];

#[test]
fn the_readme_configures_helix_and_vs_code_as_they_read_it() {
    let helix: toml::Table = toml::from_str(&readme_block("toml", "[language-server.graftal]"))
        .unwrap_or_else(|e| panic!("the Helix block is not TOML: {e}"));
    let server = &helix["language-server"]["graftal"];
    assert_eq!(server["command"].as_str(), Some("graftal"));
    assert_eq!(server["args"], toml::Value::Array(vec!["lsp".into()]));
    let languages = helix["language"].as_array().expect("[[language]]");
    let uses_graftal = |l: &&toml::Value| {
        (l.get("language-servers").and_then(|s| s.as_array()))
            .is_some_and(|s| s.contains(&"graftal".into()))
    };
    let language = languages
        .iter()
        .find(uses_graftal)
        .expect("a language served by graftal");
    for key in ["name", "scope"] {
        assert!(
            language.get(key).and_then(|v| v.as_str()).is_some(),
            "Helix needs `{key}`"
        );
    }
    let types = language["file-types"].as_array().expect("file-types");
    for ext in EXTENSIONS {
        assert!(types.contains(&ext.into()), "Helix file-types lack {ext}");
    }
    let vscode: Value = serde_json::from_str(&readme_block("json", "glspc"))
        .unwrap_or_else(|e| panic!("the VS Code block is not JSON: {e}"));
    assert_eq!(vscode["glspc.server.command"], "graftal");
    assert_eq!(vscode["glspc.server.commandArguments"], json!(["lsp"]));
    let served = vscode["glspc.server.languageId"]
        .as_array()
        .expect("languageId");
    for ext in EXTENSIONS {
        let id = &vscode["files.associations"][format!("*.{ext}")];
        assert!(
            served.contains(id),
            "VS Code does not hand *.{ext} ({id}) to graftal"
        );
    }
}

/// A copy of the cpfg object `tests/corpus/cpfg/NAME` in a folder of its own.
fn corpus_object(name: &str) -> std::path::PathBuf {
    let from = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus/cpfg")
        .join(name);
    let dir = cpfg_object(name, &[]);
    for entry in std::fs::read_dir(&from).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, dir.join(path.file_name().unwrap())).unwrap();
    }
    dir
}

/// Where `needle` is written in `text`, as (line, character) of its start.
fn line_and_column(text: &str, needle: &str) -> (u32, u32) {
    let at = text.find(needle).unwrap_or_else(|| panic!("no {needle}"));
    let line = text[..at].matches('\n').count();
    let column = at - text[..at].rfind('\n').map_or(0, |i| i + 1);
    (line as u32, column as u32)
}

#[test]
fn cpfg_user_functions_are_defined_in_their_files_and_hover_with_their_points() {
    // `func(BR_ANGLE, …)`: a function of the set the view file names.
    let dir = corpus_object("10-GettingStarted-01-Lychnis");
    let text = std::fs::read_to_string(dir.join("plant.l")).unwrap();
    let uri = format!("file://{}", dir.join("plant.l").display());
    let mut c = Client::start();
    c.open(&uri, &text);
    let (line, column) = line_and_column(&text, "func(BR_ANGLE");
    let d = c.at("textDocument/definition", &uri, line, column + 7);
    let fset = format!("file://{}", dir.join("functions.fset").display());
    assert_eq!(d["result"][0]["uri"], fset.as_str(), "{d}");
    let set = std::fs::read_to_string(dir.join("functions.fset")).unwrap();
    let (name_line, name_column) = line_and_column(&set, "BR_ANGLE");
    assert_eq!(
        places_of(&d),
        [(name_line as u64, name_column as u64, name_column as u64 + 8)]
    );
    let value = hover_text(&mut c, &uri, line, column + 7);
    assert!(value.contains("cpfg user function `BR_ANGLE`"), "{value}");
    assert!(
        value.contains("samples: 100; 4 points: (0, -0.659485)"),
        "{value}"
    );
    // Not the definition of a name in another call.
    let (line, column) = line_and_column(&text, "t/LENBR");
    let d = c.at("textDocument/definition", &uri, line, column + 3);
    assert!(!d.to_string().contains(".fset"), "{d}");
    let _ = std::fs::remove_dir_all(&dir);
    // `func(2, …)`: the view file's second `function:` file.
    let dir = corpus_object("02-Mod-vis-3D-05-monopodial");
    let text = std::fs::read_to_string(dir.join("leaf.l")).unwrap();
    let uri = format!("file://{}", dir.join("leaf.l").display());
    c.open(&uri, &text);
    let (line, column) = line_and_column(&text, "func(2,");
    let d = c.at("textDocument/definition", &uri, line, column + 5);
    let file = format!("file://{}", dir.join("leaf-length.func").display());
    assert_eq!(d["result"][0]["uri"], file.as_str(), "{d}");
    assert_eq!(d["result"][0]["range"]["start"]["line"], 1, "{d}");
    let value = hover_text(&mut c, &uri, line, column + 5);
    assert!(
        value.contains("(function 2 of `leaf-length.func`)"),
        "{value}"
    );
    let _ = std::fs::remove_dir_all(&dir);
    c.stop();
}
