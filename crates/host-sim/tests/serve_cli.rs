//! `host-sim serve` as a user starts it: the URL on standard output, the
//! page and the API over real HTTP, and a project or plant that cannot be
//! served refused before anything listens.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

/// The server, killed when dropped.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn start(project: &str) -> (Server, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["serve", "--port", "0"])
        .arg(repo(project))
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("host-sim runs");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    (Server(child), line.trim().to_owned())
}

/// `method path` with `body` over one HTTP/1.0 connection: status line
/// and body.
fn request(url: &str, method: &str, path: &str, body: &str) -> (String, String) {
    let addr = url
        .strip_prefix("http://")
        .and_then(|rest| rest.strip_suffix('/'))
        .unwrap_or_else(|| panic!("not a URL of ours: {url:?}"));
    let mut stream = TcpStream::connect(addr).unwrap();
    write!(
        stream,
        "{method} {path} HTTP/1.0\r\nHost: {addr}\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut reply = String::new();
    stream.read_to_string(&mut reply).unwrap();
    let (head, body) = reply.split_once("\r\n\r\n").unwrap();
    (head.lines().next().unwrap().to_owned(), body.to_owned())
}

#[test]
fn the_printed_url_serves_the_page_and_the_api() {
    let (_server, url) = start("models/press.plc.toml");
    assert!(url.starts_with("http://127.0.0.1:"), "{url}");
    let (status, page) = request(&url, "GET", "/", "");
    assert!(status.ends_with("200 OK"), "{status}");
    assert!(!page.is_empty());
    let (status, model) = request(&url, "GET", "/api/model", "");
    assert!(status.ends_with("200 OK"), "{status}");
    let model: serde_json::Value = serde_json::from_str(&model).unwrap();
    assert_eq!(model["project"]["name"], "stamping-press");
    let (_, state) = request(&url, "POST", "/api/step", r#"{"scans":5}"#);
    let state: serde_json::Value = serde_json::from_str(&state).unwrap();
    assert_eq!(state["scan"], 5);
    let (status, error) = request(&url, "POST", "/api/step", "{");
    assert!(status.contains(" 400 "), "{status}");
    assert!(error.contains("bad request body"), "{error}");
    let (_, inputs) = request(&url, "GET", "/api/inputs.csv", "");
    assert_eq!(
        inputs.lines().count(),
        6,
        "header and five scans:\n{inputs}"
    );
}

#[test]
fn a_plant_the_project_cannot_have_is_refused_with_what_it_lacks() {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["serve", "--port", "0", "--plant", "boiler"])
        .arg(repo("models/press.plc.toml"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("sel_high"), "{stderr}");
    assert!(out.stdout.is_empty(), "no URL for a server that never ran");
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["serve", "--port", "0", "--plant", "automata"])
        .arg(repo("models/press.plc.toml"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no plant automata"), "{stderr}");
}
