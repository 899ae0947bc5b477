//! Writes an instance of a model family ([`des_symbolic::families`]) as
//! native TOML automata, one file per component:
//!
//! ```text
//! cargo run -p des-symbolic --example family_files -- FAMILY N OUTDIR
//! ```
//!
//! writes `OUTDIR/plant/NAME.toml` for each plant component and
//! `OUTDIR/spec/NAME.toml` for each specification (directories created;
//! FAMILY is `ring`, `ringb`, `tline`, `phil` or `module`). The module
//! project `models/module/` holds `module 10` written so
//! (`crates/des-symbolic/tests/family_files.rs` checks it still is).

use des::formats::{write_file, Component, Kind};
use des_symbolic::families;
use std::path::Path;

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [family, n, dir] = args.as_slice() else {
        return Err("usage: family_files ring|ringb|tline|phil|module N OUTDIR".into());
    };
    let n: usize = n.parse().map_err(|_| format!("N: `{n}` is not a number"))?;
    let instance = families::by_name(family, n)
        .ok_or_else(|| format!("unknown family `{family}`"))?
        .map_err(|e| e.to_string())?;
    for (kind, sub, automata) in [
        (Kind::Plant, "plant", &instance.plants),
        (Kind::Spec, "spec", &instance.specs),
    ] {
        let dir = Path::new(dir).join(sub);
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        for a in automata {
            let path = dir.join(format!("{}.toml", a.name()));
            let component = Component {
                kind,
                automaton: a.clone(),
            };
            write_file(&path, &[component]).map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}
