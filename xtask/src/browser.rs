//! `cargo xtask browser`: the simulator page of `host-sim serve` driven in
//! headless Chromium over WebDriver (chromedriver), as a user would click
//! it: the press's cycle, its fault and reset, a fast-forward of the boiler,
//! the mixers' Petri net and a big project (the testbed). Screenshots go
//! to `target/browser/`.
//!
//! `--no-build` uses `target/release/host-sim` as an earlier step left it
//! (CI's release tests of host-sim build it), building it only when
//! missing. `HOST_SIM=PATH` runs the checks against another binary.

use std::io::{BufRead, BufReader};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::{cargo, root, run, sysdeps, target_dir, Result};

mod checks;
mod webdriver;

/// The page's three files, embedded by the server.
const PAGE_FILES: [&str; 3] = ["index.html", "app.js", "style.css"];

/// Runs the task.
pub fn run_task(args: &[String]) -> Result {
    let build = match args {
        [] => true,
        [a] if a == "--no-build" => false,
        _ => return Err("usage: cargo xtask browser [--no-build]".into()),
    };
    let (chromium, chromedriver) = sysdeps::ensure_chromium()?;
    let host_sim = std::env::var_os("HOST_SIM")
        .map(PathBuf::from)
        .unwrap_or_else(|| target_dir().join("release/host-sim"));
    if std::env::var_os("HOST_SIM").is_none() && (build || !host_sim.exists()) {
        run(cargo().args(["build", "--release", "-p", "host-sim"]))?;
    }
    let out = target_dir().join("browser");
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    print_bundle_size()?;

    let port = free_port()?;
    let _driver = Guard::spawn(
        Command::new(&chromedriver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null()),
        "chromedriver",
    )?;
    let driver_url = format!("http://127.0.0.1:{port}");
    wait_ready(&driver_url)?;
    let session = webdriver::Session::start(&driver_url, &chromium, 1400, 900)?;
    let ctx = checks::Ctx {
        session: &session,
        host_sim: &host_sim,
        out: &out,
    };
    let started = Instant::now();
    checks::press(&ctx)?;
    checks::boiler(&ctx)?;
    checks::mixers(&ctx)?;
    checks::big(&ctx)?;
    eprintln!(
        "xtask browser: all checks passed in {:.1} s; screenshots in {}",
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(())
}

/// A child process killed (and reaped) when dropped, on success or failure.
pub struct Guard {
    child: Child,
}

impl Guard {
    fn spawn(cmd: &mut Command, what: &str) -> Result<Guard> {
        let child = cmd
            .spawn()
            .map_err(|e| format!("cannot start {what}: {e}"))?;
        Ok(Guard { child })
    }
}

impl Drop for Guard {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `host-sim serve PROJECT --port 0` and returns it with the URL it
/// prints on its first line.
pub fn serve(host_sim: &Path, project: &str) -> Result<(Guard, String)> {
    let mut guard = Guard::spawn(
        Command::new(host_sim)
            .args(["serve", project, "--port", "0"])
            .current_dir(root())
            .stdout(Stdio::piped()),
        "host-sim serve",
    )?;
    let stdout = guard
        .child
        .stdout
        .take()
        .ok_or("host-sim serve: no stdout")?;
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let line = rx
        .recv_timeout(Duration::from_secs(30))
        .map_err(|_| format!("host-sim serve {project} printed no URL within 30 s"))?;
    let url = line.trim().to_owned();
    if !url.starts_with("http://") {
        return Err(format!(
            "host-sim serve {project}: expected its URL on stdout, got {line:?}"
        ));
    }
    Ok((guard, url))
}

fn free_port() -> Result<u16> {
    let l = TcpListener::bind("127.0.0.1:0").map_err(|e| format!("no free port: {e}"))?;
    l.local_addr()
        .map(|a| a.port())
        .map_err(|e| format!("no free port: {e}"))
}

/// Waits until chromedriver answers its status request.
fn wait_ready(driver: &str) -> Result {
    let agent = webdriver::agent(Duration::from_secs(2));
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(20) {
        if webdriver::get_text(&agent, &format!("{driver}/status")).is_ok() {
            return Ok(());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    Err(format!(
        "chromedriver did not answer on {driver} within 20 s"
    ))
}

fn page_dir() -> PathBuf {
    root().join("crates/host-sim/src/serve/page")
}

fn print_bundle_size() -> Result {
    let mut total = 0;
    let mut parts = Vec::new();
    for f in PAGE_FILES {
        let p = page_dir().join(f);
        let n = std::fs::metadata(&p)
            .map_err(|e| format!("{}: {e}", p.display()))?
            .len();
        total += n;
        parts.push(format!("{f} {n}"));
    }
    eprintln!(
        "xtask browser: page bundle {total} bytes ({})",
        parts.join(", ")
    );
    Ok(())
}
