//! `graftal serve`: a local web server with a page where a model is
//! edited and its picture and diagnostics follow as it is typed. A thin
//! face: it reads HTTP requests (tiny_http, synchronous, as the rest of
//! graftal is), checks who sent them ([`guard`]), and answers them with
//! the library's calls ([`api`]); the page itself (web/, built with npm
//! and esbuild, committed) is inside the binary ([`assets`]).

mod api;
mod assets;
mod guard;
mod json;
mod pages;

pub use api::{MAX_FRAMES, MAX_FRAME_BYTES, PAGE_MAX_MOVES, PAGE_MAX_SYMBOLS};
pub use guard::MAX_BODY;

use crate::front::Front;
use std::io::Write;
use std::net::SocketAddr;
use std::path::PathBuf;
use tiny_http::{Header, Method, Response, Server};

/// How many requests are answered at once: a page's requests wait on
/// each other ([`pages`]), so this is how many pages work side by side.
const WORKERS: usize = 4;

/// What `graftal serve` was asked to serve.
pub struct Options {
    /// A path (saved to), `std:NAME` (not saved), or nothing: an empty
    /// pfg model.
    pub file: Option<String>,
    /// Where to listen: loopback unless told otherwise.
    pub addr: SocketAddr,
}

/// What the server serves: the file's name, path and text as started,
/// its notation, the pages, and the names it answers to.
pub struct Served {
    /// The file's name as the page shows it.
    pub name: Option<String>,
    /// Where Save writes: the served file, when it is a path.
    pub path: Option<PathBuf>,
    pub text: String,
    pub notation: &'static dyn Front,
    pages: pages::Pages,
    names: guard::Names,
}

/// Starts the server, says where to open the page on `out`, and answers
/// requests until the process ends. `Err` when the file cannot be read or
/// the address cannot be listened on.
pub fn run(opts: &Options, out: &mut dyn Write) -> Result<(), String> {
    let (server, served) = start(opts)?;
    let addr = served.names.first().to_string();
    let _ = writeln!(out, "graftal serve: open http://{addr}/");
    let _ = out.flush();
    serve(&server, &served);
    Ok(())
}

/// Listens and reads the file: the server and what it serves.
pub fn start(opts: &Options) -> Result<(Server, Served), String> {
    let (name, path, text) = read_file(opts.file.as_deref())?;
    let file = crate::source::SourceFile::new(name.clone().unwrap_or_default(), text.as_str());
    let notation = crate::driver::compile(file).front;
    let server =
        Server::http(opts.addr).map_err(|e| format!("cannot listen on {}: {e}", opts.addr))?;
    let addr = server
        .server_addr()
        .to_ip()
        .ok_or("the server listens on no IP address")?;
    let served = Served {
        name,
        path,
        text,
        notation,
        pages: pages::Pages::default(),
        names: guard::Names::of(addr),
    };
    Ok((server, served))
}

/// The served file's name, path (when it is one) and text; a path that
/// does not exist yet is an empty model, created when saved.
fn read_file(file: Option<&str>) -> Result<(Option<String>, Option<PathBuf>, String), String> {
    let Some(spec) = file else {
        return Ok((None, None, String::new()));
    };
    if spec.starts_with("std:") {
        let f = crate::driver::load(spec).map_err(|e| e.to_string())?;
        return Ok((Some(spec.to_string()), None, f.text.to_string()));
    }
    let path = PathBuf::from(spec);
    let text = if path.exists() {
        crate::driver::load(spec)
            .map_err(|e| e.to_string())?
            .text
            .to_string()
    } else {
        String::new()
    };
    Ok((Some(spec.to_string()), Some(path), text))
}

/// Answers requests on [`WORKERS`] threads until the server stops.
pub fn serve(server: &Server, served: &Served) {
    std::thread::scope(|scope| {
        for _ in 0..WORKERS {
            scope.spawn(|| {
                while let Ok(request) = server.recv() {
                    answer(request, served);
                }
            });
        }
    });
}

/// Answers one request; a panic while answering is a 500, and the
/// server goes on.
fn answer(mut request: tiny_http::Request, served: &Served) {
    let header = |name: &'static str| {
        (request.headers().iter())
            .find(|h| h.field.equiv(name))
            .map(|h| h.value.as_str().to_string())
    };
    let (host, origin) = (header("Host"), header("Origin"));
    let reply = match served.names.refuses(host.as_deref(), origin.as_deref()) {
        Some(why) => Reply::error(403, &why),
        None => {
            let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                route(&mut request, served)
            }));
            caught.unwrap_or_else(|_| Reply::error(500, "graftal failed on this request"))
        }
    };
    let _ = request.respond(reply.response());
}

/// An answer: status, media type, body, and a file name for a download.
struct Reply {
    status: u16,
    media_type: &'static str,
    body: Vec<u8>,
    download: Option<String>,
}

impl Reply {
    fn ok(media_type: &'static str, body: impl Into<Vec<u8>>) -> Reply {
        Reply {
            status: 200,
            media_type,
            body: body.into(),
            download: None,
        }
    }

    fn json(value: &serde_json::Value) -> Reply {
        Reply::ok("application/json; charset=utf-8", value.to_string())
    }

    fn error(status: u16, message: &str) -> Reply {
        Reply {
            status,
            ..Reply::json(&serde_json::json!({ "error": message }))
        }
    }

    fn response(self) -> Response<std::io::Cursor<Vec<u8>>> {
        let mut headers = vec![
            ("Content-Type", self.media_type.to_string()),
            ("Cache-Control", "no-store".to_string()),
            ("X-Content-Type-Options", "nosniff".to_string()),
            // Nothing from elsewhere; CodeMirror writes its styles inline.
            (
                "Content-Security-Policy",
                "default-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:"
                    .to_string(),
            ),
        ];
        if let Some(name) = &self.download {
            let name: String = name.chars().filter(|c| c.is_ascii_graphic()).collect();
            let name = name.replace('"', "");
            headers.push((
                "Content-Disposition",
                format!("attachment; filename=\"{name}\""),
            ));
        }
        // A length, never chunks: every answer is whole when it is sent.
        let mut response = Response::from_data(self.body)
            .with_status_code(self.status)
            .with_chunked_threshold(usize::MAX);
        for (field, value) in headers {
            if let Ok(h) = Header::from_bytes(field.as_bytes(), value.as_bytes()) {
                response.add_header(h);
            }
        }
        response
    }
}

/// The answer to a request that passed the guard.
fn route(request: &mut tiny_http::Request, served: &Served) -> Reply {
    let path = request.url().split('?').next().unwrap_or("").to_string();
    // HEAD is answered as GET (tiny_http sends no body for it).
    let method = match request.method() {
        Method::Head => Method::Get,
        m => m.clone(),
    };
    match (method, path.as_str()) {
        (Method::Get, "/") | (Method::Get, "/index.html") => {
            Reply::ok("text/html; charset=utf-8", assets::INDEX_HTML)
        }
        (Method::Get, "/assets/page.js") => {
            Reply::ok("text/javascript; charset=utf-8", assets::PAGE_JS)
        }
        (Method::Get, "/assets/page.css") => Reply::ok("text/css; charset=utf-8", assets::PAGE_CSS),
        (Method::Get, "/api/start") => Reply::json(&api::start(served)),
        (Method::Post, api) if api.starts_with("/api/") => {
            let declared = request.body_length();
            match guard::body(request.as_reader(), declared) {
                Ok(body) => post(api, &body, served),
                Err(guard::BodyError::TooLarge) => Reply::error(
                    413,
                    &format!("a request over {} MB is not read", guard::MAX_BODY >> 20),
                ),
                Err(guard::BodyError::Unreadable) => Reply::error(400, "the request was cut off"),
            }
        }
        (Method::Get, _) => Reply::error(404, &format!("nothing at `{path}`")),
        (method, _) => Reply::error(405, &format!("{method} is not answered here")),
    }
}

/// The answer to `POST /api/…` with `body`.
fn post(api: &str, body: &[u8], served: &Served) -> Reply {
    let m: api::Model = match serde_json::from_slice(body) {
        Ok(m) => m,
        Err(e) => return Reply::error(400, &format!("the request is not the JSON expected: {e}")),
    };
    let answered = match api {
        "/api/update" => api::in_turn(served, &m, |kept| api::update(served, &m, kept)),
        "/api/frames" => api::in_turn(served, &m, |kept| api::frames(served, &m, kept)),
        "/api/hover" => api::hover(served, &m),
        "/api/translate" => api::translate(served, &m),
        "/api/save" => api::save(served, &m),
        "/api/std" => api::std_entry(&m),
        "/api/export" => {
            return match api::export(served, &m) {
                Ok(d) => Reply {
                    download: Some(d.name),
                    ..Reply::ok(d.media_type, d.bytes)
                },
                Err(r) => Reply::error(r.status, &r.message),
            }
        }
        _ => return Reply::error(404, &format!("no request `{api}`")),
    };
    match answered {
        Ok(value) => Reply::json(&value),
        Err(r) => Reply::error(r.status, &r.message),
    }
}
