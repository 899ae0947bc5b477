//! The server's routes: the page's three files, the JSON API and the
//! run's files (docs/simulator.md, "API").

use super::json;
use super::session::{Driver, Session, MAX_SCANS_PER_REQUEST};
use serde::Deserialize;
use std::io::Read;
use std::time::Instant;
use tiny_http::{Header, Method, Request, Response, Server};

const INDEX: &str = include_str!("page/index.html");
const APP: &str = include_str!("page/app.js");
const STYLE: &str = include_str!("page/style.css");

/// The largest request body read.
const MAX_BODY: u64 = 64 << 10;

/// The page's plots: samples per request by default.
const DEFAULT_POINTS: usize = 600;

/// A served session and the name its project file is shown under.
pub struct App {
    /// The simulation.
    pub session: Session,
    /// The project file as given on the command line.
    pub file: String,
}

/// A reply: status, content type, body.
#[derive(Debug)]
pub struct Reply {
    /// HTTP status.
    pub status: u16,
    /// Content type.
    pub content_type: &'static str,
    /// Body.
    pub body: Vec<u8>,
    /// A file name to save the body under (`Content-Disposition`).
    pub attachment: Option<&'static str>,
}

impl Reply {
    fn new(content_type: &'static str, body: impl Into<Vec<u8>>) -> Reply {
        Reply {
            status: 200,
            content_type,
            body: body.into(),
            attachment: None,
        }
    }

    fn json(value: &impl serde::Serialize) -> Reply {
        Reply::new(
            "application/json",
            serde_json::to_vec(value).expect("the API's values serialise"),
        )
    }

    fn error(status: u16, message: &str) -> Reply {
        Reply {
            status,
            ..Reply::json(&serde_json::json!({ "error": message }))
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Scans {
    scans: u64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SetInput {
    name: String,
    value: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Named {
    name: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SetDriver {
    driver: Driver,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Empty {}

fn parse<'de, T: Deserialize<'de>>(body: &'de [u8]) -> Result<T, String> {
    let body = if body.is_empty() {
        b"{}".as_slice()
    } else {
        body
    };
    serde_json::from_slice(body).map_err(|e| format!("bad request body: {e}"))
}

fn scans(n: u64) -> Result<u64, String> {
    if (1..=MAX_SCANS_PER_REQUEST).contains(&n) {
        Ok(n)
    } else {
        Err(format!(
            "scans must be 1 … {MAX_SCANS_PER_REQUEST}, got {n}"
        ))
    }
}

/// The value of query parameter `key` in `query`.
fn query_value<'q>(query: &'q str, key: &str) -> Option<&'q str> {
    query
        .split('&')
        .filter_map(|kv| kv.split_once('='))
        .find(|(k, _)| *k == key)
        .map(|(_, v)| v)
}

impl App {
    /// Answers one request (`path` with its query string, `body`).
    pub fn handle(&mut self, method: &str, url: &str, body: &[u8]) -> Reply {
        let (path, query) = url.split_once('?').unwrap_or((url, ""));
        let result = match (method, path) {
            ("GET", "/" | "/index.html") => Ok(Reply::new("text/html; charset=utf-8", INDEX)),
            ("GET", "/app.js") => Ok(Reply::new("text/javascript; charset=utf-8", APP)),
            ("GET", "/style.css") => Ok(Reply::new("text/css; charset=utf-8", STYLE)),
            ("GET", "/api/model") => Ok(Reply::json(&json::model(&self.session, &self.file))),
            ("GET", "/api/state") => Ok(self.state()),
            ("GET", "/api/history") => self.history(query),
            ("GET", "/api/inputs.csv") => self.session.inputs_csv().map(|text| Reply {
                attachment: Some("inputs.csv"),
                ..Reply::new("text/csv; charset=utf-8", text)
            }),
            ("GET", "/api/trace.csv") => self.session.trace_csv().map(|text| Reply {
                attachment: Some("trace.csv"),
                ..Reply::new("text/csv; charset=utf-8", text)
            }),
            ("POST", "/api/step") => parse::<Scans>(body).and_then(|s| scans(s.scans)).map(|n| {
                self.session.step(n);
                self.state()
            }),
            ("POST", "/api/run") => parse::<Scans>(body).and_then(|s| scans(s.scans)).map(|n| {
                let start = Instant::now();
                self.session.step(n);
                let elapsed = start.elapsed().as_micros() as u64;
                Reply::json(&json::state(&self.session).with_run(n, elapsed))
            }),
            ("POST", "/api/input") => parse::<SetInput>(body)
                .and_then(|s| self.session.set_input(&s.name, s.value))
                .map(|()| self.state()),
            ("POST", "/api/event") => parse::<Named>(body)
                .and_then(|s| self.session.click(&s.name))
                .map(|()| self.state()),
            ("POST", "/api/action") => parse::<Named>(body)
                .and_then(|s| self.session.act(&s.name))
                .map(|()| self.state()),
            ("POST", "/api/driver") => parse::<SetDriver>(body).map(|s| {
                self.session.set_driver(s.driver);
                self.state()
            }),
            ("POST", "/api/restart") => parse::<Empty>(body)
                .and_then(|Empty {}| self.session.restart())
                .map(|()| self.state()),
            (_, p) if p == "/" || p.starts_with("/api/") || p.ends_with(".js") => {
                return Reply::error(405, &format!("{method} {path} is not served"))
            }
            _ => return Reply::error(404, &format!("{path}: no such page")),
        };
        result.unwrap_or_else(|e| Reply::error(400, &e))
    }

    fn state(&self) -> Reply {
        Reply::json(&json::state(&self.session))
    }

    fn history(&self, query: &str) -> Result<Reply, String> {
        let number = |key: &str, default: u64| -> Result<u64, String> {
            query_value(query, key).map_or(Ok(default), |v| {
                v.parse()
                    .map_err(|_| format!("`{key}` must be a non-negative integer, got `{v}`"))
            })
        };
        let points = number("points", DEFAULT_POINTS as u64)?.min(100_000) as usize;
        let from = number("from_ms", 0)?;
        Ok(Reply::json(&self.session.series(points, from)))
    }

    /// Serves requests on `server` until it fails.
    pub fn serve(&mut self, server: &Server) -> std::io::Result<()> {
        loop {
            let mut request = server.recv()?;
            let reply = self.reply_to(&mut request);
            let mut response = Response::from_data(reply.body)
                .with_status_code(reply.status)
                .with_header(header("Content-Type", reply.content_type))
                .with_header(header("Cache-Control", "no-store"));
            if let Some(name) = reply.attachment {
                response = response.with_header(header(
                    "Content-Disposition",
                    &format!("attachment; filename=\"{name}\""),
                ));
            }
            // A client that went away is not the server's failure.
            let _ = request.respond(response);
        }
    }

    fn reply_to(&mut self, request: &mut Request) -> Reply {
        let mut body = Vec::new();
        if let Err(e) = request
            .as_reader()
            .take(MAX_BODY + 1)
            .read_to_end(&mut body)
        {
            return Reply::error(400, &format!("reading the request: {e}"));
        }
        if body.len() as u64 > MAX_BODY {
            return Reply::error(413, &format!("a request body over {MAX_BODY} bytes"));
        }
        let method = match request.method() {
            Method::Get => "GET",
            Method::Post => "POST",
            _ => "OTHER",
        };
        let url = request.url().to_owned();
        self.handle(method, &url, &body)
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("ASCII header")
}
