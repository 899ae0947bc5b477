//! Symbolic synthesis of one family instance, with its figures:
//! `cargo run --release -p des-symbolic --example scale -- ring 13`.

use des_symbolic::{families, synthesize};
use std::process::ExitCode;
use std::time::Instant;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(family), Some(n)) = (args.first(), args.get(1).and_then(|n| n.parse().ok())) else {
        eprintln!("usage: scale ring|ringb|tline|phil|module N");
        return ExitCode::from(2);
    };
    let instance = match families::by_name(family, n) {
        Some(Ok(f)) => f,
        Some(Err(e)) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
        None => {
            eprintln!("unknown family `{family}` (ring, ringb, tline, phil, module)");
            return ExitCode::from(2);
        }
    };
    let start = Instant::now();
    let s = match synthesize(&instance.plants, &instance.specs) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let time = start.elapsed();
    println!("instance           {}", instance.name);
    println!(
        "components         {} plants, {} specs, {} BDD variables",
        instance.plants.len(),
        instance.specs.len(),
        s.model.layout().num_vars
    );
    println!("reachable states   {}", s.reachable_states());
    println!("supervisor states  {}", s.supervisor_states());
    println!("reachable nodes    {}", s.fixpoint.reachable.size());
    println!("supervisor nodes   {}", s.fixpoint.supervisor.size());
    println!(
        "guard nodes        {} ({} guards)",
        s.guard_nodes(),
        s.guards.len()
    );
    println!("fixpoint rounds    {}", s.fixpoint.rounds);
    let t = s.timings;
    println!(
        "time               {:.3} s (relations {:.3}, fixpoint {:.3}, guards {:.3})",
        time.as_secs_f64(),
        t.model.as_secs_f64(),
        t.fixpoint.as_secs_f64(),
        t.guards.as_secs_f64()
    );
    ExitCode::SUCCESS
}
