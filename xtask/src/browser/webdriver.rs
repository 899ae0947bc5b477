//! A minimal W3C WebDriver client over blocking HTTP (ureq): enough to
//! drive headless Chromium through chromedriver — navigate, find, click,
//! type, run a script, wait for a condition, take a screenshot.

use std::path::Path;
use std::time::{Duration, Instant};

use base64::Engine;
use serde_json::{json, Value};

use crate::Result;

/// The key W3C WebDriver uses for an element reference.
const ELEMENT: &str = "element-6066-11e4-a52e-4f735466cecf";

/// A plain HTTP agent that returns error statuses as responses (WebDriver
/// puts its error in the body) and gives up after `timeout`.
pub fn agent(timeout: Duration) -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .timeout_global(Some(timeout))
        .build()
        .into()
}

/// GET `url` and the body as text; fails on a non-2xx status.
pub fn get_text(agent: &ureq::Agent, url: &str) -> Result<String> {
    let (ok, body) = text_of(agent.get(url).call(), "GET", url)?;
    if ok {
        Ok(body)
    } else {
        Err(format!("GET {url}: {body}"))
    }
}

/// Whether a response has a 2xx status, and its body as text (up to 256 MiB).
fn text_of(
    resp: std::result::Result<ureq::http::Response<ureq::Body>, ureq::Error>,
    method: &str,
    url: &str,
) -> Result<(bool, String)> {
    let mut resp = resp.map_err(|e| format!("{method} {url}: {e}"))?;
    let text = resp
        .body_mut()
        .with_config()
        .limit(256 << 20)
        .read_to_string()
        .map_err(|e| format!("{method} {url}: {e}"))?;
    Ok((resp.status().is_success(), text))
}

/// A browser session of one chromedriver.
pub struct Session {
    agent: ureq::Agent,
    base: String,
}

impl Session {
    /// Opens a session on the chromedriver at `driver` (`http://127.0.0.1:PORT`)
    /// with headless Chromium at `binary`, a `width`×`height` window.
    pub fn start(driver: &str, binary: &str, width: u32, height: u32) -> Result<Session> {
        let agent = agent(Duration::from_secs(180));
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": binary,
                "args": ["--headless=new", "--no-sandbox", "--disable-gpu",
                         "--disable-dev-shm-usage", format!("--window-size={width},{height}")]
            }
        }}});
        let v = call(&agent, "POST", &format!("{driver}/session"), Some(caps))?;
        let id = v["sessionId"]
            .as_str()
            .ok_or_else(|| format!("chromedriver gave no session id: {v}"))?;
        Ok(Session {
            agent,
            base: format!("{driver}/session/{id}"),
        })
    }

    fn cmd(&self, method: &str, path: &str, body: Option<Value>) -> Result<Value> {
        call(&self.agent, method, &format!("{}{path}", self.base), body)
    }

    /// Loads `url` (returns when the document has loaded).
    pub fn goto(&self, url: &str) -> Result {
        self.cmd("POST", "/url", Some(json!({ "url": url })))
            .map(drop)
    }

    /// The element matching the CSS `selector`.
    pub fn find(&self, selector: &str) -> Result<String> {
        let v = self
            .cmd(
                "POST",
                "/element",
                Some(json!({"using": "css selector", "value": selector})),
            )
            .map_err(|e| format!("no element `{selector}` on the page: {e}"))?;
        v[ELEMENT]
            .as_str()
            .map(str::to_owned)
            .ok_or_else(|| format!("no element reference for `{selector}`: {v}"))
    }

    /// Clicks the element matching `selector`, as a user would (scrolled
    /// into view; refused if hidden or covered).
    pub fn click(&self, selector: &str) -> Result {
        let id = self.find(selector)?;
        self.cmd("POST", &format!("/element/{id}/click"), Some(json!({})))
            .map(drop)
            .map_err(|e| format!("cannot click `{selector}`: {e}"))
    }

    /// Replaces the text of the input field matching `selector`.
    pub fn type_into(&self, selector: &str, text: &str) -> Result {
        let id = self.find(selector)?;
        self.cmd("POST", &format!("/element/{id}/clear"), Some(json!({})))?;
        self.cmd(
            "POST",
            &format!("/element/{id}/value"),
            Some(json!({ "text": text })),
        )
        .map(drop)
    }

    /// Runs `script` (a function body; `arguments` holds `args`) in the page
    /// and returns its value.
    pub fn exec(&self, script: &str, args: Value) -> Result<Value> {
        self.cmd(
            "POST",
            "/execute/sync",
            Some(json!({"script": script, "args": args})),
        )
        .map_err(|e| format!("script failed: {e}\n  script: {script}"))
    }

    /// Polls the expression `expr` until it is truthy; fails after `timeout`
    /// with `what` and the page's status line.
    pub fn wait_for(&self, expr: &str, timeout: Duration, what: &str) -> Result {
        let start = Instant::now();
        let script = format!("return !!({expr});");
        loop {
            if self.exec(&script, json!([]))? == json!(true) {
                return Ok(());
            }
            if start.elapsed() > timeout {
                let status = self
                    .exec(
                        "const s = document.getElementById('status'); return s ? s.textContent : '';",
                        json!([]),
                    )
                    .unwrap_or_default();
                return Err(format!(
                    "timed out after {timeout:?} waiting for {what} (`{expr}`); page status: {status}"
                ));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Saves a PNG screenshot of the window to `path`.
    pub fn screenshot(&self, path: &Path) -> Result {
        let v = self.cmd("GET", "/screenshot", None)?;
        let b64 = v.as_str().ok_or("screenshot: no image data")?;
        let png = base64::engine::general_purpose::STANDARD
            .decode(b64)
            .map_err(|e| format!("screenshot: {e}"))?;
        std::fs::write(path, png).map_err(|e| format!("{}: {e}", path.display()))
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        let _ = self.agent.delete(&self.base).call();
    }
}

/// One WebDriver command: its `value`, or the driver's error as text.
fn call(agent: &ureq::Agent, method: &str, url: &str, body: Option<Value>) -> Result<Value> {
    let resp = match (method, body) {
        ("GET", _) => agent.get(url).call(),
        ("DELETE", _) => agent.delete(url).call(),
        (_, body) => agent
            .post(url)
            .content_type("application/json")
            .send(body.unwrap_or(json!({})).to_string()),
    };
    let (ok, text) = text_of(resp, method, url)?;
    let v: Value = serde_json::from_str(&text)
        .map_err(|e| format!("{method} {url}: not JSON ({e}): {text:.200}"))?;
    let value = v.get("value").cloned().unwrap_or(Value::Null);
    if ok {
        Ok(value)
    } else {
        Err(format!(
            "{}: {}",
            value["error"].as_str().unwrap_or("error"),
            value["message"]
                .as_str()
                .unwrap_or("")
                .lines()
                .next()
                .unwrap_or("")
        ))
    }
}
