//! `cargo xtask layers`: the one-way rules, checked from the manifests and
//! the source text alone (no compilation; it takes well under a second).
//!
//! The workspace is built in stages and every arrow points down them:
//!
//! | stage | crates | may use (normal and build dependencies) |
//! |---|---|---|
//! | core | `des`, `executor`, `iec-st` | no workspace crate |
//! | core on des | `des-symbolic` (symbolic synthesis) | `des` only |
//! | front end | `plc-project` | core |
//! | backends | `codegen` (lowering, backends, emission, build-script API), `iec-export` | core and the front end; never each other |
//! | on top | `codegen-cli` (the `codegen` binary), `host-sim`, `firmware` | anything below |
//! | tooling | `e2e` (`tests/`), `xtask` | anything below |
//!
//! A front end knows nothing downstream of it, a backend never reaches
//! into another backend, and the CLI sits on top of them all. Two checks
//! hold the rules:
//!
//! 1. **Crate layering.** From `cargo metadata --no-deps`, every
//!    dependency of a workspace crate on another workspace crate must be
//!    in [`LAYERS`], the table below, for its kind (`[dependencies]`,
//!    `[build-dependencies]`; `[dev-dependencies]` have their own,
//!    broader allowance, since tests may drive a crate from above). The
//!    table itself must respect the stages (normal and build arrows go to
//!    a strictly lower stage, dev arrows to a stage no higher), so a new
//!    upward arrow (`plc-project` → `codegen`, `codegen` → `iec-export`)
//!    cannot be allowed by just adding it to the table.
//! 2. **No import circle inside a crate.** For each library crate
//!    (`src/lib.rs`), the graph of its top-level modules (the first path
//!    segment under `src/`; `lib.rs` itself is the root and left out),
//!    with an edge wherever a module names another one through
//!    `crate::a::…`, `use crate::{a, b::c}` or a `super::` chain that
//!    climbs to the root. Comments and string literals are not code; test
//!    code is skipped (from a `#[cfg(test)]` line to the end of its file,
//!    modules declared test-only, and `tests/`). A strongly connected
//!    component of more than one module is a circle: it is printed with
//!    one `file:line` for each of its edges.
//!
//! [`KNOWN_CYCLES`] lets named edges through while a crate is being
//! reworked elsewhere; it is meant to be empty.

mod crates;
mod modules;
#[cfg(test)]
mod tests;

use crate::Result;
use crates::{crate_failures, stale_rows, table_failures, workspace_packages, LAYERS};
use modules::{circle_failures, module_graph, read_sources, KNOWN_CYCLES};
use std::collections::BTreeMap;

/// Runs both checks on the workspace; `--edges` also prints every
/// library's module edges, each with the place that makes it.
pub fn run_task(args: &[String]) -> Result {
    let mut show_edges = false;
    for arg in args {
        match arg.as_str() {
            "--edges" => show_edges = true,
            _ => return Err(format!("layers: unknown argument `{arg}` (try --edges)")),
        }
    }
    let packages = workspace_packages()?;
    let mut failures = table_failures(LAYERS);
    failures.extend(crate_failures(&packages, LAYERS));
    failures.extend(stale_rows(&packages, LAYERS));
    let arrows: usize = packages.iter().map(|p| p.deps.len()).sum();

    let mut libraries = Vec::new();
    for p in &packages {
        // Libraries with their own `src/` (the e2e package's lib is the
        // test helpers at the root of `tests/`).
        let Some(lib) = p.lib.as_ref().filter(|l| l.ends_with("src/lib.rs")) else {
            continue;
        };
        let src = lib.parent().expect("src/lib.rs has a parent");
        let mut files = BTreeMap::new();
        read_sources(src, &mut files)?;
        let graph = module_graph(&files, lib)?;
        if show_edges {
            eprintln!(
                "{}: modules {}",
                p.name,
                graph.modules.iter().cloned().collect::<Vec<_>>().join(", ")
            );
            for ((a, b), site) in &graph.edges {
                eprintln!("  {a} -> {b}: {}:{}", site.file.display(), site.line);
            }
        }
        let (circles, stale) = circle_failures(&p.name, &graph, KNOWN_CYCLES);
        failures.extend(circles);
        failures.extend(stale);
        libraries.push(p.name.as_str());
    }
    for (krate, _, _) in KNOWN_CYCLES {
        if !libraries.contains(krate) {
            failures.push(format!(
                "xtask/src/layers/modules.rs: KNOWN_CYCLES names `{krate}`, which is not a library crate \
                 of the workspace: delete the entry"
            ));
        }
    }
    if !failures.is_empty() {
        return Err(format!(
            "the one-way rules are broken (docs/architecture.md, \"The one-way rules\"):\n{}",
            failures
                .iter()
                .map(|f| format!("  {f}"))
                .collect::<Vec<_>>()
                .join("\n")
        ));
    }
    eprintln!(
        "xtask: layers: {} crates, {arrows} arrows between them, all in the layer table; \
         no import circle in {} ({} libraries)",
        packages.len(),
        libraries.join(", "),
        libraries.len()
    );
    if !KNOWN_CYCLES.is_empty() {
        eprintln!(
            "xtask: layers: {} circle edges let through for now (KNOWN_CYCLES, to be emptied):",
            KNOWN_CYCLES.len()
        );
        for (krate, a, b) in KNOWN_CYCLES {
            eprintln!("  {krate}: {a} -> {b}");
        }
    }
    Ok(())
}
