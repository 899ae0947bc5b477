//! The checks of `cargo xtask browser`, one function per project. Each
//! compares what the page shows (the DOM) with what the server says and,
//! for the press, with what `host-sim replay` makes of the inputs the page
//! lets the user save.

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use super::webdriver::{agent, get_text, Session};
use super::{serve, Guard};
use crate::{root, Result};

/// What every check needs.
pub struct Ctx<'a> {
    /// The browser.
    pub session: &'a Session,
    /// The `host-sim` binary.
    pub host_sim: &'a Path,
    /// Where screenshots and downloaded files go.
    pub out: &'a Path,
}

const WAIT: Duration = Duration::from_secs(20);

/// A served project opened in the browser.
struct Page<'a> {
    ctx: &'a Ctx<'a>,
    url: String,
    _server: Guard,
}

impl<'a> Page<'a> {
    /// Serves `project`, loads the page and waits for its first state;
    /// prints the load time (navigation start to the first state shown).
    fn open(ctx: &'a Ctx<'a>, project: &str) -> Result<Page<'a>> {
        let (server, url) = serve(ctx.host_sim, project)?;
        let s = ctx.session;
        s.goto(&url)?;
        s.wait_for(
            "document.body.dataset.ready === '1'",
            WAIT,
            "the page to show its first state",
        )?;
        let ms = s.exec("return Number(document.body.dataset.readyMs);", json!([]))?;
        let ms = ms.as_f64().unwrap_or(f64::NAN);
        eprintln!(
            "xtask browser: {project}: page ready {ms:.0} ms after navigation start{}",
            if ms < 1000.0 {
                ""
            } else {
                " (goal: < 1000 ms)"
            }
        );
        Ok(Page {
            ctx,
            url,
            _server: server,
        })
    }

    fn get(&self, path: &str) -> Result<String> {
        get_text(
            &agent(Duration::from_secs(60)),
            &format!("{}{path}", self.url),
        )
    }

    fn get_json(&self, path: &str) -> Result<Value> {
        let text = self.get(path)?;
        serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))
    }

    /// Clicks `selector` and waits for the page to render the reply.
    fn act(&self, selector: &str) -> Result {
        let s = self.ctx.session;
        let before = self.eval("Number(document.body.dataset.renders || 0)")?;
        s.click(selector)?;
        s.wait_for(
            &format!("Number(document.body.dataset.renders || 0) > {before}"),
            WAIT,
            &format!("the page to render after clicking {selector}"),
        )
    }

    fn eval(&self, expr: &str) -> Result<Value> {
        self.ctx.session.exec(&format!("return {expr};"), json!([]))
    }

    fn text(&self, id: &str) -> Result<String> {
        let v = self.eval(&format!(
            "(document.getElementById({id:?}) || {{}}).textContent"
        ))?;
        v.as_str()
            .map(str::to_owned)
            .ok_or_else(|| format!("no element #{id} on the page"))
    }

    /// The level an output's lamp shows (`data-level`).
    fn output(&self, name: &str) -> Result<bool> {
        let v = self.eval(&format!(
            "(document.getElementById('output-' + {name:?}) || {{dataset: {{}}}}).dataset.level"
        ))?;
        match v.as_str() {
            Some("1") => Ok(true),
            Some("0") => Ok(false),
            _ => Err(format!("output-{name}: no data-level on the page ({v})")),
        }
    }

    fn fault_shown(&self) -> Result<bool> {
        Ok(self.eval("!document.getElementById('fault').hidden")? == json!(true))
    }

    /// Saves a screenshot once the plots show the scan the page shows.
    fn screenshot(&self, name: &str) -> Result {
        self.ctx.session.wait_for(
            "document.body.dataset.plotScan === document.body.dataset.scan",
            WAIT,
            "the plots to show the last scan",
        )?;
        let path = self.ctx.out.join(name);
        self.ctx.session.screenshot(&path)?;
        eprintln!("xtask browser: screenshot {}", path.display());
        Ok(())
    }
}

/// The press's outputs in each state (models/press.plc.toml).
fn press_outputs(state: &str) -> [(&'static str, bool); 4] {
    let s = |set: &[&str]| set.contains(&state);
    [
        ("auto_lamp", s(&["2", "3", "4", "6"])),
        ("part_hold", s(&["3", "4"])),
        ("up_sol", s(&["4"])),
        ("down_sol", s(&["3"])),
    ]
}

/// The press: a whole cycle clicked through, then an unexpected event, the
/// fault and its reset; the page against the server's trace and the trace
/// against `host-sim replay` of the saved inputs.
pub fn press(ctx: &Ctx) -> Result {
    let page = Page::open(ctx, "models/press.plc.toml")?;
    // (what to click, the press's state after it: None = unchanged)
    let cycle: [(&str, Option<&str>); 11] = [
        ("#input-top_ls", Some("1")),
        ("#event-auto", Some("2")),
        ("#event-part_in", Some("3")),
        ("#input-top_ls", None),
        ("#step", None),
        ("#event-at_bottom", Some("4")),
        ("#input-bottom_ls", None),
        ("#step", None),
        ("#event-at_top", Some("6")),
        ("#event-part_out", Some("2")),
        ("#step", Some("2")),
    ];
    let mut state = "1".to_owned();
    for (click, expect) in cycle {
        page.act(click)?;
        if let Some(e) = expect {
            state = e.to_owned();
        }
        let shown = page.text("state-press")?;
        if shown != state {
            return Err(format!(
                "press: after clicking {click} the page shows state {shown:?}, expected {state:?}"
            ));
        }
        for (out, level) in press_outputs(&state) {
            if page.output(out)? != level {
                return Err(format!(
                    "press: after clicking {click} (state {state}) output {out} shows {}, expected {}",
                    !level, level
                ));
            }
        }
    }
    let events = trace_matches_dom(&page)?;
    eprintln!("xtask browser: press cycle: {events} logged scans with events agree with the server's trace");
    page.screenshot("press.png")?;

    // An event the supervisor does not expect: fault mode, safe outputs.
    let expected = page.eval("document.getElementById('event-at_bottom').dataset.expected")?;
    if expected != json!("0") {
        return Err(format!(
            "press: in state 2 at_bottom should be shown unexpected, data-expected = {expected}"
        ));
    }
    page.act("#event-at_bottom")?;
    if !page.fault_shown()? {
        return Err("press: no fault banner after the unexpected at_bottom".into());
    }
    let banner = page.text("fault")?;
    if !banner.contains("Unexpected:at_bottom") {
        return Err(format!(
            "press: the fault banner says {banner:?}, expected it to name Unexpected:at_bottom"
        ));
    }
    let model = page.get_json("api/model")?;
    for o in model["outputs"].as_array().into_iter().flatten() {
        let (name, safe) = (
            o["name"].as_str().unwrap_or(""),
            o["safe"].as_bool().unwrap_or(false),
        );
        if page.output(name)? != safe {
            return Err(format!(
                "press: in fault mode output {name} shows {}, its safe level is {safe}",
                !safe
            ));
        }
    }
    page.screenshot("press-fault.png")?;
    for click in ["#input-reset_pb", "#step", "#input-reset_pb", "#step"] {
        page.act(click)?;
    }
    if page.fault_shown()? {
        return Err(format!(
            "press: the fault banner is still shown after reset_pb rose: {:?}",
            page.text("fault")?
        ));
    }
    let events = trace_matches_dom(&page)?;
    replay_matches(&page)?;
    eprintln!(
        "xtask browser: press fault and reset: banner, safe outputs, reset; {events} logged scans agree; replay of the saved inputs gives the server's trace byte for byte"
    );
    controls(&page)
}

/// Restart, run and pause, the random driver on and off.
fn controls(page: &Page) -> Result {
    let s = page.ctx.session;
    page.act("#restart")?;
    let (scan, state, log) = (
        scan_shown(page)?,
        page.text("state-press")?,
        page.eval("document.querySelectorAll('#log .entry').length")?,
    );
    if scan != 0 || state != "1" || log != json!(0) {
        return Err(format!(
            "press: after restart the page shows scan {scan}, state {state:?}, {log} log entries; expected 0, \"1\", 0"
        ));
    }
    s.exec(
        "const sp = document.getElementById('speed'); sp.value = '10'; return sp.value;",
        json!([]),
    )?;
    s.click("#run")?;
    s.wait_for(
        "Number(document.body.dataset.scan) >= 100",
        WAIT,
        "the run at ×10 to reach scan 100",
    )?;
    s.click("#pause")?;
    std::thread::sleep(Duration::from_millis(300));
    let paused = scan_shown(page)?;
    std::thread::sleep(Duration::from_millis(300));
    let later = scan_shown(page)?;
    let server = page.get_json("api/state")?["scan"].as_u64();
    if later != paused || server != Some(paused) {
        return Err(format!(
            "press: after pause the page went on from scan {paused} to {later} (server: {server:?})"
        ));
    }
    for (on, driver) in [(true, "random"), (false, "none")] {
        page.act("#driver")?;
        let pressed =
            page.eval("document.getElementById('driver').getAttribute('aria-pressed')")?;
        let server = page.get_json("api/state")?["driver"].clone();
        if pressed != json!(on.to_string()) || server != json!(driver) {
            return Err(format!(
                "press: the driver button shows pressed = {pressed}, the server's driver is {server}; expected {on}, {driver:?}"
            ));
        }
    }
    eprintln!("xtask browser: press controls: restart to scan 0, run ×10 and pause at scan {paused}, random driver on and off");
    Ok(())
}

/// The page's supervisor states, outputs, fault and log against the
/// server's trace (`/api/trace.csv`); returns how many log entries agreed.
fn trace_matches_dom(page: &Page) -> Result<usize> {
    let trace = page.get("api/trace.csv")?;
    let mut lines = trace.lines();
    let header: Vec<&str> = lines
        .next()
        .ok_or("trace.csv is empty")?
        .split(',')
        .collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or_else(|| format!("trace.csv has no column {name}"))
    };
    let last = rows.last().ok_or("trace.csv has no scan")?;
    for pair in last[col("states")?].split(' ').filter(|p| !p.is_empty()) {
        let (sup, state) = pair.split_once('=').ok_or("trace.csv: bad states field")?;
        let shown = page.text(&format!("state-{sup}"))?;
        if shown != state {
            return Err(format!(
                "the page shows {sup} in state {shown:?}, the trace's last scan {state:?}"
            ));
        }
    }
    let model = page.get_json("api/model")?;
    for o in model["outputs"].as_array().into_iter().flatten() {
        let name = o["name"].as_str().unwrap_or("");
        let traced = last[col(name)?] == "1";
        if page.output(name)? != traced {
            return Err(format!(
                "the page shows output {name} = {}, the trace's last scan {traced}",
                !traced
            ));
        }
    }
    let fault = last[col("fault")?];
    let shown = page.fault_shown()?;
    if shown == fault.is_empty() {
        return Err(format!(
            "fault banner shown: {shown}, the trace's last scan has fault {fault:?}"
        ));
    }
    // The log, oldest first, against the trace's scans that did something.
    let (ev, ig, tm) = (col("events")?, col("ignored")?, col("time_ms")?);
    let traced: Vec<String> = rows
        .iter()
        .filter(|r| !r[ev].is_empty() || !r[ig].is_empty())
        .map(|r| format!("{} [{}] [{}]", r[tm], r[ev], r[ig]))
        .collect();
    let logged = page.eval(
        "[...document.querySelectorAll('#log .entry')].reverse()
           .filter(e => e.dataset.events || e.dataset.unexpected)
           .map(e => `${e.dataset.time} [${e.dataset.events}] [${e.dataset.unexpected}]`)",
    )?;
    let logged: Vec<String> = serde_json::from_value(logged).map_err(|e| e.to_string())?;
    let tail = &traced[traced.len().saturating_sub(logged.len())..];
    if logged.is_empty() || logged != tail {
        return Err(format!(
            "the page's log (time [events] [unexpected]) differs from the trace:\n  page:  {logged:?}\n  trace: {tail:?}"
        ));
    }
    Ok(logged.len())
}

/// Downloads the inputs and the trace through the page's links, replays the
/// inputs with `host-sim replay` and compares the traces byte for byte.
fn replay_matches(page: &Page) -> Result {
    let href = |id: &str| -> Result<String> {
        let v = page.eval(&format!("document.getElementById({id:?}).href"))?;
        v.as_str()
            .map(str::to_owned)
            .ok_or_else(|| format!("no link #{id} on the page"))
    };
    let a = agent(Duration::from_secs(60));
    let inputs = get_text(&a, &href("inputs-csv")?)?;
    let trace = get_text(&a, &href("trace-csv")?)?;
    let out = page.ctx.out;
    let (inputs_path, replayed_path) = (out.join("press.inputs.csv"), out.join("press.replay.csv"));
    std::fs::write(&inputs_path, &inputs).map_err(|e| e.to_string())?;
    std::fs::write(out.join("press.trace.csv"), &trace).map_err(|e| e.to_string())?;
    let status = Command::new(page.ctx.host_sim)
        .arg("replay")
        .arg("models/press.plc.toml")
        .arg("--inputs")
        .arg(&inputs_path)
        .arg("--out")
        .arg(&replayed_path)
        .current_dir(root())
        .stdout(std::process::Stdio::null())
        .status()
        .map_err(|e| format!("host-sim replay: {e}"))?;
    if !status.success() {
        return Err(format!(
            "host-sim replay of the saved inputs failed ({status})"
        ));
    }
    let replayed = std::fs::read_to_string(&replayed_path).map_err(|e| e.to_string())?;
    if replayed != trace {
        let line = replayed
            .lines()
            .zip(trace.lines())
            .position(|(a, b)| a != b)
            .map_or("its length".to_owned(), |i| format!("line {}", i + 1));
        return Err(format!(
            "host-sim replay of {} differs from /api/trace.csv at {line} (see {})",
            inputs_path.display(),
            replayed_path.display()
        ));
    }
    Ok(())
}

/// The boiler: a plant action, then a fast-forward of 200,000 scans through
/// the page's control; the scan count must advance by exactly that many.
pub fn boiler(ctx: &Ctx) -> Result {
    const N: u64 = 200_000;
    let page = Page::open(ctx, "models/boiler/boiler.plc.toml")?;
    let model = page.get_json("api/model")?;
    let high = model["plant"]["actions"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|a| a["name"].as_str())
        .find(|n| n.contains("high"));
    if let Some(action) = high {
        page.act(&format!("#action-{action}"))?;
    }
    let before = scan_shown(&page)?;
    ctx.session.type_into("#ffwd-n", &N.to_string())?;
    let start = Instant::now();
    ctx.session.click("#ffwd")?;
    ctx.session.wait_for(
        &format!(
            "document.body.dataset.scan === '{}' && document.getElementById('perf').dataset.ran",
            before + N
        ),
        Duration::from_secs(300),
        &format!("the fast-forward of {N} scans from scan {before}"),
    )?;
    let wall = start.elapsed();
    let server = page.get_json("api/state")?["scan"].as_u64();
    if server != Some(before + N) {
        return Err(format!(
            "boiler: after fast-forwarding {N} scans from {before} the server is at scan {server:?}"
        ));
    }
    let perf = page.eval("document.getElementById('perf').dataset")?;
    let rate = |k: &str| {
        perf[k]
            .as_str()
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    eprintln!(
        "xtask browser: boiler fast-forward: {N} scans, scan {before} → {}; server {:.0} scans/s, page {:.0} scans/s, click to shown {:.2} s",
        before + N,
        rate("serverRate"),
        rate("pageRate"),
        wall.as_secs_f64()
    );
    page.screenshot("boiler.png")
}

fn scan_shown(page: &Page) -> Result<u64> {
    let v = page.eval("document.body.dataset.scan")?;
    v.as_str()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("body has no data-scan ({v})"))
}

/// The mixers: the Petri net is drawn with every place and its tokens, and
/// the tokens follow a transition fired by a request input.
pub fn mixers(ctx: &Ctx) -> Result {
    let page = Page::open(ctx, "models/petri/mixers.plc.toml")?;
    let model = page.get_json("api/model")?;
    let net = &model["nets"][0];
    let name = net["name"].as_str().ok_or("mixers: the model has no net")?;
    let places = net["places"].as_array().map_or(0, Vec::len);
    let compare = |when: &str| -> Result<Vec<u64>> {
        let state = page.get_json("api/state")?;
        let marking: Vec<u64> = serde_json::from_value(state["markings"][0].clone())
            .map_err(|e| format!("mixers: markings: {e}"))?;
        let shown = page.eval(&format!(
            "[...document.querySelectorAll('#net-{name} .place .tokens')].map(t => Number(t.textContent))"
        ))?;
        let shown: Vec<u64> = serde_json::from_value(shown).map_err(|e| e.to_string())?;
        if shown.len() != places || shown != marking {
            return Err(format!(
                "mixers {when}: the net diagram shows {} places with tokens {shown:?}; the model has {places} places, the server's marking is {marking:?}",
                shown.len()
            ));
        }
        Ok(marking)
    };
    let initial = compare("at start")?;
    page.act("#input-start_a")?;
    page.act("#step")?;
    let after = compare("after start_a")?;
    if after == initial {
        return Err("mixers: the marking did not change after start_a and a scan".into());
    }
    eprintln!(
        "xtask browser: mixers: net {name} drawn with {places} places; tokens {initial:?} → {after:?}"
    );
    page.screenshot("mixers.png")
}

/// A big project (the testbed: 45 supervisors, 56 inputs): the page loads,
/// its long lists start collapsed, and the name filter narrows them.
pub fn big(ctx: &Ctx) -> Result {
    let page = Page::open(ctx, "models/testbed/testbed.plc.toml")?;
    let count = |sel: &str| -> Result<u64> {
        page.eval(&format!(
            "[...document.querySelectorAll({sel:?})].filter(e => e.offsetParent !== null).length"
        ))?
        .as_u64()
        .ok_or_else(|| format!("cannot count {sel}"))
    };
    let (inputs, diagrams) = (count("#inputs .io")?, count("#diagrams .diagram")?);
    let model = page.get_json("api/model")?;
    let total = model["inputs"].as_array().map_or(0, Vec::len) as u64;
    if total > 40 && inputs != 40 {
        return Err(format!(
            "testbed: {inputs} of {total} inputs shown; a list over 40 should show its first 40"
        ));
    }
    page.screenshot("testbed.png")?;
    ctx.session.type_into("#filter", "s1_")?;
    let narrowed = count("#inputs .io")?;
    if narrowed == 0 || narrowed >= inputs {
        return Err(format!(
            "testbed: the name filter `s1_` leaves {narrowed} of {inputs} inputs shown"
        ));
    }
    eprintln!(
        "xtask browser: testbed: {total} inputs ({inputs} shown, {narrowed} after filtering `s1_`), {diagrams} diagrams"
    );
    Ok(())
}
