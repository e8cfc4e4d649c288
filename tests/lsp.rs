//! `graftal lsp` driven as an editor drives it: the real binary, JSON-RPC
//! over its standard input and output (LSP 3.17 base protocol).

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

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

impl Client {
    /// Starts `graftal lsp` and initializes it.
    fn start() -> Client {
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
        };
        let init = c.request("initialize", json!({ "capabilities": {} }));
        assert!(
            init["result"]["capabilities"]["hoverProvider"] == json!(true),
            "{init}"
        );
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
    assert_eq!(names, vec![json!("X"), json!("F")]);
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
    // 10,000 productions of `F` (each after the first shadowed: a warning
    // with related information apiece), with non-ASCII comments.
    let mut text = String::from("derivation length: 2\nangle factor: 4\naxiom: F\n");
    for i in 0..10_000 {
        text.push_str(&format!("F --> F+F-F /* é {i} */\n"));
    }
    let mut c = Client::start();
    let t = Instant::now();
    let ds = c.open(URI, &text);
    let open = c.arrived - t;
    assert_eq!(ds.len(), 1_001); // the first 1,000 and a count of the rest
    let t = Instant::now();
    c.change(URI, 2, &text.replacen("axiom: F", "axiom: F+F", 1));
    let change = c.arrived - t;
    let mut times = vec![("open", open), ("change", change)];
    for (method, line, col) in [
        ("textDocument/hover", 2, 7),
        ("textDocument/definition", 2, 7),
        ("textDocument/references", 2, 7),
        ("textDocument/completion", 9_000, 0),
    ] {
        let t = Instant::now();
        let r = c.at(method, URI, line, col);
        times.push((method, c.arrived - t));
        assert!(r.get("result").is_some(), "{r}");
    }
    let t = Instant::now();
    c.request(
        "textDocument/documentSymbol",
        json!({ "textDocument": { "uri": URI } }),
    );
    times.push(("textDocument/documentSymbol", c.arrived - t));
    eprintln!("answer times: {times:?}");
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
